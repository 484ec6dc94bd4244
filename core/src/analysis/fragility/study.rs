//! A fragility study by incremental dynamic analysis, the parts the command line and the Python
//! bindings share: the suite as a sweep's axis (`excitation.path`), the checks made before
//! anything runs, each record's intensity measure at scale 1 and its name, each record's
//! capacity from the sweep's minimum search, and the summary with the fit and its bootstrap.
//! Where the sweep's rows are kept (on disk in chunks, or in memory) is the caller's business.
//!
//! An error names the value by its key: `records`, `scale`, `bootstrap`, `period`; the
//! command line renames them to its flags.

use std::path::Path;

use super::{
    bootstrap, fit_capacities, Capacity, FitError, Interval90, Lognormal, Measure, RecordResult,
    StateFit, Summary, CAPACITY_RULE, PERCENTILES,
};
use crate::analysis::sweep::{axis::Interval, Axis, Sweep};
use crate::floor::RecordedMotion;
use crate::model::Setting;
use crate::{Error, Result};

/// What a study is asked, besides its model and suite.
#[derive(Debug, Clone)]
pub struct Study {
    /// The model file as named (or how the model was given), for fragility.json.
    pub model_file: String,
    /// The intensity measure.
    pub measure: Measure,
    /// The period of Sa, s [default: the body's pre-uplift period].
    pub period: Option<f64>,
    /// The range of excitation.scale searched.
    pub scale: Interval,
    /// Bootstrap resamples (0: no intervals).
    pub bootstrap: usize,
    /// The bootstrap's seed.
    pub seed: u64,
}

impl Study {
    /// Refuses what no sweep needs to run to know is wrong.
    pub fn check(&self) -> Result<()> {
        if self.scale.lo <= 0.0 {
            return Err(Error::invalid(
                "scale",
                format!("{}:{}", self.scale.lo, self.scale.hi),
                "LO must be above 0 (a capacity is a positive intensity)",
            ));
        }
        if self.bootstrap == 1 {
            return Err(Error::invalid(
                "bootstrap",
                self.bootstrap,
                "must be 0 (no intervals) or at least 2",
            ));
        }
        if let Some(t) = self.period {
            if self.measure != Measure::Sa {
                return Err(Error::invalid(
                    "period",
                    t,
                    "is the period of Sa: give it with the intensity measure sa",
                ));
            }
        }
        Ok(())
    }
}

