//! One row of sweep.csv: what a point's run (or minimum search) gave, and the dimensionless
//! numbers the rocking literature plots. The column names are a contract (README, "sweep.csv").
//!
//! No wall-clock time appears in a row, so that a sweep writes the same file every time.

use crate::automaton::EventKind;
use crate::model::Model;
use crate::output::shortest;
use crate::solution::Solution;

/// How a point ended.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Status {
    /// The run finished (overturned or not).
    Ok,
    /// The point's model breaks a rule of the model file; `reason` says which.
    Invalid,
    /// The run could not be completed (a solver failure, a cap on steps or events).
    Failed,
}

impl Status {
    /// The name in the `status` column.
    pub fn name(self) -> &'static str {
        match self {
            Status::Ok => "ok",
            Status::Invalid => "invalid",
            Status::Failed => "failed",
        }
    }
}

/// The body and excitation numbers of a point, dimensionless where the literature plots them.
/// A number is None (an empty field) where it is not known: the excitation has no period, or
/// a minimum search found no overturning value and the number depends on the searched key.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Scales {
    /// alpha = atan(B/H), rad.
    pub alpha: Option<f64>,
    /// p = sqrt(3 g/(4 R)), rad/s.
    pub p: Option<f64>,
    /// Pre-uplift period T, s.
    pub period: Option<f64>,
    /// s_n, m.
    pub uplift_displacement: Option<f64>,
    /// Peak floor acceleration over g tan(alpha).
    pub amplitude_over_g_tan_alpha: Option<f64>,
    /// Peak floor acceleration over the quasi-static uplift acceleration omega^2 s_n / beta1.
    pub amplitude_over_uplift_acceleration: Option<f64>,
    /// (2 pi / Tp) / p, for analytic motions with a period Tp.
    pub omega_p_over_p: Option<f64>,
    /// T / Tp.
    pub period_over_excitation_period: Option<f64>,
}

impl Scales {
    /// The numbers of a point's model.
    pub fn of(model: &Model) -> Scales {
        let body = &model.body;
        let c = &model.constants;
        let alpha = body.slenderness_angle();
        let p = body.block_frequency_parameter();
        let peak = model.floor.peak_acceleration();
        let excitation_period = model.floor.period();
        Scales {
            alpha: Some(alpha),
            p: Some(p),
            period: Some(c.period),
            uplift_displacement: Some(c.uplift_displacement),
            amplitude_over_g_tan_alpha: Some(peak / (body.gravity * alpha.tan())),
            amplitude_over_uplift_acceleration: Some(peak / c.quasi_static_uplift_acceleration),
            omega_p_over_p: excitation_period.map(|tp| 2.0 * std::f64::consts::PI / tp / p),
            period_over_excitation_period: excitation_period.map(|tp| c.period / tp),
        }
    }

    /// The numbers that `self` and `other` share; the others None. For a minimum search that
    /// found no overturning value, the numbers at the two ends of the interval: what depends on
    /// the searched key differs between them and is left empty, never shown at the bound.
    pub fn common(&self, other: &Scales) -> Scales {
        let keep = |a: Option<f64>, b: Option<f64>| a.filter(|_| a == b);
        Scales {
            alpha: keep(self.alpha, other.alpha),
            p: keep(self.p, other.p),
            period: keep(self.period, other.period),
            uplift_displacement: keep(self.uplift_displacement, other.uplift_displacement),
            amplitude_over_g_tan_alpha: keep(
                self.amplitude_over_g_tan_alpha,
                other.amplitude_over_g_tan_alpha,
            ),
            amplitude_over_uplift_acceleration: keep(
                self.amplitude_over_uplift_acceleration,
                other.amplitude_over_uplift_acceleration,
            ),
            omega_p_over_p: keep(self.omega_p_over_p, other.omega_p_over_p),
            period_over_excitation_period: keep(
                self.period_over_excitation_period,
                other.period_over_excitation_period,
            ),
        }
    }

    /// Column names of [`Scales::fields`].
    pub const COLUMNS: [&'static str; 8] = [
        "alpha",
        "p",
        "T",
        "s_n",
        "amplitude_over_g_tan_alpha",
        "amplitude_over_uplift_acceleration",
        "omega_p_over_p",
        "T_over_Tp",
    ];

