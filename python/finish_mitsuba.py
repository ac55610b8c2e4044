"""Rouge's finish lobes against Mitsuba 3 (docs/FINISHES.md, "Against Mitsuba 3").

A flat film of each named finish (rouge_measure::finish: Beckmann roughness and index) as
Rouge's Kelemen/Szirmay-Kalos lobe (the `rouge` package's `specular_BRDF_Kelemen`) and as
Mitsuba 3's `roughplastic` with the same Beckmann alpha (its RMS slope) and interior index, no
diffuse part: a full microfacet BRDF with Smith shadowing and the exact dielectric Fresnel
factor, which the Kelemen lobe approximates. Compared:

- the directional albedo of the lobe (the light it reflects) per angle of incidence, by importance
  sampling with Mitsuba's own sampler (the same samples weigh both BRDFs);
- the gloss units at 20, 60 and 85 degrees (ISO 2813 receptor apertures, relative to black glass
  of index 1.567 with the same model's Fresnel), integrated here over the aperture in view
  angles (Rouge's own integral runs over half-vector slopes; this checks it too).

Usage: python python/finish_mitsuba.py [--plot docs/images/finish_lobes_mitsuba.png]
(prints a Markdown table; a few seconds).
"""

from __future__ import annotations

import argparse
import math

import numpy as np

import rouge

FINISHES = {"matte": (0.45, 1.45), "satin": (0.25, 1.45), "dewy": (0.12, 1.48), "gloss": (0.04, 1.50)}
GEOMETRIES = {20: (1.8, 3.6), 60: (4.4, 11.7), 85: (4.0, 6.0)}
STANDARD_IOR = 1.567


def _mi():
    import mitsuba as mi

    mi.set_variant("scalar_rgb")
    return mi


def mitsuba_lobe(roughness: float, ior: float):
    mi = _mi()
    return mi.load_dict({"type": "roughplastic", "distribution": "beckmann", "alpha": roughness,
                         "int_ior": ior, "ext_ior": 1.0, "nonlinear": False,
                         "diffuse_reflectance": {"type": "rgb", "value": [0.0, 0.0, 0.0]}})


def _interaction(wi):
    mi = _mi()
    si = mi.SurfaceInteraction3f()
    si.sh_frame = mi.Frame3f(mi.Vector3f(0.0, 0.0, 1.0))
    si.wi = mi.Vector3f(*wi)
    return si


def mitsuba_brdf(bsdf, wi, wo) -> float:
    """Mitsuba's BRDF (1/sr, without the cosine its `eval` includes)."""
    mi = _mi()
    if wo[2] <= 0.0:
        return 0.0
    value = bsdf.eval(mi.BSDFContext(), _interaction(wi), mi.Vector3f(*wo))
    return float(value[0]) / wo[2]


def directional_albedo(roughness: float, ior: float, theta_deg: float, samples: int = 4000) -> tuple[float, float]:
    """(Rouge, Mitsuba) directional albedo of the lobe for light at `theta_deg`, by importance
    sampling Mitsuba's lobe (stratified in the sample square)."""
    mi = _mi()
    bsdf = mitsuba_lobe(roughness, ior)
    t = math.radians(theta_deg)
    wi = (math.sin(t), 0.0, math.cos(t))
    si = _interaction(wi)
    ctx = mi.BSDFContext()
    side = int(math.sqrt(samples))
    rng = np.random.default_rng(7)
    ours, theirs = 0.0, 0.0
    for i in range(side):
        for j in range(side):
            u = ((i + rng.random()) / side, (j + rng.random()) / side)
            bs, weight = bsdf.sample(ctx, si, float(rng.random()), mi.Point2f(*u))
            if bs.pdf <= 0.0 or bs.wo[2] <= 0.0:
                continue
            wo = (float(bs.wo[0]), float(bs.wo[1]), float(bs.wo[2]))
            theirs += float(weight[0])
            ours += rouge.specular_BRDF_Kelemen(wi, _unit(wo), roughness, ior) * wo[2] / float(bs.pdf)
    n = side * side
    return ours / n, theirs / n


def _unit(v):
    length = math.sqrt(sum(c * c for c in v))
    return tuple(c / length for c in v)


def _schlick(ior: float, cos: float) -> float:
    f0 = ((ior - 1.0) / (ior + 1.0)) ** 2
    return f0 + (1.0 - f0) * (1.0 - cos) ** 5


def _fresnel(ior: float, cos_i: float) -> float:
    """Exact unpolarised Fresnel reflectance from air into index `ior`."""
    sin_t = math.sqrt(max(0.0, 1.0 - cos_i * cos_i)) / ior
    cos_t = math.sqrt(max(0.0, 1.0 - sin_t * sin_t))
    rs = (cos_i - ior * cos_t) / (cos_i + ior * cos_t)
    rp = (ior * cos_i - cos_t) / (ior * cos_i + cos_t)
    return 0.5 * (rs * rs + rp * rp)


