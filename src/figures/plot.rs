//! SVG figures from series of points. Knows nothing about solvers or models: callers hand it
//! panels of named (x, y) series and get the SVG text back, to be written atomically.

use plotters::coord::types::RangedCoordf64;
use plotters::coord::Shift;
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
    /// Draw the line dashed, so that a curve under it shows through the gaps (two curves that
    /// nearly coincide stay apart to the eye).
    pub dashed: bool,
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
            dashed: false,
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

    /// The series drawn dashed.
    pub fn dashed(mut self) -> Self {
        self.dashed = true;
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
    /// A margin at both ends of the x axis, as the y axis has (a curve that is not a history in
    /// time, whose ends would otherwise touch the frame).
    pub pad_x: bool,
    /// Horizontal lines drawn in grey (e.g. +-s_n), with their legend text (empty: none).
    pub reference_lines: Vec<(f64, String)>,
    /// Horizontal dashed lines in dark grey (e.g. the overturning limit +-B), with their legend
    /// text (empty: none).
    pub dashed_lines: Vec<(f64, String)>,
    /// Thin vertical lines across the whole panel (events in time), drawn under the series.
    pub vertical_lines: Vec<VerticalLine>,
    /// Shaded stretches of the x axis across the whole panel (e.g. a state that lasts), drawn
    /// over the vertical lines and under the series.
    pub spans: Vec<Span>,
}

/// A stretch of the x axis shaded across a panel, in a pale palette colour; the first span of
/// each non-empty label gets a legend entry.
#[derive(Debug, Clone)]
pub struct Span {
    /// Where it starts.
    pub from: f64,
    /// Where it ends.
    pub to: f64,
    /// Index into the palette.
    pub color: usize,
    /// The legend text (empty: none).
    pub label: String,
    /// Drawn in a stronger tint of its colour (a stretch within a paler one).
    pub strong: bool,
}

impl Panel {
    /// A value of the y axis in axis coordinates: its log10 on a log axis (None where that has
    /// none), else itself. Lines are given in the data's own units, as the series are.
    fn y_axis(&self, y: f64) -> Option<f64> {
        if self.log_y {
            (y > 0.0).then(|| y.log10())
        } else {
            Some(y)
        }
    }

    /// As [`Panel::y_axis`], for the x axis.
    fn x_axis(&self, x: f64) -> Option<f64> {
        if self.log_x {
            (x > 0.0).then(|| x.log10())
        } else {
            Some(x)
        }
    }
}

/// A thin vertical line across a panel, at an abscissa, in a palette colour; the first line of
/// each non-empty label gets a legend entry.
#[derive(Debug, Clone)]
pub struct VerticalLine {
    /// The abscissa.
    pub x: f64,
    /// Index into the palette.
    pub color: usize,
    /// The legend text (empty: none).
    pub label: String,
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

/// Where a panel's legend goes: a corner inside the plotting area, or a strip to the right of it,
/// where it cannot cover any curve. A corner is a preference: when the legend box there would
/// cover any drawn point or line of the panel, the first free corner of upper right, upper left,
/// lower right, lower left is taken, and when none is free the legend goes beside the plot
/// ([`Legend::Outside`]).
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
/// font). A figure with a longer label widens the strip of all its panels to hold it, so that
/// panels stacked in one column still share their x axis.
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

/// The embedded font (DejaVu Sans, assets/fonts/LICENSE-DejaVu.txt): PNG text is drawn with it
/// and every figure's text is measured with it, so no system font is needed.
static FONT: &[u8] = include_bytes!("../../assets/fonts/DejaVuSans.ttf");

/// Registers the embedded font as "sans-serif" (once); every drawing calls this first.
pub fn register_fonts() {
    static ONCE: std::sync::Once = std::sync::Once::new();
    ONCE.call_once(|| {
        // The font is a fixed, valid file: a failure here is a broken build, and the tests
        // (which draw text) catch it.
        let loaded = plotters::style::register_font("sans-serif", FontStyle::Normal, FONT);
        assert!(loaded.is_ok(), "the embedded DejaVu Sans font loads");
    });
}

/// The image format of a figure.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Format {
    /// SVG text.
    Svg,
    /// PNG, 8-bit RGB.
    Png,
}

