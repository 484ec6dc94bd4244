//! SVG figures from series of points. Knows nothing about solvers or models: callers hand it
//! panels of named (x, y) series and get the SVG text back, to be written atomically.

use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, Pos, VPos};

use crate::error::{Error, Result};

/// One line of a panel.
#[derive(Debug, Clone)]
pub struct Series {
    /// The legend text.
    pub name: String,
    /// The (x, y) points, in drawing order.
    pub points: Vec<(f64, f64)>,
    /// Index into the palette; 0 is black (for references). An empty name keeps the series out
    /// of the legend.
    pub color: usize,
    /// A marker at every point (for convergence studies with few points, or for events).
    pub marker: Option<Marker>,
    /// Join the points by a line (false: markers only).
    pub line: bool,
    /// Line width in pixels [default: 2 for color 0, else 1].
    pub width: Option<u32>,
}

/// The shape of a series' markers.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Marker {
    /// A filled circle.
    Circle,
    /// A filled triangle pointing up.
    TriangleUp,
    /// A filled triangle pointing down.
    TriangleDown,
    /// A diagonal cross.
    Cross,
}

impl Series {
    /// A line through `points` in palette colour `color`, without markers.
    pub fn line(name: &str, points: Vec<(f64, f64)>, color: usize) -> Self {
        Series {
            name: name.to_string(),
            points,
            color,
            marker: None,
            line: true,
            width: None,
        }
    }

    /// Markers only, no line.
    pub fn markers(name: &str, points: Vec<(f64, f64)>, color: usize, marker: Marker) -> Self {
        Series {
            marker: Some(marker),
            line: false,
            ..Series::line(name, points, color)
        }
    }

    /// Draw circles at the points as well.
    pub fn with_markers(mut self) -> Self {
        self.marker = Some(Marker::Circle);
        self
    }

    /// The series drawn `width` pixels wide.
    pub fn with_width(mut self, width: u32) -> Self {
        self.width = Some(width);
        self
    }

    fn stroke_width(&self) -> u32 {
        self.width.unwrap_or(if self.color == 0 { 2 } else { 1 })
    }
}

/// One chart of a figure.
#[derive(Debug, Clone, Default)]
pub struct Panel {
    /// The title above the chart.
    pub title: String,
    /// The x axis label.
    pub x_label: String,
    /// The y axis label.
    pub y_label: String,
    /// The series, drawn in order.
    pub series: Vec<Series>,
    /// Logarithmic axes (decades); non-positive values are left out.
    pub log_x: bool,
    /// Logarithmic y axis (decades); non-positive values are left out.
    pub log_y: bool,
    /// Where the legend goes, so that it hides no data.
    pub legend: Legend,
    /// Same length per unit on both axes (drawings of shapes).
    pub equal_aspect: bool,
    /// Horizontal lines drawn in grey (e.g. +-s_n), with their legend text (empty: none).
    pub reference_lines: Vec<(f64, String)>,
    /// Horizontal dashed lines in dark grey (e.g. the overturning limit +-B), with their legend
    /// text (empty: none).
    pub dashed_lines: Vec<(f64, String)>,
}

impl Panel {
    /// An empty panel with a title and axis labels.
    pub fn new(title: &str, x_label: &str, y_label: &str) -> Self {
        Panel {
            title: title.to_string(),
            x_label: x_label.to_string(),
            y_label: y_label.to_string(),
            ..Panel::default()
        }
    }

    /// The panel with `series` added.
    pub fn with(mut self, series: Series) -> Self {
        self.series.push(series);
        self
    }
}

/// Where a panel's legend goes: a corner inside the plotting area (choose one the data leave
/// free), or a strip to the right of it, where it cannot cover any curve.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub enum Legend {
    #[default]
    /// Inside, upper right corner.
    UpperRight,
    /// Inside, lower right corner.
    LowerRight,
    /// Inside, upper left corner.
    UpperLeft,
    /// Inside, lower left corner.
    LowerLeft,
    /// In a strip of [`LEGEND_STRIP`] pixels right of the plotting area. The strip is kept even
    /// when the panel has nothing to list, so that panels stacked in one column share their
    /// x axis.
    Outside,
}

