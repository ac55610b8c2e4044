"""Remakes the Mitsuba 3 references of data/reference/translucency/ (docs/TRANSLUCENCY.md).

Each reference scene is a set of `rouge render` scene options. For each one:
  1. `export`: `rouge export mitsuba OPTIONS --interior medium|absorber` into SCENES_DIR/NAME/;
  2. `render`: both scenes rendered by Mitsuba 3 (volpathmis, max_depth = -1) in passes with
     independent seeds, split into two halves, the medium once per colour channel with a gray
     medium of that channel's coefficients (mitsuba_ref.gray_channel_scenes); writes NAME.exr (RGB = the subsurface radiance,
     medium − absorber; A = coverage) as half floats, and NAME.json, the sidecar: the options
     (which `rouge bench translucency` renders again), Mitsuba's version and variant, samples,
     seconds, the scene hash, and the noise floor (RMS standard error of the subsurface image
     over covered pixels, from the two halves).

The two stages can run on different machines (export where `rouge` is built, render where a
GPU is: the cuda_ad_rgb variant is picked when one answers, else scalar_rgb).

  python python/render_reference.py export --rouge target/debug/rouge --scenes-dir build/ref
  python python/render_reference.py render --scenes-dir build/ref --out data/reference/translucency
  python python/render_reference.py all --rouge target/debug/rouge   # both, here
"""

from __future__ import annotations

import argparse
import json
import shutil
import subprocess
import sys
from pathlib import Path

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE))

import mitsuba_ref  # noqa: E402

SIZE = ["--width", "256", "--height", "256"]
# Index-matched boundary (η = 1): the path tracer's light samples then reach every medium vertex
# through the surface. With a dielectric boundary a delta light is reached only through a rough
# interface by rare, huge samples (measured in docs/TRANSLUCENCY.md); the boundary's Fresnel
# terms are checked against 50-digit references instead (python/test_profile_reference.py).
BARE = ["--look", "bare", "--eta", "1"]

HEAD, HAND, SPHERE, WEDGE = "builtin:head", "data/hands/hm08_hand.obj", "builtin:sphere", "builtin:wedge"


def scene(mesh: str, lights: str, medium: str, size: list[str], spp: int, description: str, *extra: str):
    """One reference scene: its `rouge render` / `rouge export mitsuba` options, samples per pixel
    and description."""
    return (["--mesh", mesh, *BARE, "--lights", lights, "--medium", medium, *extra, *size], spp, description)


# name -> (options for `rouge render` / `rouge export mitsuba`, samples per pixel, description)
SCENES: dict[str, tuple[list[str], int, str]] = {
    "head-skin1-front-left": scene(HEAD, "front-left", "skin1", SIZE, 4096,
                                   "the default head (hm08) in skin1, one white key light from the front left"),
    "head-skin1-back": scene(HEAD, "back", "skin1", SIZE, 4096,
                             "the default head in skin1 lit from behind: ears, nose and lips glow"),
    "hand-skin1-back": scene(HAND, "back", "skin1", SIZE, 4096,
                             "the hm08 left hand (python/gen_hand.py) in skin1, lit from behind: the fingers glow"),
    # The backlit head deformed (a morph toward its bounding sphere, `--morph`): what a local
    # thickness baked on the rest pose gets wrong (paper 004's caveat), rendered on a CPU at 128².
    "head-skin1-back-morph": scene(
        HEAD, "back", "skin1", ["--width", "128", "--height", "128"], 512,
        "the backlit head of head-skin1-back morphed 30% toward its bounding sphere (a deformation)",
        "--morph", "0.3"),
}
for medium in ("marble", "skimmilk", "ketchup"):
    SCENES[f"sphere-{medium}"] = scene(SPHERE, "front-left", medium, SIZE, 4096,
                                       f"a 25 mm sphere of {medium}, key light from the front left")
    SCENES[f"wedge-{medium}"] = scene(WEDGE, "back", medium, SIZE, 4096,
                                      f"a wedge of {medium} 1 to 15 mm thick, lit from behind")

