//! The book's reference pages list what the code has, so that they cannot drift from it:
//! every model-file key (book/src/reference/model-file.md), every column of every output table
//! in order (outputs.md, against the column constants the writers use), every key of
//! summary.json, and every limit constant with its value (limits.md, against the constants and
//! a scan of the source for `MAX_`, `MIN_` and `EXIT_` constants). Likewise the developer
//! guide: the code map links every source file, and the tests page lists every test file.
//!
//! A table is found by the HTML comment just above it (`<!-- columns: history.csv -->`), which
//! the built book does not show. A table's names are the backticked names of its first column,
//! in order.

use crate::common;

use std::collections::BTreeMap;
use std::path::Path;

fn page(name: &str) -> String {
    let path = common::repo(&format!("book/src/reference/{name}"));
    std::fs::read_to_string(&path).unwrap_or_else(|e| panic!("{}: {e}", path.display()))
}

/// The rows of the table after the marker line `<!-- MARKER -->`: each row's cells, trimmed
/// (the header and the separator row left out).
fn table(text: &str, marker: &str) -> Vec<Vec<String>> {
    let tag = format!("<!-- {marker} -->");
    let mut lines = text.lines().skip_while(|l| l.trim() != tag);
    assert!(lines.next().is_some(), "no table marked {tag}");
    lines
        .take_while(|l| l.trim_start().starts_with('|'))
        .skip(2)
        .map(cells)
        .collect()
}

/// Every table after a marker line `<!-- MARKER -->` (markers may repeat), with its header.
fn tables(text: &str, marker: &str) -> Vec<(Vec<String>, Vec<Vec<String>>)> {
    let tag = format!("<!-- {marker} -->");
    let lines: Vec<&str> = text.lines().collect();
    let mut out = Vec::new();
    for (i, line) in lines.iter().enumerate() {
        if line.trim() == tag {
            let rows: Vec<Vec<String>> = lines[i + 1..]
                .iter()
                .take_while(|l| l.trim_start().starts_with('|'))
                .map(|l| cells(l))
                .collect();
            assert!(
                rows.len() > 2,
                "the table marked {tag} at line {} is empty",
                i + 1
            );
            out.push((rows[0].clone(), rows[2..].to_vec()));
        }
    }
    out
}

/// The cells of a table row (`\|` inside a cell is a bar, not a border).
fn cells(line: &str) -> Vec<String> {
    let protected = line.trim().replace("\\|", "\u{0}");
    let inner = protected.trim_start_matches('|').trim_end_matches('|');
    inner
        .split('|')
        .map(|c| c.replace('\u{0}', "|").trim().to_string())
        .collect()
}

/// The backticked names of a cell, in order.
fn names(cell: &str) -> Vec<String> {
    cell.split('`')
        .skip(1)
        .step_by(2)
        .map(str::to_string)
        .collect()
}

/// The backticked names of the first column of the table marked `marker`.
fn listed(text: &str, marker: &str) -> Vec<String> {
    table(text, marker)
        .iter()
        .flat_map(|row| names(&row[0]))
        .collect()
}

fn strings(list: &[&str]) -> Vec<String> {
    list.iter().map(|s| s.to_string()).collect()
}

