//! `flexrock criteria`: the overturning criteria study of [`flexrock_core::analysis::criteria`] on the
//! body of a model file, written as criteria.csv, continuity.csv, fit.json, criteria.json and
//! two figures (SVG and PNG); the wall time and the commit flexrock was built from go to
//! timings.json, so that every other file is byte-stable.

use std::fmt::Write as _;
use std::path::{Path, PathBuf};

use serde::Serialize;

use crate::commands::run::VERSION;
use crate::error::Result;
use crate::figures::criteria as figures;
use crate::writers::{self, Table};
use flexrock_core::analysis::criteria::{self, continuity, fit, Point, Study};
use flexrock_core::base::format::shortest;
use flexrock_core::physics::rigid_criteria::{
    ishiyama_acceleration, ishiyama_velocity, ISHIYAMA_VELOCITY_COEFFICIENT,
};
use flexrock_core::simulate::{COMMIT, DIRTY};

/// Column names of criteria.csv (a contract), units in the names.
pub const CRITERIA_COLUMNS: [&str; 25] = [
    "self_weight",
    "B_over_H",
    "excitation",
    "Tp_s",
    "E_Pa",
    "phi_pT",
    "T_s",
    "p_rad_per_s",
    "critical_pga_m_per_s2",
    "critical_pgv_m_per_s",
    "critical_pga_over_gB_H",
    "safe_below_pga_m_per_s2",
    "overturning_bands_searched_key",
    "n_bands",
    "rigid_full_pga_m_per_s2",
    "rigid_full_pgv_m_per_s",
    "rigid_small_angle_pga_m_per_s2",
    "rigid_small_angle_pgv_m_per_s",
    "rigid_limit_pga_m_per_s2",
    "rel_diff_vs_rigid_full",
    "rel_diff_vs_rigid_limit",
    "below_rigid_full",
    "ishiyama_pga_m_per_s2",
    "ishiyama_pgv_m_per_s",
    "reason",
];

/// Column names of continuity.csv.
pub const CONTINUITY_COLUMNS: [&str; 8] = [
    "self_weight",
    "B_over_H",
    "excitations",
    "E_Pa",
    "phi_pT",
    "max_abs_rel_diff_vs_rigid_limit",
    "max_abs_rel_diff_vs_rigid_full",
    "points",
];

use crate::figures::page::{FigureOptions, Format, PAGE_MM};
pub use crate::geometry::Geometry;

/// The formats the study's figures are written in unless asked otherwise.
pub const FIGURE_FORMATS: [Format; 2] = [Format::Svg, Format::Png];

fn opt(x: Option<f64>) -> String {
    x.map(shortest).unwrap_or_default()
}

fn criteria_csv(points: &[Point], g: Geometry) -> Vec<u8> {
    let mut table = Table::new(&CRITERIA_COLUMNS);
    for p in points {
        let a_i = ishiyama_acceleration(p.width, p.height, g.gravity);
        let v_i = ishiyama_velocity(p.width, p.height);
        table.row([
            p.self_weight.clone(),
            shortest(p.slenderness),
            p.excitation.clone(),
            opt(p.period),
            shortest(p.youngs_modulus),
            opt(p.flexibility),
            opt(p.pre_uplift_period),
            opt(p.p),
            opt(p.critical_pga),
            opt(p.critical_pgv()),
            opt(p.critical_pga.map(|a| a / a_i)),
            opt(p.safe_below_pga),
            p.bands.clone(),
            p.n_bands.to_string(),
            opt(p.rigid_full_pga),
            opt(p.pgv_of(p.rigid_full_pga)),
            opt(p.rigid_small_angle_pga),
            opt(p.pgv_of(p.rigid_small_angle_pga)),
            opt(p.rigid_limit_pga),
            opt(p.relative_difference(p.rigid_full_pga)),
            opt(p.relative_difference(p.rigid_limit_pga)),
            match (p.critical_pga, p.rigid_full_pga) {
                (Some(a), Some(r)) => (a < r).to_string(),
                (Some(_), None) => "true".into(),
                _ => String::new(),
            },
            shortest(a_i),
            shortest(v_i),
            p.reason.clone(),
        ]);
    }
    table.into_bytes()
}

fn continuity_csv(decades: &[continuity::Decade]) -> Vec<u8> {
    let mut table = Table::new(&CONTINUITY_COLUMNS);
    for d in decades {
        table.row([
            d.self_weight.clone(),
            shortest(d.slenderness),
            d.excitations.to_string(),
            shortest(d.youngs_modulus),
            opt(d.flexibility),
            opt(d.max_abs_difference_rigid_limit),
            opt(d.max_abs_difference_rigid_full),
            d.points.to_string(),
        ]);
    }
    table.into_bytes()
}

