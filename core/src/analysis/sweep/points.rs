//! The points of a sweep: each point's model (the `--set` keys, then the axes' values) and the
//! row it gives: a run, a minimum search beside the rigid blocks', or a row of columns' run
//! beside each column's alone. Points are computed in parallel, and returned in point order.

use crate::bodies::rigid::RigidBlock;
use crate::error::{Error, Result};
use crate::model::{Model, Setting};

use super::find_min::{self, FindMin, HousnerOptions};
use super::in_order::in_order;
use super::point_result::{
    reason, Outcome, PointResult, RecordCells, RigidMinima, RunOutcome, Scales, Status,
};
use super::rows;
use super::setup::Sweep;

impl Sweep {
    /// The model of point `index` with `further` keys set after the axes' values (a record's
    /// scale, say): what a study built on a sweep reads of a point besides its row.
    pub fn model_at(&self, index: usize, further: &[Setting]) -> Result<Model> {
        let mut settings = self.settings_at(index);
        settings.extend_from_slice(further);
        self.model(&settings)
    }

    /// The settings of point `index`: the `--set` keys, then the axes' values.
    pub(super) fn settings_at(&self, index: usize) -> Vec<Setting> {
        let mut settings = self.settings.clone();
        for (axis, &i) in self.plan.axes.iter().zip(&self.plan.coordinates(index)) {
            settings.push(self.absolute_path_setting(axis.setting(i)));
        }
        settings
    }

    /// A value of an `excitation.path` axis made absolute: record files of an axis are relative
    /// to the directory the sweep was started from. Other settings are returned unchanged.
    pub(super) fn absolute_path_setting(&self, mut setting: Setting) -> Setting {
        if setting.key == "excitation.path" {
            if let toml::Value::String(path) = &setting.value {
                let absolute = self.paths_base.join(path);
                setting.value = toml::Value::String(absolute.to_string_lossy().into_owned());
            }
        }
        setting
    }

    /// The row model's table with `settings` set.
    pub(super) fn row_table(&self, settings: &[Setting]) -> Result<toml::Table> {
        let mut table = self.schema.table().clone();
        for setting in settings {
            rows::apply(&mut table, setting)?;
        }
        Ok(table)
    }

    /// The row of a point of a row sweep: the row's run, and each column's alone.
    fn row_point(&self, settings: &[Setting]) -> PointResult {
        let invalid = |e: &Error| PointResult::failure(Status::Invalid, reason(e));
        let table = match self.row_table(settings) {
            Ok(table) => table,
            Err(e) => return invalid(&e),
        };
        let model = match rows::row_model(&table, &self.source, &self.base_dir, &self.records) {
            Ok(model) => model,
            Err(e) => return invalid(&e),
        };
        let mut alone = Vec::with_capacity(model.bodies.len());
        for i in 0..model.bodies.len() {
            let single = rows::alone_model(
                &table,
                i,
                model.duration,
                (&self.source, &self.base_dir),
                &self.records,
            );
            let in_column = |e: &Error| format!("column {i} alone: {}", reason(e));
            let single = match single {
                Ok(single) => single,
                Err(e) => return PointResult::failure(Status::Invalid, in_column(&e)),
            };
            match crate::simulate::simulate_peaks(&single) {
                Ok(s) => alone.push((
                    s.overturned,
                    s.t_overturn,
                    s.max_q.value.abs().max(s.min_q.value.abs()),
                )),
                Err(e) => return PointResult::failure(Status::Failed, in_column(&e)),
            }
        }
        match rows::solve_peaks(&model) {
            Ok(solution) => PointResult {
                status: Status::Ok,
                reason: String::new(),
                outcome: Some(Outcome::Row(rows::RowOutcome::of(&solution, &alone))),
                scales: None,
                record: None,
            },
            Err(e) => PointResult::failure(Status::Failed, reason(&e)),
        }
    }

    /// The model of the sweep's `--set` keys (`settings` starts with them), then the rest of
    /// `settings`.
    pub(super) fn model(&self, settings: &[Setting]) -> Result<Model> {
        debug_assert!(settings.starts_with(&self.settings));
        let further = settings.get(self.settings.len()..).unwrap_or_default();
        let file = self.schema.read(further, &self.source)?;
        Model::for_peaks(file, &self.base_dir, &self.records)
    }

    /// The rows of the points `points`, in point order (in parallel with the `parallel`
    /// feature); `done` is called as each point finishes, from the thread that computed it.
    pub fn rows(
        &self,
        points: std::ops::Range<usize>,
        done: &(dyn Fn() + Sync),
    ) -> Vec<PointResult> {
        self.rows_as(points, done, |_, row| row)
    }

    /// The rows of the points `points`, in point order, or None once `stop()` is true: each
    /// point asks before it starts, so that a caller who stops waiting (the Python bindings on
    /// Ctrl-C) waits for no more than the points under way.
    pub fn rows_until(
        &self,
        points: std::ops::Range<usize>,
        stop: &(dyn Fn() -> bool + Sync),
    ) -> Option<Vec<PointResult>> {
        in_order(points, |i| (!stop()).then(|| self.evaluate(i)))
            .into_iter()
            .collect()
    }

    /// `with(index, row)` of the points `points`, in point order; each computed in parallel
    /// with its point (with the `parallel` feature), so that turning rows into text is shared
    /// among the threads too.
    pub fn rows_as<T: Send>(
        &self,
        points: std::ops::Range<usize>,
        done: &(dyn Fn() + Sync),
        with: impl Fn(usize, PointResult) -> T + Sync + Send,
    ) -> Vec<T> {
        in_order(points, |i| {
            let row = self.evaluate(i);
            done();
            with(i, row)
        })
    }

