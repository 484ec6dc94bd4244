//! The hybrid automaton of the rocking body (book/src/model.md §6): its modes, the right-hand side
//! of eq. 16 in each mode, the guards between modes and the angular-momentum resets at them.
//!
//! This is the only place where the model's dynamics are written down. It knows nothing about
//! integrators: the adaptive diffsol driver and the fixed-step Newmark solver both drive it.

use serde::{Deserialize, Serialize};

use crate::base::double_double::DoubleDouble;
use crate::physics::constants::{Constants, LinearRates};

/// A discrete mode of the body.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum Mode {
    /// Both toes on the floor, |q| < s_n: a linear damped oscillator.
    PreUplift,
    /// Rocking about the right (+x) toe, q > s_n.
    RockRight,
    /// Rocking about the left (-x) toe, q < -s_n.
    RockLeft,
    /// |q| reached B, where the restoring force vanishes: the body falls over. Terminal.
    Overturned,
}

impl Mode {
    /// The mode's name in events.csv and messages, e.g. "rock-right".
    pub fn name(self) -> &'static str {
        match self {
            Mode::PreUplift => "pre-uplift",
            Mode::RockRight => "rock-right",
            Mode::RockLeft => "rock-left",
            Mode::Overturned => "overturned",
        }
    }

    /// +1 rocking right, -1 rocking left, 0 otherwise.
    fn rocking_sign(self) -> f64 {
        match self {
            Mode::RockRight => 1.0,
            Mode::RockLeft => -1.0,
            Mode::PreUplift | Mode::Overturned => 0.0,
        }
    }
}

/// What happens at a mode change.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum EventKind {
    /// The body lifts off one toe: |q| reaches s_n from pre-uplift.
    Uplift,
    /// The body lands back on both toes: |q| returns to s_n while rocking.
    Landing,
    /// |q| reaches B: the body falls over.
    Overturn,
    /// A neighbouring column of a row strikes the body: q' jumps by the contact's impulse and
    /// the mode stays. Never an event of a body alone.
    Impact,
    /// A neighbouring column of a row comes into contact under the compliant law: its contact
    /// force acts from here on; q' and the mode stay. Never an event of a body alone.
    ContactStart,
    /// That contact's force falls to zero and it ends; q' and the mode stay.
    ContactEnd,
    /// The faces of that contact stop sliding and stick (Coulomb's friction); q' and the mode
    /// stay.
    FrictionStick,
    /// The faces of that contact start sliding, or slide the other way; q' and the mode stay.
    FrictionSlip,
}

impl EventKind {
    /// The event's name in events.csv and messages, e.g. "uplift".
    pub fn name(self) -> &'static str {
        match self {
            EventKind::Uplift => "uplift",
            EventKind::Landing => "landing",
            EventKind::Overturn => "overturn",
            EventKind::Impact => "impact",
            EventKind::ContactStart => "contact-start",
            EventKind::ContactEnd => "contact-end",
            EventKind::FrictionStick => "friction-stick",
            EventKind::FrictionSlip => "friction-slip",
        }
    }
}

/// A guard: the surface q = `level`, which the body leaves its mode through when q moves in
/// `direction` (+1 rising, -1 falling).
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Guard {
    /// The value of q on the guard, m.
    pub level: f64,
    /// The direction q crosses the guard in: +1 rising, -1 falling.
    pub direction: f64,
    /// The event that crossing the guard is.
    pub kind: EventKind,
    /// The mode the body enters past the guard.
    pub to: Mode,
}

impl Guard {
    /// Signed distance past the guard: negative inside the mode, zero on the guard, positive beyond.
    pub fn overshoot(&self, q: f64) -> f64 {
        self.direction * (q - self.level)
    }
}

