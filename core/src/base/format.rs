//! Numbers and file kinds for people: the formatting every message, table and file of flexrock
//! shares (one home; the command layer's `output` module re-exports it).

use std::fmt::Write;

/// Formats a number so that it reads back exactly (shortest round-trip form): as Rust's `{}`
/// writes it, plain decimal without a trailing ".0" (1, 0.005, -0, 1e-7 as 0.0000001), for
/// magnitudes from [`PLAIN_FROM`] to below [`PLAIN_BELOW`] (and zero); as `{:e}` writes it
/// beyond (1e-300, 2.5e16), where the plain form would take up to 326 characters. At most
/// [`MAX_NUMBER_CHARS`] characters.
pub fn number(x: f64) -> String {
    let mut text = String::new();
    push_number(&mut text, x);
    text
}

/// The smallest magnitude [`number`] writes in plain decimal: 0.000000000000000001; smaller
/// ones take an exponent. Every number of the results committed under validation/ is above it
/// (the smallest has 17 zeros after the point), so that none of them changed form.
pub const PLAIN_FROM: f64 = 1e-18;

/// The magnitude from which [`number`] writes an exponent (as ryu and JSON do): 1e16, the
/// first whole number of 17 digits.
pub const PLAIN_BELOW: f64 = 1e16;

/// The most characters [`number`] writes: 37, for a negative number of 17 significant digits
/// just above [`PLAIN_FROM`] (-0.0000000000000000012345678901234567). The exponent form takes
/// at most 24 (-1.2345678901234567e-308), the plain one above 1e-5 at most 24.
pub const MAX_NUMBER_CHARS: usize = 37;

/// Appends [`number`]`(x)` to `text`. The shortest digits come from `ryu`, several times faster
/// than the standard library's formatting (which was most of the time `flexrock run` took to
/// write history.csv); they are placed as `{}` places them, and a test compares the two on
/// millions of doubles.
pub fn push_number(text: &mut String, x: f64) {
    if !x.is_finite() {
        // NaN, inf, -inf, as `{}` writes them.
        text.push_str(if x.is_nan() {
            "NaN"
        } else if x > 0.0 {
            "inf"
        } else {
            "-inf"
        });
        return;
    }
    let mut buffer = ryu::Buffer::new();
    let formatted = buffer.format_finite(x);
    if x != 0.0 && !(PLAIN_FROM..PLAIN_BELOW).contains(&x.abs()) {
        push_exponent(text, &Digits::of_ryu(x, formatted));
        return;
    }
    // From 1e-5 to 1e16 ryu writes the plain form as `{}` does, but for the ".0" of a whole
    // number. Only a number with at most 18 digits in all can be halfway between two shortest
    // candidates (below), and only one with a few binary digits after the point has so few.
    // ryu's exponent, where it writes one, is among its last five characters ("e-324").
    let tail = &formatted.as_bytes()[formatted.len().saturating_sub(5)..];
    if !tail.contains(&b'e') && !short_fraction(x) {
        text.push_str(formatted.strip_suffix(".0").unwrap_or(formatted));
        return;
    }
    push_plain(text, &Digits::of_ryu(x, formatted));
}

/// The shortest round-trip digits of a finite number, those of the standard library's `{}`
/// and `{:e}`: value = 0.DIGITS times 10^point (no digits for zero).
pub(crate) struct Digits {
    pub(crate) negative: bool,
    digits: [u8; 24],
    count: usize,
    pub(crate) point: i32,
}

impl Digits {
    /// The digits ryu finds, or where x lies halfway between two shortest candidates (ryu takes
    /// the even one, the standard library the one above) the standard library's.
    pub(crate) fn of(x: f64) -> Self {
        let mut buffer = ryu::Buffer::new();
        Self::of_ryu(x, buffer.format_finite(x))
    }

