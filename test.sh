#!/usr/bin/env bash
# The whole test suite: formatting, lints, and every test of the workspace.
# This is what CI runs (.ci/run); it installs what it needs itself.
set -euo pipefail
cd "$(dirname "$0")"

echo "== cargo fmt --check"
cargo fmt --all -- --check
echo "== cargo clippy"
cargo clippy --workspace --all-targets -- -D warnings
echo "== cargo test"
cargo test --workspace --release
