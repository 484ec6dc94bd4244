//! A step of a body with one coordinate q (y[0]) and its rate q' (y[1]) cut into pieces on which
//! q moves one way: where q' changes sign between the step's ends, at its root. A body of the
//! diffsol event loop looks for its crossings piece by piece, so that each guard is met at most
//! once, in the direction q moves.

use super::event_loop::{DenseOutput, StepStart};
use super::SolverError;

/// A stretch of a step on which q moves one way.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Piece {
    /// Where it starts, s, and q there.
    pub from: f64,
    /// q at `from`.
    pub q_from: f64,
    /// Where it ends, s.
    pub to: f64,
    /// q at `to`.
    pub q_to: f64,
    /// +1 when q rises, -1 when it falls, 0 when it does not move.
    pub direction: f64,
}

/// The step from `start` to `t1` in pieces of monotone q.
pub(crate) struct MonotonePieces {
    pieces: [Piece; 2],
    count: usize,
    /// The root of q' inside the step (time and q: a peak of q), if q' changes sign.
    pub turn: Option<(f64, f64)>,
    /// The state (q, q') at `t1`.
    pub end: [f64; 2],
}

impl MonotonePieces {
    /// Cuts the step [start, `t1`] of `dense` at the root of q' when q' has opposite signs at its
    /// ends (located by [`super::sign_change::locate`]).
    pub fn of(
        dense: &dyn DenseOutput,
        start: &StepStart,
        t1: f64,
    ) -> Result<MonotonePieces, SolverError> {
        let state_at = |t: f64| -> Result<[f64; 2], SolverError> {
            let y = dense.state_at(t)?;
            Ok([y[0], y[1]])
        };
        let end = state_at(t1)?;
        let (qdot0, qdot1) = (start.y[1], end[1]);
        let whole = Piece {
            from: start.t,
            q_from: start.y[0],
            to: t1,
            q_to: end[0],
            direction: 0.0,
        };
        let mut pieces = [whole; 2];
        if qdot0 * qdot1 < 0.0 {
            let t_turn =
                super::sign_change::locate(start.t, t1, |t| -> Result<f64, SolverError> {
                    Ok(state_at(t)?[1])
                })?;
            let q_turn = state_at(t_turn)?[0];
            pieces[0].to = t_turn;
            pieces[0].q_to = q_turn;
            pieces[0].direction = qdot0.signum();
            pieces[1] = Piece {
                from: t_turn,
                q_from: q_turn,
                direction: qdot1.signum(),
                ..whole
            };
            return Ok(MonotonePieces {
                pieces,
                count: 2,
                turn: Some((t_turn, q_turn)),
                end,
            });
        }
        let direction = if qdot1 != 0.0 { qdot1 } else { qdot0 };
        pieces[0].direction = if direction == 0.0 {
            0.0
        } else {
            direction.signum()
        };
        Ok(MonotonePieces {
            pieces,
            count: 1,
            turn: None,
            end,
        })
    }

    /// The pieces, in order.
    pub fn pieces(&self) -> &[Piece] {
        &self.pieces[..self.count]
    }
}
