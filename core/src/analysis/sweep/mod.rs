//! Parametric studies: one model, axes over any of its numeric keys (and over record files),
//! one [`Row`] per point.
//!
//! - [`axis`]: the axes and their values (`KEY=LO:HI:STEP`, `log:LO:HI:N`, lists, file patterns);
//! - [`find_min`]: the smallest overturning value of a key at every point (scan, then bisect);
//! - [`row`]: what a point gives, typed, and the column names of sweep.csv;
//! - [`rows`]: sweeps of a row of columns (a model file with a `[row]` table): the keys of a
//!   row, and each column's outcome in the row against its outcome alone.
//!
//! Every point is the base model with the point's keys set ([`crate::model::Setting`]), read
//! and checked by the same rules as a model file: a point that breaks one is a row with its
//! reason, not the end of the sweep. Points run in parallel (with the `parallel` feature, on by
//! default); each is computed alone, so that the rows are the same whatever the number of
//! threads. Writing the rows to disk (chunks, resuming, shards) is the command line's business.
//!
//! Values a request holds are named by the sweep file's keys in messages (`vary KEY`,
//! `find_min KEY`, `scan`, `tol`, `chunk_size`); the command line names them by its flags.

pub mod axis;
pub mod cell;
pub mod find_min;
mod in_order;
pub mod row;
pub mod rows;

use std::path::{Path, PathBuf};

use serde::{Deserialize, Serialize};

pub use axis::{Axis, Interval};
pub use cell::Cell;
pub use find_min::{FindMin, HousnerOptions};
pub(crate) use in_order::in_order;
pub use row::{Layout, Outcome, RecordCells, Row, Status};
use row::{RigidMinima, RunOutcome, Scales};

use crate::bodies::rigid::{RigidBlock, RigidForm, RigidOverturning};
use crate::error::{Error, Result};
use crate::floor::record::Record;
use crate::model::{read_schema, Model, PreparedSchema, RecordCache, Setting};

/// Simulations per chunk, roughly: a chunk is the most a kill can lose.
pub const SIMULATIONS_PER_CHUNK: usize = 1024;

/// What a sweep is, as stored with its results: enough to tell whether a directory holds this
/// sweep (to resume it, or to merge its shards) and to say how the results were made.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Plan {
    /// Version of flexrock that made the results.
    pub flexrock_version: String,
    /// The model file as named on the command line.
    pub model_file: String,
    /// Its text, so that a changed file is not mistaken for the same sweep.
    pub model_text: String,
    /// `--set` keys, as `key=value`.
    pub settings: Vec<String>,
    /// The axes, the last varying fastest.
    pub axes: Vec<Axis>,
    /// The minimum search, if the sweep makes one at each point.
    pub find_min: Option<FindMin>,
    /// Points per chunk file.
    pub chunk_size: usize,
    /// The record files the sweep reads, each with the SHA-256 of its bytes, so that a record
    /// replaced between a kill and the resume (or a relative path that names another file from
    /// another directory) makes another sweep, never a mixed one.
    pub records: Vec<RecordInput>,
    /// For a sweep of a row of columns, their number; absent for a single body's sweep, so that
    /// a single body's plan is written as before rows could be swept.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub row_columns: Option<usize>,
}

/// A record file a sweep reads: where it is named, and the digest of its contents.
#[derive(Debug, Clone, PartialEq, Eq, Serialize, Deserialize)]
pub struct RecordInput {
    /// Where the sweep names it: `model` for the model file's (and `--set`'s) `excitation.path`,
    /// else the value of the `excitation.path` axis as typed.
    pub named_by: String,
    /// SHA-256 of the file's bytes, in hex; or why the file could not be read (then every point
    /// that reads it is an invalid row).
    pub sha256: String,
}

impl Plan {
    /// Number of points: the product of the axes' lengths (1 without axes).
    pub fn points(&self) -> usize {
        self.axes.iter().map(Axis::len).product()
    }

    /// The column names of sweep.csv.
    pub fn columns(&self) -> Vec<String> {
        let mut columns = vec!["point".to_string()];
        columns.extend(self.axes.iter().map(|a| a.key.clone()));
        columns.extend(self.result_columns());
        columns
    }

    /// The result columns of sweep.csv (after the point number and the axes): a row's
    /// ([`Row::columns`]), then in a sweep over records the record's ([`Row::record_columns`]).
    pub fn result_columns(&self) -> Vec<String> {
        let mut columns = Row::columns(self.layout());
        if self.reads_records() {
            columns.extend(Row::record_columns());
        }
        columns
    }

