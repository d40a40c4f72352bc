#!/usr/bin/env bash
# Builds the core for the browser: wasm32 with SIMD (see wasm-core/.cargo/config.toml),
# wasm-bindgen's ES-module glue into web/pkg/, then binaryen's wasm-opt -O3 (from npm), which
# makes the module both smaller and faster. Skips wasm-bindgen and wasm-opt when the module is
# unchanged. scripts/setup.sh installs wasm-bindgen and the npm packages.
#
#   --compile  only the cargo build of the raw module
#   --finish   only wasm-bindgen and wasm-opt, from the raw module a --compile left
# (scripts/test.sh runs wasm-opt, which keeps one core busy for about a minute, beside the Rust
# tests.)
set -euo pipefail
compile=1
finish=1
case "${1:-}" in
  --compile) finish=0 ;;
  --finish) compile=0 ;;
  "") ;;
  *) printf 'usage: %s [--compile | --finish]\n' "$0" >&2; exit 2 ;;
esac
root="$(cd "$(dirname "$0")/.." && pwd)"
cd "$root/wasm-core"
export PATH="${CARGO_HOME:-$HOME/.cargo}/bin:$PATH"
log() { printf '[build-wasm] %s\n' "$*"; }

target_dir="${CARGO_TARGET_DIR:-target}"
raw="$target_dir/wasm32-unknown-unknown/wasm/windfield.wasm"
stamp="$target_dir/wasm32-unknown-unknown/wasm/windfield.wasm-opt.stamp"
out="$root/web/pkg/windfield_bg.wasm"

# cargo runs quietly (warnings and errors still show); one line says when it has work to do.
if ((compile)); then
  if [[ ! -f "$raw" ]]; then
    log "compiling the core for wasm32 from scratch (about 1.5 minutes on 2 cores)"
  elif [[ -n "$(find src fft-plans Cargo.toml Cargo.lock .cargo -newer "$raw" -print -quit 2>/dev/null)" ]]; then
    log "recompiling the core for wasm32 (about a minute on 2 cores)"
  fi
  cargo build --quiet --lib --profile wasm --target wasm32-unknown-unknown --no-default-features
fi
((finish)) || exit 0
[[ -f "$raw" ]] || { log "$raw is missing: run bash scripts/build-wasm.sh --compile first" >&2; exit 1; }
if [[ -f "$stamp" && -f "$out" && "$stamp" -nt "$raw" ]] && cmp -s "$stamp" "$out"; then
  exit 0
fi

command -v wasm-bindgen >/dev/null || { log "wasm-bindgen is missing; run bash scripts/setup.sh first" >&2; exit 1; }
wasm_opt="$root/node_modules/.bin/wasm-opt"
[[ -x "$wasm_opt" ]] || { log "$wasm_opt is missing; run bash scripts/setup.sh (or npm ci) first" >&2; exit 1; }
wasm-bindgen --target web --out-dir ../web/pkg --out-name windfield "$raw"
"$wasm_opt" -O3 "$out" -o "$out"
cp "$out" "$stamp"