/// Width of the legend strip of [`Legend::Outside`], pixels (about 26 characters of the legend
/// font; longer labels run off the figure).
pub const LEGEND_STRIP: u32 = 300;

const PALETTE: [RGBColor; 8] = [
    RGBColor(0, 0, 0),
    RGBColor(214, 39, 40),
    RGBColor(31, 119, 180),
    RGBColor(44, 160, 44),
    RGBColor(255, 127, 14),
    RGBColor(148, 103, 189),
    RGBColor(140, 86, 75),
    RGBColor(23, 190, 207),
];

/// Draws `panels` in a grid of `columns` columns, each panel `size` pixels; returns the SVG text.
pub fn figure(name: &str, panels: &[Panel], columns: usize, size: (u32, u32)) -> Result<String> {
    let columns = columns.max(1);
    let rows = panels.len().div_ceil(columns).max(1);
    let mut svg = String::new();
    {
        let root =
            SVGBackend::with_string(&mut svg, (size.0 * columns as u32, size.1 * rows as u32))
                .into_drawing_area();
        let fail = |e: &dyn std::fmt::Display| Error::Plot {
            name: name.to_string(),
            message: e.to_string(),
        };
        root.fill(&WHITE).map_err(|e| fail(&e))?;
        let areas = root.split_evenly((rows, columns));
        for (panel, area) in panels.iter().zip(areas.iter()) {
            draw_panel(panel, area).map_err(|e| fail(&e))?;
        }
        root.present().map_err(|e| fail(&e))?;
    }
    Ok(svg)
}

type Area<'a> = DrawingArea<SVGBackend<'a>, plotters::coord::Shift>;
/// One unbroken stretch of a curve, in drawing coordinates.
type Polyline = Vec<(f64, f64)>;

const MARGIN: u32 = 12;
const X_LABEL_AREA: u32 = 60;
const Y_LABEL_AREA: u32 = 104;
/// Height of the title line, for the equal-aspect layout.
const CAPTION: u32 = 38;
/// Font sizes as plotters takes them (the SVG gets 0.81 of these in pixels). A figure of 1150
/// pixels across printed 16 cm wide gives the tick labels and legends about 6.5 pt and the
/// titles about 8.5 pt; printed at half a page wide, use a figure of fewer panels across.
const TITLE_FONT: u32 = 26;
const AXIS_FONT: u32 = 22;
const TICK_FONT: u32 = 20;
const LEGEND_FONT: u32 = 20;
/// Marker size, pixels (half the width of a marker).
const MARKER_SIZE: i32 = 5;

/// What a legend shows for one entry.
#[derive(Clone, Copy)]
enum Swatch {
    Line(RGBColor, u32),
    Dashed(RGBColor),
    Marker(RGBColor, Marker),
}

/// Draws markers of `shape` centred on `points` (in the coordinates of `area`). Each shape is
/// an element of its own type: plotters cannot draw boxed elements whose backend borrows.
fn draw_markers<DB: DrawingBackend, CT: plotters::coord::CoordTranslate>(
    area: &DrawingArea<DB, CT>,
    points: &[CT::From],
    shape: Marker,
    color: RGBColor,
) -> std::result::Result<(), DrawingAreaErrorKind<DB::ErrorType>>
where
    CT::From: Clone,
{
    let r = MARKER_SIZE;
    let filled = color.filled();
    for p in points {
        let at = EmptyElement::at(p.clone());
        match shape {
            Marker::Circle => area.draw(&(at + Circle::new((0, 0), r - 1, filled)))?,
            Marker::TriangleUp => {
                area.draw(&(at + Polygon::new(vec![(0, -r - 1), (r, r - 1), (-r, r - 1)], filled)))?
            }
            Marker::TriangleDown => area
                .draw(&(at + Polygon::new(vec![(0, r + 1), (r, -r + 1), (-r, -r + 1)], filled)))?,
            Marker::Cross => area.draw(
                &(at + PathElement::new(vec![(-r, -r), (r, r)], color.stroke_width(2))
                    + PathElement::new(vec![(-r, r), (r, -r)], color.stroke_width(2))),
            )?,
        }
    }
    Ok(())
}

