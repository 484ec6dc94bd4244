//! Solving a model: [`simulate`] with the solver its file names, [`simulate_with`] other
//! settings, [`simulate_peaks`] without a history; [`properties`], the body and its derived
//! constants as `flexrock props` shows them.

use serde::Serialize;

use crate::automaton::Automaton;
use crate::body::Body;
use crate::constants::Constants;
use crate::error::Result;
use crate::model::Model;
use crate::solution::Solution;
use crate::solver::{adaptive, newmark};
use crate::solver::{History, SolverSettings};

/// Version of flexrock that made a result.
pub const VERSION: &str = env!("CARGO_PKG_VERSION");

/// Solves a model with the solver its settings name.
pub fn simulate(model: &Model) -> Result<Solution> {
    simulate_with(model, &model.solver)
}

/// Solves a model with the given solver settings instead of its own.
pub fn simulate_with(model: &Model, settings: &SolverSettings) -> Result<Solution> {
    solve(model, settings, History::Sampled)
}

/// Solves a model with its own solver, keeping no history: events, peaks and statistics only
/// (what a sweep needs of each of its points).
pub fn simulate_peaks(model: &Model) -> Result<Solution> {
    solve(model, &model.solver, History::PeaksOnly)
}

fn solve(model: &Model, settings: &SolverSettings, history: History) -> Result<Solution> {
    let automaton = Automaton::new(&model.constants);
    let (floor, initial, duration) = (model.floor.as_ref(), model.initial, model.duration);
    let solution = match settings {
        SolverSettings::Adaptive(s) => {
            adaptive::solve(&automaton, floor, initial, duration, s, history)
        }
        SolverSettings::Newmark(s) => {
            newmark::solve(&automaton, floor, initial, duration, s, history)
        }
    };
    Ok(solution?)
}

/// The head of every summary flexrock writes (summary.json, compare.json, convergence.json,
/// fem_summary.json, pushover.json, `props --json`): which flexrock made it, from which model file.
#[derive(Debug, Clone, Serialize)]
pub struct Provenance {
    /// The version of flexrock that wrote the file.
    pub flexrock_version: &'static str,
    /// The model file read, if any.
    pub model_file: Option<String>,
}

impl Provenance {
    /// The provenance of results computed from `model`.
    pub fn of(model: &Model) -> Self {
        Provenance {
            flexrock_version: VERSION,
            model_file: model.path.as_ref().map(|p| p.display().to_string()),
        }
    }
}

/// What `flexrock props` prints: the body as understood and its derived constants.
#[derive(Debug, Serialize)]
pub struct Properties<'a> {
    /// Which flexrock computed the properties, from which model file.
    #[serde(flatten)]
    pub provenance: Provenance,
    /// The validated body.
    pub body: &'a Body,
    /// The constants derived from it.
    pub constants: &'a Constants,
}

/// The body of a model and its derived constants, with the version and the model file.
pub fn properties(model: &Model) -> Properties<'_> {
    Properties {
        provenance: Provenance::of(model),
        body: &model.body,
        constants: &model.constants,
    }
}
