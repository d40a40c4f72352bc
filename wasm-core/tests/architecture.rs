//! The folders are the architecture (`src/lib.rs`): data flows one way, field → scene → wind →
//! gas → render → frame → export → classroom, with the contract and the WASM door on top and the
//! shared helpers below. These tests read the library's sources and check three things:
//!
//! - a module names (`crate::…`, `super::…`, `self::…`) only its own folder and the layers
//!   below it;
//! - `render/` draws a blob list from the scene's formats and knows nothing of the wind or the
//!   gas that made it;
//! - no file imports another that imports it back, through any number of files between.
//!
//! Comments are not read (a doc comment may point anywhere); code inside a file's own inline
//! modules (`mod tests { … }`) counts as the file's.

use std::collections::BTreeMap;
use std::fs;
use std::path::Path;

/// The layers, lowest first: a module of layer i may use layers 0..=i.
const LAYERS: [&[&str]; 10] = [
    &["check", "error", "lanes", "whole"],
    &["field"],
    &["scene"],
    &["wind"],
    &["gas"],
    &["render"],
    &["frame"],
    &["export"],
    &["classroom"],
    &["contract", "api"],
];

/// Folders that see less than every layer below their own: beside the shared helpers, only
/// these folders.
const SEES_ONLY: [(&str, &[&str]); 2] = [
    ("render", &["render", "scene"]),
    ("scene", &["scene", "field"]),
];

fn layer(top: &str) -> Option<usize> {
    LAYERS.iter().position(|names| names.contains(&top))
}

/// One source file of the library.
struct Source {
    /// Its path below `src/`.
    path: String,
    /// Its module's path from the crate's root (`["scene", "validate"]`; `[]` for `lib.rs`).
    module: Vec<String>,
    /// Its code, comments left out, line by line as in the file.
    code: Vec<String>,
    /// For each line, how many of the file's inline modules it lies in.
    depth: Vec<usize>,
}

/// Every `.rs` file of the library (the command line in `bin/` is a crate of its own).
fn sources() -> Vec<Source> {
    let out = crate_sources("src", "lib");
    assert!(out.len() > 30, "read {} files", out.len());
    out
}

/// Every `.rs` file of the command line's crate (`src/bin/windfield/`, its root `main.rs`).
fn cli_sources() -> Vec<Source> {
    let out = crate_sources("src/bin/windfield", "main");
    assert!(out.len() > 10, "read {} files", out.len());
    out
}

/// Every `.rs` file of the crate whose root file `root` (`lib`, `main`) lies in `dir` (below the
/// manifest's folder), with its module path from that root; the library leaves out `bin/`.
fn crate_sources(dir: &str, root: &str) -> Vec<Source> {
    fn walk(dir: &Path, module: &[String], root: &str, out: &mut Vec<Source>) {
        let mut entries: Vec<_> = fs::read_dir(dir)
            .expect("src is readable")
            .map(|e| e.expect("a directory entry").path())
            .collect();
        entries.sort();
        for path in entries {
            let name = path.file_stem().unwrap().to_string_lossy().to_string();
            let mut inner = module.to_vec();
            if path.is_dir() {
                if module.is_empty() && name == "bin" {
                    continue;
                }
                inner.push(name);
                walk(&path, &inner, root, out);
            } else if path.extension().is_some_and(|e| e == "rs") {
                if !(name == "mod" || (module.is_empty() && name == root)) {
                    inner.push(name);
                }
                let text = fs::read_to_string(&path).expect("a source file");
                let (code, depth) = code_lines(&text);
                let src = Path::new(env!("CARGO_MANIFEST_DIR")).join("src");
                out.push(Source {
                    path: path.strip_prefix(&src).unwrap().display().to_string(),
                    module: inner,
                    code,
                    depth,
                });
            }
        }
    }
    let mut out = Vec::new();
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join(dir);
    walk(&dir, &[], root, &mut out);
    out
}

