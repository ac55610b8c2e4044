#!/usr/bin/env bash
# The renderer's GPU figures on a lent NVIDIA machine (the workplace's `device` tool; see
# docs/BENCHMARKS.md, "Renderer: frame time per pass"). Not part of CI: CI has no GPU.
#
# The device machine has no Rust toolchain and no Vulkan loader, so both travel:
#   cargo build --release -p rouge-app && mkdir -p .devbin && cp target/release/rouge .devbin/
#   (the loader debs into .gl/ as the device tool's README says), then run, from the repo root,
#   bash tests/gpu_bench.sh            with `.gl` and `.devbin` carried.
# Writes the JSON of every bench and a frame under $OUT (or ./gpu-bench-out) and prints the tables.
# With ROUGE_BASE=path/to/an/older/rouge, that binary's render and paint benches run first on the
# same machine (render_base.json, paint_base.json): a change's figures beside its baseline's.
# Binaries may travel gzipped (.devbin/*.gz: the device tool carries 64 MiB in all).
set -uo pipefail
OUT=${OUT:-gpu-bench-out}
mkdir -p "$OUT"
if compgen -G ".gl/*.deb" >/dev/null; then
  for f in .gl/*.deb; do dpkg -x "$f" /; done
  ldconfig
fi
if [ -f /usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json ]; then
  export VK_DRIVER_FILES=/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json
  export __EGL_VENDOR_LIBRARY_FILENAMES=/usr/local/nvidia/share/glvnd/egl_vendor.d/10_nvidia.json
fi
# Paths compiled into the binary (CARGO_MANIFEST_DIR, the glitter bench's preset) point at the
# checkout it was built in: make that path this checkout.
SRC=${ROUGE_BUILT_IN:-/work/main}
if [ ! -e "$SRC" ]; then mkdir -p "$(dirname "$SRC")" && ln -s "$PWD" "$SRC"; fi
for z in .devbin/*.gz; do [ -e "$z" ] && gunzip -f "$z" && chmod +x "${z%.gz}"; done
B=${ROUGE_BIN:-.devbin/rouge}
nvidia-smi --query-gpu=name,driver_version,clocks.sm,clocks.mem --format=csv 2>&1
run() { echo "== $*" >&2; "$@"; }
# The GPU's clocks while the benches run (an idle H200 sits at 345 MHz; the frames of a bench
# are short and waited for one by one, so say what clock they ran at).
CLOCKS_CSV=$(mktemp)
nvidia-smi --query-gpu=timestamp,clocks.sm,clocks.mem,utilization.gpu --format=csv -lms 250 >"$CLOCKS_CSV" 2>&1 &
CLOCKS=$!
if [ -n "${ROUGE_BASE:-}" ]; then
  run "$ROUGE_BASE" bench render --no-sss-study --frames 300 --json "$OUT/render_base.json" 2>/dev/null
  run "$ROUGE_BASE" bench paint --dabs 200 --json "$OUT/paint_base.json" 2>/dev/null
fi
run "$B" render --out "$OUT/face.png" --explain 2>&1 | tail -n 25
run "$B" bench deform --frames 60 --json "$OUT/deform.json" 2>/dev/null
run "$B" bench render --no-sss-study --frames 300 --json "$OUT/render.json" 2>/dev/null
run "$B" bench paint --dabs 200 --json "$OUT/paint.json" 2>/dev/null
run "$B" bench glitter --pixel-mm 1 --frames 2 --size 32 --gpu-frames 50 2>/dev/null | tail -n 5
# The same frame through wgpu's GL backend (NVIDIA's EGL), to tell the driver's path from the shaders.
WGPU_BACKEND=gl run "$B" bench render --no-sss-study --frames 100 --json "$OUT/render_gl.json" 2>&1 | grep -E "^\|| on " | head -n 12
kill $CLOCKS 2>/dev/null
echo "SM clock samples (count, clock):"
awk -F, 'NR>1 {print $2}' "$CLOCKS_CSV" | sort | uniq -c | sort -rn | head -n 5
if [ -n "${TRANSLUCENCY:-}" ]; then
  # The translucency bench on the committed references (issue 31), bounded in time.
  timeout 240 "$B" bench translucency --frames 10 --json "$OUT/translucency.json" 2>/dev/null | grep -E "^\|" | head -n 40
fi
