"""Expression wrinkles and lip furrows of the default head (docs/FINISHES.md), rendered by the
real `rouge` binary with the skin maps and their detail, bare skin, under the studio lights:

  docs/images/wrinkles_closeup.png  the forehead at rest and with raised brows (browInnerUp),
                                    the left eye's corner at rest and squinting in a smile
                                    (crow's feet), the mouth at rest (the nasolabial folds and
                                    the lips' furrows at their rest depth) and smiling

The wrinkles' map is python/gen_wrinkles.py's; which Face Units deepen which family is
rouge_model::skin::wrinkles.

Usage: python python/wrinkles_figure.py [--rouge target/release/rouge] [--out docs/images]
"""

from __future__ import annotations

import argparse
import tempfile
from pathlib import Path

from skin_maps_figure import grid, label, render

SIZE = ["--width", "420", "--height", "280", "--look", "bare"]
CELLS = [
    (["--close-up", "forehead", "--pitch", "10"], "", "forehead at rest"),
    (["--close-up", "forehead", "--pitch", "10"], "browInnerUp=1", "browInnerUp 1"),
    (["--close-up", "eyelids", "--yaw", "35"], "", "eye corner at rest"),
    (["--close-up", "eyelids", "--yaw", "35"], "eyeSquintLeft=0.8,mouthSmileLeft=0.6", "squint 0.8 + smile 0.6"),
    (["--close-up", "lips", "--yaw", "20"], "", "mouth at rest"),
    (["--close-up", "lips", "--yaw", "20"], "smile=1", "smile 1"),
]


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--rouge", default="target/release/rouge")
    ap.add_argument("--out", type=Path, default=Path("docs/images"))
    a = ap.parse_args()
    with tempfile.TemporaryDirectory() as tmp:
        cells = []
        for i, (view, expression, text) in enumerate(CELLS):
            args = [*view, *SIZE] + (["--expression", expression] if expression else [])
            cells.append(label(render(a.rouge, Path(tmp) / f"{i}.png", *args), text))
        grid(cells, 2).save(a.out / "wrinkles_closeup.png")


if __name__ == "__main__":
    main()
