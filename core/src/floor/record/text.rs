//! The text of record files: numbers, numbered lines, a byte-order mark, and pieces of text
//! quoted in messages.

/// Longest piece of file text quoted in a message, in characters.
pub(super) const MAX_QUOTED_CHARS: usize = 80;

/// Why a token is not a usable value.
pub(super) enum NumberError {
    NotANumber,
    NotFinite,
}

/// A finite number in Rust/Fortran free form (`-0.00128`, `.1181069E-02`, `1e5`).
pub(super) fn parse_number(token: &str) -> Result<f64, NumberError> {
    match token.parse::<f64>() {
        Ok(value) if value.is_finite() => Ok(value),
        Ok(_) => Err(NumberError::NotFinite),
        Err(_) => Err(NumberError::NotANumber),
    }
}

/// `text` cut to at most [`MAX_QUOTED_CHARS`] characters, for quoting in a message.
pub(super) fn quote(text: &str) -> String {
    let mut chars = text.chars();
    let mut quoted: String = chars.by_ref().take(MAX_QUOTED_CHARS).collect();
    if chars.next().is_some() {
        quoted.push_str("...");
    }
    quoted
}

/// The lines of `text` without line ends (`\n` or `\r\n`), numbered from 1.
pub(super) fn numbered_lines(text: &str) -> impl Iterator<Item = (usize, &str)> {
    text.lines()
        .enumerate()
        .map(|(index, line)| (index + 1, line))
}

pub(super) fn strip_byte_order_mark(text: &str) -> &str {
    text.strip_prefix('\u{feff}').unwrap_or(text)
}

/// `text` without the prefix `prefix` (compared ignoring ASCII case), if it starts with it.
pub(super) fn strip_prefix_ignore_case<'a>(text: &'a str, prefix: &str) -> Option<&'a str> {
    let head = text.get(..prefix.len())?;
    if head.eq_ignore_ascii_case(prefix) {
        text.get(prefix.len()..)
    } else {
        None
    }
}
