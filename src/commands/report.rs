//! `flexrock report`: assembles validation/REPORT.md from the files that `compare`, `converge`
//! and `run` wrote. It computes nothing new about the dynamics except Housner's closed form for
//! the rigid-limit check and the linear acceleration method's stability limit; every other
//! number is read from those files.
//!
//! The files are read into typed structs (`CompareFile`, `ConvergeFile` with the [`Case`]s
//! and [`Slope`]s that `converge` writes, `RigidRunFile`, CSV rows by column name): a
//! missing key or column is an [`Error::ReadResult`] naming the file and the key, not a "?" or
//! NaN in the report. Where the written summary borrows the model and the solution (compare.json,
//! summary.json), or the committed files predate some of its newer keys, the reader is an owned
//! struct here holding the keys the report uses, under the names the commands write.

use std::fmt::Write as _;
use std::path::{Path, PathBuf};

use serde::de::DeserializeOwned;
use serde::Deserialize;

use crate::commands::converge::{Case, Slope};
use crate::commands::run::VERSION;
use crate::error::{Error, Result};
use crate::writers;
use flexrock_core::integrate::newmark::critical_omega_dt;

/// Where the inputs of the report are.
#[derive(Debug, Clone)]
pub struct ReportInputs {
    /// Output directory of `flexrock compare` with the compensate variant.
    pub compare_compensate: PathBuf,
    /// Output directory of `flexrock compare` with the substep variant.
    pub compare_substep: PathBuf,
    /// Output directory of `flexrock converge`.
    pub converge: PathBuf,
    /// Output directory of `flexrock run` on the rigid-limit free-rocking model.
    pub rigid: PathBuf,
    /// Figures, relative to the report's directory: (file name in figures dir, caption).
    pub figures_dir: String,
    /// The command that regenerates the report (printed in it).
    pub command: String,
}

/// Readers of values written as null (NaN) and of optional values whose key must be there.
pub(crate) use flexrock_core::tables::fields::{nan_if_null, required};

/// A peak of q, as compare.json writes it.
#[derive(Debug, Clone, Deserialize)]
pub(crate) struct PeakRead {
    pub value: f64,
    pub t: f64,
}

/// The solver settings of one solution in compare.json (`[solver]` keys).
#[derive(Debug, Clone, Deserialize)]
pub(crate) struct SolverRead {
    #[serde(default)]
    pub rtol: Option<f64>,
    #[serde(default)]
    pub dt: Option<f64>,
    #[serde(default)]
    pub newmark_beta: Option<f64>,
    #[serde(default)]
    pub newmark_gamma: Option<f64>,
}

/// The cost of one solution.
#[derive(Debug, Clone, Deserialize)]
pub(crate) struct StatisticsRead {
    pub method: String,
    pub steps: usize,
    pub rhs_evaluations: usize,
}

/// One dent of s (findings.dents).
#[derive(Debug, Clone, Deserialize)]
pub(crate) struct DentRead {
    pub mode: String,
    pub t_start: f64,
    pub t_end: f64,
    pub max_abs_r: f64,
    pub min_abs_s: f64,
    pub depth: f64,
}

/// The paper's findings measured on one solution.
#[derive(Debug, Clone, Deserialize)]
pub(crate) struct FindingsRead {
    #[serde(deserialize_with = "nan_if_null")]
    pub max_abs_s_over_s_n: f64,
    pub s_never_exceeds_s_n: bool,
    #[serde(deserialize_with = "nan_if_null")]
    pub max_abs_r_where_abs_q_within_s_n: f64,
    #[serde(deserialize_with = "nan_if_null")]
    pub max_q_r_relation_residual: f64,
    #[serde(deserialize_with = "nan_if_null")]
    pub max_s_r_relation_residual: f64,
    pub rocking_episodes: usize,
    pub episodes_with_dent: usize,
    pub dents: Vec<DentRead>,
}

