//! Figures of a sweep, drawn from sweep.csv alone (so that a merge of shards draws the same):
//! - `map.svg` for a sweep over two numeric axes: max |q|/B as colour, overturned cells black,
//!   the boundary between overturned and standing cells drawn in red; beside it the same map
//!   over the dimensionless axes when an axis is the excitation's amplitude (plotted over
//!   g tan(alpha)) or period (plotted as omega_p/p);
//! - `spectrum.svg` for a minimum search over one numeric axis: the smallest overturning value
//!   against the axis, in physical and in dimensionless units, with the rigid block's (the
//!   slender Housner block of the same geometry, and the rigid limit of the elastic model);
//! - `ida.svg` for a sweep over records (`excitation.path`) and an intensity (`excitation.scale`
//!   or `excitation.amplitude`), or over `excitation.scale` alone: max |q|/B against the
//!   intensity, one line per record, overturned points marked (incremental dynamic analysis).

use std::path::Path;

use crate::error::Result;
use crate::figures::page::{FigureOptions, PAGE_MM};
use crate::figures::plot::{self, Dash, Figure, Marker, Panel, Series, Swatch};
use flexrock_core::analysis::sweep::Plan;

use crate::figures::sweep_axes::axis_label;
use crate::figures::sweep_axes::{ascending, drawable, edges};
pub use crate::sweep_table::SweepTable;

/// The figures of a sweep, as (file stem, figure): the map, the spectrum, the IDA curves or a
/// row's verdict maps, whichever its axes make.
pub fn figures(plan: &Plan, table: &SweepTable) -> Result<Vec<(&'static str, Figure)>> {
    let numeric: Vec<usize> = (0..plan.axes.len())
        .filter(|&i| plan.axes[i].is_numeric())
        .collect();
    if let Some(n) = plan.row_columns {
        return match (plan.axes.len(), numeric.as_slice()) {
            (2, [x, y]) => Ok(
                crate::figures::sweep_row::verdict_maps(plan, table, n, *x, *y)?
                    .map(|f| (VERDICTS, f))
                    .into_iter()
                    .collect(),
            ),
            _ => Ok(Vec::new()),
        };
    }
    match (&plan.find_min, plan.axes.len(), numeric.as_slice()) {
        (None, 2, [x, y]) => Ok(map(plan, table, *x, *y)?
            .map(|f| ("map", f))
            .into_iter()
            .collect()),
        (Some(_), 1, [x]) => Ok(spectrum(plan, table, *x)?
            .map(|f| ("spectrum", f))
            .into_iter()
            .collect()),
        // Incremental dynamic analysis: records against an intensity, or one record's scale.
        (None, 1 | 2, [x]) if is_ida(plan, *x) => Ok(vec![(
            IDA,
            ida_figure(&IdaData::of_sweep(plan, table, *x)?),
        )]),
        _ => Ok(Vec::new()),
    }
}

/// The figure files of a sweep in the formats and size of `options`: map.svg, map.pdf, ...
pub fn files(
    plan: &Plan,
    table: &SweepTable,
    options: &FigureOptions,
) -> Result<Vec<(String, Vec<u8>)>> {
    let mut files = Vec::new();
    for (stem, figure) in figures(plan, table)? {
        files.extend(plot::files(stem, &figure, options, PAGE_MM)?);
    }
    Ok(files)
}

/// The figure files a sweep writes with its table: SVG, and the verdict maps of a row as PNG
/// too (as they always were).
pub fn sweep_files(plan: &Plan, table: &SweepTable) -> Result<Vec<(String, Vec<u8>)>> {
    use crate::figures::page::Format;
    let mut files = Vec::new();
    for (stem, figure) in figures(plan, table)? {
        let formats: &[Format] = if stem == VERDICTS {
            &[Format::Svg, Format::Png]
        } else {
            &[Format::Svg]
        };
        let options = FigureOptions::default().with_formats(formats);
        files.extend(plot::files(stem, &figure, &options, PAGE_MM)?);
    }
    Ok(files)
}

/// The stem of the figure of a sweep over records and an intensity.
pub const IDA: &str = "ida";
/// The stem of the maps of a row sweep over two numeric axes: each column's verdict.
pub const VERDICTS: &str = "verdicts";
/// Every figure file a sweep may write, in every format.
pub fn figure_files() -> Vec<String> {
    let mut names = Vec::new();
    for stem in ["map", "spectrum", IDA, VERDICTS] {
        for format in [
            crate::figures::page::Format::Svg,
            crate::figures::page::Format::Pdf,
            crate::figures::page::Format::Png,
        ] {
            names.push(format!("{stem}.{}", format.extension()));
        }
    }
    names
}