    /// [`Digits::of`] from the text ryu wrote for `x`.
    fn of_ryu(x: f64, formatted: &str) -> Self {
        let digits = Self::parse(formatted.as_bytes());
        let count = digits.count;
        if count > 0
            && digits.digits[count - 1].is_multiple_of(2)
            && is_midpoint(x.abs(), &digits.digits[..count], digits.point)
        {
            return Self::parse(format!("{x:e}").as_bytes());
        }
        digits
    }

    /// The digits of d.ddd, 0.000ddd, ddd.0 or d.ddde-N (ryu's forms, and `{:e}`'s).
    fn parse(formatted: &[u8]) -> Self {
        let (negative, formatted) = match formatted.split_first() {
            Some((b'-', rest)) => (true, rest),
            _ => (false, formatted),
        };
        let (mantissa, exponent) = match formatted.iter().position(|&b| b == b'e') {
            Some(e) => (&formatted[..e], parse_exponent(&formatted[e + 1..])),
            None => (formatted, 0),
        };
        let mut digits = Digits {
            negative,
            digits: [0; 24],
            count: 0,
            point: exponent,
        };
        let mut seen_point = false;
        for &b in mantissa {
            if b == b'.' {
                seen_point = true;
                continue;
            }
            if digits.count == 0 && b == b'0' {
                // A leading zero: only moves the point when it follows it.
                if seen_point {
                    digits.point -= 1;
                }
                continue;
            }
            digits.digits[digits.count] = b;
            digits.count += 1;
            if !seen_point {
                digits.point += 1;
            }
        }
        while digits.count > 0 && digits.digits[digits.count - 1] == b'0' {
            digits.count -= 1;
        }
        digits
    }

    /// The length of [`push_plain`]'s text.
    fn plain_len(&self) -> usize {
        let (count, point) = (self.count as i64, i64::from(self.point));
        let body = if count == 0 {
            1
        } else if point <= 0 {
            2 - point + count
        } else if point >= count {
            point
        } else {
            count + 1
        };
        usize::from(self.negative) + body as usize
    }

    /// The length of [`push_exponent`]'s text.
    fn exponent_len(&self) -> usize {
        let mantissa = if self.count <= 1 { 1 } else { self.count + 1 };
        let exponent = if self.count == 0 { 0 } else { self.point - 1 };
        let exponent_digits = exponent.unsigned_abs().checked_ilog10().unwrap_or(0) as usize + 1;
        usize::from(self.negative) + mantissa + 1 + usize::from(exponent < 0) + exponent_digits
    }

    /// The digits, as ASCII.
    pub(crate) fn ascii(&self) -> &[u8] {
        &self.digits[..self.count]
    }

    fn text(&self) -> &str {
        std::str::from_utf8(&self.digits[..self.count]).unwrap_or("0")
    }
}

/// The plain form of `{}`: 0.00ddd, ddd00 or dd.ddd.
fn push_plain(text: &mut String, d: &Digits) {
    if d.negative {
        text.push('-');
    }
    if d.count == 0 {
        text.push('0');
        return;
    }
    text.reserve(d.plain_len());
    let (digits, point, count) = (d.text(), d.point, d.count);
    if point <= 0 {
        text.push_str("0.");
        push_zeros(text, (-point) as usize);
        text.push_str(digits);
    } else if point as usize >= count {
        text.push_str(digits);
        push_zeros(text, point as usize - count);
    } else {
        text.push_str(&digits[..point as usize]);
        text.push('.');
        text.push_str(&digits[point as usize..]);
    }
}

/// Appends `n` zeros.
fn push_zeros(text: &mut String, mut n: usize) {
    const ZEROS: &str = "0000000000000000000000000000000000000000000000000000000000000000";
    while n > 0 {
        let now = n.min(ZEROS.len());
        text.push_str(&ZEROS[..now]);
        n -= now;
    }
}

/// The exponent form of `{:e}`: d.ddde-N, de0.
fn push_exponent(text: &mut String, d: &Digits) {
    if d.negative {
        text.push('-');
    }
    let digits = d.text();
    match digits.split_at_checked(1) {
        None | Some(("", _)) => text.push('0'),
        Some((first, rest)) => {
            text.push_str(first);
            if !rest.is_empty() {
                text.push('.');
                text.push_str(rest);
            }
        }
    }
    text.push('e');
    let exponent = if d.count == 0 { 0 } else { d.point - 1 };
    let _ = write!(text, "{exponent}");
}

