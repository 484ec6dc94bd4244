//! Writing output files atomically: a set of files put in place together or not at all, a
//! checkpoint whole or absent, and the checks on what may be replaced.

use std::io::Write;
use std::path::{Path, PathBuf};

use super::file_kind;
use crate::error::{Error, Result};

/// Start of the name of the temporary directory a write uses inside the output directory:
/// `.flexrock-tmp-<pid>-<nonce>`.
pub const TEMPORARY_PREFIX: &str = ".flexrock-tmp-";

/// A temporary entry older than this is stale whatever its pid says. A write takes seconds (the
/// computation happens before it), so this only matters where a pid cannot be checked (no
/// `/proc`) or has been reused by another process.
const STALE_AGE: std::time::Duration = std::time::Duration::from_secs(3600);

/// Writes a set of files into `dir` (created if missing) so that it replaces the previous set
/// as a whole or not at all.
///
/// 1. Before anything is written, every target is checked: an existing target must be a
///    regular file (or a symbolic link to one, which is then replaced by the file); a directory,
///    device, FIFO or socket (or a link to one) is refused with [`Error::OutputTarget`], an
///    input error, and so is a `dir` that exists and is not a directory.
/// 2. Temporaries that an earlier, killed write left in `dir` are removed: entries named
///    `.flexrock-tmp-<pid>-<nonce>` (and `.<name>.tmp-<pid>` of older versions, for the names
///    of this set) whose process is no longer running (checked in `/proc`), or older than an
///    hour.
/// 3. Every new file is written and synced into a fresh directory
///    `dir/.flexrock-tmp-<pid>-<nonce>/` as `new-<name>`. That directory itself is not synced:
///    its entries are temporary, and the names that matter are made durable in step 4.
/// 4. The previous files of the set are renamed into that directory as `old-<name>`, then the
///    new files are renamed into place, the set's last name last, and `dir` is synced (where
///    the system allows): one directory sync a set.
/// 5. On any failure in 3 or 4 the new files are taken out and the previous ones renamed back,
///    so that `dir` holds exactly what it held before; if even that fails, the error says
///    where the previous files are ([`Error::Rollback`]). On success the temporary directory,
///    with the previous files, is removed.
///
/// What a reader can observe: the files of the set that are present at any moment are all
/// previous ones (while step 4 moves them away) or all new ones (while it moves the new ones
/// in), never a mix of both; each file is whole. If the process is killed during step 4, some
/// files of the set may be missing (a set of several files cannot be replaced in one atomic
/// step without swapping the whole directory); the previous files are then in
/// `dir/.flexrock-tmp-<pid>-<nonce>/old-<name>` until the next write into `dir` removes that
/// directory. Files in `dir` that are not part of the set are left alone.
pub fn write_atomically(dir: &Path, files: &[(&str, Vec<u8>)]) -> Result<Vec<PathBuf>> {
    write_set(dir, files, &mut |from, to| std::fs::rename(from, to))
}

/// [`write_atomically`] for files whose names are made at run time (a figure in each format
/// asked for).
pub fn write_named_atomically(
    dir: &Path,
    mut files: Vec<(String, Vec<u8>)>,
) -> Result<Vec<PathBuf>> {
    let named: Vec<(&str, Vec<u8>)> = (files.iter_mut())
        .map(|(name, bytes)| (name.as_str(), std::mem::take(bytes)))
        .collect();
    write_atomically(dir, &named)
}

/// [`write_atomically`] with the rename operation given, so that tests can make it fail.
fn write_set(
    dir: &Path,
    files: &[(&str, Vec<u8>)],
    rename: &mut dyn FnMut(&Path, &Path) -> std::io::Result<()>,
) -> Result<Vec<PathBuf>> {
    let names: Vec<&str> = files.iter().map(|(name, _)| *name).collect();
    let set = FileSet::begin(dir, &names)?;
    // Every target before any file is written (staging checks each again as it writes it).
    for name in &names {
        check_target(&dir.join(name))?;
    }
    set.stage_each(files)?;
    set.commit_with(rename)
}