#[test]
fn the_output_tables_list_exactly_the_columns_the_writers_write() {
    use flexrock_core::analysis::sweep::find_min::MinimumOutcome;
    use flexrock_core::analysis::sweep::point_result::{
        PointResult, RigidMinima, RunOutcome, Scales,
    };
    let text = page("outputs.md");
    let tables: [(&str, &[&str]); 11] = [
        (
            "columns: rigid events.csv",
            &flexrock_core::tables::rigid_results::RIGID_EVENT_COLUMNS,
        ),
        (
            "columns: criteria.csv",
            &flexrock::commands::criteria::CRITERIA_COLUMNS,
        ),
        (
            "columns: continuity.csv",
            &flexrock::commands::criteria::CONTINUITY_COLUMNS,
        ),
        ("columns: history.csv", &flexrock::writers::HISTORY_COLUMNS),
        ("columns: events.csv", &flexrock::writers::EVENT_COLUMNS),
        ("columns: episodes.csv", &flexrock::writers::EPISODE_COLUMNS),
        (
            "columns: compare.csv",
            &flexrock::commands::compare::COMPARE_COLUMNS,
        ),
        (
            "columns: compare_history.csv",
            &flexrock::commands::compare::COMPARE_HISTORY_COLUMNS,
        ),
        (
            "columns: convergence.csv",
            &flexrock::commands::converge::CONVERGENCE_COLUMNS,
        ),
        (
            "columns: fem_history.csv",
            &flexrock::commands::fem::HISTORY_COLUMNS,
        ),
        (
            "columns: fem_events.csv",
            &flexrock::commands::fem::EVENT_COLUMNS,
        ),
    ];
    for (marker, columns) in tables {
        assert_eq!(
            listed(&text, marker),
            strings(columns),
            "the table marked {marker}"
        );
    }
    assert_eq!(
        listed(&text, "columns: pushover.csv"),
        strings(&flexrock::commands::pushover::PUSHOVER_COLUMNS)
    );
    // sweep.csv: the point, the axes (one unnamed row), status and reason, then one of two
    // groups, then the scales; the groups must be what a row writes, in that order.
    assert_eq!(
        listed(&text, "columns: sweep.csv start"),
        ["point", "status", "reason"]
    );
    let run = listed(&text, "columns: sweep.csv run");
    let find_min = listed(&text, "columns: sweep.csv find-min");
    let scales = listed(&text, "columns: sweep.csv scales");
    assert_eq!(run, strings(&RunOutcome::default().named().map(|(n, _)| n)));
    let search: Vec<&str> = (MinimumOutcome::default().named().iter())
        .chain(&RigidMinima::default().named())
        .map(|(n, _)| *n)
        .collect();
    assert_eq!(find_min, strings(&search));
    assert_eq!(scales, strings(&Scales::default().named().map(|(n, _)| n)));
    // A sweep over records: its record columns; `record intensity` and `record spectrum`.
    assert_eq!(
        listed(&text, "columns: sweep.csv record"),
        PointResult::record_columns()
    );
    assert_eq!(
        listed(&text, "columns: record intensity"),
        flexrock::commands::record::intensity_columns()
    );
    assert_eq!(
        listed(&text, "columns: record spectrum"),
        strings(&flexrock::commands::record::SPECTRUM_COLUMNS)
    );
    // A row's: the row's run, then each column's, named `cI_...` on the page.
    let row = flexrock_core::analysis::sweep::rows::RowOutcome::columns(1);
    assert_eq!(listed(&text, "columns: sweep.csv row"), row[..5]);
    let column: Vec<String> = row[5..]
        .iter()
        .map(|c| c.replacen("c0_", "cI_", 1))
        .collect();
    assert_eq!(listed(&text, "columns: sweep.csv row column"), column);
    assert_eq!(
        PointResult::columns(flexrock_core::analysis::sweep::Layout::Row(1)),
        strings(&["status", "reason"])
            .into_iter()
            .chain(row)
            .collect::<Vec<_>>()
    );
    for (find, group) in [(false, &run), (true, &find_min)] {
        let mut documented = strings(&["status", "reason"]);
        documented.extend(group.iter().cloned());
        documented.extend(scales.iter().cloned());
        assert_eq!(PointResult::columns(find), documented, "find_min = {find}");
    }
}

#[test]
fn a_table_that_leaves_out_or_reorders_a_column_is_caught() {
    let text = "<!-- columns: x -->\n| column | unit |\n|---|---|\n| `t` | s |\n| `q`, `qdot` | m |\n\nafter\n";
    assert_eq!(listed(text, "columns: x"), ["t", "q", "qdot"]);
    assert_ne!(listed(text, "columns: x"), strings(&["t", "qdot", "q"]));
    assert_eq!(cells("| a \\| b | `c` |"), ["a | b", "`c`"]);
}

