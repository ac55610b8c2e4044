#!/usr/bin/env bash
# Runs every Rouge test from a fresh machine (this is what CI runs, through .ci/run):
#   1. installs what the tests need: a Python venv with the pinned packages of python/requirements.txt
#      (colour-science, mpmath, numpy, pytest) in .venv/;
#   2. checks formatting and lints (cargo fmt --check, clippy -D warnings);
#   3. runs the Rust tests of the whole workspace (unit, integration, proptests, doc tests);
#   4. runs the Python cross-checks against colour-science and 50-digit mpmath references,
#      driving the real `rouge` binary.
# Usage: bash tests/run.sh            (from anywhere; about 5-10 minutes on 2 cores from scratch)
set -euo pipefail
cd "$(dirname "$0")/.."

step() { printf '\n==> %s\n' "$*"; }

step "Python venv (.venv) with python/requirements.txt"
PY=${PYTHON:-python3}
if [ ! -x .venv/bin/python ]; then
  "$PY" -m venv .venv
fi
.venv/bin/python -m pip install --quiet --disable-pip-version-check -r python/requirements.txt

step "cargo fmt --check"
cargo fmt --all -- --check

step "cargo clippy (all targets, -D warnings)"
cargo clippy --workspace --all-targets --locked -- -D warnings

step "cargo test (workspace)"
cargo test --workspace --locked

step "pytest python/ (cross-checks against colour-science and mpmath)"
cargo build -p rouge-app --locked
ROUGE_BIN="$PWD/target/debug/rouge" .venv/bin/python -m pytest python -q
