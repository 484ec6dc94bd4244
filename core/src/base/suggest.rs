//! Hints for a misspelt or misunderstood value: "did you mean" for keys and named values, and
//! the unit a key takes when a number was written with a unit suffix.

/// The candidate closest to `word` by edit distance, if it is close enough to be a likely
/// misspelling: at most a third of the word's length (and at least one edit) away.
pub(crate) fn closest<'a>(
    word: &str,
    candidates: impl IntoIterator<Item = &'a str>,
) -> Option<&'a str> {
    let limit = (word.chars().count() / 3).max(1);
    candidates
        .into_iter()
        .filter(|c| *c != word)
        .map(|c| (strsim::damerau_levenshtein(word, c), c))
        .filter(|(d, _)| *d <= limit)
        .min_by_key(|(d, _)| *d)
        .map(|(_, c)| c)
}

/// The words between double quotes in `text` (the alternatives a rule names).
fn quoted(text: &str) -> Vec<&str> {
    text.split('"').skip(1).step_by(2).collect()
}

/// The words between backticks in `text` (the fields a schema message names).
fn backticked(text: &str) -> Vec<&str> {
    text.split('`').skip(1).step_by(2).collect()
}

/// `rule` with "did you mean" added when `value` (as quoted in a message) is close to one of the
/// quoted alternatives the rule lists.
pub(crate) fn rule_with_hint(value: &str, rule: &str) -> String {
    let value = value.trim_matches('"');
    match closest(value, quoted(rule)) {
        // What the value already holds, quoted back in its rule, is no hint.
        Some(hint) if !value.contains(hint) && !rule.contains("did you mean") => {
            format!("{rule}; did you mean \"{hint}\"?")
        }
        _ => rule.to_string(),
    }
}

/// A schema error message (from reading a model file's table) with a hint added: the closest
/// field to an unknown one, or, for text where a number belongs that starts with a number (a
/// unit suffix such as `0.3g` or `5MPa`), the unit the key takes.
pub(crate) fn schema_hint(message: &str) -> String {
    // "unknown field `amplitud`, expected one of `kind`, `amplitude`, ..."
    if let Some(rest) = message.split("unknown field ").nth(1) {
        let names = backticked(rest);
        if let Some((unknown, known)) = names.split_first() {
            if let Some(hint) = closest(unknown, known.iter().copied()) {
                return format!("{message}; did you mean `{hint}`?");
            }
        }
    }
    // "invalid type: string \"0.3g\", expected f64 in `excitation.amplitude`"
    if message.contains("invalid type: string") && message.contains("expected f64") {
        let text = message.split('"').nth(1).unwrap_or("");
        let starts_with_number = text
            .trim_start_matches(['+', '-'])
            .starts_with(|c: char| c.is_ascii_digit() || c == '.');
        let key = backticked(message).last().copied().unwrap_or("");
        if starts_with_number {
            let unit = match crate::base::units::unit_of_key(key) {
                Some(unit) => format!("the unit {key} takes ({unit})"),
                None => "the key's SI unit".to_string(),
            };
            return format!("{message}; a unit suffix is not read: write a plain number in {unit}");
        }
    }
    message.to_string()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn close_words_are_suggested_and_far_ones_are_not() {
        let methods = ["bdf", "esdirk34", "tr-bdf2", "tsit45", "newmark"];
        assert_eq!(closest("tsit54", methods), Some("tsit45"));
        assert_eq!(closest("newmrk", methods), Some("newmark"));
        assert_eq!(closest("rk4", methods), None);
        assert_eq!(
            closest("bdf", methods),
            None,
            "an exact match is not a hint"
        );
    }

    #[test]
    fn schema_messages_get_the_closest_field_or_the_unit() {
        let m = "unknown field `amplitud`, expected one of `kind`, `amplitude`, `period` in `excitation`";
        assert!(
            schema_hint(m).ends_with("did you mean `amplitude`?"),
            "{}",
            schema_hint(m)
        );
        let m = "unknown field `zzz`, expected one of `kind`, `amplitude`";
        assert_eq!(schema_hint(m), m);
        let m = "invalid type: string \"0.3g\", expected f64 in `excitation.amplitude`";
        assert!(schema_hint(m).contains("(m/s^2)"), "{}", schema_hint(m));
        let m = "invalid type: string \"abc\", expected f64 in `excitation.amplitude`";
        assert_eq!(schema_hint(m), m);
    }

    #[test]
    fn rules_that_list_names_suggest_the_closest() {
        let rule =
            "must be \"paper\" (the paper's model) or \"consistent\" (the weight in the bending)";
        assert!(rule_with_hint("\"consistant\"", rule).ends_with("did you mean \"consistent\"?"));
        assert_eq!(rule_with_hint("\"xyz\"", rule), rule);
        assert_eq!(rule_with_hint("3", "must be positive"), "must be positive");
        // A rule that quotes the value back does not offer it as a hint.
        let rule = "the key \"a.b.c.d\" must be section.name";
        assert_eq!(rule_with_hint("a.b.c.d=1", rule), rule);
    }
}
