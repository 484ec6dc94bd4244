//! The figures of `flexrock fragility`: the fitted curve with the records' empirical points and
//! the bootstrap band (fragility), and the records' capacities on the intensity axis with the
//! median and the 16/84 % fractiles (capacities).

use crate::error::Result;
use crate::figures::page::{FigureOptions, PAGE_MM};
use crate::figures::plot::{self, Dash, Figure, Marker, Panel, Series, VerticalLine};
use flexrock_core::analysis::fragility::{bootstrap, Capacity, Lognormal, Summary, PERCENTILES};
use flexrock_core::base::format::significant;

/// Points of a drawn curve.
const CURVE_POINTS: usize = 200;

/// The figure files, in each format asked.
pub fn files(summary: &Summary, options: &FigureOptions) -> Result<Vec<(String, Vec<u8>)>> {
    let mut files = plot::files("fragility", &curves(summary), options, PAGE_MM)?;
    files.extend(plot::files(
        "capacities",
        &capacities(summary),
        options,
        PAGE_MM,
    )?);
    Ok(files)
}

fn im_label(summary: &Summary) -> String {
    match summary.sa_period_s {
        Some(t) => format!(
            "Sa({} s, 5 %), {}",
            flexrock_core::base::format::shortest(t),
            summary.im_unit
        ),
        None => format!("{}, {}", summary.im.name().to_uppercase(), summary.im_unit),
    }
}

/// The legend's name of the fitted curve, with its median and dispersion.
fn fit_name(summary: &Summary) -> String {
    let fit = &summary.fits[0];
    format!(
        "lognormal fit: θ = {} {}, β = {}",
        significant(fit.theta, 3),
        summary.im_unit,
        significant(fit.beta, 2)
    )
}

/// The fitted curve, the bootstrap band and the empirical fractions.
fn curves(summary: &Summary) -> Figure {
    let fit = &summary.fits[0];
    let curve = Lognormal {
        theta: fit.theta,
        beta: fit.beta,
    };
    let values: Vec<f64> = summary.records.iter().map(|r| r.capacity.value()).collect();
    let top = values
        .iter()
        .copied()
        .fold(fit.theta * (2.5 * fit.beta).exp(), f64::max);
    let xs: Vec<f64> = (1..=CURVE_POINTS)
        .map(|i| top * 1.05 * i as f64 / CURVE_POINTS as f64)
        .collect();
    let mut panel = Panel::new("", &im_label(summary), &format!("P({} | IM)", fit.state));
    panel.y_range = Some((0.0, 1.0));
    // The band: the percentiles of the bootstrap curves at each intensity.
    let fits = bootstrap_fits(summary);
    if !fits.is_empty() {
        for (k, q) in PERCENTILES.iter().enumerate() {
            let band: Vec<(f64, f64)> = xs
                .iter()
                .map(|&x| {
                    let p: Vec<f64> = fits.iter().map(|f| f.probability(x)).collect();
                    (x, bootstrap::quantile(&p, q / 100.0).unwrap_or(f64::NAN))
                })
                .collect();
            let name = if k == 0 {
                format!("bootstrap {}-{} %", PERCENTILES[0], PERCENTILES[1])
            } else {
                String::new()
            };
            panel = panel.with(
                Series::line(&name, band, 2)
                    .with_dash(Dash::Dashed)
                    .with_width(0.7),
            );
        }
    }
    let line: Vec<(f64, f64)> = xs.iter().map(|&x| (x, curve.probability(x))).collect();
    panel = panel.with(Series::line(&fit_name(summary), line, 1));
    // The empirical fractions: the i-th smallest observed capacity at i/n (censored records
    // lie above every observed one and never reach the plot).
    let mut observed: Vec<f64> = summary
        .records
        .iter()
        .filter_map(|r| match r.capacity {
            Capacity::Observed(x) => Some(x),
            Capacity::Censored(_) => None,
        })
        .collect();
    observed.sort_by(f64::total_cmp);
    let n = summary.records.len() as f64;
    let points: Vec<(f64, f64)> = observed
        .iter()
        .enumerate()
        .map(|(i, &x)| (x, (i + 1) as f64 / n))
        .collect();
    panel = panel.with(Series::markers("records, i/n", points, 0, Marker::Circle));
    Figure::new(vec![panel], 1)
}

/// The bootstrap fits again, from the same seed (the summary keeps only their intervals).
fn bootstrap_fits(summary: &Summary) -> Vec<Lognormal> {
    let capacities: Vec<Capacity> = summary.records.iter().map(|r| r.capacity).collect();
    bootstrap::resample(capacities.len(), summary.bootstrap, summary.seed, |drawn| {
        let sample: Vec<Capacity> = drawn.iter().map(|&i| capacities[i]).collect();
        flexrock_core::analysis::fragility::fit_capacities(&sample).map(|f| f.fit)
    })
    .0
}

/// The capacities on the intensity axis, one row per record named on the y axis, with the
/// median and fractiles.
fn capacities(summary: &Summary) -> Figure {
    let fit = &summary.fits[0];
    let mut panel = Panel::new("", &im_label(summary), "record");
    let n = summary.records.len();
    panel.y_range = Some((0.0, n as f64 + 1.0));
    // Each row named by its record (event, station and component, else the file's name).
    panel.y_names = (summary.records.iter().enumerate())
        .map(|(i, r)| ((i + 1) as f64, r.label.clone()))
        .collect();
    // From 0, and wide enough for the 84 % fractile, which may lie beyond every capacity.
    let right = summary
        .records
        .iter()
        .map(|r| r.capacity.value())
        .fold(fit.fractile_84, f64::max);
    panel.x_range = Some((0.0, 1.05 * right));
    let mut observed = Vec::new();
    let mut censored = Vec::new();
    for (i, r) in summary.records.iter().enumerate() {
        match r.capacity {
            Capacity::Observed(x) => observed.push((x, (i + 1) as f64)),
            Capacity::Censored(x) => censored.push((x, (i + 1) as f64)),
        }
    }
    panel = panel.with(Series::markers("capacity", observed, 1, Marker::Circle));
    if !censored.is_empty() {
        panel = panel.with(Series::markers(
            "censored (above)",
            censored,
            3,
            Marker::OpenCircle,
        ));
    }
    panel.vertical_lines = vec![
        VerticalLine {
            x: fit.theta,
            color: 0,
            label: format!(
                "median θ = {} {}",
                significant(fit.theta, 3),
                summary.im_unit
            ),
        },
        VerticalLine {
            x: fit.fractile_16,
            color: 2,
            label: format!("16 and 84 % fractiles, β = {}", significant(fit.beta, 2)),
        },
        VerticalLine {
            x: fit.fractile_84,
            color: 2,
            label: String::new(),
        },
    ];
    Figure::new(vec![panel], 1)
}
