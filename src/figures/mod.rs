//! Figures, as SVG (and PNG): [`plot`] draws panels from plain series; [`run`] the figures of a
//! run from its files; [`sweep`] the map, the spectrum and the IDA curves from sweep.csv alone.

pub mod plot;
pub mod run;
pub mod sweep;