/// True for a sweep whose numeric axis `x` scales the excitation (excitation.scale or
/// excitation.amplitude) beside an axis of records (excitation.path), or is excitation.scale
/// alone (one record): an incremental dynamic analysis.
fn is_ida(plan: &Plan, x: usize) -> bool {
    let key = plan.axes[x].key.as_str();
    let records = plan.axes.iter().any(|a| a.key == "excitation.path");
    match plan.axes.len() {
        1 => key == "excitation.scale",
        _ => records && matches!(key, "excitation.scale" | "excitation.amplitude"),
    }
}

/// The short name of a record file: its file name without the extension.
fn record_name(path: &str) -> String {
    Path::new(path)
        .file_stem()
        .map_or_else(|| path.to_string(), |n| n.to_string_lossy().into_owned())
}

/// The curves of an incremental dynamic analysis as plain data: what the x axis is, and per
/// record (or other setting) a label and its points, so that another intensity measure or
/// other labels can be given than a sweep's own.
#[derive(Debug, Clone, PartialEq)]
pub struct IdaData {
    /// The x axis's label (the intensity measure and its unit).
    pub x_label: String,
    /// One curve per record.
    pub curves: Vec<IdaCurve>,
}

/// One record's curve of an incremental dynamic analysis.
#[derive(Debug, Clone, PartialEq)]
pub struct IdaCurve {
    /// The legend text (a record's name).
    pub label: String,
    /// (intensity, max |q|/B, overturned), in any order; an overturned point's value is
    /// not used.
    pub points: Vec<(f64, f64, bool)>,
}

impl IdaData {
    /// The curves of a sweep with intensity axis `x`: the axis's values as the intensity, one
    /// curve per value of the other axis, labelled by the record's file stem.
    pub fn of_sweep(plan: &Plan, table: &SweepTable, x: usize) -> Result<IdaData> {
        let q_column = table.column("max_abs_q_over_B")?;
        let over_column = table.column("overturned")?;
        let other = (0..plan.axes.len()).find(|&i| i != x);
        let groups = other.map_or(1, |o| plan.axes[o].len());
        let mut points: Vec<Vec<(f64, f64, bool)>> = vec![Vec::new(); groups];
        for (r, row) in table.rows.iter().enumerate() {
            let point = table.point(r, row)?;
            let c = plan.coordinates(point);
            let Some(xv) = plan.axes[x].number(c[x]) else {
                continue;
            };
            let overturned = &row[over_column] == "true";
            let g = other.map_or(0, |o| c[o]);
            match (overturned, table.number(r, q_column)) {
                (true, _) => points[g].push((xv, 1.0, true)),
                (false, Some(v)) => points[g].push((xv, v, false)),
                (false, None) => {}
            }
        }
        let label = |g: usize| match other {
            Some(o) if plan.axes[o].key == "excitation.path" => {
                record_name(&plan.axes[o].values[g])
            }
            Some(o) => format!(
                "{} = {}",
                axis_label(&plan.axes[o].key),
                plan.axes[o].values[g]
            ),
            None => "max |q|/B".to_string(),
        };
        Ok(IdaData {
            x_label: axis_label(&plan.axes[x].key),
            curves: points
                .into_iter()
                .enumerate()
                .map(|(g, points)| IdaCurve {
                    label: label(g),
                    points,
                })
                .collect(),
        })
    }
}

/// The p-quantile (0 to 1) of `values` sorted ascending (+inf for an overturned record), by
/// linear interpolation between order statistics.
fn quantile(sorted: &[f64], p: f64) -> f64 {
    let h = p * (sorted.len() - 1) as f64;
    let (lo, hi) = (h.floor() as usize, h.ceil() as usize);
    if sorted[hi].is_infinite() {
        return f64::INFINITY;
    }
    sorted[lo] + (h - lo as f64) * (sorted[hi] - sorted[lo])
}

