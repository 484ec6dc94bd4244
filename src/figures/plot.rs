//! Figures from series of points, laid out for print. Knows nothing about solvers or models:
//! callers hand it a [`Figure`] of panels of named (x, y) series and a [`Page`] (the size on
//! paper) and get the file back, to be written atomically.
//!
//! The conventions are a journal's: text in points that stay the same whatever the figure's
//! size (ticks and legend 7 pt, axis labels 8 pt, panel labels 9 pt); panels labelled (a), (b),
//! ... instead of titled; panels stacked in a column share their x axis, labelled once at the
//! bottom; one legend for the whole figure, in a strip above the panels where it covers no data;
//! tick counts chosen so that no two labels overprint; minus signs as U+2212; colours of the
//! Okabe-Ito palette (told apart by most colour-blind readers), with dashes where colours may
//! meet in greyscale. Every figure is drawn as SVG in dots of a 300 dpi print (plotters' SVG
//! backend) and converted to PDF and PNG from that one drawing ([`page::convert`]).

use plotters::coord::Shift;
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, Pos, VPos};
use plotters::style::FontTransform;

use crate::error::{Error, Result};
use crate::figures::page::{self, dots, pt, FigureOptions};
pub use crate::figures::page::{Format, Page};

/// One line of a panel.
#[derive(Debug, Clone)]
pub struct Series {
    /// The legend text (empty: not in the legend).
    pub name: String,
    /// The (x, y) points, in drawing order.
    pub points: Vec<(f64, f64)>,
    /// Index into the palette; 0 is black (for references).
    pub color: usize,
    /// A marker at every point.
    pub marker: Option<Marker>,
    /// Join the points by a line (false: markers only).
    pub line: bool,
    /// Line width, points [default: [`LINE_PT`]].
    pub width: Option<f64>,
    /// The line's dash pattern.
    pub dash: Dash,
}

/// The shape of a series' markers.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Marker {
    /// A filled circle.
    Circle,
    /// A circle's outline.
    OpenCircle,
    /// A filled triangle pointing up.
    TriangleUp,
    /// A triangle's outline pointing up (a bound, not a value).
    OpenTriangleUp,
    /// A filled triangle pointing down.
    TriangleDown,
    /// A diagonal cross.
    Cross,
    /// A filled square.
    Square,
}

/// A line's dash pattern.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Dash {
    /// Unbroken.
    #[default]
    Solid,
    /// Dashes of 3.5 pt, gaps of 2 pt.
    Dashed,
    /// Dots of 1 pt, gaps of 1.5 pt.
    Dotted,
    /// Dash, gap, dot, gap.
    DashDot,
}

impl Dash {
    /// The pattern, points: on, off, on, off, ...
    fn pattern(self) -> &'static [f64] {
        match self {
            Dash::Solid => &[],
            Dash::Dashed => &[3.5, 2.0],
            Dash::Dotted => &[1.0, 1.5],
            Dash::DashDot => &[3.5, 1.5, 1.0, 1.5],
        }
    }
}

/// Width of a data line, points.
pub const LINE_PT: f64 = 0.9;

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
            dash: Dash::Solid,
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

    /// Draw `marker` at the points as well.
    pub fn with_marker(mut self, marker: Marker) -> Self {
        self.marker = Some(marker);
        self
    }

    /// The series drawn `width` points wide.
    pub fn with_width(mut self, width: f64) -> Self {
        self.width = Some(width);
        self
    }

    /// The series drawn dashed.
    pub fn dashed(mut self) -> Self {
        self.dash = Dash::Dashed;
        self
    }

    /// The series drawn with `dash`.
    pub fn with_dash(mut self, dash: Dash) -> Self {
        self.dash = dash;
        self
    }

    fn stroke_pt(&self) -> f64 {
        self.width.unwrap_or(LINE_PT)
    }
}

/// One chart of a figure.
#[derive(Debug, Clone, Default)]
pub struct Panel {
    /// A short text after the panel's label, only where the axes do not say what the panel
    /// shows (the instant of a snapshot); empty for most panels.
    pub title: String,
    /// The x axis label.
    pub x_label: String,
    /// The y axis label.
    pub y_label: String,
    /// The series, drawn in order.
    pub series: Vec<Series>,
    /// Logarithmic x axis (decades); non-positive values are left out.
    pub log_x: bool,
    /// Logarithmic y axis (decades); non-positive values are left out.
    pub log_y: bool,
    /// Same length per unit on both axes (drawings of shapes).
    pub equal_aspect: bool,
    /// A margin at both ends of the x axis, as the y axis has (a curve that is not a history in
    /// time, whose ends would otherwise touch the frame).
    pub pad_x: bool,
    /// The x axis's range, instead of the data's extent.
    pub x_range: Option<(f64, f64)>,
    /// The y axis's range, instead of the data's extent.
    pub y_range: Option<(f64, f64)>,
    /// Horizontal thin grey lines (e.g. +-s_n), with their legend text (empty: none).
    pub reference_lines: Vec<(f64, String)>,
    /// Horizontal dashed dark grey lines (e.g. the overturning limit +-B), with their legend
    /// text (empty: none).
    pub dashed_lines: Vec<(f64, String)>,
    /// Thin vertical lines across the whole panel (a threshold), drawn under the series.
    pub vertical_lines: Vec<VerticalLine>,
    /// Short ticks along the bottom or top edge of the plotting area at instants (events in
    /// time): a rug that marks without covering the data.
    pub rug: Vec<RugMark>,
    /// Shaded stretches of the x axis across the whole panel (e.g. a state that lasts), drawn
    /// under the series.
    pub spans: Vec<Span>,
    /// Coloured rectangles in data coordinates (the cells of a map), drawn first.
    pub cells: Vec<Cell>,
    /// Names at places of the y axis (one per row of a chart of records), in place of its
    /// numbers, thinned and shortened to fit (see `named_ticks`).
    pub y_names: Vec<(f64, String)>,
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

/// A thin vertical line across a panel, at an abscissa; the first line of each non-empty label
/// gets a legend entry.
#[derive(Debug, Clone)]
pub struct VerticalLine {
    /// The abscissa.
    pub x: f64,
    /// Index into the palette.
    pub color: usize,
    /// The legend text (empty: none).
    pub label: String,
}

/// A tick of a rug at an abscissa; the legend shows the first mark of each non-empty label
/// with its marker.
#[derive(Debug, Clone)]
pub struct RugMark {
    /// The abscissa.
    pub x: f64,
    /// Index into the palette.
    pub color: usize,
    /// Along the top edge (pointing down) instead of the bottom edge (pointing up).
    pub top: bool,
    /// The legend text (empty: none).
    pub label: String,
    /// The marker the legend shows for it (that of the same events elsewhere in the figure).
    pub marker: Marker,
}

/// A filled rectangle in data coordinates.
#[derive(Debug, Clone, Copy)]
pub struct Cell {
    /// Lower left corner.
    pub from: (f64, f64),
    /// Upper right corner.
    pub to: (f64, f64),
    /// The fill.
    pub rgb: (u8, u8, u8),
}

impl Panel {
    /// An empty panel with a title (see [`Panel::title`]) and axis labels.
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

    /// A value of the y axis in axis coordinates: its log10 on a log axis (None where that has
    /// none), else itself.
    fn y_axis(&self, y: f64) -> Option<f64> {
        axis_value(self.log_y, y)
    }

    /// As [`Panel::y_axis`], for the x axis.
    fn x_axis(&self, x: f64) -> Option<f64> {
        axis_value(self.log_x, x)
    }
}

fn axis_value(log: bool, v: f64) -> Option<f64> {
    if log {
        (v > 0.0 && v.is_finite()).then(|| v.log10())
    } else {
        v.is_finite().then_some(v)
    }
}

/// A figure: panels in a grid, and how they share axes and a legend.
#[derive(Debug, Clone)]
pub struct Figure {
    /// The panels, row by row.
    pub panels: Vec<Panel>,
    /// Panels across.
    pub columns: usize,
    /// Panels stacked in a column share their x axis (one range, labelled at the bottom only).
    pub shared_x: bool,
    /// The plotting area's width over its height, for a page whose height is not given.
    pub aspect: f64,
    /// The least height of a plotting area then, mm (a narrow page keeps its panels legible
    /// by making them less wide than `aspect` says).
    pub min_plot_mm: f64,
    /// Extra entries of the figure's legend, after those of the panels (a colour bar's
    /// classes, say).
    pub extra_legend: Vec<(String, Swatch)>,
}

impl Figure {
    /// A figure of `panels`, `columns` across, x axes not shared, plotting areas 1.6 times as
    /// wide as high.
    pub fn new(panels: Vec<Panel>, columns: usize) -> Self {
        Figure {
            panels,
            columns: columns.max(1),
            shared_x: false,
            aspect: 1.6,
            min_plot_mm: MIN_PLOT_MM,
            extra_legend: Vec::new(),
        }
    }

