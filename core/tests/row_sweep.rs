//! Sweeps of a row of columns, checked against what does not depend on the row's code: a row
//! whose gaps never close gives, at every point, each column's outcome of the single-column
//! sweep of that column (the row moves each column by the column's own exact flows: the same
//! numbers, the instant of overturning to rounding); identical columns under one floor motion never touch; a row's plan is told apart from
//! a single body's.

use std::path::Path;

use flexrock_core::analysis::sweep::{Axis, Cell, Plan, PointResult, Request, Sweep};

/// Two columns of 4 m x 0.7 m (E = 5 MPa and 50 MPa) under the paper's sine of amplitude
/// `amplitude`, for 6 s, `gap` m apart: models/row-pair.toml written out.
fn pair(gap: f64) -> String {
    format!(
        "[row]\ngaps = [{gap:?}]\nrestitution = 0.5\n\n{}\n{}\n{}",
        column(5.0e6),
        column(5.0e7),
        FLOOR
    )
}

fn column(youngs_modulus: f64) -> String {
    format!(
        "[[column]]\nheight = 4.0\nwidth = 0.7\ndepth = 1.0\ndensity = 600.0\n\
         youngs_modulus = {youngs_modulus:?}\ndamping_ratio = 0.05\n"
    )
}

const FLOOR: &str = "[excitation]\nkind = \"paper-sine\"\namplitude = 4.0\nperiod = 1.0\n\
                     ramp = 0.412\n\n[simulation]\nduration = 6.0\n\n[solver]\n\
                     method = \"exact\"\noutput_dt = 0.005\n";

/// The single body of one column, with the same floor motion, by the exact method.
fn single(youngs_modulus: f64) -> String {
    let body = column(youngs_modulus).replace("[[column]]", "[body]");
    format!("{body}\n{FLOOR}")
}

/// Every point's cells by column name.
fn sweep(text: &str, axes: &[&str]) -> (Plan, Vec<Vec<(String, Cell)>>) {
    let here = std::env::current_dir().unwrap();
    let request = Request {
        axes: axes
            .iter()
            .map(|a| Axis::parse(a, Path::new(".")).unwrap())
            .collect(),
        ..Request::default()
    };
    let sweep = Sweep::from_text(text, &here, request, &here).unwrap();
    let names = PointResult::columns(sweep.plan.layout());
    let rows = sweep.rows(0..sweep.points(), &|| {});
    let named = rows
        .iter()
        .map(|row| {
            names
                .iter()
                .cloned()
                .zip(row.cells(sweep.plan.layout()))
                .collect()
        })
        .collect();
    (sweep.plan, named)
}

fn at<'a>(row: &'a [(String, Cell)], name: &str) -> &'a Cell {
    &row.iter()
        .find(|(n, _)| n == name)
        .unwrap_or_else(|| panic!("no column {name}"))
        .1
}

fn float(cell: &Cell) -> Option<f64> {
    match cell {
        Cell::Float(x) => *x,
        other => panic!("not a number: {other:?}"),
    }
}

fn boolean(cell: &Cell) -> bool {
    match cell {
        Cell::Bool(Some(b)) => *b,
        other => panic!("not a bool: {other:?}"),
    }
}