/// The automaton, built once from the derived constants. The restoring force has one home,
/// [`Automaton::restoring_force`], and everything else (its slope, the potential, the flexural
/// part) follows from the two branches the variant's [`Constants`] supply: F = Ke q before uplift,
/// F = F' (q - q_topple) while rocking, with s linear in q there as well.
#[derive(Debug, Clone)]
pub struct Automaton {
    me: f64,
    ke: f64,
    damping_coefficient: f64,
    s_n: f64,
    width: f64,
    /// F' while rocking (negative), N/m.
    rocking_stiffness: f64,
    /// |q| where F = 0 while rocking: the overturning guard.
    topple: f64,
    /// ds/dq while rocking, and s at q_topple.
    rocking_flexural_slope: f64,
    flexural_part_at_topple: f64,
    beta1: f64,
    nu2: f64,
    beta2: f64,
    zeta_uplift: f64,
    zeta_landing: f64,
    /// e, the factor on q' at a landing on top of q' -> q'/zetaL: the body's
    /// `landing_restitution` as written (0.8 is eight tenths).
    landing_restitution: DoubleDouble,
    /// Whether the damping term acts while rocking.
    damping_while_rocking: bool,
    /// k and c of eq. 16 in each mode, rounded once from the constants to twice the precision.
    rates: LinearRates,
    /// M int U^2 and M int V^2, kg: the body's kinetic energy is these times q'^2/2.
    kinetic_mass_pre_uplift: f64,
    kinetic_mass_rocking: f64,
    /// Relative uncertainty of the constants above as computed (see
    /// [`Automaton::constants_uncertainty`]).
    uncertainty: f64,
}

/// Relative uncertainty of the constants of the paper's self-weight variant: closed forms
/// computed in twice the precision and rounded once, so within an ulp; eight, to be generous.
const CLOSED_FORM_UNCERTAINTY: f64 = 8.0 * f64::EPSILON;
/// Relative uncertainty of the constants of the consistent variant: they come from a Ritz
/// solution in double precision, which agrees with the same solution in 40-digit arithmetic to
/// 1.1e-11 on the reference body (validation/exact); ten times that.
const RITZ_UNCERTAINTY: f64 = 1e-10;

impl Automaton {
    /// The automaton of the body whose constants are `constants`.
    pub fn new(constants: &Constants) -> Self {
        Automaton {
            me: constants.generalised_mass,
            ke: constants.generalised_stiffness,
            damping_coefficient: constants.damping_coefficient,
            s_n: constants.uplift_displacement,
            width: constants.width,
            rocking_stiffness: constants.rocking_stiffness,
            topple: constants.topple_displacement,
            rocking_flexural_slope: constants.rocking_flexural_slope,
            flexural_part_at_topple: constants.flexural_part_at_topple,
            beta1: constants.beta1,
            nu2: constants.nu2,
            beta2: constants.beta2,
            zeta_uplift: constants.zeta_uplift,
            zeta_landing: constants.zeta_landing,
            landing_restitution: DoubleDouble::decimal(constants.landing_restitution),
            damping_while_rocking: constants.damping_while_rocking,
            rates: constants.linear_rates,
            kinetic_mass_pre_uplift: constants.kinetic_mass(false),
            kinetic_mass_rocking: constants.kinetic_mass(true),
            uncertainty: match constants.self_weight {
                crate::physics::body::SelfWeight::Paper => CLOSED_FORM_UNCERTAINTY,
                crate::physics::body::SelfWeight::Consistent => RITZ_UNCERTAINTY,
            },
        }
    }

    /// The relative uncertainty of the automaton's constants as computed in double precision.
    pub fn constants_uncertainty(&self) -> f64 {
        self.uncertainty
    }

