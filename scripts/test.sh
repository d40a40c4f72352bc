#!/usr/bin/env bash
# The whole suite: lints, Rust tests, the WASM build, JS unit tests (the export tests with the
# formats' own readers), the site build and the Playwright tests in Debian's chromium. Installs
# what is missing first. Prints how far into the run each step starts.
set -euo pipefail
cd "$(dirname "$0")/.."
export PATH="${CARGO_HOME:-$HOME/.cargo}/bin:$PATH"
started=$SECONDS
step() { printf '\n== %s (%d s in)\n' "$*" "$((SECONDS - started))"; }

step "setup"
bash scripts/setup.sh --browser --readers
step "lint (rustfmt, ESLint; clippy lints the two builds below)"
bash scripts/lint.sh --no-clippy
# shellcheck source=scripts/clippy-env.sh
source scripts/clippy-env.sh
step "wasm build"
bash scripts/build-wasm.sh --compile
# wasm-bindgen and wasm-opt (one thread, about a minute) run beside the Rust tests, at a low
# priority: they take what the Rust build and tests leave of the two cores.
finish_log="wasm-core/target/build-wasm-finish.log"
nice -n 15 bash scripts/build-wasm.sh --finish >"$finish_log" 2>&1 &
finish_pid=$!
trap 'kill "$finish_pid" 2>/dev/null || true' EXIT
step "rust tests"
# One profile: the CLI the JavaScript tests call is the binary this run builds.
(cd wasm-core && cargo test --release)
step "wasm build: wasm-bindgen and wasm-opt"
finish_status=0
wait "$finish_pid" || finish_status=$?
cat "$finish_log"
((finish_status == 0)) || { echo "the WASM build's last stage failed (status $finish_status)" >&2; exit "$finish_status"; }
step "site build"
npx vite build --config web/vite.config.js --logLevel warn
npx vite build --config web/vite.embed.config.js --logLevel warn
step "js unit tests"
# Two files at a time: the runner's default, one fewer than the cores, is one here, while most
# files wait on a child process (the CLI, the formats' readers) or keep one core busy.
concurrency=()
# (grep reads the whole help, not -q: node never writes into a closed pipe under pipefail.)
node --help | grep -- --test-concurrency >/dev/null && concurrency=(--test-concurrency=2)
node --test "${concurrency[@]}" tests/
step "end-to-end tests (chromium)"
npx playwright test --config e2e/playwright.config.js
step "done"
