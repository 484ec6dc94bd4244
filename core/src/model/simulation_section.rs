//! The `[simulation]` section's rules: the run's duration and the initial state.

use super::schema::{ExcitationSection, SimulationSection, MAX_DURATION, MAX_INITIAL_VELOCITY};
use crate::error::{Error, Result};
use crate::integrate::InitialState;
use crate::physics::body::{positive, Body};

/// The simulated time, s: `given` (`simulation.duration`), else the excitation's natural length
/// `natural` (a record's or a pulse's, with its tail); positive and at most [`MAX_DURATION`].
/// A natural length beyond it is blamed on the tail that made it.
pub(super) fn run_duration(
    given: Option<f64>,
    natural: Option<f64>,
    excitation: &ExcitationSection,
) -> Result<f64> {
    // Formatted only for a message: this is read at every point of a sweep.
    let rule = || {
        format!(
            "must be at most {MAX_DURATION:e} s: no earthquake or shaking-table test lasts \
             nearly that long"
        )
    };
    match (given, natural) {
        (Some(d), _) => {
            positive("simulation.duration", d)?;
            if d > MAX_DURATION {
                return Err(Error::invalid("simulation.duration", d, &rule()));
            }
            Ok(d)
        }
        (None, Some(d)) => {
            if !(d > 0.0 && d <= MAX_DURATION) {
                // Blamed on the tail, unless the motion alone is too long.
                let tail = excitation.tail.unwrap_or(0.0);
                let (key, value) = match excitation.kind.as_str() {
                    _ if d - tail <= MAX_DURATION => {
                        ("excitation.tail", crate::base::format::shortest(tail))
                    }
                    "sine-pulse" => (
                        "excitation.cycles",
                        format!(
                            "{} (with excitation.period = {})",
                            crate::base::format::shortest(excitation.cycles.unwrap_or(1.0)),
                            crate::base::format::shortest(excitation.period.unwrap_or(0.0))
                        ),
                    ),
                    _ => {
                        return Err(Error::invalid(
                            "excitation.path",
                            excitation.path.clone().unwrap_or_default(),
                            &format!(
                                "the record lasts {} s: with no simulation.duration the run lasts \
                             the record and the tail, which {rule} (give simulation.duration \
                             or excitation.end)",
                                crate::base::format::shortest(d - tail),
                                rule = rule()
                            ),
                        ))
                    }
                };
                return Err(Error::invalid(
                    key,
                    value,
                    &format!(
                        "with no simulation.duration the run lasts the {} ({} s) and the tail, \
                         {} s in all, which {rule}",
                        excitation.kind,
                        crate::base::format::shortest(d - tail),
                        crate::base::format::shortest(d),
                        rule = rule()
                    ),
                ));
            }
            Ok(d)
        }
        (None, None) => Err(Error::invalid(
            "simulation.duration",
            "(missing)",
            &format!(
                "required for kind = \"{}\" (records, and sine pulses with excitation.tail, have \
                 a natural length)",
                excitation.kind
            ),
        )),
    }
}

pub(super) fn initial_from_section(s: &SimulationSection, body: &Body) -> Result<InitialState> {
    let q = s.q0.unwrap_or(0.0);
    let qdot = s.qdot0.unwrap_or(0.0);
    if !(q.is_finite() && q.abs() < body.width) {
        return Err(Error::invalid(
            "simulation.q0",
            q,
            &format!(
                "the initial top displacement must satisfy |q0| < B = {} m (at |q0| >= B the body has already overturned)",
                body.width
            ),
        ));
    }
    if qdot.is_nan() || qdot.abs() > MAX_INITIAL_VELOCITY {
        return Err(Error::invalid(
            "simulation.qdot0",
            qdot,
            &format!(
                "must lie within +-{MAX_INITIAL_VELOCITY} m/s: far beyond any velocity a floor gives a body \
                 (earthquake ground velocities stay within a few m/s)"
            ),
        ));
    }
    Ok(InitialState { q, qdot })
}
