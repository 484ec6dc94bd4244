//! Rules of the `[excitation]` section: which keys each kind takes, and the floor motion it makes.

use std::collections::HashMap;
use std::path::{Path, PathBuf};
use std::sync::{Arc, Mutex};

use super::schema::{BodySection, ExcitationSection};
use crate::error::{Error, Result};
use crate::floor::record::{read_record_named, Record, RecordFormat};
use crate::floor::{
    above_floor_minimum, floor_limit_rule, floor_minimum_rule, within_floor_limit, FloorMotion,
    Free, Harmonic, PaperSine, PulseShape, RecordedMotion, Ricker, SinePulse,
    MIN_EXCITATION_PERIOD,
};
use crate::physics::body::{positive, Body, ConstantSet, SelfWeight};
use crate::physics::constants::Constants;

/// A record is known by its path, format and given sampling interval (as bits).
type RecordKey = (PathBuf, Option<RecordFormat>, Option<u64>);
type RecordMap = HashMap<RecordKey, Arc<Record>>;

/// Records read once and shared: a sweep builds thousands of models from a few record files.
/// A record is known by its path, format and given sampling interval.
#[derive(Debug, Default)]
pub struct RecordCache {
    records: Mutex<RecordMap>,
    /// The constants of the bodies met so far: a sweep that varies the excitation derives
    /// them once instead of at every point (they are a pure function of the body).
    constants: Mutex<HashMap<BodyKey, Constants>>,
    /// The last `[body]` section read and its body: a sweep that varies the excitation reads
    /// the same section at every point.
    last_body: Mutex<Option<(BodySection, Body)>>,
}

/// A body known by the bits of its numbers and its variants.
type BodyKey = ([u64; 8], ConstantSet, SelfWeight, bool);

/// Bodies whose constants a cache keeps at most (a sweep over the body itself would otherwise
/// keep one per point).
const MAX_CACHED_BODIES: usize = 256;

impl RecordCache {
    /// `read(section)`, from the cache when the section is the last one read (the same bits
    /// in every number, the same texts). A section that is refused is read every time, so
    /// that its message is always its own.
    pub(crate) fn body(
        &self,
        section: &BodySection,
        read: impl FnOnce(&BodySection) -> Result<Body>,
    ) -> Result<Body> {
        let lock = || self.last_body.lock().unwrap_or_else(|e| e.into_inner());
        if let Some((last, body)) = lock().as_ref() {
            if last.same_as(section) {
                return Ok(body.clone());
            }
        }
        let body = read(section)?;
        *lock() = Some((section.clone(), body.clone()));
        Ok(body)
    }

    /// `Constants::new(body)`, from the cache when this body was met before.
    pub(crate) fn constants(&self, body: &Body) -> Result<Constants> {
        let key = (
            [
                body.height,
                body.width,
                body.depth,
                body.mass,
                body.flexural_rigidity,
                body.damping_ratio,
                body.gravity,
                body.landing_restitution,
            ]
            .map(f64::to_bits),
            body.constant_set,
            body.self_weight,
            body.damping_while_rocking,
        );
        let lock = || self.constants.lock().unwrap_or_else(|e| e.into_inner());
        if let Some(constants) = lock().get(&key) {
            return Ok(constants.clone());
        }
        let constants = Constants::new(body)?;
        let mut cache = lock();
        if cache.len() >= MAX_CACHED_BODIES {
            cache.clear();
        }
        cache.insert(key, constants.clone());
        Ok(constants)
    }
}

impl RecordCache {
    /// Puts `record` in the cache as if read from the file `path` without a format or a dt
    /// given: a model whose `excitation.path` names `path` (joined to its base directory) and
    /// no `excitation.format` or `excitation.dt` takes the record from here, and reads no file.
    pub fn insert(&self, path: &Path, record: Record) {
        // Kept under the path a model reads it from ([`record_path`]).
        self.lock().insert(
            (super::setting::normalised(path), None, None),
            Arc::new(record),
        );
    }

