"""three.js draws `rouge export web`'s page: the page in headless Chromium beside
`rouge render --lights front --subsurface none`'s PNG of the same view, with the CIEDE2000 between
them (python/test_export_viewers.py holds it within a bound; docs/FORMATS.md §8.2).

The page's view is Rouge's camera with one white directional light from the camera of
irradiance π, which is `rouge render --lights front`. The page is opened with `#embed` (the
canvas alone, at the frame's size, the look) by tests/web/check.mjs (playwright-core driving
Debian's chromium, SwiftShader's WebGL). Both images are 8-bit sRGB, and Rouge's PNG is its
display frame, **tone-mapped**, so the distance includes Rouge's tone curve: a coarse check of
the page (colour space, texture orientation, materials), cheap enough for CI. The viewers are
measured in linear light by python/viewers_figure.py. ΔE2000 (colour-science) is taken over the
pixels where both differ from their background.

    npm ci --prefix tests/web && apt-get install chromium
    .venv/bin/python python/web_check.py --rouge target/debug/rouge [--out web_check.png]
"""

import argparse
import json
import pathlib
import subprocess
import sys
import tempfile

ROOT = pathlib.Path(__file__).resolve().parent.parent


def run(cmd):
    print("$", " ".join(map(str, cmd)), flush=True)
    return subprocess.run([str(c) for c in cmd], check=True, capture_output=True, text=True).stdout


def main(argv=None) -> dict:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--rouge", default="target/debug/rouge")
    parser.add_argument("--out", default="web_check.png")
    parser.add_argument("--width", type=int, default=400)
    parser.add_argument("--height", type=int, default=300)
    parser.add_argument("--textures", default="1024")
    parser.add_argument("--no-sss", action="store_true", help="skip the frame with subsurface scattering")
    args = parser.parse_args(argv)

    import colour
    import numpy as np
    from PIL import Image
    from side_by_side import heat, write_sheet

    def load(path):
        return np.asarray(Image.open(path).convert("RGB"), dtype=np.float64) / 255.0

    with tempfile.TemporaryDirectory() as tmp:
        tmp = pathlib.Path(tmp)
        size = ["--width", str(args.width), "--height", str(args.height)]
        run([args.rouge, "export", "web", "--textures", args.textures, "--out", tmp / "page"])
        run([args.rouge, "render", "--lights", "front", *size, "--subsurface", "none", "--out", tmp / "rouge.png"])
        if not args.no_sss:
            run([args.rouge, "render", "--lights", "front", *size, "--out", tmp / "rouge_sss.png"])
        report = json.loads(run(["node", ROOT / "tests/web/check.mjs", tmp / "page/index.html", tmp,
                                 "--embed", args.width, args.height]))
        if report["errors"]:
            sys.exit(f"the page reported errors: {report['errors']}")
        three, rouge = load(tmp / "embed.png"), load(tmp / "rouge.png")
        sss = None if args.no_sss else load(tmp / "rouge_sss.png")

    def foreground(img):
        return np.abs(img - img[0, 0]).sum(axis=-1) > 8 / 255

    mask = foreground(three) & foreground(rouge)
    lab = lambda rgb: colour.XYZ_to_Lab(colour.RGB_to_XYZ(rgb, "sRGB", apply_cctf_decoding=True))
    de = colour.delta_E(lab(rouge), lab(three), method="CIE 2000")
    stats = {
        "pixels": int(mask.sum()),
        "delta_e_mean": float(de[mask].mean()),
        "delta_e_median": float(np.median(de[mask])),
        "delta_e_p95": float(np.percentile(de[mask], 95)),
        "only_three_js_pixels": int((foreground(three) & ~foreground(rouge)).sum()),
        "only_rouge_pixels": int((foreground(rouge) & ~foreground(three)).sum()),
        "textures": args.textures,
        "size": [args.width, args.height],
    }
    if sss is not None:
        de_sss = colour.delta_E(lab(sss), lab(three), method="CIE 2000")
        stats["delta_e_mean_vs_rouge_screen_space_sss"] = float(de_sss[mask].mean())
        stats["delta_e_p95_vs_rouge_screen_space_sss"] = float(np.percentile(de_sss[mask], 95))
    print(json.dumps(stats, indent=1))

    as_image = lambda v: Image.fromarray((v * 255 + 0.5).astype(np.uint8))
    panels = [("Rouge (--lights front --subsurface none)", as_image(rouge)),
              ("three.js in Chromium (the share page)", as_image(three)),
              ("dE2000 (blue 0, red 10 or more)", heat(de, mask))]
    write_sheet(panels, stats, args.out)
    return stats


if __name__ == "__main__":
    main()
