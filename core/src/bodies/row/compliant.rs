//! A row of columns with the compliant contact law (book/src/row.md §4a), integrated by diffsol's
//! Tsit45 in the event loop of every diffsol run ([`crate::integrate::event_loop`]), with the
//! events located as the single body's are ([`crate::integrate::adaptive`]).
//!
//! The state is (q_i, q'_i) of every column. Each column's own acceleration is its automaton's,
//! in its mode; a contact in force adds Phi P / m_Phi (book/src/row.md §2) with
//! P = k delta + c delta' (delta = -gap, the penetration; delta' the closing velocity of the
//! contact points). The work integrals ride along as diffsol's quadratures: each column's input,
//! damping and contact work in its SDOF energy, and each contact's P delta', the energy the
//! contact takes from the bodies.
//!
//! Events, located on the dense output of each step: every column's uplift, landing and
//! overturning (the step split at the roots of its q', each guard crossed only in the direction q
//! moves, regula falsi on the dense output, a step whose crossing its dense output cannot resolve
//! taken again four times shorter); a contact's start, where its gap falls through zero (the step
//! split at the root of the closing velocity); its end, where P falls through zero while in
//! contact (the step split at the root of P'). A pair let go while its faces still overlap (P
//! falls to zero with delta > 0, the dashpot pulling the faces apart faster than the spring) is in
//! contact again if P rises through zero before the faces part. The dashpot c is set at each
//! contact's start from the modes then (the reduced mass of the two contact points, m / Phi^2 of
//! each, depends on them) and kept to its end. At an event the solver is moved back to it, the
//! reset (or the change of contacts) is applied, and the method restarts there. An overturning
//! column ends the row's run. [`RunBudget`]s cap events (and the loop steps), so that every run
//! ends.

use std::cell::RefCell;
use std::time::Instant;

use diffsol::{NalgebraMat, OdeBuilder};

use super::contact::{ContactSample, ContactState, GAP_ROUNDING_ULPS, OVERLAP_ERROR_SHARE};
use super::description::{ContactLaw, Row};
use super::solution::{ContactStretch, RowSolution, StickStretch};
use crate::floor::FloorMotion;
use crate::integrate::budget::RunBudget;
use crate::integrate::event_loop::{
    self, DenseOutput, EventBody, Found, LoopSetup, Outcome, StepStart,
};
use crate::integrate::exact::kernel::ulp;
use crate::integrate::solution::{Recorder, SolverStats};
use crate::integrate::{History, OutputGrid, SolverError};
use crate::physics::automaton::{Automaton, EventKind, Guard, Mode};

type Matrix = NalgebraMat<f64>;
type Result<T> = std::result::Result<T, SolverError>;

/// The method the compliant row is integrated with.
pub const METHOD: &str = "tsit45";
/// rtol and atol of the compliant row when the model file gives none.
pub const DEFAULT_TOLERANCE: f64 = 1e-10;
/// Events at one instant (a reset that lets a contact go, that starts another), per column of
/// the row, before giving up: identical columns may all lift off, and their contacts all close,
/// at one instant.
const MAX_CHAIN: usize = 16;

/// Settings of a compliant row's run.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub struct CompliantSettings {
    /// Relative tolerance.
    pub rtol: f64,
    /// Absolute tolerance (m for q, m/s for q').
    pub atol: f64,
    /// Spacing of the sampled history, s.
    pub output_dt: f64,
}

/// Coulomb's friction at a contact in force (book/src/row.md §4b).
#[derive(Debug, Clone, Copy, PartialEq)]
enum Friction {
    /// No friction: the contact is not in force, or the row has none.
    Off,
    /// The faces slide, sigma of the sign given; the friction force is -mu P that sign.
    Slip(f64),
    /// The faces stick: the friction force is what keeps sigma' = 0, within mu P.
    Stick,
}

/// What changes along the run and the right-hand side depends on.
#[derive(Debug, Clone)]
struct Config {
    modes: Vec<Mode>,
    active: Vec<bool>,
    /// c of each contact, N s/m, set at its start.
    damping: Vec<f64>,
    /// The friction state of each contact.
    friction: Vec<Friction>,
}

/// The row's fixed data.
struct RowEquations<'r> {
    row: &'r Row,
    stiffness: f64,
    zeta: f64,
    /// Coulomb's coefficient of friction between the faces.
    mu: f64,
    /// The integration's atol, m/s: a sliding speed this small is not told from zero.
    atol: f64,
}

/// The contact forces at one state: the normal force P and the friction force T on the left
/// column's face (up; the right column's face takes -T), N, 0 where not in contact.
struct Forces {
    normal: Vec<f64>,
    friction: Vec<f64>,
}

