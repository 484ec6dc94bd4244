//! The record readers on the shipped files and on broken ones.

use std::fmt;

use super::read::decode_utf8;
use super::*;
use proptest::prelude::*;
use std::path::Path;

const EL_CENTRO: &str = concat!(
    env!("CARGO_MANIFEST_DIR"),
    "/../validation/records/elCentro.AT2"
);
const ANLA196: &str = concat!(
    env!("CARGO_MANIFEST_DIR"),
    "/../validation/records/ANLA196.AT2"
);

fn read_text(path: &str) -> String {
    std::fs::read_to_string(path).unwrap_or_else(|error| panic!("cannot read {path}: {error}"))
}

fn el_centro_text() -> String {
    read_text(EL_CENTRO)
}

fn parse_el_centro(text: &str) -> Result<Record, RecordError> {
    parse_at2(text, "elCentro.AT2")
}

/// The Display message of an error that must occur.
fn error_message<T: fmt::Debug>(result: Result<T, RecordError>) -> String {
    match result {
        Ok(value) => panic!("expected an error, got {value:?}"),
        Err(error) => error.to_string(),
    }
}

fn assert_close(actual: f64, expected: f64) {
    assert!(
        (actual - expected).abs() <= 1e-12 * expected.abs().max(1.0),
        "expected {expected}, got {actual}"
    );
}

/// A small valid AT2 text mixing the 5E15.7 and 8F10.5 layouts (6 values).
const SMALL_AT2: &str = "PEER STRONG MOTION DATABASE RECORD.\n\
    SOME EVENT, SOME STATION, 090\n\
    ACCELERATION TIME HISTORY IN UNITS OF G\n\
    NPTS=   6, DT= .01000 SEC\n\
    \x20  .1181069E-02  -.1366453E-02   .9006674E-03\n\
    \x20 -0.00128   0.00368   0.00864\n";

// --- the validation records ---------------------------------------------------------------

#[test]
fn el_centro_count_dt_title_first_and_last_values() {
    let record = parse_el_centro(&el_centro_text()).expect("elCentro.AT2 parses");
    assert_eq!(record.values.len(), 1559);
    assert_close(record.dt, 0.02);
    assert_eq!(record.title.len(), 3);
    assert_eq!(
        record.title[0],
        "Data for El Centro 1940 North South Component (Peknold Version)"
    );
    assert_eq!(record.title[2], "The units are (g)");
    // From the file text: line 5 starts "   0.00630", the file ends "   0.00000".
    assert_close(record.values[0], 0.00630);
    assert_close(record.values[1], 0.00364);
    assert_close(record.values[1558], 0.00000);
    assert_close(record.values[1557], -0.00006);
    assert_close(record.duration(), 1558.0 * 0.02);
}

#[test]
fn el_centro_peak_value_and_time() {
    // Computed independently with awk over the values after line 4: the largest magnitude
    // is -0.31882, the 102nd value (index 101, line 17), so t = 101 * 0.02 s = 2.02 s.
    let record = parse_el_centro(&el_centro_text()).expect("elCentro.AT2 parses");
    let (peak, time) = record.peak();
    assert_close(peak, -0.31882);
    assert_close(time, 2.02);
}

#[test]
fn anla196_count_dt_title_first_and_last_values() {
    let record = parse_at2(&read_text(ANLA196), "ANLA196.AT2").expect("ANLA196.AT2 parses");
    assert_eq!(record.values.len(), 1451);
    assert_close(record.dt, 0.02);
    assert_eq!(
        record.title[1],
        "BORAH PEAK EQ, 10/28/83, 14:06, ANL-767 REACTOR PLANT (BASEMENT), 196"
    );
    // From the file text: line 5 starts "  -.1941782E-03", the last line is "  -.8501408E-05".
    assert_close(record.values[0], -0.1941782e-3);
    assert_close(record.values[1], -0.9395342e-3);
    assert_close(record.values[1450], -0.8501408e-5);
    assert_close(record.values[1449], -0.6450653e-5);
}

#[test]
fn read_record_detects_at2_by_extension_and_names_the_path() {
    let record = read_record(Path::new(EL_CENTRO), None, None).expect("elCentro.AT2 reads");
    assert_eq!(record.source, EL_CENTRO);
    let parsed = parse_el_centro(&el_centro_text()).expect("elCentro.AT2 parses");
    assert_eq!(record.values, parsed.values);
    assert_eq!(record.title, parsed.title);

    let with_dt = read_record(Path::new(ANLA196), Some(RecordFormat::PeerAt2), Some(0.02));
    assert_eq!(with_dt.expect("ANLA196.AT2 reads").values.len(), 1451);
    let message = error_message(read_record(Path::new(ANLA196), None, Some(0.01)));
    assert!(
        message.contains("dt given as 0.01 but the file says 0.02"),
        "{message}"
    );
}

#[test]
fn crlf_and_trailing_blank_lines_parse_identically() {
    let text = el_centro_text();
    let original = parse_el_centro(&text).expect("elCentro.AT2 parses");
    let crlf = text.replace('\n', "\r\n");
    assert!(crlf.contains("\r\n"));
    assert_eq!(parse_el_centro(&crlf).expect("CRLF parses"), original);
    let padded = format!("{crlf}\r\n\r\n   \r\n\n");
    assert_eq!(parse_el_centro(&padded).expect("padded parses"), original);
    let with_bom = format!("\u{feff}{text}");
    assert_eq!(parse_el_centro(&with_bom).expect("BOM parses"), original);
}