/// A set of files written into one directory as a whole, as [`write_atomically`] writes them,
/// but staged one by one as each is ready, from any thread (a large file is written and synced
/// while the next is still being made), then put in place together by [`FileSet::commit`].
/// Dropped without a commit (an error on the way), it removes what it staged: the directory is
/// left as it was.
pub struct FileSet {
    dir: PathBuf,
    /// The names the set may hold, in the order they are put in place.
    order: Vec<String>,
    staging: PathBuf,
    /// The names staged so far.
    staged: std::sync::Mutex<Vec<String>>,
    /// Set when a failed commit could not put the previous files back: they stay in `staging`.
    keep_staging: bool,
}

impl FileSet {
    /// Starts a set in `dir` (which must be a directory, or is created) of files among `order`,
    /// plain names in the order they are to be put in place; removes the temporaries a killed
    /// write left in `dir` (steps 1 and 2 of [`write_atomically`], but for the targets, which
    /// [`FileSet::stage`] checks).
    pub fn begin(dir: &Path, order: &[&str]) -> Result<Self> {
        check_output_dir(dir)?;
        for name in order {
            check_file_name(dir, name)?;
        }
        let write_err = |source| Error::Write {
            path: dir.to_path_buf(),
            source,
        };
        std::fs::create_dir_all(dir).map_err(write_err)?;
        remove_stale_temporaries(dir, order);
        let staging = create_staging_dir(dir).map_err(write_err)?;
        Ok(FileSet {
            dir: dir.to_path_buf(),
            order: order.iter().map(|name| name.to_string()).collect(),
            staging,
            staged: std::sync::Mutex::new(Vec::new()),
            keep_staging: false,
        })
    }

    /// Writes the file `name` of the set, the bytes of `parts` one after another, and syncs it
    /// (step 3 of [`write_atomically`]); its target must be a regular file or absent.
    pub fn stage(&self, name: &str, parts: &[&[u8]]) -> Result<()> {
        let target = self.dir.join(name);
        if !self.order.iter().any(|n| n == name) {
            return Err(Error::Write {
                path: target,
                source: std::io::Error::new(
                    std::io::ErrorKind::InvalidInput,
                    "not one of the files of the set being written",
                ),
            });
        }
        check_target(&target)?;
        let path = self.staging.join(format!("new-{name}"));
        let write_err = |source| Error::Write {
            path: path.clone(),
            source,
        };
        let mut f = std::fs::File::create(&path).map_err(write_err)?;
        for part in parts {
            f.write_all(part).map_err(write_err)?;
        }
        f.sync_all().map_err(write_err)?;
        let mut staged = self.staged.lock().unwrap_or_else(|e| e.into_inner());
        if !staged.iter().any(|n| n == name) {
            staged.push(name.to_string());
        }
        Ok(())
    }

    /// Stages each of `files` (name, bytes), each on a thread of its own: the disk syncs them
    /// at once, not one after another. A file whose thread the system cannot start is staged
    /// on this one.
    pub fn stage_each<N, B>(&self, files: &[(N, B)]) -> Result<()>
    where
        N: AsRef<str> + Sync,
        B: AsRef<[u8]> + Sync,
    {
        let stage = |(name, bytes): &(N, B)| self.stage(name.as_ref(), &[bytes.as_ref()]);
        std::thread::scope(|scope| {
            let mut here = Vec::new();
            let threads: Vec<_> = files
                .get(1..)
                .unwrap_or_default()
                .iter()
                .filter_map(|file| {
                    let started =
                        std::thread::Builder::new().spawn_scoped(scope, move || stage(file));
                    if started.is_err() {
                        here.push(file);
                    }
                    started.ok()
                })
                .collect();
            let first = here
                .into_iter()
                .map(stage)
                .fold(files.first().map_or(Ok(()), stage), Result::and);
            threads
                .into_iter()
                .map(|thread| {
                    thread
                        .join()
                        .unwrap_or_else(|e| std::panic::resume_unwind(e))
                })
                .fold(first, Result::and)
        })
    }

    /// Puts the staged files in place, in the set's order (steps 4 and 5 of
    /// [`write_atomically`]); their paths.
    pub fn commit(self) -> Result<Vec<PathBuf>> {
        self.commit_with(&mut |from, to| std::fs::rename(from, to))
    }