    /// The figure with its panels' x axes shared down each column.
    pub fn shared_x(mut self) -> Self {
        self.shared_x = true;
        self
    }

    /// The figure with plotting areas `aspect` times as wide as high, and at least
    /// `min_mm` high, where the page's height is not given.
    pub fn aspect(mut self, aspect: f64, min_mm: f64) -> Self {
        self.aspect = aspect;
        self.min_plot_mm = min_mm.max(MIN_PLOT_MM);
        self
    }
}

/// The palette: black, then Okabe and Ito's colours for colour-blind readers (vermillion, blue,
/// bluish green, orange, reddish purple, sky blue), then a mid grey. Vermillion and blue, the
/// first two, also differ in greyscale.
const PALETTE: [RGBColor; 8] = [
    RGBColor(0, 0, 0),
    RGBColor(213, 94, 0),
    RGBColor(0, 114, 178),
    RGBColor(0, 158, 115),
    RGBColor(230, 159, 0),
    RGBColor(204, 121, 167),
    RGBColor(86, 180, 233),
    RGBColor(120, 120, 120),
];

/// The palette colour `i` (wrapping), as red, green, blue.
pub fn palette(i: usize) -> (u8, u8, u8) {
    let c = PALETTE[i % PALETTE.len()];
    (c.0, c.1, c.2)
}

/// Registers the embedded font as "sans-serif" (once), for measuring text; every drawing calls
/// this first.
pub fn register_fonts() {
    static ONCE: std::sync::Once = std::sync::Once::new();
    ONCE.call_once(|| {
        // The font is a fixed, valid file: a failure here is a broken build, and the tests
        // (which draw text) catch it.
        let loaded = plotters::style::register_font("sans-serif", FontStyle::Normal, page::FONT);
        assert!(loaded.is_ok(), "the embedded DejaVu Sans font loads");
    });
}

/// Text sizes, points.
pub const TICK_PT: f64 = 7.0;
/// Axis labels, points.
pub const LABEL_PT: f64 = 8.0;
/// The legend, points.
pub const LEGEND_PT: f64 = 7.0;
/// Panel labels (a), (b), ..., points.
pub const PANEL_PT: f64 = 9.0;

/// The font of `size_pt` points in colour `color`, anchored at `pos`. plotters writes 1/1.24 of
/// the size it is given into the SVG: given 1.24 times the size, the SVG gets it exactly.
pub fn font(size_pt: f64, pos: Pos) -> TextStyle<'static> {
    ("sans-serif", pt(size_pt) * 1.24)
        .into_font()
        .color(&BLACK)
        .pos(pos)
}

/// The width of `text` at `size_pt` points, dots. plotters measures at its own size, which for
/// DejaVu Sans draws each glyph 1.165 / 1.24 as wide as the SVG does: the measure is scaled to
/// what is drawn, with 3 % to spare for rounding.
pub fn text_width(text: &str, size_pt: f64) -> f64 {
    register_fonts();
    let measured = ("sans-serif", pt(size_pt) * 1.24)
        .into_font()
        .box_size(text)
        .map_or(0, |(w, _)| w);
    f64::from(measured) * 1.165 / 1.24 * 1.03
}

/// Draws `figure` on `page` in `format` (SVG text, PNG or PDF bytes).
pub fn render(format: Format, name: &str, figure: &Figure, page: &Page) -> Result<Vec<u8>> {
    let svg = svg(name, figure, page)?;
    page::convert(format, name, &svg, page.dpi)
}

/// The files of `figure` named `stem`.EXT in each format of `options`, on a page of its size
/// (`width_mm` wide where it gives none).
pub fn files(
    stem: &str,
    figure: &Figure,
    options: &FigureOptions,
    width_mm: f64,
) -> Result<Vec<(String, Vec<u8>)>> {
    let page = options.sizes.page(width_mm);
    let name = |format: Format| format!("{stem}.{}", format.extension());
    let svg = svg(&name(Format::Svg), figure, &page)?;
    options
        .formats
        .iter()
        .map(|&format| {
            let bytes = page::convert(format, &name(format), &svg, page.dpi)?;
            Ok((name(format), bytes))
        })
        .collect()
}

/// `figure` as SVG text two columns wide, its height as it needs.
pub fn double_column_svg(name: &str, figure: &Figure) -> Result<String> {
    svg(name, figure, &Page::double())
}

/// Draws `figure` on `page` as SVG text.
pub fn svg(name: &str, figure: &Figure, page: &Page) -> Result<String> {
    register_fonts();
    let layout = Layout::of(name, figure, page)?;
    let mut svg = String::new();
    {
        let (w, h) = (layout.width.round() as u32, layout.height.round() as u32);
        let root = SVGBackend::with_string(&mut svg, (w, h)).into_drawing_area();
        layout.draw(figure, &root).map_err(|e| Error::Plot {
            name: name.to_string(),
            message: e.to_string(),
        })?;
        root.present().map_err(|e| Error::Plot {
            name: name.to_string(),
            message: e.to_string(),
        })?;
    }
    let desc: Vec<String> = figure
        .panels
        .iter()
        .enumerate()
        .map(|(i, p)| {
            let what = [p.title.as_str(), p.y_label.as_str()]
                .into_iter()
                .filter(|s| !s.is_empty())
                .collect::<Vec<_>>()
                .join(", ");
            format!("{}: {what} against {}", panel_label(i), p.x_label)
        })
        .collect();
    let size = (page.width, page.height.unwrap_or(page::mm(layout.height)));
    Ok(page::on_paper(svg, size, &desc.join("; ")))
}

/// "(a)", "(b)", ... for panel `i`.
pub fn panel_label(i: usize) -> String {
    let letter = char::from(b'a' + (i % 26) as u8);
    format!("({letter})")
}

/// What a legend shows for one entry.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Swatch {
    /// A line of a palette colour, width (pt) and dash.
    Line(usize, f64, Dash),
    /// A line of a grey (0-255), solid or dashed.
    Grey(u8, Dash),
    /// A marker of a palette colour, with a line through it when the series has one.
    Marker(usize, Marker, Option<Dash>),
    /// A pale band of a palette colour (strong: a stronger tint).
    Band(usize, bool),
    /// A filled square of a colour.
    Fill((u8, u8, u8)),
}

/// The legend of a figure: the entries of every panel, in panel order, each label once.
fn legend_entries(figure: &Figure) -> Vec<(String, Swatch)> {
    let mut entries: Vec<(String, Swatch)> = Vec::new();
    let mut push = |label: &str, swatch: Swatch| {
        if !label.is_empty() && !entries.iter().any(|(l, _)| l == label) {
            entries.push((label.to_string(), swatch));
        }
    };
    for panel in &figure.panels {
        for s in &panel.series {
            if s.points.is_empty() {
                continue;
            }
            let swatch = match (s.line, s.marker) {
                (false, Some(m)) => Swatch::Marker(s.color, m, None),
                (true, Some(m)) => Swatch::Marker(s.color, m, Some(s.dash)),
                _ => Swatch::Line(s.color, s.stroke_pt(), s.dash),
            };
            push(&s.name, swatch);
        }
        for (_, label) in &panel.reference_lines {
            push(label, Swatch::Grey(REFERENCE_GREY, Dash::Solid));
        }
        for (_, label) in &panel.dashed_lines {
            push(label, Swatch::Grey(DASHED_GREY, Dash::Dashed));
        }
        for v in &panel.vertical_lines {
            push(&v.label, Swatch::Line(v.color, 0.5, Dash::Solid));
        }
        for span in &panel.spans {
            push(&span.label, Swatch::Band(span.color, span.strong));
        }
        for r in &panel.rug {
            push(&r.label, Swatch::Marker(r.color, r.marker, None));
        }
    }
    for (label, swatch) in &figure.extra_legend {
        push(label, *swatch);
    }
    entries
}

const REFERENCE_GREY: u8 = 150;
const DASHED_GREY: u8 = 70;
/// The grid at the major ticks.
const GRID: RGBColor = RGBColor(230, 230, 230);

