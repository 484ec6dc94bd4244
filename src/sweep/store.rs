//! A sweep on disk: chunks written as they finish, resumed after a kill, split into shards for a
//! scheduler and merged back.
//!
//! Layout of an output directory (a shard K of N writes into `DIR/shard-K-of-N/` instead):
//! - while running: `chunks/plan.json` (what is being computed) and `chunks/<c>.csv`, the rows
//!   of chunk c (points c x chunk_size onwards), each file written whole (temporary file, then
//!   rename), in the order the chunks finish;
//! - when done: `sweep.csv`, the figure, and last `sweep.json` (the plan and the counts),
//!   written as one set; then `chunks/` is removed.
//!
//! Running the same command again skips the chunks on disk; a kill at any moment loses at most
//! the chunk being computed. A directory holding another sweep (another model text, other axes,
//! settings, search, chunk size or version) is refused, never mixed with.

use std::path::{Path, PathBuf};

use rayon::prelude::*;
use serde::{Deserialize, Serialize};

use super::{figure, Plan, Sweep};
use crate::error::{Error, Result};
use crate::output;

/// Which slice of the chunks a process computes: shard `index` of `count` (1-based, as a user
/// writes `--shard 3/8`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
pub struct Shard {
    /// K, 1-based.
    pub index: usize,
    /// N.
    pub count: usize,
}

impl Shard {
    /// Parses `K/N`, 1 <= K <= N.
    pub fn parse(text: &str) -> Result<Shard> {
        let rule = "must be K/N with 1 <= K <= N, e.g. 3/8";
        let (k, n) = text
            .split_once('/')
            .ok_or_else(|| Error::invalid("--shard", text, rule))?;
        let parse = |s: &str| s.trim().parse::<usize>().ok();
        match (parse(k), parse(n)) {
            (Some(index), Some(count)) if index >= 1 && index <= count => {
                Ok(Shard { index, count })
            }
            _ => Err(Error::invalid("--shard", text, rule)),
        }
    }

    /// The shard of a Slurm job array task, from `SLURM_ARRAY_TASK_ID`, `SLURM_ARRAY_TASK_MIN`
    /// (default 0) and `SLURM_ARRAY_TASK_COUNT`, when they are set: task ids min..min+count-1
    /// are shards 1..count.
    pub fn from_slurm(var: impl Fn(&str) -> Option<String>) -> Result<Option<Shard>> {
        let (Some(id), Some(count)) = (var("SLURM_ARRAY_TASK_ID"), var("SLURM_ARRAY_TASK_COUNT"))
        else {
            return Ok(None);
        };
        let min = var("SLURM_ARRAY_TASK_MIN").unwrap_or_else(|| "0".to_string());
        let number = |name: &str, value: &str| {
            value
                .trim()
                .parse::<usize>()
                .map_err(|_| Error::invalid(name, value, "must be a whole number (set by Slurm)"))
        };
        let (id, count, min) = (
            number("SLURM_ARRAY_TASK_ID", &id)?,
            number("SLURM_ARRAY_TASK_COUNT", &count)?,
            number("SLURM_ARRAY_TASK_MIN", &min)?,
        );
        if id < min || id - min >= count {
            return Err(Error::invalid(
                "SLURM_ARRAY_TASK_ID",
                id,
                &format!(
                    "must lie in {min}..{} (SLURM_ARRAY_TASK_MIN .. + SLURM_ARRAY_TASK_COUNT); \
                     use a contiguous array such as --array=0-{}",
                    min + count,
                    count.saturating_sub(1)
                ),
            ));
        }
        Ok(Some(Shard {
            index: id - min + 1,
            count,
        }))
    }

    /// The directory of this shard inside the sweep's output directory.
    pub fn dir(&self, out: &Path) -> PathBuf {
        out.join(format!("shard-{}-of-{}", self.index, self.count))
    }
}

/// The points of a directory's rows: [first, end) of total.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
pub struct PointRange {
    /// First point.
    pub first: usize,
    /// One past the last point.
    pub end: usize,
    /// Points of the whole sweep.
    pub total: usize,
}

/// Counts of the rows, by status, and of the points that overturned (for a minimum search:
/// that overturned somewhere in the interval).
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, Serialize, Deserialize)]
pub struct Counts {
    /// Rows with status ok.
    pub ok: usize,
    /// Rows with status invalid.
    pub invalid: usize,
    /// Rows with status failed.
    pub failed: usize,
    /// Points that overturned.
    pub overturned: usize,
    /// Runs whose energy residual exceeds [`crate::run::ENERGY_RESIDUAL_WARNING_SHARE`] of their
    /// energy scale: no more accurate than that (a sweep with a minimum search has none).
    pub inaccurate: usize,
}