impl RowEquations<'_> {
    fn n(&self) -> usize {
        self.row.columns().len()
    }

    fn automaton(&self, i: usize) -> &Automaton {
        &self.row.columns()[i].automaton
    }

    fn slopes(&self, c: usize, modes: &[Mode]) -> (f64, f64) {
        let automata = (self.automaton(c), self.automaton(c + 1));
        self.row.contacts()[c].slopes(automata, (modes[c], modes[c + 1]))
    }

    /// delta = -gap, m.
    fn penetration(&self, c: usize, modes: &[Mode], x: &[f64]) -> f64 {
        let automata = (self.automaton(c), self.automaton(c + 1));
        -self.row.contacts()[c].gap(automata, (modes[c], x[2 * c]), (modes[c + 1], x[2 * c + 2]))
    }

    /// delta' = Phi_l q'_l - Phi_r q'_r, m/s.
    fn closing(&self, c: usize, modes: &[Mode], x: &[f64]) -> f64 {
        let (pl, pr) = self.slopes(c, modes);
        pl * x[2 * c + 1] - pr * x[2 * c + 3]
    }

    /// P = k delta + c delta' with dashpot `damping`, N.
    fn force_with(&self, c: usize, modes: &[Mode], damping: f64, x: &[f64]) -> f64 {
        self.stiffness * self.penetration(c, modes, x) + damping * self.closing(c, modes, x)
    }

    /// The force contact `c` would carry at `x` were it in force now, N: P with the dashpot it
    /// would start with.
    fn force_if_started(&self, c: usize, modes: &[Mode], x: &[f64]) -> f64 {
        self.force_with(c, modes, self.dashpot(c, modes), x)
    }

    /// Whether contact `c`, not in force, must be: its faces touch or overlap and would press
    /// on each other.
    fn presses(&self, c: usize, modes: &[Mode], x: &[f64]) -> bool {
        self.penetration(c, modes, x) >= 0.0 && self.force_if_started(c, modes, x) > 0.0
    }

    /// How far the faces of contact `c` may read as overlapping, m, at `x` and time `t`, with
    /// no contact in force and nothing pushing them apart: the gap's rounding
    /// ([`GAP_ROUNDING_ULPS`] of its size), the distance the points close over
    /// the width of a located crossing (a few ulps of `t`), and `share` of the gap's size.
    fn overlap_tolerance(&self, c: usize, modes: &[Mode], x: &[f64], t: f64, share: f64) -> f64 {
        let automata = (self.automaton(c), self.automaton(c + 1));
        let size = self.row.contacts()[c].gap_size(
            automata,
            (modes[c], x[2 * c]),
            (modes[c + 1], x[2 * c + 2]),
        );
        GAP_ROUNDING_ULPS * ulp(size)
            + share * size
            + self.closing(c, modes, x).abs() * 8.0 * ulp(t)
    }

    /// What contact `c`, not in force, is doing at `x` (time `t`): open, or parting (its faces,
    /// let go at zero force, still overlap and nothing presses them together); an error where
    /// its faces overlap by more than [`RowEquations::overlap_tolerance`] with `share` and would
    /// press, which the run never leaves standing.
    fn idle_state(
        &self,
        c: usize,
        modes: &[Mode],
        x: &[f64],
        t: f64,
        share: f64,
    ) -> Result<ContactState> {
        let overlap = self.penetration(c, modes, x);
        if overlap > 0.0 && self.force_if_started(c, modes, x) <= 0.0 {
            return Ok(ContactState::Parting);
        }
        let tolerance = self.overlap_tolerance(c, modes, x, t, share);
        if overlap > tolerance {
            return Err(failed(
                t,
                format!(
                    "the faces of columns {c} and {} overlap by {overlap:e} m and press on each \
                     other with no contact in force (more than the {tolerance:e} m of rounding \
                     allowed): a closing was missed, and the run stops rather than let them pass \
                     through each other",
                    c + 1
                ),
            ));
        }
        Ok(ContactState::Open)
    }

    /// The reduced mass of the contact points of contact `c`, kg.
    fn reduced_mass(&self, c: usize, modes: &[Mode]) -> f64 {
        self.row.reduced_mass(c, (modes[c], modes[c + 1]))
    }

    /// c = 2 zeta sqrt(k m_red), N s/m.
    fn dashpot(&self, c: usize, modes: &[Mode]) -> f64 {
        2.0 * self.zeta * (self.stiffness * self.reduced_mass(c, modes)).sqrt()
    }

    /// dv/dq of the two faces of contact `c` (book/src/row.md §4b): the faces slide at
    /// sigma = `.0` q'_left - `.1` q'_right.
    fn sliding_slopes(&self, c: usize, modes: &[Mode], x: &[f64]) -> (f64, f64) {
        let automata = (self.automaton(c), self.automaton(c + 1));
        self.row.contacts()[c].sliding_slopes(
            automata,
            (modes[c], x[2 * c]),
            (modes[c + 1], x[2 * c + 2]),
        )
    }

    /// sigma, the speed at which the left face slides up past the right one, m/s.
    fn sliding(&self, c: usize, modes: &[Mode], x: &[f64]) -> f64 {
        let (vl, vr) = self.sliding_slopes(c, modes, x);
        vl * x[2 * c + 1] - vr * x[2 * c + 3]
    }

    /// The sliding speed below which the faces of contact `c` count as not sliding, m/s: the
    /// integration's atol on q' carried to sigma.
    fn sliding_tolerance(&self, c: usize, modes: &[Mode], x: &[f64]) -> f64 {
        let (vl, vr) = self.sliding_slopes(c, modes, x);
        self.atol * (vl.abs() + vr.abs())
    }

    /// The contact forces at `x` with floor acceleration `floor_acc`. A sticking contact's
    /// friction is the force that keeps its faces from sliding: sigma' = 0, with the other
    /// forces as they are; neighbouring sticking contacts share a column, so each run of them
    /// is one tridiagonal system.
    fn forces(&self, cfg: &Config, x: &[f64], floor_acc: f64) -> Forces {
        let contacts = self.n() - 1;
        let mut normal = vec![0.0; contacts];
        let mut friction = vec![0.0; contacts];
        let mut sticking = false;
        for c in 0..contacts {
            if !cfg.active[c] {
                continue;
            }
            normal[c] = self.force_with(c, &cfg.modes, cfg.damping[c], x);
            match cfg.friction[c] {
                Friction::Off => {}
                Friction::Slip(sign) => friction[c] = -self.mu * normal[c].max(0.0) * sign,
                Friction::Stick => sticking = true,
            }
        }
        if sticking {
            let mut y = vec![0.0; x.len()];
            self.accelerations_with(cfg, x, floor_acc, &normal, &friction, &mut y);
            self.stick(cfg, x, &y, &mut friction);
        }
        Forces { normal, friction }
    }

    /// Sets the friction of every sticking contact in `friction` from the accelerations `y`
    /// the other forces give: D T = -sigma' over each run of neighbouring sticking contacts,
    /// D = G M^-1 G^T with G the faces' slopes. Faces whose slopes give D = 0 cannot slide
    /// against each other, and take no friction.
    fn stick(&self, cfg: &Config, x: &[f64], y: &[f64], friction: &mut [f64]) {
        let contacts = self.n() - 1;
        let mass = |i: usize| self.automaton(i).kinetic_mass(cfg.modes[i]);
        let mut c = 0;
        while c < contacts {
            if cfg.friction[c] != Friction::Stick {
                c += 1;
                continue;
            }
            let first = c;
            while c < contacts && cfg.friction[c] == Friction::Stick {
                c += 1;
            }
            // Thomas' algorithm over the run first..c.
            let len = c - first;
            let slopes: Vec<(f64, f64)> = (first..c)
                .map(|k| self.sliding_slopes(k, &cfg.modes, x))
                .collect();
            let mut diag = Vec::with_capacity(len);
            let mut upper = Vec::with_capacity(len);
            let mut rhs = Vec::with_capacity(len);
            for (j, &(vl, vr)) in slopes.iter().enumerate() {
                let k = first + j;
                diag.push(vl * vl / mass(k) + vr * vr / mass(k + 1));
                upper.push(if j + 1 < len {
                    -vr * slopes[j + 1].0 / mass(k + 1)
                } else {
                    0.0
                });
                rhs.push(-(vl * y[2 * k + 1] - vr * y[2 * k + 3]));
            }
            for j in 1..len {
                if diag[j - 1] > 0.0 {
                    let factor = upper[j - 1] / diag[j - 1];
                    diag[j] -= factor * upper[j - 1];
                    rhs[j] -= factor * rhs[j - 1];
                }
            }
            for j in (0..len).rev() {
                let above = if j + 1 < len {
                    upper[j] * friction[first + j + 1]
                } else {
                    0.0
                };
                friction[first + j] = if diag[j] > 0.0 {
                    (rhs[j] - above) / diag[j]
                } else {
                    0.0
                };
            }
        }
    }

    /// Each column's q'' from its automaton with the contact forces' shares, Phi P / m_Phi and
    /// the faces' dv/dq T / m_Phi.
    fn accelerations_with(
        &self,
        cfg: &Config,
        x: &[f64],
        floor_acc: f64,
        normal: &[f64],
        friction: &[f64],
        y: &mut [f64],
    ) {
        let n = self.n();
        for i in 0..n {
            y[2 * i] = x[2 * i + 1];
            y[2 * i + 1] =
                self.automaton(i)
                    .acceleration(cfg.modes[i], x[2 * i], x[2 * i + 1], floor_acc);
        }
        for c in 0..n - 1 {
            let (p, f) = (normal[c], friction[c]);
            if p == 0.0 && f == 0.0 {
                continue;
            }
            let (pl, pr) = self.slopes(c, &cfg.modes);
            let (vl, vr) = self.sliding_slopes(c, &cfg.modes, x);
            y[2 * c + 1] += (vl * f - pl * p) / self.automaton(c).kinetic_mass(cfg.modes[c]);
            y[2 * c + 3] +=
                (pr * p - vr * f) / self.automaton(c + 1).kinetic_mass(cfg.modes[c + 1]);
        }
    }

    /// Each column's q'' from its automaton, with the contact forces.
    fn rhs(&self, cfg: &Config, x: &[f64], floor_acc: f64, y: &mut [f64]) {
        let forces = self.forces(cfg, x, floor_acc);
        self.accelerations_with(cfg, x, floor_acc, &forces.normal, &forces.friction, y);
    }

    /// The Jacobian of [`RowEquations::rhs`] times `v`.
    fn jacobian(&self, cfg: &Config, v: &[f64], y: &mut [f64]) {
        let n = self.n();
        for i in 0..n {
            let (d_q, d_qdot) = self.automaton(i).acceleration_jacobian(cfg.modes[i]);
            y[2 * i] = v[2 * i + 1];
            y[2 * i + 1] = d_q * v[2 * i] + d_qdot * v[2 * i + 1];
        }
        for c in 0..n - 1 {
            if !cfg.active[c] {
                continue;
            }
            let (pl, pr) = self.slopes(c, &cfg.modes);
            let dp = self.stiffness * (pl * v[2 * c] - pr * v[2 * c + 2])
                + cfg.damping[c] * (pl * v[2 * c + 1] - pr * v[2 * c + 3]);
            y[2 * c + 1] -= pl * dp / self.automaton(c).kinetic_mass(cfg.modes[c]);
            y[2 * c + 3] += pr * dp / self.automaton(c + 1).kinetic_mass(cfg.modes[c + 1]);
            // A slipping contact's friction -mu P sign; a sticking one's is left out (Tsit45,
            // an explicit method, asks for no Jacobian: this one serves diffsol's interface).
            if let Friction::Slip(sign) = cfg.friction[c] {
                let (vl, vr) = self.slopes_for_jacobian(c, cfg);
                let df = -self.mu * sign * dp;
                y[2 * c + 1] += vl * df / self.automaton(c).kinetic_mass(cfg.modes[c]);
                y[2 * c + 3] -= vr * df / self.automaton(c + 1).kinetic_mass(cfg.modes[c + 1]);
            }
        }
    }

    /// dv/dq of the faces of contact `c` at a state the Jacobian does not pass: a slipping
    /// column's face slopes depend on its q only through an overturned column's side, and an
    /// overturned column ends the run.
    fn slopes_for_jacobian(&self, c: usize, cfg: &Config) -> (f64, f64) {
        let automata = (self.automaton(c), self.automaton(c + 1));
        self.row.contacts()[c].sliding_slopes(
            automata,
            (cfg.modes[c], 0.0),
            (cfg.modes[c + 1], 0.0),
        )
    }

    /// The integrands of the work integrals: per column its input, damping and contact power
    /// in its SDOF energy (the contact forces' terms of its equation times M_e q'), then per
    /// contact P delta' (what the spring and dashpot take), then per contact -T sigma (what
    /// friction takes).
    fn integrands(&self, cfg: &Config, x: &[f64], floor_acc: f64, y: &mut [f64]) {
        let n = self.n();
        let Forces { normal, friction } = self.forces(cfg, x, floor_acc);
        for i in 0..n {
            let (a, mode, qdot) = (self.automaton(i), cfg.modes[i], x[2 * i + 1]);
            y[3 * i] = a.input_power(mode, qdot, floor_acc);
            y[3 * i + 1] = a.damping_power(mode, qdot);
            let mut generalised = 0.0;
            if i > 0 && (normal[i - 1] != 0.0 || friction[i - 1] != 0.0) {
                let vr = self.sliding_slopes(i - 1, &cfg.modes, x).1;
                generalised +=
                    self.slopes(i - 1, &cfg.modes).1 * normal[i - 1] - vr * friction[i - 1];
            }
            if i + 1 < n && (normal[i] != 0.0 || friction[i] != 0.0) {
                let vl = self.sliding_slopes(i, &cfg.modes, x).0;
                generalised += vl * friction[i] - self.slopes(i, &cfg.modes).0 * normal[i];
            }
            y[3 * i + 2] = a.generalised_mass() / a.kinetic_mass(mode) * generalised * qdot;
        }
        for c in 0..n - 1 {
            y[3 * n + c] = if normal[c] == 0.0 {
                0.0
            } else {
                normal[c] * self.closing(c, &cfg.modes, x)
            };
            y[4 * n - 1 + c] = if friction[c] == 0.0 {
                0.0
            } else {
                -friction[c] * self.sliding(c, &cfg.modes, x)
            };
        }
    }
}