    /// A copy whose constants of the dynamics (Me, Ke, the damping, s_n, F' while rocking,
    /// q_topple, beta, nu and the resets) are each moved by `size` relative, in a pseudo-random
    /// direction fixed by `pattern`: the exact solver runs such copies to estimate its error.
    /// The landing restitution e is the body's own number, not a derived one, and stays (as does
    /// a damping of 0 while rocking, which a relative move keeps 0).
    pub(crate) fn nudged(&self, pattern: u64, size: f64) -> Automaton {
        let nudge = |value: f64, item: u64| value * (1.0 + size * nudge_sign(pattern, item));
        Automaton {
            me: nudge(self.me, 0),
            ke: nudge(self.ke, 1),
            damping_coefficient: nudge(self.damping_coefficient, 2),
            s_n: nudge(self.s_n, 3),
            rocking_stiffness: nudge(self.rocking_stiffness, 4),
            topple: nudge(self.topple, 5),
            beta1: nudge(self.beta1, 6),
            nu2: nudge(self.nu2, 7),
            beta2: nudge(self.beta2, 8),
            zeta_uplift: nudge(self.zeta_uplift, 9),
            zeta_landing: nudge(self.zeta_landing, 10),
            rates: LinearRates {
                pre_uplift_stiffness: nudge(self.rates.pre_uplift_stiffness, 11),
                pre_uplift_damping: nudge(self.rates.pre_uplift_damping, 12),
                rocking_stiffness: nudge(self.rates.rocking_stiffness, 13),
                rocking_damping: nudge(self.rates.rocking_damping, 14),
            },
            ..self.clone()
        }
    }

    /// Me, kg.
    pub fn generalised_mass(&self) -> f64 {
        self.me
    }

    /// s_n, m.
    pub fn uplift_displacement(&self) -> f64 {
        self.s_n
    }

    /// B, m.
    pub fn width(&self) -> f64 {
        self.width
    }

    /// |q| at which the body falls over (B in the paper's model), m.
    pub fn topple_displacement(&self) -> f64 {
        self.topple
    }

    /// The mode a body starts in: rocking about the matching toe when |q0| > s_n.
    pub fn initial_mode(&self, q0: f64) -> Mode {
        if q0 > self.s_n {
            Mode::RockRight
        } else if q0 < -self.s_n {
            Mode::RockLeft
        } else {
            Mode::PreUplift
        }
    }