/// Whether x = m 2^-j with m odd and 1 <= j <= 22: one whose exact decimal form has j digits
/// after the point, the last a 5. A number halfway between two shortest candidates has at most
/// 18 significant digits, and in the plain form (x >= 1e-5) at most 4 zeros lead them.
fn short_fraction(x: f64) -> bool {
    odd_binary(x).is_some_and(|(_, exponent)| (-22..0).contains(&exponent))
}

/// |x| = m 2^e with m odd, as (m, e); None for zero.
fn odd_binary(x: f64) -> Option<(u64, i32)> {
    let bits = x.to_bits();
    let (biased, fraction) = (((bits >> 52) & 0x7ff) as i32, bits & ((1 << 52) - 1));
    let (mantissa, exponent) = if biased == 0 {
        (fraction, -1074)
    } else {
        (fraction | (1 << 52), biased - 1075)
    };
    if mantissa == 0 {
        return None;
    }
    let shift = mantissa.trailing_zeros();
    Some((mantissa >> shift, exponent + shift as i32))
}

/// Whether `x` (positive, finite) is exactly 0.DIGITS5 times 10^point: halfway between the
/// shortest digits and the next ones up. With x = m 2^e (m odd) and the midpoint N 10^k (N
/// odd, as it ends in 5), they are equal when e = k and m = N 5^k (k >= 0) or m 5^-k = N.
fn is_midpoint(x: f64, digits: &[u8], point: i32) -> bool {
    let Some((odd, exponent)) = odd_binary(x) else {
        return false;
    };
    let odd = u128::from(odd);
    let k = point - digits.len() as i32 - 1;
    if exponent != k {
        // The common case, settled without the arithmetic below.
        return false;
    }
    let midpoint = digits
        .iter()
        .fold(0u128, |acc, &d| acc * 10 + u128::from(d - b'0'))
        * 10
        + 5;
    let power = |n: i32| 5u128.checked_pow(n.unsigned_abs());
    if k >= 0 {
        power(k).and_then(|p| midpoint.checked_mul(p)) == Some(odd)
    } else {
        power(k).and_then(|p| odd.checked_mul(p)) == Some(midpoint)
    }
}

/// The exponent ryu writes after its "e": an optional minus and at most three digits.
fn parse_exponent(bytes: &[u8]) -> i32 {
    let (sign, digits) = match bytes.split_first() {
        Some((b'-', rest)) => (-1, rest),
        _ => (1, bytes),
    };
    sign * digits
        .iter()
        .fold(0i32, |acc, &b| acc * 10 + i32::from(b - b'0'))
}

/// A number as a person would type it, for messages and help texts: its shortest round-trip
/// digits, in exponent form when that is shorter by two characters or more (1e-4, 1e300, 2e5;
/// but 0.005, 0.0003125, 43.98). It reads back exactly, and 1e300 or 1e-300 never print as
/// 301 digits.
pub fn shortest(x: f64) -> String {
    let mut text = String::with_capacity(24);
    push_shortest(&mut text, x);
    text
}