    /// [`FileSet::commit`] with the rename operation given.
    fn commit_with(
        mut self,
        rename: &mut dyn FnMut(&Path, &Path) -> std::io::Result<()>,
    ) -> Result<Vec<PathBuf>> {
        let staged = std::mem::take(self.staged.get_mut().unwrap_or_else(|e| e.into_inner()));
        let names: Vec<&str> = self
            .order
            .iter()
            .filter(|name| staged.contains(name))
            .map(String::as_str)
            .collect();
        let result = swap_in(&self.dir, &self.staging, &names, rename);
        // The previous files could not all be put back: they stay in the staging directory.
        self.keep_staging = matches!(result, Err(Error::Rollback { .. }));
        result
    }
}

impl Drop for FileSet {
    fn drop(&mut self) {
        if !self.keep_staging {
            let _ = std::fs::remove_dir_all(&self.staging);
        }
    }
}

/// Moves the previous files of the set into `staging` and the new ones from it into `dir`;
/// on failure puts everything back as it was.
fn swap_in(
    dir: &Path,
    staging: &Path,
    names: &[&str],
    rename: &mut dyn FnMut(&Path, &Path) -> std::io::Result<()>,
) -> Result<Vec<PathBuf>> {
    let target = |name: &str| dir.join(name);
    let old = |name: &str| staging.join(format!("old-{name}"));
    let new = |name: &str| staging.join(format!("new-{name}"));
    // Names whose previous file was moved aside, and names whose new file is in place.
    let mut moved_aside: Vec<&str> = Vec::new();
    let mut installed: Vec<&str> = Vec::new();
    let mut step = || -> std::result::Result<(), (PathBuf, std::io::Error)> {
        for &name in names {
            match std::fs::symlink_metadata(target(name)) {
                // Checked before, and again here: nothing but a file or a link is moved aside
                // (and later removed with the staging directory).
                Ok(m) if m.is_file() || m.file_type().is_symlink() => {
                    rename(&target(name), &old(name)).map_err(|e| (target(name), e))?;
                    moved_aside.push(name);
                }
                Ok(m) => {
                    let message = format!(
                        "it became {} after it was checked; {TARGET_RULE}",
                        file_kind(m.file_type())
                    );
                    return Err((target(name), std::io::Error::other(message)));
                }
                Err(e) if e.kind() == std::io::ErrorKind::NotFound => {}
                Err(e) => return Err((target(name), e)),
            }
        }
        for &name in names {
            rename(&new(name), &target(name)).map_err(|e| (target(name), e))?;
            installed.push(name);
        }
        Ok(())
    };
    let outcome = step();
    match outcome {
        Ok(()) => {
            sync_dir(dir);
            Ok(names.iter().map(|name| target(name)).collect())
        }
        Err((path, source)) => {
            // Put the previous set back: a previous file renamed over a new one replaces it; a
            // new file without a previous one is removed.
            let mut restore_error = None;
            for &name in names {
                let restored = if moved_aside.contains(&name) {
                    rename(&old(name), &target(name))
                } else if installed.contains(&name) {
                    std::fs::remove_file(target(name))
                } else {
                    Ok(())
                };
                if let Err(e) = restored {
                    restore_error.get_or_insert(e);
                }
            }
            sync_dir(dir);
            match restore_error {
                None => Err(Error::Write { path, source }),
                Some(restore_error) => Err(Error::Rollback {
                    path,
                    source,
                    restore_error,
                    kept: staging.to_path_buf(),
                }),
            }
        }
    }
}

/// Syncs a directory's entries to disk where the system allows it (best effort: some systems
/// cannot open or sync a directory).
fn sync_dir(dir: &Path) {
    #[cfg(test)]
    tests::SYNCED_DIRS.with(|synced| synced.borrow_mut().push(dir.to_path_buf()));
    if let Ok(d) = std::fs::File::open(dir) {
        let _ = d.sync_all();
    }
}