/// Outer margin, mm.
const MARGIN_MM: f64 = 1.0;
/// Tick length, pt.
const TICK_LEN_PT: f64 = 2.5;
/// Gap between a tick and its label, and between labels, pt.
const GAP_PT: f64 = 2.0;
/// Length of a legend swatch, pt.
const SWATCH_PT: f64 = 14.0;
/// Gap between legend entries in a row, pt.
const ENTRY_GAP_PT: f64 = 9.0;
/// Marker radius, pt.
const MARKER_PT: f64 = 2.2;
/// The narrowest plotting area a figure puts beside another, mm: on a narrower page its panels
/// wrap to fewer across.
const MIN_ACROSS_MM: f64 = 24.0;
/// Smallest plotting area height, mm: below it the page is refused as too small.
const MIN_PLOT_MM: f64 = 12.0;

/// Ticks of an axis: positions (axis coordinates), their labels, and unlabelled minor ticks.
#[derive(Debug, Clone, Default)]
struct Ticks {
    major: Vec<(f64, String)>,
    minor: Vec<f64>,
}

/// Where everything goes, dots.
struct Layout {
    width: f64,
    height: f64,
    /// The legend's entries, each with its upper left corner.
    legend: Vec<(String, Swatch, (f64, f64))>,
    /// Per panel: the plotting area (left, top, width, height), its ranges and ticks, and
    /// whether its x tick labels and axis label are drawn.
    panels: Vec<PanelLayout>,
    /// Panel labels drawn at all (more than one panel).
    labelled: bool,
}

struct PanelLayout {
    area: (f64, f64, f64, f64),
    ranges: (f64, f64, f64, f64),
    x_ticks: Ticks,
    y_ticks: Ticks,
    x_labelled: bool,
    /// The left edge of the panel's cell, for its label and y axis label.
    cell_left: f64,
}

/// The axis ranges of a panel's data, unpadded, in axis coordinates: (x0, x1, y0, y1).
fn data_extent(panel: &Panel) -> (f64, f64, f64, f64) {
    let (mut x0, mut x1, mut y0, mut y1) = (f64::MAX, f64::MIN, f64::MAX, f64::MIN);
    for s in &panel.series {
        for &(x, y) in &s.points {
            if let (Some(x), Some(y)) = (panel.x_axis(x), panel.y_axis(y)) {
                x0 = x0.min(x);
                x1 = x1.max(x);
                y0 = y0.min(y);
                y1 = y1.max(y);
            }
        }
    }
    for c in &panel.cells {
        for (x, y) in [c.from, c.to] {
            if let (Some(x), Some(y)) = (panel.x_axis(x), panel.y_axis(y)) {
                x0 = x0.min(x);
                x1 = x1.max(x);
                y0 = y0.min(y);
                y1 = y1.max(y);
            }
        }
    }
    for &(level, _) in panel.reference_lines.iter().chain(&panel.dashed_lines) {
        if let Some(level) = panel.y_axis(level) {
            y0 = y0.min(level);
            y1 = y1.max(level);
        }
    }
    for v in &panel.vertical_lines {
        if let Some(x) = panel.x_axis(v.x) {
            x0 = x0.min(x);
            x1 = x1.max(x);
        }
    }
    if x0 > x1 {
        (x0, x1) = (0.0, 1.0);
    }
    if y0 > y1 {
        (y0, y1) = (0.0, 1.0);
    }
    if let Some((a, b)) = panel.x_range {
        if let (Some(a), Some(b)) = (panel.x_axis(a), panel.x_axis(b)) {
            (x0, x1) = (a, b);
        }
    }
    if let Some((a, b)) = panel.y_range {
        if let (Some(a), Some(b)) = (panel.y_axis(a), panel.y_axis(b)) {
            (y0, y1) = (a, b);
        }
    }
    (x0, x1, y0, y1)
}

/// `lo..hi` widened by `fraction` of its span at each end (a span of zero by its size, or 1).
fn pad(lo: f64, hi: f64, fraction: f64) -> (f64, f64) {
    let span = if hi > lo { hi - lo } else { lo.abs().max(1.0) };
    (lo - fraction * span, hi + fraction * span)
}

/// The padded ranges of a panel (before an equal aspect is made).
fn padded_ranges(panel: &Panel, extent: (f64, f64, f64, f64)) -> (f64, f64, f64, f64) {
    let (x0, x1, y0, y1) = extent;
    let (x0, x1) = if panel.x_range.is_some() {
        (x0, x1)
    } else if panel.log_x || panel.equal_aspect || panel.pad_x || !panel.cells.is_empty() {
        if panel.cells.is_empty() {
            pad(x0, x1, 0.03)
        } else {
            (x0, x1)
        }
    } else if x1 > x0 {
        (x0, x1)
    } else {
        pad(x0, x1, 0.05)
    };
    let (y0, y1) = if panel.y_range.is_some() || !panel.cells.is_empty() {
        (y0, y1)
    } else {
        pad(y0, y1, 0.05)
    };
    (x0, x1, y0, y1)
}

/// A number as a tick label: the decimals of `step`, the minus sign U+2212, no "-0".
fn tick_text(v: f64, step: f64) -> String {
    // The fewest decimals that write the step exactly (2.5 needs one, 0.25 two).
    let decimals = (0..12)
        .find(|&d| {
            let scaled = step * 10f64.powi(d);
            (scaled - scaled.round()).abs() <= 1e-9 * scaled.max(1.0)
        })
        .unwrap_or(12) as usize;
    let text = format!("{v:.decimals$}");
    let zero = text
        .trim_start_matches('-')
        .chars()
        .all(|c| c == '0' || c == '.');
    if zero {
        "0".to_string()
    } else {
        text.replace('-', "−")
    }
}

/// Superscript digits and minus of `n`.
fn superscript(n: i64) -> String {
    n.to_string()
        .chars()
        .map(|c| match c {
            '-' => '⁻',
            '0' => '⁰',
            '1' => '¹',
            '2' => '²',
            '3' => '³',
            '4' => '⁴',
            '5' => '⁵',
            '6' => '⁶',
            '7' => '⁷',
            '8' => '⁸',
            _ => '⁹',
        })
        .collect()
}

/// Linear ticks over `lo..hi` at a step of 1, 2, 2.5 or 5 times a power of ten, at most `max`
/// of them. Numbers of 10^4 and more, or below 10^-3, are written m×10^n.
fn linear_ticks(lo: f64, hi: f64, max: usize) -> Ticks {
    let span = (hi - lo).abs().max(f64::MIN_POSITIVE);
    let max = max.max(2) as f64;
    let mut step = f64::NAN;
    let base = 10f64.powf((span / max).log10().floor());
    'search: for k in [base, base * 10.0] {
        for m in [1.0, 2.0, 2.5, 5.0] {
            let s = m * k;
            if (hi / s + 1e-9).floor() - (lo / s - 1e-9).ceil() + 1.0 <= max {
                step = s;
                break 'search;
            }
        }
    }
    if !step.is_finite() {
        step = base * 10.0;
    }
    // Within rounding of a multiple of the step (0.3 / 0.1 = 2.9999999999999996) counts.
    let first = (lo / step - 1e-9).ceil() as i64;
    let last = (hi / step + 1e-9).floor() as i64;
    let big = lo.abs().max(hi.abs());
    let exponent = if big >= 1e4 || (big < 1e-3 && big > 0.0) {
        Some(big.log10().floor() as i64)
    } else {
        None
    };
    let major = (first..=last)
        .map(|i| {
            let v = i as f64 * step;
            let text = match exponent {
                None => tick_text(v, step),
                Some(e) => {
                    let scale = 10f64.powi(e as i32);
                    let m = tick_text(v / scale, step / scale);
                    if m == "0" {
                        m
                    } else {
                        format!("{m}×10{}", superscript(e))
                    }
                }
            };
            (v, text)
        })
        .collect();
    Ticks {
        major,
        minor: Vec::new(),
    }
}

