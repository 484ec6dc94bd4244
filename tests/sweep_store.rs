//! The sweep store under attack: directories it does not own, chunks and shards tampered with
//! between a kill and the resume or merge, records replaced, two processes in one directory,
//! finished results damaged. Every case ends either in the bytes of an uninterrupted run or in a
//! refusal with exit code 2 that names the file; nothing of the user's is removed.

use crate::common;

use std::path::{Path, PathBuf};
use std::process::{Child, Command, Output, Stdio};
use std::time::{Duration, Instant};

use crate::common::{flexrock, kill_after_chunks, ok, repo, scratch_dir};

fn files_of(dir: &Path) -> Vec<(String, Vec<u8>)> {
    let mut files: Vec<(String, Vec<u8>)> = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap())
        .filter(|e| e.file_type().unwrap().is_file())
        .map(|e| {
            (
                e.file_name().to_string_lossy().into_owned(),
                std::fs::read(e.path()).unwrap(),
            )
        })
        .collect();
    files.sort();
    files
}

/// `flexrock sweep models/pulse-map.toml --out OUT`, to be given its axes.
fn pulse_sweep(out: &Path) -> Command {
    let mut command = common::flexrock_command();
    command.args([
        "sweep",
        repo("models/pulse-map.toml").to_str().unwrap(),
        "--out",
        out.to_str().unwrap(),
    ]);
    command
}

/// The 480-point map of the pulse model, one thread, chunks of 16 points: slow enough (a
/// second or more) to be caught half-way.
fn grid(out: &Path, extra: &[&str]) -> Command {
    let mut command = pulse_sweep(out);
    command.args([
        "--vary",
        "excitation.period=lin:0.3:1.5:24",
        "--vary",
        "excitation.amplitude=lin:1:8:20",
        "--chunk-size",
        "16",
        "--threads",
        "1",
        "--quiet",
    ]);
    command.args(extra);
    command
}

/// Exit code 2, a message naming `needle`, no panic. Returns standard error.
fn refused(o: &Output, needle: &str) -> String {
    let stderr = String::from_utf8_lossy(&o.stderr).into_owned();
    assert_eq!(o.status.code(), Some(2), "{stderr}");
    assert!(stderr.contains(needle), "expected {needle:?} in: {stderr}");
    assert!(!stderr.contains("panicked"), "{stderr}");
    stderr
}

/// The uninterrupted run, made once per test that needs it.
fn reference(dir: &Path) -> Vec<(String, Vec<u8>)> {
    let out = dir.join("reference");
    ok(&mut grid(&out, &[]));
    files_of(&out)
}

#[test]
fn a_chunks_directory_flexrock_did_not_make_is_refused_and_kept() {
    let dir = scratch_dir("store-foreign-chunks");
    let out = dir.join("P");
    std::fs::create_dir_all(out.join("chunks")).unwrap();
    std::fs::write(out.join("chunks/mydata.txt"), "precious").unwrap();
    let o = grid(&out, &[]).output().unwrap();
    let stderr = refused(&o, "mydata.txt");
    assert!(stderr.contains(&out.join("chunks").display().to_string()));
    assert_eq!(
        std::fs::read_to_string(out.join("chunks/mydata.txt")).unwrap(),
        "precious"
    );
    assert!(!out.join("sweep.csv").exists());
    // --force replaces only what flexrock wrote: still refused.
    let o = grid(&out, &["--force"]).output().unwrap();
    refused(&o, "mydata.txt");
    assert!(out.join("chunks/mydata.txt").exists());

    // A chunks link to a directory is neither followed nor removed.
    let target = dir.join("target");
    std::fs::create_dir_all(&target).unwrap();
    std::fs::write(target.join("keep.txt"), "mine").unwrap();
    let linked = dir.join("L");
    std::fs::create_dir_all(&linked).unwrap();
    std::os::unix::fs::symlink(&target, linked.join("chunks")).unwrap();
    let o = grid(&linked, &[]).output().unwrap();
    refused(&o, "symbolic link");
    assert!(linked
        .join("chunks")
        .symlink_metadata()
        .unwrap()
        .is_symlink());
    assert_eq!(common::file_names(&target), ["keep.txt"]);
}