    /// The guards of `mode`, in a fixed order (the index is used by solvers to name a guard).
    pub(crate) fn guards(&self, mode: Mode) -> &'static [GuardSlot] {
        match mode {
            Mode::PreUplift => &[GuardSlot::UpliftRight, GuardSlot::UpliftLeft],
            Mode::RockRight | Mode::RockLeft => &[GuardSlot::Landing, GuardSlot::Overturn],
            Mode::Overturned => &[],
        }
    }

    /// The guard behind a slot of `mode`.
    pub(crate) fn guard(&self, mode: Mode, slot: GuardSlot) -> Guard {
        let side = mode.rocking_sign();
        match slot {
            GuardSlot::UpliftRight => Guard {
                level: self.s_n,
                direction: 1.0,
                kind: EventKind::Uplift,
                to: Mode::RockRight,
            },
            GuardSlot::UpliftLeft => Guard {
                level: -self.s_n,
                direction: -1.0,
                kind: EventKind::Uplift,
                to: Mode::RockLeft,
            },
            GuardSlot::Landing => Guard {
                level: side * self.s_n,
                direction: -side,
                kind: EventKind::Landing,
                to: Mode::PreUplift,
            },
            GuardSlot::Overturn => Guard {
                level: side * self.topple,
                direction: side,
                kind: EventKind::Overturn,
                to: Mode::Overturned,
            },
        }
    }

    /// A guard of `mode` that the state (q, q') has crossed, or sits on while moving across it.
    /// A state on a guard but moving back into its mode does not trigger it.
    pub(crate) fn crossed_guard(&self, mode: Mode, q: f64, qdot: f64) -> Option<Guard> {
        self.guards(mode)
            .iter()
            .map(|&slot| self.guard(mode, slot))
            .find(|g| {
                let past = g.overshoot(q);
                past > 0.0 || (past == 0.0 && g.direction * qdot > 0.0)
            })
    }

    /// The reset of q' at an event (eqs. 21-22): uplift q' -> zetaU q', landing
    /// q' -> e q'/zetaL, with e the body's landing restitution (1 in the paper's model).
    pub fn reset_velocity(&self, kind: EventKind, qdot: f64) -> f64 {
        self.reset_velocity_twice(kind, DoubleDouble::exact(qdot))
            .value()
    }

    /// [`Automaton::reset_velocity`] to twice the precision, for a solver that carries q' so
    /// (rounded, it is the double product or quotient itself).
    pub(crate) fn reset_velocity_twice(&self, kind: EventKind, qdot: DoubleDouble) -> DoubleDouble {
        match kind {
            EventKind::Uplift => qdot * self.zeta_uplift,
            EventKind::Landing => qdot / self.zeta_landing * self.landing_restitution,
            // No reset of the body's own: a row's impact law gives the jump.
            EventKind::Overturn
            | EventKind::Impact
            | EventKind::ContactStart
            | EventKind::ContactEnd
            | EventKind::FrictionStick
            | EventKind::FrictionSlip => qdot,
        }
    }

    /// Effectiveness factor nu of the mode.
    pub fn effectiveness(&self, mode: Mode) -> f64 {
        match mode {
            Mode::PreUplift => 1.0,
            _ => self.nu2,
        }
    }

    /// Participation factor beta of the mode.
    pub fn participation(&self, mode: Mode) -> f64 {
        match mode {
            Mode::PreUplift => self.beta1,
            _ => self.beta2,
        }
    }

    /// Restoring force F(q) (the base shear, eq. 17) on the branch that belongs to `mode`.
    pub fn restoring_force(&self, mode: Mode, q: f64) -> f64 {
        match mode {
            Mode::PreUplift => self.ke * q,
            Mode::RockRight | Mode::RockLeft => {
                let side = mode.rocking_sign();
                self.rocking_stiffness * (q - side * self.topple)
            }
            Mode::Overturned => 0.0,
        }
    }

    /// F'(q) on the branch of `mode` (negative while rocking).
    pub fn restoring_stiffness(&self, mode: Mode) -> f64 {
        match mode {
            Mode::PreUplift => self.ke,
            Mode::RockRight | Mode::RockLeft => self.rocking_stiffness,
            Mode::Overturned => 0.0,
        }
    }

    /// Coefficient of q' in eq. 16, (gamma/E) nu F'(q). Negative while rocking: as in the paper,
    /// the strain-rate damping then feeds energy into q. 0 while rocking when the body's
    /// `damping_while_rocking` is false.
    pub fn damping(&self, mode: Mode) -> f64 {
        match mode {
            Mode::RockRight | Mode::RockLeft if !self.damping_while_rocking => 0.0,
            _ => {
                self.damping_coefficient * self.effectiveness(mode) * self.restoring_stiffness(mode)
            }
        }
    }

    /// q'' from eq. 16: Me q'' + (gamma/E) nu F' q' + nu F(q) = -beta Me a.
    pub fn acceleration(&self, mode: Mode, q: f64, qdot: f64, floor_acc: f64) -> f64 {
        if mode == Mode::Overturned {
            return 0.0;
        }
        let nu = self.effectiveness(mode);
        -(self.damping(mode) * qdot + nu * self.restoring_force(mode, q)) / self.me
            - self.participation(mode) * floor_acc
    }

    /// Eq. 16 within `mode` as the linear equation it is there, x'' + c x' + k x = -beta a(t)
    /// with x = q - q_eq: the coefficients the exact solver integrates in closed form. k and c
    /// are the partial derivatives of [`Automaton::acceleration`] (the same branch of F, the same
    /// nu and damping), as the constants compute them to twice the precision and round once
    /// (`Constants::linear_rates`). None for the terminal mode.
    pub fn linear_form(&self, mode: Mode) -> Option<LinearForm> {
        if mode == Mode::Overturned {
            return None;
        }
        let rates = &self.rates;
        let (stiffness, damping) = match mode {
            Mode::PreUplift => (rates.pre_uplift_stiffness, rates.pre_uplift_damping),
            _ => (rates.rocking_stiffness, rates.rocking_damping),
        };
        Some(LinearForm {
            stiffness,
            damping,
            // F(q) = F' (q - q_eq) on the branch: q_eq is where the branch's force vanishes.
            equilibrium: match mode {
                Mode::PreUplift | Mode::Overturned => 0.0,
                Mode::RockRight | Mode::RockLeft => mode.rocking_sign() * self.topple,
            },
            participation: self.participation(mode),
        })
    }

    /// Partial derivatives of q'' with respect to q and q' (constant within a mode).
    pub fn acceleration_jacobian(&self, mode: Mode) -> (f64, f64) {
        if mode == Mode::Overturned {
            return (0.0, 0.0);
        }
        let nu = self.effectiveness(mode);
        (
            -nu * self.restoring_stiffness(mode) / self.me,
            -self.damping(mode) / self.me,
        )
    }

    /// Potential V(q) of the effective restoring force: V' = nu F on the mode's branch and V is
    /// continuous at |q| = s_n, so that Me q'^2/2 + V(q) is the SDOF energy.
    pub fn potential_energy(&self, mode: Mode, q: f64) -> f64 {
        match mode {
            Mode::PreUplift => 0.5 * self.ke * q * q,
            Mode::RockRight | Mode::RockLeft | Mode::Overturned => {
                // nu2 times the integral of F' (x - q_topple) from s_n to |q|.
                let (x, t) = (q.abs(), self.topple);
                0.5 * self.ke * self.s_n * self.s_n
                    + self.nu2
                        * self.rocking_stiffness
                        * 0.5
                        * ((x - t) * (x - t) - (self.s_n - t) * (self.s_n - t))
            }
        }
    }

    /// Kinetic energy of the SDOF body, Me q'^2/2.
    pub fn kinetic_energy(&self, qdot: f64) -> f64 {
        0.5 * self.me * qdot * qdot
    }

    /// Kinetic energy of the body's horizontal motion in `mode`, J: M (int U^2) q'^2/2 before
    /// uplift, M (int V^2) q'^2/2 while rocking (book/src/model.md §5). Unlike the SDOF energy,
    /// it falls at every uplift and landing; the fall is the energy the impact takes.
    pub fn body_kinetic_energy(&self, mode: Mode, qdot: f64) -> f64 {
        0.5 * self.kinetic_mass(mode) * qdot * qdot
    }

    /// The SDOF energy E = Me q'^2/2 + V(q) in `mode`, whose balance the solvers book.
    pub fn energy(&self, mode: Mode, q: f64, qdot: f64) -> f64 {
        self.kinetic_energy(qdot) + self.potential_energy(mode, q)
    }

    /// Change of the SDOF energy at an event from `from` to `to` at q, as q' jumps from
    /// `qdot_before` to `qdot_after` (V is continuous, so this is the change of the kinetic
    /// energy): negative when the event takes energy out.
    pub fn event_energy_jump(
        &self,
        from: Mode,
        to: Mode,
        q: f64,
        qdot_before: f64,
        qdot_after: f64,
    ) -> f64 {
        self.energy(to, q, qdot_after) - self.energy(from, q, qdot_before)
    }

    /// Power fed into the SDOF energy by the floor, -beta Me a q'.
    pub fn input_power(&self, mode: Mode, qdot: f64, floor_acc: f64) -> f64 {
        -self.participation(mode) * self.me * floor_acc * qdot
    }

    /// Power dissipated by the damping term, (gamma/E) nu F' q'^2 (negative while rocking).
    pub fn damping_power(&self, mode: Mode, qdot: f64) -> f64 {
        self.damping(mode) * qdot * qdot
    }

    /// Flexural part s of q (eq. 9; validation/SELF-WEIGHT.md for the consistent variant).
    pub fn flexural_part(&self, mode: Mode, q: f64) -> f64 {
        match mode {
            Mode::PreUplift => q,
            _ => {
                let side = if q >= 0.0 { 1.0 } else { -1.0 };
                side * self.flexural_part_at_topple
                    + self.rocking_flexural_slope * (q - side * self.topple)
            }
        }
    }

    /// |s| on the rocking branch where the rocking part is |r| = `abs_r` (the s-r relation of the
    /// paper's Fig. 13, s_n (1 - |r|/B) in the paper's model): s and r are both linear in q there.
    pub fn flexural_part_at_rocking_part(&self, abs_r: f64) -> f64 {
        let slope = self.rocking_flexural_slope;
        self.s_n + slope / (1.0 - slope) * abs_r
    }

    /// M int Phi^2, kg, with Phi the velocity shape of `mode` (U before uplift, V while rocking):
    /// the body's horizontal kinetic energy is this times q'^2/2, and a horizontal impulse J at
    /// height xi H changes q' by Phi(xi) J over it.
    pub fn kinetic_mass(&self, mode: Mode) -> f64 {
        match mode {
            Mode::PreUplift => self.kinetic_mass_pre_uplift,
            Mode::RockRight | Mode::RockLeft | Mode::Overturned => self.kinetic_mass_rocking,
        }
    }

    /// Horizontal displacement u = U(xi) s + xi r of the section at height xi H relative to the
    /// floor, m, in `mode` at q; `shape` is U(xi), the flexural shape there (1 at the top, where
    /// u = q).
    pub fn displacement_at(&self, mode: Mode, q: f64, xi: f64, shape: f64) -> f64 {
        let s = self.flexural_part(mode, q);
        shape * s + xi * (q - s)
    }

    /// du/dq at height xi H in `mode` (the velocity shape Phi(xi): U(xi) before uplift, V(xi)
    /// while rocking), with `shape` = U(xi). Within a mode u is affine in q, with this slope.
    pub fn displacement_slope_at(&self, mode: Mode, xi: f64, shape: f64) -> f64 {
        let ds = self.flexural_slope(mode);
        shape * ds + xi * (1.0 - ds)
    }

    /// ds/dq in `mode`: 1 before uplift, the constant of eq. (9b) while rocking; dr/dq is one
    /// less it.
    pub fn flexural_slope(&self, mode: Mode) -> f64 {
        match mode {
            Mode::PreUplift => 1.0,
            Mode::RockRight | Mode::RockLeft | Mode::Overturned => self.rocking_flexural_slope,
        }
    }

    /// Rocking part r = q - s of q (eq. 9).
    pub fn rocking_part(&self, mode: Mode, q: f64) -> f64 {
        q - self.flexural_part(mode, q)
    }
}

