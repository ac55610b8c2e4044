"""The cube-atlas dipole ([Benmounah2009]) against the path tracer, and deforming.

    python python/cube_atlas_figure.py --rouge target/release/rouge

Writes two sheets (docs/BENCHMARKS.md, docs/TRANSLUCENCY.md):
- docs/images/cube_atlas.png: per reference scene, Mitsuba 3, no subsurface term, the standard
  dipole's radiance maps, the cube atlas with the paper's kernel reach (one mean free path) and
  with Rouge's default (the profile's support), then the absolute error of both atlas frames
  (linear radiance, 0 to --error-max, black to white);
- docs/images/cube_atlas_deform.png: the cube atlas on deforming meshes: the backlit hand morphed
  toward its bounding sphere (the paper's test, t = 0, 0.2, 0.4, 0.6; at t = 1 the two sides of each finger land on one sphere) and the front-lit default head
  with expressions (neutral, smile, surprise, talk). The atlas is drawn from the current positions
  every frame.
"""

from __future__ import annotations

import json
import sys
import tempfile
from pathlib import Path

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE))

from thickness_figure import REFS, comparison_rows, figure_args, render, sheet, tone  # noqa: E402

SCENES = ["head-skin1-back", "head-skin1-back-morph", "head-skin1-front-left", "hand-skin1-back", "sphere-marble", "wedge-marble"]
ATLAS = ["--subsurface", "cube-atlas"]
MODELS = [
    ("none", ["--subsurface", "none"]),
    ("standard dipole", ["--subsurface", "standard-dipole", "--dipole-frames", "8"]),
    ("atlas, 1 mfp", [*ATLAS, "--atlas-reach", "1"]),
    ("atlas, support", ATLAS),
]
DEFORM = [
    ("hand-skin1-back", [["--morph", t] for t in ["0", "0.2", "0.4", "0.6"]]),
    ("head-skin1-front-left", [[], ["--expression", "smile"], ["--expression", "surprise"], ["--expression", "talk"]]),
]
DEFORM_COLUMNS = ["morph 0 / neutral", "morph 0.2 / smile", "morph 0.4 / surprise", "morph 0.6 / talk"]


def main() -> None:
    a = figure_args(__doc__, 176, ("--out-dir", HERE.parent / "docs" / "images"))
    with tempfile.TemporaryDirectory() as tmp:
        is_atlas = lambda m: m.startswith("atlas")  # noqa: E731
        rows = comparison_rows(a.rouge, SCENES, MODELS, a.exposure, a.error_max, Path(tmp), is_atlas)
        columns = ["Mitsuba 3", *(m[0] for m in MODELS), "|error| 1 mfp", "|error| support"]
        a.out_dir.mkdir(parents=True, exist_ok=True)
        sheet(columns, rows, a.size).save(a.out_dir / "cube_atlas.png")

        rows = []
        for scene, variants in DEFORM:
            base = json.loads((REFS / f"{scene}.json").read_text())["rouge_options"]
            tiles = [
                tone(render(a.rouge, base, [*ATLAS, *extra], Path(tmp) / f"{scene}-deform-{i}.exr"), a.exposure)
                for i, extra in enumerate(variants)
            ]
            rows.append((f"{scene}, cube atlas", tiles))
        sheet(DEFORM_COLUMNS, rows, a.size).save(a.out_dir / "cube_atlas_deform.png")
    print(f"wrote {a.out_dir / 'cube_atlas.png'} and {a.out_dir / 'cube_atlas_deform.png'}")


if __name__ == "__main__":
    main()