fn failed(t: f64, message: impl std::fmt::Display) -> SolverError {
    SolverError::Failed {
        method: METHOD.to_string(),
        t,
        message: message.to_string(),
    }
}

/// Solves `row` (whose contact law must be compliant) on `floor` over [0, duration].
pub fn solve_row_compliant(
    row: &Row,
    floor: &dyn FloorMotion,
    duration: f64,
    settings: &CompliantSettings,
    history: History,
) -> Result<RowSolution> {
    let started = Instant::now();
    let ContactLaw::Compliant {
        stiffness,
        damping_ratio,
    } = row.law()
    else {
        return Err(failed(0.0, "the row's contact law is not compliant"));
    };
    let model = RowEquations {
        row,
        stiffness,
        zeta: damping_ratio,
        mu: row.friction(),
        atol: settings.atol,
    };
    let n = model.n();
    let nstates = 2 * n;
    let nout = 3 * n + 2 * (n - 1);
    let initial: Vec<f64> = row
        .columns()
        .iter()
        .flat_map(|c| [c.initial.q, c.initial.qdot])
        .collect();
    let cfg = RefCell::new(Config {
        modes: row
            .columns()
            .iter()
            .map(|c| c.automaton.initial_mode(c.initial.q))
            .collect(),
        active: vec![false; n - 1],
        damping: vec![0.0; n - 1],
        friction: vec![Friction::Off; n - 1],
    });
    let floor_cache = std::cell::Cell::new((f64::NAN, 0.0));
    let floor_acc = |t: f64| {
        let (t_cached, a_cached) = floor_cache.get();
        if t == t_cached {
            a_cached
        } else {
            let a = floor.acceleration(t);
            floor_cache.set((t, a));
            a
        }
    };
    let rhs_evaluations = std::cell::Cell::new(0usize);
    let scratch = RefCell::new((vec![0.0; nstates], vec![0.0; nout.max(nstates)]));
    let mut problem = OdeBuilder::<Matrix>::new()
        .t0(0.0)
        .rtol(settings.rtol)
        .atol(vec![settings.atol; nstates])
        .rhs_implicit(
            |x, _p, t, y| {
                rhs_evaluations.set(rhs_evaluations.get() + 1);
                let mut s = scratch.borrow_mut();
                let (xs, ys) = &mut *s;
                for (i, v) in xs.iter_mut().enumerate() {
                    *v = x[i];
                }
                model.rhs(&cfg.borrow(), xs, floor_acc(t), &mut ys[..nstates]);
                for (i, v) in ys[..nstates].iter().enumerate() {
                    y[i] = *v;
                }
            },
            |_x, _p, _t, v, y| {
                let mut s = scratch.borrow_mut();
                let (vs, ys) = &mut *s;
                for (i, value) in vs.iter_mut().enumerate() {
                    *value = v[i];
                }
                model.jacobian(&cfg.borrow(), vs, &mut ys[..nstates]);
                for (i, value) in ys[..nstates].iter().enumerate() {
                    y[i] = *value;
                }
            },
        )
        .init(
            |_p, _t, y| {
                for (i, v) in initial.iter().enumerate() {
                    y[i] = *v;
                }
            },
            nstates,
        )
        .out_implicit(
            |x, _p, t, y| {
                let mut s = scratch.borrow_mut();
                let (xs, ys) = &mut *s;
                for (i, v) in xs.iter_mut().enumerate() {
                    *v = x[i];
                }
                model.integrands(&cfg.borrow(), xs, floor_acc(t), &mut ys[..nout]);
                for (i, v) in ys[..nout].iter().enumerate() {
                    y[i] = *v;
                }
            },
            // The work integrals are quadratures of the accepted steps: an explicit method asks
            // for no derivative of them.
            |_x, _p, _t, _v, y| (0..nout).for_each(|i| y[i] = 0.0),
            nout,
        )
        .integrate_out(true)
        .build()
        .map_err(|e| failed(0.0, e))?;
    problem.ode_options.min_timestep = problem.ode_options.min_timestep.min(1e-3 * duration);
    let solver = problem.tsit45().map_err(|e| failed(0.0, e))?;
    let run = LoopSetup {
        method: METHOD,
        floor,
        vertical: None,
        duration,
        history,
        output_dt: settings.output_dt,
    };
    let modes = cfg.borrow().modes.clone();
    let mut body = Columns {
        model: &model,
        cfg: &cfg,
        floor,
        history,
        recorders: (0..n)
            .map(|i| {
                Recorder::new(
                    model.automaton(i),
                    0.0,
                    initial[2 * i],
                    initial[2 * i + 1],
                    modes[i],
                    history,
                )
            })
            .collect(),
        budgets: (0..n).map(|_| RunBudget::new()).collect(),
        stretches: Vec::new(),
        open: vec![None; n - 1],
        overturned: None,
        contact_history: Vec::new(),
        sticking: Vec::new(),
        stuck: vec![None; n - 1],
    };
    let finish = event_loop::run(&run, &mut body, solver)?;
    let final_time = finish.t;
    let stats = SolverStats {
        method: METHOD.to_string(),
        steps: finish.statistics.number_of_steps,
        error_test_failures: 0,
        nonlinear_iterations: 0,
        jacobian_evaluations: 0,
        crossing_retries: finish.crossing_retries,
        rhs_evaluations: rhs_evaluations.get(),
        wall_time_s: started.elapsed().as_secs_f64(),
    };
    let modes = cfg.borrow().modes.clone();
    let Columns {
        recorders,
        stretches,
        overturned,
        contact_history,
        sticking,
        ..
    } = body;
    let columns = recorders
        .into_iter()
        .zip(modes)
        .map(|(r, mode)| r.finish(final_time, mode, stats.clone()))
        .collect();
    Ok(RowSolution {
        columns,
        impacts: Vec::new(),
        impact_energy_loss: Vec::new(),
        overturned,
        held: Vec::new(),
        contacts: stretches,
        contact_history,
        sticking,
        final_time,
    })
}

