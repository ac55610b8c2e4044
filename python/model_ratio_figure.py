"""Where two subsurface models differ from the path tracer on one translucency scene: the
reference, each model's frame (tone-mapped as the bench scores them: Khronos PBR Neutral, sRGB),
and per model the ratio model / reference of the red and green channels as a map (red: too
bright, blue: too dark, black: within a few percent; log2 from −1.5 to 1.5), with the mean
ΔE2000 over the object's pixels in each model's caption.

    .venv/bin/python python/model_ratio_figure.py --scene hand-skin1-back \
        --model "kernel + slab=--subsurface screen-space-slab --diffuse half-space" \
        --model "kernel + slab-gather=--subsurface screen-space-slab-gather --diffuse half-space" \
        --out docs/images/hand_transmission_gather.png

Each model renders with `rouge render` and the scene's sidecar options, `--no-specular` (the
references hold the subsurface light only). Needs the release binary (target/release/rouge).
"""

from __future__ import annotations

import argparse
import json
import shlex
import subprocess
import sys
import tempfile
from pathlib import Path

import numpy as np

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE))

import mitsuba_ref  # noqa: E402
from reference_noise_floor import delta_e, pbr_neutral  # noqa: E402

ROOT = HERE.parent


def srgb8(linear: np.ndarray) -> np.ndarray:
    c = np.clip(pbr_neutral(linear), 0.0, 1.0)
    c = np.where(c <= 0.0031308, 12.92 * c, 1.055 * np.power(c, 1 / 2.4) - 0.055)
    return (np.clip(c, 0, 1) * 255 + 0.5).astype(np.uint8)


def ratio_map(model: np.ndarray, ref: np.ndarray, covered: np.ndarray) -> np.ndarray:
    q = np.log2(np.maximum(model, 1e-5) / np.maximum(ref, 1e-5))
    q = np.clip(q, -1.5, 1.5) / 1.5
    img = np.zeros(q.shape + (3,), np.uint8)
    img[..., 0] = (np.clip(q, 0, 1) * 255).astype(np.uint8)
    img[..., 2] = (np.clip(-q, 0, 1) * 255).astype(np.uint8)
    img[~covered] = 60
    return img


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--scene", required=True, help="sidecar name in --references")
    ap.add_argument("--references", default=str(ROOT / "data/reference/translucency"))
    ap.add_argument("--model", action="append", required=True, help="LABEL=rouge render options")
    ap.add_argument("--rouge", default=str(ROOT / "target/release/rouge"))
    ap.add_argument("--out", required=True)
    args = ap.parse_args()
    from PIL import Image, ImageDraw

    refs = Path(args.references)
    side = json.loads((refs / f"{args.scene}.json").read_text())
    ref = mitsuba_ref.read_exr(refs / side["image"])
    covered, r = ref[..., 3] > 0.999, ref[..., :3]
    tiles, captions = [srgb8(r)], ["path tracer (Mitsuba 3)"]
    ratios = []
    with tempfile.TemporaryDirectory() as tmp:
        for spec in args.model:
            label, _, options = spec.partition("=")
            out = Path(tmp) / "m.exr"
            cmd = [args.rouge, "render", *side["rouge_options"], *shlex.split(options), "--no-specular", "--out", str(out)]
            subprocess.run(cmd, check=True, capture_output=True, cwd=ROOT)
            img = mitsuba_ref.read_exr(out)[..., :3]
            score = delta_e(img[covered], r[covered])
            tiles.append(srgb8(img))
            captions.append(f"{label}: mean dE2000 {score:.2f}")
            ratios += [(ratio_map(img[..., c], r[..., c], covered), f"{label}: {name} / path tracer") for c, name in ((0, "R"), (1, "G"))]
            print(f"{label}: mean ΔE2000 {score:.2f}")
    h, w = r.shape[:2]
    cols = max(len(tiles), len(ratios))
    canvas = Image.new("RGB", (cols * w, 2 * (h + 16)), (255, 255, 255))
    draw = ImageDraw.Draw(canvas)
    for i, (tile, caption) in enumerate(zip(tiles, captions)):
        canvas.paste(Image.fromarray(tile), (i * w, 16))
        draw.text((i * w + 3, 2), caption, fill=(0, 0, 0))
    for i, (tile, caption) in enumerate(ratios):
        canvas.paste(Image.fromarray(tile), (i * w, h + 32))
        draw.text((i * w + 3, h + 18), caption, fill=(0, 0, 0))
    canvas = canvas.resize((canvas.width * 2, canvas.height * 2), Image.NEAREST)
    canvas.save(args.out)
    print(f"wrote {args.out}")


if __name__ == "__main__":
    main()
