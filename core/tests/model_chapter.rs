//! The model chapter (book/src/model.md) against the program and against the places that cite it:
//! the constants it prints for the reference body (computed from its formulas by
//! book/constants.py, with the Python standard library alone) are the program's, rounded; every
//! section that code, tests and documents cite exists; every link into it lands on a heading.

use crate::common;

use std::collections::BTreeSet;
use std::path::{Path, PathBuf};

use flexrock_core::physics::constants::Constants;

const CHAPTER: &str = include_str!("../../book/src/model.md");

/// The numbered sections of the chapter: "1" ... "10", "7a", "7b", "7c".
fn sections() -> BTreeSet<String> {
    sections_of(CHAPTER)
}

/// The numbered sections ("2", "7a") of a chapter's text.
fn sections_of(chapter: &str) -> BTreeSet<String> {
    chapter
        .lines()
        .filter_map(|line| {
            let title = line.strip_prefix("## ").or(line.strip_prefix("### "))?;
            let (number, _) = title.split_once(". ")?;
            let numbered = number.chars().next()?.is_ascii_digit()
                && number.chars().all(|c| c.is_ascii_alphanumeric());
            numbered.then(|| number.to_string())
        })
        .collect()
}

/// The link anchors of the chapter's headings, as mdBook (and a repository host) make them: the
/// text in lower case, whitespace to hyphens, everything but letters, digits, '-' and '_' dropped.
fn anchors() -> BTreeSet<String> {
    CHAPTER
        .lines()
        .filter(|line| line.starts_with('#'))
        .map(|line| common::anchor_of(line.trim_start_matches('#')))
        .collect()
}

/// The repository's text files that may cite the chapter (outside the chapter's own book).
fn cited_files() -> Vec<PathBuf> {
    fn walk(dir: &Path, out: &mut Vec<PathBuf>) {
        let Ok(entries) = std::fs::read_dir(dir) else {
            return;
        };
        for entry in entries.flatten() {
            let path = entry.path();
            let name = entry.file_name().to_string_lossy().into_owned();
            if path.is_dir() {
                let skipped = name.starts_with('.')
                    || name.starts_with("target")
                    || ["book", "out", "node_modules", "__pycache__"].contains(&name.as_str());
                if !skipped {
                    walk(&path, out);
                }
            } else if ["rs", "md", "py", "toml", "sh", "sbatch", "cff"]
                .iter()
                .any(|ext| name.ends_with(&format!(".{ext}")))
                // This file quotes the patterns it looks for.
                && name != "model_chapter.rs"
            {
                out.push(path);
            }
        }
    }
    let mut files = Vec::new();
    walk(&common::workspace_file(""), &mut files);
    files
}

#[test]
fn every_cited_section_and_anchor_exists_and_nothing_cites_a_missing_model_description() {
    let sections = sections();
    let expected: BTreeSet<String> = (1..=10)
        .map(|n| n.to_string())
        .chain(["7a", "7b", "7c", "7d"].map(String::from))
        .collect();
    assert_eq!(sections, expected, "the chapter's numbered sections");
    let anchors = anchors();
    let row_chapter = std::fs::read_to_string(common::workspace_file("book/src/row.md"))
        .expect("the row's chapter");
    let row_sections = sections_of(&row_chapter);
    assert!(row_sections.contains("4a"), "{row_sections:?}");
    // Written in two pieces so that this file does not cite it itself.
    let missing_description = format!("{}.md", "MODEL");

    let files = cited_files();
    assert!(files.len() > 50, "found only {} files", files.len());
    let mut citations = 0;
    let mut links = 0;
    for path in &files {
        let Ok(text) = std::fs::read_to_string(path) else {
            continue;
        };
        let name = path.display();
        assert!(
            !text.contains(&missing_description),
            "{name} cites {missing_description}, which is not in the repository: cite book/src/model.md"
        );
        // "§7a", "§2-§5": every section sign names a section of the chapter (or, on a line
        // that names book/src/row.md, of the row's chapter).
        for (at, _) in text.match_indices('§') {
            let number: String = text[at + '§'.len_utf8()..]
                .chars()
                .take_while(|c| c.is_ascii_alphanumeric())
                .collect();
            let line_start = text[..at].rfind('\n').map_or(0, |i| i + 1);
            let line_end = text[at..].find('\n').map_or(text.len(), |i| at + i);
            let (chapter, known) = if text[line_start..line_end].contains("row.md") {
                ("the row's chapter", &row_sections)
            } else {
                ("the chapter", &sections)
            };
            assert!(
                known.contains(&number),
                "{name} cites §{number}, which {chapter} does not have"
            );
            citations += 1;
        }
        // "book/src/model.md section 7", "model.md sections 2-5 and 7a" (the Python scripts).
        for (at, _) in text.match_indices("model.md section") {
            let rest = &text[at + "model.md section".len()..];
            let rest = rest.strip_prefix('s').unwrap_or(rest);
            let list: String = rest
                .chars()
                .take_while(|c| c.is_ascii_alphanumeric() || " ,-".contains(*c))
                .collect();
            for number in list
                .split([' ', ',', '-'])
                .filter(|w| w.starts_with(|c: char| c.is_ascii_digit()))
            {
                assert!(
                    sections.contains(number),
                    "{name} cites section {number} of the chapter, which it does not have"
                );
                citations += 1;
            }
        }
        // Markdown links into the chapter land on one of its headings.
        for (at, _) in text.match_indices("model.md#") {
            let anchor: String = text[at + "model.md#".len()..]
                .chars()
                .take_while(|c| c.is_alphanumeric() || *c == '-' || *c == '_')
                .collect();
            assert!(
                anchors.contains(&anchor),
                "{name} links to model.md#{anchor}, which is not a heading of the chapter"
            );
            links += 1;
        }
    }
    assert!(citations > 50, "found only {citations} citations");
    assert!(links > 20, "found only {links} links");
}