/// Incremental dynamic analysis: max |q|/B against the intensity, a line per record up to its
/// first overturning; the overturnings as crosses above |q| = B, stacked where records first
/// overturn at one intensity so that none hides another; with three records or more, the
/// median and the 16 % and 84 % fractiles of max |q|/B over the records at each intensity (an
/// overturned record counts as above every value), drawn while they stand.
pub fn ida_figure(data: &IdaData) -> Figure {
    let mut panel = Panel::new("", &data.x_label, "max |q|/B");
    let mut firsts: Vec<(f64, usize)> = Vec::new();
    let many = data.curves.len() > 1;
    for (g, curve) in data.curves.iter().enumerate() {
        let mut group = curve.points.clone();
        group.sort_by(|a, b| a.0.total_cmp(&b.0));
        // The line up to the first overturning point; the points beyond it overturn too, or
        // (rarely, resurrection) stand again: those are drawn as markers only.
        let first_over = group.iter().position(|p| p.2);
        let upto = first_over.unwrap_or(group.len());
        let mut line: Vec<(f64, f64)> = group[..upto].iter().map(|p| (p.0, p.1)).collect();
        if let Some(i) = first_over {
            line.push((group[i].0, 1.0));
        }
        // Palette colours 1..7 (0, black, is for the median), dashes cycling with them.
        let color = 1 + g % 7;
        let dash = [Dash::Solid, Dash::Dashed, Dash::DashDot][(g / 7) % 3];
        let width = if many { 0.7 } else { LINE };
        let mut series = Series::line(&curve.label, line, color)
            .with_width(width)
            .with_dash(dash);
        if data.curves.len() <= 7 {
            series = series.with_marker(Marker::Circle);
        }
        panel = panel.with(series);
        let beyond: Vec<(f64, f64)> = group[upto..]
            .iter()
            .filter(|p| !p.2)
            .map(|p| (p.0, p.1))
            .collect();
        if !beyond.is_empty() {
            panel = panel.with(Series::markers("", beyond, color, Marker::OpenCircle));
        }
        if let Some(i) = first_over {
            firsts.push((group[i].0, color));
        }
    }
    // The crosses: at 1.06, 1.12, ... above |q| = B, one row per record that first overturns
    // at that intensity.
    firsts.sort_by(|a, b| a.0.total_cmp(&b.0));
    let mut stacked = 0usize;
    let mut k = 0;
    while k < firsts.len() {
        let same = firsts[k..]
            .iter()
            .take_while(|f| f.0 == firsts[k].0)
            .count();
        for (j, &(x, color)) in firsts[k..k + same].iter().enumerate() {
            panel = panel.with(Series::markers(
                "",
                vec![(x, 1.0 + 0.06 * (j + 1) as f64)],
                color,
                Marker::Cross,
            ));
            stacked = stacked.max(j + 1);
        }
        k += same;
    }
    // The median and fractiles over the records at each intensity they all share.
    if data.curves.len() >= 3 {
        let mut xs: Vec<f64> = data
            .curves
            .iter()
            .flat_map(|c| c.points.iter().map(|p| p.0))
            .collect();
        xs.sort_by(f64::total_cmp);
        xs.dedup();
        let mut stats: [Vec<(f64, f64)>; 3] = Default::default();
        for &x in &xs {
            let mut at: Vec<f64> = data
                .curves
                .iter()
                .filter_map(|c| c.points.iter().find(|p| p.0 == x))
                .map(|p| if p.2 { f64::INFINITY } else { p.1 })
                .collect();
            if at.len() < data.curves.len() {
                continue;
            }
            at.sort_by(f64::total_cmp);
            for (s, p) in stats.iter_mut().zip([0.5, 0.16, 0.84]) {
                let v = quantile(&at, p);
                if v.is_finite() {
                    s.push((x, v));
                }
            }
        }
        let [median, low, high] = stats;
        panel = panel
            .with(Series::line("median", median, 0).with_width(1.8))
            .with(Series::line("16 % and 84 % fractiles", low, 0).with_dash(Dash::Dashed))
            .with(Series::line("", high, 0).with_dash(Dash::Dashed));
    }
    panel.dashed_lines = vec![(1.0, "|q| = B (overturning)".to_string())];
    if stacked > 0 {
        let lo = panel
            .series
            .iter()
            .flat_map(|s| s.points.iter().map(|p| p.1))
            .filter(|v| v.is_finite())
            .fold(0.0f64, f64::min);
        panel.y_range = Some((lo, 1.0 + 0.06 * (stacked + 1) as f64));
    }
    let mut figure = Figure::new(vec![panel], 1).aspect(1.5, 40.0);
    if stacked > 0 {
        figure.extra_legend.push((
            "first overturning of a record (stacked above |q| = B)".to_string(),
            Swatch::Marker(0, Marker::Cross, None),
        ));
    }
    figure
}

/// Width of a single curve, pt.
const LINE: f64 = plot::LINE_PT;