# Scenes the half-space law (issue 31) was not developed on, rendered after it was fixed and
# reported without re-fitting: another medium and mesh or light than the scenes above, small
# enough for this machine's CPU (`--set unseen`, into data/reference/translucency-unseen/).
SMALL = ["--width", "96", "--height", "96"]
UNSEEN: dict[str, tuple[list[str], int, str]] = {
    "sphere-apple-front": scene(SPHERE, "front", "apple", SMALL, 256,
                                "a 25 mm sphere of apple, lit from the camera's side (medium and light unseen)"),
    "head-skin2-front-left": scene(
        HEAD, "front-left", "skin2", SMALL, 256,
        "the default head in skin2 (Jensen et al.'s second skin sample), key light from the front left"),
    "hand-skin2-front-left": scene(
        HAND, "front-left", "skin2", SMALL, 256,
        "the hm08 hand in skin2, lit from the front left (mesh, medium and light together unseen)"),
    # Rendered after the slab law's hidden-entry gather was fixed (2026-11-27), for the light
    # that crosses thin parts and comes around from hidden faces, reported without re-fitting
    # (`--spp-scale 16` for the hand, 8 for the wedge: they are dark). A cream sphere lit from
    # behind was left out: 345 s for 256 samples here, and its noise still 39% of its mean.
    "hand-skin2-back": scene(
        HAND, "back", "skin2", SMALL, 256,
        "the hm08 hand in skin2 lit from behind (the gather's scene in a medium it was not developed on)"),
    "wedge-apple-back": scene(
        WEDGE, "back", "apple", SMALL, 256, "a wedge of apple 1 to 15 mm thick, lit from behind"),
}

# Scenes with a dielectric boundary (issue 31, item 5): a smooth boundary of the medium's own
# eta, lit only by a uniform white environment, which the path tracer reaches by following the
# refracted paths out (no light sampling through the boundary, so no fireflies: the estimator
# converges on a CPU). Rouge's medium albedo is exact at normal incidence there (the sphere's
# centre, render/src/dielectric_half_space.rs); the rim measures the angle dependence no diffuse
# law has at eta != 1 (`--set dielectric`, data/reference/translucency-dielectric/).
WHITE_ENV = HERE.parent / "data" / "reference" / "translucency-dielectric" / "white_env.exr"
DIELECTRIC_EXPORT = ["--boundary-alpha", "0"]


def dielectric(medium: str, eta: str, spp: int, description: str, *extra: str):
    args = ["--mesh", SPHERE, *extra, "--look", "bare", "--eta", eta, "--lights", "none",
            "--env", str(WHITE_ENV.relative_to(HERE.parent)), "--medium", medium, *SMALL]
    return (args, spp, description)


DIELECTRIC: dict[str, tuple[list[str], int, str]] = {
    "sphere-skin1-env-eta1.3": dielectric(
        "skin1", "1.3", 1024, "a 25 mm sphere of skin1 behind a smooth boundary of eta 1.3, under a uniform white sky"),
    "sphere-ketchup-env-eta1.3": dielectric(
        "ketchup", "1.3", 512, "a 25 mm sphere of ketchup behind a smooth boundary of eta 1.3, under a uniform white sky"),
    # The same skin1 sphere four times larger: what the sphere's curvature adds under a uniform
    # sky shrinks as 1/R (docs/BENCHMARKS.md, "The dielectric half-space").
    "sphere100-skin1-env-eta1.3": dielectric(
        "skin1", "1.3", 1024,
        "a 100 mm sphere of skin1 behind a smooth boundary of eta 1.3, under a uniform white sky", "--mesh-scale", "4"),
    # Rendered after the curvature term of the half-space law was fixed (render/src/
    # curved_half_space.rs), to report it on scenes it was not developed on: another skin, a
    # sphere of a finger's radius, and a medium whose mean free path is 2-6 mm.
    "sphere-skin2-env-eta1.3": dielectric(
        "skin2", "1.3", 1024, "a 25 mm sphere of skin2 behind a smooth boundary of eta 1.3, under a uniform white sky"),
    "sphere10-skin1-env-eta1.3": dielectric(
        "skin1", "1.3", 1024,
        "a 10 mm sphere of skin1 behind a smooth boundary of eta 1.3, under a uniform white sky", "--mesh-scale", "0.4"),
    "sphere-chicken1-env-eta1.3": dielectric(
        "chicken1", "1.3", 1024, "a 25 mm sphere of chicken1 behind a smooth boundary of eta 1.3, under a uniform white sky"),
}


def write_white_env(path: Path) -> None:
    """A uniform environment of radiance 1 (16 x 8 texels, RGB = 1)."""
    import numpy as np

    path.parent.mkdir(parents=True, exist_ok=True)
    img = np.ones((8, 16, 4), dtype=np.float32)
    mitsuba_ref.write_exr(path, img)


def do_export(rouge: str, scenes_dir: Path, names: list[str], scenes: dict = SCENES) -> None:
    if scenes is DIELECTRIC and not WHITE_ENV.exists():
        write_white_env(WHITE_ENV)
    extra = DIELECTRIC_EXPORT if scenes is DIELECTRIC else []
    for name in names:
        args, spp, _ = scenes[name]
        for interior in ("medium", "absorber"):
            out = scenes_dir / name / interior
            # As `rouge bench translucency` draws the scene: the head without the lashes, brows,
            # teeth and tongue its committed references predate (`as_referenced` there).
            mitsuba_ref.export(rouge, [*args, *extra, "--without-parts", "--spp", str(spp)], interior, out)
        (scenes_dir / name / "options.json").write_text(json.dumps(args))
        print(f"exported {name}", flush=True)


