//! The threads a sweep computes its points on.

use crate::error::{Error, Result};

/// The most threads `--threads` takes: more than the cores of any machine a sweep runs on.
/// Each thread reserves its stack, and a system limits how many a process may start: far
/// above this, starting them takes minutes and then fails.
pub const MAX_THREADS: usize = 1024;

/// Starts the threads a sweep computes its points on: `threads` of them (checked against
/// [`MAX_THREADS`], an input error naming `--threads`), or one per core. A system that cannot
/// start them is an error (exit code 1), before anything is written.
pub fn start_threads(threads: Option<usize>) -> Result<()> {
    if let Some(threads) = threads {
        if !(1..=MAX_THREADS).contains(&threads) {
            return Err(Error::invalid(
                "--threads",
                threads,
                &format!("must be from 1 to {MAX_THREADS}"),
            ));
        }
    }
    let mut builder = rayon::ThreadPoolBuilder::new();
    if let Some(threads) = threads {
        builder = builder.num_threads(threads);
    }
    builder.build_global().map_err(|e| Error::Threads {
        threads: threads.map_or_else(|| "one per core".to_string(), |n| n.to_string()),
        message: e.to_string(),
    })
}
