#!/usr/bin/env bash
# Builds the core for the browser: wasm32 with SIMD (see wasm-core/.cargo/config.toml),
# wasm-bindgen's ES-module glue into web/pkg/, then binaryen's wasm-opt -O3 (from npm), which
# makes the module both smaller and faster. Skips wasm-opt when the module is unchanged.
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
cd "$root/wasm-core"
export PATH="$HOME/.cargo/bin:$PATH"
cargo build --lib --release --target wasm32-unknown-unknown --no-default-features
raw=target/wasm32-unknown-unknown/release/windfield.wasm
stamp=target/wasm32-unknown-unknown/release/windfield.wasm-opt.stamp
out="$root/web/pkg/windfield_bg.wasm"
if [[ -f "$stamp" && -f "$out" && "$stamp" -nt "$raw" ]] && cmp -s "$stamp" "$out"; then
  exit 0
fi
wasm-bindgen --target web --out-dir ../web/pkg --out-name windfield "$raw"
wasm_opt="$root/node_modules/.bin/wasm-opt"
if [[ ! -x "$wasm_opt" ]]; then
  echo "build-wasm: $wasm_opt is missing; run npm install first" >&2
  exit 1
fi
"$wasm_opt" -O3 "$out" -o "$out"
cp "$out" "$stamp"