/// The dimensionless column that stands for an axis, and its label.
fn dimensionless(key: &str) -> Option<(&'static str, &'static str)> {
    match key {
        "excitation.amplitude" => Some(("amplitude_over_g_tan_alpha", "aₚ/(g tan α)")),
        "excitation.scale" => Some(("amplitude_over_g_tan_alpha", "PFA/(g tan α)")),
        "excitation.period" => Some(("omega_p_over_p", "ωₚ/p")),
        _ => None,
    }
}

/// One map cell.
#[derive(Clone, Copy)]
struct MapCell {
    /// Value of max |q|/B; None for an invalid or failed point.
    value: Option<f64>,
    overturned: bool,
}

/// The map over axes `x` and `y` (indices into the plan's axes).
/// None when the axes cannot be drawn as cells (values too close to tell apart in the figure's
/// arithmetic).
fn map(plan: &Plan, table: &SweepTable, x: usize, y: usize) -> Result<Option<Figure>> {
    let (nx, ny) = (plan.axes[x].len(), plan.axes[y].len());
    let q_column = table.column("max_abs_q_over_B")?;
    let over_column = table.column("overturned")?;
    let mut cells = vec![
        vec![
            MapCell {
                value: None,
                overturned: false
            };
            ny
        ];
        nx
    ];
    for (r, row) in table.rows.iter().enumerate() {
        let point = table.point(r, row)?;
        let c = plan.coordinates(point);
        cells[c[x]][c[y]] = MapCell {
            value: table.number(r, q_column),
            overturned: &row[over_column] == "true",
        };
    }
    let physical = |axis: usize| -> Vec<f64> {
        (0..plan.axes[axis].len())
            .map(|i| plan.axes[axis].number(i).unwrap_or(f64::NAN))
            .collect()
    };
    // Dimensionless coordinates: the column's value at the first valid point of each index.
    let scaled = |axis: usize, column: &str| -> Result<Option<Vec<f64>>> {
        let column = table.column(column)?;
        let mut values = vec![None; plan.axes[axis].len()];
        for (r, row) in table.rows.iter().enumerate() {
            let point: usize = row[0].parse().unwrap_or(0);
            let i = plan.coordinates(point)[axis];
            if values[i].is_none() {
                values[i] = table.number(r, column);
            }
        }
        Ok(values.into_iter().collect())
    };
    let mut views: Vec<(Vec<f64>, String, Vec<f64>, String)> = vec![(
        physical(x),
        axis_label(&plan.axes[x].key),
        physical(y),
        axis_label(&plan.axes[y].key),
    )];
    let dx = dimensionless(&plan.axes[x].key);
    let dy = dimensionless(&plan.axes[y].key);
    if dx.is_some() || dy.is_some() {
        let axis_view = |axis: usize, d: Option<(&str, &str)>| -> Result<(Vec<f64>, String)> {
            if let Some((column, label)) = d {
                if let Some(values) = scaled(axis, column)? {
                    return Ok((values, label.to_string()));
                }
            }
            Ok((physical(axis), axis_label(&plan.axes[axis].key)))
        };
        let (xs, xl) = axis_view(x, dx)?;
        let (ys, yl) = axis_view(y, dy)?;
        // Drawn only when the body is the same at every point: the scaled values are in the
        // order of the physical ones (or its reverse).
        let same_order = |scaled: &[f64], axis: usize| {
            let (a, b) = (ascending(scaled), ascending(&physical(axis)));
            a == b || a.iter().rev().eq(b.iter())
        };
        if drawable(&xs) && drawable(&ys) && same_order(&xs, x) && same_order(&ys, y) {
            views.push((xs, xl, ys, yl));
        }
    }
    if !views
        .iter()
        .all(|(xs, _, ys, _)| drawable(xs) && drawable(ys))
    {
        return Ok(None);
    }

    let panels: Vec<Panel> = views
        .iter()
        .map(|(xs, x_label, ys, y_label)| map_panel(&cells, xs, ys, x_label, y_label))
        .collect();
    let mut figure = Figure::new(panels, views.len()).aspect(1.2, 40.0);
    for (k, &(lo, hi)) in CLASSES.iter().enumerate() {
        let what = if k == 0 { "max |q|/B: " } else { "" };
        figure.extra_legend.push((
            format!("{what}{}–{}", tick(lo), tick(hi)),
            Swatch::Fill(CLASS_COLOURS[k]),
        ));
    }
    figure
        .extra_legend
        .push(("overturned".to_string(), Swatch::Fill((0, 0, 0))));
    figure.extra_legend.push((
        "not solved (invalid or failed)".to_string(),
        Swatch::Fill(MISSING),
    ));
    Ok(Some(figure))
}

