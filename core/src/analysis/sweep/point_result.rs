//! One row of sweep.csv: what a point's run (or minimum search) gave, and the dimensionless
//! numbers the rocking literature plots, typed ([`Cell`]). The column names are a contract (the
//! book's output reference, "sweep.csv"). Each part of a row names its cells in one place
//! (`named`), from which both the header and the fields are made.
//!
//! No wall-clock time appears in a row, so that a sweep writes the same file every time.

use crate::base::units::STANDARD_GRAVITY;
use crate::bodies::oscillator;
use crate::error::Error;
use crate::floor::intensity::{self, GroundMeasures};
use crate::floor::record::RecordMeta;
use crate::floor::RecordedMotion;
use crate::integrate::solution::Solution;
use crate::model::Model;
use crate::physics::automaton::EventKind;

use super::cell::{emptied, names, values, Cell};
use super::find_min::{HousnerOptions, MinimumOutcome};
use super::rows::RowOutcome;

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
#[derive(Debug, Clone, Copy, PartialEq, Default)]
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

    /// The cells, by column name.
    pub fn named(&self) -> [(&'static str, Cell); 8] {
        [
            ("alpha", Cell::Float(self.alpha)),
            ("p", Cell::Float(self.p)),
            ("T", Cell::Float(self.period)),
            ("s_n", Cell::Float(self.uplift_displacement)),
            (
                "amplitude_over_g_tan_alpha",
                Cell::Float(self.amplitude_over_g_tan_alpha),
            ),
            (
                "amplitude_over_uplift_acceleration",
                Cell::Float(self.amplitude_over_uplift_acceleration),
            ),
            ("omega_p_over_p", Cell::Float(self.omega_p_over_p)),
            ("T_over_Tp", Cell::Float(self.period_over_excitation_period)),
        ]
    }
}

/// A point's record, in a sweep over records: what its file says about itself, and the
/// intensity measures of the motion the point applies (the record scaled and trimmed). A
/// number is None (an empty field) where it is not known: the file does not give it, the
/// point's model is invalid, or (in a minimum search that found no overturning value) it
/// depends on the searched key.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct RecordCells {
    /// The record file's metadata.
    pub meta: Option<RecordMeta>,
    /// PGA, PGV, PGD, Arias intensity and CAV.
    pub ground: Option<GroundMeasures>,
    /// Sa(T, 5 %) at the body's pre-uplift period T, m/s^2.
    pub sa: Option<f64>,
}

impl RecordCells {
    /// The record of a point's model (all empty for an analytic motion).
    pub fn of(model: &Model) -> RecordCells {
        let Some(record) = RecordedMotion::of(model.floor.as_ref()) else {
            return RecordCells::default();
        };
        RecordCells {
            meta: Some(record.meta().clone()),
            ground: Some(intensity::ground_measures(record)),
            sa: oscillator::spectral_acceleration(
                record,
                model.constants.period,
                oscillator::DEFAULT_DAMPING,
            )
            .ok()
            .map(|s| s.sa),
        }
    }

    /// What `self` and `other` share; the rest None (see [`Scales::common`]).
    pub fn common(&self, other: &RecordCells) -> RecordCells {
        let keep = |a: Option<f64>, b: Option<f64>| a.filter(|_| a == b);
        let ground = match (self.ground, other.ground) {
            (Some(a), Some(b)) if a == b => Some(a),
            _ => None,
        };
        RecordCells {
            meta: self.meta.clone().filter(|m| Some(m) == other.meta.as_ref()),
            ground,
            sa: keep(self.sa, other.sa),
        }
    }

    /// The cells, by column name: the metadata, then the measures (PGA and Sa in g, the
    /// others in SI units).
    pub fn named(&self) -> [(&'static str, Cell); 12] {
        let meta = self.meta.as_ref();
        let text = |f: fn(&RecordMeta) -> &Option<String>| {
            Cell::Text(meta.and_then(|m| f(m).clone()).filter(|t| !t.is_empty()))
        };
        let ground = |f: fn(&GroundMeasures) -> f64| Cell::Float(self.ground.as_ref().map(f));
        [
            ("event", text(|m| &m.event)),
            ("date", text(|m| &m.date)),
            ("station", text(|m| &m.station)),
            ("component", text(|m| &m.component)),
            ("magnitude", Cell::Float(meta.and_then(|m| m.magnitude))),
            ("distance_km", Cell::Float(meta.and_then(|m| m.distance_km))),
            ("pga_g", ground(|g| g.pga / STANDARD_GRAVITY)),
            ("pgv_m_s", ground(|g| g.pgv)),
            ("pgd_m", ground(|g| g.pgd)),
            ("arias_m_s", ground(|g| g.arias)),
            ("cav_m_s", ground(|g| g.cav)),
            ("sa_g", Cell::Float(self.sa.map(|sa| sa / STANDARD_GRAVITY))),
        ]
    }
}

/// What one run of a point gave.
#[derive(Debug, Clone, Copy, Default)]
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
    /// beyond [`crate::simulate::ENERGY_RESIDUAL_WARNING_SHARE`] the run is no more accurate than that.
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

