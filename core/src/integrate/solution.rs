//! What a solver returns, whichever solver it is: sampled history, event log, peaks, energy
//! balance and statistics. `Recorder` builds it, so that every solver books results the same way.

use serde::{Deserialize, Serialize};

use crate::physics::automaton::{Automaton, EventKind, Mode};

/// One row of the history (a row of history.csv, whose columns are these fields; the restoring
/// force is the column `F`).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Sample {
    /// Time, s.
    pub t: f64,
    /// q, top displacement relative to the floor, m.
    pub q: f64,
    /// q', top velocity relative to the floor, m/s.
    pub qdot: f64,
    /// Flexural part of q.
    pub s: f64,
    /// Rocking part of q.
    pub r: f64,
    /// The mode the body is in.
    pub mode: Mode,
    /// Floor acceleration, m/s^2.
    pub floor_acc: f64,
    /// Restoring force (base shear) F(q), N.
    #[serde(rename = "F")]
    pub restoring_force: f64,
    /// Energy balance error, J: see `Recorder`.
    pub energy_residual: f64,
    /// Work done on the SDOF body by the floor since the start, J: the integral of
    /// [`Automaton::input_power`].
    pub work_input: f64,
    /// Work done by the damping term since the start, J: the integral of
    /// [`Automaton::damping_power`] (negative while rocking; see the README's Known limits).
    pub work_damping: f64,
}

/// One mode change (a row of events.csv, whose columns are these fields).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Event {
    /// Position of the event in the run, from 0.
    pub index: usize,
    /// Time of the event, s.
    pub t: f64,
    /// What happened.
    pub kind: EventKind,
    /// The mode before the event.
    pub from: Mode,
    /// The mode after the event.
    pub to: Mode,
    /// q at the event, m.
    pub q: f64,
    /// q' just before the event's reset, m/s.
    pub qdot_before: f64,
    /// q' just after the event's reset, m/s.
    pub qdot_after: f64,
}

/// One rocking episode: from an uplift to the landing or overturning that ends it, or to the end
/// of the run (a row of episodes.csv).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Episode {
    /// Position of the episode in the run, from 0.
    pub index: usize,
    /// The rocking mode: which toe the body turns on.
    pub mode: Mode,
    /// Time of the uplift (or the start of a run that starts rocking), s.
    pub t_start: f64,
    /// Time of the landing or overturning that ended it; None when the run ended first, s.
    pub t_end: Option<f64>,
    /// What ended it: a landing or an overturning; None when the run ended first.
    pub ended_by: Option<EventKind>,
    /// Floor acceleration at the uplift, m/s^2; None for a run that starts rocking.
    pub floor_acc_at_uplift: Option<f64>,
    /// Largest |q| during the episode, m, located as the run's peaks are.
    pub peak_abs_q: f64,
    /// When |q| was largest, s.
    pub t_peak: f64,
    /// Largest |r| (the rocking part of q) during the episode, m.
    pub peak_abs_r: f64,
    /// q' just before and just after the uplift's reset, m/s; None for a run that starts
    /// rocking.
    pub qdot_uplift: Option<(f64, f64)>,
    /// q' just before and just after the landing's reset, m/s; None without a landing.
    pub qdot_landing: Option<(f64, f64)>,
    /// The body's kinetic energy ([`Automaton::body_kinetic_energy`]) just before and just
    /// after the uplift, J; None for a run that starts rocking.
    pub kinetic_energy_uplift: Option<(f64, f64)>,
    /// The same just before and just after the landing, J; None without a landing.
    pub kinetic_energy_landing: Option<(f64, f64)>,
}

impl Episode {
    /// How long it lasted, s; None when the run ended first.
    pub fn duration(&self) -> Option<f64> {
        self.t_end.map(|end| end - self.t_start)
    }
}

