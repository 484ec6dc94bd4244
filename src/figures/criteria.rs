//! The figures of `flexrock criteria`: the (peak velocity, peak acceleration) plane with each
//! flexibility's critical points and Ishiyama's two lines, and the critical values against the
//! flexibility phi = p T with the fitted criterion and the continuity with the rigid block.

use crate::figures::plot::{Marker, Panel, Series, VerticalLine};
use crate::geometry::Geometry;
use flexrock_core::analysis::criteria::fit::{Fit, Surface};
use flexrock_core::analysis::criteria::{continuity, Point};
use flexrock_core::base::format::shortest;
use flexrock_core::physics::rigid_criteria::{ishiyama_acceleration, ishiyama_velocity};

const SELF_WEIGHTS: [&str; 2] = ["paper", "consistent"];

/// One panel per self-weight variant, for the model file's own slenderness: each body's
/// critical (PGV, PGA) under the one-sine pulses (a line across Tp), the sines and one-cosine
/// pulses (markers), Housner's full-equation block (black), and Ishiyama's lines.
pub fn plane(points: &[Point], g: Geometry) -> Vec<Panel> {
    let a_i = ishiyama_acceleration(g.width, g.height, g.gravity);
    let v_i = ishiyama_velocity(g.width, g.height);
    let own = g.slenderness();
    let points: Vec<Point> = points
        .iter()
        .filter(|p| p.slenderness == own)
        .cloned()
        .collect();
    let points = &points[..];
    let mut moduli: Vec<f64> = points.iter().map(|p| p.youngs_modulus).collect();
    moduli.sort_by(|a, b| b.total_cmp(a));
    moduli.dedup();
    let mut panels = Vec::new();
    for sw in SELF_WEIGHTS {
        let mine: Vec<&Point> = points.iter().filter(|p| p.self_weight == sw).collect();
        if mine.is_empty() {
            continue;
        }
        let mut panel = Panel::new(
            &format!("{sw} self-weight, B/H = {}", shortest(own)),
            "floor peak velocity (m/s)",
            "floor peak acceleration (m/s²)",
        );
        panel.log_x = true;
        panel.log_y = true;
        let rigid: Vec<&Point> = mine
            .iter()
            .copied()
            .filter(|p| p.youngs_modulus == moduli[0])
            .collect();
        // In the order of the pulse period (the points' order), Tp = 0.5 s first.
        let one_sine = |ps: &[&Point], f: &dyn Fn(&Point) -> Option<(f64, f64)>| {
            ps.iter()
                .filter(|p| p.excitation == "one-sine")
                .filter_map(|p| f(p))
                .collect::<Vec<_>>()
        };
        panel = panel.with(
            Series::line(
                "Housner, full eq., one-sine",
                one_sine(&rigid, &|p| {
                    Some((p.pgv_of(p.rigid_full_pga)?, p.rigid_full_pga?))
                }),
                0,
            )
            .with_markers(),
        );
        for (k, e) in moduli.iter().enumerate() {
            let same: Vec<&Point> = mine
                .iter()
                .copied()
                .filter(|p| p.youngs_modulus == *e)
                .collect();
            // A body that could not be run (it buckles) has no flexibility and no points.
            let Some(phi) = same.iter().find_map(|p| p.flexibility) else {
                continue;
            };
            let color = k + 1;
            panel = panel.with(
                Series::line(
                    &format!("φ = {phi:.3} (E = {e:.1e} Pa), one-sine pulses"),
                    one_sine(&same, &|p| Some((p.critical_pgv()?, p.critical_pga?))),
                    color,
                )
                .with_markers(),
            );
            let others: Vec<(f64, f64)> = same
                .iter()
                .filter(|p| p.excitation != "one-sine")
                .filter_map(|p| Some((p.critical_pgv()?, p.critical_pga?)))
                .collect();
            let name = if k == 0 {
                "other pulses and sines (×, in the colour of φ)"
            } else {
                ""
            };
            panel = panel.with(Series::markers(name, others, color, Marker::Cross));
        }
        panel
            .reference_lines
            .push((a_i, "Ishiyama: A = g B/H".into()));
        panel.vertical_lines.push(VerticalLine {
            x: v_i,
            color: 0,
            label: "Ishiyama: V = c B/√H".into(),
        });
        // The corner of Ishiyama's region, which also keeps both lines within the axes.
        panel = panel.with(Series::markers(
            "Ishiyama: both thresholds",
            vec![(v_i, a_i)],
            0,
            Marker::TriangleDown,
        ));
        panels.push(panel);
    }
    panels
}