/// Thins a curve for drawing on a plotting area `pixels` wide and high whose axes span `x`
/// and `y`, so that a history of a million rows does not become an SVG of hundreds of
/// megabytes, and keeps what the eye sees, peaks included:
///
/// - a curve whose x never decreases (a time series) keeps, in each pixel column, its first
///   and last point and its lowest and highest one (min/max per pixel column): every peak
///   stays exactly, and at most four points per column remain;
/// - any other curve (F(q), q against r) keeps a point only if it lies in another pixel than
///   the last point kept, and leaves out a stretch between two pixels that it drew already
///   (a path that retraces itself, as the model's curves of q do): the drawing is the same to a
///   pixel, and the extremes stay within a pixel of where they were.
///
/// Curves of at most four points per pixel column are returned as they are.
pub fn decimate(
    points: &[(f64, f64)],
    x: (f64, f64),
    y: (f64, f64),
    pixels: (u32, u32),
) -> Vec<Polyline> {
    let columns = pixels.0.max(1) as usize;
    if points.len() <= 4 * columns {
        return vec![points.to_vec()];
    }
    let monotone = points.windows(2).all(|w| w[1].0 >= w[0].0);
    let column = |px: f64| -> i64 {
        let span = if x.1 > x.0 { x.1 - x.0 } else { 1.0 };
        ((px - x.0) / span * columns as f64).floor() as i64
    };
    if monotone {
        let mut kept = Vec::new();
        let mut start = 0;
        while start < points.len() {
            let c = column(points[start].0);
            let mut end = start;
            let (mut low, mut high) = (start, start);
            while end < points.len() && column(points[end].0) == c {
                if points[end].1 < points[low].1 {
                    low = end;
                }
                if points[end].1 > points[high].1 {
                    high = end;
                }
                end += 1;
            }
            let mut chosen = [start, low, high, end - 1];
            chosen.sort_unstable();
            let mut last = None;
            for i in chosen {
                if last != Some(i) {
                    kept.push(points[i]);
                    last = Some(i);
                }
            }
            start = end;
        }
        return vec![kept];
    }
    let rows = pixels.1.max(1) as f64;
    let cell = |(px, py): (f64, f64)| -> (i64, i64) {
        let span = if y.1 > y.0 { y.1 - y.0 } else { 1.0 };
        (column(px), ((py - y.0) / span * rows).floor() as i64)
    };
    let mut drawn = std::collections::HashSet::new();
    let mut pieces: Vec<Polyline> = vec![vec![points[0]]];
    let mut last = cell(points[0]);
    for &p in &points[1..] {
        let here = cell(p);
        if here == last {
            continue;
        }
        let stretch = if last < here {
            (last, here)
        } else {
            (here, last)
        };
        if drawn.insert(stretch) {
            match pieces.last_mut() {
                Some(piece) if !piece.is_empty() => piece.push(p),
                _ => {}
            }
        } else {
            // Drawn already: start a new piece at this point.
            pieces.push(vec![p]);
        }
        last = here;
    }
    pieces.retain(|piece| piece.len() > 1);
    pieces
}

/// The series of a panel in axis coordinates (log10 of the values on a log axis), each cut into
/// the pieces between points that cannot be drawn.
fn drawable_pieces(panel: &Panel) -> Vec<(&Series, Vec<Polyline>)> {
    // Log axes are drawn as linear axes of log10 values, labelled with powers of ten.
    let transform = |(x, y): (f64, f64)| -> Option<(f64, f64)> {
        let x = if panel.log_x {
            (x > 0.0).then(|| x.log10())?
        } else {
            x
        };
        let y = if panel.log_y {
            (y > 0.0).then(|| y.log10())?
        } else {
            y
        };
        (x.is_finite() && y.is_finite()).then_some((x, y))
    };
    // A point that cannot be drawn (non-finite, or not positive on a log axis) breaks the curve.
    panel
        .series
        .iter()
        .map(|s| {
            let mut pieces = vec![Vec::new()];
            for &p in &s.points {
                match (transform(p), pieces.last_mut()) {
                    (Some(q), Some(piece)) => piece.push(q),
                    _ => pieces.push(Vec::new()),
                }
            }
            pieces.retain(|piece| !piece.is_empty());
            (s, pieces)
        })
        .collect()
}