/// Whether a run keeps its sampled history, or only its events, peaks and statistics (sweeps,
/// where thousands of runs need one row each).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum History {
    /// Samples every `output_dt`, and both sides of every event.
    Sampled,
    /// No samples: events, peaks, the energy balance at events, statistics.
    PeaksOnly,
}

/// A peak of q and when it happened.
#[derive(Debug, Clone, Copy, Serialize)]
pub struct Extremum {
    /// The peak value, m.
    pub value: f64,
    /// When it happened, s.
    pub t: f64,
}

/// Cost of a solution.
#[derive(Debug, Clone, Default, Serialize)]
pub struct SolverStats {
    /// The solver's name, e.g. "bdf" or "newmark-compensate".
    pub method: String,
    /// Accepted steps.
    pub steps: usize,
    /// Steps rejected by the error test.
    pub error_test_failures: usize,
    /// Newton iterations.
    pub nonlinear_iterations: usize,
    /// Jacobian evaluations.
    pub jacobian_evaluations: usize,
    /// Steps taken again because their dense output could not resolve a grazing crossing.
    pub crossing_retries: usize,
    /// Evaluations of the right-hand side.
    pub rhs_evaluations: usize,
    /// Wall-clock time of the solve, s.
    pub wall_time_s: f64,
}

/// A complete solution of one run.
#[derive(Debug, Clone, Serialize)]
pub struct Solution {
    /// The sampled history (empty for a peaks-only run).
    pub samples: Vec<Sample>,
    /// Every mode change, in order.
    pub events: Vec<Event>,
    /// Every rocking episode, in order.
    pub episodes: Vec<Episode>,
    /// Largest q and when, m.
    pub max_q: Extremum,
    /// Smallest q and when, m.
    pub min_q: Extremum,
    /// Largest |s|, the flexural part, m.
    pub max_abs_s: f64,
    /// Largest |r|, the rocking part, m.
    pub max_abs_r: f64,
    /// Whether the body fell over.
    pub overturned: bool,
    /// When it fell over (|q| reached B), s.
    pub t_overturn: Option<f64>,
    /// Time the run ended, s.
    pub final_time: f64,
    /// The mode at the end of the run.
    pub final_mode: Mode,
    /// Largest |energy_residual| over the samples, J.
    pub max_energy_residual: f64,
    /// The size of the energies the residual is measured against, J: the largest of the SDOF
    /// energy, the input work and the damping work over the samples.
    pub energy_scale: f64,
    /// The rounding of the energy books, J: [`ENERGY_ROUNDING_ULPS`] units in the last place of
    /// the body's potential energy at its overturning point (or of the energy scale, if larger).
    /// The energies are sums of terms of that size, so a residual below it is no imbalance.
    pub energy_rounding: f64,
    /// What the solution cost.
    pub stats: SolverStats,
    /// The exact solver's estimate of its own error; None for the other methods.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub rounding: Option<RoundingEstimate>,
}

/// The exact solver's first-order estimate of its own error (rounding of the terms summed and
/// the phases formed, and a few ulps of the model's constants), carried through the run.
#[derive(Debug, Clone, Serialize, PartialEq)]
pub struct RoundingEstimate {
    /// For each event, in the order of [`Solution::events`]: the error of its time, s.
    pub event_time: Vec<f64>,
    /// Error of the largest q, m.
    pub max_q: f64,
    /// Error of the time of the largest q, s.
    pub t_max_q: f64,
    /// Error of the smallest q, m.
    pub min_q: f64,
    /// Error of the time of the smallest q, s.
    pub t_min_q: f64,
    /// Where q came within the run's rounding of a guard without crossing it, or crossed it by
    /// no more than that, in time order: whether the event happened there is not decided by
    /// the run's arithmetic. Left out of summary.json where there is none.
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub grazes: Vec<Graze>,
    /// From when the sequence of events is not certain, s (the start of the first graze, or
    /// where a run with its constants moved within their rounding logs another sequence); None
    /// where it is certain throughout (and then left out of summary.json).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub uncertain_from: Option<f64>,
}

