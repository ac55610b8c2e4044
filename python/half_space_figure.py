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
from pathlib import Path

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE))

from thickness_figure import comparison_figure  # noqa: E402

SCENES = ["head-skin1-front-left", "sphere-ketchup", "sphere-marble", "head-skin1-back"]
MODELS = [
    ("lambert", ["--diffuse", "lambert"]),
    ("half-space", ["--diffuse", "half-space"]),
]


def main() -> None:
    labels = ["Mitsuba 3", "kernel, Lambert", "kernel, half-space", "|error| Lambert", "|error| half-space"]
    out = HERE.parent / "docs" / "images" / "half_space.png"
    comparison_figure(__doc__, out, SCENES, MODELS, labels, lambda m: True)


if __name__ == "__main__":
    main()
