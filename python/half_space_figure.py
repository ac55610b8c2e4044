"""The exact half-space under the kernel against the path tracer (issue 31, item 1;
docs/BENCHMARKS.md "The exact half-space under the kernel"): front-lit and backlit reference
scenes rendered by `rouge render` with the screen-space kernel of the better dipole under the
Lambert law (the medium's adding-doubling albedo) and under the half-space law (`--diffuse
half-space`), next to the Mitsuba 3 reference and each one's per-pixel error.

    python python/half_space_figure.py --rouge target/release/rouge --out docs/images/half_space.png

Each row is a scene; columns: reference, Lambert, half-space (tone-mapped alike), then the
absolute error of each (linear radiance averaged over RGB, 0 to --error-max, black to white).
Pixels outside the reference's coverage are black.
"""

from __future__ import annotations

import sys
import tempfile
from pathlib import Path

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE))

from thickness_figure import comparison_rows, figure_args, sheet  # noqa: E402

SCENES = ["head-skin1-front-left", "sphere-ketchup", "sphere-marble", "head-skin1-back"]
MODELS = [
    ("lambert", ["--diffuse", "lambert"]),
    ("half-space", ["--diffuse", "half-space"]),
]


def main() -> None:
    a = figure_args(__doc__, 192, ("--out", HERE.parent / "docs" / "images" / "half_space.png"))
    with tempfile.TemporaryDirectory() as tmp:
        rows = comparison_rows(a.rouge, SCENES, MODELS, a.exposure, a.error_max, Path(tmp), lambda m: True)
    labels = ["Mitsuba 3", "kernel, Lambert", "kernel, half-space", "|error| Lambert", "|error| half-space"]
    a.out.parent.mkdir(parents=True, exist_ok=True)
    sheet(labels, rows, a.size).save(a.out)
    print(f"wrote {a.out}")


if __name__ == "__main__":
    main()
