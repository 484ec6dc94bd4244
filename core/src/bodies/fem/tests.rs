//! Tests against closed forms and independent numbers (none taken from this program's output).

use std::f64::consts::PI;

use nalgebra::{DMatrix, DVector, SMatrix, Vector3};

use super::assembly::Assembly;
use super::banded::{BandedLdl, BandedSym};
use super::element::{plane_stress_matrix, Qm6};
use super::*;
use crate::physics::constants::cantilever_mode;

const L: f64 = 1.875_104_068_711_961;
const SIG: f64 = 0.734_095_513_758_9;

fn body_with_modulus(e: f64) -> FemBody {
    FemBody {
        youngs_modulus: e,
        ..FemBody::reference()
    }
}

/// Euler-Bernoulli cantilever period 2π/(L² sqrt(EI/(ρ_l H⁴))).
fn euler_bernoulli_period(body: &FemBody) -> f64 {
    let rho_l = body.density * body.width * body.depth;
    2.0 * PI / (L * L * (body.flexural_rigidity() / (rho_l * body.height.powi(4))).sqrt())
}

/// SDOF constants of book/src/model.md §2-§3: (s_n, Ke).
fn sdof_uplift(body: &FemBody) -> (f64, f64) {
    let ei = body.flexural_rigidity();
    let h = body.height;
    let s_n =
        body.width / (2.0 * ei * L * L / (body.mass() * body.gravity * h * h) + 2.0 * SIG / L);
    let ke = L.powi(3) * SIG * ei / h.powi(3);
    (s_n, ke)
}

#[test]
fn banded_ldl_matches_dense_solve() {
    let (n, hb) = (30, 4);
    let mut a = BandedSym::zeros(n, hb);
    for i in 0..n {
        a.add(i, i, 10.0 + i as f64 * 0.1);
        for k in 1..=hb.min(i) {
            a.add(i, i - k, ((i * 7 + k * 3) % 5) as f64 * 0.4 - 0.9);
        }
    }
    let dense = DMatrix::from_fn(n, n, |i, j| a.get(i, j));
    let b: Vec<f64> = (0..n).map(|i| (i as f64 * 0.37).sin()).collect();
    let expected = dense.lu().solve(&DVector::from_vec(b.clone())).unwrap();
    let mut x = b;
    BandedLdl::factor(&a).unwrap().solve_in_place(&mut x);
    for i in 0..n {
        assert!((x[i] - expected[i]).abs() < 1e-12, "dof {i}");
    }
}

/// A chain of springs k (i, i+1): free at both ends it is singular (rigid translation), which
/// the factorisation must report even when one spring is 1e8 times stiffer than the rest; held
/// at one end it solves, stiff spring and all, to the closed form x_i = sum of 1/k up to i.
#[test]
fn banded_ldl_reports_singular_chains_and_solves_held_ones() {
    let n = 12;
    let chain = |held: bool| {
        let mut a = BandedSym::zeros(n, 1);
        for i in 0..n - 1 {
            let k = if i == 5 { 1e8 } else { 1.0 };
            a.add(i, i, k);
            a.add(i + 1, i + 1, k);
            a.add(i + 1, i, -k);
        }
        if held {
            a.add(0, 0, 1.0);
        }
        a
    };
    assert!(BandedLdl::factor(&chain(false)).is_err());
    // unit load at the free end: every spring carries 1
    let mut x = vec![0.0; n];
    x[n - 1] = 1.0;
    BandedLdl::factor(&chain(true))
        .unwrap()
        .solve_in_place(&mut x);
    let mut expected = 1.0; // the grounding spring
    for (i, xi) in x.iter().enumerate() {
        // round-off grows with the stiffness contrast (1e8): about 1e-16 x 1e8
        assert!((xi - expected).abs() < 1e-6 * expected, "dof {i}: {xi}");
        expected += if i == 5 { 1e-8 } else { 1.0 };
    }
}