    /// The cells of a row without values, in the order of [`Plan::result_columns`] (their
    /// kinds are the columns').
    pub fn empty_cells(&self) -> Vec<Cell> {
        let mut row = Row::failure(Status::Invalid, String::new());
        if self.reads_records() {
            row.record = Some(RecordCells::default());
        }
        row.cells(self.layout())
    }

    /// True for a single body's sweep that reads record files: its rows carry each point's
    /// record (metadata and intensity measures).
    pub fn reads_records(&self) -> bool {
        self.row_columns.is_none() && !self.records.is_empty()
    }

    /// The result columns the sweep has: runs, or a minimum search with its rigid block's form.
    pub fn layout(&self) -> Layout {
        match (&self.find_min, self.row_columns) {
            (_, Some(n)) => Layout::Row(n),
            (None, None) => Layout::Runs,
            (Some(find), None) => Layout::Minimum(find.housner()),
        }
    }

    /// The index of each axis at point `index` (the last axis varies fastest).
    pub fn coordinates(&self, mut index: usize) -> Vec<usize> {
        let mut coordinates = vec![0; self.axes.len()];
        for (slot, axis) in coordinates.iter_mut().zip(&self.axes).rev() {
            *slot = index % axis.len();
            index /= axis.len();
        }
        coordinates
    }

    /// True when `other` computes the same points: everything but the model file's name as
    /// typed (its text is compared), so that a sweep resumed from another directory, or a shard
    /// started there, is recognised.
    pub fn same_sweep(&self, other: &Plan) -> bool {
        Plan {
            model_file: other.model_file.clone(),
            ..self.clone()
        } == *other
    }

    /// The SHA-256 (hex) of everything that decides the sweep's rows: the plan but the model
    /// file's name as typed. Chunks are sealed with it, so that a chunk of another sweep is
    /// never taken for one of this sweep.
    pub fn identity(&self) -> String {
        let plan = Plan {
            model_file: String::new(),
            ..self.clone()
        };
        sha256_hex(&serde_json::to_vec(&plan).unwrap_or_default())
    }

    /// The plan as read back from a file (a sweep.json): its axes' values made settings again,
    /// which are not stored.
    pub fn restored(mut self) -> Plan {
        self.axes = self.axes.into_iter().map(Axis::restored).collect();
        self
    }
}

/// What a user asks for.
#[derive(Debug, Clone, Default)]
pub struct Request {
    /// `--set` keys, applied to every point before its axis values.
    pub settings: Vec<Setting>,
    /// `--vary` axes.
    pub axes: Vec<Axis>,
    /// `--find-min KEY=LO:HI`.
    pub find_min: Option<(String, Interval)>,
    /// Scanned values of the minimum search [default: [`find_min::DEFAULT_SCAN`]].
    pub scan: Option<usize>,
    /// Bisection tolerance [default: [`find_min::DEFAULT_TOL_SHARE`] of HI - LO].
    pub tol: Option<f64>,
    /// Points per chunk [default: about [`SIMULATIONS_PER_CHUNK`] simulations].
    pub chunk_size: Option<usize>,
    /// The equation of Housner's block in the minimum search [default: small-angle].
    pub rigid_form: Option<RigidForm>,
    /// When Housner's block of the minimum search counts as overturned [default: when its
    /// tilt reaches its limit].
    pub rigid_overturning: Option<RigidOverturning>,
    /// Housner's block's own coefficient of restitution [default: Housner's].
    pub rigid_restitution: Option<f64>,
    /// Records held in memory (the Python bindings' ground motions), each under the path the
    /// model's `excitation.path` names it by: a point reads it from here, not from a file.
    pub records: Vec<(String, Record)>,
}

