//! The analyses of the core, as the command line runs them: `compare` (Newmark against the
//! adaptive reference), `converge` (a convergence study) and `fem_check` (the finite element
//! check against the one-mode model). Each returns plain dicts and lists of numbers.

use std::sync::Arc;

use pyo3::prelude::*;
use pyo3::types::PyDict;

use flexrock_core::analysis::{compare as comparison, converge as convergence, fem_check as fem};
use flexrock_core::integrate::SolverSettings;
use flexrock_core::model::FemOverrides;

use crate::interrupt;
use crate::model::Model;
use crate::simulate::{err_naming, json};

/// `compare(model, dt=None, variant=None, reference_rtol=None)`: the model solved by Newmark
/// (its `solver.dt`, or `dt`) and by the adaptive reference, measured against each other.
#[pyfunction]
#[pyo3(signature = (model, dt=None, variant=None, reference_rtol=None))]
pub(crate) fn compare<'py>(
    py: Python<'py>,
    model: &Model,
    dt: Option<f64>,
    variant: Option<String>,
    reference_rtol: Option<f64>,
) -> PyResult<Bound<'py, PyDict>> {
    let m = model.state().model;
    let names = [
        ("solver.dt", "dt"),
        ("solver.newmark_variant", "variant"),
        ("rtol", "reference_rtol"),
    ];
    let reference = m
        .reference(reference_rtol)
        .map_err(|e| err_naming(e, &names))?;
    let newmark = SolverSettings::Newmark(
        m.newmark_settings(dt, variant.as_deref())
            .map_err(|e| err_naming(e, &names))?,
    );
    let solved = interrupt::run(py, move || -> flexrock_core::Result<_> {
        let m = &*m;
        let r = flexrock_core::simulate_with(m, &reference)?;
        let n = flexrock_core::simulate_with(m, &newmark)?;
        let c = comparison::compare(&r, &n, m.solver.output_dt(), comparison::max_event_shift(m));
        let grid = comparison::grid_rows(&r, &n, m.solver.output_dt());
        Ok((c, grid))
    })?;
    let (c, grid) = solved.map_err(|e| err_naming(e, &names))?;
    let out = PyDict::new(py);
    out.set_item("reference", reference.label())?;
    out.set_item("newmark", newmark.label())?;
    out.set_item("comparison", json(py, &c)?)?;
    out.set_item("grid", crate::table::records(py, &grid)?)?;
    Ok(out)
}

/// `converge(model, dts=None, rtols=None, reference_rtol=None)`: every Newmark step of `dts`
/// and every adaptive tolerance of `rtols` measured against one reference, with the fitted
/// orders and efficiency slopes.
#[pyfunction]
#[pyo3(signature = (model, dts=None, rtols=None, reference_rtol=None))]
pub(crate) fn converge<'py>(
    py: Python<'py>,
    model: &Model,
    dts: Option<Vec<f64>>,
    rtols: Option<Vec<f64>>,
    reference_rtol: Option<f64>,
) -> PyResult<Bound<'py, PyDict>> {
    let m = model.state().model;
    let dts = dts.unwrap_or_else(|| convergence::DEFAULT_DTS.to_vec());
    let rtols = rtols.unwrap_or_else(|| convergence::DEFAULT_RTOLS.to_vec());
    let names = [
        ("solver.dt", "dts"),
        ("solver.rtol", "rtols"),
        ("rtol", "reference_rtol"),
    ];
    let reference = m
        .reference(reference_rtol)
        .map_err(|e| err_naming(e, &names))?;
    // The cases' steps and tolerances are named by the lists that gave them.
    let case_names = [
        ("solver.dt", "dts"),
        ("dt", "dts"),
        ("solver.rtol", "rtols"),
        ("rtol", "rtols"),
    ];
    let configurations =
        convergence::configurations(&m, &dts, &rtols).map_err(|e| err_naming(e, &case_names))?;
    let study = interrupt::run(py, move || {
        convergence::converge(&m, reference, &configurations)
    })?
    .map_err(|e| err_naming(e, &names))?;
    let out = PyDict::new(py);
    out.set_item("reference", study.reference_settings.label())?;
    out.set_item("output_dt", study.output_dt)?;
    out.set_item("cases", json(py, &study.cases)?)?;
    out.set_item("slopes", json(py, &study.slopes)?)?;
    Ok(out)
}

/// `fem_check(model, nx=None, ny=None, dt=None, scheme=None)`: the plane-stress finite element
/// model of the body under the model's floor motion, and its comparison with the one-mode model.
#[pyfunction]
#[pyo3(signature = (model, nx=None, ny=None, dt=None, scheme=None))]
pub(crate) fn fem_check<'py>(
    py: Python<'py>,
    model: &Model,
    nx: Option<usize>,
    ny: Option<usize>,
    dt: Option<f64>,
    scheme: Option<String>,
) -> PyResult<Bound<'py, PyDict>> {
    let m = model.state().model;
    let names = [
        ("fem.nx", "nx"),
        ("fem.ny", "ny"),
        ("fem.dt", "dt"),
        ("fem.scheme", "scheme"),
    ];
    let setup = m
        .fem_with(&FemOverrides { nx, ny, scheme, dt })
        .map_err(|e| err_naming(e, &names))?;
    let solving = Arc::clone(&m);
    let done = interrupt::run(py, move || -> flexrock_core::Result<_> {
        let m = &*solving;
        let analysis = fem::analyse(m, &setup)?;
        let sdof = flexrock_core::simulate(m)?;
        let comparison = fem::compare(m, &sdof, &analysis);
        Ok((analysis, comparison))
    })?;
    let (analysis, comparison) = done.map_err(|e| err_naming(e, &names))?;
    let m = &*m;
    let out = PyDict::new(py);
    out.set_item("comparison", json(py, &comparison)?)?;
    out.set_item("peaks", json(py, &fem::peaks(&analysis.result.steps))?)?;
    out.set_item("uplifts", json(py, &analysis.uplifts)?)?;
    out.set_item(
        "history",
        crate::table::records(py, &fem::history_rows(m, &analysis.result.steps))?,
    )?;
    out.set_item(
        "warnings",
        analysis
            .warnings
            .iter()
            .map(|w| w.text("the scheme argument"))
            .collect::<Vec<_>>(),
    )?;
    Ok(out)
}