/// A new, empty directory `dir/.flexrock-tmp-<pid>-<nonce>`.
fn create_staging_dir(dir: &Path) -> std::io::Result<PathBuf> {
    create_temporary(dir, |path| std::fs::create_dir(path)).map(|(path, ())| path)
}

/// A new entry `dir/.flexrock-tmp-<pid>-<nonce>` made by `create`, which must fail with
/// `AlreadyExists` if the name is taken (another nonce is then tried); its path and what
/// `create` returned.
fn create_temporary<T>(
    dir: &Path,
    create: impl Fn(&Path) -> std::io::Result<T>,
) -> std::io::Result<(PathBuf, T)> {
    use std::sync::atomic::{AtomicU64, Ordering};
    static COUNTER: AtomicU64 = AtomicU64::new(0);
    let pid = std::process::id();
    loop {
        let clock = std::time::SystemTime::now()
            .duration_since(std::time::UNIX_EPOCH)
            .map_or(0, |d| d.subsec_nanos() as u64);
        let nonce = clock ^ (COUNTER.fetch_add(1, Ordering::Relaxed) << 32);
        let path = dir.join(format!("{TEMPORARY_PREFIX}{pid}-{nonce:x}"));
        match create(&path) {
            Err(e) if e.kind() == std::io::ErrorKind::AlreadyExists => continue,
            other => return other.map(|made| (path, made)),
        }
    }
}

/// Writes a checkpoint: a file that can be made again, and whose reader checks it before use
/// (a sweep's chunk, under its seal), from `parts` in order. The file is written whole into a
/// temporary file `.flexrock-tmp-<pid>-<nonce>` beside `path` and renamed over it, so a kill
/// leaves the previous file or the new one, never a part of it; unlike [`write_atomically`]
/// it is not synced to the disk, because a crash of the machine that tears it costs only its
/// computation: its reader finds it torn and makes it again. On failure the temporary file is
/// removed.
pub fn write_checkpoint(path: &Path, parts: &[&[u8]]) -> Result<()> {
    let write_err = |path: &Path, source| Error::Write {
        path: path.to_path_buf(),
        source,
    };
    let dir = match path.parent() {
        Some(d) if !d.as_os_str().is_empty() => d,
        _ => Path::new("."),
    };
    let (temporary, mut file) = create_temporary(dir, |candidate| {
        std::fs::OpenOptions::new()
            .write(true)
            .create_new(true)
            .open(candidate)
    })
    .map_err(|e| write_err(path, e))?;
    let written = parts
        .iter()
        .try_for_each(|part| file.write_all(part))
        .and_then(|()| {
            drop(file);
            std::fs::rename(&temporary, path)
        });
    written.map_err(|e| {
        let _ = std::fs::remove_file(&temporary);
        write_err(path, e)
    })
}

/// The pid in the name of a temporary entry of flexrock, if the name is one: the current
/// `.flexrock-tmp-<pid>-<nonce>` or, for the names of the set being written, the
/// `.<name>.tmp-<pid>` files of earlier versions.
fn temporary_pid(entry: &str, names: &[&str]) -> Option<u32> {
    if let Some(rest) = entry.strip_prefix(TEMPORARY_PREFIX) {
        let (pid, nonce) = rest.split_once('-')?;
        let all_hex = !nonce.is_empty() && nonce.chars().all(|c| c.is_ascii_hexdigit());
        return all_hex.then(|| pid.parse().ok()).flatten();
    }
    names.iter().find_map(|name| {
        entry
            .strip_prefix(&format!(".{name}.tmp-"))
            .and_then(|pid| pid.parse().ok())
    })
}

/// Whether a process with this pid runs on this machine: Some(answer) where `/proc` tells,
/// None where it cannot be known.
fn process_is_running(pid: u32) -> Option<bool> {
    if pid == std::process::id() {
        return Some(true);
    }
    if !Path::new("/proc/self").exists() {
        return None;
    }
    Some(Path::new(&format!("/proc/{pid}")).exists())
}

