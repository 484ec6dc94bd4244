//! The commands behind the binary, as library functions: `props` and `run`.

use std::fmt::Write as _;
use std::path::{Path, PathBuf};

use crate::error::Result;
use crate::writers;
use flexrock_core::floor::FloorMotion;
use flexrock_core::integrate::solution::Solution;
use flexrock_core::model::Model;
use flexrock_core::model::STANDARD_GRAVITY;
use flexrock_core::physics::automaton::EventKind;
use flexrock_core::physics::body::SelfWeight;

pub use flexrock_core::simulate::{
    properties, simulate, simulate_peaks, simulate_with, warnings, Properties, Provenance,
    ENERGY_RESIDUAL_WARNING_SHARE, VERSION,
};

/// The human-readable table of `flexrock props`.
pub fn properties_table(model: &Model) -> String {
    let b = &model.body;
    let c = &model.constants;
    let mut t = String::new();
    let mut row = |name: &str, value: String, unit: &str, note: &str| {
        let line = format!("  {name:<34} {value:>14} {unit:<7} {note}");
        let _ = writeln!(t, "{}", line.trim_end());
    };
    row("height H", fmt(b.height), "m", "");
    row("width B", fmt(b.width), "m", "");
    row("depth D", fmt(b.depth), "m", "");
    row("mass M", fmt(b.mass), "kg", "");
    row(
        "flexural rigidity EI",
        fmt(b.flexural_rigidity),
        "N m^2",
        "",
    );
    row("damping ratio h", fmt(b.damping_ratio), "", "before uplift");
    row("gravity g", fmt(b.gravity), "m/s^2", "");
    row(
        "constant set",
        c.constant_set.name().to_string(),
        "",
        "\"exact\" or the paper's rounded values",
    );
    row(
        "self weight",
        c.self_weight.name().to_string(),
        "",
        "\"paper\" or \"consistent\" (the weight in the bending)",
    );
    row("generalised mass Me", fmt(c.generalised_mass), "kg", "");
    row(
        "generalised stiffness Ke",
        fmt(c.generalised_stiffness),
        "N/m",
        "",
    );
    row(
        "circular frequency omega",
        fmt(c.omega),
        "rad/s",
        "pre-uplift",
    );
    row("period T", fmt(c.period), "s", "pre-uplift");
    row(
        "damping coefficient gamma/E",
        fmt(c.damping_coefficient),
        "s",
        "2 h / omega",
    );
    row(
        "uplift displacement s_n",
        fmt(c.uplift_displacement),
        "m",
        "top displacement at uplift",
    );
    row("beta1", fmt(c.beta1), "", "participation, pre-uplift");
    row("nu2", fmt(c.nu2), "", "effectiveness, rocking");
    row("beta2", fmt(c.beta2), "", "participation, rocking");
    row("zetaU", fmt(c.zeta_uplift), "", "q' -> zetaU q' at uplift");
    row(
        "zetaL",
        fmt(c.zeta_landing),
        "",
        "q' -> q'/zetaL at landing",
    );
    // The body's own model choices, listed where they are not the paper's.
    if c.landing_restitution != 1.0 {
        row(
            "landing restitution e",
            fmt(c.landing_restitution),
            "",
            "q' -> e q'/zetaL at landing",
        );
    }
    if !c.damping_while_rocking {
        row(
            "damping while rocking",
            "false".to_string(),
            "",
            "no damping term while rocking",
        );
    }
    row(
        "rocking stiffness F'",
        fmt(c.rocking_stiffness),
        "N/m",
        "dF/dq while rocking",
    );
    row(
        "rocking flexural slope ds/dq",
        fmt(c.rocking_flexural_slope),
        "",
        "while rocking",
    );
    row(
        "topple displacement",
        fmt(c.topple_displacement),
        "m",
        "|q| where F = 0: overturning",
    );
    row(
        "flexural part there",
        fmt(c.flexural_part_at_topple),
        "m",
        "",
    );
    row(
        "quasi-static uplift acceleration",
        fmt(c.quasi_static_uplift_acceleration),
        "m/s^2",
        "omega^2 s_n / beta1",
    );
    row(
        "gravity parameter M g H^2/EI",
        fmt(c.gravity_parameter),
        "",
        "",
    );
    row(
        "  ratio to 7.837 (buckling)",
        fmt(c.gravity_parameter_ratio),
        "",
        match c.self_weight {
            SelfWeight::Paper => "self-weight left out of bending; the model, §7a",
            SelfWeight::Consistent => "self-weight in the bending",
        },
    );
    t
}

