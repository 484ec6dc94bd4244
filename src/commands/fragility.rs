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
use flexrock_core::analysis::fragility::{
    bootstrap, fit_capacities, lognormal::CapacityFit, Capacity, Interval90, Lognormal, Measure,
    RecordResult, StateFit, Summary, CAPACITY_RULE, PERCENTILES,
};
use flexrock_core::analysis::sweep::{axis::Interval, Axis, Request, Sweep};
use flexrock_core::floor::RecordedMotion;
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

/// The records of a suite: a directory or list file read as a suite, else a file pattern.
fn record_axis(records: &str) -> Result<Axis> {
    let path = Path::new(records);
    if path.exists() {
        let suite = flexrock_core::floor::record::suite::read_suite(path)
            .map_err(|e| Error::invalid("--records", records, &e.to_string()))?;
        let mut values = Vec::new();
        for entry in &suite.entries {
            if entry.scale != 1.0 || entry.vertical.is_some() {
                return Err(Error::invalid(
                    "--records",
                    records,
                    &format!(
                        "line {} gives scale= or vertical=: fragility scales every record \
                         itself and reads horizontal records only; remove them",
                        entry.line.unwrap_or(0)
                    ),
                ));
            }
            values.push(entry.path.to_string_lossy().into_owned());
        }
        Ok(Axis::new("excitation.path", values))
    } else if !records.contains(['*', '?', '[']) {
        Err(Error::invalid(
            "--records",
            records,
            "no such file or directory: give a directory of record files, a list file (one path \
             a line) or a quoted pattern such as 'suite/*.AT2'",
        ))
    } else {
        Axis::parse(&format!("excitation.path={records}"), Path::new("."))
            .map_err(|e| Error::invalid("--records", records, &e.to_string()))
    }
}

/// Checks what can be checked before anything runs, and builds the sweep.
pub fn prepare(options: &Options) -> Result<(Sweep, Vec<f64>, Option<f64>)> {
    let axis = record_axis(&options.records)?;
    if axis.len() < 2 {
        return Err(Error::invalid(
            "--records",
            options.records.as_str(),
            &format!(
                "names {} record: a fragility fit needs at least 2 (and a real study a suite of \
                 tens, e.g. the FEMA P695 far-field set)",
                axis.len()
            ),
        ));
    }
    if options.scale.lo <= 0.0 {
        return Err(Error::invalid(
            "--scale",
            format!("{}:{}", options.scale.lo, options.scale.hi),
            "LO must be above 0 (a capacity is a positive intensity)",
        ));
    }
    if options.bootstrap == 1 {
        return Err(Error::invalid(
            "--bootstrap",
            options.bootstrap,
            "must be 0 (no intervals) or at least 2",
        ));
    }
    if let Some(t) = options.period {
        if options.measure != Measure::Sa {
            return Err(Error::invalid(
                "--period",
                t,
                "is the period of Sa: give it with --im sa",
            ));
        }
    }
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
    let mut unscaled = Vec::new();
    let mut period = None;
    let paths = &sweep.plan.axes[0].values;
    for (i, name) in paths.iter().enumerate() {
        let model = sweep.model_at(i, &[Setting::number("excitation.scale", 1.0)])?;
        let Some(record) = RecordedMotion::of(model.floor.as_ref()) else {
            return Err(Error::invalid(
                "--records",
                name.as_str(),
                "is not a record",
            ));
        };
        let g = flexrock_core::STANDARD_GRAVITY;
        let ground = flexrock_core::floor::intensity::ground_measures(record);
        let value = match options.measure {
            Measure::Pga => ground.pga / g,
            Measure::Pgv => ground.pgv,
            Measure::Pgd => ground.pgd,
            Measure::Arias => ground.arias,
            Measure::Cav => ground.cav,
            Measure::Sa => {
                let t = options.period.unwrap_or(model.constants.period);
                period = Some(t);
                flexrock_core::bodies::oscillator::spectral_acceleration(
                    record,
                    t,
                    flexrock_core::bodies::oscillator::DEFAULT_DAMPING,
                )
                .map_err(|e| Error::invalid("--period", t, &e.to_string()))?
                .sa / g
            }
        };
        if !(value > 0.0 && value.is_finite()) {
            return Err(Error::invalid(
                "--records",
                name.as_str(),
                &format!(
                    "has {} = {value}: a record scaled to an intensity needs a positive one",
                    options.measure.name()
                ),
            ));
        }
        unscaled.push(value);
    }
    Ok((sweep, unscaled, period))
}

