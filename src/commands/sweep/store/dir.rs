//! The directory a sweep writes: one process at a time (a lock on the directory), and a chunks
//! directory that flexrock made itself. Nothing else in it is ever removed, followed or written
//! into: a `chunks` that is a link, a file, or a directory holding anything flexrock did not
//! write, is refused with its path.

use std::fs::File;
use std::path::{Path, PathBuf};

use crate::error::{Error, Result};
use crate::writers;

/// The name of the chunks directory inside a sweep's directory.
pub(super) const CHUNKS_DIR: &str = "chunks";
/// The plan of the running sweep, inside the chunks directory: flexrock's mark on it.
pub(super) const PLAN_FILE: &str = "plan.json";

/// The exclusive lock of a sweep directory, held until dropped.
pub(super) struct Lock {
    _file: Option<File>,
}

/// Creates `dir` if needed (refusing a path whose existing part is not a directory, before
/// anything is computed) and takes its lock. A directory whose file system cannot lock is
/// written without one, with a warning pushed on `warnings`.
pub(super) fn lock(dir: &Path, warnings: &mut Vec<String>) -> Result<Lock> {
    writers::check_creatable(dir)?;
    std::fs::create_dir_all(dir).map_err(|e| Error::Write {
        path: dir.to_path_buf(),
        source: e,
    })?;
    let file = File::open(dir).map_err(|e| Error::Write {
        path: dir.to_path_buf(),
        source: e,
    })?;
    match file.try_lock() {
        Ok(()) => Ok(Lock { _file: Some(file) }),
        Err(std::fs::TryLockError::WouldBlock) => Err(Error::OutputTarget {
            path: dir.to_path_buf(),
            found: "is being written by another flexrock process (it holds the directory's lock)"
                .to_string(),
            rule: "one process at a time writes a sweep directory: wait for the other to end, \
                   or use another --out"
                .to_string(),
        }),
        Err(std::fs::TryLockError::Error(e)) => {
            warnings.push(format!(
                "cannot lock {} ({e}): make sure no other process writes it meanwhile",
                dir.display()
            ));
            Ok(Lock { _file: None })
        }
    }
}

/// What a chunks directory holds, once it is known to be flexrock's.
pub(super) struct Chunks {
    /// Its path.
    pub path: PathBuf,
    /// plan.json's bytes, if it has one.
    pub plan: Option<Vec<u8>>,
}

/// True for the names flexrock writes in a chunks directory: plan.json, `<9 digits>.csv`, and
/// the temporary entries of its atomic writes.
fn is_chunks_entry(name: &str) -> bool {
    name == PLAN_FILE
        || name.starts_with(writers::TEMPORARY_PREFIX)
        || name
            .strip_suffix(".csv")
            .is_some_and(|n| n.len() == 9 && n.bytes().all(|b| b.is_ascii_digit()))
}

/// Opens `dir/chunks` if it is flexrock's (or makes it if absent): Ok(None) when absent and
/// `create` is false.
pub(super) fn chunks(dir: &Path, create: bool) -> Result<Option<Chunks>> {
    let path = dir.join(CHUNKS_DIR);
    let refuse = |found: String| Error::OutputTarget {
        path: path.clone(),
        found,
        rule: "flexrock keeps its chunks only in a chunks directory it made itself, and never \
               follows, writes into or removes anything else: move it away or use another --out"
            .to_string(),
    };
    match std::fs::symlink_metadata(&path) {
        Err(e) if e.kind() == std::io::ErrorKind::NotFound => {
            if !create {
                return Ok(None);
            }
            std::fs::create_dir(&path).map_err(|e| Error::Write {
                path: path.clone(),
                source: e,
            })?;
            Ok(Some(Chunks { path, plan: None }))
        }
        Err(e) => Err(Error::Write {
            path: path.clone(),
            source: e,
        }),
        Ok(m) if m.file_type().is_symlink() => Err(refuse("is a symbolic link".to_string())),
        Ok(m) if !m.is_dir() => Err(refuse(format!("is {}", writers::file_kind(m.file_type())))),
        Ok(_) => {
            let entries = std::fs::read_dir(&path).map_err(|e| Error::Write {
                path: path.clone(),
                source: e,
            })?;
            let mut foreign: Vec<String> = Vec::new();
            for entry in entries.flatten() {
                let name = entry.file_name().to_string_lossy().into_owned();
                let kind = entry.file_type().ok();
                let ours = is_chunks_entry(&name)
                    && (name.starts_with(writers::TEMPORARY_PREFIX)
                        || kind.is_some_and(|k| k.is_file()));
                if !ours {
                    foreign.push(name);
                }
            }
            if !foreign.is_empty() {
                foreign.sort();
                return Err(refuse(format!(
                    "holds {}, which flexrock did not write",
                    foreign
                        .iter()
                        .take(3)
                        .map(|n| format!("\"{n}\""))
                        .collect::<Vec<_>>()
                        .join(", ")
                        + if foreign.len() > 3 { " and more" } else { "" }
                )));
            }
            let plan = std::fs::read(path.join(PLAN_FILE)).ok();
            Ok(Some(Chunks { path, plan }))
        }
    }
}

/// Removes what flexrock wrote in a chunks directory it owns (see [`chunks`]), then the
/// directory if that leaves it empty. Returns a warning when something is left.
pub(super) fn remove_chunks(chunks: &Path) -> Option<String> {
    let entries = std::fs::read_dir(chunks).ok()?;
    for entry in entries.flatten() {
        let name = entry.file_name().to_string_lossy().into_owned();
        if !is_chunks_entry(&name) {
            continue;
        }
        let is_dir = entry.file_type().is_ok_and(|k| k.is_dir());
        let _ = if is_dir && name.starts_with(writers::TEMPORARY_PREFIX) {
            std::fs::remove_dir_all(entry.path())
        } else if !is_dir {
            std::fs::remove_file(entry.path())
        } else {
            Ok(())
        };
    }
    std::fs::remove_dir(chunks).err().map(|e| {
        format!(
            "left {} in place ({e}): it holds files flexrock did not write",
            chunks.display()
        )
    })
}
