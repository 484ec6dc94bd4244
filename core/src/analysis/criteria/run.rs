//! Running the criteria study: the sweep's minimum search over the moduli and periods of each
//! slenderness, with the rigid blocks' minima beside it.

use std::path::Path;

use super::point::Point;
use super::study::{slendernesses, valid_slenderness, Excitation, Study, SLENDERNESS_RULE};
use super::velocity;
use crate::analysis::sweep::{find_min, Axis, Outcome, Request, Status, Sweep};
use crate::bodies::rigid::{RigidBlock, RigidForm};
use crate::error::{Error, Result};
use crate::model::{Model, Overrides};

/// The model text of a point: the base model's `[body]` with `self_weight`, the excitation, the
/// exact method.
fn model_table(body: &toml::Table, self_weight: &str, excitation: &Excitation) -> toml::Table {
    let mut body = body.clone();
    body.insert("self_weight".into(), self_weight.into());
    let mut solver = toml::Table::new();
    solver.insert("method".into(), "exact".into());
    let mut table = toml::Table::new();
    table.insert("body".into(), body.into());
    table.insert("excitation".into(), excitation.table().into());
    table.insert("solver".into(), solver.into());
    table
}

fn list_axis(key: &str, values: &[f64]) -> Result<Axis> {
    let text = values
        .iter()
        .map(|v| crate::base::format::shortest(*v))
        .collect::<Vec<_>>()
        .join(",");
    Axis::parse(&format!("{key}={text}"), Path::new("."))
}

/// Runs the study on the body of the model file `model` (its `[body]` table; its excitation and
/// solver are replaced, and its width for each slenderness of the study). Record paths are
/// taken as given (make them absolute).
pub fn run(model: &Path, study: &Study) -> Result<Vec<Point>> {
    let (_, table) = crate::model::read_model_table(model)?;
    let body = match table.get("body") {
        Some(toml::Value::Table(body)) => body.clone(),
        _ => {
            return Err(Error::invalid(
                "body",
                model.display().to_string(),
                "the model file needs a [body] table",
            ))
        }
    };
    if let Some(bad) = study.slendernesses.iter().find(|s| !valid_slenderness(**s)) {
        return Err(Error::invalid("slenderness", *bad, SLENDERNESS_RULE));
    }
    let base = Model::load(model, &Overrides::default())?;
    let height = base.body.height;
    // Every body of the study must be one the model accepts, in both variants, before anything
    // is computed (its stiffness and mass are the file's, its width the slenderness's).
    for &slenderness in &study.slendernesses {
        let mut body = body.clone();
        body.insert("width".into(), (slenderness * height).into());
        for self_weight in &study.self_weights {
            let period = study.periods.first().copied();
            unit_model(&model_table(&body, self_weight, &Excitation::Sine), period).map_err(
                |e| {
                    Error::invalid(
                        "slenderness",
                        slenderness,
                        &format!(
                            "gives a body of width B = {} m (H = {} m) that the model refuses \
                             (body.self_weight = \"{self_weight}\"): {e}",
                            crate::base::format::shortest(slenderness * height),
                            crate::base::format::shortest(height)
                        ),
                    )
                },
            )?;
        }
    }
    let mut points = Vec::new();
    for slenderness in slendernesses(study, base.body.width / height) {
        let mut body = body.clone();
        let width = if study.slendernesses.is_empty() {
            base.body.width
        } else {
            slenderness * height
        };
        body.insert("width".into(), width.into());
        points.extend(run_body(&body, study, (slenderness, width, height))?);
    }
    Ok(points)
}

