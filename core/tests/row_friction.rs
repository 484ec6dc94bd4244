//! Coulomb's friction between the faces of a compliant row (book/src/row.md §4b), checked
//! against what does not depend on its code: the faces' vertical motion against the geometry of
//! a column turned about its toe and bent, computed here with exact trigonometry; an isolated
//! contact, sliding throughout or sticking throughout, against the two-mass oscillator whose
//! inverse mass friction changes (written out here); zero friction against the frictionless
//! row, bit for bit; the energy books with the friction's work; bad keys refused by name.

use flexrock_core::bodies::row::{solve_row_compliant, ColumnSpec, CompliantSettings, Face, Row};
use flexrock_core::floor::{PaperSine, PulseShape, SinePulse};
use flexrock_core::integrate::{History, InitialState};
use flexrock_core::model::RowModel;
use flexrock_core::physics::automaton::{Automaton, EventKind, Mode};
use flexrock_core::physics::constants::Constants;

use crate::common;
use crate::row::{at_rest, body, mode_shape, sigma, L};
use crate::row_compliant::{pair_of_row_compliant_toml, ROW};

const TIGHT: CompliantSettings = CompliantSettings {
    rtol: 1e-10,
    atol: 1e-10,
    output_dt: 0.01,
};

/// dU/dxi of the paper's shape, from its closed form.
fn mode_slope(xi: f64) -> f64 {
    let z = L * xi;
    L * (z.sinh() + z.sin() - sigma() * (z.cosh() - z.cos())) / 2.0
}

/// ln e of two points alone with damping ratio zeta, let go at zero force (book/src/row.md §4a).
fn restitution_of(zeta: f64) -> f64 {
    if zeta < 1.0 {
        (-2.0 * zeta * zeta.acos() / (1.0 - zeta * zeta).sqrt()).exp()
    } else {
        (-2.0 * zeta * zeta.acosh() / (zeta * zeta - 1.0).sqrt()).exp()
    }
}

/// The vertical displacement of the point of a face at height `y` of a column of width `b` and
/// height `h`, bent by s U(xi) and turned by r/H about its toe on the side of q: the section at
/// y (centre at U(y/h) s + y r/h across) turned by the bending slope, then the whole body turned
/// about the toe, with exact trigonometry. `side` is +1 for the right face.
fn face_height(b: f64, h: f64, y: f64, side: f64, s: f64, r: f64, q: f64) -> f64 {
    let xi = y / h;
    // Bent: the section's centre moves across by U s, the section turns by U' s / h.
    let bend = (mode_slope(xi) * s / h).atan();
    let (cx, cy) = (mode_shape(xi) * s, y);
    let (px, py) = (
        cx + side * 0.5 * b * bend.cos(),
        cy - side * 0.5 * b * bend.sin(),
    );
    // Turned about the toe on the side of q by the angle whose top displacement is r.
    let toe = 0.5 * b * q.signum();
    let angle = (r / h).asin();
    let (dx, dy) = (px - toe, py);
    // A clockwise turn (leaning right) for r > 0.
    dx * (-angle).sin() + dy * angle.cos()
}

/// The faces' dv/dq against a finite difference of the geometry above, before uplift and rocking
/// both ways, for both faces, at the top and below it, both variants of the paper's body.
#[test]
fn the_faces_move_as_the_geometry_of_a_turned_and_bent_column() {
    let b = body(4.0, 0.7, 600.0, 5e6, 0.05);
    let automaton = Automaton::new(&Constants::new(&b).unwrap());
    let s_n = automaton.uplift_displacement();
    let width = b.width;
    // s and r of q (eq. 9).
    let parts = |q: f64| {
        if q.abs() <= s_n {
            (q, 0.0)
        } else {
            let s = s_n * (width - q.abs()) / (width - s_n) * q.signum();
            (s, q - s)
        }
    };
    for (q, mode) in [
        (0.05, Mode::PreUplift),
        (-0.08, Mode::PreUplift),
        (0.3, Mode::RockRight),
        (-0.25, Mode::RockLeft),
    ] {
        for y in [4.0, 3.0] {
            for side in [1.0, -1.0] {
                let face = Face {
                    side,
                    width,
                    height: 4.0,
                    shape_slope: mode_slope(y / 4.0),
                };
                let slope = face.vertical_slope(&automaton, mode, q);
                // The geometry is exact; its slope at small amplitude is the model's, which is
                // first order: scale q down (keeping the mode's side) and difference.
                let scale = 1e-4;
                let at = |dq: f64| {
                    let qq = q + dq;
                    let (s, r) = parts(qq);
                    let (s0, r0) = parts(q);
                    // Only the change from q is scaled: the model is affine in q within a mode.
                    face_height(width, 4.0, y, side, scale * (s - s0), scale * (r - r0), q)
                };
                let h = 1e-3;
                let difference = (at(h) - at(-h)) / (2.0 * h * scale);
                assert!(
                    (slope - difference).abs() < 1e-6 * (1.0 + slope.abs()),
                    "q = {q} ({mode:?}), y = {y}, side {side}: dv/dq {slope} vs geometry {difference}"
                );
            }
        }
    }
}