#[test]
fn summary_json_has_exactly_the_documented_keys() {
    let out = common::scratch_dir("book-reference-summary");
    // An adaptive method: the list holds every key but the exact method's error_estimate.
    let o = common::run_reference(&out, &["--method", "bdf"]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let text = std::fs::read_to_string(out.join("summary.json")).unwrap();
    let summary: serde_json::Value = serde_json::from_str(&text).unwrap();
    let mut written: Vec<String> = summary.as_object().unwrap().keys().cloned().collect();
    let mut documented = listed(&page("outputs.md"), "keys: summary.json");
    written.sort();
    documented.sort();
    assert_eq!(documented, written);
}

#[test]
fn the_model_file_tables_list_every_key_of_the_schema() {
    use flexrock_core::model::{
        BodySection, ExcitationSection, FemSection, ModelFile, SimulationSection, SolverSection,
    };
    // Every field given, so that every key is written. A field added to a section without a
    // line here does not compile.
    let file = ModelFile {
        body: BodySection {
            height: 1.0,
            width: 1.0,
            depth: Some(1.0),
            density: Some(1.0),
            mass: Some(1.0),
            youngs_modulus: Some(1.0),
            flexural_rigidity: Some(1.0),
            period: Some(1.0),
            damping_ratio: Some(1.0),
            gravity: Some(1.0),
            constants: Some("x".into()),
            self_weight: Some("x".into()),
            poisson_ratio: Some(1.0),
            landing_restitution: Some(1.0),
            damping_while_rocking: Some(true),
        },
        excitation: ExcitationSection {
            kind: "x".into(),
            amplitude: Some(1.0),
            period: Some(1.0),
            ramp: Some(1.0),
            cycles: Some(1.0),
            shape: Some("x".into()),
            center: Some(1.0),
            path: Some("x".into()),
            format: Some("x".into()),
            units: Some("x".into()),
            scale: Some(1.0),
            start: Some(1.0),
            end: Some(1.0),
            tail: Some(1.0),
            dt: Some(1.0),
            ratio: Some(1.0),
            vertical: None,
        },
        simulation: SimulationSection {
            duration: Some(1.0),
            q0: Some(1.0),
            qdot0: Some(1.0),
        },
        solver: SolverSection {
            method: Some("x".into()),
            rtol: Some(1.0),
            atol: Some(1.0),
            output_dt: Some(1.0),
            dt: Some(1.0),
            newmark_beta: Some(1.0),
            newmark_gamma: Some(1.0),
            newmark_variant: Some("x".into()),
        },
        fem: Some(FemSection {
            nx: Some(1),
            ny: Some(1),
            dt: Some(1.0),
            scheme: Some("x".into()),
            theta: Some(1.0),
            mu_s: Some(1.0),
            mu_k: Some(1.0),
            p_delta: Some(true),
            base: Some("x".into()),
            damping_period: Some(1.0),
            duration: Some(1.0),
        }),
    };
    // The keys in the order the schema declares them: the TOML text of the file.
    let text = toml::to_string(&file).unwrap();
    let mut schema: BTreeMap<String, Vec<String>> = BTreeMap::new();
    let mut section = String::new();
    for line in text.lines() {
        if let Some(name) = line.strip_prefix('[').and_then(|l| l.strip_suffix(']')) {
            section = name.to_string();
        } else if let Some((key, _)) = line.split_once(" = ") {
            schema
                .entry(section.clone())
                .or_default()
                .push(key.to_string());
        }
    }
    assert_eq!(schema.len(), 5, "{text}");
    let text = page("model-file.md");
    for (section, keys) in schema {
        assert_eq!(
            listed(&text, &format!("keys: {section}")),
            keys,
            "the [{section}] table of model-file.md"
        );
    }
}

#[test]
fn the_excitation_kinds_table_lists_every_kind_the_model_file_takes() {
    // The kinds, from the rule a wrong kind is refused with.
    let text = common::reference_body("[excitation]\nkind = \"nothing\"\n");
    let Err(e) = flexrock_core::model::Model::from_toml_str(&text, &Default::default()) else {
        panic!("an unknown kind is refused");
    };
    let message = e.to_string();
    let kinds: Vec<String> = message
        .split("must be one of ")
        .nth(1)
        .unwrap_or_else(|| panic!("{message}"))
        .split(", ")
        .map(|k| k.trim().trim_matches('"').to_string())
        .collect();
    assert!(kinds.len() >= 6, "{message}");
    assert_eq!(listed(&page("model-file.md"), "kinds"), kinds);
}

/// A number as the limits table writes it: `64 MiB`, `1e-5 s`, `196.133 m/s²`, `200000`.
fn value_of(cell: &str) -> Option<f64> {
    let mut words = cell.split_whitespace();
    let number: f64 = words.next()?.parse().ok()?;
    let factor = match words.next() {
        Some("KiB") => 1024.0,
        Some("MiB") => 1024.0 * 1024.0,
        Some("GiB") => 1024.0 * 1024.0 * 1024.0,
        _ => 1.0,
    };
    Some(number * factor)
}

/// The limit constants the code has, by name, with their values: each public one read from the
/// library (so that its value is the compiled one), the rest found below by scanning the source.
fn known_values() -> BTreeMap<&'static str, f64> {
    use flexrock::commands::run;
    use flexrock::writers::run_dir;
    use flexrock_core::analysis::sweep::axis;
    use flexrock_core::bodies::fem;
    use flexrock_core::floor as excitation;
    use flexrock_core::floor::record;
    use flexrock_core::integrate as solver;
    use flexrock_core::integrate::solution;
    use flexrock_core::model;
    use flexrock_core::physics::constants;
    BTreeMap::from([
        ("MAX_MODEL_FILE_BYTES", model::MAX_MODEL_FILE_BYTES as f64),
        ("MIN_RTOL", model::MIN_RTOL),
        ("MAX_RTOL", model::MAX_RTOL),
        ("MAX_ATOL_OVER_WIDTH", model::MAX_ATOL_OVER_WIDTH),
        ("MAX_DURATION", model::MAX_DURATION),
        ("MAX_INITIAL_VELOCITY", model::MAX_INITIAL_VELOCITY),
        ("MAX_FLOOR_ACCELERATION", excitation::MAX_FLOOR_ACCELERATION),
        ("MIN_EXCITATION_PERIOD", excitation::MIN_EXCITATION_PERIOD),
        ("MIN_PERIOD", constants::MIN_PERIOD),
        (
            "SELF_WEIGHT_BUCKLING_PARAMETER",
            constants::SELF_WEIGHT_BUCKLING_PARAMETER,
        ),
        (
            "SELF_WEIGHT_WARNING_SHARE",
            constants::SELF_WEIGHT_WARNING_SHARE,
        ),
        ("MAX_RECORD_BYTES", record::MAX_RECORD_BYTES as f64),
        ("MIN_DT", record::MIN_DT),
        ("MIN_SAMPLES", record::MIN_SAMPLES as f64),
        ("MAX_RECORD_SAMPLES", record::MAX_RECORD_SAMPLES as f64),
        ("MAX_ELEMENTS_PER_SIDE", fem::MAX_ELEMENTS_PER_SIDE as f64),
        ("MAX_BAND_ENTRIES", fem::MAX_BAND_ENTRIES),
        ("FACTOR_CACHE_BYTES", fem::FACTOR_CACHE_BYTES),
        ("MAX_STEPS", fem::MAX_STEPS),
        ("MAX_STEP_WORK", fem::MAX_STEP_WORK),
        ("MAX_HISTORY_BYTES", run_dir::MAX_HISTORY_BYTES as f64),
        ("MAX_HISTORY_ROWS", run_dir::MAX_HISTORY_ROWS as f64),
        ("MAX_EVENTS_BYTES", run_dir::MAX_EVENTS_BYTES as f64),
        ("MAX_SUMMARY_BYTES", run_dir::MAX_SUMMARY_BYTES as f64),
        (
            "MAX_HISTORY_ROW_BYTES",
            flexrock_core::tables::run_tables::MAX_HISTORY_ROW_BYTES as f64,
        ),
        ("MAX_POINTS", axis::MAX_POINTS as f64),
        ("MAX_AXIS_VALUES", axis::MAX_AXIS_VALUES as f64),
        ("MAX_MAGNITUDE", axis::MAX_MAGNITUDE),
        ("BASE_STEPS", solver::budget::BASE_STEPS as f64),
        ("STEPS_PER_SECOND", solver::budget::STEPS_PER_SECOND),
        ("BASE_EVENTS", solver::budget::BASE_EVENTS as f64),
        ("EVENTS_PER_SECOND", solver::budget::EVENTS_PER_SECOND),
        ("CASCADE_EVENTS", solver::budget::CASCADE_EVENTS as f64),
        ("CASCADE_SPAN", solver::budget::CASCADE_SPAN),
        (
            "ENERGY_RESIDUAL_WARNING_SHARE",
            run::ENERGY_RESIDUAL_WARNING_SHARE,
        ),
        ("ENERGY_ROUNDING_ULPS", solution::ENERGY_ROUNDING_ULPS),
    ])
}

