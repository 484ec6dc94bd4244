//! Helpers shared by the integration tests of the core crate (and, through a path module, by
//! those of the command-line crate).
#![allow(dead_code)]
pub mod imports;

use flexrock_core::integrate::solution::Solution;
use flexrock_core::model::{Model, Overrides};
use flexrock_core::physics::automaton::{EventKind, Mode};

/// The reference body of book/src/model.md §8 (the paper's example) with the given excitation,
/// simulation and solver sections (TOML text) appended.
pub fn reference_body(extra: &str) -> String {
    format!(
        "[body]\nheight = 4.0\nwidth = 0.7\ndepth = 1.0\ndensity = 600.0\nyoungs_modulus = 5.0e6\n\
         damping_ratio = 0.05\ngravity = 9.81\n\n{extra}"
    )
}

pub fn model(text: &str) -> Model {
    match Model::from_toml_str(text, &Overrides::default()) {
        Ok(m) => m,
        Err(e) => panic!("test model is invalid: {e}\n{text}"),
    }
}

pub fn solve(text: &str) -> Solution {
    flexrock_core::simulate::simulate(&model(text)).expect("simulation succeeds")
}

/// A fresh, empty directory under cargo's temporary directory for integration tests.
///
/// The tests of a binary run as threads of one process, so a name belongs to the first test
/// (thread) that asks for it: another test asking for the same name panics instead of emptying
/// the directory under the first one's feet. The same test may ask again for a fresh directory.
pub fn scratch_dir(name: &str) -> std::path::PathBuf {
    use std::collections::HashMap;
    use std::sync::{Mutex, OnceLock};
    use std::thread::ThreadId;
    static OWNERS: OnceLock<Mutex<HashMap<String, ThreadId>>> = OnceLock::new();
    let me = std::thread::current();
    let mut owners = OWNERS
        .get_or_init(Mutex::default)
        .lock()
        .unwrap_or_else(|poisoned| poisoned.into_inner());
    let owner = *owners.entry(name.to_string()).or_insert(me.id());
    drop(owners);
    assert!(
        owner == me.id(),
        "scratch directory {name} is already used by another test of this binary; give it a name of its own"
    );
    let dir = std::path::Path::new(env!("CARGO_TARGET_TMPDIR")).join(name);
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).expect("scratch dir");
    dir
}

/// Closed-form response of q'' + 2 h w q' + w^2 q = -beta1 A sin(W t) from rest, W = 2 pi / Tp:
/// the pre-uplift motion under a harmonic floor acceleration.
pub fn damped_oscillator_response(
    omega: f64,
    damping_ratio: f64,
    beta1: f64,
    amplitude: f64,
    period: f64,
) -> impl Fn(f64) -> f64 {
    let (w, h, big_w) = (omega, damping_ratio, 2.0 * std::f64::consts::PI / period);
    let f0 = -beta1 * amplitude;
    let den = (w * w - big_w * big_w).powi(2) + (2.0 * h * w * big_w).powi(2);
    let xs = f0 * (w * w - big_w * big_w) / den;
    let xc = -f0 * 2.0 * h * w * big_w / den;
    let wd = w * (1.0 - h * h).sqrt();
    let e = -xc;
    let g = (h * w * e - big_w * xs) / wd;
    move |t: f64| {
        xs * (big_w * t).sin()
            + xc * (big_w * t).cos()
            + (-h * w * t).exp() * (e * (wd * t).cos() + g * (wd * t).sin())
    }
}

/// The first logged event whose q' does not point across its guard (an uplift or an overturn
/// away from the floor, a landing back towards it), described; None when every event does.
pub fn event_against_its_direction(sol: &Solution) -> Option<String> {
    sol.events.iter().find_map(|e| {
        let side = if e.from == Mode::RockRight || e.to == Mode::RockRight {
            1.0
        } else {
            -1.0
        };
        let outward = side * e.qdot_before;
        let right = match e.kind {
            EventKind::Uplift | EventKind::Overturn => outward > 0.0,
            EventKind::Landing => outward < 0.0,
            // A body alone is never struck nor touched.
            EventKind::Impact
            | EventKind::ContactStart
            | EventKind::ContactEnd
            | EventKind::FrictionStick
            | EventKind::FrictionSlip => false,
        };
        (!right).then(|| format!("{:?} at t = {} with q' = {}", e.kind, e.t, e.qdot_before))
    })
}

/// A file of the repository, by its path from the root: the workspace's root, the directory
/// of Cargo.lock (this module serves the tests of both crates).
pub fn workspace_file(path: &str) -> std::path::PathBuf {
    let manifest = std::path::Path::new(env!("CARGO_MANIFEST_DIR"));
    let root = manifest
        .ancestors()
        .find(|dir| dir.join("Cargo.lock").is_file())
        .unwrap_or(manifest);
    root.join(path)
}