#[test]
fn an_output_path_inside_a_file_is_refused_before_computing() {
    let dir = scratch_dir("store-out-in-file");
    let file = dir.join("afile");
    std::fs::write(&file, "x").unwrap();
    let started = Instant::now();
    let o = grid(&file.join("sub"), &[]).output().unwrap();
    refused(&o, &file.display().to_string());
    // Refused before the 480 points (a second or more) were computed.
    assert!(started.elapsed() < Duration::from_secs(1), "computed first");
    assert_eq!(std::fs::read_to_string(&file).unwrap(), "x");
}

#[test]
fn tampered_chunks_are_computed_again_and_named() {
    let dir = scratch_dir("store-tampered");
    let expected = reference(&dir);
    type Edit = fn(&[PathBuf]);
    let edits: [(&str, Edit); 7] = [
        ("copied over another", |c| {
            std::fs::copy(&c[0], &c[1]).unwrap();
        }),
        ("lines swapped", |c| {
            let text = std::fs::read_to_string(&c[1]).unwrap();
            let mut lines: Vec<&str> = text.lines().collect();
            lines.swap(1, 2);
            std::fs::write(&c[1], lines.join("\n") + "\n").unwrap();
        }),
        ("overturned flag edited", |c| {
            let text = std::fs::read_to_string(&c[2]).unwrap();
            let edited = if text.contains(",false,") {
                text.replacen(",false,", ",true,", 1)
            } else {
                text.replacen(",true,", ",false,", 1)
            };
            assert_ne!(edited, text);
            std::fs::write(&c[2], edited).unwrap();
        }),
        ("CRLF line ends", |c| {
            let text = std::fs::read_to_string(&c[0]).unwrap();
            std::fs::write(&c[0], text.replace('\n', "\r\n")).unwrap();
        }),
        ("seal line removed", |c| {
            let text = std::fs::read_to_string(&c[1]).unwrap();
            let rows = text.split_once('\n').unwrap().1;
            std::fs::write(&c[1], rows).unwrap();
        }),
        ("truncated", |c| {
            let bytes = std::fs::read(&c[2]).unwrap();
            std::fs::write(&c[2], &bytes[..bytes.len() / 2]).unwrap();
        }),
        // What a crash of the machine can leave of a chunk, which is not synced: its name
        // with none of its data, and a temporary file of a write under way.
        ("emptied", |c| {
            std::fs::write(&c[0], "").unwrap();
            let bytes = std::fs::read(&c[1]).unwrap();
            let torn = c[1].with_file_name(".flexrock-tmp-999999999-7f3a");
            std::fs::write(torn, &bytes[..bytes.len() / 3]).unwrap();
        }),
    ];
    for (name, edit) in edits {
        let out = dir.join(name.replace(' ', "-"));
        kill_after_chunks(&mut grid(&out, &[]), &out, 3);
        let chunks = crate::common::chunk_files(&out);
        edit(&chunks);
        let o = ok(&mut grid(&out, &[]));
        let stderr = String::from_utf8_lossy(&o.stderr);
        assert!(
            stderr.contains("computed again") && stderr.contains("chunks/0000000"),
            "{name}: {stderr}"
        );
        assert_eq!(files_of(&out), expected, "{name}");
        assert_eq!(
            common::file_names(&out),
            ["map.svg", "sweep.csv", "sweep.json"]
        );
    }
}

