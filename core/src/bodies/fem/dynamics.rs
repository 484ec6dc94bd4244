//! Time stepping with base contact and friction (see the module documentation of `fem`).

use std::collections::HashMap;
use std::f64::consts::PI;

use super::assembly::Assembly;
use super::banded::{BandedLdl, BandedSym};
use super::body::{validate_body, FemBody};
use super::decomposition::decompose;
use super::error::FemError;
use super::frequencies::{critical_time_step, highest_frequency_of};
use super::results::{ContactEvent, ContactState, FemResult, FemStep, Snapshot};
use super::settings::{validate_settings, FemSettings, TimeScheme};

/// Most friction re-solves within one step.
const FRICTION_ITERATIONS: usize = 10;
/// Most distinct constraint patterns kept factorised (fewer on large meshes: see
/// [`super::FACTOR_CACHE_BYTES`]).
const FACTOR_CACHE_SIZE: usize = 256;

/// Runs the dynamic analysis: static gravity first, then the floor acceleration
/// `floor_acc(t)` (m/s², horizontal) from t = 0 to `settings.duration`.
///
/// Returns an error for invalid input or when the solution diverges (for instance when dt
/// exceeds the stability limit of a conditionally stable scheme, see
/// [`FemResult::critical_time_step`]). A run stops early, without error, when |q| exceeds the
/// width (overturning, [`FemResult::overturned_at`]).
pub fn simulate_fem(
    body: &FemBody,
    settings: &FemSettings,
    floor_acc: &dyn Fn(f64) -> f64,
) -> Result<FemResult, FemError> {
    validate_body(body)?;
    validate_settings(settings)?;
    let model = Assembly::build(body, settings.nx, settings.ny)?;
    let omega_max = highest_frequency_of(&model)?;
    let mut run = FemRun::new(&model, body, settings, floor_acc)?;
    let mut result = FemResult {
        steps: Vec::new(),
        events: Vec::new(),
        snapshots: Vec::new(),
        node_coordinates: model.mesh.coords.clone(),
        static_reactions: model.static_reactions.clone(),
        highest_frequency: omega_max,
        critical_time_step: critical_time_step(settings.scheme, omega_max),
        overturned_at: None,
    };
    let mut snapshot_times = settings.snapshot_times.clone();
    snapshot_times.sort_by(f64::total_cmp);
    let mut next_snapshot = 0;

    let steps = (settings.duration / settings.dt + 1e-9).floor() as usize;
    result.steps.reserve(steps + 1);
    for n in 0..=steps {
        if n > 0 {
            run.advance(n as f64 * settings.dt)?;
        }
        let lowest = run.lowest_base_uy();
        run.apply_state_changes(&mut result.events);
        let step = run.record(lowest);
        while next_snapshot < snapshot_times.len()
            && snapshot_times[next_snapshot] <= step.t + 1e-9 * settings.dt
        {
            result.snapshots.push(Snapshot {
                requested: snapshot_times[next_snapshot],
                t: step.t,
                displacements: run.u.chunks(2).map(|c| [c[0], c[1]]).collect(),
            });
            next_snapshot += 1;
        }
        let overturned = step.q.abs() > body.width;
        let t = step.t;
        result.steps.push(step);
        if overturned {
            result.overturned_at = Some(t);
            break;
        }
    }
    Ok(result)
}

/// Integration constants of one displacement-form linear-acceleration/Newmark solve over τ.
#[derive(Debug, Clone, Copy)]
struct StepRule {
    beta: f64,
    gamma: f64,
    tau: f64,
    /// Wilson θ (1 for Newmark).
    theta: f64,
}

impl StepRule {
    fn a0(&self) -> f64 {
        1.0 / (self.beta * self.tau * self.tau)
    }
    fn a1(&self) -> f64 {
        self.gamma / (self.beta * self.tau)
    }
}

struct FemRun<'a> {
    model: &'a Assembly,
    settings: &'a FemSettings,
    floor_acc: &'a dyn Fn(f64) -> f64,
    rule: StepRule,
    tangent: BandedSym,
    damping: BandedSym,
    effective: BandedSym,
    constant_load: Vec<f64>,
    factors: HashMap<Vec<bool>, BandedLdl>,
    base_nodes: usize,
    t: f64,
    u: Vec<f64>,
    v: Vec<f64>,
    a: Vec<f64>,
    /// Load vector at the current time (needed by Wilson θ).
    load: Vec<f64>,
    states: Vec<ContactState>,
    /// Horizontal position held by Fixed nodes, m.
    held_x: Vec<f64>,
    /// Friction direction s (±1) of slipping nodes.
    friction_sign: Vec<f64>,
    /// Friction force on slipping nodes, N.
    friction: Vec<f64>,
    /// Reactions (Rx, Ry) of the base nodes at the current time, N.
    reactions: Vec<[f64; 2]>,
}