/// Removes the temporaries a killed write left in `dir` (see [`write_atomically`]). Best
/// effort: an entry that cannot be removed is left, and the write goes on.
pub(crate) fn remove_stale_temporaries(dir: &Path, names: &[&str]) {
    let Ok(entries) = std::fs::read_dir(dir) else {
        return;
    };
    for entry in entries.flatten() {
        let file_name = entry.file_name();
        let Some(pid) = file_name.to_str().and_then(|n| temporary_pid(n, names)) else {
            continue;
        };
        let Ok(metadata) = entry.path().symlink_metadata() else {
            continue;
        };
        let old = metadata
            .modified()
            .ok()
            .and_then(|m| m.elapsed().ok())
            .is_some_and(|age| age > STALE_AGE);
        let stale = process_is_running(pid) == Some(false) || old;
        if !stale {
            continue;
        }
        let _ = if metadata.is_dir() {
            std::fs::remove_dir_all(entry.path())
        } else {
            std::fs::remove_file(entry.path())
        };
    }
}

/// The rule of [`check_target`], as messages state it.
const TARGET_RULE: &str = "flexrock replaces only regular files, never a directory, device, \
     FIFO or socket (nor a symbolic link to one): remove it or choose another output path";

/// An existing output target must be a regular file (after following symbolic links).
fn check_target(path: &Path) -> Result<()> {
    match std::fs::metadata(path) {
        Ok(m) if m.is_file() => Ok(()),
        Ok(m) => {
            let linked = std::fs::symlink_metadata(path).is_ok_and(|l| l.file_type().is_symlink());
            let kind = file_kind(m.file_type());
            Err(Error::OutputTarget {
                path: path.to_path_buf(),
                found: if linked {
                    format!("is a symbolic link to {kind}")
                } else {
                    format!("is {kind}")
                },
                rule: TARGET_RULE.to_string(),
            })
        }
        // Nothing there, or a dangling symbolic link (replaced by the file).
        Err(e) if e.kind() == std::io::ErrorKind::NotFound => Ok(()),
        Err(e) => Err(Error::Write {
            path: path.to_path_buf(),
            source: e,
        }),
    }
}

/// An existing output directory must be a directory.
fn check_output_dir(dir: &Path) -> Result<()> {
    match std::fs::metadata(dir) {
        Ok(m) if !m.is_dir() => Err(Error::OutputTarget {
            path: dir.to_path_buf(),
            found: format!("is {}", file_kind(m.file_type())),
            rule: "the output directory must be a directory (or not exist yet)".to_string(),
        }),
        _ => Ok(()),
    }
}

/// An output name must be a plain file name: no separator, not `.` or `..`.
fn check_file_name(dir: &Path, name: &str) -> Result<()> {
    let plain = Path::new(name).file_name().and_then(|n| n.to_str()) == Some(name);
    if plain {
        Ok(())
    } else {
        Err(Error::Write {
            path: dir.join(name),
            source: std::io::Error::new(std::io::ErrorKind::InvalidInput, "not a file name"),
        })
    }
}

/// Writes one file atomically (see [`write_atomically`]): a regular file is replaced whole or
/// left as it was; anything else at `path` is refused before anything is written.
pub fn write_file_atomically(path: &Path, bytes: &[u8]) -> Result<()> {
    let dir = match path.parent() {
        Some(d) if !d.as_os_str().is_empty() => d,
        _ => Path::new("."),
    };
    let Some(name) = path.file_name().and_then(|n| n.to_str()) else {
        // "/", "..", "dir/.." or a name that is not UTF-8.
        return match std::fs::metadata(path) {
            Ok(m) if !m.is_file() => Err(Error::OutputTarget {
                path: path.to_path_buf(),
                found: format!("is {}", file_kind(m.file_type())),
                rule: TARGET_RULE.to_string(),
            }),
            _ => Err(Error::Write {
                path: path.to_path_buf(),
                source: std::io::Error::new(
                    std::io::ErrorKind::InvalidInput,
                    "not a file name flexrock can write (it must end in a UTF-8 file name)",
                ),
            }),
        };
    };
    write_atomically(dir, &[(name, bytes.to_vec())]).map(|_| ())
}