#[test]
fn chunks_of_another_sweep_are_never_mixed_in() {
    let dir = scratch_dir("store-other-chunks");
    let expected = reference(&dir);
    // Chunks of the same grid at another amplitude range, with this sweep's plan.json beside
    // them: the seals tell them apart.
    let other = dir.join("other");
    let mut other_grid = grid(&other, &[]);
    other_grid.args(["--set", "body.damping_ratio=0.02"]);
    kill_after_chunks(&mut other_grid, &other, 4);
    let out = dir.join("out");
    kill_after_chunks(&mut grid(&out, &[]), &out, 1);
    for chunk in crate::common::chunk_files(&other) {
        std::fs::copy(&chunk, out.join("chunks").join(chunk.file_name().unwrap())).unwrap();
    }
    let o = ok(&mut grid(&out, &[]));
    assert!(String::from_utf8_lossy(&o.stderr).contains("does not match its seal"));
    assert_eq!(files_of(&out), expected);
    // Its plan.json too: refused, then replaced with --force.
    let o = grid(&other, &[]).output().unwrap();
    refused(&o, "another sweep");
    ok(&mut grid(&other, &["--force"]));
    assert_eq!(files_of(&other), expected);
}

/// A record model whose record file lives in the scratch directory.
fn record_model(dir: &Path, record: &str) -> PathBuf {
    std::fs::copy(repo(record), dir.join("record.AT2")).unwrap();
    let model = dir.join("model.toml");
    std::fs::write(
        &model,
        "[body]\nheight = 4.0\nwidth = 0.7\ndepth = 1.0\ndensity = 600.0\n\
         youngs_modulus = 5.0e6\ndamping_ratio = 0.05\ngravity = 9.81\n\n\
         [excitation]\nkind = \"record\"\npath = \"record.AT2\"\nend = 6.0\n",
    )
    .unwrap();
    model
}

fn scale_sweep(model: &Path, out: &Path, extra: &[&str]) -> Command {
    let mut command = common::flexrock_command();
    command.args([
        "sweep",
        model.to_str().unwrap(),
        "--out",
        out.to_str().unwrap(),
        "--vary",
        "excitation.scale=lin:0.5:3:60",
        "--chunk-size",
        "4",
        "--threads",
        "1",
        "--quiet",
    ]);
    command.args(extra);
    command
}

#[test]
fn a_record_replaced_between_kill_and_resume_makes_another_sweep() {
    let dir = scratch_dir("store-record");
    let model = record_model(&dir, "validation/records/elCentro.AT2");
    let out = dir.join("out");
    kill_after_chunks(&mut scale_sweep(&model, &out, &[]), &out, 2);
    std::fs::copy(
        repo("validation/records/A-ELC180.AT2"),
        dir.join("record.AT2"),
    )
    .unwrap();
    let o = scale_sweep(&model, &out, &[]).output().unwrap();
    refused(&o, "record file");
    // With --force, every row is of the new record: the same bytes as a fresh run of it.
    ok(&mut scale_sweep(&model, &out, &["--force"]));
    let fresh = dir.join("fresh");
    ok(&mut scale_sweep(&model, &fresh, &[]));
    assert_eq!(files_of(&out), files_of(&fresh));
}

#[test]
fn a_record_axis_resumed_from_another_directory_is_another_sweep() {
    let dir = scratch_dir("store-record-axis");
    let model = record_model(&dir, "validation/records/elCentro.AT2");
    let (one, two) = (dir.join("one"), dir.join("two"));
    for (place, record) in [
        (&one, "validation/records/elCentro.AT2"),
        (&two, "validation/records/A-ELC180.AT2"),
    ] {
        std::fs::create_dir_all(place.join("records")).unwrap();
        for name in ["a.AT2", "b.AT2"] {
            std::fs::copy(repo(record), place.join("records").join(name)).unwrap();
        }
    }
    let out = dir.join("out");
    let sweep = |cwd: &Path| {
        let mut command = scale_sweep(&model, &out, &[]);
        command
            .current_dir(cwd)
            .args(["--vary", "excitation.path=records/*.AT2"]);
        command
    };
    kill_after_chunks(&mut sweep(&one), &out, 2);
    let o = sweep(&two).output().unwrap();
    refused(&o, "another sweep");
    // From the first directory it resumes.
    ok(&mut sweep(&one));
}

