"""The exact diffuse transmission of a plane slab, tabulated for `render/src/slab_transmittance.rs`.

A slab of reduced optical thickness tau = (sigma_a + sigma_s') d and reduced albedo
a' = sigma_s' / (sigma_a + sigma_s'), isotropic scattering (the similarity relation), both faces
index-matched (eta = 1), lit on one face by collimated light at incidence cosine mu_l. Its
scattered transmitted radiance toward exit cosine mu_v is

    L = E mu_l T(mu_v, mu_l; a', tau) / pi

with E the light's irradiance at normal incidence; T is adding-doubling's transmission matrix
(`iadpython`, S. Prahl: every order of scattering), minus the unscattered beam, which iadpython
keeps on the diagonal (taken as the same run at a' = 0). T is symmetric in its two cosines
(reciprocity), so the table keeps the upper triangle.

Axes: 25 albedos even in t = (1 - a')^(1/4), as the dielectric half-space table; 32 thicknesses
even in u = ln(1 + tau) from 0 to ln(257); 9 cosines even in [0, 1], interpolated from 32
quadrature angles. Stored is G = (T - T1) exp(kappa tau): T1, single scattering, has a closed
form (`single`) that the renderer evaluates exactly, and holds the sharp structure of thin slabs
at grazing cosines that no grid of cosines follows; kappa(a') is the slowest decay of transport in
the slab (Case's discrete eigenvalue: a'/(2 kappa) ln((1 + kappa)/(1 - kappa)) = 1), which turns
an exponential fall over tau into a slowly varying function that interpolates linearly.
"check" holds 240 points off the grid computed independently (24 quadrature angles, whose
nodes are not the table's) to measure the interpolation.

    python python/gen_slab_transmittance.py --out data/reference/slab_transmittance.json
"""

import argparse
import json
import math

import iadpython
import numpy as np

ALBEDO_NODES = 25
TAU_NODES = 32
TAU_MAX = 256.0
MU_NODES = 9
QUAD = 32
QUAD_CHECK = 24


def kappa(albedo: float) -> float:
    """Case's discrete eigenvalue of isotropic scattering: the slowest decay rate per optical depth."""
    if albedo >= 1.0:
        return 0.0
    if albedo <= 0.0:
        return 1.0
    lo, hi = 0.0, 1.0
    for _ in range(200):
        k = 0.5 * (lo + hi)
        if k <= 0.0 or k >= 1.0:
            break
        f = albedo / (2.0 * k) * math.log((1.0 + k) / (1.0 - k)) - 1.0
        # The left side grows from a' at k = 0 to infinity at k = 1.
        if f > 0.0:
            hi = k
        else:
            lo = k
    return 0.5 * (lo + hi)


def scattered(albedo: float, tau: float, quad: int):
    """The scattered transmission matrix T and its cosines, iadpython at `quad` angles."""
    s = iadpython.Sample(a=albedo, b=tau, g=0.0, n=1.0, n_above=1.0, n_below=1.0, quad_pts=quad)
    _, _, t, _ = s.rt_matrices()
    s0 = iadpython.Sample(a=0.0, b=tau, g=0.0, n=1.0, n_above=1.0, n_below=1.0, quad_pts=quad)
    _, _, t0, _ = s0.rt_matrices()
    return np.asarray(t - t0), np.asarray(s.nu)


def single(albedo: float, tau: float, mu_v, mu_l):
    """Single scattering's share of T, in closed form ([Chandrasekhar1960] ch. 1, the transmitted
    intensity of once-scattered light): a'/4 (e^(-tau/mu_l) - e^(-tau/mu_v)) / (mu_l - mu_v), and
    a'/4 tau e^(-tau/mu)/mu^2 where the cosines meet."""
    mu_v, mu_l = np.broadcast_arrays(np.asarray(mu_v, float), np.asarray(mu_l, float))
    out = np.zeros(mu_v.shape)
    with np.errstate(all="ignore"):
        same = np.abs(mu_v - mu_l) < 1e-9
        ev, el = np.exp(-tau / mu_v), np.exp(-tau / mu_l)
        out = np.where(same, tau * ev / mu_v**2, (el - ev) / (mu_l - mu_v))
    return albedo / 4.0 * np.nan_to_num(out)


def on_grid(t: np.ndarray, nu: np.ndarray, mu: np.ndarray) -> np.ndarray:
    """T at the cosines `mu` (both axes), linear between quadrature angles, held at the ends."""
    rows = np.array([np.interp(mu, nu, t[:, j]) for j in range(len(nu))]).T
    return np.array([np.interp(mu, nu, rows[i, :]) for i in range(len(mu))])


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--out", default="data/reference/slab_transmittance.json")
    args = ap.parse_args()
    t_nodes = np.linspace(0.0, 1.0, ALBEDO_NODES)
    albedos = 1.0 - t_nodes**4
    u_nodes = np.linspace(0.0, math.log1p(TAU_MAX), TAU_NODES)
    taus = np.expm1(u_nodes)
    mu = np.linspace(0.0, 1.0, MU_NODES)
    upper = [(i, j) for i in range(MU_NODES) for j in range(i, MU_NODES)]
    kappas = [kappa(a) for a in albedos]
    values = []
    for a, k in zip(albedos, kappas):
        for tau in taus:
            if tau == 0.0 or a == 0.0:
                values.extend([0.0] * len(upper))
                continue
            t, nu = scattered(a, tau, QUAD)
            multiple = t - single(a, tau, nu[:, None], nu[None, :])
            g = on_grid(multiple, nu, mu) * math.exp(k * tau)
            values.extend(float(f"{g[i, j]:.6g}") for i, j in upper)
        print(f"albedo {a:.6f}: kappa {k:.6f}", flush=True)
    rng = np.random.default_rng(31)
    check = []
    while len(check) < 240:
        a = 1.0 - rng.uniform(0.0, 1.0) ** 4
        tau = math.expm1(rng.uniform(0.0, math.log1p(64.0)))
        t, nu = scattered(a, tau, QUAD_CHECK)
        i, j = rng.integers(0, QUAD_CHECK, size=2)
        check.append({"albedo": a, "tau": tau, "mu_v": float(nu[i]), "mu_l": float(nu[j]), "t": float(t[i, j])})
    doc = {
        "schema": "rouge-slab-transmittance",
        "version": 1,
        "source": f"iadpython {iadpython.__version__} (adding-doubling, S. Prahl), {QUAD} quadrature angles, "
        "eta = 1 on both faces, isotropic scattering; python/gen_slab_transmittance.py",
        "albedo_axis": "t = (1 - albedo)^(1/4), even in [0, 1]",
        "tau_axis": f"u = ln(1 + tau), even in [0, ln(1 + {TAU_MAX:g})]",
        "mu_axis": "even in [0, 1], both cosines",
        "albedo_nodes": ALBEDO_NODES,
        "tau_nodes": TAU_NODES,
        "tau_max": TAU_MAX,
        "mu_nodes": MU_NODES,
        "kappa": [float(f"{k:.12g}") for k in kappas],
        "values": "G = (T - T1) exp(kappa tau), T1 single scattering in closed form, per [albedo][tau][(mu_v, mu_l) with mu_v index <= mu_l index, row-major]",
        "g": values,
        "check": check,
    }
    with open(args.out, "w") as f:
        json.dump(doc, f, separators=(",", ":"))
        f.write("\n")
    print(f"wrote {args.out}: {len(values)} values, {len(check)} check points")


if __name__ == "__main__":
    main()
