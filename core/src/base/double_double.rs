//! Numbers to twice the working precision: hi + lo, with |lo| at most half an ulp of hi (Dekker
//! 1971; Hida, Li and Bailey 2001), and the error-free transformations they are built from.
//!
//! The body's derived constants are computed in this arithmetic and rounded once
//! ([`crate::physics::constants`]), so that each constant the exact method reads is the double nearest its
//! true value for the body as written; the exact method also keeps its state to this precision.

use std::ops::{Add, Div, Mul, Neg, Sub};

/// Defines a function whose body is compiled twice, as written and with the processor's fused
/// multiply-add (x86-64 processors that have it, detected when the function is called), where
/// each product to twice the precision ([`two_product`]) is one instruction instead of a call to
/// the library's `fma`. Both give the same result to the bit: a fused multiply-add is rounded
/// once either way, and Rust never fuses an expression on its own. For the hot paths of the
/// exact method only; the body should call small functions that inline into it.
macro_rules! fused {
    ($(#[$attr:meta])* $vis:vis fn $name:ident($($arg:ident: $ty:ty),* $(,)?) -> $ret:ty $body:block) => {
        $(#[$attr])*
        $vis fn $name($($arg: $ty),*) -> $ret {
            #[inline(always)]
            fn body($($arg: $ty),*) -> $ret $body
            #[cfg(target_arch = "x86_64")]
            {
                #[target_feature(enable = "fma")]
                unsafe fn with_fma($($arg: $ty),*) -> $ret {
                    body($($arg),*)
                }
                if $crate::base::double_double::fma_in_use() {
                    // SAFETY: the processor has the instruction `with_fma` is compiled with.
                    return unsafe { with_fma($($arg),*) };
                }
            }
            body($($arg),*)
        }
    };
}
pub(crate) use fused;

/// Whether [`fused`] functions take their fused multiply-add version: where the processor has
/// the instruction, unless a test turned it off ([`set_fma_in_use`]).
#[cfg(target_arch = "x86_64")]
#[inline(always)]
pub(crate) fn fma_in_use() -> bool {
    #[cfg(test)]
    if !FMA_ALLOWED.load(std::sync::atomic::Ordering::Relaxed) {
        return false;
    }
    std::is_x86_feature_detected!("fma")
}

#[cfg(test)]
static FMA_ALLOWED: std::sync::atomic::AtomicBool = std::sync::atomic::AtomicBool::new(true);

/// Lets the tests run [`fused`] functions as written (false) to compare the two versions.
#[cfg(test)]
pub(crate) fn set_fma_in_use(allowed: bool) {
    FMA_ALLOWED.store(allowed, std::sync::atomic::Ordering::Relaxed);
}

/// a + b = s + e exactly (Knuth's two-sum).
#[inline(always)]
pub(crate) fn two_sum(a: f64, b: f64) -> (f64, f64) {
    let s = a + b;
    let bb = s - a;
    (s, (a - (s - bb)) + (b - bb))
}

/// a + b = s + e exactly when |a| >= |b| (Dekker's fast two-sum).
#[inline(always)]
pub(crate) fn quick_two_sum(a: f64, b: f64) -> (f64, f64) {
    let s = a + b;
    (s, b - (s - a))
}

/// a b = p + e exactly (by a fused multiply-add).
#[inline(always)]
pub(crate) fn two_product(a: f64, b: f64) -> (f64, f64) {
    let p = a * b;
    (p, a.mul_add(b, -p))
}

/// hi + lo, normalised: hi is the double nearest the sum.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub(crate) struct DoubleDouble {
    pub hi: f64,
    pub lo: f64,
}

impl DoubleDouble {
    /// Normalises hi + lo.
    pub fn new(hi: f64, lo: f64) -> Self {
        let (hi, lo) = two_sum(hi, lo);
        DoubleDouble { hi, lo }
    }

    /// The double x, exactly.
    pub const fn exact(x: f64) -> Self {
        DoubleDouble { hi: x, lo: 0.0 }
    }

    /// The decimal number x is written as (its shortest round-trip digits), to twice the
    /// precision: 0.7 is seven tenths, not the double nearest it. A model file's numbers are
    /// read this way, as a person typed them.
    pub fn decimal(x: f64) -> Self {
        // An integer below 2^53 (a height of 4 m, a density of 600) is its own decimal.
        if !x.is_finite() || (x.trunc() == x && x.abs() < 9007199254740992.0) {
            return Self::exact(x);
        }
        Self::from_digits(x)
    }

    /// [`DoubleDouble::decimal`] of a finite x from its shortest round-trip digits.
    fn from_digits(x: f64) -> Self {
        // The digits of `{:e}` (format::Digits: ryu's, checked equal to the standard library's).
        let written = crate::base::format::Digits::of(x);
        let (digits, negative) = (written.ascii(), written.negative);
        let power = written.point - 1;
        // At most 17 digits: two integers below 2^53 make them exactly.
        let split = digits.len().saturating_sub(9);
        let integer_of = |digits: &[u8]| {
            digits
                .iter()
                .fold(0u64, |acc, &d| acc * 10 + u64::from(d - b'0')) as f64
        };
        let (high, low) = (integer_of(&digits[..split]), integer_of(&digits[split..]));
        let low_digits = (digits.len() - split) as i32;
        let integer = DoubleDouble::from(two_product(high, 10f64.powi(low_digits))) + low;
        // The value is integer * 10^(power - digits + 1).
        let scale = power - digits.len() as i32 + 1;
        let value = if scale >= 0 {
            integer * power_of_ten(scale)
        } else {
            integer / power_of_ten(-scale)
        };
        // Beyond the range where 10^k is finite (subnormal numbers), the double itself.
        if !value.hi.is_finite() || value.hi == 0.0 {
            return Self::exact(x);
        }
        if negative {
            -value
        } else {
            value
        }
    }

    /// The nearest double.
    pub fn value(self) -> f64 {
        self.hi
    }

    /// The square root (one Newton step from the double root).
    pub fn sqrt(self) -> Self {
        if self.hi <= 0.0 || !self.hi.is_finite() {
            return Self::exact(self.hi.sqrt());
        }
        let root = self.hi.sqrt();
        let square = DoubleDouble::from(two_product(root, root));
        let residual = self - square;
        DoubleDouble::new(root, residual.hi / (2.0 * root))
    }

    /// The cube.
    pub fn cube(self) -> Self {
        self * self * self
    }

    /// e^self: self = n ln 2 + r, e^r by its Taylor series at r / 32 and five squarings.
    pub fn exp(self) -> Self {
        exp_of(self)
    }
}

fused! {
    /// [`DoubleDouble::exp`].
    fn exp_of(x: DoubleDouble) -> DoubleDouble {
        if !x.hi.is_finite() || x.hi.abs() > 700.0 {
            return DoubleDouble::exact(x.hi.exp());
        }
        let n = (x.hi / LN_2.hi).round();
        let r = x - LN_2 * n;
        let r = r * (1.0 / 32.0);
        // |r| < 0.011: the terms of degree 7 to 14 add up to less than 4e-18, so they are summed
        // in double precision (an error below 1e-33), and 14 terms leave less than 1e-36. The
        // rest by Horner's rule to twice the precision, with the coefficients 1/n! as constants.
        let tail = INVERSE_FACTORIALS[7..]
            .iter()
            .rev()
            .fold(0.0, |acc: f64, coefficient| acc * r.hi + coefficient.hi);
        let mut sum = INVERSE_FACTORIALS[6] + r * tail;
        for &coefficient in INVERSE_FACTORIALS[..6].iter().rev() {
            sum = sum * r + coefficient;
        }
        for _ in 0..5 {
            sum = sum * sum;
        }
        // 2^n exactly, in two factors so that neither overflows (|n| <= 1010).
        let half = (n / 2.0).trunc();
        sum * power_of_two(half) * power_of_two(n - half)
    }
}

/// 2^k for an integer k with |k| <= 1022, exactly (from its bits).
#[inline(always)]
fn power_of_two(k: f64) -> f64 {
    f64::from_bits(((k as i64 + 1023) as u64) << 52)
}

/// 1/n! for n = 0 to 14, to twice the precision: hi the double nearest 1/n!, lo the double
/// nearest the rest (computed in rational arithmetic; the tests check that n/n! = 1/(n-1)!).
const INVERSE_FACTORIALS: [DoubleDouble; 15] = {
    const fn dd(hi: f64, lo: f64) -> DoubleDouble {
        DoubleDouble { hi, lo }
    }
    [
        dd(1.0, 0.0),
        dd(1.0, 0.0),
        dd(0.5, 0.0),
        dd(0.16666666666666666, 9.25185853854297e-18),
        dd(0.041666666666666664, 2.3129646346357427e-18),
        dd(0.008333333333333333, 1.1564823173178714e-19),
        dd(0.001388888888888889, -5.300543954373577e-20),
        dd(0.0001984126984126984, 1.7209558293420705e-22),
        dd(2.48015873015873e-05, 2.1511947866775882e-23),
        dd(2.7557319223985893e-06, -1.858393274046472e-22),
        dd(2.755731922398589e-07, 2.3767714622250297e-23),
        dd(2.505210838544172e-08, -1.448814070935912e-24),
        dd(2.08767569878681e-09, -1.20734505911326e-25),
        dd(1.6059043836821613e-10, 1.2585294588752098e-26),
        dd(1.1470745597729725e-11, 2.0655512752830745e-28),
    ]
};

/// 2 pi to twice the precision.
pub(crate) const TWO_PI: DoubleDouble = DoubleDouble {
    hi: 2.0 * std::f64::consts::PI,
    lo: 2.0 * 1.224_646_799_147_353_2e-16,
};

/// ln 2 to twice the precision: 0.693147180559945309417232121458176568075500134360255.
const LN_2: DoubleDouble = DoubleDouble {
    hi: std::f64::consts::LN_2,
    lo: 2.319_046_813_846_299_6e-17,
};

/// 10^n to twice the precision (exact up to 10^22, then by products).
fn power_of_ten(n: i32) -> DoubleDouble {
    let mut result = DoubleDouble::exact(1.0);
    let mut left = n;
    while left > 22 {
        result = result * 1e22;
        left -= 22;
    }
    result * 10f64.powi(left)
}

impl From<(f64, f64)> for DoubleDouble {
    fn from((hi, lo): (f64, f64)) -> Self {
        DoubleDouble::new(hi, lo)
    }
}

impl From<f64> for DoubleDouble {
    fn from(x: f64) -> Self {
        DoubleDouble::exact(x)
    }
}

impl Neg for DoubleDouble {
    type Output = Self;
    fn neg(self) -> Self {
        DoubleDouble {
            hi: -self.hi,
            lo: -self.lo,
        }
    }
}

impl Add for DoubleDouble {
    type Output = Self;
    #[inline(always)]
    fn add(self, other: Self) -> Self {
        let (s, e) = two_sum(self.hi, other.hi);
        let (t, f) = two_sum(self.lo, other.lo);
        let (s, e) = quick_two_sum(s, e + t);
        let (hi, lo) = quick_two_sum(s, e + f);
        DoubleDouble { hi, lo }
    }
}

impl Sub for DoubleDouble {
    type Output = Self;
    fn sub(self, other: Self) -> Self {
        self + (-other)
    }
}

impl Mul for DoubleDouble {
    type Output = Self;
    #[inline(always)]
    fn mul(self, other: Self) -> Self {
        let (p, e) = two_product(self.hi, other.hi);
        let e = e + (self.hi * other.lo + self.lo * other.hi);
        let (hi, lo) = quick_two_sum(p, e);
        DoubleDouble { hi, lo }
    }
}

impl Div for DoubleDouble {
    type Output = Self;
    fn div(self, other: Self) -> Self {
        // Long division: three quotient digits, each from the remainder so far.
        let q1 = self.hi / other.hi;
        let r = self - other * q1;
        let q2 = r.hi / other.hi;
        let r = r - other * q2;
        let q3 = r.hi / other.hi;
        let (hi, lo) = quick_two_sum(q1, q2);
        DoubleDouble { hi, lo } + q3
    }
}

macro_rules! with_f64 {
    ($($trait:ident $method:ident),*) => {$(
        impl $trait<f64> for DoubleDouble {
            type Output = Self;
            #[inline(always)]
            fn $method(self, other: f64) -> Self {
                $trait::$method(self, DoubleDouble::exact(other))
            }
        }
        impl $trait<DoubleDouble> for f64 {
            type Output = DoubleDouble;
            #[inline(always)]
            fn $method(self, other: DoubleDouble) -> DoubleDouble {
                $trait::$method(DoubleDouble::exact(self), other)
            }
        }
    )*};
}
with_f64!(Add add, Sub sub, Mul mul);

impl Div<f64> for DoubleDouble {
    type Output = Self;
    /// By a double: one quotient digit, then the remainder's (exact by a fused product).
    fn div(self, other: f64) -> Self {
        let q1 = self.hi / other;
        let (p, e) = two_product(q1, other);
        let (s, f) = two_sum(self.hi, -p);
        let q2 = (s + (f - e + self.lo)) / other;
        let (hi, lo) = quick_two_sum(q1, q2);
        DoubleDouble { hi, lo }
    }
}

impl Div<DoubleDouble> for f64 {
    type Output = DoubleDouble;
    fn div(self, other: DoubleDouble) -> DoubleDouble {
        DoubleDouble::exact(self) / other
    }
}

#[cfg(test)]
mod tests {
    use super::DoubleDouble as Dd;

    /// The error of hi + lo from the rational p/q, relative, in integer arithmetic: exact (for
    /// q up to about 10^4).
    fn relative_error_from(x: Dd, p: i128, q: i128) -> f64 {
        let (m_hi, e_hi) = frexp(x.hi);
        let (m_lo, e_lo) = frexp(x.lo);
        let k = -if m_lo == 0 { e_hi } else { e_hi.min(e_lo) };
        let scaled = |m: i128, e: i32| (m * q) << (e + k);
        let numerator = scaled(m_hi, e_hi) + scaled(m_lo, e_lo) - (p << k);
        numerator as f64 / (p << k) as f64
    }

    /// v = mantissa 2^exponent with an integer mantissa.
    fn frexp(v: f64) -> (i128, i32) {
        if v == 0.0 {
            return (0, 0);
        }
        let bits = v.to_bits();
        let sign = if bits >> 63 == 1 { -1 } else { 1 };
        let exponent = ((bits >> 52) & 0x7ff) as i32;
        let fraction = (bits & ((1 << 52) - 1)) as i128;
        let (mantissa, exponent) = if exponent == 0 {
            (fraction, -1074)
        } else {
            (fraction | (1 << 52), exponent - 1075)
        };
        (sign * mantissa, exponent)
    }

    #[test]
    fn decimals_are_read_to_twice_the_precision() {
        // 0.7 = 7/10, 142916.66666666663 = 14291666666666663/10^11, 1.8751 = 18751/10^4.
        for (x, p, q) in [
            (0.7, 7, 10),
            (0.123, 123, 1000),
            (1.8751, 18751, 10_000),
            (-2.5e-3, -25, 10_000),
            (600.0, 600, 1),
        ] {
            let error = relative_error_from(Dd::decimal(x), p, q);
            assert!(error.abs() < 1e-30, "{x}: {error:e}");
        }
    }

    /// An integer is read as itself without its digits, as its digits read it: the small ones of
    /// model files and integers spread up to 2^53 (ends included).
    #[test]
    fn integers_are_their_own_decimals() {
        let mut state = 0x9e37_79b9_7f4a_7c15u64;
        let mut integers = vec![0.0, -0.0, 1.0, 4.0, 600.0, 5e6, -3.0, 9007199254740991.0];
        for _ in 0..20_000 {
            state ^= state << 13;
            state ^= state >> 7;
            state ^= state << 17;
            let bits = (state % 53) as u32;
            integers.push((state >> 11 >> (53 - bits.max(1))) as f64);
        }
        for x in integers {
            let read = Dd::decimal(x);
            assert_eq!((read.hi, read.lo), (x, 0.0), "{x}");
            if x != 0.0 {
                let digits = Dd::from_digits(x);
                assert_eq!((digits.hi, digits.lo), (x, 0.0), "{x}");
            }
        }
        // Beyond 2^53 the digits are read: 1e17 is 10^17, exactly a double.
        assert_eq!(Dd::decimal(1e17).value(), 1e17);
    }

    /// The ends of the doubles' range read back as themselves, not as zero or infinity.
    #[test]
    fn decimals_at_the_ends_of_the_range_are_the_doubles() {
        for x in [5e-324, -2.5e-320, 1e-300, 1.7976931348623157e308, -1e308] {
            let read = Dd::decimal(x);
            assert_eq!(read.value(), x, "{x:e}");
            assert!(read.lo.is_finite());
        }
    }

    #[test]
    fn arithmetic_is_good_to_twice_the_precision() {
        let seven_tenths = Dd::decimal(0.7);
        // 0.7^3 / 12 = 343/12000.
        let cube = seven_tenths.cube() / 12.0;
        assert!(relative_error_from(cube, 343, 12_000).abs() < 1e-30);
        // sqrt(0.49) = 0.7; (0.7 - 1/3) * 3 = 11/10.
        let root = Dd::decimal(0.49).sqrt();
        assert!(relative_error_from(root, 7, 10).abs() < 1e-30);
        let third = Dd::exact(1.0) / 3.0;
        // By a double: 0.7 / 12 = 7/120, and 1 / 3 against the division by a double-double.
        assert!(relative_error_from(seven_tenths / 12.0, 7, 120).abs() < 1e-30);
        assert!(relative_error_from(third, 1, 3).abs() < 1e-30);
        assert!(relative_error_from((seven_tenths - third) * 3.0, 11, 10).abs() < 1e-30);
        // The double nearest 7/10 is the rounding of the double-double.
        assert_eq!(seven_tenths.value(), 0.7);
    }

    /// Each constant 1/n! times n is the one before it, to twice the precision (so each is
    /// right if 1/0! = 1 is), and each is normalised.
    #[test]
    fn the_inverse_factorials_follow_their_recurrence() {
        let table = super::INVERSE_FACTORIALS;
        assert_eq!(table[0], Dd::exact(1.0));
        for n in 1..table.len() {
            let back = table[n] * (n as f64);
            let relative = ((back - table[n - 1]) / table[n - 1]).hi.abs();
            assert!(relative < 1e-31, "1/{n}!: {relative:e}");
            assert_eq!(Dd::new(table[n].hi, table[n].lo), table[n], "1/{n}!");
        }
    }

    /// e^x against its value computed apart (Python's decimal module, 60 digits, split into
    /// the nearest double and the nearest double to the rest), to 1e-30.
    #[test]
    fn exp_matches_values_computed_apart() {
        for (x, hi, lo) in [
            (1.0, std::f64::consts::E, 1.4456468917292502e-16),
            (-0.5, 0.6065306597126334, -6.593178415491414e-19),
            (10.0, 22026.465794806718, -1.3780134700517372e-12),
            (0.0078125, 1.007843097206448, -6.872774751042842e-17),
            (-20.0, 2.061153622438558e-09, -4.19755767595054e-26),
        ] {
            let expected = Dd { hi, lo };
            let relative = ((Dd::exact(x).exp() - expected) / expected).hi.abs();
            assert!(relative < 1e-30, "e^{x}: {relative:e}");
        }
    }

    /// The processor's fused multiply-add and the library's give the same e^x to the bit.
    #[test]
    fn exp_is_the_same_with_and_without_the_processors_fma() {
        let values = || {
            (-2000..2000)
                .map(|i| {
                    let x = Dd::new(
                        f64::from(i) * 0.173_205_080_756_887_72,
                        f64::from(i) * 1e-19,
                    );
                    let e = x.exp();
                    (e.hi.to_bits(), e.lo.to_bits())
                })
                .collect::<Vec<_>>()
        };
        let fused = values();
        super::set_fma_in_use(false);
        let library = values();
        super::set_fma_in_use(true);
        assert_eq!(fused, library);
    }

    /// e^x against the product of its factors: e^(a + b) = e^a e^b for exact doubles a and b
    /// (each found independently), and e^(ln 2 k) = 2^k; and e^x e^-x = 1, all to 1e-29.
    #[test]
    fn exp_is_good_to_twice_the_precision() {
        let close = |a: Dd, b: Dd| ((a - b) / b).hi.abs();
        for (a, b) in [(0.375, 1.25), (-3.5, 0.0625), (10.0, -0.5), (1e-3, 2e-3)] {
            let together = Dd::exact(a + b).exp();
            let apart = Dd::exact(a).exp() * Dd::exact(b).exp();
            assert!(close(together, apart) < 1e-29, "{a} + {b}");
        }
        for x in [0.1, 1.0, 3.7, 12.5, -20.0, 1e-9] {
            let one = Dd::exact(x).exp() * Dd::exact(-x).exp();
            assert!(close(one, Dd::exact(1.0)) < 1e-29, "{x}");
            // The double part is the double exp within its own rounding.
            assert!((Dd::exact(x).exp().hi / x.exp() - 1.0).abs() < 4e-16);
        }
        let sixteen = (super::LN_2 * 4.0).exp();
        assert!(close(sixteen, Dd::exact(16.0)) < 1e-29);
    }
}
