//! A suite of records, the input of a study over many ground motions: a directory of record
//! files, or a list file.
//!
//! - A directory: every regular file in it whose extension names a record format
//!   ([`RecordFormat::from_extension`]: `.AT2`, `.csv`, `.txt`, `.dat`, `.V1`, `.V2`, `.V1c`,
//!   `.V2c`, `.ASC`), in the order of their names; other files (a `PROVENANCE.md`, a list file)
//!   are not records and are left out.
//! - A list file: one record a line, `PATH [scale=FACTOR] [vertical=PATH]`, a path relative to
//!   the list file's directory (in double quotes if it holds spaces). `scale` (finite, > 0,
//!   default 1) multiplies the record; `vertical` names the file of the same station's vertical
//!   component. `#` starts a comment; blank lines are skipped.
//!
//! Every record named must be a regular file; a list file's line that breaks a rule is refused
//! naming the file, the line and the rule. The records themselves are read later, by the
//! model's rules (their formats and units).

use std::path::{Path, PathBuf};

use super::error::{Location, RecordError};
use super::format::RecordFormat;
use super::read::{decode_utf8, read_bounded};
use super::text::{numbered_lines, quote};

/// One record of a suite.
#[derive(Debug, Clone, PartialEq)]
pub struct SuiteEntry {
    /// The record file (joined to the list file's directory, or the directory's).
    pub path: PathBuf,
    /// The factor on the record.
    pub scale: f64,
    /// The file of the vertical component of the same motion, if given.
    pub vertical: Option<PathBuf>,
    /// The list file's line that names it (None for a directory's file).
    pub line: Option<usize>,
}

/// A suite of records: where it was read from, and its records in order.
#[derive(Debug, Clone, PartialEq)]
pub struct Suite {
    /// The directory or list file.
    pub source: PathBuf,
    /// Its records.
    pub entries: Vec<SuiteEntry>,
}

/// Refuses a record file given where a suite is read: its extension or its first line says what
/// it is (a list file may be .txt or .csv, so those extensions alone say nothing).
fn refuse_a_record(path: &Path, text: &str, name: &str) -> Result<(), RecordError> {
    let format = match RecordFormat::from_extension(path) {
        Some(RecordFormat::Csv | RecordFormat::Text) | None => RecordFormat::from_content(text),
        known => known,
    };
    match format {
        Some(format) => Err(RecordError::HeaderRule {
            at: Location::file(name),
            rule: format!(
                "is a record file ({}), not a suite: a suite is a directory of record files or a \
                 list file of their paths, one a line",
                format.name()
            ),
        }),
        None => Ok(()),
    }
}

/// Reads the suite at `path`: a directory, or a list file.
pub fn read_suite(path: &Path) -> Result<Suite, RecordError> {
    let name = path.display().to_string();
    let metadata = std::fs::metadata(path).map_err(|error| RecordError::Read {
        file: name.clone(),
        error,
    })?;
    let entries = if metadata.is_dir() {
        directory_entries(path, &name)?
    } else {
        let text = decode_utf8(read_bounded(path, &name)?, &name)?;
        refuse_a_record(path, &text, &name)?;
        parse_list(&text, &name, path.parent().unwrap_or(Path::new(".")))?
    };
    if entries.is_empty() {
        return Err(RecordError::HeaderRule {
            at: Location::file(&name),
            rule: if metadata.is_dir() {
                "the directory holds no record file (.AT2, .csv, .txt, .dat, .V1, .V2, .V1c, \
                 .V2c, .ASC)"
                    .to_string()
            } else {
                "the list file names no record".to_string()
            },
        });
    }
    Ok(Suite {
        source: path.to_path_buf(),
        entries,
    })
}

