#!/usr/bin/env bash
# Lints are errors: rustfmt, clippy (native and wasm32) and ESLint.
set -euo pipefail
cd "$(dirname "$0")/.."
export PATH="$HOME/.cargo/bin:$PATH"
(cd wasm-core && cargo fmt --check)
(cd wasm-core && cargo clippy --all-targets -- -D warnings)
(cd wasm-core && cargo clippy --lib --target wasm32-unknown-unknown --no-default-features -- -D warnings)
npx eslint .