/// The slopes of an isolated contact of a 3 m column's top against a 4 m column at xi = 3/4,
/// both before uplift: Phi (1 and U(3/4)), the faces' dv/dq (the left column's right face
/// -B/2 U'(1)/H, the right column's left face +B/2 U'(3/4)/H) and the kinetic masses M/4.
struct Pair {
    phi: (f64, f64),
    psi: (f64, f64),
    mass: (f64, f64),
}

impl Pair {
    fn new(
        left: &flexrock_core::physics::body::Body,
        right: &flexrock_core::physics::body::Body,
    ) -> Self {
        let xi = left.height / right.height;
        Pair {
            phi: (1.0, mode_shape(xi)),
            psi: (
                -0.5 * left.width * mode_slope(1.0) / left.height,
                0.5 * right.width * mode_slope(xi) / right.height,
            ),
            mass: (left.mass / 4.0, right.mass / 4.0),
        }
    }

    /// A = Phi_l^2/m_l + Phi_r^2/m_r, C = Phi_l psi_l/m_l + Phi_r psi_r/m_r and
    /// D = psi_l^2/m_l + psi_r^2/m_r: a force P between the faces and T on the left face (up)
    /// change delta'' by -A P + C T and sigma' by -C P + D T.
    fn acd(&self) -> (f64, f64, f64) {
        let (pl, pr) = self.phi;
        let (vl, vr) = self.psi;
        let (ml, mr) = self.mass;
        (
            pl * pl / ml + pr * pr / mr,
            pl * vl / ml + pr * vr / mr,
            vl * vl / ml + vr * vr / mr,
        )
    }
}

/// Each column's q' where the contact ends.
fn after_contact(solved: &flexrock_core::bodies::row::RowSolution) -> (f64, f64) {
    let at_end = |i: usize| {
        solved.columns[i]
            .events
            .iter()
            .find(|e| e.kind == EventKind::ContactEnd)
            .expect("the contact ends")
            .qdot_after
    };
    (at_end(0), at_end(1))
}

