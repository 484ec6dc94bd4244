//! The units of a record's values: the names accepted, their factors to m/s^2, and the unit in
//! effect where the file declares one, a key or flag gives one, or both.

use super::accelerogram::Record;
use crate::base::invalid::InvalidParameter;

/// Names of the units of acceleration a record may be in (the values of `excitation.units` and
/// `--units`), for messages.
pub const UNIT_NAMES: &str = "\"g\", \"m/s2\" or \"cm/s2\"";

/// The canonical name of the unit `units` named by the key or flag `key`, and its factor to
/// m/s^2 (g is standard gravity, whatever a body's `gravity`).
pub fn acceleration_unit(
    key: &str,
    units: &str,
) -> Result<(&'static str, f64), crate::base::invalid::InvalidParameter> {
    match units {
        "g" => Ok(("g", crate::base::units::STANDARD_GRAVITY)),
        "m/s2" => Ok(("m/s2", 1.0)),
        "cm/s2" => Ok(("cm/s2", 0.01)),
        other => Err(crate::base::invalid::InvalidParameter::new(
            key,
            format!("\"{other}\""),
            &format!("must be {UNIT_NAMES}"),
        )),
    }
}

/// The unit of a record's values and its factor to m/s^2 (g is standard gravity): the unit its
/// file declares, or the one `given` by the key or flag `key` where the file declares none.
/// Refused when both are there and disagree (nothing is rescaled silently), and when neither
/// is (nothing is assumed).
pub fn resolve_units(
    record: &Record,
    key: &str,
    given: Option<&str>,
) -> Result<(&'static str, f64), InvalidParameter> {
    let given = given.map(|u| acceleration_unit(key, u)).transpose()?;
    match (record.meta.units, given) {
        (Some(declared), Some((name, _))) if declared != name => Err(InvalidParameter::new(
            key,
            format!("\"{name}\""),
            &format!(
                "contradicts the record file {}, whose header says its values are in {declared} \
                 ({}); leave {key} out, or give the file's unit",
                record.source, record.meta.units_said
            ),
        )),
        (Some(declared), _) => acceleration_unit(key, declared),
        (None, Some(unit)) => Ok(unit),
        (None, None) => Err(InvalidParameter::new(
            key,
            "(missing)",
            &format!(
                "required: the record file {} does not say the unit of its values ({} file); \
                 give it as {}",
                record.source,
                record.meta.format,
                super::UNIT_NAMES
            ),
        )),
    }
}