/// A class bound as a legend writes it: 0, 0.2, ..., 1.
fn tick(v: f64) -> String {
    flexrock_core::base::format::significant(v, 2)
}

/// The classes of max |q|/B a map's cells are coloured by: five of 0.2 each, the last to 1.
const CLASSES: [(f64, f64); 5] = [(0.0, 0.2), (0.2, 0.4), (0.4, 0.6), (0.6, 0.8), (0.8, 1.0)];
/// Their colours: a sequential ramp of light to dark (viridis at five stops, reversed so that
/// the larger response is darker, and overturned black beyond it): ordered in greyscale too.
const CLASS_COLOURS: [(u8, u8, u8); 5] = [
    (253, 231, 37),
    (94, 201, 98),
    (33, 145, 140),
    (59, 82, 139),
    (68, 1, 84),
];
/// An unsolved cell.
const MISSING: (u8, u8, u8) = (255, 255, 255);
/// The boundary between overturned and standing cells: vermillion, over black and over the
/// ramp's colours.
const BOUNDARY: usize = 1;

/// The colour of max |q|/B: its class's.
fn class_colour(value: f64) -> (u8, u8, u8) {
    let k = CLASSES
        .iter()
        .position(|&(_, hi)| value < hi)
        .unwrap_or(CLASSES.len() - 1);
    CLASS_COLOURS[k]
}

/// An axis of positive values is drawn on a log scale where its cells are more even so: the
/// steps between its sorted values vary less in log10 than as they are (a log-spaced grid, or
/// omega_p/p of evenly spaced periods), relative to their mean.
fn log_scale(values: &[f64]) -> bool {
    if values.len() < 3 || !values.iter().all(|&v| v > 0.0) {
        return false;
    }
    let spread = |v: Vec<f64>| {
        let mut v = v;
        v.sort_by(f64::total_cmp);
        let steps: Vec<f64> = v.windows(2).map(|w| w[1] - w[0]).collect();
        let mean = steps.iter().sum::<f64>() / steps.len() as f64;
        let var = steps.iter().map(|d| (d - mean).powi(2)).sum::<f64>() / steps.len() as f64;
        var.sqrt() / mean
    };
    spread(values.iter().map(|v| v.log10()).collect()) < spread(values.to_vec())
}

/// Edges of cells centred on ascending `centres`, taken in log10 on a log axis.
fn cell_edges(centres: &[f64], log: bool) -> Vec<f64> {
    if log {
        let logged: Vec<f64> = centres.iter().map(|v| v.log10()).collect();
        edges(&logged).into_iter().map(|e| 10f64.powf(e)).collect()
    } else {
        edges(centres)
    }
}

/// One map: the cells coloured by class, overturned black, unsolved white with a grey cross,
/// and the boundary between overturned and standing cells.
fn map_panel(
    cells: &[Vec<MapCell>],
    xs: &[f64],
    ys: &[f64],
    x_label: &str,
    y_label: &str,
) -> Panel {
    // Cells in ascending order of both coordinates, whatever the order the axes were given in.
    let (ox, oy) = (ascending(xs), ascending(ys));
    let sorted = |v: &[f64], order: &[usize]| order.iter().map(|&i| v[i]).collect::<Vec<f64>>();
    let (log_x, log_y) = (log_scale(xs), log_scale(ys));
    let (ex, ey) = (
        cell_edges(&sorted(xs, &ox), log_x),
        cell_edges(&sorted(ys, &oy), log_y),
    );
    let cells: Vec<Vec<MapCell>> = ox
        .iter()
        .map(|&i| oy.iter().map(|&j| cells[i][j]).collect())
        .collect();
    let mut panel = Panel::new("", x_label, y_label);
    panel.log_x = log_x;
    panel.log_y = log_y;
    let color_of = |cell: &MapCell| match (cell.value, cell.overturned) {
        (_, true) => (0, 0, 0),
        (Some(v), false) => class_colour(v),
        (None, false) => MISSING,
    };
    for (i, column) in cells.iter().enumerate() {
        // A run of cells of one colour up a column is one rectangle (a file of 20,000
        // rectangles is slow to draw, write and open).
        let mut first = 0;
        for run in column.chunk_by(|a, b| color_of(a) == color_of(b)) {
            let end = first + run.len();
            panel.cells.push(plot::Cell {
                from: (ex[i], ey[first]),
                to: (ex[i + 1], ey[end]),
                rgb: color_of(&run[0]),
            });
            first = end;
        }
    }
    // Unsolved points: a grey cross.
    let mut crosses = Vec::new();
    for (i, column) in cells.iter().enumerate() {
        for (j, cell) in column.iter().enumerate() {
            if cell.value.is_none() && !cell.overturned {
                crosses.extend([(ex[i], ey[j]), (ex[i + 1], ey[j + 1]), (f64::NAN, f64::NAN)]);
            }
        }
    }
    if !crosses.is_empty() {
        panel = panel.with(Series::line("", crosses, 7).with_width(0.4));
    }
    // The boundary: every cell edge between an overturned and a standing cell, as edges between
    // corners (i, j) of the grid, joined end to end into lines (one drawn path per line, not
    // per edge: a map of a million cells has thousands of edges on its boundary).
    let mut edges: Vec<(Corner, Corner)> = Vec::new();
    for i in 0..cells.len() {
        for j in 0..cells[i].len() {
            let here = cells[i][j].overturned;
            if i + 1 < cells.len() && cells[i + 1][j].overturned != here {
                edges.push(((i + 1, j), (i + 1, j + 1)));
            }
            if j + 1 < cells[i].len() && cells[i][j + 1].overturned != here {
                edges.push(((i, j + 1), (i + 1, j + 1)));
            }
        }
    }
    let mut boundary = Vec::new();
    for line in join_edges(&edges) {
        boundary.extend(line.into_iter().map(|(i, j)| (ex[i], ey[j])));
        boundary.push((f64::NAN, f64::NAN));
    }
    if !boundary.is_empty() {
        panel =
            panel.with(Series::line("boundary of overturning", boundary, BOUNDARY).with_width(1.3));
    }
    panel
}

