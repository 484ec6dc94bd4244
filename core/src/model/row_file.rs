//! The model file of a row of columns (book/src/row.md): a `[row]` table with the gaps and the
//! restitution, one `[[column]]` table per column (left to right) with the keys of `[body]` and
//! the column's `q0` and `qdot0`, and the `[excitation]`, `[simulation]` and `[solver]` tables of
//! a single body's file. Keys in messages: `row.gaps[0]`, `column[1].width`, `column[0].q0`.

use std::path::{Path, PathBuf};

use serde::{Deserialize, Serialize};

use super::body_section::{body_from_section, check_stands_up};
use super::excitation_section::{floor_from_section, RecordCache};
use super::read::{parse_table, read_model_text, MODEL_TEXT};
use super::schema::{BodySection, ExcitationSection, SimulationSection, SolverSection};
use super::simulation_section::{initial_from_section, run_duration};
use super::solver_section::solver_from_section;
use super::solver_section::{check_atol, check_rtol};
use crate::bodies::row::{ColumnSpec, CompliantSettings, Row, DEFAULT_TOLERANCE, METHOD};
use crate::error::{Error, Result};
use crate::floor::FloorMotion;
use crate::integrate::exact::ExactSettings;
use crate::integrate::{History, SolverSettings};
use crate::physics::body::Body;
use crate::physics::constants::Constants;

/// The `[row]` table.
#[derive(Debug, Clone, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct RowSection {
    /// Clear gaps between neighbours at rest, m, left to right (one fewer than the columns).
    pub gaps: Vec<f64>,
    /// Newton's coefficient of restitution at every contact, in [0, 1].
    pub restitution: f64,
    /// The contact law: "impact" (the default) or "compliant".
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub contact: Option<String>,
    /// The compliant law's contact stiffness k, N/m (required with contact = "compliant" and
    /// refused with the impact law).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub stiffness: Option<f64>,
    /// Coulomb's coefficient of friction between faces in contact, >= 0 (0, the default, is
    /// none; above 0 it needs contact = "compliant").
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub friction: Option<f64>,
}

/// The `[simulation]` table of a row: its duration (each column has its own q0 and qdot0).
#[derive(Debug, Clone, Default, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct RowSimulationSection {
    /// Simulated time, s (required except for records and pulses with a tail).
    pub duration: Option<f64>,
}

/// A row model, validated and ready to run.
pub struct RowModel {
    /// The file it came from, if any.
    pub path: Option<PathBuf>,
    /// The row: columns, contacts, restitution.
    pub row: Row,
    /// Each column's body, left to right.
    pub bodies: Vec<Body>,
    /// The `[row]` table as read.
    pub section: RowSection,
    /// The floor motion all columns stand on.
    pub floor: Box<dyn FloorMotion>,
    /// Simulated time, s.
    pub duration: f64,
    /// The exact solver's settings (its output_dt serves the compliant law's run too).
    pub settings: ExactSettings,
    /// The compliant law's integration settings; None under the impact law.
    pub compliant: Option<CompliantSettings>,
}

impl RowModel {
    /// Reads and validates a row model file; `duration` overrides `simulation.duration`.
    pub fn load(path: &Path, duration: Option<f64>) -> Result<RowModel> {
        let text = read_model_text(path)?;
        let linked = super::setting::linked_dir(path);
        let base_dir = linked
            .as_deref()
            .unwrap_or_else(|| path.parent().unwrap_or(Path::new(".")));
        let mut model = RowModel::from_text(&text, path, base_dir, duration).map_err(|e| {
            match e {
                e @ (Error::ParseModel { .. } | Error::ReadModel { .. }) => e,
                // A duration given from outside the file is not the file's fault.
                Error::InvalidParameter { ref key, .. }
                    if duration.is_some() && key == "simulation.duration" =>
                {
                    e
                }
                other => Error::InModel {
                    path: path.to_path_buf(),
                    source: Box::new(other),
                },
            }
        })?;
        model.path = Some(path.to_path_buf());
        Ok(model)
    }

    /// Validates the text of a row model file; record paths are relative to the current
    /// directory.
    pub fn from_toml_str(text: &str) -> Result<RowModel> {
        RowModel::from_text(text, Path::new(MODEL_TEXT), Path::new("."), None)
    }

