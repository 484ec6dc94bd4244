//! Overturning criteria of the elastic body, beside the rigid block's: the smallest floor peak
//! acceleration (and the peak velocity of the same floor motion) that overturns bodies of one
//! height, a few slendernesses B/H and a range of flexibilities, under sines of a few cycles, one-sine and one-cosine
//! pulses across period, and records scaled; with Housner's rigid block of the same geometry
//! (full and small-angle equations) and the elastic model's own rigid limit at the same points.
//!
//! - Ishiyama's (1982) acceleration and velocity conditions for rigid bodies come from
//!   [`crate::physics::rigid_criteria`], their one home;
//! - [`velocity`]: the peak floor velocity of a motion, in closed form;
//! - [`continuity`]: the elastic body against the rigid block, decade by decade of E;
//! - [`fit`]: a closed-form criterion fitted to the points, its error on each.
//!
//! Every minimum is the sweep's search ([`crate::analysis::sweep::find_min`]: a scan of the interval,
//! then a bisection of the first transition to overturning, with the bands above it that leave
//! the body standing reported), run by [`crate::Sweep`] over the Young's moduli and the
//! excitation periods, with the exact method.
//!
//! # The flexibility parameter
//!
//! phi = p T, the body's pre-uplift period T (s) over the rocking time scale 1/p of the rigid
//! block of the same geometry, p = sqrt(3 g/(4 R)), R the half-diagonal. The rigid block's
//! overturning is governed by p and the excitation alone (Housner 1963; Zhang and Makris 2001
//! plot the critical acceleration against omega_p/p); flexibility adds one time scale, T, and
//! phi says how it compares with p's: phi -> 0 is the rigid block, and a body whose elastic
//! vibration is slow against its rocking (phi of order one and above) rocks with its bending
//! lagging behind. phi varies as E^(-1/2) (T ~ sqrt(M H^3/(E I))), so a decade of E is a factor
//! sqrt(10) in phi. The paper's body (H = 4 m, B = 0.7 m, E = 5 MPa, T = 1.55 s, p = 1.904 rad/s)
//! has phi = 2.95.

pub mod continuity;
pub mod fit;
pub mod velocity;

use std::path::{Path, PathBuf};

use serde::Serialize;

use crate::analysis::sweep::{find_min, Axis, Interval, Outcome, Request, Status, Sweep};
use crate::bodies::rigid::{RigidBlock, RigidForm};
use crate::error::{Error, Result};
use crate::model::Model;
use crate::model::Overrides;

/// The excitations' periods, s: sines and pulses of 0.25 to 2 Hz.
pub const PERIODS: [f64; 4] = [0.5, 1.0, 2.0, 4.0];

/// The Young's moduli, Pa: one a decade from near-rigid to the paper's body, and one beyond.
pub const YOUNGS_MODULI: [f64; 6] = [5e10, 5e9, 5e8, 5e7, 5e6, 2.5e6];

/// Cycles of the sines (Ishiyama's tests shook the floor for several cycles).
pub const SINE_CYCLES: f64 = 3.0;

/// Free rocking after the floor stops, s.
pub const TAIL: f64 = 5.0;

/// The interval of the peak acceleration searched for the sines and pulses, m/s^2.
pub const AMPLITUDE: Interval = Interval { lo: 0.5, hi: 40.0 };

/// The interval of a record's scale searched.
pub const SCALE: Interval = Interval { lo: 0.1, hi: 20.0 };

/// Scanned values of each search.
pub const SCAN: usize = 40;

/// The bisection's tolerance, as a share of the interval.
pub const TOL_SHARE: f64 = 1e-5;

/// A family of floor motions.
#[derive(Debug, Clone, PartialEq, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum Excitation {
    /// [`SINE_CYCLES`] cycles of a = A sin(2 pi t/Tp).
    Sine,
    /// One cycle of a = A sin(2 pi t/Tp): the one-sine pulse.
    OneSine,
    /// One cycle of a = A cos(2 pi t/Tp): the symmetric one-cosine pulse.
    OneCosine,
    /// A record (PEER AT2, in g), scaled.
    Record(PathBuf),
}

