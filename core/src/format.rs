//! Numbers and file kinds for people: the formatting every message, table and file of flexrock
//! shares (one home; the command layer's `output` module re-exports it).

/// Formats a number so that it reads back exactly (shortest round-trip form).
pub fn number(x: f64) -> String {
    format!("{x}")
}

/// A number as a person would type it, for messages and help texts: its shortest round-trip
/// digits, in exponent form when that is shorter by two characters or more (1e-4, 1e300, 2e5;
/// but 0.005, 0.0003125, 43.98). It reads back exactly, and 1e300 or 1e-300 never print as
/// 301 digits.
pub fn shortest(x: f64) -> String {
    if !x.is_finite() {
        return format!("{x}");
    }
    // One shortest-digit conversion (the costly part of a sweep's table), in exponent form;
    // the plain form has the same digits, placed by the exponent.
    let exponent = format!("{x:e}");
    let (mantissa, power) = exponent.split_once('e').unwrap_or((&exponent, "0"));
    let power: i64 = power.parse().unwrap_or(0);
    let (sign, mantissa) = match mantissa.strip_prefix('-') {
        Some(rest) => ("-", rest),
        None => ("", mantissa),
    };
    let (lead, rest) = mantissa.split_once('.').unwrap_or((mantissa, ""));
    let n = (lead.len() + rest.len()) as i64;
    let plain_len = sign.len() as i64
        + if power >= 0 {
            n.max(power + 1) + i64::from(n > power + 1)
        } else {
            1 + 1 + (-power - 1) + n
        };
    if exponent.len() as i64 + 2 <= plain_len {
        return exponent;
    }
    let mut plain = String::with_capacity(plain_len as usize);
    plain.push_str(sign);
    if power >= 0 {
        // The first digit, then `power` more before the point (zeros where the digits end).
        plain.push_str(lead);
        let before = power as usize;
        if rest.len() <= before {
            plain.push_str(rest);
            plain.extend(std::iter::repeat_n('0', before - rest.len()));
        } else {
            plain.push_str(&rest[..before]);
            plain.push('.');
            plain.push_str(&rest[before..]);
        }
    } else {
        plain.push_str("0.");
        plain.extend(std::iter::repeat_n('0', (-power - 1) as usize));
        plain.push_str(lead);
        plain.push_str(rest);
    }
    plain
}

/// A short time step or period in seconds: five decimals, or two significant digits below
/// 1 ms.
pub fn short_seconds(t: f64) -> String {
    if t >= 1e-3 {
        format!("{t:.5}")
    } else {
        format!("{t:.2e}")
    }
}

/// A number in exponent form (1e-8, 2.5e-3), as tolerances are written.
pub fn scientific(x: f64) -> String {
    format!("{x:e}")
}

/// Significant digits of [`readable`].
const READABLE_DIGITS: usize = 12;

/// A computed quantity for people: rounded to 12 significant digits, then in the form of
/// [`shortest`], so that a sum such as 43.980000000000004 prints as 43.98.
pub fn readable(x: f64) -> String {
    if !x.is_finite() || x == 0.0 {
        return shortest(x);
    }
    let rounded = format!("{x:.prec$e}", prec = READABLE_DIGITS - 1)
        .parse::<f64>()
        .unwrap_or(x);
    shortest(rounded)
}

/// A number rounded to `digits` significant digits, in the form of [`shortest`] (figure
/// labels: 0.1524, 1085, 1.2e-7).
pub fn significant(x: f64, digits: usize) -> String {
    if !x.is_finite() || x == 0.0 {
        return shortest(x);
    }
    let rounded = format!("{x:.prec$e}", prec = digits.max(1) - 1)
        .parse::<f64>()
        .unwrap_or(x);
    shortest(rounded)
}

/// A count with its noun: "1 uplift", "2 uplifts", "0 uplifts".
pub fn count(n: usize, singular: &str, plural: &str) -> String {
    format!("{n} {}", if n == 1 { singular } else { plural })
}

/// Values as a comma-separated list, each in the form `format` gives ([`shortest`],
/// [`scientific`]), as a user types them after a flag such as `--dt`.
pub fn list(values: &[f64], format: fn(f64) -> String) -> String {
    values
        .iter()
        .map(|&x| format(x))
        .collect::<Vec<_>>()
        .join(",")
}

