#!/usr/bin/env python3
"""How exact is Kubelka-Munk for cosmetic layers? Rouge's KM against Prahl's adding-doubling.

Adding-doubling ([Prahl1993], the PyPI package ``iadpython``, pinned) solves the radiative
transport equation in a plane-parallel slab exactly (to its quadrature: 16 points here, converged
to ~1e-6) for an albedo, an optical thickness, a Henyey-Greenstein anisotropy g and the
refractive indices of the slab and its surroundings. It is the reference; Rouge's two-flux
Kubelka-Munk ([Kubelka1948], ``measure/src/km.rs``) is what is judged, through the real ``rouge``
binary (``rouge km invert``, ``rouge km layer``), exactly as a formulator would use it:

1. **Coefficients.** A layer of reduced scattering sigma_s' = sigma_s (1 - g) and absorption
   sigma_a (mm^-1), thickness d, index-matched (no surface reflection: KM's own assumption). AD
   gives its diffuse reflectance over black R0(d), transmittance T(d) and the opaque R_inf (URU,
   UTU: diffuse light in, all light out). Rouge inverts S and K from R_inf and R0(d) over black,
   and the ratios S/sigma_s', K/sigma_a are compared with the classical relations: K = 2 sigma_a
   and S = (3/4) sigma_s' - (1/4) sigma_a from diffusion theory ([vanGemert1987], [Star1988];
   valid where scattering dominates and the layer is many transport lengths thick), against
   which [Thennadil2008] measured the departures.
2. **Predictions.** With those S and K, KM's T(d), the reflectance over a white background
   (Rg = 0.8) and R0 at twice the thickness, against AD (the white background composed with AD's
   R and T exactly, since diffuse light off a Lambertian background re-enters as diffuse light).
   Coverage, shade matching and mixing all extrapolate like this.
3. **Surfaces.** The same layer with refractive index 1.5 in air (on an index-matched black), as
   a d/8 instrument with the specular component included sees it (UR1: near-normal light in, all
   light out): S and K inverted from those readings directly, and after Saunderson's correction
   (``rouge km invert --saunderson-ior 1.5``, K2 = 0.6), against the index-matched S and K of
   step 1.

    .venv/bin/python python/km_adding_doubling.py [--json build/km_ad.json]

prints the tables of docs/FORMULATION.md. python/test_km_adding_doubling.py runs a small set in CI.
"""

from __future__ import annotations

import argparse
import json
import os
import subprocess
import sys
from pathlib import Path

import numpy as np
import iadpython as iad

QUAD = 16
REPO = Path(__file__).resolve().parent.parent
WHITE = 0.8
N_SLAB = 1.5


def rouge_bin() -> str:
    return os.environ.get("ROUGE_BIN", str(REPO / "target" / "debug" / "rouge"))


def rouge(*args: str) -> dict:
    out = subprocess.run([rouge_bin(), *args], capture_output=True, text=True)
    if out.returncode != 0:
        raise RuntimeError(f"rouge {' '.join(args)}: {out.stderr.strip()}")
    return json.loads(out.stdout)


def ad(sigma_a: float, sigma_s_red: float, d_mm: float, g: float, n: float = 1.0) -> dict[str, float]:
    """Adding-doubling for a slab of sigma_a, sigma_s' (mm^-1), thickness d (np.inf: opaque),
    anisotropy g, index n in air over an index-matched black (n_below = n). Returns UR1, UT1
    (collimated normal incidence) and URU, UTU (diffuse incidence), total (specular included)."""
    sigma_s = sigma_s_red / (1.0 - g)
    sigma_t = sigma_a + sigma_s
    b = 1e4 if np.isinf(d_mm) else sigma_t * d_mm
    s = iad.Sample(a=sigma_s / sigma_t, b=b, g=g, d=1.0, n=n, n_above=1.0, n_below=n, quad_pts=QUAD)
    ur1, ut1, uru, utu = (float(v) for v in s.rt())
    return {"ur1": ur1, "ut1": ut1, "uru": uru, "utu": 0.0 if np.isinf(d_mm) else utu}


def over(r0: float, t: float, rg: float) -> float:
    """A layer (R0, T) over an opaque Lambertian background: R0 + T^2 Rg / (1 - R0 Rg)."""
    return r0 + t * t * rg / (1.0 - r0 * rg)


