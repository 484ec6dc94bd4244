//! `flexrock run` on a row model (a file with a `[row]` table): every column's history, events
//! and episodes, the impacts, summary.json and the figure, written as one atomic set.

use std::fmt::Write as _;
use std::path::{Path, PathBuf};

use crate::error::Result;
use crate::figures::page::FigureOptions;
use crate::figures::row::ShapeTime;
use crate::writers;
use flexrock_core::bodies::row::{ContactLaw, RowSolution, METHOD};
use flexrock_core::model::RowModel;
use flexrock_core::physics::automaton::EventKind;
use flexrock_core::simulate::{simulate_row, VERSION};
use flexrock_core::tables::fields::fields;
use flexrock_core::tables::row_results::{
    impact_rows, row_summary, CONTACT_COLUMNS, CONTACT_COLUMN_NAMES, IMPACT_COLUMNS,
    IMPACT_COLUMN_NAMES,
};

/// What `flexrock run` on a row returns.
pub struct RowReport {
    /// The solution.
    pub solution: RowSolution,
    /// The files written.
    pub files: Vec<PathBuf>,
}

/// Solves a row and writes, for each column i (from 0, left to right), `history-i.csv`,
/// `events-i.csv` and `episodes-i.csv` (the columns of a single body's files), and
/// `impacts.csv`, `contacts.csv` (every contact at every sampled instant), `summary.json` and,
/// with `plots`, `row_motion` and the strip of the row's shapes `row_shapes` in the formats and
/// size of `figures` (at `shapes_at`, or at the times
/// [`crate::figures::row::automatic_shape_times`] chooses), as one atomic set. Times
/// given without `plots` draw the strip alone. Nothing in them depends on the machine: the
/// same row gives the same bytes.
pub fn run_row_to_dir(
    model: &RowModel,
    out_dir: &Path,
    plots: bool,
    shapes_at: Option<&[ShapeTime]>,
    figures: &FigureOptions,
) -> Result<RowReport> {
    let solution = simulate_row(model)?;
    let mut files: Vec<(String, Vec<u8>)> = Vec::new();
    for (i, column) in solution.columns.iter().enumerate() {
        files.push((
            format!("history-{i}.csv"),
            writers::history_csv(&column.samples),
        ));
        files.push((
            format!("events-{i}.csv"),
            writers::events_csv(&column.events),
        ));
        files.push((
            format!("episodes-{i}.csv"),
            writers::episodes_csv(&column.episodes, model.bodies[i].height),
        ));
    }
    let mut impacts = writers::Table::new(&IMPACT_COLUMN_NAMES);
    for row in impact_rows(model, &solution) {
        impacts.row(fields(&IMPACT_COLUMNS, &row));
    }
    files.push(("impacts.csv".to_string(), impacts.into_bytes()));
    let mut contacts = writers::Table::new(&CONTACT_COLUMN_NAMES);
    for sample in &solution.contact_history {
        contacts.row(fields(&CONTACT_COLUMNS, sample));
    }
    files.push(("contacts.csv".to_string(), contacts.into_bytes()));
    files.push((
        "summary.json".to_string(),
        writers::json_bytes(&row_summary(model, &solution)),
    ));
    if plots {
        files.extend(crate::figures::row::figures(model, &solution, figures)?);
    }
    if plots || shapes_at.is_some() {
        let instants = crate::figures::row::sampled_instants(&solution);
        let times = match shapes_at {
            Some(times) => times.to_vec(),
            None => crate::figures::row::automatic_shape_times(model, &solution, &instants),
        };
        files.extend(crate::figures::row::shape_figures(
            model, &solution, &instants, &times, figures,
        )?);
    }
    let files = writers::write_named_atomically(out_dir, files)?;
    Ok(RowReport { solution, files })
}