/// Every `const MAX_*`, `MIN_*` or `EXIT_*` of the source, with the file and the text of its
/// value (`1e8`, `1_000_000`, `64 * 1024 * 1024`).
fn limit_constants_in_source() -> Vec<(String, String, String)> {
    fn walk(dir: &Path, out: &mut Vec<std::path::PathBuf>) {
        for entry in std::fs::read_dir(dir).unwrap().flatten() {
            let path = entry.path();
            if path.is_dir() {
                walk(&path, out);
            } else if path.extension().is_some_and(|e| e == "rs") {
                out.push(path);
            }
        }
    }
    let mut files = Vec::new();
    walk(&common::repo("core/src"), &mut files);
    walk(&common::repo("src"), &mut files);
    files.sort();
    let mut found = Vec::new();
    for file in files {
        let text = std::fs::read_to_string(&file).unwrap();
        for line in text.lines() {
            let Some(at) = line.find("const ") else {
                continue;
            };
            let rest = &line[at + "const ".len()..];
            let Some((name, value)) = rest.split_once(':') else {
                continue;
            };
            let name = name.trim();
            if ["MAX_", "MIN_", "EXIT_"]
                .iter()
                .any(|p| name.starts_with(p))
            {
                let value = value
                    .split_once('=')
                    .map(|(_, v)| v.trim().trim_end_matches(';').trim().to_string())
                    .unwrap_or_default();
                let shown = file.strip_prefix(common::repo("")).unwrap_or(&file);
                found.push((name.to_string(), shown.display().to_string(), value));
            }
        }
    }
    found
}