/// sweep.json.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct SweepSummary {
    /// Version of flexrock that wrote it.
    pub flexrock_version: String,
    /// What was computed.
    pub plan: Plan,
    /// Set for a shard's directory; absent for a whole sweep (also a merged one).
    pub shard: Option<Shard>,
    /// The points of this directory's rows.
    pub points: PointRange,
    /// Counts of its rows.
    pub counts: Counts,
    /// sweep.csv's columns, in order.
    pub columns: Vec<String>,
    /// The files written with it.
    pub files: Vec<String>,
}

/// What `flexrock sweep` reports.
#[derive(Debug)]
pub struct SweepReport {
    /// The directory written.
    pub dir: PathBuf,
    /// Its sweep.json.
    pub summary: SweepSummary,
    /// Points computed by this process (0 when the directory already held the whole result).
    pub computed: usize,
    /// Points found on disk from an earlier, interrupted run.
    pub resumed: usize,
    /// The files written.
    pub files: Vec<PathBuf>,
}

const PLAN_FILE: &str = "plan.json";
const CHUNKS_DIR: &str = "chunks";
const SUMMARY_FILE: &str = "sweep.json";
const TABLE_FILE: &str = "sweep.csv";

/// Progress of a sweep, for a progress bar: points done (including resumed ones) of the points
/// this process is to do.
pub trait Progress: Sync {
    /// The sweep (or shard) has `total` points, of which `done` were found on disk.
    fn start(&self, total: usize, done: usize);
    /// `points` more are done.
    fn advance(&self, points: usize);
}

/// No progress shown.
pub struct Silent;

impl Progress for Silent {
    fn start(&self, _total: usize, _done: usize) {}
    fn advance(&self, _points: usize) {}
}

/// The plan as stored while running (with the shard, so that shards never share chunks).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
struct RunningPlan {
    plan: Plan,
    shard: Option<Shard>,
}

/// Runs (or resumes) a sweep into `out` (into the shard's directory for a shard).
pub fn run(
    sweep: &Sweep,
    out: &Path,
    shard: Option<Shard>,
    progress: &dyn Progress,
) -> Result<SweepReport> {
    let dir = match shard {
        Some(s) => s.dir(out),
        None => out.to_path_buf(),
    };
    let plan = &sweep.plan;
    let range = point_range(plan, shard);

    if let Some(summary) = read_summary(&dir)? {
        if !summary.plan.same_sweep(plan) || summary.shard != shard {
            return Err(other_sweep(&dir.join(SUMMARY_FILE)));
        }
        // Done before: an interrupted clean-up may have left the chunks.
        let _ = std::fs::remove_dir_all(dir.join(CHUNKS_DIR));
        let files = summary.files.iter().map(|f| dir.join(f)).collect();
        return Ok(SweepReport {
            dir,
            summary,
            computed: 0,
            resumed: range.end - range.first,
            files,
        });
    }

    let chunks_dir = dir.join(CHUNKS_DIR);
    let running = RunningPlan {
        plan: plan.clone(),
        shard,
    };
    let plan_path = chunks_dir.join(PLAN_FILE);
    match std::fs::read(&plan_path) {
        Ok(bytes) => {
            let stored: Option<RunningPlan> = serde_json::from_slice(&bytes).ok();
            let same =
                stored.is_some_and(|s| s.shard == shard && s.plan.restored().same_sweep(plan));
            if !same {
                return Err(other_sweep(&plan_path));
            }
        }
        Err(e) if e.kind() == std::io::ErrorKind::NotFound => {
            output::write_file_atomically(&plan_path, &output::json_bytes(&running))?;
        }
        Err(e) => {
            return Err(Error::Write {
                path: plan_path,
                source: e,
            })
        }
    }

    let first_chunk = range.first / plan.chunk_size;
    let end_chunk = range.end.div_ceil(plan.chunk_size);
    let pending: Vec<usize> = (first_chunk..end_chunk)
        .filter(|&c| !chunk_path(&chunks_dir, c).is_file())
        .collect();
    let points_in = |c: usize| chunk_points(plan, c, range.end).len();
    let resumed: usize = (first_chunk..end_chunk)
        .filter(|c| !pending.contains(c))
        .map(points_in)
        .sum();
    progress.start(range.end - range.first, resumed);
    let mut computed = 0;
    for &c in &pending {
        let points = chunk_points(plan, c, range.end);
        let rows = rows_of(sweep, points.clone(), progress);
        let mut table = output::Table::without_header();
        for fields in rows {
            table.row(fields);
        }
        output::write_file_atomically(&chunk_path(&chunks_dir, c), &table.into_bytes())?;
        computed += points.len();
    }

    // Assemble.
    let mut body = Vec::new();
    for c in first_chunk..end_chunk {
        let path = chunk_path(&chunks_dir, c);
        let bytes = std::fs::read(&path).map_err(|e| Error::ReadResult {
            path: path.clone(),
            message: format!("cannot read a chunk of this sweep: {e}"),
        })?;
        body.extend_from_slice(&bytes);
    }
    let (summary, files) = finish(&dir, plan, shard, range, &body)?;
    let _ = std::fs::remove_dir_all(&chunks_dir);
    Ok(SweepReport {
        dir,
        summary,
        computed,
        resumed,
        files,
    })
}