/// A sweep file: the axes, settings and search of a sweep, written as on the command line.
///
/// ```toml
/// vary = ["excitation.amplitude=0.5:15:0.5", "excitation.period=log:0.2:3:40"]
/// set = ["solver.method=tsit45", "solver.rtol=1e-8"]
/// find_min = "excitation.amplitude=0.5:15"   # optional
/// scan = 100                                  # optional
/// tol = 1e-3                                  # optional
/// rigid_form = "full"                         # optional, with find_min
/// rigid_overturning = "cannot-return"         # optional, with find_min
/// rigid_restitution = 0.9                     # optional, with find_min
/// ```
#[derive(Debug, Clone, Default, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SweepFile {
    /// As `--vary`.
    #[serde(default)]
    pub vary: Vec<String>,
    /// As `--set`.
    #[serde(default)]
    pub set: Vec<String>,
    /// As `--find-min`.
    pub find_min: Option<String>,
    /// As `--scan`.
    pub scan: Option<usize>,
    /// As `--tol`.
    pub tol: Option<f64>,
    /// As `--chunk-size`.
    pub chunk_size: Option<usize>,
    /// As `--rigid-form`.
    pub rigid_form: Option<String>,
    /// As `--rigid-overturning`.
    pub rigid_overturning: Option<String>,
    /// As `--rigid-restitution`.
    pub rigid_restitution: Option<f64>,
}

impl Request {
    /// Adds the axis `KEY=SPEC` (file patterns relative to `base_dir`), checking that the sweep
    /// stays within [`axis::MAX_POINTS`] before the axis's values are made.
    pub fn vary(&mut self, text: &str, base_dir: &Path) -> Result<()> {
        let others = (self.axes.iter()).fold(1usize, |n, a| n.saturating_mul(a.len()));
        self.axes.push(Axis::parse_beside(text, base_dir, others)?);
        Ok(())
    }

    /// Adds a sweep file to the request; file patterns and record paths in it are relative to
    /// the file (its `set` record paths are written again relative to the model file `model`,
    /// which reads them). Relative `path` and `model` are relative to the directory `here`.
    pub fn add_file(&mut self, path: &Path, model: &Path, here: &Path) -> Result<()> {
        // Read as a model file is (a regular file of limited size), so that /dev/zero is refused.
        let text = crate::model::read_model_text(path).map_err(|e| match e {
            Error::ReadModel { path, source } => Error::SweepFile {
                path,
                message: format!("cannot read the sweep file: {source}"),
            },
            other => other,
        })?;
        let file: SweepFile = toml::from_str(&text).map_err(|e| Error::ParseModel {
            path: path.to_path_buf(),
            message: e.to_string().trim_end().to_string(),
        })?;
        let base = path.parent().unwrap_or(Path::new("."));
        let in_file = |e: Error| Error::InModel {
            path: path.to_path_buf(),
            source: Box::new(e),
        };
        let model_dir = crate::model::model_dir(here, Some(model));
        for text in &file.set {
            let setting = Setting::parse(text).map_err(in_file)?;
            self.settings
                .push(setting.rebased(&here.join(base), &model_dir));
        }
        for text in &file.vary {
            self.vary(text, base).map_err(in_file)?;
        }
        if let Some(text) = &file.find_min {
            self.find_min = Some(axis::parse_interval(text).map_err(in_file)?);
        }
        self.scan = self.scan.or(file.scan);
        self.tol = self.tol.or(file.tol);
        self.chunk_size = self.chunk_size.or(file.chunk_size);
        if let Some(text) = &file.rigid_form {
            let form = RigidForm::parse("rigid_form", text).map_err(|e| in_file(e.into()))?;
            self.rigid_form = self.rigid_form.or(Some(form));
        }
        if let Some(text) = &file.rigid_overturning {
            let rule = RigidOverturning::parse("rigid_overturning", text)
                .map_err(|e| in_file(e.into()))?;
            self.rigid_overturning = self.rigid_overturning.or(Some(rule));
        }
        self.rigid_restitution = self.rigid_restitution.or(file.rigid_restitution);
        Ok(())
    }
}

/// A sweep ready to run: the plan, and the base model's table.
pub struct Sweep {
    /// What is computed.
    pub plan: Plan,
    /// The model file, or what names a model given as text, in messages.
    source: PathBuf,
    /// The model's record paths are relative to this directory.
    base_dir: PathBuf,
    settings: Vec<Setting>,
    /// The base model's table, read with `settings`; each point's file is read again from it
    /// in the sections its own settings name.
    schema: PreparedSchema,
    /// Record files of an `excitation.path` axis are relative to this directory (where the user
    /// typed the pattern), not to the model file.
    paths_base: PathBuf,
    records: RecordCache,
    /// The records held in memory, by their paths joined to `base_dir`, with their digests.
    in_memory: Vec<(PathBuf, String)>,
}