/// What ends a step early.
#[derive(Debug, Clone, Copy)]
enum What {
    /// Column `.0` crosses a guard of its mode.
    Guard(usize, Guard),
    /// Contact `.0`'s faces meet (or, overlapping, its force rises through zero).
    Start(usize),
    /// Contact `.0`'s force falls through zero.
    End(usize),
    /// Contact `.0`'s faces: stick or slide, as the state says; with `Some(sign)`, start
    /// sliding that way (a sticking contact whose friction reached mu P).
    Friction(usize, Option<f64>),
}

/// The row, as the event loop drives it.
struct Columns<'d> {
    model: &'d RowEquations<'d>,
    cfg: &'d RefCell<Config>,
    floor: &'d dyn FloorMotion,
    history: History,
    recorders: Vec<Recorder<'d>>,
    budgets: Vec<RunBudget>,
    stretches: Vec<ContactStretch>,
    /// Per contact: the index of its open stretch and the integrals of what the spring and
    /// dashpot took and of what friction took, at its start.
    open: Vec<Option<(usize, f64, f64)>>,
    overturned: Option<(usize, f64)>,
    /// Every contact at every sampled instant.
    contact_history: Vec<ContactSample>,
    /// Every stretch of sticking faces, and per contact the index of the one under way.
    sticking: Vec<StickStretch>,
    stuck: Vec<Option<usize>>,
}

impl<'d> Columns<'d> {
    fn n(&self) -> usize {
        self.model.n()
    }

    /// q'' of every column at (t, x) in the current configuration.
    fn accelerations(&self, t: f64, x: &[f64]) -> Vec<f64> {
        let mut y = vec![0.0; x.len()];
        self.model
            .rhs(&self.cfg.borrow(), x, self.floor.acceleration(t), &mut y);
        y
    }

