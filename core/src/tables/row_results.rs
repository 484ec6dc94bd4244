//! The results of a row's run (book/src/row.md): summary.json (how it was made: version, model
//! file, the row as read, the floor motion, the method; each column's peaks and counts; the
//! impacts), the rows of impacts.csv and those of contacts.csv.

use serde::Serialize;

use crate::base::format::number;
use crate::tables::fields::{names, Column};

use crate::bodies::row::{
    CompliantSettings, ContactLaw, ContactSample, ContactStretch, HeldContact, RowSolution,
    StickStretch,
};
use crate::integrate::exact::ExactSettings;
use crate::integrate::InitialState;
use crate::model::{RowModel, RowSection};
use crate::physics::automaton::EventKind;
use crate::physics::body::Body;
use crate::simulate::{Commit, VERSION};

/// summary.json of a row.
#[derive(Debug, Serialize)]
pub struct RowSummary<'a> {
    /// The version of flexrock that wrote the file.
    pub flexrock_version: &'static str,
    /// The commit it was built from.
    #[serde(flatten)]
    pub build: Commit,
    /// The model file read, if any.
    pub model_file: Option<String>,
    /// The method: the exact solution under the impact law, Tsit45 under the compliant law.
    pub method: &'static str,
    /// Its settings.
    pub solver: ExactSettings,
    /// The compliant law's integration settings (rtol, atol, output_dt); absent under the
    /// impact law.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub tolerances: Option<CompliantSettings>,
    /// The contact law and its constants: k (N/m) and the damping ratio zeta that restitutes
    /// e; absent under the impact law (each stretch's dashpot c is in `contact_stretches`).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub contact_law: Option<ContactLaw>,
    /// The `[row]` table as read.
    pub row: &'a RowSection,
    /// The floor motion as understood.
    pub excitation: serde_json::Value,
    /// Simulated time asked for, s.
    pub duration: f64,
    /// Time the run ended, s (earlier than the duration when a column overturned).
    pub final_time: f64,
    /// The column that overturned, if one did (counted from 0, left to right): the run ends there.
    pub overturned_column: Option<usize>,
    /// When it overturned, s.
    pub t_overturn: Option<f64>,
    /// Impacts, counted per contact (a simultaneous impact of two contacts counts two).
    pub n_impacts: usize,
    /// Instants with impacts.
    pub n_impact_instants: usize,
    /// The body kinetic energy the impacts took, J, summed over the run.
    pub impact_energy_lost: f64,
    /// Every stretch of persistent contact (impacts that accumulated, after which the pair was
    /// held together until its contact force fell to zero): contact, t_start, t_end (s; null
    /// if held to the end).
    pub held_contacts: Vec<HeldContact>,
    /// Under the compliant law, every stretch of contact: contact, t_start, t_end, the reduced
    /// mass and the dashpot c, the closing and separating velocities, the peak force and when,
    /// the energy taken. Absent under the impact law.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub contact_stretches: Option<Vec<ContactStretch>>,
    /// With friction, every stretch over which a contact's faces stuck: contact, t_start, t_end
    /// (s; null if stuck at the end). Absent without friction.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub friction_sticking: Option<Vec<StickStretch>>,
    /// Each column, left to right.
    pub columns: Vec<ColumnSummary<'a>>,
    /// What the run warns of, as `flexrock run` prints it ([`crate::simulate::row_warnings`]).
    pub warnings: Vec<String>,
}

