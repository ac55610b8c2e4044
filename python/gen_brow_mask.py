"""The brows' region of the default head: data/heads/masks/brows.png.

The brow hairs of data/heads/hm08_head.obj (groups `brow_l`, `brow_r`, grown by
python/gen_head_parts.py) carry the UVs of the skin under them. Their roots and shafts, splatted
into the head's UV space at MASK_PX² and blurred by a Gaussian of BLUR_MM on the skin, give where
the brows grow; the mask is that density over the level DENSE (a brow's well-filled middle), with
a soft edge: 1 where the brow is full, falling to 0 about a millimetre outside its last hairs. A
brow pencil, powder or gel layer uses it as its region (`"region": "brows"` in a look,
rouge_model::look::Region::Brows).

8-bit greyscale, row 0 at v = 1, filter 0 on every row (as gen_head_raster.write_png). Deterministic;
no arguments; reads only the committed OBJ.

Run: .venv/bin/python python/gen_brow_mask.py
"""
from __future__ import annotations

from pathlib import Path

import numpy as np

from gen_head_raster import write_png
from gen_wrinkles import read_obj

ROOT = Path(__file__).resolve().parent.parent
OUT = ROOT / "data/heads/masks/brows.png"
MASK_PX = 1024
MM_PER_UV = 784.0  # the default head's mean scale (rouge_model::skin::detail::tiles_per_uv × 8 mm)
BLUR_MM = 1.2
DENSE = 0.35  # of the density's 99th percentile


def blur(img: np.ndarray, sigma_px: float) -> np.ndarray:
    r = int(np.ceil(3 * sigma_px))
    k = np.exp(-0.5 * (np.arange(-r, r + 1) / sigma_px) ** 2)
    k /= k.sum()
    out = np.apply_along_axis(lambda row: np.convolve(row, k, mode="same"), 1, img)
    return np.apply_along_axis(lambda col: np.convolve(col, k, mode="same"), 0, out)


def main() -> None:
    _, VT, groups = read_obj()
    density = np.zeros((MASK_PX, MASK_PX))
    for g in ("brow_l", "brow_r"):
        uv = VT[sorted({c[1] for f in groups[g] for c in f})]
        cols = np.clip((uv[:, 0] * MASK_PX).astype(int), 0, MASK_PX - 1)
        rows = np.clip(((1.0 - uv[:, 1]) * MASK_PX).astype(int), 0, MASK_PX - 1)
        np.add.at(density, (rows, cols), 1.0)
    density = blur(density, BLUR_MM / MM_PER_UV * MASK_PX)
    level = DENSE * np.percentile(density[density > 0], 99)
    t = np.clip(density / level, 0.0, 1.0)
    mask = t * t * (3.0 - 2.0 * t)
    write_png(OUT, np.round(mask * 255.0))
    print(f"wrote {OUT}: {int((mask > 0.5).sum())} texels over 0.5, {int((mask > 0).sum())} over 0")


if __name__ == "__main__":
    main()