/// One solution in compare.json.
#[derive(Debug, Clone, Deserialize)]
pub(crate) struct SolutionRead {
    pub method: String,
    pub solver: SolverRead,
    pub n_events: usize,
    pub max_q: PeakRead,
    pub min_q: PeakRead,
    pub statistics: StatisticsRead,
    pub findings: FindingsRead,
}

/// comparison.events of compare.json.
#[derive(Debug, Clone, Deserialize)]
pub(crate) struct EventAgreementRead {
    pub n_reference: usize,
    pub n_matched: usize,
    #[serde(deserialize_with = "nan_if_null")]
    pub max_abs_time_difference: f64,
    #[serde(deserialize_with = "nan_if_null")]
    pub mean_abs_time_difference: f64,
}

/// comparison.peaks of compare.json.
#[derive(Debug, Clone, Deserialize)]
pub(crate) struct PeakDifferencesRead {
    pub max_q_difference: f64,
    pub min_q_difference: f64,
}

/// comparison.grid of compare.json.
#[derive(Debug, Clone, Deserialize)]
pub(crate) struct GridRead {
    pub output_dt: f64,
    #[serde(deserialize_with = "nan_if_null")]
    pub rms_q_difference: f64,
    #[serde(deserialize_with = "nan_if_null")]
    pub max_abs_q_difference: f64,
}

/// comparison of compare.json.
#[derive(Debug, Clone, Deserialize)]
pub(crate) struct ComparisonRead {
    pub events: EventAgreementRead,
    pub peaks: PeakDifferencesRead,
    pub grid: GridRead,
}

/// compare.json, the keys the report uses.
#[derive(Debug, Clone, Deserialize)]
pub(crate) struct CompareFile {
    #[serde(deserialize_with = "required")]
    pub model_file: Option<String>,
    #[serde(rename = "T")]
    pub period: f64,
    pub s_n: f64,
    pub duration: f64,
    pub reference: SolutionRead,
    pub newmark: SolutionRead,
    pub comparison: ComparisonRead,
}

/// convergence.json, the keys the report uses.
#[derive(Debug, Clone, Deserialize)]
pub(crate) struct ConvergeFile {
    pub reference_method: String,
    pub reference_rtol: Option<f64>,
    pub reference_events: usize,
    pub output_dt: f64,
    pub cases: Vec<Case>,
    pub slopes: Vec<Slope>,
}

/// inputs.body of summary.json: the model file's `[body]`.
#[derive(Debug, Clone, Deserialize)]
pub(crate) struct BodyInputsRead {
    pub height: f64,
    pub width: f64,
    /// Absent or null: the default gravity.
    #[serde(default)]
    pub gravity: Option<f64>,
}

/// inputs of summary.json.
#[derive(Debug, Clone, Deserialize)]
pub(crate) struct InputsRead {
    pub body: BodyInputsRead,
}

/// initial_state of summary.json.
#[derive(Debug, Clone, Deserialize)]
pub(crate) struct InitialStateRead {
    pub q: f64,
}

/// constants of summary.json, the restitution pair.
#[derive(Debug, Clone, Deserialize)]
pub(crate) struct ZetasRead {
    pub zeta_uplift: f64,
    pub zeta_landing: f64,
}

/// summary.json of `flexrock run` on the rigid-limit model, the keys the report uses.
#[derive(Debug, Clone, Deserialize)]
pub(crate) struct RigidRunFile {
    pub s_n: f64,
    #[serde(rename = "T")]
    pub period: f64,
    pub solver: SolverRead,
    pub statistics: StatisticsRead,
    pub constants: ZetasRead,
    pub initial_state: InitialStateRead,
    pub inputs: InputsRead,
}

/// A row of compare.csv (the columns the report uses; empty numbers are None).
#[derive(Debug, Clone, Deserialize)]
pub(crate) struct CompareRow {
    pub index: String,
    pub kind: String,
    pub from: String,
    pub to: String,
    #[serde(deserialize_with = "required")]
    pub t_reference: Option<f64>,
    #[serde(deserialize_with = "required")]
    pub t_newmark: Option<f64>,
    #[serde(deserialize_with = "required")]
    pub t_difference: Option<f64>,
}