/// A graze: q came within the run's rounding of a guard, or crossed it by no more than that.
#[derive(Debug, Clone, Serialize, PartialEq)]
pub struct Graze {
    /// When the hump of q topped (for a crossing, where its flow would have turned back), s.
    pub t: f64,
    /// The event the guard is.
    pub event: EventKind,
    /// Whether the run logged the event there.
    pub happened: bool,
    /// q on the guard, m.
    pub level: f64,
    /// How far the hump of q went beyond the guard (positive) or stayed short of it
    /// (negative), m.
    pub margin: f64,
    /// The run's estimate of the error of that margin, m: the margin is within it.
    pub rounding: f64,
}

/// Units in the last place of the body's energy scale below which an energy residual is taken
/// for rounding: the books add and subtract energies of that size over thousands of steps.
pub const ENERGY_ROUNDING_ULPS: f64 = 1e4;

impl Solution {
    /// How many events of `kind` happened.
    pub fn count(&self, kind: EventKind) -> usize {
        self.events.iter().filter(|e| e.kind == kind).count()
    }

    /// True when the run ended with the body rocking: it did not overturn within the duration,
    /// but nothing says it would not have later.
    pub fn ended_while_rocking(&self) -> bool {
        matches!(self.final_mode, Mode::RockRight | Mode::RockLeft)
    }

    /// The largest energy residual as a share of the energy scale (0 when nothing moved): how
    /// far the integration is from the exact solution's energy books.
    pub fn energy_residual_share(&self) -> f64 {
        if self.max_energy_residual.is_nan() {
            // No energy books were kept.
            f64::NAN
        } else if self.max_energy_residual <= self.energy_rounding {
            // A run too short or too quiet for its energies to rise above their rounding
            // (1 microsecond: energies near 1e-19 J) balances to rounding.
            0.0
        } else if self.energy_scale > 0.0 {
            self.max_energy_residual / self.energy_scale
        } else {
            0.0
        }
    }
}

/// Books samples, events, peaks and the energy balance as a solver advances.
///
/// Energy balance: with E = Me q'^2/2 + V(q) (see [`Automaton::energy`]), eq. 16 gives
/// dE/dt = input power - damping power between events, and E jumps at events by the resets.
/// The solver integrates the two powers; the residual
/// `E(t) - E(0) - W_input(t) + W_damping(t) - sum of jumps` is zero for the exact solution, so its
/// size measures the integration error.
pub(crate) struct Recorder<'a> {
    automaton: &'a Automaton,
    samples: Vec<Sample>,
    events: Vec<Event>,
    episodes: Vec<Episode>,
    max_q: Extremum,
    min_q: Extremum,
    max_abs_s: f64,
    max_abs_r: f64,
    /// The mode the body is in, as the events booked so far say.
    mode: Mode,
    history: History,
    initial_energy: f64,
    event_jumps: f64,
    /// Work of contact forces while held against a neighbour, J.
    contact_work: f64,
    max_energy_residual: f64,
    energy_scale: f64,
    t_overturn: Option<f64>,
    /// Whether the energy books are kept (see [`Recorder::without_energy_books`]).
    energy_books: bool,
}