    /// The fields, in the order of [`Scales::COLUMNS`].
    pub fn fields(&self) -> [String; 8] {
        [
            optional(self.alpha),
            optional(self.p),
            optional(self.period),
            optional(self.uplift_displacement),
            optional(self.amplitude_over_g_tan_alpha),
            optional(self.amplitude_over_uplift_acceleration),
            optional(self.omega_p_over_p),
            optional(self.period_over_excitation_period),
        ]
    }
}

fn optional(x: Option<f64>) -> String {
    x.map(shortest).unwrap_or_default()
}

/// What one run of a point gave.
#[derive(Debug, Clone, Copy)]
pub struct RunOutcome {
    /// The body overturned within the duration.
    pub overturned: bool,
    /// When, s.
    pub t_overturn: Option<f64>,
    /// Number of uplifts.
    pub n_uplift: usize,
    /// Number of landings.
    pub n_landing: usize,
    /// Largest |q| over B.
    pub max_abs_q_over_b: f64,
    /// Largest |r| (rocking part) over B.
    pub max_abs_r_over_b: f64,
    /// Largest |s| (flexural part) over s_n.
    pub max_abs_s_over_s_n: f64,
    /// The run ended with the body rocking.
    pub ended_while_rocking: bool,
    /// The largest energy residual over the energy scale (see [`Solution::energy_residual_share`]);
    /// beyond [`crate::run::ENERGY_RESIDUAL_WARNING_SHARE`] the run is no more accurate than that.
    pub energy_residual_share: f64,
    /// Accepted steps.
    pub steps: usize,
    /// Right-hand-side evaluations.
    pub rhs_evaluations: usize,
}

impl RunOutcome {
    /// What a solution of a point's model gave.
    pub fn of(model: &Model, solution: &Solution) -> RunOutcome {
        let b = model.body.width;
        let max_abs_q = solution.max_q.value.abs().max(solution.min_q.value.abs());
        RunOutcome {
            overturned: solution.overturned,
            t_overturn: solution.t_overturn,
            n_uplift: solution.count(EventKind::Uplift),
            n_landing: solution.count(EventKind::Landing),
            max_abs_q_over_b: max_abs_q / b,
            max_abs_r_over_b: solution.max_abs_r / b,
            max_abs_s_over_s_n: solution.max_abs_s / model.constants.uplift_displacement,
            ended_while_rocking: solution.ended_while_rocking(),
            energy_residual_share: solution.energy_residual_share(),
            steps: solution.stats.steps,
            rhs_evaluations: solution.stats.rhs_evaluations,
        }
    }

    /// Column names of [`RunOutcome::fields`].
    pub const COLUMNS: [&'static str; 11] = [
        "overturned",
        "t_overturn",
        "n_uplift",
        "n_landing",
        "max_abs_q_over_B",
        "max_abs_r_over_B",
        "max_abs_s_over_s_n",
        "ended_while_rocking",
        "energy_residual_share",
        "steps",
        "rhs_evaluations",
    ];

    /// The fields, in the order of [`RunOutcome::COLUMNS`].
    pub fn fields(&self) -> [String; 11] {
        [
            self.overturned.to_string(),
            optional(self.t_overturn),
            self.n_uplift.to_string(),
            self.n_landing.to_string(),
            shortest(self.max_abs_q_over_b),
            shortest(self.max_abs_r_over_b),
            shortest(self.max_abs_s_over_s_n),
            self.ended_while_rocking.to_string(),
            shortest(self.energy_residual_share),
            self.steps.to_string(),
            self.rhs_evaluations.to_string(),
        ]
    }
}

/// What the search for the smallest overturning value of a point found.
#[derive(Debug, Clone, Default)]
pub struct MinimumOutcome {
    /// The smallest value found to overturn: the upper end of the final bracket. None when no
    /// scanned value overturned.
    pub min_overturning: Option<f64>,
    /// The largest value below it found not to overturn (the lower end of the bracket). None
    /// when the lowest value of the interval already overturned.
    pub safe_below: Option<f64>,
    /// The bands of scanned values that overturned, as `lo-hi` (`lo` alone for one value),
    /// separated by `;`.
    pub bands: String,
    /// Number of bands.
    pub n_bands: usize,
    /// Time of overturning at `min_overturning`.
    pub t_overturn: Option<f64>,
    /// Simulations run for the search, and their steps and right-hand-side evaluations.
    pub simulations: usize,
    /// Accepted steps of all the search's runs.
    pub steps: usize,
    /// Right-hand-side evaluations of all the search's runs.
    pub rhs_evaluations: usize,
}