/// Two columns meeting with a gap of a micrometre and a very stiff spring, so that the contact
/// is over before their own forces matter. Sliding with T = -mu P sign(sigma), the penetration
/// follows delta'' = -(A + mu s C)(k delta + c delta'): the frictionless oscillator with its
/// inverse mass A changed, so the points leave at e(zeta') with zeta' = zeta sqrt(1 + mu s C / A)
/// after the normal impulse J = (1 + e') w / (A + mu s C), and the velocities change by
/// (-Phi_l - mu s psi_l) J / m_l and (Phi_r + mu s psi_r) J / m_r. Sticking, T = (C/D) P holds
/// sigma' = 0 (within mu P while mu >= |C|/D) and the inverse mass is A - C^2/D.
#[test]
fn an_isolated_contact_slides_or_sticks_as_the_oscillator_says() {
    let left = body(3.0, 0.7, 600.0, 5e6, 0.0);
    let right = body(4.0, 0.7, 900.0, 8e6, 0.0);
    let pair = Pair::new(&left, &right);
    let (a, c, d) = pair.acd();
    let (gap, k, e) = (1e-6, 1e12, 0.5);
    let settings = CompliantSettings {
        rtol: 1e-12,
        atol: 1e-15,
        output_dt: 1e-3,
    };
    let run = |vl: f64, vr: f64, mu: f64| {
        let specs = [
            ColumnSpec {
                body: left.clone(),
                initial: InitialState { q: 0.0, qdot: vl },
            },
            ColumnSpec {
                body: right.clone(),
                initial: InitialState { q: 0.0, qdot: vr },
            },
        ];
        let row = Row::new(&specs, &[gap], e)
            .unwrap()
            .compliant(k)
            .unwrap()
            .with_friction(mu)
            .unwrap();
        let floor = flexrock_core::floor::Free;
        solve_row_compliant(&row, &floor, 2e-3, &settings, History::Sampled)
            .unwrap_or_else(|err| panic!("mu = {mu}: {err}"))
    };
    let zeta = {
        let row = Row::new(&[at_rest(left.clone()), at_rest(right.clone())], &[gap], e)
            .unwrap()
            .compliant(k)
            .unwrap();
        match row.law() {
            flexrock_core::bodies::row::ContactLaw::Compliant { damping_ratio, .. } => {
                damping_ratio
            }
            _ => unreachable!(),
        }
    };
    // Sliding throughout: the left column swaying onto the right one at rest, sigma < 0.
    let v0 = 0.05;
    for mu in [0.1, 0.4] {
        let (pl, pr) = pair.phi;
        let (vl, vr) = pair.psi;
        let (ml, mr) = pair.mass;
        let sigma0 = vl * v0;
        let s = sigma0.signum();
        let inverse = a + mu * s * c;
        let e_slide = restitution_of(zeta * (inverse / a).sqrt());
        let w = pl * v0;
        let j = (1.0 + e_slide) * w / inverse;
        let after = (
            v0 + (-pl - mu * s * vl) * j / ml,
            (pr + mu * s * vr) * j / mr,
        );
        // Still sliding the same way at the end: the closed form holds throughout.
        let sigma_end = vl * after.0 - vr * after.1;
        assert!(
            sigma_end * s > 0.0,
            "mu = {mu}: sigma {sigma0} -> {sigma_end}"
        );
        let solved = run(v0, 0.0, mu);
        assert_eq!(solved.contacts.len(), 1, "mu = {mu}");
        let stretch = solved.contacts[0];
        assert_eq!(stretch.friction_changes, 0, "mu = {mu}: {stretch:?}");
        let got = after_contact(&solved);
        eprintln!(
            "sliding, mu = {mu}: velocities after {got:?}, the oscillator {after:?}; \
             friction took {} J",
            stretch.friction_dissipated
        );
        for (g, x) in [(got.0, after.0), (got.1, after.1)] {
            assert!((g - x).abs() < 1e-7 * v0, "mu = {mu}: {g} vs {x}");
        }
        // The energy lost is what the dashpot and friction took.
        let kinetic = |u: (f64, f64)| 0.5 * ml * u.0 * u.0 + 0.5 * mr * u.1 * u.1;
        let lost = kinetic((v0, 0.0)) - kinetic(after);
        let taken = stretch.energy_dissipated + stretch.friction_dissipated;
        assert!(
            (lost - taken).abs() < 1e-6 * kinetic((v0, 0.0)),
            "mu = {mu}: lost {lost} J, taken {taken} J"
        );
        assert!(stretch.friction_dissipated > 0.0);
    }

    // Sticking throughout: the columns meet with their faces not sliding (the right one moving
    // left at psi_l v0 / psi_r), and mu above |C|/D keeps them stuck.
    let (pl, pr) = pair.phi;
    let (vl, vr) = pair.psi;
    let (ml, mr) = pair.mass;
    let u0 = vl * v0 / vr;
    let ratio = (c / d).abs();
    let inverse = a - c * c / d;
    let e_stick = restitution_of(zeta * (inverse / a).sqrt());
    let w = pl * v0 - pr * u0;
    let j = (1.0 + e_stick) * w / inverse;
    let t = (c / d) * j;
    let after = (v0 + (-pl * j + vl * t) / ml, u0 + (pr * j - vr * t) / mr);
    let solved = run(v0, u0, 1.5 * ratio);
    assert_eq!(solved.contacts.len(), 1);
    let stretch = solved.contacts[0];
    let got = after_contact(&solved);
    eprintln!(
        "sticking, mu = {}: velocities after {got:?}, the oscillator {after:?}; friction took \
         {} J, peak {} N of P {} N",
        1.5 * ratio,
        stretch.friction_dissipated,
        stretch.peak_friction_force,
        stretch.peak_force
    );
    for (g, x) in [(got.0, after.0), (got.1, after.1)] {
        assert!((g - x).abs() < 1e-7 * v0, "sticking: {g} vs {x}");
    }
    assert!(
        (stretch.peak_friction_force - ratio * stretch.peak_force).abs()
            < 1e-6 * stretch.peak_force,
        "{stretch:?}"
    );
    assert!(stretch.friction_dissipated.abs() < 1e-9 * 0.5 * ml * v0 * v0);
    // The faces meet sliding at the little the columns' own forces gave them over the gap,
    // stick almost at once, and slide again as the force vanishes at the release (the own
    // forces then need more than mu P).
    let kinds: Vec<EventKind> = solved.columns[1].events.iter().map(|e| e.kind).collect();
    eprintln!("sticking: {kinds:?}");
    assert!(kinds.contains(&EventKind::FrictionStick), "{kinds:?}");
    // Below |C|/D the same meeting cannot stick: the faces slide from the start.
    let solved = run(v0, u0, 0.5 * ratio);
    let got = after_contact(&solved).0;
    assert!((got - after.0).abs() > 1e-4 * v0, "mu below |C|/D stuck");
    let kinds: Vec<EventKind> = solved.columns[0].events.iter().map(|e| e.kind).collect();
    eprintln!("mu below |C|/D: {kinds:?}");
    assert!(kinds.contains(&EventKind::FrictionSlip), "{kinds:?}");
    assert!(!kinds.contains(&EventKind::FrictionStick), "{kinds:?}");
}

