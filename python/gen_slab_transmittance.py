"""The exact diffuse transmission of a plane slab, tabulated for `render/src/slab_transmittance.rs`.

A slab of reduced optical thickness tau = (sigma_a + sigma_s') d and reduced albedo
a' = sigma_s' / (sigma_a + sigma_s'), isotropic scattering (the similarity relation), under a
smooth boundary of relative index eta on both faces (air outside; eta = 1 is index-matched, as
the references of docs/TRANSLUCENCY.md), lit on one face by collimated light at external
incidence cosine mu_l. Its scattered transmitted radiance toward external exit cosine mu_v is

    L = E mu_l T(mu_v, mu_l; a', tau, eta) / pi

with E the light's irradiance at normal incidence; T is adding-doubling's transmission matrix
(`iadpython`, S. Prahl: every order of scattering and every internal reflection at the two
faces) taken to external cosines (`scattered`), minus the unscattered beam, which iadpython keeps
on the diagonal (taken as the same run at a' = 0). T is symmetric in its two cosines
(reciprocity), so the table keeps the upper triangle.

Axes: 7 eta even in sqrt(eta - 1) from 1 to 1.6 (Catmull-Rom between them, as the dielectric
tables); 25 albedos even in t = (1 - a')^(1/4), as the dielectric half-space table; 32
thicknesses even in u = ln(1 + tau) from 0 to ln(257); 9 external cosines even in [0, 1],
interpolated from 32 quadrature angles. Stored is G = (T - T1) exp(kappa tau) / (T_F(mu_v)
T_F(mu_l)): T1, single scattering under the boundary (`single_eta`), has a closed form that the
renderer evaluates exactly, and holds the sharp structure of thin slabs at grazing cosines that no
grid of cosines follows; kappa(a') is the slowest decay of transport in the slab (Case's discrete
eigenvalue: a'/(2 kappa) ln((1 + kappa)/(1 - kappa)) = 1), which turns an exponential fall over
tau into a slowly varying function that interpolates linearly; T_F, the faces' Fresnel
transmittances, fall steeply toward grazing, and divided out leave the radiance just inside,
which varies slowly. "check" holds 60 points per eta off the grid (7 eta, 6 of them between
nodes) computed independently (24 quadrature angles, whose nodes are not the table's) to
measure the interpolation.

    python python/gen_slab_transmittance.py --out data/reference/slab_transmittance.json   # 50 s
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
ETA_STEPS = 6
ETA_MAX = 1.6
ETAS = [round(1.0 + (ETA_MAX - 1.0) * (j / ETA_STEPS) ** 2, 12) for j in range(ETA_STEPS + 1)]
# Off the grid: between the nodes, skin's 1.33-1.44 among them; eta 1 keeps the index-matched law's check.
CHECK_ETAS = [1.0, 1.05, 1.2, 1.33, 1.37, 1.44, 1.55]
CHECK_PER_ETA = 60


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


def fresnel_t(mu, eta: float):
    """Unpolarised Fresnel transmittance between air and relative index eta at external cosine mu
    ([Born and Wolf] 1.5; Rust: rouge_render::diffusion::fresnel_dielectric; the same from
    inside at the refracted cosine)."""
    mu = np.asarray(mu, dtype=float)
    if eta == 1.0:
        return np.ones_like(mu)
    cos_t = np.sqrt(np.clip(1.0 - (1.0 - mu**2) / eta**2, 0.0, 1.0))
    with np.errstate(all="ignore"):
        rs = (mu - eta * cos_t) / (mu + eta * cos_t)
        rp = (eta * mu - cos_t) / (eta * mu + cos_t)
    return np.nan_to_num(1.0 - 0.5 * (rs**2 + rp**2))


def inside(mu, eta: float):
    """The internal cosine of light refracted at external cosine mu (Snell's law)."""
    return np.sqrt(1.0 - (1.0 - np.asarray(mu, dtype=float) ** 2) / eta**2)


def scattered(albedo: float, tau: float, eta: float, quad: int):
    """pi f_t, the scattered transmission over external cosines mu (ascending), and mu.

    iadpython's matrix T is over internal cosines nu; light leaves only above the critical
    cosine, toward mu = sqrt(1 - eta^2 (1 - nu^2)); since eta^2 nu dnu = mu dmu, the external
    function is T / eta^2 (the column sums against iadpython's own UT1 and UTU are checked, as
    python/gen_dielectric_brdf.py does for reflection). The run at a' = 0 is the unscattered
    beam, a delta on the diagonal, taken out."""

    def run(a: float):
        s = iadpython.Sample(a=a, b=tau, g=0.0, n=eta, n_above=1.0, n_below=1.0, quad_pts=quad)
        _, _, t, _ = s.rt_matrices()
        _, ut1, _, utu = s.rt()
        return np.asarray(t, dtype=float), np.asarray(s.nu, dtype=float), np.asarray(s.twonuw, dtype=float), ut1, utu

    t, nu, tw, ut1, utu = run(albedo)
    t0, _, _, ut10, utu0 = run(0.0)
    t = t - t0
    t_dh = (t * tw[:, None]).sum(axis=0)
    if abs(t_dh[-1] - (ut1 - ut10)) > 1e-9 * max(1.0, ut1) or abs(eta**2 * (t_dh * tw).sum() - (utu - utu0)) > 1e-9 * max(1.0, utu):
        raise SystemExit(f"eta {eta}, a' {albedo}, tau {tau}: the matrix sums are not iadpython's UT1 and UTU")
    leaves = nu > np.sqrt(1.0 - 1.0 / eta**2) + 1e-12 if eta > 1.0 else nu > 0.0
    mu = np.sqrt(np.clip(1.0 - eta**2 * (1.0 - nu[leaves] ** 2), 0.0, 1.0))
    return t[np.ix_(leaves, leaves)] / eta**2, mu


def single(albedo: float, tau: float, mu_v, mu_l):
    """Single scattering's share of T inside the slab, over its internal cosines, in closed form
    ([Chandrasekhar1960] ch. 1, the transmitted intensity of once-scattered light):
    a'/4 (e^(-tau/mu_l) - e^(-tau/mu_v)) / (mu_l - mu_v), and a'/4 tau e^(-tau/mu)/mu^2 where the
    cosines meet."""
    mu_v, mu_l = np.broadcast_arrays(np.asarray(mu_v, float), np.asarray(mu_l, float))
    out = np.zeros(mu_v.shape)
    with np.errstate(all="ignore"):
        same = np.abs(mu_v - mu_l) < 1e-9
        ev, el = np.exp(-tau / mu_v), np.exp(-tau / mu_l)
        out = np.where(same, tau * ev / mu_v**2, (el - ev) / (mu_l - mu_v))
    return albedo / 4.0 * np.nan_to_num(out)


def single_eta(albedo: float, tau: float, eta: float, mu_v, mu_l):
    """Single scattering under the boundary, over external cosines: the light enters (Fresnel
    T_F(mu_l)), scatters once at the refracted cosines nu, and leaves (T_F(mu_v), and 1/eta^2 for
    the radiance's change of solid angle); with it the two paths that meet one internal
    reflection: the beam reflected by the exit face (F(mu_l)) and scattered back toward it, and
    the light scattered toward the entry face and reflected there (F(mu_v)), each
    a'/4 (1 - e^(-tau (1/nu_v + 1/nu_l))) / (nu_v + nu_l) times the attenuation of the extra
    crossing, e^(-tau/nu_l) or e^(-tau/nu_v). Every other path is left to the table."""
    nv, nl = inside(mu_v, eta), inside(mu_l, eta)
    tv, tl = fresnel_t(mu_v, eta), fresnel_t(mu_l, eta)
    once = single(albedo, tau, nv, nl)
    if eta > 1.0:
        with np.errstate(all="ignore"):
            s = 1.0 / nv + 1.0 / nl
            back = albedo / 4.0 * np.nan_to_num(-np.expm1(-tau * s) / (nv + nl))
        once = once + back * ((1.0 - tl) * np.exp(-tau / nl) + (1.0 - tv) * np.exp(-tau / nv))
    return tv * tl * once / eta**2


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
    for eta in ETAS:
        for a, k in zip(albedos, kappas):
            for tau in taus:
                if tau == 0.0 or a == 0.0:
                    values.extend([0.0] * len(upper))
                    continue
                t, mu_q = scattered(a, tau, eta, QUAD)
                multiple = t - single_eta(a, tau, eta, mu_q[:, None], mu_q[None, :])
                # The boundary's transmittances divided out on the quadrature's cosines (where
                # they vary steeply toward grazing), before resampling.
                t_q = fresnel_t(mu_q, eta)
                g = on_grid(multiple / np.outer(t_q, t_q), mu_q, mu) * math.exp(k * tau)
                values.extend(float(f"{g[i, j]:.6g}") for i, j in upper)
        print(f"eta {eta:.6f}", flush=True)
    rng = np.random.default_rng(31)
    check = []
    for eta in CHECK_ETAS:
        for _ in range(CHECK_PER_ETA):
            a = 1.0 - rng.uniform(0.0, 1.0) ** 4
            tau = math.expm1(rng.uniform(0.0, math.log1p(64.0)))
            t, mu_q = scattered(a, tau, eta, QUAD_CHECK)
            i, j = rng.integers(0, len(mu_q), size=2)
            check.append(
                {"eta": eta, "albedo": a, "tau": tau, "mu_v": float(mu_q[i]), "mu_l": float(mu_q[j]), "t": float(t[i, j])}
            )
    doc = {
        "schema": "rouge-slab-transmittance",
        "version": 2,
        "source": f"iadpython {iadpython.__version__} (adding-doubling, S. Prahl), {QUAD} quadrature angles, "
        "a smooth boundary of relative index eta on both faces (air outside), isotropic scattering; "
        "python/gen_slab_transmittance.py",
        "eta_axis": f"s = sqrt(eta - 1), even in [0, sqrt({ETA_MAX:g} - 1)]",
        "albedo_axis": "t = (1 - albedo)^(1/4), even in [0, 1]",
        "tau_axis": f"u = ln(1 + tau), even in [0, ln(1 + {TAU_MAX:g})]",
        "mu_axis": "external cosines, even in [0, 1], both cosines",
        "etas": ETAS,
        "albedo_nodes": ALBEDO_NODES,
        "tau_nodes": TAU_NODES,
        "tau_max": TAU_MAX,
        "mu_nodes": MU_NODES,
        "kappa": [float(f"{k:.12g}") for k in kappas],
        "values": "G = (T - T1) exp(kappa tau) / (T_F(mu_v) T_F(mu_l)), T1 single scattering under the boundary in "
        "closed form, T_F the Fresnel transmittance, per [eta][albedo][tau][(mu_v, mu_l) with mu_v index <= mu_l "
        "index, row-major]",
        "g": values,
        "check": check,
    }
    with open(args.out, "w") as f:
        json.dump(doc, f, separators=(",", ":"))
        f.write("\n")
    print(f"wrote {args.out}: {len(values)} values, {len(check)} check points")


if __name__ == "__main__":
    main()