impl Format {
    /// The file extension, without the dot.
    pub fn extension(self) -> &'static str {
        match self {
            Format::Svg => "svg",
            Format::Png => "png",
        }
    }
}

/// Draws `panels` in a grid of `columns` columns, each panel `size` pixels; returns the SVG text.
pub fn figure(name: &str, panels: &[Panel], columns: usize, size: (u32, u32)) -> Result<String> {
    let bytes = figure_sized(
        Format::Svg,
        name,
        panels,
        columns,
        grid_size(panels, columns, size),
    )?;
    Ok(String::from_utf8(bytes).unwrap_or_default())
}

/// [`figure`] in `format` (SVG text or PNG bytes), the whole figure `total` pixels (the panels
/// share it evenly).
pub fn figure_sized(
    format: Format,
    name: &str,
    panels: &[Panel],
    columns: usize,
    (width, height): (u32, u32),
) -> Result<Vec<u8>> {
    match format {
        Format::Svg => {
            let mut svg = String::new();
            {
                let root = SVGBackend::with_string(&mut svg, (width, height)).into_drawing_area();
                draw_figure(name, &root, panels, columns, false)?;
            }
            Ok(svg.into_bytes())
        }
        Format::Png => {
            let mut pixels = vec![255u8; 3 * width as usize * height as usize];
            {
                let root =
                    BitMapBackend::with_buffer(&mut pixels, (width, height)).into_drawing_area();
                draw_figure(name, &root, panels, columns, true)?;
            }
            encode_png(name, &pixels, (width, height))
        }
    }
}

/// 8-bit RGB pixels, row by row, as a PNG file.
pub fn encode_png(name: &str, pixels: &[u8], (width, height): (u32, u32)) -> Result<Vec<u8>> {
    let fail = |e: &dyn std::fmt::Display| Error::Plot {
        name: name.to_string(),
        message: e.to_string(),
    };
    let mut bytes = Vec::new();
    {
        let mut encoder = png::Encoder::new(&mut bytes, width, height);
        encoder.set_color(png::ColorType::Rgb);
        encoder.set_depth(png::BitDepth::Eight);
        let mut writer = encoder.write_header().map_err(|e| fail(&e))?;
        writer.write_image_data(pixels).map_err(|e| fail(&e))?;
        writer.finish().map_err(|e| fail(&e))?;
    }
    Ok(bytes)
}

/// The width in pixels of an `equal_aspect` panel `height` pixels high whose data span `span`
/// (across, up, in the same unit) fills its height: the width at which the axes are widened
/// across only (so nothing is added below or above the data). With no legend strip.
pub fn equal_aspect_width(height: u32, (across, up): (f64, f64)) -> u32 {
    let plot_h = f64::from(
        height
            .saturating_sub(X_LABEL_AREA + 2 * MARGIN + CAPTION)
            .max(1),
    );
    // The paddings of `axis_ranges`: 3 % each side across, 5 % up and down.
    let plot_w = plot_h * (1.06 * across) / (1.1 * up);
    plot_w.ceil() as u32 + 2 + Y_LABEL_AREA + 2 * MARGIN
}

fn grid_size(panels: &[Panel], columns: usize, size: (u32, u32)) -> (u32, u32) {
    let columns = columns.max(1);
    let rows = panels.len().div_ceil(columns).max(1);
    (size.0 * columns as u32, size.1 * rows as u32)
}

