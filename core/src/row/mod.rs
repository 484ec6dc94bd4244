//! A row of slender elastic columns on one floor, each the single body of the model, with clear
//! gaps between neighbours: columns that rock or sway far enough strike each other
//! (book/src/row.md).
//!
//! Each column keeps its own automaton: its modes, its flow within each, its uplifts, landings
//! and overturning are exactly those of the body alone. The row adds contacts between
//! neighbours, each at the top of the shorter of the two ([`Contact`]), and an impact law at
//! them ([`impulses`]): Newton's restitution on the closing velocity of the contact points, the
//! impulse acting on each column through its velocity shape, simultaneous impacts of a chain
//! resolved together as a linear complementarity problem. Between impacts the columns move
//! independently, so a row whose gaps never close gives each column's single run.
//!
//! ```
//! use flexrock_core::automaton::EventKind;
//! use flexrock_core::body::{prism_mass, solid_section_flexural_rigidity, Body};
//! use flexrock_core::body::{ConstantSet, SelfWeight};
//! use flexrock_core::excitation::PaperSine;
//! use flexrock_core::row::{solve_row, ColumnSpec, Row};
//! use flexrock_core::solver::exact::ExactSettings;
//! use flexrock_core::solver::{History, InitialState};
//!
//! // Two columns of the paper's size, the right one stiffer, 2 cm apart, under the paper's sine.
//! let column = |youngs_modulus: f64| ColumnSpec {
//!     body: Body {
//!         height: 4.0,
//!         width: 0.7,
//!         depth: 1.0,
//!         mass: prism_mass(600.0, 4.0, 0.7, 1.0),
//!         flexural_rigidity: solid_section_flexural_rigidity(youngs_modulus, 0.7, 1.0),
//!         damping_ratio: 0.05,
//!         gravity: 9.81,
//!         constant_set: ConstantSet::Exact,
//!         self_weight: SelfWeight::Paper,
//!     },
//!     initial: InitialState { q: 0.0, qdot: 0.0 },
//! };
//! let row = Row::new(&[column(5e6), column(5e7)], &[0.02], 0.5)?;
//! let floor = PaperSine::new(4.0, 1.0, 0.412);
//! let settings = ExactSettings { output_dt: 0.01 };
//! let solved = solve_row(&row, &floor, 6.0, &settings, History::Sampled)?;
//! // The softer column sways further and strikes its neighbour.
//! assert!(!solved.impacts.is_empty());
//! let first = solved.impacts[0];
//! assert!(first.impulse > 0.0 && first.separating_velocity > 0.0);
//! // Each impact is an event of both columns, whose q' jumps there.
//! for column in &solved.columns {
//!     assert!(column.events.iter().any(|e| e.kind == EventKind::Impact));
//! }
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```

mod compliant;
mod contact;
mod impact;
pub mod law;
mod solve;

pub use compliant::{
    solve_row_compliant, CompliantSettings, ContactStretch, StickStretch, DEFAULT_TOLERANCE, METHOD,
};
pub use contact::{Contact, ContactSample, ContactState, Face};
pub use impact::{impulses, ImpactError, MAX_SIMULTANEOUS};
pub use solve::{solve_row, HeldContact, ImpactRecord, RowSolution, ACCUMULATION_SHARE};

use crate::automaton::Automaton;
use crate::body::Body;
use crate::constants::{flexural_shape_at, flexural_shape_slope_at, Constants};
use crate::invalid::InvalidParameter as Error;
use crate::solver::InitialState;

/// One column of a row: its body and where it starts.
#[derive(Debug, Clone)]
pub struct ColumnSpec {
    /// The body.
    pub body: Body,
    /// q and q' at t = 0.
    pub initial: InitialState,
}

/// A column as the row uses it: its automaton and its size.
#[derive(Debug, Clone)]
pub struct Column {
    /// The body's automaton (the body alone: its modes, guards and resets).
    pub automaton: Automaton,
    /// H, m.
    pub height: f64,
    /// B, m.
    pub width: f64,
    /// q and q' at t = 0.
    pub initial: InitialState,
}

/// How two neighbours that touch act on each other (book/src/row.md §3 and §4a).
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
#[serde(tag = "law", rename_all = "kebab-case")]
pub enum ContactLaw {
    /// Newton's restitution over an instant, solved by the exact method.
    Impact,
    /// A linear spring and dashpot between the faces, P = k delta + c delta', let go where P
    /// falls through zero; c gives Newton's restitution to two contact points alone.
    Compliant {
        /// k, N/m.
        stiffness: f64,
        /// zeta = c / (2 sqrt(k m_red)), from the restitution ([`law::damping_ratio_for`]).
        damping_ratio: f64,
    },
}

/// A row of N >= 2 columns, left to right, with the contacts between neighbours.
#[derive(Debug, Clone)]
pub struct Row {
    columns: Vec<Column>,
    contacts: Vec<Contact>,
    restitution: f64,
    law: ContactLaw,
    friction: f64,
}

impl Row {
    /// The row of `columns` (left to right) with clear gaps `gaps` (m, `gaps[i]` between column
    /// i and i + 1, at rest) and Newton's coefficient of restitution `restitution` at every
    /// contact. Errors name the key: `column[i].…`, `row.gaps`, `row.restitution`.
    pub fn new(columns: &[ColumnSpec], gaps: &[f64], restitution: f64) -> Result<Self, Error> {
        if columns.len() < 2 {
            return Err(Error::new(
                "column",
                columns.len(),
                "a row needs at least 2 columns",
            ));
        }
        if gaps.len() != columns.len() - 1 {
            return Err(Error::new(
                "row.gaps",
                format!("{} gaps", gaps.len()),
                &format!(
                    "a row of {} columns has {} gaps, one between each pair of neighbours",
                    columns.len(),
                    columns.len() - 1
                ),
            ));
        }
        for (i, &gap) in gaps.iter().enumerate() {
            if !(gap.is_finite() && gap > 0.0) {
                return Err(Error::new(
                    &format!("row.gaps[{i}]"),
                    gap,
                    "must be a finite clear gap > 0 m (columns touching at rest would stay in \
                     contact, which the row does not model)",
                ));
            }
        }
        if !(0.0..=1.0).contains(&restitution) {
            return Err(Error::new(
                "row.restitution",
                restitution,
                "must be in [0, 1]",
            ));
        }
        let mut built = Vec::with_capacity(columns.len());
        for (i, spec) in columns.iter().enumerate() {
            let body = spec.body.clone().validated().map_err(|e| e.in_column(i))?;
            let constants = Constants::new(&body).map_err(|e| e.in_column(i))?;
            built.push(Column {
                automaton: Automaton::new(&constants),
                height: spec.body.height,
                width: spec.body.width,
                initial: spec.initial,
            });
        }
        let mut contacts = Vec::with_capacity(gaps.len());
        for (i, &gap) in gaps.iter().enumerate() {
            let (left, right) = (&columns[i].body, &columns[i + 1].body);
            let height = left.height.min(right.height);
            let point = |body: &Body, index: usize| {
                let xi = height / body.height;
                // The top itself: U(1) = 1 in every variant.
                let shape = if xi == 1.0 {
                    Some(1.0)
                } else {
                    flexural_shape_at(body, xi)
                };
                shape.map(|shape| (xi, shape)).ok_or_else(|| {
                    Error::new(
                        &format!("column[{index}].height"),
                        body.height,
                        "the body buckles under its own weight",
                    )
                })
            };
            let face = |body: &Body, index: usize, side: f64| {
                let xi = height / body.height;
                flexural_shape_slope_at(body, xi)
                    .map(|shape_slope| Face {
                        side,
                        width: body.width,
                        height: body.height,
                        shape_slope,
                    })
                    .ok_or_else(|| {
                        Error::new(
                            &format!("column[{index}].height"),
                            body.height,
                            "the body buckles under its own weight",
                        )
                    })
            };
            contacts.push(Contact::new(
                i,
                height,
                gap,
                point(left, i)?,
                point(right, i + 1)?,
                (face(left, i, 1.0)?, face(right, i + 1, -1.0)?),
            ));
        }
        for contact in &contacts {
            let c = contact.index;
            let (left, right) = (&built[c], &built[c + 1]);
            let at = |column: &Column| {
                let q = column.initial.q;
                (column.automaton.initial_mode(q), q)
            };
            let gap = contact.gap((&left.automaton, &right.automaton), at(left), at(right));
            if gap.is_nan() || gap <= 0.0 {
                return Err(Error::new(
                    &format!("row.gaps[{c}]"),
                    contact.clearance,
                    &format!(
                        "columns {c} and {} overlap or touch at their initial q (clear gap {gap} \
                         m): the gap must be open at the start",
                        c + 1
                    ),
                ));
            }
        }
        Ok(Row {
            columns: built,
            contacts,
            restitution,
            law: ContactLaw::Impact,
            friction: 0.0,
        })
    }

    /// The row with the compliant contact law of stiffness `stiffness` (N/m) at every contact,
    /// its dashpot chosen so that two contact points alone restitute the row's restitution.
    /// Errors name `row.stiffness`, or `row.restitution` when it is 0 (that needs an infinite
    /// dashpot).
    pub fn compliant(mut self, stiffness: f64) -> Result<Self, Error> {
        if !(stiffness.is_finite() && stiffness > 0.0) {
            return Err(Error::new(
                "row.stiffness",
                stiffness,
                "must be a finite contact stiffness > 0 N/m",
            ));
        }
        if self.restitution <= 0.0 {
            return Err(Error::new(
                "row.restitution",
                self.restitution,
                "must be > 0 with contact = \"compliant\": a contact let go where its force \
                 falls to zero restitutes e = 0 only with an infinite dashpot",
            ));
        }
        self.law = ContactLaw::Compliant {
            stiffness,
            damping_ratio: law::damping_ratio_for(self.restitution),
        };
        Ok(self)
    }

    /// The row with Coulomb's friction of coefficient `mu` between faces in contact
    /// (book/src/row.md §4b): on their vertical sliding, at most `mu` times the contact force,
    /// with stick and slip. The contact law must be compliant; 0 is no friction. Errors name
    /// `row.friction`.
    pub fn with_friction(mut self, mu: f64) -> Result<Self, Error> {
        if !(mu.is_finite() && mu >= 0.0) {
            return Err(Error::new(
                "row.friction",
                mu,
                "must be a finite coefficient of friction >= 0",
            ));
        }
        if mu > 0.0 && self.law == ContactLaw::Impact {
            return Err(Error::new(
                "row.friction",
                mu,
                "needs contact = \"compliant\": friction acts through the contact force while \
                 two faces press, and the impact law has no such stretch (leave friction out, or \
                 set contact = \"compliant\" with its stiffness)",
            ));
        }
        self.friction = mu;
        Ok(self)
    }

    /// Coulomb's coefficient of friction between faces in contact (0: none).
    pub fn friction(&self) -> f64 {
        self.friction
    }

    /// The columns, left to right.
    pub fn columns(&self) -> &[Column] {
        &self.columns
    }

    /// The contacts: `contacts()[i]` between column i and i + 1.
    pub fn contacts(&self) -> &[Contact] {
        &self.contacts
    }

    /// Newton's coefficient of restitution.
    pub fn restitution(&self) -> f64 {
        self.restitution
    }

    /// The contact law.
    pub fn law(&self) -> ContactLaw {
        self.law
    }
}
