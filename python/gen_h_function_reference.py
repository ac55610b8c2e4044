"""50-digit values of Chandrasekhar's H-function for isotropic scattering, the reference for
render/src/half_space.rs (render/tests/half_space.rs).

Computed from the closed integral representation ([Chandrasekhar1960] chapter V, eq. 55 in the
form of [vandeHulst1980] vol. 1, section 5.3), not from the integral equation Rouge iterates:

    ln H(mu) = -(mu/pi) * integral_0^inf ln(1 - w arctan(t)/t) / (1 + mu^2 t^2) dt,

with mpmath's tanh-sinh quadrature at 60 digits, split at t = 1, 10, 100. H(0) = 1 for every w.
Also written: the half-space quantities Rouge derives from H (the directional-hemispherical
reflectance 1 - sqrt(1 - w) H(mu0) and pi times the BRDF at mu = mu0 = 1, w H(1)^2 / 8), the latter
the quantity data/reference/slab_albedo.json measured with Mitsuba 3.

    python python/gen_h_function_reference.py --out data/reference/h_function.json
"""

from __future__ import annotations

import argparse
import json
import sys
from pathlib import Path

import mpmath as mp

HERE = Path(__file__).resolve().parent
ALBEDOS = ["0.01", "0.1", "0.3", "0.5", "0.7", "0.9", "0.99", "0.999", "0.9999", "1"]
COSINES = ["0", "0.001", "0.01", "0.05", "0.1", "0.25", "0.5", "0.75", "1"]


def h_function(w: mp.mpf, mu: mp.mpf) -> mp.mpf:
    if mu == 0:
        return mp.mpf(1)

    def integrand(t):
        # 1 - w arctan(t)/t, by its series 1 - w + w(t^2/3 - t^4/5 + t^6/7) where the quadrature
        # samples t so close to 0 that the difference would cancel to nothing (w = 1).
        if t < mp.mpf("1e-12"):
            q = 1 - w + w * (t**2 / 3 - t**4 / 5 + t**6 / 7)
        else:
            q = 1 - w * mp.atan(t) / t
        return mp.log(q) / (1 + mu * mu * t * t)

    return mp.exp(-(mu / mp.pi) * mp.quad(integrand, [0, 1, 10, 100, mp.inf]))


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--out", type=Path, default=HERE.parent / "data" / "reference" / "h_function.json")
    a = ap.parse_args()
    mp.mp.dps = 60
    rows = []
    for ws in ALBEDOS:
        w = mp.mpf(ws)
        hs = [h_function(w, mp.mpf(m)) for m in COSINES]
        h1 = hs[-1]
        rows.append({
            "albedo": ws,
            "h": [mp.nstr(h, 50) for h in hs],
            "directional_reflectance": [mp.nstr(1 - mp.sqrt(1 - w) * h, 50) for h in hs],
            "pi_brdf_normal": mp.nstr(w * h1 * h1 / 8, 50),
        })
        print(ws, mp.nstr(h1, 12), flush=True)
    out = {
        "description": "Chandrasekhar's H-function for isotropic scattering of single-scattering albedo "
        "`albedo` at the cosines `mu`, 50 digits (python/gen_h_function_reference.py, mpmath "
        + mp.__version__ + "), with the half-space's directional-hemispherical reflectance "
        "1 - sqrt(1 - albedo) H(mu) and pi * BRDF(mu = mu0 = 1) = albedo H(1)^2 / 8",
        "mu": COSINES,
        "rows": rows,
    }
    a.out.write_text(json.dumps(out, indent=1) + "\n")
    print(f"wrote {a.out}")


if __name__ == "__main__":
    sys.exit(main())
