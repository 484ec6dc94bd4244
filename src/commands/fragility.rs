//! `flexrock fragility`: a lognormal fragility function of overturning over a suite of records,
//! by incremental dynamic analysis on the sweep's minimum search.
//!
//! The records are one axis of a sweep (`excitation.path`) whose points each search the
//! smallest overturning `excitation.scale` ([`flexrock_core::analysis::sweep::find_min`]): the
//! sweep is stored, resumed and sharded as any other, in `OUT/sweep/`. Each record's capacity
//! is that scale's intensity, the record's intensity measure at scale 1 times scale^p (p = 2
//! for the Arias intensity, 1 for the others). Where the scan finds several overturning bands
//! the capacity is the first (smallest) overturning intensity. A record that does not overturn
//! up to the top of the range is a censored capacity, above the top's intensity, and enters the
//! fit by its likelihood ([`flexrock_core::analysis::fragility::lognormal`]).

use std::path::{Path, PathBuf};

use crate::error::{Error, Result};
use crate::figures::page::FigureOptions;
use flexrock_core::analysis::fragility::study::{self, Study, SuiteMeasures};
use flexrock_core::analysis::fragility::{Measure, RecordResult, Summary, PERCENTILES};
use flexrock_core::analysis::sweep::{axis::Interval, Request, Sweep};
use flexrock_core::model::Setting;

/// The sweep's directory under the output directory.
pub const SWEEP_DIR: &str = "sweep";
/// The result files, written as one set.
pub const JSON_FILE: &str = "fragility.json";
/// One row per damage state.
pub const CSV_FILE: &str = "fragility.csv";
/// The fit in pelicun's fragility database format.
pub const PELICUN_FILE: &str = "fragility-pelicun.csv";
/// What `flexrock fragility` is asked.
#[derive(Debug, Clone)]
pub struct Options {
    /// The model file.
    pub model: PathBuf,
    /// The suite: a directory, a list file, or a file pattern.
    pub records: String,
    /// The intensity measure.
    pub measure: Measure,
    /// The period of Sa, s [default: the body's pre-uplift period].
    pub period: Option<f64>,
    /// The range of excitation.scale searched.
    pub scale: Interval,
    /// Scanned scales (the sweep's --scan).
    pub scan: Option<usize>,
    /// Bisection tolerance, in scale.
    pub tol: Option<f64>,
    /// Bootstrap resamples.
    pub bootstrap: usize,
    /// The bootstrap's seed.
    pub seed: u64,
    /// `--set` keys.
    pub settings: Vec<Setting>,
    /// Points per chunk of the sweep.
    pub chunk_size: Option<usize>,
    /// The output directory.
    pub out: PathBuf,
    /// The shard of the sweep to compute, if any.
    pub shard: Option<super::sweep::store::Shard>,
    /// Replace another sweep's results.
    pub force: bool,
    /// The figures' formats and size.
    pub figures: FigureOptions,
}

/// What `flexrock fragility` reports.
#[derive(Debug)]
pub struct Report {
    /// The summary (None for a shard, which only computes its part of the sweep).
    pub summary: Option<Summary>,
    /// The sweep's report.
    pub sweep: super::sweep::store::SweepReport,
    /// The files written.
    pub files: Vec<PathBuf>,
}

/// The study's settings, as the core takes them.
fn study(options: &Options) -> Study {
    Study {
        model_file: options.model.display().to_string(),
        measure: options.measure,
        period: options.period,
        scale: options.scale,
        bootstrap: options.bootstrap,
        seed: options.seed,
    }
}

/// A core error about the study named by its flag.
fn flagged(e: flexrock_core::Error) -> Error {
    e.renamed("records", "--records")
        .renamed("scale", "--scale")
        .renamed("bootstrap", "--bootstrap")
        .renamed("period", "--period")
        .into()
}