    /// The value and rate of the event function of `what` at `t`: q of a column, the gap of a
    /// free contact, the force of a contact.
    fn function(&self, dense: &dyn DenseOutput, t: f64, what: Watch) -> Result<(f64, f64)> {
        let x = dense.state_at(t)?;
        let cfg = self.cfg.borrow();
        Ok(match what {
            Watch::Q(i) => (x[2 * i], x[2 * i + 1]),
            Watch::Gap(c) => (
                -self.model.penetration(c, &cfg.modes, &x),
                -self.model.closing(c, &cfg.modes, &x),
            ),
            Watch::Force(c, damping) => {
                drop(cfg);
                let acc = self.accelerations(t, &x);
                let cfg = self.cfg.borrow();
                let (pl, pr) = self.model.slopes(c, &cfg.modes);
                let rate = self.model.stiffness * self.model.closing(c, &cfg.modes, &x)
                    + damping * (pl * acc[2 * c + 1] - pr * acc[2 * c + 3]);
                (self.model.force_with(c, &cfg.modes, damping, &x), rate)
            }
            Watch::Sliding(c) => {
                drop(cfg);
                let acc = self.accelerations(t, &x);
                let cfg = self.cfg.borrow();
                let (vl, vr) = self.model.sliding_slopes(c, &cfg.modes, &x);
                (
                    self.model.sliding(c, &cfg.modes, &x),
                    vl * acc[2 * c + 1] - vr * acc[2 * c + 3],
                )
            }
            Watch::Margin(c, sign, t0, t1) => {
                drop(cfg);
                let margin = |t: f64| -> Result<f64> {
                    let x = dense.state_at(t)?;
                    let cfg = self.cfg.borrow();
                    let forces = self.model.forces(&cfg, &x, self.floor.acceleration(t));
                    Ok(self.model.mu * forces.normal[c] - sign * forces.friction[c])
                };
                // Within a step the margin is smooth (linear in the state and the floor's
                // acceleration, both smooth between stops): a central difference on the dense
                // output, one-sided at the step's ends.
                let h = 1e-6 * (t1 - t0);
                let (lo, hi) = ((t - h).max(t0), (t + h).min(t1));
                let rate = if hi > lo {
                    (margin(hi)? - margin(lo)?) / (hi - lo)
                } else {
                    0.0
                };
                (margin(t)?, rate)
            }
        })
    }

    /// Finds the time in [lo, hi] at which `f` passes from its sign at `lo` (zero counts as that
    /// side) to its sign at `hi` ([`crate::integrate::sign_change::locate`]).
    fn locate(&self, lo: f64, hi: f64, f: impl Fn(f64) -> Result<f64>) -> Result<f64> {
        crate::integrate::sign_change::locate(lo, hi, f)
    }

    /// The monotone pieces of the function of `what` over [t0, t1]: split at the root of its
    /// rate, each with the direction it moves in, and the root itself (an extremum), if any.
    #[allow(clippy::type_complexity)]
    fn pieces(
        &self,
        dense: &dyn DenseOutput,
        t0: f64,
        t1: f64,
        what: Watch,
    ) -> Result<(Vec<(f64, f64, f64)>, Option<f64>)> {
        let d0 = self.function(dense, t0, what)?.1;
        let d1 = self.function(dense, t1, what)?.1;
        if d0 * d1 < 0.0 {
            let tp = self.locate(t0, t1, |t| Ok(self.function(dense, t, what)?.1))?;
            Ok((vec![(t0, tp, d0.signum()), (tp, t1, d1.signum())], Some(tp)))
        } else {
            let d = if d1 != 0.0 { d1 } else { d0 };
            Ok((
                vec![(t0, t1, if d == 0.0 { 0.0 } else { d.signum() })],
                None,
            ))
        }
    }

    /// The first crossing of zero by the function of `what` in `direction` (+1 rising, -1
    /// falling) over the step, found piece by piece; `Err(())` when its dense output put it
    /// where the rate points back.
    fn first_crossing_of(
        &self,
        dense: &dyn DenseOutput,
        t0: f64,
        t1: f64,
        what: Watch,
        level: f64,
        direction: f64,
    ) -> Result<std::result::Result<Option<f64>, ()>> {
        let (pieces, _) = self.pieces(dense, t0, t1, what)?;
        let over =
            |t: f64| -> Result<f64> { Ok(direction * (self.function(dense, t, what)?.0 - level)) };
        for (from, to, moving) in pieces {
            if moving != direction || over(to)? <= 0.0 {
                continue;
            }
            if over(from)? >= 0.0 {
                return Ok(Err(()));
            }
            let t = self.locate(from, to, over)?;
            if direction * self.function(dense, t, what)?.1 <= 0.0 {
                return Ok(Err(()));
            }
            return Ok(Ok(Some(t)));
        }
        Ok(Ok(None))
    }

