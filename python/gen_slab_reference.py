"""Total diffuse reflectance of a semi-infinite slab under normal incidence, by Mitsuba 3's
volumetric path tracer: the reference for the energy of the dipole BSSRDFs
(render/tests/directional_dipole.rs; docs/BENCHMARKS.md).

For each medium and colour channel, a gray medium of that channel's σa, σs′ (g = 0, index-matched
boundary, η = 1) fills a box 4000 mm wide and 2000 mm deep, lit by a directional light of
irradiance E = π along −z; a `radiancemeter` looks straight down at the centre. The slab's
reflectance is then ρ = π L / E = L (the radiance leaving a Lambertian of reflectance ρ lit by
irradiance π is ρ). Samples are split into independent halves for a standard error.

    .venv/bin/python python/gen_slab_reference.py --out data/reference/slab_albedo.json
"""

from __future__ import annotations

import argparse
import json
import sys
import time
from pathlib import Path

import numpy as np

HERE = Path(__file__).resolve().parent
MEDIA = HERE.parent / "data" / "media"
NAMES = ["skin1", "marble", "skimmilk", "ketchup"]


def scene_dict(sigma_a: float, sigma_s: float, seed: int) -> dict:
    import mitsuba as mi

    sigma_t = sigma_a + sigma_s
    albedo = sigma_s / sigma_t if sigma_t > 0 else 0.0
    return {
        "type": "scene",
        "integrator": {"type": "volpath", "max_depth": -1, "rr_depth": 100000},
        "sensor": {
            "type": "radiancemeter",
            "origin": [0.0, 0.0, 10.0],
            "direction": [0.0, 0.0, -1.0],
            "film": {"type": "hdrfilm", "width": 1, "height": 1, "rfilter": {"type": "box"},
                     "pixel_format": "rgb"},
            "sampler": {"type": "independent", "seed": seed},
        },
        "light": {"type": "directional", "direction": [0.0, 0.0, -1.0], "irradiance": {"type": "rgb", "value": np.pi}},
        "slab": {
            "type": "cube",
            "to_world": mi.ScalarTransform4f().translate([0.0, 0.0, -1000.0]).scale([2000.0, 2000.0, 1000.0]),
            "bsdf": {"type": "null"},
            "interior": {
                "type": "homogeneous",
                "albedo": {"type": "rgb", "value": [albedo] * 3},
                "sigma_t": sigma_t,
                "scale": 1.0,
            },
        },
    }


def reflectance(sigma_a: float, sigma_s: float, spp: int, passes: int) -> tuple[float, float]:
    import mitsuba as mi

    values = []
    for seed in range(passes):
        scene = mi.load_dict(scene_dict(sigma_a, sigma_s, seed))
        img = np.array(mi.render(scene, spp=spp))
        values.append(float(img[..., 0].mean()))
    v = np.array(values)
    return float(v.mean()), float(v.std(ddof=1) / np.sqrt(len(v)))


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--out", type=Path, default=HERE.parent / "data" / "reference" / "slab_albedo.json")
    ap.add_argument("--spp", type=int, default=4096, help="samples per pass")
    ap.add_argument("--passes", type=int, default=8)
    a = ap.parse_args()
    import mitsuba as mi

    mi.set_variant("scalar_rgb")
    out = {
        "description": "semi-infinite slab, normal incidence, index-matched boundary (eta = 1), g = 0: total "
        "diffuse reflectance per linear RGB channel by Mitsuba 3 volpath (python/gen_slab_reference.py)",
        "mitsuba": mi.__version__,
        "spp": a.spp * a.passes,
        "media": {},
    }
    for name in NAMES:
        m = json.loads((MEDIA / f"{name}.json").read_text())
        t = time.time()
        rho, err = zip(*(reflectance(sa, ss, a.spp, a.passes)
                         for sa, ss in zip(m["sigma_a_per_mm"], m["sigma_s_prime_per_mm"])))
        out["media"][name] = {
            "sigma_a_per_mm": m["sigma_a_per_mm"],
            "sigma_s_prime_per_mm": m["sigma_s_prime_per_mm"],
            "reflectance": list(rho),
            "standard_error": list(err),
            "seconds": round(time.time() - t, 1),
        }
        print(name, rho, err, flush=True)
    a.out.write_text(json.dumps(out, indent=2) + "\n")
    print(f"wrote {a.out}")


if __name__ == "__main__":
    sys.exit(main())
