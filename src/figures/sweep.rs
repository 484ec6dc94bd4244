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

use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, Pos, VPos};

use crate::commands::sweep::store::Counts;
use crate::error::{Error, Result};
use crate::figures::plot::{Legend, Marker, Panel, Series};
use flexrock_core::sweep::{Layout, Plan};

/// sweep.csv read back: its columns and rows of text.
pub struct SweepTable {
    /// Column names, from the header.
    pub columns: Vec<String>,
    /// The fields of each row, as text (one allocation per row: a map has many).
    pub rows: Vec<csv::StringRecord>,
    path: std::path::PathBuf,
}

impl SweepTable {
    /// The table of the rows `pieces` under `columns`: what a CSV reader finds in sweep.csv,
    /// the header and the pieces' text joined. A piece's fields are taken as they are where it
    /// has them (the text was written from them), else read from its text, the pieces in
    /// parallel; `path` names the table in messages.
    pub(crate) fn of_pieces(
        columns: &[String],
        pieces: &mut [crate::commands::sweep::store::Piece],
        path: &Path,
    ) -> Result<SweepTable> {
        use rayon::prelude::*;
        let read =
            |piece: &mut crate::commands::sweep::store::Piece| -> Result<Vec<csv::StringRecord>> {
                if let Some(records) = piece.records.take() {
                    return Ok(records);
                }
                csv::ReaderBuilder::new()
                    .has_headers(false)
                    .from_reader(piece.rows.as_slice())
                    .records()
                    .map(|record| {
                        let malformed = |message: String| Error::ReadResult {
                            path: path.to_path_buf(),
                            message: format!("a malformed row: {message}"),
                        };
                        let record = record.map_err(|e| malformed(e.to_string()))?;
                        if record.len() != columns.len() {
                            return Err(malformed(format!(
                                "{} fields under {} columns",
                                record.len(),
                                columns.len()
                            )));
                        }
                        Ok(record)
                    })
                    .collect()
            };
        let parts: Vec<Vec<csv::StringRecord>> =
            pieces.par_iter_mut().map(read).collect::<Result<_>>()?;
        Ok(SweepTable {
            columns: columns.to_vec(),
            rows: parts.into_iter().flatten().collect(),
            path: path.to_path_buf(),
        })
    }

    /// The index of a column.
    pub fn column(&self, name: &str) -> Result<usize> {
        self.columns
            .iter()
            .position(|c| c == name)
            .ok_or_else(|| Error::ReadResult {
                path: self.path.clone(),
                message: format!("has no column {name}"),
            })
    }

    /// A numeric field; None when empty or not a number.
    pub fn number(&self, row: usize, column: usize) -> Option<f64> {
        self.rows[row][column].parse().ok()
    }

    /// Counts of the rows by status, and of the points that overturned: for a minimum search,
    /// that overturned somewhere in the interval; for a row, where a column overturned.
    pub fn counts(&self, layout: Layout) -> Result<Counts> {
        let status = self.column("status")?;
        // Counted where the column is not empty (and, for runs, "true").
        let (overturned, any_value) = match layout {
            Layout::Runs => (self.column("overturned")?, false),
            Layout::Minimum(_) => (self.column("min_overturning")?, true),
            Layout::Row(_) => (self.column("overturned_column")?, true),
        };
        let find_min = any_value;
        let share = match layout {
            Layout::Runs => Some(self.column("energy_residual_share")?),
            _ => None,
        };
        let mut counts = Counts::default();
        for (r, row) in self.rows.iter().enumerate() {
            if share
                .and_then(|c| self.number(r, c))
                .is_some_and(|s| s > crate::commands::run::ENERGY_RESIDUAL_WARNING_SHARE)
            {
                counts.inaccurate += 1;
            }
            match &row[status] {
                "ok" => counts.ok += 1,
                "invalid" => counts.invalid += 1,
                _ => counts.failed += 1,
            }
            let over = &row[overturned];
            if (find_min && !over.is_empty()) || (!find_min && over == "true") {
                counts.overturned += 1;
            }
        }
        Ok(counts)
    }
}

