"""The subsurface reflectance of a half-space under a smooth dielectric boundary, by
adding-doubling ([Prahl1993], iadpython), the reference for render/src/dielectric_half_space.rs.

An isotropically scattering medium of reduced albedo a' = sigma_s'/sigma_t' (g = 0 by the
similarity relation, as data/media/ writes its media), semi-infinite (optical thickness 1e6),
below a flat interface of relative index eta (air above). For each (eta, a'):

- r_normal: the directional-hemispherical reflectance at normal incidence, UR1(a') - UR1(0):
  the light that entered, scattered and left, without the boundary's specular reflection (at
  a' = 0 nothing scatters, so UR1(0) is the Fresnel reflectance alone);
- r_diffuse: the same under diffuse (uniform) incidence, URU(a') - URU(0).

Two sets: "grid", the table Rouge interpolates (25 eta from 1 to 3 evenly spaced in
sqrt(eta - 1), and 49 albedos evenly spaced in t = (1 - a')^(1/4): the reflectances fall
steeply from a' = 1, as sqrt(1 - a') times a factor that grows with eta), and "check", points off the grid (other eta, pseudo-random
albedos, and the four media of data/media/ at eta 1, their own eta and 1.4), on which the
interpolation is reported. quad_pts = 16 at eta = 1 and 32 above (`quadrature`); each entry
also gives its change at 24 and 40 points.

    python python/gen_dielectric_half_space.py --out data/reference/dielectric_half_space.json
"""

from __future__ import annotations

import argparse
import json
import random
from pathlib import Path

import iadpython

HERE = Path(__file__).resolve().parent
# Even in sqrt(eta - 1): the critical angle, cos = sqrt(1 - 1/eta^2), opens as sqrt(eta - 1),
# so the reflectances bend sharply just above eta = 1 and are smooth in this variable.
# eta 1 to 3, the domain of data/media/ files (model/src/medium.rs).
GRID_ETA_STEPS = 24
GRID_ETAS = [round(1.0 + 2.0 * (j / GRID_ETA_STEPS) ** 2, 12) for j in range(GRID_ETA_STEPS + 1)]
GRID_STEPS = 48
CHECK_ETAS = [1.05, 1.25, 1.33, 1.37, 1.45, 1.55, 1.8, 2.2, 2.7]
OPTICAL_THICKNESS = 1e6


def reflectances(albedo: float, eta: float, quad_pts: int) -> tuple[float, float]:
    """(UR1, URU) of the half-space, the boundary's specular reflection included."""
    sample = iadpython.Sample(
        a=albedo, b=OPTICAL_THICKNESS, g=0.0, n=eta, n_above=1.0, n_below=1.0, quad_pts=quad_pts
    )
    ur1, _, uru, _ = sample.rt()
    return float(ur1), float(uru)


def quadrature(eta: float) -> tuple[int, int]:
    """Quadrature points used and checked against. With eta = 1, 8-24 points give the 50-digit
    H-function's reflectance (data/reference/h_function.json) to 6 digits and 32 or more lose
    digits at high albedo; with eta > 1 the critical angle's kink converges slowly (about 1e-4 at
    32 points), so 32 are used there and 40 checked (from about 48 on, digits are lost as a' -> 1)."""
    return (16, 24) if eta == 1.0 else (32, 40)


def entry(albedo: float, eta: float, label: str | None = None) -> dict:
    q, q_check = quadrature(eta)
    ur1, uru = reflectances(albedo, eta, q)
    spec1, specu = reflectances(0.0, eta, q)
    fine1, fineu = reflectances(albedo, eta, q_check)
    fspec1, fspecu = reflectances(0.0, eta, q_check)
    change = max(abs((fine1 - fspec1) - (ur1 - spec1)), abs((fineu - fspecu) - (uru - specu)))
    e = {
        "eta": eta,
        "albedo": albedo,
        "r_normal": round(ur1 - spec1, 10),
        "r_diffuse": round(uru - specu, 10),
        "quadrature_change": float(f"{change:.2e}"),
    }
    if label:
        e["medium"] = label
    return e


def media() -> list[tuple[str, float, float]]:
    """(name + channel, reduced albedo, eta) of the media in data/media/."""
    out = []
    for path in sorted((HERE.parent / "data" / "media").glob("*.json")):
        m = json.loads(path.read_text())
        for c, (sa, ss) in enumerate(zip(m["sigma_a_per_mm"], m["sigma_s_prime_per_mm"])):
            out.append((f"{m['name']} {'RGB'[c]}", ss / (sa + ss), m["eta"]))
    return out


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--out", type=Path, default=HERE.parent / "data" / "reference" / "dielectric_half_space.json")
    args = ap.parse_args()
    grid = [
        entry(1.0 - (k / GRID_STEPS) ** 4, eta) for eta in GRID_ETAS for k in range(GRID_STEPS + 1)
    ]
    rng = random.Random(31)
    check = [entry(1.0 - rng.random() ** 2, eta) for eta in CHECK_ETAS for _ in range(12)]
    for name, albedo, eta in media():
        for e in sorted({1.0, eta, 1.4}):
            check.append(entry(albedo, e, name))
    doc = {
        "description": __doc__.split("\n\n")[0].replace("\n", " "),
        "source": f"iadpython {iadpython.__version__} (adding-doubling, S. Prahl), quad_pts 16 at eta 1 and 32 above, "
        f"optical thickness {OPTICAL_THICKNESS:g}, g = 0, air above",
        "script": "python/gen_dielectric_half_space.py",
        "grid_etas": GRID_ETAS,
        "grid_steps": GRID_STEPS,
        "grid": grid,
        "check": check,
    }
    # One entry a line: small, and still readable in a diff.
    text = json.dumps({k: v for k, v in doc.items() if k not in ("grid", "check")}, indent=1)[:-2]
    for key in ("grid", "check"):
        rows = ",\n  ".join(json.dumps(e) for e in doc[key])
        text += f',\n "{key}": [\n  {rows}\n ]'
    args.out.write_text(text + "\n}\n")
    worst = max(e["quadrature_change"] for e in grid + check)
    print(f"wrote {args.out}: {len(grid)} grid and {len(check)} check entries; worst change with more quadrature points {worst:.2e}")


if __name__ == "__main__":
    main()
