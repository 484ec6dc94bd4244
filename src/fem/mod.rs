//! The plane-stress finite element check of the paper's Section 3: the numerics of
//! [`flexrock_core::fem`] (re-exported here), and the commands that write their files:
//! [`run`] (`flexrock fem`, the dynamic run and its comparison with the one-mode model) and
//! [`pushover_run`] (`flexrock fem --pushover`).

pub use flexrock_core::fem::*;

pub mod pushover_run;
pub mod run;
