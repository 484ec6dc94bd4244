//! Running a sweep into its directory: the chunks on disk, resumed after a kill, and the
//! finished set of files.

use std::path::{Path, PathBuf};

use serde::{Deserialize, Serialize};

use super::dir;
use super::progress::Progress;
use super::shard::{chunk_points, point_range, PointRange, Shard};
use super::summary::{
    read_summary, read_table, result_files, SweepReport, SweepSummary, SUMMARY_FILE, TABLE_FILE,
};
use super::verify;
use super::Piece;
use crate::error::{Error, Result};
use crate::figures::sweep as figure;
use crate::writers;
use flexrock_core::analysis::sweep::{Plan, Sweep};

/// The plan as stored while running (with the shard, so that shards never share chunks).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
struct RunningPlan {
    plan: Plan,
    shard: Option<Shard>,
}

impl RunningPlan {
    /// What the chunks are sealed with: the plan's identity and the shard.
    fn identity(&self) -> String {
        let shard = self
            .shard
            .map_or_else(String::new, |s| format!(" {}", s.dir_name()));
        format!("{}{shard}", self.plan.identity())
    }
}

/// Where and how [`run`] writes.
#[derive(Debug, Clone, Default)]
pub struct Target {
    /// The output directory (a shard writes into `out/shard-K-of-N`).
    pub out: PathBuf,
    /// The shard to compute, if any.
    pub shard: Option<Shard>,
    /// Replace what the directory holds of another sweep (or a damaged result of this one)
    /// instead of refusing it; only files flexrock writes are removed.
    pub force: bool,
}

/// Runs (or resumes) a sweep into `target.out` (into the shard's directory for a shard).
///
/// The directory is locked for the whole run. A finished result of this sweep is checked
/// (sweep.csv against the digest in sweep.json and every row against the plan) and reported
/// done; a finished result of another sweep is refused. Chunks on disk are used only when their
/// seal and rows verify; one that does not is computed again, with a warning naming it.
pub fn run(sweep: &Sweep, target: &Target, progress: &dyn Progress) -> Result<SweepReport> {
    let shard = target.shard;
    let dir = match shard {
        Some(s) => s.dir(&target.out),
        None => target.out.clone(),
    };
    let plan = &sweep.plan;
    let range = point_range(plan, shard);
    let mut warnings = Vec::new();
    let _lock = dir::lock(&dir, &mut warnings)?;

    if let Some(report) = finished(&dir, plan, shard, range, target.force, &mut warnings)? {
        return Ok(report);
    }

    let identity = RunningPlan {
        plan: plan.clone(),
        shard,
    }
    .identity();
    let chunks = open_chunks(&dir, plan, shard, target.force)?;

    let first_chunk = range.first / plan.chunk_size;
    let end_chunk = range.end.div_ceil(plan.chunk_size);
    // The chunks on disk that verify; every other chunk is computed.
    let mut done: Vec<Option<Piece>> = Vec::new();
    for c in first_chunk..end_chunk {
        let path = chunk_path(&chunks, c);
        let points = chunk_points(plan, c, range.end);
        let rows = match std::fs::read(&path) {
            Ok(bytes) => match verify::chunk_rows(plan, &identity, &points, &bytes) {
                Ok(rows) => Some(Piece::read_back(rows.to_vec())),
                Err(problem) => {
                    warnings.push(format!("{} {problem}: computed again", path.display()));
                    None
                }
            },
            Err(e) if e.kind() == std::io::ErrorKind::NotFound => None,
            Err(e) => {
                warnings.push(format!(
                    "{} cannot be read ({e}): computed again",
                    path.display()
                ));
                None
            }
        };
        done.push(rows);
    }
    let resumed: usize = (first_chunk..end_chunk)
        .zip(&done)
        .filter(|(_, rows)| rows.is_some())
        .map(|(c, _)| chunk_points(plan, c, range.end).len())
        .sum();
    progress.start(range.len(), resumed);
    // The missing chunks are computed in parallel on the thread pool, and this thread writes
    // each as it comes: no thread of the pool waits for a chunk's slowest point, or for a disk.
    let missing: Vec<usize> = (first_chunk..end_chunk)
        .zip(&done)
        .filter(|(_, rows)| rows.is_none())
        .map(|(c, _)| c)
        .collect();
    let rows_of_chunk = |c: usize| -> Result<Piece> {
        let points = chunk_points(plan, c, range.end);
        let records = rows_of(sweep, points.clone(), progress);
        // What was computed is checked as what is read back is: a row out of place never
        // reaches a chunk or sweep.csv.
        verify::check_fields(plan, &points, &records).map_err(|problem| Error::SweepStore {
            path: chunk_path(&chunks, c),
            message: format!("the rows to be written: {problem}"),
        })?;
        let mut rows = Vec::with_capacity(256 * records.len());
        for record in &records {
            writers::push_row(&mut rows, record.iter());
        }
        Ok(Piece {
            rows,
            records: Some(records),
        })
    };
    let stop = std::sync::atomic::AtomicBool::new(false);
    let mut computed = 0;
    let mut failure = None;
    std::thread::scope(|scope| {
        let (sender, receiver) = std::sync::mpsc::channel();
        scope.spawn(|| {
            use rayon::prelude::*;
            // Once a chunk fails, the chunks not yet started are left alone.
            missing.par_iter().for_each_with(sender, |sender, &c| {
                if !stop.load(std::sync::atomic::Ordering::Relaxed) {
                    let _ = sender.send((c, rows_of_chunk(c)));
                }
            });
        });
        for (c, rows) in receiver {
            let points = chunk_points(plan, c, range.end);
            let written = rows.and_then(|piece| {
                // A chunk is sealed and checked when read back: it is not synced, as a crash
                // that tears it costs only its computation (writers::write_checkpoint).
                let seal = verify::chunk_seal_line(&identity, &points, &piece.rows);
                writers::write_checkpoint(
                    &chunk_path(&chunks, c),
                    &[seal.as_bytes(), &piece.rows],
                )?;
                Ok(piece)
            });
            match written {
                Ok(rows) => {
                    computed += points.len();
                    done[c - first_chunk] = Some(rows);
                }
                Err(e) => {
                    stop.store(true, std::sync::atomic::Ordering::Relaxed);
                    failure.get_or_insert(e);
                }
            }
        }
    });
    if let Some(e) = failure {
        return Err(e);
    }

    let pieces: Vec<Piece> = done.into_iter().flatten().collect();
    let (summary, files) = finish(&dir, plan, shard, range, pieces)?;
    warnings.extend(dir::remove_chunks(&chunks));
    Ok(SweepReport {
        dir,
        summary,
        computed,
        resumed,
        files,
        written: true,
        warnings,
    })
}

