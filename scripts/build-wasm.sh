#!/usr/bin/env bash
# Builds the core for the browser: wasm32 with SIMD (see wasm-core/.cargo/config.toml),
# then wasm-bindgen's ES-module glue into web/pkg/.
set -euo pipefail
cd "$(dirname "$0")/../wasm-core"
export PATH="$HOME/.cargo/bin:$PATH"
cargo build --lib --release --target wasm32-unknown-unknown --no-default-features
wasm-bindgen --target web --out-dir ../web/pkg --out-name windfield \
  target/wasm32-unknown-unknown/release/windfield.wasm
