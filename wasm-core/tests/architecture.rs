//! The folders are the architecture (`src/lib.rs`): data flows one way, field → gas → render →
//! frame → export, with the contract and the WASM door on top and the shared helpers below. A module
//! may name (`crate::…`) only its own folder and the layers below it; this test reads the
//! sources and fails on a path that points up, which is how an import cycle between the
//! folders would begin.

use std::fs;
use std::path::Path;

/// The layers, lowest first: a module of layer i may use layers 0..=i.
const LAYERS: [&[&str]; 7] = [
    &["check", "error", "lanes", "whole"],
    &["field"],
    &["gas"],
    &["render"],
    &["frame"],
    &["export"],
    &["contract", "api"],
];

fn layer(top: &str) -> Option<usize> {
    LAYERS.iter().position(|names| names.contains(&top))
}

/// Every `.rs` file below `dir`, with the top-level module it belongs to.
fn sources(dir: &Path, top: Option<&str>, out: &mut Vec<(String, String, String)>) {
    for entry in fs::read_dir(dir).expect("src is readable") {
        let path = entry.expect("a directory entry").path();
        let name = path.file_stem().unwrap().to_string_lossy().to_string();
        if path.is_dir() {
            if name != "bin" {
                sources(&path, Some(top.unwrap_or(&name)), out);
            }
        } else if path.extension().is_some_and(|e| e == "rs") && name != "lib" {
            let text = fs::read_to_string(&path).expect("a source file");
            let module = top.unwrap_or(&name).to_string();
            out.push((path.display().to_string(), module, text));
        }
    }
}

#[test]
fn no_module_names_a_layer_above_its_own() {
    let mut files = Vec::new();
    sources(
        &Path::new(env!("CARGO_MANIFEST_DIR")).join("src"),
        None,
        &mut files,
    );
    assert!(files.len() > 30, "read {} files", files.len());
    let mut upward = Vec::new();
    for (path, module, text) in &files {
        let own = layer(module).unwrap_or_else(|| panic!("{path}: module {module} has no layer"));
        for (n, line) in text.lines().enumerate() {
            let code = line.split("//").next().unwrap_or("");
            for (at, _) in code.match_indices("crate::") {
                let top: String = code[at + 7..]
                    .chars()
                    .take_while(|c| c.is_alphanumeric() || *c == '_')
                    .collect();
                if let Some(l) = layer(&top) {
                    if l > own {
                        upward.push(format!("{path}:{}: {module} uses crate::{top}", n + 1));
                    }
                }
            }
        }
    }
    assert!(
        upward.is_empty(),
        "paths pointing up:\n{}",
        upward.join("\n")
    );
}
