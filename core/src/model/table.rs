//! A model file as a table of values, for programs that read or write a model rather than run
//! it (the Python bindings' `Model.get`, `to_dict` and `to_toml`): the file's table with
//! settings applied ([`effective_table`]), every key the schema knows ([`schema_keys`]), the
//! default the core uses for a key the file leaves out ([`default_value`]) and the value in
//! effect for one key ([`value_in_effect`]).

use std::path::Path;

use super::fem_section::{
    DEFAULT_FEM_DT, DEFAULT_FEM_MU_K, DEFAULT_FEM_MU_S, DEFAULT_FEM_NX, DEFAULT_FEM_NY,
    DEFAULT_FEM_THETA, DEFAULT_POISSON_RATIO,
};
use super::read::read_schema;
use super::schema::{
    BodySection, ExcitationSection, FemSection, ModelFile, SimulationSection, SolverSection,
    DEFAULT_ATOL, DEFAULT_DAMPING_RATIO, DEFAULT_DEPTH, DEFAULT_GRAVITY, DEFAULT_OUTPUT_DT,
    DEFAULT_RTOL,
};
use super::setting::{check_key, Setting, VERTICAL_PREFIX};
use super::solver_section::{
    default_method, DEFAULT_NEWMARK_BETA, DEFAULT_NEWMARK_DT, DEFAULT_NEWMARK_GAMMA,
};
use crate::error::{Error, Result};
use crate::physics::body::DEFAULT_LANDING_RESTITUTION;

/// The model file's table with `settings` applied in order, read into the schema on the way
/// (so that an unknown key or a value of the wrong type is refused as the file would be) but
/// returned as a table: keys the file leaves out stay out.
pub fn effective_table(
    table: &toml::Table,
    settings: &[Setting],
    source: &Path,
) -> Result<toml::Table> {
    read_schema(table, settings, source)?;
    let mut out = table.clone();
    for setting in settings {
        setting.apply(&mut out)?;
    }
    Ok(out)
}

/// Every key of the model file, `section.name`, sorted. Taken from the schema
/// itself (each section written out field by field, so that a field added to a section without
/// a place here does not compile).
pub fn schema_keys() -> Vec<String> {
    let file = ModelFile {
        body: BodySection {
            height: 0.0,
            width: 0.0,
            depth: None,
            density: None,
            mass: None,
            youngs_modulus: None,
            flexural_rigidity: None,
            period: None,
            damping_ratio: None,
            gravity: None,
            constants: None,
            self_weight: None,
            poisson_ratio: None,
            // Left out of a written file when None: given here so that they are listed.
            landing_restitution: Some(DEFAULT_LANDING_RESTITUTION),
            damping_while_rocking: Some(true),
        },
        excitation: ExcitationSection {
            kind: "listed".into(),
            amplitude: None,
            period: None,
            ramp: None,
            cycles: None,
            shape: None,
            center: None,
            path: None,
            format: None,
            units: None,
            scale: None,
            start: None,
            end: None,
            tail: None,
            dt: None,
            // Left out of a written file when None: given here so that it is listed.
            ratio: Some(0.0),
            vertical: None,
        },
        simulation: SimulationSection::default(),
        solver: SolverSection::default(),
        fem: Some(FemSection::default()),
    };
    // JSON keeps a None field (as null), where TOML would drop it.
    let value = serde_json::to_value(&file).unwrap_or_default();
    let mut keys = Vec::new();
    if let serde_json::Value::Object(sections) = value {
        for (section, fields) in sections {
            if let serde_json::Value::Object(fields) = fields {
                keys.extend(fields.keys().map(|name| format!("{section}.{name}")));
            }
        }
    }
    // The vertical motion's table takes the excitation's keys.
    let vertical: Vec<String> = keys
        .iter()
        .filter_map(|k| k.strip_prefix("excitation."))
        .map(|name| format!("{VERTICAL_PREFIX}{name}"))
        .collect();
    keys.extend(vertical);
    keys.sort();
    keys
}

/// The value the core uses for `key` when the model file leaves it out, where the core has one
/// default (not one that depends on other keys, such as a record's units or fem.damping_period).
pub fn default_value(key: &str) -> Option<toml::Value> {
    use toml::Value::{Boolean, Float, Integer, String as Text};
    let text = |s: &str| Some(Text(s.to_string()));
    match key {
        "body.depth" => Some(Float(DEFAULT_DEPTH)),
        "body.damping_ratio" => Some(Float(DEFAULT_DAMPING_RATIO)),
        "body.gravity" => Some(Float(DEFAULT_GRAVITY)),
        "body.constants" => text("exact"),
        "body.self_weight" => text("paper"),
        "body.poisson_ratio" => Some(Float(DEFAULT_POISSON_RATIO)),
        "body.landing_restitution" => Some(Float(DEFAULT_LANDING_RESTITUTION)),
        "body.damping_while_rocking" => Some(Boolean(true)),
        "excitation.cycles" => Some(Float(1.0)),
        "excitation.shape" => text("antisymmetric"),
        "excitation.scale" => Some(Float(1.0)),
        "excitation.start" => Some(Float(0.0)),
        "excitation.tail" => Some(Float(0.0)),
        "simulation.q0" => Some(Float(0.0)),
        "simulation.qdot0" => Some(Float(0.0)),
        "solver.rtol" => Some(Float(DEFAULT_RTOL)),
        "solver.atol" => Some(Float(DEFAULT_ATOL)),
        "solver.output_dt" => Some(Float(DEFAULT_OUTPUT_DT)),
        "solver.dt" => Some(Float(DEFAULT_NEWMARK_DT)),
        "solver.newmark_beta" => Some(Float(DEFAULT_NEWMARK_BETA)),
        "solver.newmark_gamma" => Some(Float(DEFAULT_NEWMARK_GAMMA)),
        "solver.newmark_variant" => text("compensate"),
        "fem.nx" => Some(Integer(DEFAULT_FEM_NX as i64)),
        "fem.ny" => Some(Integer(DEFAULT_FEM_NY as i64)),
        "fem.dt" => Some(Float(DEFAULT_FEM_DT)),
        "fem.scheme" => text("linear-acceleration"),
        "fem.theta" => Some(Float(DEFAULT_FEM_THETA)),
        "fem.mu_s" => Some(Float(DEFAULT_FEM_MU_S)),
        "fem.mu_k" => Some(Float(DEFAULT_FEM_MU_K)),
        "fem.p_delta" => Some(Boolean(true)),
        "fem.base" => text("flexible"),
        _ => None,
    }
}