/// Force-driven constant-stress patch test on two distorted quadrilaterals: the consistent
/// edge loads of a uniform stress, minimal supports; the displacement must be the exact linear
/// field and the stress uniform at every Gauss point.
#[test]
fn patch_test_distorted_two_element_patch() {
    let nodes = [
        [0.0, 0.0],
        [1.1, 0.2],
        [2.2, 0.0],
        [0.0, 1.0],
        [0.8, 1.2],
        [2.0, 1.1],
    ];
    let elements = [[0usize, 1, 4, 3], [1, 2, 5, 4]];
    let (e, nu, t) = (2.0e7, 0.3, 0.5);
    let d = plane_stress_matrix(e, nu);
    let stress = Vector3::new(1.0e5, -0.4e5, 0.3e5);
    let strain = d.try_inverse().unwrap() * stress;
    let mut k = DMatrix::zeros(12, 12);
    let mut qm6 = Vec::new();
    for el in &elements {
        let coords = el.map(|n| nodes[n]);
        let q = Qm6::new(&coords, d, t).unwrap();
        for a in 0..8 {
            for b in 0..8 {
                k[(2 * el[a / 2] + a % 2, 2 * el[b / 2] + b % 2)] += q.stiffness[(a, b)];
            }
        }
        qm6.push(q);
    }
    // boundary loop, counter-clockwise: outward normal of edge (p -> q) is (dy, -dx)/len
    let boundary = [0usize, 1, 2, 5, 4, 3, 0];
    let mut f: DVector<f64> = DVector::zeros(12);
    for w in boundary.windows(2) {
        let (p, q) = (nodes[w[0]], nodes[w[1]]);
        let (dx, dy) = (q[0] - p[0], q[1] - p[1]);
        // traction × length = σ · (dy, -dx)
        let tx = stress[0] * dy - stress[2] * dx;
        let ty = stress[2] * dy - stress[1] * dx;
        for node in [w[0], w[1]] {
            f[2 * node] += 0.5 * tx * t;
            f[2 * node + 1] += 0.5 * ty * t;
        }
    }
    // supports: node 0 pinned, node 2 (same y) held vertically
    let held = [0usize, 1, 5];
    let free: Vec<usize> = (0..12).filter(|i| !held.contains(i)).collect();
    let kff = DMatrix::from_fn(free.len(), free.len(), |r, c| k[(free[r], free[c])]);
    let ff = DVector::from_fn(free.len(), |r, _| f[free[r]]);
    let uf = kff.lu().solve(&ff).unwrap();
    let mut u: DVector<f64> = DVector::zeros(12);
    for (r, &i) in free.iter().enumerate() {
        u[i] = uf[r];
    }
    // exact field with u(0) = 0, uy(node 2) = 0: ux = εxx x + γ y, uy = εyy y
    let scale = strain.abs().max() * 2.2;
    for (n, p) in nodes.iter().enumerate() {
        let ux = strain[0] * p[0] + strain[2] * p[1];
        let uy = strain[1] * p[1];
        assert!((u[2 * n] - ux).abs() < 1e-10 * scale, "ux of node {n}");
        assert!((u[2 * n + 1] - uy).abs() < 1e-10 * scale, "uy of node {n}");
    }
    for (q, el) in qm6.iter().zip(&elements) {
        let nodal = SMatrix::<f64, 8, 1>::from_fn(|r, _| u[2 * el[r / 2] + r % 2]);
        for s in q.stresses(&nodal) {
            assert!((s - stress).abs().max() < 1e-8 * stress.abs().max());
        }
    }
}

