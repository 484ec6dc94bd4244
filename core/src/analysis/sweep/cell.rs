//! One field of a sweep's table, typed ([`Cell`]), and the kinds of its columns ([`Kind`]).

use crate::base::format::{push_decimal, push_shortest};

/// One field of a row, typed; `None` where the field is empty (no value is known).
#[derive(Debug, Clone, PartialEq)]
pub enum Cell {
    /// true or false.
    Bool(Option<bool>),
    /// A count.
    Int(Option<usize>),
    /// A number.
    Float(Option<f64>),
    /// Text (a status, a reason, a list of bands, a record file).
    Text(Option<String>),
}

/// The type of a column: that of its cells.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Kind {
    /// [`Cell::Bool`].
    Bool,
    /// [`Cell::Int`].
    Int,
    /// [`Cell::Float`].
    Float,
    /// [`Cell::Text`].
    Text,
}

impl Kind {
    /// The kind's name: `bool`, `int`, `float` or `str`.
    pub fn name(self) -> &'static str {
        match self {
            Kind::Bool => "bool",
            Kind::Int => "int",
            Kind::Float => "float",
            Kind::Text => "str",
        }
    }
}

impl Cell {
    /// The cell's kind.
    pub fn kind(&self) -> Kind {
        match self {
            Cell::Bool(_) => Kind::Bool,
            Cell::Int(_) => Kind::Int,
            Cell::Float(_) => Kind::Float,
            Cell::Text(_) => Kind::Text,
        }
    }

    /// An empty cell of kind `kind`.
    pub fn empty(kind: Kind) -> Cell {
        match kind {
            Kind::Bool => Cell::Bool(None),
            Kind::Int => Cell::Int(None),
            Kind::Float => Cell::Float(None),
            Kind::Text => Cell::Text(None),
        }
    }

    /// Text as a cell: empty text is an empty cell.
    pub fn text(text: &str) -> Cell {
        Cell::Text((!text.is_empty()).then(|| text.to_string()))
    }

    /// The field as sweep.csv holds it: `true`/`false`, a decimal count, a number in its
    /// shortest form that reads back to the same bits, the text; empty for `None`.
    pub fn field(&self) -> String {
        let mut text = String::new();
        self.push_field(&mut text);
        text
    }

    /// Appends [`Cell::field`] to `text`.
    pub fn push_field(&self, text: &mut String) {
        match self {
            Cell::Bool(Some(b)) => text.push_str(if *b { "true" } else { "false" }),
            Cell::Int(Some(n)) => push_decimal(text, *n),
            Cell::Float(Some(x)) => push_shortest(text, *x),
            Cell::Text(Some(t)) => text.push_str(t),
            Cell::Bool(None) | Cell::Int(None) | Cell::Float(None) | Cell::Text(None) => {}
        }
    }
}

/// The names of `cells`.
pub(super) fn names(cells: impl IntoIterator<Item = (&'static str, Cell)>) -> Vec<&'static str> {
    cells.into_iter().map(|(name, _)| name).collect()
}

/// Empty cells of the kinds of `cells`.
pub(super) fn emptied(cells: impl IntoIterator<Item = (&'static str, Cell)>) -> Vec<Cell> {
    cells
        .into_iter()
        .map(|(_, c)| Cell::empty(c.kind()))
        .collect()
}

/// The cells of `cells`, without their names.
pub(super) fn values(cells: impl IntoIterator<Item = (&'static str, Cell)>) -> Vec<Cell> {
    cells.into_iter().map(|(_, c)| c).collect()
}