    /// The first event of the step [start, t1]; `Unresolved` where the dense output cannot
    /// place one, or leaves a contact out of force overlapping and pressing before it.
    fn find_crossing(
        &self,
        dense: &dyn DenseOutput,
        start: &StepStart,
        t1: f64,
        grid: &OutputGrid,
    ) -> Result<Found<What>> {
        let n = self.n();
        let t0 = start.t;
        let mut first: Option<(f64, What)> = None;
        let mut consider = |t: f64, what: What| {
            if first.is_none_or(|(t_first, _)| t < t_first) {
                first = Some((t, what));
            }
        };
        let cfg = self.cfg.borrow().clone();
        for i in 0..n {
            let automaton = self.model.automaton(i);
            let mode = cfg.modes[i];
            let mut crossed = false;
            for &slot in automaton.guards(mode) {
                let guard = automaton.guard(mode, slot);
                match self.first_crossing_of(
                    dense,
                    t0,
                    t1,
                    Watch::Q(i),
                    guard.level,
                    guard.direction,
                )? {
                    Err(()) => return Ok(Found::Unresolved),
                    Ok(Some(t)) => {
                        crossed = true;
                        consider(t, What::Guard(i, guard));
                    }
                    Ok(None) => {}
                }
            }
            // The column must end inside its mode; if not, q turned more than once.
            let q1 = dense.state_at(t1)?[2 * i];
            if !crossed
                && automaton
                    .guards(mode)
                    .iter()
                    .any(|&slot| automaton.guard(mode, slot).overshoot(q1) > 0.0)
            {
                return Ok(Found::Unresolved);
            }
        }
        for c in 0..n - 1 {
            if cfg.active[c] {
                let watch = Watch::Force(c, cfg.damping[c]);
                // A contact whose force starts at zero or below is let go at once (settle).
                if let Ok(Some(t)) = self.first_crossing_of(dense, t0, t1, watch, 0.0, -1.0)? {
                    consider(t, What::End(c));
                }
                match cfg.friction[c] {
                    Friction::Off => {}
                    // Sliding faces that come to a stop: stick, or slide back.
                    Friction::Slip(sign) => {
                        let x0 = dense.state_at(t0)?;
                        let level = -sign * self.model.sliding_tolerance(c, &cfg.modes, &x0);
                        let watch = Watch::Sliding(c);
                        match self.first_crossing_of(dense, t0, t1, watch, level, -sign)? {
                            Ok(Some(t)) => consider(t, What::Friction(c, None)),
                            Ok(None) => {}
                            Err(()) => {
                                if -sign * (self.function(dense, t0, watch)?.0 - level) >= 0.0 {
                                    // Past the stop already at the step's start: look again
                                    // there, unless the answer is the state it has (which would
                                    // stop the run at the same instant without end).
                                    if self.friction_state(c, t0, &x0) != cfg.friction[c] {
                                        consider(t0, What::Friction(c, None));
                                    }
                                } else {
                                    return Ok(Found::Unresolved);
                                }
                            }
                        }
                    }
                    // Sticking faces whose friction reaches mu P: slide.
                    Friction::Stick => {
                        for sign in [1.0, -1.0] {
                            let watch = Watch::Margin(c, sign, t0, t1);
                            match self.first_crossing_of(dense, t0, t1, watch, 0.0, -1.0)? {
                                Ok(Some(t)) => consider(t, What::Friction(c, Some(-sign))),
                                Ok(None) => {}
                                Err(()) => {
                                    if self.function(dense, t0, watch)?.0 <= 0.0 {
                                        consider(t0, What::Friction(c, Some(-sign)));
                                    } else {
                                        return Ok(Found::Unresolved);
                                    }
                                }
                            }
                        }
                    }
                }
            } else {
                let x0 = dense.state_at(t0)?;
                // Faces that touch and press at the step's start (a closing a hair too late,
                // found at the end of the step before): in contact there.
                if self.model.presses(c, &cfg.modes, &x0) {
                    consider(t0, What::Start(c));
                    continue;
                }
                let overlapping = |t: f64| -> Result<bool> {
                    Ok(self.function(dense, t, Watch::Gap(c))?.0 < 0.0)
                };
                let parting = overlapping(t0)?;
                match self.first_crossing_of(dense, t0, t1, Watch::Gap(c), 0.0, -1.0)? {
                    Ok(Some(t)) => consider(t, What::Start(c)),
                    Ok(None) => {}
                    // Faces that still overlap after a release open their gap from below
                    // zero: the force's search below finds where they press again.
                    Err(()) if parting => {}
                    Err(()) => return Ok(Found::Unresolved),
                }
                // Faces that still overlap after a release: contact again where the force
                // would push.
                if parting {
                    let watch = Watch::Force(c, self.model.dashpot(c, &cfg.modes));
                    match self.first_crossing_of(dense, t0, t1, watch, 0.0, 1.0)? {
                        Ok(Some(t)) => {
                            if overlapping(t)? {
                                consider(t, What::Start(c));
                            }
                        }
                        Ok(None) => {}
                        // Overlapping with a force just at zero at the step's start.
                        Err(()) if self.model.force_if_started(c, &cfg.modes, &x0) >= 0.0 => {
                            consider(t0, What::Start(c));
                        }
                        Err(()) => return Ok(Found::Unresolved),
                    }
                }
            }
        }
        // No contact out of force may be left overlapping and pressing before the first event
        // (at the step's end, or at a sample of the history within it): a closing the search
        // did not see, where the closing velocity turned more than once within the step. The
        // step is taken again, shorter.
        let until = first.map_or(t1, |(t, _)| t);
        let mut times: Vec<f64> = Vec::new();
        let mut samples = grid.clone();
        while let Some(ts) = samples.peek() {
            if ts >= until {
                break;
            }
            if ts > t0 {
                times.push(ts);
            }
            samples.advance();
        }
        if first.is_none() {
            times.push(t1);
        }
        for ts in times {
            let x = dense.state_at(ts)?;
            for c in (0..n - 1).filter(|&c| !cfg.active[c]) {
                if self.model.idle_state(c, &cfg.modes, &x, ts, 0.0).is_err() {
                    return Ok(Found::Unresolved);
                }
            }
        }
        Ok(match first {
            Some((t, what)) => Found::At(t, what),
            None => Found::None,
        })
    }

    /// Books the peaks of q of every column and the peak forces of the contacts within
    /// [start, until].
    fn peaks(&mut self, dense: &dyn DenseOutput, start: &StepStart, until: f64) -> Result<()> {
        if until <= start.t {
            return Ok(());
        }
        let cfg = self.cfg.borrow().clone();
        for i in 0..self.n() {
            if let (_, Some(tp)) = self.pieces(dense, start.t, until, Watch::Q(i))? {
                let q = dense.state_at(tp)?[2 * i];
                self.recorders[i].peak_candidate(tp, q);
            }
        }
        for c in 0..self.n() - 1 {
            if !cfg.active[c] {
                continue;
            }
            let watch = Watch::Force(c, cfg.damping[c]);
            let (_, root) = self.pieces(dense, start.t, until, watch)?;
            for t in root.into_iter().chain([until]) {
                let p = self.function(dense, t, watch)?.0;
                self.force_candidate(c, t, p);
                if cfg.friction[c] != Friction::Off {
                    let x = dense.state_at(t)?;
                    let f = self
                        .model
                        .forces(&cfg, &x, self.floor.acceleration(t))
                        .friction[c];
                    if let Some((k, _, _)) = self.open[c] {
                        let s = &mut self.stretches[k];
                        s.peak_friction_force = s.peak_friction_force.max(f.abs());
                    }
                }
            }
        }
        Ok(())
    }

    fn force_candidate(&mut self, c: usize, t: f64, p: f64) {
        if let Some((k, _, _)) = self.open[c] {
            let s = &mut self.stretches[k];
            if p > s.peak_force {
                s.peak_force = p;
                s.t_peak_force = t;
            }
        }
    }