/// A finished result in `dir`: reported done if it is this sweep's and verifies (its missing
/// figures drawn again from sweep.csv), refused if not (or, with `force`, its files removed so
/// that the sweep is computed anew). None when `dir` holds no sweep.json.
fn finished(
    dir: &Path,
    plan: &Plan,
    shard: Option<Shard>,
    range: PointRange,
    force: bool,
    warnings: &mut Vec<String>,
) -> Result<Option<SweepReport>> {
    let summary_path = dir.join(SUMMARY_FILE);
    let summary = match read_summary(dir) {
        Ok(Some(summary)) => summary,
        Ok(None) => return Ok(None),
        Err(_) if force => {
            remove_results(dir, None);
            return Ok(None);
        }
        Err(e) => return Err(e),
    };
    if !summary.plan.same_sweep(plan) || summary.shard != shard {
        if force {
            remove_results(dir, Some(&summary));
            return Ok(None);
        }
        return Err(other_sweep(&summary_path));
    }
    let table_path = dir.join(TABLE_FILE);
    let body = match read_table(&table_path, &summary) {
        Ok(body) => body,
        Err(problem) if force => {
            warnings.push(format!("{} {problem}: computed again", table_path.display()));
            remove_results(dir, Some(&summary));
            return Ok(None);
        }
        Err(problem) => {
            return Err(Error::OutputTarget {
                path: table_path,
                found: problem,
                rule: format!(
                    "{} records this sweep as finished, and flexrock reports only results that                      verify: run the same command with --force to compute it anew",
                    summary_path.display()
                ),
            })
        }
    };
    // Done before: an interrupted clean-up may have left the chunks, or a kill during the
    // last write its temporary directory.
    if let Ok(Some(chunks)) = dir::chunks(dir, false) {
        warnings.extend(dir::remove_chunks(&chunks.path));
    }
    let result_files = result_files();
    let names: Vec<&str> = result_files.iter().map(String::as_str).collect();
    writers::remove_stale_temporaries(dir, &names);
    let missing = summary.files.iter().any(|f| !dir.join(f).is_file());
    let (summary, files) = if missing {
        finish(dir, plan, shard, range, vec![Piece::read_back(body)])?
    } else {
        let files = summary.files.iter().map(|f| dir.join(f)).collect();
        (summary, files)
    };
    let written = missing;
    Ok(Some(SweepReport {
        dir: dir.to_path_buf(),
        summary,
        computed: 0,
        resumed: range.len(),
        files,
        written,
        warnings: std::mem::take(warnings),
    }))
}

