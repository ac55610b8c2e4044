"""Independent transport reference for a two-layer skin slab: Mitsuba 3 (volumetric path tracing)
against Scott Prahl's adding-doubling (iadpython).

What it computes
----------------
The total reflectance, for collimated light at normal incidence, of an epidermis (absorption
mua_e, scattering mus_e per mm, Henyey-Greenstein g, thickness d_e mm) over a semi-infinite
dermis (mua_d, mus_d, same g), both of refractive index n (index-matched to each other), under
air (n = 1) with a smooth Fresnel top surface. "Total" = specular surface reflection + diffuse
reflectance (directional-hemispherical, what a d/8 spectrophotometer with specular included
measures). Three single-layer rows (no epidermis: thickness_epi_mm = 0 and the "epidermis"
columns repeating the dermis) validate the set-up, with and without the n = 1.4 boundary.

How
---
* Mitsuba 3 (scalar_rgb, `volpath`, max_depth = -1, no Russian roulette). By reciprocity the
  directional-hemispherical reflectance for normal incidence equals the radiance leaving the slab
  straight up (+z) when it is lit by a uniform `constant` environment of radiance 1. An
  orthographic sensor looking along -z (16 x 16 pixels, box filter; every pixel is an equivalent
  position on a laterally uniform slab) measures that radiance, specular reflection included.
  Geometry: a 2000 mm x 2000 mm rectangle at z = 0 with a `dielectric` BSDF (int_ior = n,
  ext_ior = 1; a `null` BSDF when n = 1), interior = the epidermis medium (Mitsuba: the exterior
  is the side the normal points to; rectangles face +z, so the side below is the interior); a
  `null` rectangle at z = -d_e with exterior = epidermis and interior = dermis; the dermis down to
  a black (reflectance 0) floor at depth D below the epidermis, and black side walls. D =
  max(3 mm, 20 / mu_eff) with mu_eff = sqrt(3 mua_d (mua_d + mus_d (1 - g))), so what the floor
  removes is of order exp(-2 mu_eff D) = exp(-40): the dermis is semi-infinite for this purpose,
  while the paths (which, without Russian roulette, only end by leaving the slab) stay short.
  Homogeneous media are gray (the three RGB channels identical); HG phase function.
  Russian roulette is off on purpose: Mitsuba's survival probability is capped at 0.95 per
  event, so with albedo > 0.95 the weights of surviving paths grow like (albedo / 0.95)^depth and
  the variance explodes in these diffusive media.
* Samples are split into independent renders (batches) with distinct seeds passed to
  mi.render(seed=...) (Mitsuba multiplies that seed by the pixel count, so the per-pixel RNG
  seeds never overlap; the sampler's own "seed" property only offsets them by one and must not be
  used for batches). The estimate is the mean of the batch means, the standard error their
  standard deviation / sqrt(batches). A pilot of 8 small batches per case measures the
  per-sample spread and the cost; it is discarded and the main run is sized to reach
  --target-stderr within --budget-s seconds of rendering in total.
* iadpython, two layers listed bottom first (iadpython's stack returns the reflection from the
  last layer's side), the dermis as optical thickness 1e4, 16 quadrature points; UR1 from
  UX1_and_UXU is the total reflectance for normal collimated incidence and includes the
  specular reflection (an opaque black slab gives ((n-1)/(n+1))^2 = 0.0278 for n = 1.4).

Run (from the repository root; 8 minutes measured on 2 shared, busy cores: 489 s for the committed
table; the main runs are sized to at most --budget-s = 900 s of rendering, so under 20 minutes):

    .venv/bin/python python/gen_skin_transport_reference.py

writes data/skin/transport_reference.csv (checked by python/test_skin_transport_reference.py).
"""

from __future__ import annotations

import argparse
import datetime as _dt
import math
import sys
import time
from dataclasses import dataclass
from pathlib import Path

import numpy as np

HERE = Path(__file__).resolve().parent
OUT = HERE.parent / "data" / "skin" / "transport_reference.csv"

