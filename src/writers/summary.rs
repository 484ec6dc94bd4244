//! JSON summaries and the wall-clock times they may hold.

use flexrock_core::simulate::{Commit, Provenance};

/// `value` as pretty-printed JSON with a final newline.
pub fn json_bytes<T: serde::Serialize>(value: &T) -> Vec<u8> {
    let mut bytes = serde_json::to_vec_pretty(value).unwrap_or_default();
    bytes.push(b'\n');
    bytes
}

/// Where a command puts the wall-clock times of its solves.
///
/// Wall times change from run to run; everything else a command writes does not. With
/// [`WallTimes::Apart`] (the `--timings-apart` flag) they go to `timings.json` beside the other
/// files, and those carry none, so that a committed result can be compared byte for byte with a
/// fresh run of the same command.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum WallTimes {
    /// In the summaries (`wall_time_s` keys, the `wall_time_s` column, the printed text).
    #[default]
    Inline,
    /// In `timings.json`; the summaries hold `null` (JSON) or an empty cell (CSV) in their place
    /// and the printed text leaves them out.
    Apart,
}

/// The wall times a command takes out of its outputs ([`WallTimes::Apart`]).
#[derive(Debug, Default)]
pub struct Timings {
    mode: WallTimes,
    /// Where each time was (file name and JSON path, such as
    /// `compare.json/reference/statistics/wall_time_s`), in the order taken.
    times: serde_json::Map<String, serde_json::Value>,
}

impl Timings {
    /// Collects nothing with [`WallTimes::Inline`].
    pub fn new(mode: WallTimes) -> Self {
        Timings {
            mode,
            times: serde_json::Map::new(),
        }
    }

    /// With [`WallTimes::Apart`], records `*wall_time_s` under `key` and replaces it by NaN (which
    /// JSON writes as `null` and the printed text leaves out); otherwise leaves it alone.
    pub fn take(&mut self, key: &str, wall_time_s: &mut f64) {
        if self.mode == WallTimes::Apart {
            self.times.insert(key.to_string(), (*wall_time_s).into());
            *wall_time_s = f64::NAN;
        }
    }

    /// With [`WallTimes::Apart`], records the commit flexrock was built from under `file`
    /// (`summary.json/flexrock_commit`, `.../flexrock_dirty`) and takes it out of `provenance`;
    /// otherwise leaves it alone. Like a wall time, it changes while the result does not.
    pub fn take_commit(&mut self, file: &str, provenance: &mut Provenance) {
        if self.mode == WallTimes::Apart {
            if let Some(commit) = provenance.build.take() {
                self.insert_commit(file, commit);
            }
        }
    }

    /// The provenance of `file`, a summary of results computed from `model`: with
    /// [`WallTimes::Apart`] without the commit, which goes to timings.json ([`Self::take_commit`]).
    pub fn provenance(&mut self, file: &str, model: &flexrock_core::model::Model) -> Provenance {
        let mut provenance = Provenance::of(model);
        self.take_commit(file, &mut provenance);
        provenance
    }

    /// Records `commit` under `file` (for a file whose summary never holds it).
    pub fn insert_commit(&mut self, file: &str, commit: Commit) {
        self.times.insert(
            format!("{file}/flexrock_commit"),
            commit.flexrock_commit.into(),
        );
        self.times.insert(
            format!("{file}/flexrock_dirty"),
            commit.flexrock_dirty.into(),
        );
    }

    /// `timings.json` for the set of files a command writes, with [`WallTimes::Apart`].
    pub fn file(&self) -> Option<(&'static str, Vec<u8>)> {
        (self.mode == WallTimes::Apart).then(|| ("timings.json", json_bytes(&self.times)))
    }
}

/// A wall time as printed (`"2.948 ms"` with `decimals` = 3), or `None` where it was taken out.
pub fn milliseconds(wall_time_s: f64, decimals: usize) -> Option<String> {
    wall_time_s
        .is_finite()
        .then(|| format!("{:.*} ms", decimals, wall_time_s * 1e3))
}