#[test]
fn gravity_reactions_sum_to_weight() {
    for (nx, ny) in [(2, 5), (8, 40)] {
        let body = FemBody::reference();
        let model = Assembly::build(&body, nx, ny).unwrap();
        let weight = body.mass() * body.gravity;
        let ry: f64 = model.static_reactions.iter().map(|r| r[1]).sum();
        let rx: f64 = model.static_reactions.iter().map(|r| r[0]).sum();
        assert!(
            (ry - weight).abs() < 1e-9 * weight,
            "{nx}x{ny}: {ry} vs {weight}"
        );
        assert!(rx.abs() < 1e-9 * weight);
        assert!((model.total_mass - body.mass()).abs() < 1e-9 * body.mass());
    }
}

#[test]
fn fixed_base_period_converges_to_cantilever() {
    let body = FemBody::reference();
    let t_eb = euler_bernoulli_period(&body);
    assert!((t_eb - 1.550).abs() < 5e-4, "reference body: {t_eb}");
    let periods: Vec<f64> = [(2, 5), (4, 20), (8, 40)]
        .iter()
        .map(|&(nx, ny)| fixed_base_periods(&body, nx, ny, false, 1).unwrap()[0])
        .collect();
    // converging, and the continuum (shear deformation included) a few % above Euler-Bernoulli
    assert!((periods[2] - periods[1]).abs() < (periods[1] - periods[0]).abs());
    assert!(periods[2] > t_eb && periods[2] < 1.04 * t_eb, "{periods:?}");
    // with the self-weight's P-Delta: the beam-column value 1.772 s (book/src/model.md §7a)
    let with_weight = fixed_base_periods(&body, 8, 40, true, 1).unwrap()[0];
    assert!((with_weight / 1.772 - 1.0).abs() < 0.04, "{with_weight}");
    // and the lengthening ratio of the beam-column model, 1.772/1.550, within 1 %
    let ratio = with_weight / periods[2];
    assert!((ratio / (1.772 / 1.550) - 1.0).abs() < 0.01, "{ratio}");
}

#[test]
fn iterative_eigen_solvers_agree_with_dense() {
    let body = FemBody::reference();
    let model = Assembly::build(&body, 4, 20).unwrap();
    let base = model.base_dof_count();
    let fixed: Vec<bool> = (0..model.mesh.dof_count()).map(|d| d < base).collect();
    let k = model.tangent(true);
    let dense = eigen::dense_eigenvalues(&k, &model.mass, &fixed).unwrap();
    let lowest = eigen::subspace_iteration(&k, &model.mass, &fixed, 3).unwrap();
    for i in 0..3 {
        assert!((lowest[i] / dense[i] - 1.0).abs() < 1e-8, "mode {i}");
    }
    let elastic_dense = eigen::dense_eigenvalues(&model.stiffness, &model.mass, &fixed).unwrap();
    let highest = eigen::lanczos_highest(&model.stiffness, &model.mass, &fixed).unwrap();
    let top = *elastic_dense.last().unwrap();
    assert!(
        (highest / top - 1.0).abs() < 1e-9,
        "{highest} against {top}"
    );
}

#[test]
fn stability_limit_is_linear_acceleration_bound() {
    let body = FemBody::reference();
    let w = highest_frequency(&body, 2, 5).unwrap();
    let dt = stability_limit(&body, 2, 5).unwrap();
    assert!((dt * w - 12f64.sqrt()).abs() < 1e-12);
    let limit = critical_time_step(TimeScheme::linear_acceleration(), w).unwrap();
    assert!((limit / dt - 1.0).abs() < 1e-12);
    assert_eq!(
        critical_time_step(TimeScheme::average_acceleration(), w),
        None
    );
    assert_eq!(critical_time_step(TimeScheme::wilson(), w), None);
}