G = 0.8
N_SKIN = 1.4
RES = 16          # film is RES x RES pixels
BLOCK = 8         # render blocks (so the two cores both work and the RNG seeds tile exactly)
HALF_WIDTH = 1000.0  # mm, half the slab's lateral size
QUAD_PTS = 16

COLUMNS = ["name", "mua_epi_per_mm", "mus_epi_per_mm", "g", "thickness_epi_mm", "mua_derm_per_mm",
           "mus_derm_per_mm", "n", "r_mitsuba", "r_mitsuba_stderr", "r_iad", "samples"]


@dataclass(frozen=True)
class Case:
    name: str
    mua_e: float
    mus_e: float
    d_e: float        # 0: no epidermis (single semi-infinite layer)
    mua_d: float
    mus_d: float
    n: float = N_SKIN
    g: float = G


def _mus(reduced: float) -> float:
    return reduced / (1.0 - G)


def _two(name, mua_e, mua_d, red, d_e) -> Case:
    return Case(name, mua_e, _mus(red), d_e, mua_d, _mus(red))


def _one(name, mua, red, n) -> Case:
    return Case(name, mua, _mus(red), 0.0, mua, _mus(red), n)


CASES = [
    # single semi-infinite layer (validation of the set-up), with and without the boundary
    _one("single_low_abs_dense_n1.0", 0.02, 4.0, 1.0),
    _one("single_low_abs_dense_n1.4", 0.02, 4.0, N_SKIN),
    _one("single_mid_abs_n1.4", 1.0, 1.5, N_SKIN),
    # two layers: mua_e in {0.05,0.5,3,15}, mua_d in {0.02,0.2,1,5}, mus' in {1.5,4}, d_e in {0.06,0.1}
    _two("light_red", 0.05, 0.02, 1.5, 0.06),
    _two("light_red_dense_thick", 0.05, 0.02, 4.0, 0.10),
    _two("light_yellow", 0.05, 0.2, 4.0, 0.06),
    _two("light_blood_peak", 0.05, 5.0, 1.5, 0.06),
    _two("medium_orange", 0.5, 0.2, 1.5, 0.10),
    _two("medium_green", 0.5, 1.0, 4.0, 0.10),
    _two("dark_red", 3.0, 0.02, 1.5, 0.10),
    _two("dark_green", 3.0, 1.0, 1.5, 0.06),
    _two("light_blue_soret", 3.0, 5.0, 4.0, 0.06),
    _two("very_dark_orange", 15.0, 0.2, 1.5, 0.06),
    _two("very_dark_green", 15.0, 1.0, 4.0, 0.10),
    _two("very_dark_blue", 15.0, 5.0, 4.0, 0.10),
]


# ----------------------------------------------------------------------------- iadpython

def r_iad(case: Case, quad_pts: int = QUAD_PTS) -> float:
    """Total reflectance (specular included) for normal collimated incidence by iadpython."""
    import iadpython as iad

    if case.d_e == 0.0:
        s = iad.Sample(a=case.mus_d / (case.mus_d + case.mua_d), b=1e4, g=case.g, d=1, n=case.n,
                       quad_pts=quad_pts)
    else:
        # bottom layer first: the stack's reflection is for light from the last layer's side
        s = iad.Sample(a=np.array([case.mus_d / (case.mus_d + case.mua_d), case.mus_e / (case.mus_e + case.mua_e)]),
                       b=np.array([1e4, (case.mus_e + case.mua_e) * case.d_e]),
                       g=np.array([case.g, case.g]), d=1, n=case.n, quad_pts=quad_pts)
    R, _, T, _ = s.rt_matrices()
    return float(s.UX1_and_UXU(R, T)[0])


# ----------------------------------------------------------------------------- Mitsuba

def floor_depth(case: Case) -> float:
    mu_eff = math.sqrt(3.0 * case.mua_d * (case.mua_d + case.mus_d * (1.0 - case.g)))
    return max(3.0, 20.0 / mu_eff)