/// A row of events.csv (the columns the report uses).
#[derive(Debug, Clone, Deserialize)]
pub(crate) struct EventRow {
    pub t: f64,
    pub kind: String,
}

/// Reads a JSON file into `T`; a missing key, a wrong type or an unreadable file is an
/// [`Error::ReadResult`] naming the file (and serde's message names the key).
pub fn read_json<T: DeserializeOwned>(path: &Path) -> Result<T> {
    let fail = |message: String| Error::ReadResult {
        path: path.to_path_buf(),
        message,
    };
    let text = std::fs::read_to_string(path).map_err(|e| fail(e.to_string()))?;
    serde_json::from_str(&text).map_err(|e| fail(e.to_string()))
}

/// Reads a CSV file by column name into rows of `T`; a missing column is an
/// [`Error::ReadResult`] naming the file and the column.
pub fn read_csv<T: DeserializeOwned>(path: &Path) -> Result<Vec<T>> {
    let fail = |message: String| Error::ReadResult {
        path: path.to_path_buf(),
        message,
    };
    let mut reader = csv::Reader::from_path(path).map_err(|e| fail(e.to_string()))?;
    reader
        .deserialize()
        .collect::<std::result::Result<Vec<T>, _>>()
        .map_err(|e| fail(e.to_string()))
}

fn sci(x: f64) -> String {
    if x.is_nan() {
        "-".to_string()
    } else {
        format!("{x:.3e}")
    }
}

/// A number from a CSV field, rounded for the report; empty fields read "-".
fn short(field: Option<f64>, digits: usize) -> String {
    field.map_or("-".to_string(), |v| format!("{v:.digits$}"))
}

/// A solver setting that the solution's kind of solver must have (`dt` for Newmark, `rtol` for
/// the adaptive reference): an error naming the file and the key when it is absent.
fn setting(value: Option<f64>, path: &Path, within: &str, key: &str) -> Result<f64> {
    value.ok_or_else(|| Error::ReadResult {
        path: path.to_path_buf(),
        message: format!("missing field `{key}` in {within}"),
    })
}

/// The method of a run and the setting its accuracy follows: "bdf at rtol = 1e-10",
/// "newmark-compensate at dt = 0.001 s", "exact" (which has no such setting).
fn solved_by(method: &str, solver: &SolverRead) -> String {
    match (solver.rtol, solver.dt) {
        (Some(rtol), _) => format!("{method} at rtol = {rtol:e}"),
        (None, Some(dt)) => format!("{method} at dt = {} s", writers::shortest(dt)),
        (None, None) => method.to_string(),
    }
}

/// Stability limit of the compensate run's Newmark method (its beta, gamma) as a share of the
/// period: sqrt(12)/(2 pi) = 0.551 for linear acceleration; None when unconditionally stable.
fn stability_share(file: &CompareFile, path: &Path) -> Result<Option<f64>> {
    let s = &file.newmark.solver;
    let beta = setting(s.newmark_beta, path, "newmark.solver", "newmark_beta")?;
    let gamma = setting(s.newmark_gamma, path, "newmark.solver", "newmark_gamma")?;
    Ok(critical_omega_dt(beta, gamma).map(|omega_dt| omega_dt / (2.0 * std::f64::consts::PI)))
}

/// Every input of the report, read and checked.
struct Read {
    compensate: CompareFile,
    substep: CompareFile,
    /// The reference's relative tolerance (compensate run); None for the exact solution.
    reference_rtol: Option<f64>,
    /// The Newmark steps of the two compare runs, s.
    compensate_dt: f64,
    substep_dt: f64,
    /// Newmark's stability limit over T (compensate run's beta and gamma).
    stability_share: Option<f64>,
    compensate_pairs: Vec<CompareRow>,
    converge: ConvergeFile,
    rigid: RigidRunFile,
    rigid_events: Vec<EventRow>,
}

