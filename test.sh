#!/usr/bin/env bash
# The whole test suite: formatting, lints, and every test of the workspace.
# This is what CI runs (.ci/run); it installs what it needs itself.
set -euo pipefail
cd "$(dirname "$0")"

# The C back end's tests need gcc (present with the Rust toolchain), make,
# and cppcheck with its MISRA addon (Debian package cppcheck); the netlist
# back end's tests validate its documents with xmllint (libxml2-utils).
missing=""
command -v xmllint >/dev/null 2>&1 || missing="$missing libxml2-utils"
command -v cppcheck >/dev/null 2>&1 || missing="$missing cppcheck"
command -v make >/dev/null 2>&1 || missing="$missing make"
command -v gcc >/dev/null 2>&1 || missing="$missing gcc"
sudo=""
[ "$(id -u)" = 0 ] || sudo="sudo"
if [ -n "$missing" ]; then
    echo "== installing$missing"
    $sudo apt-get update -qq && $sudo apt-get install -y -qq $missing
fi
# The monitor's web page is tested in headless Chromium
# (crates/stc/tests/browser.rs); where it cannot be installed, that test
# says SKIPPED.
if ! command -v chromium >/dev/null 2>&1 && command -v apt-get >/dev/null 2>&1; then
    echo "== installing chromium"
    { $sudo apt-get update -qq && $sudo apt-get install -y -qq chromium; } ||
        echo "== chromium could not be installed: the browser test will be SKIPPED"
fi
# rustfmt and clippy, when the toolchain is managed by rustup.
if command -v rustup >/dev/null 2>&1; then
    rustup component add rustfmt clippy >/dev/null 2>&1 || true
fi

echo "== cargo fmt --check"
cargo fmt --all -- --check
echo "== cargo clippy"
cargo clippy --workspace --all-targets -- -D warnings
echo "== cargo test"
cargo test --workspace --release