/// The figures of a sweep, as (file name, SVG bytes).
pub fn figures(plan: &Plan, table: &SweepTable) -> Result<Vec<(String, Vec<u8>)>> {
    let numeric: Vec<usize> = (0..plan.axes.len())
        .filter(|&i| plan.axes[i].is_numeric())
        .collect();
    if let Some(n) = plan.row_columns {
        return match (plan.axes.len(), numeric.as_slice()) {
            (2, [x, y]) => crate::figures::sweep_row::verdict_maps(plan, table, n, *x, *y),
            _ => Ok(Vec::new()),
        };
    }
    match (&plan.find_min, plan.axes.len(), numeric.as_slice()) {
        (None, 2, [x, y]) => Ok(map(plan, table, *x, *y)?
            .map(|svg| ("map.svg".to_string(), svg))
            .into_iter()
            .collect()),
        (Some(_), 1, [x]) => Ok(vec![(
            "spectrum.svg".to_string(),
            spectrum(plan, table, *x)?,
        )]),
        // Incremental dynamic analysis: records against an intensity, or one record's scale.
        (None, 1 | 2, [x]) if is_ida(plan, *x) => {
            Ok(vec![(IDA_FILE.to_string(), ida(plan, table, *x)?)])
        }
        _ => Ok(Vec::new()),
    }
}

/// The figure of a sweep over records and an intensity (incremental dynamic analysis).
pub const IDA_FILE: &str = "ida.svg";
/// The maps of a row sweep over two numeric axes: each column's verdict.
pub const VERDICTS_SVG: &str = "verdicts.svg";
/// The same maps as PNG.
pub const VERDICTS_PNG: &str = "verdicts.png";

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

/// The short name of a record file: its file name.
fn record_name(path: &str) -> String {
    Path::new(path)
        .file_name()
        .map_or_else(|| path.to_string(), |n| n.to_string_lossy().into_owned())
}