/// The value of `key` in an effective table (see [`effective_table`]): the table's, else the
/// core's default, else None. A key the schema does not know is an error naming it, with the
/// closest known key.
pub fn value_in_effect(table: &toml::Table, key: &str) -> Result<Option<toml::Value>> {
    check_key(key).map_err(|rule| Error::invalid("key", key, &rule))?;
    let keys = schema_keys();
    if !keys.iter().any(|k| k == key) {
        let hint = match crate::base::suggest::closest(key, keys.iter().map(String::as_str)) {
            Some(close) => format!("; did you mean {close}?"),
            None => String::new(),
        };
        return Err(Error::invalid(
            "key",
            key,
            &format!("not a key of the model file{hint}"),
        ));
    }
    let (tables, name) = match key.strip_prefix(VERTICAL_PREFIX) {
        Some(name) => (vec!["excitation", "vertical"], name),
        None => {
            let (section, name) = key.split_once('.').unwrap_or(("", key));
            (vec![section], name)
        }
    };
    let given = tables
        .iter()
        .try_fold(table, |t, part| {
            t.get(*part).and_then(toml::Value::as_table)
        })
        .and_then(|t| t.get(name))
        .cloned();
    if key == "solver.method" && given.is_none() {
        // The default method depends on whether the section gives a tolerance.
        let gives_tolerance = table
            .get("solver")
            .and_then(toml::Value::as_table)
            .is_some_and(|t| t.contains_key("rtol") || t.contains_key("atol"));
        return Ok(Some(toml::Value::String(
            default_method(gives_tolerance).to_string(),
        )));
    }
    Ok(given.or_else(|| default_value(key)))
}

#[cfg(test)]
mod tests {
    use super::*;

    const PAPER: &str = include_str!("../../../models/ichinose1986.toml");

    fn table(text: &str) -> toml::Table {
        text.parse().unwrap()
    }

    #[test]
    fn the_schema_keys_are_the_sections_fields() {
        let keys = schema_keys();
        for key in [
            "body.height",
            "body.poisson_ratio",
            "excitation.kind",
            "excitation.dt",
            "simulation.qdot0",
            "solver.newmark_variant",
            "fem.duration",
        ] {
            assert!(keys.iter().any(|k| k == key), "{key} in {keys:?}");
        }
        // 15 body, 16 excitation and its vertical table's 16, 3 simulation, 8 solver, 11 fem
        // fields.
        assert_eq!(keys.len(), 15 + 2 * 16 + 3 + 8 + 11, "{keys:?}");
        // Every default belongs to a key of the schema.
        for key in &keys {
            let _ = default_value(key);
        }
        assert!(default_value("excitation.nonsense").is_none());
    }

    #[test]
    fn a_default_is_the_one_the_model_uses() {
        let model =
            super::super::Model::from_toml_str(PAPER, &super::super::Overrides::default()).unwrap();
        let file = table(PAPER);
        let float = |key| value_in_effect(&file, key).unwrap().unwrap().as_float();
        assert_eq!(float("body.gravity"), Some(model.body.gravity));
        assert_eq!(float("body.depth"), Some(model.body.depth));
        assert_eq!(float("simulation.q0"), Some(model.initial.q));
        assert_eq!(float("solver.output_dt"), Some(model.solver.output_dt()));
    }

    #[test]
    fn settings_are_in_effect_and_unknown_keys_are_named() {
        let file = table(PAPER);
        let settings = [
            Setting::number("excitation.amplitude", 3.5),
            Setting::text("solver.method", "tsit45"),
        ];
        let effective = effective_table(&file, &settings, Path::new("x.toml")).unwrap();
        let get = |key| value_in_effect(&effective, key).unwrap();
        assert_eq!(get("excitation.amplitude"), Some(toml::Value::Float(3.5)));
        assert_eq!(
            get("solver.method"),
            Some(toml::Value::String("tsit45".into()))
        );
        // Given by the file and not set: the file's value.
        assert_eq!(get("body.height"), file["body"]["height"].clone().into());
        // Known, omitted and without one default: None.
        assert_eq!(get("excitation.units"), None);
        let message = value_in_effect(&effective, "excitation.amplitud")
            .unwrap_err()
            .to_string();
        assert!(message.contains("excitation.amplitud"), "{message}");
        assert!(
            message.contains("did you mean excitation.amplitude?"),
            "{message}"
        );
        assert!(value_in_effect(&effective, "amplitude").is_err());
        // A setting the schema refuses is refused here too, naming its key.
        let bad = [Setting::number("excitation.amplitud", 1.0)];
        let message = effective_table(&file, &bad, Path::new("x.toml"))
            .unwrap_err()
            .to_string();
        assert!(message.contains("excitation.amplitud"), "{message}");
    }
}