#[test]
fn the_spectrum_command_runs_twice_and_resumes_after_a_kill() {
    // The default --tol, (15 - 0.5)/1e4 = 0.0014500000000000001, did not read back bit for bit.
    let dir = scratch_dir("store-find-min");
    let spectrum = |out: &Path| {
        let mut command = pulse_sweep(out);
        command.args([
            "--vary",
            "excitation.period=log:0.2:3:6",
            "--find-min",
            "excitation.amplitude=0.5:15",
            "--scan",
            "20",
            "--chunk-size",
            "1",
            "--threads",
            "1",
            "--quiet",
        ]);
        command
    };
    let reference = dir.join("reference");
    ok(&mut spectrum(&reference));
    let o = ok(&mut spectrum(&reference));
    let stdout = String::from_utf8_lossy(&o.stdout);
    assert!(stdout.contains("0 computed now"), "{stdout}");
    // It wrote nothing, and says so.
    assert!(
        stdout.contains("found") && !stdout.contains("wrote"),
        "{stdout}"
    );
    let out = dir.join("killed");
    kill_after_chunks(&mut spectrum(&out), &out, 1);
    ok(&mut spectrum(&out));
    assert_eq!(files_of(&out), files_of(&reference));
}

#[test]
fn two_processes_cannot_write_one_sweep() {
    let dir = scratch_dir("store-lock");
    let expected = reference(&dir);
    let out = dir.join("out");
    let mut first = grid(&out, &[])
        .stdout(Stdio::null())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    let started = Instant::now();
    while crate::common::chunk_files(&out).is_empty() {
        assert!(started.elapsed() < Duration::from_secs(120));
        std::thread::sleep(Duration::from_millis(2));
    }
    let o = grid(&out, &[]).output().unwrap();
    refused(&o, "another flexrock process");
    assert!(first.wait().unwrap().success());
    assert_eq!(files_of(&out), expected);
}

#[test]
fn a_damaged_finished_sweep_is_refused_or_recomputed_with_force() {
    let dir = scratch_dir("store-damaged");
    let expected = reference(&dir);
    let out = dir.join("out");
    ok(&mut grid(&out, &[]));
    // A missing figure is drawn again from sweep.csv.
    std::fs::remove_file(out.join("map.svg")).unwrap();
    let o = ok(&mut grid(&out, &[]));
    assert!(String::from_utf8_lossy(&o.stdout).contains("0 computed now"));
    assert_eq!(files_of(&out), expected);
    // sweep.csv deleted: the old code printed "wrote .../sweep.csv" and wrote nothing.
    std::fs::remove_file(out.join("sweep.csv")).unwrap();
    let o = grid(&out, &[]).output().unwrap();
    let stderr = refused(&o, "sweep.csv");
    assert!(stderr.contains("--force"), "{stderr}");
    // An edited row.
    std::fs::write(out.join("sweep.csv"), "point\n").unwrap();
    refused(&grid(&out, &[]).output().unwrap(), "sweep.csv");
    std::fs::write(out.join("notes.txt"), "mine").unwrap();
    ok(&mut grid(&out, &["--force"]));
    assert_eq!(
        std::fs::read_to_string(out.join("notes.txt")).unwrap(),
        "mine"
    );
    std::fs::remove_file(out.join("notes.txt")).unwrap();
    assert_eq!(files_of(&out), expected);
}

fn merge(dirs: &[&Path], out: &Path) -> Output {
    let mut args = vec!["sweep".to_string(), "merge".to_string()];
    args.extend(dirs.iter().map(|d| d.to_string_lossy().into_owned()));
    args.extend(["--out".to_string(), out.to_string_lossy().into_owned()]);
    let args: Vec<&str> = args.iter().map(String::as_str).collect();
    flexrock(&args)
}