/// Removes the files of a finished result (sweep.json first, so that a kill meanwhile leaves
/// no result that looks finished): the names flexrock writes, and no other.
fn remove_results(dir: &Path, summary: Option<&SweepSummary>) {
    let _ = std::fs::remove_file(dir.join(SUMMARY_FILE));
    for name in &result_files() {
        let listed = summary.is_none_or(|s| s.files.iter().any(|f| f == name));
        let path = dir.join(name);
        if listed && std::fs::symlink_metadata(&path).is_ok_and(|m| m.is_file()) {
            let _ = std::fs::remove_file(path);
        }
    }
}

/// The chunks directory of a running sweep, made or resumed: refused when it holds another
/// sweep's plan (or, with `force`, emptied of flexrock's files and begun anew).
fn open_chunks(dir: &Path, plan: &Plan, shard: Option<Shard>, force: bool) -> Result<PathBuf> {
    let running = RunningPlan {
        plan: plan.clone(),
        shard,
    };
    let chunks = dir::chunks(dir, true)?.ok_or_else(|| Error::Write {
        path: dir.join(dir::CHUNKS_DIR),
        source: std::io::Error::other("the chunks directory could not be made"),
    })?;
    let plan_path = chunks.path.join(dir::PLAN_FILE);
    let same = chunks.plan.as_deref().map(|bytes| {
        serde_json::from_slice::<RunningPlan>(bytes)
            .is_ok_and(|s| s.shard == shard && s.plan.restored().same_sweep(plan))
    });
    match same {
        Some(true) => {}
        Some(false) if !force => return Err(other_sweep(&plan_path)),
        Some(false) | None => {
            if same == Some(false) {
                // --force: the chunks of the other sweep go, and nothing else.
                let _ = dir::remove_chunks(&chunks.path);
                std::fs::create_dir_all(&chunks.path).map_err(|e| Error::Write {
                    path: chunks.path.clone(),
                    source: e,
                })?;
            }
            writers::write_file_atomically(&plan_path, &writers::json_bytes(&running))?;
        }
    }
    Ok(chunks.path)
}

/// The rows of sweep.csv for every point, in point order, computed in memory (no file is read
/// or written): the fields of each row as the file has them, under the header
/// [`Plan::columns`]; [`run`] writes the same rows.
pub fn rows(sweep: &Sweep, progress: &dyn Progress) -> Vec<Vec<String>> {
    progress.start(sweep.points(), 0);
    rows_of(sweep, 0..sweep.points(), progress)
        .iter()
        .map(|record| record.iter().map(str::to_string).collect())
        .collect()
}

/// The fields of the rows of the points `points`, in point order, as sweep.csv holds them.
fn rows_of(
    sweep: &Sweep,
    points: std::ops::Range<usize>,
    progress: &dyn Progress,
) -> Vec<csv::StringRecord> {
    sweep.rows_as(points, &|| progress.advance(1), |i, row| {
        row_record(&sweep.plan, i, &row)
    })
}

fn chunk_path(dir: &Path, chunk: usize) -> PathBuf {
    dir.join(format!("{chunk:09}.csv"))
}

