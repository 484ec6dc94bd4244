//! Reading a model file: its text (a regular file of bounded size), its TOML table, and the
//! table read into the schema with settings applied, at once or, for a sweep's many points,
//! section by section from a prepared schema.

use std::path::Path;

use super::schema::ModelFile;
use super::setting::Setting;
use crate::error::{Error, Result};

/// True when a model file's table describes a row (it has a `[row]` table).
pub fn is_row_table(table: &toml::Table) -> bool {
    table.contains_key("row")
}

/// Largest model file read, bytes: a model file is a few hundred bytes.
pub const MAX_MODEL_FILE_BYTES: u64 = 1024 * 1024;

/// The text of a model file: only a regular file of at most [`MAX_MODEL_FILE_BYTES`] (so that
/// /dev/zero or a FIFO is refused rather than read until memory runs out).
pub fn read_model_text(path: &Path) -> Result<String> {
    use std::io::Read as _;
    let refuse = |source| Error::ReadModel {
        path: path.to_path_buf(),
        source,
    };
    let invalid = |message: String| {
        refuse(std::io::Error::new(
            std::io::ErrorKind::InvalidInput,
            message,
        ))
    };
    let metadata = std::fs::metadata(path).map_err(refuse)?;
    if !metadata.is_file() {
        return Err(invalid(format!(
            "it is {}; a model file must be a regular file",
            crate::base::format::file_kind(metadata.file_type())
        )));
    }
    let mut text = String::new();
    std::fs::File::open(path)
        .map_err(refuse)?
        .take(MAX_MODEL_FILE_BYTES + 1)
        .read_to_string(&mut text)
        .map_err(refuse)?;
    if text.len() as u64 > MAX_MODEL_FILE_BYTES {
        return Err(invalid(format!(
            "larger than the limit of {MAX_MODEL_FILE_BYTES} bytes for a model file"
        )));
    }
    Ok(text)
}

/// A model file's text and its TOML table, as written (the schema is checked by
/// [`read_schema`]); the file is read as [`Model::load`](super::Model::load) reads it (a regular file of at most
/// [`MAX_MODEL_FILE_BYTES`]).
pub fn read_model_table(path: &Path) -> Result<(String, toml::Table)> {
    let text = read_model_text(path)?;
    let table = parse_table(&text, path)?;
    Ok((text, table))
}

/// What names a model given as text (not read from a file) in messages.
pub const MODEL_TEXT: &str = "(model text)";

pub(crate) fn parse_table(text: &str, source: &Path) -> Result<toml::Table> {
    toml::from_str(text).map_err(|e| Error::ParseModel {
        path: source.to_path_buf(),
        message: e.to_string().trim_end().to_string(),
    })
}

/// The text of a model file read into the schema, with `settings` applied. Without settings
/// the text is read directly, so that a message points at the line of the file.
pub(super) fn parse_model_text(
    text: &str,
    settings: &[Setting],
    source: &Path,
) -> Result<ModelFile> {
    if settings.is_empty() {
        return toml::from_str(text).map_err(|e| {
            if toml::from_str::<toml::Table>(text).is_ok_and(|table| is_row_table(&table)) {
                return row_model_refused(source);
            }
            Error::ParseModel {
                path: source.to_path_buf(),
                message: crate::base::suggest::schema_hint(e.to_string().trim_end()),
            }
        });
    }
    let table = parse_table(text, source)?;
    if is_row_table(&table) {
        return Err(row_model_refused(source));
    }
    read_schema(&table, settings, source)
}

/// The error for a row model given where one body is read.
fn row_model_refused(source: &Path) -> Error {
    Error::ParseModel {
        path: source.to_path_buf(),
        message: "a model of a row of columns (it has a [row] table), where one body is read: \
                  this command takes a model file with a [body] table; `flexrock run` and \
                  `flexrock sweep` take a row"
            .to_string(),
    }
}

