//! The static pushover check, as an analysis: pushover curves of the model's body on its mesh,
//! for both ways the base can meet the floor (flexible and rigid plate), against the SDOF model's
//! restoring force F(q) (book/src/model.md §3, restoring force). The numerics of one curve are
//! in [`crate::bodies::fem::pushover`].

use std::time::Instant;

use serde::Serialize;

use crate::base::format::number;
use crate::bodies::fem::{pushover, BaseSupport, FemBody, Pushover};
use crate::error::Result;
use crate::model::{FemSetup, Model};
use crate::physics::automaton::Automaton;
use crate::tables::fields::Column;

/// The sweep prescribes q = k B / SWEEP_POINTS, k = 1..=SWEEP_POINTS.
pub const SWEEP_POINTS: usize = 400;

/// The two bases, in the order of the files.
pub const BASES: [BaseSupport; 2] = [BaseSupport::Flexible, BaseSupport::RigidPlate];

/// What one curve shows.
#[derive(Debug, Clone, PartialEq, Serialize)]
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
    /// The curve of each base support, in the order of [`BASES`].
    pub curves: Vec<(BaseSupport, Pushover)>,
    /// What each curve shows, in the same order.
    pub summaries: Vec<CurveSummary>,
    /// Ke of the SDOF model, N/m.
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

/// What the curve of `base` shows, against the SDOF model's stiffness `ke` (N/m).
pub fn summarise(base: BaseSupport, curve: &Pushover, ke: f64) -> CurveSummary {
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
pub fn sdof_force(automaton: &Automaton, q: f64) -> f64 {
    automaton.restoring_force(automaton.initial_mode(q), q)
}

/// One row of pushover.csv: a point of a curve, with the SDOF model's force at its q.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct PushoverRow {
    /// The base support's name.
    pub base: &'static str,
    /// Prescribed top displacement, m.
    pub q: f64,
    /// Base shear, N.
    pub base_shear: f64,
    /// Load factor of the lateral pattern.
    pub load_factor: f64,
    /// Flexural part, m.
    pub flexural: f64,
    /// Rocking part, m.
    pub rocking: f64,
    /// Shearing part, m.
    pub shearing: f64,
    /// Base nodes on the floor.
    pub contact_nodes: usize,
    /// A corner of the base is off the floor.
    pub heel_lifted: bool,
    /// The body stands on one corner.
    pub uplift: bool,
    /// The contact iteration did not settle exactly.
    pub approximate_contact: bool,
    /// F(q) of the SDOF model, N.
    pub sdof_force: f64,
}

/// The columns of pushover.csv (a contract), one per field of [`PushoverRow`].
pub const PUSHOVER_COLUMNS: [Column<PushoverRow>; 12] = [
    Column::new("base", |r| r.base.to_string()),
    Column::new("q", |r| number(r.q)),
    Column::new("base_shear", |r| number(r.base_shear)),
    Column::new("load_factor", |r| number(r.load_factor)),
    Column::new("flexural", |r| number(r.flexural)),
    Column::new("rocking", |r| number(r.rocking)),
    Column::new("shearing", |r| number(r.shearing)),
    Column::new("contact_nodes", |r| r.contact_nodes.to_string()),
    Column::new("heel_lifted", |r| r.heel_lifted.to_string()),
    Column::new("uplift", |r| r.uplift.to_string()),
    Column::new("approximate_contact", |r| r.approximate_contact.to_string()),
    Column::new("sdof_force", |r| number(r.sdof_force)),
];

/// The rows of pushover.csv: every point of every curve, in the order of the curves.
pub fn rows(model: &Model, a: &PushoverAnalysis) -> Vec<PushoverRow> {
    let automaton = Automaton::new(&model.constants);
    a.curves
        .iter()
        .flat_map(|(base, curve)| {
            let automaton = &automaton;
            curve.points.iter().map(move |p| PushoverRow {
                base: base.name(),
                q: p.q,
                base_shear: p.base_shear,
                load_factor: p.load_factor,
                flexural: p.flexural,
                rocking: p.rocking,
                shearing: p.shearing,
                contact_nodes: p.contact_nodes,
                heel_lifted: p.heel_lifted,
                uplift: p.uplift,
                approximate_contact: p.approximate_contact,
                sdof_force: sdof_force(automaton, p.q),
            })
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::bodies::fem::PushoverPoint;
    use crate::tables::fields::{fields, names, serialized_keys};

    fn point(q: f64, base_shear: f64, heel_lifted: bool, uplift: bool) -> PushoverPoint {
        PushoverPoint {
            q,
            base_shear,
            load_factor: 0.0,
            uplift,
            heel_lifted,
            contact_nodes: 3,
            flexural: 0.0,
            rocking: 0.0,
            shearing: 0.0,
            approximate_contact: false,
        }
    }

    /// A curve k0 = 400 N/m at first, peaking at 6 N at q = 0.03, heel lifting at 0.02 and
    /// standing on one toe at 0.04; against Ke = 200 N/m.
    #[test]
    fn a_curve_is_summarised_by_its_stiffness_lifts_and_peak() {
        let curve = Pushover {
            points: vec![
                point(0.01, 4.0, false, false),
                point(0.02, 5.0, true, false),
                point(0.03, 6.0, true, false),
                point(0.04, 5.5, true, true),
            ],
            free_rotation_at: None,
        };
        let s = summarise(BaseSupport::Flexible, &curve, 200.0);
        assert_eq!(s.initial_stiffness, 400.0);
        assert_eq!(s.initial_stiffness_over_ke, 2.0);
        assert_eq!((s.heel_lift_q, s.uplift_q), (Some(0.02), Some(0.04)));
        assert_eq!((s.peak_base_shear, s.peak_q), (6.0, 0.03));
        let empty = Pushover {
            points: Vec::new(),
            free_rotation_at: Some(0.0),
        };
        let s = summarise(BaseSupport::RigidPlate, &empty, 200.0);
        assert!(s.initial_stiffness.is_nan() && s.peak_q.is_nan());
        assert_eq!(s.heel_lift_q, None);
    }

    /// The columns of pushover.csv are the fields of its rows, in order.
    #[test]
    fn the_columns_are_the_fields_of_a_row() {
        let row = PushoverRow {
            base: "flexible",
            q: 0.5,
            base_shear: 100.0,
            load_factor: 2.0,
            flexural: 0.1,
            rocking: 0.3,
            shearing: 0.1,
            contact_nodes: 1,
            heel_lifted: true,
            uplift: true,
            approximate_contact: false,
            sdof_force: 90.0,
        };
        assert_eq!(serialized_keys(&row), names(&PUSHOVER_COLUMNS));
        assert_eq!(
            fields(&PUSHOVER_COLUMNS, &row),
            [
                "flexible", "0.5", "100", "2", "0.1", "0.3", "0.1", "1", "true", "true", "false",
                "90"
            ]
        );
    }
}