/// ω_max is taken with the base free: holding the base can only lower it (interlacing), and
/// Gershgorin's theorem bounds it by max_i Σ_j |K_ij| / m_i. A rigid base plate's stiff
/// springs raise it far above the flexible base's.
#[test]
fn highest_frequency_bounds_every_contact_state() {
    let body = FemBody::reference();
    let model = Assembly::build(&body, 2, 5).unwrap();
    let n = model.mesh.dof_count();
    let base = model.base_dof_count();
    let fixed: Vec<bool> = (0..n).map(|d| d < base).collect();
    let fixed_top = eigen::dense_eigenvalues(&model.stiffness, &model.mass, &fixed)
        .unwrap()
        .last()
        .unwrap()
        .sqrt();
    let gershgorin = (0..n)
        .map(|i| (0..n).map(|j| model.stiffness.get(i, j).abs()).sum::<f64>() / model.mass[i])
        .fold(0.0, f64::max)
        .sqrt();
    let w = highest_frequency(&body, 2, 5).unwrap();
    assert!(
        w >= fixed_top && w <= gershgorin,
        "{fixed_top} <= {w} <= {gershgorin}"
    );
    let plate = FemBody {
        base: BaseSupport::RigidPlate,
        ..body
    };
    assert!(highest_frequency(&plate, 2, 5).unwrap() > 50.0 * w);
}

/// The q at which the pre-uplift line meets the rocking line extrapolated back.
fn bilinear_uplift(k0: f64, (q1, f1): (f64, f64), (q2, f2): (f64, f64)) -> f64 {
    let slope = (f2 - f1) / (q2 - q1);
    (f1 - slope * q1) / (k0 - slope)
}

#[test]
fn pushover_stiff_body_follows_sdof_rocking() {
    let body = body_with_modulus(5.0e8);
    let (s_n, ke) = sdof_uplift(&body);
    assert!((s_n - 1.833e-3).abs() < 1e-5);
    let b = body.width;
    let qs = [0.1 * s_n, 0.2 * b, 0.3 * b, 0.4 * b, 0.5 * b, 0.6 * b];
    let points = pushover(&body, 8, 40, true, &qs).unwrap().points;
    let k0 = points[0].base_shear / points[0].q;
    assert!(!points[0].heel_lifted);
    for p in &points[1..] {
        let f = ke * s_n * (b - p.q) / (b - s_n);
        assert!((p.base_shear / f - 1.0).abs() < 0.05, "q = {}", p.q);
        assert!(p.uplift);
    }
    let q_up = bilinear_uplift(
        k0,
        (points[1].q, points[1].base_shear),
        (points[2].q, points[2].base_shear),
    );
    assert!(
        (q_up / s_n - 1.0).abs() < 0.05,
        "uplift at {q_up}, s_n {s_n}"
    );
}

#[test]
fn pushover_reference_body_stiffness() {
    let body = FemBody::reference();
    let (_, ke) = sdof_uplift(&body);
    let q = [0.02];
    let with_weight = pushover(&body, 8, 40, true, &q).unwrap().points[0].clone();
    let without = pushover(&body, 8, 40, false, &q).unwrap().points[0].clone();
    assert!(!with_weight.heel_lifted && !without.heel_lifted);
    let k_pd = with_weight.base_shear / q[0];
    let k_lin = without.base_shear / q[0];
    assert!((k_pd / (0.764 * ke) - 1.0).abs() < 0.06, "{}", k_pd / ke);
    assert!((k_lin / ke - 1.0).abs() < 0.05, "{}", k_lin / ke);
}

/// First q of `qs` at which a corner of the base is off the floor.
fn first_heel_lift(body: &FemBody, p_delta: bool, qs: &[f64]) -> PushoverPoint {
    pushover(body, 8, 40, p_delta, qs)
        .unwrap()
        .points
        .into_iter()
        .find(|p| p.heel_lifted)
        .expect("the heel lifts within the sweep")
}