def _medium(mua: float, mus: float, g: float) -> dict:
    st = mua + mus
    return {"type": "homogeneous", "sigma_t": st, "scale": 1.0,
            "albedo": {"type": "rgb", "value": [mus / st] * 3},
            "phase": {"type": "hg", "g": g}}


def scene_dict(case: Case) -> dict:
    import mitsuba as mi

    T = mi.ScalarTransform4f
    h = HALF_WIDTH
    black = {"type": "diffuse", "reflectance": {"type": "rgb", "value": [0.0, 0.0, 0.0]}}
    derm = _medium(case.mua_d, case.mus_d, case.g)
    top_bsdf = ({"type": "null"} if case.n == 1.0
                else {"type": "dielectric", "int_ior": case.n, "ext_ior": 1.0})
    s = {
        "type": "scene",
        "integrator": {"type": "volpath", "max_depth": -1, "rr_depth": 2**30, "block_size": BLOCK},
        "sensor": {
            "type": "orthographic",
            "to_world": T().look_at(origin=[0, 0, 10], target=[0, 0, 0], up=[0, 1, 0]) @ T().scale([0.5, 0.5, 1]),
            "film": {"type": "hdrfilm", "width": RES, "height": RES, "rfilter": {"type": "box"},
                     "pixel_format": "rgb", "component_format": "float32"},
            "sampler": {"type": "independent"},
        },
        "env": {"type": "constant", "radiance": {"type": "rgb", "value": [1.0, 1.0, 1.0]}},
    }
    if case.d_e == 0.0:
        s["top"] = {"type": "rectangle", "to_world": T().scale([h, h, 1]), "bsdf": top_bsdf, "interior": derm}
        z_derm = 0.0
    else:
        epi = _medium(case.mua_e, case.mus_e, case.g)
        s["top"] = {"type": "rectangle", "to_world": T().scale([h, h, 1]), "bsdf": top_bsdf, "interior": epi}
        s["epi_derm"] = {"type": "rectangle", "to_world": T().translate([0, 0, -case.d_e]) @ T().scale([h, h, 1]),
                         "bsdf": {"type": "null"}, "exterior": epi, "interior": derm}
        z_derm = -case.d_e
    zb = z_derm - floor_depth(case)
    zc, hz = 0.5 * zb, -0.5 * zb  # side walls span z in [zb, 0]
    s["floor"] = {"type": "rectangle", "to_world": T().translate([0, 0, zb]) @ T().scale([h, h, 1]), "bsdf": black}
    for i, (axis, sign) in enumerate([("x", 1), ("x", -1), ("y", 1), ("y", -1)]):
        if axis == "x":
            tf = T().translate([sign * h, 0, zc]) @ T().rotate([0, 1, 0], 90) @ T().scale([hz, h, 1])
        else:
            tf = T().translate([0, sign * h, zc]) @ T().rotate([1, 0, 0], 90) @ T().scale([h, hz, 1])
        s[f"wall{i}"] = {"type": "rectangle", "to_world": tf, "bsdf": black}
    return s