def gloss_units(roughness: float, ior: float, angle: int, cells: int = 96) -> tuple[float, float]:
    """(Rouge, Mitsuba) gloss units at `angle`: each BRDF integrated over the receptor aperture in
    view angles (α in the plane of incidence, β across it; dω = cos β dα dβ), relative to the
    standard's mirror reflectance with the model's own Fresnel (Schlick for Rouge, exact for
    Mitsuba)."""
    bsdf = mitsuba_lobe(roughness, ior)
    theta = math.radians(angle)
    a, b = (math.radians(x) for x in GEOMETRIES[angle])
    wi = (-math.sin(theta), 0.0, math.cos(theta))
    da, db = a / cells, b / cells
    ours, theirs = 0.0, 0.0
    for i in range(cells):
        alpha = theta - 0.5 * a + (i + 0.5) * da
        for j in range(cells):
            beta = -0.5 * b + (j + 0.5) * db
            wo = _unit((math.sin(alpha) * math.cos(beta), math.sin(beta), math.cos(alpha) * math.cos(beta)))
            w = wo[2] * math.cos(beta) * da * db
            ours += rouge.specular_BRDF_Kelemen(wi, wo, roughness, ior) * w
            theirs += mitsuba_brdf(bsdf, wi, wo) * w
    return 100.0 * ours / _schlick(STANDARD_IOR, math.cos(theta)), 100.0 * theirs / _fresnel(STANDARD_IOR, math.cos(theta))


def table() -> list[dict]:
    rows = []
    for name, (m, ior) in FINISHES.items():
        row = {"finish": name, "roughness": m, "ior": ior}
        for theta in (0, 30, 60, 75):
            row[f"albedo_{theta}"] = directional_albedo(m, ior, theta)
        for angle in GEOMETRIES:
            row[f"gu_{angle}"] = gloss_units(m, ior, angle) + (rouge.gloss_units_ISO2813(m, ior, angle),)
        rows.append(row)
    return rows


def plot(path: str) -> None:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, axes = plt.subplots(1, 2, figsize=(10, 4))
    for ax, theta in zip(axes, (30, 60)):
        t = math.radians(theta)
        wi = (math.sin(t), 0.0, math.cos(t))
        out = np.linspace(-89, 89, 357)
        for (name, (m, ior)), colour in zip(FINISHES.items(), ("C0", "C1", "C2", "C3")):
            bsdf = mitsuba_lobe(m, ior)
            dirs = [(-math.sin(math.radians(o)), 0.0, math.cos(math.radians(o))) for o in out]
            ours = [rouge.specular_BRDF_Kelemen(wi, d, m, ior) * d[2] for d in dirs]
            theirs = [mitsuba_brdf(bsdf, wi, d) * d[2] for d in dirs]
            ax.semilogy(out, np.maximum(ours, 1e-4), colour, label=f"{name} (m {m}): Rouge")
            ax.semilogy(out, np.maximum(theirs, 1e-4), colour + "--", label=f"{name}: Mitsuba roughplastic")
        ax.set_title(f"light at {theta}°: f_r cos θ_o in the plane of incidence")
        ax.set_xlabel("view angle θ_o (°, mirror direction at +θ_i)")
        ax.set_ylim(1e-3, 30)
        ax.grid(True, which="both", alpha=0.3)
    axes[0].set_ylabel("f_r · cos θ_o (1/sr)")
    axes[1].legend(fontsize=7, loc="lower left")
    fig.tight_layout()
    fig.savefig(path, dpi=110)


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--plot")
    a = ap.parse_args()
    print("| finish | albedo 0° | 30° | 60° | 75° (Rouge / Mitsuba) | GU 20° | 60° | 85° (Rouge here / Rouge's own / Mitsuba) |")
    print("| --- | --- | --- | --- | --- | --- | --- | --- |")
    for r in table():
        alb = " | ".join(f"{r[f'albedo_{t}'][0]:.4f} / {r[f'albedo_{t}'][1]:.4f}" for t in (0, 30, 60, 75))
        gu = " | ".join(f"{r[f'gu_{g}'][0]:.2f} / {r[f'gu_{g}'][2]:.2f} / {r[f'gu_{g}'][1]:.2f}" for g in GEOMETRIES)
        print(f"| {r['finish']} (m {r['roughness']}, n {r['ior']}) | {alb} | {gu} |")
    if a.plot:
        plot(a.plot)


if __name__ == "__main__":
    main()
