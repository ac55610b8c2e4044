#!/usr/bin/env python3
"""Writes data/skin/transport_ad.csv: the reflectance of a two-layer skin slab by adding-doubling
(Prahl's iadpython, [Prahl1993] in docs/REFERENCES.md), tabulated for the spectral skin model of
rouge-measure (measure/src/skin/transport.rs).

The slab: an epidermis of thickness d over a semi-infinite dermis, both Henyey-Greenstein
scatterers with g = 0.8 and refractive index n = 1.4 (index-matched between them), air above, a
smooth surface, collimated normal incidence. What is tabulated is the diffuse part of the total
reflectance (iadpython's UR1, everything that leaves the top surface, minus the specular
reflection ((n - 1)/(n + 1))^2 of the surface, which is added back in Rust). For fixed g and n that
reflectance depends on three numbers only, so each wavelength of the model is one lookup:

* ``sqrt_tau_a_epi`` = sqrt(μa,epi · d), the square root of the epidermis' absorption optical
  thickness (0-8; on the square-root axis ln R is smooth: its fall is steepest at the first
  absorption, which takes the long diffuse paths through the epidermis);
* ``tau_sr_epi`` = μs'epi · d = μs,epi (1 - g) d, its reduced scattering optical thickness (0-3);
* ``y_derm``     = sqrt(1 - a'), a' = μs'derm / (μs'derm + μa,derm), the dermis' reduced albedo
  on a square-root axis (0-1), on which the semi-infinite reflectance is smooth (R ≈ 1 - c·y
  near y = 0). At y = 0 exactly (no absorption in the dermis, never the case in skin) the
  doubling stops on its convergence test with 0.14% still leaking through the bottom.

iadpython lists multi-layer samples bottom first (its stacking returns the reflection for light
arriving from the last layer's side), so the layers are [dermis, epidermis]; the dermis is
1e4 optical thicknesses deep. 16 quadrature angles (24 changes R by < 2e-4).

    .venv/bin/python python/gen_skin_transport.py          # about 8 minutes on 2 cores
    .venv/bin/python python/gen_skin_transport.py --check  # 300 random off-grid points (1 minute)

``--check`` writes data/skin/transport_ad_check.csv: adding-doubling at random points between the
nodes (a seeded generator), the reference measure/tests/skin_transport.rs holds the interpolated
table to.
"""

from __future__ import annotations

import multiprocessing as mp
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parent.parent
OUT = ROOT / "data" / "skin" / "transport_ad.csv"
CHECK = ROOT / "data" / "skin" / "transport_ad_check.csv"

G = 0.8
N = 1.4
QUAD = 16
# Nodes even in sqrt(tau_a): ln R falls steeply at the first absorption in the epidermis (the
# long diffuse paths through it go first) and slowly after, nearly linearly in sqrt(tau_a).
SQRT_TAU_A = np.linspace(0.0, np.sqrt(8.0), 33)
TAU_A = SQRT_TAU_A**2
TAU_SR = np.array([0.0, 0.1, 0.2, 0.35, 0.5, 0.75, 1.0, 1.5, 2.0, 3.0])
Y = np.linspace(0.0, 1.0, 41)


def specular() -> float:
    return ((N - 1.0) / (N + 1.0)) ** 2


def diffuse_reflectance(tau_a: float, tau_sr: float, y: float) -> float:
    """UR1 minus the surface's specular reflection, for one point of the table."""
    import iadpython as iad

    a_reduced = 1.0 - y * y
    # The dermis: reduced albedo a' -> albedo a for scattering mu_s = mu_s'/(1 - g):
    # a = mu_s/(mu_s + mu_a) with mu_s' = a' / (1 - a') * mu_a  =>  a = a'/(a' + (1 - a')(1 - g)).
    a_derm = a_reduced / (a_reduced + (1.0 - a_reduced) * (1.0 - G)) if a_reduced > 0 else 0.0
    tau_s = tau_sr / (1.0 - G)
    tau_e = tau_s + tau_a
    a_epi = tau_s / tau_e if tau_e > 0 else 0.0
    # iadpython cannot take a zero-thickness layer in a stack: a vanishing one stands in for it.
    b_epi = max(tau_e, 1e-9)
    s = iad.Sample(
        a=np.array([a_derm, a_epi]),
        b=np.array([1e4, b_epi]),
        g=np.array([G, G]),
        d=1,
        n=N,
        quad_pts=QUAD,
    )
    r, _, t, _ = s.rt_matrices()
    ur1 = float(s.UX1_and_UXU(r, t)[0])
    return max(ur1 - specular(), 0.0)


