//! The `flexrock fem --pushover` command: static pushover curves of the model's body on its
//! mesh, for both ways the base can meet the floor (flexible and rigid plate), against the
//! SDOF model's restoring force F(q) (book/src/model.md §3, restoring force).

use std::fmt::Write as _;
use std::path::{Path, PathBuf};
use std::time::Instant;

use serde::Serialize;

use super::run::ELEMENT;
use super::{pushover, BaseSupport, FemBody, Pushover};
use crate::automaton::Automaton;
use crate::error::Result;
use crate::model::{FemSetup, Model, ModelFile};
use crate::output::{self, number, Table};
use crate::plot::{self, Legend, Panel, Series};
use crate::run::VERSION;

/// Column names of pushover.csv (a contract).
pub const PUSHOVER_COLUMNS: [&str; 12] = [
    "base",
    "q",
    "base_shear",
    "load_factor",
    "flexural",
    "rocking",
    "shearing",
    "contact_nodes",
    "heel_lifted",
    "uplift",
    "approximate_contact",
    "sdof_force",
];

/// The sweep prescribes q = k B / SWEEP_POINTS, k = 1..=SWEEP_POINTS.
pub const SWEEP_POINTS: usize = 400;

/// The two bases, in the order of the files.
const BASES: [BaseSupport; 2] = [BaseSupport::Flexible, BaseSupport::RigidPlate];

/// What one curve shows.
#[derive(Debug, Clone, Serialize)]
pub struct CurveSummary {
    /// The base support of the curve.
    pub base: BaseSupport,
    /// Secant stiffness at the first point, N/m.
    pub initial_stiffness: f64,
    /// The same over the SDOF model's Ke.
    pub initial_stiffness_over_ke: f64,
    /// First swept q at which a corner of the base is off the floor, m.
    pub heel_lift_q: Option<f64>,
    /// First swept q at which the body stands on one corner, m.
    pub uplift_q: Option<f64>,
    /// Largest base shear of the curve, N.
    pub peak_base_shear: f64,
    /// The q of that largest base shear, m.
    pub peak_q: f64,
    /// Where the sweep ended because the body turned freely about a corner, m.
    pub free_rotation_at: Option<f64>,
}

/// The curves and their summaries.
pub struct PushoverAnalysis {
    /// The validated finite element analysis.
    pub setup: FemSetup,
    /// The curve of each base support, in the order of the files.
    pub curves: Vec<(BaseSupport, Pushover)>,
    /// What each curve shows, in the same order.
    pub summaries: Vec<CurveSummary>,
    /// SDOF Ke (N/m), s_n (m) and width B (m).
    pub generalised_stiffness: f64,
    /// s_n of the SDOF model, m.
    pub uplift_displacement: f64,
    /// B, m.
    pub width: f64,
    /// Wall-clock time of both sweeps, s.
    pub wall_time_s: f64,
}

/// Sweeps q from B/SWEEP_POINTS to B for the flexible base and the rigid plate.
pub fn analyse(model: &Model, setup: &FemSetup) -> Result<PushoverAnalysis> {
    let started = Instant::now();
    let s = &setup.settings;
    let width = setup.body.width;
    let qs: Vec<f64> = (1..=SWEEP_POINTS)
        .map(|k| width * k as f64 / SWEEP_POINTS as f64)
        .collect();
    let ke = model.constants.generalised_stiffness;
    let mut curves = Vec::new();
    let mut summaries = Vec::new();
    for base in BASES {
        let body = FemBody {
            base,
            ..setup.body.clone()
        };
        let curve = pushover(&body, s.nx, s.ny, s.p_delta, &qs)?;
        summaries.push(summarise(base, &curve, ke));
        curves.push((base, curve));
    }
    Ok(PushoverAnalysis {
        setup: setup.clone(),
        curves,
        summaries,
        generalised_stiffness: ke,
        uplift_displacement: model.constants.uplift_displacement,
        width,
        wall_time_s: started.elapsed().as_secs_f64(),
    })
}

fn summarise(base: BaseSupport, curve: &Pushover, ke: f64) -> CurveSummary {
    let first = curve.points.first();
    let initial_stiffness = first.map_or(f64::NAN, |p| p.base_shear / p.q);
    let peak = curve
        .points
        .iter()
        .max_by(|a, b| a.base_shear.total_cmp(&b.base_shear));
    CurveSummary {
        base,
        initial_stiffness,
        initial_stiffness_over_ke: initial_stiffness / ke,
        heel_lift_q: curve.points.iter().find(|p| p.heel_lifted).map(|p| p.q),
        uplift_q: curve.points.iter().find(|p| p.uplift).map(|p| p.q),
        peak_base_shear: peak.map_or(f64::NAN, |p| p.base_shear),
        peak_q: peak.map_or(f64::NAN, |p| p.q),
        free_rotation_at: curve.free_rotation_at,
    }
}

/// F(q) of the SDOF model on the branch q belongs to (q >= 0).
fn sdof_force(automaton: &Automaton, q: f64) -> f64 {
    automaton.restoring_force(automaton.initial_mode(q), q)
}

pub(crate) fn curves_csv(model: &Model, a: &PushoverAnalysis) -> Vec<u8> {
    let automaton = Automaton::new(&model.constants);
    let mut table = Table::new(&PUSHOVER_COLUMNS);
    for (base, curve) in &a.curves {
        for p in &curve.points {
            table.row([
                base.name().to_string(),
                number(p.q),
                number(p.base_shear),
                number(p.load_factor),
                number(p.flexural),
                number(p.rocking),
                number(p.shearing),
                p.contact_nodes.to_string(),
                p.heel_lifted.to_string(),
                p.uplift.to_string(),
                p.approximate_contact.to_string(),
                number(sdof_force(&automaton, p.q)),
            ]);
        }
    }
    table.into_bytes()
}

/// pushover.json: how the curves were made and what they show.
#[derive(Serialize)]
pub(crate) struct PushoverSummary<'a> {
    /// Which flexrock wrote the file, from which model file.
    #[serde(flatten)]
    pub provenance: crate::run::Provenance,
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
        provenance: crate::run::Provenance::of(model),
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
    // the curves start low: small q with a large shear is empty in every case
    panel.legend = Legend::UpperLeft;
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

/// Runs both sweeps and writes pushover.csv, pushover.json and pushover.svg (all or none); with
/// [`output::WallTimes::Apart`] the wall time goes to timings.json.
pub fn run(
    model: &Model,
    setup: &FemSetup,
    out_dir: &Path,
    wall_times: output::WallTimes,
) -> Result<PushoverReport> {
    let mut analysis = analyse(model, setup)?;
    let mut timings = output::Timings::new(wall_times);
    timings.take("pushover.json/wall_time_s", &mut analysis.wall_time_s);
    let svg = plot::figure("pushover.svg", &[figure(model, &analysis)], 1, (900, 550))?;
    let mut files = vec![
        ("pushover.csv", curves_csv(model, &analysis)),
        (
            "pushover.json",
            output::json_bytes(&summary(model, &analysis)),
        ),
        ("pushover.svg", svg.into_bytes()),
    ];
    files.extend(timings.file());
    let files = output::write_atomically(out_dir, &files)?;
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