// --- AT2 errors ---------------------------------------------------------------------------

#[test]
fn dropped_last_value_fails_with_the_count_message() {
    let text = el_centro_text();
    let truncated = text
        .trim_end()
        .strip_suffix("0.00000")
        .expect("elCentro.AT2 ends with 0.00000");
    let message = error_message(parse_el_centro(truncated));
    assert_eq!(
        message,
        "elCentro.AT2: header says NPTS=1559 but the file has 1558 values (truncated file?)"
    );
}

#[test]
fn an_extra_value_fails_with_the_count_message() {
    let text = format!("{}   0.00001\n", el_centro_text());
    let message = error_message(parse_el_centro(&text));
    assert_eq!(
        message,
        "elCentro.AT2: header says NPTS=1559 but the file has 1560 values"
    );
}

#[test]
fn zero_or_negative_header_dt_fails() {
    let text = el_centro_text();
    let zero = text.replacen("DT= .02000 SEC", "DT= 0 SEC", 1);
    assert_eq!(
        error_message(parse_el_centro(&zero)),
        "elCentro.AT2 line 4: dt must be > 0, found 0"
    );
    let negative = text.replacen("DT= .02000 SEC", "DT= -.02000 SEC", 1);
    assert_eq!(
        error_message(parse_el_centro(&negative)),
        "elCentro.AT2 line 4: dt must be > 0, found -0.02"
    );
    let huge = text.replacen("DT= .02000 SEC", "DT= 1e999 SEC", 1);
    assert_eq!(
        error_message(parse_el_centro(&huge)),
        "elCentro.AT2 line 4: dt must be a finite number, found inf"
    );
}

#[test]
fn malformed_header_line_fails_quoting_it() {
    let text = el_centro_text().replacen("NPTS=  1559, DT= .02000 SEC", "NPTS 1559 DT .02", 1);
    assert_eq!(
        error_message(parse_el_centro(&text)),
        "elCentro.AT2 line 4: expected \"NPTS=<count>, DT=<seconds>\" in the 4th header \
         line, found \"NPTS 1559 DT .02\""
    );
    let no_count = el_centro_text().replacen("NPTS=  1559,", "NPTS=  0,", 1);
    assert_eq!(
        error_message(parse_el_centro(&no_count)),
        "elCentro.AT2 line 4: NPTS must be > 0, found 0"
    );
}

#[test]
fn non_number_token_fails_naming_the_line() {
    // -0.31882 is on line 17 of elCentro.AT2.
    let text = el_centro_text().replacen("-0.31882", " 0.0O123", 1);
    assert_eq!(
        error_message(parse_el_centro(&text)),
        "elCentro.AT2 line 17: value \"0.0O123\" is not a number"
    );
}

#[test]
fn nan_and_infinite_values_fail_naming_the_line() {
    for token in ["     NaN", "     nan", "     inf", "-Infinity", "  1e999 "] {
        let text = el_centro_text().replacen("-0.31882", token, 1);
        let message = error_message(parse_el_centro(&text));
        assert!(
            message.starts_with("elCentro.AT2 line 17: value \"")
                && message.ends_with("\" is NaN or infinite"),
            "{message}"
        );
    }
}

#[test]
fn empty_file_fails() {
    for text in ["", "   ", "\n\n", "\r\n  \r\n"] {
        assert_eq!(
            error_message(parse_el_centro(text)),
            "elCentro.AT2: empty file"
        );
    }
}

#[test]
fn header_only_fails() {
    let text = el_centro_text();
    let header: String = text
        .lines()
        .take(4)
        .map(|line| format!("{line}\n"))
        .collect();
    assert_eq!(
        error_message(parse_el_centro(&header)),
        "elCentro.AT2: no values after the header (header says NPTS=1559)"
    );
}

#[test]
fn fewer_than_four_header_lines_fails() {
    let text = "Data for El Centro\nThe units are (g)\n";
    assert_eq!(
        error_message(parse_el_centro(text)),
        "elCentro.AT2: fewer than 4 header lines (the file has 2 lines)"
    );
}

#[test]
fn header_variants_are_accepted() {
    let header_lines = [
        "NPTS=  6, DT= .01000 SEC",
        "NPTS=   6, dt=  .01000",
        "NPTS=   6, dt=   .0100 SEC",
        "npts=6 dt=0.01 s",
        "NPTS=6,DT=1.0E-02 seconds",
        "  6  0.01  NPTS, DT",
        "6 .01000 npts,dt",
        "NPTS=   6, DT=   .0100 SEC,",
    ];
    for header_line in header_lines {
        let text = SMALL_AT2.replacen("NPTS=   6, DT= .01000 SEC", header_line, 1);
        let record = parse_at2(&text, "small.AT2")
            .unwrap_or_else(|error| panic!("{header_line:?} rejected: {error}"));
        assert_eq!(record.values.len(), 6);
        assert_close(record.dt, 0.01);
    }
}

