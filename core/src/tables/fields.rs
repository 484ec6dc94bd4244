//! Typed rows of the analyses' tables, and their columns: each table's columns are one list of
//! (name, field) pairs, from which both the header and every row's fields come, so that the two
//! cannot drift apart. The rows also serialize (serde) under the column names, and the tests of
//! each analysis check that the row type and its columns name the same fields in the same order.
//!
//! Numbers are written in their shortest round-trip form ([`number`]), a value that does not
//! exist as an empty field.

use serde::{Deserialize, Deserializer};

use crate::base::format::number;

/// One column of a table of rows `R`: its name and how a row gives its field.
pub struct Column<R> {
    /// The column's name in the header.
    pub name: &'static str,
    /// The row's field in this column, as the table writes it.
    pub field: fn(&R) -> String,
}

impl<R> Column<R> {
    /// A column named `name` whose field `field` gives.
    pub const fn new(name: &'static str, field: fn(&R) -> String) -> Self {
        Column { name, field }
    }
}

/// The header: the names of `columns`, in order.
pub const fn names<R, const N: usize>(columns: &[Column<R>; N]) -> [&'static str; N] {
    let mut out = [""; N];
    let mut i = 0;
    while i < N {
        out[i] = columns[i].name;
        i += 1;
    }
    out
}

/// The fields of `row`, in the order of `columns`.
pub fn fields<R>(columns: &[Column<R>], row: &R) -> Vec<String> {
    columns.iter().map(|c| (c.field)(row)).collect()
}

/// A number that may not exist: its shortest form, or an empty field.
pub fn optional(x: Option<f64>) -> String {
    x.map(number).unwrap_or_default()
}

/// A number that the writer may have stored as null (serde_json writes NaN as null): null reads
/// back as NaN. The key itself must be there.
pub fn nan_if_null<'de, D: Deserializer<'de>>(d: D) -> std::result::Result<f64, D::Error> {
    Ok(Option::<f64>::deserialize(d)?.unwrap_or(f64::NAN))
}

/// An optional value whose key must be there (serde would otherwise read a missing key as None).
pub fn required<'de, D: Deserializer<'de>, T: Deserialize<'de>>(
    d: D,
) -> std::result::Result<T, D::Error> {
    T::deserialize(d)
}

/// The keys a value serializes to (a struct's field names), in order: what the tests compare
/// with a table's column names.
#[cfg(test)]
pub(crate) fn serialized_keys<T: serde::Serialize>(value: &T) -> Vec<String> {
    use serde::de::{IgnoredAny, MapAccess, Visitor};
    struct Keys(Vec<String>);
    impl<'de> Deserialize<'de> for Keys {
        fn deserialize<D: Deserializer<'de>>(d: D) -> std::result::Result<Self, D::Error> {
            struct KeysVisitor;
            impl<'de> Visitor<'de> for KeysVisitor {
                type Value = Keys;
                fn expecting(&self, f: &mut std::fmt::Formatter) -> std::fmt::Result {
                    f.write_str("a map")
                }
                fn visit_map<A: MapAccess<'de>>(
                    self,
                    mut map: A,
                ) -> std::result::Result<Keys, A::Error> {
                    let mut keys = Vec::new();
                    while let Some((key, IgnoredAny)) = map.next_entry::<String, IgnoredAny>()? {
                        keys.push(key);
                    }
                    Ok(Keys(keys))
                }
            }
            d.deserialize_map(KeysVisitor)
        }
    }
    let text = serde_json::to_string(value).unwrap();
    serde_json::from_str::<Keys>(&text).unwrap().0
}

#[cfg(test)]
mod tests {
    use super::*;

    #[derive(serde::Serialize)]
    struct Point {
        x: f64,
        label: &'static str,
        weight: Option<f64>,
    }

    const POINT_COLUMNS: [Column<Point>; 3] = [
        Column::new("x", |p| number(p.x)),
        Column::new("label", |p| p.label.to_string()),
        Column::new("weight", |p| optional(p.weight)),
    ];

    #[test]
    fn header_and_fields_come_from_one_list() {
        assert_eq!(names(&POINT_COLUMNS), ["x", "label", "weight"]);
        let p = Point {
            x: 0.25,
            label: "a",
            weight: None,
        };
        assert_eq!(fields(&POINT_COLUMNS, &p), ["0.25", "a", ""]);
        assert_eq!(serialized_keys(&p), ["x", "label", "weight"]);
    }

    #[test]
    fn serialized_keys_keep_the_order_of_the_fields() {
        #[derive(serde::Serialize)]
        struct Backwards {
            z: u8,
            a: u8,
        }
        assert_eq!(serialized_keys(&Backwards { z: 1, a: 2 }), ["z", "a"]);
    }

    #[test]
    fn null_reads_back_as_nan_and_a_required_key_must_be_there() {
        #[derive(Deserialize)]
        struct Read {
            #[serde(deserialize_with = "nan_if_null")]
            x: f64,
            #[serde(deserialize_with = "required")]
            y: Option<f64>,
        }
        let r: Read = serde_json::from_str(r#"{"x": null, "y": null}"#).unwrap();
        assert!(r.x.is_nan());
        assert_eq!(r.y, None);
        assert!(serde_json::from_str::<Read>(r#"{"x": 1.0}"#).is_err());
    }
}