impl Sweep {
    /// Checks a request against the model file: keys known to the schema, axes distinct,
    /// the minimum searched over a key that is not an axis. Values are checked per point.
    /// Record paths of the model file are relative to the file; the values of an
    /// `excitation.path` axis, typed by the user, are relative to the directory `here`.
    pub fn new(model_path: &Path, request: Request, here: &Path) -> Result<Sweep> {
        let (model_text, table) = crate::model::read_model_table(model_path)?;
        let base_dir = model_path.parent().unwrap_or(Path::new("."));
        Sweep::build(
            model_path.display().to_string(),
            model_text,
            table,
            (model_path, base_dir),
            request,
            here,
        )
    }

    /// [`Sweep::new`] for a model given as the text of a model file: its record paths are
    /// relative to `base_dir`, and messages name it `(model text)`.
    pub fn from_text(text: &str, base_dir: &Path, request: Request, here: &Path) -> Result<Sweep> {
        let source = Path::new(crate::model::MODEL_TEXT);
        let table = crate::model::parse_table(text, source)?;
        Sweep::build(
            crate::model::MODEL_TEXT.to_string(),
            text.to_string(),
            table,
            (source, base_dir),
            request,
            here,
        )
    }

    fn build(
        model_file: String,
        model_text: String,
        table: toml::Table,
        (source, base_dir): (&Path, &Path),
        request: Request,
        here: &Path,
    ) -> Result<Sweep> {
        let model_path = source;
        let row_columns = crate::model::is_row_table(&table).then(|| rows::column_count(&table));
        if let (Some(_), Some((key, interval))) = (row_columns, &request.find_min) {
            return Err(Error::invalid(
                "find_min",
                format!("{key}={}:{}", interval.lo, interval.hi),
                "a minimum search is not made for a row of columns (yet): sweep the key as an \
                 axis (vary) and read each column's verdict",
            ));
        }
        let find_min = match &request.find_min {
            None => None,
            Some((key, interval)) => {
                // An interval made in code (not parsed from `KEY=LO:HI`) meets the same rules.
                axis::check_interval(key, interval)?;
                let scan = request.scan.unwrap_or(find_min::DEFAULT_SCAN);
                if !(2..=axis::MAX_AXIS_VALUES).contains(&scan) {
                    return Err(Error::invalid(
                        "scan",
                        scan,
                        &format!("must lie in 2..={}", axis::MAX_AXIS_VALUES),
                    ));
                }
                let tol = request
                    .tol
                    .unwrap_or(find_min::DEFAULT_TOL_SHARE * (interval.hi - interval.lo));
                if !(tol > 0.0 && tol.is_finite()) {
                    return Err(Error::invalid("tol", tol, "must be a positive number"));
                }
                Some(FindMin {
                    key: key.clone(),
                    lo: interval.lo,
                    hi: interval.hi,
                    scan,
                    tol,
                    rigid_form: request.rigid_form.unwrap_or_default(),
                    rigid_overturning: request.rigid_overturning.unwrap_or_default(),
                    rigid_restitution: request.rigid_restitution,
                })
            }
        };
        const NOT_SEARCHED: &str = "chooses the rigid block of a minimum search (find_min, \
                                    --find-min), which this sweep does not make";
        if find_min.is_none() {
            if let Some(form) = request.rigid_form {
                return Err(Error::invalid("rigid_form", form.name(), NOT_SEARCHED));
            }
            if let Some(rule) = request.rigid_overturning {
                return Err(Error::invalid(
                    "rigid_overturning",
                    rule.name(),
                    NOT_SEARCHED,
                ));
            }
            if let Some(e) = request.rigid_restitution {
                return Err(Error::invalid("rigid_restitution", e, NOT_SEARCHED));
            }
        }
        if let Some(e) = request.rigid_restitution {
            crate::bodies::rigid::check_restitution("rigid_restitution", e)?;
        }
        if request.axes.is_empty() && find_min.is_none() {
            return Err(Error::invalid(
                "vary",
                "(none)",
                "a sweep needs at least one axis or a minimum search",
            ));
        }
        // Axes made in code (not parsed from `KEY=SPEC`) meet the rules of parsed ones.
        for axis in &request.axes {
            axis::check_axis(axis)?;
        }
        let mut keys: Vec<&str> = request.axes.iter().map(|a| a.key.as_str()).collect();
        if let Some(f) = &find_min {
            keys.push(&f.key);
        }
        for (i, key) in keys.iter().enumerate() {
            if keys[..i].contains(key) {
                return Err(Error::invalid(
                    &format!("vary {key}"),
                    key,
                    "each key may be varied (or searched) once",
                ));
            }
            if let Some(other) = keys[..i].iter().find(|k| rows::overlapping(k, key)) {
                return Err(Error::invalid(
                    &format!("vary {key}"),
                    key,
                    &format!("sets a value that the axis {other} sets too: vary one of them"),
                ));
            }
        }
        let points = request
            .axes
            .iter()
            .try_fold(1usize, |n, a| n.checked_mul(a.len()))
            .filter(|&n| n <= axis::MAX_POINTS)
            .ok_or_else(|| {
                Error::invalid(
                    "vary",
                    request
                        .axes
                        .iter()
                        .map(|a| a.len().to_string())
                        .collect::<Vec<_>>()
                        .join(" x "),
                    &format!("a sweep may have at most {} points", axis::MAX_POINTS),
                )
            })?;
        // Every key must exist in the schema: try the first value of each (a value's own rules
        // are the point's business).
        let mut probe: Vec<Setting> = request.settings.clone();
        probe.extend(request.axes.iter().map(|a| a.setting(0)));
        if let Some(f) = &find_min {
            probe.push(Setting::number(&f.key, f.lo));
        }
        for (i, setting) in probe.iter().enumerate() {
            let checked = match row_columns {
                None => read_schema(&table, &probe[..=i], model_path).map(|_| ()),
                Some(_) => row_schema(&table, &probe[..=i], model_path),
            };
            if let Err(e) = checked {
                let is_axis = i >= request.settings.len();
                return Err(if is_axis {
                    // A rule about this very key and value is said once.
                    let rule = match &e {
                        Error::InvalidParameter { key, rule, .. } if *key == setting.key => {
                            rule.clone()
                        }
                        _ => e.to_string(),
                    };
                    Error::invalid(
                        &setting.key,
                        setting.value_text(),
                        &format!("cannot be swept: {rule}"),
                    )
                } else {
                    e
                });
            }
        }
        check_kinds_take(&table, &request.settings, &request.axes, find_min.as_ref())?;
        let simulations_per_point = find_min.as_ref().map_or(1, |f| f.scan + 16);
        let chunk_size = request
            .chunk_size
            .unwrap_or((SIMULATIONS_PER_CHUNK / simulations_per_point).max(1));
        if chunk_size == 0 {
            return Err(Error::invalid("chunk_size", 0, "must be at least 1"));
        }
        let plan = Plan {
            flexrock_version: crate::simulate::VERSION.to_string(),
            model_file,
            model_text,
            settings: request
                .settings
                .iter()
                .map(|s| format!("{}={}", s.key, s.value_text()))
                .collect(),
            axes: request.axes,
            find_min,
            chunk_size: chunk_size.min(points.max(1)),
            records: Vec::new(),
            row_columns,
        };
        let schema = PreparedSchema::new(table, &request.settings, source);
        let records = RecordCache::default();
        let in_memory = request
            .records
            .into_iter()
            .map(|(path, record)| {
                let path = crate::model::record_path(base_dir, &path);
                let digest = record_digest(&record);
                records.insert(&path, record);
                (path, digest)
            })
            .collect();
        let mut sweep = Sweep {
            plan,
            schema,
            source: source.to_path_buf(),
            base_dir: base_dir.to_path_buf(),
            settings: request.settings,
            paths_base: here.to_path_buf(),
            records,
            in_memory,
        };
        sweep.plan.records = sweep.record_inputs();
        if let Some(find) = &sweep.plan.find_min {
            sweep.check_search_ends(find)?;
        }
        Ok(sweep)
    }