/// A corner of a map's grid: the indices of its cell edges across and up.
type Corner = (usize, usize);

/// The lines `edges` (pairs of corners) make, joined end to end: each edge once, in the order
/// found (at a corner where four edges meet, a line goes on along any of the others).
fn join_edges(edges: &[(Corner, Corner)]) -> Vec<Vec<Corner>> {
    let mut at: std::collections::HashMap<Corner, Vec<usize>> = Default::default();
    for (k, &(a, b)) in edges.iter().enumerate() {
        at.entry(a).or_default().push(k);
        at.entry(b).or_default().push(k);
    }
    let mut used = vec![false; edges.len()];
    let mut lines = Vec::new();
    for k in 0..edges.len() {
        if used[k] {
            continue;
        }
        used[k] = true;
        let mut line = std::collections::VecDeque::from([edges[k].0, edges[k].1]);
        // Grow the line at its end, then at its start.
        for forward in [true, false] {
            loop {
                let end = if forward {
                    line[line.len() - 1]
                } else {
                    line[0]
                };
                let next = at[&end].iter().copied().find(|&e| !used[e]);
                let Some(e) = next else { break };
                used[e] = true;
                let (a, b) = edges[e];
                let other = if a == end { b } else { a };
                if forward {
                    line.push_back(other);
                } else {
                    line.push_front(other);
                }
            }
        }
        lines.push(line.into_iter().collect());
    }
    lines
}

