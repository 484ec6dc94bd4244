//! Floor motions. Every solver sees an excitation only through the [`FloorMotion`] trait, so new
//! kinds (recorded ground motions, pulses) need no change in any solver.

mod closed_form;
mod free;
mod harmonic;
pub mod intensity;
mod limits;
mod motion;
mod paper_sine;
mod pulse;
pub mod record;
mod recorded;
mod scaled;
mod shaking;

pub use closed_form::{ClosedForm, Shape, MAX_DEGREE};
pub use free::Free;
pub use harmonic::Harmonic;
pub use limits::{
    above_floor_minimum, floor_limit_rule, floor_minimum_rule, within_floor_limit,
    MAX_FLOOR_ACCELERATION, MIN_EXCITATION_PERIOD, MIN_FLOOR_ACCELERATION,
};
pub use motion::FloorMotion;
pub use paper_sine::PaperSine;
pub use pulse::{PulseShape, Ricker, SinePulse};
pub use recorded::RecordedMotion;
pub use scaled::Scaled;
pub use shaking::{LiftOff, Shaking};