fn shards(out: &Path, n: usize, extra: &[&str]) {
    for k in 1..=n {
        let shard = format!("{k}/{n}");
        let mut args = vec!["--shard", shard.as_str()];
        args.extend(extra);
        ok(&mut grid(out, &args));
    }
}

#[test]
fn tampered_shards_are_refused_by_merge() {
    let dir = scratch_dir("store-merge");
    let expected = reference(&dir);
    let sharded = dir.join("sharded");
    shards(&sharded, 3, &[]);
    let shard = |k: usize| sharded.join(format!("shard-{k}-of-3"));
    let merged = dir.join("merged");
    let o = merge(&[&sharded], &merged);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    assert_eq!(files_of(&merged), expected);

    let attempt = |name: &str, edit: &dyn Fn(&Path), needle: &str| {
        let copy = dir.join(name);
        for k in 1..=3 {
            let to = copy.join(format!("shard-{k}-of-3"));
            std::fs::create_dir_all(&to).unwrap();
            for (file, bytes) in files_of(&shard(k)) {
                std::fs::write(to.join(file), bytes).unwrap();
            }
        }
        edit(&copy);
        let out = dir.join(format!("{name}-out"));
        let o = merge(&[&copy], &out);
        refused(&o, needle);
        assert!(!out.join("sweep.json").exists(), "{name}");
    };
    // One shard's sweep.csv replaced by another's.
    attempt(
        "replaced",
        &|d| {
            std::fs::copy(
                d.join("shard-1-of-3/sweep.csv"),
                d.join("shard-2-of-3/sweep.csv"),
            )
            .unwrap();
        },
        "shard-2-of-3/sweep.csv",
    );
    // A row moved from one shard to the next.
    attempt(
        "moved",
        &|d| {
            let first = std::fs::read_to_string(d.join("shard-1-of-3/sweep.csv")).unwrap();
            let (kept, last) = first.trim_end().rsplit_once('\n').unwrap();
            std::fs::write(d.join("shard-1-of-3/sweep.csv"), format!("{kept}\n")).unwrap();
            let second = std::fs::read_to_string(d.join("shard-2-of-3/sweep.csv")).unwrap();
            let (header, rows) = second.split_once('\n').unwrap();
            std::fs::write(
                d.join("shard-2-of-3/sweep.csv"),
                format!("{header}\n{last}\n{rows}"),
            )
            .unwrap();
        },
        "shard-1-of-3/sweep.csv",
    );
    // An overturned flag edited.
    attempt(
        "edited",
        &|d| {
            let path = d.join("shard-3-of-3/sweep.csv");
            let text = std::fs::read_to_string(&path).unwrap();
            std::fs::write(&path, text.replacen(",true,", ",false,", 1)).unwrap();
        },
        "shard-3-of-3/sweep.csv",
    );
    // Both files of shard 2 in shard 3's directory.
    attempt(
        "swapped",
        &|d| {
            for f in ["sweep.csv", "sweep.json"] {
                std::fs::copy(
                    d.join("shard-2-of-3").join(f),
                    d.join("shard-3-of-3").join(f),
                )
                .unwrap();
            }
        },
        "shard-3-of-3",
    );
    // A crafted sweep.json whose axes have no values panicked the figure.
    attempt(
        "empty-axes",
        &|d| {
            let path = d.join("shard-1-of-3/sweep.json");
            let mut json: serde_json::Value =
                serde_json::from_slice(&std::fs::read(&path).unwrap()).unwrap();
            for axis in json["plan"]["axes"].as_array_mut().unwrap() {
                axis["values"] = serde_json::json!([]);
            }
            std::fs::write(&path, serde_json::to_vec(&json).unwrap()).unwrap();
        },
        "has no values",
    );
}

