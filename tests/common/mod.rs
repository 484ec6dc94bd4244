//! Helpers shared by the integration tests.
#![allow(dead_code)]

use flexrock::model::{Model, Overrides};
use flexrock::solution::Solution;

/// The reference body of MODEL.md section 8 with the given excitation, simulation and solver
/// sections (TOML text) appended.
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
    flexrock::run::simulate(&model(text)).expect("simulation succeeds")
}

/// A fresh, empty directory under cargo's temporary directory for integration tests.
pub fn scratch_dir(name: &str) -> std::path::PathBuf {
    let dir = std::path::Path::new(env!("CARGO_TARGET_TMPDIR")).join(name);
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).expect("scratch dir");
    dir
}