/// The record files of a directory, in the order of their names.
fn directory_entries(dir: &Path, name: &str) -> Result<Vec<SuiteEntry>, RecordError> {
    let read_error = |error| RecordError::Read {
        file: name.to_string(),
        error,
    };
    let mut paths = Vec::new();
    for entry in std::fs::read_dir(dir).map_err(read_error)? {
        let path = entry.map_err(read_error)?.path();
        if RecordFormat::from_extension(&path).is_some() && path.is_file() {
            paths.push(path);
        }
    }
    paths.sort();
    Ok(paths
        .into_iter()
        .map(|path| SuiteEntry {
            path,
            scale: 1.0,
            vertical: None,
            line: None,
        })
        .collect())
}

/// The words of a list file's line: whitespace-separated, a word in double quotes kept whole
/// (`"my records/a.AT2"`, or `vertical="b c.AT2"`); None for an unclosed quote.
fn words(line: &str) -> Option<Vec<String>> {
    let mut words = Vec::new();
    let mut word = String::new();
    let (mut quoted, mut started) = (false, false);
    for c in line.chars() {
        match c {
            '"' => {
                quoted = !quoted;
                started = true;
            }
            c if c.is_whitespace() && !quoted => {
                if started {
                    words.push(std::mem::take(&mut word));
                    started = false;
                }
            }
            c => {
                word.push(c);
                started = true;
            }
        }
    }
    if quoted {
        return None;
    }
    if started {
        words.push(word);
    }
    Some(words)
}

/// The entries of a list file's text; paths are relative to `base`.
pub fn parse_list(text: &str, source: &str, base: &Path) -> Result<Vec<SuiteEntry>, RecordError> {
    let mut entries = Vec::new();
    for (number, line) in numbered_lines(text) {
        let content = line.split('#').next().unwrap_or("");
        let rule = |rule: String| RecordError::HeaderRule {
            at: Location::line(source, number),
            rule,
        };
        let Some(words) = words(content) else {
            return Err(rule("a double quote is not closed".to_string()));
        };
        let Some((path, options)) = words.split_first() else {
            continue;
        };
        let mut entry = SuiteEntry {
            path: base.join(path),
            scale: 1.0,
            vertical: None,
            line: Some(number),
        };
        let (mut scale_given, mut vertical_given) = (false, false);
        for option in options {
            let form = "expected PATH [scale=FACTOR] [vertical=PATH]";
            match option.split_once('=') {
                Some(("scale", value)) if !scale_given => {
                    scale_given = true;
                    entry.scale = value
                        .parse::<f64>()
                        .ok()
                        .filter(|s| s.is_finite() && *s > 0.0)
                        .ok_or_else(|| {
                            rule(format!(
                                "scale = {:?}: must be a finite number > 0",
                                quote(value)
                            ))
                        })?;
                }
                Some(("vertical", value)) if !vertical_given && !value.is_empty() => {
                    vertical_given = true;
                    entry.vertical = Some(base.join(value));
                }
                Some((key @ ("scale" | "vertical"), _)) => {
                    return Err(rule(format!("{key} is given twice, or empty ({form})")))
                }
                _ => {
                    return Err(rule(format!("{form}, found {:?}", quote(option))));
                }
            }
        }
        for file in std::iter::once(&entry.path).chain(&entry.vertical) {
            if !file.is_file() {
                return Err(rule(format!(
                    "{} is not a record file (no regular file there)",
                    file.display()
                )));
            }
        }
        entries.push(entry);
    }
    Ok(entries)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_line_is_split_into_words_quotes_kept_whole() {
        assert_eq!(
            words("  a.AT2 scale=1.5  vertical=\"b c.AT2\" ").unwrap(),
            ["a.AT2", "scale=1.5", "vertical=b c.AT2"]
        );
        assert_eq!(words("\"my records/a.AT2\"").unwrap(), ["my records/a.AT2"]);
        assert_eq!(words("\"\"").unwrap(), [""]);
        assert!(words("").unwrap().is_empty());
        assert_eq!(words("\"open"), None);
    }
}