fn draw_figure<DB: DrawingBackend>(
    name: &str,
    root: &DrawingArea<DB, Shift>,
    panels: &[Panel],
    columns: usize,
    raster: bool,
) -> Result<()>
where
    DB::ErrorType: 'static,
{
    register_fonts();
    let columns = columns.max(1);
    let rows = panels.len().div_ceil(columns).max(1);
    let fail = |e: &dyn std::fmt::Display| Error::Plot {
        name: name.to_string(),
        message: e.to_string(),
    };
    root.fill(&WHITE).map_err(|e| fail(&e))?;
    let areas = root.split_evenly((rows, columns));
    let strip = strip_width(panels);
    for (panel, area) in panels.iter().zip(areas.iter()) {
        draw_panel(panel, area, strip, raster).map_err(|e| fail(&e))?;
    }
    root.present().map_err(|e| fail(&e))?;
    Ok(())
}

/// The width of the legend strips of a figure's panels: [`LEGEND_STRIP`], or the widest legend
/// box of its panels whose legend is [`Legend::Outside`] where that is wider.
fn strip_width(panels: &[Panel]) -> u32 {
    panels
        .iter()
        .filter(|panel| panel.legend == Legend::Outside)
        .map(|panel| {
            let series = drawable_pieces(panel);
            legend_box(&legend_entries(panel, &series)).0.max(0) as u32
        })
        .fold(LEGEND_STRIP, u32::max)
}

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
/// The grid at the tick marks: one light grey, no minor lines (they darken a printed figure).
const GRID: RGBColor = RGBColor(222, 222, 222);
/// The frame of an inside legend (a colour no series uses, so that tests find the box).
pub const LEGEND_FRAME: RGBColor = RGBColor(180, 180, 180);

/// What a legend shows for one entry.
#[derive(Clone, Copy)]
enum Swatch {
    Line(RGBColor, u32),
    Dashed(RGBColor, u32),
    Vertical(RGBColor),
    Marker(RGBColor, Marker),
    Band(RGBColor),
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
        if let Some(level) = panel.y_axis(level) {
            y0 = y0.min(level);
            y1 = y1.max(level);
        }
    }
    if x0 > x1 {
        (x0, x1, y0, y1) = (0.0, 1.0, 0.0, 1.0);
    }
    let pad = |lo: f64, hi: f64, fraction: f64| {
        let span = if hi > lo { hi - lo } else { lo.abs().max(1.0) };
        (lo - fraction * span, hi + fraction * span)
    };
    let (mut x0, mut x1) = if panel.log_x || panel.equal_aspect || panel.pad_x {
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

/// The chart of a panel on `area`, with the axis ranges.
fn build_chart<'a, DB: DrawingBackend>(
    panel: &Panel,
    area: &'a DrawingArea<DB, Shift>,
    (x0, x1, y0, y1): (f64, f64, f64, f64),
) -> std::result::Result<
    ChartContext<'a, DB, Cartesian2d<RangedCoordf64, RangedCoordf64>>,
    Box<dyn std::error::Error>,
>
where
    DB::ErrorType: 'static,
{
    Ok(ChartBuilder::on(area)
        .caption(&panel.title, ("sans-serif", TITLE_FONT))
        .margin(MARGIN)
        .x_label_area_size(X_LABEL_AREA)
        .y_label_area_size(Y_LABEL_AREA)
        .build_cartesian_2d(x0..x1, y0..y1)?)
}

/// The axis ranges for a panel drawn on an area of `dims` pixels.
fn ranges_on(
    panel: &Panel,
    series: &[(&Series, Vec<Polyline>)],
    (width, height): (u32, u32),
) -> ((f64, f64, f64, f64), (u32, u32)) {
    let plot_w = width.saturating_sub(Y_LABEL_AREA + 2 * MARGIN).max(1);
    let plot_h = height
        .saturating_sub(X_LABEL_AREA + 2 * MARGIN + CAPTION)
        .max(1);
    (
        axis_ranges(panel, series, (plot_w, plot_h)),
        (plot_w, plot_h),
    )
}

/// A straight stretch of a drawing, in pixels, with the half width of its stroke.
#[derive(Debug, Clone, Copy)]
pub struct Stroke {
    /// Start.
    pub a: (f64, f64),
    /// End.
    pub b: (f64, f64),
    /// Half the stroke width (or the marker radius), pixels.
    pub half_width: f64,
}

