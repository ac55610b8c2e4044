"""Single scattering on a convex surface under a light near grazing, against Mitsuba 3 (issue 31;
docs/BENCHMARKS.md "Single scattering at grazing light on a convex surface").

In a flat half-space lit at cosine μ₀ the light reaching depth z has travelled z/μ₀; on a convex
body the surface falls away ahead of the beam, so near the terminator the light scattered once
is brighter than the flat law's α·μ₀/(4π(μ + μ₀)) per unit beam irradiance (Chandrasekhar's first
order, η = 1). This script predicts the ratio from the osculating sphere alone: the integral of
e^{−σt(t(s) + s)} along the view ray (t(s): the distance from the ray's point back toward the light
to the sphere), over the flat e^{−σt·s(1 + μ/μ₀)}. It checks the prediction against Mitsuba 3's own
single scattering (`volpathmis`, `max_depth` 2, `scalar_rgb`) of a reference sphere scene exported
by `rouge export mitsuba` (`mitsuba_ref.scene_view`): per bin of μ₀, the mean predicted ratio
and Mitsuba's single scattering over the flat law, the beam's irradiance calibrated on the pixels lit within 45° of
normal incidence (where both are flat).

    .venv/bin/python python/grazing_single_check.py --scene sphere-skimmilk --spp 128

Needs the release binary (the export) and the `.venv` (mitsuba). Spheres only: the radius is the
builtin sphere's times the scene's `--mesh-scale`.
"""

from __future__ import annotations

import argparse
import json
import sys
from pathlib import Path

import numpy as np

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE))

import mitsuba_ref  # noqa: E402

ROOT = HERE.parent
SPHERE_RADIUS_MM = 25.0  # model/src/mesh/shapes.rs SPHERE_RADIUS_MM
BINS = [(0.7, 1.0), (0.4, 0.7), (0.2, 0.4), (0.1, 0.2), (0.05, 0.1), (0.02, 0.05), (0.005, 0.02)]


def curved_over_flat(radius: float, sigma_t: float, n: np.ndarray, to_light: np.ndarray, to_view: np.ndarray,
                     samples: int = 400) -> float:
    """The osculating sphere's single scattering over the flat half-space's, η = 1 (midpoints in
    u, s = L·u³ along the view ray's chord, cut at 12 mean free paths)."""
    mu0, mu = float(to_light @ n), float(to_view @ n)
    if mu0 <= 0.0 or mu <= 0.0:
        return float("nan")
    reach = min(2.0 * radius * mu, 12.0 / sigma_t)
    u = (np.arange(samples) + 0.5) / samples
    s, ds = reach * u**3, reach * 3.0 * u * u / samples
    y = n[None, :] * radius - to_view[None, :] * s[:, None]
    yl = y @ to_light
    t = -yl + np.sqrt(np.maximum(yl * yl - ((y * y).sum(1) - radius * radius), 0.0))
    return float((np.exp(-sigma_t * (np.maximum(t, 0.0) + s)) * ds).sum() * sigma_t * (1.0 + mu / mu0))


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--scene", default="sphere-skimmilk", help="a sphere's sidecar name in --references")
    ap.add_argument("--references", default=str(ROOT / "data/reference/translucency"))
    ap.add_argument("--spp", type=int, default=128, help="samples per pixel of Mitsuba's single scattering")
    ap.add_argument("--per-bin", type=int, default=60, help="pixels per bin the prediction is evaluated at")
    ap.add_argument("--rouge", default=str(ROOT / "target/release/rouge"))
    a = ap.parse_args()
    side = json.loads((Path(a.references) / f"{a.scene}.json").read_text())
    opts = side["rouge_options"]
    if "builtin:sphere" not in opts or "--eta" not in opts or opts[opts.index("--eta") + 1] != "1":
        sys.exit(f"{a.scene}: a builtin:sphere scene at --eta 1 is needed")
    scale = float(opts[opts.index("--mesh-scale") + 1]) if "--mesh-scale" in opts else 1.0
    radius = SPHERE_RADIUS_MM * scale
    medium = json.loads((ROOT / "data/media" / f"{opts[opts.index('--medium') + 1]}.json").read_text())
    sigma_t = np.array(medium["sigma_a_per_mm"]) + np.array(medium["sigma_s_prime_per_mm"])
    alpha = np.array(medium["sigma_s_prime_per_mm"]) / sigma_t
    view = mitsuba_ref.scene_view(a.rouge, opts, a.spp)
    n, v, to_light, ss = view.n, view.v, view.l, view.single
    covered = np.linalg.norm(n, axis=-1) > 0.5
    mu0, mu = (n * to_light).sum(-1), (n * v).sum(-1)
    with np.errstate(divide="ignore", invalid="ignore"):
        flat = alpha * mu0[..., None] / (4.0 * np.pi * (mu + mu0)[..., None])
    calib = covered & (mu0 > 0.7) & (mu > 0.3)
    beam = np.median(ss[calib] / flat[calib], axis=0)
    print(f"{a.scene}: radius {radius} mm, σt {sigma_t} mm⁻¹, α {alpha.round(4)}, "
          f"Mitsuba {a.spp} spp; beam irradiance (calibrated) {beam.round(3)}")
    print("| μ₀ | pixels | predicted: sphere over flat, R / G / B | Mitsuba's single scattering over flat |")
    print("| --- | ---: | --- | --- |")
    for lo, hi in BINS:
        m = covered & (mu0 >= lo) & (mu0 < hi) & (mu > 0.2)
        at = np.argwhere(m)
        if len(at) < 5:
            continue
        pick = at[np.linspace(0, len(at) - 1, min(a.per_bin, len(at))).astype(int)]
        pred = np.array([[curved_over_flat(radius, s, n[y, x], to_light, v[y, x]) for s in sigma_t] for y, x in pick])
        mits = np.array([ss[y, x] / (beam * flat[y, x]) for y, x in pick])
        f = lambda r: " / ".join(f"{c:.2f}" for c in np.nanmean(r, 0))  # noqa: E731
        print(f"| {lo}-{hi} | {int(m.sum())} | {f(pred)} | {f(mits)} |")


if __name__ == "__main__":
    main()