#[test]
fn a_merge_into_its_own_directory_uses_the_shards_not_an_old_result() {
    let dir = scratch_dir("store-stale-merge");
    let out = dir.join("out");
    // An old merged result of another sweep (another damping) in OUT.
    shards(&out, 2, &["--set", "body.damping_ratio=0.02"]);
    let o = merge(&[&out], &out);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    for k in 1..=2 {
        std::fs::remove_dir_all(out.join(format!("shard-{k}-of-2"))).unwrap();
    }
    // New shards of this sweep, merged as the Slurm merge job does.
    shards(&out, 2, &[]);
    let o = merge(&[&out], &out);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let expected = reference(&dir);
    let merged: Vec<_> = files_of(&out);
    assert_eq!(merged, expected);
}

#[test]
fn a_merge_killed_at_random_moments_leaves_the_old_result_or_the_new() {
    let dir = scratch_dir("store-merge-kill");
    let expected = reference(&dir);
    let sharded = dir.join("sharded");
    shards(&sharded, 4, &[]);
    let out = dir.join("out");
    let mut state: u64 = 0x2545_F491_4F6C_DD1D;
    for _ in 0..25 {
        state ^= state << 13;
        state ^= state >> 7;
        state ^= state << 17;
        let mut child = common::flexrock_command()
            .args([
                "sweep",
                "merge",
                sharded.to_str().unwrap(),
                "--out",
                out.to_str().unwrap(),
            ])
            .stdout(Stdio::null())
            .stderr(Stdio::null())
            .spawn()
            .unwrap();
        std::thread::sleep(Duration::from_micros(state % 30_000));
        let _ = child.kill();
        child.wait().unwrap();
        // Whatever is there is nothing or the whole result.
        if out.join("sweep.json").exists() {
            assert_eq!(files_of(&out), expected);
        }
    }
    let o = merge(&[&sharded], &out);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    assert_eq!(files_of(&out), expected);
}

/// serde_json without float_roundtrip read 0.0014500000000000001 back one unit in the last
/// place off, so that a sweep's stored plan was taken for another sweep's.
#[test]
fn a_plan_reads_back_bit_for_bit() {
    use flexrock_core::analysis::sweep::{FindMin, Plan};
    let mut state: u64 = 0x9E37_79B9_7F4A_7C15;
    let mut values = vec![(15.0 - 0.5) / 1e4, 0.1 + 0.2, f64::MIN_POSITIVE, 1e308];
    for _ in 0..2000 {
        state ^= state << 13;
        state ^= state >> 7;
        state ^= state << 17;
        let x = f64::from_bits(state >> 2);
        if x.is_finite() && x > 0.0 {
            values.push(x);
        }
    }
    for tol in values {
        let plan = Plan {
            flexrock_version: "x".to_string(),
            model_file: String::new(),
            model_text: String::new(),
            settings: Vec::new(),
            axes: Vec::new(),
            find_min: Some(FindMin {
                key: "excitation.amplitude".to_string(),
                lo: 0.5,
                hi: 15.0,
                scan: 100,
                tol,
                rigid_form: Default::default(),
                rigid_overturning: Default::default(),
                rigid_restitution: None,
            }),
            chunk_size: 1,
            records: Vec::new(),
            row_columns: None,
        };
        let back: Plan =
            serde_json::from_slice(&serde_json::to_vec_pretty(&plan).unwrap()).unwrap();
        assert_eq!(
            back.find_min.unwrap().tol.to_bits(),
            tol.to_bits(),
            "{tol:e}"
        );
    }
}

/// Runs a command and waits at most `limit` for it; a run still going then is killed and
/// reported (a hang fails the test instead of hanging it).
fn within(command: &mut Command, limit: Duration) -> Output {
    let mut child: Child = command
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    let start = Instant::now();
    while child.try_wait().unwrap().is_none() {
        if start.elapsed() > limit {
            child.kill().unwrap();
            panic!("{command:?} still ran after {limit:?}");
        }
        std::thread::sleep(Duration::from_millis(20));
    }
    child.wait_with_output().unwrap()
}