#[test]
fn header_variants_are_rejected() {
    let header_lines = [
        "NPTS=6, DT=0.01 MIN",
        "NPTS=6.0, DT=0.01",
        "NPTS=, DT=0.01",
        "NPTS=6",
        "DT=0.01, NPTS=6",
        "NPTS=6, DT=0.01 SEC extra",
        "6 0.01",
        "6 0.01 NPTS, DT, G",
        "   .1181069E-02  -.1366453E-02",
    ];
    for header_line in header_lines {
        let text = SMALL_AT2.replacen("NPTS=   6, DT= .01000 SEC", header_line, 1);
        let message = error_message(parse_at2(&text, "small.AT2"));
        assert!(
            message.starts_with("small.AT2 line 4: expected \"NPTS=<count>, DT=<seconds>\""),
            "{header_line:?}: {message}"
        );
    }
}

#[test]
fn fixed_width_fields_that_touch_are_read() {
    let f10 = SMALL_AT2.replacen(
        "  -0.00128   0.00368   0.00864",
        "-100.12345-200.12345   0.00864",
        1,
    );
    let record = parse_at2(&f10, "f10.AT2").expect("touching F10.5 fields parse");
    assert_eq!(&record.values[3..], &[-100.12345, -200.12345, 0.00864]);

    let e15 = SMALL_AT2.replacen(
        "   .1181069E-02  -.1366453E-02   .9006674E-03",
        "-1.1181069E-002-2.1366453E-002   .9006674E-03",
        1,
    );
    let record = parse_at2(&e15, "e15.AT2").expect("touching E15.7 fields parse");
    assert_eq!(
        &record.values[..3],
        &[-1.1181069e-2, -2.1366453e-2, 0.9006674e-3]
    );

    // Touching fields that are not on a 10- or 15-character grid are an error.
    let misaligned = SMALL_AT2.replacen("  -0.00128   0.00368", " -0.00128-0.00368  ", 1);
    assert_eq!(
        error_message(parse_at2(&misaligned, "bad.AT2")),
        "bad.AT2 line 6: value \"-0.00128-0.00368\" is not a number"
    );
}

#[test]
fn touching_fifteen_character_fields_on_a_line_of_a_multiple_of_ten_are_read_at_15() {
    // Two F15.12 fields that touch, 30 characters: read at 10 they would be three numbers
    // ("-0.0001234", "5678900.00", "0987654321"); the file is laid out in 15-character
    // fields (its other line has 45 characters for 3 values), and NPTS = 5 says so too.
    let text = "PEER\nEVENT\nUNITS OF G\nNPTS=   5, DT= .01000 SEC\n\
        \x20 0.000111111111 -0.000222222222 -0.000333333333\n\
        -0.0001234567890.000987654321\n";
    // (the second field is 15 characters: "0.000987654321" with a trailing "0")
    let text = text.replace("0.000987654321\n", "0.0009876543210\n");
    let record = parse_at2(&text, "f15.AT2").expect("touching F15 fields parse");
    assert_eq!(
        record.values,
        [
            0.000111111111,
            -0.000222222222,
            -0.000333333333,
            -0.000123456789,
            0.000987654321
        ]
    );
    // A file of touching lines only: NPTS decides between 2 values a line and 3.
    let only = "PEER\nEVENT\nUNITS OF G\nNPTS=   4, DT= .01000 SEC\n\
        -0.0001234567890.0009876543210\n\
        -0.0001234567890.0009876543210\n";
    let record = parse_at2(only, "only.AT2").expect("touching F15 fields parse");
    assert_eq!(
        record.values,
        [
            -0.000123456789,
            0.000987654321,
            -0.000123456789,
            0.000987654321
        ]
    );
}

#[test]
fn a_record_of_one_sample_is_refused_naming_the_file() {
    let one = "PEER\nEVENT\nUNITS OF G\nNPTS=   1, DT= .01000 SEC\n   0.00128\n";
    assert_eq!(
        error_message(parse_at2(one, "one.AT2")),
        "one.AT2: the record has 1 sample; a record needs at least 2 samples (one interval \
         of dt) to define the floor acceleration between them"
    );
    assert!(error_message(parse_csv("0.1\n", "one.csv", Some(0.01)))
        .starts_with("one.csv: the record has 1 sample; a record needs at least 2 samples"));
}

// --- CSV ----------------------------------------------------------------------------------

#[test]
fn csv_with_time_column_derives_dt() {
    let text = "# a comment\nt, acc # names\n0.00, 0.1\n0.01, -0.3\n\n0.02, 0.2\n0.03,0.0\n";
    let record = parse_csv(text, "two.csv", None).expect("two-column CSV parses");
    assert_close(record.dt, 0.01);
    assert_eq!(record.values, vec![0.1, -0.3, 0.2, 0.0]);
    assert_eq!(record.title, vec!["t, acc".to_string()]);
    let (peak, time) = record.peak();
    assert_close(peak, -0.3);
    assert_close(time, 0.01);

    let crlf = text.replace('\n', "\r\n");
    assert_eq!(
        parse_csv(&crlf, "two.csv", Some(0.01)).expect("CRLF parses"),
        record
    );
    assert_eq!(
        error_message(parse_csv(text, "two.csv", Some(0.02))),
        "two.csv: dt given as 0.02 but the file says 0.01"
    );
}

