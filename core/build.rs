//! Records which commit flexrock is built from, for the summaries to say how a result was made:
//! `FLEXROCK_COMMIT`, the commit's hash ("unknown" outside a git work tree or without git), and
//! `FLEXROCK_DIRTY`, "true" when the program's tracked sources ([`SOURCES`]) differed from it
//! ("unknown" with the hash).

use std::path::{Path, PathBuf};
use std::process::Command;

/// The sources of the program, from the workspace's folder: the core library, the command
/// line and the manifests. A change elsewhere (tests, the book) does not make a build dirty.
const SOURCES: [&str; 4] = ["core", "src", "Cargo.toml", "Cargo.lock"];

/// The trimmed standard output of `git ARGS` run in this crate's folder, if git ran and succeeded.
fn git(args: &[&str]) -> Option<String> {
    let output = Command::new("git")
        // Never take the index lock: `git status` would otherwise refresh the index, whose
        // change would run this script again on the next build.
        .arg("--no-optional-locks")
        .args(args)
        .current_dir(env!("CARGO_MANIFEST_DIR"))
        .output()
        .ok()?;
    output
        .status
        .success()
        .then(|| String::from_utf8_lossy(&output.stdout).trim().to_string())
}

fn main() {
    let manifest = PathBuf::from(env!("CARGO_MANIFEST_DIR"));
    let workspace = manifest.parent().unwrap_or(&manifest).to_path_buf();
    let commit = git(&["rev-parse", "HEAD"]).filter(|hash| !hash.is_empty());
    let mut status = vec![
        "-C",
        workspace.to_str().unwrap_or("."),
        "status",
        "--porcelain",
    ];
    status.extend(["--untracked-files=no", "--"]);
    status.extend(SOURCES);
    let dirty = commit
        .as_ref()
        .and_then(|_| git(&status))
        .map(|changes| (!changes.is_empty()).to_string());
    println!(
        "cargo:rustc-env=FLEXROCK_COMMIT={}",
        commit.as_deref().unwrap_or("unknown")
    );
    println!(
        "cargo:rustc-env=FLEXROCK_DIRTY={}",
        dirty.as_deref().unwrap_or("unknown")
    );
    // Run again when the commit or the index moves, or when a source changes (which can make
    // the build dirty or clean).
    let mut watched: Vec<PathBuf> = SOURCES.iter().map(|path| workspace.join(path)).collect();
    if let Some(dir) = git(&["rev-parse", "--absolute-git-dir"]) {
        let dir = PathBuf::from(dir);
        watched.extend([dir.join("HEAD"), dir.join("index")]);
        if let Some(common) = git(&["rev-parse", "--git-common-dir"]) {
            let common = absolute(&manifest, Path::new(&common));
            watched.push(common.join("packed-refs"));
            if let Some(branch) = git(&["symbolic-ref", "-q", "HEAD"]) {
                watched.push(common.join(branch));
            }
        }
    }
    for path in watched.iter().filter(|path| path.exists()) {
        println!("cargo:rerun-if-changed={}", path.display());
    }
}

/// `path` taken from `base` when it is relative (git prints some of its folders relative).
fn absolute(base: &Path, path: &Path) -> PathBuf {
    if path.is_absolute() {
        path.to_path_buf()
    } else {
        base.join(path)
    }
}