/// Ticks of a log axis over `lo..hi` (log10 of the values): the decades, labelled (0.01 ... 1000
/// as decimals, else 10^n) at most `max` of them (every second or third decade when more), and
/// 2-9 times each as minor ticks; within less than a decade, 1, 2 and 5 times labelled.
fn log_ticks(lo: f64, hi: f64, max: usize) -> Ticks {
    let label = |e: i64, m: f64| -> String {
        let v = m * 10f64.powi(e as i32);
        if (-3..4).contains(&e) {
            flexrock_core::base::format::significant(v, 2)
        } else if m == 1.0 {
            format!("10{}", superscript(e))
        } else {
            format!("{}×10{}", m, superscript(e))
        }
    };
    let (e0, e1) = (lo.floor() as i64, hi.ceil() as i64);
    let decades: Vec<i64> = (e0..=e1)
        .filter(|&e| (lo..=hi).contains(&(e as f64)))
        .collect();
    let mut ticks = Ticks::default();
    if decades.len() >= 2 {
        let every = decades.len().div_ceil(max.max(2));
        for &e in &decades {
            if e.rem_euclid(every as i64) == 0 {
                ticks.major.push((e as f64, label(e, 1.0)));
            } else {
                ticks.minor.push(e as f64);
            }
        }
        if every == 1 {
            for e in e0..=e1 {
                for m in 2..10 {
                    let v = e as f64 + f64::from(m).log10();
                    if (lo..=hi).contains(&v) {
                        ticks.minor.push(v);
                    }
                }
            }
        }
    } else {
        for e in e0..=e1 {
            for m in [1.0f64, 2.0, 5.0] {
                let v = e as f64 + m.log10();
                if (lo..=hi).contains(&v) {
                    ticks.major.push((v, label(e, m)));
                }
            }
            for m in [3.0f64, 4.0, 6.0, 7.0, 8.0, 9.0] {
                let v = e as f64 + m.log10();
                if (lo..=hi).contains(&v) {
                    ticks.minor.push(v);
                }
            }
        }
        if ticks.major.len() < 2 {
            return linear_on_log(lo, hi, max);
        }
    }
    ticks
}

/// Linear ticks of the values of a log axis spanning less than a factor of 2.
fn linear_on_log(lo: f64, hi: f64, max: usize) -> Ticks {
    let t = linear_ticks(10f64.powf(lo), 10f64.powf(hi), max);
    Ticks {
        major: t
            .major
            .into_iter()
            .filter(|(v, _)| *v > 0.0)
            .map(|(v, s)| (v.log10(), s))
            .collect(),
        minor: Vec::new(),
    }
}

/// The ticks of an axis over `lo..hi` with room for labels `room` dots long each way: as many
/// as fit with a label every `per_label(text)` dots.
fn fit_ticks(log: bool, lo: f64, hi: f64, length: f64, per_label: impl Fn(&str) -> f64) -> Ticks {
    let mut max = 10;
    let mut fewest: Option<Ticks> = None;
    loop {
        let ticks = if log {
            log_ticks(lo, hi, max)
        } else {
            linear_ticks(lo, hi, max)
        };
        let n = ticks.major.len();
        let need: f64 = ticks
            .major
            .iter()
            .map(|(_, t)| per_label(t))
            .fold(0.0, f64::max);
        if need * n as f64 <= length {
            // Where this step leaves fewer than two labels, the two ends of the finer step
            // before it, if they fit (a label each at the ends of the axis is far apart).
            if let (Some(before), 0 | 1) = (&fewest, n) {
                let (first, last) = (before.major.first(), before.major.last());
                if let (Some(a), Some(b)) = (first, last) {
                    let need = per_label(&a.1).max(per_label(&b.1));
                    if before.major.len() >= 2 && 2.0 * need <= length {
                        return Ticks {
                            major: vec![a.clone(), b.clone()],
                            minor: Vec::new(),
                        };
                    }
                }
            }
            return ticks;
        }
        if max <= 2 {
            return ticks;
        }
        max = (n.saturating_sub(1)).clamp(2, max - 1);
        fewest = Some(ticks);
    }
}

/// The ticks of a y axis of names at places (equally spaced, in order): where a name a line
/// apart would overprint the next, every k-th is labelled (from the first) and the others get a
/// minor tick; a name wider than `widest` dots is shortened at its end with an ellipsis.
fn named_ticks(names: &[(f64, String)], range: (f64, f64), length: f64, widest: f64) -> Ticks {
    let inside: Vec<&(f64, String)> = names
        .iter()
        .filter(|(y, _)| *y >= range.0 && *y <= range.1)
        .collect();
    let spacing = inside
        .windows(2)
        .map(|w| (w[1].0 - w[0].0).abs())
        .fold(f64::INFINITY, f64::min);
    let per_name = spacing * length / (range.1 - range.0);
    let line = pt(TICK_PT) * 1.2;
    let every = if per_name.is_finite() && per_name > 0.0 {
        (line / per_name).ceil().max(1.0) as usize
    } else {
        1
    };
    let mut ticks = Ticks::default();
    for (i, (y, name)) in inside.into_iter().enumerate() {
        if i % every == 0 {
            ticks.major.push((*y, shortened(name, widest)));
        } else {
            ticks.minor.push(*y);
        }
    }
    ticks
}

/// `text`, or as much of its start as fits in `widest` dots at the tick size with an ellipsis.
fn shortened(text: &str, widest: f64) -> String {
    if text_width(text, TICK_PT) <= widest {
        return text.to_string();
    }
    let chars: Vec<char> = text.chars().collect();
    for keep in (1..chars.len()).rev() {
        let short = format!("{}…", chars[..keep].iter().collect::<String>().trim_end());
        if text_width(&short, TICK_PT) <= widest {
            return short;
        }
    }
    "…".to_string()
}

impl Layout {
    fn of(name: &str, figure: &Figure, page: &Page) -> Result<Layout> {
        let bad_size = |message: String| {
            Error::from(flexrock_core::Error::InvalidParameter {
                key: "--height".to_string(),
                value: format!(
                    "{} mm",
                    flexrock_core::base::format::significant(page.height.unwrap_or(0.0), 4)
                ),
                rule: format!("{message} ({name})"),
            })
        };
        let width = dots(page.width);
        let margin = dots(MARGIN_MM);
        // Fewer panels across where the page is too narrow for them: each plotting area at
        // least MIN_ACROSS_MM wide.
        let rough_left = pt(TICK_PT) * 3.0 + pt(TICK_LEN_PT) + pt(GAP_PT) + pt(LABEL_PT) * 1.4;
        let columns = (1..=figure.columns)
            .rev()
            .find(|&c| {
                (width - 2.0 * margin) / c as f64 - rough_left - pt(TICK_PT) * 1.6
                    >= dots(MIN_ACROSS_MM)
            })
            .unwrap_or(1);
        let rows = figure.panels.len().div_ceil(columns).max(1);
        let labelled = figure.panels.len() > 1;
        // The legend: entries in rows across the page.
        let entries = legend_entries(figure);
        let line_h = pt(LEGEND_PT) * 1.45;
        let mut legend = Vec::new();
        let (mut x, mut y) = (margin, margin);
        for (label, swatch) in entries {
            let w = pt(SWATCH_PT) + pt(3.0) + text_width(&label, LEGEND_PT);
            if x > margin && x + w > width - margin {
                x = margin;
                y += line_h;
            }
            legend.push((label, swatch, (x, y)));
            x += w + pt(ENTRY_GAP_PT);
        }
        let legend_h = if legend.is_empty() {
            0.0
        } else {
            y + line_h + pt(3.0) - margin
        };
        // Vertical parts: per row a panel label line, the plotting area, and (unless shared)
        // an x axis of tick labels and its label.
        // A lone panel's title, drawn above it, needs its own line too (else it runs into the
        // legend).
        let titled = figure.panels.iter().any(|p| !p.title.is_empty());
        let label_h = if labelled {
            pt(PANEL_PT) * 1.15 + pt(TICK_PT) * 0.5
        } else if titled {
            pt(LABEL_PT) * 1.15 + pt(TICK_PT) * 0.6
        } else {
            pt(TICK_PT) * 0.6
        };
        let x_axis_h = pt(TICK_LEN_PT) + pt(GAP_PT) + pt(TICK_PT) * 1.2 + pt(LABEL_PT) * 1.3;
        let x_axes = if figure.shared_x { 1 } else { rows };
        let fixed = 2.0 * margin + legend_h + rows as f64 * label_h + x_axes as f64 * x_axis_h;
        // Horizontal parts: the y axis's labels (measured below), the plotting area, a margin
        // for the last x tick label's half.
        let right_pad = pt(TICK_PT) * 1.6;
        let y_label_h = pt(LABEL_PT) * 1.4;
        let guess_y_labels = rough_left;
        let cell_w = (width - 2.0 * margin) / columns as f64;
        let plot_h = match page.height {
            Some(h) => {
                let plot_h = (dots(h) - fixed) / rows as f64;
                if plot_h < dots(MIN_PLOT_MM) {
                    return Err(bad_size(format!(
                        "must leave each of the {rows} rows of panels at least {MIN_PLOT_MM} mm: give at least {} mm",
                        flexrock_core::base::format::significant(page::mm(fixed + rows as f64 * dots(MIN_PLOT_MM)), 3)
                    )));
                }
                plot_h
            }
            None => ((cell_w - guess_y_labels - right_pad) / figure.aspect)
                .max(dots(figure.min_plot_mm)),
        };
        let height = page.height.map_or(fixed + rows as f64 * plot_h, dots);
        // Ranges: shared down a column when asked.
        let mut ranges: Vec<(f64, f64, f64, f64)> = figure
            .panels
            .iter()
            .map(|p| padded_ranges(p, data_extent(p)))
            .collect();
        if figure.shared_x {
            for c in 0..columns {
                let members: Vec<usize> = (c..figure.panels.len()).step_by(columns).collect();
                let lo = members
                    .iter()
                    .map(|&i| ranges[i].0)
                    .fold(f64::MAX, f64::min);
                let hi = members
                    .iter()
                    .map(|&i| ranges[i].1)
                    .fold(f64::MIN, f64::max);
                for &i in &members {
                    ranges[i].0 = lo;
                    ranges[i].1 = hi;
                }
            }
        }
        // The y ticks (their count depends on the height only) and the widest of their
        // labels, which sets the room left of every plotting area.
        let y_ticks: Vec<Ticks> = figure
            .panels
            .iter()
            .zip(&ranges)
            .map(|(p, r)| {
                if p.y_names.is_empty() {
                    fit_ticks(p.log_y, r.2, r.3, plot_h, |_| pt(TICK_PT) * 2.2)
                } else {
                    // Names take at most 40 % of the panel's cell across.
                    named_ticks(&p.y_names, (r.2, r.3), plot_h, 0.4 * cell_w)
                }
            })
            .collect();
        let widest = y_ticks
            .iter()
            .flat_map(|t| t.major.iter().map(|(_, s)| text_width(s, TICK_PT)))
            .fold(0.0, f64::max);
        let left_room = widest + pt(TICK_LEN_PT) + pt(GAP_PT) + y_label_h;
        let plot_w = cell_w - left_room - right_pad;
        if plot_w < dots(MIN_PLOT_MM) {
            return Err(Error::from(flexrock_core::Error::InvalidParameter {
                key: "--width".to_string(),
                value: format!("{} mm", flexrock_core::base::format::significant(page.width, 4)),
                rule: format!(
                    "must leave each of the {columns} panels across at least {MIN_PLOT_MM} mm of plotting area ({name})"
                ),
            }));
        }
        let mut panels = Vec::new();
        for (i, panel) in figure.panels.iter().enumerate() {
            let (row, col) = (i / columns, i % columns);
            let x_rows_above = if figure.shared_x { 0 } else { row };
            let top = margin
                + legend_h
                + (row + 1) as f64 * label_h
                + row as f64 * plot_h
                + x_rows_above as f64 * x_axis_h;
            let cell_left = margin + col as f64 * cell_w;
            let area = (cell_left + left_room, top, plot_w, plot_h);
            let mut r = ranges[i];
            let mut y_t = y_ticks[i].clone();
            if panel.equal_aspect {
                // Widen one range so that a unit is as long across as up.
                let scale = ((r.1 - r.0) / plot_w).max((r.3 - r.2) / plot_h);
                let (xc, yc) = (0.5 * (r.0 + r.1), 0.5 * (r.2 + r.3));
                r = (
                    xc - 0.5 * scale * plot_w,
                    xc + 0.5 * scale * plot_w,
                    yc - 0.5 * scale * plot_h,
                    yc + 0.5 * scale * plot_h,
                );
                y_t = fit_ticks(panel.log_y, r.2, r.3, plot_h, |_| pt(TICK_PT) * 2.2);
            }
            let x_ticks = fit_ticks(panel.log_x, r.0, r.1, plot_w, |s| {
                text_width(s, TICK_PT) + pt(TICK_PT) * 0.8
            });
            let bottom_row = row + 1 == rows || i + columns >= figure.panels.len();
            panels.push(PanelLayout {
                area,
                ranges: r,
                x_ticks,
                y_ticks: y_t,
                x_labelled: !figure.shared_x || bottom_row,
                cell_left,
            });
        }
        Ok(Layout {
            width,
            height,
            legend,
            panels,
            labelled,
        })
    }

