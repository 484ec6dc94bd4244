//! The `[body]` section's rules: the body from its keys (the mass from the density or given, the
//! stiffness from the modulus or given), and the refusal of a body that cannot stand.

use super::schema::{BodySection, DEFAULT_DAMPING_RATIO, DEFAULT_DEPTH, DEFAULT_GRAVITY};
use crate::error::{Error, Result};
use crate::physics::body::{positive, Body, ConstantSet, SelfWeight, DEFAULT_LANDING_RESTITUTION};
use crate::physics::constants::Constants;

/// Exactly one of a set of alternative keys must be given.
fn exactly_one(section: &str, alternatives: &[(&str, Option<f64>)]) -> Result<(usize, f64)> {
    let given: Vec<(usize, &str, f64)> = alternatives
        .iter()
        .enumerate()
        .filter_map(|(i, (k, v))| v.map(|v| (i, *k, v)))
        .collect();
    // Built only for a message: a sweep reads a body for every point.
    let names = || {
        alternatives
            .iter()
            .map(|(k, _)| format!("{section}.{k}"))
            .collect::<Vec<_>>()
            .join(", ")
    };
    match given.as_slice() {
        [(i, _, v)] => Ok((*i, *v)),
        [] => Err(Error::invalid(
            &format!("{section}.{}", alternatives[0].0),
            "(missing)",
            &format!("give exactly one of {}", names()),
        )),
        [(_, k1, v1), (_, k2, v2), ..] => Err(Error::invalid(
            &format!("{section}.{k1}"),
            format!("{v1} (and {section}.{k2} = {v2})"),
            &format!("give exactly one of {}, not several", names()),
        )),
    }
}

pub(super) fn body_from_section(s: &BodySection) -> Result<Body> {
    let constant_set = match s.constants.as_deref().unwrap_or("exact") {
        "exact" => ConstantSet::Exact,
        "paper" => ConstantSet::Paper,
        other => {
            return Err(Error::invalid(
                "body.constants",
                format!("\"{other}\""),
                "must be \"exact\" or \"paper\"",
            ))
        }
    };
    let self_weight = match s.self_weight.as_deref() {
        None => SelfWeight::Paper,
        Some(name) => SelfWeight::from_name(name).ok_or_else(|| {
            Error::invalid(
                "body.self_weight",
                format!("\"{name}\""),
                "must be \"paper\" (the paper's model) or \"consistent\" (the weight in the bending)",
            )
        })?,
    };
    if self_weight == SelfWeight::Consistent && constant_set == ConstantSet::Paper {
        return Err(Error::invalid(
            "body.constants",
            "\"paper\" (with body.self_weight = \"consistent\")",
            "the paper's rounded constants belong to the paper's mode shape; the consistent \
             variant computes its own, so use constants = \"exact\"",
        ));
    }
    positive("body.height", s.height)?;
    positive("body.width", s.width)?;
    let depth = s.depth.unwrap_or(DEFAULT_DEPTH);
    positive("body.depth", depth)?;

    let mass = match exactly_one("body", &[("density", s.density), ("mass", s.mass)])? {
        (0, density) => {
            positive("body.density", density)?;
            derived_product(
                "mass M = density H B D",
                "kg",
                crate::physics::body::prism_mass(density, s.height, s.width, depth),
                &[
                    ("body.density", density),
                    ("body.height", s.height),
                    ("body.width", s.width),
                    ("body.depth", depth),
                ],
            )?
        }
        (_, mass) => {
            positive("body.mass", mass)?;
            mass
        }
    };
    let damping_ratio = s.damping_ratio.unwrap_or(DEFAULT_DAMPING_RATIO);
    if !damping_ratio.is_finite() {
        return Err(Error::invalid(
            "body.damping_ratio",
            damping_ratio,
            "the damping ratio must lie in [0, 1)",
        ));
    }
    let mut body = Body {
        height: s.height,
        width: s.width,
        depth,
        mass,
        flexural_rigidity: f64::NAN,
        damping_ratio,
        gravity: s.gravity.unwrap_or(DEFAULT_GRAVITY),
        constant_set,
        self_weight,
        landing_restitution: s.landing_restitution.unwrap_or(DEFAULT_LANDING_RESTITUTION),
        damping_while_rocking: s.damping_while_rocking.unwrap_or(true),
    };
    body.flexural_rigidity = match exactly_one(
        "body",
        &[
            ("youngs_modulus", s.youngs_modulus),
            ("flexural_rigidity", s.flexural_rigidity),
            ("period", s.period),
        ],
    )? {
        (0, e) => {
            positive("body.youngs_modulus", e)?;
            derived_product(
                "flexural rigidity EI = E D B^3/12",
                "N m^2",
                crate::physics::body::solid_section_flexural_rigidity(e, s.width, depth),
                &[
                    ("body.youngs_modulus", e),
                    ("body.width", s.width),
                    ("body.depth", depth),
                ],
            )?
        }
        (1, ei) => {
            positive("body.flexural_rigidity", ei)?;
            ei
        }
        (_, period) => {
            positive("body.period", period)?;
            positive("body.gravity", body.gravity)?;
            // EI grows as M H^3 / T^2: it leaves the range of numbers for a period far from
            // any body's (2.2e-308 s made it inf).
            let (mass_key, mass_value) = match s.density {
                Some(density) => ("body.density", density),
                None => ("body.mass", body.mass),
            };
            derived_product(
                "flexural rigidity EI found from the period",
                "N m^2",
                Constants::flexural_rigidity_for_period(period, &body)?,
                &[
                    ("body.period", period),
                    (mass_key, mass_value),
                    ("body.height", s.height),
                ],
            )?
        }
    };
    Ok(body.validated()?)
}