impl<'a> Recorder<'a> {
    /// A recorder for `automaton` starting at t0 in `mode` with q = q0 (m) and q' = qdot0 (m/s).
    pub fn new(
        automaton: &'a Automaton,
        t0: f64,
        q0: f64,
        qdot0: f64,
        mode: Mode,
        history: History,
    ) -> Self {
        // A run that starts rocking starts in an episode.
        let episodes = match mode {
            Mode::RockLeft | Mode::RockRight => vec![Episode {
                index: 0,
                mode,
                t_start: t0,
                t_end: None,
                ended_by: None,
                floor_acc_at_uplift: None,
                peak_abs_q: q0.abs(),
                t_peak: t0,
                peak_abs_r: automaton.rocking_part(mode, q0).abs(),
                qdot_uplift: None,
                qdot_landing: None,
                kinetic_energy_uplift: None,
                kinetic_energy_landing: None,
            }],
            _ => Vec::new(),
        };
        Recorder {
            automaton,
            samples: Vec::new(),
            events: Vec::new(),
            episodes,
            max_q: Extremum { value: q0, t: t0 },
            min_q: Extremum { value: q0, t: t0 },
            max_abs_s: automaton.flexural_part(mode, q0).abs(),
            max_abs_r: automaton.rocking_part(mode, q0).abs(),
            mode,
            history,
            initial_energy: automaton.energy(mode, q0, qdot0),
            event_jumps: 0.0,
            contact_work: 0.0,
            max_energy_residual: 0.0,
            energy_scale: 0.0,
            t_overturn: None,
            energy_books: true,
        }
    }

    /// The work done on the body so far by a neighbour's contact force while held against it
    /// (a row's persistent contact), J, in the SDOF energy: it enters the energy residual as
    /// the input work does.
    pub fn set_contact_work(&mut self, work: f64) {
        self.contact_work = work;
    }

    /// Makes room for `samples` more samples (a solver that knows its grid allocates once).
    pub fn reserve(&mut self, samples: usize) {
        if self.history == History::Sampled {
            self.samples.reserve(samples);
        }
    }

    /// A recorder that keeps no energy books: the solver integrates no work, and the solution's
    /// energy residual and scale are NaN (not computed). The exact method's runs without a
    /// history (sweeps, minimum searches) are such runs: their energy balance holds by
    /// construction, and checking it would cost more than the solution.
    pub fn without_energy_books(mut self) -> Self {
        self.energy_books = false;
        self
    }

    /// Records a state; `work_input` and `work_damping` are the integrals (J) of
    /// [`Automaton::input_power`] and [`Automaton::damping_power`] from the start.
    #[allow(clippy::too_many_arguments)]
    pub fn sample(
        &mut self,
        t: f64,
        mode: Mode,
        q: f64,
        qdot: f64,
        floor_acc: f64,
        work_input: f64,
        work_damping: f64,
    ) {
        let a = self.automaton;
        let energy = a.energy(mode, q, qdot);
        let residual = energy - self.initial_energy - work_input + work_damping
            - self.event_jumps
            - self.contact_work;
        if self.energy_books {
            self.max_energy_residual = self.max_energy_residual.max(residual.abs());
            self.energy_scale = self
                .energy_scale
                .max(energy.abs())
                .max(work_input.abs())
                .max(work_damping.abs());
        }
        self.peak_candidate(t, q);
        if self.history == History::PeaksOnly {
            return;
        }
        self.samples.push(Sample {
            t,
            q,
            qdot,
            s: a.flexural_part(mode, q),
            r: a.rocking_part(mode, q),
            mode,
            floor_acc,
            restoring_force: a.restoring_force(mode, q),
            energy_residual: residual,
            work_input,
            work_damping,
        });
    }

    /// Offers a state at which q may be extremal (a root of q', an event, an end point). Within
    /// a mode |s| and |r| are monotone in |q| (book/src/model.md §3), so their peaks are among
    /// these states too.
    pub fn peak_candidate(&mut self, t: f64, q: f64) {
        if q > self.max_q.value {
            self.max_q = Extremum { value: q, t };
        }
        if q < self.min_q.value {
            self.min_q = Extremum { value: q, t };
        }
        let a = self.automaton;
        self.max_abs_s = self.max_abs_s.max(a.flexural_part(self.mode, q).abs());
        self.max_abs_r = self.max_abs_r.max(a.rocking_part(self.mode, q).abs());
        let abs_r = a.rocking_part(self.mode, q).abs();
        if let Some(episode) = self.open_episode() {
            if q.abs() > episode.peak_abs_q {
                episode.peak_abs_q = q.abs();
                episode.t_peak = t;
            }
            episode.peak_abs_r = episode.peak_abs_r.max(abs_r);
        }
    }