#[test]
fn a_row_whose_gaps_never_close_gives_each_column_its_single_sweep() {
    // 10 m apart, the columns (0.7 m wide, overturning when |q| passes about B) never touch.
    let amplitudes = "excitation.amplitude=lin:3:9:7";
    let (plan, row) = sweep(&pair(10.0), &[amplitudes]);
    assert_eq!(plan.row_columns, Some(2));
    let mut verdicts = std::collections::BTreeSet::new();
    let mut overturned_alone = [0usize; 2];
    for (i, e) in [5.0e6, 5.0e7].into_iter().enumerate() {
        let (_, alone) = sweep(&single(e), &[amplitudes]);
        for (r, a) in row.iter().zip(&alone) {
            assert_eq!(at(r, "status"), &Cell::Text(Some("ok".into())));
            assert_eq!(at(r, "n_contacts"), &Cell::Int(Some(0)));
            assert_eq!(float(at(r, "t_first_contact")), None);
            assert_eq!(float(at(r, "contact_energy")), Some(0.0));
            let c = |name: &str| at(r, &format!("c{i}_{name}")).clone();
            let over = boolean(at(a, "overturned"));
            overturned_alone[i] += usize::from(over);
            // The column alone: the single body's sweep, to the last digit.
            assert_eq!(boolean(&c("alone_overturned")), over);
            assert_eq!(float(&c("alone_t_overturn")), float(at(a, "t_overturn")));
            let q_over_b = float(at(a, "max_abs_q_over_B")).unwrap();
            assert_eq!(float(&c("alone_max_abs_q")).unwrap() / 0.7, q_over_b);
            let verdict = c("verdict");
            verdicts.insert(format!("{verdict:?}"));
            match at(r, "overturned_column") {
                // Another column overturned first and ended the run: undecided.
                Cell::Int(Some(j)) if *j != i => {
                    assert_eq!(verdict, Cell::Text(Some("undecided".into())));
                    assert!(!boolean(&c("overturned")));
                }
                _ => {
                    assert_eq!(verdict, Cell::Text(Some("same".into())));
                    assert_eq!(boolean(&c("overturned")), over);
                    // The instant of overturning is found along the row's windows rather
                    // than the column's own steps: the same root, to rounding.
                    match (float(&c("t_overturn")), float(at(a, "t_overturn"))) {
                        (Some(t), Some(u)) => assert!((t - u).abs() <= 1e-12 * u, "{t} {u}"),
                        (t, u) => assert_eq!(t, u),
                    }
                    let q = float(&c("max_abs_q")).unwrap() / 0.7;
                    assert!((q - q_over_b).abs() <= 1e-12 * q_over_b, "{q} {q_over_b}");
                }
            }
        }
    }
    // The range holds points where a column stands and points where it overturns.
    assert!(
        overturned_alone.iter().all(|&n| n > 0 && n < 7),
        "{overturned_alone:?}"
    );
    assert!(!verdicts
        .iter()
        .any(|v| v.contains("saved") || v.contains("toppled")));
}

#[test]
fn identical_columns_never_touch_at_any_point() {
    let text = format!(
        "[row]\ngaps = [0.01, 0.01]\nrestitution = 0.3\n\n{0}\n{0}\n{0}\n{FLOOR}",
        column(2.0e7)
    );
    let (plan, rows) = sweep(
        &text,
        &[
            "row.gaps=lin:0.002:0.05:4",
            "excitation.amplitude=lin:2:9:5",
        ],
    );
    assert_eq!(plan.row_columns, Some(3));
    assert_eq!(rows.len(), 20);
    let mut overturned = 0;
    for r in &rows {
        assert_eq!(at(r, "status"), &Cell::Text(Some("ok".into())));
        assert_eq!(at(r, "n_contacts"), &Cell::Int(Some(0)));
        assert_eq!(float(at(r, "t_first_contact")), None);
        assert_eq!(float(at(r, "contact_energy")), Some(0.0));
        if let Cell::Int(Some(_)) = at(r, "overturned_column") {
            overturned += 1;
        }
    }
    // The amplitudes reach overturning: the columns swing far, and still never touch.
    assert!(overturned > 0 && overturned < rows.len(), "{overturned}");
}

#[test]
fn a_row_plan_is_not_a_single_body_plan() {
    let (row, _) = sweep(&pair(0.02), &["excitation.amplitude=2,3"]);
    let (body, _) = sweep(&single(5.0e6), &["excitation.amplitude=2,3"]);
    assert_eq!(row.row_columns, Some(2));
    assert_eq!(body.row_columns, None);
    let other_kind = Plan {
        row_columns: None,
        ..row.clone()
    };
    assert!(!row.same_sweep(&other_kind));
    assert_ne!(row.identity(), other_kind.identity());
    // A single body's plan is written as before rows could be swept.
    assert!(!serde_json::to_string(&body)
        .unwrap()
        .contains("row_columns"));
}

#[test]
fn the_energy_a_compliant_row_takes_counts_friction_too() {
    // models/row-friction.toml: faces that stick and slide under mu = 0.5.
    let path =
        std::path::PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../models/row-friction.toml");
    let text = std::fs::read_to_string(&path).unwrap();
    let (_, rows) = sweep(&text, &["row.friction=0.5"]);
    let model = flexrock_core::model::RowModel::load(&path, None).unwrap();
    let run = flexrock_core::simulate::simulate_row(&model).unwrap();
    let friction: f64 = run.contacts.iter().map(|c| c.friction_dissipated).sum();
    let normal: f64 = run.contacts.iter().map(|c| c.energy_dissipated).sum();
    assert!(friction > 0.0 && normal > 0.0, "{friction} {normal}");
    let energy = float(at(&rows[0], "contact_energy")).unwrap();
    assert!(
        (energy - (friction + normal)).abs() <= 1e-6 * (friction + normal),
        "{energy} against {normal} + {friction}"
    );
    assert_eq!(
        at(&rows[0], "n_contacts"),
        &Cell::Int(Some(run.contacts.len()))
    );
}