    fn read(
        &self,
        path: &Path,
        name: &str,
        format: Option<RecordFormat>,
        dt: Option<f64>,
    ) -> std::result::Result<Arc<Record>, crate::floor::record::RecordError> {
        let key = (path.to_path_buf(), format, dt.map(f64::to_bits));
        if let Some(record) = self.lock().get(&key) {
            return Ok(Arc::clone(record));
        }
        // Read outside the lock; two threads may read one file at once, and agree.
        let record = Arc::new(read_record_named(path, name, format, dt)?);
        self.lock().insert(key, Arc::clone(&record));
        Ok(record)
    }

    fn lock(&self) -> std::sync::MutexGuard<'_, RecordMap> {
        // A panic elsewhere cannot leave the map half-updated: insert is one call.
        self.records.lock().unwrap_or_else(|e| e.into_inner())
    }
}

/// The kinds of `[excitation]`. Each knows its name, the keys it takes and which of them must be
/// given; [`floor_from_section`] builds each with an exhaustive match, so that a kind added here
/// cannot fall through to another's motion.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Kind {
    PaperSine,
    Harmonic,
    SinePulse,
    Ricker,
    Record,
    Free,
}

impl Kind {
    const ALL: [Kind; 6] = [
        Kind::PaperSine,
        Kind::Harmonic,
        Kind::SinePulse,
        Kind::Ricker,
        Kind::Record,
        Kind::Free,
    ];

    fn name(self) -> &'static str {
        match self {
            Kind::PaperSine => "paper-sine",
            Kind::Harmonic => "harmonic",
            Kind::SinePulse => "sine-pulse",
            Kind::Ricker => "ricker",
            Kind::Record => "record",
            Kind::Free => "free",
        }
    }

    /// The keys this kind takes (any other given key is an error).
    fn keys(self) -> &'static [Key] {
        use Key::*;
        match self {
            Kind::PaperSine => &[Amplitude, Period, Ramp],
            Kind::Harmonic => &[Amplitude, Period],
            Kind::SinePulse => &[Amplitude, Period, Cycles, Shape, Tail],
            Kind::Ricker => &[Amplitude, Period, Center],
            Kind::Record => &[Path, Format, Units, Scale, Start, End, Tail, Dt],
            Kind::Free => &[],
        }
    }

    /// The keys of [`Kind::keys`] that have no default.
    fn required(self) -> &'static [Key] {
        use Key::*;
        match self {
            Kind::PaperSine => &[Amplitude, Period, Ramp],
            Kind::Harmonic | Kind::SinePulse => &[Amplitude, Period],
            Kind::Ricker => &[Amplitude, Period, Center],
            Kind::Record => &[Path],
            Kind::Free => &[],
        }
    }
}

/// The keys of `[excitation]` besides `kind`.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Key {
    Amplitude,
    Period,
    Ramp,
    Cycles,
    Shape,
    Center,
    Path,
    Format,
    Units,
    Scale,
    Start,
    End,
    Tail,
    Dt,
    Ratio,
}

impl Key {
    const ALL: [Key; 15] = [
        Key::Amplitude,
        Key::Period,
        Key::Ramp,
        Key::Cycles,
        Key::Shape,
        Key::Center,
        Key::Path,
        Key::Format,
        Key::Units,
        Key::Scale,
        Key::Start,
        Key::End,
        Key::Tail,
        Key::Dt,
        Key::Ratio,
    ];

    fn name(self) -> &'static str {
        match self {
            Key::Amplitude => "amplitude",
            Key::Period => "period",
            Key::Ramp => "ramp",
            Key::Cycles => "cycles",
            Key::Shape => "shape",
            Key::Center => "center",
            Key::Path => "path",
            Key::Format => "format",
            Key::Units => "units",
            Key::Scale => "scale",
            Key::Start => "start",
            Key::End => "end",
            Key::Tail => "tail",
            Key::Dt => "dt",
            Key::Ratio => "ratio",
        }
    }

    /// The value the section gives the key, if any. The section is taken apart field by field,
    /// so that a field added to it without a key here does not compile.
    fn given(self, s: &ExcitationSection) -> Option<Given<'_>> {
        let ExcitationSection {
            kind: _,
            amplitude,
            period,
            ramp,
            cycles,
            shape,
            center,
            path,
            format,
            units,
            scale,
            start,
            end,
            tail,
            dt,
            ratio,
            vertical: _,
        } = s;
        let number = |x: &Option<f64>| x.map(Given::Number);
        fn text(x: &Option<String>) -> Option<Given<'_>> {
            x.as_deref().map(Given::Text)
        }
        match self {
            Key::Amplitude => number(amplitude),
            Key::Period => number(period),
            Key::Ramp => number(ramp),
            Key::Cycles => number(cycles),
            Key::Shape => text(shape),
            Key::Center => number(center),
            Key::Path => text(path),
            Key::Format => text(format),
            Key::Units => text(units),
            Key::Scale => number(scale),
            Key::Start => number(start),
            Key::End => number(end),
            Key::Tail => number(tail),
            Key::Dt => number(dt),
            Key::Ratio => number(ratio),
        }
    }
}