fn fmt(x: f64) -> String {
    if x != 0.0 && (x.abs() >= 1e6 || x.abs() < 1e-3) {
        format!("{x:.6e}")
    } else {
        format!("{x:.6}")
    }
}

pub use flexrock_core::tables::summary::{summary, RunSummary};

/// Result of `flexrock run`.
pub struct RunReport {
    /// The solution.
    pub solution: Solution,
    /// The files written.
    pub files: Vec<PathBuf>,
    /// What a reader of the result must know (also in summary.json).
    pub warnings: Vec<String>,
    /// The run against the exact solution, with `--check`.
    pub check: Option<flexrock_core::analysis::compare::Check>,
}

/// What `flexrock run` writes besides its four files.
#[derive(Debug, Clone)]
pub struct RunOptions {
    /// check.json: the run against the exact solution.
    pub check: bool,
    /// The figures of `flexrock plot`.
    pub plots: bool,
    /// Their formats and size.
    pub figures: crate::figures::page::FigureOptions,
    /// Where the wall time goes.
    pub wall_times: writers::WallTimes,
}

/// Solves a model and writes history.csv, events.csv, episodes.csv and summary.json into
/// `out_dir`; with `options.check` also check.json (the run against the exact solution), and with
/// `options.plots` the figures of [`crate::figures::run`], drawn from the files as they are about
/// to be written. All are written as one atomic set. With [`writers::WallTimes::Apart`] the
/// solve's wall time goes to timings.json, written with them.
pub fn run_to_dir_checked(
    model: &Model,
    out_dir: &Path,
    options: &RunOptions,
) -> Result<RunReport> {
    let (plots, wall_times) = (options.plots, options.wall_times);
    let mut solution = simulate(model)?;
    let check = if options.check {
        Some(flexrock_core::analysis::compare::check(model, &solution)?)
    } else {
        None
    };
    let mut timings = writers::Timings::new(wall_times);
    timings.take(
        "summary.json/statistics/wall_time_s",
        &mut solution.stats.wall_time_s,
    );
    // The small files are written and synced while history.csv is formatted (on every core),
    // then history.csv and the figures; the set is put in place as one.
    let mut run_summary = summary(model, &solution);
    timings.take_commit("summary.json", &mut run_summary.provenance);
    let mut small = vec![
        ("events.csv", writers::events_csv(&solution.events)),
        (
            "episodes.csv",
            writers::episodes_csv(&solution.episodes, model.body.height),
        ),
        ("summary.json", writers::json_bytes(&run_summary)),
    ];
    if let Some(check) = &check {
        small.push(("check.json", writers::json_bytes(check)));
    }
    small.extend(timings.file());
    let mut order = vec![
        "history.csv",
        "events.csv",
        "episodes.csv",
        "summary.json",
        "check.json",
    ];
    let figure_names: Vec<String> = crate::figures::run::FIGURES
        .iter()
        .flat_map(|name| {
            let stem = name.trim_end_matches(".svg");
            (options.figures.formats.iter()).map(move |f| format!("{stem}.{}", f.extension()))
        })
        .collect();
    order.extend(figure_names.iter().map(String::as_str));
    order.push("timings.json");
    let set = writers::FileSet::begin(out_dir, &order)?;
    let history = std::thread::scope(|scope| {
        let staged = std::thread::Builder::new().spawn_scoped(scope, || set.stage_each(&small));
        let history = writers::history_csv(&solution.samples);
        match staged {
            Ok(thread) => thread
                .join()
                .unwrap_or_else(|e| std::panic::resume_unwind(e)),
            // No thread to be had: staged here instead.
            Err(_) => set.stage_each(&small),
        }
        .map(|()| history)
    })?;
    set.stage("history.csv", &[&history])?;
    if plots {
        let data = crate::writers::run_dir::RunData::from_bytes(
            out_dir,
            &history,
            &small[0].1,
            &small[2].1,
        )?;
        let plot_options = crate::figures::run::PlotOptions {
            formats: options.figures.formats.clone(),
            sizes: options.figures.sizes,
            from: None,
            to: None,
        };
        set.stage_each(&crate::figures::run::figures_with(&data, &plot_options)?)?;
    }
    let files = set.commit()?;
    let mut warnings = warnings(model, &solution);
    let rows = solution.samples.len();
    if rows > writers::run_dir::MAX_HISTORY_ROWS {
        warnings.push(format!(
            "history.csv has {rows} rows (the grid's and two per event), more than `flexrock \
             plot` reads ({}); a shorter duration gives fewer",
            writers::run_dir::MAX_HISTORY_ROWS
        ));
    }
    Ok(RunReport {
        solution,
        files,
        warnings,
        check,
    })
}

