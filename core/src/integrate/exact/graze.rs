//! Grazes: where q comes within the run's own rounding of a guard without crossing it, or
//! crosses it by no more than that, so that the run's arithmetic does not decide whether the
//! event happens, nor what follows it.
//!
//! Every run books its close approaches to the guards ([`Approach`]): the extrema of q that stop
//! short of a guard by at most [`APPROACH_SHARE`] of its level, and the crossings whose flow
//! would have turned back within that beyond it. The margin, how far the hump of q reaches
//! beyond the guard, is smooth through the tangency at which the event appears, so the shadow
//! runs' margins measure its uncertainty as they measure every other result's; with the run's
//! own rounding of q there, that is the margin's uncertainty d. An approach whose margin is
//! within d is a graze.
//!
//! Near its top a hump is q = q_top - a u^2/2 (u the time from the top, a = |q''|). Where q is
//! uncertain by d, it may reach the guard anywhere within sqrt(2 (d + |margin|)/a) before the
//! top: the error of a time there goes as the square root of d, not as d/|q'| as at a crossing
//! at speed. It would reach the guard at no more than v = sqrt(2 a (d + |margin|)). Where the
//! mode beyond brings q back (r = |q''| there, towards the guard), it is back within 2 zeta v/r
//! (zeta the reset's factor on q'), having gone at most (zeta v)^2/(2 r) beyond, and q' then
//! differs by at most v (|1 - zeta zeta'| + 2 |1 - zeta a/r|) (zeta' the reset back) from a hump
//! without the event (or with it, where the run has it): a small episode, whose effect on the
//! rest of the run two more runs measure, q' kicked by that much either way at the hump's end
//! ([`Kick`]). Where the mode beyond does not bring q back (it carries q away from the guard, or
//! the guard is the overturning point, past which nothing returns), or the hump is no parabola
//! over that time, or the episode lasts so long that q'' beyond changes by half, nothing after
//! the graze is bounded but by the model's range, |q| up to the overturning point.

use crate::floor::FloorMotion;
use crate::integrate::solution::{Graze, RoundingEstimate, Solution};
use crate::physics::automaton::{Automaton, EventKind, Guard};

/// Safety factor on the first-order error estimate.
pub(crate) const ESTIMATE_SAFETY: f64 = 4.0;

/// Runs that estimate the error of a run with a history.
pub const SHADOW_RUNS: usize = 2;
const _: () = assert!(SHADOW_RUNS == 2, "solve runs two shadow runs");

/// Share of a guard's level within which a run books an approach to it: far beyond any run's
/// rounding (a run whose q is that uncertain logs other sequences of events in its shadow runs).
pub(crate) const APPROACH_SHARE: f64 = 1e-6;

/// A hump of q that comes close to a guard: an extremum of q short of it, or a crossing whose
/// flow would have turned back just beyond it.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Approach {
    /// The time of the hump's top (for a crossing, where its flow would have turned back), s.
    pub t: f64,
    pub guard: Guard,
    /// How far the hump reaches beyond the guard, m: negative short of it.
    pub margin: f64,
    /// |q''| at the top (at the crossing, for a crossing), m/s^2.
    pub curvature: f64,
    /// |q'''| there, m/s^3.
    pub jerk: f64,
    /// The run's own estimate of the error of q there, m (0 in a run that books none).
    pub error: f64,
    /// Events booked before it.
    pub events_before: usize,
    /// The time of the last event before it (0 for none), s.
    pub since: f64,
    /// The largest and smallest q before it, m.
    pub max_before: f64,
    pub min_before: f64,
}

impl Approach {
    /// Whether a hump whose margin past `guard` is `margin` comes close enough to book.
    pub fn close(guard: &Guard, margin: f64) -> bool {
        margin.abs() <= APPROACH_SHARE * guard.level.abs()
    }

    /// Whether `other` (of another run) is an approach to the same guard after as many events.
    fn same_guard(&self, other: &Approach) -> bool {
        self.guard.kind == other.guard.kind
            && self.guard.to == other.guard.to
            && self.events_before == other.events_before
    }

    /// The uncertainty of the margin: the run's own rounding of q there, and the safety factor
    /// times its distance from each shadow run's (the nearest approach in time of the same guard
    /// after as many events). A shadow run without one has its margin beyond the share booked,
    /// at least that far from this one.
    fn uncertainty(&self, shadows: &[&[Approach]]) -> f64 {
        let spread = shadows
            .iter()
            .map(|list| {
                list.iter()
                    .filter(|other| self.same_guard(other))
                    .min_by(|a, b| (a.t - self.t).abs().total_cmp(&(b.t - self.t).abs()))
                    .map_or(
                        APPROACH_SHARE * self.guard.level.abs() - self.margin.abs(),
                        |other| (other.margin - self.margin).abs(),
                    )
            })
            .fold(0.0, f64::max);
        self.error + ESTIMATE_SAFETY * spread
    }
}