def regime(albedo_red: float, tau_red: float, g: float = 0.0) -> dict[str, float]:
    """One layer: reduced albedo a' = sigma_s'/(sigma_a + sigma_s'), reduced optical thickness
    tau' = (sigma_a + sigma_s') d, with sigma_a + sigma_s' = 100 mm^-1 (cosmetic-like: tau' = 1
    is a 10 um film)."""
    sigma_tr = 100.0
    sigma_s_red, sigma_a = albedo_red * sigma_tr, (1.0 - albedo_red) * sigma_tr
    d = tau_red / sigma_tr
    thick, thin, twice = ad(sigma_a, sigma_s_red, np.inf, g), ad(sigma_a, sigma_s_red, d, g), ad(sigma_a, sigma_s_red, 2 * d, g)
    row = {"albedo_red": albedo_red, "tau_red": tau_red, "g": g, "d_mm": d, "sigma_a": sigma_a, "sigma_s_red": sigma_s_red,
           "r_inf": thick["uru"], "r0": thin["uru"], "t": thin["utu"]}
    km = rouge("km", "invert", "--r-inf", repr(thick["uru"]), "--r", repr(thin["uru"]), "--rg", "0", "--thickness-mm", repr(d))
    s, k = km["s_per_mm"], km["k_per_mm"]
    row.update(s=s, k=k, s_ratio=s / sigma_s_red, k_ratio=k / sigma_a if sigma_a > 0 else float("nan"),
               s_diffusion=0.75 * sigma_s_red - 0.25 * sigma_a)
    lay = rouge("km", "layer", "--s", repr(s), "--k", repr(k), "--thickness-mm", repr(d))
    lay2 = rouge("km", "layer", "--s", repr(s), "--k", repr(k), "--thickness-mm", repr(2 * d))
    row.update(
        t_km=lay["t"], dt=lay["t"] - thin["utu"],
        r_white_ad=over(thin["uru"], thin["utu"], WHITE), r_white_km=over(lay["r0"], lay["t"], WHITE),
        r0_2d_ad=twice["uru"], r0_2d_km=lay2["r0"],
    )
    row["dr_white"] = row["r_white_km"] - row["r_white_ad"]
    row["dr0_2d"] = row["r0_2d_km"] - row["r0_2d_ad"]
    # Surfaces: n = 1.5 in air, read at near-normal incidence with the specular component.
    thick_n, thin_n = ad(sigma_a, sigma_s_red, np.inf, g, N_SLAB), ad(sigma_a, sigma_s_red, d, g, N_SLAB)
    k1 = ((N_SLAB - 1) / (N_SLAB + 1)) ** 2
    args = ["km", "invert", "--r-inf", repr(thick_n["ur1"]), "--r", repr(thin_n["ur1"]), "--rg", repr(k1), "--thickness-mm", repr(d)]
    for key, extra in (("raw", []), ("saunderson", ["--saunderson-ior", repr(N_SLAB)])):
        try:
            got = rouge(*args, *extra)
            row[f"s_{key}_ratio"], row[f"k_{key}_ratio"] = got["s_per_mm"] / s, got["k_per_mm"] / k
        except RuntimeError as e:
            row[f"s_{key}_ratio"] = row[f"k_{key}_ratio"] = float("nan")
            row[f"{key}_error"] = str(e)
    return row


def lab(refl: np.ndarray) -> np.ndarray:
    """CIELAB (D65, CIE 1931) of a reflectance on 380-780 nm / 5 nm, by colour-science."""
    import colour

    shape = colour.SpectralShape(380, 780, 5)
    sd = colour.SpectralDistribution(dict(zip(np.arange(380, 781, 5), refl)))
    xyz = colour.sd_to_XYZ(sd, colour.MSDS_CMFS["CIE 1931 2 Degree Standard Observer"], colour.SDS_ILLUMINANTS["D65"],
                           method="Integration", shape=shape)
    return colour.XYZ_to_Lab(xyz / 100.0, colour.CCS_ILLUMINANTS["CIE 1931 2 Degree Standard Observer"]["D65"])


def ad_spectral(sigma_a: np.ndarray, sigma_s_red: np.ndarray, d_mm: float) -> tuple[np.ndarray, np.ndarray]:
    """Diffuse R0 and T of an index-matched isotropic slab at every wavelength at once."""
    sigma_t = sigma_a + sigma_s_red
    b = np.full_like(sigma_t, 1e4) if np.isinf(d_mm) else sigma_t * d_mm
    s = iad.Sample(a=sigma_s_red / sigma_t, b=b, g=0.0, d=1.0, quad_pts=QUAD)
    _, _, uru, utu = s.rt()
    return np.asarray(uru, float), (np.zeros_like(sigma_t) if np.isinf(d_mm) else np.asarray(utu, float))


