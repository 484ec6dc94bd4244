//! Recorded ground motions and pulses through the model file and the command line.
//! Expected numbers were read off the record files with awk, independently of the reader.

use crate::common;

use crate::common::{flexrock, repo};

use std::path::{Path, PathBuf};

use flexrock_core::excitation::{FloorMotion, PulseShape, Ricker, SinePulse};
use flexrock_core::model::{Model, Overrides};

/// A model in `dir` whose excitation is the given record section.
fn record_model(dir: &Path, excitation: &str, simulation: &str) -> PathBuf {
    let text = common::reference_body(&format!(
        "[excitation]\nkind = \"record\"\n{excitation}\n[simulation]\n{simulation}\n\
         [solver]\nrtol = 1e-8\natol = 1e-10\noutput_dt = 0.01\n"
    ));
    let path = dir.join("model.toml");
    std::fs::write(&path, text).unwrap();
    path
}

#[test]
fn el_centro_is_read_as_the_file_says() {
    // awk over the file: 1559 values, dt 0.02, |a| peaks at -0.31882 g at t = 1.01 * 2 = 2.02 s.
    let dir = common::scratch_dir("rec-elcentro");
    std::fs::copy(repo("validation/records/elCentro.AT2"), dir.join("el.AT2")).unwrap();
    let model = Model::load(
        &record_model(&dir, "path = \"el.AT2\"\ntail = 2.0", ""),
        &Overrides::default(),
    )
    .unwrap();
    // Duration defaults to the record length (1558 * 0.02 s) plus the tail.
    assert!((model.duration - (1558.0 * 0.02 + 2.0)).abs() < 1e-9);
    let p = model.floor.parameters();
    assert_eq!(p["points"], 1559);
    assert!((p["dt"].as_f64().unwrap() - 0.02).abs() < 1e-15);
    // Units of g by default for AT2, converted with standard gravity.
    assert!((p["pga"].as_f64().unwrap() - 0.31882 * 9.80665).abs() < 1e-12);
    assert!((p["t_pga"].as_f64().unwrap() - 2.02).abs() < 1e-12);
    // First value 0.00630 g; the last sample (at 31.16 s) is 0.00000; after it, rest.
    assert!((model.floor.acceleration(0.0) - 0.00630 * 9.80665).abs() < 1e-12);
    assert!((model.floor.acceleration(0.01) - 0.5 * (0.00630 + 0.00364) * 9.80665).abs() < 1e-12);
    assert_eq!(model.floor.acceleration(31.17), 0.0);
    assert_eq!(model.floor.breakpoints().len(), 1559);
}

#[test]
fn units_scale_and_trimming() {
    let dir = common::scratch_dir("rec-units");
    std::fs::copy(repo("validation/records/ANLA196.AT2"), dir.join("anl.AT2")).unwrap();
    let load = |excitation: &str| {
        Model::load(
            &record_model(&dir, excitation, "duration = 3.0"),
            &Overrides::default(),
        )
        .unwrap()
    };
    let in_g = load("path = \"anl.AT2\"");
    let in_cm = load("path = \"anl.AT2\"\nunits = \"cm/s2\"");
    let scaled = load("path = \"anl.AT2\"\nscale = 2.5");
    // awk: PGA of ANLA196 is -0.03980445 g at t = 8.44 s.
    let pga = |m: &Model| m.floor.parameters()["pga"].as_f64().unwrap();
    assert!((pga(&in_g) - 0.03980445 * 9.80665).abs() < 1e-12);
    assert!((pga(&in_cm) - 0.03980445 * 0.01).abs() < 1e-15);
    assert!((pga(&scaled) - 2.5 * pga(&in_g)).abs() < 1e-12);
    // Trimming: start at 8.0 s puts the 8.44 s peak at 0.44 s; the first value is sample 400.
    let trimmed = load("path = \"anl.AT2\"\nstart = 8.0\nend = 9.0");
    let p = trimmed.floor.parameters();
    assert!((p["t_pga"].as_f64().unwrap() - 0.44).abs() < 1e-12);
    assert_eq!(p["points"], 51);
}