/// The rows of sweep.csv for every point, in point order, computed in parallel in memory (no
/// file is read or written): the fields of each row as the file has them, under the header
/// [`Plan::columns`]. What the Python bindings return; [`run`] writes the same rows.
pub fn rows(sweep: &Sweep, progress: &dyn Progress) -> Vec<Vec<String>> {
    progress.start(sweep.points(), 0);
    rows_of(sweep, 0..sweep.points(), progress)
}

/// The rows of the points `points`, in point order.
fn rows_of(
    sweep: &Sweep,
    points: std::ops::Range<usize>,
    progress: &dyn Progress,
) -> Vec<Vec<String>> {
    points
        .into_par_iter()
        .map(|i| {
            let row = sweep.evaluate(i);
            progress.advance(1);
            row_fields(&sweep.plan, i, &row)
        })
        .collect()
}

/// The points of shard `shard` (all of them without one): whole chunks, split as evenly as
/// chunks allow.
pub fn point_range(plan: &Plan, shard: Option<Shard>) -> PointRange {
    let total = plan.points();
    let chunks = total.div_ceil(plan.chunk_size);
    let (first_chunk, end_chunk) = match shard {
        None => (0, chunks),
        Some(s) => ((s.index - 1) * chunks / s.count, s.index * chunks / s.count),
    };
    PointRange {
        first: (first_chunk * plan.chunk_size).min(total),
        end: (end_chunk * plan.chunk_size).min(total),
        total,
    }
}

fn chunk_points(plan: &Plan, chunk: usize, end: usize) -> std::ops::Range<usize> {
    let first = chunk * plan.chunk_size;
    first..((chunk + 1) * plan.chunk_size).min(end)
}

fn chunk_path(dir: &Path, chunk: usize) -> PathBuf {
    dir.join(format!("{chunk:09}.csv"))
}

fn row_fields(plan: &Plan, index: usize, row: &super::Row) -> Vec<String> {
    let mut fields = vec![index.to_string()];
    for (axis, &i) in plan.axes.iter().zip(&plan.coordinates(index)) {
        fields.push(axis.values[i].clone());
    }
    fields.extend(row.fields(plan.find_min.is_some()));
    fields
}

fn other_sweep(path: &Path) -> Error {
    Error::OutputTarget {
        path: path.to_path_buf(),
        found: "holds the results of another sweep (another model text, axes, --set keys, \
                search, chunk size, shard or flexrock version)"
            .to_string(),
        rule:
            "a sweep resumes only its own results: use another --out directory, or remove this one"
                .to_string(),
    }
}

fn read_summary(dir: &Path) -> Result<Option<SweepSummary>> {
    let path = dir.join(SUMMARY_FILE);
    let bytes = match std::fs::read(&path) {
        Ok(bytes) => bytes,
        Err(e) if e.kind() == std::io::ErrorKind::NotFound => return Ok(None),
        Err(e) => {
            return Err(Error::SweepFile {
                path,
                message: format!("cannot read: {e}"),
            })
        }
    };
    let summary: SweepSummary = serde_json::from_slice(&bytes).map_err(|e| Error::SweepFile {
        path: path.clone(),
        message: format!("not a flexrock sweep.json: {e}"),
    })?;
    Ok(Some(SweepSummary {
        plan: summary.plan.clone().restored(),
        ..summary
    }))
}

