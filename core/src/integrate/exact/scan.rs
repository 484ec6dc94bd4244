//! Events that cannot be missed: the search of one flow for its first guard crossing and for
//! the extrema of q that matter.
//!
//! Between two consecutive extrema q is monotone, so it crosses a guard there at most once, and
//! only if its values at the two ends lie on either side. The search cuts the flow into such
//! monotone pieces with certified tests, from bounds M2 >= |q''| and M3 >= |q'''| over an
//! interval of length h ([`Flow::derivative_bounds`]):
//!
//! * q' keeps its sign on the interval when q' has the same sign at both ends and
//!   |q'(t0)| + |q'(t1)| > M2 h (a root between would need q' to come down from both ends);
//! * q' has at most one root when q'' keeps its sign by the same test with M3; the root is then
//!   found by safeguarded Newton steps, and it is an extremum of q;
//! * otherwise the interval is halved.
//!
//! An interval on which q cannot reach any guard, nor a value beyond the extremes already
//! recorded, is dropped at once: from the ends, q stays within q(t0) + max(q'(t0), 0) h +
//! M2 h^2/2 (and the like from t1), and an oscillator at rest before uplift within its
//! envelope. So only the extrema near a guard or a new peak are located, and a grazing uplift
//! whose excursion beyond s_n is shorter than any step is still found: its extremum is.

use crate::physics::automaton::Guard;

use super::flow::{Flow, Point};
use super::rounding::ulp;

/// A smooth function of time searched for crossings: q along one flow, or the gap between two
/// columns of a row along theirs. Its [`Point`]s hold the value and three derivatives.
pub(crate) trait Smooth {
    /// The value and its first three derivatives at `t`.
    fn point(&self, t: f64) -> Point;
    /// Bounds on the second, third and fourth derivatives over `[p.t, p.t + h]`.
    fn derivative_bounds(&self, p: &Point, h: f64) -> (f64, f64, f64);
    /// A bound on the distance from [`Smooth::equilibrium`] over the rest of the function from
    /// `t0` on, where one is known.
    fn envelope(&self, _t0: f64) -> Option<f64> {
        None
    }
    /// The centre of [`Smooth::envelope`].
    fn equilibrium(&self) -> f64 {
        0.0
    }
}

impl Smooth for Flow {
    fn point(&self, t: f64) -> Point {
        Flow::point(self, t)
    }
    fn derivative_bounds(&self, p: &Point, h: f64) -> (f64, f64, f64) {
        Flow::derivative_bounds(self, p, h)
    }
    fn envelope(&self, t0: f64) -> Option<f64> {
        Flow::envelope(self, t0)
    }
    fn equilibrium(&self) -> f64 {
        Flow::equilibrium(self)
    }
}

/// Halvings of one interval before it is taken as monotone: far beyond what any extremum of a
/// closed form needs (a simple root of q' is isolated after a few), reached only at a double
/// root of q' (an inflection with zero slope).
const MAX_DEPTH: usize = 60;
/// Evaluations of the closed form allowed in one flow: a run that needs more is not well posed.
pub(crate) const MAX_EVALUATIONS: usize = 1_000_000;

/// The levels of q that matter in a flow: the guards, and the extremes recorded so far.
#[derive(Debug, Clone)]
pub(crate) struct Watch {
    /// Lowest guard crossed rising, highest crossed falling.
    pub guard_up: f64,
    pub guard_down: f64,
    /// The largest and smallest q that matter for the peaks.
    pub max: f64,
    pub min: f64,
    /// Extrema of q found, in time order.
    pub extrema: Vec<Point>,
    /// The intervals still to search (a buffer kept from flow to flow).
    pub stack: Vec<Interval>,
    /// Evaluations of the closed form.
    pub evaluations: usize,
    /// Intervals taken as monotone after [`MAX_DEPTH`] halvings.
    pub unresolved: usize,
}

