//! The `flexrock fem --pushover` command: static pushover curves of the model's body on its
//! mesh, for both ways the base can meet the floor (flexible and rigid plate), against the
//! SDOF model's restoring force F(q) (book/src/model.md §3, restoring force). The curves and
//! their summaries are [`flexrock_core::analysis::pushover_check`] (re-exported here); this module writes
//! pushover.csv, pushover.json and pushover.svg and prints the summary.

use std::fmt::Write as _;
use std::path::{Path, PathBuf};

use serde::Serialize;

use crate::commands::fem::ELEMENT;
use crate::commands::run::VERSION;
use crate::error::Result;
use crate::figures::page::{FigureOptions, PAGE_MM};
use crate::figures::plot::{self, Figure, Panel, Series};
use crate::writers::{self, Table};
use flexrock_core::analysis::pushover_check;
use flexrock_core::bodies::fem::FemBody;
use flexrock_core::model::{FemSetup, Model, ModelFile};
use flexrock_core::physics::automaton::Automaton;
use flexrock_core::tables::fields;

pub use flexrock_core::analysis::pushover_check::{
    analyse, rows, sdof_force, summarise, CurveSummary, PushoverAnalysis, PushoverRow, BASES,
    SWEEP_POINTS,
};

/// Column names of pushover.csv (a contract): the names of
/// [`flexrock_core::analysis::pushover_check::PUSHOVER_COLUMNS`].
pub const PUSHOVER_COLUMNS: [&str; 12] = fields::names(&pushover_check::PUSHOVER_COLUMNS);

pub(crate) fn curves_csv(model: &Model, a: &PushoverAnalysis) -> Vec<u8> {
    let mut table = Table::new(&PUSHOVER_COLUMNS);
    for row in rows(model, a) {
        table.row(fields::fields(&pushover_check::PUSHOVER_COLUMNS, &row));
    }
    table.into_bytes()
}

/// pushover.json: how the curves were made and what they show.
#[derive(Serialize)]
pub(crate) struct PushoverSummary<'a> {
    /// Which flexrock wrote the file, from which model file.
    #[serde(flatten)]
    pub provenance: crate::commands::run::Provenance,
    pub element: &'static str,
    pub body: &'a FemBody,
    pub nx: usize,
    pub ny: usize,
    pub p_delta: bool,
    pub load_pattern: &'static str,
    pub points: usize,
    #[serde(rename = "sdof_Ke")]
    pub sdof_ke: f64,
    pub sdof_s_n: f64,
    pub curves: &'a [CurveSummary],
    pub wall_time_s: f64,
    pub inputs: &'a ModelFile,
}

pub(crate) fn summary<'a>(model: &'a Model, a: &'a PushoverAnalysis) -> PushoverSummary<'a> {
    PushoverSummary {
        provenance: crate::commands::run::Provenance::of(model),
        element: ELEMENT,
        body: &a.setup.body,
        nx: a.setup.settings.nx,
        ny: a.setup.settings.ny,
        p_delta: a.setup.settings.p_delta,
        load_pattern: "lateral loads m U(y) (U the cantilever's first mode, U(H) = 1) from the \
                       gravity state, q = mean ux of the top nodes prescribed",
        points: SWEEP_POINTS,
        sdof_ke: a.generalised_stiffness,
        sdof_s_n: a.uplift_displacement,
        curves: &a.summaries,
        wall_time_s: a.wall_time_s,
        inputs: &model.file,
    }
}

pub(crate) fn figure(model: &Model, a: &PushoverAnalysis) -> Panel {
    let automaton = Automaton::new(&model.constants);
    let mut panel = Panel::new(
        &format!(
            "Static pushover, {} × {} mesh, P-Δ {}",
            a.setup.settings.nx,
            a.setup.settings.ny,
            if a.setup.settings.p_delta {
                "on"
            } else {
                "off"
            }
        ),
        "q (m)",
        "base shear V_b (N)",
    );
    // the kink at s_n is a point of the curve
    let mut sdof: Vec<(f64, f64)> = (0..=SWEEP_POINTS)
        .map(|k| a.width * k as f64 / SWEEP_POINTS as f64)
        .chain([a.uplift_displacement])
        .map(|q| (q, sdof_force(&automaton, q)))
        .collect();
    sdof.sort_by(|x, y| x.0.total_cmp(&y.0));
    panel = panel.with(Series::line("SDOF model F(q)", sdof, 0));
    for (k, (base, curve)) in a.curves.iter().enumerate() {
        let points = std::iter::once((0.0, 0.0))
            .chain(curve.points.iter().map(|p| (p.q, p.base_shear)))
            .collect();
        panel = panel.with(Series::line(
            &format!("FEM, {} base", base.name()),
            points,
            k + 1,
        ));
    }
    panel
}

