//! The elastic body against the rigid block as E grows: the largest relative difference of the
//! critical peak acceleration over all excitations, per Young's modulus (one a decade), and the
//! flexibility below which Housner's criteria hold within a share.

use serde::Serialize;

use super::point::Point;

/// One Young's modulus of one self-weight variant and slenderness: the largest |critical /
/// rigid - 1| over the excitations where both overturned.
#[derive(Debug, Clone, Serialize)]
pub struct Decade {
    /// `body.self_weight`.
    pub self_weight: String,
    /// B/H.
    pub slenderness: f64,
    /// Which excitations: "smooth" ([`Point::is_smooth`]) or "all".
    pub excitations: &'static str,
    /// E, Pa.
    pub youngs_modulus: f64,
    /// phi = p T; None for a body that could not be run.
    pub flexibility: Option<f64>,
    /// Against the elastic model's own rigid limit (small-angle, uplift at 1.1226 g B/H).
    pub max_abs_difference_rigid_limit: Option<f64>,
    /// Against Housner's block, full equation.
    pub max_abs_difference_rigid_full: Option<f64>,
    /// Points compared.
    pub points: usize,
}

fn max_abs(values: impl Iterator<Item = Option<f64>>) -> Option<f64> {
    values.flatten().map(f64::abs).reduce(f64::max)
}

/// The decades over the smooth excitations ([`Point::is_smooth`]) and over all, stiffest first
/// within each self-weight variant and slenderness.
pub fn decades(points: &[Point]) -> Vec<Decade> {
    let smooth: Vec<Point> = points.iter().filter(|p| p.is_smooth()).cloned().collect();
    let mut out = decades_of(&smooth, "smooth");
    out.extend(decades_of(points, "all"));
    out
}

fn decades_of(points: &[Point], excitations: &'static str) -> Vec<Decade> {
    let mut out: Vec<Decade> = Vec::new();
    let body = |p: &Point, q: &Point| {
        q.self_weight == p.self_weight
            && q.slenderness == p.slenderness
            && q.youngs_modulus == p.youngs_modulus
    };
    for p in points {
        if out.iter().any(|d| {
            d.self_weight == p.self_weight
                && d.slenderness == p.slenderness
                && d.youngs_modulus == p.youngs_modulus
        }) {
            continue;
        }
        let same: Vec<&Point> = points.iter().filter(|q| body(p, q)).collect();
        out.push(Decade {
            self_weight: p.self_weight.clone(),
            slenderness: p.slenderness,
            excitations,
            youngs_modulus: p.youngs_modulus,
            flexibility: same.iter().find_map(|q| q.flexibility),
            max_abs_difference_rigid_limit: max_abs(
                same.iter()
                    .map(|q| q.relative_difference(q.rigid_limit_pga)),
            ),
            max_abs_difference_rigid_full: max_abs(
                same.iter().map(|q| q.relative_difference(q.rigid_full_pga)),
            ),
            points: same.len(),
        });
    }
    // The stiffest first (the smallest flexibility), bodies that could not be run last.
    out.sort_by(|a, b| {
        (a.self_weight.cmp(&b.self_weight))
            .then(a.slenderness.total_cmp(&b.slenderness))
            .then(b.youngs_modulus.total_cmp(&a.youngs_modulus))
    });
    out
}

/// The largest flexibility of `self_weight` at `slenderness` up to which (from the stiffest
/// body on) every smooth excitation's critical peak acceleration is within `share` of the rigid
/// block's (Housner's full-equation block with `housner`, else the model's rigid limit); None
/// when not even the stiffest body is.
pub fn rigid_holds_below(
    decades: &[Decade],
    self_weight: &str,
    slenderness: f64,
    share: f64,
    housner: bool,
) -> Option<f64> {
    let mut last = None;
    for d in decades.iter().filter(|d| {
        d.self_weight == self_weight && d.slenderness == slenderness && d.excitations == "smooth"
    }) {
        let diff = if housner {
            d.max_abs_difference_rigid_full
        } else {
            d.max_abs_difference_rigid_limit
        };
        match diff {
            Some(x) if x <= share => last = d.flexibility,
            _ => break,
        }
    }
    last
}

/// A point where the elastic body overturns below Housner's full-equation block (by more than
/// `margin` of it), or where only the elastic body overturns within the searched interval.
pub fn unconservative(points: &[Point], margin: f64) -> Vec<&Point> {
    points
        .iter()
        .filter(|p| match (p.critical_pga, p.rigid_full_pga) {
            (Some(a), Some(r)) => a < r * (1.0 - margin),
            (Some(_), None) => p.reason.is_empty(),
            _ => false,
        })
        .collect()
}