/// Incremental dynamic analysis: max |q|/B against the intensity axis `x`, one line per value of
/// the other axis (a record, or any other setting), overturned points marked with a cross in the
/// record's colour at |q|/B = 1, where the line of that record ends.
fn ida(plan: &Plan, table: &SweepTable, x: usize) -> Result<Vec<u8>> {
    let q_column = table.column("max_abs_q_over_B")?;
    let over_column = table.column("overturned")?;
    let other = (0..plan.axes.len()).find(|&i| i != x);
    let groups = other.map_or(1, |o| plan.axes[o].len());
    // (intensity, max |q|/B, overturned) per group.
    let mut points: Vec<Vec<(f64, f64, bool)>> = vec![Vec::new(); groups];
    for (r, row) in table.rows.iter().enumerate() {
        let point = point_of(table, r, row)?;
        let c = plan.coordinates(point);
        let Some(xv) = plan.axes[x].number(c[x]) else {
            continue;
        };
        let overturned = &row[over_column] == "true";
        let value = table.number(r, q_column);
        let g = other.map_or(0, |o| c[o]);
        match (overturned, value) {
            (true, _) => points[g].push((xv, 1.0, true)),
            (false, Some(v)) => points[g].push((xv, v, false)),
            (false, None) => {}
        }
    }
    let mut panel = Panel::new(
        "Incremental dynamic analysis",
        &axis_label(&plan.axes[x].key),
        "max |q| / B",
    );
    let mut crosses = Vec::new();
    for (g, mut group) in points.into_iter().enumerate() {
        group.sort_by(|a, b| a.0.total_cmp(&b.0));
        // The line up to the first overturning point; the points beyond it overturn too, or
        // (rarely, resurrection) stand again: those are drawn as markers only.
        let first_over = group.iter().position(|p| p.2);
        let upto = first_over.map_or(group.len(), |i| i + 1);
        let line: Vec<(f64, f64)> = group[..upto].iter().map(|p| (p.0, p.1)).collect();
        let name = match other {
            Some(o) if plan.axes[o].key == "excitation.path" => {
                record_name(&plan.axes[o].values[g])
            }
            Some(o) => format!(
                "{} = {}",
                axis_label(&plan.axes[o].key),
                plan.axes[o].values[g]
            ),
            None => "max |q| / B".to_string(),
        };
        // Palette colours 1..7 (0, black, is for references), with a marker shape per line.
        let color = 1 + g % 7;
        panel = panel.with(
            Series::line(&name, line, color)
                .with_width(2)
                .with_markers(),
        );
        let beyond: Vec<(f64, f64)> = group[upto..]
            .iter()
            .filter(|p| !p.2)
            .map(|p| (p.0, p.1))
            .collect();
        if !beyond.is_empty() {
            panel = panel.with(Series::markers("", beyond, color, Marker::Circle));
        }
        let over: Vec<(f64, f64)> = group.iter().filter(|p| p.2).map(|p| (p.0, p.1)).collect();
        crosses.extend(over.iter().copied());
        if !over.is_empty() {
            panel = panel.with(Series::markers("", over, color, Marker::Cross));
        }
    }
    if !crosses.is_empty() {
        // The legend's entry for the crosses, in black; drawn first, each under the cross in
        // its record's colour.
        panel
            .series
            .insert(0, Series::markers("overturned", crosses, 0, Marker::Cross));
    }
    panel.dashed_lines = vec![(1.0, "|q| = B".to_string())];
    panel.legend = Legend::Outside;
    crate::figures::plot::figure(IDA_FILE, &[panel], 1, (1100, 600)).map(String::into_bytes)
}

/// The dimensionless column that stands for an axis, and its label.
fn dimensionless(key: &str) -> Option<(&'static str, &'static str)> {
    match key {
        "excitation.amplitude" => Some(("amplitude_over_g_tan_alpha", "a_p / (g tan α)")),
        "excitation.scale" => Some(("amplitude_over_g_tan_alpha", "PFA / (g tan α)")),
        "excitation.period" => Some(("omega_p_over_p", "ω_p / p")),
        _ => None,
    }
}

/// The axis label of a model-file key: the quantity's symbol and unit (the key itself for a key
/// without one here).
pub fn axis_label(key: &str) -> String {
    let label = match key {
        "excitation.amplitude" => "a_p (m/s²)",
        "excitation.period" => "T_p (s)",
        "excitation.scale" => "scale factor",
        "excitation.cycles" => "cycles",
        "excitation.start" => "t_start (s)",
        "excitation.ramp" => "t_ramp (s)",
        "body.height" => "H (m)",
        "body.width" => "B (m)",
        "body.depth" => "depth (m)",
        "body.period" => "T (s)",
        "body.damping_ratio" => "h",
        "body.youngs_modulus" => "E (Pa)",
        "body.flexural_rigidity" => "EI (N m²)",
        "body.density" => "ρ (kg/m³)",
        "body.mass" => "mass (kg)",
        "body.poisson_ratio" => "ν",
        "body.gravity" => "g (m/s²)",
        "solver.dt" => "Δt (s)",
        "solver.rtol" => "rtol",
        "row.gaps" => "gap g, every gap (m)",
        "row.restitution" => "restitution e",
        "row.stiffness" => "contact stiffness k (N/m)",
        "simulation.duration" => "duration (s)",
        _ => return row_key_label(key).unwrap_or_else(|| key.to_string()),
    };
    label.to_string()
}