    /// The cells, by column name.
    pub fn named(&self) -> [(&'static str, Cell); 11] {
        [
            ("overturned", Cell::Bool(Some(self.overturned))),
            ("t_overturn", Cell::Float(self.t_overturn)),
            ("n_uplift", Cell::Int(Some(self.n_uplift))),
            ("n_landing", Cell::Int(Some(self.n_landing))),
            ("max_abs_q_over_B", Cell::Float(Some(self.max_abs_q_over_b))),
            ("max_abs_r_over_B", Cell::Float(Some(self.max_abs_r_over_b))),
            (
                "max_abs_s_over_s_n",
                Cell::Float(Some(self.max_abs_s_over_s_n)),
            ),
            (
                "ended_while_rocking",
                Cell::Bool(Some(self.ended_while_rocking)),
            ),
            (
                "energy_residual_share",
                // Empty where the run kept no energy books (the exact method's).
                Cell::Float(Some(self.energy_residual_share).filter(|x| !x.is_nan())),
            ),
            ("steps", Cell::Int(Some(self.steps))),
            ("rhs_evaluations", Cell::Int(Some(self.rhs_evaluations))),
        ]
    }
}

/// The same search for the rigid blocks of the body's geometry under the same floor motion:
/// Housner's block (uplift at g B/H), made as `housner` says, and the block the elastic model
/// tends to as E grows (uplift at its quasi-static uplift acceleration's limit), always by the
/// small-angle equation, overturned when its tilt reaches B/H and with Housner's restitution,
/// the elastic model's own limit; see [`crate::bodies::rigid`].
#[derive(Debug, Clone, Copy, Default)]
pub struct RigidMinima {
    /// How Housner's block is made. Each choice other than the default adds a column after its
    /// two: `rigid_form` (`full`), `rigid_overturning` (`cannot-return`), `rigid_restitution`
    /// (the number); a default block has none of them, so that its columns are those of before
    /// the choices existed.
    pub housner_options: HousnerOptions,
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
    /// The cells, by column name (`rigid_form`, `rigid_overturning` and `rigid_restitution`
    /// only where Housner's block is not the default).
    pub fn named(&self) -> Vec<(&'static str, Cell)> {
        let options = self.housner_options;
        let mut cells = vec![
            ("rigid_min_overturning", Cell::Float(self.housner)),
            (
                "rigid_amplitude_over_g_tan_alpha",
                Cell::Float(self.housner_over_g_tan_alpha),
            ),
        ];
        if !options.form.is_small_angle() {
            cells.push(("rigid_form", Cell::text(options.form.name())));
        }
        if !options.overturning.is_reaches_limit() {
            cells.push(("rigid_overturning", Cell::text(options.overturning.name())));
        }
        if let Some(e) = options.restitution {
            cells.push(("rigid_restitution", Cell::Float(Some(e))));
        }
        cells.extend([
            (
                "rigid_limit_min_overturning",
                Cell::Float(self.elastic_limit),
            ),
            (
                "rigid_limit_amplitude_over_g_tan_alpha",
                Cell::Float(self.elastic_limit_over_g_tan_alpha),
            ),
        ]);
        cells
    }

    /// No values, Housner's block made as `options` say.
    pub fn with_options(options: HousnerOptions) -> Self {
        RigidMinima {
            housner_options: options,
            ..RigidMinima::default()
        }
    }
}

/// Which result columns a sweep has.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Layout {
    /// One run per point.
    Runs,
    /// A minimum search per point, with the rigid blocks' searches, Housner's block made as
    /// the options say (see [`RigidMinima`]).
    Minimum(HousnerOptions),
    /// One run of a row of this many columns per point, and each column's run alone (see
    /// [`super::rows`]).
    Row(usize),
}

impl From<bool> for Layout {
    /// `true`: a minimum search with the default (small-angle) rigid block; `false`: runs.
    fn from(find_min: bool) -> Self {
        if find_min {
            Layout::Minimum(HousnerOptions::default())
        } else {
            Layout::Runs
        }
    }
}

/// The result part of a row (after the point number and the axis values).
#[derive(Debug, Clone)]
pub enum Outcome {
    /// One run of the point.
    Run(RunOutcome),
    /// A minimum search at the point, for the elastic body and the rigid blocks.
    Minimum(MinimumOutcome, RigidMinima),
    /// One run of a row, and each of its columns alone.
    Row(RowOutcome),
}