/// True when the stroke touches the rectangle `(left, top, right, bottom)` (pixels).
pub fn stroke_hits_box(s: &Stroke, (l, t, r, b): (f64, f64, f64, f64)) -> bool {
    let (l, t, r, b) = (
        l - s.half_width,
        t - s.half_width,
        r + s.half_width,
        b + s.half_width,
    );
    // Liang-Barsky clipping of the segment against the widened box.
    let (dx, dy) = (s.b.0 - s.a.0, s.b.1 - s.a.1);
    let (mut u0, mut u1) = (0.0f64, 1.0f64);
    for (p, q) in [
        (-dx, s.a.0 - l),
        (dx, r - s.a.0),
        (-dy, s.a.1 - t),
        (dy, b - s.a.1),
    ] {
        if p == 0.0 {
            if q < 0.0 {
                return false;
            }
        } else {
            let u = q / p;
            if p < 0.0 {
                u0 = u0.max(u);
            } else {
                u1 = u1.min(u);
            }
            if u0 > u1 {
                return false;
            }
        }
    }
    true
}

/// Everything a panel draws inside its plotting area, as strokes in the pixel coordinates of
/// that area (origin at its upper left corner).
fn drawn_strokes<DB: DrawingBackend>(
    chart: &ChartContext<'_, DB, Cartesian2d<RangedCoordf64, RangedCoordf64>>,
    panel: &Panel,
    series: &[(&Series, Vec<Polyline>)],
    (x0, x1, y0, y1): (f64, f64, f64, f64),
    plot: (u32, u32),
) -> Vec<Stroke> {
    let area = chart.plotting_area();
    let (xr, yr) = area.get_pixel_range();
    let at = |p: (f64, f64)| {
        let (x, y) = area.map_coordinate(&p);
        (f64::from(x - xr.start), f64::from(y - yr.start))
    };
    let mut strokes = Vec::new();
    let mut marks = Vec::new();
    let mut line = |a: (f64, f64), b: (f64, f64), width: u32| {
        strokes.push(Stroke {
            a: at(a),
            b: at(b),
            half_width: 0.5 * f64::from(width),
        })
    };
    for (level, _) in panel.reference_lines.iter().chain(&panel.dashed_lines) {
        if let Some(level) = panel.y_axis(*level) {
            line((x0, level), (x1, level), 1);
        }
    }
    for v in &panel.vertical_lines {
        if let Some(x) = panel.x_axis(v.x) {
            line((x, y0), (x, y1), 1);
        }
    }
    for (s, pieces) in series {
        for points in pieces {
            if s.line {
                for piece in decimate(points, (x0, x1), (y0, y1), plot) {
                    if piece.len() == 1 {
                        line(piece[0], piece[0], s.stroke_width());
                    }
                    for w in piece.windows(2) {
                        line(w[0], w[1], s.stroke_width());
                    }
                }
            }
            if s.marker.is_some() {
                for &p in points {
                    marks.push(Stroke {
                        a: at(p),
                        b: at(p),
                        half_width: f64::from(MARKER_SIZE + 1),
                    });
                }
            }
        }
    }
    strokes.extend(marks);
    strokes
}