/// The excitation as understood, in one line: its kind and parameters, and its peak.
fn excitation_text(floor: &dyn FloorMotion) -> String {
    let mut parts = vec![floor.kind().to_string()];
    if let serde_json::Value::Object(map) = floor.parameters() {
        for (key, value) in map {
            match value {
                // The peak is printed below, for every kind.
                serde_json::Value::Number(_) if key == "pga" || key == "t_pga" => {}
                serde_json::Value::Number(n) => parts.push(format!(
                    "{key} = {}{}",
                    n.as_f64().map_or_else(|| n.to_string(), writers::readable),
                    parameter_unit(&key)
                )),
                serde_json::Value::String(text) if key != "kind" => {
                    parts.push(format!("{key} = {text}"))
                }
                _ => {}
            }
        }
    }
    let peak = floor.peak_acceleration();
    parts.push(format!(
        "peak floor acceleration {peak:.6} m/s^2 = {:.6} g",
        peak / STANDARD_GRAVITY
    ));
    parts.join(", ")
}

/// The unit of an excitation's parameter (as [`FloorMotion::parameters`] names it), with its
/// leading space: that of the model file's key of that name; a record's duration, which is no
/// key, in s; none for a count or a factor.
fn parameter_unit(key: &str) -> String {
    match flexrock_core::unit_of_key(&format!("excitation.{key}")) {
        Some(unit) => unit
            .symbol()
            .map_or_else(String::new, |symbol| format!(" {symbol}")),
        None if key == "duration" => " s".to_string(),
        None => String::new(),
    }
}

/// The short human summary printed after a run.
pub fn run_report_text(model: &Model, report: &RunReport) -> String {
    let s = &report.solution;
    let mut t = String::new();
    let _ = writeln!(
        t,
        "flexrock {VERSION}: {} solution over {} s, T = {:.4} s, s_n = {:.6} m",
        s.stats.method,
        // A natural duration (a pulse's end and its tail) to 12 significant digits.
        writers::significant(model.duration, 12),
        model.constants.period,
        model.constants.uplift_displacement
    );
    let _ = writeln!(t, "  excitation: {}", excitation_text(model.floor.as_ref()));
    let _ = writeln!(
        t,
        "  max q = {:.9} m at t = {:.9} s; min q = {:.9} m at t = {:.9} s",
        s.max_q.value, s.max_q.t, s.min_q.value, s.min_q.t
    );
    let _ = writeln!(
        t,
        "  {}, {}, {}",
        writers::count(s.count(EventKind::Uplift), "uplift", "uplifts"),
        writers::count(s.count(EventKind::Landing), "landing", "landings"),
        match s.t_overturn {
            Some(to) => format!("overturned at t = {to:.9} s"),
            None if s.ended_while_rocking() => {
                "ended while rocking; no overturning within the duration".to_string()
            }
            None => "no overturning".to_string(),
        }
    );
    let _ = writeln!(
        t,
        "  {} steps, {} right-hand-side evaluations{}; max energy residual {:.3e} J",
        s.stats.steps,
        s.stats.rhs_evaluations,
        writers::milliseconds(s.stats.wall_time_s, 3)
            .map_or_else(String::new, |t| format!(", {t}")),
        s.max_energy_residual
    );
    if let Some(c) = &report.check {
        let e = &c.comparison.events;
        let _ = writeln!(
            t,
            "  check against the exact solution: {} of {} events matched ({} missed, {} spurious), \
             {}, peak error {:.3e} m, largest error of q on the grid \
             {:.3e} m (the exact solution's own estimate: {:.1e} s)",
            e.n_matched,
            e.n_reference,
            e.n_missed,
            e.n_spurious,
            if e.n_matched == 0 {
                "no event to time".to_string()
            } else {
                format!("largest event-time error {:.3e} s", e.max_abs_time_difference)
            },
            c.comparison.peaks.peak_error,
            c.comparison.grid.max_abs_q_difference,
            c.exact_error_estimate
        );
    }
    for f in &report.files {
        let _ = writeln!(t, "  wrote {}", f.display());
    }
    t
}
