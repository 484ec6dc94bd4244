//! Solving a model: [`simulate`] with the solver its file names, [`simulate_with`] other
//! settings, [`simulate_peaks`] without a history; [`properties`], the body and its derived
//! constants as `flexrock props` shows them.

use serde::Serialize;

use crate::error::Result;
use crate::floor::RecordedMotion;
use crate::integrate::solution::{RoundingEstimate, Solution};
use crate::integrate::{adaptive, exact, newmark};
use crate::integrate::{History, SolverSettings};
use crate::model::Model;
use crate::physics::automaton::{Automaton, EventKind};
use crate::physics::body::{Body, SelfWeight};
use crate::physics::constants::{
    Constants, SELF_WEIGHT_BUCKLING_PARAMETER, SELF_WEIGHT_WARNING_SHARE,
};

/// Version of flexrock that made a result.
pub const VERSION: &str = env!("CARGO_PKG_VERSION");

/// The git commit flexrock was built from (its hash), or "unknown" when it was built without
/// git or outside a git work tree (build.rs).
pub const COMMIT: &str = env!("FLEXROCK_COMMIT");

/// Whether the program's sources (core/, src/, the manifests) differed from [`COMMIT`] when
/// flexrock was built; None when unknown.
pub const DIRTY: Option<bool> = match env!("FLEXROCK_DIRTY").as_bytes() {
    b"true" => Some(true),
    b"false" => Some(false),
    _ => None,
};

/// Solves a model with the solver its settings name.
pub fn simulate(model: &Model) -> Result<Solution> {
    simulate_with(model, &model.solver)
}

/// Solves a model with the given solver settings instead of its own.
pub fn simulate_with(model: &Model, settings: &SolverSettings) -> Result<Solution> {
    solve(model, settings, History::Sampled)
}

/// Solves a row of columns (its own exact method, or Tsit45 under the compliant contact law)
/// keeping every column's history.
pub fn simulate_row(model: &crate::model::RowModel) -> Result<crate::bodies::row::RowSolution> {
    if let Some(settings) = &model.compliant {
        return Ok(crate::bodies::row::solve_row_compliant(
            &model.row,
            model.floor.as_ref(),
            model.duration,
            settings,
            History::Sampled,
        )?);
    }
    Ok(crate::bodies::row::solve_row(
        &model.row,
        model.floor.as_ref(),
        model.duration,
        &model.settings,
        History::Sampled,
    )?)
}

/// Solves a model with its own solver, keeping no history: events, peaks and statistics only
/// (what a sweep needs of each of its points).
pub fn simulate_peaks(model: &Model) -> Result<Solution> {
    solve(model, &model.solver, History::PeaksOnly)
}

fn solve(model: &Model, settings: &SolverSettings, history: History) -> Result<Solution> {
    refuse_vertical(model, "the elastic body's solvers")?;
    let automaton = Automaton::new(&model.constants);
    let (floor, initial, duration) = (model.floor.as_ref(), model.initial, model.duration);
    let solution = match settings {
        SolverSettings::Adaptive(s) => {
            adaptive::solve(&automaton, floor, initial, duration, s, history)
        }
        SolverSettings::Newmark(s) => {
            newmark::solve(&automaton, floor, initial, duration, s, history)
        }
        SolverSettings::Exact(s) => exact::solve(&automaton, floor, initial, duration, s, history),
    };
    Ok(solution?)
}

/// Runs the rigid block `block` alone on the floor of `model` (both its motions), from rest,
/// over the model's duration, with the block's default settings.
pub fn simulate_rigid(
    model: &Model,
    block: &crate::bodies::rigid::RigidBlock,
) -> Result<crate::bodies::rigid::RigidOutcome> {
    Ok(crate::bodies::rigid::simulate_shaken(
        block,
        &model.shaking(),
        crate::integrate::InitialState { q: 0.0, qdot: 0.0 },
        model.duration,
        &crate::bodies::rigid::RigidSettings::for_block(block),
    )?)
}

/// Refuses a model with vertical floor motion for `what`, which does not take it: the rigid
/// block alone does so far.
pub fn refuse_vertical(model: &Model, what: &str) -> Result<()> {
    match &model.vertical {
        None => Ok(()),
        Some(v) => Err(crate::error::Error::invalid(
            "excitation.vertical",
            format!("kind = \"{}\"", v.kind()),
            &format!(
                "{what} do not take vertical floor motion yet; Housner's rigid block does \
                 (`flexrock rigid`, flexrock.rigid_block in Python): leave [excitation.vertical] \
                 out for the elastic body"
            ),
        )),
    }
}