/// The names of the `[excitation]` keys kind `kind` takes besides `kind` (a sweep refuses an
/// axis over any other); None for a name that is no kind.
pub(crate) fn keys_of_kind(kind: &str) -> Option<Vec<&'static str>> {
    let kind = Kind::ALL.into_iter().find(|k| k.name() == kind)?;
    Some(kind.keys().iter().map(|k| k.name()).collect())
}

/// A value an `[excitation]` section gives; written out only for a message.
#[derive(Debug, Clone, Copy)]
enum Given<'a> {
    Number(f64),
    Text(&'a str),
}

impl Given<'_> {
    fn text(self) -> String {
        match self {
            Given::Number(x) => crate::base::format::number(x),
            Given::Text(t) => t.to_string(),
        }
    }
}

/// The floor motion of the `[excitation]` section, and its natural length if it has one.
pub(super) fn floor_from_section(
    s: &ExcitationSection,
    base_dir: &Path,
    records: &RecordCache,
) -> Result<(Box<dyn FloorMotion>, Option<f64>)> {
    let kinds = || {
        let kinds: Vec<String> = Kind::ALL
            .iter()
            .map(|k| format!("\"{}\"", k.name()))
            .collect();
        format!("must be one of {}", kinds.join(", "))
    };
    if s.kind.is_empty() {
        return Err(Error::invalid("excitation.kind", "(missing)", &kinds()));
    }
    if s.kind == RATIO {
        return Err(Error::invalid(
            "excitation.kind",
            format!("\"{RATIO}\""),
            "only the vertical motion, [excitation.vertical], can be a ratio of the horizontal one",
        ));
    }
    let kind = Kind::ALL
        .into_iter()
        .find(|k| k.name() == s.kind)
        .ok_or_else(|| Error::invalid("excitation.kind", format!("\"{}\"", s.kind), &kinds()))?;
    for key in Key::ALL {
        let wanted = kind.keys().contains(&key);
        match key.given(s) {
            Some(v) if !wanted => {
                return Err(Error::invalid(
                    &format!("excitation.{}", key.name()),
                    v.text(),
                    &format!("not a parameter of kind = \"{}\"", kind.name()),
                ))
            }
            None if kind.required().contains(&key) => {
                return Err(Error::invalid(
                    &format!("excitation.{}", key.name()),
                    "(missing)",
                    &format!("required for kind = \"{}\"", kind.name()),
                ))
            }
            _ => {}
        }
    }
    let amplitude = s.amplitude.unwrap_or(0.0);
    if !amplitude.is_finite() {
        return Err(Error::invalid(
            "excitation.amplitude",
            amplitude,
            "must be a finite number",
        ));
    }
    let period = s.period.unwrap_or(1.0);
    if kind.keys().contains(&Key::Period)
        && (period.is_nan() || !period.is_finite() || period < MIN_EXCITATION_PERIOD)
    {
        return Err(Error::invalid(
            "excitation.period",
            period,
            &format!("must be a finite number of at least {MIN_EXCITATION_PERIOD} s"),
        ));
    }
    let floor: Box<dyn FloorMotion> = match kind {
        Kind::PaperSine => {
            let ramp = s.ramp.unwrap_or(0.0);
            positive("excitation.ramp", ramp)?;
            if !crate::base::limits::at_least(ramp, MIN_EXCITATION_PERIOD) {
                return Err(Error::invalid(
                    "excitation.ramp",
                    ramp,
                    &format!(
                        "must be at least {MIN_EXCITATION_PERIOD} s, the shortest time over which \
                         a floor motion may change (as its period)"
                    ),
                ));
            }
            Box::new(PaperSine::new(amplitude, period, ramp))
        }
        Kind::Harmonic => Box::new(Harmonic { amplitude, period }),
        Kind::SinePulse => {
            let cycles = s.cycles.unwrap_or(1.0);
            positive("excitation.cycles", cycles)?;
            let shape = match s.shape.as_deref().unwrap_or("antisymmetric") {
                "antisymmetric" => PulseShape::Antisymmetric,
                "symmetric" => PulseShape::Symmetric,
                other => {
                    return Err(Error::invalid(
                        "excitation.shape",
                        format!("\"{other}\""),
                        "must be \"antisymmetric\" (sine) or \"symmetric\" (cosine)",
                    ))
                }
            };
            let pulse = SinePulse::new(amplitude, period, cycles, shape);
            if !crate::base::limits::at_least(pulse.end(), MIN_EXCITATION_PERIOD) {
                return Err(Error::invalid(
                    "excitation.cycles",
                    cycles,
                    &format!(
                        "the pulse, cycles x period = {} s, must last at least \
                         {MIN_EXCITATION_PERIOD} s, the shortest time over which a floor motion \
                         may change (as its period)",
                        crate::base::format::shortest(pulse.end())
                    ),
                ));
            }
            // With a tail, the run lasts the pulse and the tail (unless simulation.duration says
            // otherwise): a sweep over the pulse period keeps the free rocking after it the same.
            let natural = match s.tail {
                Some(tail) => Some(pulse.end() + check_tail(tail)?),
                None => None,
            };
            return finish_analytic(Box::new(pulse), amplitude, s, natural);
        }
        Kind::Ricker => {
            let center = s.center.unwrap_or(0.0);
            if !center.is_finite() {
                return Err(Error::invalid(
                    "excitation.center",
                    center,
                    "must be a finite number",
                ));
            }
            Box::new(Ricker {
                amplitude,
                period,
                center,
            })
        }
        Kind::Record => {
            let (record, tail, unscaled) = recorded_motion(s, base_dir, records)?;
            let (peak, t_peak) = record.peak();
            let scale = s.scale.unwrap_or(1.0);
            // The minimum is checked on the product, which may underflow to 0 where the scaled
            // samples did.
            if !above_floor_minimum(unscaled) {
                return Err(Error::invalid(
                    "excitation.path",
                    s.path.clone().unwrap_or_default(),
                    &floor_minimum_rule(unscaled),
                ));
            }
            if !above_floor_minimum(unscaled * scale) {
                return Err(Error::invalid(
                    "excitation.scale",
                    scale,
                    &floor_minimum_rule(unscaled * scale),
                ));
            }
            if !within_floor_limit(peak) {
                // Blame the scale only when the record itself is within the limit.
                return Err(if within_floor_limit(peak / scale.abs().max(1e-300)) {
                    Error::invalid("excitation.scale", scale, &floor_limit_rule(peak))
                } else {
                    Error::invalid(
                        "excitation.path",
                        s.path.clone().unwrap_or_default(),
                        &format!(
                            "{}: the record's largest sample is at t = {t_peak} s",
                            floor_limit_rule(peak)
                        ),
                    )
                });
            }
            let length = record.end() + tail;
            return Ok((Box::new(record), Some(length)));
        }
        Kind::Free => Box::new(Free),
    };
    finish_analytic(floor, amplitude, s, None)
}