/// Result of `flexrock fem --pushover`.
pub struct PushoverReport {
    /// The curves and their summaries.
    pub analysis: PushoverAnalysis,
    /// The files written.
    pub files: Vec<PathBuf>,
}

/// Runs both sweeps and writes pushover.csv, pushover.json and the figure pushover in the
/// formats and size of `options` (all or none); with
/// [`writers::WallTimes::Apart`] the wall time goes to timings.json.
pub fn run(
    model: &Model,
    setup: &FemSetup,
    out_dir: &Path,
    wall_times: writers::WallTimes,
    options: &FigureOptions,
) -> Result<PushoverReport> {
    let mut analysis = analyse(model, setup)?;
    let mut timings = writers::Timings::new(wall_times);
    timings.take("pushover.json/wall_time_s", &mut analysis.wall_time_s);
    let figure_files = plot::files(
        "pushover",
        &Figure::new(vec![figure(model, &analysis)], 1).aspect(1.8, 40.0),
        options,
        PAGE_MM,
    )?;
    let mut pushover_summary = summary(model, &analysis);
    timings.take_commit("pushover.json", &mut pushover_summary.provenance);
    let mut files = vec![
        ("pushover.csv", curves_csv(model, &analysis)),
        ("pushover.json", writers::json_bytes(&pushover_summary)),
    ];
    files.extend(timings.file());
    let mut files: Vec<(String, Vec<u8>)> = (files.into_iter())
        .map(|(name, bytes)| (name.to_string(), bytes))
        .collect();
    files.extend(figure_files);
    let files = writers::write_named_atomically(out_dir, files)?;
    Ok(PushoverReport { analysis, files })
}

/// The text `flexrock fem --pushover` prints: each curve's summary and the files written.
pub fn report_text(report: &PushoverReport) -> String {
    let a = &report.analysis;
    let s = &a.setup.settings;
    let mut t = String::new();
    let _ = writeln!(
        t,
        "flexrock {VERSION} fem --pushover: {} x {} QM6 mesh, lateral loads m U(y), P-Delta {}, \
         {SWEEP_POINTS} steps of q to B = {} m",
        s.nx,
        s.ny,
        if s.p_delta { "on" } else { "off" },
        a.width
    );
    let _ = writeln!(
        t,
        "  SDOF model: Ke = {:.1} N/m, s_n = {:.5} m, F(s_n) = {:.1} N",
        a.generalised_stiffness,
        a.uplift_displacement,
        a.generalised_stiffness * a.uplift_displacement
    );
    let _ = writeln!(
        t,
        "  {:<12} {:>8} {:>14} {:>14} {:>16} {:>12}",
        "base", "k0/Ke", "heel lifts q", "on one toe q", "peak shear (N)", "at q (m)"
    );
    let show = |q: Option<f64>| q.map_or_else(|| "-".to_string(), |q| format!("{q:.4}"));
    for c in &a.summaries {
        let _ = writeln!(
            t,
            "  {:<12} {:>8.4} {:>14} {:>14} {:>16.1} {:>12.4}",
            c.base.name(),
            c.initial_stiffness_over_ke,
            show(c.heel_lift_q),
            show(c.uplift_q),
            c.peak_base_shear,
            c.peak_q
        );
        if let Some(q) = c.free_rotation_at {
            let _ = writeln!(
                t,
                "  {}: the body turned freely about its toe from q = {q:.4} m on (no stiffness \
                 left without P-Delta); the curve ends there",
                c.base.name()
            );
        }
    }
    for f in &report.files {
        let _ = writeln!(t, "  wrote {}", f.display());
    }
    t
}
