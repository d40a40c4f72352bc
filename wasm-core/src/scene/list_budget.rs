//! The list budgets of both formats ([`super::limits`]), counted in the JSON text before it is
//! parsed: one pass over the bytes that allocates nothing a list's length could grow, so a
//! scene of ten million `{}` emitters is refused at the cost of reading its text, not of
//! building ten million emitters (or the JSON tree that would hold them). The validation walk
//! ([`super::validate`]) checks the same lengths again on what was built; this pass only makes
//! sure nothing too long is built first.
//!
//! Every array is counted against the budget of its path (indices written `[]`: `wind[].path`);
//! an array on no budget's path is one of the formats' vectors, colours or sizes (3 or 4
//! numbers) and may hold at most [`OTHER_LIST_MAX`] items; nesting deeper than serde_json reads
//! is refused too. The pass is lenient about anything else: text that is not JSON is left to
//! the parser to refuse with its own message.

use crate::error::ParamError;
use crate::scene::limits::{
    MAX_EMITTERS, MAX_LIGHTS, MAX_LIST_BLOBS, MAX_LIST_OBJECTS, MAX_OBJECTS, MAX_PATH_KEYS,
    MAX_PRIMITIVES, MAX_SHAPES, MAX_SHAPE_BLOBS,
};

/// The most items the list at `path` may hold; `what` names them in the refusal.
#[derive(Debug, Clone, Copy)]
pub struct ListBudget {
    pub path: &'static str,
    pub max: usize,
    pub what: &'static str,
}

const fn budget(path: &'static str, max: usize, what: &'static str) -> ListBudget {
    ListBudget { path, max, what }
}

/// The lists of a scene (docs/FORMATS.md, hard budgets).
pub const SCENE_LISTS: &[ListBudget] = &[
    budget("wind", MAX_PRIMITIVES, "primitives"),
    budget("wind[].path", MAX_PATH_KEYS, "keys"),
    budget("emitters", MAX_EMITTERS, "emitters"),
    budget("emitters[].path", MAX_PATH_KEYS, "keys"),
    budget("shapes", MAX_SHAPES, "shapes"),
    budget("shapes[].points", MAX_SHAPE_BLOBS, "points"),
    budget("render.lights", MAX_LIGHTS, "lights"),
    budget("render.objects", MAX_OBJECTS, "objects"),
];

/// The lists of a blob list.
pub const BLOB_LIST_LISTS: &[ListBudget] = &[
    budget("blobs", MAX_LIST_BLOBS, "blobs"),
    budget("lights", MAX_LIGHTS, "lights"),
    budget("objects", MAX_LIST_OBJECTS, "objects"),
];

/// Most items of an array on no budget's path: every other list of the formats is a vector, a
/// colour or a size of 3 or 4 numbers.
pub const OTHER_LIST_MAX: usize = 16;

/// Deepest nesting read: serde_json's recursion limit (deeper lists and objects are refused
/// here, wherever they lie, as serde_json refuses them where it recurses).
const MAX_DEPTH: usize = 128;

/// The budget of the array at `path` (`wind[].path`).
pub fn budget_of(path: &str, lists: &[ListBudget]) -> ListBudget {
    lists
        .iter()
        .find(|b| b.path == path)
        .copied()
        .unwrap_or(budget("", OTHER_LIST_MAX, "items"))
}

/// How a container was reached from its parent.
enum Step {
    Root,
    /// The key's text between its quotes, escapes as written.
    Key(usize, usize),
    Index(usize),
}

/// An open object or array.
struct Open {
    step: Step,
    /// Length of the budget path before this container added its step.
    path_len: usize,
    /// Arrays: the items begun so far, whether one is begun and not yet ended by a comma, and
    /// the budget.
    array: Option<(usize, bool, ListBudget)>,
    /// Objects: the last key read, while its value is pending.
    key: Option<(usize, usize)>,
}

