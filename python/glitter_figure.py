"""The picture of glitter against explicit flakes (docs/images/glitter_scales.png).

Runs `rouge bench glitter --frames-dir` (the turning patch of 100 µm flakes, 16 per mm², at
0.083, 0.3, 1 and 3 mm a pixel) and tiles the first frame of each method: the explicit flakes'
exact box filter (the reference), 16×16 and 2×2 supersampling of them, and Rouge's estimator.
Each row is scaled to its exact frame's brightest pixel and shown as the square root of the lit
fraction (so a quarter-lit pixel reads half grey); a 48-pixel corner, magnified 4× with
nearest-neighbour pixels.

    .venv/bin/python python/glitter_figure.py [--rouge target/release/rouge] [--out docs/images/glitter_scales.png]
"""

import argparse
import json
import pathlib
import subprocess
import tempfile

import numpy as np
from PIL import Image, ImageDraw

COLUMNS = [("exact", "explicit flakes, exact (reference)"), ("ssaa16", "16x16 samples"),
           ("ssaa2", "2x2 samples"), ("rouge", "Rouge's estimator, 1 evaluation")]
CROP = 48
SCALE = 4
LABEL_W = 120
HEAD_H = 22


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--rouge", default="target/release/rouge")
    parser.add_argument("--out", default="docs/images/glitter_scales.png")
    args = parser.parse_args()
    with tempfile.TemporaryDirectory() as tmp:
        subprocess.run([args.rouge, "bench", "glitter", "--frames", "2", "--frames-dir", tmp], check=True,
                       capture_output=True)
        entries = json.loads((pathlib.Path(tmp) / "frames.json").read_text())
        sizes = sorted({e["pixel_mm"] for e in entries})
        tile = CROP * SCALE
        width = LABEL_W + len(COLUMNS) * (tile + 6)
        height = HEAD_H + len(sizes) * (tile + 6)
        canvas = Image.new("RGB", (width, height), (24, 24, 24))
        draw = ImageDraw.Draw(canvas)
        for c, (_, title) in enumerate(COLUMNS):
            draw.text((LABEL_W + c * (tile + 6) + 4, 5), title, fill=(230, 230, 230))
        for r, mm in enumerate(sizes):
            y = HEAD_H + r * (tile + 6)
            draw.text((6, y + tile // 2 - 12), f"{mm:g} mm a pixel", fill=(230, 230, 230))
            draw.text((6, y + tile // 2 + 2), f"({1 / mm:.1f} px/mm)", fill=(170, 170, 170))
            for c, (slug, _) in enumerate(COLUMNS):
                (entry,) = [e for e in entries if e["pixel_mm"] == mm and e["method"] == slug]
                lit = np.asarray(Image.open(pathlib.Path(tmp) / entry["file"]), dtype=float) / 65535.0
                grey = (np.sqrt(lit[:CROP, :CROP]) * 255).round().astype(np.uint8)
                img = Image.fromarray(grey).resize((tile, tile), Image.NEAREST).convert("RGB")
                canvas.paste(img, (LABEL_W + c * (tile + 6), y))
    canvas.save(args.out)
    print(f"wrote {args.out}")


if __name__ == "__main__":
    main()