fn read_inputs(inputs: &ReportInputs) -> Result<Read> {
    let compensate_json = inputs.compare_compensate.join("compare.json");
    let substep_json = inputs.compare_substep.join("compare.json");
    let compensate: CompareFile = read_json(&compensate_json)?;
    let substep: CompareFile = read_json(&substep_json)?;
    Ok(Read {
        reference_rtol: match compensate.reference.method.as_str() {
            flexrock_core::integrate::exact::NAME => None,
            _ => Some(setting(
                compensate.reference.solver.rtol,
                &compensate_json,
                "reference.solver",
                "rtol",
            )?),
        },
        compensate_dt: setting(
            compensate.newmark.solver.dt,
            &compensate_json,
            "newmark.solver",
            "dt",
        )?,
        substep_dt: setting(
            substep.newmark.solver.dt,
            &substep_json,
            "newmark.solver",
            "dt",
        )?,
        stability_share: stability_share(&compensate, &compensate_json)?,
        compensate,
        substep,
        compensate_pairs: read_csv(&inputs.compare_compensate.join("compare.csv"))?,
        converge: read_json(&inputs.converge.join("convergence.json"))?,
        rigid: read_json(&inputs.rigid.join("summary.json"))?,
        rigid_events: read_csv(&inputs.rigid.join("events.csv"))?,
    })
}

/// The report's text from the files under `inputs`.
pub fn report_text(inputs: &ReportInputs) -> Result<String> {
    let r = read_inputs(inputs)?;
    let fig = |name: &str| format!("{}/{name}", inputs.figures_dir);
    let mut t = String::new();
    write_preamble(&mut t, &inputs.command);
    write_paper_example(&mut t, &r, &fig);
    write_convergence(&mut t, &r.converge, &fig);
    write_rigid_limit(&mut t, &r);
    write_findings(&mut t, &r, &fig);
    Ok(t)
}

/// Writes the report to `out` (a markdown file).
pub fn write_report(inputs: &ReportInputs, out: &Path) -> Result<PathBuf> {
    let t = report_text(inputs)?;
    let dir = out.parent().unwrap_or(Path::new("."));
    let name = out
        .file_name()
        .map(|n| n.to_string_lossy().into_owned())
        .unwrap_or_else(|| "REPORT.md".to_string());
    let mut files = writers::write_atomically(dir, &[(&name, t.into_bytes())])?;
    Ok(files.remove(0))
}

/// Title and provenance.
fn write_preamble(t: &mut String, command: &str) {
    let _ = writeln!(
        t,
        "# Validation report: Newmark against the event-driven reference\n"
    );
    let _ = writeln!(
        t,
        "Generated by flexrock {VERSION} with `{command}`; every number below is read from the files the \
         commands wrote (see validation/README.md). Do not edit by hand.\n",
    );
}

