//! The exact method's entry: a run of the automaton, and the shadow runs whose spread, added
//! to the run's own books, is the estimate of its error.

use std::time::Instant;

use super::graze::{self, Kick, ESTIMATE_SAFETY};
use super::run::{Books, ExactRun};
use super::settings::ExactSettings;
use crate::floor::FloorMotion;
use crate::integrate::solution::{RoundingEstimate, Solution};
use crate::integrate::{History, InitialState, SolverError};
use crate::physics::automaton::Automaton;

/// Solves the automaton exactly from `initial` over [0, duration].
///
/// A run that keeps its history also estimates its own error: to the rounding of each event
/// time and peak where it is computed, it adds the spread of [`SHADOW_RUNS`](super::SHADOW_RUNS) runs of the same
/// model whose constants and initial state are moved by their own uncertainty in pseudo-random
/// directions (`Automaton::nudged`), times a safety factor. This is discrete stochastic
/// arithmetic in the manner of CESTAC (Vignes 1993): the spread measures how far rounding of
/// that size carries each result, including through ill-conditioned (grazing) events.
pub fn solve(
    automaton: &Automaton,
    floor: &dyn FloorMotion,
    initial: InitialState,
    duration: f64,
    settings: &ExactSettings,
    history: History,
) -> Result<Solution, SolverError> {
    let started = Instant::now();
    // A run without a history keeps no energy books (Recorder::without_energy_books).
    let energy = history == History::Sampled;
    let run = || {
        solve_once(
            automaton,
            floor,
            initial,
            duration,
            settings,
            history,
            energy,
            Vec::new(),
        )
    };
    if history != History::Sampled {
        let (mut solution, _) = run()?;
        solution.stats.wall_time_s = started.elapsed().as_secs_f64();
        return Ok(solution);
    }
    let size = automaton.constants_uncertainty();
    let shadow = |pattern: usize| {
        let nudged = automaton.nudged(pattern as u64 + 1, size);
        let moved = InitialState {
            q: initial.q
                * (1.0 + size * crate::physics::automaton::nudge_sign(pattern as u64 + 1, 100)),
            qdot: initial.qdot
                * (1.0 + size * crate::physics::automaton::nudge_sign(pattern as u64 + 1, 101)),
        };
        solve_once(
            &nudged,
            floor,
            moved,
            duration,
            settings,
            History::PeaksOnly,
            false,
            Vec::new(),
        )
    };
    // The shadow runs are independent of the run: with the `parallel` feature they run beside
    // it on another core (the same results, in less time on a machine with a core to spare).
    let (main, (first, second)) = beside(run, || (shadow(0), shadow(1)));
    let (mut solution, books) = main?;
    let shadows = [first?, second?];
    let mut estimate = books.estimate;
    let mut diverged: Option<usize> = None;
    for (shadow, _) in &shadows {
        if let Some(index) = spread_into(&mut estimate, &solution, shadow, duration) {
            diverged = Some(diverged.map_or(index, |other| other.min(index)));
        }
    }
    let diverged = diverged.map(|index| {
        let (max, min) = index
            .checked_sub(1)
            .map_or((initial.q, initial.q), |before| books.extremes[before]);
        (index, max, min)
    });
    let kicks = graze::assess(
        &mut estimate,
        &solution,
        &books.approaches,
        [&shadows[0].1.approaches, &shadows[1].1.approaches],
        diverged,
        automaton,
        floor,
        duration,
    );
    // The small episodes of the grazes: their effect on the rest of the run, measured by two
    // runs whose q' is kicked by each episode's bound, one way and the other.
    if !kicks.is_empty() {
        for sign in [1.0, -1.0] {
            let kicked = kicks
                .iter()
                .map(|kick| Kick {
                    dv: sign * kick.dv,
                    ..*kick
                })
                .collect();
            let (other, _) = solve_once(
                automaton,
                floor,
                initial,
                duration,
                settings,
                History::PeaksOnly,
                false,
                kicked,
            )?;
            spread_peaks(&mut estimate, &solution, &other);
        }
    }
    solution.rounding = Some(estimate);
    solution.stats.wall_time_s = started.elapsed().as_secs_f64();
    Ok(solution)
}

/// `main()` on this thread, and `aside()` beside it on the thread pool: the caller's thread
/// starts the main run at once instead of waiting for a pool thread to wake (a join from
/// outside the pool would hand both to the pool and wait). The shadow runs keep no history
/// and are much shorter than the main run, so one pool thread takes both.
#[cfg(feature = "parallel")]
fn beside<A, B: Send>(main: impl FnOnce() -> A, aside: impl FnOnce() -> B + Send) -> (A, B) {
    let mut other = None;
    let first = rayon::in_place_scope(|scope| {
        scope.spawn(|_| other = Some(aside()));
        main()
    });
    (
        first,
        other.expect("a scope ends after the work it spawned"),
    )
}

/// `main()`, then `aside()`.
#[cfg(not(feature = "parallel"))]
fn beside<A, B>(main: impl FnOnce() -> A, aside: impl FnOnce() -> B) -> (A, B) {
    (main(), aside())
}

/// Adds to `estimate` the safety factor times the distance of the shadow run from the run.
/// From the first event whose kind differs (or that one run lacks) on, the event sequence itself
/// is not robust to rounding, and the estimate is the whole duration; returns that event's
/// index (the run's count of events where the shadow run logs more).
fn spread_into(
    estimate: &mut RoundingEstimate,
    run: &Solution,
    shadow: &Solution,
    duration: f64,
) -> Option<usize> {
    let mut robust = true;
    let mut diverged = None;
    for (i, error) in estimate.event_time.iter_mut().enumerate() {
        let other = shadow.events.get(i);
        robust = robust
            && other.is_some_and(|o| o.kind == run.events[i].kind && o.to == run.events[i].to);
        *error = if robust {
            error.max(0.0) + ESTIMATE_SAFETY * (run.events[i].t - other.map_or(0.0, |o| o.t)).abs()
        } else {
            diverged = diverged.or(Some(i));
            duration
        };
    }
    if robust && shadow.events.len() > run.events.len() {
        diverged = Some(run.events.len());
    }
    spread_peaks(estimate, run, shadow);
    diverged
}

/// Adds to the estimates of the peaks the safety factor times their distance in `shadow` (a run
/// of the same model moved within its rounding).
fn spread_peaks(estimate: &mut RoundingEstimate, run: &Solution, shadow: &Solution) {
    let spread = |a: f64, b: f64| ESTIMATE_SAFETY * (a - b).abs();
    estimate.max_q += spread(run.max_q.value, shadow.max_q.value);
    estimate.t_max_q += spread(run.max_q.t, shadow.max_q.t);
    estimate.min_q += spread(run.min_q.value, shadow.min_q.value);
    estimate.t_min_q += spread(run.min_q.t, shadow.min_q.t);
}

/// One run; with `energy`, the energy books are kept; q' changed by each of `kicks` on the way.
/// Returns what it books for its own estimate.
#[allow(clippy::too_many_arguments)]
fn solve_once(
    automaton: &Automaton,
    floor: &dyn FloorMotion,
    initial: InitialState,
    duration: f64,
    settings: &ExactSettings,
    history: History,
    energy: bool,
    kicks: Vec<Kick>,
) -> Result<(Solution, Books), SolverError> {
    let started = Instant::now();
    let mut run = ExactRun::new(
        automaton, floor, initial, duration, settings, history, energy,
    );
    run.kicks = kicks;
    let final_time = run.go(duration)?;
    Ok(run.finish(final_time, started))
}
