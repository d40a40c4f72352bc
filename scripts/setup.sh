#!/usr/bin/env bash
# Installs what a fresh machine lacks, skipping whatever is already there:
# the wasm32 target, the wasm-bindgen CLI pinned to the crate's wasm-bindgen, npm packages
# (exactly package-lock.json's, with `npm ci`), (with --browser) Debian's chromium for the
# end-to-end tests, and (with --readers) the file formats' own readers the export tests hold
# windfield's files to: Debian's python3-openvdb (OpenVDB's Python bindings) and, in a
# project-local Python (.venv/, made from Debian's python3 with its system packages so that it
# sees pyopenvdb), the OpenEXR project's bindings from PyPI.
#
# On a fresh machine the slow part is compiling the wasm-bindgen CLI. It is compiled
# unoptimised (opt-level 0) and without its test runner or TLS stack: about a third of the
# CPU time of a default `cargo install`, and the CLI still runs our module in under a second
# with byte-identical output. While it compiles, npm installs and the wasm core builds (the same
# `cargo build` that scripts/build-wasm.sh runs next, which then has nothing left to do).
set -euo pipefail
cd "$(dirname "$0")/.."
root=$PWD

want_browser=0
want_readers=0
for arg in "$@"; do
  [ "$arg" = "--browser" ] && want_browser=1
  [ "$arg" = "--readers" ] && want_readers=1
done

log() { printf '[setup] %s\n' "$*"; }
fail() { printf '[setup] %s\n' "$*" >&2; exit 1; }

export PATH="${CARGO_HOME:-$HOME/.cargo}/bin:$PATH"
command -v cargo >/dev/null || fail "cargo is required (https://rustup.rs)"
command -v node >/dev/null || fail "Node.js is required (20.19 or later; see package.json's engines)"
# package.json's engines, as Vite 7 needs: ^20.19.0 || >=22.12.0.
node -e 'const [a, b] = process.versions.node.split(".").map(Number);
  process.exit((a === 20 && b >= 19) || (a === 22 && b >= 12) || a > 22 ? 0 : 1)' \
  || fail "Node.js $(node --version) is too old: Vite 7 needs ^20.19.0 || >=22.12.0 (package.json's engines)"

if command -v rustup >/dev/null; then
  if ! rustup target list --installed | grep -qx wasm32-unknown-unknown; then
    log "adding the wasm32-unknown-unknown target (a one-time download)"
    rustup target add wasm32-unknown-unknown
  fi
  for component in rustfmt clippy; do
    if ! rustup component list --installed | grep -q "^$component"; then
      log "adding the $component component"
      rustup component add "$component"
    fi
  done
fi

# The CLI must match the crate's wasm-bindgen exactly (pinned with "=" in Cargo.toml).
pinned=$(sed -n 's/^wasm-bindgen *= *\({ *version *= *\)\{0,1\}"=\([0-9][0-9.]*\)".*/\2/p' wasm-core/Cargo.toml | head -n 1)
[ -n "$pinned" ] || fail 'wasm-core/Cargo.toml must pin wasm-bindgen exactly (wasm-bindgen = "=x.y.z")'
have=$(wasm-bindgen --version 2>/dev/null | awk '{print $2}' || true)

logs="$root/wasm-core/target/setup"
jobs_pids=()
jobs_names=()
# Background jobs die with the script if it stops early (npm ci failing, Ctrl-C).
stop_jobs() { for pid in "${jobs_pids[@]}"; do kill "$pid" 2>/dev/null || true; done; }
trap stop_jobs EXIT

start_job() { # name, log file, command...
  local name=$1 file=$2
  shift 2
  "$@" >"$file" 2>&1 &
  jobs_pids+=("$!")
  jobs_names+=("$name|$file")
}

if [ "$have" != "$pinned" ]; then
  mkdir -p "$logs"
  found=${have:+PATH has $have}
  log "compiling wasm-bindgen-cli $pinned once (${found:-none on PATH}; about 2 minutes on 2 cores; log: wasm-core/target/setup/)"
  # A registry install reads no lock file (the crate's own lock pins a since-yanked crate).
  # CARGO_TARGET_DIR is left out so that it never waits on the core's build directory.
  start_job "wasm-bindgen-cli $pinned" "$logs/wasm-bindgen-cli.log" \
    env -u CARGO_TARGET_DIR CARGO_PROFILE_RELEASE_OPT_LEVEL=0 CARGO_PROFILE_RELEASE_DEBUG=false \
    cargo install wasm-bindgen-cli --version "$pinned" --no-default-features --bin wasm-bindgen
  log "building the wasm core alongside it (both done in about 2.5 minutes on 2 cores)"
  start_job "the wasm core" "$logs/wasm-core.log" \
    bash -c 'cd wasm-core && exec cargo build --lib --profile wasm --target wasm32-unknown-unknown --no-default-features'
fi

if [ ! -d node_modules ] || [ package-lock.json -nt node_modules/.package-lock.json ]; then
  log "installing npm packages from package-lock.json (under a minute)"
  # --ignore-scripts: the only install script in the tree is esbuild's optional postinstall
  # (esbuild finds its binary without it); npm 11 would otherwise warn that it skipped it.
  npm ci --ignore-scripts --no-audit --no-fund
fi

if [ "$want_browser" = 1 ] && [ ! -x "${CHROMIUM_PATH:-/usr/bin/chromium}" ]; then
  log "installing Debian's chromium (about a minute)"
  SUDO=""
  [ "$(id -u)" = 0 ] || SUDO="sudo"
  $SUDO apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq chromium
fi

if [ "$want_readers" = 1 ]; then
  SUDO=""
  [ "$(id -u)" = 0 ] || SUDO="sudo"
  missing=()
  /usr/bin/python3 -c 'import pyopenvdb' 2>/dev/null || missing+=(python3-openvdb)
  /usr/bin/python3 -c 'import ensurepip, venv' 2>/dev/null || missing+=(python3-venv)
  if [ "${#missing[@]}" -gt 0 ]; then
    log "installing Debian's ${missing[*]} (OpenVDB's own reader, for the export tests)"
    $SUDO apt-get update -qq
    DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq "${missing[@]}" >/dev/null
  fi
  if ! "$root/.venv/bin/python" -c 'import OpenEXR, pyopenvdb, numpy' 2>/dev/null; then
    log "making .venv/ with the OpenEXR project's Python bindings (OpenEXR's own reader)"
    /usr/bin/python3 -m venv --system-site-packages "$root/.venv"
    "$root/.venv/bin/pip" install --quiet --disable-pip-version-check OpenEXR numpy
  fi
fi

if [ "${#jobs_pids[@]}" -gt 0 ]; then
  log "waiting for the compiles started above"
  failed=0
  for i in "${!jobs_pids[@]}"; do
    name=${jobs_names[$i]%%|*}
    file=${jobs_names[$i]#*|}
    if ! wait "${jobs_pids[$i]}"; then
      printf '[setup] compiling %s failed; the end of %s:\n' "$name" "$file" >&2
      tail -n 30 "$file" >&2
      failed=1
    fi
  done
  jobs_pids=()
  [ "$failed" = 0 ] || exit 1
  have=$(wasm-bindgen --version 2>/dev/null | awk '{print $2}' || true)
  [ "$have" = "$pinned" ] || fail "wasm-bindgen on PATH is '${have:-none}' after the install, not $pinned"
  log "wasm-bindgen $pinned and the wasm core are ready"
fi
