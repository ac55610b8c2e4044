"""The pictures of edge antialiasing in docs/BENCHMARKS.md.

`--scene head` (docs/images/aa_edges.png): the default head turned 30° at 320×240 with
`rouge render --aa MODE` for no antialiasing, sorted two-sided edge overdraw, the paper's line
coverage, and 2×2 and 4×4 supersampling, the same crop of each (the cheek, nose and ear against
the background and against each other), magnified 6× with nearest-neighbour pixels so the edge
pixels show.

`--scene face` (docs/images/aa_face.png): issue 27's scene, the default head turned 35° at
320×180, the eye and brow: no antialiasing, the default edge antialiasing (two-sided overdraw
and the hairs' coverage), 2×2 supersampling, and the 16×16 reference (`--aa ssaa4` at 4× the
size, box-filtered 4×4 again in linear light).

    .venv/bin/python python/aa_figure.py [--scene head|face] [--rouge target/release/rouge] [--out PNG]
"""

import argparse
import pathlib
import subprocess
import tempfile

from PIL import Image, ImageDraw

MODES = [
    ("none", ["--aa", "none"]),
    ("edges-sorted (two-sided)", ["--aa", "edges-sorted"]),
    ("edges-sorted (line, paper)", ["--aa", "edges-sorted", "--aa-coverage", "line"]),
    ("ssaa2", ["--aa", "ssaa2"]),
    ("ssaa4", ["--aa", "ssaa4"]),
]
CROP = (92, 124, 156, 196)  # x0, y0, x1, y1 of the 320×240 frame: nose, lips, chin
SCALE = 6


FACE_MODES = [
    ("none", ["--aa", "none"], 1),
    ("edges (default edge AA)", ["--aa", "edges"], 1),
    ("ssaa2", ["--aa", "ssaa2"], 1),
    ("reference 16x16", ["--aa", "ssaa4"], 4),
]
FACE_CROP = (110, 60, 190, 108)  # the eyes and brows of the 320×180 frame


def srgb_to_linear(a):
    import numpy as np
    return np.where(a <= 0.04045, a / 12.92, ((a + 0.055) / 1.055) ** 2.4)


def linear_to_srgb(a):
    import numpy as np
    a = np.clip(a, 0.0, 1.0)
    return np.where(a <= 0.0031308, 12.92 * a, 1.055 * a ** (1 / 2.4) - 0.055)


def face_tiles(rouge: str) -> list:
    """The face's crops, each magnified 6×."""
    import numpy as np
    tiles = []
    with tempfile.TemporaryDirectory() as tmp:
        for label, flags, k in FACE_MODES:
            path = pathlib.Path(tmp) / "frame.png"
            cmd = [rouge, "render", "--width", str(320 * k), "--height", str(180 * k), "--yaw", "35",
                   "--out", str(path), *flags]
            subprocess.run(cmd, check=True, capture_output=True)
            image = Image.open(path).convert("RGB")
            if k > 1:  # box filter k×k in linear light
                a = srgb_to_linear(np.asarray(image, dtype=np.float64) / 255.0)
                a = a.reshape(180, k, 320, k, 3).mean(axis=(1, 3))
                image = Image.fromarray((linear_to_srgb(a) * 255.0 + 0.5).astype(np.uint8))
            crop = image.crop(FACE_CROP)
            tiles.append((label, crop.resize((crop.width * SCALE, crop.height * SCALE), Image.NEAREST)))
    return tiles


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--rouge", default="target/release/rouge")
    parser.add_argument("--scene", choices=["head", "face"], default="head")
    parser.add_argument("--out", default=None)
    args = parser.parse_args()
    out = args.out or ("docs/images/aa_edges.png" if args.scene == "head" else "docs/images/aa_face.png")
    tiles = face_tiles(args.rouge) if args.scene == "face" else head_tiles(args.rouge)
    w, h = tiles[0][1].size
    sheet = Image.new("RGB", (len(tiles) * (w + 8) + 8, h + 36), "white")
    draw = ImageDraw.Draw(sheet)
    for i, (label, tile) in enumerate(tiles):
        x = 8 + i * (w + 8)
        sheet.paste(tile, (x, 28))
        draw.text((x, 8), label, fill="black")
    sheet.save(out)


def head_tiles(rouge: str) -> list:
    """The head's crops, each magnified 6×."""
    tiles = []
    with tempfile.TemporaryDirectory() as tmp:
        for label, flags in MODES:
            path = pathlib.Path(tmp) / "frame.png"
            cmd = [rouge, "render", "--width", "320", "--height", "240", "--yaw", "30", "--pitch", "5",
                   "--out", str(path), *flags]
            subprocess.run(cmd, check=True, capture_output=True)
            crop = Image.open(path).convert("RGB").crop(CROP)
            tiles.append((label, crop.resize((crop.width * SCALE, crop.height * SCALE), Image.NEAREST)))
    return tiles


if __name__ == "__main__":
    main()