impl Excitation {
    /// The name in criteria.csv.
    pub fn name(&self) -> String {
        match self {
            Excitation::Sine => format!("sine-{SINE_CYCLES}-cycles"),
            Excitation::OneSine => "one-sine".into(),
            Excitation::OneCosine => "one-cosine".into(),
            Excitation::Record(path) => format!("record {}", record_name(path)),
        }
    }

    /// The model key searched.
    pub fn key(&self) -> &'static str {
        match self {
            Excitation::Record(_) => "excitation.scale",
            _ => "excitation.amplitude",
        }
    }

    fn interval(&self) -> Interval {
        match self {
            Excitation::Record(_) => SCALE,
            _ => AMPLITUDE,
        }
    }

    fn table(&self) -> toml::Table {
        let mut t = toml::Table::new();
        let (cycles, shape) = match self {
            Excitation::Record(path) => {
                t.insert("kind".into(), "record".into());
                t.insert("path".into(), path.to_string_lossy().into_owned().into());
                t.insert("format".into(), "peer-at2".into());
                t.insert("units".into(), "g".into());
                t.insert("scale".into(), 1.0.into());
                t.insert("tail".into(), TAIL.into());
                return t;
            }
            Excitation::Sine => (SINE_CYCLES, "antisymmetric"),
            Excitation::OneSine => (1.0, "antisymmetric"),
            Excitation::OneCosine => (1.0, "symmetric"),
        };
        t.insert("kind".into(), "sine-pulse".into());
        t.insert("amplitude".into(), 1.0.into());
        t.insert("period".into(), 1.0.into());
        t.insert("cycles".into(), cycles.into());
        t.insert("shape".into(), shape.into());
        t.insert("tail".into(), TAIL.into());
        t
    }
}

/// A record's file name without its extension.
pub fn record_name(path: &Path) -> String {
    path.file_stem()
        .map(|s| s.to_string_lossy().into_owned())
        .unwrap_or_default()
}

/// What to compute.
#[derive(Debug, Clone, Serialize)]
pub struct Study {
    /// Slendernesses B/H: the model's body with its width set to B/H times its height (every
    /// other property kept); empty for the model's own width only.
    pub slendernesses: Vec<f64>,
    /// Young's moduli, Pa.
    pub youngs_moduli: Vec<f64>,
    /// `body.self_weight` variants: "paper", "consistent".
    pub self_weights: Vec<String>,
    /// Excitation periods of the sines and pulses, s.
    pub periods: Vec<f64>,
    /// The floor motions.
    pub excitations: Vec<Excitation>,
    /// Scanned values of each search.
    pub scan: usize,
    /// Bisection tolerance as a share of the interval.
    pub tol_share: f64,
}

impl Study {
    /// The standard study: the slendernesses given (none: the model's own width only),
    /// [`YOUNGS_MODULI`], both self-weight variants, [`PERIODS`], sines, one-sine and one-cosine
    /// pulses, and the given records.
    pub fn standard(records: Vec<PathBuf>, slendernesses: Vec<f64>) -> Study {
        let mut excitations = vec![Excitation::Sine, Excitation::OneSine, Excitation::OneCosine];
        excitations.extend(records.into_iter().map(Excitation::Record));
        Study {
            slendernesses,
            youngs_moduli: YOUNGS_MODULI.to_vec(),
            self_weights: vec!["paper".into(), "consistent".into()],
            periods: PERIODS.to_vec(),
            excitations,
            scan: SCAN,
            tol_share: TOL_SHARE,
        }
    }
}

