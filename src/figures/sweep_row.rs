//! The figure of a row sweep over two numeric axes, drawn from sweep.csv alone:
//! `verdicts.svg` and `verdicts.png`, one map per column of the row, each cell coloured by what
//! the row did to that column at that point (`cI_verdict`, and `cI_alone_overturned` to tell the
//! two kinds of `same` apart): saved, toppled, overturns both, stands both, or undecided (another
//! column overturned first and ended the row's run). Invalid and failed points are white cells
//! crossed in grey.

use plotters::coord::Shift;
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, Pos, VPos};

use crate::error::{Error, Result};
use crate::figures::plot::{encode_png, register_fonts};
use crate::figures::sweep::{
    ascending, axis_label, drawable, edges, fill_cell, SweepTable, VERDICTS_PNG, VERDICTS_SVG,
};
use flexrock_core::sweep::Plan;

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
/// common colour-vision deficiencies) and labels.
const LEGEND: [(Class, RGBColor, &str); 5] = [
    (Class::Saved, RGBColor(0, 114, 178), "saved"),
    (Class::Toppled, RGBColor(213, 94, 0), "toppled"),
    (Class::OverturnsBoth, RGBColor(45, 45, 45), "overturns both"),
    (Class::StandsBoth, RGBColor(222, 222, 222), "stands both"),
    (Class::Undecided, RGBColor(240, 228, 66), "undecided"),
];

fn colour(class: Class) -> RGBColor {
    LEGEND
        .iter()
        .find(|(c, _, _)| *c == class)
        .map_or(WHITE, |(_, colour, _)| *colour)
}

/// A panel's size in pixels, and the legend's width.
const PANEL: (u32, u32) = (640, 560);
const LEGEND_WIDTH: u32 = 300;
/// Panels per line of the figure.
const PER_LINE: usize = 3;
const TITLE_FONT: u32 = 26;
const AXIS_FONT: u32 = 22;
const TICK_FONT: u32 = 20;

fn plot_error(name: &str) -> impl Fn(Box<dyn std::error::Error>) -> Error + '_ {
    move |e| Error::Plot {
        name: name.to_string(),
        message: e.to_string(),
    }
}

/// `verdicts.svg` and `verdicts.png` of a row of `n` columns over axes `x` and `y`; nothing
/// when the axes cannot be drawn as cells.
pub fn verdict_maps(
    plan: &Plan,
    table: &SweepTable,
    n: usize,
    x: usize,
    y: usize,
) -> Result<Vec<(String, Vec<u8>)>> {
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
    // An axis of positive values spanning two decades or more is drawn in log10 of its values.
    let logged = |v: Vec<f64>| {
        let (lo, hi) = v.iter().fold((f64::INFINITY, 0.0f64), |(lo, hi), &x| {
            (lo.min(x), hi.max(x))
        });
        if lo > 0.0 && hi / lo >= 100.0 {
            (v.iter().map(|x| x.log10()).collect(), true)
        } else {
            (v, false)
        }
    };
    let ((xs, log_x), (ys, log_y)) = (logged(xs), logged(ys));
    if !(drawable(&xs) && drawable(&ys)) {
        return Ok(Vec::new());
    }
    let labels = (axis_label(&plan.axes[x].key), axis_label(&plan.axes[y].key));
    let lines = n.div_ceil(PER_LINE);
    let across = n.min(PER_LINE) as u32;
    let size = (PANEL.0 * across + LEGEND_WIDTH, PANEL.1 * lines as u32);
    register_fonts();
    let figure = Figure {
        maps: &maps,
        xs: &xs,
        ys: &ys,
        labels: (&labels.0, &labels.1),
        log: (log_x, log_y),
    };
    let mut svg = String::new();
    {
        let root = SVGBackend::with_string(&mut svg, size).into_drawing_area();
        figure.draw(&root).map_err(plot_error(VERDICTS_SVG))?;
    }
    let mut pixels = vec![255u8; 3 * size.0 as usize * size.1 as usize];
    {
        let root = BitMapBackend::with_buffer(&mut pixels, size).into_drawing_area();
        figure.draw(&root).map_err(plot_error(VERDICTS_PNG))?;
    }
    let png = encode_png(VERDICTS_PNG, &pixels, size)?;
    Ok(vec![
        (VERDICTS_SVG.to_string(), svg.into_bytes()),
        (VERDICTS_PNG.to_string(), png),
    ])
}