/// The short human summary printed after a row's run.
pub fn row_report_text(model: &RowModel, report: &RowReport) -> String {
    let s = &report.solution;
    let mut t = String::new();
    match model.row.law() {
        ContactLaw::Compliant {
            stiffness,
            damping_ratio,
        } => {
            let friction = match model.row.friction() {
                mu if mu > 0.0 => format!(", friction mu = {}", writers::significant(mu, 6)),
                _ => String::new(),
            };
            let _ = writeln!(
                t,
                "flexrock {VERSION}: {METHOD} solution of a row of {} columns over {} s, compliant \
                 contacts (k = {} N/m, zeta = {}{friction})",
                s.columns.len(),
                model.duration,
                writers::significant(stiffness, 6),
                writers::significant(damping_ratio, 6),
            );
        }
        ContactLaw::Impact => {
            let _ = writeln!(
                t,
                "flexrock {VERSION}: exact solution of a row of {} columns over {} s",
                s.columns.len(),
                model.duration
            );
        }
    }
    for (i, c) in s.columns.iter().enumerate() {
        let _ = writeln!(
            t,
            "  column {i}: max q = {:.9} m at t = {:.9} s; min q = {:.9} m at t = {:.9} s; {}, {}, {}",
            c.max_q.value,
            c.max_q.t,
            c.min_q.value,
            c.min_q.t,
            writers::count(c.count(EventKind::Uplift), "uplift", "uplifts"),
            writers::count(c.count(EventKind::Landing), "landing", "landings"),
            if let ContactLaw::Compliant { .. } = model.row.law() {
                writers::count(c.count(EventKind::ContactStart), "contact", "contacts")
            } else {
                writers::count(c.count(EventKind::Impact), "impact", "impacts")
            },
        );
    }
    let lost: f64 = s.impact_energy_loss.iter().map(|(_, e)| e).sum();
    if let ContactLaw::Compliant { .. } = model.row.law() {
        let taken: f64 = s.contacts.iter().map(|c| c.energy_dissipated).sum();
        let friction = if model.row.friction() > 0.0 {
            let rubbed: f64 = s.contacts.iter().map(|c| c.friction_dissipated).sum();
            let changes: usize = s.contacts.iter().map(|c| c.friction_changes).sum();
            format!(
                ", friction {} J ({} between sticking and sliding)",
                writers::significant(rubbed, 6),
                writers::count(changes, "change", "changes")
            )
        } else {
            String::new()
        };
        let _ = writeln!(
            t,
            "  {} of contact, taking {} J{friction}; {}",
            writers::count(s.contacts.len(), "stretch", "stretches"),
            writers::significant(taken, 6),
            ending(s)
        );
        for f in &report.files {
            let _ = writeln!(t, "  wrote {}", f.display());
        }
        return t;
    }
    let _ = writeln!(
        t,
        "  {} at {}, taking {} J; {}",
        writers::count(s.impacts.len(), "impact", "impacts"),
        writers::count(s.impact_energy_loss.len(), "instant", "instants"),
        writers::significant(lost, 6),
        ending(s)
    );
    if !s.held.is_empty() {
        let _ = writeln!(
            t,
            "  {} of persistent contact (impacts that accumulated: the pair held together until \
             its contact force fell to zero), listed in summary.json",
            writers::count(s.held.len(), "stretch", "stretches"),
        );
    }
    for f in &report.files {
        let _ = writeln!(t, "  wrote {}", f.display());
    }
    t
}

/// How a row's run ended, as its summary line says it: where a column overturned (after which
/// no other column moves on), or the columns still rocking at the end of the duration.
fn ending(s: &RowSolution) -> String {
    if let Some((i, at)) = s.overturned {
        return format!(
            "column {i} overturned at t = {at:.9} s (the run ends there: the other columns' \
             motion after it is not computed)"
        );
    }
    let rocking: Vec<String> = (s.columns.iter().enumerate())
        .filter(|(_, c)| c.ended_while_rocking())
        .map(|(i, _)| i.to_string())
        .collect();
    match rocking.len() {
        0 => "no overturning".to_string(),
        1 => format!(
            "column {} ended while rocking; no overturning within the duration",
            rocking[0]
        ),
        _ => format!(
            "columns {} ended while rocking; no overturning within the duration",
            rocking.join(", ")
        ),
    }
}
