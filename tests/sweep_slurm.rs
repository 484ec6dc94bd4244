//! `flexrock sweep` as the tasks of a Slurm job array (validation/slurm/sweep.sbatch): without
//! --shard, the shard comes from SLURM_ARRAY_TASK_ID, SLURM_ARRAY_TASK_MIN and
//! SLURM_ARRAY_TASK_COUNT; `flexrock sweep merge` joins the shards into what one process writes.

use crate::common::{file_names, repo, scratch_dir};
use std::path::Path;
use std::process::Output;

const SLURM_VARS: [&str; 3] = [
    "SLURM_ARRAY_TASK_ID",
    "SLURM_ARRAY_TASK_MIN",
    "SLURM_ARRAY_TASK_COUNT",
];

/// A 6 x 5 grid in chunks of 4 points: 8 chunks, so 3 shards get 2, 3 and 3 chunks (the last
/// one short).
fn sweep_args(out: &Path) -> Vec<String> {
    [
        "sweep",
        repo("models/pulse-map.toml").to_str().unwrap(),
        "--out",
        out.to_str().unwrap(),
        "--vary",
        "excitation.period=lin:0.2:3:6",
        "--vary",
        "excitation.amplitude=lin:0.5:15:5",
        "--chunk-size",
        "4",
        "--threads",
        "1",
        "--quiet",
    ]
    .iter()
    .map(|s| s.to_string())
    .collect()
}

/// Runs the binary with exactly these SLURM_ARRAY_TASK_* variables (none inherited, so that the
/// test means the same inside a Slurm job).
fn flexrock_in_task(args: &[String], vars: &[(&str, &str)]) -> Output {
    let mut command = crate::common::flexrock_command();
    command.args(args);
    for name in SLURM_VARS {
        command.env_remove(name);
    }
    command.envs(vars.iter().copied());
    command.output().expect("the binary runs")
}

fn assert_ok(o: &Output, what: &str) {
    assert!(
        o.status.success(),
        "{what}: exit {:?}\n{}",
        o.status.code(),
        String::from_utf8_lossy(&o.stderr)
    );
}

#[test]
fn array_tasks_5_to_7_merge_into_the_single_process_sweep() {
    let dir = scratch_dir("sweep-slurm-array");
    let (array_out, single_out) = (dir.join("array"), dir.join("single"));

    for id in ["5", "6", "7"] {
        let o = flexrock_in_task(
            &sweep_args(&array_out),
            &[
                ("SLURM_ARRAY_TASK_ID", id),
                ("SLURM_ARRAY_TASK_MIN", "5"),
                ("SLURM_ARRAY_TASK_COUNT", "3"),
            ],
        );
        assert_ok(&o, &format!("task {id}"));
    }
    assert_eq!(
        file_names(&array_out),
        ["shard-1-of-3", "shard-2-of-3", "shard-3-of-3"],
        "task ids 5, 6, 7 are shards 1, 2, 3 of 3"
    );
    for (k, rows) in [(1, 8), (2, 12), (3, 10)] {
        let csv =
            std::fs::read_to_string(array_out.join(format!("shard-{k}-of-3/sweep.csv"))).unwrap();
        assert_eq!(csv.lines().count(), 1 + rows, "rows of shard {k}");
    }

    let out = array_out.to_str().unwrap().to_string();
    let merge: Vec<String> = ["sweep", "merge", &out, "--out", &out]
        .iter()
        .map(|s| s.to_string())
        .collect();
    assert_ok(&flexrock_in_task(&merge, &[]), "merge");
    assert_ok(&flexrock_in_task(&sweep_args(&single_out), &[]), "single");

    let merged_csv = std::fs::read(array_out.join("sweep.csv")).unwrap();
    let single_csv = std::fs::read(single_out.join("sweep.csv")).unwrap();
    assert_eq!(
        String::from_utf8_lossy(&merged_csv).lines().count(),
        31,
        "header and 30 points"
    );
    assert!(
        merged_csv == single_csv,
        "merged sweep.csv differs from the single-process one"
    );
    // The other files a whole sweep writes (sweep.json, the figure) are the same too.
    let whole: Vec<String> = file_names(&array_out)
        .into_iter()
        .filter(|n| !n.starts_with("shard-"))
        .collect();
    assert_eq!(whole, file_names(&single_out));
    for name in &whole {
        assert!(
            std::fs::read(array_out.join(name)).unwrap()
                == std::fs::read(single_out.join(name)).unwrap(),
            "{name} differs"
        );
    }
}

/// Exit code 2, a message naming `variable`, no output directory.
fn refused(name: &str, vars: &[(&str, &str)], variable: &str) {
    let out = scratch_dir(&format!("sweep-slurm-{name}")).join("out");
    let o = flexrock_in_task(&sweep_args(&out), vars);
    let stderr = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(2), "{name}: {stderr}");
    assert!(stderr.contains(variable), "{name}: {stderr}");
    assert!(!stderr.contains("panicked"), "{name}: {stderr}");
    assert!(!out.exists(), "{name}: output directory was created");
}

#[test]
fn task_id_outside_the_array_is_refused() {
    let vars = |id| {
        [
            ("SLURM_ARRAY_TASK_ID", id),
            ("SLURM_ARRAY_TASK_MIN", "5"),
            ("SLURM_ARRAY_TASK_COUNT", "3"),
        ]
    };
    // Ids 5..=7 are the array; a strided array (--array=5-9:2) also gives 9.
    refused("above", &vars("9"), "SLURM_ARRAY_TASK_ID");
    refused("below", &vars("4"), "SLURM_ARRAY_TASK_ID");
}

#[test]
fn non_numeric_task_variables_are_refused() {
    refused(
        "id-word",
        &[
            ("SLURM_ARRAY_TASK_ID", "abc"),
            ("SLURM_ARRAY_TASK_MIN", "5"),
            ("SLURM_ARRAY_TASK_COUNT", "3"),
        ],
        "SLURM_ARRAY_TASK_ID",
    );
    refused(
        "id-negative",
        &[
            ("SLURM_ARRAY_TASK_ID", "-1"),
            ("SLURM_ARRAY_TASK_COUNT", "3"),
        ],
        "SLURM_ARRAY_TASK_ID",
    );
    refused(
        "count-word",
        &[
            ("SLURM_ARRAY_TASK_ID", "5"),
            ("SLURM_ARRAY_TASK_MIN", "5"),
            ("SLURM_ARRAY_TASK_COUNT", "three"),
        ],
        "SLURM_ARRAY_TASK_COUNT",
    );
    refused(
        "min-word",
        &[
            ("SLURM_ARRAY_TASK_ID", "5"),
            ("SLURM_ARRAY_TASK_MIN", "x"),
            ("SLURM_ARRAY_TASK_COUNT", "3"),
        ],
        "SLURM_ARRAY_TASK_MIN",
    );
}
