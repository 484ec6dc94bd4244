//! Fragility fits against closed forms and against data drawn from known distributions.

use flexrock_core::analysis::fragility::bootstrap::{resample, SplitMix64};
use flexrock_core::analysis::fragility::{
    fit_capacities, fit_stripes, normal, Capacity, FitError, Lognormal, Stripe,
};

/// A standard normal draw (Box-Muller), from `rng`.
fn gaussian(rng: &mut SplitMix64) -> f64 {
    let u1 = ((rng.next_u64() >> 11) as f64 + 0.5) / (1u64 << 53) as f64;
    let u2 = ((rng.next_u64() >> 11) as f64) / (1u64 << 53) as f64;
    (-2.0 * u1.ln()).sqrt() * (2.0 * std::f64::consts::PI * u2).cos()
}

#[test]
fn capacities_fit_by_their_moments() {
    // ln c = -1, 0, 1: mean 0, sum of squares 2; beta = sqrt(2/3) with n, 1 with n - 1.
    let c = [-1.0f64, 0.0, 1.0].map(|y| Capacity::Observed(y.exp()));
    let fit = fit_capacities(&c).unwrap();
    assert!((fit.fit.theta - 1.0).abs() < 1e-15);
    assert!((fit.fit.beta - (2.0f64 / 3.0).sqrt()).abs() < 1e-15);
    assert!((fit.beta_unbiased.unwrap() - 1.0).abs() < 1e-15);
    assert_eq!(fit.method, "moments");
}

#[test]
fn capacities_drawn_from_a_known_lognormal_give_it_back() {
    // 4000 draws of theta = 0.5 g, beta = 0.4: the standard error of ln theta is
    // 0.4 / sqrt(4000) = 0.0063, of beta 0.4 / sqrt(8000) = 0.0045; allowed 4 of each.
    let mut rng = SplitMix64::new(7);
    let draws: Vec<f64> = (0..4000)
        .map(|_| (0.5f64.ln() + 0.4 * gaussian(&mut rng)).exp())
        .collect();
    let full: Vec<Capacity> = draws.iter().map(|&c| Capacity::Observed(c)).collect();
    let fit = fit_capacities(&full).unwrap().fit;
    assert!(
        (fit.theta.ln() - 0.5f64.ln()).abs() < 4.0 * 0.0063,
        "{fit:?}"
    );
    assert!((fit.beta - 0.4).abs() < 4.0 * 0.0045, "{fit:?}");
    // The same draws censored at 0.6 g (about 32 % of them): the censored likelihood still
    // finds the distribution, where the observed ones alone would not.
    let censored: Vec<Capacity> = draws
        .iter()
        .map(|&c| {
            if c > 0.6 {
                Capacity::Censored(0.6)
            } else {
                Capacity::Observed(c)
            }
        })
        .collect();
    let fit = fit_capacities(&censored).unwrap();
    assert_eq!(fit.method, "censored-mle");
    assert!(fit.censored > 1000, "{}", fit.censored);
    assert!(
        (fit.fit.theta.ln() - 0.5f64.ln()).abs() < 4.0 * 0.008,
        "{fit:?}"
    );
    assert!((fit.fit.beta - 0.4).abs() < 4.0 * 0.006, "{fit:?}");
}

#[test]
fn the_censored_fit_solves_the_score_equations() {
    // The score equations of the censored likelihood, differentiated by hand, vanish at the
    // fit: d/dmu = sum z_i / beta + sum h(z_u) / beta, d/dbeta = sum (z_i^2 - 1) / beta
    // + sum z_u h(z_u) / beta, h the normal hazard phi / (1 - Phi).
    let obs = [0.21, 0.35, 0.28, 0.52, 0.44];
    let cens = [0.6, 0.6];
    let mut c: Vec<Capacity> = obs.iter().map(|&x| Capacity::Observed(x)).collect();
    c.extend(cens.iter().map(|&x| Capacity::Censored(x)));
    let Lognormal { theta, beta } = fit_capacities(&c).unwrap().fit;
    let phi = |z: f64| (-0.5 * z * z).exp() / (2.0 * std::f64::consts::PI).sqrt();
    let hazard = |z: f64| phi(z) / (1.0 - normal::cdf(z));
    let z = |x: f64| (x / theta).ln() / beta;
    let d_mu: f64 =
        obs.iter().map(|&x| z(x)).sum::<f64>() + cens.iter().map(|&u| hazard(z(u))).sum::<f64>();
    let d_beta: f64 = obs.iter().map(|&x| z(x) * z(x) - 1.0).sum::<f64>()
        + cens.iter().map(|&u| z(u) * hazard(z(u))).sum::<f64>();
    // A search without derivatives stops where the likelihood is flat to rounding: about
    // 1e-8 relative in the parameters.
    assert!(d_mu.abs() < 1e-6 && d_beta.abs() < 1e-6, "{d_mu} {d_beta}");
}