/// Runs the sweep (or resumes it) and fits.
pub fn run(options: &Options, progress: &dyn super::sweep::store::Progress) -> Result<Report> {
    let (sweep, unscaled, period) = prepare(options)?;
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
    let records = read_records(&report.dir.join("sweep.csv"), &sweep, &unscaled, options)?;
    let summary = fit(options, &records, period)?;
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
    unscaled: &[f64],
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
        let capacity = match scale {
            Some(s) => Capacity::Observed(options.measure.scaled(unscaled[i], s)),
            None => Capacity::Censored(options.measure.scaled(unscaled[i], options.scale.hi)),
        };
        out.push(RecordResult {
            path,
            im_unscaled: unscaled[i],
            min_overturning_scale: scale,
            capacity,
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

/// The fit, its bootstrap and the summary.
fn fit(options: &Options, records: &[RecordResult], period: Option<f64>) -> Result<Summary> {
    let capacities: Vec<Capacity> = records.iter().map(|r| r.capacity).collect();
    let fit: CapacityFit = fit_capacities(&capacities)
        .map_err(|e| Error::invalid("--records", options.records.as_str(), &e.to_string()))?;
    let (fits, failed) =
        bootstrap::resample(capacities.len(), options.bootstrap, options.seed, |drawn| {
            let sample: Vec<Capacity> = drawn.iter().map(|&i| capacities[i]).collect();
            fit_capacities(&sample).map(|f| f.fit)
        });
    let interval = |of: fn(&Lognormal) -> f64| {
        let values: Vec<f64> = fits.iter().map(of).collect();
        Some(Interval90 {
            lo: bootstrap::quantile(&values, PERCENTILES[0] / 100.0)?,
            hi: bootstrap::quantile(&values, PERCENTILES[1] / 100.0)?,
        })
    };
    let mut warnings = Vec::new();
    if records.len() < 10 {
        warnings.push(format!(
            "{} records are far too few for a fragility function: a real study needs a suite \
             of tens of records (e.g. the FEMA P695 far-field set)",
            records.len()
        ));
    }
    for r in records.iter().filter(|r| r.n_bands > 1) {
        warnings.push(format!(
            "{}: overturning is not monotonic in the scale (overturning bands {}); its capacity \
             is the first overturning intensity",
            r.path, r.overturning_bands
        ));
    }
    if fit.censored > 0 {
        warnings.push(format!(
            "{} of {} records did not overturn up to scale {}: their capacities are censored \
             (above the top of the range) and enter the fit by their likelihood",
            fit.censored,
            records.len(),
            options.scale.hi
        ));
    }
    if failed > 0 {
        warnings.push(format!(
            "{failed} of {} bootstrap resamples gave no fit (too few distinct observed \
             capacities) and are left out of the intervals",
            options.bootstrap
        ));
    }
    let Lognormal { theta, beta } = fit.fit;
    Ok(Summary {
        flexrock_version: flexrock_core::simulate::VERSION.to_string(),
        flexrock_commit: flexrock_core::simulate::COMMIT.to_string(),
        model_file: options.model.display().to_string(),
        analysis: "ida".into(),
        im: options.measure,
        im_unit: options.measure.unit().into(),
        im_scale_power: options.measure.scale_power(),
        sa_period_s: period,
        scale_range: [options.scale.lo, options.scale.hi],
        capacity_rule: CAPACITY_RULE.into(),
        censoring: "a record that does not overturn up to the top of the range has a capacity \
                    above the top's intensity: it enters the maximum likelihood fit as \
                    1 - Phi(z) at that intensity"
            .into(),
        fits: vec![StateFit {
            state: "overturning".into(),
            theta,
            beta,
            beta_unbiased: fit.beta_unbiased,
            method: fit.method.into(),
            fractile_16: theta * (-beta).exp(),
            fractile_84: theta * beta.exp(),
            theta_interval: interval(|f| f.theta),
            beta_interval: interval(|f| f.beta),
            observed: fit.observed,
            censored: fit.censored,
        }],
        bootstrap: options.bootstrap,
        bootstrap_failed: failed,
        seed: options.seed,
        percentiles: PERCENTILES,
        records: records.to_vec(),
        warnings,
    })
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