/// The lines of `text` without their comments, and how deep each lies in the file's inline
/// modules (rustfmt closes `mod name {` with a `}` at the same indentation).
fn code_lines(text: &str) -> (Vec<String>, Vec<usize>) {
    let (mut code, mut depth) = (Vec::new(), Vec::new());
    let mut open: Vec<usize> = Vec::new();
    for line in text.lines() {
        let indent = line.len() - line.trim_start().len();
        if open.last() == Some(&indent) && line.trim() == "}" {
            open.pop();
        }
        let c = line.split("//").next().unwrap_or("").to_string();
        code.push(c.clone());
        depth.push(open.len());
        let t = c.trim_start();
        let t = t.strip_prefix("pub ").unwrap_or(t);
        if let Some(rest) = t.strip_prefix("mod ") {
            if rest.trim_end().ends_with('{') {
                open.push(indent);
            }
        }
    }
    (code, depth)
}

/// The paths a path or `use` tree starting at `s` names, each as its segments: `a::{b, c::d}`
/// names `a::b` and `a::c::d`.
fn tree(s: &str) -> Vec<Vec<String>> {
    fn ident(b: &[u8], i: usize) -> usize {
        let mut j = i;
        while j < b.len() && (b[j].is_ascii_alphanumeric() || b[j] == b'_') {
            j += 1;
        }
        j
    }
    fn walk(b: &[u8], mut i: usize, prefix: &[String], out: &mut Vec<Vec<String>>) -> usize {
        let mut segments = prefix.to_vec();
        loop {
            if b.get(i) == Some(&b'{') {
                i += 1;
                loop {
                    while matches!(b.get(i), Some(b' ' | b'\n' | b',')) {
                        i += 1;
                    }
                    if matches!(b.get(i), None | Some(b'}')) {
                        return i + 1;
                    }
                    let j = walk(b, i, &segments, out);
                    if j == i {
                        return i;
                    }
                    i = j;
                }
            }
            let j = ident(b, i);
            if j == i {
                out.push(segments);
                return i;
            }
            segments.push(String::from_utf8_lossy(&b[i..j]).into_owned());
            i = j;
            if b[i..].starts_with(b"::") {
                i += 2;
            } else {
                out.push(segments);
                return i;
            }
        }
    }
    let mut out = Vec::new();
    walk(s.as_bytes(), 0, &[], &mut out);
    out
}

/// What a file names: for each path, its line (from 1) and the module path it points to from
/// the crate's root; none for a path into the file itself (its own inline modules).
fn named(source: &Source) -> Vec<(usize, Option<Vec<String>>)> {
    let text = source.code.join("\n");
    let mut starts = Vec::new();
    let mut at = 0;
    for line in &source.code {
        starts.push(at);
        at += line.len() + 1;
    }
    let mut out = Vec::new();
    for keyword in ["crate::", "super::", "self::"] {
        for (i, _) in text.match_indices(keyword) {
            let before = text[..i].chars().next_back();
            if before.is_some_and(|c| c.is_alphanumeric() || c == '_' || c == ':') {
                continue;
            }
            let line = starts.partition_point(|&s| s <= i) - 1;
            let depth = source.depth[line];
            let mut rest = &text[i + keyword.len()..];
            // The module the path starts from; none inside the file's own inline modules.
            let base: Option<Vec<String>> = match keyword {
                "crate::" => Some(Vec::new()),
                "self::" => (depth == 0).then(|| source.module.clone()),
                _ => {
                    let mut up = 1;
                    while let Some(r) = rest.strip_prefix("super::") {
                        up += 1;
                        rest = r;
                    }
                    (up > depth).then(|| {
                        let m = &source.module;
                        m[..m.len().saturating_sub(up - depth)].to_vec()
                    })
                }
            };
            // A `use` tree is read from at most its first 4,000 bytes (cut on a character).
            let mut end = rest.len().min(4000);
            while !rest.is_char_boundary(end) {
                end -= 1;
            }
            for segments in tree(&rest[..end]) {
                let target = base.as_ref().map(|b| {
                    let mut t = b.clone();
                    t.extend(segments.into_iter().filter(|s| s != "self"));
                    t
                });
                out.push((line + 1, target));
            }
        }
    }
    out
}

/// The file a module path lies in: the longest of its prefixes that is a file's module.
fn file_of<'a>(path: &[String], files: &'a BTreeMap<Vec<String>, String>) -> Option<&'a String> {
    (0..=path.len()).rev().find_map(|k| files.get(&path[..k]))
}