/// The axis ranges (x0, x1, y0, y1) of a panel: the extent of its pieces and horizontal lines,
/// padded, and widened to equal lengths per unit on a plotting area of `plot` pixels when the
/// panel asks for it.
fn axis_ranges(
    panel: &Panel,
    series: &[(&Series, Vec<Polyline>)],
    (plot_w, plot_h): (u32, u32),
) -> (f64, f64, f64, f64) {
    let (mut x0, mut x1, mut y0, mut y1) = (f64::MAX, f64::MIN, f64::MAX, f64::MIN);
    for &(x, y) in series
        .iter()
        .flat_map(|(_, pieces)| pieces.iter().flatten())
    {
        x0 = x0.min(x);
        x1 = x1.max(x);
        y0 = y0.min(y);
        y1 = y1.max(y);
    }
    for &(level, _) in panel.reference_lines.iter().chain(&panel.dashed_lines) {
        y0 = y0.min(level);
        y1 = y1.max(level);
    }
    if x0 > x1 {
        (x0, x1, y0, y1) = (0.0, 1.0, 0.0, 1.0);
    }
    let pad = |lo: f64, hi: f64, fraction: f64| {
        let span = if hi > lo { hi - lo } else { lo.abs().max(1.0) };
        (lo - fraction * span, hi + fraction * span)
    };
    let (mut x0, mut x1) = if panel.log_x || panel.equal_aspect {
        pad(x0, x1, 0.03)
    } else {
        (x0, x1)
    };
    let (mut y0, mut y1) = pad(y0, y1, 0.05);
    if panel.equal_aspect {
        // Widen one range so that a metre is as long across as up, in the plotting area.
        let (plot_w, plot_h) = (f64::from(plot_w), f64::from(plot_h));
        let scale = ((x1 - x0) / plot_w).max((y1 - y0) / plot_h);
        let (xc, yc) = (0.5 * (x0 + x1), 0.5 * (y0 + y1));
        (x0, x1) = (xc - 0.5 * scale * plot_w, xc + 0.5 * scale * plot_w);
        (y0, y1) = (yc - 0.5 * scale * plot_h, yc + 0.5 * scale * plot_h);
    }
    (x0, x1, y0, y1)
}