def device_name(variant: str) -> str:
    if variant.startswith("cuda"):
        try:
            q = ["nvidia-smi", "--query-gpu=name", "--format=csv,noheader"]
            return subprocess.run(q, capture_output=True, text=True, check=True).stdout.strip()
        except (OSError, subprocess.CalledProcessError):
            return "CUDA device"
    import os

    return f"CPU ({os.cpu_count()} threads)"


def do_render(
    scenes_dir: Path, out: Path, names: list[str], variant: str | None, spp_scale: float, max_seconds: float | None,
    scenes: dict = SCENES,
) -> None:
    import mitsuba as mi

    variant = mitsuba_ref.pick_variant(variant)
    per_pass = 256 if variant.startswith("cuda") else 16
    for name in names:
        args, spp, description = scenes[name]
        spp = max(2 * per_pass, int(spp * spp_scale))
        med = mitsuba_ref.render_halves_per_channel(
            scenes_dir / name / "medium" / "scene.xml", spp, per_pass, seed0=0, max_seconds=max_seconds
        )
        spp = med.spp
        # The same seeds for both: what the surface does is sampled alike and cancels in the difference.
        absb = mitsuba_ref.render_halves(scenes_dir / name / "absorber" / "scene.xml", spp, per_pass, seed0=0)
        img, noise, mask = mitsuba_ref.subsurface(med, absb)
        exr = out / f"{name}.exr"
        mitsuba_ref.write_exr(exr, img)
        sidecar = {
            "scene": name,
            "description": description,
            "rouge_options": args,
            "image": exr.name,
            "channels": "RGB: subsurface radiance (medium minus absorber), linear; A: coverage",
            "mitsuba": mi.__version__,
            "variant": variant,
            "device": device_name(variant),
            "spp": med.spp,
            "seconds": round(med.seconds + absb.seconds, 2),
            "noise_rms": noise,
            "covered_pixels": int(mask.sum()),
            "mean_radiance": float(img[..., :3][mask].mean()) if mask.any() else 0.0,
            "scene_hash": {
                "medium": mitsuba_ref.scene_hash(scenes_dir / name / "medium"),
                "absorber": mitsuba_ref.scene_hash(scenes_dir / name / "absorber"),
            },
        }
        (out / f"{name}.json").write_text(json.dumps(sidecar, indent=2) + "\n")
        print(f"{name}: {med.spp} spp, {sidecar['seconds']} s, noise {noise:.2e}, mean {sidecar['mean_radiance']:.4f}",
              flush=True)


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("stage", choices=["export", "render", "all"])
    ap.add_argument("--rouge", default=str(HERE.parent / "target" / "debug" / "rouge"))
    ap.add_argument("--scenes-dir", type=Path, default=HERE.parent / "build" / "reference-scenes")
    ap.add_argument("--set", choices=["committed", "unseen", "dielectric"], default="committed",
                    help="the committed scenes, those the half-space law was not developed on, or those with a "
                    "dielectric boundary under a uniform sky")
    ap.add_argument("--out", type=Path,
                    help="default: data/reference/translucency (-unseen or -dielectric for those sets)")
    ap.add_argument("--only", nargs="*", help="scene names (default: all)")
    ap.add_argument("--variant", help="Mitsuba variant (default: cuda_ad_rgb if a GPU answers, else scalar_rgb)")
    ap.add_argument("--spp-scale", type=float, default=1.0, help="multiply every scene's samples")
    ap.add_argument("--max-seconds", type=float, help="stop a scene's medium render after this long (samples vary)")
    a = ap.parse_args()
    scenes = {"unseen": UNSEEN, "dielectric": DIELECTRIC}.get(a.set, SCENES)
    suffix = {"unseen": "-unseen", "dielectric": "-dielectric"}.get(a.set, "")
    out = a.out or HERE.parent / "data" / "reference" / f"translucency{suffix}"
    names = a.only or list(scenes)
    unknown = [n for n in names if n not in scenes]
    if unknown:
        ap.error(f"unknown scenes {unknown}; known: {', '.join(scenes)}")
    if a.stage in ("export", "all"):
        if not shutil.which(a.rouge) and not Path(a.rouge).is_file():
            ap.error(f"--rouge {a.rouge}: no such binary (cargo build -p rouge-app)")
        do_export(a.rouge, a.scenes_dir, names, scenes)
    if a.stage in ("render", "all"):
        out.mkdir(parents=True, exist_ok=True)
        do_render(a.scenes_dir, out, names, a.variant, a.spp_scale, a.max_seconds, scenes)


if __name__ == "__main__":
    main()