/// Refuses an output directory that cannot be made because a part of its path is a file (or
/// anything but a directory): `--out afile/sub`. Every command checks its --out with it before it computes anything.
pub fn check_creatable(dir: &Path) -> Result<()> {
    for ancestor in dir.ancestors() {
        if ancestor.as_os_str().is_empty() {
            break;
        }
        match std::fs::metadata(ancestor) {
            Ok(m) if m.is_dir() => return Ok(()),
            Ok(m) => {
                return Err(Error::OutputTarget {
                    path: ancestor.to_path_buf(),
                    found: format!("is {}", file_kind(m.file_type())),
                    rule: if ancestor == dir {
                        "the output directory must be a directory (or not exist yet)".to_string()
                    } else {
                        format!(
                            "the output directory {} lies inside it, so it cannot be made",
                            dir.display()
                        )
                    },
                })
            }
            Err(_) => continue,
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    thread_local! {
        /// The directories [`sync_dir`] synced on this thread, in order.
        pub(super) static SYNCED_DIRS: std::cell::RefCell<Vec<PathBuf>> =
            const { std::cell::RefCell::new(Vec::new()) };
    }

    /// A set's files are synced one by one, its temporary directory not at all: only the
    /// output directory is synced, once, after its names are in place.
    #[test]
    fn a_set_syncs_only_its_output_directory() {
        let dir = scratch("one-sync");
        SYNCED_DIRS.with(|synced| synced.borrow_mut().clear());
        write_atomically(&dir, &[("a", b"1".to_vec()), ("b", b"2".to_vec())]).unwrap();
        assert_eq!(
            SYNCED_DIRS.with(|synced| synced.take()),
            std::slice::from_ref(&dir)
        );
        let _ = std::fs::remove_dir_all(&dir);
    }

    fn scratch(name: &str) -> PathBuf {
        let dir =
            std::env::temp_dir().join(format!("flexrock-output-{name}-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&dir);
        std::fs::create_dir_all(&dir).unwrap();
        dir
    }

    fn names(dir: &Path) -> Vec<String> {
        let mut names: Vec<String> = std::fs::read_dir(dir)
            .unwrap()
            .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
            .collect();
        names.sort();
        names
    }

    /// Files staged out of order (the last first, from other threads) are put in place in the
    /// set's order; a set dropped before its commit leaves the directory as it was; a name
    /// outside the set is refused.
    #[test]
    fn a_file_set_is_put_in_place_in_its_order_or_not_at_all() {
        let dir = scratch("file-set");
        std::fs::write(dir.join("b.csv"), "previous").unwrap();
        let order = ["a.csv", "b.csv", "c.json"];
        let set = FileSet::begin(&dir, &order).unwrap();
        std::thread::scope(|scope| {
            scope.spawn(|| set.stage("c.json", &[b"{}"]).unwrap());
        });
        set.stage("a.csv", &[b"x,", b"y\n"]).unwrap();
        let e = set.stage("d.txt", &[b"no"]).unwrap_err();
        assert!(e.to_string().contains("d.txt"), "{e}");
        let mut renamed = Vec::new();
        set.commit_with(&mut |from, to| {
            renamed.push(to.file_name().unwrap().to_string_lossy().into_owned());
            std::fs::rename(from, to)
        })
        .unwrap();
        // b.csv was not staged: it is kept, not moved aside.
        assert_eq!(renamed, ["a.csv", "c.json"]);
        assert_eq!(names(&dir), ["a.csv", "b.csv", "c.json"]);
        assert_eq!(std::fs::read(dir.join("a.csv")).unwrap(), b"x,y\n");
        assert_eq!(std::fs::read(dir.join("b.csv")).unwrap(), b"previous");

        let dropped = FileSet::begin(&dir, &order).unwrap();
        dropped.stage("b.csv", &[b"new"]).unwrap();
        drop(dropped);
        assert_eq!(names(&dir), ["a.csv", "b.csv", "c.json"]);
        assert_eq!(std::fs::read(dir.join("b.csv")).unwrap(), b"previous");
        let _ = std::fs::remove_dir_all(&dir);
    }

    /// A checkpoint is its parts in order, replaces a previous file whole, and leaves nothing
    /// behind when it cannot be put in place (here: a directory stands at its path).
    #[test]
    fn a_checkpoint_is_whole_or_absent() {
        let dir = scratch("checkpoint");
        let path = dir.join("000000001.csv");
        std::fs::write(&path, "previous, longer than the new content\n").unwrap();
        write_checkpoint(&path, &[b"seal\n", b"", b"a,b\n1,2\n"]).unwrap();
        assert_eq!(std::fs::read(&path).unwrap(), b"seal\na,b\n1,2\n");
        assert_eq!(names(&dir), ["000000001.csv"]);

        let blocked = dir.join("blocked");
        std::fs::create_dir(blocked.join("")).unwrap();
        std::fs::write(blocked.join("inside"), "kept").unwrap();
        let e = write_checkpoint(&blocked, &[b"rows"]).unwrap_err();
        assert!(e.to_string().contains("blocked"), "{e}");
        assert_eq!(names(&dir), ["000000001.csv", "blocked"]);
        assert_eq!(std::fs::read(blocked.join("inside")).unwrap(), b"kept");
        let _ = std::fs::remove_dir_all(&dir);
    }

    /// A rename that fails at its `fail_at`-th call (0-based), like a disk error in the middle.
    fn failing_rename(fail_at: usize) -> impl FnMut(&Path, &Path) -> std::io::Result<()> {
        let mut calls = 0;
        move |from, to| {
            calls += 1;
            if calls - 1 == fail_at {
                Err(std::io::Error::other("injected failure"))
            } else {
                std::fs::rename(from, to)
            }
        }
    }

    #[test]
    fn a_failed_rename_puts_the_previous_set_back() {
        let files = |tag: &str| -> Vec<(&'static str, Vec<u8>)> {
            ["a.csv", "b.csv", "c.json"]
                .into_iter()
                .map(|n| (n, format!("{tag} {n}").into_bytes()))
                .collect()
        };
        // 2 of the 3 targets exist: calls 0-1 move them aside, 2-4 move the new files in.
        // Fail each of them in turn.
        for fail_at in 0..5 {
            let dir = scratch(&format!("rollback-{fail_at}"));
            write_atomically(&dir, &files("old")[..2]).unwrap();
            let mut rename = failing_rename(fail_at);
            let error = write_set(&dir, &files("new"), &mut rename).unwrap_err();
            assert!(matches!(error, Error::Write { .. }), "{fail_at}: {error}");
            assert!(error.to_string().contains("injected failure"), "{error}");
            // The two previous files as they were, no third file, no temporary left.
            assert_eq!(names(&dir), ["a.csv", "b.csv"], "{fail_at}");
            for n in ["a.csv", "b.csv"] {
                assert_eq!(
                    std::fs::read_to_string(dir.join(n)).unwrap(),
                    format!("old {n}")
                );
            }
            let _ = std::fs::remove_dir_all(&dir);
        }
    }

    #[test]
    fn the_whole_set_is_replaced() {
        let dir = scratch("replace");
        write_atomically(&dir, &[("a", b"1".to_vec()), ("b", b"1".to_vec())]).unwrap();
        let written =
            write_atomically(&dir, &[("a", b"2".to_vec()), ("b", b"2".to_vec())]).unwrap();
        assert_eq!(written, vec![dir.join("a"), dir.join("b")]);
        assert_eq!(names(&dir), ["a", "b"]);
        assert_eq!(std::fs::read(dir.join("b")).unwrap(), b"2");
        let _ = std::fs::remove_dir_all(&dir);
    }

    #[test]
    fn temporary_names() {
        let names = ["history.csv"];
        assert_eq!(temporary_pid(".flexrock-tmp-123-abc0", &names), Some(123));
        assert_eq!(temporary_pid(".history.csv.tmp-77", &names), Some(77));
        assert_eq!(temporary_pid(".events.csv.tmp-77", &names), None);
        assert_eq!(temporary_pid(".flexrock-tmp-123-", &names), None);
        assert_eq!(temporary_pid(".flexrock-tmp-x-1", &names), None);
        assert_eq!(temporary_pid("history.csv", &names), None);
    }
}