/// `value`, a product of the keys `factors` (each finite and positive), when it is finite and
/// positive; otherwise the product overflowed or underflowed, and the factor farthest from 1 (the
/// key the user most likely mistyped) is blamed with its own value.
fn derived_product(what: &str, unit: &str, value: f64, factors: &[(&str, f64)]) -> Result<f64> {
    if value.is_normal() && value > 0.0 {
        return Ok(value);
    }
    let (key, factor) = factors
        .iter()
        .copied()
        .max_by(|a, b| a.1.ln().abs().total_cmp(&b.1.ln().abs()))
        .unwrap_or(("body", value));
    Err(Error::invalid(
        key,
        factor,
        &format!(
            "with it the {what} is {} {unit}, beyond the range of numbers, whose smallest normal \
             positive value is 2.2e-308 (give sizes in m, densities in kg/m^3, moduli in Pa)",
            crate::base::format::shortest(value)
        ),
    ))
}

/// Refuses a body whose uplift displacement s_n is not below its width B: it would lift off under
/// its own weight, and eq. 16 has no meaning. (In the paper's model self-weight buckling comes
/// first; with the weight in the bending s_n can reach B well short of buckling.) The message
/// names the stiffness key the file set, with its value, and the keys that move s_n.
pub(super) fn check_stands_up(s: &BodySection, body: &Body, constants: &Constants) -> Result<()> {
    let s_n = constants.uplift_displacement;
    if s_n < body.width {
        return Ok(());
    }
    let (key, value) = [
        ("body.youngs_modulus", s.youngs_modulus),
        ("body.flexural_rigidity", s.flexural_rigidity),
        ("body.period", s.period),
    ]
    .into_iter()
    .find_map(|(key, value)| value.map(|v| (key, v)))
    .unwrap_or(("body.flexural_rigidity", body.flexural_rigidity));
    let mass_key = if s.mass.is_some() {
        "body.mass"
    } else {
        "body.density"
    };
    let remedy = if key == "body.period" {
        "shorten body.period"
    } else {
        "raise it"
    };
    Err(Error::invalid(
        key,
        value,
        &format!(
            "the body is unstable under its own weight: its derived uplift displacement s_n = {} m \
             (body.self_weight = \"{}\") must be less than the width B = {} m (body.width); \
             {remedy}, or lower {mass_key} or body.height",
            crate::base::format::significant(s_n, 6),
            body.self_weight.name(),
            crate::base::format::shortest(body.width),
        ),
    ))
}

#[cfg(test)]
mod body_cache_tests {
    use super::*;
    use crate::model::{read_model_table, read_schema, RecordCache};
    use std::cell::Cell;
    use std::path::Path;

    fn section() -> BodySection {
        let table = read_model_table(
            &Path::new(env!("CARGO_MANIFEST_DIR")).join("../models/pulse-map.toml"),
        )
        .expect("a model of the repository")
        .1;
        read_schema(&table, &[], Path::new("model.toml"))
            .expect("it reads")
            .body
    }

    /// The cache gives the body the section reads to, reads a section again unless every
    /// number has the same bits and every text is the same, and never keeps a refusal.
    #[test]
    fn a_body_is_read_again_unless_its_section_is_the_same() {
        let cache = RecordCache::default();
        let reads = Cell::new(0);
        let read = |s: &BodySection| {
            reads.set(reads.get() + 1);
            body_from_section(s)
        };
        let base = section();
        let first = cache.body(&base, read).expect("a body");
        assert_eq!(
            format!("{first:?}"),
            format!("{:?}", body_from_section(&base).unwrap())
        );
        cache.body(&base.clone(), read).expect("a body");
        assert_eq!(reads.get(), 1, "the same section is read once");
        let mut taller = base.clone();
        taller.height = f64::from_bits(base.height.to_bits() + 1);
        let body = cache.body(&taller, read).expect("a body");
        assert_eq!(body.height, taller.height);
        assert_eq!(reads.get(), 2);
        let mut signed = taller.clone();
        signed.poisson_ratio = Some(-0.0);
        let mut unsigned = taller.clone();
        unsigned.poisson_ratio = Some(0.0);
        cache.body(&signed, read).expect("a body");
        cache.body(&unsigned, read).expect("a body");
        let mut paper = unsigned.clone();
        paper.constants = Some("paper".into());
        cache.body(&paper, read).expect("a body");
        assert_eq!(
            reads.get(),
            5,
            "-0 and 0, and another text, are other sections"
        );
        let mut refused = paper.clone();
        refused.width = -1.0;
        assert!(cache.body(&refused, read).is_err());
        assert!(cache.body(&refused, read).is_err());
        assert_eq!(reads.get(), 7, "a refusal is not kept");
    }
}