#[test]
fn every_limit_constant_appears_in_the_limits_page_with_its_value() {
    let text = page("limits.md");
    let mut documented: BTreeMap<String, String> = BTreeMap::new();
    for (header, rows) in tables(&text, "limits") {
        let column = |name: &str| {
            header
                .iter()
                .position(|h| h == name)
                .unwrap_or_else(|| panic!("a limits table without a '{name}' column: {header:?}"))
        };
        let (value, constant) = (column("value"), column("constant"));
        for row in rows {
            for name in names(&row[constant]) {
                documented.insert(name, row[value].clone());
            }
        }
    }
    for row in table(&text, "exit codes") {
        for name in names(&row[1]) {
            documented.insert(name, row[0].clone());
        }
    }
    let mut values = known_values();
    let mut missing = Vec::new();
    for (name, file, source_value) in limit_constants_in_source() {
        let value = match values.get(name.as_str()) {
            Some(v) => *v,
            // A private constant: its value as the source writes it.
            None => match source_value.replace('_', "").parse::<f64>() {
                Ok(v) => v,
                Err(_) => panic!(
                    "{file}: const {name} = {source_value}: add it to known_values() of this test"
                ),
            },
        };
        values.remove(name.as_str());
        match documented.get(&name) {
            None => missing.push(format!("{name} ({file}, value {source_value})")),
            Some(cell) => {
                let shown = value_of(cell).unwrap_or(f64::NAN);
                assert!(
                    (shown - value).abs() <= 1e-12 * value.abs(),
                    "limits.md gives {name} as {cell:?}; the code has {value:e}"
                );
            }
        }
    }
    // The constants of known_values() that are not MAX_/MIN_/EXIT_ named.
    for (name, value) in values {
        match documented.get(name) {
            None => missing.push(format!("{name} (value {value:e})")),
            Some(cell) => assert!(
                (value_of(cell).unwrap_or(f64::NAN) - value).abs() <= 1e-12 * value.abs(),
                "limits.md gives {name} as {cell:?}; the code has {value:e}"
            ),
        }
    }
    assert!(
        missing.is_empty(),
        "constants missing from book/src/reference/limits.md:\n{}",
        missing.join("\n")
    );
}