#[test]
fn no_module_names_a_layer_above_its_own() {
    let mut upward = Vec::new();
    for source in sources() {
        let Some(top) = source.module.first() else {
            continue;
        };
        let own =
            layer(top).unwrap_or_else(|| panic!("{}: module {top} has no layer", source.path));
        for (line, target) in named(&source) {
            let Some(to) = target.as_ref().and_then(|t| t.first()) else {
                continue;
            };
            if layer(to).is_some_and(|l| l > own) {
                upward.push(format!("{}:{line}: {top} uses crate::{to}", source.path));
            }
        }
    }
    upward.dedup();
    assert!(
        upward.is_empty(),
        "paths pointing up:\n{}",
        upward.join("\n")
    );
}

#[test]
fn render_and_scene_never_see_the_wind() {
    let mut seen = Vec::new();
    for source in sources() {
        let Some(top) = source.module.first() else {
            continue;
        };
        let Some((_, allowed)) = SEES_ONLY.iter().find(|(folder, _)| folder == top) else {
            continue;
        };
        for (line, target) in named(&source) {
            let Some(to) = target.as_ref().and_then(|t| t.first()) else {
                continue;
            };
            if layer(to).is_some_and(|l| l > 0) && !allowed.contains(&to.as_str()) {
                seen.push(format!("{}:{line}: {top} uses crate::{to}", source.path));
            }
        }
    }
    seen.dedup();
    assert!(seen.is_empty(), "paths out of bounds:\n{}", seen.join("\n"));
}

#[test]
fn no_file_imports_itself_through_others() {
    no_import_cycle(&sources());
}

#[test]
fn no_file_of_the_command_line_imports_itself_through_others() {
    no_import_cycle(&cli_sources());
}

/// Fails on two files of one crate that import each other, or any longer cycle of imports.
fn no_import_cycle(sources: &[Source]) {
    let files: BTreeMap<Vec<String>, String> = sources
        .iter()
        .map(|s| (s.module.clone(), s.path.clone()))
        .collect();
    // The files each file names (other than itself), in order.
    let mut imports: BTreeMap<&str, Vec<&str>> = BTreeMap::new();
    for source in sources {
        let mut to: Vec<&str> = named(source)
            .into_iter()
            .filter_map(|(_, t)| t.and_then(|t| file_of(&t, &files).map(String::as_str)))
            .filter(|&f| f != source.path)
            .collect();
        to.sort_unstable();
        to.dedup();
        imports.insert(&source.path, to);
    }
    let mutual: Vec<String> = imports
        .iter()
        .flat_map(|(&a, to)| {
            let imports = &imports;
            to.iter()
                .filter(move |&&b| a < b && imports[b].contains(&a))
                .map(move |b| format!("{a} ⇄ {b}"))
        })
        .collect();
    assert!(
        mutual.is_empty(),
        "files that import each other:\n{}",
        mutual.join("\n")
    );
    // A depth-first walk: a file met again while it is still being walked closes a cycle.
    fn walk<'a>(
        file: &'a str,
        imports: &BTreeMap<&'a str, Vec<&'a str>>,
        state: &mut BTreeMap<&'a str, bool>,
        trail: &mut Vec<&'a str>,
        cycles: &mut Vec<String>,
    ) {
        state.insert(file, false);
        trail.push(file);
        for &next in &imports[file] {
            match state.get(next) {
                None => walk(next, imports, state, trail, cycles),
                Some(false) => {
                    let from = trail.iter().position(|&f| f == next).unwrap();
                    cycles.push(format!("{} → {next}", trail[from..].join(" → ")));
                }
                Some(true) => {}
            }
        }
        trail.pop();
        state.insert(file, true);
    }
    let (mut state, mut cycles) = (BTreeMap::new(), Vec::new());
    for &file in imports.keys() {
        if !state.contains_key(file) {
            walk(file, &imports, &mut state, &mut Vec::new(), &mut cycles);
        }
    }
    assert!(
        cycles.is_empty(),
        "import cycles among files:\n{}",
        cycles.join("\n")
    );
}