/// Appends [`shortest`]`(x)` to `text`.
pub fn push_shortest(text: &mut String, x: f64) {
    if !x.is_finite() {
        let _ = write!(text, "{x}");
        return;
    }
    // One shortest-digit conversion (the costly part of a sweep's table). Where ryu writes the
    // plain form as `{}` does (as in `push_number`), it is the shorter unless at least three
    // zeros follow the point before the digits (0.000d) or end a whole number (d000): then
    // the exponent form can be two characters shorter, and the digits decide.
    let mut buffer = ryu::Buffer::new();
    let formatted = buffer.format_finite(x);
    // ryu's exponent, where it writes one, is among its last five characters ("e-324").
    let tail = &formatted.as_bytes()[formatted.len().saturating_sub(5)..];
    if !tail.contains(&b'e') && !short_fraction(x) {
        let plain = formatted.strip_suffix(".0").unwrap_or(formatted);
        let unsigned = plain.strip_prefix('-').unwrap_or(plain);
        let zeros_lead = unsigned.starts_with("0.000");
        let zeros_end = !plain.contains('.') && unsigned.ends_with("000");
        if !zeros_lead && !zeros_end {
            text.push_str(plain);
            return;
        }
    }
    // Otherwise the lengths of both forms follow from the digits, and only the shorter is
    // written.
    let digits = Digits::of(x);
    if digits.exponent_len() + 2 <= digits.plain_len() {
        push_exponent(text, &digits);
    } else {
        push_plain(text, &digits);
    }
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

/// Appends the decimal digits of `n`, as `{}` writes them, without the formatting machinery
/// (a sweep writes several counts a row).
pub fn push_decimal(text: &mut String, mut n: usize) {
    let mut digits = [0u8; 20];
    let mut start = digits.len();
    loop {
        start -= 1;
        digits[start] = b'0' + (n % 10) as u8;
        n /= 10;
        if n == 0 {
            break;
        }
    }
    for &d in &digits[start..] {
        text.push(char::from(d));
    }
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

    /// A xorshift stream of bit patterns from `state`.
    fn xorshift(mut state: u64) -> impl FnMut() -> u64 {
        move || {
            state ^= state << 13;
            state ^= state >> 7;
            state ^= state << 17;
            state
        }
    }

    /// push_decimal writes what `{}` writes: the ends, each power of ten and the number below
    /// it, and a stream of others.
    #[test]
    fn push_decimal_writes_what_display_writes() {
        let mut next = xorshift(7);
        let mut numbers = vec![0, usize::MAX];
        let mut power = 1usize;
        while let Some(p) = power.checked_mul(10) {
            numbers.extend([power - 1, power, power + 1]);
            power = p;
        }
        numbers.extend((0..10_000).map(|_| (next() >> (next() % 64)) as usize));
        for n in numbers {
            let mut text = String::from("x");
            push_decimal(&mut text, n);
            assert_eq!(text, format!("x{n}"));
        }
    }

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

    /// Extreme magnitudes take an exponent, and no number is longer than [`MAX_NUMBER_CHARS`]:
    /// the longest plain ones lie just above [`PLAIN_FROM`].
    #[test]
    fn number_is_bounded_in_length() {
        assert_eq!(number(1e-300), "1e-300");
        assert_eq!(number(-2.5e-19), "-2.5e-19");
        assert_eq!(number(1e-18), "0.000000000000000001");
        assert_eq!(number(1e16), "1e16");
        assert_eq!(number(9999999999999998.0), "9999999999999998");
        assert_eq!(number(f64::MIN), "-1.7976931348623157e308");
        assert_eq!(number(5e-324), "5e-324");
        let longest = number(-1.2345678901234566e-18);
        assert_eq!(longest, "-0.0000000000000000012345678901234566");
        assert_eq!(longest.len(), MAX_NUMBER_CHARS);
        for x in [1e-300, f64::MIN_POSITIVE, -1.2345678901234567e-300, 1e308] {
            assert!(number(x).len() <= 24, "{x:e}");
            assert_eq!(number(x).parse::<f64>().unwrap(), x);
        }
    }

    /// `number` writes what the standard library's `{}` writes (`{:e}` beyond its plain range),
    /// character for character: on the doubles at the ends of every range, on random bit
    /// patterns (every exponent, the subnormals) and on numbers of everyday size with few and
    /// many digits, two million in all.
    #[test]
    fn number_is_the_standard_librarys_plain_form() {
        let mut values = vec![
            0.0,
            -0.0,
            1.0,
            -1.0,
            0.1,
            0.3,
            1e-5,
            1e-7,
            1e15,
            1e16,
            1e17,
            1e21,
            1e22,
            1e23,
            123456.0,
            9007199254740993.0,
            // 1347897590845337.25, halfway between two 17-digit candidates (its ulp is 0.25):
            // `{}` writes ...337.3.
            -5391590363381349.0 / 4.0,
            5391590363381349.0 / 4.0,
            f64::MAX,
            f64::MIN,
            f64::MIN_POSITIVE,
            f64::EPSILON,
            5e-324,
            -5e-324,
            f64::from_bits(0x000f_ffff_ffff_ffff),
            f64::NAN,
            f64::INFINITY,
            f64::NEG_INFINITY,
        ];
        let mut next = xorshift(0x2545_f491_4f6c_dd1d_u64);
        for _ in 0..700_000 {
            values.push(f64::from_bits(next()));
            let scale = 10f64.powi((next() % 40) as i32 - 20);
            values.push((next() % 100_000) as f64 * scale);
            values.push((next() as f64 / u64::MAX as f64 - 0.5) * scale);
        }
        let mut text = String::new();
        for x in values {
            let plain = x == 0.0 || !x.is_finite() || (PLAIN_FROM..PLAIN_BELOW).contains(&x.abs());
            let expected = if plain {
                format!("{x}")
            } else {
                format!("{x:e}")
            };
            assert_eq!(number(x), expected, "{x:e}");
            assert!(number(x).len() <= MAX_NUMBER_CHARS, "{x:e}");
            // Appending to a buffer that already holds text gives the same characters.
            text.clear();
            text.push_str("a,");
            push_number(&mut text, x);
            assert_eq!(&text[2..], expected, "{x:e}");
            if x.is_finite() {
                // The lengths `shortest` chooses by are those of the two forms.
                let digits = Digits::of(x);
                assert_eq!(digits.plain_len(), format!("{x}").len(), "{x:e}");
                assert_eq!(digits.exponent_len(), format!("{x:e}").len(), "{x:e}");
            }
        }
    }

    /// Numbers with few binary digits after the point, m 2^-j, are where a double can lie
    /// halfway between two shortest candidates (0.020746231079101562 and ...563 for m 2^-19):
    /// `number` writes what `{}` writes for every j up to 60, below 1 and above it.
    #[test]
    fn number_is_the_standard_librarys_on_short_binary_fractions() {
        let mut next = xorshift(0x1234_5678_9abc_def1_u64);
        let mut bad = 0;
        for j in 1..60 {
            for _ in 0..40_000 {
                let bits = 64 - 53 + (next() % 53) as u32;
                let m = (next() >> bits) | 1;
                let x = m as f64 / 2f64.powi(j);
                for x in [x, -x, x * 2f64.powi(j.min(40))] {
                    if x.abs() >= PLAIN_FROM && format!("{x}") != number(x) {
                        bad += 1;
                        if bad < 5 {
                            eprintln!("m 2^-{j}: {x:e} written {}", number(x));
                        }
                    }
                }
            }
        }
        assert_eq!(bad, 0);
    }

    /// The plain form built from the exponent form's digits is the standard library's own
    /// plain form, wherever it is chosen; and the choice is the one the two lengths make.
    #[test]
    fn shortest_is_the_shorter_of_the_two_standard_forms() {
        let mut next = xorshift(0x9e37_79b9_7f4a_7c15_u64);
        let mut values = vec![
            0.0, -0.0, 1.0, 10.0, 100.0, 0.1, 0.01, 1e-5, 1e21, 1e22, 123456.0,
        ];
        // Where the plain and the exponent forms are of about one length: a few digits after
        // zeros that follow the point, or before zeros that end a whole number.
        for digits in [1.0, 7.0, 12.0, 125.0, 1234.0, 123456789.0] {
            for power in -12..=12 {
                let x = digits * 10f64.powi(power);
                values.extend([x, -x]);
            }
        }
        // Numbers with few binary digits after the point (where ryu and `{}` can differ).
        for j in 1..40 {
            for _ in 0..200 {
                let m = (next() >> (11 + next() % 53)) | 1;
                values.push(m as f64 / 2f64.powi(j));
            }
        }
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
