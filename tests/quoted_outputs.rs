//! The commands the README and the book show, and what they print, are what the program does
//! today. In README.md and in every page under book/src/, every fenced block whose first line is
//! `$ flexrock ...` is run and what it prints is compared line by line with the rest of the
//! block. Only wall-clock times, which no two runs share, are set aside; a line `...` stands for
//! one or more lines left out.
//!
//! The blocks of one page run in order in one scratch directory, so that a page can `run` a model
//! and then `plot` or `events` its output directory. The scratch directory holds links to the
//! repository's `models/` and `validation/`, so that a command names the repository's files by
//! the paths a user types at the root of a clone (`models/ichinose1986.toml`,
//! `validation/records/*.AT2`), and prints them so.
//!
//! The figures the book shows are committed under book/src/figures/. Each is named on its page by
//! a comment `<!-- figure: PATH -->` on the line before its image, PATH being the file the page's
//! commands write (relative to the scratch directory); the committed copy must be that file, byte
//! for byte. `book/figures.sh` writes them anew (this test with `FLEXROCK_WRITE_FIGURES=1`).

use crate::common;

use std::path::{Path, PathBuf};

/// A command the documents show: where it is, the command line after `$ flexrock `, and the
/// lines quoted after it.
#[derive(Debug)]
struct Quoted {
    line: usize,
    command: String,
    lines: Vec<String>,
}

/// The fenced blocks of `text` whose first line is a flexrock command. A command may go on over
/// several lines, each but the last ending in ` \`, as in a shell.
fn quoted_runs(text: &str) -> Vec<Quoted> {
    let lines: Vec<&str> = text.lines().collect();
    let mut runs = Vec::new();
    let mut i = 0;
    while i < lines.len() {
        if lines[i].trim_start().starts_with("```") {
            let start = i + 1;
            let mut end = start;
            while end < lines.len() && !lines[end].trim_start().starts_with("```") {
                end += 1;
            }
            if let Some(first) = lines.get(start).and_then(|l| l.strip_prefix("$ flexrock ")) {
                let mut command = first.to_string();
                let mut k = start;
                while command.ends_with('\\') && k + 1 < end {
                    command.pop();
                    k += 1;
                    command.push(' ');
                    command.push_str(lines[k].trim());
                }
                runs.push(Quoted {
                    line: start + 1,
                    command,
                    lines: lines[k + 1..end].iter().map(|l| l.to_string()).collect(),
                });
            }
            i = end + 1;
        } else {
            i += 1;
        }
    }
    runs
}

/// The words of a command line as a POSIX shell splits them: single and double quotes group,
/// a backslash outside single quotes escapes the next character. No variables, no globbing
/// (flexrock expands the patterns it is given itself).
fn shell_words(line: &str) -> Vec<String> {
    let mut words = Vec::new();
    let mut word = String::new();
    let mut in_word = false;
    let mut chars = line.chars();
    while let Some(c) = chars.next() {
        match c {
            '\'' => {
                in_word = true;
                for c in chars.by_ref() {
                    if c == '\'' {
                        break;
                    }
                    word.push(c);
                }
            }
            '"' => {
                in_word = true;
                while let Some(c) = chars.next() {
                    match c {
                        '"' => break,
                        '\\' => word.extend(chars.next()),
                        c => word.push(c),
                    }
                }
            }
            '\\' => {
                in_word = true;
                word.extend(chars.next());
            }
            c if c.is_whitespace() => {
                if in_word {
                    words.push(std::mem::take(&mut word));
                    in_word = false;
                }
            }
            c => {
                in_word = true;
                word.push(c);
            }
        }
    }
    if in_word {
        words.push(word);
    }
    words
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
                if in_timed_table {
                    // The header's last column is as wide as the longest time.
                    let head = line.trim_end().trim_end_matches("ms").trim_end();
                    return format!("{head} <time>");
                }
            }
            let mut words: Vec<String> = line.split(' ').map(str::to_string).collect();
            for k in 1..words.len() {
                let unit = words[k].trim_end_matches([',', ';', ')']).to_string();
                if unit == "ms" && words[k - 1].parse::<f64>().is_ok() {
                    words[k - 1] = "<time>".to_string();
                }
                // A sweep's "(0.412 s, 2184 points/s)".
                if unit == "points/s" && k >= 3 && words[k - 2] == "s," {
                    let seconds = words[k - 3].trim_start_matches('(');
                    if seconds.parse::<f64>().is_ok() && words[k - 1].parse::<f64>().is_ok() {
                        words[k - 3] = "(<time>".to_string();
                        words[k - 1] = "<rate>".to_string();
                    }
                }
            }
            words.join(" ")
        })
        .collect()
}