/// Checks what can be checked before anything runs, and builds the sweep.
pub fn prepare(options: &Options) -> Result<(Sweep, SuiteMeasures)> {
    let axis = study::record_axis(&options.records).map_err(flagged)?;
    study(options).check().map_err(flagged)?;
    let request = Request {
        settings: options.settings.clone(),
        axes: vec![axis],
        find_min: Some(("excitation.scale".to_string(), options.scale)),
        scan: options.scan,
        tol: options.tol,
        chunk_size: options.chunk_size,
        ..Request::default()
    };
    let here = std::env::current_dir().unwrap_or_default();
    let sweep = Sweep::new(&options.model, request, &here).map_err(|e| {
        e.renamed("find_min", "--scale")
            .renamed("scan", "--scan")
            .renamed("tol", "--tol")
    })?;
    // Each record's measure at scale 1, before anything runs.
    let measures =
        study::suite_measures(&sweep, options.measure, options.period).map_err(flagged)?;
    Ok((sweep, measures))
}

/// Runs the sweep (or resumes it) and fits.
pub fn run(options: &Options, progress: &dyn super::sweep::store::Progress) -> Result<Report> {
    let (sweep, measures) = prepare(options)?;
    let target = super::sweep::store::Target {
        out: options.out.join(SWEEP_DIR),
        shard: options.shard,
        force: options.force,
    };
    let report = super::sweep::store::run(&sweep, &target, progress)?;
    if options.shard.is_some() {
        return Ok(Report {
            summary: None,
            sweep: report,
            files: Vec::new(),
        });
    }
    let records = read_records(&report.dir.join("sweep.csv"), &sweep, &measures, options)?;
    let summary = study::summarize(
        &Study {
            period: measures.period,
            ..study(options)
        },
        records,
    )
    .map_err(|e| Error::invalid("--records", options.records.as_str(), &e.to_string()))?;
    let mut files: Vec<(String, Vec<u8>)> = vec![
        (JSON_FILE.to_string(), crate::writers::json_bytes(&summary)),
        (CSV_FILE.to_string(), fragility_csv(&summary)),
        (PELICUN_FILE.to_string(), pelicun_csv(&summary, options)),
    ];
    files.extend(crate::figures::fragility::files(
        &summary,
        &options.figures,
    )?);
    let named: Vec<(&str, Vec<u8>)> = files.iter().map(|(n, b)| (n.as_str(), b.clone())).collect();
    let written = crate::writers::write_atomically(&options.out, &named)?;
    Ok(Report {
        summary: Some(summary),
        sweep: report,
        files: written,
    })
}

/// Each record's result from the sweep's table.
fn read_records(
    table: &Path,
    sweep: &Sweep,
    measures: &SuiteMeasures,
    options: &Options,
) -> Result<Vec<RecordResult>> {
    let read_error = |message: String| Error::ReadResult {
        path: table.to_path_buf(),
        message,
    };
    let mut reader = csv::Reader::from_path(table).map_err(|e| read_error(e.to_string()))?;
    let headers = reader
        .headers()
        .map_err(|e| read_error(e.to_string()))?
        .clone();
    let col = |name: &str| {
        headers
            .iter()
            .position(|h| h == name)
            .ok_or_else(|| read_error(format!("has no column {name}")))
    };
    let (status, reason, min, bands, n_bands) = (
        col("status")?,
        col("reason")?,
        col("min_overturning")?,
        col("overturning_bands")?,
        col("n_bands")?,
    );
    let paths = &sweep.plan.axes[0].values;
    let mut out = Vec::new();
    for (i, row) in reader.records().enumerate() {
        let row = row.map_err(|e| read_error(e.to_string()))?;
        let path = paths.get(i).cloned().unwrap_or_default();
        if &row[status] != "ok" {
            return Err(Error::invalid(
                "--records",
                path.as_str(),
                &format!(
                    "its minimum search is {}: {} (see {})",
                    &row[status],
                    &row[reason],
                    table.display()
                ),
            ));
        }
        let scale: Option<f64> = row[min].parse().ok();
        let unscaled = measures.unscaled[i];
        out.push(RecordResult {
            path,
            label: measures.labels[i].clone(),
            im_unscaled: unscaled,
            capacity: study::capacity(options.measure, unscaled, scale, options.scale.hi),
            min_overturning_scale: scale,
            overturning_bands: row[bands].to_string(),
            n_bands: row[n_bands].parse().unwrap_or(0),
        });
    }
    if out.len() != paths.len() {
        return Err(read_error(format!(
            "has {} rows for {} records",
            out.len(),
            paths.len()
        )));
    }
    Ok(out)
}