impl<'a> FemRun<'a> {
    fn new(
        model: &'a Assembly,
        body: &FemBody,
        settings: &'a FemSettings,
        floor_acc: &'a dyn Fn(f64) -> f64,
    ) -> Result<Self, FemError> {
        let rule = match settings.scheme {
            TimeScheme::Newmark { beta, gamma } => StepRule {
                beta,
                gamma,
                tau: settings.dt,
                theta: 1.0,
            },
            TimeScheme::WilsonTheta { theta } => StepRule {
                beta: 1.0 / 6.0,
                gamma: 0.5,
                tau: theta * settings.dt,
                theta,
            },
        };
        let tangent = model.tangent(settings.p_delta);
        let damping = model
            .stiffness
            .scaled(body.damping_ratio * body.damping_period / PI);
        let mut effective = tangent.clone();
        effective.add_scaled(&damping, rule.a1());
        for (d, m) in model.mass.iter().enumerate() {
            effective.add(d, d, rule.a0() * m);
        }
        let base_nodes = model.mesh.nx + 1;
        let n = model.mesh.dof_count();
        let mut u = model.static_displacement.clone();
        let mut states = vec![ContactState::Fixed; base_nodes];
        let rotation = settings.initial_rotation;
        if rotation != 0.0 {
            // rigid rotation (clockwise positive) about the toe it tips over
            let (toe_x, toe) = if rotation > 0.0 {
                (body.width, base_nodes - 1)
            } else {
                (0.0, 0)
            };
            for (node, c) in model.mesh.coords.iter().enumerate() {
                u[2 * node] += rotation * c[1];
                u[2 * node + 1] += rotation * (toe_x - c[0]);
            }
            for (i, s) in states.iter_mut().enumerate() {
                if i != toe {
                    *s = ContactState::Free;
                }
            }
        }
        let held_x = (0..base_nodes).map(|i| u[2 * i]).collect();
        let mut run = Self {
            model,
            settings,
            floor_acc,
            rule,
            tangent,
            damping,
            effective,
            constant_load: model.constant_load(settings.p_delta),
            factors: HashMap::new(),
            base_nodes,
            t: 0.0,
            u,
            v: vec![0.0; n],
            a: vec![0.0; n],
            load: Vec::new(),
            states,
            held_x,
            friction_sign: vec![0.0; base_nodes],
            friction: vec![0.0; base_nodes],
            reactions: vec![[0.0; 2]; base_nodes],
        };
        // initial acceleration of the unconstrained dofs from equilibrium at rest
        run.load = run.load_at(0.0);
        let constrained = run.constrained_dofs();
        let mut internal = vec![0.0; n];
        run.tangent.mul_vec(&run.u, &mut internal);
        for d in 0..n {
            run.a[d] = if constrained[d] {
                0.0
            } else {
                (run.load[d] - internal[d]) / model.mass[d]
            };
        }
        run.update_reactions();
        Ok(run)
    }

    fn load_at(&self, t: f64) -> Vec<f64> {
        let mut f = self.constant_load.clone();
        let acc = (self.floor_acc)(t);
        for node in 0..self.model.mesh.node_count() {
            f[2 * node] -= self.model.mass[2 * node] * acc;
        }
        for (i, s) in self.states.iter().enumerate() {
            if *s == ContactState::Slip {
                f[2 * i] += self.friction[i];
            }
        }
        f
    }

    fn constrained_dofs(&self) -> Vec<bool> {
        let mut c = vec![false; self.model.mesh.dof_count()];
        for (i, s) in self.states.iter().enumerate() {
            match s {
                ContactState::Free => {}
                ContactState::Slip => c[2 * i + 1] = true,
                ContactState::Fixed => {
                    c[2 * i] = true;
                    c[2 * i + 1] = true;
                }
            }
        }
        c
    }

    /// Prescribed displacement of a constrained base dof.
    fn prescribed(&self, dof: usize) -> f64 {
        if dof.is_multiple_of(2) {
            self.held_x[dof / 2]
        } else {
            0.0
        }
    }

