//! Whole numbers as JSON writes them. JSON has one number type: `32` and `32.0` are the same
//! number, and a JSON Schema's `"integer"` accepts both. serde reads only the first into an
//! integer field; these readers take either, so a scene written by a program that keeps every
//! number as a float (Python's `json` module, a spreadsheet) reads as one written by hand.
//! Fractions, negative numbers and numbers out of the type's range are refused with serde's
//! own messages, which `scene::json_errors` words for people.

use serde::de::{Error, Unexpected, Visitor};
use serde::{Deserialize, Deserializer};
use std::fmt;
use std::marker::PhantomData;

/// An unsigned integer type a whole number is read into.
pub trait Unsigned: TryFrom<u64> + Copy {
    /// The type's name as serde writes it in its messages (`usize`).
    const NAME: &'static str;
}

impl Unsigned for u32 {
    const NAME: &'static str = "u32";
}
impl Unsigned for u64 {
    const NAME: &'static str = "u64";
}
impl Unsigned for usize {
    const NAME: &'static str = "usize";
}

struct WholeVisitor<T>(PhantomData<T>);

impl<T: Unsigned> Visitor<'_> for WholeVisitor<T> {
    type Value = T;

    fn expecting(&self, f: &mut fmt::Formatter) -> fmt::Result {
        f.write_str(T::NAME)
    }

    fn visit_u64<E: Error>(self, v: u64) -> Result<T, E> {
        T::try_from(v).map_err(|_| E::invalid_value(Unexpected::Unsigned(v), &self))
    }

    fn visit_i64<E: Error>(self, v: i64) -> Result<T, E> {
        match u64::try_from(v) {
            Ok(v) => self.visit_u64(v),
            Err(_) => Err(E::invalid_value(Unexpected::Signed(v), &self)),
        }
    }

    fn visit_f64<E: Error>(self, v: f64) -> Result<T, E> {
        // 2^64 is the first float past u64::MAX; every float from 2^53 up is whole.
        if v.fract() == 0.0 && (0.0..18_446_744_073_709_551_616.0).contains(&v) {
            self.visit_u64(v as u64)
        } else {
            Err(E::invalid_type(Unexpected::Float(v), &self))
        }
    }
}

/// Reads a whole number, written with or without a zero fraction, into `T`
/// (`#[serde(deserialize_with = "whole::number")]`).
pub fn number<'de, D: Deserializer<'de>, T: Unsigned>(d: D) -> Result<T, D::Error> {
    d.deserialize_any(WholeVisitor(PhantomData))
}

/// One whole number of a list ([`list`]).
pub struct Whole<T>(pub T);

impl<'de, T: Unsigned> Deserialize<'de> for Whole<T> {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        number(d).map(Whole)
    }
}

/// [`number`] for a list of `N` whole numbers (`field.size`).
pub fn list<'de, D: Deserializer<'de>, T: Unsigned, const N: usize>(
    d: D,
) -> Result<[T; N], D::Error>
where
    [Whole<T>; N]: Deserialize<'de>,
{
    <[Whole<T>; N]>::deserialize(d).map(|a| a.map(|w| w.0))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[derive(Deserialize, Debug)]
    struct Both {
        #[serde(deserialize_with = "number")]
        n: u32,
        #[serde(deserialize_with = "list")]
        size: [usize; 4],
    }

    fn read(text: &str) -> Result<Both, String> {
        serde_json::from_str(text).map_err(|e| e.to_string())
    }

    #[test]
    fn a_whole_number_reads_with_or_without_its_zero_fraction() {
        let b = read(r#"{"n": 7.0, "size": [32, 32.0, 3.2e1, 8]}"#).unwrap();
        assert_eq!((b.n, b.size), (7, [32, 32, 32, 8]));
    }

    #[test]
    fn what_is_not_a_whole_number_is_refused_as_serde_refuses_it() {
        for (text, message) in [
            (
                r#"{"n": 7.5, "size": [4, 4, 4, 4]}"#,
                "invalid type: floating point `7.5`, expected u32",
            ),
            (
                r#"{"n": -1, "size": [4, 4, 4, 4]}"#,
                "invalid value: integer `-1`, expected u32",
            ),
            (
                r#"{"n": -1.0, "size": [4, 4, 4, 4]}"#,
                "invalid type: floating point `-1.0`, expected u32",
            ),
            (
                r#"{"n": 4294967296, "size": [4, 4, 4, 4]}"#,
                "invalid value: integer `4294967296`, expected u32",
            ),
            (
                r#"{"n": "7", "size": [4, 4, 4, 4]}"#,
                "invalid type: string \"7\", expected u32",
            ),
            (
                r#"{"n": 1, "size": [4, 4, 4, 4.5]}"#,
                "invalid type: floating point `4.5`, expected usize",
            ),
            (
                r#"{"n": 1, "size": [4, 4, 4]}"#,
                "invalid length 3, expected an array of length 4",
            ),
        ] {
            let e = read(text).unwrap_err();
            assert!(e.starts_with(message), "{text}: {e}");
        }
    }
}
