"""Figures of the skin maps (docs/SKIN.md, "Skin maps"), rendered by the real `rouge` binary:

  docs/images/skin_maps_tones.png       the ten tones' skin maps on the bare default head
  docs/images/skin_maps_foundation.png  a face with skin conditions bare, under foundation
                                        10, 20 and 40 um, with concealer on the spots over
                                        10 um of foundation, and the default look

Usage: python python/skin_maps_figure.py [--rouge target/release/rouge] [--out docs/images]
(about a minute with the release binary on 2 cores, lavapipe).
"""

from __future__ import annotations

import argparse
import json
import subprocess
import tempfile
from pathlib import Path

from PIL import Image, ImageDraw

TONES = ["very-light", "light", "light-medium", "medium", "tan",
         "olive", "brown", "dark-brown", "deep", "very-deep"]
CONDITIONS = "freckles=0.7,moles=0.5,redness=0.5,acne=0.4,hyperpigmentation=0.4,under_eye=0.6"


def render(rouge: str, out: Path, *args: str) -> Image.Image:
    subprocess.run([rouge, "render", "--out", str(out), *args], check=True,
                   stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    return Image.open(out).convert("RGB")


def foundation_look(folder: Path, microns: int) -> Path:
    look = {"schema": "rouge-look", "version": 1, "name": f"Foundation {microns} um",
            "layers": [{"name": "Foundation", "preset": "builtin:foundation_02_ivory",
                        "thickness": {"uniform_mm": microns / 1000.0}}]}
    path = folder / f"foundation_{microns}.json"
    path.write_text(json.dumps(look))
    return path


def concealer_look(rouge: str, folder: Path, face: list[str]) -> Path:
    """10 um of the ivory foundation and, over it, up to 30 um more of the same as concealer where
    `rouge skin maps --conditions-mask` says the conditions are."""
    tone, conditions, seed = face[1], face[3], face[5]
    mask = folder / "conditions_mask.png"
    subprocess.run([rouge, "skin", "maps", "--tone", tone, "--conditions", conditions, "--seed", seed,
                    "--conditions-mask", str(mask)], check=True, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    look = {"schema": "rouge-look", "version": 1, "name": "Concealer on the spots",
            "layers": [{"name": "Foundation", "preset": "builtin:foundation_02_ivory",
                        "thickness": {"uniform_mm": 0.010}},
                       {"name": "Concealer", "preset": "builtin:foundation_02_ivory",
                        "thickness": {"map": mask.name, "scale_mm": 0.030}}]}
    path = folder / "concealer.json"
    path.write_text(json.dumps(look))
    return path


def label(img: Image.Image, text: str) -> Image.Image:
    draw = ImageDraw.Draw(img)
    draw.rectangle([0, img.height - 22, img.width, img.height], fill=(40, 42, 48))
    draw.text((8, img.height - 18), text, fill=(235, 235, 235))
    return img


def grid(images: list[Image.Image], columns: int) -> Image.Image:
    w, h = images[0].size
    rows = (len(images) + columns - 1) // columns
    sheet = Image.new("RGB", (columns * w, rows * h), (40, 42, 48))
    for i, img in enumerate(images):
        sheet.paste(img, ((i % columns) * w, (i // columns) * h))
    return sheet


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--rouge", default="target/release/rouge")
    ap.add_argument("--out", type=Path, default=Path("docs/images"))
    a = ap.parse_args()
    common = ["--width", "300", "--height", "340", "--skin-map-px", "1024", "--pitch", "3"]
    with tempfile.TemporaryDirectory() as tmp:
        folder = Path(tmp)
        tones = [label(render(a.rouge, folder / f"{t}.png", "--look", "bare", "--skin-tone", t,
                              "--skin-maps", *common), t) for t in TONES]
        grid(tones, 5).save(a.out / "skin_maps_tones.png")
        face = ["--skin-tone", "light-medium", "--skin-conditions", CONDITIONS, "--skin-seed", "4"]
        cells = [label(render(a.rouge, folder / "bare.png", "--look", "bare", *face, *common), "bare")]
        for microns in (10, 20, 40):
            look = foundation_look(folder, microns)
            cells.append(label(render(a.rouge, folder / f"f{microns}.png", "--look", str(look), *face, *common),
                               f"ivory foundation {microns} um"))
        look = concealer_look(a.rouge, folder, face)
        cells.append(label(render(a.rouge, folder / "concealer.png", "--look", str(look), *face, *common),
                           "10 um + concealer on the spots"))
        cells.append(label(render(a.rouge, folder / "default.png", "--look", "default", *face, *common),
                           "default look"))
        grid(cells, 3).save(a.out / "skin_maps_foundation.png")


if __name__ == "__main__":
    main()
