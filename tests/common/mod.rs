//! Helpers shared by the integration tests.
#![allow(dead_code)]

#[path = "../../core/tests/common/mod.rs"]
mod physics;
pub use physics::*;

/// The `flexrock` binary as a command to complete (arguments, environment, directory, pipes).
pub fn flexrock_command() -> std::process::Command {
    std::process::Command::new(env!("CARGO_BIN_EXE_flexrock"))
}

/// Runs the `flexrock` binary.
pub fn flexrock(args: &[&str]) -> std::process::Output {
    flexrock_command()
        .args(args)
        .output()
        .expect("the binary runs")
}

/// Runs the `flexrock` binary in the directory `cwd`: relative paths as a user types them. The
/// tests' own working directory is shared by every test of the binary and never changed.
pub fn flexrock_in(cwd: &std::path::Path, args: &[&str]) -> std::process::Output {
    flexrock_command()
        .current_dir(cwd)
        .args(args)
        .output()
        .expect("the binary runs")
}

/// The output of `command`, which must succeed (its standard error is the message if not).
pub fn ok(command: &mut std::process::Command) -> std::process::Output {
    let o = command.output().unwrap();
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    o
}

/// A path inside the repository.
pub fn repo(path: &str) -> std::path::PathBuf {
    std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join(path)
}

/// The paper's example.
pub fn reference_model() -> std::path::PathBuf {
    repo("models/ichinose1986.toml")
}

/// Runs the paper's example, `flexrock run models/ichinose1986.toml --out OUT EXTRA...`.
pub fn run_reference(out: &std::path::Path, extra: &[&str]) -> std::process::Output {
    run_model(&reference_model(), out, extra)
}

/// `flexrock run MODEL --out OUT EXTRA...`.
pub fn run_model(
    model: &std::path::Path,
    out: &std::path::Path,
    extra: &[&str],
) -> std::process::Output {
    let mut args = vec![
        "run",
        model.to_str().unwrap(),
        "--out",
        out.to_str().unwrap(),
    ];
    args.extend_from_slice(extra);
    flexrock(&args)
}

/// Runs `flexrock SUBCOMMAND model --out DIR` on a model text that must be refused: exit code 2,
/// no output directory, no panic. Returns the error message.
pub fn refused(subcommand: &str, name: &str, model_text: &str) -> String {
    refused_with(subcommand, name, model_text, &[])
}

/// [`refused`] with more arguments after the model file (flags such as `--set`).
pub fn refused_with(subcommand: &str, name: &str, model_text: &str, args: &[&str]) -> String {
    let dir = scratch_dir(&format!("refused-{subcommand}-{name}"));
    let model = dir.join("model.toml");
    std::fs::write(&model, model_text).unwrap();
    let out = dir.join("out");
    let mut all = vec![subcommand, model.to_str().unwrap()];
    all.extend_from_slice(args);
    all.extend_from_slice(&["--out", out.to_str().unwrap()]);
    let o = flexrock(&all);
    let stderr = String::from_utf8_lossy(&o.stderr).into_owned();
    assert_eq!(o.status.code(), Some(2), "{name}: {stderr}");
    assert!(!out.exists(), "{name}: output directory was created");
    assert!(!stderr.contains("panicked"), "{name}: {stderr}");
    stderr
}

/// The sorted names of the files in a directory.
pub fn file_names(dir: &std::path::Path) -> Vec<String> {
    let mut names: Vec<String> = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    names.sort();
    names
}

/// sweep.csv of the sweep in `dir` as rows of column name -> text.
pub fn sweep_rows(dir: &std::path::Path) -> Vec<std::collections::HashMap<String, String>> {
    let mut reader = csv::Reader::from_path(dir.join("sweep.csv")).expect("sweep.csv");
    let headers = reader.headers().unwrap().clone();
    reader
        .records()
        .map(|r| {
            let r = r.unwrap();
            headers
                .iter()
                .zip(r.iter())
                .map(|(h, v)| (h.to_string(), v.to_string()))
                .collect()
        })
        .collect()
}

/// The chunk files of the sweep store in `dir` (`chunks/NNNNNNNN.csv`), sorted.
pub fn chunk_files(dir: &std::path::Path) -> Vec<std::path::PathBuf> {
    let mut files: Vec<std::path::PathBuf> = std::fs::read_dir(dir.join("chunks"))
        .map(|entries| {
            entries
                .filter_map(|e| e.ok())
                .map(|e| e.path())
                .filter(|p| {
                    p.file_name()
                        .and_then(|n| n.to_str())
                        .is_some_and(|n| n.len() == 13 && n.ends_with(".csv"))
                })
                .collect()
        })
        .unwrap_or_default();
    files.sort();
    files
}

/// The commit the tested flexrock was built from, as `git rev-parse HEAD` gives it here
/// ("unknown" without git or outside a git work tree, as the build records it then).
pub fn built_commit() -> String {
    std::process::Command::new("git")
        .args(["rev-parse", "HEAD"])
        .current_dir(env!("CARGO_MANIFEST_DIR"))
        .output()
        .ok()
        .filter(|o| o.status.success())
        .map(|o| String::from_utf8_lossy(&o.stdout).trim().to_string())
        .unwrap_or_else(|| "unknown".to_string())
}

/// Starts `command` and kills it (SIGKILL) once `dir/chunks` holds at least `chunks` chunk
/// files. Fails the test if the command ends first.
pub fn kill_after_chunks(
    command: &mut std::process::Command,
    dir: &std::path::Path,
    chunks: usize,
) {
    let mut child = command
        .stdout(std::process::Stdio::null())
        .stderr(std::process::Stdio::null())
        .spawn()
        .unwrap();
    let started = std::time::Instant::now();
    while chunk_files(dir).len() < chunks {
        if let Some(status) = child.try_wait().unwrap() {
            panic!("the command ended ({status}) before {chunks} chunks were written");
        }
        assert!(
            started.elapsed() < std::time::Duration::from_secs(120),
            "no chunks"
        );
        std::thread::sleep(std::time::Duration::from_millis(2));
    }
    child.kill().unwrap();
    child.wait().unwrap();
}
