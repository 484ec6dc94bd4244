//! The columns of a run's tables (history.csv, events.csv, episodes.csv) and the fields of an
//! episode: the names are a contract (the book's output reference), kept here so that every
//! writer and reader (the command line's files, the Python bindings) shares them.

use crate::base::format::{number, MAX_NUMBER_CHARS};
use crate::integrate::solution::Episode;

/// Column names of history.csv (a contract).
/// Columns are only ever appended: existing ones keep their names and places.
pub const HISTORY_COLUMNS: [&str; 11] = [
    "t",
    "q",
    "qdot",
    "s",
    "r",
    "mode",
    "floor_acc",
    "F",
    "energy_residual",
    "work_input",
    "work_damping",
];

/// The most bytes of one row of history.csv: ten numbers of at most [`MAX_NUMBER_CHARS`], the
/// longest name of a mode, ten commas and the newline (391).
pub const MAX_HISTORY_ROW_BYTES: usize = 10 * MAX_NUMBER_CHARS + MODE_NAME_CHARS + 10 + 1;

/// The longest name of a mode ("pre-uplift", "rock-right", "overturned").
const MODE_NAME_CHARS: usize = 10;

/// Column names of events.csv (a contract).
pub const EVENT_COLUMNS: [&str; 8] = [
    "index",
    "t",
    "kind",
    "from",
    "to",
    "q",
    "qdot_before",
    "qdot_after",
];

/// Columns of episodes.csv, one row per rocking episode (units in the README's table).
pub const EPISODE_COLUMNS: [&str; 19] = [
    "index",
    "side",
    "t_start",
    "t_end",
    "duration",
    "ended_by",
    "floor_acc_at_uplift",
    "peak_abs_q",
    "t_peak",
    "peak_abs_r",
    "peak_rotation",
    "qdot_before_uplift",
    "qdot_after_uplift",
    "qdot_before_landing",
    "qdot_after_landing",
    "kinetic_energy_before_uplift",
    "kinetic_energy_after_uplift",
    "kinetic_energy_before_landing",
    "kinetic_energy_after_landing",
];

/// One field of a row of episodes.csv.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum EpisodeField {
    /// A count (the index).
    Count(usize),
    /// A word (side, how it ended).
    Word(&'static str),
    /// A number; None where the value does not exist (an empty CSV field).
    Number(Option<f64>),
}

impl EpisodeField {
    /// The field as episodes.csv writes it.
    pub fn text(self) -> String {
        match self {
            EpisodeField::Count(n) => n.to_string(),
            EpisodeField::Word(w) => w.to_string(),
            EpisodeField::Number(x) => x.map(number).unwrap_or_default(),
        }
    }
}

/// The fields of an episode, in the order of [`EPISODE_COLUMNS`]. `height` (H, m) turns the
/// peak rocking part into the body's rotation, r/H rad. A value that does not exist (no end
/// within the run, no landing, no uplift for a run that starts rocking) is None, as is every
/// value derived from it.
pub fn episode_fields(e: &Episode, height: f64) -> [EpisodeField; 19] {
    use EpisodeField::{Count, Number, Word};
    let side = match e.mode {
        crate::physics::automaton::Mode::RockLeft => "left",
        _ => "right",
    };
    [
        Count(e.index),
        Word(side),
        Number(Some(e.t_start)),
        Number(e.t_end),
        Number(e.duration()),
        Word(e.ended_by.map_or("run-end", |k| k.name())),
        Number(e.floor_acc_at_uplift),
        Number(Some(e.peak_abs_q)),
        Number(Some(e.t_peak)),
        Number(Some(e.peak_abs_r)),
        Number(Some(e.peak_abs_r / height)),
        Number(e.qdot_uplift.map(|(before, _)| before)),
        Number(e.qdot_uplift.map(|(_, after)| after)),
        Number(e.qdot_landing.map(|(before, _)| before)),
        Number(e.qdot_landing.map(|(_, after)| after)),
        Number(e.kinetic_energy_uplift.map(|(before, _)| before)),
        Number(e.kinetic_energy_uplift.map(|(_, after)| after)),
        Number(e.kinetic_energy_landing.map(|(before, _)| before)),
        Number(e.kinetic_energy_landing.map(|(_, after)| after)),
    ]
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::physics::automaton::Mode;

    #[test]
    fn a_history_row_is_bounded() {
        let modes = [
            Mode::PreUplift,
            Mode::RockRight,
            Mode::RockLeft,
            Mode::Overturned,
        ];
        assert_eq!(
            modes.iter().map(|m| m.name().len()).max(),
            Some(MODE_NAME_CHARS)
        );
        assert_eq!(HISTORY_COLUMNS.len(), 11);
        assert_eq!(MAX_HISTORY_ROW_BYTES, 391);
    }
}
