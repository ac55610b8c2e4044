"""Where the thickness translucency ([BarreBrisebois2011]) is right and where it fails: the
backlit reference scenes rendered by `rouge render` with no subsurface term and with the
thickness model (baked and per-light local thickness, parameters fitted to the path tracer),
next to the Mitsuba 3 reference and the per-pixel error (docs/BENCHMARKS.md, docs/TRANSLUCENCY.md).

    python python/thickness_figure.py --rouge target/release/rouge --out docs/images/thickness_translucency.png

Each row is a scene; columns: reference, none, baked, per light (tone-mapped alike), then the
absolute error of the baked and per-light frames (linear radiance, 0 to --error-max, black to
white). Pixels outside the reference's coverage are black.
"""

from __future__ import annotations

import argparse
import json
import subprocess
import sys
import tempfile
from pathlib import Path

import numpy as np

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE))

import mitsuba_ref  # noqa: E402

REFS = HERE.parent / "data" / "reference" / "translucency"
SCENES = ["head-skin1-back", "hand-skin1-back", "head-skin1-back-morph", "wedge-marble"]
MODELS = [
    ("none", ["--subsurface", "none"]),
    ("baked", ["--subsurface", "thickness", "--thickness-source", "baked"]),
    ("per light", ["--subsurface", "thickness", "--thickness-source", "shadow-map"]),
]


def tone(rgb: np.ndarray, exposure: float) -> np.ndarray:
    """Reinhard on each channel, then the sRGB curve, as 8-bit."""
    x = np.clip(rgb * exposure, 0.0, None)
    x = x / (1.0 + x)
    x = np.where(x <= 0.0031308, 12.92 * x, 1.055 * np.power(x, 1 / 2.4) - 0.055)
    return (np.clip(x, 0.0, 1.0) * 255 + 0.5).astype(np.uint8)


def render(rouge: str, options: list[str], extra: list[str], out: Path) -> np.ndarray:
    cmd = [rouge, "render", *options, *extra, "--no-specular", "--out", str(out)]
    subprocess.run(cmd, check=True, capture_output=True, cwd=HERE.parent)
    return mitsuba_ref.read_exr(out)[..., :3]


def reference(scene: str, exposure: float):
    """A reference scene: its `rouge render` options, its linear RGB, the mask of fully covered
    pixels, and its tone-mapped tile."""
    sidecar = json.loads((REFS / f"{scene}.json").read_text())
    ref = mitsuba_ref.read_exr(REFS / sidecar["image"])
    return sidecar["rouge_options"], ref[..., :3], ref[..., 3] > 0.999, tone(ref[..., :3], exposure)


def figure_args(doc: str, size: int, out: tuple[str, Path]):
    """The figure scripts' command line: the `rouge` binary, where to write (`out`: the option
    and its default), exposure, error scale and tile size; parsed. Mitsuba's reader is set up."""
    import mitsuba as mi

    ap = argparse.ArgumentParser(description=doc, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--rouge", default=str(HERE.parent / "target" / "release" / "rouge"))
    ap.add_argument(out[0], type=Path, default=out[1])
    ap.add_argument("--exposure", type=float, default=8.0)
    ap.add_argument("--error-max", type=float, default=0.1)
    ap.add_argument("--size", type=int, default=size, help="each tile's side, pixels")
    mi.set_variant("scalar_rgb")
    return ap.parse_args()


def comparison_rows(rouge: str, scenes, models, exposure: float, error_max: float, tmp: Path, with_error) -> list:
    """Per scene: the reference's tile, each model's (`models`: name and `rouge render` options),
    then the absolute error of the models `with_error(name)` picks (linear radiance, 0 to
    `error_max`, black to white). Pixels the reference does not fully cover are black."""
    rows = []
    for scene in scenes:
        options, ref, covered, tile = reference(scene, exposure)
        tiles, errors = [tile], []
        for i, (name, extra) in enumerate(models):
            img = render(rouge, options, extra, tmp / f"{scene}-{i}.exr")
            img[~covered] = 0.0
            tiles.append(tone(img, exposure))
            if with_error(name):
                err = np.clip(np.abs(img - ref).mean(axis=-1) / error_max, 0.0, 1.0)
                errors.append((err[..., None].repeat(3, axis=-1) * 255).astype(np.uint8))
        rows.append((scene, tiles + errors))
    return rows


def sheet(columns: list[str], rows: list[tuple[str, list]], size: int):
    """A contact sheet: a label per column, then per row its name and its tiles (8-bit RGB
    arrays, each scaled to `size`² pixels)."""
    from PIL import Image, ImageDraw

    pad, head = 4, 18
    w = len(columns) * (size + pad) + pad
    h = head + len(rows) * (size + head + pad)
    out = Image.new("RGB", (w, h), (255, 255, 255))
    draw = ImageDraw.Draw(out)
    for i, label in enumerate(columns):
        draw.text((pad + i * (size + pad) + 4, 3), label, fill=(0, 0, 0))
    for r, (name, tiles) in enumerate(rows):
        y = head + r * (size + head + pad)
        draw.text((pad + 4, y + 2), name, fill=(0, 0, 0))
        for i, tile in enumerate(tiles):
            out.paste(Image.fromarray(tile).resize((size, size), Image.NEAREST), (pad + i * (size + pad), y + head))
    return out


def comparison_figure(
    doc: str, default_out: Path, scenes, models, labels: list[str], with_error, size: int = 192
) -> None:
    """A figure script's whole run: its command line (`figure_args`), the reference and each model
    per scene with the errors `with_error` picks (`comparison_rows`), one contact sheet under
    `labels` written to --out."""
    a = figure_args(doc, size, ("--out", default_out))
    with tempfile.TemporaryDirectory() as tmp:
        rows = comparison_rows(a.rouge, scenes, models, a.exposure, a.error_max, Path(tmp), with_error)
    a.out.parent.mkdir(parents=True, exist_ok=True)
    sheet(labels, rows, a.size).save(a.out)
    print(f"wrote {a.out}")


def main() -> None:
    labels = ["Mitsuba 3", "none", "baked", "per light", "|error| baked", "|error| per light"]
    out = HERE.parent / "docs" / "images" / "thickness_translucency.png"
    comparison_figure(__doc__, out, SCENES, MODELS, labels, lambda m: m != "none")


if __name__ == "__main__":
    main()