/// The label of a key of a row: one gap (`row.gaps.I`), a column's key (`column.I.KEY`) or
/// every column's (`column.KEY`), by the label of the body's key.
fn row_key_label(key: &str) -> Option<String> {
    let parts: Vec<&str> = key.split('.').collect();
    let body = |name: &str| {
        let label = axis_label(&format!("body.{name}"));
        (!label.starts_with("body.")).then_some(label)
    };
    let with_unit = |label: &str, suffix: &str| match label.split_once(" (") {
        Some((symbol, unit)) => format!("{symbol}{suffix} ({unit}"),
        None => format!("{label}{suffix}"),
    };
    match parts.as_slice() {
        ["row", "gaps", i] => Some(format!("gap g{} (m)", subscript(i))),
        ["column", i, name] => Some(match (body(name), *name) {
            (Some(label), _) => with_unit(&label, &subscript(i)),
            (None, "q0") => format!("q0 of column {i} (m)"),
            (None, "qdot0") => format!("q'0 of column {i} (m/s)"),
            (None, _) => key.to_string(),
        }),
        ["column", name] => body(name).map(|label| with_unit(&label, ", every column")),
        _ => None,
    }
}

/// A column's or gap's index as subscript digits.
fn subscript(index: &str) -> String {
    index
        .chars()
        .map(|c| match c.to_digit(10) {
            Some(d) => char::from_u32(0x2080 + d).unwrap_or(c),
            None => c,
        })
        .collect()
}

/// The colour of max |q|/B in [0, 1]: a perceptually ordered ramp (dark blue, teal, yellow).
fn colour(value: f64) -> RGBColor {
    const STOPS: [(f64, [f64; 3]); 5] = [
        (0.0, [68.0, 1.0, 84.0]),
        (0.25, [59.0, 82.0, 139.0]),
        (0.5, [33.0, 145.0, 140.0]),
        (0.75, [94.0, 201.0, 98.0]),
        (1.0, [253.0, 231.0, 37.0]),
    ];
    let v = value.clamp(0.0, 1.0);
    let i = STOPS
        .windows(2)
        .position(|w| v <= w[1].0)
        .unwrap_or(STOPS.len() - 2);
    let ((a, ca), (b, cb)) = (STOPS[i], STOPS[i + 1]);
    let f = if b > a { (v - a) / (b - a) } else { 0.0 };
    let mix = |k: usize| (ca[k] + f * (cb[k] - ca[k])).round() as u8;
    RGBColor(mix(0), mix(1), mix(2))
}

/// One map cell.
#[derive(Clone, Copy)]
struct Cell {
    /// Value of max |q|/B; None for an invalid or failed point.
    value: Option<f64>,
    overturned: bool,
}

/// Edges of cells centred on ascending `centres`: midpoints, the ends extended by half a cell.
/// Written so that no intermediate sum overflows; empty for no centres.
pub(crate) fn edges(centres: &[f64]) -> Vec<f64> {
    let n = centres.len();
    match n {
        0 => return Vec::new(),
        1 => {
            let half = 0.5 * centres[0].abs().max(1e-12) * 0.1;
            return vec![centres[0] - half, centres[0] + half];
        }
        _ => {}
    }
    let half_step = |a: f64, b: f64| 0.5 * b - 0.5 * a;
    let mut e = Vec::with_capacity(n + 1);
    e.push(centres[0] - half_step(centres[0], centres[1]));
    for w in centres.windows(2) {
        e.push(0.5 * w[0] + 0.5 * w[1]);
    }
    e.push(centres[n - 1] + half_step(centres[n - 2], centres[n - 1]));
    e
}

/// The indices of `values` in ascending order of value (NaN last).
pub(crate) fn ascending(values: &[f64]) -> Vec<usize> {
    let mut order: Vec<usize> = (0..values.len()).collect();
    order.sort_by(|&a, &b| values[a].total_cmp(&values[b]));
    order
}

/// True when cells around `values` can be drawn: finite, distinct, and edges that grow.
pub(crate) fn drawable(values: &[f64]) -> bool {
    let sorted: Vec<f64> = ascending(values).iter().map(|&i| values[i]).collect();
    let e = edges(&sorted);
    !e.is_empty() && e.iter().all(|x| x.is_finite()) && e.windows(2).all(|w| w[0] < w[1])
}