    /// Refuses a minimum search whose interval reaches beyond the model's rules: at the first
    /// point, the model must be valid at both ends when it is at one of them (a search whose
    /// upper end is beyond 20 g, say, would make every point invalid). Where both ends are
    /// refused, the points' rows say why.
    fn check_search_ends(&self, find: &FindMin) -> Result<()> {
        let first = self.settings_at(0);
        let at = |value: f64| {
            let mut settings = first.clone();
            settings.push(Setting::number(&find.key, value));
            self.model(&settings).err()
        };
        let (end, value, e) = match (at(find.lo), at(find.hi)) {
            (None, Some(e)) => ("upper", find.hi, e),
            (Some(e), None) => ("lower", find.lo, e),
            _ => return Ok(()),
        };
        Err(Error::invalid(
            &format!("find_min {}", find.key),
            format!(
                "{}:{}",
                crate::base::format::shortest(find.lo),
                crate::base::format::shortest(find.hi)
            ),
            &format!(
                "the search interval must lie within the model's rules, and at its {end} end, \
                 {} = {}, the model is refused: {}",
                find.key,
                crate::base::format::shortest(value),
                reason(&e)
            ),
        ))
    }

    /// The record files the sweep reads and their digests: the model's own `excitation.path`
    /// (with the `--set` keys), and every value of an `excitation.path` axis. Each file is then
    /// read into the record cache at once, so that the rows are computed from the contents just
    /// digested (not from a file replaced later in the run).
    fn record_inputs(&self) -> Vec<RecordInput> {
        let mut cases: Vec<(String, Vec<Setting>)> =
            vec![("model".to_string(), self.settings.clone())];
        for axis in self.plan.axes.iter().filter(|a| a.key == "excitation.path") {
            for i in 0..axis.len() {
                let mut settings = self.settings.clone();
                settings.push(self.absolute_path_setting(axis.setting(i)));
                cases.push((axis.values[i].clone(), settings));
            }
        }
        let mut inputs = Vec::new();
        for (named_by, settings) in cases {
            let excitation = if self.plan.row_columns.is_some() {
                let Ok(table) = self.row_table(&settings) else {
                    continue;
                };
                let Some(Ok(section)) = table
                    .get("excitation")
                    .map(|e| e.clone().try_into::<crate::model::ExcitationSection>())
                else {
                    continue;
                };
                section
            } else {
                let Ok(file) = self
                    .schema
                    .read(&settings[self.settings.len()..], &self.source)
                else {
                    continue;
                };
                file.excitation
            };
            let Some(path) = excitation.path.as_deref() else {
                continue;
            };
            if excitation.kind != "record" {
                continue;
            }
            let path = crate::model::record_path(&self.base_dir, path);
            let sha256 = match self.in_memory.iter().find(|(p, _)| *p == path) {
                Some((_, digest)) => digest.clone(),
                None => match read_record_bytes(&path) {
                    Ok(bytes) => sha256_hex(&bytes),
                    Err(e) => format!("unreadable: {e}"),
                },
            };
            // Into the cache now; a point whose record is bad reports it in its own row.
            if self.plan.row_columns.is_some() {
                if let Ok(table) = self.row_table(&settings) {
                    let _ = rows::row_model(&table, &self.source, &self.base_dir, &self.records);
                }
            } else {
                let _ = self.model(&settings);
            }
            inputs.push(RecordInput { named_by, sha256 });
        }
        inputs
    }