/// Where `printed` departs from `quoted` (both without times), or None when they agree. A quoted
/// line `...` matches one or more printed lines; the quoted lines after it are looked for from
/// there on.
fn mismatch(printed: &[String], quoted: &[String]) -> Option<String> {
    let segments: Vec<&[String]> = quoted.split(|l| l == "...").collect();
    let mut at = 0;
    for (n, segment) in segments.iter().enumerate() {
        let last = n + 1 == segments.len();
        let found = if n == 0 {
            Some(0)
        } else if segment.is_empty() {
            // A trailing `...`: at least one more line.
            if last && at >= printed.len() {
                return Some("`...` at the end, but nothing more is printed".into());
            }
            continue;
        } else if last {
            // The last lines quoted are the last lines printed.
            printed.len().checked_sub(segment.len()).filter(|&f| f > at)
        } else {
            (at + 1..=printed.len().saturating_sub(segment.len()))
                .find(|&f| printed[f..f + segment.len()] == **segment)
        };
        let Some(from) = found else {
            return Some(format!(
                "the lines quoted after `...` are not printed after line {at}: {:?}",
                segment.first()
            ));
        };
        for (k, line) in segment.iter().enumerate() {
            match printed.get(from + k) {
                Some(p) if p == line => {}
                Some(p) => {
                    return Some(format!(
                        "quoted line {} reads\n    {line}\n  but the program prints\n    {p}",
                        from + k + 1
                    ))
                }
                None => {
                    return Some(format!(
                        "quoted line {} is `{line}`, but the program prints only {} lines",
                        from + k + 1,
                        printed.len()
                    ))
                }
            }
        }
        at = from + segment.len();
        if last && at != printed.len() {
            return Some(format!(
                "the program prints {} lines, the block quotes {}; the next printed line is\n    {}",
                printed.len(),
                at,
                printed[at]
            ));
        }
    }
    None
}

fn root() -> &'static Path {
    Path::new(env!("CARGO_MANIFEST_DIR"))
}

/// A scratch directory for one document, with the repository's inputs linked in.
fn workspace(doc: &Path) -> PathBuf {
    let name = doc.to_string_lossy().replace(['/', '.'], "-");
    let dir = common::scratch_dir(&format!("quoted-{name}"));
    for linked in ["models", "validation"] {
        std::os::unix::fs::symlink(root().join(linked), dir.join(linked)).unwrap();
    }
    dir
}

/// Runs the quoted commands of one document in order; the failures, each naming its line.
fn check_commands(doc: &Path, text: &str, dir: &Path) -> Vec<String> {
    let mut failures = Vec::new();
    for run in quoted_runs(text) {
        let where_ = format!("{}:{}: `flexrock {}`", doc.display(), run.line, run.command);
        let args = shell_words(&run.command);
        let args: Vec<&str> = args.iter().map(String::as_str).collect();
        let o = common::flexrock_in(dir, &args);
        let mut printed = String::from_utf8_lossy(&o.stderr).into_owned();
        printed.push_str(&String::from_utf8_lossy(&o.stdout));
        if !o.status.success() {
            failures.push(format!("{where_} fails ({}):\n{printed}", o.status));
            continue;
        }
        // Trailing blanks are set aside: editors strip them from the pages.
        let printed: Vec<String> = printed.lines().map(|l| l.trim_end().to_string()).collect();
        let quoted: Vec<String> = run.lines.iter().map(|l| l.trim_end().to_string()).collect();
        if let Some(why) = mismatch(&without_times(&printed), &without_times(&quoted)) {
            failures.push(format!("{where_}: {why}"));
        }
    }
    failures
}

/// The figures a page shows: (line, the file its commands write, the committed copy's name).
fn figures(text: &str) -> Vec<(usize, String, String)> {
    let lines: Vec<&str> = text.lines().collect();
    let mut found = Vec::new();
    for (i, line) in lines.iter().enumerate() {
        let Some(source) = line
            .trim()
            .strip_prefix("<!-- figure:")
            .and_then(|l| l.strip_suffix("-->"))
        else {
            continue;
        };
        let image = lines.get(i + 1).copied().unwrap_or("");
        let name = image
            .split("figures/")
            .nth(1)
            .and_then(|rest| rest.split([')', '"', ' ']).next())
            .unwrap_or("");
        found.push((i + 1, source.trim().to_string(), name.to_string()));
    }
    found
}

