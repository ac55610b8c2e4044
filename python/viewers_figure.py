"""One view from Rouge, Blender and three.js side by side (docs/images/export_viewers.png,
docs/FORMATS.md §8): `rouge render --lights front` with and without its subsurface scattering,
Blender's Cycles drawing `rouge export gltf`'s .glb (python/blender_check.py's scene), and
three.js drawing `rouge export web`'s page in headless Chromium (python/web_check.py's), with the
CIEDE2000 of each against Rouge without subsurface scattering, and of Rouge's own subsurface
scattering, the part neither viewer has.

    .venv/bin/python python/viewers_figure.py --rouge target/debug/rouge \\
        --blender-python /work/venv-bpy/bin/python [--out docs/images/export_viewers.png]
"""

import argparse
import json
import pathlib
import subprocess
import tempfile

import blender_check
from blender_check import rouge_camera_and_light, run

ROOT = pathlib.Path(__file__).resolve().parent.parent


def main(argv=None) -> dict:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--rouge", default="target/debug/rouge")
    parser.add_argument("--blender-python", default="/work/venv-bpy/bin/python")
    parser.add_argument("--out", default="docs/images/export_viewers.png")
    parser.add_argument("--width", type=int, default=400)
    parser.add_argument("--height", type=int, default=300)
    parser.add_argument("--samples", type=int, default=64)
    parser.add_argument("--textures", default="1024")
    args = parser.parse_args(argv)

    import colour
    import numpy as np
    from PIL import Image, ImageDraw
    from side_by_side import heat

    scene = ["--lights", "front"]
    size = ["--width", str(args.width), "--height", str(args.height)]
    with tempfile.TemporaryDirectory() as tmp:
        tmp = pathlib.Path(tmp)
        run([args.rouge, "export", "gltf", *scene, "--textures", args.textures, "--out", tmp / "face.glb"])
        run([args.rouge, "export", "web", *scene, "--textures", args.textures, "--out", tmp / "page"])
        run([args.rouge, "export", "mitsuba", *scene, *size, "--interior", "lambert", "--flat-skin", "--out", tmp / "mitsuba"])
        run([args.rouge, "render", *scene, *size, "--subsurface", "none", "--out", tmp / "rouge.exr"])
        run([args.rouge, "render", *scene, *size, "--out", tmp / "rouge_sss.exr"])
        (tmp / "view.json").write_text(json.dumps(rouge_camera_and_light(tmp / "mitsuba" / "scene.xml")))
        run([args.blender_python, blender_check.__file__, "--samples", str(args.samples), "--blender-stage",
             tmp / "face.glb", tmp / "view.json", tmp / "rouge.exr", tmp / "rouge.npz"])
        data = np.load(tmp / "rouge.npz")
        blender, rouge = data["blender"][..., :3], data["rouge"][..., :3]
        sss = blender_check.read_exr_rgb(args.blender_python, tmp / "rouge_sss.exr", tmp / "rouge_sss.npy")[..., :3]
        report = json.loads(subprocess.run(
            ["node", ROOT / "tests/web/check.mjs", tmp / "page/index.html", tmp, "--embed", str(args.width),
             str(args.height)], check=True, capture_output=True, text=True).stdout)
        if report["errors"]:
            raise SystemExit(f"the page reported errors: {report['errors']}")
        v = np.asarray(Image.open(tmp / "embed.png").convert("RGB"), dtype=np.float64) / 255
        three = np.where(v <= 0.04045, v / 12.92, ((v + 0.055) / 1.055) ** 2.4)

    bg = three[0, 0]
    mask = (data["blender"][..., 3] >= 0.999) & (np.abs(three - bg).sum(axis=-1) > 0.01)
    lab = lambda rgb: colour.XYZ_to_Lab(colour.RGB_to_XYZ(np.clip(rgb, 0, None), "sRGB", apply_cctf_decoding=False))
    pairs = {"Blender vs Rouge": blender, "three.js vs Rouge": three, "Rouge's SSS vs Rouge": sss}
    des = {k: colour.delta_E(lab(rouge), lab(img), method="CIE 2000") for k, img in pairs.items()}
    stats = {k: {"mean": float(d[mask].mean()), "median": float(np.median(d[mask])),
                 "p95": float(np.percentile(d[mask], 95))} for k, d in des.items()}
    stats["pixels"] = int(mask.sum())
    print(json.dumps(stats, indent=1))

    def display(rgb):
        c = np.clip(np.where(mask[..., None], rgb, 0), 0, 1)
        c = np.where(c <= 0.0031308, 12.92 * c, 1.055 * np.power(c, 1 / 2.4) - 0.055)
        return Image.fromarray((c * 255 + 0.5).astype(np.uint8))

    top = [("Rouge (--subsurface none)", display(rouge)), ("Rouge (its subsurface scattering)", display(sss)),
           ("Blender Cycles (the .glb)", display(blender)), ("three.js in Chromium (the page)", display(three))]
    bottom = [(f"dE2000 {k}: mean {s['mean']:.2f}, p95 {s['p95']:.2f}", heat(des[k], mask))
              for k, s in stats.items() if k != "pixels"]
    w, h = args.width, args.height
    sheet = Image.new("RGB", (4 * (w + 8) + 8, 2 * (h + 24) + 28), "white")
    draw = ImageDraw.Draw(sheet)
    for row, panels in enumerate([top, [("", Image.new("RGB", (w, h), "white"))] + bottom]):
        for i, (label, img) in enumerate(panels):
            x, y = 8 + i * (w + 8), row * (h + 24)
            sheet.paste(img, (x, y + 20))
            draw.text((x, y + 4), label, fill="black")
    draw.text((8, 2 * (h + 24) + 6), f"One view, --lights front, {stats['pixels']} head pixels; dE2000 maps: blue 0, "
              "red 10 or more, each against Rouge without subsurface scattering", fill="black")
    sheet.save(args.out)
    pathlib.Path(args.out).with_suffix(".json").write_text(json.dumps(stats, indent=1) + "\n")
    return stats


if __name__ == "__main__":
    main()