/// What a graze leaves open: from when, and, for a small episode, until when and how far.
struct Hump {
    /// The earliest time q may reach the guard, s.
    start: f64,
    /// None where nothing after the graze is bounded but by the model's range.
    small: Option<Small>,
}

/// A small episode beyond the guard, or its absence, at a graze.
struct Small {
    /// The latest time q is back inside the mode, on either branch, s.
    end: f64,
    /// How far beyond the guard q may go, m.
    beyond: f64,
    /// How much q' may differ between the branches once q is back, m/s.
    kick: f64,
}

/// The hump of the graze `a`, whose margin is uncertain by `d`; `floor_acc` the floor's
/// acceleration at its top.
fn hump(a: &Approach, d: f64, automaton: &Automaton, floor_acc: f64) -> Hump {
    let reach = d + a.margin.abs();
    let half = (2.0 * reach / a.curvature).sqrt();
    // Over `half` the cubic term stays below half the quadratic one.
    let parabola = half.is_finite() && a.jerk * half <= 1.5 * a.curvature;
    let start = if parabola {
        (a.t - half).max(a.since)
    } else {
        a.since
    };
    let back = match a.guard.kind {
        EventKind::Uplift => Some(EventKind::Landing),
        EventKind::Landing => Some(EventKind::Uplift),
        _ => None,
    };
    // q'' of the mode beyond, on the guard, towards it.
    let returning =
        -a.guard.direction * automaton.acceleration(a.guard.to, a.guard.level, 0.0, floor_acc);
    let (Some(back), true) = (back, parabola && returning > 0.0) else {
        return Hump { start, small: None };
    };
    let v = (2.0 * a.curvature * reach).sqrt();
    let zeta = automaton.reset_velocity(a.guard.kind, 1.0).abs();
    let zeta_back = automaton.reset_velocity(back, 1.0).abs();
    let end = a.t + half + 2.0 * zeta * v / returning;
    // The floor moves q'' on both sides of the guard alike (q''' at the top is mostly its
    // doing): over the episode, q'' beyond must keep at least half of itself.
    if a.jerk * (end - start) > 0.5 * returning {
        return Hump { start, small: None };
    }
    let small = Small {
        end,
        beyond: (zeta * v).powi(2) / (2.0 * returning),
        kick: v
            * ((1.0 - zeta * zeta_back).abs() + 2.0 * (1.0 - zeta * a.curvature / returning).abs()),
    };
    Hump {
        start,
        small: Some(small),
    }
}

/// A change of q' at a time: where a graze's small episode may have changed it.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Kick {
    pub t: f64,
    /// The change of q', m/s.
    pub dv: f64,
}

/// The largest (`sign` = 1) or smallest (-1) q of a run and the estimates of it and its time.
struct Peak<'a> {
    sign: f64,
    value: f64,
    t: f64,
    error: &'a mut f64,
    t_error: &'a mut f64,
}

impl Peak<'_> {
    /// Nothing after some time is known but the model's range: the true peak lies between the
    /// run's own before then (`before`, to 2 `d`) and the overturning point `topple`, at any
    /// time. That bounds its error, whatever the estimate before.
    fn whole_range(&mut self, before: f64, d: f64, topple: f64, duration: f64) {
        let beyond = (topple - self.sign * self.value).max(self.sign * (self.value - before));
        *self.error = beyond + 2.0 * d;
        *self.t_error = duration;
    }

    /// A graze's small episode on this peak's side: the peak may be the hump's (whose top lies
    /// within |margin| + d short of the guard and `small.beyond` beyond it, at any time between
    /// the hump's start and end), or the hump may top it.
    fn at_hump(&mut self, a: &Approach, d: f64, start: f64, small: &Small) {
        let top = a.guard.level + self.sign * small.beyond;
        if self.t >= start && self.t <= small.end {
            *self.error += a.margin.abs() + d + small.beyond;
            *self.t_error += small.end - start;
        } else if self.sign * (top - self.value) > -*self.error {
            *self.error += (self.sign * (top - self.value)).max(0.0);
            *self.t_error += (self.t - start).abs().max((small.end - self.t).abs());
        }
    }
}

/// The run's largest and smallest q, with their estimates.
fn peaks<'a>(estimate: &'a mut RoundingEstimate, run: &Solution) -> [Peak<'a>; 2] {
    let RoundingEstimate {
        max_q,
        t_max_q,
        min_q,
        t_min_q,
        ..
    } = estimate;
    [
        Peak {
            sign: 1.0,
            value: run.max_q.value,
            t: run.max_q.t,
            error: max_q,
            t_error: t_max_q,
        },
        Peak {
            sign: -1.0,
            value: run.min_q.value,
            t: run.min_q.t,
            error: min_q,
            t_error: t_min_q,
        },
    ]
}