/// The legend entries of a panel, series first, then the reference lines and vertical lines.
fn legend_entries<'p>(
    panel: &'p Panel,
    series: &[(&'p Series, Vec<Polyline>)],
) -> Vec<(&'p str, Swatch)> {
    let mut legend: Vec<(&str, Swatch)> = Vec::new();
    for (s, pieces) in series {
        let color = PALETTE[s.color % PALETTE.len()];
        if !s.name.is_empty() && !pieces.is_empty() {
            legend.push((
                s.name.as_str(),
                match (s.line, s.marker) {
                    (false, Some(shape)) => Swatch::Marker(color, shape),
                    _ if s.dashed => Swatch::Dashed(color, s.stroke_width().clamp(1, 4)),
                    _ => Swatch::Line(color, s.stroke_width().clamp(2, 4)),
                },
            ));
        }
    }
    for (_, label) in &panel.reference_lines {
        if !label.is_empty() {
            legend.push((label, Swatch::Line(REFERENCE_GREY, 1)));
        }
    }
    for (_, label) in &panel.dashed_lines {
        if !label.is_empty() {
            legend.push((label, Swatch::Dashed(DASHED_GREY, 1)));
        }
    }
    let mut seen: Vec<&str> = Vec::new();
    for span in &panel.spans {
        if !span.label.is_empty() && !seen.contains(&span.label.as_str()) {
            seen.push(&span.label);
            legend.push((
                &span.label,
                Swatch::Band(span_colour(span.color, span.strong)),
            ));
        }
    }
    for v in &panel.vertical_lines {
        if !v.label.is_empty() && !seen.contains(&v.label.as_str()) {
            seen.push(&v.label);
            legend.push((&v.label, Swatch::Vertical(event_colour(v.color))));
        }
    }
    legend
}

const REFERENCE_GREY: RGBColor = RGBColor(150, 150, 150);
const DASHED_GREY: RGBColor = RGBColor(90, 90, 90);

/// The colour of a shaded span: the palette colour, three fifths white.
fn span_colour(color: usize, strong: bool) -> RGBColor {
    let c = PALETTE[color % PALETTE.len()];
    let (own, white) = if strong { (4, 1) } else { (2, 3) };
    let pale = |v: u8| ((own * u16::from(v) + white * 255) / 5) as u8;
    RGBColor(pale(c.0), pale(c.1), pale(c.2))
}

/// The colour of a vertical event line: the palette colour, lightened.
fn event_colour(color: usize) -> RGBColor {
    let c = PALETTE[color % PALETTE.len()];
    let light = |v: u8| ((u16::from(v) + 255) / 2) as u8;
    RGBColor(light(c.0), light(c.1), light(c.2))
}

/// Width and height of a legend box for `entries`, pixels.
fn legend_box(entries: &[(&str, Swatch)]) -> (i32, i32) {
    let font = ("sans-serif", LEGEND_FONT).into_font();
    let step = LEGEND_FONT as i32 + 8;
    let (swatch_width, gap, pad) = (24, 8, 8);
    // The text is measured with the embedded DejaVu Sans at the nominal size, which is 1.24
    // times the size the SVG asks for: room for a viewer that substitutes a wider sans-serif.
    let text_width = entries
        .iter()
        .map(|(label, _)| {
            let measured = font.box_size(label).map_or(0, |(w, _)| w);
            measured.max(LEGEND_FONT / 2 * label.chars().count() as u32)
        })
        .max()
        .unwrap_or(0) as i32;
    (
        pad + swatch_width + gap + text_width + pad,
        pad + step * entries.len() as i32 + pad / 2,
    )
}

/// Upper left corner of a legend box of `size` in an area of `dims`, at a corner (`Outside`:
/// the top of the strip).
fn legend_origin(placement: Legend, (w, h): (i32, i32), (width, height): (i32, i32)) -> (i32, i32) {
    let inset = LEGEND_INSET;
    match placement {
        Legend::Outside => (0, (MARGIN + CAPTION) as i32),
        Legend::UpperRight => (width - w - inset, inset),
        Legend::LowerRight => (width - w - inset, height - h - inset),
        Legend::UpperLeft => (inset, inset),
        Legend::LowerLeft => (inset, height - h - inset),
    }
}

/// Gap between an inside legend and the plotting area's edge, pixels.
const LEGEND_INSET: i32 = 6;

/// Where a legend box goes: at `(left, top)` in the plotting area, or beside the plot.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Placement {
    Inside(i32, i32),
    Outside,
}