#[test]
fn two_stripes_fit_in_closed_form() {
    // 1 of 4 at 0.2 g and 3 of 4 at 0.4 g: the likelihood's maximum passes the curve through
    // both fractions, Phi^-1(1/4) = -0.6744897501960817 at 0.2 and +0.674... at 0.4, so
    // theta = sqrt(0.2 x 0.4) and beta = ln 2 / (2 x 0.6744897501960817).
    let fit = fit_stripes(&[
        Stripe {
            level: 0.2,
            records: 4,
            damaged: 1,
        },
        Stripe {
            level: 0.4,
            records: 4,
            damaged: 3,
        },
    ])
    .unwrap();
    assert!((fit.theta - 0.08f64.sqrt()).abs() < 1e-7, "{fit:?}");
    assert!(
        (fit.beta - 2f64.ln() / (2.0 * 0.674_489_750_196_081_7)).abs() < 1e-7,
        "{fit:?}"
    );
}

#[test]
fn stripes_counted_from_known_probabilities_give_them_back() {
    // A million records a stripe, counted as round(n P): the fit returns theta = 0.35,
    // beta = 0.45 to the rounding of the counts.
    let truth = Lognormal {
        theta: 0.35,
        beta: 0.45,
    };
    let n = 1_000_000;
    let stripes: Vec<Stripe> = [0.1, 0.2, 0.3, 0.4, 0.6, 0.8]
        .iter()
        .map(|&level| Stripe {
            level,
            records: n,
            damaged: (n as f64 * truth.probability(level)).round() as usize,
        })
        .collect();
    let fit = fit_stripes(&stripes).unwrap();
    assert!((fit.theta - 0.35).abs() < 1e-5, "{fit:?}");
    assert!((fit.beta - 0.45).abs() < 1e-5, "{fit:?}");
}

#[test]
fn data_without_a_finite_fit_are_refused() {
    let one = fit_capacities(&[Capacity::Observed(0.3)]);
    assert_eq!(one, Err(FitError::TooFewRecords { records: 1 }));
    let same = fit_capacities(&[Capacity::Observed(0.3), Capacity::Observed(0.3)]);
    assert!(matches!(same, Err(FitError::Degenerate(m)) if m.contains("zero dispersion")));
    let censored = fit_capacities(&[Capacity::Observed(0.3), Capacity::Censored(1.0)]);
    assert!(matches!(censored, Err(FitError::Degenerate(m)) if m.contains("1 of 2")));
    let separated = fit_stripes(&[
        Stripe {
            level: 0.2,
            records: 4,
            damaged: 0,
        },
        Stripe {
            level: 0.4,
            records: 4,
            damaged: 4,
        },
    ]);
    assert!(matches!(separated, Err(FitError::Degenerate(m)) if m.contains("zero dispersion")));
    let none = fit_stripes(&[Stripe {
        level: 0.2,
        records: 4,
        damaged: 0,
    }]);
    assert!(matches!(none, Err(FitError::Degenerate(m)) if m.contains("above the highest")));
}

#[test]
fn the_bootstrap_is_fixed_by_its_seed() {
    let c: Vec<Capacity> = [0.21, 0.35, 0.28, 0.52, 0.44]
        .iter()
        .map(|&x| Capacity::Observed(x))
        .collect();
    let fit = |drawn: &[usize]| {
        let sample: Vec<Capacity> = drawn.iter().map(|&i| c[i]).collect();
        fit_capacities(&sample).map(|f| f.fit.theta)
    };
    let (a, failed_a) = resample(c.len(), 200, 42, fit);
    let (b, failed_b) = resample(c.len(), 200, 42, fit);
    assert_eq!((a.clone(), failed_a), (b, failed_b));
    let (other, _) = resample(c.len(), 200, 43, fit);
    assert_ne!(a, other);
    // Every bootstrap median lies between the smallest and the largest capacity.
    assert!(a.iter().all(|&t| (0.21..=0.52).contains(&t)));
}
