"""Close-ups of finishes (README, docs/FINISHES.md), rendered by the real `rouge`
binary under the studio lights:

  docs/images/finishes_closeup.png  a cheek bare, under 30 um of the ivory foundation with a
                                    matte, a satin and a dewy finish, and the dewy foundation
                                    under 8 um of a matte powder (the porcelain shade, the
                                    nearest to a translucent powder among the sample presets);
                                    the lips with the red lipstick matte, satin and gloss
  docs/images/pores_closeup.png     the side of the nose (the centre of a 1280x720 close-up):
                                    without skin detail, bare skin with its pores, and under
                                    15 um of the ivory foundation with a matte (levelling
                                    0.4) and a gloss finish (levelling 1, a primer's)
  docs/images/shimmer_closeup.png   the eyelid with 15 um of the bronze eyeshadow satin, with a
                                    gold shimmer (70 nm TiO2 on mica) and the sapphire with a
                                    blue one (125 nm), from two directions (the interference
                                    colour moves with the angle)
  docs/images/glitter_closeup.png   the eyelid with 15 um of the bronze eyeshadow with gold
                                    glitter (data/finishes/eyeshadow_03_bronze_gold_glitter.json),
                                    turned by 0, 1 and 2 degrees (the sparkles change, the
                                    flakes stay where they are), and the satin eyeshadow
                                    without glitter

The finishes are the named ones of `rouge finish --kind` (rouge_measure::finish); the presets
are written into a temporary folder, nothing in data/ changes.

Usage: python python/finish_figure.py [--rouge target/release/rouge] [--out docs/images]
       [--only glitter]
(about a minute with the release binary on 2 cores, lavapipe).
"""

from __future__ import annotations

import argparse
import json
import subprocess
import tempfile
from pathlib import Path

from skin_maps_figure import grid, label, render


