//! The physics layer's error: a parameter that breaks a rule of the model. The body, its
//! constants and the automaton report nothing else; the layers above wrap it in theirs.

use crate::base::format::Quoted;

/// A parameter breaks a rule of the model (`key` is the model-file key, e.g. `body.width`, or
/// the name of a derived quantity).
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[error("{key} = {value}: {rule}")]
pub struct InvalidParameter {
    /// The model-file key, e.g. `body.width`.
    pub key: String,
    /// The value given, as quoted in the message.
    pub value: String,
    /// The rule it breaks.
    pub rule: String,
}

impl InvalidParameter {
    /// The same error about column `index` of a row: a key `body.x` (or `simulation.q0`)
    /// becomes `column[index].x`.
    pub fn in_column(self, index: usize) -> Self {
        let key = match self
            .key
            .strip_prefix("body.")
            .or_else(|| self.key.strip_prefix("simulation."))
        {
            Some(rest) => format!("column[{index}].{rest}"),
            None => format!("column[{index}]: {}", self.key),
        };
        InvalidParameter { key, ..self }
    }

    /// The error for `key` = `value` breaking `rule`; numbers are quoted in their shortest form,
    /// and a value written with a unit (`0.3g`) gets a hint added to the rule.
    pub fn new(key: &str, value: impl Quoted, rule: &str) -> Self {
        let value = value.quoted();
        InvalidParameter {
            key: key.to_string(),
            rule: crate::base::suggest::rule_with_hint(&value, rule),
            value,
        }
    }
}
