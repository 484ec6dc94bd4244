//! What a record file says about itself besides its samples ([`RecordMeta`]), and the units of
//! its values: read from the file's header where it states them, given by the user where it
//! does not, and refused where the two disagree ([`resolve_units`]).

use serde::Serialize;

/// A record's metadata: each field as the file gives it, None where it gives none.
#[derive(Debug, Clone, Default, PartialEq, Serialize)]
pub struct RecordMeta {
    /// The file's format: `peer-at2`, `csv`, `text`, `cosmos`, `esm` (or `arrays` for samples
    /// given in memory).
    pub format: &'static str,
    /// The unit of the values as the file declares it (`g`, `m/s2` or `cm/s2`); None where the
    /// file does not say.
    pub units: Option<&'static str>,
    /// Where the file declares its units, for messages (`line 3 "... IN UNITS OF G"`).
    #[serde(skip)]
    pub units_said: String,
    /// The earthquake's name.
    pub event: Option<String>,
    /// Its date: `YYYY-MM-DD` where the file gives the year in full, else as written.
    pub date: Option<String>,
    /// The recording station.
    pub station: Option<String>,
    /// The component (direction) of the record, e.g. `180`, `HNE`, `UP`.
    pub component: Option<String>,
    /// The earthquake's magnitude.
    pub magnitude: Option<f64>,
    /// The epicentral distance, km.
    pub distance_km: Option<f64>,
}

impl RecordMeta {
    /// Metadata of a file of `format` that says nothing but its samples.
    pub fn of_format(format: &'static str) -> Self {
        RecordMeta {
            format,
            ..RecordMeta::default()
        }
    }

    /// A short name for a legend or a table: event, station and component where the file
    /// gives them (`BORAH PEAK, PBF, EAST`), else `fallback` (the file's name).
    pub fn label(&self, fallback: &str) -> String {
        let parts: Vec<&str> = [&self.event, &self.station, &self.component]
            .into_iter()
            .filter_map(|p| p.as_deref())
            .filter(|p| !p.is_empty())
            .collect();
        if parts.is_empty() {
            fallback.to_string()
        } else {
            parts.join(", ")
        }
    }
}

/// What a time series holds, by the words of its header.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Quantity {
    /// Ground acceleration: what flexrock reads.
    Acceleration,
    /// Ground velocity.
    Velocity,
    /// Ground displacement.
    Displacement,
}

impl Quantity {
    /// The quantity's name in messages.
    pub fn name(self) -> &'static str {
        match self {
            Quantity::Acceleration => "acceleration",
            Quantity::Velocity => "velocity",
            Quantity::Displacement => "displacement",
        }
    }
}

/// The quantity a unit measures and its canonical name: `g`, `m/s2`, `cm/s2` for accelerations
/// (the only ones flexrock reads), `m/s`, `cm/s` for velocities, `m`, `cm`, `mm` for
/// displacements. The unit is read as people write it: any letter case, `SEC` for `S`, `/S/S`,
/// `^2`, `**2` or `2` for the square, `GAL` for cm/s2. None for a unit not in that list.
pub fn unit_of(word: &str) -> Option<(Quantity, &'static str)> {
    let mut w = word.trim().to_ascii_uppercase().replace(' ', "");
    for (from, to) in [
        ("SECONDS", "S"),
        ("SECOND", "S"),
        ("SEC", "S"),
        ("**2", "2"),
        ("^2", "2"),
    ] {
        w = w.replace(from, to);
    }
    let w = w.replace("/S/S", "/S2");
    Some(match w.as_str() {
        "G" => (Quantity::Acceleration, "g"),
        "M/S2" => (Quantity::Acceleration, "m/s2"),
        "CM/S2" | "GAL" | "GALS" => (Quantity::Acceleration, "cm/s2"),
        "M/S" => (Quantity::Velocity, "m/s"),
        "CM/S" => (Quantity::Velocity, "cm/s"),
        "M" => (Quantity::Displacement, "m"),
        "CM" => (Quantity::Displacement, "cm"),
        "MM" => (Quantity::Displacement, "mm"),
        _ => return None,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn units_are_read_as_people_write_them() {
        for (word, quantity, name) in [
            ("G", Quantity::Acceleration, "g"),
            ("g", Quantity::Acceleration, "g"),
            ("CM/SEC/SEC", Quantity::Acceleration, "cm/s2"),
            ("cm/s^2", Quantity::Acceleration, "cm/s2"),
            ("CM/S/S", Quantity::Acceleration, "cm/s2"),
            ("cm/sec2", Quantity::Acceleration, "cm/s2"),
            ("CM/SEC**2", Quantity::Acceleration, "cm/s2"),
            ("gal", Quantity::Acceleration, "cm/s2"),
            ("M/SEC/SEC", Quantity::Acceleration, "m/s2"),
            ("m/s^2", Quantity::Acceleration, "m/s2"),
            ("CM/S", Quantity::Velocity, "cm/s"),
            ("CM/SEC", Quantity::Velocity, "cm/s"),
            ("m/s", Quantity::Velocity, "m/s"),
            ("CM", Quantity::Displacement, "cm"),
        ] {
            assert_eq!(unit_of(word), Some((quantity, name)), "{word}");
        }
        for word in ["", "FURLONG", "IN/S/S", "counts", "mg"] {
            assert_eq!(unit_of(word), None, "{word}");
        }
    }

    #[test]
    fn a_label_names_the_event_station_and_component_else_the_file() {
        let mut meta = RecordMeta::of_format("peer-at2");
        assert_eq!(meta.label("a.AT2"), "a.AT2");
        meta.event = Some("BORAH PEAK".into());
        meta.component = Some("EAST".into());
        assert_eq!(meta.label("a.AT2"), "BORAH PEAK, EAST");
        meta.station = Some("PBF".into());
        assert_eq!(meta.label("a.AT2"), "BORAH PEAK, PBF, EAST");
    }
}