#[test]
fn limit_values_are_read_as_written() {
    assert_eq!(value_of("64 MiB"), Some(64.0 * 1024.0 * 1024.0));
    assert_eq!(value_of("1e-5 s"), Some(1e-5));
    assert_eq!(value_of("196.133 m/s²"), Some(196.133));
    assert_eq!(value_of("200000"), Some(200000.0));
    assert_eq!(value_of("–"), None);
}

/// The subcommands a help text lists under `Commands:` (without `help`).
fn subcommands(help: &str) -> Vec<String> {
    help.lines()
        .skip_while(|l| l.trim() != "Commands:")
        .skip(1)
        .take_while(|l| l.starts_with("  "))
        .filter_map(|l| l.split_whitespace().next())
        .filter(|c| *c != "help")
        .map(str::to_string)
        .collect()
}

/// What `flexrock ARGS --help` prints.
fn help_of(command: &[String]) -> String {
    let mut args: Vec<&str> = command.iter().map(String::as_str).collect();
    args.push("--help");
    let o = common::flexrock(&args);
    assert!(o.status.success(), "flexrock {args:?}");
    String::from_utf8_lossy(&o.stdout).into_owned()
}

/// The quoted output of the fenced block of `text` that starts with the line `first`.
fn quoted_block(text: &str, first: &str) -> Option<String> {
    let lines: Vec<&str> = text.lines().collect();
    let start = lines.iter().position(|l| *l == first)?;
    let body: Vec<&str> = lines[start + 1..]
        .iter()
        .take_while(|l| !l.starts_with("```"))
        .copied()
        .collect();
    Some(body.join("\n") + "\n")
}

#[test]
fn the_commands_page_quotes_the_help_of_every_command_as_printed() {
    let text = page("commands.md");
    let mut queue: Vec<Vec<String>> = vec![Vec::new()];
    let mut quoted = 0;
    while let Some(command) = queue.pop() {
        let help = help_of(&command);
        for sub in subcommands(&help) {
            let mut next = command.clone();
            next.push(sub);
            queue.push(next);
        }
        let first = ["$ flexrock".to_string()]
            .into_iter()
            .chain(command.iter().cloned())
            .chain(["--help".to_string()])
            .collect::<Vec<_>>()
            .join(" ");
        match quoted_block(&text, &first) {
            None => panic!("commands.md quotes no `{first}`: add its help"),
            Some(block) => assert_eq!(block, help, "commands.md quotes another `{first}`"),
        }
        quoted += 1;
    }
    assert!(quoted >= 15, "{quoted} help texts");
}

