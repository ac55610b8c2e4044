"""Close-ups of the default head's lashes and mouth (README), rendered by the real `rouge`
binary under the studio lights with the default look:

  docs/images/lashes_mouth.png  the left eye (yaw 25, pitch 5) with natural lashes and with
                                a mascara (`--mascara length=1.4,volume=2.5,curl=20`), the
                                eyes half closed (eyeBlink 0.5) with the mascara, and an open
                                smile (smile 1, jawOpen 0.35) and a wide open mouth (jawOpen 0.8)
                                showing the teeth, tongue and the dark oral cavity; the eye again
                                with an auburn fibre brow gel on the brows, tinting them and
                                adding 60 % more hairs
                                (`--brow-gel color=0.2/0.07/0.03,strength=0.9,fill=0.6`)

Usage: python python/face_parts_figure.py [--rouge target/release/rouge] [--out docs/images]
(about a minute with the release binary on 2 cores, lavapipe).
"""

from __future__ import annotations

import argparse
import tempfile
from pathlib import Path

from skin_maps_figure import grid, label, render

MASCARA = "length=1.4,volume=2.5,curl=20"
BROW_GEL = "color=0.2/0.07/0.03,strength=0.9,fill=0.6"


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--rouge", default="target/release/rouge")
    ap.add_argument("--out", type=Path, default=Path("docs/images"))
    a = ap.parse_args()
    size = ["--width", "480", "--height", "320"]
    eye = ["--close-up", "eyelids", "--yaw", "25", "--pitch", "5", *size]
    mouth = ["--close-up", "lips", "--yaw", "10", "--pitch", "5", *size]
    views = [
        ("natural lashes", eye),
        (f"mascara {MASCARA}", [*eye, "--mascara", MASCARA]),
        ("mascara, eyeBlink 0.5", [*eye, "--mascara", MASCARA, "--expression",
                                   "eyeBlinkLeft=0.5,eyeBlinkRight=0.5"]),
        ("smile 1, jawOpen 0.35", [*mouth, "--expression", "smile=1,jawOpen=0.35"]),
        ("jawOpen 0.8", [*mouth, "--expression", "jawOpen=0.8"]),
        ("jawOpen 0.5, tongueOut 0.6", [*mouth, "--expression", "jawOpen=0.5,tongueOut=0.6"]),
        (f"brow gel {BROW_GEL}", [*eye, "--brow-gel", BROW_GEL]),
    ]
    with tempfile.TemporaryDirectory() as tmp:
        cells = [label(render(a.rouge, Path(tmp) / f"{i}.png", *args), text) for i, (text, args) in enumerate(views)]
    grid(cells, 4).save(a.out / "lashes_mouth.png")
    print(f"wrote {a.out / 'lashes_mouth.png'}")


if __name__ == "__main__":
    main()