/// The legend placement of a panel drawn on an area of `dims`: the panel's corner when the
/// legend box there covers nothing drawn (with two pixels of air), else the first free one of
/// the other corners, the middles of the left and right edges, of the top and bottom edges,
/// and the centre; else beside the plot. The layout is found by building the same chart on a
/// scratch SVG of the same size.
fn choose_legend(
    panel: &Panel,
    series: &[(&Series, Vec<Polyline>)],
    dims: (u32, u32),
) -> Placement {
    if panel.legend == Legend::Outside {
        return Placement::Outside;
    }
    let entries = legend_entries(panel, series);
    if entries.is_empty() {
        return Placement::Inside(0, 0);
    }
    let mut scratch = String::new();
    let scratch_area = SVGBackend::with_string(&mut scratch, dims).into_drawing_area();
    let (ranges, plot) = ranges_on(panel, series, dims);
    let Ok(chart) = build_chart(panel, &scratch_area, ranges) else {
        return Placement::Outside;
    };
    let strokes = drawn_strokes(&chart, panel, series, ranges, plot);
    let (xr, yr) = chart.plotting_area().get_pixel_range();
    let area = (xr.end - xr.start, yr.end - yr.start);
    let size = legend_box(&entries);
    let mut candidates = vec![legend_origin(panel.legend, size, area)];
    for corner in [
        Legend::UpperRight,
        Legend::UpperLeft,
        Legend::LowerRight,
        Legend::LowerLeft,
    ] {
        candidates.push(legend_origin(corner, size, area));
    }
    let (left, right) = (LEGEND_INSET, area.0 - size.0 - LEGEND_INSET);
    let (top, bottom) = (LEGEND_INSET, area.1 - size.1 - LEGEND_INSET);
    let (centre_x, centre_y) = ((area.0 - size.0) / 2, (area.1 - size.1) / 2);
    candidates.extend([
        (left, centre_y),
        (right, centre_y),
        (centre_x, top),
        (centre_x, bottom),
        (centre_x, centre_y),
    ]);
    candidates
        .into_iter()
        .find(|&(x, y)| {
            // A box wider or taller than the plotting area does not fit inside.
            let fits = x >= 0 && y >= 0 && x + size.0 <= area.0 && y + size.1 <= area.1;
            let rect = (
                f64::from(x) - 2.0,
                f64::from(y) - 2.0,
                f64::from(x + size.0) + 2.0,
                f64::from(y + size.1) + 2.0,
            );
            fits && !strokes.iter().any(|s| stroke_hits_box(s, rect))
        })
        .map_or(Placement::Outside, |(x, y)| Placement::Inside(x, y))
}