#[test]
fn every_output_the_reference_pages_quote_is_what_the_program_prints() {
    // Blocks that start with `$ flexrock ...`, run from the repository root, where their
    // relative paths point. They write nothing, so they may run there.
    let mut runs = 0;
    for name in [
        "model-file.md",
        "commands.md",
        "outputs.md",
        "limits.md",
        "accuracy-and-speed.md",
    ] {
        let text = page(name);
        for first in text.lines().filter(|l| l.starts_with("$ flexrock ")) {
            let args: Vec<&str> = first["$ flexrock ".len()..].split_whitespace().collect();
            assert!(
                !args.contains(&"--out"),
                "{name}: `{first}` would write into the repository"
            );
            let o = common::flexrock_in(&common::repo(""), &args);
            assert!(o.status.success(), "{name}: `{first}` failed");
            let mut printed = String::from_utf8_lossy(&o.stderr).into_owned();
            printed.push_str(&String::from_utf8_lossy(&o.stdout));
            assert_eq!(
                quoted_block(&text, first).unwrap(),
                printed,
                "{name}: `{first}` prints something else"
            );
            runs += 1;
        }
    }
    assert!(runs >= 16, "{runs} quoted runs");
}

/// The `.rs` files under `dir`, as paths relative to it, sorted.
fn rust_files(dir: &Path) -> Vec<String> {
    fn walk(root: &Path, dir: &Path, out: &mut Vec<String>) {
        for entry in std::fs::read_dir(dir).unwrap().flatten() {
            let path = entry.path();
            if path.is_dir() {
                walk(root, &path, out);
            } else if path.extension().is_some_and(|e| e == "rs") {
                let relative = path.strip_prefix(root).unwrap();
                out.push(relative.to_string_lossy().replace('\\', "/"));
            }
        }
    }
    let mut out = Vec::new();
    walk(dir, dir, &mut out);
    out.sort();
    out
}

#[test]
fn the_code_map_links_every_source_file() {
    let map = std::fs::read_to_string(common::repo("book/src/developer/code-map.md")).unwrap();
    let mut missing = Vec::new();
    for crate_dir in ["core/src", "src"] {
        for file in rust_files(&common::repo(crate_dir)) {
            let link = format!("(../../../{crate_dir}/{file})");
            if !map.contains(&link) {
                missing.push(format!("{crate_dir}/{file}"));
            }
        }
    }
    assert!(
        missing.is_empty(),
        "book/src/developer/code-map.md links no row to: {}",
        missing.join(", ")
    );
}

#[test]
fn the_tests_page_lists_exactly_the_test_files() {
    let text = std::fs::read_to_string(common::repo("book/src/developer/tests.md")).unwrap();
    let mut listed = listed(&text, "test files");
    let mut files: Vec<String> = ["tests", "core/tests"]
        .iter()
        .flat_map(|dir| {
            rust_files(&common::repo(dir))
                .into_iter()
                .filter(|f| !f.contains('/'))
                .map(move |f| format!("{dir}/{f}"))
        })
        .collect();
    listed.sort();
    files.sort();
    assert_eq!(listed, files, "the table of book/src/developer/tests.md");
}

/// The modules a test binary's main file declares (`mod name;` lines), sorted.
fn declared_modules(main: &str) -> Vec<String> {
    let mut modules: Vec<String> = main
        .lines()
        .filter_map(|line| line.trim().strip_prefix("mod "))
        .filter_map(|rest| rest.strip_suffix(';'))
        .map(str::to_string)
        .collect();
    modules.sort();
    modules
}

#[test]
fn every_test_file_is_a_module_of_its_crates_test_binary() {
    // Cargo.toml sets `autotests = false`: a file that its crate's binary does not declare is
    // never built nor run.
    for (dir, main) in [
        ("tests", "integration.rs"),
        ("core/tests", "core_integration.rs"),
    ] {
        let text = std::fs::read_to_string(common::repo(dir).join(main)).unwrap();
        let mut files: Vec<String> = rust_files(&common::repo(dir))
            .into_iter()
            .filter(|f| !f.contains('/') && f != main)
            .map(|f| f.trim_end_matches(".rs").to_string())
            .collect();
        files.push("common".to_string());
        files.sort();
        assert_eq!(
            declared_modules(&text),
            files,
            "the modules of {dir}/{main}"
        );
    }
}

#[test]
fn declared_modules_are_the_mod_lines() {
    let main = "//! mod not_this;\nmod common;\n\n// A group.\nmod b;\nmod a;\nfn f() {}\n";
    assert_eq!(declared_modules(main), ["a", "b", "common"]);
}
