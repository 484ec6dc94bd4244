//! Shards: which slice of a sweep's chunks one process computes, from `--shard K/N` or a Slurm
//! job array's variables, and the points of that slice.

use std::path::{Path, PathBuf};

use serde::{Deserialize, Serialize};

use crate::error::{Error, Result};
use flexrock_core::analysis::sweep::Plan;

/// Which slice of the chunks a process computes: shard `index` of `count` (1-based, as a user
/// writes `--shard 3/8`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
pub struct Shard {
    /// K, 1-based.
    pub index: usize,
    /// N.
    pub count: usize,
}

/// The rule of `--shard`, as messages state it.
const SHARD_RULE: &str = "must be K/N with 1 <= K <= N, e.g. 3/8";

impl Shard {
    /// Parses `K/N`, 1 <= K <= N.
    pub fn parse(text: &str) -> Result<Shard> {
        let (k, n) = text
            .split_once('/')
            .ok_or_else(|| Error::invalid("--shard", text, SHARD_RULE))?;
        let parse = |s: &str| s.trim().parse::<usize>().ok();
        match (parse(k), parse(n)) {
            (Some(index), Some(count)) if index >= 1 && index <= count => {
                Ok(Shard { index, count })
            }
            _ => Err(Error::invalid("--shard", text, SHARD_RULE)),
        }
    }

    /// The shard of a Slurm job array task, from `SLURM_ARRAY_TASK_ID`, `SLURM_ARRAY_TASK_MIN`
    /// (default 0) and `SLURM_ARRAY_TASK_COUNT`: task ids min..min+count-1 are shards 1..count.
    /// None outside a job array (neither id nor count set). One of the two without the other is
    /// refused: run unsharded, every task of the array would compute the whole sweep into one
    /// directory.
    pub fn from_slurm(var: impl Fn(&str) -> Option<String>) -> Result<Option<Shard>> {
        let (id, count) = match (var("SLURM_ARRAY_TASK_ID"), var("SLURM_ARRAY_TASK_COUNT")) {
            (None, None) => return Ok(None),
            (Some(id), Some(count)) => (id, count),
            (Some(id), None) => {
                return Err(Error::invalid(
                    "SLURM_ARRAY_TASK_COUNT",
                    "(unset)",
                    &format!(
                        "must be set with SLURM_ARRAY_TASK_ID (= {id}), as Slurm sets both in a \
                         job array task; otherwise give --shard K/N"
                    ),
                ))
            }
            (None, Some(count)) => {
                return Err(Error::invalid(
                    "SLURM_ARRAY_TASK_ID",
                    "(unset)",
                    &format!(
                        "must be set with SLURM_ARRAY_TASK_COUNT (= {count}), as Slurm sets \
                         both in a job array task; otherwise give --shard K/N"
                    ),
                ))
            }
        };
        let min = var("SLURM_ARRAY_TASK_MIN").unwrap_or_else(|| "0".to_string());
        let number = |name: &str, value: &str| {
            value
                .trim()
                .parse::<usize>()
                .map_err(|_| Error::invalid(name, value, "must be a whole number (set by Slurm)"))
        };
        let (id, count, min) = (
            number("SLURM_ARRAY_TASK_ID", &id)?,
            number("SLURM_ARRAY_TASK_COUNT", &count)?,
            number("SLURM_ARRAY_TASK_MIN", &min)?,
        );
        if count == 0 {
            return Err(Error::invalid(
                "SLURM_ARRAY_TASK_COUNT",
                count,
                "must be at least 1",
            ));
        }
        if id < min || id - min >= count {
            // In u128, so that ids near the top of usize do not overflow the message.
            let end = min as u128 + count as u128;
            return Err(Error::invalid(
                "SLURM_ARRAY_TASK_ID",
                id,
                &format!(
                    "must lie in {min}..{end} (SLURM_ARRAY_TASK_MIN .. + SLURM_ARRAY_TASK_COUNT); \
                     use a contiguous array such as --array=0-{}",
                    count - 1
                ),
            ));
        }
        Ok(Some(Shard {
            index: id - min + 1,
            count,
        }))
    }