#[test]
fn csv_round_trip_gives_the_same_solution() {
    let dir = common::scratch_dir("rec-csv");
    let csv = dir.join("el.csv");
    let o = flexrock(&[
        "record",
        "csv",
        repo("validation/records/elCentro.AT2").to_str().unwrap(),
        "--out",
        csv.to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let text = std::fs::read_to_string(&csv).unwrap();
    assert!(text.starts_with("t,acc_m_s2\n0,"));
    assert_eq!(text.lines().count(), 1560);

    std::fs::copy(repo("validation/records/elCentro.AT2"), dir.join("el.AT2")).unwrap();
    let from_at2 = Model::load(
        &record_model(&dir, "path = \"el.AT2\"", "duration = 8.0"),
        &Overrides::default(),
    )
    .unwrap();
    let from_csv = Model::load(
        &record_model(
            &dir,
            "path = \"el.csv\"\nunits = \"m/s2\"",
            "duration = 8.0",
        ),
        &Overrides::default(),
    )
    .unwrap();
    let a = flexrock::commands::run::simulate(&from_at2).unwrap();
    let b = flexrock::commands::run::simulate(&from_csv).unwrap();
    assert!(!a.events.is_empty());
    assert_eq!(a.events.len(), b.events.len());
    for (x, y) in a.events.iter().zip(&b.events) {
        assert!((x.t - y.t).abs() < 1e-9);
    }
    assert!((a.max_q.value - b.max_q.value).abs() < 1e-10);
}

#[test]
fn record_info_prints_what_was_understood() {
    let o = flexrock(&[
        "record",
        "info",
        repo("validation/records/elCentro.AT2").to_str().unwrap(),
    ]);
    assert!(o.status.success());
    let text = String::from_utf8_lossy(&o.stdout);
    for want in [
        "El Centro",
        "points     1559",
        "dt         0.02 s",
        "31.16 s",
        "0.318820 g",
        "3.126556 m/s^2",
        "t = 2.02 s",
    ] {
        assert!(text.contains(want), "{want:?} not in\n{text}");
    }
}

#[test]
fn bad_records_are_refused_with_file_and_line() {
    let dir = common::scratch_dir("rec-bad");
    let original = std::fs::read_to_string(repo("validation/records/elCentro.AT2")).unwrap();
    let cases = [
        // The last value dropped: the count no longer matches NPTS.
        (
            "dropped.AT2",
            original.trim_end().rsplit_once(' ').unwrap().0.to_string(),
            vec!["dropped.AT2", "1559", "1558"],
        ),
        (
            "dt.AT2",
            original.replace("DT= .02000 SEC", "DT= -.02000 SEC"),
            vec!["dt.AT2", "line 4", "dt"],
        ),
        (
            "nan.AT2",
            original.replacen("0.00364", "    NaN", 1),
            vec!["nan.AT2", "line 5", "NaN"],
        ),
        (
            "word.AT2",
            original.replacen("0.00364", "0.0O364", 1),
            vec!["nan.AT2", "line 5", "0.0O364"],
        ),
        ("empty.AT2", String::new(), vec!["empty.AT2", "empty"]),
    ];
    for (name, text, words) in cases {
        std::fs::write(dir.join(name), text).unwrap();
        let model = record_model(&dir, &format!("path = \"{name}\""), "duration = 1.0");
        let out = dir.join(format!("out-{name}"));
        let o = flexrock(&[
            "run",
            model.to_str().unwrap(),
            "--out",
            out.to_str().unwrap(),
        ]);
        let stderr = String::from_utf8_lossy(&o.stderr);
        assert_eq!(o.status.code(), Some(2), "{name}: {stderr}");
        assert!(!out.exists(), "{name}");
        for w in words.iter().filter(|w| !w.ends_with(".AT2") || **w == name) {
            assert!(stderr.contains(w), "{name}: {w:?} not in {stderr}");
        }
        assert!(stderr.contains(name), "{name}: {stderr}");
    }
    // A missing file names the key and the file.
    let model = record_model(&dir, "path = \"nowhere.AT2\"", "duration = 1.0");
    let o = flexrock(&[
        "run",
        model.to_str().unwrap(),
        "--out",
        dir.join("o").to_str().unwrap(),
    ]);
    assert_eq!(o.status.code(), Some(2));
    let stderr = String::from_utf8_lossy(&o.stderr);
    assert!(
        stderr.contains("excitation.path") && stderr.contains("nowhere.AT2"),
        "{stderr}"
    );
    // CSV records need their units.
    std::fs::write(dir.join("a.csv"), "t,acc\n0,0\n0.01,1\n0.02,0\n").unwrap();
    let model = record_model(&dir, "path = \"a.csv\"", "duration = 1.0");
    let o = flexrock(&[
        "run",
        model.to_str().unwrap(),
        "--out",
        dir.join("o").to_str().unwrap(),
    ]);
    assert_eq!(o.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&o.stderr).contains("excitation.units"));
}

#[test]
fn one_column_csv_needs_dt() {
    let dir = common::scratch_dir("rec-onecol");
    std::fs::write(dir.join("a.csv"), "0.0\n0.1\n-0.2\n0.05\n0.0\n").unwrap();
    let m = Model::load(
        &record_model(
            &dir,
            "path = \"a.csv\"\nunits = \"m/s2\"\ndt = 0.05",
            "duration = 1.0",
        ),
        &Overrides::default(),
    )
    .unwrap();
    assert!((m.floor.acceleration(0.075) - (-0.05)).abs() < 1e-15);
    let m = Model::load(
        &record_model(&dir, "path = \"a.csv\"\nunits = \"m/s2\"", "duration = 1.0"),
        &Overrides::default(),
    );
    assert!(m.is_err());
}

#[test]
fn pulse_definitions() {
    // One-sine (antisymmetric) and one-cosine (symmetric) acceleration pulses, then rest.
    let sine = SinePulse::new(2.0, 0.8, 1.0, PulseShape::Antisymmetric);
    assert!((sine.acceleration(0.2) - 2.0).abs() < 1e-15);
    assert!((sine.acceleration(0.6) + 2.0).abs() < 1e-15);
    assert_eq!(sine.acceleration(0.81), 0.0);
    assert_eq!(sine.breakpoints(), &[0.8]);
    let cosine = SinePulse::new(2.0, 0.8, 2.0, PulseShape::Symmetric);
    assert!((cosine.acceleration(0.0) - 2.0).abs() < 1e-15);
    assert!((cosine.acceleration(1.2) + 2.0).abs() < 1e-12);
    assert_eq!(cosine.acceleration(1.61), 0.0);
    // Ricker: peak A at the centre, zeros at tc +- Tp / (pi sqrt 2), minima -2A e^{-3/2} at
    // tc +- Tp sqrt(3/2) / pi.
    let r = Ricker {
        amplitude: 3.0,
        period: 0.5,
        center: 1.0,
    };
    assert!((r.acceleration(1.0) - 3.0).abs() < 1e-15);
    let zero = 0.5 / (std::f64::consts::PI * 2f64.sqrt());
    assert!(r.acceleration(1.0 + zero).abs() < 1e-14);
    let trough = 0.5 * 1.5f64.sqrt() / std::f64::consts::PI;
    assert!((r.acceleration(1.0 - trough) + 6.0 * (-1.5f64).exp()).abs() < 1e-14);
}

#[test]
fn shipped_scenarios_run() {
    for model in ["models/elcentro1940.toml", "models/sine-pulse.toml"] {
        let m = Model::load(&repo(model), &Overrides::default()).unwrap();
        let sol = flexrock::commands::run::simulate(&m).unwrap();
        assert!(!sol.events.is_empty(), "{model} rocks");
        assert!(!sol.overturned, "{model}");
    }
}