    fn factors_for(&mut self, constrained: &[bool]) -> Result<&BandedLdl, FemError> {
        let key = constrained[..2 * self.base_nodes].to_vec();
        if !self.factors.contains_key(&key) {
            let factor_bytes = 8.0 * (self.effective.n * (self.effective.hb + 1)) as f64;
            let capacity =
                ((super::FACTOR_CACHE_BYTES / factor_bytes) as usize).clamp(1, FACTOR_CACHE_SIZE);
            if self.factors.len() >= capacity {
                self.factors.clear();
            }
            let f = BandedLdl::factor(&self.effective.with_identity_rows(constrained))?;
            self.factors.insert(key.clone(), f);
        }
        Ok(&self.factors[&key])
    }

    /// Advances from the current time to `t_next`.
    fn advance(&mut self, t_next: f64) -> Result<(), FemError> {
        let n = self.u.len();
        let rule = self.rule;
        let (a0, a1) = (rule.a0(), rule.a1());
        let tau = rule.tau;
        let constrained = self.constrained_dofs();
        let u_star: Vec<f64> = (0..n)
            .map(|d| self.u[d] + tau * self.v[d] + tau * tau * (0.5 - rule.beta) * self.a[d])
            .collect();
        let v_star: Vec<f64> = (0..n)
            .map(|d| self.v[d] + tau * (1.0 - rule.gamma) * self.a[d])
            .collect();
        // part of the right-hand side that does not depend on the load
        let mut history = vec![0.0; n];
        let c_arg: Vec<f64> = (0..n).map(|d| a1 * u_star[d] - v_star[d]).collect();
        self.damping.mul_vec(&c_arg, &mut history);
        for d in 0..n {
            history[d] += a0 * self.model.mass[d] * u_star[d];
        }
        let slipping = self.states.contains(&ContactState::Slip);
        let hb = self.effective.hb;
        let base_dofs = 2 * self.base_nodes;
        let (mut u_new, mut v_new, mut a_new) = (vec![0.0; n], vec![0.0; n], vec![0.0; n]);
        let mut load_next = Vec::new();
        for _ in 0..FRICTION_ITERATIONS {
            load_next = self.load_at(t_next);
            let mut rhs: Vec<f64> = (0..n)
                .map(|d| {
                    let target = if rule.theta == 1.0 {
                        load_next[d]
                    } else {
                        self.load[d] + rule.theta * (load_next[d] - self.load[d])
                    };
                    target + history[d]
                })
                .collect();
            for p in (0..base_dofs).filter(|&p| constrained[p]) {
                let value = self.prescribed(p);
                if value != 0.0 {
                    for (i, r) in rhs
                        .iter_mut()
                        .enumerate()
                        .take((p + hb + 1).min(n))
                        .skip(p.saturating_sub(hb))
                    {
                        *r -= self.effective.get(i, p) * value;
                    }
                }
            }
            for p in (0..base_dofs).filter(|&p| constrained[p]) {
                rhs[p] = self.prescribed(p);
            }
            self.factors_for(&constrained)?.solve_in_place(&mut rhs);
            for d in 0..n {
                let acc = a0 * (rhs[d] - u_star[d]);
                if rule.theta == 1.0 {
                    u_new[d] = rhs[d];
                    a_new[d] = acc;
                    v_new[d] = v_star[d] + rule.gamma * tau * acc;
                } else {
                    let dt = tau / rule.theta;
                    a_new[d] = self.a[d] + (acc - self.a[d]) / rule.theta;
                    v_new[d] = self.v[d] + dt / 2.0 * (self.a[d] + a_new[d]);
                    u_new[d] =
                        self.u[d] + dt * self.v[d] + dt * dt / 6.0 * (2.0 * self.a[d] + a_new[d]);
                }
                if constrained[d] {
                    u_new[d] = self.prescribed(d);
                    v_new[d] = 0.0;
                    a_new[d] = 0.0;
                }
            }
            if !slipping {
                break;
            }
            // friction of slipping nodes from their new normal reaction
            let reactions = self.reactions_of(&u_new, &v_new, &a_new, &load_next);
            let mut change = 0.0_f64;
            let mut scale = 0.0_f64;
            for (i, reaction) in reactions.iter().enumerate() {
                if self.states[i] == ContactState::Slip {
                    let f = self.friction_sign[i] * self.settings.mu_k * reaction[1].max(0.0);
                    change = change.max((f - self.friction[i]).abs());
                    scale = scale.max(f.abs());
                    self.friction[i] = f;
                }
            }
            if change <= 1e-10 * scale.max(1e-9) {
                load_next = self.load_at(t_next);
                break;
            }
        }
        if u_new.iter().any(|x| !x.is_finite() || x.abs() > 1e6) {
            return Err(FemError::Diverged { t: t_next });
        }
        self.u = u_new;
        self.v = v_new;
        self.a = a_new;
        self.load = load_next;
        self.t = t_next;
        self.update_reactions();
        Ok(())
    }