/// Section 1: the paper's example, the reference (the exact solution, or a tight adaptive run)
/// against Newmark with both event treatments, and the compensate run's matched events.
fn write_paper_example(t: &mut String, r: &Read, fig: &dyn Fn(&str) -> String) {
    let (c, s) = (&r.compensate, &r.substep);
    let dt = r.compensate_dt;
    let _ = writeln!(
        t,
        "## 1. The paper's example: {} vs Newmark dt = {dt} s\n",
        match r.reference_rtol {
            None => "the exact solution",
            Some(_) => "adaptive reference",
        }
    );
    let _ = writeln!(
        t,
        "Model: `{}` (T = {:.4} s, s_n = {:.5} m, {} s). Reference: {} ({}). Newmark: \
         linear acceleration (beta = 1/6, gamma = 1/2), dt = {dt} s, the paper's setting; \
         *compensate* is the paper's overshoot compensation, *substep* lands a sub-step on each crossing.\n",
        c.model_file.as_deref().unwrap_or("?"),
        c.period,
        c.s_n,
        c.duration,
        c.reference.method,
        crate::commands::converge::reference_accuracy(r.reference_rtol),
    );
    let _ = writeln!(
        t,
        "| quantity | reference | Newmark compensate | Newmark substep |\n|---|---|---|---|"
    );
    let _ = writeln!(
        t,
        "| events (uplifts + landings) | {} | {} | {} |",
        c.reference.n_events, c.newmark.n_events, s.newmark.n_events
    );
    let (ce, se) = (&c.comparison.events, &s.comparison.events);
    let _ = writeln!(
        t,
        "| events matched (same transition, in order) | - | {} of {} | {} of {} |",
        ce.n_matched, ce.n_reference, se.n_matched, se.n_reference
    );
    let _ = writeln!(
        t,
        "| max / mean abs event-time difference (s) | - | {:.4} / {:.4} | {:.5} / {:.5} |",
        ce.max_abs_time_difference,
        ce.mean_abs_time_difference,
        se.max_abs_time_difference,
        se.mean_abs_time_difference
    );
    let at = |p: &PeakRead| format!("{:.5} m at {:.3} s", p.value, p.t);
    type Peak = fn(&SolutionRead) -> &PeakRead;
    type Difference = fn(&PeakDifferencesRead) -> f64;
    let peaks: [(&str, Peak, Difference); 2] = [
        ("max_q", |x| &x.max_q, |d| d.max_q_difference),
        ("min_q", |x| &x.min_q, |d| d.min_q_difference),
    ];
    for (name, peak, difference) in peaks {
        let _ = writeln!(
            t,
            "| {name} | {} | {} ({:+.5} m) | {} ({:+.5} m) |",
            at(peak(&c.reference)),
            at(peak(&c.newmark)),
            difference(&c.comparison.peaks),
            at(peak(&s.newmark)),
            difference(&s.comparison.peaks),
        );
    }
    let (cg, sg) = (&c.comparison.grid, &s.comparison.grid);
    let _ = writeln!(
        t,
        "| RMS / max abs q difference on the {} s grid (m) | - | {:.5} / {:.5} | {:.5} / {:.5} |",
        cg.output_dt,
        cg.rms_q_difference,
        cg.max_abs_q_difference,
        sg.rms_q_difference,
        sg.max_abs_q_difference
    );
    let stats = |v: &SolutionRead| {
        format!(
            "{} steps, {} rhs evaluations",
            v.statistics.steps, v.statistics.rhs_evaluations
        )
    };
    let _ = writeln!(
        t,
        "| cost | {} | {} | {} |\n",
        stats(&c.reference),
        stats(&c.newmark),
        stats(&s.newmark)
    );
    write_matched_events(t, &r.compensate_pairs, dt);
    let _ = writeln!(
        t,
        "![Fig. 6 panels, compensate]({})\n\n![Fig. 6 panels, substep]({})\n",
        fig("compare-compensate.svg"),
        fig("compare-substep.svg")
    );
}

/// The matched events of the compensate run (compare.csv), with their time differences.
fn write_matched_events(t: &mut String, pairs: &[CompareRow], dt: f64) {
    let _ = writeln!(
        t,
        "Matched events, reference vs Newmark compensate (dt = {dt} s):\n"
    );
    let _ = writeln!(t, "| # | kind | transition | t reference (s) | t Newmark (s) | difference (s) |\n|---|---|---|---|---|---|");
    for p in pairs {
        let _ = writeln!(
            t,
            "| {} | {} | {} -> {} | {} | {} | {} |",
            p.index,
            p.kind,
            p.from,
            p.to,
            short(p.t_reference, 6),
            short(p.t_newmark, 6),
            short(p.t_difference, 6)
        );
    }
    let _ = writeln!(
        t,
        "\nThe compensate variant logs an event at the step end where the crossing is detected, so \
         its event times lie on the {dt} s grid and are late by up to one step plus the drift of \
         the trajectory.\n"
    );
}