/// Writes sweep.csv, the figure and sweep.json (last) from the rows' CSV text.
fn finish(
    dir: &Path,
    plan: &Plan,
    shard: Option<Shard>,
    range: PointRange,
    body: &[u8],
) -> Result<(SweepSummary, Vec<PathBuf>)> {
    let columns = plan.columns();
    let mut table_bytes =
        output::Table::new(&columns.iter().map(String::as_str).collect::<Vec<_>>()).into_bytes();
    table_bytes.extend_from_slice(body);
    let table = figure::SweepTable::parse(&table_bytes, &dir.join(TABLE_FILE))?;
    if table.rows.len() != range.end - range.first {
        return Err(Error::ReadResult {
            path: dir.join(CHUNKS_DIR),
            message: format!(
                "the chunks hold {} rows for the {} points {}..{}",
                table.rows.len(),
                range.end - range.first,
                range.first,
                range.end
            ),
        });
    }
    let counts = table.counts(plan.find_min.is_some())?;
    let figures = if shard.is_none() {
        figure::figures(plan, &table)?
    } else {
        Vec::new()
    };
    let mut files: Vec<(String, Vec<u8>)> = vec![(TABLE_FILE.to_string(), table_bytes)];
    files.extend(figures);
    let mut names: Vec<String> = files.iter().map(|(n, _)| n.clone()).collect();
    names.push(SUMMARY_FILE.to_string());
    let summary = SweepSummary {
        flexrock_version: crate::run::VERSION.to_string(),
        plan: plan.clone(),
        shard,
        points: range,
        counts,
        columns,
        files: names,
    };
    files.push((SUMMARY_FILE.to_string(), output::json_bytes(&summary)));
    let set: Vec<(&str, Vec<u8>)> = files.iter().map(|(n, b)| (n.as_str(), b.clone())).collect();
    let written = output::write_atomically(dir, &set)?;
    Ok((summary, written))
}

