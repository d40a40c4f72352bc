#!/usr/bin/env bash
# Installs what a fresh machine lacks, skipping whatever is already there:
# the wasm32 target, the wasm-bindgen CLI pinned to the crate's wasm-bindgen, npm packages,
# and (with --browser) Debian's chromium for the end-to-end tests.
set -euo pipefail
cd "$(dirname "$0")/.."

want_browser=0
for arg in "$@"; do
  [ "$arg" = "--browser" ] && want_browser=1
done

log() { printf '[setup] %s\n' "$*"; }

export PATH="$HOME/.cargo/bin:$PATH"
command -v cargo >/dev/null || { echo "[setup] cargo is required (https://rustup.rs)"; exit 1; }

if command -v rustup >/dev/null; then
  if ! rustup target list --installed | grep -qx wasm32-unknown-unknown; then
    log "adding the wasm32-unknown-unknown target"
    rustup target add wasm32-unknown-unknown
  fi
  for component in rustfmt clippy; do
    rustup component list --installed | grep -q "^$component" || rustup component add "$component"
  done
fi

# The CLI must match the crate's wasm-bindgen exactly (pinned with "=" in Cargo.toml).
pinned=$(sed -n 's/^wasm-bindgen = "=\([0-9.]*\)"/\1/p' wasm-core/Cargo.toml)
have=$(wasm-bindgen --version 2>/dev/null | awk '{print $2}' || true)
if [ "$have" != "$pinned" ]; then
  log "installing wasm-bindgen-cli $pinned (found '${have:-none}'); this takes a few minutes"
  cargo install wasm-bindgen-cli --version "$pinned" --locked \
    || cargo install wasm-bindgen-cli --version "$pinned"
fi

if [ ! -d node_modules ] || [ package-lock.json -nt node_modules/.package-lock.json ]; then
  log "installing npm packages"
  # npm ci insists on every platform's optional packages in the lock; some npm setups leave
  # them out. npm install still takes the locked versions.
  npm ci --no-audit --no-fund || npm install --no-audit --no-fund
fi

if [ "$want_browser" = 1 ] && [ ! -x "${CHROMIUM_PATH:-/usr/bin/chromium}" ]; then
  log "installing Debian's chromium"
  SUDO=""
  [ "$(id -u)" = 0 ] || SUDO="sudo"
  $SUDO apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq chromium
fi