    /// The row of point `index`.
    pub fn evaluate(&self, index: usize) -> PointResult {
        let settings = self.settings_at(index);
        if self.plan.row_columns.is_some() {
            return self.row_point(&settings);
        }
        let mut row = match &self.plan.find_min {
            None => self.run_point(&settings),
            Some(find) => self.search_point(&settings, find),
        };
        // Every row of a sweep over records has the record's cells (empty where unknown), and
        // no row of another sweep has them: the columns are the plan's.
        if self.plan.reads_records() {
            row.record.get_or_insert_with(RecordCells::default);
        } else {
            row.record = None;
        }
        row
    }

    fn run_point(&self, settings: &[Setting]) -> PointResult {
        let model = match self.model(settings) {
            Ok(model) => model,
            Err(e) => return PointResult::failure(Status::Invalid, reason(&e)),
        };
        let record = self.plan.reads_records().then(|| RecordCells::of(&model));
        let scales = Some(Scales::of(&model));
        match crate::simulate::simulate_peaks(&model) {
            Ok(solution) => PointResult {
                status: Status::Ok,
                reason: String::new(),
                outcome: Some(Outcome::Run(RunOutcome::of(&model, &solution))),
                scales,
                record,
            },
            Err(e) => PointResult {
                scales,
                record,
                ..PointResult::failure(Status::Failed, reason(&e))
            },
        }
    }

    fn search_point(&self, settings: &[Setting], find: &FindMin) -> PointResult {
        let at = |value: f64| {
            let mut settings = settings.to_vec();
            settings.push(Setting::number(&find.key, value));
            settings
        };
        let trial = |value: f64| -> std::result::Result<find_min::Trial, (Status, Error)> {
            let model = self.model(&at(value)).map_err(|e| (Status::Invalid, e))?;
            let solution =
                crate::simulate::simulate_peaks(&model).map_err(|e| (Status::Failed, e))?;
            Ok(find_min::Trial {
                overturned: solution.overturned,
                t_overturn: solution.t_overturn,
                steps: solution.stats.steps,
                rhs_evaluations: solution.stats.rhs_evaluations,
            })
        };
        let scales_at = |value: f64| self.model(&at(value)).ok().map(|m| Scales::of(&m));
        match find_min::search(find, trial) {
            Ok(outcome) => {
                // The dimensionless numbers of the smallest overturning value; when nothing
                // overturned, only those the searched key does not change (equal at LO and HI),
                // so that no column shows a number derived from the search's bound.
                let scales = match outcome.min_overturning {
                    Some(value) => scales_at(value),
                    None => match (scales_at(find.lo), scales_at(find.hi)) {
                        (Some(lo), Some(hi)) => Some(lo.common(&hi)),
                        _ => None,
                    },
                };
                // The record's measures at the smallest overturning value likewise.
                let record = self.plan.reads_records().then(|| {
                    let at_value = |value: f64| {
                        self.model(&at(value))
                            .map(|m| RecordCells::of(&m))
                            .unwrap_or_default()
                    };
                    match outcome.min_overturning {
                        Some(value) => at_value(value),
                        None => at_value(find.lo).common(&at_value(find.hi)),
                    }
                });
                let rigid_minimum = |block: fn(
                    f64,
                    f64,
                    f64,
                ) -> std::result::Result<
                    RigidBlock,
                    crate::integrate::SolverError,
                >,
                                     options: HousnerOptions| {
                    let trial = |value: f64| -> Result<find_min::Trial> {
                        let model = self.model(&at(value))?;
                        let b = &model.body;
                        let block = options.apply(block(b.height, b.width, b.gravity)?)?;
                        find_min::Trial::of_rigid(&model, &block)
                    };
                    let min = find_min::search(find, trial)?.min_overturning;
                    let scaled = min
                        .and_then(scales_at)
                        .and_then(|s| s.amplitude_over_g_tan_alpha);
                    Ok((min, scaled))
                };
                // A rigid block's search that fails fails the point: its cells are not left
                // empty as if nothing had overturned.
                let rigid_failure = |block: &str, (value, e): (f64, Error)| {
                    PointResult::failure(
                        Status::Failed,
                        format!(
                            "{block} at {} = {}: {}",
                            find.key,
                            crate::base::format::shortest(value),
                            reason(&e)
                        ),
                    )
                };
                let (housner, housner_over_g_tan_alpha) =
                    match rigid_minimum(RigidBlock::housner, find.housner()) {
                        Ok(found) => found,
                        Err(failure) => return rigid_failure("Housner's rigid block", failure),
                    };
                // The elastic model's limit is the small-angle equation, overturned when its
                // tilt reaches B/H, with Housner's restitution, whatever Housner's block's.
                let (elastic_limit, elastic_limit_over_g_tan_alpha) =
                    match rigid_minimum(RigidBlock::elastic_limit, HousnerOptions::default()) {
                        Ok(found) => found,
                        Err(failure) => return rigid_failure("the rigid limit", failure),
                    };
                let rigid = RigidMinima {
                    housner_options: find.housner(),
                    housner,
                    housner_over_g_tan_alpha,
                    elastic_limit,
                    elastic_limit_over_g_tan_alpha,
                };
                PointResult {
                    status: Status::Ok,
                    reason: String::new(),
                    outcome: Some(Outcome::Minimum(outcome, rigid)),
                    scales,
                    record,
                }
            }
            Err((value, (status, e))) => PointResult::failure(
                status,
                format!(
                    "at {} = {}: {}",
                    find.key,
                    crate::base::format::shortest(value),
                    reason(&e)
                ),
            ),
        }
    }
}
