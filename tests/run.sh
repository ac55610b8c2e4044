#!/usr/bin/env bash
# Runs every Rouge test from a fresh machine (this is what CI runs, through .ci/run):
#   1. installs what the tests need: Mesa's software Vulkan driver (lavapipe) and its OpenGL
#      driver (llvmpipe through EGL, for wgpu's GL backend) for the renderer's GPU tests, through
#      apt-get when it is missing (sudo is used when not root), and a Python
#      venv with the pinned packages of python/requirements.txt (colour-science, mpmath, numpy,
#      pytest) in .venv/;
#      the Khronos glTF-Validator (npm, tests/gltf/) and playwright-core (npm, tests/web/) when
#      node and npm are there, and Debian's chromium for the share page's test (app/tests/export_cli/web.rs);
#   2. checks formatting and lints (cargo fmt --check, clippy -D warnings);
#   3. runs the Rust tests of the whole workspace (unit, integration, proptests, doc tests), then
#      the golden frames again on wgpu's GL backend (WGPU_BACKEND=gl) against the same goldens;
#   4. builds the Python package `rouge` (py/, a maturin wheel of rouge-measure, dev profile) into .venv;
#   5. runs the Python cross-checks against colour-science and 50-digit mpmath references,
#      driving the real `rouge` binary and the `rouge` package, and beside them checks the
#      documentation: `cargo doc --no-deps --workspace` with every rustdoc warning an error
#      (citations are written \[Key\], not intra-doc links).
# Usage: bash tests/run.sh            (from anywhere; about 5-10 minutes on 2 cores from scratch)
set -euo pipefail
cd "$(dirname "$0")/.."

# Each step prints the seconds since the start, so a CI log shows where the time goes.
step() { printf '\n==> [%ss] %s\n' "$SECONDS" "$*"; }

step "System packages: Mesa Vulkan (lavapipe) and EGL/GL (llvmpipe) drivers, Vulkan loader, Xvfb, Chromium"
# chromium: `rouge export web`'s page opened from disk in headless Chromium (about 30 s to fetch
# and unpack on a fresh machine).
APT_PACKAGES="mesa-vulkan-drivers libvulkan1 libegl1 libegl-mesa0 libgl1-mesa-dri xvfb chromium"
missing=""
for p in $APT_PACKAGES; do
  dpkg -s "$p" >/dev/null 2>&1 || missing="$missing $p"
done
if [ -n "$missing" ]; then
  SUDO=""
  [ "$(id -u)" -ne 0 ] && SUDO="sudo"
  $SUDO apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq --no-install-recommends $missing
fi
ls /usr/share/vulkan/icd.d/

step "Python venv (.venv) with python/requirements.txt"
PY=${PYTHON:-python3}
if [ ! -x .venv/bin/python ]; then
  "$PY" -m venv .venv
fi
.venv/bin/python -m pip install --quiet --disable-pip-version-check -r python/requirements.txt

step "Khronos glTF-Validator (tests/gltf/) and playwright-core (tests/web/), pinned npm packages, for the export tests"
# `npm ci` takes about 2 s (one package, no dependencies). Without node/npm, or offline, the
# export tests skip the validator and print why (app/tests/export_cli/gltf.rs).
if command -v npm >/dev/null 2>&1 && command -v node >/dev/null 2>&1; then
  (cd tests/gltf && timeout 60 npm ci --no-audit --no-fund --loglevel=error) \
    || echo "glTF-Validator not installed (npm ci failed): the glTF export tests skip it"
  # playwright-core drives Debian's chromium (no browser download); esbuild and three are only
  # for bundling the page's script by hand (tests/web/bundle.mjs), hence --omit=dev.
  (cd tests/web && timeout 60 npm ci --omit=dev --no-audit --no-fund --loglevel=error) \
    || echo "playwright-core not installed (npm ci failed): the share page's test skips Chromium"
else
  echo "node/npm absent: the glTF export tests skip the glTF-Validator, the share page's test Chromium"
fi

step "cargo fmt --check"
cargo fmt --all -- --check

step "cargo clippy (all targets, -D warnings)"
cargo clippy --workspace --all-targets --locked -- -D warnings

