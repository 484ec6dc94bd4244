//! Hostile input and output (issue 9): a full disk or a closed pipe on standard output, special
//! files as outputs and records, a failed write in the middle of a set, temporaries of a killed
//! run, values that must be refused before anything is computed, sizes beyond the limits, and
//! the program against its documents.

mod common;

use common::{flexrock, reference_model, scratch_dir};

fn stderr_of(o: &std::process::Output) -> String {
    String::from_utf8_lossy(&o.stderr).into_owned()
}

// --- 7. the program and its documents ------------------------------------------------------

#[test]
fn numbers_and_counts_read_as_people_write_them() {
    // 4399 samples at 0.01 s: (n - 1) dt = 43.980000000000004 in floating point.
    let dir = scratch_dir("hostile-readable");
    let mut text = String::from("title\nline 2\nline 3\nNPTS=  4399, DT= .01000 SEC\n");
    for k in 0..4399 {
        text.push_str(&format!("{:10.5}", 0.001 * (k % 7) as f64));
        if k % 8 == 7 {
            text.push('\n');
        }
    }
    let record = dir.join("long.AT2");
    std::fs::write(&record, text).unwrap();
    let o = flexrock(&["record", "info", record.to_str().unwrap()]);
    let stdout = String::from_utf8_lossy(&o.stdout);
    assert!(stdout.contains("duration   43.98 s"), "{stdout}");

    // fem --compare: the uplift counts are counts.
    let o = flexrock(&[
        "fem",
        reference_model().to_str().unwrap(),
        "--compare",
        "--out",
        dir.join("fem").to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{}", stderr_of(&o));
    let stdout = String::from_utf8_lossy(&o.stdout);
    let uplifts = stdout
        .lines()
        .find(|l| l.trim_start().starts_with("uplifts"))
        .unwrap();
    assert!(!uplifts.contains('.'), "{uplifts}");
    assert!(stdout.contains("uplift episodes;"), "{stdout}");
}