    /// Number of points.
    pub fn points(&self) -> usize {
        self.plan.points()
    }

    /// The model of point `index` with `further` keys set after the axes' values (a record's
    /// scale, say): what a study built on a sweep reads of a point besides its row.
    pub fn model_at(&self, index: usize, further: &[Setting]) -> Result<Model> {
        let mut settings = self.settings_at(index);
        settings.extend_from_slice(further);
        self.model(&settings)
    }

    /// The settings of point `index`: the `--set` keys, then the axes' values.
    fn settings_at(&self, index: usize) -> Vec<Setting> {
        let mut settings = self.settings.clone();
        for (axis, &i) in self.plan.axes.iter().zip(&self.plan.coordinates(index)) {
            settings.push(self.absolute_path_setting(axis.setting(i)));
        }
        settings
    }

    /// A value of an `excitation.path` axis made absolute: record files of an axis are relative
    /// to the directory the sweep was started from. Other settings are returned unchanged.
    fn absolute_path_setting(&self, mut setting: Setting) -> Setting {
        if setting.key == "excitation.path" {
            if let toml::Value::String(path) = &setting.value {
                let absolute = self.paths_base.join(path);
                setting.value = toml::Value::String(absolute.to_string_lossy().into_owned());
            }
        }
        setting
    }

    /// The row model's table with `settings` set.
    fn row_table(&self, settings: &[Setting]) -> Result<toml::Table> {
        let mut table = self.schema.table().clone();
        for setting in settings {
            rows::apply(&mut table, setting)?;
        }
        Ok(table)
    }