/// What the figure draws: per column, the class of each cell (`maps[i][x][y]`), and the axes.
struct Figure<'a> {
    maps: &'a [Vec<Vec<Class>>],
    xs: &'a [f64],
    ys: &'a [f64],
    labels: (&'a str, &'a str),
    /// Whether each axis is drawn in log10 of its values.
    log: (bool, bool),
}

/// A tick's value as a reader reads it: at most four significant digits, in scientific
/// notation for very large or small magnitudes; `logged` ticks are log10 of the value.
fn tick(value: f64, logged: bool) -> String {
    let v = if logged { 10f64.powf(value) } else { value };
    if v == 0.0 || !v.is_finite() {
        return format!("{v}");
    }
    let magnitude = v.abs();
    if !(1e-3..1e5).contains(&magnitude) {
        let text = format!("{v:.2e}");
        let (mantissa, exponent) = text.split_once('e').unwrap_or((&text, "0"));
        let mantissa = mantissa.trim_end_matches('0').trim_end_matches('.');
        return format!("{mantissa}e{exponent}");
    }
    let digits = (3 - magnitude.log10().floor() as i32).clamp(0, 6) as usize;
    let text = format!("{v:.digits$}");
    if text.contains('.') {
        text.trim_end_matches('0').trim_end_matches('.').to_string()
    } else {
        text
    }
}

type Drawn = std::result::Result<(), Box<dyn std::error::Error>>;

impl Figure<'_> {
    fn draw<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>) -> Drawn
    where
        DB::ErrorType: 'static,
    {
        root.fill(&WHITE)?;
        let (width, _) = root.dim_in_pixel();
        let (maps, legend) = root.split_horizontally(width - LEGEND_WIDTH);
        let n = self.maps.len();
        let lines = n.div_ceil(PER_LINE);
        let areas = maps.split_evenly((lines, n.min(PER_LINE)));
        for (i, (map, area)) in self.maps.iter().zip(areas.iter()).enumerate() {
            self.panel(area, map, &format!("Column {i}: in the row against alone"))?;
        }
        draw_legend(&legend)?;
        root.present()?;
        Ok(())
    }

    fn panel<DB: DrawingBackend>(
        &self,
        area: &DrawingArea<DB, Shift>,
        cells: &[Vec<Class>],
        title: &str,
    ) -> Drawn
    where
        DB::ErrorType: 'static,
    {
        // Cells in ascending order of both coordinates, whatever the order of the axes.
        let (ox, oy) = (ascending(self.xs), ascending(self.ys));
        let sorted = |v: &[f64], order: &[usize]| order.iter().map(|&i| v[i]).collect::<Vec<_>>();
        let (ex, ey) = (edges(&sorted(self.xs, &ox)), edges(&sorted(self.ys, &oy)));
        let cells: Vec<Vec<Class>> = ox
            .iter()
            .map(|&i| oy.iter().map(|&j| cells[i][j]).collect())
            .collect();
        let range = |e: &[f64]| e[0]..e[e.len() - 1];
        let mut chart = ChartBuilder::on(area)
            .caption(title, ("sans-serif", TITLE_FONT))
            .margin(14)
            .x_label_area_size(64)
            .y_label_area_size(100)
            .build_cartesian_2d(range(&ex), range(&ey))?;
        let (log_x, log_y) = self.log;
        let x_tick = move |v: &f64| tick(*v, log_x);
        let y_tick = move |v: &f64| tick(*v, log_y);
        let x_desc = if log_x {
            format!("{} (log scale)", self.labels.0)
        } else {
            self.labels.0.to_string()
        };
        let y_desc = if log_y {
            format!("{} (log scale)", self.labels.1)
        } else {
            self.labels.1.to_string()
        };
        chart
            .configure_mesh()
            .disable_mesh()
            .x_desc(x_desc)
            .y_desc(y_desc)
            .x_labels(6)
            .y_labels(6)
            .x_label_formatter(&x_tick)
            .y_label_formatter(&y_tick)
            .label_style(("sans-serif", TICK_FONT))
            .axis_desc_style(("sans-serif", AXIS_FONT))
            .draw()?;
        // The cells in pixels of the plotting area, each a pixel wider and taller than its
        // place so that neighbours overlap and no seam of the background shows.
        let plotting = chart.plotting_area();
        let (xr, yr) = plotting.get_pixel_range();
        let limit = (xr.end - xr.start, yr.end - yr.start);
        let pixels = plotting.strip_coord_spec();
        let at = |x: f64, y: f64| {
            let (a, b) = plotting.map_coordinate(&(x, y));
            (a - xr.start, b - yr.start)
        };
        let grey = RGBColor(140, 140, 140);
        for (i, column) in cells.iter().enumerate() {
            for (j, &class) in column.iter().enumerate() {
                let [(left, top), (right, bottom)] = fill_cell(
                    &pixels,
                    at(ex[i], ey[j]),
                    at(ex[i + 1], ey[j + 1]),
                    limit,
                    colour(class),
                )?;
                if class == Class::Missing {
                    pixels.draw(&PathElement::new(
                        vec![(left, bottom), (right, top)],
                        grey.stroke_width(1),
                    ))?;
                }
            }
        }
        // The frame again, over the cells.
        pixels.draw(&Rectangle::new(
            [(0, 0), (limit.0, limit.1)],
            BLACK.stroke_width(1),
        ))?;
        Ok(())
    }
}

