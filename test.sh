#!/usr/bin/env bash
# The whole test suite: formatting, lints, and every test of the workspace.
# This is what CI runs (.ci/run); it installs what it needs itself.
set -euo pipefail
cd "$(dirname "$0")"

# The C back end's tests need gcc (present with the Rust toolchain) and
# cppcheck with its MISRA addon (Debian package cppcheck).
if ! command -v cppcheck >/dev/null 2>&1; then
    echo "== installing cppcheck"
    if [ "$(id -u)" = 0 ]; then
        apt-get update -qq && apt-get install -y -qq cppcheck
    else
        sudo apt-get update -qq && sudo apt-get install -y -qq cppcheck
    fi
fi

echo "== cargo fmt --check"
cargo fmt --all -- --check
echo "== cargo clippy"
cargo clippy --workspace --all-targets -- -D warnings
echo "== cargo test"
cargo test --workspace --release
