//! SVG line charts: series of (x, y) points in, an SVG document out. Nothing here knows about the
//! finite element model, so the code can serve any command that draws curves.

use plotters::prelude::*;

/// One curve (or, with an empty label, one more polyline of the previous curve's kind).
#[derive(Debug, Clone)]
pub struct Series {
    /// Legend text; empty = not in the legend.
    pub label: String,
    pub points: Vec<(f64, f64)>,
    /// Index into the palette.
    pub color: usize,
}

impl Series {
    pub fn new(label: impl Into<String>, color: usize, points: Vec<(f64, f64)>) -> Self {
        Series {
            label: label.into(),
            points,
            color,
        }
    }
}

/// A chart of one or more series on common axes.
#[derive(Debug, Clone)]
pub struct Chart {
    pub title: String,
    pub x_label: String,
    pub y_label: String,
    pub series: Vec<Series>,
    /// Same length per unit on both axes (drawings of shapes).
    pub equal_aspect: bool,
    /// Horizontal lines drawn in grey (e.g. +-s_n), with their legend text.
    pub reference_lines: Vec<(f64, String)>,
    pub size: (u32, u32),
}

impl Chart {
    pub fn new(title: &str, x_label: &str, y_label: &str) -> Self {
        Chart {
            title: title.to_string(),
            x_label: x_label.to_string(),
            y_label: y_label.to_string(),
            series: Vec::new(),
            equal_aspect: false,
            reference_lines: Vec::new(),
            size: (900, 500),
        }
    }

    pub fn with(mut self, series: Series) -> Self {
        self.series.push(series);
        self
    }
}

const PALETTE: [RGBColor; 8] = [
    RGBColor(31, 119, 180),
    RGBColor(214, 39, 40),
    RGBColor(44, 160, 44),
    RGBColor(255, 127, 14),
    RGBColor(148, 103, 189),
    RGBColor(140, 86, 75),
    RGBColor(23, 190, 207),
    RGBColor(0, 0, 0),
];

const Y_LABEL_AREA: u32 = 70;
const X_LABEL_AREA: u32 = 45;
const MARGIN: u32 = 15;
const CAPTION: u32 = 30;

/// Axis ranges covering every finite point and reference line, padded by 5 %.
fn ranges(chart: &Chart) -> ((f64, f64), (f64, f64)) {
    let mut x = (f64::INFINITY, f64::NEG_INFINITY);
    let mut y = (f64::INFINITY, f64::NEG_INFINITY);
    for &(px, py) in chart.series.iter().flat_map(|s| s.points.iter()) {
        if px.is_finite() && py.is_finite() {
            x = (x.0.min(px), x.1.max(px));
            y = (y.0.min(py), y.1.max(py));
        }
    }
    for &(level, _) in &chart.reference_lines {
        y = (y.0.min(level), y.1.max(level));
    }
    let pad = |(lo, hi): (f64, f64)| {
        if !(lo.is_finite() && hi.is_finite()) {
            (-1.0, 1.0)
        } else if hi - lo <= f64::EPSILON * hi.abs().max(1.0) {
            let d = if lo == 0.0 { 1.0 } else { 0.1 * lo.abs() };
            (lo - d, hi + d)
        } else {
            let d = 0.05 * (hi - lo);
            (lo - d, hi + d)
        }
    };
    let (mut x, mut y) = (pad(x), pad(y));
    if chart.equal_aspect {
        let plot_w = f64::from(
            chart
                .size
                .0
                .saturating_sub(Y_LABEL_AREA + 2 * MARGIN)
                .max(1),
        );
        let plot_h = f64::from(
            chart
                .size
                .1
                .saturating_sub(X_LABEL_AREA + 2 * MARGIN + CAPTION)
                .max(1),
        );
        let scale = ((x.1 - x.0) / plot_w).max((y.1 - y.0) / plot_h);
        let grow = |(lo, hi): (f64, f64), pixels: f64| {
            let c = 0.5 * (lo + hi);
            (c - 0.5 * scale * pixels, c + 0.5 * scale * pixels)
        };
        x = grow(x, plot_w);
        y = grow(y, plot_h);
    }
    (x, y)
}

