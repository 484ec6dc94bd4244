//! Long tables as typed columns: a sweep's table, and the rows of results whose length the user
//! sets (a row's contacts at every sample, Newmark's grid beside the reference, the finite
//! element history), which Python gets as `flexrock.Records` instead of a list of dicts, at a
//! tenth of the memory.

use std::collections::HashMap;

use numpy::PyArray1;
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyString};
use serde::Serialize;

use flexrock_core::analysis::sweep::cell::Kind;
use flexrock_core::analysis::sweep::Cell;

use crate::FlexrockError;

/// Distinct texts of a column made into one Python str each (statuses, modes, states, an
/// empty reason); texts beyond them are made one per cell.
const SHARED_TEXTS: usize = 4096;

/// Python's own size of a str of `n` ASCII characters, near enough: what a text cell costs
/// beyond its place in the column.
fn str_bytes(n: usize) -> usize {
    48 + n
}

/// One column of a table. Each has a mask of the cells that hold no value.
pub(crate) enum Column {
    Float(Vec<f64>, Vec<bool>),
    Int(Vec<i64>, Vec<bool>),
    Bool(Vec<bool>, Vec<bool>),
    /// The texts (None where there is none), and the Python strs made for them.
    Text(Vec<Py<PyAny>>, Texts),
}

/// The Python strs of a text column: one for each of its first [`SHARED_TEXTS`] distinct
/// texts, shared by every cell that holds it.
#[derive(Default)]
pub(crate) struct Texts(HashMap<String, Py<PyAny>>);

impl Texts {
    /// Pushes the str of `text` onto `column`; returns the bytes of the str if one was made.
    fn push(&mut self, py: Python<'_>, column: &mut Vec<Py<PyAny>>, text: &str) -> usize {
        if let Some(s) = self.0.get(text) {
            column.push(s.clone_ref(py));
            return 0;
        }
        let s = PyString::new(py, text).into_any().unbind();
        if self.0.len() < SHARED_TEXTS {
            self.0.insert(text.to_owned(), s.clone_ref(py));
        }
        column.push(s);
        str_bytes(text.len())
    }
}

impl Column {
    /// The bytes a cell takes in a column of `kind` (a text's str aside).
    pub(crate) fn bytes_per_cell(kind: Kind) -> usize {
        match kind {
            Kind::Float | Kind::Int => 9,
            Kind::Text => 8,
            Kind::Bool => 2,
        }
    }

    /// An empty column of `kind` with room for `cells`, or None when memory cannot be had.
    pub(crate) fn with_room(kind: Kind, cells: usize) -> Option<Column> {
        fn room<T>(cells: usize) -> Option<Vec<T>> {
            let mut v = Vec::new();
            v.try_reserve_exact(cells).ok()?;
            Some(v)
        }
        Some(match kind {
            Kind::Float => Column::Float(room(cells)?, room(cells)?),
            Kind::Int => Column::Int(room(cells)?, room(cells)?),
            Kind::Bool => Column::Bool(room(cells)?, room(cells)?),
            Kind::Text => Column::Text(room(cells)?, Texts::default()),
        })
    }

    pub(crate) fn kind(&self) -> Kind {
        match self {
            Column::Float(..) => Kind::Float,
            Column::Int(..) => Kind::Int,
            Column::Bool(..) => Kind::Bool,
            Column::Text(..) => Kind::Text,
        }
    }

    /// Appends a cell of a sweep's table; returns the bytes of a Python str made for it.
    pub(crate) fn push_cell(&mut self, py: Python<'_>, cell: &Cell) -> usize {
        match (self, cell) {
            (Column::Float(v, missing), Cell::Float(x)) => {
                v.push(x.unwrap_or(f64::NAN));
                missing.push(x.is_none());
            }
            (Column::Int(v, missing), Cell::Int(n)) => {
                v.push(n.map_or(0, |n| n as i64));
                missing.push(n.is_none());
            }
            (Column::Bool(v, missing), Cell::Bool(b)) => {
                v.push(b.unwrap_or(false));
                missing.push(b.is_none());
            }
            (Column::Text(v, texts), Cell::Text(t)) => match t {
                None => v.push(py.None()),
                Some(t) => return texts.push(py, v, t),
            },
            // The core gives every row of a sweep the kinds of PointResult::columns.
            (column, cell) => unreachable!(
                "a {} cell in a {} column",
                cell.kind().name(),
                column.kind().name()
            ),
        }
        0
    }

    /// Appends a value of a row serialized by serde (a number, a bool, a str or null);
    /// false if it is not of the column's kind.
    fn push_json(&mut self, py: Python<'_>, value: &serde_json::Value) -> bool {
        use serde_json::Value;
        match (self, value) {
            (Column::Float(v, missing), Value::Null) => {
                v.push(f64::NAN);
                missing.push(true);
            }
            (Column::Float(v, missing), Value::Number(x)) => {
                v.push(x.as_f64().unwrap_or(f64::NAN));
                missing.push(false);
            }
            (Column::Int(v, missing), Value::Null) => {
                v.push(0);
                missing.push(true);
            }
            (Column::Int(v, missing), Value::Number(n)) if n.is_i64() => {
                v.push(n.as_i64().unwrap_or(0));
                missing.push(false);
            }
            (Column::Bool(v, missing), Value::Null) => {
                v.push(false);
                missing.push(true);
            }
            (Column::Bool(v, missing), Value::Bool(b)) => {
                v.push(*b);
                missing.push(false);
            }
            (Column::Text(v, _), Value::Null) => v.push(py.None()),
            (Column::Text(v, texts), Value::String(s)) => {
                texts.push(py, v, s);
            }
            _ => return false,
        }
        true
    }

