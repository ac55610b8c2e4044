"""What a dielectric boundary does to the light through a slab (issue 31 item 5; docs/BENCHMARKS.md
"The slab law under a dielectric boundary"): backlit reference scenes rendered by `rouge render
--subsurface slab` at η = 1 (as the path-traced references, whose tile is beside it) and at the
medium's own η (marble 1.5, skim milk and skin1 1.3), where the path tracer has no reference
(a delta light does not reach through a smooth dielectric). The whole scene takes the medium's η:
besides the slab law, the lit side's diffuse law and the hidden-entry gather take the faces'
Fresnel terms too (the hand's lit rims, seen at grazing, lose most).

    python python/slab_eta_figure.py --rouge target/release/rouge --out docs/images/slab_eta.png

Columns: Mitsuba 3 at η = 1, the slab law at η = 1, the slab law at the medium's η (tone-mapped
alike), and the ratio of the last two per pixel (mean over RGB; log scale, 1/2 blue, 1 grey,
2 red). Pixels outside the reference's coverage are black.
"""

from __future__ import annotations

import sys
import tempfile
from pathlib import Path

import numpy as np

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE))

from thickness_figure import figure_args, reference, render, sheet, tone  # noqa: E402

SCENES = ["wedge-marble", "wedge-skimmilk", "hand-skin1-back"]
SLAB = ["--subsurface", "slab"]


def without_eta(options: list[str]) -> list[str]:
    """The sidecar's options less its `--eta 1`: the medium keeps its own index."""
    out = list(options)
    i = out.index("--eta")
    del out[i : i + 2]
    return out


def ratio_tile(a: np.ndarray, b: np.ndarray, covered: np.ndarray) -> np.ndarray:
    """b / a per pixel (mean over RGB) as colour: log2 from −1 (blue) through 0 (grey) to 1 (red)."""
    r = np.log2(np.maximum(b.mean(axis=-1), 1e-6) / np.maximum(a.mean(axis=-1), 1e-6))
    t = np.clip(r, -1.0, 1.0)
    grey = 0.5 * (1.0 - np.abs(t))
    rgb = np.stack([grey + np.maximum(t, 0.0), grey, grey + np.maximum(-t, 0.0)], axis=-1)
    rgb[~covered] = 0.0
    return (np.clip(rgb, 0.0, 1.0) * 255 + 0.5).astype(np.uint8)


def main() -> None:
    a = figure_args(__doc__, 192, ("--out", HERE.parent / "docs" / "images" / "slab_eta.png"))
    rows = []
    with tempfile.TemporaryDirectory() as tmp:
        for scene in SCENES:
            options, _, covered, ref_tile = reference(scene, a.exposure)
            matched = render(a.rouge, options, SLAB, Path(tmp) / f"{scene}-1.exr")
            own = render(a.rouge, without_eta(options), SLAB, Path(tmp) / f"{scene}-eta.exr")
            matched[~covered] = 0.0
            own[~covered] = 0.0
            ratio = own[covered].mean() / max(matched[covered].mean(), 1e-12)
            print(f"{scene}: the medium's η over η = 1, mean radiance ×{ratio:.2f}")
            rows.append((scene, [ref_tile, tone(matched, a.exposure), tone(own, a.exposure), ratio_tile(matched, own, covered)]))
    # ASCII: the sheet's default bitmap font has no η.
    labels = ["Mitsuba 3, eta 1", "slab law, eta 1", "slab law, the medium's eta", "ratio (1/2 blue, 2 red)"]
    a.out.parent.mkdir(parents=True, exist_ok=True)
    sheet(labels, rows, a.size).save(a.out)
    print(f"wrote {a.out}")


if __name__ == "__main__":
    main()