def products(factors: tuple[float, ...] = (0.5, 2.0, 4.0)) -> list[dict]:
    """The sample products as physical media and what KM predicts of them.

    Each preset's S and K become a medium by the diffusion relations (sigma_a = K/2,
    sigma_s' = (S + sigma_a/4)/(3/4)); adding-doubling then "measures" it as a lab would (R_inf,
    and R0 over black at the preset's thickness d0), Rouge inverts S and K per wavelength, and KM's
    colour of the skin covered by d0 x factor is compared (CIEDE2000, colour-science) with
    adding-doubling's, over the ColorChecker's light and dark skin."""
    import colour

    lines = [ln for ln in (REPO / "data" / "skin" / "colorchecker_skin.csv").read_text().splitlines() if not ln.startswith("#")]
    table = np.array([[float(v) for v in ln.split(",")] for ln in lines[1:]])
    skins = {"dark_skin": table[:, 1], "light_skin": table[:, 2]}
    out = []
    for path in sorted((REPO / "data" / "presets").glob("*.json")):
        p = json.loads(path.read_text())
        S, K, d0 = np.array(p["s_per_mm"]), np.array(p["k_per_mm"]), float(p["thickness_mm"])
        sigma_a = K / 2.0
        sigma_s = (S + 0.25 * sigma_a) / 0.75
        r_inf, _ = ad_spectral(sigma_a, sigma_s, np.inf)
        r0, _ = ad_spectral(sigma_a, sigma_s, d0)
        sk = [rouge("km", "invert", "--r-inf", repr(float(a)), "--r", repr(float(b)), "--rg", "0", "--thickness-mm", repr(d0))
              for a, b in zip(r_inf, r0)]
        row = {"name": p["name"], "d0_mm": d0,
               "albedo_red_p10_p90": [float(np.percentile(sigma_s / (sigma_a + sigma_s), q)) for q in (10, 90)],
               "tau_red_p10_p90": [float(np.percentile((sigma_a + sigma_s) * d0, q)) for q in (10, 90)]}
        for f in factors:
            x = d0 * f
            r_ad, t_ad = ad_spectral(sigma_a, sigma_s, x)
            lay = [rouge("km", "layer", "--s", repr(c["s_per_mm"]), "--k", repr(c["k_per_mm"]), "--thickness-mm", repr(x)) for c in sk]
            r_km, t_km = np.array([v["r0"] for v in lay]), np.array([v["t"] for v in lay])
            des = [float(colour.delta_E(lab(over(r_km, t_km, rg)), lab(over(r_ad, t_ad, rg)), method="CIE 2000"))
                   for rg in skins.values()]
            row[f"de_x{f:g}"] = max(des)
        out.append(row)
    return out


ALBEDOS = (0.5, 0.8, 0.9, 0.95, 0.98, 0.99, 0.995, 0.999)
TAUS = (0.1, 0.3, 1.0, 3.0, 10.0)


def table(rows: list[dict], key: str, fmt: str) -> str:
    lines = ["| a' \\ tau' | " + " | ".join(f"{t:g}" for t in TAUS) + " |", "|---" * (len(TAUS) + 1) + "|"]
    for a in ALBEDOS:
        cells = [fmt.format(r[key]) for t in TAUS for r in rows if r["albedo_red"] == a and r["tau_red"] == t]
        lines.append(f"| {a:g} | " + " | ".join(cells) + " |")
    return "\n".join(lines)


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--json", type=Path)
    ap.add_argument("--g", type=float, default=0.0, help="anisotropy (default 0; 0.8 checks similarity)")
    ap.add_argument("--products", action="store_true", help="also the sample products' colour on skin (slower)")
    args = ap.parse_args()
    if args.products:
        prods = products()
        print("| product | d0 (um) | a' (p10-p90) | tau' at d0 | max dE00 KM vs AD on skin at d0/2 | at 2 d0 | at 4 d0 |")
        print("|---|---:|---|---|---:|---:|---:|")
        for r in prods:
            a, t = r["albedo_red_p10_p90"], r["tau_red_p10_p90"]
            print(f"| {r['name']} | {r['d0_mm'] * 1e3:.0f} | {a[0]:.2f}-{a[1]:.2f} | {t[0]:.2f}-{t[1]:.2f} | "
                  f"{r['de_x0.5']:.2f} | {r['de_x2']:.2f} | {r['de_x4']:.2f} |")
    rows = [regime(a, t, args.g) for a in ALBEDOS for t in TAUS]
    for title, key, fmt in (
        ("S / sigma_s' (diffusion theory: 0.75 - 0.25 (1-a')/a')", "s_ratio", "{:.3f}"),
        ("K / sigma_a (diffusion theory: 2)", "k_ratio", "{:.3f}"),
        ("T_KM - T_AD at the inversion thickness", "dt", "{:+.4f}"),
        ("R over white (0.8): KM - AD", "dr_white", "{:+.4f}"),
        ("R0 at twice the thickness: KM - AD", "dr0_2d", "{:+.4f}"),
        ("n = 1.5, no correction: S / S_matched", "s_raw_ratio", "{:.3f}"),
        ("n = 1.5, no correction: K / K_matched", "k_raw_ratio", "{:.3f}"),
        ("n = 1.5, Saunderson (K2 0.6): S / S_matched", "s_saunderson_ratio", "{:.3f}"),
        ("n = 1.5, Saunderson (K2 0.6): K / K_matched", "k_saunderson_ratio", "{:.3f}"),
    ):
        print(f"\n{title} (g = {args.g:g})\n{table(rows, key, fmt)}")
    if args.json:
        args.json.parent.mkdir(parents=True, exist_ok=True)
        args.json.write_text(json.dumps(rows, indent=1))
    return 0


if __name__ == "__main__":
    sys.exit(main())