/// The point number of row `r` (its first field).
fn point_of(table: &SweepTable, r: usize, row: &csv::StringRecord) -> Result<usize> {
    row[0].parse().map_err(|_| Error::ReadResult {
        path: table.path.clone(),
        message: format!("row {} has no point number", r + 1),
    })
}

fn plot_error(e: impl std::fmt::Display) -> Error {
    Error::Plot {
        name: "map.svg".to_string(),
        message: e.to_string(),
    }
}

/// The map over axes `x` and `y` (indices into the plan's axes).
/// None when the axes cannot be drawn as cells (values too close to tell apart in the figure's
/// arithmetic).
fn map(plan: &Plan, table: &SweepTable, x: usize, y: usize) -> Result<Option<Vec<u8>>> {
    let (nx, ny) = (plan.axes[x].len(), plan.axes[y].len());
    let q_column = table.column("max_abs_q_over_B")?;
    let over_column = table.column("overturned")?;
    let mut cells = vec![
        vec![
            Cell {
                value: None,
                overturned: false
            };
            ny
        ];
        nx
    ];
    for (r, row) in table.rows.iter().enumerate() {
        let point = point_of(table, r, row)?;
        let c = plan.coordinates(point);
        cells[c[x]][c[y]] = Cell {
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

    let panel = (720u32, 600u32);
    let legend_width = 170u32;
    let width = panel.0 * views.len() as u32 + legend_width;
    let titles = ["Peak response", "Peak response, dimensionless"];
    let mut svg = String::new();
    {
        crate::figures::plot::register_fonts();
        let root = SVGBackend::with_string(&mut svg, (width, panel.1)).into_drawing_area();
        root.fill(&WHITE).map_err(plot_error)?;
        let (maps, bar) = root.split_horizontally(panel.0 * views.len() as u32);
        let areas = maps.split_evenly((1, views.len()));
        for (((xs, x_label, ys, y_label), area), title) in
            views.iter().zip(areas.iter()).zip(titles)
        {
            draw_map(area, &cells, xs, ys, x_label, y_label, title).map_err(plot_error)?;
        }
        draw_colour_bar(&bar).map_err(plot_error)?;
        root.present().map_err(plot_error)?;
    }
    Ok(Some(svg.into_bytes()))
}

type Area<'a> = DrawingArea<SVGBackend<'a>, plotters::coord::Shift>;

/// Font sizes, as in the figures of crate::figures::plot.
const TITLE_FONT: u32 = 26;
const AXIS_FONT: u32 = 22;
const TICK_FONT: u32 = 20;
/// The boundary between overturned and standing cells.
const BOUNDARY: RGBColor = RGBColor(220, 30, 30);

/// Fills the rectangle between two corners given in pixels of `area` (any order), one pixel
/// wider and taller on the right and bottom, so that neighbouring cells overlap and no hairline
/// of the background shows between them in any viewer or zoom; clipped to `limit` (width,
/// height).
pub(crate) fn fill_cell<DB: DrawingBackend>(
    area: &DrawingArea<DB, plotters::coord::Shift>,
    (xa, ya): (i32, i32),
    (xb, yb): (i32, i32),
    limit: (i32, i32),
    color: RGBColor,
) -> std::result::Result<[(i32, i32); 2], Box<dyn std::error::Error>>
where
    DB::ErrorType: 'static,
{
    let (left, right) = (xa.min(xb), (xa.max(xb) + 1).min(limit.0));
    let (top, bottom) = (ya.min(yb), (ya.max(yb) + 1).min(limit.1));
    area.draw(&Rectangle::new(
        [(left, top), (right, bottom)],
        color.filled(),
    ))?;
    Ok([(left, top), (right, bottom)])
}

fn draw_map(
    area: &Area<'_>,
    cells: &[Vec<Cell>],
    xs: &[f64],
    ys: &[f64],
    x_label: &str,
    y_label: &str,
    title: &str,
) -> std::result::Result<(), Box<dyn std::error::Error>> {
    // Cells in ascending order of both coordinates, whatever the order the axes were given in.
    let (ox, oy) = (ascending(xs), ascending(ys));
    let sorted = |v: &[f64], order: &[usize]| order.iter().map(|&i| v[i]).collect::<Vec<f64>>();
    let (ex, ey) = (edges(&sorted(xs, &ox)), edges(&sorted(ys, &oy)));
    let cells: Vec<Vec<Cell>> = ox
        .iter()
        .map(|&i| oy.iter().map(|&j| cells[i][j]).collect())
        .collect();
    let range = |e: &[f64]| e[0]..e[e.len() - 1];
    let mut chart = ChartBuilder::on(area)
        .caption(title, ("sans-serif", TITLE_FONT))
        .margin(14)
        .x_label_area_size(60)
        .y_label_area_size(96)
        .build_cartesian_2d(range(&ex), range(&ey))?;
    chart
        .configure_mesh()
        .disable_mesh()
        .x_desc(x_label)
        .y_desc(y_label)
        .label_style(("sans-serif", TICK_FONT))
        .axis_desc_style(("sans-serif", AXIS_FONT))
        .draw()?;
    // The cells in pixels of the plotting area, overlapping by a pixel (no seams).
    let plotting = chart.plotting_area();
    let (xr, yr) = plotting.get_pixel_range();
    let limit = (xr.end - xr.start, yr.end - yr.start);
    let pixels = plotting.strip_coord_spec();
    let at = |x: f64, y: f64| {
        let (a, b) = plotting.map_coordinate(&(x, y));
        (a - xr.start, b - yr.start)
    };
    let color_of = |cell: &Cell| match (cell.value, cell.overturned) {
        (_, true) => BLACK,
        (Some(v), false) => colour(v),
        (None, false) => WHITE,
    };
    for (i, column) in cells.iter().enumerate() {
        // A run of cells of one colour up a column is one rectangle (the same pixels: the
        // overturned cells of a map are often most of it, and a file of 20,000 rectangles is
        // slow to draw, write and open).
        let mut first = 0;
        for run in column.chunk_by(|a, b| color_of(a) == color_of(b)) {
            let end = first + run.len();
            fill_cell(
                &pixels,
                at(ex[i], ey[first]),
                at(ex[i + 1], ey[end]),
                limit,
                color_of(&run[0]),
            )?;
            first = end;
        }
    }
    // Invalid or failed points: a grey cross.
    let grey = RGBColor(140, 140, 140);
    for (i, column) in cells.iter().enumerate() {
        for (j, cell) in column.iter().enumerate() {
            if cell.value.is_none() && !cell.overturned {
                chart.draw_series(std::iter::once(PathElement::new(
                    vec![(ex[i], ey[j]), (ex[i + 1], ey[j + 1])],
                    grey.stroke_width(1),
                )))?;
            }
        }
    }
    // The boundary: every cell edge between an overturned and a standing cell.
    let red = BOUNDARY.stroke_width(3);
    let mut boundary = Vec::new();
    for i in 0..cells.len() {
        for j in 0..cells[i].len() {
            let here = cells[i][j].overturned;
            if i + 1 < cells.len() && cells[i + 1][j].overturned != here {
                boundary.push(vec![(ex[i + 1], ey[j]), (ex[i + 1], ey[j + 1])]);
            }
            if j + 1 < cells[i].len() && cells[i][j + 1].overturned != here {
                boundary.push(vec![(ex[i], ey[j + 1]), (ex[i + 1], ey[j + 1])]);
            }
        }
    }
    chart.draw_series(boundary.into_iter().map(|p| PathElement::new(p, red)))?;
    Ok(())
}

/// The colour bar of max |q|/B, labelled, with the key to the overturned cells and their
/// boundary below it.
fn draw_colour_bar(area: &Area<'_>) -> std::result::Result<(), Box<dyn std::error::Error>> {
    // Drawn in pixels: the bar, its ticks and values on the right, the label beside them
    // (reading upwards), and below it the key to the overturned cells and their boundary.
    let (_, height) = area.dim_in_pixel();
    let (left, right) = (12, 36);
    let (top, bottom) = (74, height as i32 - 130);
    let span = f64::from(bottom - top);
    let y_of = |v: f64| bottom - (v * span).round() as i32;
    let steps = 100;
    for k in 0..steps {
        let (a, b) = (k as f64 / steps as f64, (k + 1) as f64 / steps as f64);
        // One pixel taller than the step: neighbours overlap, no seams.
        area.draw(&Rectangle::new(
            [(left, y_of(b)), (right, y_of(a) + 1)],
            colour(0.5 * (a + b)).filled(),
        ))?;
    }
    area.draw(&Rectangle::new(
        [(left, top), (right, bottom + 1)],
        BLACK.stroke_width(1),
    ))?;
    let tick_font = ("sans-serif", TICK_FONT).into_font().color(&BLACK);
    for i in 0..=5 {
        let v = f64::from(i) / 5.0;
        let y = y_of(v);
        area.draw(&PathElement::new(
            vec![(right, y), (right + 5, y)],
            BLACK.stroke_width(1),
        ))?;
        area.draw(&Text::new(
            format!("{v:.1}"),
            (right + 9, y),
            tick_font.pos(Pos::new(HPos::Left, VPos::Center)),
        ))?;
    }
    let label_font = ("sans-serif", AXIS_FONT)
        .into_font()
        .transform(FontTransform::Rotate270)
        .color(&BLACK);
    area.draw(&Text::new(
        "max |q| / B",
        (right + 64, (top + bottom) / 2),
        label_font.pos(Pos::new(HPos::Center, VPos::Center)),
    ))?;
    let font = ("sans-serif", TICK_FONT).into_font().color(&BLACK);
    let y = bottom + 40;
    area.draw(&Rectangle::new(
        [(left, y), (left + 22, y + 22)],
        BLACK.filled(),
    ))?;
    area.draw(&Text::new(
        "overturned",
        (left + 30, y + 11),
        font.pos(Pos::new(HPos::Left, VPos::Center)),
    ))?;
    area.draw(&PathElement::new(
        vec![(left, y + 48), (left + 22, y + 48)],
        BOUNDARY.stroke_width(3),
    ))?;
    area.draw(&Text::new(
        "boundary",
        (left + 30, y + 48),
        font.pos(Pos::new(HPos::Left, VPos::Center)),
    ))?;
    Ok(())
}

/// The spectrum of a minimum search over axis `x`.
fn spectrum(plan: &Plan, table: &SweepTable, x: usize) -> Result<Vec<u8>> {
    let Some(find) = &plan.find_min else {
        return Ok(Vec::new());
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
        } else if row[status_column] == *flexrock_core::sweep::Status::Ok.name() {
            stands_physical.push((xv, find.hi));
            let g_tan_alpha = [
                (rigid_column, rigid_scaled_column),
                (limit_column, limit_scaled_column),
            ]
            .into_iter()
            .find_map(|(value, scaled)| Some(table.number(r, value)? / table.number(r, scaled)?));
            if let Some(g_tan_alpha) = g_tan_alpha.filter(|v| v.is_finite() && *v > 0.0) {
                stands_scaled.push((xs, find.hi / g_tan_alpha));
            }
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
    let stands = format!(
        "elastic body stands up to {}",
        crate::writers::significant(find.hi, 4)
    );
    let housner = housner_label(&find.housner());
    let limit = format!(
        "rigid limit ({:.3} g B/H)",
        flexrock_core::constants::ModeShapeIntegrals::exact().rigid_limit_uplift_factor()
    );
    // The two rigid curves nearly coincide: Housner's wide and solid underneath, the rigid
    // limit dashed on top of it, so that both show.
    let curves = |elastic: Vec<(f64, f64)>,
                  rigid: Vec<(f64, f64)>,
                  limit_curve: Vec<(f64, f64)>,
                  standing: Vec<(f64, f64)>| {
        let mut series = vec![
            Series::line(&housner, rigid, 1).with_width(4),
            Series::line(&limit, limit_curve, 5).with_width(2).dashed(),
            Series::line("elastic body", elastic, 2)
                .with_width(2)
                .with_markers(),
        ];
        if !standing.is_empty() {
            series.push(Series::markers(&stands, standing, 2, Marker::TriangleUp));
        }
        series
    };
    let quantity = match find.key.as_str() {
        "excitation.amplitude" => "amplitude",
        "excitation.scale" => "scale factor",
        _ => "value",
    };
    let title = format!("Smallest overturning {quantity}");
    let mut left = Panel::new(&title, &axis_label(&axis.key), &axis_label(&find.key));
    left.series = curves(physical, rigid_physical, limit_physical, stands_physical);
    left.legend = Legend::Outside;
    // A margin at both ends of the periods, so that the end markers (and a "stands" triangle at
    // the first period) sit inside the frame.
    left.pad_x = true;
    let mut panels = vec![left];
    if let Some((_, x_label)) = dx {
        let y_label = dimensionless(&find.key).map_or("a_p / (g tan α)", |d| d.1);
        let mut right = Panel::new(&format!("{title}, dimensionless"), x_label, y_label);
        right.series = curves(scaled, rigid_scaled, limit_scaled, stands_scaled);
        right.legend = Legend::Outside;
        right.pad_x = true;
        panels.push(right);
    }
    crate::figures::plot::figure("spectrum.svg", &panels, 1, (1000, 480)).map(String::into_bytes)
}

/// The legend label of Housner's block: "rigid block (Housner)" for the default block, else
/// how it is made, in at most 33 characters, so that the legend strip widens little for it:
/// "Housner, full equation", "Housner, full, no return, e=0.825".
fn housner_label(options: &flexrock_core::sweep::HousnerOptions) -> String {
    let full = !options.form.is_small_angle();
    let no_return = !options.overturning.is_reaches_limit();
    let mut tags = Vec::new();
    match (full, no_return || options.restitution.is_some()) {
        (true, false) => tags.push("full equation".to_string()),
        (true, true) => tags.push("full".to_string()),
        (false, _) => {}
    }
    if no_return {
        tags.push("no return".to_string());
    }
    if let Some(e) = options.restitution {
        tags.push(format!("e={}", crate::writers::significant(e, 3)));
    }
    if tags.is_empty() {
        "rigid block (Housner)".to_string()
    } else {
        format!("Housner, {}", tags.join(", "))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Housner's block's legend label says how the block is made, in at most 33 characters
    /// with every choice made and a restitution of many digits.
    #[test]
    fn housners_label_names_each_choice_and_fits_the_strip() {
        use flexrock_core::rigid::{RigidForm, RigidOverturning};
        use flexrock_core::sweep::HousnerOptions;
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
                    assert!(label.chars().count() <= 33, "{label}");
                    assert_eq!(label.contains("full"), form == RigidForm::Full, "{label}");
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
        assert_eq!(labels[0], "rigid block (Housner)");
        assert!(labels.contains(&"Housner, full equation".to_string()));
        assert!(labels.contains(&"Housner, full, no return, e=0.825".to_string()));
    }

    #[test]
    fn edges_are_finite_and_growing_for_extreme_but_allowed_values() {
        let m = flexrock_core::sweep::axis::MAX_MAGNITUDE;
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