/// The fields of point `index`'s row: its index, its coordinates, then the row's cells (each
/// written into one buffer, not a string of its own).
fn row_record(
    plan: &Plan,
    index: usize,
    row: &flexrock_core::analysis::sweep::PointResult,
) -> csv::StringRecord {
    let cells = row.cells(plan.layout());
    let mut record = csv::StringRecord::with_capacity(256, 1 + plan.axes.len() + cells.len());
    let mut text = String::with_capacity(32);
    flexrock_core::base::format::push_decimal(&mut text, index);
    record.push_field(&text);
    for (axis, &i) in plan.axes.iter().zip(&plan.coordinates(index)) {
        record.push_field(&axis.values[i]);
    }
    for cell in &cells {
        text.clear();
        cell.push_field(&mut text);
        record.push_field(&text);
    }
    record
}

fn other_sweep(path: &Path) -> Error {
    Error::OutputTarget {
        path: path.to_path_buf(),
        found: "holds the results of another sweep (another model text, axes, --set keys, \
                search, chunk size, shard, record file or flexrock version)"
            .to_string(),
        rule: "a sweep resumes only its own results: use another --out directory, or run the \
               same command with --force to replace them"
            .to_string(),
    }
}

/// Writes sweep.csv, the figure and sweep.json (last) as one set ([`writers::FileSet`]) from
/// the rows' CSV text in pieces (the chunks or shards, in order), which the caller verified
/// against the plan (each against its points); then removes the files an earlier result in
/// `dir` listed that this one does not write (a map of an earlier sweep beside the spectrum of
/// this one).
pub(super) fn finish(
    dir: &Path,
    plan: &Plan,
    shard: Option<Shard>,
    range: PointRange,
    mut pieces: Vec<Piece>,
) -> Result<(SweepSummary, Vec<PathBuf>)> {
    let table_path = dir.join(TABLE_FILE);
    let columns = plan.columns();
    let header =
        writers::Table::new(&columns.iter().map(String::as_str).collect::<Vec<_>>()).into_bytes();
    let table = crate::sweep_table::SweepTable::of_pieces(&columns, &mut pieces, &table_path)?;
    let counts = table.counts(plan.layout())?;
    // sweep.csv is the header and the pieces' rows one after another (never joined in memory):
    // its digest is taken and the file written and synced while the figures are drawn.
    let table_parts: Vec<&[u8]> = std::iter::once(header.as_slice())
        .chain(pieces.iter().map(|piece| piece.rows.as_slice()))
        .collect();
    let result_files = result_files();
    let names: Vec<&str> = result_files.iter().map(String::as_str).collect();
    let set = writers::FileSet::begin(dir, &names)?;
    let (figures, table_sha256) = rayon::join(
        || match shard {
            None => figure::sweep_files(plan, &table),
            Some(_) => Ok(Vec::new()),
        },
        || -> Result<String> {
            let digest = verify::sha256_hex_of(&table_parts);
            set.stage(TABLE_FILE, &table_parts)?;
            Ok(digest)
        },
    );
    let (figures, table_sha256) = (figures?, table_sha256?);
    let mut names = vec![TABLE_FILE.to_string()];
    names.extend(figures.iter().map(|(name, _)| name.clone()));
    names.push(SUMMARY_FILE.to_string());
    let summary = SweepSummary {
        flexrock_version: crate::commands::run::VERSION.to_string(),
        flexrock_commit: flexrock_core::simulate::COMMIT.to_string(),
        flexrock_dirty: flexrock_core::simulate::DIRTY,
        plan: plan.clone(),
        shard,
        points: range,
        counts,
        columns,
        files: names,
        table_sha256,
    };
    let earlier: Vec<String> = read_summary(dir)
        .ok()
        .flatten()
        .map(|s| s.files)
        .unwrap_or_default();
    let mut files = figures;
    files.push((SUMMARY_FILE.to_string(), writers::json_bytes(&summary)));
    set.stage_each(&files)?;
    let written = set.commit()?;
    for name in &result_files {
        let stale = earlier.iter().any(|f| f == name) && !summary.files.iter().any(|f| f == name);
        let path = dir.join(name);
        if stale && std::fs::symlink_metadata(&path).is_ok_and(|m| m.is_file()) {
            let _ = std::fs::remove_file(path);
        }
    }
    Ok((summary, written))
}
