//! The one view every solver has of a floor motion: its acceleration, its breakpoints and its
//! closed form on each piece.

use super::closed_form::ClosedForm;

/// A prescribed horizontal floor acceleration a(t) = u0''(t).
pub trait FloorMotion: std::any::Any + Send + Sync {
    /// Floor acceleration at time `t` (s), m/s^2.
    fn acceleration(&self, t: f64) -> f64;

    /// Times (s, increasing) at which a(t) or one of its derivatives jumps. Adaptive solvers stop
    /// and restart there so that their order is not spoiled by integrating across a kink.
    fn breakpoints(&self) -> &[f64] {
        &[]
    }

    /// True when a(t) itself jumps at the breakpoint `t` (not only its slope): an adaptive
    /// multistep method must then restart there, as at an event.
    fn jumps_at(&self, _t: f64) -> bool {
        false
    }

    /// Largest |a(t)| over the motion, m/s^2 (for a pulse of less than a quarter cycle, a bound).
    fn peak_acceleration(&self) -> f64;

    /// A time after which the floor is at rest for good (a(t) = 0), if there is one: the end of a
    /// pulse or a record. A solver may take the rest of the run as free motion.
    fn quiet_after(&self) -> Option<f64> {
        None
    }

    /// The period of an analytic motion (sine, pulse), s; None for records and free vibration.
    fn period(&self) -> Option<f64> {
        None
    }

    /// A short name for reports, e.g. `paper-sine`.
    fn kind(&self) -> &'static str;

    /// The parameters as understood (including derived ones), for result files.
    fn parameters(&self) -> serde_json::Value;

    /// The closed form of a(t) on the stretch of the motion that holds `t` (s, t >= 0), and where
    /// that stretch ends: the exact solver's view of the motion. It must agree with
    /// [`FloorMotion::acceleration`] to rounding (or within the stated error bound).
    fn closed_form(&self, t: f64) -> ClosedForm;

    /// The nominal length of the closed form's stretches where they are the intervals between
    /// a record's samples (its dt, s), each linear: the exact solver carries the state across
    /// such an interval by a recurrence it builds once for that length. None for other motions.
    fn sample_interval(&self) -> Option<f64> {
        None
    }
}