/// A model file's table read into the schema once with some settings (a sweep's `--set` keys),
/// from which the files of further settings (a sweep point's axes) are read again section by
/// section: [`PreparedSchema::read`] gives what [`read_schema`] gives, without cloning and
/// reading the sections no further setting names.
#[derive(Debug, Clone)]
pub struct PreparedSchema {
    /// The table as the file has it, and the settings every read starts with.
    table: toml::Table,
    common: Vec<Setting>,
    /// The table with the common settings, and its schema (None where it does not read: then
    /// every read is [`read_schema`]'s, with its message).
    prepared: Option<(toml::Table, ModelFile)>,
}

impl PreparedSchema {
    /// `table` with `common` applied, read once.
    pub fn new(table: toml::Table, common: &[Setting], source: &Path) -> Self {
        let prepared = read_schema(&table, common, source).ok().and_then(|file| {
            let mut with_common = table.clone();
            for setting in common {
                setting.apply(&mut with_common).ok()?;
            }
            Some((with_common, file))
        });
        PreparedSchema {
            table,
            common: common.to_vec(),
            prepared,
        }
    }

    /// The table as the file has it (without the common settings).
    pub fn table(&self) -> &toml::Table {
        &self.table
    }

    /// [`read_schema`] of the table with the common settings, then `further`.
    pub fn read(&self, further: &[Setting], source: &Path) -> Result<ModelFile> {
        let whole = || {
            let settings: Vec<Setting> = self.common.iter().chain(further).cloned().collect();
            read_schema(&self.table, &settings, source)
        };
        let Some((table, base)) = &self.prepared else {
            return whole();
        };
        let mut file = base.clone();
        let mut done: Vec<&str> = Vec::new();
        for setting in further {
            let Some((section, _)) = setting.key.split_once('.') else {
                return whole();
            };
            if done.contains(&section) {
                continue;
            }
            done.push(section);
            let of_section = || {
                further
                    .iter()
                    .filter(move |s| s.key.split_once('.').is_some_and(|(of, _)| of == section))
            };
            // Numbers of the section's number fields are set in place, in order: reading the
            // section again (below) would give the same, at several times the cost.
            let number = |s: &Setting| match s.value {
                toml::Value::Float(x) => Some(x),
                _ => None,
            };
            if of_section().all(|s| number(s).is_some() && file.number_mut(&s.key).is_some()) {
                for s in of_section() {
                    if let (Some(x), Some(field)) = (number(s), file.number_mut(&s.key)) {
                        *field = Some(x);
                    }
                }
                continue;
            }
            // The section as the table has it, with every further setting of it, in order.
            let mut one = toml::Table::new();
            if let Some(value) = table.get(section) {
                one.insert(section.to_string(), value.clone());
            }
            for s in of_section() {
                if s.apply(&mut one).is_err() {
                    return whole();
                }
            }
            let read = one
                .remove(section)
                .is_some_and(|value| file.set_section(section, value));
            if !read {
                // Not a section, or a value that breaks it: the whole read says which.
                return whole();
            }
        }
        Ok(file)
    }
}

impl ModelFile {
    /// Reads `value` as the section `name`; false (and the file unchanged) if it is not one of
    /// the file's sections or does not follow its schema.
    fn set_section(&mut self, name: &str, value: toml::Value) -> bool {
        fn read<T: serde::de::DeserializeOwned>(value: toml::Value) -> Option<T> {
            value.try_into().ok()
        }
        let set = match name {
            "body" => read(value).map(|section| self.body = section),
            "excitation" => read(value).map(|section| self.excitation = section),
            "simulation" => read(value).map(|section| self.simulation = section),
            "solver" => read(value).map(|section| self.solver = section),
            "fem" => read(value).map(|section| self.fem = Some(section)),
            _ => None,
        };
        set.is_some()
    }
}

