//! Recorded ground motions and pulses through the model file and the command line.
//! Expected numbers were read off the record files with awk, independently of the reader.

use crate::common;

use crate::common::{flexrock, repo};

use std::path::{Path, PathBuf};

use flexrock_core::floor::{FloorMotion, PulseShape, RecordedMotion, Ricker, SinePulse};
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
    let said_g = load("path = \"anl.AT2\"\nunits = \"g\"");
    let scaled = load("path = \"anl.AT2\"\nscale = 2.5");
    // awk: PGA of ANLA196 is -0.03980445 g at t = 8.44 s.
    let pga = |m: &Model| m.floor.parameters()["pga"].as_f64().unwrap();
    assert!((pga(&in_g) - 0.03980445 * 9.80665).abs() < 1e-12);
    assert_eq!(pga(&said_g), pga(&in_g));
    assert!((pga(&scaled) - 2.5 * pga(&in_g)).abs() < 1e-12);
    // The file says g (line 3): another unit is refused, naming both, not rescaled.
    let e = match Model::load(
        &record_model(
            &dir,
            "path = \"anl.AT2\"\nunits = \"cm/s2\"",
            "duration = 3.0",
        ),
        &Overrides::default(),
    ) {
        Ok(_) => panic!("a unit against the file's is refused"),
        Err(e) => e.to_string(),
    };
    assert!(
        e.contains("excitation.units = \"cm/s2\": contradicts the record file")
            && e.contains("anl.AT2, whose header says its values are in g")
            && e.contains("UNITS OF G"),
        "{e}"
    );
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

/// A model reached through a symbolic link reads its record beside the file it links to, as
/// when it is opened where it lies: the same record, the same motion.
#[cfg(unix)]
#[test]
fn a_model_through_a_link_reads_its_record_beside_the_file_it_links_to() {
    let dir = common::scratch_dir("rec-link");
    let link = dir.join("link.toml");
    std::os::unix::fs::symlink(repo("models/elcentro1940.toml"), &link).unwrap();
    let by_link = Model::load(&link, &Overrides::default()).expect("the linked model loads");
    let direct = Model::load(&repo("models/elcentro1940.toml"), &Overrides::default()).unwrap();
    let (a, b) = (
        RecordedMotion::of(by_link.floor.as_ref()),
        RecordedMotion::of(direct.floor.as_ref()),
    );
    assert!(a.is_some(), "the linked model's floor motion is its record");
    assert_eq!(
        a.map(|r| r.values().to_vec()),
        b.map(|r| r.values().to_vec())
    );
    // The command line likewise, from the link's own folder.
    let out = dir.join("out");
    let o = common::flexrock_in(
        &dir,
        &[
            "run",
            "link.toml",
            "--duration",
            "0.5",
            "--out",
            out.to_str().unwrap(),
        ],
    );
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
}

/// A fixture of tests/data/records (synthetic records of known samples, one per format and
/// unit), copied into `dir`.
fn fixture(dir: &Path, name: &str) -> PathBuf {
    let path = dir.join(name);
    std::fs::copy(repo(&format!("tests/data/records/{name}")), &path).unwrap();
    path
}

#[test]
fn every_format_and_unit_gives_the_same_motion() {
    // The fixtures hold 0, 0.125, -0.25, 0.5, -0.375, 0.0625 in their unit (g, or cm/s^2 as 100
    // times those): the floor's peak is 0.5 g, or 0.5 m/s^2 in cm/s^2 and m/s^2.
    let dir = common::scratch_dir("rec-formats");
    for (name, peak) in [
        ("nga-g.AT2", 0.5 * 9.80665),
        ("nga-cmss.AT2", 0.5),
        ("nga-mss.AT2", 0.5),
        ("cosmos-cmss.V2", 0.5),
        ("cosmos-g.V1", 0.5 * 9.80665),
        ("esm-cmss.ASC", 0.5),
        ("text-g.txt", 0.5 * 9.80665),
    ] {
        fixture(&dir, name);
        let m = Model::load(
            &record_model(&dir, &format!("path = \"{name}\""), ""),
            &Overrides::default(),
        )
        .unwrap_or_else(|e| panic!("{name}: {e}"));
        assert_eq!(m.floor.peak_acceleration(), peak, "{name}");
        assert!((m.floor.acceleration(0.015) - 0.5 * (0.125 - 0.25) * peak / 0.5).abs() < 1e-15);
        assert_eq!(m.duration, 0.05, "{name}: the record's own length");
    }
}