    fn from_text(
        text: &str,
        source: &Path,
        base_dir: &Path,
        duration: Option<f64>,
    ) -> Result<RowModel> {
        let table = parse_table(text, source)?;
        RowModel::from_table(
            table,
            source,
            base_dir,
            duration,
            &RecordCache::default(),
            History::Sampled,
        )
    }

    /// Validates the table of a row model file (`source` names it in messages) for a run that
    /// keeps `history`; record files are read through `records`, so that a sweep reads each once.
    pub(crate) fn from_table(
        table: toml::Table,
        source: &Path,
        base_dir: &Path,
        duration: Option<f64>,
        records: &RecordCache,
        history: History,
    ) -> Result<RowModel> {
        let parse_error = |message: String| Error::ParseModel {
            path: source.to_path_buf(),
            message,
        };
        for key in table.keys() {
            if !["row", "column", "excitation", "simulation", "solver"].contains(&key.as_str()) {
                return Err(parse_error(format!(
                    "unknown table `{key}` in a row model: expected `row`, `column` (one \
                     [[column]] per column), `excitation`, `simulation` or `solver`"
                )));
            }
        }
        let part = |key: &str| table.get(key).cloned();
        let section: RowSection = match part("row") {
            Some(value) => value
                .try_into()
                .map_err(|e: toml::de::Error| parse_error(format!("[row]: {}", e.message())))?,
            None => return Err(parse_error("a row model needs a [row] table".to_string())),
        };
        let excitation: ExcitationSection = match part("excitation") {
            Some(value) => value.try_into().map_err(|e: toml::de::Error| {
                parse_error(format!("[excitation]: {}", e.message()))
            })?,
            None => return Err(parse_error("missing table [excitation]".to_string())),
        };
        let simulation: RowSimulationSection = match part("simulation") {
            Some(value) => value.try_into().map_err(|e: toml::de::Error| {
                parse_error(format!(
                    "[simulation]: {} (a row's initial state is given per column, as \
                     column q0 and qdot0)",
                    e.message()
                ))
            })?,
            None => RowSimulationSection::default(),
        };
        let solver: SolverSection = match part("solver") {
            Some(value) => value
                .try_into()
                .map_err(|e: toml::de::Error| parse_error(format!("[solver]: {}", e.message())))?,
            None => SolverSection::default(),
        };
        let columns = match part("column") {
            Some(toml::Value::Array(items)) => items,
            Some(_) => {
                return Err(parse_error(
                    "`column` must be an array of tables: one [[column]] per column".to_string(),
                ))
            }
            None => {
                return Err(parse_error(
                    "a row model needs its columns: one [[column]] table each, left to right"
                        .to_string(),
                ))
            }
        };
        let mut specs = Vec::with_capacity(columns.len());
        let mut bodies = Vec::with_capacity(columns.len());
        for (i, item) in columns.into_iter().enumerate() {
            let toml::Value::Table(mut fields) = item else {
                return Err(parse_error(format!("column[{i}] must be a table")));
            };
            let number = |value: Option<toml::Value>, key: &str| -> Result<Option<f64>> {
                match value {
                    None => Ok(None),
                    Some(toml::Value::Float(x)) => Ok(Some(x)),
                    Some(toml::Value::Integer(n)) => Ok(Some(n as f64)),
                    Some(other) => Err(parse_error(format!(
                        "column[{i}].{key}: expected a number, found {}",
                        other.type_str()
                    ))),
                }
            };
            let initial = SimulationSection {
                duration: None,
                q0: number(fields.remove("q0"), "q0")?,
                qdot0: number(fields.remove("qdot0"), "qdot0")?,
            };
            let body_section: BodySection =
                toml::Value::Table(fields)
                    .try_into()
                    .map_err(|e: toml::de::Error| {
                        parse_error(format!("column[{i}]: {}", e.message()))
                    })?;
            let in_column = |e: Error| e.in_column(i);
            let body = body_from_section(&body_section).map_err(in_column)?;
            let constants = Constants::new(&body).map_err(|e| in_column(e.into()))?;
            check_stands_up(&body_section, &body, &constants).map_err(in_column)?;
            let initial = initial_from_section(&initial, &body).map_err(in_column)?;
            specs.push(ColumnSpec {
                body: body.clone(),
                initial,
            });
            bodies.push(body);
        }
        let row = Row::new(&specs, &section.gaps, section.restitution)?;
        let compliant = match section.contact.as_deref().unwrap_or("impact") {
            "impact" => {
                if let Some(k) = section.stiffness {
                    return Err(Error::invalid(
                        "row.stiffness",
                        k,
                        "is a key of the compliant law: leave it out with contact = \"impact\" \
                         (or set contact = \"compliant\")",
                    ));
                }
                false
            }
            "compliant" => true,
            other => {
                return Err(Error::invalid(
                    "row.contact",
                    format!("\"{other}\""),
                    "must be \"impact\" or \"compliant\"",
                ))
            }
        };
        let row = if compliant {
            let Some(k) = section.stiffness else {
                return Err(Error::invalid(
                    "row.stiffness",
                    "(missing)",
                    "required with contact = \"compliant\": the contact stiffness k > 0, N/m",
                ));
            };
            row.compliant(k)?
        } else {
            row
        };
        let row = match section.friction {
            Some(mu) => row.with_friction(mu)?,
            None => row,
        };
        if excitation.vertical.is_some() {
            return Err(Error::invalid(
                "excitation.vertical",
                "(a table)",
                "a row of columns does not take vertical floor motion yet: leave \
                 [excitation.vertical] out of a row model",
            ));
        }
        let (floor, natural_duration) = floor_from_section(&excitation, base_dir, records)?;
        let duration = run_duration(
            duration.or(simulation.duration),
            natural_duration,
            &excitation,
        )?;
        if compliant {
            if let Some(method) = solver.method.as_deref().filter(|&m| m != METHOD) {
                return Err(Error::invalid(
                    "solver.method",
                    format!("\"{method}\""),
                    &format!(
                        "a row with contact = \"compliant\" is integrated by \"{METHOD}\": leave \
                         solver.method out or set it to \"{METHOD}\""
                    ),
                ));
            }
            let rtol = solver.rtol.unwrap_or(DEFAULT_TOLERANCE);
            let atol = solver.atol.unwrap_or(DEFAULT_TOLERANCE);
            check_rtol("solver.rtol", rtol)?;
            let narrowest = bodies.iter().map(|b| b.width).fold(f64::INFINITY, f64::min);
            check_atol("solver.atol", atol, narrowest)?;
            for (key, given) in [
                ("dt", solver.dt.is_some()),
                ("newmark_beta", solver.newmark_beta.is_some()),
                ("newmark_gamma", solver.newmark_gamma.is_some()),
                ("newmark_variant", solver.newmark_variant.is_some()),
            ] {
                if given {
                    return Err(Error::invalid(
                        &format!("solver.{key}"),
                        "(given)",
                        &format!("a key of Newmark's method; a compliant row is integrated by \"{METHOD}\""),
                    ));
                }
            }
            let exact = SolverSection {
                method: Some("exact".to_string()),
                output_dt: solver.output_dt,
                ..SolverSection::default()
            };
            let SolverSettings::Exact(settings) =
                solver_from_section(&exact, duration, 1.0, 1.0, history)?
            else {
                unreachable!("method = \"exact\" gives the exact settings");
            };
            return Ok(RowModel {
                path: None,
                row,
                bodies,
                section,
                floor,
                duration,
                compliant: Some(CompliantSettings {
                    rtol,
                    atol,
                    output_dt: settings.output_dt,
                }),
                settings,
            });
        }
        if let Some(method) = solver.method.as_deref().filter(|&m| m != "exact") {
            return Err(Error::invalid(
                "solver.method",
                format!("\"{method}\""),
                "a row is solved by the exact method only: leave solver.method out or set it to \
                 \"exact\"",
            ));
        }
        let exact = SolverSection {
            method: Some("exact".to_string()),
            ..solver.clone()
        };
        // The exact method has no step, so the body's frequency and width play no part here.
        let SolverSettings::Exact(settings) =
            solver_from_section(&exact, duration, 1.0, 1.0, history)?
        else {
            unreachable!("method = \"exact\" gives the exact settings");
        };
        Ok(RowModel {
            path: None,
            row,
            bodies,
            section,
            floor,
            duration,
            settings,
            compliant: None,
        })
    }
}