/// Section 2: the convergence study, its cases, orders and efficiency slopes.
fn write_convergence(t: &mut String, converge: &ConvergeFile, fig: &dyn Fn(&str) -> String) {
    let _ = writeln!(t, "## 2. Convergence study\n");
    let _ = writeln!(
        t,
        "Reference: {} ({}; {} events). Errors on the common {} s grid; event-time error \
         over matched events; peak error = the larger error of max q and min q. Wall times are left out: they change from \
         run to run (`flexrock converge --timings-apart` writes them to timings.json).\n",
        converge.reference_method,
        crate::commands::converge::reference_accuracy(converge.reference_rtol),
        converge.reference_events,
        converge.output_dt
    );
    let _ = writeln!(t, "| method | dt (s) | rtol | max q error (m) | max event-time error (s) | peak error (m) | event count diff | unmatched | steps | rhs evaluations |\n|---|---|---|---|---|---|---|---|---|---|");
    let opt = |v: Option<f64>| v.map_or("-".to_string(), |v| format!("{v}"));
    for c in &converge.cases {
        if c.status != "ok" {
            let _ = writeln!(
                t,
                "| {} | {} | {} | failed: {} | | | | | | |",
                c.method,
                opt(c.dt),
                opt(c.rtol),
                c.status
            );
            continue;
        }
        let _ = writeln!(
            t,
            "| {} | {} | {} | {} | {} | {} | {} | {} | {} | {} |",
            c.method,
            opt(c.dt),
            opt(c.rtol),
            sci(c.max_q_error),
            sci(c.max_event_time_error),
            sci(c.peak_error),
            c.event_count_difference,
            c.unmatched_events,
            c.steps,
            c.rhs_evaluations
        );
    }
    let _ = writeln!(t, "\nOrders and efficiency slopes (least-squares slope of log error against log dt for Newmark, an order; against log right-hand-side evaluations for the adaptive methods, an efficiency slope, not an order; cases with every event matched):\n");
    let _ = writeln!(
        t,
        "| method | metric | kind | against | slope | points |\n|---|---|---|---|---|---|"
    );
    for o in &converge.slopes {
        let _ = writeln!(
            t,
            "| {} | {} | {} | {} | {:.2} | {} |",
            o.method,
            o.metric,
            o.kind.name(),
            o.against,
            o.slope,
            o.points
        );
    }
    let _ = writeln!(
        t,
        "\n![error against dt]({})\n\n![error against work]({})\n",
        fig("convergence-dt.svg"),
        fig("convergence-work.svg")
    );
}

/// Section 3: the rigid-limit run against Housner's closed form (first landing, restitution),
/// and why Newmark at the paper's dt cannot run that body.
fn write_rigid_limit(t: &mut String, r: &Read) {
    let rigid = &r.rigid;
    let _ = writeln!(t, "## 3. Rigid limit against Housner\n");
    let body = &rigid.inputs.body;
    let (h, b) = (body.height, body.width);
    let g = body
        .gravity
        .unwrap_or(flexrock_core::model::DEFAULT_GRAVITY);
    let q0 = rigid.initial_state.q;
    let p = (3.0 * g / (2.0 * h)).sqrt();
    let housner_landing = (1.0 / (1.0 - q0 / b)).acosh() / p;
    let landing = r
        .rigid_events
        .iter()
        .find(|e| e.kind == "landing")
        .map(|e| e.t);
    let housner_r = (2.0 * h * h - b * b) / (2.0 * (h * h + b * b));
    let _ = writeln!(
        t,
        "Free rocking of the reference body with E x 1e5 (s_n = {:.3e} m), no damping, from \
         q0 = {q0} m (theta0/alpha = {:.3}), {}. Housner: first landing at \
         (1/p) acosh(1/(1 - theta0/alpha)), p = sqrt(3 g/(2 H)).\n",
        rigid.s_n,
        q0 / b,
        solved_by(&rigid.statistics.method, &rigid.solver)
    );
    let _ = writeln!(
        t,
        "| quantity | flexrock | Housner | difference |\n|---|---|---|---|"
    );
    match landing {
        Some(tl) => {
            let _ = writeln!(
                t,
                "| first landing (s) | {tl:.7} | {housner_landing:.7} | {:.2e} |",
                tl - housner_landing
            );
        }
        None => {
            let _ = writeln!(t, "| first landing (s) | none | {housner_landing:.7} | - |");
        }
    }
    let restitution = rigid.constants.zeta_uplift / rigid.constants.zeta_landing;
    let _ = writeln!(
        t,
        "| zetaU / zetaL (restitution of theta') | {restitution:.6} | {housner_r:.6} | {:.2e} |\n",
        restitution - housner_r
    );
    match r.stability_share {
        Some(share) => {
            let _ = writeln!(
                t,
                "Newmark at the paper's dt cannot run this body at all: with E x 1e5 the pre-uplift period is \
                 {:.4} s and linear acceleration needs dt < {share:.3} T; flexrock refuses such a dt.\n",
                rigid.period
            );
        }
        None => {
            let _ = writeln!(
                t,
                "Newmark with the compare runs' beta and gamma is unconditionally stable; the \
                 rigid body's pre-uplift period is {:.4} s.\n",
                rigid.period
            );
        }
    }
}

