//! A CSV table built in memory, and CSV rows written as text by the csv crate's rules.

/// A CSV table built in memory, so that nothing reaches the disk before it is complete.
pub struct Table {
    writer: csv::Writer<Vec<u8>>,
}

impl Table {
    /// A table whose header row is `columns`.
    pub fn new(columns: &[&str]) -> Self {
        let mut writer = csv::Writer::from_writer(Vec::new());
        // Writing to memory cannot fail.
        let _ = writer.write_record(columns);
        Table { writer }
    }

    /// A table without a header row (a part of a longer table).
    pub fn without_header() -> Self {
        Table {
            writer: csv::Writer::from_writer(Vec::new()),
        }
    }

    /// Appends a row of already formatted fields.
    pub fn row<I, S>(&mut self, fields: I)
    where
        I: IntoIterator<Item = S>,
        S: AsRef<[u8]>,
    {
        let _ = self.writer.write_record(fields);
    }

    /// The CSV text of the table.
    pub fn into_bytes(self) -> Vec<u8> {
        self.writer.into_inner().unwrap_or_default()
    }
}

/// Appends one row of `fields` to `out` as [`Table::row`] writes it (the `csv` crate's rules):
/// a field holding a comma, a quote or a line break is put in quotes, its quotes doubled; the
/// row ends with a newline (a row of one empty field aside, which the crate writes as `""`).
/// Without the crate's machinery: a sweep writes a row per point.
pub fn push_row<'a>(out: &mut Vec<u8>, fields: impl IntoIterator<Item = &'a str>) {
    for (i, field) in fields.into_iter().enumerate() {
        if i > 0 {
            out.push(b',');
        }
        let bytes = field.as_bytes();
        if bytes
            .iter()
            .any(|b| matches!(b, b',' | b'"' | b'\n' | b'\r'))
        {
            out.push(b'"');
            for &b in bytes {
                if b == b'"' {
                    out.push(b'"');
                }
                out.push(b);
            }
            out.push(b'"');
        } else {
            out.extend_from_slice(bytes);
        }
    }
    out.push(b'\n');
}

#[cfg(test)]
mod tests {
    use super::*;

    /// push_row writes what the csv crate writes: plain fields, empty ones, and fields with
    /// commas, quotes, line breaks and carriage returns anywhere in them.
    #[test]
    fn push_row_writes_what_the_csv_crate_writes() {
        let rows: [&[&str]; 5] = [
            &["0", "0.2", "ok", "", "false", "1.5e-7"],
            &["", "", ""],
            &["a,b", "say \"no\"", "\"", "two\nlines", "cr\r", ","],
            &["x", "ends with a quote\"", "\"starts", "é, ü", "tab\there"],
            &[
                "longer than eight bytes, with a comma at the end,",
                "12345678\n",
            ],
        ];
        // Flexible: the rows have different lengths.
        let mut expected = csv::WriterBuilder::new()
            .flexible(true)
            .from_writer(Vec::new());
        let mut written = Vec::new();
        for row in rows {
            expected.write_record(row).unwrap();
            push_row(&mut written, row.iter().copied());
        }
        assert_eq!(
            String::from_utf8(written).unwrap(),
            String::from_utf8(expected.into_inner().unwrap()).unwrap()
        );
    }
}
