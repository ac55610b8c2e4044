"""The angular shape of a half-space's subsurface reflection under a smooth dielectric boundary,
by adding-doubling ([Prahl1993], iadpython), the table behind render/src/dielectric_brdf.rs.

The medium and boundary are those of python/gen_dielectric_half_space.py: isotropic scattering
of reduced albedo a' (g = 0 by the similarity relation), semi-infinite (optical thickness 1e6),
below a flat interface of relative index eta, air above. For each (eta, a') adding-doubling's
reflection matrix S (the run at a' minus the run at a' = 0, which is the boundary's specular
reflection alone) is over the quadrature's internal cosines nu; light leaves only where nu is
above the critical cosine, towards the external cosine mu = sqrt(1 - eta^2 (1 - nu^2)). Since
eta^2 nu dnu = mu dmu, the external reflection function is

    pi f(mu, mu0) = S(nu, nu0) / eta^2        (radiance leaving towards mu per unit irradiance
                                                from mu0, times pi; symmetric by reciprocity)
    R(mu0) = sum_i S(nu_i, nu0) 2 nu_i w_i     (directional-hemispherical reflectance)

(iadpython's own UR1 and URU are these sums: URU = eta^2 sum_j R(mu_j) 2 nu_j w_j, which the
script checks.) Stored, per (eta, a'), normalised by the normal-incidence reflectance
r_normal = R(1) (what Rouge takes as the albedo, render/src/dielectric_half_space.rs), and by
the boundary's Fresnel transmittance T(mu) = 1 - F(mu, eta) of each cosine:

    shape(mu, mu0) = pi f(mu, mu0) (mu + mu0) / (r_normal T(mu) T(mu0))
    exit(mu)       = R(mu) / (r_normal T(mu))

(finite at grazing: at eta = 1, T = 1 and the shape is a' H(mu) H(mu0) / (4 r_normal)). What is
left is the radiance inside, just below the boundary, which varies slowly with the cosine: linear
interpolation of it between quadrature cosines agrees with a 24-point and a 40-point quadrature
within 0.1% at mu = 0.09, where interpolating pi f itself is 4% off (T falls steeply towards
grazing). It is resampled on 17 cosines even in [0, 1], held constant below the smallest external
cosine (0.068 at eta 1.4). Axes: 13 eta from 1 to 3 even in sqrt(eta - 1) and 17 albedos even in
t = (1 - a')^(1/4), as the half-space table (the node a' = 0 is taken at a' = 1e-4: the shape of
single scattering, which r_normal divides out). "check" holds points off every grid (other eta,
pseudo-random a', the cosines of a 24-point quadrature) as absolute pi f, R and r_normal.

    python python/gen_dielectric_brdf.py --out data/reference/dielectric_brdf.json
"""

from __future__ import annotations

import argparse
import json
import random
from pathlib import Path

import iadpython
import numpy as np

HERE = Path(__file__).resolve().parent
ETA_STEPS = 12
ETAS = [round(1.0 + 2.0 * (j / ETA_STEPS) ** 2, 12) for j in range(ETA_STEPS + 1)]
ALBEDO_STEPS = 16
MU_NODES = 17
QUAD = 32
QUAD_CHECK = 24
OPTICAL_THICKNESS = 1e6
SMALLEST_ALBEDO = 1e-4
CHECK_ETAS = [1.05, 1.2, 1.33, 1.37, 1.44, 1.55, 1.8, 2.4]


def matrices(albedo: float, eta: float, quad: int):
    """(S, internal cosines nu, weights 2 nu w, UR1 and URU less the specular) of adding-doubling."""

    def run(a: float):
        s = iadpython.Sample(a=a, b=OPTICAL_THICKNESS, g=0.0, n=eta, n_above=1.0, n_below=1.0, quad_pts=quad)
        r = np.asarray(s.rt_matrices()[0], dtype=float)
        ur1, _, uru, _ = s.rt()
        return r, np.asarray(s.nu, dtype=float), np.asarray(s.twonuw, dtype=float), ur1, uru

    r, nu, tw, ur1, uru = run(albedo)
    r0, _, _, spec1, specu = run(0.0)
    return r - r0, nu, tw, ur1 - spec1, uru - specu


def external(albedo: float, eta: float, quad: int):
    """(external cosines mu, pi f on them, R on them, r_normal), mu ascending; the sums checked
    against iadpython's UR1 and URU."""
    s, nu, tw, ur1, uru = matrices(albedo, eta, quad)
    leaves = nu > np.sqrt(max(0.0, 1.0 - 1.0 / eta**2)) + 1e-12 if eta > 1.0 else nu > 0.0
    r_dh = (s * tw[:, None]).sum(axis=0)
    r_normal = float(r_dh[-1])
    if abs(r_normal - ur1) > 1e-9 * max(1.0, ur1) or abs(eta**2 * (r_dh * tw).sum() - uru) > 1e-9 * max(1.0, uru):
        raise SystemExit(f"eta {eta}, a' {albedo}: the matrix sums are not iadpython's UR1 and URU")
    mu = np.sqrt(np.clip(1.0 - eta**2 * (1.0 - nu[leaves] ** 2), 0.0, 1.0))
    pi_f = s[np.ix_(leaves, leaves)] / eta**2
    return mu, pi_f, r_dh[leaves], r_normal