/// A floor motion and its natural length, s, if it has one.
type Motion = (Box<dyn FloorMotion>, Option<f64>);

/// The kind of a vertical motion given as a ratio of the horizontal one.
const RATIO: &str = "ratio";

/// The floor's vertical motion of `[excitation.vertical]` in the excitation section `s`, if it
/// has one, and its natural length. A motion that is zero throughout (a ratio or an amplitude of
/// 0, kind "free") is no vertical motion at all. The vertical
/// table takes the horizontal one's kinds and keys (its messages name them
/// `excitation.vertical.KEY`), or `ratio` alone: a_v(t) = ratio x a(t).
pub(super) fn vertical_from_section(
    s: &ExcitationSection,
    base_dir: &Path,
    records: &RecordCache,
) -> Result<Option<Motion>> {
    let Some(v) = s.vertical.as_deref() else {
        return Ok(None);
    };
    if v.vertical.is_some() {
        return Err(Error::invalid(
            "excitation.vertical.vertical",
            "(a table)",
            "the vertical motion has no vertical motion of its own",
        ));
    }
    if v.kind == RATIO || (v.kind.is_empty() && v.ratio.is_some()) {
        if let Some(key) = Key::ALL
            .into_iter()
            .find(|&k| k != Key::Ratio && k.given(v).is_some())
        {
            return Err(Error::invalid(
                &format!("excitation.vertical.{}", key.name()),
                key.given(v).map(Given::text).unwrap_or_default(),
                &format!("not a parameter of kind = \"{RATIO}\" (which takes ratio alone)"),
            ));
        }
        let Some(ratio) = v.ratio else {
            return Err(Error::invalid(
                "excitation.vertical.ratio",
                "(missing)",
                &format!("required for kind = \"{RATIO}\""),
            ));
        };
        if !ratio.is_finite() {
            return Err(Error::invalid(
                "excitation.vertical.ratio",
                ratio,
                "must be a finite number (a_v = ratio x a, upwards positive)",
            ));
        }
        if ratio == 0.0 {
            return Ok(None);
        }
        // The horizontal motion built again, to be scaled.
        let (horizontal, _) = floor_from_section(s, base_dir, records)?;
        let peak = ratio.abs() * horizontal.peak_acceleration();
        if !within_floor_limit(peak) {
            return Err(Error::invalid(
                "excitation.vertical.ratio",
                ratio,
                &floor_limit_rule(peak),
            ));
        }
        let scaled = crate::floor::Scaled {
            motion: horizontal,
            factor: ratio,
        };
        return Ok(Some((Box::new(scaled), None)));
    }
    let named = |e: Error| match e {
        Error::InvalidParameter { key, value, rule } => Error::InvalidParameter {
            key: key.replacen("excitation.", "excitation.vertical.", 1),
            value,
            rule,
        },
        other => other,
    };
    let (motion, length) = floor_from_section(v, base_dir, records).map_err(named)?;
    // A vertical motion that is zero throughout is none: the run is the horizontal one's.
    Ok((motion.peak_acceleration() > 0.0).then_some((motion, length)))
}

