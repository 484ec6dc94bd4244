//! The formats of record files flexrock reads, by name or by a file's extension, and the reader
//! of each.

use std::path::Path;

use super::text::strip_byte_order_mark;

/// The file layouts [`read_record`](super::read_record) understands.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum RecordFormat {
    /// PEER Strong Motion Database "AT2" text file.
    PeerAt2,
    /// Comma-separated values: `t, acc` or `acc`.
    Csv,
    /// Whitespace-separated columns: `t acc` or `acc`.
    Text,
    /// COSMOS Strong Motion Data Format, V1 or V2 (one channel).
    Cosmos,
    /// ESM (Engineering Strong Motion database) or ITACA ASCII: `KEY: VALUE` lines, then values.
    Esm,
}

impl RecordFormat {
    /// Every format, in the order of [`RecordFormat::NAMES`].
    pub const ALL: [RecordFormat; 5] = [
        RecordFormat::PeerAt2,
        RecordFormat::Csv,
        RecordFormat::Text,
        RecordFormat::Cosmos,
        RecordFormat::Esm,
    ];

    /// The names of the formats as a model file or a flag gives them, for messages.
    pub const NAMES: &'static str = "\"peer-at2\", \"csv\", \"text\", \"cosmos\" or \"esm\"";

    /// The format's name in a model file, a flag and a record's metadata.
    pub fn name(self) -> &'static str {
        match self {
            RecordFormat::PeerAt2 => "peer-at2",
            RecordFormat::Csv => "csv",
            RecordFormat::Text => "text",
            RecordFormat::Cosmos => "cosmos",
            RecordFormat::Esm => "esm",
        }
    }

    /// The format named `name` by a model file key or flag `key`.
    pub fn from_name(
        key: &str,
        name: &str,
    ) -> Result<Self, crate::base::invalid::InvalidParameter> {
        Self::ALL
            .into_iter()
            .find(|f| f.name() == name)
            .ok_or_else(|| {
                crate::base::invalid::InvalidParameter::new(
                    key,
                    format!("\"{name}\""),
                    &format!("must be {}", Self::NAMES),
                )
            })
    }

    /// The format implied by a file's extension, any letter case: `.AT2` (PEER; also its
    /// velocity and displacement files `.VT2` and `.DT2`, which the reader refuses by what their
    /// header says they hold), `.csv`, `.txt` and `.dat` (text), `.V1`, `.V2`, `.V1c`, `.V2c`
    /// (COSMOS), `.ASC` (ESM).
    pub fn from_extension(path: &Path) -> Option<Self> {
        let extension = path.extension()?.to_str()?.to_ascii_lowercase();
        Some(match extension.as_str() {
            "at2" | "vt2" | "dt2" => Self::PeerAt2,
            "csv" => Self::Csv,
            "txt" | "dat" => Self::Text,
            "v1" | "v2" | "v1c" | "v2c" => Self::Cosmos,
            "asc" => Self::Esm,
            _ => return None,
        })
    }

    /// The format a file's first line shows: COSMOS files name their layout there
    /// (`Corrected acceleration    (Format v01.20 with 13 text lines)`), ESM and ITACA files
    /// start with `EVENT_NAME:`.
    pub fn from_content(text: &str) -> Option<Self> {
        let first = strip_byte_order_mark(text).lines().next()?;
        if first.starts_with("EVENT_NAME:") {
            Some(Self::Esm)
        } else if first.to_ascii_lowercase().contains("(format v") {
            Some(Self::Cosmos)
        } else {
            None
        }
    }

    /// The format of the file `path` of text `text`: its extension's for `.AT2`, `.csv`, COSMOS
    /// and ESM extensions; else the one its first line shows; else text for `.txt` and `.dat`.
    pub fn detect(path: &Path, text: &str) -> Option<Self> {
        match Self::from_extension(path) {
            Some(Self::Text) | None => Self::from_content(text).or(Self::from_extension(path)),
            known => known,
        }
    }
}