    /// The row of a point of a row sweep: the row's run, and each column's alone.
    fn row_point(&self, settings: &[Setting]) -> Row {
        let invalid = |e: &Error| Row::failure(Status::Invalid, reason(e));
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
                Err(e) => return Row::failure(Status::Invalid, in_column(&e)),
            };
            match crate::simulate::simulate_peaks(&single) {
                Ok(s) => alone.push((
                    s.overturned,
                    s.t_overturn,
                    s.max_q.value.abs().max(s.min_q.value.abs()),
                )),
                Err(e) => return Row::failure(Status::Failed, in_column(&e)),
            }
        }
        match rows::solve_peaks(&model) {
            Ok(solution) => Row {
                status: Status::Ok,
                reason: String::new(),
                outcome: Some(Outcome::Row(rows::RowOutcome::of(&solution, &alone))),
                scales: None,
                record: None,
            },
            Err(e) => Row::failure(Status::Failed, reason(&e)),
        }
    }

    /// The model of the sweep's `--set` keys (`settings` starts with them), then the rest of
    /// `settings`.
    fn model(&self, settings: &[Setting]) -> Result<Model> {
        debug_assert!(settings.starts_with(&self.settings));
        let further = settings.get(self.settings.len()..).unwrap_or_default();
        let file = self.schema.read(further, &self.source)?;
        Model::for_peaks(file, &self.base_dir, &self.records)
    }

    /// The rows of the points `points`, in point order (in parallel with the `parallel`
    /// feature); `done` is called as each point finishes, from the thread that computed it.
    pub fn rows(&self, points: std::ops::Range<usize>, done: &(dyn Fn() + Sync)) -> Vec<Row> {
        self.rows_as(points, done, |_, row| row)
    }

    /// The rows of the points `points`, in point order, or None once `stop()` is true: each
    /// point asks before it starts, so that a caller who stops waiting (the Python bindings on
    /// Ctrl-C) waits for no more than the points under way.
    pub fn rows_until(
        &self,
        points: std::ops::Range<usize>,
        stop: &(dyn Fn() -> bool + Sync),
    ) -> Option<Vec<Row>> {
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
        with: impl Fn(usize, Row) -> T + Sync + Send,
    ) -> Vec<T> {
        in_order(points, |i| {
            let row = self.evaluate(i);
            done();
            with(i, row)
        })
    }

    /// The row of point `index`.
    pub fn evaluate(&self, index: usize) -> Row {
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

    fn run_point(&self, settings: &[Setting]) -> Row {
        let model = match self.model(settings) {
            Ok(model) => model,
            Err(e) => return Row::failure(Status::Invalid, reason(&e)),
        };
        let record = self.plan.reads_records().then(|| RecordCells::of(&model));
        let scales = Some(Scales::of(&model));
        match crate::simulate::simulate_peaks(&model) {
            Ok(solution) => Row {
                status: Status::Ok,
                reason: String::new(),
                outcome: Some(Outcome::Run(RunOutcome::of(&model, &solution))),
                scales,
                record,
            },
            Err(e) => Row {
                scales,
                record,
                ..Row::failure(Status::Failed, reason(&e))
            },
        }
    }

    fn search_point(&self, settings: &[Setting], find: &FindMin) -> Row {
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
                        let out = crate::simulate::simulate_rigid(&model, &block)?;
                        Ok(find_min::Trial {
                            overturned: out.overturned,
                            t_overturn: out.t_overturn,
                            steps: 0,
                            rhs_evaluations: 0,
                        })
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
                    Row::failure(
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
                Row {
                    status: Status::Ok,
                    reason: String::new(),
                    outcome: Some(Outcome::Minimum(outcome, rigid)),
                    scales,
                    record,
                }
            }
            Err((value, (status, e))) => Row::failure(
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

/// SHA-256 of `bytes`, as 64 lower-case hex digits: the digest of a record file a sweep reads,
/// and of its plan.
pub fn sha256_hex(bytes: &[u8]) -> String {
    sha256_hex_of(&[bytes])
}

/// SHA-256 of the bytes of `parts` one after another (the digest of their concatenation, which
/// is never made), as 64 lower-case hex digits.
pub fn sha256_hex_of(parts: &[&[u8]]) -> String {
    use sha2::{Digest as _, Sha256};
    let mut hasher = Sha256::new();
    for part in parts {
        hasher.update(part);
    }
    hex(&hasher.finalize())
}

/// `bytes` as lower-case hex digits, two a byte.
fn hex(bytes: &[u8]) -> String {
    let mut text = String::with_capacity(2 * bytes.len());
    for byte in bytes {
        text.push_str(&format!("{byte:02x}"));
    }
    text
}

/// SHA-256 (hex) of a record held in memory: of its interval and its samples, each as the
/// little-endian bytes of its float.
fn record_digest(record: &Record) -> String {
    use sha2::{Digest as _, Sha256};
    let mut hasher = Sha256::new();
    hasher.update(record.dt.to_le_bytes());
    for v in &record.values {
        hasher.update(v.to_le_bytes());
    }
    hex(&hasher.finalize())
}

/// The bytes of a record file, read as the record reader reads it (a regular file of bounded
/// size), for its digest.
fn read_record_bytes(path: &Path) -> std::io::Result<Vec<u8>> {
    use std::io::Read as _;
    let file = std::fs::File::open(path)?;
    if !file.metadata()?.is_file() {
        return Err(std::io::Error::other("not a regular file"));
    }
    let limit = crate::floor::record::MAX_RECORD_BYTES + 1;
    let mut bytes = Vec::new();
    file.take(limit).read_to_end(&mut bytes)?;
    Ok(bytes)
}

/// Checks the keys `settings` against a row model's table: each names a value of the row (a
/// gap, a column it has) and the table with them fits the row model file's schema. Values are
/// the points' business.
fn row_schema(table: &toml::Table, settings: &[Setting], source: &Path) -> Result<()> {
    let mut table = table.clone();
    for setting in settings {
        rows::apply(&mut table, setting)?;
    }
    match rows::schema_problem(&table) {
        None => Ok(()),
        Some(message) => Err(Error::ParseModel {
            path: source.to_path_buf(),
            message,
        }),
    }
}

/// Refuses an axis (or a minimum search) over an `[excitation]` key that no kind of the sweep
/// takes, before any point runs: every point would be invalid (`excitation.amplitude` of a
/// record, whose intensity is `excitation.scale`). The kinds are the values of an
/// `excitation.kind` axis, else the kind the model file and the `--set` keys give.
fn check_kinds_take(
    table: &toml::Table,
    settings: &[Setting],
    axes: &[Axis],
    find_min: Option<&FindMin>,
) -> Result<()> {
    let kinds: Vec<String> = match axes.iter().find(|a| a.key == "excitation.kind") {
        Some(axis) => axis.values.clone(),
        None => {
            let set = settings.iter().rev().find(|s| s.key == "excitation.kind");
            let kind = match set {
                Some(s) => s.value.as_str().map(str::to_string),
                None => table
                    .get("excitation")
                    .and_then(|e| e.get("kind"))
                    .and_then(|k| k.as_str())
                    .map(str::to_string),
            };
            kind.into_iter().collect()
        }
    };
    let keys = axes
        .iter()
        .map(|a| {
            (
                format!("vary {}", a.key),
                a.key.as_str(),
                a.values.join(","),
            )
        })
        .chain(find_min.map(|f| {
            (
                format!("find_min {}", f.key),
                f.key.as_str(),
                format!(
                    "{}:{}",
                    crate::base::format::shortest(f.lo),
                    crate::base::format::shortest(f.hi)
                ),
            )
        }));
    for (name, key, values) in keys {
        // The vertical motion's keys are its own table's business.
        let Some(field) = key
            .strip_prefix("excitation.")
            .filter(|f| *f != "kind" && !f.starts_with("vertical."))
        else {
            continue;
        };
        let taken: Vec<(&str, Vec<&str>)> = kinds
            .iter()
            .filter_map(|kind| Some((kind.as_str(), crate::model::keys_of_kind(kind)?)))
            .collect();
        // A kind the schema does not know is the points' business (each says so).
        if taken.len() < kinds.len() || taken.iter().any(|(_, keys)| keys.contains(&field)) {
            continue;
        }
        let hint = if field == "amplitude" && kinds.iter().any(|k| k == "record") {
            "; a record's intensity is swept with excitation.scale"
        } else {
            ""
        };
        let described: Vec<String> = taken
            .iter()
            .map(|(kind, keys)| match keys.as_slice() {
                [] => format!("kind = \"{kind}\" takes no key"),
                keys => format!("kind = \"{kind}\" takes {}", keys.join(", ")),
            })
            .collect();
        return Err(Error::invalid(
            &name,
            values,
            &format!(
                "cannot be swept: {key} is not a parameter of the sweep's excitation ({}){hint}",
                described.join("; ")
            ),
        ));
    }
    Ok(())
}

/// An error as one line of a CSV field.
fn reason(e: &Error) -> String {
    e.to_string().replace(['\n', '\r'], " ")
}
