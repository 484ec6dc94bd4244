//! The figure of a row sweep over two numeric axes, drawn from sweep.csv alone: `verdicts`,
//! one map per column of the row, each cell coloured by what the row did to that column at that
//! point (`cI_verdict`, and `cI_alone_overturned` to tell the two kinds of `same` apart): saved,
//! toppled, overturns both, stands both, or undecided (another column overturned first and
//! ended the row's run). Invalid and failed points are white cells crossed in grey.

use crate::error::{Error, Result};
use crate::figures::plot::{self, Figure, Panel, Series, Swatch};
use crate::figures::sweep_axes::{ascending, axis_label, drawable, edges};
use crate::sweep_table::SweepTable;
use flexrock_core::analysis::sweep::Plan;

/// What the row did to a column at one point.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Class {
    Saved,
    Toppled,
    OverturnsBoth,
    StandsBoth,
    Undecided,
    /// An invalid or failed point.
    Missing,
}

/// The classes in the legend's order, with their colours (Okabe and Ito's, told apart in the
/// common colour-vision deficiencies, and by lightness in greyscale) and labels.
const LEGEND: [(Class, (u8, u8, u8), &str); 5] = [
    (
        Class::Saved,
        (0, 114, 178),
        "saved: overturns alone, stands in the row",
    ),
    (
        Class::Toppled,
        (213, 94, 0),
        "toppled: stands alone, overturns in the row",
    ),
    (Class::OverturnsBoth, (45, 45, 45), "overturns both"),
    (Class::StandsBoth, (222, 222, 222), "stands both"),
    (
        Class::Undecided,
        (240, 228, 66),
        "undecided: another column overturned first",
    ),
];

fn colour(class: Class) -> (u8, u8, u8) {
    LEGEND
        .iter()
        .find(|(c, _, _)| *c == class)
        .map_or((255, 255, 255), |(_, colour, _)| *colour)
}

/// Panels per line of the figure.
const PER_LINE: usize = 3;

/// The verdict maps of a row of `n` columns over axes `x` and `y`; None when the axes cannot
/// be drawn as cells.
pub fn verdict_maps(
    plan: &Plan,
    table: &SweepTable,
    n: usize,
    x: usize,
    y: usize,
) -> Result<Option<Figure>> {
    let (nx, ny) = (plan.axes[x].len(), plan.axes[y].len());
    let status = table.column("status")?;
    let mut maps = vec![vec![vec![Class::Missing; ny]; nx]; n];
    for (i, map) in maps.iter_mut().enumerate() {
        let verdict = table.column(&format!("c{i}_verdict"))?;
        let alone = table.column(&format!("c{i}_alone_overturned"))?;
        for (r, row) in table.rows.iter().enumerate() {
            let point: usize = row[0].parse().map_err(|_| Error::ReadResult {
                path: std::path::PathBuf::from("sweep.csv"),
                message: format!("row {} has no point number", r + 1),
            })?;
            let c = plan.coordinates(point);
            map[c[x]][c[y]] = match (&row[status], &row[verdict], &row[alone]) {
                ("ok", "saved", _) => Class::Saved,
                ("ok", "toppled", _) => Class::Toppled,
                ("ok", "undecided", _) => Class::Undecided,
                ("ok", "same", "true") => Class::OverturnsBoth,
                ("ok", "same", _) => Class::StandsBoth,
                _ => Class::Missing,
            };
        }
    }
    let values = |axis: usize| -> Vec<f64> {
        (0..plan.axes[axis].len())
            .map(|i| plan.axes[axis].number(i).unwrap_or(f64::NAN))
            .collect()
    };
    let (xs, ys) = (values(x), values(y));
    // An axis of positive values spanning two decades or more is drawn on a log scale (the
    // cells' edges halfway between the values' logarithms).
    let logged = |v: &[f64]| {
        let (lo, hi) = v.iter().fold((f64::INFINITY, 0.0f64), |(lo, hi), &x| {
            (lo.min(x), hi.max(x))
        });
        lo > 0.0 && hi / lo >= 100.0
    };
    let (log_x, log_y) = (logged(&xs), logged(&ys));
    let in_axis = |v: &[f64], log: bool| -> Vec<f64> {
        if log {
            v.iter().map(|x| x.log10()).collect()
        } else {
            v.to_vec()
        }
    };
    let (ax, ay) = (in_axis(&xs, log_x), in_axis(&ys, log_y));
    if !(drawable(&ax) && drawable(&ay)) {
        return Ok(None);
    }
    let labels = (axis_label(&plan.axes[x].key), axis_label(&plan.axes[y].key));
    let (ox, oy) = (ascending(&ax), ascending(&ay));
    let sorted = |v: &[f64], order: &[usize]| order.iter().map(|&i| v[i]).collect::<Vec<_>>();
    let back = |e: Vec<f64>, log: bool| -> Vec<f64> {
        if log {
            e.into_iter().map(|v| 10f64.powf(v)).collect()
        } else {
            e
        }
    };
    let (ex, ey) = (
        back(edges(&sorted(&ax, &ox)), log_x),
        back(edges(&sorted(&ay, &oy)), log_y),
    );
    let mut panels = Vec::new();
    for (i, map) in maps.iter().enumerate() {
        let mut panel = Panel::new(&format!("column {i}"), &labels.0, &labels.1);
        panel.log_x = log_x;
        panel.log_y = log_y;
        let mut crosses = Vec::new();
        for (a, &xi) in ox.iter().enumerate() {
            for (b, &yi) in oy.iter().enumerate() {
                let class = map[xi][yi];
                panel.cells.push(plot::Cell {
                    from: (ex[a], ey[b]),
                    to: (ex[a + 1], ey[b + 1]),
                    rgb: colour(class),
                });
                if class == Class::Missing {
                    crosses.extend([(ex[a], ey[b]), (ex[a + 1], ey[b + 1]), (f64::NAN, f64::NAN)]);
                }
            }
        }
        if !crosses.is_empty() {
            panel = panel.with(Series::line("", crosses, 7).with_width(0.4));
        }
        panels.push(panel);
    }
    let mut figure = Figure::new(panels, n.min(PER_LINE)).aspect(1.1, 35.0);
    for (_, rgb, label) in LEGEND {
        figure
            .extra_legend
            .push((label.to_string(), Swatch::Fill(rgb)));
    }
    figure.extra_legend.push((
        "invalid or failed".to_string(),
        Swatch::Fill((255, 255, 255)),
    ));
    Ok(Some(figure))
}