/// The study's points of one body (its `[body]` table), of slenderness, width and height
/// `geometry`.
fn run_body(
    body: &toml::Table,
    study: &Study,
    (slenderness, width, height): (f64, f64, f64),
) -> Result<Vec<Point>> {
    let here = Path::new(".");
    let mut points = Vec::new();
    for self_weight in &study.self_weights {
        for excitation in &study.excitations {
            let base = model_table(body, self_weight, excitation);
            let text = toml::to_string(&base)
                .map_err(|e| Error::invalid("body", e.to_string(), "not TOML"))?;
            let is_record = matches!(excitation, Excitation::Record(_));
            let periods: Vec<Option<f64>> = if is_record {
                vec![None]
            } else {
                study.periods.iter().copied().map(Some).collect()
            };
            let mut axes = vec![list_axis("body.youngs_modulus", &study.youngs_moduli)?];
            if !is_record {
                axes.push(list_axis("excitation.period", &study.periods)?);
            }
            let interval = excitation.interval();
            let request = Request {
                axes,
                find_min: Some((excitation.key().to_string(), interval)),
                scan: Some(study.scan),
                tol: Some(study.tol_share * (interval.hi - interval.lo)),
                rigid_form: Some(RigidForm::Full),
                ..Request::default()
            };
            let sweep = Sweep::from_text(&text, here, request, here)?;
            let find = sweep.plan.find_min.clone().expect("a minimum search");
            // Per period: the floor's peaks per unit of the key, and Housner's small-angle block.
            let mut per_period = Vec::new();
            for period in &periods {
                let (t, unit) = unit_model(&base, *period)?;
                let end = unit.floor.quiet_after().unwrap_or(unit.duration);
                let pgv = velocity::peak_velocity(unit.floor.as_ref(), end).ok_or_else(|| {
                    Error::invalid(
                        "excitation",
                        excitation.name(),
                        "has no closed-form peak velocity",
                    )
                })?;
                let pga = unit.floor.peak_acceleration();
                let small_angle = rigid_minimum(&t, &find, RigidForm::SmallAngle)?;
                per_period.push((pga, pgv, small_angle));
            }
            let rows = sweep.rows(0..sweep.points(), &|| {});
            for (index, row) in rows.into_iter().enumerate() {
                let c = sweep.plan.coordinates(index);
                let (ie, ip) = (c[0], if is_record { 0 } else { c[1] });
                let (pga_unit, pgv_unit, small_angle) = per_period[ip];
                let scales = row.scales.unwrap_or_default();
                let (t, p) = (scales.period, scales.p);
                let to_pga = |x: Option<f64>| x.map(|v| v * pga_unit);
                let mut point = Point {
                    self_weight: self_weight.clone(),
                    slenderness,
                    width,
                    height,
                    excitation: excitation.name(),
                    period: periods[ip],
                    youngs_modulus: study.youngs_moduli[ie],
                    flexibility: p.zip(t).map(|(p, t)| p * t),
                    pre_uplift_period: t,
                    p,
                    pga_per_unit: pga_unit,
                    pgv_per_unit: pgv_unit,
                    critical_pga: None,
                    safe_below_pga: None,
                    bands: String::new(),
                    n_bands: 0,
                    rigid_full_pga: None,
                    rigid_small_angle_pga: to_pga(small_angle),
                    rigid_limit_pga: None,
                    reason: row.reason.clone(),
                };
                if row.status != Status::Ok {
                    points.push(point);
                    continue;
                }
                if let Some(Outcome::Minimum(min, rigid)) = &row.outcome {
                    point.critical_pga = to_pga(min.min_overturning);
                    point.safe_below_pga = to_pga(min.safe_below);
                    point.bands = min.bands.clone();
                    point.n_bands = min.n_bands;
                    point.rigid_full_pga = to_pga(rigid.housner);
                    point.rigid_limit_pga = to_pga(rigid.elastic_limit);
                }
                points.push(point);
            }
        }
    }
    Ok(points)
}

/// The model of a point's table at the excitation period `period` (none for a record), with
/// its key searched at 1, and that table.
fn unit_model(base: &toml::Table, period: Option<f64>) -> Result<(toml::Table, Model)> {
    let mut t = base.clone();
    if let (Some(tp), Some(toml::Value::Table(e))) = (period, t.get_mut("excitation")) {
        e.insert("period".into(), tp.into());
    }
    let text =
        toml::to_string(&t).map_err(|e| Error::invalid("body", e.to_string(), "not TOML"))?;
    let model = Model::from_toml_str(&text, &Overrides::default())?;
    Ok((t, model))
}

/// Housner's block of the body's geometry, by `form`, searched as the elastic body is.
fn rigid_minimum(
    table: &toml::Table,
    find: &find_min::FindMin,
    form: RigidForm,
) -> Result<Option<f64>> {
    let at = |value: f64| -> Result<Model> {
        let mut t = table.clone();
        if let Some(toml::Value::Table(e)) = t.get_mut("excitation") {
            let key = find.key.trim_start_matches("excitation.");
            e.insert(key.into(), value.into());
        }
        let text =
            toml::to_string(&t).map_err(|e| Error::invalid("body", e.to_string(), "not TOML"))?;
        Model::from_toml_str(&text, &Overrides::default())
    };
    let trial = |value: f64| -> Result<find_min::Trial> {
        let model = at(value)?;
        let b = &model.body;
        let block = RigidBlock::housner(b.height, b.width, b.gravity)?.with_form(form);
        find_min::Trial::of_rigid(&model, &block)
    };
    match find_min::search(find, trial) {
        Ok(outcome) => Ok(outcome.min_overturning),
        Err((_, e)) => Err(e),
    }
}