/// The beam-column model of book/src/model.md §7a stands on a rigid base section carried by two toe
/// springs and lifts off at q = 0.1895 m with a base shear of 8260 N/m x 0.1895 m = 1565 N. The
/// same base, a rigid plate under the plane-stress body, must lift off there too: the plate stays
/// flat until the base moment reaches N B/2 and then pivots about the toe.
#[test]
fn pushover_reference_body_uplift_point() {
    let body = FemBody {
        base: BaseSupport::RigidPlate,
        ..FemBody::reference()
    };
    let qs: Vec<f64> = (0..=200).map(|k| 0.15 + 0.0005 * k as f64).collect();
    let lift = first_heel_lift(&body, true, &qs);
    assert!((lift.q / 0.1895 - 1.0).abs() < 0.05, "lifted at {}", lift.q);
    assert!(
        lift.uplift,
        "a rigid plate lifts whole, pivoting on the toe"
    );
    assert!(
        (lift.base_shear / 1565.0 - 1.0).abs() < 0.05,
        "base shear {} at uplift",
        lift.base_shear
    );
}

/// Without P-Delta the weight keeps its line of action, so the resisting moment about the toe
/// stays M g B/2: eq. 8 without its weight-shift term 2σ/L gives the uplift point,
/// B M g H²/(2 EI L²) (0.1837 m; the continuum's shear adds ~3 %), and after it the body turns
/// rigidly about the toe at constant load, base shear = (M g B/2) ∫U / (H ∫U ξ) (loads m U).
/// Where round-off leaves that rotation without any stiffness the sweep ends and says so.
#[test]
fn rigid_plate_without_p_delta_lifts_at_small_displacement_s_n_then_turns_at_constant_load() {
    let body = FemBody {
        base: BaseSupport::RigidPlate,
        ..FemBody::reference()
    };
    let weight = body.mass() * body.gravity;
    let s_n_small_displacement =
        body.width * weight * body.height.powi(2) / (2.0 * body.flexural_rigidity() * L * L);
    let n = 100_000;
    let (int_u, int_u_xi) = (0..n).fold((0.0, 0.0), |(a, b), k| {
        let xi = (k as f64 + 0.5) / n as f64;
        let u = cantilever_mode(xi) / n as f64;
        (a + u, b + u * xi)
    });
    let plateau = weight * body.width / 2.0 * int_u / (body.height * int_u_xi);
    let qs: Vec<f64> = (1..=100).map(|k| 0.002 * k as f64).collect();
    let curve = pushover(&body, 8, 40, false, &qs).unwrap();
    // The heel lifts at a point of the curve, or the turn about the toe that follows is at once
    // without stiffness to round-off and ends the curve there (both happen, by an ulp of EI).
    let lifted = curve.points.iter().position(|p| p.heel_lifted);
    let q_lift = match lifted {
        Some(lift) => curve.points[lift].q,
        None => curve
            .free_rotation_at
            .expect("the heel lifts, or the free turn about the toe ends the curve"),
    };
    assert!(
        (q_lift / s_n_small_displacement - 1.0).abs() < 0.05,
        "lifted at {q_lift}, expected {s_n_small_displacement}"
    );
    for p in &curve.points[lifted.unwrap_or(curve.points.len())..] {
        assert!(
            (p.base_shear / plateau - 1.0).abs() < 0.02,
            "{} at {}",
            p.base_shear,
            p.q
        );
    }
    if let (Some(stop), Some(_)) = (curve.free_rotation_at, lifted) {
        assert!(stop > q_lift);
        assert_eq!(curve.points.len(), qs.iter().filter(|q| **q < stop).count());
    }
}

/// The stiff body on a rigid plate lifts off where the SDOF model does (s_n; gravity parameter
/// 0.185 leaves a P-Delta shift of 2-3 %, book/src/model.md §7a), while the flexible base of the
/// same body opens at its heel well before: a continuum's base pressure is not uniform.
#[test]
fn rigid_plate_lifts_at_sdof_uplift_flexible_base_opens_earlier() {
    let stiff = body_with_modulus(5.0e8);
    let (s_n, _) = sdof_uplift(&stiff);
    let qs: Vec<f64> = (1..=300).map(|k| k as f64 * 0.005 * s_n).collect();
    let plate = FemBody {
        base: BaseSupport::RigidPlate,
        ..stiff.clone()
    };
    let plate_lift = first_heel_lift(&plate, true, &qs);
    assert!(
        (plate_lift.q / s_n - 1.0).abs() < 0.05,
        "plate lifted at {}, s_n {s_n}",
        plate_lift.q
    );
    let flexible_lift = first_heel_lift(&stiff, true, &qs);
    assert!(flexible_lift.q < 0.7 * plate_lift.q);
    assert!(!flexible_lift.uplift);
}