    fn draw<DB: DrawingBackend>(
        &self,
        figure: &Figure,
        root: &DrawingArea<DB, Shift>,
    ) -> std::result::Result<(), Box<dyn std::error::Error>>
    where
        DB::ErrorType: 'static,
    {
        root.fill(&WHITE)?;
        let label_text = |i: usize, panel: &Panel| match panel.title.as_str() {
            "" => panel_label(i),
            title => format!("{} {title}", panel_label(i)),
        };
        // One size for every panel's label: set smaller (down to 6 pt) where one would run
        // into the next panel's.
        let label_size = (figure.panels.iter().zip(&self.panels).enumerate())
            .map(|(i, (panel, layout))| {
                let (left, _, w, _) = layout.area;
                let room = left + w - layout.cell_left;
                PANEL_PT * room / text_width(&label_text(i, panel), PANEL_PT)
            })
            .fold(PANEL_PT, f64::min)
            .max(6.0);
        for (i, (panel, layout)) in figure.panels.iter().zip(&self.panels).enumerate() {
            draw_panel(root, panel, layout)?;
            if self.labelled {
                let text = label_text(i, panel);
                let (_, top, _, _) = layout.area;
                let size = label_size;
                root.draw(&Text::new(
                    text,
                    (
                        layout.cell_left.round() as i32,
                        (top - pt(TICK_PT) * 0.6).round() as i32,
                    ),
                    font(size, Pos::new(HPos::Left, VPos::Bottom)),
                ))?;
            } else if !panel.title.is_empty() {
                let (left, top, w, _) = layout.area;
                // Set smaller (down to 6 pt) where it is wider than the plotting area.
                let size = (LABEL_PT * w / text_width(&panel.title, LABEL_PT)).clamp(6.0, LABEL_PT);
                root.draw(&Text::new(
                    panel.title.clone(),
                    ((left + w / 2.0) as i32, (top - pt(TICK_PT) * 0.6) as i32),
                    font(size, Pos::new(HPos::Center, VPos::Bottom)),
                ))?;
            }
        }
        for (label, swatch, (x, y)) in &self.legend {
            let mid = y + pt(LEGEND_PT) * 0.72;
            draw_swatch(root, *swatch, (*x, mid))?;
            root.draw(&Text::new(
                label.clone(),
                ((x + pt(SWATCH_PT) + pt(3.0)) as i32, mid as i32),
                font(LEGEND_PT, Pos::new(HPos::Left, VPos::Center)),
            ))?;
        }
        Ok(())
    }
}

fn dot(v: f64) -> i32 {
    v.round() as i32
}

fn width_dots(points: f64) -> u32 {
    pt(points).round().max(1.0) as u32
}

fn colour(i: usize) -> RGBColor {
    PALETTE[i % PALETTE.len()]
}

fn grey(v: u8) -> RGBColor {
    RGBColor(v, v, v)
}

/// The pale tint of a palette colour for a span: three fifths white (strong: one fifth).
fn tint(color: usize, strong: bool) -> RGBColor {
    let c = colour(color);
    let (own, white) = if strong { (4, 1) } else { (2, 3) };
    let pale = |v: u8| ((own * u16::from(v) + white * 255) / 5) as u8;
    RGBColor(pale(c.0), pale(c.1), pale(c.2))
}

/// Draws the polyline `points` (dots) in `style`, cut into dashes of `dash`.
fn draw_path<DB: DrawingBackend>(
    root: &DrawingArea<DB, Shift>,
    points: &[(f64, f64)],
    style: ShapeStyle,
    dash: Dash,
) -> std::result::Result<(), Box<dyn std::error::Error>>
where
    DB::ErrorType: 'static,
{
    if points.len() < 2 {
        return Ok(());
    }
    let pattern: Vec<f64> = dash.pattern().iter().map(|&p| pt(p)).collect();
    if pattern.is_empty() {
        root.draw(&PathElement::new(
            points
                .iter()
                .map(|&(x, y)| (dot(x), dot(y)))
                .collect::<Vec<_>>(),
            style,
        ))?;
        return Ok(());
    }
    // Walk the path, switching the pen on and off at the pattern's lengths.
    let (mut k, mut left, mut on) = (0usize, pattern[0], true);
    let mut piece: Vec<(i32, i32)> = vec![(dot(points[0].0), dot(points[0].1))];
    for w in points.windows(2) {
        let (mut a, b) = (w[0], w[1]);
        let mut len = ((b.0 - a.0).powi(2) + (b.1 - a.1).powi(2)).sqrt();
        while len > left {
            let f = left / len;
            let p = (a.0 + f * (b.0 - a.0), a.1 + f * (b.1 - a.1));
            if on {
                piece.push((dot(p.0), dot(p.1)));
                root.draw(&PathElement::new(std::mem::take(&mut piece), style))?;
            } else {
                piece = vec![(dot(p.0), dot(p.1))];
            }
            len -= left;
            a = p;
            on = !on;
            k = (k + 1) % pattern.len();
            left = pattern[k];
        }
        left -= len;
        if on {
            piece.push((dot(b.0), dot(b.1)));
        }
    }
    if on && piece.len() > 1 {
        root.draw(&PathElement::new(piece, style))?;
    }
    Ok(())
}