#[test]
fn csv_with_one_column_needs_dt() {
    let text = "acc\n0.1\n-0.3\n0.2\n";
    let record = parse_csv(text, "one.csv", Some(0.005)).expect("one-column CSV parses");
    assert_close(record.dt, 0.005);
    assert_eq!(record.values, vec![0.1, -0.3, 0.2]);
    let no_header = parse_csv("0.1\n-0.3\n0.2", "one.csv", Some(0.005)).expect("parses");
    assert_eq!(no_header.values, record.values);

    assert_eq!(
        error_message(parse_csv(text, "one.csv", None)),
        "one.csv: a one-column CSV file needs dt from the caller, none was given"
    );
    assert_eq!(
        error_message(parse_csv(text, "one.csv", Some(-0.02))),
        "one.csv: dt must be > 0, found -0.02"
    );
    assert_eq!(
        error_message(parse_csv(text, "one.csv", Some(f64::NAN))),
        "one.csv: dt must be a finite number, found NaN"
    );
}

#[test]
fn csv_with_non_uniform_time_column_is_rejected() {
    let text = "t,acc\n0.0,0.1\n0.01,0.2\n0.021,0.3\n0.03,0.4\n";
    let message = error_message(parse_csv(text, "gap.csv", None));
    assert!(
        message.starts_with("gap.csv line 4: time step 0.011")
            && message.contains("(the time column must be uniformly spaced)"),
        "{message}"
    );
    let late_start = "0.01,0.1\n0.02,0.2\n0.03,0.3\n";
    assert_eq!(
        error_message(parse_csv(late_start, "late.csv", None)),
        "late.csv line 1: the time column must start at 0, found 0.01"
    );
    assert_eq!(
        error_message(parse_csv("0.0,0.1\n", "single.csv", None)),
        "single.csv: a time column needs at least 2 rows to give dt, found 1"
    );
    assert_eq!(
        error_message(parse_csv("0.0,0.1\n-0.01,0.2\n", "back.csv", None)),
        "back.csv: dt must be > 0, found -0.01"
    );
}

#[test]
fn csv_errors_name_the_line() {
    assert_eq!(
        error_message(parse_csv("t,acc\n0,0.1\n0.01,x\n", "bad.csv", None)),
        "bad.csv line 3: value \"x\" is not a number"
    );
    assert_eq!(
        error_message(parse_csv("0,0.1\n0.01,NaN\n", "nan.csv", None)),
        "nan.csv line 2: value \"NaN\" is NaN or infinite"
    );
    assert_eq!(
        error_message(parse_csv("0,0.1\n0.01\n", "ragged.csv", None)),
        "ragged.csv line 2: expected 2 fields like the first row, found 1"
    );
    assert_eq!(
        error_message(parse_csv("t,acc,vel\n0,0.1,0\n", "three.csv", None)),
        "three.csv line 1: expected 1 column (acc) or 2 columns (t, acc), found 3"
    );
    assert_eq!(
        error_message(parse_csv("# only a comment\nt,acc\n", "names.csv", None)),
        "names.csv: no data rows"
    );
    assert_eq!(
        error_message(parse_csv("", "empty.csv", None)),
        "empty.csv: empty file"
    );
}

// --- files, bytes and the Record methods --------------------------------------------------

#[test]
fn invalid_utf8_is_an_error_naming_the_line() {
    let bytes = b"line one\nline two\nbad \xff byte\n".to_vec();
    assert_eq!(
        error_message(decode_utf8(bytes, "bytes.AT2")),
        "bytes.AT2 line 3: the file is not UTF-8 text (invalid byte at offset 22)"
    );
}

#[test]
fn read_record_reports_missing_files_and_unknown_extensions() {
    let missing = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../validation/records/missing.AT2"
    );
    let message = error_message(read_record(Path::new(missing), None, None));
    assert!(
        message.starts_with(&format!("{missing}: cannot read the file: ")),
        "{message}"
    );
    // A file whose extension and first line name no format (this one starts "# Validation").
    let provenance = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../validation/records/PROVENANCE.md"
    );
    let message = error_message(read_record(Path::new(provenance), None, None));
    assert!(
        message.starts_with(&format!(
            "{provenance}: cannot tell the record format from the extension"
        )) && message.contains("found \"md\""),
        "{message}"
    );
    for (name, format) in [
        ("a.txt", RecordFormat::Text),
        ("a.DAT", RecordFormat::Text),
        ("a.V2", RecordFormat::Cosmos),
        ("a.v1c", RecordFormat::Cosmos),
        ("IT.AQG..HNE.D.20090330.215717.X.ACC.ASC", RecordFormat::Esm),
    ] {
        assert_eq!(RecordFormat::from_extension(Path::new(name)), Some(format));
    }
    // The first line tells a COSMOS or ESM file whatever its name, but for the AT2 and CSV
    // extensions, which decide.
    let cosmos = "Corrected acceleration    (Format v01.20 with 13 text lines)\n";
    let esm = "EVENT_NAME: L'Aquila\n";
    assert_eq!(
        RecordFormat::detect(Path::new("a.txt"), cosmos),
        Some(RecordFormat::Cosmos)
    );
    assert_eq!(
        RecordFormat::detect(Path::new("a"), esm),
        Some(RecordFormat::Esm)
    );
    assert_eq!(
        RecordFormat::detect(Path::new("a.AT2"), esm),
        Some(RecordFormat::PeerAt2)
    );
    assert_eq!(
        RecordFormat::detect(Path::new("a.txt"), "0 1\n"),
        Some(RecordFormat::Text)
    );
    assert_eq!(RecordFormat::detect(Path::new("a"), "0 1\n"), None);
    assert_eq!(
        RecordFormat::from_extension(Path::new("a/b/X.at2")),
        Some(RecordFormat::PeerAt2)
    );
    assert_eq!(
        RecordFormat::from_extension(Path::new("X.CSV")),
        Some(RecordFormat::Csv)
    );
    assert_eq!(RecordFormat::from_extension(Path::new("X")), None);
}