/// The spectrum of a minimum search over axis `x`.
fn spectrum(plan: &Plan, table: &SweepTable, x: usize) -> Result<Option<Figure>> {
    let Some(find) = &plan.find_min else {
        return Ok(None);
    };
    let min_column = table.column("min_overturning")?;
    let axis = &plan.axes[x];
    let mut physical = Vec::new();
    let mut scaled = Vec::new();
    let mut rigid_physical = Vec::new();
    let mut rigid_scaled = Vec::new();
    let dx = dimensionless(&axis.key);
    let x_scaled_column = match dx {
        Some((column, _)) => Some(table.column(column)?),
        None => None,
    };
    let y_scaled_column = table.column("amplitude_over_g_tan_alpha")?;
    let rigid_column = table.column("rigid_min_overturning")?;
    let rigid_scaled_column = table.column("rigid_amplitude_over_g_tan_alpha")?;
    let limit_column = table.column("rigid_limit_min_overturning")?;
    let limit_scaled_column = table.column("rigid_limit_amplitude_over_g_tan_alpha")?;
    let mut limit_physical = Vec::new();
    let mut limit_scaled = Vec::new();
    // Points solved without overturning up to HI: marked at HI, so that the figure does not
    // leave them out silently (dimensionless where a rigid block's columns give g tan alpha).
    let status_column = table.column("status")?;
    let mut stands_physical = Vec::new();
    let mut stands_scaled = Vec::new();
    // Where the sweep's axis is not a property of the body, g tan alpha is one number: that of
    // any row that has a value and its scaled value, for the rows where nothing overturned.
    let body_fixed = !(axis.key.starts_with("body.") || axis.key.starts_with("column."));
    let shared_g_tan_alpha = body_fixed
        .then(|| {
            (0..table.rows.len()).find_map(|r| {
                [
                    (min_column, y_scaled_column),
                    (rigid_column, rigid_scaled_column),
                    (limit_column, limit_scaled_column),
                ]
                .into_iter()
                .find_map(|(value, scaled)| {
                    Some(table.number(r, value)? / table.number(r, scaled)?)
                })
                .filter(|v| v.is_finite() && *v > 0.0)
            })
        })
        .flatten();
    // The elastic body's curve is broken where it stands: its line joins only values.
    let mut physical_breaks = Vec::new();
    for (r, row) in table.rows.iter().enumerate() {
        let point: usize = row[0].parse().unwrap_or(0);
        let Some(xv) = axis.number(plan.coordinates(point)[x]) else {
            continue;
        };
        let xs = x_scaled_column
            .and_then(|c| table.number(r, c))
            .unwrap_or(xv);
        if let Some(min) = table.number(r, min_column) {
            physical.push((xv, min));
            if let Some(s) = table.number(r, y_scaled_column) {
                scaled.push((xs, s));
            }
        } else if row[status_column] == *flexrock_core::analysis::sweep::Status::Ok.name() {
            stands_physical.push((xv, find.hi));
            let g_tan_alpha = [
                (rigid_column, rigid_scaled_column),
                (limit_column, limit_scaled_column),
            ]
            .into_iter()
            .find_map(|(value, scaled)| Some(table.number(r, value)? / table.number(r, scaled)?))
            .filter(|v| v.is_finite() && *v > 0.0)
            .or(shared_g_tan_alpha);
            if let Some(g_tan_alpha) = g_tan_alpha {
                stands_scaled.push((xs, find.hi / g_tan_alpha));
            }
            physical_breaks.push((xv, xs));
        }
        for (column, points, x) in [
            (rigid_column, &mut rigid_physical, xv),
            (rigid_scaled_column, &mut rigid_scaled, xs),
            (limit_column, &mut limit_physical, xv),
            (limit_scaled_column, &mut limit_scaled, xs),
        ] {
            if let Some(y) = table.number(r, column) {
                points.push((x, y));
            }
        }
    }
    let sort = |v: &mut Vec<(f64, f64)>| v.sort_by(|a, b| a.0.total_cmp(&b.0));
    for v in [
        &mut physical,
        &mut scaled,
        &mut rigid_physical,
        &mut rigid_scaled,
        &mut limit_physical,
        &mut limit_scaled,
        &mut stands_physical,
        &mut stands_scaled,
    ] {
        sort(v);
    }
    // A break (a point that is not drawn) in the elastic curve at each period where it stands.
    let broken = |mut curve: Vec<(f64, f64)>, at: &[f64]| {
        curve.extend(at.iter().map(|&x| (x, f64::NAN)));
        curve.sort_by(|a, b| a.0.total_cmp(&b.0));
        curve
    };
    let breaks_physical: Vec<f64> = physical_breaks.iter().map(|b| b.0).collect();
    let breaks_scaled: Vec<f64> = physical_breaks.iter().map(|b| b.1).collect();
    let physical = broken(physical, &breaks_physical);
    let scaled = broken(scaled, &breaks_scaled);
    let stands = format!(
        "stands up to {} (no overturning found)",
        crate::writers::significant(find.hi, 4)
    );
    let housner = housner_label(&find.housner());
    let limit = format!(
        "model's rigid limit: uplift at {:.3} g B/H",
        flexrock_core::physics::constants::ModeShapeIntegrals::exact().rigid_limit_uplift_factor()
    );
    // The two rigid curves nearly coincide: Housner's wide, orange and solid underneath, the
    // rigid limit thin, dashed and black on top of it, so that both show where they meet.
    let curves = |elastic: Vec<(f64, f64)>,
                  rigid: Vec<(f64, f64)>,
                  limit_curve: Vec<(f64, f64)>,
                  standing: Vec<(f64, f64)>| {
        let mut series = vec![
            Series::line(&housner, rigid, 4).with_width(2.4),
            Series::line(&limit, limit_curve, 0)
                .with_width(0.8)
                .with_dash(Dash::Dashed),
            Series::line("elastic body (this model)", elastic, 2)
                .with_width(1.1)
                .with_markers(),
        ];
        if !standing.is_empty() {
            series.push(Series::markers(
                &stands,
                standing,
                2,
                Marker::OpenTriangleUp,
            ));
        }
        series
    };
    // The periods on a log axis, as the literature draws spectra, when they span a factor of
    // three or more.
    let spans_decades = |v: &[(f64, f64)]| {
        let (lo, hi) = v.iter().fold((f64::INFINITY, 0.0f64), |(lo, hi), p| {
            (lo.min(p.0), hi.max(p.0))
        });
        lo > 0.0 && hi / lo >= 3.0
    };
    let log_left = spans_decades(&rigid_physical) || spans_decades(&physical);
    let log_right = spans_decades(&rigid_scaled) || spans_decades(&scaled);
    let mut left = Panel::new("", &axis_label(&axis.key), &axis_label(&find.key));
    left.series = curves(physical, rigid_physical, limit_physical, stands_physical);
    left.log_x = log_left;
    // A margin at both ends of the periods, so that the end markers (and a "stands" triangle at
    // the first period) sit inside the frame.
    left.pad_x = true;
    let mut panels = vec![left];
    if let Some((_, x_label)) = dx {
        let y_label = dimensionless(&find.key).map_or("aₚ/(g tan α)", |d| d.1);
        let mut right = Panel::new("", x_label, y_label);
        right.series = curves(scaled, rigid_scaled, limit_scaled, stands_scaled);
        right.log_x = log_right;
        right.pad_x = true;
        panels.push(right);
    }
    let columns = panels.len();
    Ok(Some(Figure::new(panels, columns).aspect(1.1, 40.0)))
}