/// Reads a model file's table into the schema, with `settings` applied first. A table that does
/// not follow the schema is the file's fault (`source` names it); a setting that breaks it is
/// the setting's, and the error names its key.
pub fn read_schema(table: &toml::Table, settings: &[Setting], source: &Path) -> Result<ModelFile> {
    let read = |table: toml::Table| -> std::result::Result<ModelFile, String> {
        table.try_into::<ModelFile>().map_err(|e| {
            crate::base::suggest::schema_hint(&e.to_string().trim_end().replace('\n', " "))
        })
    };
    if settings.is_empty() {
        return read(table.clone()).map_err(|message| Error::ParseModel {
            path: source.to_path_buf(),
            message,
        });
    }
    let mut with_settings = table.clone();
    for setting in settings {
        setting.apply(&mut with_settings)?;
    }
    match read(with_settings) {
        Ok(file) => Ok(file),
        Err(message) => {
            // Blame the first setting that breaks the schema on its own, else the file.
            for setting in settings {
                let mut alone = table.clone();
                setting.apply(&mut alone)?;
                if let Err(message) = read(alone) {
                    if read(table.clone()).is_ok() {
                        return Err(Error::invalid(
                            &setting.key,
                            setting.value_text(),
                            &format!("does not fit the model file's schema: {message}"),
                        ));
                    }
                }
            }
            Err(Error::ParseModel {
                path: source.to_path_buf(),
                message,
            })
        }
    }
}

#[cfg(test)]
mod prepared_schema_tests {
    use super::*;

    fn table(path: &str) -> toml::Table {
        let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("..").join(path);
        read_model_table(&path)
            .expect("a model of the repository")
            .1
    }

    /// What a read gives, as text: the file, or the error's message.
    fn outcome(read: Result<ModelFile>) -> String {
        match read {
            Ok(file) => format!("{file:?}"),
            Err(e) => format!("error: {e}"),
        }
    }

    /// Reading again only the sections the further settings name gives the file (or the error)
    /// that reading the whole table with every setting gives: for settings that read, break a
    /// section's schema, name no section, add a section, switch the solver's family, or set a
    /// key twice.
    #[test]
    fn a_prepared_read_is_the_whole_read() {
        let number = Setting::number;
        let text = Setting::text;
        let commons = [
            vec![],
            vec![text("solver.method", "exact")],
            vec![number("solver.rtol", 1e-9), number("body.height", 3.5)],
        ];
        let furthers = [
            vec![],
            vec![
                number("excitation.period", 0.7),
                number("excitation.amplitude", 2.0),
            ],
            vec![
                number("excitation.amplitude", 2.0),
                number("body.width", 0.5),
            ],
            vec![text("excitation.amplitude", "large")],
            vec![number("excitation.no_such_key", 1.0)],
            vec![number("nosection", 1.0)],
            vec![number("row.spacing", 1.0)],
            vec![number("fem.elements", 12.0)],
            vec![number("simulation.duration", 3.0)],
            vec![text("solver.method", "newmark"), number("solver.dt", 0.01)],
            vec![number("solver.dt", 0.01), text("solver.method", "newmark")],
            vec![
                number("solver.rtol", 1e-8),
                text("solver.method", "newmark"),
            ],
            vec![text("solver.method", "bdf")],
            vec![number("body.height", -1.0)],
            vec![
                number("excitation.period", 0.7),
                number("excitation.period", 0.9),
            ],
            vec![
                text("body.height", "tall"),
                number("excitation.period", 0.9),
            ],
        ];
        let source = Path::new("model.toml");
        let mut compared = 0;
        for model in ["models/pulse-map.toml", "models/ichinose1986.toml"] {
            let table = table(model);
            for common in &commons {
                let prepared = PreparedSchema::new(table.clone(), common, source);
                for further in &furthers {
                    let all: Vec<Setting> = common.iter().chain(further).cloned().collect();
                    let whole = outcome(read_schema(&table, &all, source));
                    let part = outcome(prepared.read(further, source));
                    assert_eq!(part, whole, "{model} with {all:?}");
                    compared += 1;
                }
            }
        }
        assert_eq!(compared, 2 * commons.len() * furthers.len());
    }