/// Three panels: the smallest critical PGA over g B/H and the smallest critical PGV over
/// c B/sqrt(H) against phi, with the fits (a line per slenderness, over its range of phi) and
/// the held-out records, a colour per slenderness, the paper's self-weight solid and the
/// consistent one dashed; and the largest relative difference from the rigid blocks against phi.
pub fn against_flexibility(points: &[Point], fits: &[Fit], g: Geometry) -> Vec<Panel> {
    let mut acc = Panel::new("", "flexibility φ = p T", "smallest critical PGA / (g B/H)");
    let mut vel = Panel::new(
        "",
        "flexibility φ = p T",
        "smallest critical PGV / (c B/√H)",
    );
    for panel in [&mut acc, &mut vel] {
        panel.log_x = true;
        panel.reference_lines.push((1.0, "Ishiyama (rigid)".into()));
    }
    for (k, f) in fits.iter().enumerate() {
        let marker = if k == 0 {
            Marker::Circle
        } else {
            Marker::TriangleDown
        };
        for (j, v) in f.validity.iter().enumerate() {
            let (s, color) = (v.slenderness, j + 1);
            let smooth = |q: &Surface| -> Vec<(f64, f64)> {
                let (lo, hi) = v.flexibility_range;
                (0..=60)
                    .map(|i| {
                        let phi = lo * (hi / lo).powf(i as f64 / 60.0);
                        (phi, q.at(phi, s))
                    })
                    .collect()
            };
            // The computed points of one condition and its fitted curve at this slenderness.
            let with_fit = |panel: Panel, q: &Surface| {
                let pts = q
                    .errors
                    .iter()
                    .filter(|e| e.slenderness == s)
                    .map(|e| (e.flexibility, e.value))
                    .collect();
                let mut line = Series::line("", smooth(q), color);
                if k > 0 {
                    line = line.dashed();
                }
                panel
                    .with(Series::markers(
                        &format!("{}, B/H = {}", f.self_weight, shortest(s)),
                        pts,
                        color,
                        marker,
                    ))
                    .with(line)
            };
            if let Some(q) = &f.acceleration {
                acc = with_fit(acc, q);
            }
            if let Some(q) = &f.velocity {
                vel = with_fit(vel, q);
            }
            let held: Vec<&Point> = points
                .iter()
                .filter(|p| p.self_weight == f.self_weight && p.slenderness == s)
                .filter(|p| f.checks.iter().any(|c| c.excitation == p.excitation))
                .collect();
            let a_pts = held
                .iter()
                .filter_map(|p| {
                    let a_i = ishiyama_acceleration(p.width, p.height, g.gravity);
                    Some((p.flexibility?, p.critical_pga? / a_i))
                })
                .collect();
            let v_pts = held
                .iter()
                .filter_map(|p| {
                    let v_i = ishiyama_velocity(p.width, p.height);
                    Some((p.flexibility?, p.critical_pgv()? / v_i))
                })
                .collect();
            // Held-out records: one legend entry per slenderness.
            let label = if k == 0 {
                format!("held-out records, B/H = {}", shortest(s))
            } else {
                String::new()
            };
            acc = acc.with(Series::markers(&label, a_pts, color, Marker::Cross));
            vel = vel.with(Series::markers(&label, v_pts, color, Marker::Cross));
        }
    }
    let own = g.slenderness();
    let decades = continuity::decades(points);
    let mut cont = Panel::new(
        &format!("B/H = {}", shortest(own)),
        "flexibility φ = p T",
        "largest |critical / rigid − 1|",
    );
    cont.log_x = true;
    cont.log_y = true;
    for (k, sw) in SELF_WEIGHTS.iter().enumerate() {
        let mine: Vec<&continuity::Decade> = decades
            .iter()
            .filter(|d| d.self_weight == *sw && d.slenderness == own && d.excitations == "smooth")
            .collect();
        let limit = mine
            .iter()
            .filter_map(|d| Some((d.flexibility?, d.max_abs_difference_rigid_limit?)))
            .collect();
        let full = mine
            .iter()
            .filter_map(|d| Some((d.flexibility?, d.max_abs_difference_rigid_full?)))
            .collect();
        cont = cont
            .with(Series::line(&format!("vs rigid limit, {sw}"), limit, 2 * k + 1).with_markers())
            .with(
                Series::line(&format!("vs Housner (full), {sw}"), full, 2 * k + 2)
                    .with_markers()
                    .dashed(),
            );
    }
    cont.reference_lines.push((0.05, "5 %".into()));
    vec![acc, vel, cont]
}
