"""Where a subsurface model's error sits on one translucency scene, by the reference's luminance
(docs/BENCHMARKS.md "The transmission gather"): per bin of pixels (share of the reference's
99th-percentile luminance), the count, the median cosines μ_o = n·v and μ_i = n·l of the
surface there, the share of the path tracer's light that is single scattering, the model over
the path tracer per channel, and the bin's mean ΔE2000.

    .venv/bin/python python/translucency_pixel_bins.py --scene hand-skin1-back \
        --model "--subsurface screen-space-slab --diffuse half-space"

The cosines and the single scattering come from Mitsuba 3 (`scalar_rgb`, runs here) on the scene
`rouge export mitsuba --without-parts` writes from the sidecar's options
(`mitsuba_ref.scene_view`: the head as its references were rendered, before it had lashes,
brows, teeth and tongue; `--spp` samples of the single scattering). The model renders with
`rouge render` and the sidecar's options, `--no-specular`. Needs the release binary.

`--screen-bounce R,G,B` also estimates the light one part's glow gives another by one bounce
(the fingers facing each other; docs/BENCHMARKS.md "The next try, measured").
"""

from __future__ import annotations

import argparse
import json
import shlex
import subprocess
import sys
import tempfile
from pathlib import Path

import numpy as np

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE))

import mitsuba_ref  # noqa: E402
from reference_noise_floor import delta_e  # noqa: E402

ROOT = HERE.parent
BINS = [(0.5, None), (0.2, 0.5), (0.05, 0.2), (0.01, 0.05), (0.0, 0.01)]


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--scene", required=True, help="sidecar name in --references")
    ap.add_argument("--references", default=str(ROOT / "data/reference/translucency"))
    ap.add_argument("--model", required=True, help="rouge render options of the model")
    ap.add_argument("--spp", type=int, default=64, help="samples per pixel of the single-scattering render")
    ap.add_argument("--rouge", default=str(ROOT / "target/release/rouge"))
    ap.add_argument(
        "--screen-bounce",
        metavar="R,G,B",
        help="also estimate the light one body's glow gives another (the fingers facing each other): the "
        "radiance of the pixels the camera sees (--bounce-from), as Lambertian sources, lighting every "
        "pixel, which sends back that irradiance times the medium's total diffuse reflectance R,G,B over π "
        "(e.g. 0.60,0.35,0.20 for skin1 at η = 1)",
    )
    ap.add_argument(
        "--bounce-from",
        choices=["reference", "model"],
        default="reference",
        help="whose radiance lights the bounce: the path tracer's (what a perfect model would give) or the "
        "model's own (what a pass inside Rouge would have)",
    )
    args = ap.parse_args()
    refs = Path(args.references)
    side = json.loads((refs / f"{args.scene}.json").read_text())
    ref = mitsuba_ref.read_exr(refs / side["image"])
    covered, r = ref[..., 3] > 0.999, ref[..., :3]
    view = mitsuba_ref.scene_view(args.rouge, side["rouge_options"], args.spp)
    with tempfile.TemporaryDirectory() as tmp:
        out = Path(tmp) / "model.exr"
        cmd = [args.rouge, "render", *side["rouge_options"], *shlex.split(args.model), "--no-specular", "--out", str(out)]
        subprocess.run(cmd, check=True, capture_output=True, cwd=ROOT)
        model = mitsuba_ref.read_exr(out)[..., :3]
    n, p, v, to_light, ss = view.n, view.p, view.v, view.l, view.single
    mu_o, mu_i = (n * v).sum(-1), (n * to_light).sum(-1)
    lum = r.mean(-1)
    top = np.percentile(lum[covered], 99)
    print(f"{args.scene}, {args.model}: mean ΔE2000 {delta_e(model[covered], r[covered]):.2f}")
    print("| pixels (share of the brightest) | count | μ_o / μ_i (median) | single scattering / path tracer | model / path tracer | ΔE2000 |")
    print("| --- | ---: | --- | --- | --- | ---: |")
    for lo, hi in BINS:
        m = covered & (lum >= lo * top) & (lum < (hi if hi is not None else np.inf) * top)
        if m.sum() < 5:
            continue
        mean = np.maximum(r[m].mean(0), 1e-12)
        s = ss[m].mean(0) / mean
        k = model[m].mean(0) / mean
        name = f"> {lo}" if hi is None else f"{lo}-{hi}"
        print(
            f"| {name} | {int(m.sum())} | {np.median(mu_o[m]):.2f} / {np.median(mu_i[m]):.2f} "
            f"| {s[0]:.2f} / {s[1]:.2f} / {s[2]:.2f} | {k[0]:.2f} / {k[1]:.2f} / {k[2]:.2f} "
            f"| {delta_e(model[m], r[m]):.1f} |"
        )
    if args.screen_bounce:
        albedo = np.array([float(x) for x in args.screen_bounce.split(",")])
        if albedo.shape != (3,) or not np.all((albedo >= 0) & (albedo <= 1)):
            sys.exit(f"--screen-bounce {args.screen_bounce}: three reflectances in [0, 1], R,G,B")
        source = r if args.bounce_from == "reference" else model
        screen_bounce(covered, r, model, n, p, mu_i, albedo, source)