/// The key to the classes: a swatch and a label each, and what the undecided cells mean.
fn draw_legend<DB: DrawingBackend>(area: &DrawingArea<DB, Shift>) -> Drawn
where
    DB::ErrorType: 'static,
{
    let font = ("sans-serif", TICK_FONT).into_font().color(&BLACK);
    let head = ("sans-serif", AXIS_FONT).into_font().color(&BLACK);
    let (left, mut y) = (14, 74);
    area.draw(&Text::new(
        "The column in the row",
        (left, y),
        head.pos(Pos::new(HPos::Left, VPos::Center)),
    ))?;
    y += 40;
    let entry = |swatch: RGBColor, label: &str, y: i32, cross: bool| -> Drawn {
        area.draw(&Rectangle::new(
            [(left, y - 12), (left + 26, y + 12)],
            swatch.filled(),
        ))?;
        area.draw(&Rectangle::new(
            [(left, y - 12), (left + 26, y + 12)],
            RGBColor(90, 90, 90).stroke_width(1),
        ))?;
        if cross {
            area.draw(&PathElement::new(
                vec![(left, y + 12), (left + 26, y - 12)],
                RGBColor(140, 140, 140).stroke_width(1),
            ))?;
        }
        area.draw(&Text::new(
            label.to_string(),
            (left + 36, y),
            font.pos(Pos::new(HPos::Left, VPos::Center)),
        ))?;
        Ok(())
    };
    for (_, swatch, label) in LEGEND {
        entry(swatch, label, y, false)?;
        y += 38;
    }
    entry(WHITE, "invalid or failed", y, true)?;
    y += 56;
    let small = ("sans-serif", 17).into_font().color(&BLACK);
    for line in [
        "saved: overturns alone,",
        "  stands in the row",
        "toppled: stands alone,",
        "  overturns in the row",
        "undecided: another column",
        "  overturned first and",
        "  ended the row's run",
    ] {
        area.draw(&Text::new(
            line,
            (left, y),
            small.pos(Pos::new(HPos::Left, VPos::Center)),
        ))?;
        y += 24;
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::tick;

    #[test]
    fn ticks_are_short() {
        assert_eq!(tick(0.05, false), "0.05");
        assert_eq!(tick(6.0, false), "6");
        assert_eq!(tick(2.5, false), "2.5");
        assert_eq!(tick(8.0, true), "1e8");
        assert_eq!(tick(7.5, true), "3.16e7");
        assert_eq!(tick(0.0, false), "0");
        assert_eq!(tick(123456.0, false), "1.23e5");
    }
}
