//! The core's modules form layers with no circle: units and formatting at the bottom, then the
//! physics (body, flexural shape, constants, automaton, records, excitations), then the numerics
//! (solution, solvers, intensity measures, rigid block, finite elements), then the model file and simulation, then
//! the analyses (comparisons, convergence studies, the finite element checks). Every `crate::`
//! path in a module's code (its tests aside) must name a module listed before it.

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

/// The modules from the bottom up. A module may use only the modules before it.
const LAYERS: [&str; 33] = [
    // units and formatting
    "units",
    "format",
    "columns",
    "suggest",
    "limits",
    "invalid",
    "double_double",
    // physics
    "body",
    "flexural_shape",
    "constants",
    "automaton",
    "record",
    "excitation",
    // numerics
    "solution",
    "run_tables",
    "solver",
    "intensity",
    "rigid",
    "rigid_criteria",
    "row",
    "fem",
    "findings",
    // the model file and simulation
    "error",
    "model",
    "simulate",
    "summary",
    "row_results",
    // analysis
    "sweep",
    "compare",
    "converge",
    "fem_check",
    "pushover_check",
    "criteria",
];

/// The files of module `name` under `src`: `name.rs`, or every file under `name/`.
fn files_of(src: &Path, name: &str) -> Vec<PathBuf> {
    let single = src.join(format!("{name}.rs"));
    if single.is_file() {
        return vec![single];
    }
    let mut files = Vec::new();
    let mut dirs = vec![src.join(name)];
    while let Some(dir) = dirs.pop() {
        for entry in std::fs::read_dir(&dir).unwrap_or_else(|e| panic!("{}: {e}", dir.display())) {
            let path = entry.unwrap().path();
            if path.is_dir() {
                dirs.push(path);
            } else if path.extension().is_some_and(|e| e == "rs") {
                files.push(path);
            }
        }
    }
    files
}

/// The code of a file without its test module (a `#[cfg(test)]` followed by `mod tests`, which
/// by the project's convention ends the file) and without its comments; a file named `tests.rs`
/// is all test.
fn code_without_tests(path: &Path) -> String {
    if path.file_name().is_some_and(|n| n == "tests.rs") {
        return String::new();
    }
    let text = std::fs::read_to_string(path).unwrap();
    let lines: Vec<&str> = text.lines().collect();
    let end = lines
        .windows(2)
        .position(|w| w[0].trim() == "#[cfg(test)]" && w[1].trim_start().starts_with("mod tests"))
        .unwrap_or(lines.len());
    lines[..end]
        .iter()
        .map(|line| line.split("//").next().unwrap_or(""))
        .collect::<Vec<_>>()
        .join("\n")
}

/// The top-level modules that `code` names as `crate::NAME`.
fn used_modules(code: &str) -> Vec<String> {
    let mut used = Vec::new();
    let mut rest = code;
    while let Some(at) = rest.find("crate::") {
        rest = &rest[at + "crate::".len()..];
        let name: String = rest
            .chars()
            .take_while(|c| c.is_ascii_alphanumeric() || *c == '_')
            .collect();
        if name == "Error" || name == "Result" {
            // The crate's error, re-exported at its root.
            used.push("error".to_string());
        } else if name.is_empty() {
            // `crate::{a, b}`: every name in the braces.
            if let Some(group) = rest.strip_prefix('{').and_then(|g| g.split_once('}')) {
                for part in group.0.split(',') {
                    let name = part.trim().split("::").next().unwrap_or("").trim();
                    if !name.is_empty() {
                        used.push(name.to_string());
                    }
                }
            }
        } else {
            used.push(name);
        }
    }
    used
}

/// Module -> the modules it uses (other than itself), for every module in the layers.
fn import_graph() -> BTreeMap<&'static str, Vec<String>> {
    let src = Path::new(env!("CARGO_MANIFEST_DIR")).join("src");
    LAYERS
        .iter()
        .map(|&name| {
            let mut used: Vec<String> = files_of(&src, name)
                .iter()
                .flat_map(|file| used_modules(&code_without_tests(file)))
                .filter(|used| used != name)
                .collect();
            used.sort();
            used.dedup();
            (name, used)
        })
        .collect()
}

#[test]
fn every_module_uses_only_the_layers_below_it() {
    let position = |name: &str| LAYERS.iter().position(|&m| m == name);
    let mut upward = Vec::new();
    for (module, used) in import_graph() {
        for name in used {
            match position(&name) {
                Some(at) if at < position(module).unwrap() => {}
                Some(_) => upward.push(format!("{module} -> {name}")),
                None => upward.push(format!("{module} -> {name} (a module not in the layers)")),
            }
        }
    }
    assert!(
        upward.is_empty(),
        "imports up the layers (or into a module the layers do not list): {upward:?}"
    );
}

#[test]
fn every_module_of_the_crate_is_in_the_layers() {
    let lib =
        std::fs::read_to_string(Path::new(env!("CARGO_MANIFEST_DIR")).join("src/lib.rs")).unwrap();
    let declared: Vec<&str> = lib
        .lines()
        .filter_map(|line| {
            let line = line.trim();
            let rest = line
                .strip_prefix("pub mod ")
                .or(line.strip_prefix("mod "))?;
            rest.strip_suffix(';')
        })
        .collect();
    assert!(!declared.is_empty());
    for module in &declared {
        assert!(
            LAYERS.contains(module),
            "src/lib.rs declares {module}, which no layer lists"
        );
    }
    for module in LAYERS {
        assert!(
            declared.contains(&module),
            "the layers list {module}, which src/lib.rs lacks"
        );
    }
}

#[test]
fn the_checker_sees_an_upward_import() {
    let code = "use crate::model::Model;\nfn f() -> crate::Result<()> { crate::format::shortest(1.0); }\nuse crate::{units, limits::at_most};\n// crate::simulate in a comment\n";
    let mut used = used_modules(&code_without_tests_of(code));
    used.sort();
    assert_eq!(used, ["error", "format", "limits", "model", "units"]);
}

/// [`code_without_tests`] of text rather than a file.
fn code_without_tests_of(text: &str) -> String {
    let dir = crate::common::scratch_dir("layers-module");
    let file = dir.join("module.rs");
    std::fs::write(
        &file,
        format!("{text}#[cfg(test)]\nmod tests {{ use crate::simulate; }}\n"),
    )
    .unwrap();
    let code = code_without_tests(&file);
    std::fs::remove_dir_all(&dir).ok();
    code
}