impl MinimumOutcome {
    /// Column names of [`MinimumOutcome::fields`].
    pub const COLUMNS: [&'static str; 8] = [
        "min_overturning",
        "safe_below",
        "overturning_bands",
        "n_bands",
        "t_overturn",
        "simulations",
        "steps",
        "rhs_evaluations",
    ];

    /// The fields, in the order of [`MinimumOutcome::COLUMNS`].
    pub fn fields(&self) -> [String; 8] {
        [
            optional(self.min_overturning),
            optional(self.safe_below),
            self.bands.clone(),
            self.n_bands.to_string(),
            optional(self.t_overturn),
            self.simulations.to_string(),
            self.steps.to_string(),
            self.rhs_evaluations.to_string(),
        ]
    }
}

/// The same search for the rigid blocks of the body's geometry under the same floor motion:
/// Housner's slender block (uplift at g B/H) and the block the elastic model tends to as E grows
/// (uplift at its quasi-static uplift acceleration's limit); see [`crate::rigid`].
#[derive(Debug, Clone, Copy, Default)]
pub struct RigidMinima {
    /// Housner's block's smallest overturning value.
    pub housner: Option<f64>,
    /// Its peak floor acceleration over g tan(alpha).
    pub housner_over_g_tan_alpha: Option<f64>,
    /// The rigid limit's smallest overturning value.
    pub elastic_limit: Option<f64>,
    /// Its peak floor acceleration over g tan(alpha).
    pub elastic_limit_over_g_tan_alpha: Option<f64>,
}

impl RigidMinima {
    /// Column names of [`RigidMinima::fields`].
    pub const COLUMNS: [&'static str; 4] = [
        "rigid_min_overturning",
        "rigid_amplitude_over_g_tan_alpha",
        "rigid_limit_min_overturning",
        "rigid_limit_amplitude_over_g_tan_alpha",
    ];

    /// The fields, in the order of [`RigidMinima::COLUMNS`].
    pub fn fields(&self) -> [String; 4] {
        [
            optional(self.housner),
            optional(self.housner_over_g_tan_alpha),
            optional(self.elastic_limit),
            optional(self.elastic_limit_over_g_tan_alpha),
        ]
    }
}

/// The result part of a row (after the point number and the axis values).
#[derive(Debug, Clone)]
pub enum Outcome {
    /// One run of the point.
    Run(RunOutcome),
    /// A minimum search at the point, for the elastic body and the rigid blocks.
    Minimum(MinimumOutcome, RigidMinima),
}

/// One point's row, before formatting.
#[derive(Debug, Clone)]
pub struct Row {
    /// How the point ended.
    pub status: Status,
    /// Why it is invalid or failed (empty when ok).
    pub reason: String,
    /// What it gave, when ok.
    pub outcome: Option<Outcome>,
    /// Its body and excitation numbers, when its model is valid.
    pub scales: Option<Scales>,
}

impl Row {
    /// A row of a point that is invalid or failed.
    pub fn failure(status: Status, reason: String) -> Row {
        Row {
            status,
            reason,
            outcome: None,
            scales: None,
        }
    }

    /// The result columns, for a sweep that searches a minimum or not.
    pub fn columns(find_min: bool) -> Vec<&'static str> {
        let mut columns = vec!["status", "reason"];
        if find_min {
            columns.extend(MinimumOutcome::COLUMNS);
            columns.extend(RigidMinima::COLUMNS);
        } else {
            columns.extend(RunOutcome::COLUMNS);
        }
        columns.extend(Scales::COLUMNS);
        columns
    }

    /// The result fields, in the order of [`Row::columns`]; empty where there is no value.
    pub fn fields(&self, find_min: bool) -> Vec<String> {
        let mut fields = vec![self.status.name().to_string(), self.reason.clone()];
        match &self.outcome {
            Some(Outcome::Run(run)) => fields.extend(run.fields()),
            Some(Outcome::Minimum(min, rigid)) => {
                fields.extend(min.fields());
                fields.extend(rigid.fields());
            }
            None if find_min => fields.extend(std::iter::repeat_n(
                String::new(),
                MinimumOutcome::COLUMNS.len() + RigidMinima::COLUMNS.len(),
            )),
            None => fields.extend(std::iter::repeat_n(
                String::new(),
                RunOutcome::COLUMNS.len(),
            )),
        }
        match &self.scales {
            Some(scales) => fields.extend(scales.fields()),
            None => fields.extend(std::iter::repeat_n(String::new(), Scales::COLUMNS.len())),
        }
        fields
    }
}
