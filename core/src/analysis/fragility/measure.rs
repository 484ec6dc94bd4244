//! The intensity measures a fragility function can be expressed in, and how each scales with
//! the factor on a record.

use serde::Serialize;

/// An intensity measure of a record (see [`crate::floor::intensity`] and Sa(T, 5 %)).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum Measure {
    /// Peak ground acceleration, g.
    Pga,
    /// Peak ground velocity, m/s.
    Pgv,
    /// Peak ground displacement, m.
    Pgd,
    /// Arias intensity, m/s.
    Arias,
    /// Cumulative absolute velocity, m/s.
    Cav,
    /// Spectral acceleration Sa(T, 5 %), g.
    Sa,
}

impl Measure {
    /// Every measure, in the order the help lists them.
    pub const ALL: [Measure; 6] = [
        Measure::Pga,
        Measure::Pgv,
        Measure::Pgd,
        Measure::Arias,
        Measure::Cav,
        Measure::Sa,
    ];

    /// Reads `text` (pga, pgv, pgd, arias, cav, sa); the error names `flag`.
    pub fn parse(flag: &str, text: &str) -> crate::Result<Measure> {
        Measure::ALL
            .into_iter()
            .find(|m| m.name() == text)
            .ok_or_else(|| {
                crate::Error::invalid(flag, text, "must be one of pga, pgv, pgd, arias, cav, sa")
            })
    }

    /// Its name on the command line.
    pub fn name(self) -> &'static str {
        match self {
            Measure::Pga => "pga",
            Measure::Pgv => "pgv",
            Measure::Pgd => "pgd",
            Measure::Arias => "arias",
            Measure::Cav => "cav",
            Measure::Sa => "sa",
        }
    }

    /// Its unit, as the tables write it.
    pub fn unit(self) -> &'static str {
        match self {
            Measure::Pga | Measure::Sa => "g",
            Measure::Pgv | Measure::Arias | Measure::Cav => "m/s",
            Measure::Pgd => "m",
        }
    }

    /// Its column in a sweep.csv over records.
    pub fn sweep_column(self) -> &'static str {
        match self {
            Measure::Pga => "pga_g",
            Measure::Pgv => "pgv_m_s",
            Measure::Pgd => "pgd_m",
            Measure::Arias => "arias_m_s",
            Measure::Cav => "cav_m_s",
            Measure::Sa => "sa_g",
        }
    }

    /// The power of the record's factor the measure scales with: 2 for the Arias intensity
    /// (an integral of a^2), 1 for the others (peaks, Sa of a linear oscillator, and CAV, an
    /// integral of |a|).
    pub fn scale_power(self) -> i32 {
        match self {
            Measure::Arias => 2,
            _ => 1,
        }
    }

    /// The measure of a record multiplied by `scale`, from its measure `unscaled` at scale 1.
    pub fn scaled(self, unscaled: f64, scale: f64) -> f64 {
        unscaled * scale.powi(self.scale_power())
    }

    /// The factor that brings a record of measure `unscaled` to `level`.
    pub fn scale_to(self, unscaled: f64, level: f64) -> f64 {
        match self.scale_power() {
            1 => level / unscaled,
            _ => (level / unscaled).sqrt(),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn scaling() {
        assert_eq!(Measure::Pga.scaled(0.3, 2.0), 0.6);
        assert_eq!(Measure::Arias.scaled(0.3, 2.0), 1.2);
        assert_eq!(Measure::Arias.scale_to(0.3, 1.2), 2.0);
        assert_eq!(Measure::Cav.scale_to(0.5, 1.5), 3.0);
        assert!(Measure::parse("--im", "pgx").is_err());
        assert_eq!(Measure::parse("--im", "sa").unwrap(), Measure::Sa);
    }
}
