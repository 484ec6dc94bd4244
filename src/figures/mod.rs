//! Figures for print, as SVG, PDF and PNG: [`page`] holds a figure's size on paper and its
//! formats; [`plot`] lays out and draws panels from plain series; [`run`] the figures of a run
//! from its files; [`criteria`] the overturning criteria's figures; [`sweep`] the map, the
//! spectrum and the IDA curves from sweep.csv alone, with [`sweep_axes`] their labels and cells;
//! [`row`] and [`sweep_row`] those of rows; [`fragility`] the fragility curves and capacities.

pub mod criteria;
pub mod fragility;
pub mod page;
pub mod plot;
pub mod row;
pub mod run;
pub mod sweep;
pub mod sweep_axes;
pub mod sweep_row;
