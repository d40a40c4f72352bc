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
step "lint"
bash scripts/lint.sh
step "rust build"
# One profile: the CLI the JavaScript tests call is the binary this build makes, and the Rust
# tests' binaries are built with it.
(cd wasm-core && cargo test --release --no-run)
step "wasm build"
bash scripts/build-wasm.sh
step "site build"
npx vite build --config web/vite.config.js --logLevel warn
npx vite build --config web/vite.embed.config.js --logLevel warn

# The Rust tests run beside the JS unit tests and the end-to-end tests that time nothing: on
# two cores the browser's tests leave one mostly idle. Their output follows once they end.
step "rust tests (beside what follows), js unit tests"
rust_log="$(mktemp)"
(cd wasm-core && cargo test --release) >"$rust_log" 2>&1 &
rust_pid=$!
trap 'kill "$rust_pid" 2>/dev/null || true; rm -f "$rust_log"' EXIT
node --test tests/
step "end-to-end tests (chromium) but those that time the page"
npx playwright test --config e2e/playwright.config.js --grep-invert @timing
step "rust tests' results"
rust_status=0
wait "$rust_pid" || rust_status=$?
cat "$rust_log"
if [[ $rust_status -ne 0 ]]; then
  echo "the Rust tests failed (exit status $rust_status)" >&2
  exit "$rust_status"
fi
# Alone on the machine, as they time it.
step "end-to-end tests that time the page"
npx playwright test --config e2e/playwright.config.js --grep @timing
step "done"