/// The head of every summary flexrock writes (summary.json, compare.json, convergence.json,
/// fem_summary.json, pushover.json, `props --json`): which flexrock made it, from which model file.
#[derive(Debug, Clone, Serialize)]
pub struct Provenance {
    /// The version of flexrock that wrote the file.
    pub flexrock_version: &'static str,
    /// The commit it was built from; None where it is kept apart (the command line's
    /// `--timings-apart` puts it in timings.json, so that the file is the same for every commit).
    #[serde(flatten)]
    pub build: Option<Commit>,
    /// The model file read, if any.
    pub model_file: Option<String>,
}

impl Provenance {
    /// The provenance of results computed from `model`.
    pub fn of(model: &Model) -> Self {
        Provenance {
            flexrock_version: VERSION,
            build: Some(Commit::BUILT),
            model_file: model.path.as_ref().map(|p| p.display().to_string()),
        }
    }
}

/// The commit a flexrock was built from, as the summaries write it.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
pub struct Commit {
    /// Its hash, or "unknown" ([`COMMIT`]).
    pub flexrock_commit: &'static str,
    /// Whether the program's sources differed from it; null when unknown ([`DIRTY`]).
    pub flexrock_dirty: Option<bool>,
}

impl Commit {
    /// This build's.
    pub const BUILT: Commit = Commit {
        flexrock_commit: COMMIT,
        flexrock_dirty: DIRTY,
    };
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

/// Share of the energy scale above which the energy residual is reported as a warning.
pub const ENERGY_RESIDUAL_WARNING_SHARE: f64 = 1e-2;

/// The warning of a model whose duration ends before its record does: the rest of the record
/// is not applied. None where the record is applied whole (or there is none).
pub fn record_truncation(model: &Model) -> Option<String> {
    let record = RecordedMotion::of(model.floor.as_ref())?;
    let end = record.end();
    // A duration within rounding of the record's end applies it whole.
    (model.duration < end * (1.0 - 1e-12)).then(|| {
        format!(
            "the run lasts {} s (simulation.duration) but the record lasts {} s: its last {} s \
             are not applied; leave simulation.duration out to run the whole record",
            crate::base::format::readable(model.duration),
            crate::base::format::readable(end),
            crate::base::format::readable(end - model.duration)
        )
    })
}

/// The warnings of a run: a record cut short by the duration ([`record_truncation`]), an
/// energy residual beyond [`ENERGY_RESIDUAL_WARNING_SHARE`] of the energy scale, a gravity
/// parameter beyond [`SELF_WEIGHT_WARNING_SHARE`] of buckling, a graze within the exact
/// method's rounding (or another sequence of events in a run moved within it), and a run that
/// ended while the body was rocking.
pub fn warnings(model: &Model, solution: &Solution) -> Vec<String> {
    [
        record_truncation(model),
        energy_warning(solution, "tighten the tolerance (or the Newmark step)"),
        self_weight_warning(&model.constants, "this body", "body.self_weight"),
        solution.rounding.as_ref().and_then(graze_warning),
        rocking_warning(solution, "the body"),
    ]
    .into_iter()
    .flatten()
    .collect()
}

/// The warnings of a row's run, each naming its column: those of [`warnings`] for every column
/// (its energy residual, its gravity parameter, a run that ended while it was rocking), and a
/// run cut short by an overturning column, after which no other column's motion is computed.
pub fn row_warnings(
    model: &crate::model::RowModel,
    solution: &crate::bodies::row::RowSolution,
) -> Vec<String> {
    let advice = match model.compliant {
        Some(_) => "tighten solver.rtol and solver.atol",
        None => "tighten the tolerance",
    };
    let mut warnings = Vec::new();
    for (i, (column, body)) in solution.columns.iter().zip(&model.bodies).enumerate() {
        let own = [
            energy_warning(column, advice),
            Constants::new(body).ok().and_then(|constants| {
                self_weight_warning(
                    &constants,
                    "this column",
                    &format!("column[{i}].self_weight"),
                )
            }),
            solution
                .overturned
                .is_none()
                .then(|| rocking_warning(column, "the column"))
                .flatten(),
        ];
        warnings.extend(
            own.into_iter()
                .flatten()
                .map(|w| format!("column {i}: {w}")),
        );
    }
    if let Some((i, t)) = solution.overturned {
        if t < model.duration {
            warnings.push(format!(
                "column {i} overturned at t = {t:.9} s, and the row's run ends there: no other \
                 column's motion after it is computed (what a fallen column does to its \
                 neighbours is beyond the model), so their peaks and counts cover [0, {t:.9}] s \
                 only"
            ));
        }
    }
    warnings
}

/// An energy residual beyond [`ENERGY_RESIDUAL_WARNING_SHARE`] of the energy scale, with the
/// `advice` that would make it smaller.
fn energy_warning(solution: &Solution, advice: &str) -> Option<String> {
    let scale = solution.energy_scale;
    (solution.energy_residual_share() > ENERGY_RESIDUAL_WARNING_SHARE).then(|| {
        format!(
            "the energy residual reached {:.3e} J, {:.1} % of the energy scale {:.3e} J (above {} %): \
             the solution is no more accurate than that; {advice}",
            solution.max_energy_residual,
            100.0 * solution.max_energy_residual / scale,
            scale,
            100.0 * ENERGY_RESIDUAL_WARNING_SHARE
        )
    })
}

/// A gravity parameter beyond [`SELF_WEIGHT_WARNING_SHARE`] of buckling under the paper's
/// self-weight, for `subject` ("this body") whose variant is set by `key`.
fn self_weight_warning(c: &Constants, subject: &str, key: &str) -> Option<String> {
    (c.self_weight == SelfWeight::Paper && c.gravity_parameter_ratio > SELF_WEIGHT_WARNING_SHARE)
        .then(|| {
            format!(
                "M g H^2/EI = {:.4} is {:.3} of its buckling value {SELF_WEIGHT_BUCKLING_PARAMETER} (above {}): \
                 the self-weight the paper's model leaves out of bending matters for {subject}; \
                 {key} = \"consistent\" puts it in (book: the model, §7a)",
                c.gravity_parameter, c.gravity_parameter_ratio, SELF_WEIGHT_WARNING_SHARE
            )
        })
}

/// A run that ended while `subject` ("the body") was rocking.
fn rocking_warning(solution: &Solution, subject: &str) -> Option<String> {
    solution.ended_while_rocking().then(|| {
        format!(
            "the run ended while {subject} was rocking ({} at t = {} s): no overturning within the \
             duration, which does not mean it would not overturn later; lengthen simulation.duration",
            solution.final_mode.name(),
            solution.final_time
        )
    })
}

/// The warning of the exact method's estimate where its sequence of events is uncertain: at its
/// first graze (with how many follow), or where a run moved within its rounding logs another.
fn graze_warning(estimate: &RoundingEstimate) -> Option<String> {
    let from = estimate.uncertain_from?;
    let after = format!(
        "the events and peaks from t = {from} s on are uncertain (error_estimate in summary.json \
         bounds them)"
    );
    let Some(first) = estimate.grazes.first() else {
        return Some(format!(
            "a run with the model's constants moved within their rounding logs another sequence \
             of events: {after}"
        ));
    };
    let (point, event, noun) = match first.event {
        EventKind::Uplift => ("the uplift point", "an uplift", "uplift"),
        EventKind::Landing => ("the landing point", "a landing", "landing"),
        _ => ("the overturning point", "overturning", "overturning"),
    };
    let what = if first.happened {
        format!(
            "q crossed {point} (q = {} m) at t = {} s by a margin of {:.1e} m ({event}); no \
             {noun} there is",
            first.level, first.t, first.margin
        )
    } else if first.margin == 0.0 {
        format!(
            "q reached {point} (q = {} m) to the last bit at t = {} s without {event}; {event} \
             there is",
            first.level, first.t
        )
    } else {
        format!(
            "q came within {:.1e} m of {point} (q = {} m) at t = {} s without {event}; {event} \
             there is",
            -first.margin, first.level, first.t
        )
    };
    let more = match estimate.grazes.len() - 1 {
        0 => String::new(),
        n => format!(" ({n} more grazes follow, listed in error_estimate.grazes)"),
    };
    Some(format!(
        "a graze: {what} within the run's rounding ({:.1e} m), so {after}{more}",
        first.rounding
    ))
}