/// An analytic floor motion, checked against the floor limit, with its natural length.
fn finish_analytic(
    floor: Box<dyn FloorMotion>,
    amplitude: f64,
    s: &ExcitationSection,
    natural_duration: Option<f64>,
) -> Result<(Box<dyn FloorMotion>, Option<f64>)> {
    let peak = floor.peak_acceleration();
    if !within_floor_limit(peak) {
        // Within the limit the amplitude itself, beyond it the paper-sine's ramp (with the
        // period, which sets how far the ramp's cubic overshoots), is to blame.
        let (key, value) = if within_floor_limit(amplitude.abs()) {
            let ramp = crate::base::format::shortest(s.ramp.unwrap_or(0.0));
            let period = crate::base::format::shortest(s.period.unwrap_or(0.0));
            (
                "excitation.ramp",
                format!("{ramp} (with excitation.period = {period})"),
            )
        } else {
            (
                "excitation.amplitude",
                crate::base::format::shortest(amplitude),
            )
        };
        return Err(Error::invalid(key, value, &floor_limit_rule(peak)));
    }
    if !above_floor_minimum(peak) {
        return Err(Error::invalid(
            "excitation.amplitude",
            amplitude,
            &floor_minimum_rule(peak),
        ));
    }
    Ok((floor, natural_duration))
}

/// Free vibration after a pulse or a record, s: 0 or more.
fn check_tail(tail: f64) -> Result<f64> {
    if !(tail.is_finite() && tail >= 0.0) {
        return Err(Error::invalid("excitation.tail", tail, "must be 0 or more"));
    }
    Ok(tail)
}

pub use crate::base::units::STANDARD_GRAVITY;

