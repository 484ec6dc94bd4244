//! The command line's files import each other without a loop, and its figures draw plain data:
//! no figure takes a name from a command (book/src/developer/code-map.md).

use std::path::Path;

use crate::common::imports::Graph;

fn src() -> std::path::PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("src")
}

#[test]
fn no_files_of_the_command_line_import_each_other_round_a_loop() {
    let circles = Graph::of(&src()).circles();
    assert!(circles.is_empty(), "circles: {circles:#?}");
}

#[test]
fn no_figure_imports_a_command() {
    let graph = Graph::of(&src());
    let mut wrong = Vec::new();
    for (file, targets) in &graph.arrows {
        if !file.starts_with("figures/") {
            continue;
        }
        for (target, names) in targets {
            if target.starts_with("commands/") {
                wrong.push(format!("{file} -> {target}: {names:?}"));
            }
        }
    }
    assert!(wrong.is_empty(), "figures that import commands: {wrong:#?}");
}
