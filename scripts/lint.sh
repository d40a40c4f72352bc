#!/usr/bin/env bash
# Lints are errors: rustfmt, clippy (native, and wasm32 for both modules: the first and the full
# one, `--features full`) and ESLint.
# `--no-clippy` leaves clippy out, for scripts/test.sh, whose builds run it (scripts/clippy-env.sh).
set -euo pipefail
cd "$(dirname "$0")/.."
export PATH="$HOME/.cargo/bin:$PATH"
(cd wasm-core && cargo fmt --check)
if [[ "${1:-}" != --no-clippy ]]; then
  (cd wasm-core && cargo clippy --all-targets -- -D warnings)
  (cd wasm-core && cargo clippy --lib --target wasm32-unknown-unknown --no-default-features -- -D warnings)
  (cd wasm-core && cargo clippy --lib --target wasm32-unknown-unknown --no-default-features --features full -- -D warnings)
fi
npx eslint .
