//! The criteria study's definition: its periods, moduli and search intervals, the excitations it
//! runs, and the slendernesses it takes.

use std::path::{Path, PathBuf};

use serde::Serialize;

use crate::analysis::sweep::Interval;

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

    pub(super) fn interval(&self) -> Interval {
        match self {
            Excitation::Record(_) => SCALE,
            _ => AMPLITUDE,
        }
    }

    pub(super) fn table(&self) -> toml::Table {
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