/// Zero friction is the frictionless row, bit for bit.
#[test]
fn zero_friction_is_the_frictionless_row() {
    let row = pair_of_row_compliant_toml();
    let floor = PaperSine::new(4.0, 1.0, 0.412);
    let plain = solve_row_compliant(&row, &floor, 6.0, &TIGHT, History::Sampled).unwrap();
    let zero = solve_row_compliant(
        &row.clone().with_friction(0.0).unwrap(),
        &floor,
        6.0,
        &TIGHT,
        History::Sampled,
    )
    .unwrap();
    assert!(!plain.contacts.is_empty());
    for (a, b) in plain.columns.iter().zip(&zero.columns) {
        assert_eq!(a.events.len(), b.events.len());
        for (x, y) in a.events.iter().zip(&b.events) {
            assert_eq!((x.t, x.q, x.qdot_after), (y.t, y.q, y.qdot_after));
        }
        for (x, y) in a.samples.iter().zip(&b.samples) {
            assert_eq!((x.q, x.qdot), (y.q, y.qdot));
        }
    }
    // And friction changes the motion.
    let rough = solve_row_compliant(
        &row.with_friction(0.5).unwrap(),
        &floor,
        6.0,
        &TIGHT,
        History::Sampled,
    )
    .unwrap();
    let largest = |s: &flexrock_core::bodies::row::RowSolution| {
        s.columns
            .iter()
            .map(|c| c.max_q.value.max(-c.min_q.value))
            .fold(0.0, f64::max)
    };
    assert!(
        (largest(&rough) - largest(&plain)).abs() > 1e-3,
        "{} vs {}",
        largest(&rough),
        largest(&plain)
    );
}

/// Each column's energy books close with the work of the contact forces, friction's among them,
/// under the paper's sine and leaning under a slow pulse, where the faces stick and slip.
#[test]
fn energy_books_close_with_the_friction_work() {
    let soft = body(4.0, 0.7, 600.0, 5e6, 0.05);
    let cases = [
        (
            "paper's sine",
            [
                at_rest(soft.clone()),
                at_rest(body(4.0, 0.7, 600.0, 5e7, 0.05)),
            ],
            0.02,
            1e7,
            0.3,
            None,
        ),
        (
            "leaning",
            [
                at_rest(body(4.0, 0.7, 600.0, 5e8, 0.05)),
                at_rest(soft.clone()),
            ],
            0.003,
            1e9,
            0.5,
            Some((0.8, 20.0)),
        ),
    ];
    for (name, specs, gap, k, mu, pulse) in cases {
        let row = Row::new(&specs, &[gap], 0.5)
            .unwrap()
            .compliant(k)
            .unwrap()
            .with_friction(mu)
            .unwrap();
        let solved = match pulse {
            None => {
                let floor = PaperSine::new(4.0, 1.0, 0.412);
                solve_row_compliant(&row, &floor, 6.0, &TIGHT, History::Sampled)
            }
            Some((amplitude, period)) => {
                let floor = SinePulse::new(amplitude, period, 1.0, PulseShape::Antisymmetric);
                solve_row_compliant(&row, &floor, 12.0, &TIGHT, History::Sampled)
            }
        }
        .unwrap_or_else(|err| panic!("{name}: {err}"));
        let friction: f64 = solved.contacts.iter().map(|s| s.friction_dissipated).sum();
        let changes: usize = solved.contacts.iter().map(|s| s.friction_changes).sum();
        eprintln!(
            "{name}: {} stretches, friction took {friction} J, {changes} changes of stick and slip",
            solved.contacts.len()
        );
        assert!(friction > 0.0, "{name}");
        for s in &solved.contacts {
            assert!(s.friction_dissipated >= -1e-9, "{name}: {s:?}");
            assert!(
                s.peak_friction_force <= mu * s.peak_force * (1.0 + 1e-9),
                "{name}: {s:?}"
            );
        }
        common::row_books_close(name, &solved, 2e-8);
        for (i, c) in solved.columns.iter().enumerate() {
            // Each change of stick and slip is an event of both columns.
            let logged = c
                .events
                .iter()
                .filter(|e| matches!(e.kind, EventKind::FrictionStick | EventKind::FrictionSlip))
                .count();
            // How the faces met, and each change after.
            assert_eq!(
                logged,
                changes + solved.contacts.len(),
                "{name}, column {i}"
            );
        }
        if pulse.is_some() {
            assert!(changes >= 1, "leaning: the faces never stuck");
        }
    }
}

