//! The body's landing restitution and whether the damping acts while rocking (`[body]`
//! `landing_restitution` and `damping_while_rocking`): the exact method against the closed form
//! of undamped rocking and the landing reset q' -> e q'/zetaL, and the other methods against the
//! exact one.

use crate::common;

use flexrock_core::physics::automaton::{Automaton, EventKind, Mode};

/// The reference body (damped before uplift), the landing restitution 0.8 and no damping while
/// rocking, released at q0 = 0.4 m moving outwards at 0.3 m/s with no floor motion.
fn released(solver: &str) -> String {
    format!(
        "[body]\nheight = 4.0\nwidth = 0.7\ndepth = 1.0\ndensity = 600.0\nyoungs_modulus = 5.0e6\n\
         damping_ratio = 0.05\ngravity = 9.81\nlanding_restitution = 0.8\n\
         damping_while_rocking = false\n[excitation]\nkind = \"free\"\n\
         [simulation]\nduration = 3.0\nq0 = 0.4\nqdot0 = 0.3\n[solver]\n{solver}"
    )
}

/// While rocking right x = q - q_topple obeys x'' + k x = 0 with k = nu2 F'/Me < 0 when the
/// damping does not act then, so x = x0 cosh(mu t) + v0/mu sinh(mu t), mu = sqrt(-k). The first
/// landing is where x = s_n - q_topple, found here by bisection on that formula; there q' jumps
/// to e q'/zetaL. Within the rocking flight the SDOF energy Me q'^2/2 + V(q) stays what it was at
/// the release.
#[test]
fn undamped_rocking_is_the_cosh_and_the_landing_takes_e() {
    let text = released("method = \"exact\"\noutput_dt = 0.001\n");
    let model = common::model(&text);
    let c = &model.constants;
    let mu = (-c.nu2 * c.rocking_stiffness / c.generalised_mass).sqrt();
    let (s_n, topple) = (c.uplift_displacement, c.topple_displacement);
    let (x0, v0) = (0.4 - topple, 0.3);
    let x = |t: f64| x0 * (mu * t).cosh() + v0 / mu * (mu * t).sinh();
    let v = |t: f64| x0 * mu * (mu * t).sinh() + v0 * (mu * t).cosh();
    // x rises to its top at tanh(mu t) = -v0/(mu x0), then falls through s_n - q_topple.
    let top = (-v0 / (mu * x0)).atanh() / mu;
    let (mut low, mut high) = (top, top + 1.0);
    assert!(x(high) < s_n - topple, "the bracket holds the landing");
    for _ in 0..200 {
        let mid = 0.5 * (low + high);
        if x(mid) > s_n - topple {
            low = mid;
        } else {
            high = mid;
        }
    }
    let landing_time = 0.5 * (low + high);
    let landing_speed = v(landing_time);

    let sol = flexrock_core::simulate::simulate(&model).expect("the exact method solves");
    let first = &sol.events[0];
    assert_eq!(first.kind, EventKind::Landing, "{:#?}", sol.events);
    assert!(
        (first.t - landing_time).abs() <= 1e-12 * landing_time,
        "landing at {} against {landing_time}",
        first.t
    );
    assert!(
        (first.qdot_before - landing_speed).abs() <= 1e-12 * landing_speed.abs(),
        "q' before the landing {} against {landing_speed}",
        first.qdot_before
    );
    let ratio = first.qdot_after / first.qdot_before;
    let expected = 0.8 / c.zeta_landing;
    assert!(
        (ratio - expected).abs() <= 4.0 * f64::EPSILON * expected,
        "q' after/before the landing {ratio} against e/zetaL = {expected}"
    );

    let automaton = Automaton::new(c);
    let released = automaton.energy(Mode::RockRight, 0.4, 0.3);
    let rocking: Vec<_> = sol
        .samples
        .iter()
        .filter(|s| s.t < first.t && s.mode == Mode::RockRight)
        .collect();
    assert!(rocking.len() > 100, "{} samples", rocking.len());
    for s in rocking {
        let energy = automaton.energy(s.mode, s.q, s.qdot);
        assert!(
            (energy - released).abs() <= 1e-12 * released,
            "t = {}: energy {energy} against {released}",
            s.t
        );
    }
    // Each landing, not only the first, takes e; the uplifts keep zetaU.
    for event in &sol.events {
        let ratio = event.qdot_after / event.qdot_before;
        let expected = match event.kind {
            EventKind::Landing => 0.8 / c.zeta_landing,
            _ => c.zeta_uplift,
        };
        assert!(
            (ratio - expected).abs() <= 4.0 * f64::EPSILON * expected,
            "{event:?}"
        );
    }
    assert!(sol.events.len() >= 3, "{:#?}", sol.events);
}

/// The energy books of every method close with both keys set: the landing's extra loss is in
/// the jump of the SDOF energy at the event, and the damping work while rocking is none.
#[test]
fn the_energy_books_close_with_e_and_no_damping_while_rocking() {
    for (solver, bound) in [
        ("method = \"exact\"\n", 1e-12),
        ("method = \"tsit45\"\nrtol = 1e-10\natol = 1e-12\n", 1e-7),
        (
            "method = \"newmark\"\ndt = 0.0005\nnewmark_variant = \"substep\"\n",
            1e-3,
        ),
    ] {
        let sol = common::solve(&released(solver));
        assert!(
            sol.max_energy_residual <= bound * sol.energy_scale,
            "{solver}: residual {} of {}",
            sol.max_energy_residual,
            sol.energy_scale
        );
        let rocking_work: Vec<_> = sol
            .samples
            .windows(2)
            .filter(|w| w[0].mode == Mode::RockRight && w[1].mode == Mode::RockRight)
            .map(|w| w[1].work_damping - w[0].work_damping)
            .collect();
        assert!(!rocking_work.is_empty(), "{solver}");
        assert!(
            rocking_work.iter().all(|&w| w == 0.0),
            "{solver}: damping work while rocking"
        );
    }
}

/// Under the paper's sine, with both keys set, tsit45 and sub-stepping Newmark find the exact
/// method's events, at the times their tolerances allow: tsit45 at rtol 1e-10 came within
/// 4e-11 s of them, second-order Newmark at dt = 0.5 ms within 2e-6 s.
#[test]
fn the_methods_agree_with_both_keys_set() {
    let text = |solver: &str| {
        common::reference_body(&format!(
            "landing_restitution = 0.7\ndamping_while_rocking = false\n\
             [excitation]\nkind = \"paper-sine\"\namplitude = 5.0\nperiod = 1.0\nramp = 0.412\n\
             [simulation]\nduration = 6.0\n[solver]\n{solver}"
        ))
    };
    let exact = common::solve(&text("method = \"exact\"\n"));
    assert!(exact.events.len() >= 6, "{:#?}", exact.events);
    for (solver, tolerance) in [
        ("method = \"tsit45\"\nrtol = 1e-10\natol = 1e-12\n", 1e-8),
        (
            "method = \"newmark\"\ndt = 0.0005\nnewmark_variant = \"substep\"\n",
            1e-4,
        ),
    ] {
        let other = common::solve(&text(solver));
        assert_eq!(other.events.len(), exact.events.len(), "{solver}");
        for (a, b) in other.events.iter().zip(&exact.events) {
            assert_eq!(a.kind, b.kind, "{solver}");
            assert!(
                (a.t - b.t).abs() < tolerance,
                "{solver}: {} against {}",
                a.t,
                b.t
            );
        }
    }
}
