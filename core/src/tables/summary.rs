//! summary.json of a solved model: its peaks, events, warnings and everything it was made
//! from (the command line writes it; the Python bindings return it as a dict).

use serde::Serialize;

use crate::floor::RecordedMotion;
use crate::integrate::solution::{RoundingEstimate, Solution, SolverStats};
use crate::integrate::{InitialState, SolverSettings};
use crate::model::{Model, ModelFile};
use crate::physics::automaton::EventKind;
use crate::physics::body::Body;
use crate::physics::constants::Constants;
use crate::simulate::{warnings, Provenance};

/// summary.json of `flexrock run`.
#[derive(Debug, Serialize)]
pub struct RunSummary<'a> {
    /// Which flexrock wrote the file, from which model file.
    #[serde(flatten)]
    pub provenance: Provenance,
    /// Largest q, m.
    pub max_q: f64,
    /// When q was largest, s.
    pub t_max_q: f64,
    /// Smallest q, m.
    pub min_q: f64,
    /// When q was smallest, s.
    pub t_min_q: f64,
    /// Largest |s| (flexural part) and |r| (rocking part), m.
    pub max_abs_s: f64,
    /// Largest |r|, the rocking part, m.
    pub max_abs_r: f64,
    /// Number of uplifts.
    pub n_uplift: usize,
    /// Number of landings.
    pub n_landing: usize,
    /// Whether the body fell over.
    pub overturned: bool,
    /// When it fell over, s.
    pub t_overturn: Option<f64>,
    /// s_n, the uplift displacement, m.
    pub s_n: f64,
    #[serde(rename = "T")]
    /// T, the pre-uplift period, s.
    pub period: f64,
    /// Largest |energy_residual| over the samples, J.
    pub max_energy_residual: f64,
    /// The energies the residual is measured against, J (see [`Solution::energy_scale`]).
    pub energy_scale: f64,
    /// Time the run ended, s.
    pub final_time: f64,
    /// The mode at the end of the run.
    pub final_mode: &'static str,
    /// The run ended with the body rocking: no overturning within the duration, no more.
    pub ended_while_rocking: bool,
    /// What a reader of the result must know (also printed on stderr).
    pub warnings: Vec<String>,
    /// The solver and its settings.
    pub solver: &'a SolverSettings,
    /// What the solution cost.
    pub statistics: &'a SolverStats,
    /// The derived constants.
    pub constants: &'a Constants,
    /// The validated body.
    pub body: &'a Body,
    /// The floor motion's parameters.
    pub excitation: serde_json::Value,
    /// q and q' at t = 0.
    pub initial_state: InitialState,
    /// Simulated time, s.
    pub duration: f64,
    /// The model file as read, with command-line overrides applied.
    pub inputs: &'a ModelFile,
    /// The exact method's estimate of its own error on each event time and on the peaks
    /// (absent for the other methods).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub error_estimate: Option<&'a RoundingEstimate>,
}

/// summary.json of a solved model.
pub fn summary<'a>(model: &'a Model, solution: &'a Solution) -> RunSummary<'a> {
    RunSummary {
        provenance: Provenance::of(model),
        max_q: solution.max_q.value,
        t_max_q: solution.max_q.t,
        min_q: solution.min_q.value,
        t_min_q: solution.min_q.t,
        max_abs_s: solution.max_abs_s,
        max_abs_r: solution.max_abs_r,
        n_uplift: solution.count(EventKind::Uplift),
        n_landing: solution.count(EventKind::Landing),
        overturned: solution.overturned,
        t_overturn: solution.t_overturn,
        s_n: model.constants.uplift_displacement,
        period: model.constants.period,
        max_energy_residual: solution.max_energy_residual,
        energy_scale: solution.energy_scale,
        final_time: solution.final_time,
        final_mode: solution.final_mode.name(),
        ended_while_rocking: solution.ended_while_rocking(),
        warnings: warnings(model, solution),
        solver: &model.solver,
        statistics: &solution.stats,
        constants: &model.constants,
        body: &model.body,
        excitation: excitation_parameters(model),
        initial_state: model.initial,
        duration: model.duration,
        inputs: &model.file,
        error_estimate: solution.rounding.as_ref(),
    }
}

/// The floor motion's parameters; a record's intensity measures with its Sa(T, 5 %) at the
/// body's pre-uplift period T.
fn excitation_parameters(model: &Model) -> serde_json::Value {
    use crate::bodies::oscillator;
    let mut parameters = model.floor.parameters();
    if let Some(record) = RecordedMotion::of(model.floor.as_ref()) {
        let period = model.constants.period;
        if let Ok(measures) =
            oscillator::intensity_measures(record, period, oscillator::DEFAULT_DAMPING)
        {
            parameters["intensity"] = serde_json::json!(measures);
        }
    }
    parameters
}