#[test]
fn infinite_and_overflowing_axis_values_are_refused_at_once() {
    let dir = scratch_dir("store-overflow");
    for (i, axis) in [
        "excitation.amplitude=inf,1",
        "excitation.amplitude=-1e308,1e308",
        "body.youngs_modulus=5e6,1.5e308",
        "excitation.amplitude=lin:1e308:1.7e308:3",
    ]
    .into_iter()
    .enumerate()
    {
        let out = dir.join(format!("out{i}"));
        let o = within(
            pulse_sweep(&out).args(["--vary", "excitation.period=1,2", "--vary", axis]),
            Duration::from_secs(60),
        );
        let key = axis.split('=').next().unwrap();
        refused(&o, &format!("--vary {key}"));
        assert!(!out.exists(), "{axis}: nothing is written");
    }
}

#[test]
fn seven_huge_axes_are_refused_before_they_are_made() {
    let dir = scratch_dir("store-huge-axes");
    let mut command = pulse_sweep(&dir.join("out"));
    for key in [
        "excitation.amplitude",
        "excitation.period",
        "body.height",
        "body.width",
        "body.density",
        "body.youngs_modulus",
        "body.damping_ratio",
    ] {
        command.args(["--vary", &format!("{key}=lin:1:2:1000000")]);
    }
    let o = within(&mut command, Duration::from_secs(120));
    let message = refused(&o, "--vary excitation.period");
    assert!(message.contains("100000000 points"), "{message}");
}

/// The filled rectangles of an SVG, as (x, y, width, height, fill).
fn rectangles(svg: &str) -> Vec<(f64, f64, f64, f64, String)> {
    svg.split("<rect ")
        .skip(1)
        .map(|r| {
            let r = format!(" {}", r.split('>').next().unwrap());
            let attr = |name: &str| -> String {
                let start = r
                    .find(&format!(" {name}=\""))
                    .unwrap_or_else(|| panic!("no {name} in {r}"));
                r[start + name.len() + 3..]
                    .split('"')
                    .next()
                    .unwrap()
                    .to_string()
            };
            let n = |name: &str| attr(name).parse::<f64>().unwrap();
            (n("x"), n("y"), n("width"), n("height"), attr("fill"))
        })
        .collect()
}

