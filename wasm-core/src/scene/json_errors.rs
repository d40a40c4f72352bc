//! serde_json's refusals in a person's words. serde names Rust's types (`invalid value:
//! integer `-1`, expected usize`); a scene's author knows JSON: `must be a whole number ≥ 0
//! (got -1)`. Numbers are echoed compactly (`1e308`, not 309 digits), a JSON `null` where a
//! number belongs says why it may have come (JavaScript writes NaN and infinity as `null`),
//! and the literals JSON has no room for (`NaN`, `Infinity`, `1e999`) are named as such.
//!
//! Messages serde does not word in Rust's terms (`unknown field`, `missing field`, the
//! formats' own checks) pass through as they are.

use crate::error::number;
use serde_json::error::Category;

/// What `e`, met while reading `text` (None when a parsed JSON value was read), says in a
/// person's words. Where the error's JSON path says where, its line and column are left out;
/// text that is not JSON keeps them.
pub fn describe(e: &serde_json::Error, text: Option<&str>) -> String {
    let full = e.to_string();
    let position = format!(" at line {} column {}", e.line(), e.column());
    let bare = match e.line() {
        0 => full.as_str(),
        _ => full.strip_suffix(&position).unwrap_or(&full),
    };
    match e.classify() {
        Category::Data => data(bare),
        Category::Syntax | Category::Eof => {
            let position = if e.line() > 0 { position.as_str() } else { "" };
            if let Some(literal) = text.and_then(|t| non_finite_literal(t, e.line(), e.column())) {
                format!("{literal} is not a number JSON can hold: every number must be finite{position}")
            } else if bare == "number out of range" {
                format!(
                    "a number beyond ±1.8e308 (infinite in double precision): every number must \
                     be finite{position}"
                )
            } else {
                format!("not valid JSON: {bare}{position}")
            }
        }
        Category::Io => full,
    }
}

/// `NaN`, `Infinity` or `-Infinity` where the parser stopped (line and column are 1-based,
/// the column in bytes), if that is what it met.
fn non_finite_literal(text: &str, line: usize, column: usize) -> Option<&'static str> {
    let start = match line {
        0 => return None,
        1 => 0,
        _ => text.match_indices('\n').nth(line - 2)?.0 + 1,
    };
    let at = start + column.checked_sub(1)?;
    (at.saturating_sub(1)..=at).find_map(|i| {
        let rest = text.get(i..)?;
        ["NaN", "-Infinity", "Infinity"]
            .into_iter()
            .find(|lit| rest.starts_with(lit))
    })
}

/// A data error (a wrong type, value or length) in a person's words.
fn data(bare: &str) -> String {
    let after = |prefix: &str| bare.strip_prefix(prefix);
    if let Some(rest) = after("invalid type: ").or_else(|| after("invalid value: ")) {
        if let Some((got, expected)) = rest.rsplit_once(", expected ") {
            return must_be(expected, got);
        }
    }
    if let Some((n, expected)) = after("invalid length ").and_then(|r| r.split_once(", expected "))
    {
        return if expected == "fewer elements in array" {
            "has more items than it may hold".to_string()
        } else {
            format!("must be {} (got {n} items)", expected_words(expected, ""))
        };
    }
    if let Some((got, expected)) =
        after("unknown variant ").and_then(|r| r.split_once(", expected "))
    {
        let quoted = |s: &str| s.replace('`', "\"");
        return format!("must be {} (got {})", quoted(expected), quoted(got));
    }
    if let Some(name) = after("data did not match any variant of untagged enum ") {
        return match name {
            "Extinction" => "must be a number or a list of 3 numbers".to_string(),
            "FlowFaces" => r#"must be "open", "closed" or an object {"x", "y", "z"} of those (each axis's two faces)"#.to_string(),
            _ => format!("must be one of the forms the format allows for it ({name})"),
        };
    }
    bare.to_string()
}

/// `must be <expected> (got <got>)`, each in a person's words.
fn must_be(expected: &str, got: &str) -> String {
    let expected = expected_words(expected, got);
    let got = got_words(got);
    let why = if got == "null" && expected == "a number" {
        ": JSON has no NaN or infinity (JavaScript writes them as null)"
    } else {
        ""
    };
    format!("must be {expected} (got {got}){why}")
}