    /// Applies `what` at `t` to the state `y` with work integrals `g`, then whatever else the
    /// new state asks for at the same instant: a guard crossed by the start, a contact whose
    /// force is not compressive after a reset, a contact whose faces touch and would press.
    /// Stops the run when a column overturned.
    fn settle(&mut self, t: f64, y: &[f64], g: &[f64], what: Option<What>) -> Result<Outcome> {
        let n = self.n();
        let mut y = y.to_vec();
        let mut next = what;
        let mut started_now = vec![false; n - 1];
        let mut pending: Vec<usize> = Vec::new();
        for _ in 0..MAX_CHAIN * n {
            match next {
                Some(What::Guard(i, guard)) => {
                    let automaton = self.model.automaton(i);
                    let from = self.cfg.borrow().modes[i];
                    let before = y[2 * i + 1];
                    let after = automaton.reset_velocity(guard.kind, before);
                    y[2 * i] = guard.level;
                    y[2 * i + 1] = after;
                    self.recorders[i].set_contact_work(g[3 * i + 2]);
                    self.recorders[i].event(
                        t,
                        guard.kind,
                        from,
                        guard.to,
                        guard.level,
                        before,
                        after,
                        self.floor.acceleration(t),
                        g[3 * i],
                        g[3 * i + 1],
                    );
                    self.budgets[i].event(t).map_err(|m| failed(t, m))?;
                    self.cfg.borrow_mut().modes[i] = guard.to;
                    if guard.to == Mode::Overturned {
                        // The run ends here for every column: the state here may be a peak.
                        for (j, r) in self.recorders.iter_mut().enumerate() {
                            if j != i {
                                r.peak_candidate(t, y[2 * j]);
                            }
                        }
                        self.overturned = Some((i, t));
                        self.close_open(g);
                        return Ok(Outcome::Stop);
                    }
                }
                Some(What::Start(c)) => {
                    let modes = self.cfg.borrow().modes.clone();
                    let damping = self.model.dashpot(c, &modes);
                    {
                        let mut cfg = self.cfg.borrow_mut();
                        cfg.active[c] = true;
                        cfg.damping[c] = damping;
                    }
                    started_now[c] = true;
                    let closing = self.model.closing(c, &modes, &y);
                    self.stretches.push(ContactStretch {
                        contact: c,
                        t_start: t,
                        t_end: None,
                        reduced_mass: self.model.reduced_mass(c, &modes),
                        damping,
                        closing_velocity: closing,
                        separating_velocity: None,
                        peak_force: 0.0,
                        t_peak_force: t,
                        energy_dissipated: 0.0,
                        friction_dissipated: 0.0,
                        peak_friction_force: 0.0,
                        friction_changes: 0,
                    });
                    self.open[c] = Some((self.stretches.len() - 1, g[3 * n + c], g[4 * n - 1 + c]));
                    let p = self.model.force_with(c, &modes, damping, &y);
                    self.force_candidate(c, t, p);
                    self.contact_events(c, t, EventKind::ContactStart, &y, g)?;
                    // With friction, the faces meet sliding or sticking: an event of its own.
                    if self.model.mu > 0.0 {
                        let state = self.friction_state(c, t, &y);
                        self.set_friction(c, t, state);
                        let kind = if state == Friction::Stick {
                            EventKind::FrictionStick
                        } else {
                            EventKind::FrictionSlip
                        };
                        self.contact_events(c, t, kind, &y, g)?;
                    }
                }
                Some(What::End(c)) => {
                    self.end_contact(c, t, &y, g)?;
                }
                Some(What::Friction(c, slide)) => {
                    let state = match slide {
                        Some(sign) => Friction::Slip(sign),
                        None => self.friction_state(c, t, &y),
                    };
                    let before = self.cfg.borrow().friction[c];
                    if state != before {
                        self.set_friction(c, t, state);
                        if let Some((k, _, _)) = self.open[c] {
                            self.stretches[k].friction_changes += 1;
                        }
                        let kind = if state == Friction::Stick {
                            EventKind::FrictionStick
                        } else {
                            EventKind::FrictionSlip
                        };
                        self.contact_events(c, t, kind, &y, g)?;
                    }
                }
                None => {}
            }
            // A column's reset changes its q' and its faces' slopes: its contacts' friction is
            // looked at again.
            if let Some(What::Guard(i, _)) = next {
                for c in [i.checked_sub(1), Some(i)].into_iter().flatten() {
                    if c + 1 < n && self.cfg.borrow().active[c] && self.model.mu > 0.0 {
                        pending.push(c);
                    }
                }
            }
            // What the state asks for at once: a guard it sits on moving across, a contact
            // whose force is not compressive (one just started is not let go at its start).
            next = None;
            let cfg = self.cfg.borrow().clone();
            for i in 0..n {
                if let Some(guard) =
                    self.model
                        .automaton(i)
                        .crossed_guard(cfg.modes[i], y[2 * i], y[2 * i + 1])
                {
                    next = Some(What::Guard(i, guard));
                    break;
                }
            }
            if next.is_none() {
                next = (0..n - 1)
                    .find(|&c| {
                        cfg.active[c]
                            && !started_now[c]
                            && self.model.force_with(c, &cfg.modes, cfg.damping[c], &y) <= 0.0
                    })
                    .map(What::End);
            }
            // Every contact whose faces touch or overlap and would press starts, whatever else
            // happened at this instant (two contacts closing together, a reset that turns
            // parting faces back onto each other).
            if next.is_none() {
                next = (0..n - 1)
                    .find(|&c| !cfg.active[c] && self.model.presses(c, &cfg.modes, &y))
                    .map(What::Start);
            }
            if next.is_none() {
                next = pending.pop().map(|c| What::Friction(c, None));
            }
            if next.is_none() && self.model.mu > 0.0 {
                next = self.friction_due(t, &y);
            }
            if next.is_none() {
                return Ok(Outcome::Restart(y));
            }
        }
        Err(failed(t, "endless chain of events at one instant"))
    }

    /// Books the event `kind` (contact start or end) in both columns of contact `c`.
    fn contact_events(
        &mut self,
        c: usize,
        t: f64,
        kind: EventKind,
        y: &[f64],
        g: &[f64],
    ) -> Result<()> {
        let modes = self.cfg.borrow().modes.clone();
        for i in [c, c + 1] {
            self.recorders[i].set_contact_work(g[3 * i + 2]);
            self.recorders[i].event(
                t,
                kind,
                modes[i],
                modes[i],
                y[2 * i],
                y[2 * i + 1],
                y[2 * i + 1],
                self.floor.acceleration(t),
                g[3 * i],
                g[3 * i + 1],
            );
            self.budgets[i].event(t).map_err(|m| failed(t, m))?;
        }
        Ok(())
    }

    /// Books every contact at the sampled instant `t`, state `y`; an error where a contact out
    /// of force is left overlapping and pressing ([`RowEquations::idle_state`]).
    fn sample_contacts(&mut self, t: f64, y: &[f64], floor_acc: f64) -> Result<()> {
        let cfg = self.cfg.borrow();
        let forces = self.model.forces(&cfg, y, floor_acc);
        for c in 0..self.n() - 1 {
            let state = match (cfg.active[c], cfg.friction[c]) {
                (false, _) => self
                    .model
                    .idle_state(c, &cfg.modes, y, t, OVERLAP_ERROR_SHARE)?,
                (true, Friction::Off) => ContactState::Pressing,
                (true, Friction::Slip(_)) => ContactState::Sliding,
                (true, Friction::Stick) => ContactState::Sticking,
            };
            self.contact_history.push(ContactSample {
                t,
                contact: c,
                state,
                gap: -self.model.penetration(c, &cfg.modes, y),
                closing_velocity: self.model.closing(c, &cfg.modes, y),
                sliding_velocity: self.model.sliding(c, &cfg.modes, y),
                force: Some(forces.normal[c]),
                friction_force: Some(forces.friction[c]),
            });
        }
        Ok(())
    }