#[test]
fn peak_and_duration_of_small_records() {
    let mut record = Record {
        source: "r".to_string(),
        title: Vec::new(),
        dt: 0.5,
        values: vec![0.1, -0.4, 0.4, 0.2],
        meta: RecordMeta::default(),
    };
    assert_eq!(record.peak(), (-0.4, 0.5));
    assert_eq!(record.duration(), 1.5);
    record.values.clear();
    assert_eq!(record.peak(), (0.0, 0.0));
    assert_eq!(record.duration(), 0.0);
}

// --- the test fixtures: every format and unit ---------------------------------------------

/// The samples every fixture under tests/data/records holds, in its own unit (in g, or times
/// 100 in cm/s^2): exact binary fractions, written and read without rounding.
const FIXTURE_VALUES: [f64; 6] = [0.0, 0.125, -0.25, 0.5, -0.375, 0.0625];

fn fixture_path(name: &str) -> String {
    format!(
        "{}/../tests/data/records/{name}",
        env!("CARGO_MANIFEST_DIR")
    )
}

fn fixture(name: &str) -> String {
    read_text(&fixture_path(name))
}

fn read_fixture(name: &str) -> Result<Record, RecordError> {
    read_record(Path::new(&fixture_path(name)), None, None)
}

fn scaled(factor: f64) -> Vec<f64> {
    FIXTURE_VALUES.iter().map(|v| v * factor).collect()
}

#[test]
fn at2_files_are_read_in_the_unit_their_header_says() {
    for (name, unit, factor) in [
        ("nga-g.AT2", "g", 1.0),
        ("nga-cmss.AT2", "cm/s2", 100.0),
        ("nga-mss.AT2", "m/s2", 1.0),
    ] {
        let record = read_fixture(name).unwrap();
        assert_eq!(record.values, scaled(factor), "{name}");
        assert_eq!(record.meta.units, Some(unit), "{name}");
        assert_eq!(record.meta.format, "peer-at2");
        // The NGA-West2 line 2: event, date, station, component.
        assert_eq!(record.meta.event.as_deref(), Some("Imperial Valley-02"));
        assert_eq!(record.meta.date.as_deref(), Some("1940-05-19"));
        assert_eq!(record.meta.station.as_deref(), Some("El Centro Array #9"));
        assert_eq!(record.meta.component.as_deref(), Some("180"));
        assert_eq!(
            record.meta.label("x"),
            "Imperial Valley-02, El Centro Array #9, 180"
        );
        // The file's unit is the one used; another given is refused, naming both.
        assert_eq!(resolve_units(&record, "u", None).unwrap().0, unit);
        assert_eq!(resolve_units(&record, "u", Some(unit)).unwrap().0, unit);
        let other = if unit == "g" { "m/s2" } else { "g" };
        let e = resolve_units(&record, "excitation.units", Some(other))
            .unwrap_err()
            .to_string();
        assert!(
            e.starts_with(&format!(
                "excitation.units = \"{other}\": contradicts the record file"
            )) && e.contains(&format!("says its values are in {unit}"))
                && e.contains("line 3"),
            "{e}"
        );
    }
    let factor = |name: &str| {
        let record = read_fixture(name).unwrap();
        resolve_units(&record, "u", None).unwrap().1
    };
    assert_eq!(factor("nga-g.AT2"), 9.80665);
    assert_eq!(factor("nga-cmss.AT2"), 0.01);
    assert_eq!(factor("nga-mss.AT2"), 1.0);
}

#[test]
fn velocity_and_displacement_files_are_refused_by_name() {
    for (name, holds) in [
        ("nga-velocity.VT2", "velocity"),
        ("nga-displacement.DT2", "displacement"),
        ("cosmos-velocity.V2", "velocity"),
        ("esm-velocity.ASC", "velocity"),
    ] {
        let e = error_message(read_fixture(name));
        assert!(
            e.contains(&format!("the file holds a {holds} time series"))
                && e.contains("flexrock reads ground accelerations only"),
            "{name}: {e}"
        );
    }
    let e = error_message(read_fixture("nga-velocity.VT2"));
    assert!(
        e.ends_with(
            "nga-velocity.VT2 line 3: the file holds a velocity time series (\"VELOCITY \
             TIME SERIES IN UNITS OF CM/S\"), not an acceleration; flexrock reads ground \
             accelerations only and does not differentiate: give the acceleration record of the \
             same motion"
        ),
        "{e}"
    );
    // A velocity unit in an acceleration's header is refused the same way.
    let text = fixture("nga-g.AT2").replace("UNITS OF G", "UNITS OF CM/SEC");
    let e = error_message(parse_at2(&text, "v.AT2"));
    assert!(
        e.starts_with("v.AT2 line 3: the file holds a velocity"),
        "{e}"
    );
}