/// The rows of the table of §8: label, then one number per column (exact constants, the paper's
/// rounded constants, the consistent variant).
fn reference_table() -> Vec<(String, Vec<String>)> {
    let start = CHAPTER
        .find("**The constants of the reference body**")
        .expect("the table of §8");
    CHAPTER[start..]
        .lines()
        .skip_while(|line| !line.starts_with('|'))
        .take_while(|line| line.starts_with('|'))
        .skip(2)
        .map(|line| {
            let cells: Vec<String> = line
                .trim_matches('|')
                .split(" | ")
                .map(|cell| cell.trim().replace("\\\\(", "").replace("\\\\)", ""))
                .collect();
            (cells[0].clone(), cells[1..].to_vec())
        })
        .collect()
}

/// The printed number equals `value` rounded to the printed digits, give or take `relative`.
fn printed_as(printed: &str, value: f64, relative: f64, what: &str) {
    let number: f64 = printed
        .parse()
        .unwrap_or_else(|_| panic!("{what}: {printed:?} is not a number"));
    let decimals = printed.split_once('.').map_or(0, |(_, d)| d.len()) as i32;
    let half_unit = 0.5 * 10f64.powi(-decimals);
    assert!(
        (number - value).abs() <= half_unit * (1.0 + 1e-9) + relative * value.abs(),
        "{what}: the chapter prints {printed}, the program computes {value}"
    );
}

/// One constant of [`Constants`], read off.
type Field = fn(&Constants) -> f64;

#[test]
fn the_constants_table_of_the_paper_example_is_the_programs_rounded() {
    let body = |extra: &str| {
        common::model(&common::reference_body(&format!(
            "{extra}\n[excitation]\nkind = \"free\"\n[simulation]\nduration = 1.0\n"
        )))
        .constants
    };
    // The consistent variant's Ritz solve is truncated (12 modes here, 16 in book/constants.py):
    // its last printed digit may differ by the truncation, about 1e-7 relative.
    let columns = [
        ("exact", body(""), 0.0),
        ("paper", body("constants = \"paper\""), 0.0),
        ("consistent", body("self_weight = \"consistent\""), 1e-6),
    ];
    let fields: [(&str, Field); 16] = [
        ("M_e", |c| c.generalised_mass),
        ("K_e", |c| c.generalised_stiffness),
        ("\\omega", |c| c.omega),
        ("T", |c| c.period),
        ("\\gamma/E", |c| c.damping_coefficient),
        ("\\beta_1", |c| c.beta1),
        ("s_n", |c| c.uplift_displacement),
        ("\\nu_2", |c| c.nu2),
        ("\\beta_2", |c| c.beta2),
        ("\\zeta_U", |c| c.zeta_uplift),
        ("\\zeta_L", |c| c.zeta_landing),
        ("kinetic energy kept at uplift,", |c| {
            c.zeta_uplift.powi(2) * c.kinetic_mass(true) / c.kinetic_mass(false)
        }),
        ("kinetic energy kept at landing,", |c| {
            c.kinetic_mass(false) / (c.zeta_landing.powi(2) * c.kinetic_mass(true))
        }),
        ("F'", |c| c.rocking_stiffness),
        ("q_{\\mathrm{topple}}", |c| c.topple_displacement),
        ("a_{\\mathrm{up}}", |c| c.quasi_static_uplift_acceleration),
    ];
    let table = reference_table();
    let mut checked = 0;
    for (label, field) in fields {
        let (_, cells) = table
            .iter()
            .find(|(row, _)| row == label || row.starts_with(&format!("{label} ")))
            .unwrap_or_else(|| panic!("no row {label} in the table of §8"));
        assert_eq!(cells.len(), columns.len(), "row {label}");
        for ((column, constants, relative), printed) in columns.iter().zip(cells) {
            let what = format!("{label}, {column}");
            printed_as(printed, field(constants), *relative, &what);
            checked += 1;
        }
    }
    // The gravity parameter row: one pair for all three columns.
    let (_, cells) = table
        .iter()
        .find(|(row, _)| row.starts_with("\\gamma_g"))
        .expect("the gravity parameter row");
    let (ratio_of, share) = cells[0].split_once(", ").expect("gamma_g, gamma_g/7.837");
    for (_, constants, _) in &columns {
        printed_as(ratio_of, constants.gravity_parameter, 0.0, "gamma_g");
        printed_as(
            share,
            constants.gravity_parameter_ratio,
            0.0,
            "gamma_g/7.837",
        );
    }
    assert_eq!(checked, 48);
}
