//! `flexrock criteria`: its refusals, and the committed results of validation/criteria/run.sh
//! against the columns the command writes.

use crate::common::{flexrock, repo, scratch_dir};

#[test]
fn a_missing_record_is_refused_by_name_and_nothing_is_written() {
    let dir = scratch_dir("criteria-missing-record");
    let out = dir.join("out");
    let missing = dir.join("no-such-record.AT2");
    let o = flexrock(&[
        "criteria",
        repo("models/pulse-map.toml").to_str().unwrap(),
        "--out",
        out.to_str().unwrap(),
        "--record",
        missing.to_str().unwrap(),
    ]);
    assert_eq!(o.status.code(), Some(2));
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(err.contains("no-such-record.AT2"), "{err}");
    assert!(!out.exists(), "an output directory was made");
}

#[test]
fn the_committed_results_have_the_columns_the_command_writes() {
    let dir = repo("validation/criteria/results");
    for (file, columns) in [
        (
            "criteria.csv",
            &flexrock::commands::criteria::CRITERIA_COLUMNS[..],
        ),
        (
            "continuity.csv",
            &flexrock::commands::criteria::CONTINUITY_COLUMNS[..],
        ),
    ] {
        let text = std::fs::read_to_string(dir.join(file)).unwrap();
        assert_eq!(text.lines().next().unwrap(), columns.join(","), "{file}");
        // A body that could not be run (it buckles under its own weight) has empty fields
        // where its flexibility, period and p would be, never NaN.
        let mut reader = csv::Reader::from_reader(text.as_bytes());
        let mut empty = 0;
        for record in reader.records() {
            let record = record.unwrap();
            for (column, field) in columns.iter().zip(record.iter()) {
                assert!(
                    !field.eq_ignore_ascii_case("nan"),
                    "{file}: {column} = {field}"
                );
                empty += usize::from(field.is_empty() && column.contains("phi"));
            }
        }
        assert!(empty > 0, "{file}: no body that could not be run");
    }
}

#[test]
fn a_slenderness_out_of_range_is_refused_by_name_and_nothing_is_written() {
    let dir = scratch_dir("criteria-bad-slenderness");
    let out = dir.join("out");
    for bad in ["0", "-0.2", "1.5"] {
        let o = flexrock(&[
            "criteria",
            repo("models/pulse-map.toml").to_str().unwrap(),
            "--out",
            out.to_str().unwrap(),
            &format!("--slenderness={bad}"),
        ]);
        assert_eq!(o.status.code(), Some(2), "{bad}");
        let err = String::from_utf8_lossy(&o.stderr);
        assert!(err.contains("--slenderness"), "{err}");
        assert!(err.contains("above 0 and below 1"), "{err}");
        assert!(!out.exists(), "an output directory was made");
    }
}