/// The run's grazes, from its approaches (`approaches`, with the shadow runs' `shadows`), booked
/// in `estimate` with the time from which the sequence of events is uncertain, and the
/// estimates of the events and peaks that follow widened to cover either branch. `diverged`:
/// the first event a shadow run logs otherwise, and the largest and smallest q before the
/// event before it (or the start); a graze no later in the sequence explains it, else nothing
/// after the event before it is bounded but by the model's range. Returns the kicks of the
/// small episodes, for two more runs to measure.
#[allow(clippy::too_many_arguments)]
pub(crate) fn assess(
    estimate: &mut RoundingEstimate,
    run: &Solution,
    approaches: &[Approach],
    shadows: [&[Approach]; SHADOW_RUNS],
    diverged: Option<(usize, f64, f64)>,
    automaton: &Automaton,
    floor: &dyn FloorMotion,
    duration: f64,
) -> Vec<Kick> {
    let topple = automaton.topple_displacement();
    let grazes: Vec<(&Approach, f64)> = approaches
        .iter()
        .map(|a| (a, a.uncertainty(&shadows)))
        .filter(|(a, d)| a.margin.abs() <= *d)
        .collect();
    let unexplained = diverged
        .filter(|&(index, _, _)| grazes.first().is_none_or(|(a, _)| index < a.events_before));
    let mut kicks = Vec::new();
    if let Some((index, max_before, min_before)) = unexplained {
        let start = index
            .checked_sub(1)
            .map_or(0.0, |before| run.events[before].t);
        estimate.uncertain_from = Some(start);
        for (mut peak, before) in peaks(estimate, run)
            .into_iter()
            .zip([max_before, min_before])
        {
            peak.whole_range(before, 0.0, topple, duration);
        }
    }
    // Whether the run after the causes so far is bounded (by small episodes) at all.
    let mut bounded = unexplained.is_none();
    for (a, d) in grazes {
        estimate.grazes.push(Graze {
            t: a.t,
            event: a.guard.kind,
            happened: a.margin > 0.0,
            level: a.guard.level,
            margin: a.margin,
            rounding: d,
        });
        let hump = hump(a, d, automaton, floor.acceleration(a.t));
        let from = estimate.uncertain_from.get_or_insert(hump.start);
        *from = from.min(hump.start);
        if !bounded {
            continue;
        }
        // The sequence of events from the graze on is not certain.
        for error in estimate.event_time.iter_mut().skip(a.events_before) {
            *error = duration;
        }
        let peaks = peaks(estimate, run);
        match hump.small {
            Some(small) => {
                for mut peak in peaks {
                    if peak.sign == a.guard.direction {
                        peak.at_hump(a, d, hump.start, &small);
                    }
                }
                kicks.push(Kick {
                    t: small.end,
                    dv: small.kick,
                });
            }
            None => {
                for (mut peak, before) in peaks.into_iter().zip([a.max_before, a.min_before]) {
                    peak.whole_range(before, d, topple, duration);
                }
                bounded = false;
            }
        }
    }
    kicks
}

/// Below this share of the hump's reach beyond the guard, d/v is the crossing's time error to
/// a quarter of it (2/(1 + sqrt(1 - s)) = 1 + s/4 + ...), well within the safety factor.
const FIRST_ORDER_SHARE: f64 = 1e-6;

/// The error of the time at which q reaches a guard, s, where q is uncertain by `error` (m) and
/// crosses at `speed` (m/s) with `along` (m/s^2) the part of q'' that carries it across (negative
/// where q'' would turn it back). At speed, d/v. Where q'' carries it across, at most
/// sqrt(2 d/|q''|) too, however slow the crossing. Where q'' turns it back, the crossing nears a
/// tangency: (v - sqrt(v^2 - 2 a d))/a, up to sqrt(2 d/a) beyond the hump's top where the
/// crossing may not be at all (a graze).
pub(crate) fn crossing_time_error(error: f64, speed: f64, along: f64) -> f64 {
    let at_speed = error / speed.max(f64::MIN_POSITIVE);
    if along >= 0.0 {
        return at_speed.min((2.0 * error / along).sqrt());
    }
    let a = -along;
    let share = 2.0 * a * error / (speed * speed);
    if share < FIRST_ORDER_SHARE {
        at_speed
    } else if share < 1.0 {
        // (v - sqrt(v^2 - 2 a d))/a, without the cancellation.
        2.0 * error / (speed * (1.0 + (1.0 - share).sqrt()))
    } else {
        speed / a + (2.0 * error / a).sqrt()
    }
}