def screen_bounce(covered, r, model, n, p, mu_i, albedo, source) -> None:
    """Prints [`bounce_estimate`]'s effect on the model's score and where it is largest."""
    bounce = bounce_estimate(covered, source, n, p, albedo)
    with_bounce = model + bounce
    receivers = covered & (mu_i < 0)
    print()
    print(f"visible glow's one bounce: mean ΔE2000 {delta_e(model[covered], r[covered]):.2f} → "
          f"{delta_e(with_bounce[covered], r[covered]):.2f} with it added to the model")
    print("| pixels | count | path tracer | model | the bounce |")
    print("| --- | ---: | --- | --- | --- |")
    rims = receivers & (mu_i < -0.6) & (r[..., 0] > 1e-3) & (bounce[..., 0] > 0.2 * r[..., 0])
    rows = [
        ("all", covered),
        ("facing away from the light (μ_i < 0)", receivers),
        ("μ_i < −0.6, lit by the path tracer, where the bounce is over 20% of it", rims),
    ]
    for name, m in rows:
        if m.sum() < 5:
            continue
        f = lambda a: " / ".join(f"{c:.4f}" for c in a[m].mean(0))  # noqa: E731
        print(f"| {name} | {int(m.sum())} | {f(r)} | {f(model)} | {f(bounce)} |")


def bounce_estimate(covered, r, n, p, albedo):
    """What the camera's visible glow lights by one bounce (see --screen-bounce), per pixel:
    sources are the covered pixels whose four neighbours are covered, radiance `r`, of area
    |∂p/∂x × ∂p/∂y| (`p` the positions, mm); receivers every covered pixel, irradiance
    E = Σ L_j cos θ_i cos θ_j dA_j / r² over the sources more than 1 mm away that face it, no
    occlusion; the bounce is E · albedo / π. A lower bound on what the path tracer has (faces
    the camera does not see glow too)."""
    dx, dy = np.zeros_like(p), np.zeros_like(p)
    dx[:, 1:-1], dy[1:-1] = (p[:, 2:] - p[:, :-2]) / 2, (p[2:] - p[:-2]) / 2
    area = np.linalg.norm(np.cross(dx, dy), axis=-1)
    inner = covered.copy()
    inner[:, 1:-1] &= covered[:, 2:] & covered[:, :-2]
    inner[1:-1] &= covered[2:] & covered[:-2]
    inner[[0, -1]] = False
    inner[:, [0, -1]] = False
    lum = r.mean(-1)
    sources = inner & (lum > 0.02 * np.percentile(lum[covered], 99))
    src_p, src_n, src_l, src_a = p[sources], n[sources], r[sources], area[sources]
    at = np.argwhere(covered)
    irradiance = np.zeros((len(at), 3))
    chunk = max(1, 4_000_000 // max(len(src_p), 1))
    for k in range(0, len(at), chunk):
        y, x = at[k : k + chunk, 0], at[k : k + chunk, 1]
        d = src_p[None] - p[y, x][:, None]
        dist = np.maximum(np.linalg.norm(d, axis=-1), 1e-9)
        w = d / dist[..., None]
        cos_i, cos_j = (n[y, x][:, None] * w).sum(-1), -(src_n[None] * w).sum(-1)
        g = np.where((cos_i > 0) & (cos_j > 0) & (dist > 1.0), cos_i * cos_j / dist**2, 0.0) * src_a[None]
        irradiance[k : k + chunk] = g @ src_l
    bounce = np.zeros_like(r)
    bounce[covered] = irradiance * albedo / np.pi
    return bounce


if __name__ == "__main__":
    main()
