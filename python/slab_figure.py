"""The slab law against the path tracer (issue 31, items 3-4; docs/BENCHMARKS.md "The slab
law"): backlit reference scenes rendered by `rouge render --subsurface slab` (no fitted
parameter) and by the per-light thickness term with its fitted parameters, next to the Mitsuba 3
reference and each one's per-pixel error.

    python python/slab_figure.py --rouge target/release/rouge --out docs/images/slab_translucency.png

Each row is a scene; columns: reference, thickness term (shadow map, fitted), slab law (tone-mapped
alike), then the absolute error of each (linear radiance averaged over RGB, 0 to --error-max,
black to white). Pixels outside the reference's coverage are black. The marble wedge's speckle
is the reference's own noise (0.0046 RMS).
"""

from __future__ import annotations

import sys
from pathlib import Path

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE))

from thickness_figure import comparison_figure  # noqa: E402

SCENES = ["wedge-ketchup", "wedge-marble", "wedge-skimmilk", "hand-skin1-back"]
MODELS = [
    ("thickness", ["--subsurface", "thickness", "--thickness-source", "shadow-map"]),
    ("slab", ["--subsurface", "slab"]),
]


def main() -> None:
    labels = ["Mitsuba 3", "thickness, fitted", "slab law", "|error| thickness", "|error| slab"]
    out = HERE.parent / "docs" / "images" / "slab_translucency.png"
    comparison_figure(__doc__, out, SCENES, MODELS, labels, lambda m: True)


if __name__ == "__main__":
    main()