/// criteria.json: how the study was made, and its findings.
#[derive(Serialize)]
struct Summary<'a> {
    flexrock_version: &'a str,
    model_file: String,
    geometry: Geometry,
    flexibility_parameter: &'static str,
    solver: &'static str,
    search: String,
    rigid_blocks: &'static str,
    ishiyama: IshiyamaLines,
    study: &'a Study,
    held_out: &'a [String],
    rigid_limit_within_5_percent_up_to_phi: Vec<Holds>,
    housner_full_within_5_percent_up_to_phi: Vec<Holds>,
    below_rigid_full: Vec<Unconservative>,
}

/// The flexibility up to which a rigid criterion holds within 5 %, for one self-weight variant
/// and slenderness.
#[derive(Serialize)]
struct Holds {
    self_weight: String,
    slenderness: f64,
    phi: Option<f64>,
}

#[derive(Serialize)]
struct IshiyamaLines {
    reference: &'static str,
    acceleration_m_per_s2: f64,
    velocity_m_per_s: f64,
    velocity_constant_m_half_per_s: f64,
}

#[derive(Serialize)]
struct Unconservative {
    self_weight: String,
    slenderness: f64,
    excitation: String,
    period_s: Option<f64>,
    youngs_modulus_pa: f64,
    phi: Option<f64>,
    critical_pga_m_per_s2: Option<f64>,
    rigid_full_pga_m_per_s2: Option<f64>,
    relative_difference: Option<f64>,
}

/// What `flexrock criteria` computed and wrote.
pub struct CriteriaReport {
    /// The points.
    pub points: Vec<Point>,
    /// The decades.
    pub decades: Vec<continuity::Decade>,
    /// The fits, one per self-weight variant.
    pub fits: Vec<fit::Fit>,
    /// The files written.
    pub files: Vec<PathBuf>,
}