#[test]
fn a_map_over_unsorted_lists_draws_each_cell_once_in_order() {
    let dir = scratch_dir("store-unsorted-map");
    let out = dir.join("out");
    ok(pulse_sweep(&out).args([
        "--vary",
        "excitation.period=1,0.5,2",
        "--vary",
        "excitation.amplitude=2,6,4",
    ]));
    let csv = std::fs::read_to_string(out.join("sweep.csv")).unwrap();
    let overturned = csv.lines().filter(|l| l.contains(",ok,,true,")).count();
    assert!(overturned > 0 && overturned < 9, "{csv}");
    let svg = std::fs::read_to_string(out.join("map.svg")).unwrap();
    // The rectangles of the first (physical) panel: every filled rectangle below the legend
    // (which ends above the panel label "(a)") and left of the second panel's label "(b)". A
    // run of cells of one colour up a column is one rectangle.
    let label = |text: &str| -> (f64, f64) {
        let at = svg
            .find(&format!(">\n{text}\n</text>"))
            .expect("a panel label");
        let tag = &svg[svg[..at].rfind("<text").unwrap()..at];
        let n = |name: &str| -> f64 {
            let start = tag.find(&format!(" {name}=\"")).unwrap() + name.len() + 3;
            tag[start..].split('"').next().unwrap().parse().unwrap()
        };
        (n("x"), n("y"))
    };
    let (a, b) = (label("(a)"), label("(b)"));
    let cells: Vec<_> = rectangles(&svg)
        .into_iter()
        .filter(|r| r.4 != "none" && r.1 > a.1 && r.0 > 0.0 && r.0 < b.0)
        .collect();
    assert!((3..=9).contains(&cells.len()), "{cells:?}");
    for (i, a) in cells.iter().enumerate() {
        for b in &cells[..i] {
            let overlap_x = (a.0 + a.2).min(b.0 + b.2) - a.0.max(b.0);
            let overlap_y = (a.1 + a.3).min(b.1 + b.3) - a.1.max(b.1);
            // Neighbours overlap by one pixel on purpose (no seams between them); a cell
            // drawn twice, or over another, overlaps by more.
            assert!(
                overlap_x <= 1.0 || overlap_y <= 1.0,
                "cells {a:?} and {b:?} overlap"
            );
        }
    }
    // The centre of each of the 3 x 3 cells (the amplitudes 2, 4, 6 are evenly spaced, so the
    // rows are of one height) lies in exactly one rectangle, which gives its colour.
    // (A run of one colour across neighbouring cells is one rectangle: the columns are thirds
    // of the cells' extent.)
    let left = cells.iter().map(|r| r.0).fold(f64::INFINITY, f64::min);
    let right = cells.iter().map(|r| r.0 + r.2).fold(0.0, f64::max);
    let third = (right - left) / 3.0;
    let columns: Vec<(f64, f64)> = (0..3).map(|k| (left + k as f64 * third, third)).collect();
    let top = cells.iter().map(|r| r.1).fold(f64::INFINITY, f64::min);
    let bottom = cells.iter().map(|r| r.1 + r.3).fold(0.0, f64::max);
    let row_height = (bottom - top) / 3.0;
    let mut colours = Vec::new();
    for &(x, width) in &columns {
        for row in 0..3 {
            let centre = (x + 0.5 * width, top + (row as f64 + 0.5) * row_height);
            let holding: Vec<_> = cells
                .iter()
                .filter(|r| {
                    (r.0..r.0 + r.2).contains(&centre.0) && (r.1..r.1 + r.3).contains(&centre.1)
                })
                .collect();
            assert_eq!(holding.len(), 1, "{centre:?} in {holding:?}");
            colours.push((x, holding[0].4.clone()));
        }
    }
    let black = colours.iter().filter(|c| c.1 == "#000000").count();
    assert_eq!(black, overturned, "every overturned cell is drawn black");
    // One black rectangle per run of overturned cells up a column (amplitudes ascending).
    let rows = rows_of(&csv);
    let overturned_at = |period: &str, amplitude: &str| {
        rows.iter()
            .any(|r| r[1] == period && r[2] == amplitude && r[5] == "true")
    };
    let mut runs = 0;
    for period in ["0.5", "1", "2"] {
        let mut previous = false;
        for amplitude in ["2", "4", "6"] {
            let now = overturned_at(period, amplitude);
            runs += usize::from(now && !previous);
            previous = now;
        }
    }
    assert!(
        runs < overturned,
        "the case has a run of two overturned cells: {csv}"
    );
    assert_eq!(
        cells.iter().filter(|r| r.4 == "#000000").count(),
        runs,
        "{cells:?}"
    );
    // Period 0.5 s (the second value) is the leftmost column.
    let half_period_overturned = rows
        .iter()
        .filter(|r| r[1] == "0.5" && r[5] == "true")
        .count();
    assert_eq!(
        colours
            .iter()
            .filter(|c| c.0 == columns[0].0 && c.1 == "#000000")
            .count(),
        half_period_overturned
    );
}

fn rows_of(csv: &str) -> Vec<Vec<String>> {
    csv.lines()
        .skip(1)
        .map(|l| l.split(',').map(str::to_string).collect())
        .collect()
}