/// Draws the chart as an SVG document.
pub fn line_chart_svg(chart: &Chart) -> Result<String, String> {
    let mut svg = String::new();
    draw(chart, &mut svg).map_err(|e| format!("cannot draw \"{}\": {e}", chart.title))?;
    Ok(svg)
}

fn draw(chart: &Chart, svg: &mut String) -> Result<(), Box<dyn std::error::Error>> {
    let ((x0, x1), (y0, y1)) = ranges(chart);
    let root = SVGBackend::with_string(svg, chart.size).into_drawing_area();
    root.fill(&WHITE)?;
    let mut ctx = ChartBuilder::on(&root)
        .caption(&chart.title, ("sans-serif", 18))
        .margin(MARGIN)
        .x_label_area_size(X_LABEL_AREA)
        .y_label_area_size(Y_LABEL_AREA)
        .build_cartesian_2d(x0..x1, y0..y1)?;
    ctx.configure_mesh()
        .x_desc(chart.x_label.as_str())
        .y_desc(chart.y_label.as_str())
        .light_line_style(WHITE.mix(0.0))
        .draw()?;
    for (level, label) in &chart.reference_lines {
        let grey = RGBColor(150, 150, 150);
        let anno = ctx.draw_series(LineSeries::new(
            [(x0, *level), (x1, *level)],
            grey.stroke_width(1),
        ))?;
        if !label.is_empty() {
            anno.label(label.as_str()).legend(move |(x, y)| {
                PathElement::new(vec![(x, y), (x + 20, y)], grey.stroke_width(1))
            });
        }
    }
    let mut labelled = false;
    for s in &chart.series {
        let color = PALETTE[s.color % PALETTE.len()];
        // A non-finite value breaks the curve instead of being drawn.
        for piece in s.points.split(|(x, y)| !(x.is_finite() && y.is_finite())) {
            if piece.is_empty() {
                continue;
            }
            let anno = ctx.draw_series(LineSeries::new(piece.to_vec(), color.stroke_width(1)))?;
            if !s.label.is_empty() && !labelled {
                labelled = true;
                anno.label(s.label.as_str()).legend(move |(x, y)| {
                    PathElement::new(vec![(x, y), (x + 20, y)], color.stroke_width(2))
                });
            }
        }
        labelled = false;
    }
    if chart.series.iter().any(|s| !s.label.is_empty())
        || chart.reference_lines.iter().any(|(_, l)| !l.is_empty())
    {
        ctx.configure_series_labels()
            .background_style(WHITE.mix(0.85))
            .border_style(BLACK)
            .position(SeriesLabelPosition::UpperRight)
            .draw()?;
    }
    root.present()?;
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn svg_has_title_labels_and_one_path_per_piece() {
        let chart = Chart::new("title A", "x (s)", "y (m)")
            .with(Series::new(
                "sine",
                0,
                (0..50).map(|i| (i as f64, (i as f64).sin())).collect(),
            ))
            .with(Series::new(
                "broken",
                1,
                vec![(0.0, 0.0), (1.0, f64::NAN), (2.0, 1.0), (3.0, 2.0)],
            ));
        let svg = line_chart_svg(&chart).unwrap();
        assert!(svg.starts_with("<svg"));
        for text in ["title A", "x (s)", "y (m)", "sine", "broken"] {
            assert!(svg.contains(text), "{text}");
        }
    }

    #[test]
    fn empty_and_flat_series_still_draw() {
        assert!(line_chart_svg(&Chart::new("empty", "x", "y")).is_ok());
        let flat =
            Chart::new("flat", "x", "y").with(Series::new("", 0, vec![(0.0, 0.0), (1.0, 0.0)]));
        assert!(line_chart_svg(&flat).is_ok());
        let mut shape = flat.clone();
        shape.equal_aspect = true;
        assert!(line_chart_svg(&shape).is_ok());
    }
}