impl Watch {
    fn up(&self) -> f64 {
        self.guard_up.min(self.max)
    }
    fn down(&self) -> f64 {
        self.guard_down.max(self.min)
    }
    fn offer(&mut self, p: Point) {
        self.max = self.max.max(p.q);
        self.min = self.min.min(p.q);
        self.extrema.push(p);
    }
}

/// An interval of a flow still to search: its ends and the halvings that made it.
pub(crate) type Interval = (Point, Point, usize);

/// Why a scan stopped early.
#[derive(Debug)]
pub(crate) enum ScanError {
    /// The closed form is not finite at t.
    NotFinite(f64),
    /// More than [`MAX_EVALUATIONS`].
    TooMuchWork(f64),
}

/// The first guard of `guards` that q crosses in its direction on the flow over `[a.t, b.t]`,
/// with the state there; extrema are booked in `watch`.
pub(crate) fn first_crossing<F: Smooth>(
    flow: &F,
    a: Point,
    b: Point,
    guards: &[Guard],
    watch: &mut Watch,
) -> Result<Option<(Point, Guard)>, ScanError> {
    let mut stack = std::mem::take(&mut watch.stack);
    stack.clear();
    stack.push((a, b, 0usize));
    let found = search(flow, &mut stack, guards, watch);
    watch.stack = stack;
    found
}

/// The search of [`first_crossing`] over the intervals in `stack`.
fn search<F: Smooth>(
    flow: &F,
    stack: &mut Vec<Interval>,
    guards: &[Guard],
    watch: &mut Watch,
) -> Result<Option<(Point, Guard)>, ScanError> {
    while let Some((a, b, depth)) = stack.pop() {
        let h = b.t - a.t;
        if h <= 0.0 {
            continue;
        }
        let (m2, m3, m4) = flow.derivative_bounds(&a, h);
        let mut upper = (a.q + a.v.max(0.0) * h).min(b.q + (-b.v).max(0.0) * h) + 0.5 * m2 * h * h;
        let mut lower = (a.q + a.v.min(0.0) * h).max(b.q + (-b.v).min(0.0) * h) - 0.5 * m2 * h * h;
        if let Some(envelope) = flow.envelope(a.t) {
            upper = upper.min(flow.equilibrium() + envelope);
            lower = lower.max(flow.equilibrium() - envelope);
        }
        // Reaching a level is not passing it: a guard is crossed only beyond it, and a value equal
        // to the extreme recorded is no new peak (a body at rest stays at rest).
        if upper <= watch.up() && lower >= watch.down() {
            continue;
        }
        let monotone = a.v * b.v > 0.0 && a.v.abs() + b.v.abs() > m2 * h;
        // q'' keeps its sign when it has one sign at both ends with room to spare (M3), or when
        // q''' keeps its sign (M4), so that q'' is monotone, and q'' does not change sign between
        // the ends (one of them may be zero: the start from rest of a floor that starts at zero).
        let jerk_one_signed = a.jerk * b.jerk > 0.0 && a.jerk.abs() + b.jerk.abs() > m4 * h;
        let single_root = (a.acc * b.acc > 0.0 && a.acc.abs() + b.acc.abs() > m3 * h)
            || (jerk_one_signed && a.acc * b.acc >= 0.0 && (a.acc != 0.0 || b.acc != 0.0));
        // The monotone pieces of [a, b], and the extremum between them.
        let (pieces, peak) = if monotone {
            ([Some((a, b)), None], None)
        } else if single_root {
            if a.v * b.v < 0.0 {
                let peak = extremum(flow, a, b, watch)?;
                ([Some((a, peak)), Some((peak, b))], Some(peak))
            } else {
                ([Some((a, b)), None], None)
            }
        } else if depth >= MAX_DEPTH || h <= 4.0 * ulp(b.t) {
            watch.unresolved += 1;
            ([Some((a, b)), None], None)
        } else {
            let middle = evaluate(flow, a.t + 0.5 * h, watch)?;
            stack.push((middle, b, depth + 1));
            stack.push((a, middle, depth + 1));
            continue;
        };
        for (index, (a, b)) in pieces.into_iter().flatten().enumerate() {
            if index == 1 {
                // No crossing before the extremum: it is part of the motion.
                if let Some(peak) = peak {
                    watch.offer(peak);
                }
            }
            for guard in guards {
                if guard.overshoot(a.q) <= 0.0 && guard.overshoot(b.q) > 0.0 {
                    let at = crossing(flow, a, b, guard, watch)?;
                    return Ok(Some((at, *guard)));
                }
            }
        }
    }
    Ok(None)
}