#[test]
fn velocity_files_and_unknown_units_are_refused_by_name() {
    let dir = common::scratch_dir("rec-refused");
    for (name, words) in [
        (
            "nga-velocity.VT2",
            vec!["line 3", "velocity time series", "CM/S"],
        ),
        (
            "nga-displacement.DT2",
            vec!["line 3", "displacement time series"],
        ),
        ("cosmos-velocity.V2", vec!["line 1", "velocity time series"]),
        ("esm-velocity.ASC", vec!["velocity time series", "VELOCITY"]),
        (
            "furlongs.AT2",
            vec!["line 3", "unknown unit", "FURLONG/FORTNIGHT"],
        ),
    ] {
        let path = fixture(&dir, name);
        for args in [
            vec!["record", "info", path.to_str().unwrap()],
            vec!["record", "intensity", path.to_str().unwrap()],
        ] {
            let o = flexrock(&args);
            let stderr = String::from_utf8_lossy(&o.stderr);
            assert_eq!(o.status.code(), Some(2), "{name}: {stderr}");
            assert!(o.stdout.is_empty());
            for w in words.iter().chain(&[name]) {
                assert!(stderr.contains(w), "{name}: {w:?} not in {stderr}");
            }
        }
    }
    // A header silent on its units needs them given.
    let path = fixture(&dir, "no-units.AT2");
    let o = flexrock(&["record", "info", path.to_str().unwrap()]);
    assert_eq!(o.status.code(), Some(2));
    let stderr = String::from_utf8_lossy(&o.stderr);
    assert!(
        stderr.contains("--units = (missing)") && stderr.contains("no-units.AT2"),
        "{stderr}"
    );
    let o = flexrock(&["record", "info", path.to_str().unwrap(), "--units", "cm/s2"]);
    assert!(o.status.success());
    assert!(String::from_utf8_lossy(&o.stdout).contains("as given (the file does not say)"));
}