/// One column of a row's summary.
#[derive(Debug, Serialize)]
pub struct ColumnSummary<'a> {
    /// Its body.
    pub body: &'a Body,
    /// Its state at t = 0.
    pub initial_state: InitialState,
    /// s_n, m.
    pub s_n: f64,
    /// Largest q and when, m and s.
    pub max_q: f64,
    /// When q was largest, s.
    pub t_max_q: f64,
    /// Smallest q, m.
    pub min_q: f64,
    /// When q was smallest, s.
    pub t_min_q: f64,
    /// Uplifts.
    pub n_uplift: usize,
    /// Landings.
    pub n_landing: usize,
    /// Impacts this column took part in.
    pub n_impact: usize,
    /// Whether it fell over.
    pub overturned: bool,
    /// Largest |energy_residual| of its energy books, J.
    pub max_energy_residual: f64,
    /// The energies that residual is measured against, J.
    pub energy_scale: f64,
    /// The mode it ended in.
    pub final_mode: &'static str,
}

/// The summary of `solution`, the run of `model`.
pub fn row_summary<'a>(model: &'a RowModel, solution: &RowSolution) -> RowSummary<'a> {
    let columns = solution
        .columns
        .iter()
        .zip(&model.bodies)
        .zip(model.row.columns())
        .map(|((s, body), column)| ColumnSummary {
            body,
            initial_state: column.initial,
            s_n: column.automaton.uplift_displacement(),
            max_q: s.max_q.value,
            t_max_q: s.max_q.t,
            min_q: s.min_q.value,
            t_min_q: s.min_q.t,
            n_uplift: s.count(EventKind::Uplift),
            n_landing: s.count(EventKind::Landing),
            n_impact: s.count(EventKind::Impact),
            overturned: s.overturned,
            max_energy_residual: s.max_energy_residual,
            energy_scale: s.energy_scale,
            final_mode: s.final_mode.name(),
        })
        .collect();
    RowSummary {
        flexrock_version: VERSION,
        build: Commit::BUILT,
        model_file: model.path.as_ref().map(|p| p.display().to_string()),
        method: if model.compliant.is_some() {
            crate::bodies::row::METHOD
        } else {
            crate::integrate::exact::NAME
        },
        solver: model.settings,
        tolerances: model.compliant,
        contact_law: model.compliant.map(|_| model.row.law()),
        row: &model.section,
        excitation: model.floor.parameters(),
        duration: model.duration,
        final_time: solution.final_time,
        overturned_column: solution.overturned.map(|(i, _)| i),
        t_overturn: solution.overturned.map(|(_, t)| t),
        n_impacts: solution.impacts.len(),
        n_impact_instants: solution.impact_energy_loss.len(),
        impact_energy_lost: solution.impact_energy_loss.iter().map(|(_, e)| e).sum(),
        held_contacts: solution.held.clone(),
        contact_stretches: model.compliant.map(|_| solution.contacts.clone()),
        friction_sticking: (model.row.friction() > 0.0).then(|| solution.sticking.clone()),
        columns,
        warnings: crate::simulate::row_warnings(model, solution),
    }
}

/// One row of impacts.csv: one contact's impact.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct ImpactRow {
    /// Which instant of impacts, from 0: contacts struck at one instant share it.
    pub instant: usize,
    /// Time, s.
    pub t: f64,
    /// The contact, from 0: between columns `left` = `contact` and `right` = `contact` + 1.
    pub contact: usize,
    /// The left column.
    pub left: usize,
    /// The right column.
    pub right: usize,
    /// Height of the contact, m: the top of the shorter column.
    pub height: f64,
    /// Closing velocity of the contact points before the impact, m/s.
    pub closing_velocity: f64,
    /// Their separating velocity after it, m/s.
    pub separating_velocity: f64,
    /// The impulse, N s.
    pub impulse: f64,
    /// The body kinetic energy the instant's impacts took together, J.
    pub instant_energy_lost: f64,
}

/// The columns of impacts.csv: names and fields from one list.
pub const IMPACT_COLUMNS: [Column<ImpactRow>; 10] = [
    Column::new("instant", |r| r.instant.to_string()),
    Column::new("t", |r| number(r.t)),
    Column::new("contact", |r| r.contact.to_string()),
    Column::new("left", |r| r.left.to_string()),
    Column::new("right", |r| r.right.to_string()),
    Column::new("height", |r| number(r.height)),
    Column::new("closing_velocity", |r| number(r.closing_velocity)),
    Column::new("separating_velocity", |r| number(r.separating_velocity)),
    Column::new("impulse", |r| number(r.impulse)),
    Column::new("instant_energy_lost", |r| number(r.instant_energy_lost)),
];

