//! Sweeps of a row of columns (book/src/row.md §7): every point is the row model with the
//! point's keys set, run with peaks only, and each of its columns run alone under the same floor
//! motion, so that a row of sweep.csv says whether a neighbour saved a column or toppled it.
//!
//! Keys of a row model, beside `excitation.*`, `simulation.duration` and `solver.*`:
//! - `row.gaps` sets every gap, `row.gaps.I` the gap between columns I and I + 1;
//!   `row.restitution`, `row.contact`, `row.stiffness` and any other key of `[row]` as named;
//! - `column.I.KEY` sets KEY of column I (from 0, left to right), `column.KEY` sets it in
//!   every column (KEY any key of a `[[column]]` table: a key of `[body]`, `q0`, `qdot0`).
//!
//! The number of columns and of gaps is the model file's: a key never adds one.

use std::path::Path;

use crate::bodies::row::RowSolution;
use crate::error::{Error, Result};
use crate::integrate::History;
use crate::model::{
    read_schema, Model, RecordCache, RowModel, RowSection, RowSimulationSection, Setting,
};

use super::cell::Cell;

/// What a neighbour did to a column: the column's outcome in the row against its outcome alone.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Verdict {
    /// It overturns alone and stands in the row (to the row's end).
    Saved,
    /// It stands alone and overturns in the row.
    Toppled,
    /// The same outcome in the row and alone (both overturn, or both stand).
    Same,
    /// Another column overturned first and ended the row's run: this column's outcome in the
    /// row is not known.
    Undecided,
}

impl Verdict {
    /// The name in the `cI_verdict` column.
    pub fn name(self) -> &'static str {
        match self {
            Verdict::Saved => "saved",
            Verdict::Toppled => "toppled",
            Verdict::Same => "same",
            Verdict::Undecided => "undecided",
        }
    }

    /// The verdict of column `i`: `row` is the column that overturned in the row and when, if
    /// one did (the row's run ends there), `alone` whether column `i` overturns alone.
    pub fn of(i: usize, row: Option<(usize, f64)>, alone: bool) -> Verdict {
        match (row, alone) {
            (Some((j, _)), _) if j != i => Verdict::Undecided,
            (Some(_), true) | (None, false) => Verdict::Same,
            (Some(_), false) => Verdict::Toppled,
            (None, true) => Verdict::Saved,
        }
    }
}

/// One column of a point of a row sweep: in the row, and alone.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ColumnOutcome {
    /// It overturned in the row (it is the column that ended the row's run).
    pub overturned: bool,
    /// When, s.
    pub t_overturn: Option<f64>,
    /// Its largest |q| in the row (up to the row's end), m.
    pub max_abs_q: f64,
    /// It overturns alone (the same column, the same floor motion, no neighbours).
    pub alone_overturned: bool,
    /// When, s.
    pub alone_t_overturn: Option<f64>,
    /// Its largest |q| alone, m.
    pub alone_max_abs_q: f64,
    /// What the row did to it.
    pub verdict: Verdict,
}