#[test]
fn a_header_silent_on_units_leaves_them_to_the_user_and_an_unknown_unit_is_refused() {
    let record = read_fixture("no-units.AT2").unwrap();
    assert_eq!(record.meta.units, None);
    assert_eq!(record.meta.event, None);
    let e = resolve_units(&record, "excitation.units", None)
        .unwrap_err()
        .to_string();
    assert!(
        e.starts_with("excitation.units = (missing): required: the record file")
            && e.contains("does not say the unit of its values"),
        "{e}"
    );
    assert_eq!(
        resolve_units(&record, "excitation.units", Some("cm/s2")).unwrap(),
        ("cm/s2", 0.01)
    );
    let e = error_message(read_fixture("furlongs.AT2"));
    assert!(
        e.ends_with(
            "furlongs.AT2 line 3: unknown unit \"FURLONG/FORTNIGHT\" (the units of \
             acceleration read: g, cm/s2 (also written cm/sec/sec, cm/s^2, gal), m/s2)"
        ),
        "{e}"
    );
}

#[test]
fn the_shipped_at2_files_give_their_event_station_and_component() {
    let meta = |name: &str| {
        let path = format!(
            "{}/../validation/records/{name}",
            env!("CARGO_MANIFEST_DIR")
        );
        read_record(Path::new(&path), None, None).unwrap().meta
    };
    let m = meta("ANLA196.AT2");
    assert_eq!(m.units, Some("g"));
    assert_eq!(
        (m.event.as_deref(), m.date.as_deref()),
        (Some("BORAH PEAK EQ"), Some("10/28/83"))
    );
    assert_eq!(
        m.station.as_deref(),
        Some("ANL-767 REACTOR PLANT (BASEMENT)")
    );
    assert_eq!(m.component.as_deref(), Some("196"));
    let m = meta("A-ELC180.AT2");
    assert_eq!(m.label("x"), "BORREGO MOUNTAIN, EL CENTRO ARRAY #9, 180");
    assert_eq!(meta("HEN-E.AT2").label("x"), "CHI-CHI, HEN, E");
    assert_eq!(meta("PBFEAS.AT2").label("x"), "BORAH PEAK, PBF, EAST");
    // El Centro's line 2 is free text: no event is made up; its line 3 says "(g)".
    let m = meta("elCentro.AT2");
    assert_eq!(
        (m.units, m.label("elCentro.AT2").as_str()),
        (Some("g"), "elCentro.AT2")
    );
}

#[test]
fn cosmos_files_are_read_with_their_header() {
    let record = read_fixture("cosmos-cmss.V2").unwrap();
    assert_eq!(record.values, scaled(100.0));
    assert_eq!(record.dt, 0.01);
    let m = &record.meta;
    assert_eq!((m.format, m.units), ("cosmos", Some("cm/s2")));
    assert_eq!(m.event.as_deref(), Some("Synthetic Test Earthquake"));
    assert_eq!(m.date.as_deref(), Some("1999-09-20"));
    assert_eq!(m.station.as_deref(), Some("TW-TST"));
    assert_eq!(m.component.as_deref(), Some("090"));
    assert_eq!((m.magnitude, m.distance_km), (Some(7.6), Some(12.5)));
    let record = read_fixture("cosmos-g.V1").unwrap();
    assert_eq!(record.values, scaled(1.0));
    assert_eq!(record.meta.units, Some("g"));
}