/// Compares (or, with `FLEXROCK_WRITE_FIGURES=1`, writes) the committed figures of one page.
fn check_figures(doc: &Path, text: &str, dir: &Path, write: bool) -> Vec<String> {
    let mut failures = Vec::new();
    for (line, source, name) in figures(text) {
        let where_ = format!("{}:{line}", doc.display());
        if name.is_empty() {
            failures.push(format!(
                "{where_}: the line after `<!-- figure: ... -->` must show an image from figures/"
            ));
            continue;
        }
        let made = match std::fs::read(dir.join(&source)) {
            Ok(bytes) => bytes,
            Err(e) => {
                failures.push(format!(
                    "{where_}: the page's commands do not write {source}: {e}"
                ));
                continue;
            }
        };
        let committed = root().join("book/src/figures").join(&name);
        if write {
            std::fs::write(&committed, &made).unwrap();
        } else if std::fs::read(&committed).ok().as_deref() != Some(&made[..]) {
            failures.push(format!(
                "{where_}: book/src/figures/{name} is not what the page's commands draw into \
                 {source}; run `bash book/figures.sh` and commit the figures"
            ));
        }
    }
    failures
}

#[test]
fn the_documents_quote_what_the_program_prints() {
    let write = std::env::var_os("FLEXROCK_WRITE_FIGURES").is_some_and(|v| v == "1");
    let mut failures = Vec::new();
    let mut commands = 0;
    let mut shown = std::collections::BTreeSet::new();
    for doc in common::documents() {
        let text = std::fs::read_to_string(root().join(&doc)).unwrap();
        let runs = quoted_runs(&text).len();
        let pictures = figures(&text);
        if runs == 0 && pictures.is_empty() {
            continue;
        }
        commands += runs;
        let dir = workspace(&doc);
        failures.extend(check_commands(&doc, &text, &dir));
        failures.extend(check_figures(&doc, &text, &dir, write));
        shown.extend(pictures.into_iter().map(|(_, _, name)| name));
    }
    // No figure is committed that no page draws.
    for entry in std::fs::read_dir(root().join("book/src/figures")).unwrap() {
        let name = entry.unwrap().file_name().to_string_lossy().into_owned();
        if !name.starts_with('.') && !shown.contains(&name) {
            failures.push(format!(
                "book/src/figures/{name} is shown by no page (no `<!-- figure: ... -->` names it)"
            ));
        }
    }
    assert!(
        commands >= 10,
        "the documents quote only {commands} commands"
    );
    assert!(failures.is_empty(), "{}", failures.join("\n\n"));
}

/// The README is a front page; the manual is the book.
#[test]
fn the_readme_is_a_front_page() {
    let size = std::fs::metadata(root().join("README.md")).unwrap().len();
    assert!(
        size <= 12 * 1024,
        "README.md has {size} bytes, more than 12 KiB: move the detail into the book"
    );
    // The test command the README gives is the one CI runs.
    let ci = std::fs::read_to_string(root().join(".ci/run")).unwrap();
    let command = ci
        .lines()
        .find(|l| l.starts_with("cargo test"))
        .expect(".ci/run runs cargo test");
    let readme = std::fs::read_to_string(root().join("README.md")).unwrap();
    assert!(
        readme.lines().any(|l| l.trim() == command),
        "README.md does not give CI's test command `{command}` on a line of its own"
    );
}

#[test]
fn wall_times_are_set_aside_and_nothing_else() {
    let lines = [
        "cost: reference 6075 steps, 7371 rhs evaluations, 2.9 ms; newmark 300 steps".to_string(),
        "  method  dt  rtol  q  t  p  n  steps rhs evals        ms".to_string(),
        "  bdf  -  1e-4  9.674e-4  6.741e-4  6.469e-4  +0  467  837  0.43".to_string(),
        "orders against dt".to_string(),
        "  bdf  max_q_error  error ~ work^-8.02   (3 points)".to_string(),
        "  900 computed now, 0 found done (0.412 s, 2184 points/s)".to_string(),
    ];
    let out = without_times(&lines);
    assert_eq!(
        out[0],
        "cost: reference 6075 steps, 7371 rhs evaluations, <time> ms; newmark 300 steps"
    );
    assert_eq!(
        out[1],
        "  method  dt  rtol  q  t  p  n  steps rhs evals <time>"
    );
    assert!(out[2].ends_with("837 <time>"), "{}", out[2]);
    assert_eq!(out[4], lines[4]);
    assert_eq!(
        out[5],
        "  900 computed now, 0 found done (<time> s, <rate> points/s)"
    );
}

