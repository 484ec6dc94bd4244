//! The tables of a run: history.csv, events.csv and episodes.csv.

use flexrock_core::integrate::solution::{Episode, Event, Sample};

use super::{
    episode_fields, number, push_number, EpisodeField, Table, EPISODE_COLUMNS, EVENT_COLUMNS,
    HISTORY_COLUMNS,
};

/// history.csv: one row per sample, columns [`HISTORY_COLUMNS`].
///
/// Its fields are numbers in the form of [`number`] and the mode's name, none of which a CSV
/// field ever quotes (a test compares the text with the `csv` crate's), so the rows are written
/// as text directly: the table was most of the time `flexrock run` took. Blocks of rows are
/// formatted on the thread pool and joined in order, the same bytes on any number of threads.
pub fn history_csv(samples: &[Sample]) -> Vec<u8> {
    use rayon::prelude::*;
    /// Rows formatted by one task: large enough that a task outweighs its scheduling.
    const BLOCK: usize = 256;
    let mut text = HISTORY_COLUMNS.join(",");
    text.push('\n');
    let blocks: Vec<String> = samples.par_chunks(BLOCK).map(history_rows).collect();
    text.reserve(blocks.iter().map(String::len).sum());
    for block in &blocks {
        text.push_str(block);
    }
    text.into_bytes()
}

/// The rows of history.csv for `samples`, each ended by a newline.
fn history_rows(samples: &[Sample]) -> String {
    // About 200 bytes a row on a record's run.
    let mut text = String::with_capacity(samples.len() * 200);
    for s in samples {
        for (i, value) in [s.t, s.q, s.qdot, s.s, s.r].into_iter().enumerate() {
            if i > 0 {
                text.push(',');
            }
            push_number(&mut text, value);
        }
        text.push(',');
        text.push_str(s.mode.name());
        for value in [
            s.floor_acc,
            s.restoring_force,
            s.energy_residual,
            s.work_input,
            s.work_damping,
        ] {
            text.push(',');
            push_number(&mut text, value);
        }
        text.push('\n');
    }
    text
}

/// events.csv: one row per event, columns [`EVENT_COLUMNS`].
pub fn events_csv(events: &[Event]) -> Vec<u8> {
    let mut table = Table::new(&EVENT_COLUMNS);
    for e in events {
        table.row([
            e.index.to_string(),
            number(e.t),
            e.kind.name().to_string(),
            e.from.name().to_string(),
            e.to.name().to_string(),
            number(e.q),
            number(e.qdot_before),
            number(e.qdot_after),
        ]);
    }
    table.into_bytes()
}

/// episodes.csv: one row per rocking episode, columns [`EPISODE_COLUMNS`], fields
/// [`episode_fields`].
pub fn episodes_csv(episodes: &[Episode], height: f64) -> Vec<u8> {
    let mut table = Table::new(&EPISODE_COLUMNS);
    for e in episodes {
        table.row(episode_fields(e, height).map(EpisodeField::text));
    }
    table.into_bytes()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// history.csv written as text is the text the `csv` crate writes for the same fields:
    /// numbers of every form (tiny, huge, negative zero, not finite, halfway cases) in every
    /// mode, over more rows than one block so that blocks are joined.
    #[test]
    fn history_text_is_the_csv_crates() {
        use flexrock_core::physics::automaton::Mode;
        let values = [
            0.0,
            -0.0,
            0.005,
            1.0,
            -2.5,
            1e-7,
            -1.9219177573200075e-18,
            123456789012345680.0,
            1e300,
            -5e-324,
            0.3,
            f64::NAN,
            f64::INFINITY,
            f64::NEG_INFINITY,
            9007199254740993.0,
            0.1 + 0.2,
        ];
        let modes = [
            Mode::PreUplift,
            Mode::RockRight,
            Mode::RockLeft,
            Mode::Overturned,
        ];
        let pick = |i: usize, k: usize| values[(i * 7 + k * 3) % values.len()];
        let samples: Vec<Sample> = (0..1000)
            .map(|i| Sample {
                t: pick(i, 0),
                q: pick(i, 1),
                qdot: pick(i, 2),
                s: pick(i, 3),
                r: pick(i, 4),
                mode: modes[i % modes.len()],
                floor_acc: pick(i, 5),
                restoring_force: pick(i, 6),
                energy_residual: pick(i, 7),
                work_input: pick(i, 8),
                work_damping: pick(i, 9),
            })
            .collect();
        let mut expected = csv::Writer::from_writer(Vec::new());
        expected.write_record(HISTORY_COLUMNS).unwrap();
        for s in &samples {
            let mut fields: Vec<String> = [s.t, s.q, s.qdot, s.s, s.r]
                .into_iter()
                .map(number)
                .collect();
            fields.push(s.mode.name().to_string());
            fields.extend(
                [
                    s.floor_acc,
                    s.restoring_force,
                    s.energy_residual,
                    s.work_input,
                    s.work_damping,
                ]
                .into_iter()
                .map(number),
            );
            expected.write_record(&fields).unwrap();
        }
        let expected = expected.into_inner().unwrap();
        let written = history_csv(&samples);
        assert_eq!(
            String::from_utf8(written).unwrap(),
            String::from_utf8(expected).unwrap()
        );
        assert_eq!(
            history_csv(&[]),
            b"t,q,qdot,s,r,mode,floor_acc,F,energy_residual,work_input,work_damping\n"
        );
    }
}
