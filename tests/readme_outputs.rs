//! The outputs the README quotes are what the program prints today: every fenced block of the
//! README that starts with `$ flexrock ...` is run (in a scratch directory, the repository's
//! files named by full path) and compared line by line with the block. Only wall-clock times, which
//! no two runs share, are set aside.

mod common;

use std::path::Path;
use std::process::Command;

/// The fenced blocks of `text` whose first line is a flexrock command: (line number, command,
/// the lines quoted after it).
fn quoted_runs(text: &str) -> Vec<(usize, String, Vec<String>)> {
    let lines: Vec<&str> = text.lines().collect();
    let mut runs = Vec::new();
    let mut i = 0;
    while i < lines.len() {
        if lines[i].starts_with("```") {
            let start = i + 1;
            let mut end = start;
            while end < lines.len() && !lines[end].starts_with("```") {
                end += 1;
            }
            if let Some(command) = lines.get(start).and_then(|l| l.strip_prefix("$ flexrock ")) {
                let quoted = lines[start + 1..end]
                    .iter()
                    .map(|l| l.to_string())
                    .collect();
                runs.push((start + 1, command.to_string(), quoted));
            }
            i = end + 1;
        } else {
            i += 1;
        }
    }
    runs
}

/// A line with its wall-clock times replaced: a number followed by the word `ms`, and the last
/// column of a table whose header ends in `ms`.
fn without_times(lines: &[String]) -> Vec<String> {
    let mut in_timed_table = false;
    lines
        .iter()
        .map(|line| {
            let columns = line.split_whitespace().count();
            if in_timed_table && line.starts_with("  ") && columns > 8 {
                // The last column, right-aligned to the width of the longest time.
                let head = line.trim_end();
                let cut = head.rfind(' ').unwrap_or(0);
                return format!("{} <time>", head[..cut].trim_end());
            } else {
                in_timed_table = line.trim_end().ends_with(" ms") && line.contains("rhs evals");
            }
            let mut words: Vec<String> = line.split(' ').map(str::to_string).collect();
            for k in 1..words.len() {
                let unit = words[k].trim_end_matches([',', ';', ')']);
                if unit == "ms" && words[k - 1].parse::<f64>().is_ok() {
                    words[k - 1] = "<time>".to_string();
                }
            }
            words.join(" ")
        })
        .collect()
}

#[test]
fn the_readme_quotes_what_the_program_prints() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let readme = std::fs::read_to_string(root.join("README.md")).unwrap();
    let runs = quoted_runs(&readme);
    assert!(runs.len() >= 3, "the README quotes three runs: {runs:?}");
    for (index, (line, command, quoted)) in runs.iter().enumerate() {
        // Run in a scratch directory, so that outputs (named by --out or by default under
        // out/) land there and print as quoted; the repository's files are named by full path.
        let scratch = common::scratch_dir(&format!("readme-output-{index}"));
        let args: Vec<String> = command
            .split_whitespace()
            .map(|a| match root.join(a) {
                file if file.is_file() => file.to_string_lossy().into_owned(),
                _ => a.to_string(),
            })
            .collect();
        let o = Command::new(env!("CARGO_BIN_EXE_flexrock"))
            .args(&args)
            .current_dir(&scratch)
            .output()
            .unwrap();
        assert!(o.status.success(), "README line {line}: {command}");
        let mut printed = String::from_utf8_lossy(&o.stderr).into_owned();
        printed.push_str(&String::from_utf8_lossy(&o.stdout));
        let printed: Vec<String> = printed.lines().map(str::to_string).collect();
        let (printed, quoted) = (without_times(&printed), without_times(quoted));
        for (k, (mine, theirs)) in printed.iter().zip(&quoted).enumerate() {
            assert_eq!(
                mine,
                theirs,
                "README line {}: `flexrock {command}` prints another line",
                line + 1 + k
            );
        }
        assert_eq!(
            printed.len(),
            quoted.len(),
            "README line {line}: `flexrock {command}` prints {} lines, the README quotes {}",
            printed.len(),
            quoted.len()
        );
    }
}

#[test]
fn wall_times_are_set_aside_and_nothing_else() {
    let lines = [
        "cost: reference 6075 steps, 7371 rhs evaluations, 2.9 ms; newmark 300 steps".to_string(),
        "  method  dt  rtol  q  t  p  n  steps rhs evals        ms".to_string(),
        "  bdf  -  1e-4  9.674e-4  6.741e-4  6.469e-4  +0  467  837  0.43".to_string(),
        "orders against dt".to_string(),
        "  bdf  max_q_error  error ~ work^-8.02   (3 points)".to_string(),
    ];
    let out = without_times(&lines);
    assert_eq!(
        out[0],
        "cost: reference 6075 steps, 7371 rhs evaluations, <time> ms; newmark 300 steps"
    );
    assert!(out[2].ends_with("837 <time>"), "{}", out[2]);
    assert_eq!(out[4], lines[4]);
}
