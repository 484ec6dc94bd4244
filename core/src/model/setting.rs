//! Setting one model-file key from outside the file: `--set KEY=VALUE` on the command line, and
//! every point of a sweep. A setting is applied to the file's TOML table before the table is read
//! into [`super::ModelFile`], so that a set value meets exactly the schema and the rules a value
//! written in the file meets.

use std::path::{Component, Path, PathBuf};

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

    /// The setting as the model file reads it. A record path (`excitation.path`) that is
    /// relative is relative to where it was given: `given_in`, the current directory for the
    /// command line and Python, a sweep file's directory for the file's `set`. The model file
    /// reads record paths relative to its own directory, `model_dir`, so the path is written
    /// again relative to that (by path arithmetic alone: `..` undoes the directory before it, and
    /// links are not followed). Both directories must be absolute; other settings are unchanged.
    pub fn rebased(self, given_in: &Path, model_dir: &Path) -> Setting {
        match (&*self.key, &self.value) {
            ("excitation.path", toml::Value::String(path)) if Path::new(path).is_relative() => {
                let target = normalised(&given_in.join(path));
                let relative = relative_path(&normalised(model_dir), &target);
                Setting::text(&self.key, &relative.to_string_lossy())
            }
            _ => self,
        }
    }

    /// [`Setting::rebased`] for a setting typed in the directory `here` (on the command line, in
    /// Python) for the model file `model` (None for a model given as text, which reads its
    /// record paths from `here`).
    pub fn typed_in(self, here: &Path, model: Option<&Path>) -> Setting {
        self.rebased(here, &model_dir(here, model))
    }

    /// Parses `KEY=VALUE` as a user types it: the value is read as a TOML value (`4.5`, `1e-8`,
    /// `true`, `"bdf"`), and taken as a plain string when it is not one (`bdf`, `records/a.AT2`).
    pub fn parse(text: &str) -> Result<Setting> {
        let Some((key, value)) = text.split_once('=') else {
            return Err(Error::invalid(
                "setting",
                text,
                "must be KEY=VALUE, e.g. excitation.amplitude=4.5",
            ));
        };
        let key = key.trim();
        check_key(key).map_err(|rule| Error::invalid("setting", text, &rule))?;
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
        // `excitation.vertical.NAME` is a key of the excitation's own table `vertical`.
        let (tables, name): (Vec<&str>, &str) = match self.key.strip_prefix(VERTICAL_PREFIX) {
            Some(name) => (vec!["excitation", "vertical"], name),
            None => {
                let (section, name) = self.key.split_once('.').unwrap_or(("", &self.key));
                (vec![section], name)
            }
        };
        let mut current = table;
        for (depth, part) in tables.iter().enumerate() {
            let entry = current
                .entry(part.to_string())
                .or_insert_with(|| toml::Value::Table(toml::Table::new()));
            current = match entry {
                toml::Value::Table(inner) => inner,
                _ => {
                    return Err(Error::invalid(
                        &self.key,
                        self.value_text(),
                        &format!(
                            "[{}] is not a table in the model file",
                            tables[..=depth].join(".")
                        ),
                    ))
                }
            };
        }
        current.insert(name.to_string(), self.value.clone());
        Ok(())
    }
}

/// The start of a key of the floor's vertical motion, `[excitation.vertical]`.
pub const VERTICAL_PREFIX: &str = "excitation.vertical.";

/// `path` with `.` dropped and each `..` undoing the directory before it.
/// The directory the model file `model` (relative to `here`) reads its record paths from:
/// `here` itself for a model given as text.
pub fn model_dir(here: &Path, model: Option<&Path>) -> PathBuf {
    match model {
        Some(model) => linked_dir(&here.join(model))
            .unwrap_or_else(|| here.join(model.parent().unwrap_or(Path::new("")))),
        None => here.to_path_buf(),
    }
}

/// The folder of the file a symbolic link `path` leads to, where a model reached through a link
/// reads its record paths (as it does when opened where it lies). None for a path that is not
/// a link: its own folder, as given, is the model's.
pub(crate) fn linked_dir(path: &Path) -> Option<PathBuf> {
    let link = std::fs::symlink_metadata(path)
        .ok()?
        .file_type()
        .is_symlink();
    link.then(|| std::fs::canonicalize(path).ok())
        .flatten()
        .and_then(|real| real.parent().map(Path::to_path_buf))
}

pub(crate) fn normalised(path: &Path) -> PathBuf {
    let mut out = PathBuf::new();
    for part in path.components() {
        match part {
            Component::CurDir => {}
            Component::ParentDir => {
                if matches!(out.components().next_back(), Some(Component::Normal(_))) {
                    out.pop();
                } else if !out.has_root() {
                    out.push("..");
                }
            }
            other => out.push(other),
        }
    }
    out
}