    /// The directory of this shard inside the sweep's output directory.
    pub fn dir(&self, out: &Path) -> PathBuf {
        out.join(self.dir_name())
    }

    /// `shard-K-of-N`.
    pub fn dir_name(&self) -> String {
        format!("shard-{}-of-{}", self.index, self.count)
    }
}

/// The points of a directory's rows: [first, end) of total.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
pub struct PointRange {
    /// First point.
    pub first: usize,
    /// One past the last point.
    pub end: usize,
    /// Points of the whole sweep.
    pub total: usize,
}

impl PointRange {
    /// Number of points.
    pub fn len(&self) -> usize {
        self.end - self.first
    }

    /// True when the range holds no point (a shard of more shards than chunks).
    pub fn is_empty(&self) -> bool {
        self.end == self.first
    }
}

/// The points of shard `shard` (all of them without one): whole chunks, split as evenly as
/// chunks allow. The products are taken in u128: K x chunks cannot overflow whatever K and N.
pub fn point_range(plan: &Plan, shard: Option<Shard>) -> PointRange {
    let total = plan.points();
    let chunks = total.div_ceil(plan.chunk_size) as u128;
    let (first_chunk, end_chunk) = match shard {
        None => (0, chunks),
        Some(s) => {
            let (k, n) = (s.index as u128, s.count as u128);
            ((k - 1) * chunks / n, k * chunks / n)
        }
    };
    let point = |chunk: u128| (chunk * plan.chunk_size as u128).min(total as u128) as usize;
    PointRange {
        first: point(first_chunk),
        end: point(end_chunk),
        total,
    }
}

/// The points of chunk `chunk`, cut at `end`.
pub(super) fn chunk_points(plan: &Plan, chunk: usize, end: usize) -> std::ops::Range<usize> {
    let first = chunk.saturating_mul(plan.chunk_size).min(end);
    first..first.saturating_add(plan.chunk_size).min(end)
}

#[cfg(test)]
mod tests {
    use super::*;
    use flexrock_core::analysis::sweep::Axis;

    fn plan(points: usize, chunk_size: usize) -> Plan {
        Plan {
            flexrock_version: String::new(),
            model_file: String::new(),
            model_text: String::new(),
            settings: Vec::new(),
            axes: vec![Axis::new(
                "excitation.amplitude",
                (0..points).map(|i| i.to_string()).collect(),
            )],
            find_min: None,
            chunk_size,
            records: Vec::new(),
            row_columns: None,
        }
    }

    #[test]
    fn shards_cover_every_point_once_in_whole_chunks() {
        for (points, chunk, count) in [(100, 7, 3), (10, 3, 5), (5, 10, 3), (1000, 1, 7)] {
            let plan = plan(points, chunk);
            let mut next = 0;
            for index in 1..=count {
                let r = point_range(&plan, Some(Shard { index, count }));
                assert_eq!(r.first, next, "{points} {chunk} {count}");
                assert!(r.first.is_multiple_of(chunk) || r.first == points);
                next = r.end;
            }
            assert_eq!(next, points);
            let all = point_range(&plan, None);
            assert_eq!((all.first, all.end, all.total), (0, points, points));
        }
    }

