//! Studies built on solved models: comparisons of two solutions, convergence studies, the finite
//! element checks, the paper's findings, overturning criteria and sweeps.

pub mod compare;
pub mod converge;
pub mod criteria;
pub mod fem_check;
pub mod findings;
pub mod fragility;
pub mod pushover_check;
pub mod rigid_search;
pub mod sweep;
