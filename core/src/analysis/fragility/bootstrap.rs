//! Resampling over records, for the intervals of a fit.
//!
//! The generator is SplitMix64 (Steele, Lea and Flood 2014), written here rather than taken
//! from a crate: a reported seed must give the same draws in every later version of flexrock,
//! and a crate's stream may change with its major version. It passes BigCrush; the draws of an
//! index are made without modulo bias by rejection.

/// SplitMix64.
#[derive(Debug, Clone)]
pub struct SplitMix64(u64);

impl SplitMix64 {
    /// The generator started from `seed`.
    pub fn new(seed: u64) -> Self {
        SplitMix64(seed)
    }

    /// The next 64 bits.
    pub fn next_u64(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9e37_79b9_7f4a_7c15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
        z ^ (z >> 31)
    }

    /// A uniform index below `n` (n > 0).
    pub fn index(&mut self, n: usize) -> usize {
        let n = n as u64;
        let zone = u64::MAX - u64::MAX % n;
        loop {
            let x = self.next_u64();
            if x < zone {
                return (x % n) as usize;
            }
        }
    }
}

/// `samples` resamples of `n` records drawn with replacement, each passed to `fit`; the fits
/// that succeed, and the number that did not (a resample of one record drawn n times has no
/// dispersion).
pub fn resample<T, E>(
    n: usize,
    samples: usize,
    seed: u64,
    fit: impl Fn(&[usize]) -> Result<T, E>,
) -> (Vec<T>, usize) {
    let mut rng = SplitMix64::new(seed);
    let mut fits = Vec::with_capacity(samples);
    let mut failed = 0;
    let mut drawn = vec![0; n];
    for _ in 0..samples {
        for slot in drawn.iter_mut() {
            *slot = rng.index(n);
        }
        match fit(&drawn) {
            Ok(f) => fits.push(f),
            Err(_) => failed += 1,
        }
    }
    (fits, failed)
}

/// The `q`-quantile (0 to 1) of `values`, linear between order statistics (the definition of
/// numpy's default, Hyndman and Fan's type 7). None for no values.
pub fn quantile(values: &[f64], q: f64) -> Option<f64> {
    if values.is_empty() {
        return None;
    }
    let mut sorted = values.to_vec();
    sorted.sort_by(f64::total_cmp);
    let h = (sorted.len() - 1) as f64 * q;
    let (lo, frac) = (h.floor() as usize, h - h.floor());
    let hi = (lo + 1).min(sorted.len() - 1);
    Some(sorted[lo] + frac * (sorted[hi] - sorted[lo]))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn splitmix_reference_values() {
        // The reference outputs of SplitMix64 from seed 1234567 (Vigna's splitmix64.c).
        let mut rng = SplitMix64::new(1_234_567);
        assert_eq!(rng.next_u64(), 6_457_827_717_110_365_317);
        assert_eq!(rng.next_u64(), 3_203_168_211_198_807_973);
    }

    #[test]
    fn quantiles_as_numpy() {
        // numpy.quantile([1, 2, 3, 4], 0.05) = 1.15, 0.95 -> 3.85.
        let v = [4.0, 1.0, 3.0, 2.0];
        assert!((quantile(&v, 0.05).unwrap() - 1.15).abs() < 1e-12);
        assert!((quantile(&v, 0.95).unwrap() - 3.85).abs() < 1e-12);
        assert_eq!(quantile(&[], 0.5), None);
    }
}