def _row(args: tuple[int, int]) -> list[float]:
    i, j = args
    return [diffuse_reflectance(TAU_A[i], TAU_SR[j], y) for y in Y]


def _check_point(args: tuple[float, float, float]) -> float:
    return diffuse_reflectance(*args) + specular()


def check(count: int = 300) -> None:
    """Random points inside the table (realistic skin: tau_a below 3, a' above 0.3) by
    adding-doubling, total reflectance (specular included)."""
    import iadpython

    rng = np.random.default_rng(20261124)
    # Even in sqrt(tau_a) (0-3) and in y = sqrt(1 - a') (0.02-0.84, a' 0.3-0.9996): as dense where
    # skin's red lies (small absorption everywhere) as elsewhere.
    pts = [
        (float(rng.uniform(0, np.sqrt(3.0)) ** 2), float(rng.uniform(0, 3.0)), float(1.0 - rng.uniform(0.02, 0.84) ** 2))
        for _ in range(count)
    ]
    with mp.Pool(2) as pool:
        # The table's third axis is y = sqrt(1 - a'); diffuse_reflectance takes y.
        values = pool.map(_check_point, [(a, s, float(np.sqrt(1 - ap))) for a, s, ap in pts])
    lines = [
        f"# Generated by python/gen_skin_transport.py --check with iadpython {iadpython.__version__}. Do not edit; regenerate instead.",
        f"# Adding-doubling total reflectance (UR1) of the two-layer slab at random points between the table's nodes; g = {G}, n = {N}.",
        "tau_a_epi,tau_sr_epi,reduced_albedo_derm,reflectance",
    ]
    lines += [f"{a!r},{s!r},{ap!r},{v!r}" for (a, s, ap), v in zip(pts, values)]
    CHECK.write_text("\n".join(lines) + "\n")
    print(f"wrote {CHECK.relative_to(ROOT)}: {count} points")


def main() -> None:
    import sys

    import iadpython

    if "--check" in sys.argv:
        check()
        return

    jobs = [(i, j) for i in range(len(TAU_A)) for j in range(len(TAU_SR))]
    with mp.Pool(2) as pool:
        rows = pool.map(_row, jobs)
    lines = [
        f"# Generated by python/gen_skin_transport.py with iadpython {iadpython.__version__}. Do not edit; regenerate instead.",
        "# Two-layer skin slab by adding-doubling ([Prahl1993]): diffuse reflectance (UR1 minus the surface's",
        f"# specular ((n-1)/(n+1))^2) for collimated normal incidence; g = {G}, n = {N}, {QUAD} quadrature angles.",
        "# Axes: sqrt_tau_a_epi = sqrt(mu_a,epi*d); tau_sr_epi = mu_s',epi*d; y_derm = sqrt(1 - a'), a' the dermis' reduced albedo.",
        f"# g={G},n={N}",
        "# sqrt_tau_a_epi=" + ";".join(repr(float(v)) for v in SQRT_TAU_A),
        "# tau_sr_epi=" + ";".join(f"{v:g}" for v in TAU_SR),
        "# y_derm=" + ";".join(f"{v:g}" for v in Y),
        "sqrt_tau_a_epi,tau_sr_epi," + ",".join(f"y{k}" for k in range(len(Y))),
    ]
    for (i, j), row in zip(jobs, rows):
        lines.append(f"{SQRT_TAU_A[i]:.6f},{TAU_SR[j]:g}," + ",".join(f"{v:.7e}" for v in row))
    OUT.parent.mkdir(parents=True, exist_ok=True)
    OUT.write_text("\n".join(lines) + "\n")
    print(f"wrote {OUT.relative_to(ROOT)}: {len(jobs)} rows x {len(Y)} columns")


if __name__ == "__main__":
    main()
