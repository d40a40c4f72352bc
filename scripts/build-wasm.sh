#!/usr/bin/env bash
# Builds the core for the browser: wasm32 with SIMD (see wasm-core/.cargo/config.toml),
# wasm-bindgen's ES-module glue into web/pkg/, then binaryen's wasm-opt -O3 (from npm), which
# makes the module both smaller and faster. Two modules come out of one crate: the first
# (web/pkg/windfield.js and windfield_bg.wasm), what a player fetches, and the full one
# (windfield_full.js and windfield_full_bg.wasm, `--features full`: the exports, the reference
# renderer, the field's statistics and wind grid, the classroom), fetched on first use. Each
# has a Cargo profile of its own (`wasm`, `wasm-full`), so neither build overwrites the other.
# Skips wasm-bindgen and wasm-opt for a module that is unchanged. scripts/setup.sh installs
# wasm-bindgen and the npm packages.
#
#   --compile  only the cargo builds of the raw modules
#   --finish   only wasm-bindgen and wasm-opt, from the raw modules a --compile left
# (scripts/test.sh runs wasm-opt, which keeps one core busy for about a minute a module, beside
# the Rust tests.)
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
# Each module: its Cargo profile, its out-name in web/pkg/, and its features.
modules=("wasm windfield" "wasm-full windfield_full full")
raw_of() { printf '%s/wasm32-unknown-unknown/%s/windfield.wasm' "$target_dir" "$1"; }

# cargo runs quietly (warnings and errors still show); one line says when it has work to do.
if ((compile)); then
  for module in "${modules[@]}"; do
    read -r profile name features <<<"$module"
    raw="$(raw_of "$profile")"
    if [[ ! -f "$raw" ]]; then
      log "compiling $name for wasm32 from scratch (about 1.5 minutes on 2 cores)"
    elif [[ -n "$(find src fft-plans Cargo.toml Cargo.lock .cargo -newer "$raw" -print -quit 2>/dev/null)" ]]; then
      log "recompiling $name for wasm32 (about a minute on 2 cores)"
    fi
    cargo build --quiet --lib --profile "$profile" --target wasm32-unknown-unknown \
      --no-default-features ${features:+--features "$features"}
  done
fi
((finish)) || exit 0

for module in "${modules[@]}"; do
  read -r profile name _ <<<"$module"
  raw="$(raw_of "$profile")"
  stamp="$raw-opt.stamp"
  out="$root/web/pkg/${name}_bg.wasm"
  [[ -f "$raw" ]] || { log "$raw is missing: run bash scripts/build-wasm.sh --compile first" >&2; exit 1; }
  if [[ -f "$stamp" && -f "$out" && "$stamp" -nt "$raw" ]] && cmp -s "$stamp" "$out"; then
    continue
  fi
  command -v wasm-bindgen >/dev/null || { log "wasm-bindgen is missing; run bash scripts/setup.sh first" >&2; exit 1; }
  wasm_opt="$root/node_modules/.bin/wasm-opt"
  [[ -x "$wasm_opt" ]] || { log "$wasm_opt is missing; run bash scripts/setup.sh (or npm ci) first" >&2; exit 1; }
  wasm-bindgen --target web --out-dir ../web/pkg --out-name "$name" "$raw"
  "$wasm_opt" -O3 "$out" -o "$out"
  cp "$out" "$stamp"
done
