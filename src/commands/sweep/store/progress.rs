//! How a running sweep tells of its progress.

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