def finished(rouge: str, folder: Path, builtin: str, kind: str) -> Path:
    out = folder / f"{builtin}_{kind}.json"
    subprocess.run([rouge, "finish", f"builtin:{builtin}", "--kind", kind, "--out", str(out)], check=True,
                   stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    return out


def look(folder: Path, name: str, layers: list[tuple[Path | str, dict]]) -> Path:
    doc = {"schema": "rouge-look", "version": 1, "name": name,
           "layers": [{"preset": str(p), "thickness": t} for p, t in layers]}
    path = folder / f"{name}.json"
    path.write_text(json.dumps(doc))
    return path


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--rouge", default="target/release/rouge")
    ap.add_argument("--out", type=Path, default=Path("docs/images"))
    ap.add_argument("--only", choices=["glitter"], help="make only this figure")
    a = ap.parse_args()
    if a.only == "glitter":
        with tempfile.TemporaryDirectory() as tmp:
            glitter_figure(a.rouge, Path(tmp), a.out)
        return
    cheek = ["--close-up", "cheeks", "--yaw", "40", "--pitch", "5", "--width", "480", "--height", "320"]
    lips = ["--close-up", "lips", "--yaw", "15", "--pitch", "10", "--width", "480", "--height", "320"]
    with tempfile.TemporaryDirectory() as tmp:
        folder = Path(tmp)
        f = {k: finished(a.rouge, folder, "foundation_02_ivory", k) for k in ("matte", "satin", "dewy")}
        powder = finished(a.rouge, folder, "foundation_01_porcelain", "matte")
        coat = {"uniform_mm": 0.030}
        cells = [label(render(a.rouge, folder / "bare.png", "--look", "bare", *cheek), "bare skin")]
        for kind, preset in f.items():
            path = look(folder, f"foundation_{kind}", [(preset, coat)])
            cells.append(label(render(a.rouge, folder / f"{kind}.png", "--look", str(path), *cheek),
                               f"ivory foundation 30 um, {kind}"))
        path = look(folder, "powdered", [(f["dewy"], coat), (powder, {"uniform_mm": 0.008})])
        cells.append(label(render(a.rouge, folder / "powder.png", "--look", str(path), *cheek),
                           "dewy foundation + 8 um matte powder"))
        for kind in ("matte", "satin", "gloss"):
            red = finished(a.rouge, folder, "lipstick_02_red", kind)
            path = look(folder, f"lips_{kind}", [(red, {"region": "lips", "thickness_mm": 0.02})])
            cells.append(label(render(a.rouge, folder / f"lips_{kind}.png", "--look", str(path), *lips),
                               f"red lipstick 20 um, {kind}"))
        grid(cells, 4).save(a.out / "finishes_closeup.png")
        nose = ["--close-up", "nose", "--yaw", "35", "--pitch", "5", "--width", "1280", "--height", "720"]
        thin = {"uniform_mm": 0.015}
        gloss = finished(a.rouge, folder, "foundation_02_ivory", "gloss")
        views = [("no skin detail", ["--look", "bare", "--no-skin-detail"]),
                 ("bare skin: pores and fine lines", ["--look", "bare"]),
                 ("15 um foundation, matte (levelling 0.4)",
                  ["--look", str(look(folder, "thin_matte", [(f["matte"], thin)]))]),
                 ("15 um foundation, gloss (levelling 1)", ["--look", str(look(folder, "thin_gloss", [(gloss, thin)]))])]
        crops = []
        for i, (text, args) in enumerate(views):
            full = render(a.rouge, folder / f"nose{i}.png", *args, *nose)
            crops.append(label(full.crop((400, 200, 880, 520)), text))
        grid(crops, 4).save(a.out / "pores_closeup.png")
        finishes = Path(__file__).resolve().parent.parent / "data" / "finishes"
        lids = {"bronze satin": finished(a.rouge, folder, "eyeshadow_03_bronze", "satin"),
                "bronze, gold shimmer": finishes / "eyeshadow_03_bronze_gold_shimmer.json",
                "sapphire, blue shimmer": finishes / "eyeshadow_02_sapphire_blue_shimmer.json"}
        cells = []
        for yaw, pitch in ((15, 25), (45, 5)):
            for text, preset in lids.items():
                path = look(folder, f"lid_{len(cells)}", [(preset, {"region": "eyelids", "thickness_mm": 0.015})])
                img = render(a.rouge, folder / f"lid{len(cells)}.png", "--look", str(path), "--close-up", "eyelids",
                             "--yaw", str(yaw), "--pitch", str(pitch), "--width", "480", "--height", "320")
                cells.append(label(img, f"{text}, yaw {yaw} pitch {pitch}"))
        grid(cells, 3).save(a.out / "shimmer_closeup.png")
        glitter_figure(a.rouge, folder, a.out)


# The eye in the eyelids' close-up at 480x320.
EYE = (80, 50, 400, 250)


def glitter_figure(rouge: str, folder: Path, out: Path) -> None:
    finishes = Path(__file__).resolve().parent.parent / "data" / "finishes"
    lid = {"region": "eyelids", "thickness_mm": 0.015}
    glitter = look(folder, "lid_glitter", [(finishes / "eyeshadow_03_bronze_gold_glitter.json", lid)])
    satin = look(folder, "lid_satin", [(finished(rouge, folder, "eyeshadow_03_bronze", "satin"), lid)])
    cells = []
    for yaw in (15.0, 16.0, 17.0):
        img = render(rouge, folder / f"glitter{yaw}.png", "--look", str(glitter), "--close-up", "eyelids",
                     "--yaw", str(yaw), "--pitch", "20", "--width", "480", "--height", "320")
        cells.append(label(img.crop(EYE), f"bronze, gold glitter, yaw {yaw:g}"))
    img = render(rouge, folder / "satin.png", "--look", str(satin), "--close-up", "eyelids",
                 "--yaw", "15", "--pitch", "20", "--width", "480", "--height", "320")
    cells.append(label(img.crop(EYE), "bronze satin, no glitter, yaw 15"))
    grid(cells, 2).save(out / "glitter_closeup.png")


if __name__ == "__main__":
    main()
