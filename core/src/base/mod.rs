//! The bottom layer: units, number formatting, limits, the parameter error, "did you mean"
//! suggestions and double-double arithmetic. It knows nothing of the model.

pub(crate) mod double_double;
pub mod format;
pub(crate) mod invalid;
pub(crate) mod limits;
pub(crate) mod suggest;
pub(crate) mod units;
