//! Output files: CSV tables and JSON summaries, written atomically. Writers see only the
//! solver-agnostic [`Solution`](crate::solution::Solution) types, never a solver.

use std::io::Write;
use std::path::{Path, PathBuf};

use crate::error::{Error, Result};
use crate::solution::{Event, Sample};

/// Column names of history.csv (a contract).
pub const HISTORY_COLUMNS: [&str; 9] = [
    "t",
    "q",
    "qdot",
    "s",
    "r",
    "mode",
    "floor_acc",
    "F",
    "energy_residual",
];

/// Column names of events.csv (a contract).
pub const EVENT_COLUMNS: [&str; 8] = [
    "index",
    "t",
    "kind",
    "from",
    "to",
    "q",
    "qdot_before",
    "qdot_after",
];

/// A CSV table built in memory, so that nothing reaches the disk before it is complete.
pub struct Table {
    writer: csv::Writer<Vec<u8>>,
}

impl Table {
    pub fn new(columns: &[&str]) -> Self {
        let mut writer = csv::Writer::from_writer(Vec::new());
        // Writing to memory cannot fail.
        let _ = writer.write_record(columns);
        Table { writer }
    }

    /// Appends a row of already formatted fields.
    pub fn row<I, S>(&mut self, fields: I)
    where
        I: IntoIterator<Item = S>,
        S: AsRef<[u8]>,
    {
        let _ = self.writer.write_record(fields);
    }

    pub fn into_bytes(self) -> Vec<u8> {
        self.writer.into_inner().unwrap_or_default()
    }
}

/// Formats a number so that it reads back exactly (shortest round-trip form).
pub fn number(x: f64) -> String {
    format!("{x}")
}

/// A number as a person would type it, for messages and help texts: its shortest round-trip
/// digits, in exponent form when that is shorter by two characters or more (1e-4, 1e300, 2e5;
/// but 0.005, 0.0003125, 43.98). It reads back exactly, and 1e300 or 1e-300 never print as
/// 301 digits.
pub fn shortest(x: f64) -> String {
    let plain = format!("{x}");
    if !x.is_finite() {
        return plain;
    }
    let exponent = format!("{x:e}");
    if exponent.len() + 2 <= plain.len() {
        exponent
    } else {
        plain
    }
}

/// A number in exponent form (1e-8, 2.5e-3), as tolerances are written.
pub fn scientific(x: f64) -> String {
    format!("{x:e}")
}

/// Significant digits of [`readable`].
const READABLE_DIGITS: usize = 12;

/// A computed quantity for people: rounded to 12 significant digits, then in the form of
/// [`shortest`], so that a sum such as 43.980000000000004 prints as 43.98.
pub fn readable(x: f64) -> String {
    if !x.is_finite() || x == 0.0 {
        return shortest(x);
    }
    let rounded = format!("{x:.prec$e}", prec = READABLE_DIGITS - 1)
        .parse::<f64>()
        .unwrap_or(x);
    shortest(rounded)
}

/// A count with its noun: "1 uplift", "2 uplifts", "0 uplifts".
pub fn count(n: usize, singular: &str, plural: &str) -> String {
    format!("{n} {}", if n == 1 { singular } else { plural })
}

/// Values as a comma-separated list, each in the form `format` gives ([`shortest`],
/// [`scientific`]), as a user types them after a flag such as `--dt`.
pub fn list(values: &[f64], format: fn(f64) -> String) -> String {
    values
        .iter()
        .map(|&x| format(x))
        .collect::<Vec<_>>()
        .join(",")
}

pub fn history_csv(samples: &[Sample]) -> Vec<u8> {
    let mut table = Table::new(&HISTORY_COLUMNS);
    for s in samples {
        table.row([
            number(s.t),
            number(s.q),
            number(s.qdot),
            number(s.s),
            number(s.r),
            s.mode.name().to_string(),
            number(s.floor_acc),
            number(s.restoring_force),
            number(s.energy_residual),
        ]);
    }
    table.into_bytes()
}

pub fn events_csv(events: &[Event]) -> Vec<u8> {
    let mut table = Table::new(&EVENT_COLUMNS);
    for e in events {
        table.row([
            e.index.to_string(),
            number(e.t),
            e.kind.name().to_string(),
            e.from.name().to_string(),
            e.to.name().to_string(),
            number(e.q),
            number(e.qdot_before),
            number(e.qdot_after),
        ]);
    }
    table.into_bytes()
}