    /// The kind of a serialized value (None for null).
    fn kind_of(value: &serde_json::Value) -> Option<Kind> {
        use serde_json::Value;
        match value {
            Value::Number(n) if n.is_i64() => Some(Kind::Int),
            Value::Number(_) => Some(Kind::Float),
            Value::Bool(_) => Some(Kind::Bool),
            Value::String(_) => Some(Kind::Text),
            _ => None,
        }
    }

    /// The column as numpy arrays: its values, and where they are missing (None when nowhere).
    pub(crate) fn into_arrays(self, py: Python<'_>) -> (Py<PyAny>, Py<PyAny>) {
        let mask = |missing: Vec<bool>| -> Py<PyAny> {
            if missing.iter().any(|&m| m) {
                PyArray1::from_vec(py, missing).into_any().unbind()
            } else {
                py.None()
            }
        };
        match self {
            Column::Float(v, missing) => {
                (PyArray1::from_vec(py, v).into_any().unbind(), mask(missing))
            }
            Column::Int(v, missing) => {
                (PyArray1::from_vec(py, v).into_any().unbind(), mask(missing))
            }
            Column::Bool(v, missing) => {
                (PyArray1::from_vec(py, v).into_any().unbind(), mask(missing))
            }
            Column::Text(v, _) => (PyArray1::from_vec(py, v).into_any().unbind(), py.None()),
        }
    }
}

/// The table `{"columns", "kinds", "values", "missing"}` of named columns, as `SweepResult`
/// and `Records` take it.
pub(crate) fn table_dict<'py>(
    py: Python<'py>,
    names: Vec<String>,
    columns: Vec<Column>,
) -> PyResult<Bound<'py, PyDict>> {
    let kinds: Vec<&str> = columns.iter().map(|c| c.kind().name()).collect();
    let (values, missing): (Vec<_>, Vec<_>) =
        columns.into_iter().map(|c| c.into_arrays(py)).unzip();
    let out = PyDict::new(py);
    out.set_item("columns", names)?;
    out.set_item("kinds", kinds)?;
    out.set_item("values", values)?;
    out.set_item("missing", missing)?;
    Ok(out)
}

/// The names of a serialized struct's fields, in their order (a JSON object's keys as written).
fn field_names<T: Serialize>(row: &T) -> PyResult<Vec<String>> {
    struct Keys;
    impl<'de> serde::de::Visitor<'de> for Keys {
        type Value = Vec<String>;
        fn expecting(&self, f: &mut std::fmt::Formatter) -> std::fmt::Result {
            f.write_str("an object")
        }
        fn visit_map<A: serde::de::MapAccess<'de>>(
            self,
            mut map: A,
        ) -> Result<Self::Value, A::Error> {
            let mut keys = Vec::new();
            while let Some(key) = map.next_key::<String>()? {
                map.next_value::<serde::de::IgnoredAny>()?;
                keys.push(key);
            }
            Ok(keys)
        }
    }
    let text = serde_json::to_string(row).map_err(|e| FlexrockError::new_err(e.to_string()))?;
    serde::Deserializer::deserialize_map(&mut serde_json::Deserializer::from_str(&text), Keys)
        .map_err(|e| FlexrockError::new_err(e.to_string()))
}

/// `rows` (structs whose fields are numbers, bools, texts or None) as a `flexrock.Records`:
/// one typed numpy column per field, in the fields' order.
pub(crate) fn records<'py, T: Serialize>(
    py: Python<'py>,
    rows: &[T],
) -> PyResult<Bound<'py, PyAny>> {
    let names = match rows.first() {
        Some(row) => field_names(row)?,
        None => Vec::new(),
    };
    // A column's kind is that of its first value that is not null; until then, the nulls.
    let mut columns: Vec<Result<Column, usize>> = names.iter().map(|_| Err(0)).collect();
    for row in rows {
        let value = serde_json::to_value(row).map_err(|e| FlexrockError::new_err(e.to_string()))?;
        for (name, column) in names.iter().zip(columns.iter_mut()) {
            let cell = value.get(name).unwrap_or(&serde_json::Value::Null);
            let kind = Column::kind_of(cell);
            if let (Err(nulls), Some(kind)) = (&*column, kind) {
                let mut made = Column::with_room(kind, rows.len()).ok_or_else(|| {
                    pyo3::exceptions::PyMemoryError::new_err(format!(
                        "a table of {} rows takes more memory than this process can have",
                        rows.len()
                    ))
                })?;
                for _ in 0..*nulls {
                    made.push_json(py, &serde_json::Value::Null);
                }
                *column = Ok(made);
            }
            match column {
                Ok(c) => {
                    if !c.push_json(py, cell) {
                        return Err(FlexrockError::new_err(format!(
                            "the column {name} holds values of two kinds (a bug of flexrock)"
                        )));
                    }
                }
                Err(nulls) => *nulls += 1,
            }
        }
    }
    // A column with no value at all: floats, all missing.
    let columns = columns
        .into_iter()
        .map(|c| c.unwrap_or_else(|nulls| Column::Float(vec![f64::NAN; nulls], vec![true; nulls])))
        .collect();
    let table = table_dict(py, names, columns)?;
    py.import("flexrock._records")?
        .getattr("Records")?
        .call1((table,))
}