step "cargo test (workspace)"
cargo test --workspace --locked

step "Golden frames on wgpu's GL backend (Mesa llvmpipe through EGL)"
# The workspace step has built these test executables already. Selecting the targets again with
# cargo (`--test render`) resolves features for rouge-render alone and rebuilds wgpu and its
# dependencies (~4 min on 2 cores), so the executables are asked of the same workspace build
# (`--no-run --message-format=json`, nothing rebuilds) and run directly.
test_exe() {
  cargo test --workspace --locked --no-run --message-format=json 2>/dev/null \
    | .venv/bin/python -c '
import json, sys
name = sys.argv[1]
found = []
# Read every line (stopping early would close the pipe under cargo, which then fails).
for line in sys.stdin:
    m = json.loads(line)
    if m.get("reason") == "compiler-artifact" and m.get("executable") \
            and m["target"]["name"] == name and "test" in m["target"]["kind"]:
        found.append(m["executable"])
if not found:
    sys.exit("no test executable named " + name)
print(found[0])
' "$1"
}
RENDER_EXE=$(test_exe render)
# Test executables run from their package's directory under cargo; do the same here. The
# renderer's integration tests are one executable (render/tests/all.rs), a module per file.
(cd render && WGPU_BACKEND=gl "$RENDER_EXE" frame::golden_default_look_and_bare_skin frame::picking_and_captures \
  edges::a_turning_cube edges::sorted_overdraw \
  cube_atlas_gpu::the_gather_converges cube_atlas_gpu::a_deformed_mesh cube_atlas_gpu::light_reaches)

step "Python package \`rouge\` (py/): wheel built by maturin (dev profile, rouge-measure + pyo3 only), installed into .venv"
# The dev profile reuses the dependencies the workspace test step compiled (pyo3, nalgebra, serde:
# py/ is a workspace member), where --release compiled them all again (about 2-3 min on 2 cores);
# rouge-measure itself is at opt-level 3 in the dev profile too (Cargo.toml), so the package's
# numerics run as fast. A user's `pip install ./py` still builds a release wheel.
rm -rf target/wheels
.venv/bin/maturin build --profile dev --locked -m py/Cargo.toml -o target/wheels
.venv/bin/python -m pip install --quiet --disable-pip-version-check --force-reinstall --no-deps target/wheels/rouge_cosmetics-*.whl

# `cargo test` has just built the `rouge` binary for the CLI tests (test profile) into
# target/debug/rouge; a separate `cargo build` would rebuild everything in the dev profile.
test -x target/debug/rouge || cargo build -p rouge-app --locked

# rouge-measure's doc tests (its public functions carry examples that must run and pass) ran in
# the workspace step above; `cargo test --doc -p rouge-measure` again would resolve features for
# that crate alone and rebuild its dependencies for nothing.
# rustdoc documents the crates one after another, mostly on one core, and needs nothing the
# pytest step makes: it runs beside pytest, its output printed after pytest's, and a failure of
# either fails the run. The two took 136 s together in a fresh-clone run against 94 + 64 s one
# after the other in the run before (2026-11-28): about 20 s less.
step "Documentation (cargo doc with rustdoc warnings as errors) beside pytest python/ (cross-checks against colour-science and mpmath)"
DOC_LOG=target/doc-step.log
RUSTDOCFLAGS="-D warnings" cargo doc --no-deps --workspace --locked >"$DOC_LOG" 2>&1 &
doc_pid=$!
# -n 2: both cores (pytest-xdist); every test writes only under its own tmp_path.
pytest_status=0
ROUGE_BIN="$PWD/target/debug/rouge" .venv/bin/python -m pytest python -q -n 2 --durations=15 || pytest_status=$?
doc_status=0
wait "$doc_pid" || doc_status=$?
step "cargo doc's output (exit status $doc_status)"
cat "$DOC_LOG"
if [ "$pytest_status" -ne 0 ] || [ "$doc_status" -ne 0 ]; then
  echo "failed: pytest exit status $pytest_status, cargo doc exit status $doc_status" >&2
  exit 1
fi
step "done"