/// Draws a marker of `shape` centred at `(x, y)` (dots).
fn draw_marker<DB: DrawingBackend>(
    root: &DrawingArea<DB, Shift>,
    shape: Marker,
    color: RGBColor,
    (x, y): (f64, f64),
) -> std::result::Result<(), Box<dyn std::error::Error>>
where
    DB::ErrorType: 'static,
{
    let r = pt(MARKER_PT);
    let at = |dx: f64, dy: f64| (dot(x + dx), dot(y + dy));
    let outline = color.stroke_width(width_dots(0.7));
    match shape {
        Marker::Circle => root.draw(&Circle::new(at(0.0, 0.0), dot(r * 0.9), color.filled()))?,
        Marker::OpenCircle => {
            root.draw(&Circle::new(at(0.0, 0.0), dot(r * 0.9), WHITE.filled()))?;
            root.draw(&Circle::new(at(0.0, 0.0), dot(r * 0.9), outline))?
        }
        Marker::Square => root.draw(&Rectangle::new(
            [at(-0.8 * r, -0.8 * r), at(0.8 * r, 0.8 * r)],
            color.filled(),
        ))?,
        Marker::TriangleUp | Marker::OpenTriangleUp => {
            let corners = vec![at(0.0, -1.1 * r), at(r, 0.75 * r), at(-r, 0.75 * r)];
            if shape == Marker::TriangleUp {
                root.draw(&Polygon::new(corners, color.filled()))?
            } else {
                root.draw(&Polygon::new(corners.clone(), WHITE.filled()))?;
                let mut closed = corners.clone();
                closed.push(corners[0]);
                root.draw(&PathElement::new(closed, outline))?
            }
        }
        Marker::TriangleDown => root.draw(&Polygon::new(
            vec![at(0.0, 1.1 * r), at(r, -0.75 * r), at(-r, -0.75 * r)],
            color.filled(),
        ))?,
        Marker::Cross => {
            let s = 0.85 * r;
            let style = color.stroke_width(width_dots(0.9));
            root.draw(&PathElement::new(vec![at(-s, -s), at(s, s)], style))?;
            root.draw(&PathElement::new(vec![at(-s, s), at(s, -s)], style))?
        }
    }
    Ok(())
}

/// Draws a legend swatch whose left end is at `(x, mid)` (dots).
fn draw_swatch<DB: DrawingBackend>(
    root: &DrawingArea<DB, Shift>,
    swatch: Swatch,
    (x, mid): (f64, f64),
) -> std::result::Result<(), Box<dyn std::error::Error>>
where
    DB::ErrorType: 'static,
{
    let w = pt(SWATCH_PT);
    let line = [(x, mid), (x + w, mid)];
    match swatch {
        Swatch::Line(c, width, dash) => {
            draw_path(root, &line, colour(c).stroke_width(width_dots(width)), dash)?
        }
        Swatch::Grey(v, dash) => {
            draw_path(root, &line, grey(v).stroke_width(width_dots(0.6)), dash)?
        }
        Swatch::Marker(c, m, through) => {
            if let Some(dash) = through {
                draw_path(
                    root,
                    &line,
                    colour(c).stroke_width(width_dots(LINE_PT)),
                    dash,
                )?;
            }
            draw_marker(root, m, colour(c), (x + w / 2.0, mid))?
        }
        Swatch::Band(c, strong) => root.draw(&Rectangle::new(
            [
                (dot(x), dot(mid - pt(LEGEND_PT) * 0.4)),
                (dot(x + w), dot(mid + pt(LEGEND_PT) * 0.4)),
            ],
            tint(c, strong).filled(),
        ))?,
        Swatch::Fill(rgb) => {
            let corners = [
                (dot(x + w * 0.2), dot(mid - pt(LEGEND_PT) * 0.45)),
                (dot(x + w * 0.8), dot(mid + pt(LEGEND_PT) * 0.45)),
            ];
            root.draw(&Rectangle::new(
                corners,
                RGBColor(rgb.0, rgb.1, rgb.2).filled(),
            ))?;
            root.draw(&Rectangle::new(
                corners,
                grey(120).stroke_width(width_dots(0.4)),
            ))?
        }
    }
    Ok(())
}

/// A filled rectangle in dots: left, top, right, bottom, colour.
type DotRectangle = (f64, f64, f64, f64, (u8, u8, u8));

/// The cells of `panel` as they show at the figure's resolution, as few rectangles (left, top,
/// right, bottom, colour; dots, the right and bottom edges outside): each dot of the plotting area takes the colour of the cell over
/// its centre (the last drawn), and the dots are gathered into runs along each row, a run that
/// continues one of the row above into the same rectangle. So a map of a million cells is no
/// more rectangles than its plotting area has changes of colour along its rows, whatever the
/// grid.
fn cell_rectangles(panel: &Panel, layout: &PanelLayout) -> Vec<DotRectangle> {
    if panel.cells.is_empty() {
        return Vec::new();
    }
    let (left, top, w, h) = layout.area;
    let (x0, x1, y0, y1) = layout.ranges;
    let (nx, ny) = (w.round().max(1.0) as usize, h.round().max(1.0) as usize);
    // The dots whose centres lie in [a, b), a and b in dots from the area's edge.
    let dots_in = |a: f64, b: f64, n: usize| {
        let first = (a - 0.5).ceil().clamp(0.0, n as f64) as usize;
        let end = (b - 0.5).ceil().clamp(0.0, n as f64) as usize;
        first..end.max(first)
    };
    let mut colours: Vec<(u8, u8, u8)> = Vec::new();
    // 0: no cell; k: colours[k - 1].
    let mut grid = vec![0usize; nx * ny];
    for c in &panel.cells {
        let (Some(ax), Some(ay), Some(bx), Some(by)) = (
            panel.x_axis(c.from.0),
            panel.y_axis(c.from.1),
            panel.x_axis(c.to.0),
            panel.y_axis(c.to.1),
        ) else {
            continue;
        };
        let (xa, xb) = ((ax - x0) / (x1 - x0) * w, (bx - x0) / (x1 - x0) * w);
        let (ya, yb) = ((y1 - ay) / (y1 - y0) * h, (y1 - by) / (y1 - y0) * h);
        let k = match colours.iter().position(|&rgb| rgb == c.rgb) {
            Some(k) => k + 1,
            None => {
                colours.push(c.rgb);
                colours.len()
            }
        };
        let across = dots_in(xa.min(xb), xa.max(xb), nx);
        for j in dots_in(ya.min(yb), ya.max(yb), ny) {
            grid[j * nx..(j + 1) * nx][across.clone()].fill(k);
        }
    }
    let mut done = Vec::new();
    // Rectangles still growing down: (first dot, end dot, colour) -> their top row.
    let mut open: std::collections::HashMap<(usize, usize, usize), usize> = Default::default();
    for j in 0..=ny {
        let mut runs = std::collections::HashMap::new();
        if j < ny {
            let row = &grid[j * nx..(j + 1) * nx];
            let mut i = 0;
            while i < nx {
                let (k, start) = (row[i], i);
                while i < nx && row[i] == k {
                    i += 1;
                }
                if k != 0 {
                    let top_row = open.remove(&(start, i, k)).unwrap_or(j);
                    runs.insert((start, i, k), top_row);
                }
            }
        }
        done.extend(open.drain().map(|((a, b, k), t)| (t, a, b, j, k)));
        open = runs;
    }
    // In a fixed order, so that the same figure gives the same bytes.
    done.sort_unstable();
    done.into_iter()
        .map(|(t, a, b, end, k)| {
            (
                left + a as f64,
                top + t as f64,
                left + b as f64,
                top + end as f64,
                colours[k - 1],
            )
        })
        .collect()
}