/// `target` written relative to the directory `base` (both normalised, both absolute).
fn relative_path(base: &Path, target: &Path) -> PathBuf {
    let (base, target): (Vec<_>, Vec<_>) =
        (base.components().collect(), target.components().collect());
    let common = base.iter().zip(&target).take_while(|(a, b)| a == b).count();
    let mut out = PathBuf::new();
    for _ in common..base.len() {
        out.push("..");
    }
    for part in &target[common..] {
        out.push(part);
    }
    out
}

/// A value as a user reads it: numbers in their shortest exact form, strings bare.
pub fn value_text(value: &toml::Value) -> String {
    match value {
        toml::Value::Float(x) => crate::base::format::shortest(*x),
        toml::Value::String(s) => s.clone(),
        other => other.to_string(),
    }
}

/// A key must be `section.name`, both parts made of letters, digits and `_`; or, for a row
/// model, one gap `row.gaps.I` or one column's key `column.I.name` (I counted from 0, written
/// without leading zeros).
pub fn check_key(key: &str) -> std::result::Result<(), String> {
    let word = |w: &str| !w.is_empty() && w.chars().all(|c| c.is_ascii_alphanumeric() || c == '_');
    let index = |w: &str| {
        !w.is_empty() && w.chars().all(|c| c.is_ascii_digit()) && (w == "0" || !w.starts_with('0'))
    };
    let parts: Vec<&str> = key.split('.').collect();
    match parts.as_slice() {
        [section, name] if word(section) && word(name) => Ok(()),
        ["excitation", "vertical", name] if word(name) => Ok(()),
        ["row", name, i] if word(name) && index(i) => Ok(()),
        ["column", i, name] if index(i) && word(name) => Ok(()),
        _ => Err(format!(
            "the key \"{key}\" must be section.name, e.g. excitation.amplitude or \
             body.youngs_modulus, or excitation.vertical.name (in a row model also row.gaps.I \
             or column.I.name, I from 0)"
        )),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A method set from outside the file is the file's line changed, and nothing more: the
    /// keys of the file's method stay, to meet the new method's rules as they would in the file
    /// (before, a method of another family dropped them).
    #[test]
    fn a_method_set_leaves_the_files_other_solver_keys_as_they_are() {
        let mut table: toml::Table = toml::from_str(
            "[solver]\nmethod = \"bdf\"\nrtol = 1e-8\natol = 1e-10\noutput_dt = 0.01\n",
        )
        .unwrap();
        let mut expected = table.clone();
        expected["solver"]
            .as_table_mut()
            .unwrap()
            .insert("method".into(), toml::Value::String("exact".into()));
        Setting::parse("solver.method=exact")
            .unwrap()
            .apply(&mut table)
            .unwrap();
        assert_eq!(table, expected);
    }

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
    fn a_relative_record_path_is_written_again_relative_to_the_model_file() {
        let rebase = |text: &str, given_in: &str, model_dir: &str| {
            let s = Setting::parse(text).unwrap();
            s.rebased(Path::new(given_in), Path::new(model_dir))
                .value_text()
        };
        // Given in the repository's root, read by a model in models/.
        assert_eq!(
            rebase(
                "excitation.path=validation/records/a.AT2",
                "/repo",
                "/repo/models"
            ),
            "../validation/records/a.AT2"
        );
        // Given in a sibling directory, with `..` and `.` in it.
        assert_eq!(
            rebase(
                "excitation.path=../records/./a.AT2",
                "/repo/study/x",
                "/repo/models"
            ),
            "../study/records/a.AT2"
        );
        // Given in the model's own directory, and below it.
        assert_eq!(rebase("excitation.path=a.AT2", "/m", "/m"), "a.AT2");
        assert_eq!(
            rebase("excitation.path=r/a.AT2", "/m", "/m/deep/er"),
            "../../r/a.AT2"
        );
        // `..` beyond the root stays at the root, as the file system has it.
        assert_eq!(
            rebase("excitation.path=../../a.AT2", "/x", "/m"),
            "../a.AT2"
        );
        // Absolute paths and other keys are left as they are.
        assert_eq!(
            rebase("excitation.path=/abs/a.AT2", "/x", "/m"),
            "/abs/a.AT2"
        );
        let s = Setting::parse("excitation.amplitude=3").unwrap();
        assert_eq!(s.clone().rebased(Path::new("/x"), Path::new("/m")), s);
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
