//! Where two neighbouring columns touch, and how far apart they are (book/src/row.md §2).
//!
//! The contact is at the height of the shorter column's top, y_c = min(H_left, H_right). There
//! each column's section moves horizontally by u = U(xi) s + xi r (xi = y_c / H), with s and r
//! the flexural and rocking parts of its q; within a mode u is affine in q, with slope Phi(xi),
//! the mode's velocity shape. To the same small-rotation order as the single column, the faces
//! stay vertical, so the clear gap is the gap at rest plus the right column's u minus the left
//! column's.

use crate::automaton::{Automaton, Mode};

/// The contact between column `index` and `index + 1` of a row.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Contact {
    /// Which contact: between columns `index` and `index + 1`.
    pub index: usize,
    /// y_c, m: the top of the shorter column.
    pub height: f64,
    /// The clear gap at rest, m.
    pub clearance: f64,
    /// xi = y_c / H and the flexural shape U(xi) there, of the left and the right column.
    pub left: (f64, f64),
    /// As `left`, of the right column.
    pub right: (f64, f64),
}

impl Contact {
    pub(crate) fn new(
        index: usize,
        height: f64,
        clearance: f64,
        left: (f64, f64),
        right: (f64, f64),
    ) -> Self {
        Contact {
            index,
            height,
            clearance,
            left,
            right,
        }
    }

    /// The clear gap, m, with the left column in `left` = (mode, q) and the right in `right`.
    /// Negative where the faces would overlap.
    pub fn gap(
        &self,
        automata: (&Automaton, &Automaton),
        left: (Mode, f64),
        right: (Mode, f64),
    ) -> f64 {
        let (u_left, u_right) = self.displacements(automata, left, right);
        self.clearance - u_left + u_right
    }

    /// The size of the terms the gap is summed from, m: the gap at rest plus both columns'
    /// displacements at the contact. The gap's rounding is a few ulps of it.
    pub fn gap_size(
        &self,
        automata: (&Automaton, &Automaton),
        left: (Mode, f64),
        right: (Mode, f64),
    ) -> f64 {
        let (u_left, u_right) = self.displacements(automata, left, right);
        self.clearance.abs() + u_left.abs() + u_right.abs()
    }

    /// Each column's horizontal displacement at the contact, m.
    fn displacements(
        &self,
        automata: (&Automaton, &Automaton),
        left: (Mode, f64),
        right: (Mode, f64),
    ) -> (f64, f64) {
        (
            automata
                .0
                .displacement_at(left.0, left.1, self.left.0, self.left.1),
            automata
                .1
                .displacement_at(right.0, right.1, self.right.0, self.right.1),
        )
    }

    /// du/dq of the left and the right column at the contact, in their modes: the closing
    /// velocity is `slopes.0` q'_left - `slopes.1` q'_right.
    pub fn slopes(&self, automata: (&Automaton, &Automaton), modes: (Mode, Mode)) -> (f64, f64) {
        (
            automata
                .0
                .displacement_slope_at(modes.0, self.left.0, self.left.1),
            automata
                .1
                .displacement_slope_at(modes.1, self.right.0, self.right.1),
        )
    }
}