#[test]
fn cosmos_headers_that_break_a_rule_are_refused_naming_the_line() {
    let text = fixture("cosmos-cmss.V2");
    let refused = |from: &str, to: &str| {
        assert!(text.contains(from), "{from}");
        error_message(parse_cosmos(&text.replacen(from, to, 1), "c.V2"))
    };
    // The sampling interval unknown (real 62 is the 2nd value of the header's 13th line).
    let e = refused(
        "    -999.000000      10.000000       0.060000",
        "    -999.000000    -999.000000       0.060000",
    );
    assert!(
        e.contains("no sampling interval (real value 62, ms)"),
        "{e}"
    );
    // The length in the header against NPTS x dt.
    let e = refused(
        "      10.000000       0.060000",
        "      10.000000       0.090000",
    );
    assert!(
        e.contains("the record's length in the real header (value 63) is 0.09 s"),
        "{e}"
    );
    // NPTS against the values.
    let e = refused("       6 acceleration pts", "       7 acceleration pts");
    assert!(
        e.contains(
            "c.V2 line 52: the acceleration data ends here with 6 values, fewer than \
             the 7 its count line gives"
        ),
        "{e}"
    );
    let e = refused("       6 acceleration pts", "       5 acceleration pts");
    assert!(
        e.contains("c.V2 line 51: more values than the NPTS = 5 the data line (line 49) gives"),
        "{e}"
    );
    // The unit's code against its word, and against integer 3.
    let e = refused("units=cm/sec2(04)", "units=cm/sec2(02)");
    assert!(
        e.contains("the data line's unit code, 2, is not the unit \"cm/sec2\""),
        "{e}"
    );
    let e = refused("       2       1       4", "       2       1       2");
    assert!(
        e.contains("integer header value 3 (the unit's code), 2"),
        "{e}"
    );
    // The data's quantity in integer 2.
    let e = refused("       2       1       4", "       2       2       4");
    assert!(
        e.contains("the file holds a velocity time series (\"integer header value 2 = 2\")"),
        "{e}"
    );
    // Counts of header lines and values.
    let e = refused("follow on  10 lines", "follow on  11 lines");
    assert!(
        e.contains(
            "c.V2 line 24: the integer header takes 10 lines, not the 11 its count line gives"
        ),
        "{e}"
    );
    let e = refused("   2 Comment line(s)", "   3 Comment line(s)");
    assert!(
        e.contains("expected a comment line starting with \"|\""),
        "{e}"
    );
    let e = refused("with 13 text lines", "with 12 text lines");
    assert!(
        e.contains("expected the integer header's count line"),
        "{e}"
    );
    let e = refused("Corrected acceleration", "Raw acceleration counts");
    assert!(
        e.contains("c.V2 line 1: the file holds \"raw acceleration counts\""),
        "{e}"
    );
    let e = refused("       6 velocity", "1.0\n       6 velocity");
    assert!(e.contains("more values than the NPTS = 6"), "{e}");
    let two = format!("{text}{text}");
    let e = error_message(parse_cosmos(&two, "c.V2"));
    assert!(e.contains("the file holds more than one channel"), "{e}");
}

#[test]
fn esm_files_are_read_with_their_header() {
    let record = read_fixture("esm-cmss.ASC").unwrap();
    assert_eq!(record.values, scaled(100.0));
    assert_eq!(record.dt, 0.01);
    let m = &record.meta;
    assert_eq!((m.format, m.units), ("esm", Some("cm/s2")));
    assert_eq!(m.event.as_deref(), Some("L'AQUILA MAINSHOCK (SYNTHETIC)"));
    assert_eq!(m.date.as_deref(), Some("2009-04-06"));
    assert_eq!(m.station.as_deref(), Some("IT.AQV"));
    assert_eq!(m.component.as_deref(), Some("HNE"));
    assert_eq!((m.magnitude, m.distance_km), (Some(6.1), Some(4.9)));
    let e = error_message(read_fixture("esm-short.ASC"));
    assert!(
        e.contains("line 26: NDATA = 7 but the file has 6 values (truncated file?)"),
        "{e}"
    );
    let text = fixture("esm-cmss.ASC");
    let e = error_message(parse_esm(&text.replace("UNITS: cm/s^2\n", ""), "e.ASC"));
    assert!(e.contains("the header has no UNITS line"), "{e}");
    let e = error_message(parse_esm(
        &text.replace("UNITS: cm/s^2", "UNITS: counts"),
        "e.ASC",
    ));
    assert!(e.contains("e.ASC line 29: unknown unit \"counts\""), "{e}");
    let e = error_message(parse_esm(
        &text.replace(
            "DATA_TYPE: ACCELERATION",
            "DATA_TYPE: ACCELERATION RESPONSE SPECTRUM",
        ),
        "e.ASC",
    ));
    assert!(
        e.contains("DATA_TYPE is \"ACCELERATION RESPONSE SPECTRUM\""),
        "{e}"
    );
    // A magnitude of the event's own key wins; an empty one is not given.
    let with_event = text.replace("MAGNITUDE_W: 6.1", "EVENT_MAGNITUDE: 6.3\nMAGNITUDE_W:");
    let m = parse_esm(&with_event, "e.ASC").unwrap().meta;
    assert_eq!(m.magnitude, Some(6.3));
}

#[test]
fn text_columns_are_read_like_csv_with_their_unit_from_the_header() {
    let record = read_fixture("text-g.txt").unwrap();
    assert_eq!(record.values, scaled(1.0));
    assert_eq!(record.dt, 0.01);
    assert_eq!((record.meta.format, record.meta.units), ("text", Some("g")));
    let one = parse_text("0.5\n-0.25\n", "one.txt", Some(0.02)).unwrap();
    assert_eq!(
        (one.values, one.dt, one.meta.units),
        (vec![0.5, -0.25], 0.02, None)
    );
}

// --- no panic, whatever the input ---------------------------------------------------------

/// One edit of a text: insert, delete or replace a character at a position.
#[derive(Debug, Clone)]
enum Edit {
    Insert(usize, char),
    Delete(usize),
    Replace(usize, char),
}

fn edit_strategy() -> impl Strategy<Value = Edit> {
    // Characters that matter to the parsers, plus any character at all.
    let interesting = prop::sample::select(vec![
        ' ', '\n', '\r', ',', '=', '#', '-', '+', '.', 'E', 'e', '0', '9', 'N', 'D', 'S', 'n',
        '\u{feff}', 'é', '\u{0}',
    ]);
    let character = prop_oneof![interesting, any::<char>()];
    prop_oneof![
        (any::<usize>(), character.clone()).prop_map(|(at, c)| Edit::Insert(at, c)),
        any::<usize>().prop_map(Edit::Delete),
        (any::<usize>(), character).prop_map(|(at, c)| Edit::Replace(at, c)),
    ]
}