/// Draws one panel. `raster`: the backend is plotters' rasteriser, which fills a wide polyline
/// as one polygon (even-odd: a path that retraces itself comes out hollow), so wide lines are
/// drawn segment by segment with round joints instead.
fn draw_panel<DB: DrawingBackend>(
    panel: &Panel,
    whole: &DrawingArea<DB, Shift>,
    strip_width: u32,
    raster: bool,
) -> std::result::Result<(), Box<dyn std::error::Error>>
where
    DB::ErrorType: 'static,
{
    let series = drawable_pieces(panel);
    let placement = choose_legend(panel, &series, whole.dim_in_pixel());
    let (area, strip) = if placement == Placement::Outside {
        let width = whole.dim_in_pixel().0;
        let (left, right) = whole.split_horizontally(width.saturating_sub(strip_width));
        (left, Some(right))
    } else {
        (whole.clone(), None)
    };
    let (ranges, (plot_w, plot_h)) = ranges_on(panel, &series, area.dim_in_pixel());
    let (x0, x1, y0, y1) = ranges;
    let mut chart = build_chart(panel, &area, ranges)?;
    // Everyday sizes as decimals (0.032, 1, 3.2, 10), the rest as powers of ten.
    let log_label = |v: &f64| {
        let x = 10f64.powf(*v);
        if (1e-3..1e4).contains(&x) {
            flexrock_core::format::significant(x, 2)
        } else if (v - v.round()).abs() < 1e-9 {
            format!("1e{}", v.round() as i64)
        } else {
            format!("{x:.1e}")
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
        .bold_line_style(GRID.stroke_width(1))
        .light_line_style(TRANSPARENT)
        .max_light_lines(0)
        .axis_style(BLACK.stroke_width(1))
        .draw()?;

    for v in &panel.vertical_lines {
        let Some(x) = panel.x_axis(v.x) else { continue };
        chart.draw_series(LineSeries::new(
            [(x, y0), (x, y1)],
            event_colour(v.color).stroke_width(1),
        ))?;
    }
    for span in &panel.spans {
        let (Some(a), Some(b)) = (panel.x_axis(span.from), panel.x_axis(span.to)) else {
            continue;
        };
        let (a, b) = (a.clamp(x0, x1), b.clamp(x0, x1));
        chart.draw_series(std::iter::once(Rectangle::new(
            [(a, y0), (b, y1)],
            span_colour(span.color, span.strong).filled(),
        )))?;
    }
    for (level, _) in &panel.reference_lines {
        let Some(level) = panel.y_axis(*level) else {
            continue;
        };
        chart.draw_series(LineSeries::new(
            [(x0, level), (x1, level)],
            REFERENCE_GREY.stroke_width(1),
        ))?;
    }
    for (level, _) in &panel.dashed_lines {
        let Some(level) = panel.y_axis(*level) else {
            continue;
        };
        chart.draw_series(DashedLineSeries::new(
            [(x0, level), (x1, level)],
            8,
            5,
            DASHED_GREY.stroke_width(1),
        ))?;
    }
    for (s, pieces) in &series {
        let color = PALETTE[s.color % PALETTE.len()];
        let style = color.stroke_width(s.stroke_width());
        for points in pieces {
            if s.line {
                for piece in decimate(points, (x0, x1), (y0, y1), (plot_w, plot_h)) {
                    if s.dashed {
                        chart.draw_series(DashedLineSeries::new(piece, 9, 6, style))?;
                    } else if raster && s.stroke_width() > 1 {
                        chart.draw_series(
                            piece
                                .windows(2)
                                .map(|w| PathElement::new(vec![w[0], w[1]], style)),
                        )?;
                        if s.stroke_width() > 2 {
                            let r = s.stroke_width() / 2;
                            chart.draw_series(
                                piece.iter().map(|&p| Circle::new(p, r, color.filled())),
                            )?;
                        }
                    } else {
                        chart.draw_series(LineSeries::new(piece, style))?;
                    }
                }
            }
            if let Some(shape) = s.marker {
                draw_markers(chart.plotting_area(), points, shape, color)?;
            }
        }
    }
    let legend = legend_entries(panel, &series);
    if legend.is_empty() {
        return Ok(());
    }
    match strip {
        Some(strip) => draw_legend(&strip, &legend, Placement::Outside),
        None => draw_legend(
            &chart.plotting_area().strip_coord_spec(),
            &legend,
            placement,
        ),
    }
}

/// Draws a legend, one entry a line: in a corner of `area` (the plotting area) inside a white
/// box, or for [`Legend::Outside`] from the top of `area` (the strip) down.
fn draw_legend<DB: DrawingBackend>(
    area: &DrawingArea<DB, Shift>,
    entries: &[(&str, Swatch)],
    placement: Placement,
) -> std::result::Result<(), Box<dyn std::error::Error>>
where
    DB::ErrorType: 'static,
{
    let font = ("sans-serif", LEGEND_FONT).into_font().color(&BLACK);
    let step = LEGEND_FONT as i32 + 8;
    let (swatch_width, gap, pad) = (24, 8, 8);
    let size = legend_box(entries);
    let (left, top) = match placement {
        Placement::Inside(x, y) => (x, y),
        Placement::Outside => legend_origin(Legend::Outside, size, (0, 0)),
    };
    if placement != Placement::Outside {
        let corners = [(left, top), (left + size.0, top + size.1)];
        area.draw(&Rectangle::new(corners, WHITE.mix(0.85).filled()))?;
        area.draw(&Rectangle::new(corners, LEGEND_FRAME.stroke_width(1)))?;
    }
    for (i, (label, swatch)) in entries.iter().enumerate() {
        let y = top + pad + step / 2 + i as i32 * step;
        let x = left + pad;
        match *swatch {
            Swatch::Line(color, width) => area.draw(&PathElement::new(
                vec![(x, y), (x + swatch_width, y)],
                color.stroke_width(width),
            ))?,
            Swatch::Dashed(color, width) => {
                for dash in [0, 14] {
                    area.draw(&PathElement::new(
                        vec![(x + dash, y), (x + dash + 9, y)],
                        color.stroke_width(width),
                    ))?;
                }
            }
            Swatch::Vertical(color) => area.draw(&PathElement::new(
                vec![
                    (x + swatch_width / 2, y - step / 2 + 3),
                    (x + swatch_width / 2, y + step / 2 - 3),
                ],
                color.stroke_width(2),
            ))?,
            Swatch::Marker(color, shape) => {
                draw_markers(area, &[(x + swatch_width / 2, y)], shape, color)?
            }
            Swatch::Band(color) => area.draw(&Rectangle::new(
                [(x, y - step / 2 + 4), (x + swatch_width, y + step / 2 - 4)],
                color.filled(),
            ))?,
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

    /// On log axes the lines are given in the data's units, as the series are: a line at
    /// y = 1000 over data from 1 to 10 widens the axis to 10^3, not to 1000 decades.
    #[test]
    fn lines_on_log_axes_are_placed_at_their_logarithm() {
        let mut panel =
            Panel::new("t", "x", "y").with(Series::line("data", vec![(1.0, 1.0), (10.0, 10.0)], 0));
        panel.log_x = true;
        panel.log_y = true;
        panel.reference_lines.push((1000.0, "line".into()));
        panel.vertical_lines.push(VerticalLine {
            x: 100.0,
            color: 0,
            label: "v".into(),
        });
        let (x0, x1, y0, y1) = axis_ranges(&panel, &drawable_pieces(&panel), (400, 300));
        assert!((3.0..4.0).contains(&y1), "y axis to {y1}");
        assert!(y0 <= 0.0 && x0 <= 0.0, "{x0} {y0}");
        assert!(x1 < 4.0, "x axis to {x1}");
        figure("log.svg", &[panel], 1, (400, 300)).expect("draws");
    }

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

    /// Dark pixels in the top `rows` rows of a PNG figure.
    fn dark_pixels_on_top(png_bytes: &[u8], rows: u32) -> usize {
        let decoder = png::Decoder::new(std::io::Cursor::new(png_bytes));
        let mut reader = decoder.read_info().unwrap();
        let mut buf = vec![0; reader.output_buffer_size().unwrap()];
        let info = reader.next_frame(&mut buf).unwrap();
        assert_eq!(info.color_type, png::ColorType::Rgb);
        let stride = info.line_size;
        (0..rows as usize)
            .flat_map(|y| buf[y * stride..(y + 1) * stride].chunks(3))
            .filter(|p| p.iter().all(|&v| v < 128))
            .count()
    }

    #[test]
    fn png_figures_draw_their_text_with_the_embedded_font() {
        // An empty panel draws nothing in its top rows but its title: with a title, dark
        // pixels appear there (the glyphs), without one none do.
        let titled = figure_sized(
            Format::Png,
            "t.png",
            &[Panel::new("Title ABC", "t (s)", "q (m)")],
            1,
            (500, 300),
        )
        .unwrap();
        let untitled = figure_sized(
            Format::Png,
            "u.png",
            &[Panel::new("", "t (s)", "q (m)")],
            1,
            (500, 300),
        )
        .unwrap();
        assert_eq!(&titled[..4], b"\x89PNG");
        assert!(dark_pixels_on_top(&titled, 30) > 50, "no title drawn");
        assert_eq!(dark_pixels_on_top(&untitled, 30), 0);
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