#[test]
fn record_info_prints_the_metadata_and_the_measures() {
    let dir = common::scratch_dir("rec-info-meta");
    let path = fixture(&dir, "esm-cmss.ASC");
    let o = flexrock(&["record", "info", path.to_str().unwrap(), "--period", "1"]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let text = String::from_utf8_lossy(&o.stdout);
    for want in [
        "format     esm",
        "event      L'AQUILA MAINSHOCK (SYNTHETIC)",
        "date       2009-04-06",
        "station    IT.AQV",
        "component  HNE",
        "magnitude  6.1",
        "distance   4.9 km",
        "units      cm/s2 (1 cm/s2 = 0.01 m/s^2), as the file says (line 29 \"UNITS: cm/s^2\")",
        "PGA        0.050986 g = 0.500000 m/s^2 at t = 0.03 s",
        "PGV        ",
        "Arias      ",
        "CAV        ",
        "at T = 1 s, 5 % damping",
    ] {
        assert!(text.contains(want), "{want:?} not in\n{text}");
    }
}

/// The measures of the shipped records against an independent calculation
/// (validation/intensity/reference.py: the closed-form integrals and the Nigam-Jennings
/// solution, its peaks between samples found by bisection), committed in
/// tests/data/records/intensity_reference.csv.
#[test]
fn intensity_measures_agree_with_an_independent_calculation() {
    let text = std::fs::read_to_string(repo("tests/data/records/intensity_reference.csv")).unwrap();
    let mut rows: Vec<Vec<String>> = text
        .lines()
        .skip(1)
        .map(|l| l.split(',').map(String::from).collect())
        .collect();
    rows.sort();
    let field = |csv: &str, column: &str| -> Vec<f64> {
        let mut lines = csv.lines();
        let header: Vec<&str> = lines.next().unwrap().split(',').collect();
        let at = header.iter().position(|c| *c == column).unwrap();
        lines
            .map(|l| l.split(',').nth(at).unwrap().parse().unwrap())
            .collect()
    };
    let close = |name: &str, what: &str, got: f64, want: f64, tol: f64| {
        assert!(
            (got - want).abs() <= tol * want.abs(),
            "{name} {what}: {got} against {want}"
        );
    };
    let g = 9.80665;
    let mut checked = 0;
    for group in rows.chunk_by(|a, b| a[0] == b[0] && a[2] == b[2]) {
        let (name, damping) = (&group[0][0], &group[0][2]);
        let path = repo(&format!("validation/records/{name}"));
        let o = flexrock(&["record", "intensity", path.to_str().unwrap()]);
        assert!(o.status.success());
        let measures = String::from_utf8_lossy(&o.stdout).to_string();
        let periods: Vec<&str> = group.iter().map(|r| r[1].as_str()).collect();
        let o = flexrock(&[
            "record",
            "spectrum",
            path.to_str().unwrap(),
            "--periods",
            &periods.join(","),
            "--damping",
            damping,
        ]);
        assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
        let spectrum = String::from_utf8_lossy(&o.stdout).to_string();
        let want = |r: &Vec<String>, i: usize| r[i].parse::<f64>().unwrap();
        let r = &group[0];
        close(
            name,
            "PGA",
            field(&measures, "pga_g")[0] * g,
            want(r, 3),
            1e-9,
        );
        close(
            name,
            "PGV",
            field(&measures, "pgv_m_s")[0],
            want(r, 4),
            1e-9,
        );
        close(name, "PGD", field(&measures, "pgd_m")[0], want(r, 5), 1e-9);
        close(
            name,
            "Arias",
            field(&measures, "arias_m_s")[0],
            want(r, 6),
            1e-9,
        );
        close(
            name,
            "CAV",
            field(&measures, "cav_m_s")[0],
            want(r, 7),
            1e-9,
        );
        let sa = field(&spectrum, "sa_m_s2");
        let sa_samples = field(&spectrum, "sa_at_samples_g");
        for (i, r) in group.iter().enumerate() {
            let what = format!("Sa(T = {}, zeta = {damping})", r[1]);
            close(name, &what, sa[i], want(r, 8), 1e-6);
            close(name, &what, sa_samples[i] * g, want(r, 9), 1e-9);
            checked += 1;
        }
    }
    assert_eq!(checked, 50);
}

#[test]
fn a_sweep_over_records_and_the_amplitude_is_refused_before_it_runs() {
    let dir = common::scratch_dir("rec-sweep-amplitude");
    let out = dir.join("out");
    let o = flexrock(&[
        "sweep",
        repo("models/elcentro1940.toml").to_str().unwrap(),
        "--out",
        out.to_str().unwrap(),
        "--vary",
        &format!(
            "excitation.path={}",
            repo("validation/records/*.AT2").display()
        ),
        "--vary",
        "excitation.amplitude=1:5:1",
    ]);
    let stderr = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(2), "{stderr}");
    assert!(!out.exists());
    assert!(
        stderr.contains("--vary excitation.amplitude = 1,2,3,4,5: cannot be swept")
            && stderr.contains("kind = \"record\" takes path, format, units, scale")
            && stderr.contains("a record's intensity is swept with excitation.scale"),
        "{stderr}"
    );
    // The sweep's help says what it runs an IDA against.
    let help = String::from_utf8_lossy(&flexrock(&["sweep", "--help"]).stdout).to_string();
    assert!(!help.contains("excitation.amplitude an"), "{help}");
}