fn draw_panel(
    panel: &Panel,
    whole: &Area<'_>,
) -> std::result::Result<(), Box<dyn std::error::Error>> {
    let (area, strip) = if panel.legend == Legend::Outside {
        let width = whole.dim_in_pixel().0;
        let (left, right) = whole.split_horizontally(width.saturating_sub(LEGEND_STRIP));
        (left, Some(right))
    } else {
        (whole.clone(), None)
    };
    let series = drawable_pieces(panel);
    let (width, height) = area.dim_in_pixel();
    let plot_w = width.saturating_sub(Y_LABEL_AREA + 2 * MARGIN).max(1);
    let plot_h = height
        .saturating_sub(X_LABEL_AREA + 2 * MARGIN + CAPTION)
        .max(1);
    let (x0, x1, y0, y1) = axis_ranges(panel, &series, (plot_w, plot_h));

    let mut chart = ChartBuilder::on(&area)
        .caption(&panel.title, ("sans-serif", TITLE_FONT))
        .margin(MARGIN)
        .x_label_area_size(X_LABEL_AREA)
        .y_label_area_size(Y_LABEL_AREA)
        .build_cartesian_2d(x0..x1, y0..y1)?;
    let log_label = |v: &f64| {
        if (v - v.round()).abs() < 1e-9 {
            format!("1e{}", v.round() as i64)
        } else {
            format!("{:.1e}", 10f64.powf(*v))
        }
    };
    // Tick values are sums of float steps: one that is zero but for rounding reads as 0.
    let linear_label = |v: &f64, span: f64| {
        let a = v.abs();
        if a <= 1e-9 * span {
            "0".to_string()
        } else if !(1e-3..1e4).contains(&a) {
            format!("{v:.0e}")
        } else {
            format!("{}", (v * 1e6).round() / 1e6)
        }
    };
    let x_label = |v: &f64| linear_label(v, (x1 - x0).abs());
    let y_label = |v: &f64| linear_label(v, (y1 - y0).abs());
    chart
        .configure_mesh()
        .x_desc(panel.x_label.as_str())
        .y_desc(panel.y_label.as_str())
        .x_labels(8)
        .y_labels(8)
        .label_style(("sans-serif", TICK_FONT))
        .axis_desc_style(("sans-serif", AXIS_FONT))
        .x_label_formatter(if panel.log_x { &log_label } else { &x_label })
        .y_label_formatter(if panel.log_y { &log_label } else { &y_label })
        .light_line_style(RGBColor(235, 235, 235))
        .draw()?;

    // The legend lists the series first, then the reference lines.
    let mut legend: Vec<(&str, Swatch)> = Vec::new();
    let mut levels: Vec<(&str, Swatch)> = Vec::new();
    let grey = RGBColor(150, 150, 150);
    let dark_grey = RGBColor(90, 90, 90);
    for (level, label) in &panel.reference_lines {
        chart.draw_series(LineSeries::new(
            [(x0, *level), (x1, *level)],
            grey.stroke_width(1),
        ))?;
        if !label.is_empty() {
            levels.push((label, Swatch::Line(grey, 1)));
        }
    }
    for (level, label) in &panel.dashed_lines {
        chart.draw_series(DashedLineSeries::new(
            [(x0, *level), (x1, *level)],
            8,
            5,
            dark_grey.stroke_width(1),
        ))?;
        if !label.is_empty() {
            levels.push((label, Swatch::Dashed(dark_grey)));
        }
    }
    for (s, pieces) in &series {
        let color = PALETTE[s.color % PALETTE.len()];
        let style = color.stroke_width(s.stroke_width());
        if !s.name.is_empty() && !pieces.is_empty() {
            legend.push((
                s.name.as_str(),
                match (s.line, s.marker) {
                    (false, Some(shape)) => Swatch::Marker(color, shape),
                    _ => Swatch::Line(color, s.stroke_width().clamp(2, 4)),
                },
            ));
        }
        for points in pieces {
            if s.line {
                for piece in decimate(points, (x0, x1), (y0, y1), (plot_w, plot_h)) {
                    chart.draw_series(LineSeries::new(piece, style))?;
                }
            }
            if let Some(shape) = s.marker {
                draw_markers(chart.plotting_area(), points, shape, color)?;
            }
        }
    }
    legend.extend(levels);
    if legend.is_empty() {
        return Ok(());
    }
    match strip {
        Some(strip) => draw_legend(&strip, &legend, Legend::Outside),
        None => draw_legend(
            &chart.plotting_area().strip_coord_spec(),
            &legend,
            panel.legend,
        ),
    }
}