#[test]
fn commands_are_split_as_a_shell_splits_them() {
    let text = "```\n$ flexrock sweep m.toml \\\n    --vary 'excitation.path=a b/*.AT2' \
                --set \"x=1\" \\\n    --out o\nwrote o/sweep.csv\n```\n";
    let runs = quoted_runs(text);
    assert_eq!(runs.len(), 1);
    assert_eq!(runs[0].lines, ["wrote o/sweep.csv"]);
    assert_eq!(
        shell_words(&runs[0].command),
        [
            "sweep",
            "m.toml",
            "--vary",
            "excitation.path=a b/*.AT2",
            "--set",
            "x=1",
            "--out",
            "o"
        ]
    );
}

#[test]
fn an_ellipsis_stands_for_lines_left_out_and_nothing_else_differs() {
    let lines = |s: &str| s.lines().map(str::to_string).collect::<Vec<_>>();
    let printed = lines("a\nb\nc\nd\ne");
    assert_eq!(mismatch(&printed, &lines("a\nb\nc\nd\ne")), None);
    assert_eq!(mismatch(&printed, &lines("a\n...\ne")), None);
    assert_eq!(mismatch(&printed, &lines("a\n...\nc\n...\ne")), None);
    assert_eq!(mismatch(&printed, &lines("a\nb\n...")), None);
    assert!(mismatch(&printed, &lines("a\nb\nc\nd")).is_some());
    assert!(mismatch(&printed, &lines("a\nb\nc\nd\nX")).is_some());
    assert!(mismatch(&printed, &lines("a\n...\nd")).is_some());
    assert!(mismatch(&printed, &lines("a\n...\nb\nc\nd\ne")).is_some());
    assert!(mismatch(&printed, &lines("a\nb\nc\nd\ne\n...")).is_some());
    assert!(mismatch(&printed, &lines("a\n...\nX\n...\ne")).is_some());
}

/// The README's validation table holds the numbers of the committed convergence study
/// (validation/results/converge/convergence.csv, which CI regenerates and compares byte for
/// byte), to the two digits it prints.
#[test]
fn the_readme_validation_table_is_the_committed_evidence() {
    let readme = std::fs::read_to_string(root().join("README.md")).unwrap();
    let evidence =
        std::fs::read_to_string(root().join("validation/results/converge/convergence.csv"))
            .unwrap();
    let mut lines = evidence.lines();
    let header: Vec<&str> = lines.next().unwrap().split(',').collect();
    let column = |name: &str| header.iter().position(|h| *h == name).unwrap();
    let cases: Vec<Vec<&str>> = lines.map(|l| l.split(',').collect()).collect();
    let method_of = |label: &str| match label {
        "Newmark, the paper's compensation" => "newmark-compensate",
        "Newmark, sub-stepping to each crossing" => "newmark-substep",
        other => match other {
            "BDF" => "bdf",
            "Tsit45" => "tsit45",
            "ESDIRK34" => "esdirk34",
            "TR-BDF2" => "tr-bdf2",
            _ => panic!("README validation table: unknown method {other:?}"),
        },
    };
    let same = |a: &str, b: &str| match (a.parse::<f64>(), b.parse::<f64>()) {
        (Ok(x), Ok(y)) => x == y,
        _ => a.is_empty() && b == "-",
    };
    let table_head = "| method | dt (s) | rtol | max q error (m) | event-time error (s) | peak error (m) | rhs evaluations |";
    let rows: Vec<Vec<String>> = readme
        .lines()
        .skip_while(|l| *l != table_head)
        .skip(2)
        .take_while(|l| l.starts_with('|'))
        .map(|l| {
            l.trim_matches('|')
                .split('|')
                .map(|c| c.trim().to_string())
                .collect()
        })
        .collect();
    assert!(
        rows.len() >= 5,
        "README: no validation table under {table_head}"
    );
    for row in rows {
        let method = method_of(&row[0]);
        let case = cases
            .iter()
            .find(|c| {
                c[column("method")] == method
                    && same(c[column("dt")], &row[1])
                    && same(c[column("rtol")], &row[2])
            })
            .unwrap_or_else(|| panic!("README validation table: no case {row:?} in the evidence"));
        let two_digits = |name: &str| format!("{:.1e}", case[column(name)].parse::<f64>().unwrap());
        let expected = [
            two_digits("max_q_error"),
            two_digits("max_event_time_error"),
            two_digits("peak_error"),
            case[column("rhs_evaluations")].to_string(),
        ];
        assert_eq!(
            row[3..7],
            expected,
            "README validation table, {} at dt {} / rtol {}: the evidence says {expected:?}",
            row[0],
            row[1],
            row[2]
        );
    }
}