    /// The names of the fields serde reads for the struct `T`.
    fn fields_of<'de, T: serde::Deserialize<'de>>() -> &'static [&'static str] {
        use serde::de::{Error as _, Visitor};
        type Answer<V> = std::result::Result<V, serde::de::value::Error>;
        struct Fields(std::cell::Cell<&'static [&'static str]>);
        impl<'de> serde::Deserializer<'de> for &Fields {
            type Error = serde::de::value::Error;
            fn deserialize_any<V: Visitor<'de>>(self, _: V) -> Answer<V::Value> {
                Err(Self::Error::custom("only the fields' names"))
            }
            fn deserialize_struct<V: Visitor<'de>>(
                self,
                _: &'static str,
                fields: &'static [&'static str],
                _: V,
            ) -> Answer<V::Value> {
                self.0.set(fields);
                Err(Self::Error::custom("only the fields' names"))
            }
            serde::forward_to_deserialize_any! {
                bool i8 i16 i32 i64 i128 u8 u16 u32 u64 u128 f32 f64 char str string bytes
                byte_buf option unit unit_struct newtype_struct seq tuple tuple_struct map enum
                identifier ignored_any
            }
        }
        let fields = Fields(std::cell::Cell::new(&[]));
        let _ = T::deserialize(&fields);
        fields.0.get()
    }

    /// Every field of the body, excitation, simulation and solver sections set to a number
    /// (with another key of the excitation) reads as the whole read reads it: the 28 optional
    /// numbers set in place, the other fields by reading their section again (or refused).
    #[test]
    fn every_number_field_set_in_place_is_the_whole_read() {
        use crate::model::schema::{
            BodySection, ExcitationSection, SimulationSection, SolverSection,
        };
        let sections = [
            ("body", fields_of::<BodySection>()),
            ("excitation", fields_of::<ExcitationSection>()),
            ("simulation", fields_of::<SimulationSection>()),
            ("solver", fields_of::<SolverSection>()),
        ];
        let source = Path::new("model.toml");
        let mut in_place = 0;
        for model in ["models/pulse-map.toml", "models/ichinose1986.toml"] {
            let table = table(model);
            let prepared = PreparedSchema::new(table.clone(), &[], source);
            let mut base = prepared.read(&[], source).expect("the model reads");
            for (section, fields) in sections {
                assert!(fields.len() >= 3, "{section}: {fields:?}");
                for field in fields {
                    let key = format!("{section}.{field}");
                    let further = [
                        Setting::number(&key, 0.375),
                        Setting::number("excitation.amplitude", 2.5),
                    ];
                    let whole = outcome(read_schema(&table, &further, source));
                    let part = outcome(prepared.read(&further, source));
                    assert_eq!(part, whole, "{model}: {key}");
                    in_place += usize::from(base.number_mut(&key).is_some());
                }
            }
        }
        assert_eq!(in_place, 2 * (9 + 10 + 3 + 6));
    }

    /// A table that does not read with the common settings reads every time as a whole, with
    /// the whole read's message.
    #[test]
    fn a_table_that_does_not_read_gives_the_whole_reads_message() {
        let mut table = table("models/pulse-map.toml");
        table.insert("extra".into(), toml::Value::Integer(1));
        let source = Path::new("model.toml");
        let prepared = PreparedSchema::new(table.clone(), &[], source);
        assert!(prepared.prepared.is_none());
        let further = [Setting::number("excitation.period", 0.7)];
        let whole = outcome(read_schema(&table, &further, source));
        assert!(whole.starts_with("error"), "{whole}");
        assert_eq!(outcome(prepared.read(&further, source)), whole);
    }
}