/// Draws one panel: cells, spans, grid, reference lines, series, rug, frame, ticks and labels.
fn draw_panel<DB: DrawingBackend>(
    root: &DrawingArea<DB, Shift>,
    panel: &Panel,
    layout: &PanelLayout,
) -> std::result::Result<(), Box<dyn std::error::Error>>
where
    DB::ErrorType: 'static,
{
    let (left, top, w, h) = layout.area;
    let (x0, x1, y0, y1) = layout.ranges;
    let sx = |x: f64| left + (x - x0) / (x1 - x0) * w;
    let sy = |y: f64| top + h - (y - y0) / (y1 - y0) * h;
    let inside = |(x, y): (f64, f64)| {
        x >= left - 0.5 && x <= left + w + 0.5 && y >= top - 0.5 && y <= top + h + 0.5
    };
    let clip_x = |x: f64| x.clamp(left, left + w);
    let clip_y = |y: f64| y.clamp(top, top + h);
    let rect = |a: (f64, f64), b: (f64, f64), c: RGBColor| {
        Rectangle::new([(dot(a.0), dot(a.1)), (dot(b.0), dot(b.1))], c.filled())
    };
    for (l, t, r, b, rgb) in cell_rectangles(panel, layout) {
        // A dot wider and taller on the right and below, within the plotting area, so that
        // neighbours overlap and no seam of the background shows between them in any viewer.
        root.draw(&rect(
            (clip_x(l), clip_y(t)),
            (clip_x(r + 1.0), clip_y(b + 1.0)),
            RGBColor(rgb.0, rgb.1, rgb.2),
        ))?;
    }
    for span in &panel.spans {
        let (Some(a), Some(b)) = (panel.x_axis(span.from), panel.x_axis(span.to)) else {
            continue;
        };
        root.draw(&rect(
            (clip_x(sx(a)), top),
            (clip_x(sx(b)), top + h),
            tint(span.color, span.strong),
        ))?;
    }
    if panel.cells.is_empty() {
        let grid = GRID.stroke_width(width_dots(0.4));
        for (v, _) in &layout.x_ticks.major {
            root.draw(&PathElement::new(
                vec![(dot(sx(*v)), dot(top)), (dot(sx(*v)), dot(top + h))],
                grid,
            ))?;
        }
        for (v, _) in &layout.y_ticks.major {
            root.draw(&PathElement::new(
                vec![(dot(left), dot(sy(*v))), (dot(left + w), dot(sy(*v)))],
                grid,
            ))?;
        }
    }
    for v in &panel.vertical_lines {
        if let Some(x) = panel.x_axis(v.x) {
            root.draw(&PathElement::new(
                vec![(dot(sx(x)), dot(top)), (dot(sx(x)), dot(top + h))],
                colour(v.color).stroke_width(width_dots(0.5)),
            ))?;
        }
    }
    for (level, _) in &panel.reference_lines {
        if let Some(l) = panel.y_axis(*level) {
            draw_path(
                root,
                &[(left, sy(l)), (left + w, sy(l))],
                grey(REFERENCE_GREY).stroke_width(width_dots(0.6)),
                Dash::Solid,
            )?;
        }
    }
    for (level, _) in &panel.dashed_lines {
        if let Some(l) = panel.y_axis(*level) {
            draw_path(
                root,
                &[(left, sy(l)), (left + w, sy(l))],
                grey(DASHED_GREY).stroke_width(width_dots(0.6)),
                Dash::Dashed,
            )?;
        }
    }
    for s in &panel.series {
        let color = colour(s.color);
        let style = color.stroke_width(width_dots(s.stroke_pt()));
        // The points in axis coordinates, cut where one cannot be drawn.
        let mut pieces: Vec<Vec<(f64, f64)>> = vec![Vec::new()];
        for &(x, y) in &s.points {
            match (panel.x_axis(x), panel.y_axis(y)) {
                (Some(x), Some(y)) => pieces.last_mut().map_or((), |p| p.push((x, y))),
                _ => pieces.push(Vec::new()),
            }
        }
        for piece in pieces.iter().filter(|p| !p.is_empty()) {
            if s.line {
                for thin in decimate(piece, (x0, x1), (y0, y1), (w as u32, h as u32)) {
                    let drawn: Vec<(f64, f64)> =
                        thin.iter().map(|&(x, y)| (sx(x), sy(y))).collect();
                    draw_path(root, &drawn, style, s.dash)?;
                }
            }
            if let Some(shape) = s.marker {
                for &(x, y) in piece {
                    let p = (sx(x), sy(y));
                    if inside(p) {
                        draw_marker(root, shape, color, p)?;
                    }
                }
            }
        }
    }
    let rug_len = pt(4.0);
    for mark in &panel.rug {
        let Some(x) = panel.x_axis(mark.x) else {
            continue;
        };
        let px = sx(x);
        if px < left - 0.5 || px > left + w + 0.5 {
            continue;
        }
        let (a, b) = if mark.top {
            (top, top + rug_len)
        } else {
            (top + h - rug_len, top + h)
        };
        root.draw(&PathElement::new(
            vec![(dot(px), dot(a)), (dot(px), dot(b))],
            colour(mark.color).stroke_width(width_dots(0.8)),
        ))?;
    }
    // The frame, ticks and their labels.
    let frame = BLACK.stroke_width(width_dots(0.5));
    root.draw(&PathElement::new(
        vec![
            (dot(left), dot(top)),
            (dot(left + w), dot(top)),
            (dot(left + w), dot(top + h)),
            (dot(left), dot(top + h)),
            (dot(left), dot(top)),
        ],
        frame,
    ))?;
    let tick = pt(TICK_LEN_PT);
    let minor = tick * 0.55;
    for (v, text) in &layout.x_ticks.major {
        let x = sx(*v);
        root.draw(&PathElement::new(
            vec![(dot(x), dot(top + h)), (dot(x), dot(top + h + tick))],
            frame,
        ))?;
        if layout.x_labelled {
            root.draw(&Text::new(
                text.clone(),
                (dot(x), dot(top + h + tick + pt(GAP_PT))),
                font(TICK_PT, Pos::new(HPos::Center, VPos::Top)),
            ))?;
        }
    }
    for v in &layout.x_ticks.minor {
        let x = sx(*v);
        root.draw(&PathElement::new(
            vec![(dot(x), dot(top + h)), (dot(x), dot(top + h + minor))],
            frame,
        ))?;
    }
    for (v, text) in &layout.y_ticks.major {
        let y = sy(*v);
        root.draw(&PathElement::new(
            vec![(dot(left - tick), dot(y)), (dot(left), dot(y))],
            frame,
        ))?;
        root.draw(&Text::new(
            text.clone(),
            (dot(left - tick - pt(GAP_PT)), dot(y)),
            font(TICK_PT, Pos::new(HPos::Right, VPos::Center)),
        ))?;
    }
    for v in &layout.y_ticks.minor {
        let y = sy(*v);
        root.draw(&PathElement::new(
            vec![(dot(left - minor), dot(y)), (dot(left), dot(y))],
            frame,
        ))?;
    }
    if layout.x_labelled && !panel.x_label.is_empty() {
        root.draw(&Text::new(
            panel.x_label.clone(),
            (
                dot(left + w / 2.0),
                dot(top + h + tick + pt(GAP_PT) + pt(TICK_PT) * 1.25),
            ),
            font(LABEL_PT, Pos::new(HPos::Center, VPos::Top)),
        ))?;
    }
    if !panel.y_label.is_empty() {
        // A label longer than the axis is set smaller (down to 6 pt) rather than run past it.
        let size = (LABEL_PT * h / text_width(&panel.y_label, LABEL_PT)).clamp(6.0, LABEL_PT);
        root.draw(&Text::new(
            panel.y_label.clone(),
            (
                dot(layout.cell_left + pt(LABEL_PT) * 0.1),
                dot(top + h / 2.0),
            ),
            font(size, Pos::new(HPos::Center, VPos::Top)).transform(FontTransform::Rotate270),
        ))?;
    }
    Ok(())
}

/// One unbroken stretch of a curve, in drawing coordinates.
type Polyline = Vec<(f64, f64)>;

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

#[cfg(test)]
mod tests {
    use super::*;

    fn page(width: f64) -> Page {
        Page::width(width)
    }

    /// On log axes the lines are given in the data's units, as the series are: a line at
    /// y = 1000 over data from 1 to 10 widens the axis to 10^3, not to 1000 decades.
    #[test]
    fn names_on_a_y_axis_are_thinned_and_shortened_to_fit() {
        // 60 rows over 40 mm: a row is 40/61 mm apart, a line of 7 pt names 1.2 * 7 pt =
        // 2.96 mm, so every ceil(2.96 / 0.656) = 5th row is named, from the first.
        let names: Vec<(f64, String)> = (1..=60).map(|i| (i as f64, format!("r{i}"))).collect();
        let ticks = named_ticks(&names, (0.0, 61.0), dots(40.0), dots(30.0));
        let labelled: Vec<f64> = ticks.major.iter().map(|(y, _)| *y).collect();
        let every_fifth: Vec<f64> = (0..12).map(|k| (1 + 5 * k) as f64).collect();
        assert_eq!(labelled, every_fifth);
        assert_eq!(ticks.minor.len(), 48);
        assert_eq!(ticks.major[1].1, "r6");
        // Room for every name: all named.
        let ticks = named_ticks(&names[..5], (0.0, 6.0), dots(40.0), dots(30.0));
        assert_eq!(ticks.major.len(), 5);
        assert!(ticks.minor.is_empty());
        // A name wider than the room is cut at its end with an ellipsis, within the room.
        let long = "IMPERIAL VALLEY-06, EL CENTRO ARRAY #7, 230 DEGREES".to_string();
        let room = dots(20.0);
        let short = shortened(&long, room);
        assert!(short.ends_with('…') && short.len() < long.len(), "{short}");
        assert!(long.starts_with(short.trim_end_matches('…')));
        assert!(text_width(&short, TICK_PT) <= room);
        assert_eq!(shortened("PBF", room), "PBF");
    }