/// Runs the study on the body of `model`, at its own slenderness and at `slendernesses` (B/H,
/// the model's height kept), with the sines and pulses and the records `fitted` (used for the
/// fit) and `held_out` (only checked against it); writes everything into `out` (all files or
/// none), the figures in the formats and size of `figure_options`.
pub fn run(
    model: &Path,
    slendernesses: &[f64],
    fitted: &[PathBuf],
    held_out: &[PathBuf],
    out: &Path,
    figure_options: &FigureOptions,
) -> Result<CriteriaReport> {
    let start = std::time::Instant::now();
    if let Some(bad) = slendernesses
        .iter()
        .find(|s| !criteria::valid_slenderness(**s))
    {
        return Err(crate::error::Error::invalid(
            "--slenderness",
            *bad,
            criteria::SLENDERNESS_RULE,
        ));
    }
    let base = flexrock_core::Model::load(model, &Default::default())?;
    let geometry = Geometry {
        height: base.body.height,
        width: base.body.width,
        gravity: base.body.gravity,
    };
    // Relative record paths are relative to the current directory (as typed).
    let records: Vec<PathBuf> = fitted.iter().chain(held_out).cloned().collect();
    let list = if slendernesses.is_empty() {
        Vec::new()
    } else {
        let mut list = slendernesses.to_vec();
        list.push(geometry.slenderness());
        list
    };
    let study = Study::standard(records, list);
    let points =
        criteria::run(model, &study).map_err(|e| e.renamed("slenderness", "--slenderness"))?;
    let own = geometry.slenderness();
    let mut all_slendernesses: Vec<f64> = points.iter().map(|p| p.slenderness).collect();
    all_slendernesses.sort_by(f64::total_cmp);
    all_slendernesses.dedup();
    let held: Vec<String> = held_out
        .iter()
        .map(|p| criteria::Excitation::Record(p.clone()).name())
        .collect();
    let decades = continuity::decades(&points);
    let fits: Vec<fit::Fit> = study
        .self_weights
        .iter()
        .map(|sw| fit::fit(&points, sw, &held, own, geometry.gravity))
        .collect();
    let holds = |housner: bool| -> Vec<Holds> {
        let mut out = Vec::new();
        for sw in &study.self_weights {
            for s in &all_slendernesses {
                out.push(Holds {
                    self_weight: sw.clone(),
                    slenderness: *s,
                    phi: continuity::rigid_holds_below(&decades, sw, *s, 0.05, housner),
                });
            }
        }
        out
    };
    let summary = Summary {
        flexrock_version: VERSION,
        model_file: model.display().to_string(),
        geometry,
        flexibility_parameter: "phi = p T: the pre-uplift period T over the rocking time scale \
                                1/p, p = sqrt(3 g/(4 R)), R the half-diagonal",
        solver: "exact (the default)",
        search: format!(
            "scan of {} values of the interval, then bisection of the first transition to \
             overturning to {} of the interval; bands above it that leave the body standing are \
             listed (overturning_bands_searched_key)",
            study.scan,
            shortest(study.tol_share)
        ),
        rigid_blocks: "rigid_full: Housner's block by the full equation (uplift at g B/H); \
                       rigid_small_angle: the same block by the small-angle equation; \
                       rigid_limit: the elastic model's own E -> infinity limit (small-angle, \
                       uplift at 1.1226 g B/H)",
        ishiyama: IshiyamaLines {
            reference: "Ishiyama (1982), Earthquake Eng. Struct. Dyn. 10, 635-650: A > g B/H \
                        and V > 10 B/sqrt(H) cm/s (B, H in cm), the velocity constant as \
                        commonly quoted (not confirmed from the paper)",
            acceleration_m_per_s2: ishiyama_acceleration(
                geometry.width,
                geometry.height,
                geometry.gravity,
            ),
            velocity_m_per_s: ishiyama_velocity(geometry.width, geometry.height),
            velocity_constant_m_half_per_s: ISHIYAMA_VELOCITY_COEFFICIENT,
        },
        study: &study,
        held_out: &held,
        rigid_limit_within_5_percent_up_to_phi: holds(false),
        housner_full_within_5_percent_up_to_phi: holds(true),
        below_rigid_full: continuity::unconservative(&points, 0.0)
            .into_iter()
            .map(|p| Unconservative {
                self_weight: p.self_weight.clone(),
                slenderness: p.slenderness,
                excitation: p.excitation.clone(),
                period_s: p.period,
                youngs_modulus_pa: p.youngs_modulus,
                phi: p.flexibility,
                critical_pga_m_per_s2: p.critical_pga,
                rigid_full_pga_m_per_s2: p.rigid_full_pga,
                relative_difference: p.relative_difference(p.rigid_full_pga),
            })
            .collect(),
    };
    let plane = figures::plane(&points, geometry);
    let against = figures::against_flexibility(&points, &fits, geometry);
    let mut files = vec![
        ("criteria.csv", criteria_csv(&points, geometry)),
        ("continuity.csv", continuity_csv(&decades)),
        ("fit.json", writers::json_bytes(&fits)),
        ("criteria.json", writers::json_bytes(&summary)),
    ];
    for (name, panels, aspect) in [
        ("criteria-plane", plane, 1.5),
        ("criteria-flexibility", against, 2.2),
    ] {
        let figure = crate::figures::plot::Figure::new(panels, 1).aspect(aspect, 40.0);
        for (file, bytes) in crate::figures::plot::files(name, &figure, figure_options, PAGE_MM)? {
            files.push((leak(file), bytes));
        }
    }
    // The wall time and the commit flexrock was built from change from run to run while the
    // results do not: they go to timings.json.
    let mut timings = serde_json::json!({ "wall_time_s": start.elapsed().as_secs_f64() });
    timings["flexrock_commit"] = COMMIT.into();
    timings["flexrock_dirty"] = DIRTY.into();
    files.push(("timings.json", writers::json_bytes(&timings)));
    let files = writers::write_atomically(out, &files)?;
    Ok(CriteriaReport {
        points,
        decades,
        fits,
        files,
    })
}

fn leak(s: String) -> &'static str {
    Box::leak(s.into_boxed_str())
}

/// The text `flexrock criteria` prints.
pub fn report_text(report: &CriteriaReport) -> String {
    let mut t = String::new();
    let _ = writeln!(
        t,
        "flexrock {VERSION} criteria: {} searches (exact method)",
        report.points.len()
    );
    let _ = writeln!(
        t,
        "  {:<11} {:>6} {:<7} {:>9} {:>8} {:>22} {:>22}",
        "self_weight",
        "B/H",
        "motions",
        "E (Pa)",
        "phi",
        "max|d| rigid limit",
        "max|d| Housner full"
    );
    for d in &report.decades {
        let _ = writeln!(
            t,
            "  {:<11} {:>6} {:<7} {:>9.2e} {:>8} {:>22} {:>22}",
            d.self_weight,
            shortest(d.slenderness),
            d.excitations,
            d.youngs_modulus,
            d.flexibility.map_or("-".into(), |x| format!("{x:.4}")),
            d.max_abs_difference_rigid_limit
                .map_or("-".into(), |x| format!("{x:.5}")),
            d.max_abs_difference_rigid_full
                .map_or("-".into(), |x| format!("{x:.5}")),
        );
    }
    for f in &report.files {
        let _ = writeln!(t, "  wrote {}", f.display());
    }
    t
}
