//! The candidates for the largest and smallest q of a run, with their estimates: the extreme
//! so far and every other the run's arithmetic cannot tell apart from it.

use super::rounding;

/// A candidate for the largest or smallest q: its time and value, with their estimates.
#[derive(Debug, Clone, Copy)]
pub(super) struct Candidate {
    pub(super) t: f64,
    pub(super) q: f64,
    pub(super) error: f64,
    pub(super) t_error: f64,
}

/// Share of |q| below the extreme so far within which a candidate's errors are estimated to
/// see whether it is told apart from the extreme: far beyond any estimate.
pub(super) const CLOSE_SHARE: f64 = 1e-6;

/// The candidates for one extreme of q (`sign` 1 the largest, -1 the smallest) that the run
/// cannot tell apart: the extreme so far (the first of equal values, as the recorder keeps it),
/// and every other whose value is within the two estimates of it. Which of two such humps is
/// the extreme is not decided by the run's arithmetic, and the time of the extreme may be
/// either's.
#[derive(Debug)]
pub(super) struct Top {
    pub(super) sign: f64,
    pub(super) best: Candidate,
    pub(super) close: Vec<Candidate>,
}

impl Top {
    /// The initial state as the extreme so far: its q is the file's number rounded to a double
    /// (half an ulp), and its time t = 0, which a root of q' found in other arithmetic puts
    /// within rounding of it: an ulp of the run's duration.
    pub(super) fn initial(sign: f64, q0: f64, duration: f64) -> Self {
        let best = Candidate {
            t: 0.0,
            q: q0,
            error: 0.5 * rounding::ulp(q0),
            t_error: rounding::ulp(duration),
        };
        Top {
            sign,
            best,
            close: Vec::new(),
        }
    }

    /// Whether `q` is beyond the extreme so far or near enough to it to be a candidate.
    pub(super) fn reaches(&self, q: f64) -> bool {
        let b = &self.best;
        self.sign * (q - b.q) > -(b.error + CLOSE_SHARE * b.q.abs())
    }

    /// Takes `c`: as the extreme where it is beyond the one so far, as a close one where the
    /// estimates do not tell the two apart.
    pub(super) fn offer(&mut self, c: Candidate) {
        let (s, b) = (self.sign, self.best);
        if s * (c.q - b.q) > 0.0 {
            self.close.push(b);
            self.close
                .retain(|o| s * (o.q - c.q) + o.error + c.error >= 0.0);
            self.best = c;
        } else if s * (c.q - b.q) + c.error + b.error >= 0.0 {
            self.close.push(c);
        }
    }

    /// The estimates of the extreme's value and time (m, s): its own, or those of any candidate
    /// it cannot be told from, with the time between the two.
    pub(super) fn errors(&self) -> (f64, f64) {
        let b = &self.best;
        self.close.iter().fold((b.error, b.t_error), |(e, te), o| {
            (e.max(o.error), te.max((o.t - b.t).abs() + o.t_error))
        })
    }
}