def fresnel_t(mu: np.ndarray, eta: float) -> np.ndarray:
    """Unpolarised Fresnel transmittance from air into relative index eta at external cosine mu
    ([Born and Wolf] 1.5; Rust: rouge_render::diffusion::fresnel_dielectric)."""
    mu = np.asarray(mu, dtype=float)
    cos_t = np.sqrt(np.clip(1.0 - (1.0 - mu**2) / eta**2, 0.0, 1.0))
    rs = (mu - eta * cos_t) / (mu + eta * cos_t)
    rp = (eta * mu - cos_t) / (eta * mu + cos_t)
    return 1.0 - 0.5 * (rs**2 + rp**2)


def resample(mu: np.ndarray, values: np.ndarray, grid: np.ndarray) -> np.ndarray:
    """`values` at cosines `mu` (ascending) linearly onto `grid`, held at the ends."""
    return np.interp(grid, mu, values)


def shapes(albedo: float, eta: float):
    """The stored (shape upper triangle, exit) of one node."""
    mu, pi_f, r_dh, r_normal = external(albedo, eta, QUAD)
    grid = np.linspace(0.0, 1.0, MU_NODES)
    t = fresnel_t(mu, eta)
    g = pi_f * (mu[:, None] + mu[None, :]) / np.outer(t, t)
    rows = np.array([resample(mu, g[:, j], grid) for j in range(len(mu))]).T
    full = np.array([resample(mu, rows[i, :], grid) for i in range(MU_NODES)])
    full = 0.5 * (full + full.T) / r_normal
    exit_ = resample(mu, r_dh / t, grid) / r_normal
    upper = [float(f"{full[i, j]:.6g}") for i in range(MU_NODES) for j in range(i, MU_NODES)]
    return upper, [float(f"{e:.6g}") for e in exit_]


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--out", type=Path, default=HERE.parent / "data" / "reference" / "dielectric_brdf.json")
    args = ap.parse_args()
    shape, exits = [], []
    for eta in ETAS:
        for k in range(ALBEDO_STEPS + 1):
            albedo = max(1.0 - (k / ALBEDO_STEPS) ** 4, SMALLEST_ALBEDO)
            s, e = shapes(albedo, eta)
            shape.extend(s)
            exits.extend(e)
        print(f"eta {eta:.4f}", flush=True)
    rng = random.Random(31)
    check = []
    for eta in CHECK_ETAS:
        for _ in range(6):
            albedo = 1.0 - rng.random() ** 2
            mu, pi_f, r_dh, r_normal = external(albedo, eta, QUAD_CHECK)
            for _ in range(4):
                i, j = rng.randrange(len(mu)), rng.randrange(len(mu))
                check.append(
                    {
                        "eta": eta,
                        "albedo": round(albedo, 12),
                        "mu": round(float(mu[i]), 12),
                        "mu0": round(float(mu[j]), 12),
                        "pi_f": float(f"{pi_f[i, j]:.10g}"),
                        "r": float(f"{r_dh[j]:.10g}"),
                        "r_normal": float(f"{r_normal:.10g}"),
                    }
                )
    doc = {
        "description": __doc__.split("\n\n")[0].replace("\n", " "),
        "source": f"iadpython {iadpython.__version__} (adding-doubling, S. Prahl), quad_pts {QUAD} "
        f"(check {QUAD_CHECK}), optical thickness {OPTICAL_THICKNESS:g}, g = 0, air above",
        "script": "python/gen_dielectric_brdf.py",
        "etas": ETAS,
        "albedo_steps": ALBEDO_STEPS,
        "smallest_albedo": SMALLEST_ALBEDO,
        "mu_nodes": MU_NODES,
        "shape": "per [eta][albedo node] the upper triangle (i <= j, row-major) of "
        "pi f(mu_i, mu_j) (mu_i + mu_j) / (r_normal T(mu_i) T(mu_j)), T the Fresnel transmittance",
        "exit": "per [eta][albedo node] R(mu_i) / (r_normal T(mu_i))",
    }
    text = json.dumps(doc, indent=1)[:-2]
    text += f',\n "shape_values": {json.dumps(shape)},\n "exit_values": {json.dumps(exits)},\n "check": [\n  '
    text += ",\n  ".join(json.dumps(c) for c in check) + "\n ]\n}\n"
    args.out.write_text(text)
    print(f"wrote {args.out}: {len(shape)} shape and {len(exits)} exit values, {len(check)} check points")


if __name__ == "__main__":
    main()
