//! `flexrock._native`, the compiled half of the Python package `flexrock` (python/python/flexrock
//! re-exports it with its documentation): `Model`, `GroundMotion`, `read_record`, `props`,
//! `simulate` (a `Result` of numpy arrays), `simulate_row` (a row of columns), `sweep` (sweep.csv's columns, typed) and `compare`,
//! `converge`, `fem_check`, `fragility` (a study over a suite) and the fragility fits
//! `fit_capacities`, `fit_stripes`. Every number comes from flexrock-core exactly as the command line
//! computes it; nothing is written to disk.

mod analysis;
mod fragility;
mod intensity;
mod interrupt;
mod model;
mod motion;
mod simulate;
mod sweep;
mod table;

use pyo3::create_exception;
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;

create_exception!(
    flexrock,
    FlexrockError,
    PyValueError,
    "An error of flexrock, with the message the command line prints."
);

pub(crate) fn err(e: flexrock_core::Error) -> PyErr {
    FlexrockError::new_err(e.to_string())
}

#[pymodule]
#[pyo3(name = "_native")]
fn flexrock_module(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add("FlexrockError", m.py().get_type::<FlexrockError>())?;
    m.add("__version__", flexrock_core::simulate::VERSION)?;
    m.add_class::<model::Model>()?;
    m.add_class::<simulate::SimResult>()?;
    m.add_class::<motion::GroundMotion>()?;
    m.add_function(wrap_pyfunction!(motion::read_record, m)?)?;
    m.add_function(wrap_pyfunction!(motion::_ground_motion_from_state, m)?)?;
    m.add_function(wrap_pyfunction!(model::_model_from_state, m)?)?;
    m.add("MAX_SWEEP_TABLE_BYTES", sweep::MAX_SWEEP_TABLE_BYTES)?;
    m.add_function(wrap_pyfunction!(simulate::props, m)?)?;
    m.add_function(wrap_pyfunction!(simulate::simulate, m)?)?;
    m.add_class::<simulate::RowResult>()?;
    m.add_function(wrap_pyfunction!(simulate::simulate_row, m)?)?;
    m.add_function(wrap_pyfunction!(simulate::rigid_block, m)?)?;
    m.add_function(wrap_pyfunction!(sweep::sweep, m)?)?;
    m.add_function(wrap_pyfunction!(analysis::compare, m)?)?;
    m.add_function(wrap_pyfunction!(analysis::converge, m)?)?;
    m.add_function(wrap_pyfunction!(analysis::fem_check, m)?)?;
    m.add_function(wrap_pyfunction!(intensity::intensity_measures, m)?)?;
    m.add_function(wrap_pyfunction!(intensity::response_spectrum, m)?)?;
    m.add_function(wrap_pyfunction!(fragility::fragility, m)?)?;
    m.add_function(wrap_pyfunction!(fragility::fit_capacities, m)?)?;
    m.add_function(wrap_pyfunction!(fragility::fit_stripes, m)?)?;
    Ok(())
}
