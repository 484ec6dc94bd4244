//! `intensity_measures` and `response_spectrum`: a ground motion's intensity measures, computed
//! by the core exactly as `flexrock record intensity` and `flexrock record spectrum` compute
//! them.

use numpy::PyArray1;
use pyo3::prelude::*;
use pyo3::types::PyDict;

use flexrock_core::bodies::oscillator;
use flexrock_core::floor::intensity;
use flexrock_core::floor::RecordedMotion;
use flexrock_core::model::STANDARD_GRAVITY;

use crate::model::Model;
use crate::motion::GroundMotion;
use crate::FlexrockError;

/// The motion of `source` (a GroundMotion, or a Model whose excitation is a record: its motion
/// as the model applies it, scaled and trimmed) and the period of Sa by default (None for a
/// GroundMotion, the body's pre-uplift period T for a Model).
fn motion_of(source: &Bound<'_, PyAny>) -> PyResult<(RecordedMotion, Option<f64>)> {
    if let Ok(motion) = source.cast::<GroundMotion>() {
        return Ok((motion.get().motion.recorded(), None));
    }
    if let Ok(model) = source.cast::<Model>() {
        let m = model.get().state().model;
        return match RecordedMotion::of(m.floor.as_ref()) {
            Some(record) => Ok((record.clone(), Some(m.constants.period))),
            None => Err(FlexrockError::new_err(format!(
                "the model's excitation is kind = \"{}\", not a record: intensity measures are \
                 a recorded motion's",
                m.floor.kind()
            ))),
        };
    }
    Err(FlexrockError::new_err(
        "give a GroundMotion, or a Model whose excitation is a record",
    ))
}

fn invalid(e: impl std::fmt::Display) -> PyErr {
    FlexrockError::new_err(e.to_string())
}

/// A ground motion's intensity measures, computed exactly for the motion flexrock applies
/// (the samples, linear between them; no baseline correction, no filtering).
///
/// Parameters
/// ----------
/// motion : GroundMotion or Model
///     A GroundMotion, or a Model whose excitation is a record (its motion as the model
///     applies it: scaled and trimmed).
/// period : float, optional
///     The period of Sa, s [default: the body's pre-uplift period T for a Model; none for a
///     GroundMotion].
/// damping : float
///     The damping ratio of Sa's oscillator [default: 0.05].
///
/// Returns
/// -------
/// dict
///     ``pga`` (m/s^2), ``pga_g``, ``t_pga`` (s); ``pgv`` (m/s), ``t_pgv``; ``pgd`` (m),
///     ``t_pgd`` (the exact integrals from rest, their peaks between samples included);
///     ``arias`` (m/s), ``cav`` (m/s); with a period, ``sa`` (m/s^2, the pseudo-acceleration
///     omega^2 max |u|, between samples included), ``sa_g``, ``sd`` (m), ``t_sa`` (s),
///     ``sa_at_samples`` (m/s^2, the peak over the samples alone), ``period``, ``damping``.
#[pyfunction]
#[pyo3(signature = (motion, period=None, damping=oscillator::DEFAULT_DAMPING))]
pub(crate) fn intensity_measures<'py>(
    py: Python<'py>,
    motion: &Bound<'py, PyAny>,
    period: Option<f64>,
    damping: f64,
) -> PyResult<Bound<'py, PyDict>> {
    let (recorded, default_period) = motion_of(motion)?;
    let period = period.or(default_period);
    if let Some(period) = period {
        oscillator::check_oscillator("period", period, "damping", damping).map_err(invalid)?;
    }
    let (ground, sa) = py
        .detach(|| -> Result<_, flexrock_core::integrate::SolverError> {
            let ground = intensity::ground_measures(&recorded);
            let sa = period
                .map(|p| oscillator::spectral_acceleration(&recorded, p, damping))
                .transpose()?;
            Ok((ground, sa))
        })
        .map_err(invalid)?;
    let out = PyDict::new(py);
    out.set_item("pga", ground.pga)?;
    out.set_item("pga_g", ground.pga / STANDARD_GRAVITY)?;
    out.set_item("t_pga", ground.t_pga)?;
    out.set_item("pgv", ground.pgv)?;
    out.set_item("t_pgv", ground.t_pgv)?;
    out.set_item("pgd", ground.pgd)?;
    out.set_item("t_pgd", ground.t_pgd)?;
    out.set_item("arias", ground.arias)?;
    out.set_item("cav", ground.cav)?;
    if let Some(s) = sa {
        out.set_item("sa", s.sa)?;
        out.set_item("sa_g", s.sa / STANDARD_GRAVITY)?;
        out.set_item("sd", s.sd)?;
        out.set_item("t_sa", s.t_peak)?;
        out.set_item("sa_at_samples", s.sa_at_samples)?;
        out.set_item("period", s.period)?;
        out.set_item("damping", s.damping)?;
    }
    Ok(out)
}

/// The pseudo-acceleration response spectrum of a ground motion.
///
/// Parameters
/// ----------
/// motion : GroundMotion or Model
///     As for `intensity_measures`.
/// periods : sequence of float, optional
///     Periods, s [default: 0.01 s to 10 s, 20 a decade on a logarithmic scale].
/// damping : float
///     The damping ratio of the oscillators [default: 0.05].
///
/// Returns
/// -------
/// dict of numpy arrays
///     ``period`` (s), ``sa`` (m/s^2), ``sd`` (m), ``t_peak`` (s), ``sa_at_samples`` (m/s^2).
#[pyfunction]
#[pyo3(signature = (motion, periods=None, damping=oscillator::DEFAULT_DAMPING))]
pub(crate) fn response_spectrum<'py>(
    py: Python<'py>,
    motion: &Bound<'py, PyAny>,
    periods: Option<Vec<f64>>,
    damping: f64,
) -> PyResult<Bound<'py, PyDict>> {
    let (recorded, _) = motion_of(motion)?;
    let periods = periods.unwrap_or_else(oscillator::default_periods);
    let ordinates = py
        .detach(|| oscillator::spectrum(&recorded, &periods, damping))
        .map_err(invalid)?;
    let out = PyDict::new(py);
    let column = |f: fn(&oscillator::SpectralOrdinate) -> f64| {
        PyArray1::from_iter(py, ordinates.iter().map(f))
    };
    out.set_item("period", column(|s| s.period))?;
    out.set_item("sa", column(|s| s.sa))?;
    out.set_item("sd", column(|s| s.sd))?;
    out.set_item("t_peak", column(|s| s.t_peak))?;
    out.set_item("sa_at_samples", column(|s| s.sa_at_samples))?;
    Ok(out)
}