    /// Lets contact `c` go at `t`.
    fn end_contact(&mut self, c: usize, t: f64, y: &[f64], g: &[f64]) -> Result<()> {
        let n = self.n();
        self.cfg.borrow_mut().active[c] = false;
        self.set_friction(c, t, Friction::Off);
        let modes = self.cfg.borrow().modes.clone();
        if let Some((k, dissipation, friction)) = self.open[c].take() {
            let s = &mut self.stretches[k];
            s.t_end = Some(t);
            s.separating_velocity = Some(-self.model.closing(c, &modes, y));
            s.energy_dissipated = g[3 * n + c] - dissipation;
            s.friction_dissipated = g[4 * n - 1 + c] - friction;
        }
        self.contact_events(c, t, EventKind::ContactEnd, y, g)
    }

    /// Closes the books of the stretches still open at the end of the run.
    fn close_open(&mut self, g: &[f64]) {
        let n = self.n();
        for c in 0..n - 1 {
            if let Some((k, dissipation, friction)) = self.open[c].take() {
                self.stretches[k].energy_dissipated = g[3 * n + c] - dissipation;
                self.stretches[k].friction_dissipated = g[4 * n - 1 + c] - friction;
            }
        }
    }

    /// Sets contact `c`'s friction to `state` at `t`, keeping the stretches of sticking.
    fn set_friction(&mut self, c: usize, t: f64, state: Friction) {
        self.cfg.borrow_mut().friction[c] = state;
        if state == Friction::Stick {
            if self.stuck[c].is_none() {
                self.sticking.push(StickStretch {
                    contact: c,
                    t_start: t,
                    t_end: None,
                });
                self.stuck[c] = Some(self.sticking.len() - 1);
            }
        } else if let Some(k) = self.stuck[c].take() {
            self.sticking[k].t_end = Some(t);
        }
    }

    /// A change of friction the state at (t, `y`) asks for at once: sticking faces whose
    /// friction exceeds mu P, sliding faces that slide the other way.
    fn friction_due(&self, t: f64, y: &[f64]) -> Option<What> {
        let cfg = self.cfg.borrow();
        let forces = self.model.forces(&cfg, y, self.floor.acceleration(t));
        (0..self.n() - 1).find_map(|c| match cfg.friction[c] {
            Friction::Off => None,
            Friction::Stick => {
                let f = forces.friction[c];
                (f.abs() > self.model.mu * forces.normal[c])
                    .then_some(What::Friction(c, Some(-f.signum())))
            }
            Friction::Slip(sign) => {
                let tolerance = self.model.sliding_tolerance(c, &cfg.modes, y);
                (sign * self.model.sliding(c, &cfg.modes, y) < -2.0 * tolerance)
                    .then_some(What::Friction(c, None))
            }
        })
    }

    /// Whether the faces of contact `c` (in force) stick or slide at (t, `y`): sliding faces
    /// slide on; faces not sliding stick if the friction that keeps them so is within mu P,
    /// and otherwise start sliding the way that friction would have to push against.
    fn friction_state(&self, c: usize, t: f64, y: &[f64]) -> Friction {
        let mut cfg = self.cfg.borrow().clone();
        let sigma = self.model.sliding(c, &cfg.modes, y);
        if sigma.abs() > 2.0 * self.model.sliding_tolerance(c, &cfg.modes, y) {
            return Friction::Slip(sigma.signum());
        }
        cfg.friction[c] = Friction::Stick;
        let forces = self.model.forces(&cfg, y, self.floor.acceleration(t));
        let (p, f) = (forces.normal[c], forces.friction[c]);
        if f.abs() <= self.model.mu * p {
            Friction::Stick
        } else {
            Friction::Slip(-f.signum())
        }
    }
}

impl EventBody for Columns<'_> {
    type Event = What;

    fn derivatives(&self, t: f64, y: &[f64], dy: &mut [f64], dg: &mut [f64]) {
        let floor_acc = self.floor.acceleration(t);
        let cfg = self.cfg.borrow();
        self.model.rhs(&cfg, y, floor_acc, dy);
        self.model.integrands(&cfg, y, floor_acc, dg);
    }

    fn find_event(
        &mut self,
        dense: &dyn DenseOutput,
        start: &StepStart,
        t1: f64,
        grid: &OutputGrid,
    ) -> Result<Found<What>> {
        self.find_crossing(dense, start, t1, grid)
    }

    fn book_step(&mut self, dense: &dyn DenseOutput, start: &StepStart, until: f64) -> Result<()> {
        self.peaks(dense, start, until)
    }

    fn apply(&mut self, t: f64, y: &[f64], g: &[f64], event: Option<What>) -> Result<Outcome> {
        self.settle(t, y, g, event)
    }

    /// Samples every column, and every contact when the history is kept.
    fn sample(&mut self, t: f64, y: &[f64], g: &[f64]) -> Result<()> {
        let floor_acc = self.floor.acceleration(t);
        let modes = self.cfg.borrow().modes.clone();
        if self.history == History::Sampled {
            self.sample_contacts(t, y, floor_acc)?;
        }
        for (i, r) in self.recorders.iter_mut().enumerate() {
            r.set_contact_work(g[3 * i + 2]);
            r.sample(
                t,
                modes[i],
                y[2 * i],
                y[2 * i + 1],
                floor_acc,
                g[3 * i],
                g[3 * i + 1],
            );
        }
        Ok(())
    }

    /// Offers every column's end state as a peak and closes the books of the open contacts.
    fn finish(&mut self, t: f64, y: &[f64], g: &[f64]) {
        for (i, r) in self.recorders.iter_mut().enumerate() {
            r.peak_candidate(t, y[2 * i]);
        }
        self.close_open(g);
    }
}

/// The function an event is found on.
#[derive(Debug, Clone, Copy)]
enum Watch {
    /// q of a column.
    Q(usize),
    /// The gap of a contact.
    Gap(usize),
    /// The force of a contact, with its dashpot.
    Force(usize, f64),
    /// The sliding speed sigma of a contact's faces.
    Sliding(usize),
    /// mu P - sign T of a sticking contact: how far its friction is from the most it can be,
    /// with its rate taken on the dense output of the step (t0, t1).
    Margin(usize, f64, f64, f64),
}