/// One body under one floor motion: the elastic body's and the rigid blocks' critical values.
#[derive(Debug, Clone, Serialize)]
pub struct Point {
    /// `body.self_weight`.
    pub self_weight: String,
    /// B/H.
    pub slenderness: f64,
    /// B, m.
    pub width: f64,
    /// H, m.
    pub height: f64,
    /// The excitation's family ([`Excitation::name`]).
    pub excitation: String,
    /// Tp, s (sines and pulses).
    pub period: Option<f64>,
    /// E, Pa.
    pub youngs_modulus: f64,
    /// phi = p T; None for a body that could not be run (`reason` says why).
    pub flexibility: Option<f64>,
    /// T, s; None likewise.
    pub pre_uplift_period: Option<f64>,
    /// p, rad/s; None likewise.
    pub p: Option<f64>,
    /// The floor's peak acceleration per unit of the searched key (1 for the pulses).
    pub pga_per_unit: f64,
    /// The floor's peak velocity per unit of the searched key, m/s.
    pub pgv_per_unit: f64,
    /// The smallest overturning peak acceleration of the elastic body, m/s^2.
    pub critical_pga: Option<f64>,
    /// The largest value below it found to leave the body standing, m/s^2.
    pub safe_below_pga: Option<f64>,
    /// The scanned bands that overturned, in the searched key's units.
    pub bands: String,
    /// Number of such bands.
    pub n_bands: usize,
    /// Housner's block, full equation, m/s^2.
    pub rigid_full_pga: Option<f64>,
    /// Housner's block, small-angle equation, m/s^2.
    pub rigid_small_angle_pga: Option<f64>,
    /// The elastic model's rigid limit (small-angle, uplift at 1.1226 g B/H), m/s^2.
    pub rigid_limit_pga: Option<f64>,
    /// Why the point has no values (empty when it has).
    pub reason: String,
}

impl Point {
    /// The critical peak velocity of the same motion, m/s.
    pub fn critical_pgv(&self) -> Option<f64> {
        self.critical_pga
            .map(|a| a / self.pga_per_unit * self.pgv_per_unit)
    }

    /// A rigid value's peak velocity, m/s.
    pub fn pgv_of(&self, pga: Option<f64>) -> Option<f64> {
        pga.map(|a| a / self.pga_per_unit * self.pgv_per_unit)
    }

    /// True for a floor motion whose acceleration starts from zero (no jump at t = 0): the
    /// sines and one-sine pulses. The one-cosine pulse starts at its peak, a step that sets an
    /// elastic body vibrating however stiff it is; records are left out as well, since their
    /// first overturning scale can jump between narrow bands from one body to the next.
    pub fn is_smooth(&self) -> bool {
        self.excitation == Excitation::Sine.name() || self.excitation == Excitation::OneSine.name()
    }

    /// True when the body overturned at the bottom of the searched interval (its first scanned
    /// value): the critical value is then only an upper bound of the true one.
    pub fn at_interval_bottom(&self) -> bool {
        self.critical_pga.is_some() && self.safe_below_pga.is_none()
    }

    /// critical / reference - 1, when both are known.
    pub fn relative_difference(&self, reference: Option<f64>) -> Option<f64> {
        Some(self.critical_pga? / reference? - 1.0)
    }
}

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

/// The rule a slenderness B/H of the study must follow.
pub const SLENDERNESS_RULE: &str =
    "a slenderness B/H must be above 0 and below 1 (the model is for bodies narrower than tall)";

/// Whether `s` is a slenderness the study accepts ([`SLENDERNESS_RULE`]).
pub fn valid_slenderness(s: f64) -> bool {
    s > 0.0 && s < 1.0
}

/// The slendernesses a study runs: its list, sorted and without repeats, or the model's own.
pub fn slendernesses(study: &Study, own: f64) -> Vec<f64> {
    let mut list = if study.slendernesses.is_empty() {
        vec![own]
    } else {
        study.slendernesses.clone()
    };
    list.sort_by(f64::total_cmp);
    list.dedup();
    list
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
        let out =
            crate::bodies::rigid::simulate_block(&block, model.floor.as_ref(), model.duration)?;
        Ok(find_min::Trial {
            overturned: out.overturned,
            t_overturn: out.t_overturn,
            steps: 0,
            rhs_evaluations: 0,
        })
    };
    match find_min::search(find, trial) {
        Ok(outcome) => Ok(outcome.min_overturning),
        Err((_, e)) => Err(e),
    }
}