/// mdBook's anchor of a heading's plain text (as a repository host makes it too): lower case,
/// whitespace to hyphens, everything but letters, digits, '-' and '_' dropped.
pub fn anchor_of(text: &str) -> String {
    text.trim()
        .chars()
        .filter_map(|c| {
            if c.is_alphanumeric() || c == '_' || c == '-' {
                Some(c.to_ascii_lowercase())
            } else if c.is_whitespace() {
                Some('-')
            } else {
                None
            }
        })
        .collect()
}

/// The user documentation: README.md and every page of the book (book/src/), as paths from the
/// repository's root, in a fixed order.
pub fn documents() -> Vec<std::path::PathBuf> {
    fn pages(root: &std::path::Path, dir: &std::path::Path, into: &mut Vec<std::path::PathBuf>) {
        let mut entries: Vec<std::path::PathBuf> = std::fs::read_dir(dir)
            .unwrap()
            .map(|e| e.unwrap().path())
            .collect();
        entries.sort();
        for path in entries {
            if path.is_dir() {
                pages(root, &path, into);
            } else if path.extension().is_some_and(|e| e == "md") {
                into.push(path.strip_prefix(root).unwrap().to_path_buf());
            }
        }
    }
    let root = workspace_file("");
    let mut docs = vec![std::path::PathBuf::from("README.md")];
    pages(&root, &root.join("book/src"), &mut docs);
    docs
}

/// Every column of a solved row closes its energy books to `share` of its scale (the largest
/// energy or work it booked); `what` names the case in messages.
pub fn row_books_close(what: &str, solved: &flexrock_core::bodies::row::RowSolution, share: f64) {
    for (i, c) in solved.columns.iter().enumerate() {
        eprintln!(
            "{what}, column {i}: energy residual {} of {} J",
            c.max_energy_residual, c.energy_scale
        );
        assert!(
            c.max_energy_residual <= share * c.energy_scale,
            "{what}, column {i}: energy residual {} of {}",
            c.max_energy_residual,
            c.energy_scale
        );
    }
}

/// How far below zero an open contact's gap may read in these tests, m: a hundred times the
/// rounding at which contacts are found (the exact method's states to about 1e-16 of the
/// displacements, the compliant law's crossings located on its dense output to a few ulps of
/// t), nine orders below the overlaps of faces passing through each other (millimetres to a
/// metre).
pub const OPEN_GAP_TOLERANCE: f64 = 1e-12;

/// The first sample of `solved`'s contact history at which two faces stand overlapping with
/// no contact between them, as a message: an open contact's gap below -[`OPEN_GAP_TOLERANCE`],
/// or parting faces (the compliant law's faces let go at zero force) that do not overlap, that
/// close, or that carry a force.
pub fn faces_passing(solved: &flexrock_core::bodies::row::RowSolution) -> Option<String> {
    use flexrock_core::bodies::row::ContactState;
    solved.contact_history.iter().find_map(|c| {
        let wrong = match c.state {
            ContactState::Open => c.gap < -OPEN_GAP_TOLERANCE,
            ContactState::Parting => {
                !(c.gap < 0.0 && c.closing_velocity < 0.0) || c.force.is_some_and(|p| p != 0.0)
            }
            _ => false,
        };
        wrong.then(|| format!("faces overlapping out of contact: {c:?}"))
    })
}

/// The longest of `stretches` (of contact, of sticking faces), each closed: `span` gives its
/// start and end, s.
pub fn longest<T>(stretches: &[T], span: impl Fn(&T) -> (f64, Option<f64>)) -> Option<&T> {
    let length = |s: &T| {
        let (start, end) = span(s);
        end.expect("a closed stretch") - start
    };
    stretches
        .iter()
        .max_by(|a, b| length(a).total_cmp(&length(b)))
}

/// The seed of a property test's random cases: fixed, so that every machine (CI included) runs
/// the same cases and a pass is not a lottery; `PROPTEST_RNG_SEED` explores others.
pub fn proptest_seed(fixed: u64) -> proptest::test_runner::RngSeed {
    std::env::var("PROPTEST_RNG_SEED")
        .ok()
        .and_then(|s| s.parse().ok())
        .map_or(
            proptest::test_runner::RngSeed::Fixed(fixed),
            proptest::test_runner::RngSeed::Fixed,
        )
}

/// A floor acceleration that is `value` from t = 0 on.
pub struct Constant(pub f64);

impl flexrock_core::floor::FloorMotion for Constant {
    fn acceleration(&self, t: f64) -> f64 {
        if t >= 0.0 {
            self.0
        } else {
            0.0
        }
    }
    fn peak_acceleration(&self) -> f64 {
        self.0.abs()
    }
    fn kind(&self) -> &'static str {
        "constant"
    }
    fn parameters(&self) -> serde_json::Value {
        serde_json::json!({ "kind": "constant", "value": self.0 })
    }
    fn closed_form(&self, _t: f64) -> flexrock_core::floor::ClosedForm {
        flexrock_core::floor::ClosedForm::polynomial(0.0, &[self.0], f64::INFINITY)
    }
}