#[test]
fn a_sweep_over_records_carries_their_metadata_and_intensity_measures() {
    let dir = common::scratch_dir("rec-sweep-measures");
    let out = dir.join("out");
    let records = ["ANLA196.AT2", "PBFEAS.AT2"].map(|n| repo(&format!("validation/records/{n}")));
    let o = flexrock(&[
        "sweep",
        repo("models/elcentro1940.toml").to_str().unwrap(),
        "--out",
        out.to_str().unwrap(),
        "--vary",
        &format!(
            "excitation.path={},{}",
            records[0].display(),
            records[1].display()
        ),
        "--vary",
        "excitation.scale=1,2",
        "--quiet",
    ]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let text = std::fs::read_to_string(out.join("sweep.csv")).unwrap();
    let mut lines = text.lines();
    let header: Vec<&str> = lines.next().unwrap().split(',').collect();
    let rows: Vec<Vec<&str>> = lines.map(|l| l.split(',').collect()).collect();
    let at = |name: &str| header.iter().position(|c| *c == name).unwrap();
    assert_eq!(
        header[at("event")..],
        [
            "event",
            "date",
            "station",
            "component",
            "magnitude",
            "distance_km",
            "pga_g",
            "pgv_m_s",
            "pgd_m",
            "arias_m_s",
            "cav_m_s",
            "sa_g"
        ]
    );
    // ANLA196's line 2: BORAH PEAK EQ, 10/28/83, 14:06, ANL-767 REACTOR PLANT (BASEMENT), 196
    // (its station holds no comma).
    assert_eq!(rows[0][at("event")], "BORAH PEAK EQ");
    assert_eq!(rows[0][at("component")], "196");
    assert_eq!(rows[2][at("station")], "PBF");
    assert_eq!(rows[0][at("magnitude")], "");
    // The measures are the scaled motion's: PGA 0.03980445 g (awk), twice at scale 2; Sa
    // and PGV in proportion.
    let number = |r: usize, c: &str| rows[r][at(c)].parse::<f64>().unwrap();
    assert!((number(0, "pga_g") - 0.03980445).abs() < 1e-15);
    for c in ["pga_g", "pgv_m_s", "pgd_m", "cav_m_s", "sa_g"] {
        assert!(
            (number(1, c) - 2.0 * number(0, c)).abs() <= 1e-12 * number(1, c),
            "{c}"
        );
    }
    assert!((number(1, "arias_m_s") - 4.0 * number(0, "arias_m_s")).abs() < 1e-12);
}

#[test]
fn a_run_on_a_record_says_its_record_and_a_duration_that_cuts_it() {
    let dir = common::scratch_dir("rec-summary");
    let out = dir.join("out");
    let o = flexrock(&[
        "run",
        repo("models/elcentro1940.toml").to_str().unwrap(),
        "--duration",
        "10",
        "--out",
        out.to_str().unwrap(),
    ]);
    assert!(o.status.success());
    let stderr = String::from_utf8_lossy(&o.stderr);
    assert!(
        stderr.contains(
            "warning: the run lasts 10 s (simulation.duration) but the record lasts 31.16 s: its \
             last 21.16 s are not applied"
        ),
        "{stderr}"
    );
    let summary: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("summary.json")).unwrap()).unwrap();
    let excitation = &summary["excitation"];
    assert_eq!(excitation["record"]["format"], "peer-at2");
    assert_eq!(excitation["record"]["units"], "g");
    let intensity = &excitation["intensity"];
    assert!((intensity["pga"].as_f64().unwrap() - 0.31882 * 9.80665).abs() < 1e-12);
    // Sa at the body's pre-uplift period T, 5 %.
    assert_eq!(intensity["sa"]["period"], summary["T"]);
    assert_eq!(intensity["sa"]["damping"], 0.05);
    assert!(summary["warnings"][0]
        .as_str()
        .unwrap()
        .contains("the record lasts 31.16 s"));
    // The whole record: no warning.
    let o = flexrock(&[
        "run",
        repo("models/elcentro1940.toml").to_str().unwrap(),
        "--out",
        dir.join("whole").to_str().unwrap(),
    ]);
    assert!(!String::from_utf8_lossy(&o.stderr).contains("record lasts"));
}