pub fn json_bytes<T: serde::Serialize>(value: &T) -> Vec<u8> {
    let mut bytes = serde_json::to_vec_pretty(value).unwrap_or_default();
    bytes.push(b'\n');
    bytes
}

/// Writes a set of files into `dir` so that each appears whole or not at all: every file is first
/// written and synced under a temporary name, and only when all are written are they renamed.
///
/// Before anything is written, every target is checked: an existing target must be a regular
/// file (or a symbolic link to one, which is then replaced by the file); a directory, device,
/// FIFO or socket (or a link to one) is refused with [`Error::OutputTarget`], an input error,
/// and so is a `dir` that exists and is not a directory.
pub fn write_atomically(dir: &Path, files: &[(&str, Vec<u8>)]) -> Result<Vec<PathBuf>> {
    let write_err = |path: &Path, source| Error::Write {
        path: path.to_path_buf(),
        source,
    };
    check_output_dir(dir)?;
    for (name, _) in files {
        check_target(&dir.join(name))?;
    }
    std::fs::create_dir_all(dir).map_err(|e| write_err(dir, e))?;
    let mut staged = Vec::new();
    let result = (|| {
        for (name, bytes) in files {
            let tmp = dir.join(format!(".{name}.tmp-{}", std::process::id()));
            staged.push(tmp.clone());
            let mut f = std::fs::File::create(&tmp).map_err(|e| write_err(&tmp, e))?;
            f.write_all(bytes).map_err(|e| write_err(&tmp, e))?;
            f.sync_all().map_err(|e| write_err(&tmp, e))?;
        }
        let mut finals = Vec::new();
        for ((name, _), tmp) in files.iter().zip(&staged) {
            let target = dir.join(name);
            std::fs::rename(tmp, &target).map_err(|e| write_err(&target, e))?;
            finals.push(target);
        }
        Ok(finals)
    })();
    if result.is_err() {
        for tmp in &staged {
            let _ = std::fs::remove_file(tmp);
        }
    }
    result
}

/// What a file system entry is, for messages: "a directory", "a FIFO (named pipe)", ...
pub(crate) fn file_kind(file_type: std::fs::FileType) -> &'static str {
    #[cfg(unix)]
    {
        use std::os::unix::fs::FileTypeExt;
        if file_type.is_fifo() {
            return "a FIFO (named pipe)";
        }
        if file_type.is_char_device() {
            return "a character device";
        }
        if file_type.is_block_device() {
            return "a block device";
        }
        if file_type.is_socket() {
            return "a socket";
        }
    }
    if file_type.is_dir() {
        "a directory"
    } else if file_type.is_file() {
        "a regular file"
    } else {
        "a special file"
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

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn numbers_for_people() {
        assert_eq!(shortest(1e300), "1e300");
        assert_eq!(shortest(-1e-300), "-1e-300");
        assert_eq!(shortest(0.005), "0.005");
        assert_eq!(shortest(0.0003125), "0.0003125");
        assert_eq!(shortest(1e-4), "1e-4");
        assert_eq!(shortest(43.980000000000004), "43.980000000000004");
        assert_eq!(shortest(f64::NAN), "NaN");
        assert_eq!(shortest(f64::NEG_INFINITY), "-inf");
        assert_eq!(readable(43.980000000000004), "43.98");
        assert_eq!(readable(0.1 + 0.2), "0.3");
        assert_eq!(readable(1.0 / 3.0), "0.333333333333");
        assert_eq!(readable(0.0), "0");
        assert_eq!(readable(6e4), "6e4");
        assert_eq!(readable(31.16), "31.16");
        assert_eq!(count(1, "uplift", "uplifts"), "1 uplift");
        assert_eq!(count(0, "uplift", "uplifts"), "0 uplifts");
        assert_eq!(count(2, "uplift", "uplifts"), "2 uplifts");
        assert_eq!(list(&[1e-3, 1e-11], scientific), "1e-3,1e-11");
        assert_eq!(list(&[0.04, 0.0003125], shortest), "0.04,0.0003125");
    }
}
