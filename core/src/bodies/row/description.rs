//! The row's description: its columns left to right, the contacts between neighbours, the
//! restitution, the contact law and the friction, each checked as the row is built.

use super::contact::{Contact, Face};
use super::law;
use crate::base::invalid::InvalidParameter as Error;
use crate::integrate::budget::STEPS_PER_SECOND;
use crate::integrate::InitialState;
use crate::physics::automaton::{Automaton, Mode};
use crate::physics::body::Body;
use crate::physics::constants::{flexural_shape_at, flexural_shape_slope_at, Constants};

/// Largest coefficient of friction between the faces of a row. Building materials against
/// each other take 0.2 to about 1.2 (concrete, masonry, steel, timber; rubber on concrete
/// about 1); at 1e160 the slip friction mu P overflows the integration (histories of NaN), and
/// from 1e6 on in the example of models/row-friction.toml faces that meet sliding stop within a
/// time no integrator resolves.
pub const MAX_FRICTION: f64 = 10.0;

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
        let damping_ratio = law::damping_ratio_for(self.restitution);
        self.check_contact_rate(stiffness, damping_ratio)?;
        self.law = ContactLaw::Compliant {
            stiffness,
            damping_ratio,
        };
        Ok(self)
    }

    /// The reduced mass of the two contact points of contact `c` with its columns in `modes`,
    /// kg: m / Phi^2 of each, m the column's kinetic mass and Phi its velocity shape at the
    /// contact.
    pub(crate) fn reduced_mass(&self, c: usize, modes: (Mode, Mode)) -> f64 {
        let automata = (&self.columns[c].automaton, &self.columns[c + 1].automaton);
        let (pl, pr) = self.contacts[c].slopes(automata, modes);
        let ml = automata.0.kinetic_mass(modes.0) / (pl * pl);
        let mr = automata.1.kinetic_mass(modes.1) / (pr * pr);
        ml * mr / (ml + mr)
    }

    /// Refuses a compliant law whose contacts move faster than the integrator can follow: two
    /// contact points alone, of reduced mass m, vibrate at w = sqrt(k / m), and an overdamped
    /// dashpot adds the faster rate w (zeta + sqrt(zeta^2 - 1)). An explicit method steps no
    /// further than a few times 1 / rate, and a run is allowed [`STEPS_PER_SECOND`] steps per
    /// simulated second: the fastest rate, in every pair of modes, must not exceed it. (Far
    /// beyond it a contact lasts less than the spacing of floating-point times, and the run made
    /// NaN: a stiffness of 1e154 N/m, a restitution of 1e-300, a column 1e-300 m deep.)
    fn check_contact_rate(&self, stiffness: f64, zeta: f64) -> Result<(), Error> {
        let overdamped = if zeta > 1.0 {
            zeta + (zeta * zeta - 1.0).sqrt()
        } else {
            1.0
        };
        let modes = [Mode::PreUplift, Mode::RockRight, Mode::RockLeft];
        for c in 0..self.contacts.len() {
            for (left, right) in modes
                .iter()
                .flat_map(|l| modes.iter().map(move |r| (*l, *r)))
            {
                let mass = self.reduced_mass(c, (left, right));
                let spring = (stiffness / mass).sqrt();
                let rate = spring * overdamped;
                // A contact point that does not move in these modes (Phi = 0) sets no rate.
                if rate.is_nan() || crate::base::limits::at_most(rate, STEPS_PER_SECOND) {
                    continue;
                }
                let between = format!(
                    "the contact of column {c} and column {} (its points' reduced mass {} kg, \
                     from the columns' density, height, width and depth, column {c} {} and \
                     column {} {})",
                    c + 1,
                    crate::base::format::significant(mass, 6),
                    left.name(),
                    c + 1,
                    right.name()
                );
                let rule = format!(
                    "must be at most {STEPS_PER_SECOND:e} per second, the integrator's steps per \
                     simulated second"
                );
                return Err(if !crate::base::limits::at_most(spring, STEPS_PER_SECOND) {
                    Error::new(
                        "row.stiffness",
                        stiffness,
                        &format!(
                            "gives {between} the rate sqrt(k / m) = {} per second, which {rule}",
                            crate::base::format::significant(spring, 6)
                        ),
                    )
                } else {
                    Error::new(
                        "row.restitution",
                        self.restitution,
                        &format!(
                            "sets the dashpot's damping ratio {} under the compliant law, which \
                             gives {between} the rate sqrt(k / m) (zeta + sqrt(zeta^2 - 1)) = {} \
                             per second, which {rule}",
                            crate::base::format::significant(zeta, 6),
                            crate::base::format::significant(rate, 6)
                        ),
                    )
                });
            }
        }
        Ok(())
    }

    /// The row with Coulomb's friction of coefficient `mu` between faces in contact
    /// (book/src/row.md §4b): on their vertical sliding, at most `mu` times the contact force,
    /// with stick and slip. The contact law must be compliant; 0 is no friction. Errors name
    /// `row.friction`.
    pub fn with_friction(mut self, mu: f64) -> Result<Self, Error> {
        if !(mu >= 0.0 && crate::base::limits::at_most(mu, MAX_FRICTION)) {
            return Err(Error::new(
                "row.friction",
                mu,
                &format!(
                    "must be a finite coefficient of friction >= 0 and at most {MAX_FRICTION}: no \
                     pair of materials comes near {MAX_FRICTION}, and far beyond it faces that \
                     meet sliding stop within a time no integrator resolves"
                ),
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