/// Section 4: the paper's qualitative findings measured on the three solutions, and the
/// reference's dents of s.
fn write_findings(t: &mut String, r: &Read, fig: &dyn Fn(&str) -> String) {
    let _ = writeln!(t, "## 4. The paper's qualitative findings, in numbers\n");
    let _ = writeln!(
        t,
        "Fig. 6: |s| never exceeds s_n, s dents while the body rocks, r = 0 whenever |q| <= s_n. \
         Figs. 12-13: while rocking r = B (|q| - s_n)/(B - s_n) and |s| = s_n (1 - |r|/B). \
         Measured on every history sample (the grid and both sides of every event).\n"
    );
    let _ = writeln!(
        t,
        "| check | reference | Newmark compensate dt = {} | Newmark substep dt = {} |\n|---|---|---|---|",
        r.compensate_dt, r.substep_dt
    );
    let three = [
        &r.compensate.reference.findings,
        &r.compensate.newmark.findings,
        &r.substep.newmark.findings,
    ];
    let row = |t: &mut String, name: &str, cell: &dyn Fn(&FindingsRead) -> String| {
        let _ = writeln!(
            t,
            "| {name} | {} | {} | {} |",
            cell(three[0]),
            cell(three[1]),
            cell(three[2])
        );
    };
    row(t, "max abs s / s_n", &|f| {
        format!("{:.6}", f.max_abs_s_over_s_n)
    });
    row(t, "abs s never exceeds s_n", &|f| {
        f.s_never_exceeds_s_n.to_string()
    });
    row(t, "max abs r where abs q <= s_n (m)", &|f| {
        sci(f.max_abs_r_where_abs_q_within_s_n)
    });
    row(t, "max residual of the q-r relation (m)", &|f| {
        sci(f.max_q_r_relation_residual)
    });
    row(t, "max residual of the s-r relation (m)", &|f| {
        sci(f.max_s_r_relation_residual)
    });
    row(t, "rocking episodes", &|f| f.rocking_episodes.to_string());
    row(t, "episodes with a dent in s", &|f| {
        f.episodes_with_dent.to_string()
    });
    let _ = writeln!(t, "\nDents of s in the reference (depth = s_n - min abs s while rocking = s_n max abs r / B):\n");
    let _ = writeln!(t, "| episode | mode | from (s) | to (s) | max abs r (m) | min abs s (m) | depth (m) |\n|---|---|---|---|---|---|---|");
    for (i, d) in three[0].dents.iter().enumerate() {
        let _ = writeln!(
            t,
            "| {i} | {} | {:.4} | {:.4} | {:.5} | {:.5} | {:.5} |",
            d.mode, d.t_start, d.t_end, d.max_abs_r, d.min_abs_s, d.depth
        );
    }
    let _ = writeln!(
        t,
        "\nIn the compensate variant the mode changes only at the step end after a crossing, so the \
         samples between crossing and detection break the findings: s follows the pre-uplift branch \
         past s_n before uplift is detected, and a rocking sample below s_n (negative r) is booked \
         before landing is detected. The rows above give the size of these violations.\n"
    );
    let _ = writeln!(
        t,
        "![q-r and s-r, compensate]({})\n\n![q-r and s-r, substep]({})",
        fig("relations-compensate.svg"),
        fig("relations-substep.svg")
    );
}
