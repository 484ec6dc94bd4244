//! flexrock against an independent implementation of the model (validation/independent/:
//! Python, scipy's DOP853 at rtol 1e-12, cross-checked with Radau). Each case is a model file in
//! tests/data/cases/ with the independent solution beside it; flexrock runs it at the model
//! file's tolerance (rtol = 1e-10) and must give the same event sequence, event times within
//! 1e-6 s and peaks within 1e-7 m.

use crate::common;

use std::path::PathBuf;

use flexrock_core::model::{Model, Overrides};
use serde_json::Value;

fn cases() -> Vec<PathBuf> {
    let dir = common::workspace_file("tests/data/cases");
    let mut cases: Vec<PathBuf> = std::fs::read_dir(&dir)
        .expect("tests/data/cases exists")
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|x| x == "toml"))
        .collect();
    cases.sort();
    cases
}

fn field(v: &Value, key: &str) -> f64 {
    v[key].as_f64().unwrap_or_else(|| panic!("{key} missing"))
}

#[test]
fn bdf_matches_the_independent_solution() {
    matches_the_independent_solution("bdf");
}

#[test]
fn tsit45_matches_the_independent_solution() {
    matches_the_independent_solution("tsit45");
}

fn matches_the_independent_solution(method: &str) {
    let cases = cases();
    assert!(
        cases.len() >= 8,
        "expected at least 8 cases, found {}",
        cases.len()
    );
    let mut report = Vec::new();
    for case in &cases {
        let name = case.file_stem().unwrap().to_string_lossy().into_owned();
        let expected: Value = serde_json::from_str(
            &std::fs::read_to_string(case.with_extension("expected.json")).unwrap(),
        )
        .unwrap();
        let overrides = Overrides {
            method: Some(method.to_string()),
            ..Overrides::default()
        };
        let model = Model::load(case, &overrides).unwrap();
        let sol = flexrock_core::simulate::simulate(&model).unwrap();

        // Constants.
        let c = &expected["constants"];
        let k = &model.constants;
        for (ours, theirs) in [
            (k.generalised_mass, field(c, "Me")),
            (k.generalised_stiffness, field(c, "Ke")),
            (k.uplift_displacement, field(c, "s_n")),
            (k.nu2, field(c, "nu2")),
            (k.beta2, field(c, "beta2")),
            (k.zeta_uplift, field(c, "zetaU")),
            (k.zeta_landing, field(c, "zetaL")),
        ] {
            assert!(
                (ours - theirs).abs() <= 1e-12 * theirs.abs(),
                "{name}: {ours} vs {theirs}"
            );
        }

        // Events: same sequence, times within 1e-6 s, velocities close.
        let events = expected["events"].as_array().unwrap();
        assert_eq!(sol.events.len(), events.len(), "{name}: event count");
        let mut worst_t: f64 = 0.0;
        for (ours, theirs) in sol.events.iter().zip(events) {
            assert_eq!(ours.kind.name(), theirs["kind"].as_str().unwrap(), "{name}");
            assert_eq!(ours.from.name(), theirs["from"].as_str().unwrap(), "{name}");
            assert_eq!(ours.to.name(), theirs["to"].as_str().unwrap(), "{name}");
            let dt = (ours.t - field(theirs, "t")).abs();
            worst_t = worst_t.max(dt);
            assert!(
                dt < 1e-6,
                "{name}: event at {} vs {}",
                ours.t,
                field(theirs, "t")
            );
            assert!((ours.q - field(theirs, "q")).abs() < 1e-12, "{name}");
            assert!(
                (ours.qdot_after - field(theirs, "qdot_after")).abs() < 1e-6,
                "{name}"
            );
        }

        // Peaks.
        let dmax = (sol.max_q.value - field(&expected, "max_q")).abs();
        let dmin = (sol.min_q.value - field(&expected, "min_q")).abs();
        assert!(
            dmax < 1e-7 && dmin < 1e-7,
            "{name}: peaks off by {dmax:e}, {dmin:e}"
        );
        assert!(
            (sol.max_q.t - field(&expected, "t_max_q")).abs() < 1e-4,
            "{name}"
        );
        assert!(
            (sol.min_q.t - field(&expected, "t_min_q")).abs() < 1e-4,
            "{name}"
        );
        assert_eq!(
            sol.overturned,
            expected["overturned"].as_bool().unwrap(),
            "{name}"
        );
        if let Some(t) = expected["t_overturn"].as_f64() {
            assert!((sol.t_overturn.unwrap() - t).abs() < 1e-6, "{name}");
        }

        // Samples of q on the independent solution's grid, from our history (both sampled exactly
        // at those times: the grid is a multiple of output_dt).
        // Every sample of the reference must be matched: a test that matched none would pass.
        let mut worst_q: f64 = 0.0;
        let expected_samples = expected["samples"].as_array().unwrap();
        let mut matched = 0;
        for sample in expected_samples {
            let (t, q) = (sample[0].as_f64().unwrap(), sample[1].as_f64().unwrap());
            if let Some(s) = sol.samples.iter().find(|s| (s.t - t).abs() < 1e-12) {
                worst_q = worst_q.max((s.q - q).abs());
                matched += 1;
            }
        }
        assert!(
            !expected_samples.is_empty(),
            "{name}: the reference has no samples"
        );
        assert_eq!(
            matched,
            expected_samples.len(),
            "{name}: only {matched} of the reference's samples fall on the history's grid"
        );
        assert!(worst_q < 1e-6, "{name}: q off by {worst_q:e}");
        report.push(format!("{method} {name}: {} events, worst event time {worst_t:.1e} s, peaks {dmax:.1e}/{dmin:.1e} m, q {worst_q:.1e} m", sol.events.len()));
    }
    println!("{}", report.join("\n"));
}
