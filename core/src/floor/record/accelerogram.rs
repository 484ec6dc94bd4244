//! An accelerogram as read: its samples at a uniform interval and what its file says of itself.

use super::meta::RecordMeta;

/// An accelerogram sampled at a uniform interval.
#[derive(Debug, Clone, PartialEq)]
pub struct Record {
    /// The file name as given, for messages.
    pub source: String,
    /// The header lines before the NPTS line (event/station lines); for CSV the row of column
    /// names, if the file has one.
    pub title: Vec<String>,
    /// Sampling interval, s.
    pub dt: f64,
    /// The values as in the file (units of the file, e.g. g).
    pub values: Vec<f64>,
    /// What the file says about itself: its units, event, station, component...
    pub meta: RecordMeta,
}

impl Record {
    /// Time of the last value, `(n - 1) * dt`, s (0 for fewer than two values).
    pub fn duration(&self) -> f64 {
        self.values.len().saturating_sub(1) as f64 * self.dt
    }

    /// The value of largest magnitude (with its sign) and its time, s. The first one wins a tie;
    /// `(0.0, 0.0)` for a record without values.
    pub fn peak(&self) -> (f64, f64) {
        let mut peak_index = 0;
        let mut peak_value = 0.0_f64;
        for (index, &value) in self.values.iter().enumerate() {
            if value.abs() > peak_value.abs() {
                peak_index = index;
                peak_value = value;
            }
        }
        (peak_value, peak_index as f64 * self.dt)
    }
}
