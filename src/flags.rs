//! The command line's names for model-file keys. The core names a value by its key
//! (`solver.rtol`, `fem.nx`); a value given by a flag is named in what the command line prints by
//! the flag that gave it (`--rtol (sets solver.rtol)`, `--nx`, `--set excitation.period`).

use flexrock_core::error::Error;
use flexrock_core::model::{FemOverrides, Overrides};

/// The flag that set the model-file key `key`, as a message names it, if a flag did.
fn flag_for(key: &str, overrides: &Overrides, fem: &FemOverrides) -> Option<String> {
    let solver_flag = match key {
        "solver.method" if overrides.method.is_some() => Some("--method"),
        "solver.rtol" if overrides.rtol.is_some() => Some("--rtol"),
        "solver.atol" if overrides.atol.is_some() => Some("--atol"),
        "solver.dt" if overrides.dt.is_some() => Some("--dt"),
        "solver.newmark_variant" if overrides.newmark_variant.is_some() => Some("--variant"),
        "simulation.duration" if overrides.duration.is_some() => Some("--duration"),
        _ => None,
    };
    if let Some(flag) = solver_flag {
        return Some(format!("{flag} (sets {key})"));
    }
    let fem_flag = match key {
        "fem.nx" if fem.nx.is_some() => Some("--nx"),
        "fem.ny" if fem.ny.is_some() => Some("--ny"),
        "fem.dt" if fem.dt.is_some() => Some("--dt"),
        "fem.scheme" if fem.scheme.is_some() => Some("--scheme"),
        _ => None,
    };
    if let Some(flag) = fem_flag {
        return Some(flag.to_string());
    }
    overrides
        .settings
        .iter()
        .any(|s| s.key == key)
        .then(|| format!("--set {key}"))
}

/// `error` with every key a flag set named by that flag (a key list such as `fem.nx, fem.ny`
/// part by part); other errors are returned unchanged.
pub fn named_by_flags(
    error: impl Into<crate::Error>,
    overrides: &Overrides,
    fem: &FemOverrides,
) -> crate::Error {
    match error.into() {
        crate::Error::Core(e) => crate::Error::Core(core_named_by_flags(e, overrides, fem)),
        other => other,
    }
}

fn core_named_by_flags(error: Error, overrides: &Overrides, fem: &FemOverrides) -> Error {
    match error {
        Error::InvalidParameter { key, value, rule } => {
            let named: Vec<String> = key
                .split(", ")
                .map(|k| flag_for(k, overrides, fem).unwrap_or_else(|| k.to_string()))
                .collect();
            let rule = match rule.strip_suffix(flexrock_core::model::DT_WITHOUT_NEWMARK) {
                Some(rule) if overrides.dt.is_some() => {
                    format!("{rule} (--dt needs --method newmark)")
                }
                _ => rule,
            };
            Error::InvalidParameter {
                key: named.join(", "),
                value,
                rule,
            }
        }
        Error::InModel { path, source } => Error::InModel {
            path,
            source: Box::new(core_named_by_flags(*source, overrides, fem)),
        },
        Error::Record { key, source } => Error::Record {
            key: flag_for(&key, overrides, fem).unwrap_or(key),
            source,
        },
        other => other,
    }
}

/// The flag of a sweep request's value named by the sweep file's key (`vary KEY`,
/// `find_min KEY`, `scan`, `tol`, `chunk_size`, `rigid_form`, `rigid_overturning`,
/// `rigid_restitution`), as the core names it.
fn sweep_flag_for(key: &str) -> Option<String> {
    let (name, rest) = match key.split_once(' ') {
        Some((name, rest)) => (name, Some(rest)),
        None => (key, None),
    };
    let flag = match name {
        "vary" => "--vary",
        "find_min" => "--find-min",
        "scan" if rest.is_none() => "--scan",
        "tol" if rest.is_none() => "--tol",
        "chunk_size" if rest.is_none() => "--chunk-size",
        "rigid_form" if rest.is_none() => "--rigid-form",
        "rigid_overturning" if rest.is_none() => "--rigid-overturning",
        "rigid_restitution" if rest.is_none() => "--rigid-restitution",
        _ => return None,
    };
    Some(match rest {
        Some(rest) => format!("{flag} {rest}"),
        None => flag.to_string(),
    })
}

/// `error` with a sweep request's values named by their flags (`--vary KEY`, `--scan`, ...)
/// rather than the sweep file's keys; other errors are returned unchanged.
pub fn sweep_named_by_flags(error: impl Into<crate::Error>) -> crate::Error {
    match error.into() {
        crate::Error::Core(e) => crate::Error::Core(core_sweep_named_by_flags(e)),
        other => other,
    }
}

fn core_sweep_named_by_flags(error: Error) -> Error {
    match error {
        Error::InvalidParameter { key, value, rule } => Error::InvalidParameter {
            key: sweep_flag_for(&key).unwrap_or(key),
            value,
            rule,
        },
        // A sweep file's error names the key as the file writes it.
        other => other,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use flexrock_core::model::Setting;

    #[test]
    fn keys_set_by_flags_are_named_by_the_flags_and_no_others() {
        let overrides = Overrides {
            rtol: Some(-1.0),
            settings: vec![Setting::number("excitation.period", -1.0)],
            ..Overrides::default()
        };
        let fem = FemOverrides {
            nx: Some(200),
            ..FemOverrides::default()
        };
        let named = |key: &str| match named_by_flags(
            Error::invalid(key, 1.0, "a rule"),
            &overrides,
            &fem,
        ) {
            crate::Error::Core(Error::InvalidParameter { key, .. }) => key,
            other => panic!("{other:?}"),
        };
        assert_eq!(named("solver.rtol"), "--rtol (sets solver.rtol)");
        assert_eq!(named("solver.atol"), "solver.atol");
        assert_eq!(named("excitation.period"), "--set excitation.period");
        assert_eq!(named("fem.nx, fem.ny"), "--nx, fem.ny");
        assert_eq!(named("body.width"), "body.width");
        let sweep_named = |key: &str| match sweep_named_by_flags(Error::invalid(key, 1.0, "r")) {
            crate::Error::Core(Error::InvalidParameter { key, .. }) => key,
            other => panic!("{other:?}"),
        };
        assert_eq!(
            sweep_named("vary excitation.amplitude"),
            "--vary excitation.amplitude"
        );
        assert_eq!(sweep_named("vary"), "--vary");
        assert_eq!(sweep_named("find_min body.width"), "--find-min body.width");
        assert_eq!(sweep_named("chunk_size"), "--chunk-size");
        assert_eq!(sweep_named("scan"), "--scan");
        assert_eq!(sweep_named("solver.rtol"), "solver.rtol");
        let dt = Overrides {
            dt: Some(0.01),
            ..Overrides::default()
        };
        let rule = format!(
            "not a parameter of bdf{}",
            flexrock_core::model::DT_WITHOUT_NEWMARK
        );
        match named_by_flags(Error::invalid("solver.dt", 0.01, &rule), &dt, &fem) {
            crate::Error::Core(Error::InvalidParameter { key, rule, .. }) => {
                assert_eq!(key, "--dt (sets solver.dt)");
                assert_eq!(rule, "not a parameter of bdf (--dt needs --method newmark)");
            }
            other => panic!("{other:?}"),
        }
    }
}