/// Joins the results of shards into `out`: each of `dirs` is a shard's directory, or a
/// directory holding `shard-K-of-N` directories. Refuses shards of different sweeps, shards
/// that have not finished, gaps and overlaps; the result is the file a single process writes.
pub fn merge(dirs: &[PathBuf], out: &Path) -> Result<SweepReport> {
    let mut parts: Vec<(PathBuf, SweepSummary)> = Vec::new();
    for dir in dirs {
        match read_summary(dir)? {
            Some(summary) => parts.push((dir.clone(), summary)),
            None => {
                let mut found = false;
                let entries = std::fs::read_dir(dir).map_err(|e| Error::SweepFile {
                    path: dir.clone(),
                    message: format!("cannot read the directory: {e}"),
                })?;
                let mut subdirs: Vec<PathBuf> = entries
                    .filter_map(|e| e.ok())
                    .map(|e| e.path())
                    .filter(|p| {
                        p.is_dir()
                            && p.file_name()
                                .and_then(|n| n.to_str())
                                .is_some_and(|n| n.starts_with("shard-"))
                    })
                    .collect();
                subdirs.sort();
                for sub in subdirs {
                    found = true;
                    match read_summary(&sub)? {
                        Some(summary) => parts.push((sub, summary)),
                        None => {
                            return Err(Error::SweepFile {
                                path: sub,
                                message: "this shard has not finished (no sweep.json): run it again to complete it"
                                    .to_string(),
                            })
                        }
                    }
                }
                if !found {
                    return Err(Error::SweepFile {
                        path: dir.clone(),
                        message: "holds neither a sweep.json nor shard-K-of-N directories"
                            .to_string(),
                    });
                }
            }
        }
    }
    let Some((first_dir, first)) = parts.first().cloned() else {
        return Err(Error::invalid(
            "merge",
            "(no directories)",
            "name at least one directory",
        ));
    };
    for (dir, summary) in &parts {
        if !summary.plan.same_sweep(&first.plan) {
            return Err(Error::SweepFile {
                path: dir.join(SUMMARY_FILE),
                message: format!(
                    "is a shard of another sweep than {} (model text, axes, settings, search, chunk size or version differ)",
                    first_dir.join(SUMMARY_FILE).display()
                ),
            });
        }
    }
    parts.sort_by_key(|(_, s)| (s.points.first, s.points.end));
    let plan = first.plan.clone();
    let total = plan.points();
    let mut next = 0;
    let mut body = Vec::new();
    for (dir, summary) in &parts {
        let r = summary.points;
        if r.first > next {
            return Err(Error::SweepFile {
                path: dir.clone(),
                message: format!(
                    "points {}..{} are in none of the shards given (a gap before this shard's {}..{})",
                    next, r.first, r.first, r.end
                ),
            });
        }
        if r.first < next {
            return Err(Error::SweepFile {
                path: dir.clone(),
                message: format!(
                    "points {}..{} of this shard were given already by another (overlap)",
                    r.first,
                    next.min(r.end)
                ),
            });
        }
        let path = dir.join(TABLE_FILE);
        let bytes = std::fs::read(&path).map_err(|e| Error::SweepFile {
            path: path.clone(),
            message: format!("cannot read: {e}"),
        })?;
        let header_end = bytes
            .iter()
            .position(|&b| b == b'\n')
            .map_or(bytes.len(), |i| i + 1);
        body.extend_from_slice(&bytes[header_end..]);
        next = r.end;
    }
    if next < total {
        return Err(Error::SweepFile {
            path: parts[parts.len() - 1].0.clone(),
            message: format!(
                "points {next}..{total} are in none of the shards given (missing at the end)"
            ),
        });
    }
    let range = PointRange {
        first: 0,
        end: total,
        total,
    };
    let (summary, files) = finish(out, &plan, None, range, &body)?;
    Ok(SweepReport {
        dir: out.to_path_buf(),
        summary,
        computed: 0,
        resumed: total,
        files,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn plan(points: usize, chunk_size: usize) -> Plan {
        Plan {
            flexrock_version: String::new(),
            model_file: String::new(),
            model_text: String::new(),
            settings: Vec::new(),
            axes: vec![super::super::Axis::new(
                "excitation.amplitude",
                (0..points).map(|i| i.to_string()).collect(),
            )],
            find_min: None,
            chunk_size,
        }
    }

    #[test]
    fn shards_cover_every_point_once_in_whole_chunks() {
        for (points, chunk, count) in [(100, 7, 3), (10, 3, 5), (5, 10, 3), (1000, 1, 7)] {
            let plan = plan(points, chunk);
            let mut next = 0;
            for index in 1..=count {
                let r = point_range(&plan, Some(Shard { index, count }));
                assert_eq!(r.first, next, "{points} {chunk} {count}");
                assert!(r.first.is_multiple_of(chunk) || r.first == points);
                next = r.end;
            }
            assert_eq!(next, points);
            let all = point_range(&plan, None);
            assert_eq!((all.first, all.end, all.total), (0, points, points));
        }
    }

    #[test]
    fn shard_flags_and_slurm_variables() {
        assert_eq!(Shard::parse("2/5").unwrap(), Shard { index: 2, count: 5 });
        for bad in ["0/3", "4/3", "1", "a/b", "1/0", "-1/3"] {
            assert!(Shard::parse(bad).is_err(), "{bad}");
        }
        let env = |vars: &'static [(&'static str, &'static str)]| {
            move |name: &str| {
                vars.iter()
                    .find(|(k, _)| *k == name)
                    .map(|(_, v)| v.to_string())
            }
        };
        assert_eq!(Shard::from_slurm(env(&[])).unwrap(), None);
        const ARRAY: [(&str, &str); 2] = [
            ("SLURM_ARRAY_TASK_ID", "7"),
            ("SLURM_ARRAY_TASK_COUNT", "3"),
        ];
        // Without SLURM_ARRAY_TASK_MIN the ids start at 0: 7 is out of range.
        assert!(Shard::from_slurm(env(&ARRAY)).is_err());
        const WITH_MIN: [(&str, &str); 3] = [
            ("SLURM_ARRAY_TASK_ID", "7"),
            ("SLURM_ARRAY_TASK_COUNT", "3"),
            ("SLURM_ARRAY_TASK_MIN", "5"),
        ];
        assert_eq!(
            Shard::from_slurm(env(&WITH_MIN)).unwrap(),
            Some(Shard { index: 3, count: 3 })
        );
        const BAD: [(&str, &str); 2] = [
            ("SLURM_ARRAY_TASK_ID", "x"),
            ("SLURM_ARRAY_TASK_COUNT", "3"),
        ];
        assert!(Shard::from_slurm(env(&BAD)).is_err());
    }
}