def render_pixels(scene, spp: int, seeds: list[int]) -> np.ndarray:
    """One row of RES*RES pixel values (each the mean of spp paths) per seed."""
    import mitsuba as mi

    return np.array([np.array(mi.render(scene, spp=spp, seed=s))[..., 0].astype(np.float64).ravel()
                     for s in seeds])


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--out", type=Path, default=OUT)
    ap.add_argument("--target-stderr", type=float, default=0.001)
    ap.add_argument("--budget-s", type=float, default=900.0, help="rendering time for the main runs, all cases")
    ap.add_argument("--batches", type=int, default=16, help="independent batches per case (main run)")
    ap.add_argument("--only", nargs="*", help="case names to run (default: all)")
    a = ap.parse_args()

    import iadpython
    import mitsuba as mi

    mi.set_variant("scalar_rgb")
    cases = [c for c in CASES if not a.only or c.name in a.only]
    t_start = time.time()

    # pilot: per-sample spread and cost
    pilot_spp, pilot_seeds = 4, [1_000_001 + k for k in range(8)]
    plans = []
    for c in cases:
        scene = mi.load_dict(scene_dict(c))
        t = time.time()
        px = render_pixels(scene, pilot_spp, pilot_seeds)
        dt = time.time() - t
        n_pilot = px.size * pilot_spp
        # per-sample spread from the pixel values; at least that of the specular term alone
        # (probability Rs of a path worth 1), which a small pilot can miss
        rs = ((c.n - 1.0) / (c.n + 1.0)) ** 2
        sigma = max(float(px.std(ddof=1)) * math.sqrt(pilot_spp), math.sqrt(rs * (1.0 - rs)), 0.05)
        v = px.mean(axis=1)
        need = (sigma / a.target_stderr) ** 2
        plans.append([c, scene, sigma, dt / n_pilot, need])
        print(f"pilot {c.name:28s} R~{v.mean():.4f} sigma/sample~{sigma:.3f} "
              f"{n_pilot / dt:8.0f} samples/s  need~{need:9.0f} samples", flush=True)

    total_need_s = sum(p[3] * p[4] for p in plans)
    scale = min(1.0, a.budget_s / total_need_s) if total_need_s > 0 else 1.0
    print(f"main runs need ~{total_need_s:.0f} s; scale {scale:.2f}", flush=True)

    rows = []
    seed = 1
    for c, scene, sigma, cost, need in plans:
        n = max(need * scale, 4 * a.batches * RES * RES)
        spp = max(1, math.ceil(n / (a.batches * RES * RES)))
        seeds = list(range(seed, seed + a.batches))
        seed += a.batches
        t = time.time()
        v = render_pixels(scene, spp, seeds).mean(axis=1)
        r_m, se = float(v.mean()), float(v.std(ddof=1) / math.sqrt(len(v)))
        r_i = r_iad(c)
        samples = spp * RES * RES * a.batches
        rows.append([c.name, c.mua_e, c.mus_e, c.g, c.d_e, c.mua_d, c.mus_d, c.n, r_m, se, r_i, samples])
        print(f"{c.name:28s} mitsuba {r_m:.4f} +- {se:.4f}  iad {r_i:.4f}  diff {r_m - r_i:+.4f} "
              f"({(r_m - r_i) / se:+.1f} se)  {samples} samples  {time.time() - t:.0f} s  D={floor_depth(c):.1f} mm",
              flush=True)

    elapsed = time.time() - t_start
    today = _dt.date.today().isoformat()
    header = [
        "# Two-layer skin slab, total reflectance (specular + diffuse) for normal collimated incidence",
        f"# generator: python/gen_skin_transport_reference.py; mitsuba {mi.__version__} (scalar_rgb volpath), "
        f"iadpython {iadpython.__version__} (quad_pts {QUAD_PTS}); date {today}; run time {elapsed:.0f} s",
        "# per mm; epidermis over semi-infinite dermis, index-matched (n both layers), air above, Fresnel top;",
        "# thickness_epi_mm = 0: single semi-infinite layer (epidermis columns repeat the dermis);",
        "# r_mitsuba_stderr: standard error from independent batches; samples: Mitsuba paths (main run)",
    ]
    def fmt(col: str, x) -> str:
        if col in ("r_mitsuba", "r_mitsuba_stderr"):
            return f"{x:.6f}"
        if col == "r_iad":
            return f"{x:.9f}"
        return str(x) if isinstance(x, (str, int)) else f"{x:.6g}"

    lines = header + [",".join(COLUMNS)] + [",".join(fmt(k, x) for k, x in zip(COLUMNS, r)) for r in rows]
    a.out.parent.mkdir(parents=True, exist_ok=True)
    a.out.write_text("\n".join(lines) + "\n")
    print(f"wrote {a.out} ({elapsed:.0f} s)")
    return 0


if __name__ == "__main__":
    sys.exit(main())
