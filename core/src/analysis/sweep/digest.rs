//! SHA-256 digests of what decides a sweep's rows: its plan, and the records it reads (files,
//! or records held in memory).

use std::path::Path;

use crate::floor::record::Record;

/// SHA-256 of `bytes`, as 64 lower-case hex digits: the digest of a record file a sweep reads,
/// and of its plan.
pub fn sha256_hex(bytes: &[u8]) -> String {
    sha256_hex_of(&[bytes])
}

/// SHA-256 of the bytes of `parts` one after another (the digest of their concatenation, which
/// is never made), as 64 lower-case hex digits.
pub fn sha256_hex_of(parts: &[&[u8]]) -> String {
    use sha2::{Digest as _, Sha256};
    let mut hasher = Sha256::new();
    for part in parts {
        hasher.update(part);
    }
    hex(&hasher.finalize())
}

/// `bytes` as lower-case hex digits, two a byte.
fn hex(bytes: &[u8]) -> String {
    let mut text = String::with_capacity(2 * bytes.len());
    for byte in bytes {
        text.push_str(&format!("{byte:02x}"));
    }
    text
}

/// SHA-256 (hex) of a record held in memory: of its interval and its samples, each as the
/// little-endian bytes of its float.
pub(super) fn record_digest(record: &Record) -> String {
    use sha2::{Digest as _, Sha256};
    let mut hasher = Sha256::new();
    hasher.update(record.dt.to_le_bytes());
    for v in &record.values {
        hasher.update(v.to_le_bytes());
    }
    hex(&hasher.finalize())
}

/// The bytes of a record file, read as the record reader reads it (a regular file of bounded
/// size), for its digest.
pub(super) fn read_record_bytes(path: &Path) -> std::io::Result<Vec<u8>> {
    use std::io::Read as _;
    let file = std::fs::File::open(path)?;
    if !file.metadata()?.is_file() {
        return Err(std::io::Error::other("not a regular file"));
    }
    let limit = crate::floor::record::MAX_RECORD_BYTES + 1;
    let mut bytes = Vec::new();
    file.take(limit).read_to_end(&mut bytes)?;
    Ok(bytes)
}
