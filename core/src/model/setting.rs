//! Setting one model-file key from outside the file: `--set KEY=VALUE` on the command line, and
//! every point of a sweep. A setting is applied to the file's TOML table before the table is read
//! into [`super::ModelFile`], so that a set value meets exactly the schema and the rules a value
//! written in the file meets.

use crate::error::{Error, Result};

/// One model-file key and the value it is given.
#[derive(Debug, Clone, PartialEq)]
pub struct Setting {
    /// `section.key`, e.g. `excitation.amplitude`.
    pub key: String,
    /// The value, as TOML.
    pub value: toml::Value,
}

impl Setting {
    /// A setting of `key` to a number.
    pub fn number(key: &str, value: f64) -> Setting {
        Setting {
            key: key.to_string(),
            value: toml::Value::Float(value),
        }
    }

    /// A setting of `key` to a string.
    pub fn text(key: &str, value: &str) -> Setting {
        Setting {
            key: key.to_string(),
            value: toml::Value::String(value.to_string()),
        }
    }

    /// Parses `KEY=VALUE` as a user types it: the value is read as a TOML value (`4.5`, `1e-8`,
    /// `true`, `"bdf"`), and taken as a plain string when it is not one (`bdf`, `records/a.AT2`).
    pub fn parse(text: &str) -> Result<Setting> {
        let Some((key, value)) = text.split_once('=') else {
            return Err(Error::invalid(
                "--set",
                text,
                "must be KEY=VALUE, e.g. excitation.amplitude=4.5",
            ));
        };
        let key = key.trim();
        check_key(key).map_err(|rule| Error::invalid("--set", text, &rule))?;
        let value = value.trim();
        let parsed = toml::from_str::<toml::Table>(&format!("value = {value}"))
            .ok()
            .and_then(|mut table| table.remove("value"));
        let value = match parsed {
            // Tables and arrays are never model-file values; keep the text as the user wrote it.
            Some(
                v @ (toml::Value::Float(_) | toml::Value::Integer(_) | toml::Value::Boolean(_)),
            ) => v,
            Some(toml::Value::String(s)) => toml::Value::String(s),
            _ => toml::Value::String(value.to_string()),
        };
        Ok(Setting {
            key: key.to_string(),
            value,
        })
    }

    /// The value as a user reads it: numbers in their shortest exact form, strings bare.
    pub fn value_text(&self) -> String {
        value_text(&self.value)
    }

    /// Puts the value into a model file's table, creating the section if the file has none.
    /// Whether the key exists is left to the schema, when the table is read.
    pub fn apply(&self, table: &mut toml::Table) -> Result<()> {
        let (section, name) = self.key.split_once('.').unwrap_or(("", &self.key));
        let entry = table
            .entry(section.to_string())
            .or_insert_with(|| toml::Value::Table(toml::Table::new()));
        match entry {
            toml::Value::Table(section_table) => {
                section_table.insert(name.to_string(), self.value.clone());
                Ok(())
            }
            _ => Err(Error::invalid(
                &self.key,
                self.value_text(),
                &format!("[{section}] is not a table in the model file"),
            )),
        }
    }
}

/// A value as a user reads it: numbers in their shortest exact form, strings bare.
pub fn value_text(value: &toml::Value) -> String {
    match value {
        toml::Value::Float(x) => crate::format::shortest(*x),
        toml::Value::String(s) => s.clone(),
        other => other.to_string(),
    }
}

/// A key must be `section.name`, both parts made of letters, digits and `_`.
pub fn check_key(key: &str) -> std::result::Result<(), String> {
    let word = |w: &str| !w.is_empty() && w.chars().all(|c| c.is_ascii_alphanumeric() || c == '_');
    match key.split_once('.') {
        Some((section, name)) if word(section) && word(name) => Ok(()),
        _ => Err(format!(
            "the key \"{key}\" must be section.name, e.g. excitation.amplitude or body.youngs_modulus"
        )),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn values_are_read_as_toml_and_else_as_text() {
        let s = Setting::parse("excitation.amplitude=4.5").unwrap();
        assert_eq!(s.value, toml::Value::Float(4.5));
        let s = Setting::parse("solver.method=tsit45").unwrap();
        assert_eq!(s.value, toml::Value::String("tsit45".into()));
        let s = Setting::parse("excitation.path=\"a b.AT2\"").unwrap();
        assert_eq!(s.value, toml::Value::String("a b.AT2".into()));
        let s = Setting::parse("fem.p_delta=true").unwrap();
        assert_eq!(s.value, toml::Value::Boolean(true));
        let s = Setting::parse("excitation.path=[1,2]").unwrap();
        assert_eq!(s.value, toml::Value::String("[1,2]".into()));
    }

    #[test]
    fn malformed_settings_are_refused() {
        for bad in [
            "amplitude",
            "amplitude=3",
            "=3",
            "a.b.c=3",
            "excitation.=3",
            ".x=1",
        ] {
            assert!(Setting::parse(bad).is_err(), "{bad}");
        }
    }

    #[test]
    fn a_setting_creates_its_section() {
        let mut table = toml::Table::new();
        Setting::number("simulation.duration", 3.0)
            .apply(&mut table)
            .unwrap();
        assert_eq!(
            table["simulation"]["duration"].as_float(),
            Some(3.0),
            "{table:?}"
        );
        let mut flat = toml::Table::new();
        flat.insert("body".into(), toml::Value::Integer(1));
        assert!(Setting::number("body.width", 1.0).apply(&mut flat).is_err());
    }
}
