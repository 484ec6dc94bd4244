//! `flexrock sweep merge`: the results of shards joined into the file one process writes.
//!
//! Every shard is checked before its rows are used: its sweep.json must describe a plan that
//! can exist (axes with values, a chunk size, its points the shard's slice of that plan), its
//! sweep.csv must match the digest in its sweep.json, and every row must be the point the plan
//! puts there. Shards of different sweeps, gaps and overlaps are refused, naming the directory.

use std::path::{Path, PathBuf};

use super::run::finish;
use super::summary::{
    read_summary, read_table, SweepReport, SweepSummary, SUMMARY_FILE, TABLE_FILE,
};
use super::{dir, point_range, PointRange};
use crate::error::{Error, Result};

/// Joins the results of shards into `out`: each of `dirs` is a shard's directory, or a
/// directory holding `shard-K-of-N` directories (whose shards are used, whatever result of an
/// earlier merge it holds itself). Refuses shards of different sweeps, shards that have not
/// finished or do not verify, gaps and overlaps; the result is the file a single process writes.
pub fn merge(dirs: &[PathBuf], out: &Path) -> Result<SweepReport> {
    if dirs.is_empty() {
        return Err(Error::invalid(
            "merge",
            "(no directories)",
            "name at least one directory",
        ));
    }
    let mut parts: Vec<(PathBuf, SweepSummary)> = Vec::new();
    for dir in dirs {
        for part in parts_in(dir)? {
            let summary = read_summary(&part)?.ok_or_else(|| Error::SweepStore {
                path: part.clone(),
                message: "this shard has not finished (no sweep.json): run it again to complete it"
                    .to_string(),
            })?;
            check_part(&part, &summary)?;
            parts.push((part, summary));
        }
    }
    let (first_dir, first) = parts[0].clone();
    for (dir, summary) in &parts {
        if !summary.plan.same_sweep(&first.plan) {
            return Err(Error::SweepStore {
                path: dir.join(SUMMARY_FILE),
                message: format!(
                    "is a shard of another sweep than {} (model text, axes, settings, search, \
                     chunk size, record files or version differ)",
                    first_dir.join(SUMMARY_FILE).display()
                ),
            });
        }
    }
    parts.sort_by_key(|(_, s)| (s.points.first, s.points.end));
    let plan = first.plan.clone();
    let total = plan.points();
    let mut next = 0;
    let mut pieces = Vec::new();
    for (dir, summary) in &parts {
        let r = summary.points;
        if r.first > next {
            return Err(Error::SweepStore {
                path: dir.clone(),
                message: format!(
                    "points {}..{} are in none of the shards given (a gap before this shard's {}..{})",
                    next, r.first, r.first, r.end
                ),
            });
        }
        if r.first < next {
            return Err(Error::SweepStore {
                path: dir.clone(),
                message: format!(
                    "points {}..{} of this shard were given already by another (overlap)",
                    r.first,
                    next.min(r.end)
                ),
            });
        }
        let table = dir.join(TABLE_FILE);
        let rows = read_table(&table, summary).map_err(|problem| Error::SweepStore {
            path: table.clone(),
            message: problem,
        })?;
        pieces.push(super::Piece::read_back(rows));
        next = r.end;
    }
    if next < total {
        return Err(Error::SweepStore {
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
    // Locked (and made) only now, so that a refused merge leaves no directory behind.
    let mut warnings = Vec::new();
    let _lock = dir::lock(out, &mut warnings)?;
    let (summary, files) = finish(out, &plan, None, range, pieces)?;
    Ok(SweepReport {
        dir: out.to_path_buf(),
        summary,
        computed: 0,
        resumed: total,
        files,
        written: true,
        warnings,
    })
}

/// The result directories `dir` stands for: its `shard-K-of-N` directories when it has any,
/// else itself when it holds a sweep.json.
fn parts_in(dir: &Path) -> Result<Vec<PathBuf>> {
    let entries = std::fs::read_dir(dir).map_err(|e| Error::SweepStore {
        path: dir.to_path_buf(),
        message: format!("cannot read the directory: {e}"),
    })?;
    let mut shards: Vec<PathBuf> = entries
        .filter_map(|e| e.ok())
        .filter(|e| e.file_type().is_ok_and(|t| t.is_dir()))
        .filter(|e| {
            e.file_name()
                .to_str()
                .is_some_and(|n| n.starts_with("shard-"))
        })
        .map(|e| e.path())
        .collect();
    shards.sort();
    if !shards.is_empty() {
        return Ok(shards);
    }
    if dir.join(SUMMARY_FILE).exists() {
        return Ok(vec![dir.to_path_buf()]);
    }
    Err(Error::SweepStore {
        path: dir.to_path_buf(),
        message: "holds neither a sweep.json nor shard-K-of-N directories".to_string(),
    })
}

/// Refuses a sweep.json that describes no possible shard: axes without values, no chunk size,
/// a point count that overflows, points that are not this shard's slice of its plan, columns
/// that are not the plan's, or a shard in a directory named for another.
fn check_part(dir: &Path, summary: &SweepSummary) -> Result<()> {
    let refuse = |message: String| Error::SweepStore {
        path: dir.join(SUMMARY_FILE),
        message,
    };
    let plan = &summary.plan;
    if let Some(axis) = plan.axes.iter().find(|a| a.is_empty()) {
        return Err(refuse(format!("the axis {} has no values", axis.key)));
    }
    if plan.chunk_size == 0 {
        return Err(refuse("the chunk size is 0".to_string()));
    }
    let total = plan
        .axes
        .iter()
        .try_fold(1usize, |n, a| n.checked_mul(a.len()))
        .filter(|&n| n <= flexrock_core::analysis::sweep::axis::MAX_POINTS)
        .ok_or_else(|| refuse("its axes have more points than a sweep may".to_string()))?;
    let expected = match summary.shard {
        Some(shard) => {
            if shard.index == 0 || shard.index > shard.count {
                return Err(refuse(format!(
                    "shard {}/{} is not a shard",
                    shard.index, shard.count
                )));
            }
            let named = dir.file_name().and_then(|n| n.to_str());
            if named.is_some_and(|n| n.starts_with("shard-") && n != shard.dir_name()) {
                return Err(refuse(format!(
                    "holds shard {} of {} in a directory named for another",
                    shard.index, shard.count
                )));
            }
            point_range(plan, Some(shard))
        }
        None => point_range(plan, None),
    };
    if summary.points != expected || expected.total != total {
        return Err(refuse(format!(
            "its points {}..{} of {} are not the slice its plan gives ({}..{} of {})",
            summary.points.first,
            summary.points.end,
            summary.points.total,
            expected.first,
            expected.end,
            expected.total
        )));
    }
    if summary.columns != plan.columns() {
        return Err(refuse("its columns are not those of its plan".to_string()));
    }
    Ok(())
}