/// serde's name of what it expected (`usize`, `an array of length 3`, `struct Camera`) as a
/// JSON author reads it; `got` tells a whole number too large from one below zero.
fn expected_words(expected: &str, got: &str) -> String {
    let unsigned_max = match expected {
        "u8" => Some(u8::MAX as u128),
        "u16" => Some(u16::MAX as u128),
        "u32" => Some(u32::MAX as u128),
        "u64" => Some(u64::MAX as u128),
        "usize" => Some(usize::MAX as u128),
        "u128" => Some(u128::MAX),
        _ => None,
    };
    if let Some(max) = unsigned_max {
        let too_large = got
            .strip_prefix("integer `")
            .is_some_and(|n| !n.starts_with('-'));
        return if too_large {
            format!("a whole number from 0 to {max}")
        } else {
            "a whole number ≥ 0".to_string()
        };
    }
    match expected {
        "i8" | "i16" | "i32" | "i64" | "i128" | "isize" => "a whole number".into(),
        "f32" | "f64" => "a number".into(),
        "a boolean" => "true or false".into(),
        "a string" | "a borrowed string" => "a string".into(),
        "a sequence" => "a list".into(),
        "a map" | "map" => "an object".into(),
        "unit" => "null".into(),
        // A tagged object written as a list: serde looked for its type first.
        "variant identifier" => "an object with its type".into(),
        _ => {
            if let Some(n) = expected.strip_prefix("an array of length ") {
                format!("a list of {n} numbers")
            } else if ["struct ", "internally tagged enum ", "struct variant "]
                .iter()
                .any(|p| expected.starts_with(p))
            {
                "an object".into()
            } else {
                expected.into()
            }
        }
    }
}

/// serde's description of what it met (`floating point `1e308``, `string "x"`) as a JSON
/// author reads it.
fn got_words(got: &str) -> String {
    let inner = |prefix: &str| got.strip_prefix(prefix)?.strip_suffix('`');
    if let Some(n) = inner("integer `") {
        n.to_string()
    } else if let Some(x) = inner("floating point `") {
        x.parse::<f64>().map_or_else(|_| x.to_string(), number)
    } else if let Some(b) = inner("boolean `") {
        b.to_string()
    } else if let Some(s) = got.strip_prefix("string ") {
        let s = match s.char_indices().nth(60) {
            Some((cut, _)) => format!("{}…\"", &s[..cut]),
            None => s.to_string(),
        };
        format!("the string {s}")
    } else {
        match got {
            "sequence" => "a list".into(),
            "map" => "an object".into(),
            "unit value" | "null" => "null".into(),
            other => other.into(),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use serde::Deserialize;

    #[derive(Debug, Deserialize)]
    #[allow(dead_code)]
    struct Sample {
        #[serde(default)]
        count: usize,
        #[serde(default)]
        small: u8,
        #[serde(default)]
        offset: i32,
        #[serde(default)]
        rate: f64,
        #[serde(default)]
        on: bool,
        #[serde(default)]
        name: String,
        #[serde(default)]
        centre: [f32; 3],
        #[serde(default)]
        list: Vec<u32>,
    }

    fn message(text: &str) -> String {
        let e = serde_json::from_str::<Sample>(text).unwrap_err();
        describe(&e, Some(text))
    }

    #[test]
    fn wrong_types_are_said_in_a_json_authors_words() {
        for (text, want) in [
            (r#"{"count": -1}"#, "must be a whole number ≥ 0 (got -1)"),
            (r#"{"count": 1.5}"#, "must be a whole number ≥ 0 (got 1.5)"),
            (
                r#"{"count": "3"}"#,
                "must be a whole number ≥ 0 (got the string \"3\")",
            ),
            (
                r#"{"count": 1e308}"#,
                "must be a whole number ≥ 0 (got 1e308)",
            ),
            (
                r#"{"small": 300}"#,
                "must be a whole number from 0 to 255 (got 300)",
            ),
            (r#"{"offset": true}"#, "must be a whole number (got true)"),
            (
                r#"{"rate": "fast"}"#,
                "must be a number (got the string \"fast\")",
            ),
            (r#"{"on": 1}"#, "must be true or false (got 1)"),
            (r#"{"name": []}"#, "must be a string (got a list)"),
            (
                r#"{"centre": [1, 2]}"#,
                "must be a list of 3 numbers (got 2 items)",
            ),
            (
                r#"{"centre": {}}"#,
                "must be a list of 3 numbers (got an object)",
            ),
            (r#"{"list": 3}"#, "must be a list (got 3)"),
        ] {
            let got = message(text);
            assert!(got.starts_with(want), "{text}: {got}");
            for rust in ["usize", "u8", "i32", "f64", "expected", " at line "] {
                assert!(!got.contains(rust), "{text}: {got}");
            }
        }
        let null = message(r#"{"rate": null}"#);
        assert!(
            null.starts_with("must be a number (got null): JSON has no NaN or infinity"),
            "{null}"
        );
    }

    #[test]
    fn literals_json_has_no_room_for_are_named() {
        for (text, want) in [
            (r#"{"rate": NaN}"#, "NaN is not a number JSON can hold"),
            (
                r#"{"rate": Infinity}"#,
                "Infinity is not a number JSON can hold",
            ),
            (
                r#"{"rate":-Infinity}"#,
                "-Infinity is not a number JSON can hold",
            ),
            (
                "{\n  \"rate\":\n    NaN}",
                "NaN is not a number JSON can hold",
            ),
            (r#"{"rate": 1e999}"#, "a number beyond ±1.8e308"),
        ] {
            let got = message(text);
            assert!(got.starts_with(want), "{text}: {got}");
            assert!(!got.contains("null"), "{text}: {got}");
        }
        assert!(message(r#"{"rate": 1,}"#).starts_with("not valid JSON: trailing comma"));
    }
}