#[test]
fn bad_friction_is_refused_by_name() {
    let read = |extra: &str| {
        let text = ROW.replace(
            "restitution = 0.5\n",
            &format!("restitution = 0.5\n{extra}"),
        );
        RowModel::from_toml_str(&text).map(|_| ())
    };
    for (extra, rule) in [
        ("friction = 0.3\n", "needs contact = \"compliant\""),
        (
            "contact = \"compliant\"\nstiffness = 1e7\nfriction = -0.1\n",
            "finite coefficient of friction >= 0",
        ),
        (
            "contact = \"compliant\"\nstiffness = 1e7\nfriction = inf\n",
            "finite coefficient of friction >= 0",
        ),
    ] {
        let message = read(extra).expect_err(extra).to_string();
        assert!(
            message.contains("row.friction") && message.contains(rule),
            "{extra}: {message}"
        );
    }
    assert!(read("friction = 0.0\n").is_ok());
    assert!(read("contact = \"compliant\"\nstiffness = 1e7\nfriction = 0.6\n").is_ok());
}

/// A soft column leaning on a stiff one under a slow pulse (models/row-friction.toml): once the
/// faces stick, the pair is locked (psi_l q_l - psi_r q_r stays what it was) and moves
/// quasi-statically with the floor: each column's static balance with the contact force
/// P = k delta and the friction T, written out here as four linear equations, gives T / P at
/// every instant, and the faces must slide again where |T| reaches mu P. Inertia and damping,
/// left out of the closed form, move that instant by microseconds on a pulse of 20 s (1.4e-6 s).
#[test]
fn locked_faces_slide_where_the_quasi_static_friction_reaches_mu_p() {
    let stiff = body(4.0, 0.7, 600.0, 5e8, 0.05);
    let soft = body(4.0, 0.7, 600.0, 5e6, 0.05);
    let (gap, k, mu, amplitude, period) = (0.003, 1e9, 0.5, 0.8, 20.0);
    let row = Row::new(
        &[at_rest(stiff.clone()), at_rest(soft.clone())],
        &[gap],
        0.5,
    )
    .unwrap()
    .compliant(k)
    .unwrap()
    .with_friction(mu)
    .unwrap();
    let floor = SinePulse::new(amplitude, period, 1.0, PulseShape::Antisymmetric);
    let solved = solve_row_compliant(&row, &floor, 12.0, &TIGHT, History::Sampled).unwrap();
    let longest =
        common::longest(&solved.sticking, |s| (s.t_start, s.t_end)).expect("the faces stick");
    let (t_stick, t_slip) = (longest.t_start, longest.t_end.unwrap());
    // The pair's state where the faces stuck: q of each column at its friction-stick event.
    let q_at = |i: usize| {
        solved.columns[i]
            .events
            .iter()
            .find(|e| e.kind == EventKind::FrictionStick && e.t == t_stick)
            .expect("a stick event")
            .q
    };
    let (q_l0, q_r0) = (q_at(0), q_at(1));
    // Both before uplift: Phi = 1 at the top, psi = -+ B U'(1) / (2 H), m = M/4, beta = 4 sigma / L.
    let beta = 4.0 * sigma() / L;
    let psi = 0.5 * 0.7 * mode_slope(1.0) / 4.0;
    let (psi_l, psi_r) = (-psi, psi);
    let column = |b: &flexrock_core::physics::body::Body| {
        let m = b.mass / 4.0;
        let omega2 = L.powi(4) * b.flexural_rigidity / (b.mass * b.height.powi(3));
        (m, m * omega2)
    };
    let ((m_l, k_l), (m_r, k_r)) = (column(&stiff), column(&soft));
    let locked = psi_l * q_l0 - psi_r * q_r0;
    // Unknowns (q_l, q_r, P, T):
    //   k_l q_l + P - psi_l T = -m_l beta a
    //   k_r q_r - P + psi_r T = -m_r beta a
    //   psi_l q_l - psi_r q_r = locked
    //   k q_l - k q_r - P     = k gap
    let ratio = |t: f64| {
        let a = amplitude * (2.0 * std::f64::consts::PI * t / period).sin();
        let mut m = [
            [k_l, 0.0, 1.0, -psi_l, -m_l * beta * a],
            [0.0, k_r, -1.0, psi_r, -m_r * beta * a],
            [psi_l, -psi_r, 0.0, 0.0, locked],
            [k, -k, -1.0, 0.0, k * gap],
        ];
        // Gaussian elimination with partial pivoting.
        for col in 0..4 {
            let pivot = (col..4)
                .max_by(|&i, &j| m[i][col].abs().total_cmp(&m[j][col].abs()))
                .unwrap();
            m.swap(col, pivot);
            let pivot_row = m[col];
            for (r, row) in m.iter_mut().enumerate() {
                if r != col {
                    let f = row[col] / pivot_row[col];
                    for (x, p) in row.iter_mut().zip(pivot_row.iter()).skip(col) {
                        *x -= f * p;
                    }
                }
            }
        }
        let (p, t_force) = (m[2][4] / m[2][2], m[3][4] / m[3][3]);
        (t_force.abs() / p, p)
    };
    let (start_ratio, start_force) = ratio(t_stick + 1e-3);
    assert!(
        start_ratio < mu && start_force > 0.0,
        "stuck at {t_stick} s with |T|/P = {start_ratio}"
    );
    // The first instant after the stick where |T| reaches mu P, by bisection on a fine scan.
    let mut t = t_stick + 1e-3;
    while ratio(t).0 < mu {
        t += 1e-3;
        assert!(t < 12.0, "the closed form never slides");
    }
    let (mut lo, mut hi) = (t - 1e-3, t);
    for _ in 0..60 {
        let mid = 0.5 * (lo + hi);
        if ratio(mid).0 < mu {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    eprintln!(
        "locked from {t_stick} s: slides at {t_slip} s, the quasi-static closed form at {hi} s"
    );
    assert!(
        (t_slip - hi).abs() < 1e-4,
        "slides at {t_slip} s, the quasi-static closed form at {hi} s"
    );
}

/// Three columns a millimetre apart under El Centro with a stiff contact, much friction and a
/// loose tolerance: sliding faces whose sliding the loose dense output puts past its stop at a
/// step's start, where looking again leaves them sliding, must not stop the run at that
/// instant over and over (it did, step after step, until the step cap).
#[test]
fn a_loose_tolerance_with_much_friction_runs_to_its_end() {
    let records = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../validation/records/elCentro.AT2"
    );
    let text = format!(
        "[row]\ngaps = [0.001, 0.001]\nrestitution = 0.6\ncontact = \"compliant\"\n\
         stiffness = 1e8\nfriction = 5.0\n\
         [[column]]\nheight = 4.0\nwidth = 0.7\ndensity = 600.0\nyoungs_modulus = 5e6\ndamping_ratio = 0.05\n\
         [[column]]\nheight = 3.2\nwidth = 0.7\ndensity = 600.0\nyoungs_modulus = 8e6\ndamping_ratio = 0.05\n\
         [[column]]\nheight = 4.0\nwidth = 0.8\ndensity = 500.0\nyoungs_modulus = 2e7\ndamping_ratio = 0.03\n\
         [excitation]\nkind = \"record\"\npath = \"{records}\"\nformat = \"peer-at2\"\nunits = \"g\"\n\
         tail = 5.0\n[solver]\nmethod = \"tsit45\"\nrtol = 1e-4\natol = 1e-4\noutput_dt = 0.01\n"
    );
    let model = RowModel::from_toml_str(&text).unwrap();
    let solved = flexrock_core::simulate::simulate_row(&model).unwrap();
    assert_eq!(solved.final_time, model.duration);
    let steps = solved.columns[0].stats.steps;
    eprintln!(
        "loose tolerance: {steps} steps, {} stretches",
        solved.contacts.len()
    );
    assert!(steps < 100_000, "{steps} steps");
}
