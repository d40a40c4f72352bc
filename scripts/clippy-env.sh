# Sourced by scripts/test.sh: every cargo build after it is linted by clippy as it compiles, with
# warnings as errors. clippy-driver stands in as the crate's compiler (cargo's workspace wrapper,
# as `cargo clippy` sets it) and CLIPPY_ARGS carries `-D warnings` in cargo clippy's own encoding,
# so `cargo test --release` lints every target `cargo clippy --all-targets` does (the lib, its
# tests, the command line, the integration tests, the examples) and the wasm32 builds lint the
# lib for wasm32 (the first module and the full one), without type-checking the crate twice
# more. Dependencies are not linted.
# Builds under it and without it do not share the crate's artifacts (cargo rebuilds the crate
# when the wrapper changes).
clippy_driver="$(command -v clippy-driver)" || { echo "clippy-driver is missing: rustup component add clippy" >&2; exit 1; }
export RUSTC_WORKSPACE_WRAPPER="$clippy_driver"
export CLIPPY_ARGS="-D__CLIPPY_HACKERY__warnings__CLIPPY_HACKERY__"