/// The file an `excitation.path` names, read from the directory `base_dir` (the directory of the
/// model file as its path was given): joined and normalised by path arithmetic alone, `..`
/// undoing the directory before it, as [`super::Setting::rebased`] writes paths. A model reached
/// through a symbolic link reads its records from the link's directory, and `..` after a
/// linked directory leads where the path says, not into the link's target.
pub fn record_path(base_dir: &Path, relative: &str) -> PathBuf {
    super::setting::normalised(&base_dir.join(relative))
}

/// Reads and trims the record of a `kind = "record"` section; returns it with the tail length
/// and its peak before the scale, m/s^2.
fn recorded_motion(
    s: &ExcitationSection,
    base_dir: &Path,
    records: &RecordCache,
) -> Result<(RecordedMotion, f64, f64)> {
    let relative = s.path.clone().unwrap_or_default();
    let path = record_path(base_dir, &relative);
    let format = s
        .format
        .as_deref()
        .map(|name| RecordFormat::from_name("excitation.format", name))
        .transpose()?;
    if let Some(dt) = s.dt {
        positive("excitation.dt", dt)?;
    }
    // Messages name the file by the full path it was looked for at, so that they say which
    // directory a relative path was read from.
    let here = std::env::current_dir().unwrap_or_default();
    let name = super::setting::normalised(&here.join(&path))
        .display()
        .to_string();
    let record = records
        .read(&path, &name, format, s.dt)
        .map_err(|e| Error::Record {
            key: "excitation.path".to_string(),
            source: e,
        })?;
    // The file's declared unit, else the key's; both, disagreeing, are refused.
    let (units, unit_factor) =
        crate::floor::record::resolve_units(&record, "excitation.units", s.units.as_deref())?;
    let scale = s.scale.unwrap_or(1.0);
    if !scale.is_finite() {
        return Err(Error::invalid(
            "excitation.scale",
            scale,
            "must be a finite number",
        ));
    }
    let record_length = record.duration();
    let start = s.start.unwrap_or(0.0);
    let end = s.end.unwrap_or(record_length);
    if !(start.is_finite() && start >= 0.0 && start < record_length) {
        return Err(Error::invalid(
            "excitation.start",
            start,
            &format!("must lie in [0, {record_length}) s, the record's length"),
        ));
    }
    if !(end.is_finite() && end > start && end <= record_length * (1.0 + 1e-12)) {
        return Err(Error::invalid(
            "excitation.end",
            end,
            &format!("must lie in ({start}, {record_length}] s"),
        ));
    }
    let tail = check_tail(s.tail.unwrap_or(0.0))?;
    // Trimming keeps whole samples: the first at or after `start`, the last at or before `end`.
    let first = (start / record.dt - 1e-9).ceil().max(0.0) as usize;
    let last = ((end / record.dt + 1e-9).floor() as usize).min(record.values.len() - 1);
    if last <= first {
        return Err(Error::invalid(
            "excitation.end",
            end,
            "leaves fewer than two samples of the record",
        ));
    }
    let values = record.values[first..=last]
        .iter()
        .map(|v| v * unit_factor * scale)
        .collect();
    let unscaled = record.values[first..=last]
        .iter()
        .fold(0.0_f64, |peak, v| peak.max((v * unit_factor).abs()));
    Ok((
        RecordedMotion::new(
            format!(
                "{} (samples {}..={} of {}, {units} x {unit_factor} x scale {scale})",
                relative,
                first,
                last,
                record.values.len()
            ),
            record.dt,
            values,
        )
        .with_meta(record.meta.clone()),
        tail,
        unscaled,
    ))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_kind_requires_only_keys_it_takes_and_names_itself_once() {
        for kind in Kind::ALL {
            for key in kind.required() {
                assert!(kind.keys().contains(key), "{kind:?} requires {key:?}");
            }
            assert_eq!(
                Kind::ALL.iter().filter(|k| k.name() == kind.name()).count(),
                1
            );
        }
        let mut names: Vec<&str> = Key::ALL.iter().map(|k| k.name()).collect();
        names.sort();
        names.dedup();
        assert_eq!(names.len(), Key::ALL.len());
    }
}