/// Counts every array of `text` against its budget in `lists`; the first over its budget is
/// refused with its JSON path and its whole length (`emitters: must hold at most 256 emitters
/// (got 10000000)`), in the words of the validation walk's length check.
/// `root` names the document itself (`scene`), should its own array be refused.
pub fn check_lists(text: &str, lists: &[ListBudget], root: &str) -> Result<(), ParamError> {
    let s = text.as_bytes();
    let mut path = String::new();
    let mut stack: Vec<Open> = Vec::new();
    let mut i = 0;
    while i < s.len() {
        match s[i] {
            b' ' | b'\t' | b'\n' | b'\r' | b':' => i += 1,
            b',' => {
                if let Some(open) = stack.last_mut() {
                    if let Some((_, begun, _)) = &mut open.array {
                        *begun = false;
                    }
                    open.key = None;
                }
                i += 1;
            }
            b'"' => {
                let Some(end) = string_end(s, i) else {
                    return Ok(());
                };
                match stack.last_mut() {
                    Some(open) if open.array.is_none() && open.key.is_none() => {
                        open.key = Some((i + 1, end - 1));
                    }
                    _ => begin_item(text, &mut stack, i, root)?,
                }
                i = end;
            }
            c @ (b'{' | b'[') => {
                begin_item(text, &mut stack, i, root)?;
                if stack.len() >= MAX_DEPTH {
                    return Err(ParamError::new(
                        root,
                        format!(
                            "lists and objects nested more than {MAX_DEPTH} deep (recursion \
                             limit exceeded at byte {i})"
                        ),
                    ));
                }
                let path_len = path.len();
                let step = match stack.last() {
                    None => Step::Root,
                    Some(Open {
                        array: Some((n, _, _)),
                        ..
                    }) => {
                        path.push_str("[]");
                        Step::Index(n - 1)
                    }
                    Some(Open { key: Some(k), .. }) => {
                        if !path.is_empty() {
                            path.push('.');
                        }
                        push_key(&mut path, text, *k);
                        Step::Key(k.0, k.1)
                    }
                    // A value where a key belongs: not JSON; the parser says so.
                    Some(_) => return Ok(()),
                };
                let array = (c == b'[').then(|| (0, false, budget_of(&path, lists)));
                stack.push(Open {
                    step,
                    path_len,
                    array,
                    key: None,
                });
                i += 1;
            }
            b'}' | b']' => {
                let Some(open) = stack.pop() else {
                    return Ok(());
                };
                path.truncate(open.path_len);
                i += 1;
            }
            _ => {
                begin_item(text, &mut stack, i, root)?;
                while i < s.len()
                    && !matches!(s[i], b',' | b']' | b'}' | b' ' | b'\t' | b'\n' | b'\r')
                {
                    i += 1;
                }
            }
        }
    }
    Ok(())
}

/// A value begins at `at`: counted if it is a new item of the innermost array, and refused
/// if that array has no room for it.
fn begin_item(text: &str, stack: &mut [Open], at: usize, root: &str) -> Result<(), ParamError> {
    let Some((count, begun, budget)) = stack.last_mut().and_then(|open| open.array.as_mut()) else {
        return Ok(());
    };
    if *begun {
        return Ok(());
    }
    *begun = true;
    *count += 1;
    if *count <= budget.max {
        return Ok(());
    }
    let (max, what) = (budget.max, budget.what);
    let got = match items_from(text.as_bytes(), at) {
        Some(rest) => (max + rest).to_string(),
        None => format!("more than {max}"),
    };
    let path = json_path(text, stack);
    Err(ParamError::new(
        if path.is_empty() {
            root.to_string()
        } else {
            path
        },
        format!("must hold at most {max} {what} (got {got})"),
    ))
}

/// The index just after the string that starts at `start` (its opening quote), or None if
/// the text ends inside it.
fn string_end(s: &[u8], start: usize) -> Option<usize> {
    let mut i = start + 1;
    while i < s.len() {
        match s[i] {
            b'\\' => i += 2,
            b'"' => return Some(i + 1),
            _ => i += 1,
        }
    }
    None
}

/// The items of an array from the item that starts at `at` to the array's end, counted
/// without building them; None if the text ends first.
fn items_from(s: &[u8], at: usize) -> Option<usize> {
    let (mut depth, mut items, mut i) = (0usize, 1usize, at);
    while i < s.len() {
        match s[i] {
            b'"' => {
                i = string_end(s, i)?;
                continue;
            }
            b'{' | b'[' => depth += 1,
            b'}' | b']' if depth == 0 => return Some(items),
            b'}' | b']' => depth -= 1,
            b',' if depth == 0 => items += 1,
            _ => {}
        }
        i += 1;
    }
    None
}

/// Appends a key to a path without allocating, unless it has escapes to decode.
fn push_key(path: &mut String, text: &str, (start, end): (usize, usize)) {
    match &text[start..end] {
        raw if raw.contains('\\') => path.push_str(&key_text(text, (start, end))),
        raw => path.push_str(raw),
    }
}

