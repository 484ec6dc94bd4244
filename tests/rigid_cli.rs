//! `flexrock rigid`: Housner's block alone on the model's floor, horizontal and vertical.

use crate::common::{flexrock, refused, refused_with, scratch_dir};

const MODEL: &str = r#"
[body]
height = 2.0
width = 0.4
mass = 1000.0
period = 0.05

[excitation]
kind = "sine-pulse"
amplitude = 4.0
period = 0.5
tail = 2.0

[excitation.vertical]
ratio = 0.5
"#;

#[test]
fn the_block_writes_its_events_and_summary() {
    let dir = scratch_dir("rigid-cli-writes");
    let model = dir.join("block.toml");
    std::fs::write(&model, MODEL).unwrap();
    let out = dir.join("out");
    let o = flexrock(&[
        "rigid",
        model.to_str().unwrap(),
        "--form",
        "full",
        "--out",
        out.to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let summary: serde_json::Value =
        serde_json::from_slice(&std::fs::read(out.join("summary.json")).unwrap()).unwrap();
    // Uplift when 4 sin(w t) = (g B/H)(1 + 2 sin(w t)/g), sin(w t) = 1.962/3.6, w = 4 pi.
    let t_up = (1.962_f64 / 3.6).asin() / (4.0 * std::f64::consts::PI);
    let found = summary["first_uplift_s"].as_f64().unwrap();
    assert!((found - t_up).abs() < 1e-12, "{found} against {t_up}");
    assert_eq!(summary["block"]["equation"], "full");
    assert_eq!(summary["vertical_excitation"]["ratio"], 0.5);
    let events = std::fs::read_to_string(out.join("events.csv")).unwrap();
    assert!(events.starts_with("t_s,event,q_m,qdot_before_m_s,qdot_after_m_s,to\n"));
    assert!(events
        .lines()
        .nth(1)
        .unwrap()
        .contains(",uplift,0,0,0,rock-left"));
}

#[test]
fn a_floor_falling_faster_than_gravity_is_refused_before_anything_is_written() {
    let text = refused_with(
        "rigid",
        "falls",
        MODEL,
        &["--set", "excitation.vertical.ratio=3"],
    );
    assert!(
        text.contains("excitation.vertical") && text.contains("falls faster than gravity"),
        "{text}"
    );
    // The elastic body says it does not take vertical motion yet, and writes nothing.
    let text = refused("run", "elastic", MODEL);
    assert!(
        text.contains("excitation.vertical") && text.contains("rigid"),
        "{text}"
    );
    let text = refused_with("rigid", "form", MODEL, &["--form", "ful"]);
    assert!(text.contains("--form") && text.contains("full"), "{text}");
    let text = refused_with("rigid", "restitution", MODEL, &["--restitution", "1.5"]);
    assert!(text.contains("--restitution"), "{text}");
}