/// The header of impacts.csv.
pub const IMPACT_COLUMN_NAMES: [&str; 10] = names(&IMPACT_COLUMNS);

/// The rows of impacts.csv of `solution`, the run of `model`'s row.
pub fn impact_rows(model: &RowModel, solution: &RowSolution) -> Vec<ImpactRow> {
    let mut instant = 0usize;
    let mut rows: Vec<ImpactRow> = Vec::with_capacity(solution.impacts.len());
    for impact in &solution.impacts {
        if let Some(last) = rows.last() {
            if impact.t != last.t {
                instant += 1;
            }
        }
        let lost = solution
            .impact_energy_loss
            .get(instant)
            .map_or(f64::NAN, |&(_, e)| e);
        rows.push(ImpactRow {
            instant,
            t: impact.t,
            contact: impact.contact,
            left: impact.contact,
            right: impact.contact + 1,
            height: model.row.contacts()[impact.contact].height,
            closing_velocity: impact.closing_velocity,
            separating_velocity: impact.separating_velocity,
            impulse: impact.impulse,
            instant_energy_lost: lost,
        });
    }
    rows
}

/// A value the law may not have: empty in the table when it has none.
fn optional(value: Option<f64>) -> String {
    value.map(number).unwrap_or_default()
}

/// The columns of contacts.csv (one row per contact per sampled instant): names and fields from
/// one list.
pub const CONTACT_COLUMNS: [Column<ContactSample>; 8] = [
    Column::new("t", |r| number(r.t)),
    Column::new("contact", |r| r.contact.to_string()),
    Column::new("state", |r| {
        serde_json::to_value(r.state)
            .ok()
            .and_then(|v| v.as_str().map(str::to_string))
            .unwrap_or_default()
    }),
    Column::new("gap", |r| number(r.gap + 0.0)),
    // + 0.0: a zero that rounding made negative is written 0.
    Column::new("closing_velocity", |r| number(r.closing_velocity + 0.0)),
    Column::new("sliding_velocity", |r| number(r.sliding_velocity + 0.0)),
    Column::new("force", |r| optional(r.force.map(|f| f + 0.0))),
    Column::new("friction_force", |r| {
        optional(r.friction_force.map(|f| f + 0.0))
    }),
];

/// The header of contacts.csv.
pub const CONTACT_COLUMN_NAMES: [&str; 8] = names(&CONTACT_COLUMNS);

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_impact_columns_name_the_row_fields_in_order() {
        let row = ImpactRow {
            instant: 0,
            t: 0.0,
            contact: 0,
            left: 0,
            right: 1,
            height: 1.0,
            closing_velocity: 0.0,
            separating_velocity: 0.0,
            impulse: 0.0,
            instant_energy_lost: 0.0,
        };
        assert_eq!(
            crate::tables::fields::serialized_keys(&row),
            IMPACT_COLUMN_NAMES.to_vec()
        );
    }

    #[test]
    fn the_contact_columns_name_the_sample_fields_in_order() {
        let sample = ContactSample {
            t: 0.0,
            contact: 0,
            state: crate::bodies::row::ContactState::Sticking,
            gap: -1e-4,
            closing_velocity: 0.0,
            sliding_velocity: 0.0,
            force: Some(1.0),
            friction_force: None,
        };
        assert_eq!(
            crate::tables::fields::serialized_keys(&sample),
            CONTACT_COLUMN_NAMES.to_vec()
        );
        assert_eq!((CONTACT_COLUMNS[2].field)(&sample), "sticking");
        assert_eq!((CONTACT_COLUMNS[7].field)(&sample), "");
    }
}
