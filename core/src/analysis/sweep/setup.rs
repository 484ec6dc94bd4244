//! A sweep ready to run ([`Sweep`]): a request checked against the model file (its keys, axes,
//! minimum search and kinds of excitation) and made a plan, with the record files it reads
//! digested.

use std::path::{Path, PathBuf};

use crate::error::{Error, Result};
use crate::model::{read_schema, PreparedSchema, RecordCache, Setting};

use super::axis::{self, Axis};
use super::digest::{read_record_bytes, record_digest, sha256_hex};
use super::find_min::{self, FindMin};
use super::plan::{Plan, RecordInput, SIMULATIONS_PER_CHUNK};
use super::point_result::reason;
use super::request::Request;
use super::rows;

/// A sweep ready to run: the plan, and the base model's table.
pub struct Sweep {
    /// What is computed.
    pub plan: Plan,
    /// The model file, or what names a model given as text, in messages.
    pub(super) source: PathBuf,
    /// The model's record paths are relative to this directory.
    pub(super) base_dir: PathBuf,
    pub(super) settings: Vec<Setting>,
    /// The base model's table, read with `settings`; each point's file is read again from it
    /// in the sections its own settings name.
    pub(super) schema: PreparedSchema,
    /// Record files of an `excitation.path` axis are relative to this directory (where the user
    /// typed the pattern), not to the model file.
    pub(super) paths_base: PathBuf,
    pub(super) records: RecordCache,
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
