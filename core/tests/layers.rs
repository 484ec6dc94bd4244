//! The core's folders are its layers, bottom up: the base (units, formatting, limits), the physics
//! of one body, the floor motions, the integrators, the bodies built on them, then the error,
//! the model file and simulation, the tables, and the analyses. A file may take names only from
//! its own layer and the layers below it, and no files import each other round a loop
//! (book/src/developer/code-map.md).

use std::path::Path;

use crate::common::imports::{named_paths, Graph};

/// The entries of core/src from the bottom up (lib.rs aside). A file may use only its own layer
/// and those before it.
const LAYERS: [&str; 10] = [
    "base",
    "physics",
    "floor",
    "integrate",
    "bodies",
    "error",
    "model",
    "simulate",
    "tables",
    "analysis",
];

fn src() -> std::path::PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("src")
}

/// The layer of a file of core/src (its first path component, without `.rs`).
fn layer_of(file: &str) -> &str {
    let first = file.split('/').next().unwrap();
    first.strip_suffix(".rs").unwrap_or(first)
}

#[test]
fn core_src_holds_the_layers_and_lib_rs() {
    let mut entries: Vec<String> = std::fs::read_dir(src())
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().to_string())
        .map(|name| name.strip_suffix(".rs").map(str::to_string).unwrap_or(name))
        .filter(|name| name != "lib")
        .collect();
    entries.sort();
    let mut layers: Vec<String> = LAYERS.iter().map(|s| s.to_string()).collect();
    layers.sort();
    assert_eq!(entries, layers, "core/src's entries are not the layers");
}

#[test]
fn every_file_uses_only_its_layer_and_those_below() {
    let position = |name: &str| LAYERS.iter().position(|&m| m == name);
    let graph = Graph::of(&src());
    let mut upward = Vec::new();
    for (file, targets) in &graph.arrows {
        if file == "lib.rs" {
            continue;
        }
        let own = position(layer_of(file)).unwrap_or_else(|| panic!("{file}: no layer"));
        for (target, names) in targets {
            if target == "lib.rs" {
                // The crate's error and result, re-exported at its root.
                continue;
            }
            match position(layer_of(target)) {
                Some(at) if at <= own => {}
                _ => upward.push(format!("{file} -> {target}: {names:?}")),
            }
        }
    }
    assert!(upward.is_empty(), "imports up the layers: {upward:#?}");
}

/// Folders whose files still import each other round a loop: each is to be taken apart, and
/// none may be added (a folder taken apart leaves this list). Empty: no folder has one.
const FOLDERS_WITH_CIRCLES: [&str; 0] = [];

/// The folder of a circle's line "from -> to: names" (its first file's).
fn folder_of(line: &str) -> &str {
    let file = line.split(" -> ").next().unwrap_or("");
    file.rsplit_once('/').map_or("", |(folder, _)| folder)
}

#[test]
fn no_files_of_the_core_import_each_other_round_a_loop() {
    let circles = Graph::of(&src()).circles();
    let mut folders = Vec::new();
    for circle in &circles {
        let folder = folder_of(&circle[0]);
        // A circle across folders is one between modules: never allowed.
        assert!(
            circle.iter().all(|line| folder_of(line) == folder)
                && circle.iter().all(|line| {
                    let to = line.split(" -> ").nth(1).unwrap_or("");
                    to.rsplit_once('/').map_or("", |(f, _)| f) == folder
                }),
            "a circle between modules: {circle:#?}"
        );
        assert!(
            FOLDERS_WITH_CIRCLES.contains(&folder),
            "a new circle in {folder}: {circle:#?}"
        );
        folders.push(folder);
    }
    for known in FOLDERS_WITH_CIRCLES {
        assert!(
            folders.contains(&known),
            "{known} has no circle any more: take it off FOLDERS_WITH_CIRCLES"
        );
    }
}

#[test]
fn the_reader_sees_use_trees_and_inline_paths() {
    let code = "use crate::physics::{automaton::{Automaton, Mode as M}, body};\n\
                pub use flow::Flow;\n\
                fn f() -> crate::Result<()> { crate::base::format::number(1.0); super::super::x::Y }\n";
    let paths: Vec<String> = named_paths(code)
        .iter()
        .map(|n| {
            format!(
                "{}::{}{}",
                n.start,
                n.segments.join("::"),
                if n.reexport { " (re-export)" } else { "" }
            )
        })
        .collect();
    assert_eq!(
        paths,
        [
            "crate::physics::automaton::Automaton",
            "crate::physics::automaton::Mode",
            "crate::physics::body",
            "flow::Flow (re-export)",
            "crate::Result",
            "crate::base::format::number",
            "super::super::x::Y",
        ]
    );
}

#[test]
fn the_checker_finds_a_circle_and_sees_through_a_face() {
    let dir = crate::common::scratch_dir("layers-circle");
    let write = |name: &str, text: &str| {
        let path = dir.join(name);
        std::fs::create_dir_all(path.parent().unwrap()).unwrap();
        std::fs::write(path, text).unwrap();
    };
    write("lib.rs", "pub mod a;\npub mod b;\n");
    // a's face re-exports its submodule; b takes the name through the face.
    write("a/mod.rs", "mod inner;\npub use inner::Thing;\n");
    write("a/inner.rs", "use crate::b::Other;\npub struct Thing;\n");
    write(
        "b.rs",
        "use crate::a::Thing;\npub struct Other;\n#[cfg(test)]\nmod tests { use crate::a; }\n",
    );
    let circles = Graph::of(&dir).circles();
    assert_eq!(circles.len(), 1, "{circles:?}");
    assert_eq!(
        circles[0],
        ["a/inner.rs -> b.rs: Other", "b.rs -> a/inner.rs: Thing"]
    );
    // Without the arrow back there is no circle, and the face draws none.
    write("a/inner.rs", "pub struct Thing;\n");
    assert!(Graph::of(&dir).circles().is_empty());
    std::fs::remove_dir_all(&dir).ok();
}