/// Linearised rigid block released from θ0 about its toe: θ - B/H = (θ0 - B/H) cosh(p t),
/// p² = M g (H/2)/I_toe = 3 g H/(2 (B² + H²)); it lands when θ = 0.
#[test]
fn released_tilted_body_lands_like_rigid_block() {
    for base in [BaseSupport::Flexible, BaseSupport::RigidPlate] {
        released_tilted_body_lands(FemBody {
            base,
            ..body_with_modulus(5.0e8)
        });
    }
}

fn released_tilted_body_lands(body: FemBody) {
    let (b, h) = (body.width, body.height);
    let theta0 = 0.05;
    let p = (3.0 * body.gravity * h / (2.0 * (b * b + h * h))).sqrt();
    let t_land = (1.0 / (1.0 - theta0 / (b / h))).acosh() / p;
    let settings = FemSettings {
        nx: 4,
        ny: 20,
        dt: 0.001,
        duration: 0.7,
        scheme: TimeScheme::average_acceleration(),
        initial_rotation: theta0,
        ..FemSettings::paper()
    };
    let result = simulate_fem(&body, &settings, &|_| 0.0).unwrap();
    let first_landing = result
        .events
        .iter()
        .find(|e| e.from == ContactState::Free && e.to == ContactState::Fixed)
        .expect("the body lands");
    assert!(
        (first_landing.t / t_land - 1.0).abs() < 0.03,
        "{:?}: landed at {} s, rigid block {t_land} s",
        body.base,
        first_landing.t
    );
    let max_speed = result
        .steps
        .iter()
        .map(|s| s.top_velocity.abs())
        .fold(0.0, f64::max);
    let lowest = result
        .steps
        .iter()
        .map(|s| s.lowest_base_uy)
        .fold(f64::INFINITY, f64::min);
    // a landing node overshoots the floor by at most its speed x dt before it is set back
    assert!(
        lowest > -max_speed * b / h * settings.dt * 2.0,
        "{:?}: {lowest}",
        body.base
    );
    assert!(result.overturned_at.is_none());
}

#[test]
fn frictionless_base_slides_under_floor_acceleration() {
    let body = FemBody::reference();
    let acc = 2.0;
    let run = |mu_s: f64, mu_k: f64, acc: f64| {
        let settings = FemSettings {
            dt: 0.005,
            duration: 1.0,
            scheme: TimeScheme::average_acceleration(),
            mu_s,
            mu_k,
            ..FemSettings::paper()
        };
        simulate_fem(&body, &settings, &|t| if t > 0.0 { acc } else { 0.0 }).unwrap()
    };
    let frictionless = run(0.0, 0.0, acc);
    let last = frictionless.steps.last().unwrap();
    // free rigid translation relative to the floor: -a t²/2
    let expected = -acc * last.t * last.t / 2.0;
    assert!(
        (last.slipping / expected - 1.0).abs() < 0.02,
        "{}",
        last.slipping
    );
    // with μs = 0.8 and a step of 0.2 m/s² (base moment, dynamically amplified, far below the
    // M g B/4 at which a corner of the 2-element base unloads) nothing slides or lifts
    let sticking = run(0.8, 0.4, 0.2);
    assert!(sticking.events.is_empty(), "{:?}", sticking.events.first());
    assert!(sticking.steps.iter().all(|s| s.slipping == 0.0));
}

fn paper_floor_acceleration(t: f64) -> f64 {
    if t < 0.412 {
        -133.694 * t + 1043.29 * t * t - 1707.09 * t * t * t
    } else {
        5.0 * (2.0 * PI * t).sin()
    }
}

