"""The dipole models' error against the path tracer after F frames of progressive accumulation
and at several radiance-map resolutions (docs/BENCHMARKS.md), on one reference scene.

    .venv/bin/python python/dipole_progressive.py --rouge target/release/rouge --scene sphere-skimmilk

Each configuration is one `rouge render ... --dipole-frames F --out X.exr` of the scene's
options (data/reference/translucency/SCENE.json) with specular off; the RMSE of linear radiance
is taken over the pixels fully covered in the reference, as `rouge bench translucency` does.
"""

from __future__ import annotations

import argparse
import json
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import numpy as np

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE))

import mitsuba_ref  # noqa: E402

REFS = HERE.parent / "data" / "reference" / "translucency"


def rmse(rouge: str, options: list[str], extra: list[str], ref: np.ndarray, tmp: Path) -> tuple[float, float]:
    out = tmp / "frame.exr"
    t = time.time()
    subprocess.run([rouge, "render", *options, *extra, "--no-specular", "--out", str(out)], check=True,
                   capture_output=True, cwd=HERE.parent)
    seconds = time.time() - t
    img = mitsuba_ref.read_exr(out)[..., :3]
    mask = ref[..., 3] > 0.999
    return float(np.sqrt(np.mean((img[mask] - ref[..., :3][mask]) ** 2))), seconds


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--rouge", default=str(HERE.parent / "target" / "release" / "rouge"))
    ap.add_argument("--scene", default="sphere-skimmilk")
    ap.add_argument("--model", default="directional-dipole")
    a = ap.parse_args()
    import mitsuba as mi

    mi.set_variant("scalar_rgb")
    sidecar = json.loads((REFS / f"{a.scene}.json").read_text())
    ref = mitsuba_ref.read_exr(REFS / sidecar["image"])
    options = sidecar["rouge_options"]
    rows = []
    with tempfile.TemporaryDirectory() as tmp:
        for frames in (1, 10, 100):
            e, s = rmse(a.rouge, options, ["--subsurface", a.model, "--dipole-frames", str(frames)], ref, Path(tmp))
            rows.append({"frames": frames, "map_px": 256, "rmse": e, "seconds": s})
            print(rows[-1], flush=True)
        for px in (64, 128, 512):
            e, s = rmse(a.rouge, options, ["--subsurface", a.model, "--dipole-frames", "10", "--dipole-map-px", str(px)],
                        ref, Path(tmp))
            rows.append({"frames": 10, "map_px": px, "rmse": e, "seconds": s})
            print(rows[-1], flush=True)
    print(json.dumps({"scene": a.scene, "model": a.model, "rows": rows}, indent=2))


if __name__ == "__main__":
    main()