/// The flow's point at t, counted and checked.
pub(crate) fn evaluate<F: Smooth>(flow: &F, t: f64, watch: &mut Watch) -> Result<Point, ScanError> {
    watch.evaluations += 1;
    if watch.evaluations > MAX_EVALUATIONS {
        return Err(ScanError::TooMuchWork(t));
    }
    let p = flow.point(t);
    if p.q.is_finite() && p.v.is_finite() && p.acc.is_finite() && p.jerk.is_finite() {
        Ok(p)
    } else {
        Err(ScanError::NotFinite(t))
    }
}

/// The root of q' between a and b, where q' changes sign and q'' keeps its sign.
fn extremum<F: Smooth>(
    flow: &F,
    a: Point,
    b: Point,
    watch: &mut Watch,
) -> Result<Point, ScanError> {
    refine(flow, a, b, watch, |p| p.v, |p| p.acc)
}

/// The time in (a, b] at which q reaches the guard, q monotone there; q is put on the guard.
fn crossing<F: Smooth>(
    flow: &F,
    a: Point,
    b: Point,
    guard: &Guard,
    watch: &mut Watch,
) -> Result<Point, ScanError> {
    if guard.overshoot(a.q) == 0.0 {
        return Ok(Point {
            q: guard.level,
            ..a
        });
    }
    let g = |p: &Point| guard.overshoot(p.q);
    let dg = |p: &Point| guard.direction * p.v;
    let mut p = refine(flow, a, b, watch, g, dg)?;
    p.q = guard.level;
    Ok(p)
}

/// The root of `g` between a and b (where g changes sign, monotone) by Newton steps from the
/// better end, kept inside the bracket and replaced by halving where they leave it, until the
/// bracket is a few ulps wide or a step is below 2 ulps.
fn refine<F: Smooth>(
    flow: &F,
    a: Point,
    b: Point,
    watch: &mut Watch,
    g: impl Fn(&Point) -> f64,
    dg: impl Fn(&Point) -> f64,
) -> Result<Point, ScanError> {
    let (mut lo, mut hi) = (a, b);
    let lo_sign = g(&lo) > 0.0;
    let mut best = if g(&a).abs() <= g(&b).abs() { a } else { b };
    for _ in 0..200 {
        let value = g(&best);
        if value == 0.0 {
            break;
        }
        let slope = dg(&best);
        let mut t = best.t - value / slope;
        if t == best.t {
            // The Newton step is below half an ulp of t: the root is the double found.
            break;
        }
        if !(t > lo.t && t < hi.t) {
            t = lo.t + 0.5 * (hi.t - lo.t);
        }
        if t <= lo.t || t >= hi.t {
            break;
        }
        let p = evaluate(flow, t, watch)?;
        let step = (t - best.t).abs();
        if (g(&p) > 0.0) == lo_sign {
            lo = p;
        } else {
            hi = p;
        }
        best = if g(&p).abs() <= g(&best).abs() {
            p
        } else {
            best
        };
        if step <= 2.0 * ulp(t) || hi.t - lo.t <= 2.0 * ulp(hi.t) {
            break;
        }
    }
    Ok(best)
}