#[test]
fn paper_run_parts_sum_and_snapshots() {
    let body = FemBody::reference();
    let settings = FemSettings {
        snapshot_times: vec![0.9, 1.0, 1.1],
        ..FemSettings::paper()
    };
    let result = simulate_fem(&body, &settings, &paper_floor_acceleration).unwrap();
    assert_eq!(result.steps.len(), 846);
    for s in &result.steps {
        let sum = s.rocking + s.slipping + s.flexural + s.shearing;
        assert!((sum - s.q).abs() < 1e-12);
        assert_eq!(s.base_states.len(), 3);
    }
    assert_eq!(result.snapshots.len(), 3);
    assert!(result.snapshots[0].t >= 0.9 && result.snapshots[0].t < 0.9 + settings.dt);
    assert!(result.events.iter().any(|e| e.to == ContactState::Free));
}

#[test]
fn invalid_input_is_reported_not_panicked() {
    let body = FemBody::reference();
    let name_of = |r: Result<FemResult, FemError>| match r {
        Err(FemError::InvalidParameter { name, .. }) => name,
        other => panic!("expected InvalidParameter, got {other:?}"),
    };
    let zero = |_: f64| 0.0;
    let bad = |f: &dyn Fn(&mut FemSettings)| {
        let mut s = FemSettings::paper();
        f(&mut s);
        name_of(simulate_fem(&body, &s, &zero))
    };
    assert_eq!(bad(&|s| s.nx = 0), "nx");
    assert_eq!(bad(&|s| s.ny = 0), "ny");
    assert_eq!(bad(&|s| s.dt = 0.0), "dt");
    assert_eq!(bad(&|s| s.dt = f64::NAN), "dt");
    assert_eq!(bad(&|s| s.mu_k = 0.9), "mu_k");
    assert_eq!(
        bad(&|s| s.scheme = TimeScheme::Newmark {
            beta: 0.0,
            gamma: 0.5
        }),
        "beta"
    );
    assert_eq!(
        bad(&|s| s.scheme = TimeScheme::WilsonTheta { theta: 0.5 }),
        "theta"
    );
    let bad_body = |f: &dyn Fn(&mut FemBody)| {
        let mut b = FemBody::reference();
        f(&mut b);
        name_of(simulate_fem(&b, &FemSettings::paper(), &zero))
    };
    assert_eq!(bad_body(&|b| b.poisson_ratio = 0.5), "poisson_ratio");
    assert_eq!(bad_body(&|b| b.youngs_modulus = -1.0), "youngs_modulus");
    assert_eq!(bad_body(&|b| b.height = 0.0), "height");
    assert!(matches!(
        fixed_base_periods(&body, 2, 5, false, 0),
        Err(FemError::InvalidParameter { name: "count", .. })
    ));
    assert!(matches!(
        pushover(&body, 2, 5, true, &[f64::INFINITY]),
        Err(FemError::InvalidParameter { .. })
    ));
}

/// Without P-Delta a coarse mesh loses all resistance to turning about the toe once it stands
/// on it: the sweep must end there and say where, on both bases, not fail.
#[test]
fn pushover_without_p_delta_ends_where_the_body_turns_freely() {
    for base in [BaseSupport::Flexible, BaseSupport::RigidPlate] {
        let body = FemBody {
            height: 3.0,
            width: 0.6,
            density: 500.0,
            base,
            ..FemBody::reference()
        };
        let qs: Vec<f64> = (1..=400).map(|k| body.width * k as f64 / 400.0).collect();
        let curve = pushover(&body, 3, 6, false, &qs).unwrap();
        let stop = curve.free_rotation_at.expect("the sweep ends");
        assert!(stop < body.width, "{base:?}: {stop}");
        assert_eq!(curve.points.len(), qs.iter().filter(|q| **q < stop).count());
    }
}
