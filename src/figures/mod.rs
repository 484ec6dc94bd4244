//! Figures, as SVG (and PNG): [`plot`] draws panels from plain series; [`run`] the figures of a
//! run from its files; [`criteria`] the overturning criteria's figures; [`sweep`] the map, the spectrum and the IDA curves from sweep.csv alone.

pub mod criteria;
pub mod plot;
pub mod row;
pub mod run;
pub mod sweep;
pub mod sweep_row;