/// What one point gave (its line of sweep.csv), before formatting.
#[derive(Debug, Clone)]
pub struct PointResult {
    /// How the point ended.
    pub status: Status,
    /// Why it is invalid or failed (empty when ok).
    pub reason: String,
    /// What it gave, when ok.
    pub outcome: Option<Outcome>,
    /// Its body and excitation numbers, when its model is valid.
    pub scales: Option<Scales>,
    /// Its record, in a sweep over records (every row of such a sweep has it, empty where
    /// nothing is known); None in other sweeps, whose rows have no record columns.
    pub record: Option<RecordCells>,
}

impl PointResult {
    /// A row of a point that is invalid or failed.
    pub fn failure(status: Status, reason: String) -> PointResult {
        PointResult {
            status,
            reason,
            outcome: None,
            scales: None,
            record: None,
        }
    }

    /// The result columns, for a sweep that searches a minimum (`true` or a [`Layout`]) or not.
    pub fn columns(layout: impl Into<Layout>) -> Vec<String> {
        let mut columns = vec!["status", "reason"];
        match layout.into() {
            Layout::Minimum(options) => {
                columns.extend(names(MinimumOutcome::default().named()));
                columns.extend(names(RigidMinima::with_options(options).named()));
            }
            Layout::Runs => columns.extend(names(RunOutcome::default().named())),
            // A row's columns are named by their index, and no row has the single body's
            // dimensionless numbers.
            Layout::Row(n) => {
                let mut columns: Vec<String> = columns.into_iter().map(String::from).collect();
                columns.extend(RowOutcome::columns(n));
                return columns;
            }
        }
        columns.extend(names(Scales::default().named()));
        columns.into_iter().map(String::from).collect()
    }

    /// The result cells, in the order of [`PointResult::columns`]; empty where there is no value.
    pub fn cells(&self, layout: impl Into<Layout>) -> Vec<Cell> {
        let layout = layout.into();
        let mut cells = vec![
            Cell::Text(Some(self.status.name().to_string())),
            Cell::text(&self.reason),
        ];
        match &self.outcome {
            Some(Outcome::Run(run)) => cells.extend(values(run.named())),
            Some(Outcome::Minimum(min, rigid)) => {
                cells.extend(values(min.named()));
                cells.extend(values(rigid.named()));
            }
            Some(Outcome::Row(row)) => {
                cells.extend(row.cells());
                return cells;
            }
            None => match layout {
                Layout::Minimum(options) => {
                    cells.extend(emptied(MinimumOutcome::default().named()));
                    cells.extend(emptied(RigidMinima::with_options(options).named()));
                }
                Layout::Runs => cells.extend(emptied(RunOutcome::default().named())),
                Layout::Row(n) => {
                    cells.extend(RowOutcome::empty_cells(n));
                    return cells;
                }
            },
        }
        match &self.scales {
            Some(scales) => cells.extend(values(scales.named())),
            None => cells.extend(emptied(Scales::default().named())),
        }
        if let Some(record) = &self.record {
            cells.extend(values(record.named()));
        }
        cells
    }

    /// The names of the record columns, after [`PointResult::columns`] in a sweep over records.
    pub fn record_columns() -> Vec<String> {
        names(RecordCells::default().named())
            .into_iter()
            .map(String::from)
            .collect()
    }

    /// The result fields as sweep.csv holds them, in the order of [`PointResult::columns`].
    pub fn fields(&self, layout: impl Into<Layout>) -> Vec<String> {
        self.cells(layout).iter().map(Cell::field).collect()
    }
}