/// A key as serde reads it: its escapes decoded.
fn key_text(text: &str, (start, end): (usize, usize)) -> String {
    let raw = &text[start..end];
    if raw.contains('\\') {
        serde_json::from_str(&text[start - 1..end + 1]).unwrap_or_else(|_| raw.to_string())
    } else {
        raw.to_string()
    }
}

/// The JSON path of the innermost open container, indices included (`wind[3].path`).
fn json_path(text: &str, stack: &[Open]) -> String {
    let mut out = String::new();
    for open in stack {
        match open.step {
            Step::Root => {}
            Step::Key(a, b) => {
                if !out.is_empty() {
                    out.push('.');
                }
                out.push_str(&key_text(text, (a, b)));
            }
            Step::Index(n) => out.push_str(&format!("[{n}]")),
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use serde_json::Value;

    /// `{"version": 1, <outer>[<items>]<close>}` with `n` copies of `item`.
    fn list(outer: &str, item: &str, n: usize, close: &str) -> String {
        format!(
            r#"{{"version": 1, {outer}[{}]{close}}}"#,
            vec![item; n].join(",")
        )
    }

    #[test]
    fn every_scene_list_is_refused_one_past_its_budget_with_its_path() {
        let key = r#"[0, [1, ","], {"a": "]"}, 3]"#;
        for (outer, item, close, path, max, what) in [
            (
                r#""wind": "#,
                r#"{"type": "uniform"}"#,
                "",
                "wind",
                MAX_PRIMITIVES,
                "primitives",
            ),
            (
                r#""emitters": "#,
                "{}",
                "",
                "emitters",
                MAX_EMITTERS,
                "emitters",
            ),
            (
                r#""shapes": "#,
                r#"{"shape": "cube"}"#,
                "",
                "shapes",
                MAX_SHAPES,
                "shapes",
            ),
            (
                r#""wind": [{}, {}, {"type": "repulsor", "path": "#,
                key,
                "}]",
                "wind[2].path",
                MAX_PATH_KEYS,
                "keys",
            ),
            (
                r#""emitters": [{"path": "#,
                "[0,0,0,0]",
                "}]",
                "emitters[0].path",
                MAX_PATH_KEYS,
                "keys",
            ),
            (
                r#""shapes": [{"shape": "points", "points": "#,
                "[0,0,0]",
                "}]",
                "shapes[0].points",
                MAX_SHAPE_BLOBS,
                "points",
            ),
            (
                r#""render": {"lights": "#,
                "{}",
                "}",
                "render.lights",
                MAX_LIGHTS,
                "lights",
            ),
            (
                r#""render": {"camera": {}, "objects": "#,
                r#"{"type": "sphere", "note": "[,,,]"}"#,
                "}",
                "render.objects",
                MAX_OBJECTS,
                "objects",
            ),
        ] {
            let at = list(outer, item, max, close);
            assert_eq!(check_lists(&at, SCENE_LISTS, "scene"), Ok(()), "{path}");
            let over = list(outer, item, max + 5, close);
            let e = check_lists(&over, SCENE_LISTS, "scene").unwrap_err();
            assert_eq!(e.path, path);
            assert_eq!(
                e.message,
                format!("must hold at most {max} {what} (got {})", max + 5)
            );
        }
    }

    #[test]
    fn strings_escapes_and_nesting_neither_hide_nor_invent_items() {
        // Escaped keys are read as serde reads them.
        let escaped = list(r#""emi\u0074ters": "#, "{}", 300, "");
        let e = check_lists(&escaped, SCENE_LISTS, "scene").unwrap_err();
        assert_eq!(
            (e.path.as_str(), e.message.contains("(got 300)")),
            ("emitters", true)
        );
        // Brackets, commas and quotes inside strings are not structure.
        let quoted = list(r#""emitters": "#, r#"{"note": "[1,2,\"],[\"]"}"#, 256, "");
        assert_eq!(check_lists(&quoted, SCENE_LISTS, "scene"), Ok(()));
        // A list on no budget's path holds a vector's few numbers.
        let e = check_lists(
            r#"{"render": {"background": [1,2,3,4,5,6,7,8,9,10,11,12,13,14,15,16,17]}}"#,
            SCENE_LISTS,
            "scene",
        )
        .unwrap_err();
        assert_eq!(
            e.to_string(),
            "render.background: must hold at most 16 items (got 17)"
        );
        let e = check_lists(
            &format!("[{}]", vec!["1"; 20].join(",")),
            SCENE_LISTS,
            "scene",
        )
        .unwrap_err();
        assert_eq!(e.path, "scene");
        // A list cut short is refused for what it holds so far.
        let cut = list(r#""emitters": "#, "{}", 300, "");
        let e = check_lists(&cut[..cut.len() - 10], SCENE_LISTS, "scene").unwrap_err();
        assert!(e.message.ends_with("(got more than 256)"), "{e}");
        // Nesting beyond serde_json's limit is refused wherever it lies; text that is not JSON
        // is the parser's to refuse.
        let nest = |n: usize| format!(r#"{{"wind": {}{}}}"#, "[".repeat(n), "]".repeat(n));
        assert_eq!(check_lists(&nest(126), SCENE_LISTS, "scene"), Ok(()));
        let e = check_lists(&nest(200), SCENE_LISTS, "scene").unwrap_err();
        assert!(
            e.to_string()
                .starts_with("scene: lists and objects nested more than 128"),
            "{e}"
        );
        assert_eq!(check_lists("{]]]", SCENE_LISTS, "scene"), Ok(()));
        assert_eq!(
            check_lists(r#"{"a" "b": [1,2]}"#, SCENE_LISTS, "scene"),
            Ok(())
        );
        // Blob lists: the blobs, lights and objects.
        let blobs = format!(r#"{{"blobs": [{}]}}"#, ["{}"; 3].join(","));
        assert_eq!(check_lists(&blobs, BLOB_LIST_LISTS, "blob_list"), Ok(()));
        let lights = format!(r#"{{"lights": [{}]}}"#, vec!["{}"; 65].join(","));
        let e = check_lists(&lights, BLOB_LIST_LISTS, "blob_list").unwrap_err();
        assert_eq!(
            e.to_string(),
            "lights: must hold at most 64 lights (got 65)"
        );
    }

    /// Every array the scene's JSON Schema describes, by budget path, with its `maxItems`.
    fn schema_arrays(
        node: &Value,
        root: &Value,
        path: &str,
        depth: usize,
        out: &mut Vec<(String, Option<u64>)>,
    ) {
        assert!(
            depth < 32,
            "the schema nests deeper than expected at {path}"
        );
        if let Some(r) = node.get("$ref").and_then(Value::as_str) {
            let name = r.strip_prefix("#/$defs/").expect("local references");
            return schema_arrays(&root["$defs"][name], root, path, depth + 1, out);
        }
        for key in ["oneOf", "anyOf", "allOf"] {
            for sub in node
                .get(key)
                .and_then(Value::as_array)
                .into_iter()
                .flatten()
            {
                schema_arrays(sub, root, path, depth + 1, out);
            }
        }
        let is_array = match node.get("type") {
            Some(Value::String(t)) => t == "array",
            Some(Value::Array(ts)) => ts.iter().any(|t| t == "array"),
            _ => false,
        };
        if is_array {
            out.push((
                path.to_string(),
                node.get("maxItems").and_then(Value::as_u64),
            ));
        }
        if let Some(items) = node.get("items") {
            schema_arrays(items, root, &format!("{path}[]"), depth + 1, out);
        }
        for (key, sub) in node
            .get("properties")
            .and_then(Value::as_object)
            .into_iter()
            .flatten()
        {
            let p = if path.is_empty() {
                key.clone()
            } else {
                format!("{path}.{key}")
            };
            schema_arrays(sub, root, &p, depth + 1, out);
        }
    }

    #[test]
    fn the_budgets_are_the_schemas_list_lengths() {
        let schema: Value =
            serde_json::from_str(&crate::scene::scene_format::json_schema()).unwrap();
        let mut arrays = Vec::new();
        schema_arrays(&schema, &schema, "", 0, &mut arrays);
        assert!(arrays.len() > 20, "{arrays:?}");
        for (path, max_items) in &arrays {
            let b = budget_of(path, SCENE_LISTS);
            let max_items =
                max_items.unwrap_or_else(|| panic!("{path}: an array without maxItems"));
            if SCENE_LISTS.iter().any(|l| l.path == path) {
                assert_eq!(b.max as u64, max_items, "{path}");
            } else {
                assert!(
                    max_items <= OTHER_LIST_MAX as u64,
                    "{path}: {max_items} needs a budget"
                );
            }
        }
        for b in SCENE_LISTS {
            assert!(
                arrays.iter().any(|(p, _)| p == b.path),
                "{}: not in the schema",
                b.path
            );
        }
    }
}