    /// K x chunks overflowed usize for K near 2^63 and 2^64 - 1 (a panic in debug builds, a
    /// wrong slice in release ones). The last shard of any N must end at the last point.
    #[test]
    fn huge_shard_numbers_do_not_overflow() {
        let plan = plan(100, 7);
        for count in [1usize << 63, usize::MAX, usize::MAX - 1] {
            let last = point_range(
                &plan,
                Some(Shard {
                    index: count,
                    count,
                }),
            );
            assert_eq!(last.end, 100, "{count}");
            let first = point_range(&plan, Some(Shard { index: 1, count }));
            assert_eq!(first.first, 0);
            assert!(first.is_empty(), "{count}: {first:?}");
            let middle = point_range(
                &plan,
                Some(Shard {
                    index: count / 2,
                    count,
                }),
            );
            assert!(middle.end <= 100 && middle.first <= middle.end);
        }
        assert!(Shard::parse(&format!("{0}/{0}", usize::MAX)).is_ok());
        assert!(Shard::parse("18446744073709551616/18446744073709551616").is_err());
    }

    fn env(vars: &'static [(&'static str, &'static str)]) -> impl Fn(&str) -> Option<String> {
        move |name: &str| {
            vars.iter()
                .find(|(k, _)| *k == name)
                .map(|(_, v)| v.to_string())
        }
    }

    #[test]
    fn shard_flags_and_slurm_variables() {
        assert_eq!(Shard::parse("2/5").unwrap(), Shard { index: 2, count: 5 });
        for bad in ["0/3", "4/3", "1", "a/b", "1/0", "-1/3"] {
            assert!(Shard::parse(bad).is_err(), "{bad}");
        }
        assert_eq!(Shard::from_slurm(env(&[])).unwrap(), None);
        const ARRAY: [(&str, &str); 2] = [
            ("SLURM_ARRAY_TASK_ID", "7"),
            ("SLURM_ARRAY_TASK_COUNT", "3"),
        ];
        // Without SLURM_ARRAY_TASK_MIN the ids start at 0: 7 is out of range.
        assert!(Shard::from_slurm(env(&ARRAY)).is_err());
        const WITH_MIN: [(&str, &str); 3] = [
            ("SLURM_ARRAY_TASK_ID", "7"),
            ("SLURM_ARRAY_TASK_COUNT", "3"),
            ("SLURM_ARRAY_TASK_MIN", "5"),
        ];
        assert_eq!(
            Shard::from_slurm(env(&WITH_MIN)).unwrap(),
            Some(Shard { index: 3, count: 3 })
        );
        const BAD: [(&str, &str); 2] = [
            ("SLURM_ARRAY_TASK_ID", "x"),
            ("SLURM_ARRAY_TASK_COUNT", "3"),
        ];
        assert!(Shard::from_slurm(env(&BAD)).is_err());
    }

    /// A task id without a count ran the whole sweep unsharded in every task, all in one
    /// directory; it is refused, naming the variable that is missing.
    #[test]
    fn half_a_slurm_array_is_refused() {
        const ID_ONLY: [(&str, &str); 1] = [("SLURM_ARRAY_TASK_ID", "2")];
        let e = Shard::from_slurm(env(&ID_ONLY)).unwrap_err().to_string();
        assert!(e.contains("SLURM_ARRAY_TASK_COUNT"), "{e}");
        const COUNT_ONLY: [(&str, &str); 1] = [("SLURM_ARRAY_TASK_COUNT", "4")];
        let e = Shard::from_slurm(env(&COUNT_ONLY)).unwrap_err().to_string();
        assert!(e.contains("SLURM_ARRAY_TASK_ID"), "{e}");
        const ZERO: [(&str, &str); 2] = [
            ("SLURM_ARRAY_TASK_ID", "0"),
            ("SLURM_ARRAY_TASK_COUNT", "0"),
        ];
        assert!(Shard::from_slurm(env(&ZERO)).is_err());
        const TOP: [(&str, &str); 3] = [
            ("SLURM_ARRAY_TASK_ID", "1"),
            ("SLURM_ARRAY_TASK_COUNT", "18446744073709551615"),
            ("SLURM_ARRAY_TASK_MIN", "18446744073709551615"),
        ];
        let e = Shard::from_slurm(env(&TOP)).unwrap_err().to_string();
        assert!(e.contains("36893488147419103230"), "{e}");
    }
}