    /// Base reactions (Rx, Ry): the residual M a + C v + K_t u - F of the base dofs.
    /// For a slipping node Rx is the friction force.
    fn reactions_of(&self, u: &[f64], v: &[f64], a: &[f64], load: &[f64]) -> Vec<[f64; 2]> {
        let row = |m: &BandedSym, i: usize, x: &[f64]| -> f64 {
            let lo = i.saturating_sub(m.hb);
            let hi = (i + m.hb + 1).min(m.n);
            (lo..hi).map(|j| m.get(i, j) * x[j]).sum()
        };
        (0..self.base_nodes)
            .map(|node| {
                let mut r = [0.0; 2];
                for (k, rk) in r.iter_mut().enumerate() {
                    let d = 2 * node + k;
                    *rk = self.model.mass[d] * a[d]
                        + row(&self.damping, d, v)
                        + row(&self.tangent, d, u)
                        - load[d];
                }
                if self.states[node] == ContactState::Slip {
                    r[0] = self.friction[node];
                }
                if self.states[node] == ContactState::Free {
                    r = [0.0; 2];
                }
                r
            })
            .collect()
    }

    fn update_reactions(&mut self) {
        self.reactions = self.reactions_of(&self.u, &self.v, &self.a, &self.load);
    }

    fn lowest_base_uy(&self) -> f64 {
        (0..self.base_nodes)
            .map(|i| self.u[2 * i + 1])
            .fold(f64::INFINITY, f64::min)
    }

    /// The paper's state-change rules, decided at the current step, effective from the next.
    fn apply_state_changes(&mut self, events: &mut Vec<ContactEvent>) {
        for i in 0..self.base_nodes {
            let [rx, ry] = self.reactions[i];
            let (ux, uy, vx) = (self.u[2 * i], self.u[2 * i + 1], self.v[2 * i]);
            let from = self.states[i];
            let to = match from {
                ContactState::Free if uy <= 0.0 => ContactState::Fixed,
                ContactState::Fixed | ContactState::Slip if ry < 0.0 => ContactState::Free,
                ContactState::Fixed if rx.abs() > self.settings.mu_s * ry => ContactState::Slip,
                ContactState::Slip if self.friction_sign[i] * vx >= 0.0 => ContactState::Fixed,
                s => s,
            };
            if to == from {
                continue;
            }
            events.push(ContactEvent {
                t: self.t,
                node: i,
                from,
                to,
                rx,
                ry,
            });
            self.states[i] = to;
            match to {
                ContactState::Fixed => {
                    // landing or sticking: the node stops where it is (plastic impact)
                    self.u[2 * i + 1] = 0.0;
                    self.held_x[i] = ux;
                    for d in [2 * i, 2 * i + 1] {
                        self.v[d] = 0.0;
                        self.a[d] = 0.0;
                    }
                }
                ContactState::Slip => {
                    self.friction_sign[i] = if rx >= 0.0 { 1.0 } else { -1.0 };
                    self.friction[i] = self.friction_sign[i] * self.settings.mu_k * ry.max(0.0);
                }
                ContactState::Free => {}
            }
        }
        // the load vector (friction part) follows the new states
        self.load = self.load_at(self.t);
    }

    fn record(&self, lowest_base_uy: f64) -> FemStep {
        let mesh = &self.model.mesh;
        let [q, rocking, slipping, flexural, shearing] = decompose(mesh, &self.u);
        let top = mesh.top_nodes();
        let top_velocity = top.iter().map(|&n| self.v[2 * n]).sum::<f64>() / top.len() as f64;
        let momentum = |toe_x: f64| -> f64 {
            mesh.coords
                .iter()
                .enumerate()
                .map(|(n, c)| {
                    let m = self.model.mass[2 * n];
                    let dx = c[0] + self.u[2 * n] - toe_x;
                    let dy = c[1] + self.u[2 * n + 1];
                    m * (dy * self.v[2 * n] - dx * self.v[2 * n + 1])
                })
                .sum()
        };
        FemStep {
            t: self.t,
            q,
            rocking,
            slipping,
            flexural,
            shearing,
            top_velocity,
            momentum_left_toe: momentum(0.0),
            momentum_right_toe: momentum(mesh.width),
            lowest_base_uy,
            base_states: self.states.clone(),
        }
    }
}