/// An error as one line of a CSV field.
pub(super) fn reason(e: &Error) -> String {
    e.to_string().replace(['\n', '\r'], " ")
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_row_has_a_cell_for_every_column_and_a_column_keeps_its_kind() {
        let run = PointResult {
            status: Status::Ok,
            reason: String::new(),
            outcome: Some(Outcome::Run(RunOutcome {
                overturned: true,
                t_overturn: Some(2.5),
                n_uplift: 3,
                ..RunOutcome::default()
            })),
            scales: Some(Scales::default()),
            record: None,
        };
        let failed = PointResult::failure(Status::Failed, "a reason".into());
        for layout in [
            Layout::Runs,
            Layout::Minimum(HousnerOptions::default()),
            Layout::Minimum(full()),
            Layout::Minimum(every_choice()),
            Layout::Row(3),
        ] {
            let find_min = layout != Layout::Runs;
            let columns = PointResult::columns(layout);
            let mut seen = std::collections::BTreeSet::new();
            assert!(
                columns.iter().all(|c| seen.insert(c.clone())),
                "{columns:?}"
            );
            let empty = failed.cells(layout);
            assert_eq!(empty.len(), columns.len());
            assert_eq!(empty[1], Cell::Text(Some("a reason".into())));
            assert!(empty[2..].iter().all(|c| c.field().is_empty()));
            if !find_min {
                let full = run.cells(false);
                assert_eq!(full.len(), columns.len());
                let kinds = |cells: &[Cell]| cells.iter().map(Cell::kind).collect::<Vec<_>>();
                assert_eq!(kinds(&full), kinds(&empty));
                let at =
                    |name: &str| full[columns.iter().position(|c| *c == name).unwrap()].clone();
                assert_eq!(at("overturned"), Cell::Bool(Some(true)));
                assert_eq!(at("n_uplift"), Cell::Int(Some(3)));
                assert_eq!(at("t_overturn").field(), "2.5");
                assert_eq!(at("reason"), Cell::Text(None));
                assert_eq!(at("omega_p_over_p"), Cell::Float(None));
            }
        }
    }

    use crate::bodies::rigid::{RigidForm, RigidOverturning};

    fn full() -> HousnerOptions {
        HousnerOptions {
            form: RigidForm::Full,
            ..HousnerOptions::default()
        }
    }

    fn every_choice() -> HousnerOptions {
        HousnerOptions {
            form: RigidForm::Full,
            overturning: RigidOverturning::CannotReturn,
            restitution: Some(0.9),
        }
    }

    /// The `rigid_form` column is there, after Housner's block's two, only for the full form:
    /// the default's columns are those of before the full form existed.
    #[test]
    fn the_rigid_form_column_names_the_full_form_only() {
        assert_eq!(
            PointResult::columns(true),
            PointResult::columns(Layout::Minimum(HousnerOptions::default()))
        );
        for name in ["rigid_form", "rigid_overturning", "rigid_restitution"] {
            assert!(!PointResult::columns(true).iter().any(|c| c == name));
        }
        let columns = PointResult::columns(Layout::Minimum(full()));
        let at = |name: &str| columns.iter().position(|c| *c == name).unwrap();
        assert_eq!(at("rigid_form"), at("rigid_amplitude_over_g_tan_alpha") + 1);
        assert_eq!(at("rigid_limit_min_overturning"), at("rigid_form") + 1);
        let row = PointResult {
            status: Status::Ok,
            reason: String::new(),
            outcome: Some(Outcome::Minimum(
                MinimumOutcome::default(),
                RigidMinima {
                    housner: Some(3.0),
                    ..RigidMinima::with_options(full())
                },
            )),
            scales: None,
            record: None,
        };
        let fields = row.fields(Layout::Minimum(full()));
        assert_eq!(fields.len(), columns.len());
        assert_eq!(fields[at("rigid_form")], "full");
        assert_eq!(fields[at("rigid_min_overturning")], "3");
    }

    /// A rule of overturning and a restitution of Housner's block's own each add a column, in
    /// the order rigid_form, rigid_overturning, rigid_restitution, between Housner's block's
    /// two and the rigid limit's.
    #[test]
    fn housners_choices_add_their_columns_in_order() {
        let columns = PointResult::columns(Layout::Minimum(every_choice()));
        let at = |name: &str| columns.iter().position(|c| *c == name).unwrap();
        assert_eq!(at("rigid_form"), at("rigid_amplitude_over_g_tan_alpha") + 1);
        assert_eq!(at("rigid_overturning"), at("rigid_form") + 1);
        assert_eq!(at("rigid_restitution"), at("rigid_overturning") + 1);
        assert_eq!(
            at("rigid_limit_min_overturning"),
            at("rigid_restitution") + 1
        );
        let row = PointResult {
            status: Status::Ok,
            reason: String::new(),
            outcome: Some(Outcome::Minimum(
                MinimumOutcome::default(),
                RigidMinima::with_options(every_choice()),
            )),
            scales: None,
            record: None,
        };
        let fields = row.fields(Layout::Minimum(every_choice()));
        assert_eq!(fields.len(), columns.len());
        assert_eq!(fields[at("rigid_overturning")], "cannot-return");
        assert_eq!(fields[at("rigid_restitution")], "0.9");
        let only_rule = HousnerOptions {
            overturning: RigidOverturning::CannotReturn,
            ..HousnerOptions::default()
        };
        let columns = PointResult::columns(Layout::Minimum(only_rule));
        assert!(!columns
            .iter()
            .any(|c| c == "rigid_form" || c == "rigid_restitution"));
        assert!(columns.iter().any(|c| c == "rigid_overturning"));
    }
}