    /// The episode under way: the last one, while the body rocks.
    fn open_episode(&mut self) -> Option<&mut Episode> {
        let rocking = matches!(self.mode, Mode::RockLeft | Mode::RockRight);
        self.episodes
            .last_mut()
            .filter(|e| rocking && e.t_end.is_none())
    }

    /// Records a mode change and the states on both sides of it.
    #[allow(clippy::too_many_arguments)]
    pub fn event(
        &mut self,
        t: f64,
        kind: EventKind,
        from: Mode,
        to: Mode,
        q: f64,
        qdot_before: f64,
        qdot_after: f64,
        floor_acc: f64,
        work_input: f64,
        work_damping: f64,
    ) {
        self.mode = from;
        self.sample(t, from, q, qdot_before, floor_acc, work_input, work_damping);
        let a = self.automaton;
        let ends_episode = matches!(kind, EventKind::Landing | EventKind::Overturn);
        if let Some(episode) = self.open_episode().filter(|_| ends_episode) {
            // A landing or an overturning ends the episode.
            episode.t_end = Some(t);
            episode.ended_by = Some(kind);
            if kind == EventKind::Landing {
                episode.qdot_landing = Some((qdot_before, qdot_after));
                episode.kinetic_energy_landing = Some((
                    a.body_kinetic_energy(from, qdot_before),
                    a.body_kinetic_energy(to, qdot_after),
                ));
            }
        }
        self.mode = to;
        if kind == EventKind::Uplift {
            self.episodes.push(Episode {
                index: self.episodes.len(),
                mode: to,
                t_start: t,
                t_end: None,
                ended_by: None,
                floor_acc_at_uplift: Some(floor_acc),
                peak_abs_q: q.abs(),
                t_peak: t,
                peak_abs_r: a.rocking_part(to, q).abs(),
                qdot_uplift: Some((qdot_before, qdot_after)),
                qdot_landing: None,
                kinetic_energy_uplift: Some((
                    a.body_kinetic_energy(from, qdot_before),
                    a.body_kinetic_energy(to, qdot_after),
                )),
                kinetic_energy_landing: None,
            });
        }
        self.event_jumps += a.event_energy_jump(from, to, q, qdot_before, qdot_after);
        self.events.push(Event {
            index: self.events.len(),
            t,
            kind,
            from,
            to,
            q,
            qdot_before,
            qdot_after,
        });
        if kind == EventKind::Overturn {
            self.t_overturn = Some(t);
        }
        self.sample(t, to, q, qdot_after, floor_acc, work_input, work_damping);
    }

    /// The solution booked, ended at `final_time` (s) in `final_mode`.
    pub fn finish(self, final_time: f64, final_mode: Mode, stats: SolverStats) -> Solution {
        Solution {
            samples: self.samples,
            events: self.events,
            episodes: self.episodes,
            max_q: self.max_q,
            min_q: self.min_q,
            max_abs_s: self.max_abs_s,
            max_abs_r: self.max_abs_r,
            overturned: self.t_overturn.is_some(),
            t_overturn: self.t_overturn,
            final_time,
            final_mode,
            max_energy_residual: if self.energy_books {
                self.max_energy_residual
            } else {
                f64::NAN
            },
            energy_scale: if self.energy_books {
                self.energy_scale
            } else {
                f64::NAN
            },
            energy_rounding: ENERGY_ROUNDING_ULPS
                * f64::EPSILON
                * self.energy_scale.max(
                    self.automaton
                        .potential_energy(Mode::RockRight, self.automaton.topple_displacement()),
                ),
            stats,
            rounding: None,
        }
    }
}