impl ColumnOutcome {
    /// The cells, by column name (without the column's prefix `cI_`).
    pub fn named(&self) -> [(&'static str, Cell); 7] {
        [
            ("overturned", Cell::Bool(Some(self.overturned))),
            ("t_overturn", Cell::Float(self.t_overturn)),
            ("max_abs_q", Cell::Float(Some(self.max_abs_q))),
            ("alone_overturned", Cell::Bool(Some(self.alone_overturned))),
            ("alone_t_overturn", Cell::Float(self.alone_t_overturn)),
            ("alone_max_abs_q", Cell::Float(Some(self.alone_max_abs_q))),
            ("verdict", Cell::Text(Some(self.verdict.name().to_string()))),
        ]
    }

    fn empty() -> ColumnOutcome {
        ColumnOutcome {
            overturned: false,
            t_overturn: None,
            max_abs_q: 0.0,
            alone_overturned: false,
            alone_t_overturn: None,
            alone_max_abs_q: 0.0,
            verdict: Verdict::Same,
        }
    }
}

/// What a point of a row sweep gave.
#[derive(Debug, Clone, PartialEq)]
pub struct RowOutcome {
    /// When the row's run ended, s: the duration, or the instant a column overturned.
    pub t_end: f64,
    /// The column that overturned and ended the run, if one did.
    pub overturned_column: Option<usize>,
    /// Impacts (the impact law, counted per contact) or stretches of contact (the compliant
    /// law).
    pub n_contacts: usize,
    /// When two columns first touched, s.
    pub t_first_contact: Option<f64>,
    /// The energy the contacts took from the columns, J: the impacts', or under the compliant
    /// law the contact force's and friction's.
    pub contact_energy: f64,
    /// Each column, left to right.
    pub columns: Vec<ColumnOutcome>,
}

/// The cells of the row's part, by column name.
fn row_named(o: &RowOutcome) -> [(&'static str, Cell); 5] {
    [
        ("t_end", Cell::Float(Some(o.t_end))),
        ("overturned_column", Cell::Int(o.overturned_column)),
        ("n_contacts", Cell::Int(Some(o.n_contacts))),
        ("t_first_contact", Cell::Float(o.t_first_contact)),
        ("contact_energy", Cell::Float(Some(o.contact_energy))),
    ]
}

/// The prefix of column `i`'s cells in sweep.csv.
fn prefix(i: usize) -> String {
    format!("c{i}_")
}

impl RowOutcome {
    /// The result columns of a row of `n` columns (after `status` and `reason`).
    pub fn columns(n: usize) -> Vec<String> {
        let empty = RowOutcome::empty(n);
        let mut names: Vec<String> = row_named(&empty)
            .iter()
            .map(|(name, _)| name.to_string())
            .collect();
        for i in 0..n {
            let p = prefix(i);
            names.extend(
                ColumnOutcome::empty()
                    .named()
                    .iter()
                    .map(|(name, _)| format!("{p}{name}")),
            );
        }
        names
    }

    /// The cells, in the order of [`RowOutcome::columns`].
    pub fn cells(&self) -> Vec<Cell> {
        let mut cells: Vec<Cell> = row_named(self).into_iter().map(|(_, c)| c).collect();
        for column in &self.columns {
            cells.extend(column.named().into_iter().map(|(_, c)| c));
        }
        cells
    }

    /// Empty cells of a row of `n` columns, of the kinds of [`RowOutcome::cells`].
    pub fn empty_cells(n: usize) -> Vec<Cell> {
        RowOutcome::empty(n)
            .cells()
            .iter()
            .map(|c| Cell::empty(c.kind()))
            .collect()
    }

    fn empty(n: usize) -> RowOutcome {
        RowOutcome {
            t_end: 0.0,
            overturned_column: None,
            n_contacts: 0,
            t_first_contact: None,
            contact_energy: 0.0,
            columns: vec![ColumnOutcome::empty(); n],
        }
    }

    /// The outcome of a row's `solution` beside each column's run alone (`alone[i]`: whether
    /// column i overturned alone, when, and its largest |q|, m).
    pub fn of(solution: &RowSolution, alone: &[(bool, Option<f64>, f64)]) -> RowOutcome {
        let compliant = !solution.contacts.is_empty();
        let (n_contacts, t_first_contact, contact_energy) = if compliant {
            (
                solution.contacts.len(),
                solution
                    .contacts
                    .iter()
                    .map(|c| c.t_start)
                    .min_by(f64::total_cmp),
                solution
                    .contacts
                    .iter()
                    .map(|c| c.energy_dissipated + c.friction_dissipated)
                    .sum(),
            )
        } else {
            (
                solution.impacts.len(),
                solution.impacts.iter().map(|i| i.t).min_by(f64::total_cmp),
                solution.impact_energy_loss.iter().map(|(_, e)| e).sum(),
            )
        };
        let columns = solution
            .columns
            .iter()
            .zip(alone)
            .enumerate()
            .map(|(i, (column, &(alone_overturned, alone_t, alone_q)))| {
                let t_overturn = solution.overturned.filter(|&(j, _)| j == i).map(|(_, t)| t);
                ColumnOutcome {
                    overturned: t_overturn.is_some(),
                    t_overturn,
                    max_abs_q: column.max_q.value.abs().max(column.min_q.value.abs()),
                    alone_overturned,
                    alone_t_overturn: alone_t,
                    alone_max_abs_q: alone_q,
                    verdict: Verdict::of(i, solution.overturned, alone_overturned),
                }
            })
            .collect();
        RowOutcome {
            t_end: solution.final_time,
            overturned_column: solution.overturned.map(|(i, _)| i),
            n_contacts,
            t_first_contact,
            contact_energy,
            columns,
        }
    }
}

/// The number of `[[column]]` tables of a row model's table.
pub fn column_count(table: &toml::Table) -> usize {
    match table.get("column") {
        Some(toml::Value::Array(items)) => items.len(),
        _ => 0,
    }
}

/// Sets `setting` in a row model's table, by the keys of the module's documentation. Refused,
/// naming the key and the value: a gap or a column the model does not have, a `[body]` key
/// (a row's bodies are its columns), a key of no table of a row.
pub fn apply(table: &mut toml::Table, setting: &Setting) -> Result<()> {
    let key = setting.key.as_str();
    let refuse = |rule: &str| Err(Error::invalid(key, setting.value_text(), rule));
    let parts: Vec<&str> = key.split('.').collect();
    let n = column_count(table);
    let gaps = match table.get("row").and_then(|r| r.get("gaps")) {
        Some(toml::Value::Array(items)) => items.len(),
        _ => 0,
    };
    let gap_names = |gaps: usize| match gaps {
        0 => "no gaps".to_string(),
        1 => "1 gap: row.gaps.0".to_string(),
        g => format!("{g} gaps: row.gaps.0 to row.gaps.{}", g - 1),
    };
    let number = || {
        matches!(
            setting.value,
            toml::Value::Float(_) | toml::Value::Integer(_)
        )
    };
    match parts.as_slice() {
        ["row", "gaps"] | ["row", "gaps", _] => {
            if !number() {
                return refuse("a gap is a number, m");
            }
            let index = match parts.get(2) {
                None => None,
                Some(i) => match i.parse::<usize>() {
                    Ok(i) if i < gaps => Some(i),
                    _ => {
                        return refuse(&format!(
                            "the row has {} (or row.gaps for every gap)",
                            gap_names(gaps)
                        ))
                    }
                },
            };
            let Some(toml::Value::Array(items)) = table
                .get_mut("row")
                .and_then(|r| r.as_table_mut())
                .and_then(|r| r.get_mut("gaps"))
            else {
                return refuse("the model has no row.gaps to set");
            };
            for (i, item) in items.iter_mut().enumerate() {
                if index.is_none_or(|k| k == i) {
                    *item = setting.value.clone();
                }
            }
            Ok(())
        }
        ["row", _, _] => refuse("of row's keys only row.gaps has one value per gap (row.gaps.I)"),
        ["row", name] => match table.get_mut("row") {
            Some(toml::Value::Table(row)) => {
                row.insert(name.to_string(), setting.value.clone());
                Ok(())
            }
            _ => refuse("the model has no [row] table"),
        },
        ["column", i, name] => {
            let index = match i.parse::<usize>() {
                Ok(i) if i < n => i,
                _ => {
                    return refuse(&format!(
                        "the row has {n} columns: column.0 to column.{} (or column.{name} for \
                         every column)",
                        n.saturating_sub(1)
                    ))
                }
            };
            set_in_columns(table, Some(index), name, &setting.value);
            Ok(())
        }
        ["column", name] => {
            if name.chars().all(|c| c.is_ascii_digit()) {
                return refuse("names no key: a column's key is column.I.KEY");
            }
            set_in_columns(table, None, name, &setting.value);
            Ok(())
        }
        ["body", _] => refuse(
            "a row model has no [body]: a column's key is column.I.KEY (column I from 0, left \
             to right), or column.KEY for every column",
        ),
        ["excitation" | "simulation" | "solver", _] => setting.apply(table),
        _ => refuse(
            "is no key of a row model: row.KEY, row.gaps.I, column.I.KEY, column.KEY, \
             excitation.KEY, simulation.duration or solver.KEY",
        ),
    }
}

fn set_in_columns(table: &mut toml::Table, only: Option<usize>, name: &str, value: &toml::Value) {
    if let Some(toml::Value::Array(items)) = table.get_mut("column") {
        for (i, item) in items.iter_mut().enumerate() {
            if only.is_none_or(|k| k == i) {
                if let toml::Value::Table(column) = item {
                    column.insert(name.to_string(), value.clone());
                }
            }
        }
    }
}

/// What is wrong with the schema of a row model's table (an unknown key or table, a value of
/// the wrong type), if anything: the rules the row model file's reader applies before it looks
/// at any value, here for every table at once.
pub fn schema_problem(table: &toml::Table) -> Option<String> {
    for key in table.keys() {
        if !["row", "column", "excitation", "simulation", "solver"].contains(&key.as_str()) {
            return Some(format!("unknown table `{key}` in a row model"));
        }
    }
    fn part<T: serde::de::DeserializeOwned>(
        table: &toml::Table,
        key: &str,
    ) -> std::result::Result<(), String> {
        match table.get(key) {
            Some(value) => value
                .clone()
                .try_into::<T>()
                .map(|_| ())
                .map_err(|e: toml::de::Error| format!("[{key}]: {}", e.message())),
            None => Ok(()),
        }
    }
    let checks = [
        part::<RowSection>(table, "row"),
        part::<crate::model::ExcitationSection>(table, "excitation"),
        part::<RowSimulationSection>(table, "simulation"),
        part::<crate::model::SolverSection>(table, "solver"),
    ];
    if let Some(Err(problem)) = checks.into_iter().find(|c| c.is_err()) {
        return Some(problem);
    }
    if let Some(toml::Value::Array(items)) = table.get("column") {
        for (i, item) in items.iter().enumerate() {
            let toml::Value::Table(fields) = item else {
                return Some(format!("column[{i}] must be a table"));
            };
            let mut fields = fields.clone();
            for key in ["q0", "qdot0"] {
                if let Some(value) = fields.remove(key) {
                    if !matches!(value, toml::Value::Float(_) | toml::Value::Integer(_)) {
                        return Some(format!(
                            "column[{i}].{key}: expected a number, found {}",
                            value.type_str()
                        ));
                    }
                }
            }
            if let Err(e) = toml::Value::Table(fields).try_into::<crate::model::BodySection>() {
                return Some(format!("column[{i}]: {}", e.message()));
            }
        }
    }
    None
}

/// The row model of a point's table.
pub(crate) fn row_model(
    table: &toml::Table,
    source: &Path,
    base_dir: &Path,
    records: &RecordCache,
) -> Result<RowModel> {
    RowModel::from_table(
        table.clone(),
        source,
        base_dir,
        None,
        records,
        History::PeaksOnly,
    )
}

/// Column `i` of a row model's table alone: a single body's model with the column's body and
/// initial state, the row's floor motion and duration (`duration`, s, the row's as read), solved
/// by the exact method at the row's output_dt.
pub(crate) fn alone_model(
    table: &toml::Table,
    i: usize,
    duration: f64,
    (source, base_dir): (&Path, &Path),
    records: &RecordCache,
) -> Result<Model> {
    let mut body = match table.get("column").and_then(|c| c.get(i)) {
        Some(toml::Value::Table(t)) => t.clone(),
        _ => toml::Table::new(),
    };
    let mut simulation = toml::Table::new();
    simulation.insert("duration".into(), toml::Value::Float(duration));
    for key in ["q0", "qdot0"] {
        if let Some(value) = body.remove(key) {
            simulation.insert(key.into(), value);
        }
    }
    let mut solver = toml::Table::new();
    solver.insert("method".into(), toml::Value::String("exact".into()));
    if let Some(dt) = table.get("solver").and_then(|s| s.get("output_dt")) {
        solver.insert("output_dt".into(), dt.clone());
    }
    let mut single = toml::Table::new();
    single.insert("body".into(), toml::Value::Table(body));
    single.insert("simulation".into(), toml::Value::Table(simulation));
    single.insert("solver".into(), toml::Value::Table(solver));
    if let Some(excitation) = table.get("excitation") {
        single.insert("excitation".into(), excitation.clone());
    }
    let file = read_schema(&single, &[], source)?;
    Model::for_peaks(file, base_dir, records)
}

/// A row's run with peaks only (no samples), by its contact law's method.
pub(crate) fn solve_peaks(model: &RowModel) -> Result<RowSolution> {
    Ok(match &model.compliant {
        Some(settings) => crate::bodies::row::solve_row_compliant(
            &model.row,
            model.floor.as_ref(),
            model.duration,
            settings,
            History::PeaksOnly,
        )?,
        None => crate::bodies::row::solve_row(
            &model.row,
            model.floor.as_ref(),
            model.duration,
            &model.settings,
            History::PeaksOnly,
        )?,
    })
}

/// True when two keys of a row sweep set the same value (`row.gaps` and `row.gaps.0`,
/// `column.width` and `column.1.width`).
pub fn overlapping(a: &str, b: &str) -> bool {
    let covers = |all: &str, one: &str| {
        let all: Vec<&str> = all.split('.').collect();
        let one: Vec<&str> = one.split('.').collect();
        match (all.as_slice(), one.as_slice()) {
            (["row", "gaps"], ["row", "gaps", _]) => true,
            (["column", name], ["column", _, other]) => name == other,
            _ => false,
        }
    };
    covers(a, b) || covers(b, a)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_verdict_compares_the_row_with_the_column_alone() {
        assert_eq!(Verdict::of(0, None, true), Verdict::Saved);
        assert_eq!(Verdict::of(0, None, false), Verdict::Same);
        assert_eq!(Verdict::of(0, Some((0, 2.0)), false), Verdict::Toppled);
        assert_eq!(Verdict::of(0, Some((0, 2.0)), true), Verdict::Same);
        assert_eq!(Verdict::of(1, Some((0, 2.0)), true), Verdict::Undecided);
        assert_eq!(Verdict::of(1, Some((0, 2.0)), false), Verdict::Undecided);
    }

    #[test]
    fn keys_name_one_gap_or_every_gap_and_one_column_or_every_column() {
        let mut table: toml::Table = toml::from_str(
            "[row]\ngaps = [0.01, 0.02]\nrestitution = 0.5\n[[column]]\nwidth = 1.0\n\
             [[column]]\nwidth = 2.0\n[[column]]\nwidth = 3.0\n",
        )
        .unwrap();
        apply(&mut table, &Setting::number("row.gaps.1", 0.5)).unwrap();
        assert_eq!(table["row"]["gaps"][0].as_float(), Some(0.01));
        assert_eq!(table["row"]["gaps"][1].as_float(), Some(0.5));
        apply(&mut table, &Setting::number("row.gaps", 0.25)).unwrap();
        assert_eq!(table["row"]["gaps"][0].as_float(), Some(0.25));
        assert_eq!(table["row"]["gaps"][1].as_float(), Some(0.25));
        apply(&mut table, &Setting::number("column.2.width", 9.0)).unwrap();
        assert_eq!(table["column"][2]["width"].as_float(), Some(9.0));
        assert_eq!(table["column"][1]["width"].as_float(), Some(2.0));
        apply(&mut table, &Setting::number("column.height", 4.0)).unwrap();
        for i in 0..3 {
            assert_eq!(table["column"][i]["height"].as_float(), Some(4.0));
        }
        for bad in [
            "row.gaps.2",
            "column.3.width",
            "body.width",
            "row.restitution.0",
        ] {
            let e = apply(&mut table, &Setting::number(bad, 1.0)).unwrap_err();
            assert!(e.to_string().contains(bad), "{bad}: {e}");
        }
        assert!(overlapping("row.gaps", "row.gaps.1"));
        assert!(overlapping("column.1.width", "column.width"));
        assert!(!overlapping("column.1.width", "column.height"));
        assert!(!overlapping("row.gaps.0", "row.gaps.1"));
    }
}