/// What a file system entry is, for messages: "a directory", "a FIFO (named pipe)", ...
pub fn file_kind(file_type: std::fs::FileType) -> &'static str {
    #[cfg(unix)]
    {
        use std::os::unix::fs::FileTypeExt;
        if file_type.is_fifo() {
            return "a FIFO (named pipe)";
        }
        if file_type.is_char_device() {
            return "a character device";
        }
        if file_type.is_block_device() {
            return "a block device";
        }
        if file_type.is_socket() {
            return "a socket";
        }
    }
    if file_type.is_dir() {
        "a directory"
    } else if file_type.is_file() {
        "a regular file"
    } else {
        "a special file"
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn numbers_for_people() {
        assert_eq!(shortest(1e300), "1e300");
        assert_eq!(shortest(-1e-300), "-1e-300");
        assert_eq!(shortest(0.005), "0.005");
        assert_eq!(shortest(0.0003125), "0.0003125");
        assert_eq!(shortest(1e-4), "1e-4");
        assert_eq!(shortest(43.980000000000004), "43.980000000000004");
        assert_eq!(shortest(f64::NAN), "NaN");
        assert_eq!(shortest(f64::NEG_INFINITY), "-inf");
        assert_eq!(shortest(-0.0), "-0");
        assert_eq!(shortest(120.0), "120");
        assert_eq!(shortest(1.5e5), "150000");
    }

    /// The plain form built from the exponent form's digits is the standard library's own
    /// plain form, wherever it is chosen; and the choice is the one the two lengths make.
    #[test]
    fn shortest_is_the_shorter_of_the_two_standard_forms() {
        let mut state = 0x9e37_79b9_7f4a_7c15_u64;
        let mut next = || {
            state ^= state << 13;
            state ^= state >> 7;
            state ^= state << 17;
            state
        };
        let mut values = vec![
            0.0, -0.0, 1.0, 10.0, 100.0, 0.1, 0.01, 1e-5, 1e21, 1e22, 123456.0,
        ];
        for _ in 0..20_000 {
            let bits = next();
            let x = f64::from_bits(bits);
            if x.is_finite() {
                values.push(x);
            }
            // Numbers of everyday size, with few and with many digits.
            let scale = 10f64.powi((next() % 30) as i32 - 15);
            values.push((next() % 100_000) as f64 * scale);
            values.push((next() as f64 / u64::MAX as f64 - 0.5) * scale);
        }
        for x in values {
            let plain = format!("{x}");
            let exponent = format!("{x:e}");
            let expected = if exponent.len() + 2 <= plain.len() {
                exponent
            } else {
                plain
            };
            assert_eq!(shortest(x), expected, "{x:e}");
            assert_eq!(shortest(x).parse::<f64>().unwrap().to_bits(), x.to_bits());
        }
        assert_eq!(readable(43.980000000000004), "43.98");
        assert_eq!(readable(0.1 + 0.2), "0.3");
        assert_eq!(readable(1.0 / 3.0), "0.333333333333");
        assert_eq!(readable(0.0), "0");
        assert_eq!(readable(6e4), "6e4");
        assert_eq!(readable(31.16), "31.16");
        assert_eq!(significant(0.15236512, 4), "0.1524");
        assert_eq!(significant(1085.4, 4), "1085");
        assert_eq!(significant(0.7, 4), "0.7");
        assert_eq!(count(1, "uplift", "uplifts"), "1 uplift");
        assert_eq!(count(0, "uplift", "uplifts"), "0 uplifts");
        assert_eq!(count(2, "uplift", "uplifts"), "2 uplifts");
        assert_eq!(list(&[1e-3, 1e-11], scientific), "1e-3,1e-11");
        assert_eq!(list(&[0.04, 0.0003125], shortest), "0.04,0.0003125");
    }
}

/// A value quoted in an error message. Numbers appear in their shortest exact form
/// ([`shortest`]), so that 1e300 reads `1e300`, not 301 digits.
pub trait Quoted {
    /// The value as an error message quotes it.
    fn quoted(&self) -> String;
}

impl Quoted for f64 {
    fn quoted(&self) -> String {
        shortest(*self)
    }
}

impl Quoted for f32 {
    fn quoted(&self) -> String {
        shortest(f64::from(*self))
    }
}

macro_rules! quoted_by_display {
    ($($t:ty),*) => {
        $(impl Quoted for $t {
            fn quoted(&self) -> String {
                self.to_string()
            }
        })*
    };
}
quoted_by_display!(usize, u8, u16, u32, u64, isize, i8, i16, i32, i64, bool, char, str, String);
