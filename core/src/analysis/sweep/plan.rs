//! The plan of a sweep ([`Plan`]): what it computes, as stored with its results, and the
//! columns of sweep.csv it makes.

use serde::{Deserialize, Serialize};

use super::axis::Axis;
use super::cell::Cell;
use super::digest::sha256_hex;
use super::find_min::FindMin;
use super::point_result::{Layout, PointResult, RecordCells, Status};

/// Simulations per chunk, roughly: a chunk is the most a kill can lose.
pub const SIMULATIONS_PER_CHUNK: usize = 1024;

/// What a sweep is, as stored with its results: enough to tell whether a directory holds this
/// sweep (to resume it, or to merge its shards) and to say how the results were made.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Plan {
    /// Version of flexrock that made the results.
    pub flexrock_version: String,
    /// The model file as named on the command line.
    pub model_file: String,
    /// Its text, so that a changed file is not mistaken for the same sweep.
    pub model_text: String,
    /// `--set` keys, as `key=value`.
    pub settings: Vec<String>,
    /// The axes, the last varying fastest.
    pub axes: Vec<Axis>,
    /// The minimum search, if the sweep makes one at each point.
    pub find_min: Option<FindMin>,
    /// Points per chunk file.
    pub chunk_size: usize,
    /// The record files the sweep reads, each with the SHA-256 of its bytes, so that a record
    /// replaced between a kill and the resume (or a relative path that names another file from
    /// another directory) makes another sweep, never a mixed one.
    pub records: Vec<RecordInput>,
    /// For a sweep of a row of columns, their number; absent for a single body's sweep, so that
    /// a single body's plan is written as before rows could be swept.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub row_columns: Option<usize>,
}

/// A record file a sweep reads: where it is named, and the digest of its contents.
#[derive(Debug, Clone, PartialEq, Eq, Serialize, Deserialize)]
pub struct RecordInput {
    /// Where the sweep names it: `model` for the model file's (and `--set`'s) `excitation.path`,
    /// else the value of the `excitation.path` axis as typed.
    pub named_by: String,
    /// SHA-256 of the file's bytes, in hex; or why the file could not be read (then every point
    /// that reads it is an invalid row).
    pub sha256: String,
}

impl Plan {
    /// Number of points: the product of the axes' lengths (1 without axes).
    pub fn points(&self) -> usize {
        self.axes.iter().map(Axis::len).product()
    }

    /// The column names of sweep.csv.
    pub fn columns(&self) -> Vec<String> {
        let mut columns = vec!["point".to_string()];
        columns.extend(self.axes.iter().map(|a| a.key.clone()));
        columns.extend(self.result_columns());
        columns
    }

    /// The result columns of sweep.csv (after the point number and the axes): a row's
    /// ([`PointResult::columns`]), then in a sweep over records the record's ([`PointResult::record_columns`]).
    pub fn result_columns(&self) -> Vec<String> {
        let mut columns = PointResult::columns(self.layout());
        if self.reads_records() {
            columns.extend(PointResult::record_columns());
        }
        columns
    }

    /// The cells of a row without values, in the order of [`Plan::result_columns`] (their
    /// kinds are the columns').
    pub fn empty_cells(&self) -> Vec<Cell> {
        let mut row = PointResult::failure(Status::Invalid, String::new());
        if self.reads_records() {
            row.record = Some(RecordCells::default());
        }
        row.cells(self.layout())
    }

    /// True for a single body's sweep that reads record files: its rows carry each point's
    /// record (metadata and intensity measures).
    pub fn reads_records(&self) -> bool {
        self.row_columns.is_none() && !self.records.is_empty()
    }

    /// The result columns the sweep has: runs, or a minimum search with its rigid block's form.
    pub fn layout(&self) -> Layout {
        match (&self.find_min, self.row_columns) {
            (_, Some(n)) => Layout::Row(n),
            (None, None) => Layout::Runs,
            (Some(find), None) => Layout::Minimum(find.housner()),
        }
    }

    /// The index of each axis at point `index` (the last axis varies fastest).
    pub fn coordinates(&self, mut index: usize) -> Vec<usize> {
        let mut coordinates = vec![0; self.axes.len()];
        for (slot, axis) in coordinates.iter_mut().zip(&self.axes).rev() {
            *slot = index % axis.len();
            index /= axis.len();
        }
        coordinates
    }

    /// True when `other` computes the same points: everything but the model file's name as
    /// typed (its text is compared), so that a sweep resumed from another directory, or a shard
    /// started there, is recognised.
    pub fn same_sweep(&self, other: &Plan) -> bool {
        Plan {
            model_file: other.model_file.clone(),
            ..self.clone()
        } == *other
    }

    /// The SHA-256 (hex) of everything that decides the sweep's rows: the plan but the model
    /// file's name as typed. Chunks are sealed with it, so that a chunk of another sweep is
    /// never taken for one of this sweep.
    pub fn identity(&self) -> String {
        let plan = Plan {
            model_file: String::new(),
            ..self.clone()
        };
        sha256_hex(&serde_json::to_vec(&plan).unwrap_or_default())
    }

    /// The plan as read back from a file (a sweep.json): its axes' values made settings again,
    /// which are not stored.
    pub fn restored(mut self) -> Plan {
        self.axes = self.axes.into_iter().map(Axis::restored).collect();
        self
    }
}
