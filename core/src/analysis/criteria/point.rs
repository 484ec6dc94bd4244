//! One point of the criteria study: a body, an excitation and a period, with the smallest
//! overturning amplitudes of the body, Housner's block and the model's rigid limit.

use serde::Serialize;

use super::study::Excitation;

/// One body under one floor motion: the elastic body's and the rigid blocks' critical values.
#[derive(Debug, Clone, Serialize)]
pub struct Point {
    /// `body.self_weight`.
    pub self_weight: String,
    /// B/H.
    pub slenderness: f64,
    /// B, m.
    pub width: f64,
    /// H, m.
    pub height: f64,
    /// The excitation's family ([`Excitation::name`]).
    pub excitation: String,
    /// Tp, s (sines and pulses).
    pub period: Option<f64>,
    /// E, Pa.
    pub youngs_modulus: f64,
    /// phi = p T; None for a body that could not be run (`reason` says why).
    pub flexibility: Option<f64>,
    /// T, s; None likewise.
    pub pre_uplift_period: Option<f64>,
    /// p, rad/s; None likewise.
    pub p: Option<f64>,
    /// The floor's peak acceleration per unit of the searched key (1 for the pulses).
    pub pga_per_unit: f64,
    /// The floor's peak velocity per unit of the searched key, m/s.
    pub pgv_per_unit: f64,
    /// The smallest overturning peak acceleration of the elastic body, m/s^2.
    pub critical_pga: Option<f64>,
    /// The largest value below it found to leave the body standing, m/s^2.
    pub safe_below_pga: Option<f64>,
    /// The scanned bands that overturned, in the searched key's units.
    pub bands: String,
    /// Number of such bands.
    pub n_bands: usize,
    /// Housner's block, full equation, m/s^2.
    pub rigid_full_pga: Option<f64>,
    /// Housner's block, small-angle equation, m/s^2.
    pub rigid_small_angle_pga: Option<f64>,
    /// The elastic model's rigid limit (small-angle, uplift at 1.1226 g B/H), m/s^2.
    pub rigid_limit_pga: Option<f64>,
    /// Why the point has no values (empty when it has).
    pub reason: String,
}

impl Point {
    /// The critical peak velocity of the same motion, m/s.
    pub fn critical_pgv(&self) -> Option<f64> {
        self.critical_pga
            .map(|a| a / self.pga_per_unit * self.pgv_per_unit)
    }

    /// A rigid value's peak velocity, m/s.
    pub fn pgv_of(&self, pga: Option<f64>) -> Option<f64> {
        pga.map(|a| a / self.pga_per_unit * self.pgv_per_unit)
    }

    /// True for a floor motion whose acceleration starts from zero (no jump at t = 0): the
    /// sines and one-sine pulses. The one-cosine pulse starts at its peak, a step that sets an
    /// elastic body vibrating however stiff it is; records are left out as well, since their
    /// first overturning scale can jump between narrow bands from one body to the next.
    pub fn is_smooth(&self) -> bool {
        self.excitation == Excitation::Sine.name() || self.excitation == Excitation::OneSine.name()
    }

    /// True when the body overturned at the bottom of the searched interval (its first scanned
    /// value): the critical value is then only an upper bound of the true one.
    pub fn at_interval_bottom(&self) -> bool {
        self.critical_pga.is_some() && self.safe_below_pga.is_none()
    }

    /// critical / reference - 1, when both are known.
    pub fn relative_difference(&self, reference: Option<f64>) -> Option<f64> {
        Some(self.critical_pga? / reference? - 1.0)
    }
}