fn apply_edits(text: &str, edits: &[Edit]) -> String {
    let mut chars: Vec<char> = text.chars().collect();
    for edit in edits {
        match *edit {
            Edit::Insert(at, c) => chars.insert(at % (chars.len() + 1), c),
            Edit::Delete(at) if !chars.is_empty() => {
                chars.remove(at % chars.len());
            }
            Edit::Replace(at, c) if !chars.is_empty() => {
                let index = at % chars.len();
                chars[index] = c;
            }
            _ => {}
        }
    }
    chars.into_iter().collect()
}

fn parse_everything(text: &str) {
    let _ = parse_at2(text, "fuzz.AT2");
    let _ = parse_cosmos(text, "fuzz.V2");
    let _ = parse_esm(text, "fuzz.ASC");
    let _ = parse_text(text, "fuzz.txt", Some(0.01));
    let _ = parse_csv(text, "fuzz.csv", None);
    let _ = parse_csv(text, "fuzz.csv", Some(0.01));
    let _ = parse_csv(text, "fuzz.csv", Some(-1.0));
    if let Ok(record) = parse_at2(text, "fuzz.AT2") {
        let _ = (record.peak(), record.duration());
    }
}

proptest! {
    #[test]
    fn arbitrary_strings_do_not_panic(text in any::<String>()) {
        parse_everything(&text);
    }

    #[test]
    fn arbitrary_bytes_do_not_panic(bytes in prop::collection::vec(any::<u8>(), 0..400)) {
        parse_everything(&String::from_utf8_lossy(&bytes));
        if let Ok(text) = decode_utf8(bytes, "fuzz.bin") {
            parse_everything(&text);
        }
    }

    #[test]
    fn mutated_at2_texts_do_not_panic(edits in prop::collection::vec(edit_strategy(), 1..12)) {
        let mutated = apply_edits(SMALL_AT2, &edits);
        parse_everything(&mutated);
        parse_everything(&mutated.replace('\n', "\r\n"));
    }

    #[test]
    fn mutated_cosmos_and_esm_texts_do_not_panic(
        edits in prop::collection::vec(edit_strategy(), 1..12)
    ) {
        for name in ["cosmos-cmss.V2", "esm-cmss.ASC"] {
            parse_everything(&apply_edits(&fixture(name), &edits));
        }
    }

    #[test]
    fn mutated_csv_texts_do_not_panic(edits in prop::collection::vec(edit_strategy(), 1..12)) {
        let csv = "t,acc\n0.00,0.1\n0.01,-0.3 # peak\n0.02,0.2\n";
        parse_everything(&apply_edits(csv, &edits));
    }

    #[test]
    fn numeric_fields_round_trip(values in prop::collection::vec(-1e3f64..1e3, 2..40)) {
        let mut text = format!("a\nb\nc\nNPTS= {}, DT= .005 SEC\n", values.len());
        for (index, value) in values.iter().enumerate() {
            text.push_str(&format!("{value:15.7E}"));
            if index % 5 == 4 {
                text.push('\n');
            }
        }
        let record = parse_at2(&text, "round.AT2").map_err(|e| TestCaseError::fail(e.to_string()))?;
        prop_assert_eq!(record.values.len(), values.len());
        for (read, written) in record.values.iter().zip(&values) {
            prop_assert!((read - written).abs() <= 1e-6 * written.abs().max(1e-30));
        }
    }
}

/// A time column in steps of exactly 1e-5 s is a record at the smallest sampling interval,
/// whatever its length: its mean step (last - first) / (n - 1) rounds to 9.999999999999999e-6
/// at 150 000 rows and to 1e-5 at 1e6, and both pass the one rule of a dt, which is inclusive.
/// The same dt given with samples in memory passes too, and a dt meaningfully below is refused
/// with the dt as given.
#[test]
fn a_dt_of_exactly_the_smallest_interval_passes_whatever_the_rounding() {
    for rows in [1000usize, 150_000, 1_000_000] {
        let mut text = String::from("t,acc\n");
        for k in 0..rows {
            text.push_str(&format!("{:.5},0.01\n", k as f64 / 1e5));
        }
        let record =
            parse_csv(&text, "steps.csv", None).unwrap_or_else(|e| panic!("{rows} rows: {e}"));
        assert!((record.dt - MIN_DT).abs() <= 1e-15 * MIN_DT, "{rows} rows");
    }
    let mean = 1.49999 / 149_999.0;
    assert!(mean < MIN_DT, "the rounding this test is about");
    assert_eq!(check_sample_dt("dt", mean), Ok(mean));
    let values = "0.01\n".repeat(10);
    assert!(parse_csv(&values, "one.csv", Some(mean)).is_ok());
    let message = error_message(parse_csv(&values, "one.csv", Some(9.99e-6)));
    assert!(message.contains("dt = 9.99e-6 s is below"), "{message}");
}