/// The legend label of Housner's block, naming its equation and each choice made:
/// "Housner block, small-angle eq.", "Housner block, full eq., no return, e=0.825".
fn housner_label(options: &flexrock_core::analysis::sweep::HousnerOptions) -> String {
    let mut label = if options.form.is_small_angle() {
        "Housner block, small-angle eq.".to_string()
    } else {
        "Housner block, full eq.".to_string()
    };
    if !options.overturning.is_reaches_limit() {
        label.push_str(", no return");
    }
    if let Some(e) = options.restitution {
        label.push_str(&format!(", e={}", crate::writers::significant(e, 3)));
    }
    label
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Housner's block's legend label names its equation and how the block is made, with
    /// every choice made and a restitution of many digits.
    #[test]
    fn housners_label_names_its_equation_and_each_choice() {
        use flexrock_core::analysis::sweep::HousnerOptions;
        use flexrock_core::bodies::rigid::{RigidForm, RigidOverturning};
        let mut labels = Vec::new();
        for form in RigidForm::ALL {
            for overturning in RigidOverturning::ALL {
                for restitution in [None, Some(0.9), Some(0.824_559_3)] {
                    let options = HousnerOptions {
                        form,
                        overturning,
                        restitution,
                    };
                    let label = housner_label(&options);
                    assert!(label.chars().count() <= 52, "{label}");
                    assert_eq!(
                        label.contains("full eq."),
                        form == RigidForm::Full,
                        "{label}"
                    );
                    assert_eq!(
                        label.contains("small-angle eq."),
                        form != RigidForm::Full,
                        "{label}"
                    );
                    assert_eq!(
                        label.contains("no return"),
                        overturning == RigidOverturning::CannotReturn,
                        "{label}"
                    );
                    assert_eq!(label.contains("e="), restitution.is_some(), "{label}");
                    labels.push(label);
                }
            }
        }
        assert_eq!(labels[0], "Housner block, small-angle eq.");
        assert!(labels.contains(&"Housner block, full eq., no return, e=0.825".to_string()));
    }

    #[test]
    fn edges_are_finite_and_growing_for_extreme_but_allowed_values() {
        let m = flexrock_core::analysis::sweep::axis::MAX_MAGNITUDE;
        for centres in [
            vec![-m, m],
            vec![m / 2.0, m],
            vec![-m, 0.0, m],
            vec![0.5, 1.0, 2.0],
        ] {
            let e = edges(&centres);
            assert_eq!(e.len(), centres.len() + 1);
            assert!(e.iter().all(|x| x.is_finite()), "{centres:?}: {e:?}");
            assert!(e.windows(2).all(|w| w[0] < w[1]), "{centres:?}: {e:?}");
        }
        assert!(edges(&[]).is_empty());
        assert!(!drawable(&[]));
        assert!(!drawable(&[1.0, f64::INFINITY]));
    }

    #[test]
    fn values_are_drawn_in_ascending_order() {
        assert_eq!(ascending(&[1.0, 0.5, 2.0]), [1, 0, 2]);
        assert_eq!(ascending(&[3.0, f64::NAN, -1.0]), [2, 0, 1]);
    }
}
