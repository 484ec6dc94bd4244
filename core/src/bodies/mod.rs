//! Bodies built on the automaton and the integrators: the rigid block of the rigid limit, the row
//! of columns that strike each other, the plane-stress finite element model of the body, and the
//! linear oscillator whose peak response is a floor motion's spectral acceleration.

pub mod fem;
pub mod oscillator;
pub mod rigid;
pub mod row;
