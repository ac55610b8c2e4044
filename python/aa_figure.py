"""The picture of edge antialiasing in docs/BENCHMARKS.md (docs/images/aa_edges.png).

Renders the default head turned 30° at 320×240 with `rouge render --aa MODE` for no
antialiasing, sorted two-sided edge overdraw, the paper's line coverage, and 2×2 and 4×4
supersampling, and tiles the same crop of each (the cheek, nose and ear against the background
and against each other), magnified 6× with nearest-neighbour pixels so the edge pixels show.

    .venv/bin/python python/aa_figure.py [--rouge target/release/rouge] [--out docs/images/aa_edges.png]
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


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--rouge", default="target/release/rouge")
    parser.add_argument("--out", default="docs/images/aa_edges.png")
    args = parser.parse_args()
    tiles = []
    with tempfile.TemporaryDirectory() as tmp:
        for label, flags in MODES:
            path = pathlib.Path(tmp) / "frame.png"
            cmd = [args.rouge, "render", "--width", "320", "--height", "240", "--yaw", "30", "--pitch", "5",
                   "--out", str(path), *flags]
            subprocess.run(cmd, check=True, capture_output=True)
            crop = Image.open(path).convert("RGB").crop(CROP)
            tiles.append((label, crop.resize((crop.width * SCALE, crop.height * SCALE), Image.NEAREST)))
    w, h = tiles[0][1].size
    sheet = Image.new("RGB", (len(tiles) * (w + 8) + 8, h + 36), "white")
    draw = ImageDraw.Draw(sheet)
    for i, (label, tile) in enumerate(tiles):
        x = 8 + i * (w + 8)
        sheet.paste(tile, (x, 28))
        draw.text((x, 8), label, fill="black")
    sheet.save(args.out)


if __name__ == "__main__":
    main()
