//! Reading a record file: only a regular file of bounded size, its bytes as UTF-8 text, read by
//! the reader of its format.

use std::path::Path;

use super::accelerogram::Record;
use super::at2::parse_at2;
use super::cosmos::parse_cosmos;
use super::csv::{parse_csv, parse_text};
use super::error::{Location, RecordError};
use super::esm::parse_esm;
use super::format::RecordFormat;
use super::sampling::{check_dt, dt_agrees};

/// Largest record file read, bytes (64 MiB). The largest real AT2 files are a few MB (a long
/// record at 200 Hz has some 60 000 values, 10-16 characters each).
pub const MAX_RECORD_BYTES: u64 = 64 * 1024 * 1024;

/// The text of a file's bytes; invalid UTF-8 is an error naming the line and byte offset.
pub(super) fn decode_utf8(bytes: Vec<u8>, source: &str) -> Result<String, RecordError> {
    String::from_utf8(bytes).map_err(|error| {
        let byte_offset = error.utf8_error().valid_up_to();
        let valid_part = error.as_bytes().get(..byte_offset).unwrap_or(&[]);
        let line = 1 + valid_part.iter().filter(|&&byte| byte == b'\n').count();
        RecordError::NotUtf8 {
            at: Location::line(source, line),
            byte_offset,
        }
    })
}

/// The bytes of a record file: only a regular file (checked before opening it, so that a FIFO
/// does not block and /dev/zero is not read), of at most [`MAX_RECORD_BYTES`] (checked before
/// reading, and enforced while reading in case the file grows).
pub(super) fn read_bounded(path: &Path, source: &str) -> Result<Vec<u8>, RecordError> {
    use std::io::Read as _;
    let read_error = |error| RecordError::Read {
        file: source.to_string(),
        error,
    };
    let too_large = |size| RecordError::TooLarge {
        file: source.to_string(),
        size,
        limit: MAX_RECORD_BYTES,
    };
    let metadata = std::fs::metadata(path).map_err(read_error)?;
    if !metadata.is_file() {
        return Err(RecordError::NotRegularFile {
            file: source.to_string(),
            found: crate::base::format::file_kind(metadata.file_type()),
        });
    }
    if metadata.len() > MAX_RECORD_BYTES {
        return Err(too_large(metadata.len()));
    }
    let file = std::fs::File::open(path).map_err(read_error)?;
    let mut bytes = Vec::with_capacity(metadata.len() as usize);
    file.take(MAX_RECORD_BYTES + 1)
        .read_to_end(&mut bytes)
        .map_err(read_error)?;
    if bytes.len() as u64 > MAX_RECORD_BYTES {
        return Err(too_large(bytes.len() as u64));
    }
    Ok(bytes)
}

/// Reads a record file. Without `format`, [`RecordFormat::detect`] tells it from the extension
/// and the first line. `dt` is required for one-column CSV and text; otherwise, if given, it
/// must agree with the file's dt to 1e-6 relative.
pub fn read_record(
    path: &Path,
    format: Option<RecordFormat>,
    dt: Option<f64>,
) -> Result<Record, RecordError> {
    read_record_named(path, &path.display().to_string(), format, dt)
}

/// [`read_record`], with the file named `name` in every error (a full path, say, where `path`
/// is relative to another directory); the record's source is `path` as given.
pub fn read_record_named(
    path: &Path,
    name: &str,
    format: Option<RecordFormat>,
    dt: Option<f64>,
) -> Result<Record, RecordError> {
    let mut record = read_named(path, name, format, dt)?;
    record.source = path.display().to_string();
    Ok(record)
}

pub(super) fn read_named(
    path: &Path,
    name: &str,
    format: Option<RecordFormat>,
    dt: Option<f64>,
) -> Result<Record, RecordError> {
    let source = name.to_string();
    let bytes = read_bounded(path, &source)?;
    let text = decode_utf8(bytes, &source)?;
    let format = match format.or_else(|| RecordFormat::detect(path, &text)) {
        Some(format) => format,
        None => {
            return Err(RecordError::UnknownFormat {
                extension: path
                    .extension()
                    .map(|extension| extension.to_string_lossy().into_owned())
                    .unwrap_or_default(),
                file: source,
            })
        }
    };
    let record = match format {
        RecordFormat::Csv => return parse_csv(&text, &source, dt),
        RecordFormat::Text => return parse_text(&text, &source, dt),
        RecordFormat::PeerAt2 => parse_at2(&text, &source)?,
        RecordFormat::Cosmos => parse_cosmos(&text, &source)?,
        RecordFormat::Esm => parse_esm(&text, &source)?,
    };
    if let Some(given) = dt {
        let given = check_dt(given, Location::file(&source))?;
        if !dt_agrees(given, record.dt) {
            return Err(RecordError::DtConflict {
                file: source,
                given,
                found: record.dt,
            });
        }
    }
    Ok(record)
}