/// A pseudo-random sign for nudge pattern `pattern`, item `item` (a fixed hash: results do not
/// change from run to run).
pub(crate) fn nudge_sign(pattern: u64, item: u64) -> f64 {
    let mut x = pattern
        .wrapping_mul(0x9E37_79B9_7F4A_7C15)
        .wrapping_add(item.wrapping_mul(0xBF58_476D_1CE4_E5B9));
    x ^= x >> 31;
    x = x.wrapping_mul(0x94D0_49BB_1331_11EB);
    x ^= x >> 29;
    if x & 1 == 0 {
        1.0
    } else {
        -1.0
    }
}

/// Eq. 16 within one mode: x'' + c x' + k x = -beta a(t), x = q - q_eq
/// (see [`Automaton::linear_form`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LinearForm {
    /// k = nu F' / Me, 1/s^2: positive before uplift, negative while rocking.
    pub stiffness: f64,
    /// c = (gamma/E) nu F' / Me, 1/s: negative while rocking (the paper's damping term).
    pub damping: f64,
    /// q_eq, m: where the branch's restoring force vanishes (0, or +-q_topple while rocking).
    pub equilibrium: f64,
    /// beta, the participation factor of the mode.
    pub participation: f64,
}

/// Names of the guards, so that a solver can refer to "the i-th guard of this mode".
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum GuardSlot {
    /// Uplift about the right toe: q rises through s_n.
    UpliftRight,
    /// Uplift about the left toe: q falls through -s_n.
    UpliftLeft,
    /// Landing: |q| returns to s_n while rocking.
    Landing,
    /// Overturn: |q| reaches B while rocking.
    Overturn,
}