/// Draws a legend, one entry a line: in a corner of `area` (the plotting area) inside a white
/// box, or for [`Legend::Outside`] from the top of `area` (the strip) down.
fn draw_legend(
    area: &Area<'_>,
    entries: &[(&str, Swatch)],
    placement: Legend,
) -> std::result::Result<(), Box<dyn std::error::Error>> {
    let font = ("sans-serif", LEGEND_FONT).into_font().color(&BLACK);
    let step = LEGEND_FONT as i32 + 8;
    let (swatch_width, gap, pad) = (24, 8, 8);
    // plotters' estimate without font files is narrow for the sans-serif fonts viewers use
    // (DejaVu Sans is about 0.6 em a character): take the larger of the two.
    let text_width = entries
        .iter()
        .map(|(label, _)| {
            let estimate = area.estimate_text_size(label, &font).map_or(0, |(w, _)| w);
            estimate.max((0.6 * (LEGEND_FONT * label.chars().count() as u32) as f64) as u32)
        })
        .max()
        .unwrap_or(0) as i32;
    let box_width = pad + swatch_width + gap + text_width + pad;
    let box_height = pad + step * entries.len() as i32 + pad / 2;
    let (width, height) = area.dim_in_pixel();
    let (width, height) = (width as i32, height as i32);
    let inset = 6;
    let (left, top) = match placement {
        Legend::Outside => (0, (MARGIN + CAPTION) as i32),
        Legend::UpperRight => (width - box_width - inset, inset),
        Legend::LowerRight => (width - box_width - inset, height - box_height - inset),
        Legend::UpperLeft => (inset, inset),
        Legend::LowerLeft => (inset, height - box_height - inset),
    };
    if placement != Legend::Outside {
        area.draw(&Rectangle::new(
            [(left, top), (left + box_width, top + box_height)],
            WHITE.mix(0.85).filled(),
        ))?;
        area.draw(&Rectangle::new(
            [(left, top), (left + box_width, top + box_height)],
            RGBColor(180, 180, 180).stroke_width(1),
        ))?;
    }
    for (i, (label, swatch)) in entries.iter().enumerate() {
        let y = top + pad + step / 2 + i as i32 * step;
        let x = left + pad;
        match *swatch {
            Swatch::Line(color, width) => area.draw(&PathElement::new(
                vec![(x, y), (x + swatch_width, y)],
                color.stroke_width(width),
            ))?,
            Swatch::Dashed(color) => {
                for dash in [0, 14] {
                    area.draw(&PathElement::new(
                        vec![(x + dash, y), (x + dash + 9, y)],
                        color.stroke_width(1),
                    ))?;
                }
            }
            Swatch::Marker(color, shape) => {
                draw_markers(area, &[(x + swatch_width / 2, y)], shape, color)?
            }
        }
        area.draw(&Text::new(
            label.to_string(),
            (x + swatch_width + gap, y),
            font.pos(Pos::new(HPos::Left, VPos::Center)),
        ))?;
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn svg_has_title_labels_and_legend() {
        let mut panel = Panel::new("title A", "x (s)", "y (m)")
            .with(Series::line(
                "sine",
                (0..50).map(|i| (i as f64, (i as f64).sin())).collect(),
                0,
            ))
            .with(Series::line(
                "broken",
                vec![(0.0, 0.0), (1.0, f64::NAN), (2.0, 1.0), (3.0, 2.0)],
                1,
            ));
        panel.reference_lines = vec![(0.5, "limit".to_string()), (-0.5, String::new())];
        let svg = figure("a.svg", &[panel], 1, (600, 400)).unwrap();
        assert!(svg.starts_with("<svg"));
        for text in ["title A", "x (s)", "y (m)", "sine", "broken", "limit"] {
            assert!(svg.contains(text), "{text}");
        }
    }

    #[test]
    fn empty_flat_and_equal_aspect_panels_still_draw() {
        assert!(figure("e.svg", &[Panel::new("empty", "x", "y")], 1, (400, 300)).is_ok());
        let flat =
            Panel::new("flat", "x", "y").with(Series::line("", vec![(0.0, 0.0), (1.0, 0.0)], 0));
        assert!(figure("f.svg", std::slice::from_ref(&flat), 1, (400, 300)).is_ok());
        let mut shape = flat;
        shape.equal_aspect = true;
        assert!(figure("s.svg", &[shape], 1, (400, 300)).is_ok());
    }

    #[test]
    fn decimation_keeps_every_peak_of_a_time_series() {
        // A million samples of a slow sine with two one-sample spikes, which a thinning by
        // stride would miss; and a jump (two samples at one time), as at an event.
        let n = 1_000_000;
        let mut points: Vec<(f64, f64)> = (0..n)
            .map(|i| {
                let t = i as f64 * 1e-5;
                (t, (2.0 * t).sin())
            })
            .collect();
        points[123_457].1 = 5.0;
        points[876_543].1 = -7.0;
        points.insert(500_000, (points[500_000].0, 3.0));
        let peaks = [points[123_457], points[876_544], points[500_000]];
        assert_eq!([peaks[0].1, peaks[1].1, peaks[2].1], [5.0, -7.0, 3.0]);
        let x = (0.0, points[points.len() - 1].0);
        let thinned = decimate(&points, x, (-7.0, 5.0), (800, 300));
        assert_eq!(thinned.len(), 1);
        let kept = &thinned[0];
        assert!(kept.len() <= 4 * 800 + 4, "{} points", kept.len());
        for peak in peaks {
            assert!(kept.contains(&peak), "{peak:?}");
        }
        assert_eq!(kept[0], points[0]);
        assert_eq!(kept[kept.len() - 1], points[points.len() - 1]);
        assert!(kept.windows(2).all(|w| w[1].0 >= w[0].0));
        // Short series are left alone.
        assert_eq!(
            decimate(&points[..100], x, (-1.0, 1.0), (800, 300))[0],
            &points[..100]
        );
    }

    #[test]
    fn decimation_of_a_retraced_path_keeps_its_extremes_to_a_pixel() {
        // A path to and fro along one curve, as F(q) or q against r: 400 swings of growing
        // then shrinking amplitude, a million points.
        let n = 1_000_000;
        let points: Vec<(f64, f64)> = (0..n)
            .map(|i| {
                let u = i as f64 / n as f64;
                let q = (u * std::f64::consts::PI).sin() * (u * 2513.0).sin();
                (q, q * q.abs())
            })
            .collect();
        let (x_max, y_min) = points
            .iter()
            .fold((f64::MIN, f64::MAX), |(a, b), p| (a.max(p.0), b.min(p.1)));
        let pixels = (600, 400);
        let pieces = decimate(&points, (-1.0, 1.0), (-1.0, 1.0), pixels);
        let kept: Vec<(f64, f64)> = pieces.iter().flatten().copied().collect();
        assert!(kept.len() < 10_000, "{} points", kept.len());
        let (kept_x_max, kept_y_min) = kept
            .iter()
            .fold((f64::MIN, f64::MAX), |(a, b), p| (a.max(p.0), b.min(p.1)));
        let pixel = 2.0 / 600.0;
        assert!(x_max - kept_x_max <= pixel, "{x_max} {kept_x_max}");
        assert!(kept_y_min - y_min <= 2.0 / 400.0, "{y_min} {kept_y_min}");
    }

    #[test]
    fn a_figure_of_a_million_points_stays_small() {
        let n = 1_000_000;
        let line: Vec<(f64, f64)> = (0..n)
            .map(|i| (i as f64, (i as f64 * 1e-3).sin()))
            .collect();
        let path: Vec<(f64, f64)> = line.iter().map(|&(_, y)| (y, y * y)).collect();
        let panels = [
            Panel::new("time", "t", "y").with(Series::line("y", line, 0)),
            Panel::new("path", "x", "y").with(Series::line("path", path, 1)),
        ];
        let svg = figure("big.svg", &panels, 1, (1000, 400)).unwrap();
        assert!(svg.len() < 2_000_000, "{} bytes", svg.len());
    }

    #[test]
    fn outside_legends_and_markers() {
        let mut panel = Panel::new("events", "t (s)", "q' (m/s)")
            .with(Series::line(
                "q'",
                vec![(0.0, 0.0), (1.0, 1.0), (2.0, -1.0)],
                0,
            ))
            .with(Series::markers(
                "uplift",
                vec![(1.0, 1.0)],
                1,
                Marker::TriangleUp,
            ))
            .with(Series::markers(
                "landing",
                vec![(2.0, -1.0)],
                2,
                Marker::TriangleDown,
            ))
            .with(Series::markers(
                "overturn",
                vec![(2.0, 0.0)],
                4,
                Marker::Cross,
            ));
        panel.legend = Legend::Outside;
        panel.dashed_lines = vec![(0.5, "limit B".to_string())];
        let svg = figure("m.svg", &[panel], 1, (900, 300)).unwrap();
        for text in ["uplift", "landing", "overturn", "limit B"] {
            assert!(svg.contains(text), "{text}");
        }
        assert!(svg.contains("<polygon"), "triangles are polygons");
    }
}