    #[test]
    fn lines_on_log_axes_are_placed_at_their_logarithm() {
        let mut panel =
            Panel::new("", "x", "y").with(Series::line("data", vec![(1.0, 1.0), (10.0, 10.0)], 0));
        panel.log_x = true;
        panel.log_y = true;
        panel.reference_lines.push((1000.0, "line".into()));
        panel.vertical_lines.push(VerticalLine {
            x: 100.0,
            color: 0,
            label: "v".into(),
        });
        let (x0, x1, y0, y1) = padded_ranges(&panel, data_extent(&panel));
        assert!((3.0..4.0).contains(&y1), "y axis to {y1}");
        assert!(y0 <= 0.0 && x0 <= 0.0, "{x0} {y0}");
        assert!(x1 < 4.0, "x axis to {x1}");
        let svg = svg("log.svg", &Figure::new(vec![panel], 1), &page(85.0)).expect("draws");
        // Decades labelled as decimals where everyday: 1, 10, 100, 1000.
        for label in [">1<", ">10<", ">100<", ">1000<"] {
            assert!(svg.replace('\n', "").contains(label), "{label}");
        }
    }

    #[test]
    fn tick_labels_use_minus_signs_and_the_step_s_decimals() {
        let t = linear_ticks(-0.3, 0.3, 7);
        let labels: Vec<&str> = t.major.iter().map(|(_, s)| s.as_str()).collect();
        assert_eq!(labels, ["−0.3", "−0.2", "−0.1", "0", "0.1", "0.2", "0.3"]);
        let t = linear_ticks(0.0, 25_000.0, 6);
        assert_eq!(t.major[1].1, "0.5×10⁴");
        let t = linear_ticks(-5.2, 8.4, 6);
        let labels: Vec<&str> = t.major.iter().map(|(_, s)| s.as_str()).collect();
        // Every label with the step's decimals, as a journal sets them.
        assert_eq!(labels, ["−5.0", "−2.5", "0", "2.5", "5.0", "7.5"]);
        assert_eq!(tick_text(0.5, 0.25), "0.50");
        assert_eq!(tick_text(-1e-17, 0.25), "0");
    }

    #[test]
    fn svg_has_labels_and_one_legend_with_panel_labels() {
        let sine = Series::line(
            "sine",
            (0..50).map(|i| (i as f64, (i as f64).sin())).collect(),
            0,
        );
        let mut a = Panel::new("", "x (s)", "y (m)").with(sine.clone());
        a.reference_lines = vec![(0.5, "limit".to_string()), (-0.5, String::new())];
        let b = Panel::new("", "x (s)", "z (m)").with(sine);
        let svg = svg("a.svg", &Figure::new(vec![a, b], 1).shared_x(), &page(85.0)).unwrap();
        assert!(svg.starts_with("<svg width=\"85mm\""));
        let texts: Vec<&str> = svg
            .split("<text")
            .skip(1)
            .map(|t| {
                let inner = t.split('>').nth(1).unwrap_or("");
                inner.split('<').next().unwrap_or("").trim()
            })
            .collect();
        for text in ["(a)", "(b)", "y (m)", "z (m)", "sine", "limit"] {
            assert_eq!(texts.iter().filter(|t| **t == text).count(), 1, "{text}");
        }
        // The x axis is shared: labelled once.
        assert_eq!(texts.iter().filter(|t| **t == "x (s)").count(), 1);
    }

    #[test]
    fn a_page_too_small_for_its_panels_is_refused_naming_the_flag() {
        let panels = vec![Panel::new("", "t", "y"); 6];
        let mut small = page(85.0);
        small.height = Some(40.0);
        let e = svg("s.svg", &Figure::new(panels.clone(), 1), &small).unwrap_err();
        assert!(e.to_string().contains("--height"), "{e}");
        // Six panels across do not fit on 60 mm: they wrap to fewer across, each at least
        // MIN_ACROSS_MM wide.
        let layout = Layout::of("w.svg", &Figure::new(panels, 6), &page(60.0)).unwrap();
        let lefts: std::collections::BTreeSet<i64> =
            layout.panels.iter().map(|p| p.area.0 as i64).collect();
        assert!(lefts.len() < 6, "{lefts:?}");
        assert!(layout
            .panels
            .iter()
            .all(|p| p.area.2 >= dots(MIN_ACROSS_MM)));
    }

    #[test]
    fn empty_flat_and_equal_aspect_panels_still_draw() {
        let one = |p: Panel| svg("e.svg", &Figure::new(vec![p], 1), &page(85.0));
        assert!(one(Panel::new("", "x", "y")).is_ok());
        let flat = Panel::new("", "x", "y").with(Series::line("", vec![(0.0, 0.0), (1.0, 0.0)], 0));
        assert!(one(flat.clone()).is_ok());
        let mut shape = flat;
        shape.equal_aspect = true;
        assert!(one(shape).is_ok());
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
        let panels = vec![
            Panel::new("", "t", "y").with(Series::line("y", line, 0)),
            Panel::new("", "x", "y").with(Series::line("path", path, 1)),
        ];
        let svg = svg("big.svg", &Figure::new(panels, 1), &page(180.0)).unwrap();
        assert!(svg.len() < 2_000_000, "{} bytes", svg.len());
    }

    /// A map's file does not grow with its grid beyond what its dots show: the same field
    /// (rings of five colours) over 600 x 600 and over 1200 x 1200 cells, both finer than the
    /// dots of a 40 mm figure, draws about as many rectangles (a rectangle per run of a colour
    /// up each column of cells drew twice as many).
    #[test]
    fn a_map_of_a_finer_grid_draws_no_more_rectangles() {
        let rectangles = |n: usize| {
            let mut panel = Panel::new("", "x", "y");
            for i in 0..n {
                for j in 0..n {
                    let (x, y) = (i as f64 / n as f64, j as f64 / n as f64);
                    let ring = ((x * x + y * y).sqrt() * 7.0) as usize % 5;
                    panel.cells.push(Cell {
                        from: (x, y),
                        to: (x + 1.0 / n as f64, y + 1.0 / n as f64),
                        rgb: palette(ring + 1),
                    });
                }
            }
            let svg = svg("map.svg", &Figure::new(vec![panel], 1), &page(40.0)).unwrap();
            svg.matches("<rect").count()
        };
        let (coarse, fine) = (rectangles(600), rectangles(1200));
        assert!(
            (fine as f64) < 1.1 * coarse as f64,
            "{coarse} rectangles for 600 x 600 cells, {fine} for 1200 x 1200"
        );
    }

    #[test]
    fn markers_rugs_and_dashes_draw() {
        let mut panel = Panel::new("", "t (s)", "q' (m/s)")
            .with(Series::line("q'", vec![(0.0, 0.0), (1.0, 1.0), (2.0, -1.0)], 0).dashed())
            .with(Series::markers(
                "uplift",
                vec![(1.0, 1.0)],
                1,
                Marker::TriangleUp,
            ))
            .with(Series::markers(
                "stands",
                vec![(2.0, -1.0)],
                2,
                Marker::OpenTriangleUp,
            ))
            .with(Series::markers(
                "overturn",
                vec![(2.0, 0.0)],
                4,
                Marker::Cross,
            ));
        panel.rug.push(RugMark {
            x: 1.0,
            color: 1,
            top: false,
            label: "uplift".into(),
            marker: Marker::TriangleUp,
        });
        panel.dashed_lines = vec![(0.5, "limit B".to_string())];
        let svg = svg("m.svg", &Figure::new(vec![panel], 1), &page(85.0)).unwrap();
        for text in ["uplift", "overturn", "limit B", "stands"] {
            assert!(svg.contains(text), "{text}");
        }
        assert!(svg.contains("<polygon"), "triangles are polygons");
    }
}