#[test]
fn a_suite_is_a_directory_or_a_list_file() {
    use flexrock_core::floor::record::suite::read_suite;
    let d = common::scratch_dir("rec-suite");
    for name in [
        "b.AT2",
        "a.csv",
        "PROVENANCE.md",
        "c.list",
        "a-up.AT2",
        "b c.AT2",
    ] {
        std::fs::write(d.join(name), "x").unwrap();
    }
    // A directory: its record files by name, not its other files.
    let suite = read_suite(&d).unwrap();
    let names: Vec<_> = suite
        .entries
        .iter()
        .map(|e| e.path.file_name().unwrap().to_string_lossy().into_owned())
        .collect();
    assert_eq!(names, ["a-up.AT2", "a.csv", "b c.AT2", "b.AT2"]);
    assert!(suite
        .entries
        .iter()
        .all(|e| e.scale == 1.0 && e.line.is_none()));
    let empty = d.join("empty");
    std::fs::create_dir_all(&empty).unwrap();
    let e = read_suite(&empty).unwrap_err().to_string();
    assert!(e.contains("holds no record file"), "{e}");
    // A list file: paths relative to it, a scale and a vertical component each.
    let list = d.join("suite.list");
    std::fs::write(
        &list,
        "# the suite\na.csv scale=1.5 vertical=a-up.AT2\n\n\"b c.AT2\"   # spaces\n",
    )
    .unwrap();
    let suite = read_suite(&list).unwrap();
    assert_eq!(suite.entries.len(), 2);
    assert_eq!(suite.entries[0].path, d.join("a.csv"));
    assert_eq!(suite.entries[0].scale, 1.5);
    assert_eq!(suite.entries[0].vertical, Some(d.join("a-up.AT2")));
    assert_eq!(suite.entries[0].line, Some(2));
    assert_eq!(suite.entries[1].path, d.join("b c.AT2"));
    let refused = |text: &str| {
        std::fs::write(&list, text).unwrap();
        read_suite(&list).unwrap_err().to_string()
    };
    let e = refused("a.csv scale=-1\n");
    assert!(
        e.contains("suite.list line 1: scale = \"-1\": must be a finite number > 0"),
        "{e}"
    );
    let e = refused("a.csv scale=2 scale=3\n");
    assert!(e.contains("line 1: scale is given twice"), "{e}");
    let e = refused("\n\nmissing.AT2\n");
    assert!(
        e.contains("line 3:") && e.contains("missing.AT2 is not a record file"),
        "{e}"
    );
    let e = refused("a.csv factor=2\n");
    assert!(
        e.contains("expected PATH [scale=FACTOR] [vertical=PATH], found \"factor=2\""),
        "{e}"
    );
    let e = refused("\"a.csv\n");
    assert!(e.contains("line 1: a double quote is not closed"), "{e}");
    let e = refused("# nothing\n");
    assert!(e.contains("names no record"), "{e}");
}

#[test]
fn the_shipped_suite_lists_every_shipped_record() {
    let o = flexrock(&[
        "record",
        "intensity",
        repo("validation/records/records.list").to_str().unwrap(),
        "--period",
        "1.55",
    ]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let text = String::from_utf8_lossy(&o.stdout).to_string();
    let mut names: Vec<String> = text
        .lines()
        .skip(1)
        .map(|l| {
            let file = l.split(',').next().unwrap();
            Path::new(file)
                .file_name()
                .unwrap()
                .to_string_lossy()
                .into_owned()
        })
        .collect();
    names.sort();
    let mut shipped: Vec<String> = std::fs::read_dir(repo("validation/records"))
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .filter(|n| n.ends_with(".AT2"))
        .collect();
    shipped.sort();
    assert_eq!(names, shipped);
    // The directory is the same suite.
    let o = flexrock(&[
        "record",
        "intensity",
        repo("validation/records").to_str().unwrap(),
    ]);
    assert!(o.status.success());
    assert_eq!(String::from_utf8_lossy(&o.stdout).lines().count(), 6);
}
