#!/usr/bin/env bash
# The long fuzz run: the core's mutation fuzzer over scenes, blob lists and .npy fields with
# 1,000,000 inputs (or the first argument), and 100,000 mutated links through the URL codec.
# The scene corpus includes the hostile inputs of wasm-core/tests/hostile/ (floods of emitters,
# shapes and kept steps, long lists, deep nesting, σ → 0), which must stay refused.
# `npm test` runs the same fuzzers with 120,000 and 5,000 inputs.
set -euo pipefail
cd "$(dirname "$0")/.."
export PATH="$HOME/.cargo/bin:$PATH"
inputs="${1:-1000000}"
bash scripts/build-wasm.sh
(cd wasm-core && WINDFIELD_FUZZ_INPUTS="$inputs" cargo test --release --test integration fuzz_inputs:: -- --nocapture 2>&1 | grep -E '^(scenes|blob lists|npy):|inputs in|panicked|test result')
WINDFIELD_FUZZ_LINKS="${FUZZ_LINKS:-100000}" node --test tests/url-codec-fuzz.test.js 2>&1 | grep -E 'links:|^# (pass|fail)'