/// The records of a suite as the axis `excitation.path`: a directory or list file read as a
/// suite, else a file pattern (relative to the current directory). At least 2 records.
pub fn record_axis(records: &str) -> Result<Axis> {
    let path = Path::new(records);
    let axis = if path.exists() {
        let suite = crate::floor::record::suite::read_suite(path)
            .map_err(|e| Error::invalid("records", records, &e.to_string()))?;
        let mut values = Vec::new();
        for entry in &suite.entries {
            if entry.scale != 1.0 || entry.vertical.is_some() {
                return Err(Error::invalid(
                    "records",
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
        Axis::new("excitation.path", values)
    } else if !records.contains(['*', '?', '[']) {
        return Err(Error::invalid(
            "records",
            records,
            "no such file or directory: give a directory of record files, a list file (one path \
             a line) or a quoted pattern such as 'suite/*.AT2'",
        ));
    } else {
        Axis::parse(&format!("excitation.path={records}"), Path::new("."))
            .map_err(|e| Error::invalid("records", records, &e.to_string()))?
    };
    if axis.len() < 2 {
        return Err(Error::invalid(
            "records",
            records,
            &format!(
                "names {} record: a fragility fit needs at least 2 (and a real study a suite of \
                 tens, e.g. the FEMA P695 far-field set)",
                axis.len()
            ),
        ));
    }
    Ok(axis)
}

/// Each record of a sweep over `excitation.path` (its first axis) at scale 1: its intensity
/// measure and its name.
#[derive(Debug, Clone)]
pub struct SuiteMeasures {
    /// The measure at scale 1, in its unit, per record.
    pub unscaled: Vec<f64>,
    /// The name of each record: event, station and component where its file gives them, else
    /// the file's name.
    pub labels: Vec<String>,
    /// The period of Sa, s, for `sa` only.
    pub period: Option<f64>,
}

/// The measures of the records of `sweep` (see [`SuiteMeasures`]), before anything runs.
pub fn suite_measures(
    sweep: &Sweep,
    measure: Measure,
    period: Option<f64>,
) -> Result<SuiteMeasures> {
    let mut out = SuiteMeasures {
        unscaled: Vec::new(),
        labels: Vec::new(),
        period: None,
    };
    let paths = &sweep.plan.axes[0].values;
    for (i, name) in paths.iter().enumerate() {
        let model = sweep.model_at(i, &[Setting::number("excitation.scale", 1.0)])?;
        let Some(record) = RecordedMotion::of(model.floor.as_ref()) else {
            return Err(Error::invalid("records", name.as_str(), "is not a record"));
        };
        let g = crate::STANDARD_GRAVITY;
        let ground = crate::floor::intensity::ground_measures(record);
        let value = match measure {
            Measure::Pga => ground.pga / g,
            Measure::Pgv => ground.pgv,
            Measure::Pgd => ground.pgd,
            Measure::Arias => ground.arias,
            Measure::Cav => ground.cav,
            Measure::Sa => {
                let t = period.unwrap_or(model.constants.period);
                out.period = Some(t);
                crate::bodies::oscillator::spectral_acceleration(
                    record,
                    t,
                    crate::bodies::oscillator::DEFAULT_DAMPING,
                )
                .map_err(|e| Error::invalid("period", t, &e.to_string()))?
                .sa / g
            }
        };
        if !(value > 0.0 && value.is_finite()) {
            return Err(Error::invalid(
                "records",
                name.as_str(),
                &format!(
                    "has {} = {value}: a record scaled to an intensity needs a positive one",
                    measure.name()
                ),
            ));
        }
        let file_name = Path::new(name)
            .file_name()
            .map(|f| f.to_string_lossy().into_owned())
            .unwrap_or_else(|| name.clone());
        out.unscaled.push(value);
        out.labels.push(record.meta().label(&file_name));
    }
    Ok(out)
}

/// A record's capacity: its measure at the smallest overturning scale found, or, where none
/// was found up to the top of the range, censored at the top's intensity.
pub fn capacity(measure: Measure, unscaled: f64, min_scale: Option<f64>, top: f64) -> Capacity {
    match min_scale {
        Some(s) => Capacity::Observed(measure.scaled(unscaled, s)),
        None => Capacity::Censored(measure.scaled(unscaled, top)),
    }
}

/// The fit of the records' capacities, its bootstrap and the summary (fragility.json).
pub fn summarize(
    study: &Study,
    records: Vec<RecordResult>,
) -> std::result::Result<Summary, FitError> {
    let capacities: Vec<Capacity> = records.iter().map(|r| r.capacity).collect();
    let fit = fit_capacities(&capacities)?;
    let (fits, failed) =
        bootstrap::resample(capacities.len(), study.bootstrap, study.seed, |drawn| {
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
            study.scale.hi
        ));
    }
    if failed > 0 {
        warnings.push(format!(
            "{failed} of {} bootstrap resamples gave no fit (too few distinct observed \
             capacities) and are left out of the intervals",
            study.bootstrap
        ));
    }
    let Lognormal { theta, beta } = fit.fit;
    Ok(Summary {
        flexrock_version: crate::simulate::VERSION.to_string(),
        flexrock_commit: crate::simulate::COMMIT.to_string(),
        model_file: study.model_file.clone(),
        analysis: "ida".into(),
        im: study.measure,
        im_unit: study.measure.unit().into(),
        im_scale_power: study.measure.scale_power(),
        sa_period_s: study.period,
        scale_range: [study.scale.lo, study.scale.hi],
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
        bootstrap: study.bootstrap,
        bootstrap_failed: failed,
        seed: study.seed,
        percentiles: PERCENTILES,
        records,
        warnings,
    })
}
