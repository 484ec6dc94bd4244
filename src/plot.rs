//! SVG figures from series of points. Knows nothing about solvers or models: callers hand it
//! panels of named (x, y) series and get the SVG text back, to be written atomically.

use plotters::prelude::*;

use crate::error::{Error, Result};

/// One line of a panel.
#[derive(Debug, Clone)]
pub struct Series {
    pub name: String,
    pub points: Vec<(f64, f64)>,
    /// Index into the palette; 0 is black (for references). An empty name keeps the series out
    /// of the legend.
    pub color: usize,
    /// Draw markers at the points (for convergence studies with few points).
    pub markers: bool,
}

impl Series {
    pub fn line(name: &str, points: Vec<(f64, f64)>, color: usize) -> Self {
        Series {
            name: name.to_string(),
            points,
            color,
            markers: false,
        }
    }

    pub fn with_markers(mut self) -> Self {
        self.markers = true;
        self
    }
}

/// One chart of a figure.
#[derive(Debug, Clone, Default)]
pub struct Panel {
    pub title: String,
    pub x_label: String,
    pub y_label: String,
    pub series: Vec<Series>,
    /// Logarithmic axes (decades); non-positive values are left out.
    pub log_x: bool,
    pub log_y: bool,
    /// Where the legend goes, so that it hides no data.
    pub legend: Legend,
    /// Same length per unit on both axes (drawings of shapes).
    pub equal_aspect: bool,
    /// Horizontal lines drawn in grey (e.g. +-s_n), with their legend text (empty: none).
    pub reference_lines: Vec<(f64, String)>,
}

impl Panel {
    pub fn new(title: &str, x_label: &str, y_label: &str) -> Self {
        Panel {
            title: title.to_string(),
            x_label: x_label.to_string(),
            y_label: y_label.to_string(),
            ..Panel::default()
        }
    }

    pub fn with(mut self, series: Series) -> Self {
        self.series.push(series);
        self
    }
}

/// Corner of a panel for its legend.
#[derive(Debug, Clone, Copy, Default)]
pub enum Legend {
    #[default]
    UpperRight,
    LowerRight,
    UpperLeft,
    LowerLeft,
}

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
const X_LABEL_AREA: u32 = 38;
const Y_LABEL_AREA: u32 = 70;
/// Height of the title line, for the equal-aspect layout.
const CAPTION: u32 = 30;

fn draw_panel(
    panel: &Panel,
    area: &Area<'_>,
) -> std::result::Result<(), Box<dyn std::error::Error>> {
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
    let series: Vec<(&Series, Vec<Polyline>)> = panel
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
        .collect();
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
    for &(level, _) in &panel.reference_lines {
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
        let (width, height) = area.dim_in_pixel();
        let plot_w = f64::from(width.saturating_sub(Y_LABEL_AREA + 2 * MARGIN).max(1));
        let plot_h = f64::from(
            height
                .saturating_sub(X_LABEL_AREA + 2 * MARGIN + CAPTION)
                .max(1),
        );
        let scale = ((x1 - x0) / plot_w).max((y1 - y0) / plot_h);
        let (xc, yc) = (0.5 * (x0 + x1), 0.5 * (y0 + y1));
        (x0, x1) = (xc - 0.5 * scale * plot_w, xc + 0.5 * scale * plot_w);
        (y0, y1) = (yc - 0.5 * scale * plot_h, yc + 0.5 * scale * plot_h);
    }

    let mut chart = ChartBuilder::on(area)
        .caption(&panel.title, ("sans-serif", 18))
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
        .x_label_formatter(if panel.log_x { &log_label } else { &x_label })
        .y_label_formatter(if panel.log_y { &log_label } else { &y_label })
        .light_line_style(RGBColor(235, 235, 235))
        .draw()?;

    for (level, label) in &panel.reference_lines {
        let grey = RGBColor(150, 150, 150);
        let line = chart.draw_series(LineSeries::new(
            [(x0, *level), (x1, *level)],
            grey.stroke_width(1),
        ))?;
        if !label.is_empty() {
            line.label(label.as_str()).legend(move |(x, y)| {
                PathElement::new(vec![(x, y), (x + 18, y)], grey.stroke_width(1))
            });
        }
    }
    for (s, pieces) in &series {
        let color = PALETTE[s.color % PALETTE.len()];
        let style = color.stroke_width(if s.color == 0 { 2 } else { 1 });
        for (i, points) in pieces.iter().enumerate() {
            let line = chart.draw_series(LineSeries::new(points.iter().copied(), style))?;
            if i == 0 && !s.name.is_empty() {
                line.label(s.name.as_str()).legend(move |(x, y)| {
                    PathElement::new(vec![(x, y), (x + 18, y)], color.stroke_width(2))
                });
            }
            if s.markers {
                chart.draw_series(points.iter().map(|&p| Circle::new(p, 3, color.filled())))?;
            }
        }
    }
    let labelled = panel.series.iter().any(|s| !s.name.is_empty())
        || panel.reference_lines.iter().any(|(_, l)| !l.is_empty());
    if !labelled {
        return Ok(());
    }
    chart
        .configure_series_labels()
        .background_style(WHITE.mix(0.85))
        .border_style(RGBColor(180, 180, 180))
        .position(match panel.legend {
            Legend::UpperRight => SeriesLabelPosition::UpperRight,
            Legend::LowerRight => SeriesLabelPosition::LowerRight,
            Legend::UpperLeft => SeriesLabelPosition::UpperLeft,
            Legend::LowerLeft => SeriesLabelPosition::LowerLeft,
        })
        .draw()?;
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
}