/// fragility.csv: one row per damage state.
fn fragility_csv(summary: &Summary) -> Vec<u8> {
    use flexrock_core::base::format::shortest;
    let unit = match summary.im_unit.as_str() {
        "m/s" => "m_s",
        other => other,
    };
    let theta = format!("theta_{unit}");
    let theta_lo = format!("theta_p5_{unit}");
    let theta_hi = format!("theta_p95_{unit}");
    let columns = [
        "state",
        "im",
        theta.as_str(),
        "beta",
        "beta_unbiased",
        theta_lo.as_str(),
        theta_hi.as_str(),
        "beta_p5",
        "beta_p95",
        "records",
        "censored",
        "method",
    ];
    let mut table = crate::writers::Table::new(&columns);
    let opt = |x: Option<f64>| x.map(shortest).unwrap_or_default();
    for f in &summary.fits {
        table.row([
            f.state.clone(),
            summary.im.name().to_string(),
            shortest(f.theta),
            shortest(f.beta),
            opt(f.beta_unbiased),
            opt(f.theta_interval.map(|i| i.lo)),
            opt(f.theta_interval.map(|i| i.hi)),
            opt(f.beta_interval.map(|i| i.lo)),
            opt(f.beta_interval.map(|i| i.hi)),
            (f.observed + f.censored).to_string(),
            f.censored.to_string(),
            f.method.clone(),
        ]);
    }
    table.into_bytes()
}

/// The fit in pelicun's fragility database format: one component per damage state, its one
/// limit state lognormal (Theta_0 the median, Theta_1 the dispersion).
fn pelicun_csv(summary: &Summary, options: &Options) -> Vec<u8> {
    use flexrock_core::base::format::shortest;
    let (demand, unit) = match summary.im {
        Measure::Pga => ("Peak Ground Acceleration", "g"),
        Measure::Pgv => ("Peak Ground Velocity", "mps"),
        Measure::Pgd => ("Peak Ground Displacement", "m"),
        Measure::Arias => ("Arias Intensity", "mps"),
        Measure::Cav => ("Cumulative Absolute Velocity", "mps"),
        Measure::Sa => ("Spectral Acceleration", "g"),
    };
    let stem = options
        .model
        .file_stem()
        .map(|s| s.to_string_lossy().into_owned())
        .unwrap_or_default();
    let mut table = crate::writers::Table::new(&[
        "ID",
        "Incomplete",
        "Demand-Type",
        "Demand-Unit",
        "Demand-Offset",
        "Demand-Directional",
        "LS1-Family",
        "LS1-Theta_0",
        "LS1-Theta_1",
        "LS1-DamageStateWeights",
    ]);
    for f in &summary.fits {
        table.row([
            format!("flexrock.{stem}.{}", f.state),
            "0".into(),
            demand.into(),
            unit.into(),
            "0".into(),
            "0".into(),
            "lognormal".into(),
            shortest(f.theta),
            shortest(f.beta),
            String::new(),
        ]);
    }
    table.into_bytes()
}

/// The lines `flexrock fragility` prints.
pub fn report_text(report: &Report) -> String {
    use std::fmt::Write as _;
    let mut t = super::sweep::report_text(&report.sweep, None);
    let Some(s) = &report.summary else {
        t.push_str("  a shard computes its part of the sweep only: merge the shards (flexrock sweep merge) into OUT/sweep and run the command again to fit\n");
        return t;
    };
    let u = &s.im_unit;
    for f in &s.fits {
        let _ = writeln!(
            t,
            "fragility of {} in {} ({}): theta = {:.4} {u}, beta = {:.3} ({}; {} records, {} censored)",
            f.state,
            s.im.name(),
            s.analysis,
            f.theta,
            f.beta,
            f.method,
            f.observed + f.censored,
            f.censored
        );
        if let (Some(ti), Some(bi)) = (f.theta_interval, f.beta_interval) {
            let _ = writeln!(
                t,
                "  bootstrap {}/{} %: theta {:.4}..{:.4} {u}, beta {:.3}..{:.3} ({} resamples, seed {})",
                PERCENTILES[0], PERCENTILES[1], ti.lo, ti.hi, bi.lo, bi.hi, s.bootstrap, s.seed
            );
        }
    }
    for f in &report.files {
        let _ = writeln!(t, "  wrote {}", f.display());
    }
    t
}
