"""Diffusion inside a whole sphere lit from one side, against the path tracer (issue 31; docs/BENCHMARKS.md,
"A sphere's diffusion solution against the path tracer").

The translucency references' spheres (`builtin:sphere`, radius 25 mm, index-matched boundary) are
lit by one directional light. Diffusion theory solves that case in closed form per Legendre order
l of the incident flux E(μ) = max(μ, 0) (μ the cosine between the surface normal and the light):
inside the sphere the fluence of order l is i_l(σ_tr r)·P_l(μ) (i_l the modified spherical Bessel
function of the first kind), and Marshak's boundary condition at η = 1 (inward partial current
φ/4 + (D/2)∂φ/∂r equal to the incident flux) gives the order's reflectance

    T_l = (1 − 2Dρ_l) / (1 + 2Dρ_l),   ρ_l = σ_tr i_l'(σ_tr R) / i_l(σ_tr R),

whose limit as R → ∞ (ρ_l → σ_tr) is the flat half-space's T_∞ for every l. The sphere's exitance is
Σ_l T_l E_l P_l(μ), scaled here by A/T_∞ per channel (A the path tracer's half-space albedo at
normal incidence, data/reference/slab_albedo.json) so that the flat limit is exact and what is
left is the sphere's own effect. Orders stop where T_l ≤ 0 (structure finer than a mean free
path, beyond diffusion). D = 1/(3σ′_t), σ_tr = √(σ_a/D).

The script bins the reference's pixels by μ (normals from ray-sphere intersection through Rouge's
framing camera, `Camera::framing`: it sees any radius the same) and prints, per bin, the path
tracer, this solution, and Rouge's half-space law at each pixel (`--subsurface none --diffuse
half-space`, the local law without any transport along the surface).

    .venv/bin/python python/sphere_diffusion.py --scene sphere-skimmilk
"""

from __future__ import annotations

import argparse
import json
import subprocess
import sys
import tempfile
from pathlib import Path

import numpy as np

HERE = Path(__file__).resolve().parent
ROOT = HERE.parent
sys.path.insert(0, str(HERE))

import mitsuba_ref  # noqa: E402

SPHERE_RADIUS_MM = 25.0  # model/src/mesh/shapes.rs SPHERE_RADIUS_MM
FOV_Y_DEG = 25.0  # render/src/scene.rs Camera::framing


def option(opts: list[str], name: str) -> str:
    if name not in opts:
        sys.exit(f"the reference's rouge_options carry no {name}")
    return opts[opts.index(name) + 1]


def light_direction(rig: str) -> np.ndarray:
    """render/src/scene.rs Scene::rig."""
    toward = {"front-left": (-0.6, 0.35, 0.72), "back": (0.55, 0.3, -0.78), "front": (0.0, 0.0, 1.0)}
    if rig not in toward:
        sys.exit(f"light rig {rig!r} is not one of {sorted(toward)}")
    v = np.array(toward[rig])
    return v / np.linalg.norm(v)


def normals(n: int, radius: float) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Per pixel: hit mask, unit normal and cosine toward the camera, for the framing camera
    (bounds of the sphere: half height 0.95 R, target raised by 0.05 of the height)."""
    t = np.tan(np.radians(0.5 * FOV_Y_DEG))
    distance = 0.95 * radius / t + radius
    cam = np.array([0.0, 0.1 * radius, distance])
    jj, ii = np.mgrid[:n, :n]
    d = np.stack([((ii + 0.5) / (n / 2) - 1) * t, (1 - (jj + 0.5) / (n / 2)) * t, -np.ones((n, n))], -1)
    d /= np.linalg.norm(d, axis=-1, keepdims=True)
    b = (d * cam).sum(-1)
    disc = b * b - (cam @ cam - radius * radius)
    hit = disc > 0
    s = -b - np.sqrt(np.maximum(disc, 0.0))
    normal = (cam + s[..., None] * d) / radius
    return hit, normal, (-d * normal).sum(-1)


def sphere_orders(sigma_a: float, sigma_s_prime: float, radius: float, albedo: float) -> np.ndarray:
    """Per Legendre order l: T_l·E_l, scaled to `albedo` in the flat limit (the sphere's diffuse
    exitance per unit irradiance along μ is Σ_l of these times P_l(μ))."""
    from numpy.polynomial.legendre import leggauss
    from scipy.special import eval_legendre, spherical_in

    d = 1.0 / (3.0 * (sigma_a + sigma_s_prime))
    tr = np.sqrt(sigma_a / d)
    x = tr * radius
    t_inf = (1 - 2 * d * tr) / (1 + 2 * d * tr)
    nodes, weights = leggauss(800)
    flux = np.maximum(nodes, 0.0)
    out = []
    for order in range(400):
        rho = tr * spherical_in(order, x, derivative=True) / spherical_in(order, x)
        t_l = (1 - 2 * d * rho) / (1 + 2 * d * rho)
        if t_l <= 0:
            break
        e_l = (2 * order + 1) / 2 * np.sum(weights * flux * eval_legendre(order, nodes))
        out.append(t_l * e_l * albedo / t_inf)
    return np.array(out)


def sphere_exitance(mu: np.ndarray, orders: np.ndarray) -> np.ndarray:
    """Σ_l orders[l]·P_l(μ): the sphere's exitance per unit irradiance along μ."""
    from scipy.special import eval_legendre

    return sum(c * eval_legendre(order, mu) for order, c in enumerate(orders))


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--scene", default="sphere-skimmilk")
    ap.add_argument("--references", type=Path, default=ROOT / "data" / "reference" / "translucency")
    ap.add_argument("--rouge", default=str(ROOT / "target" / "release" / "rouge"))
    ap.add_argument("--bins", type=int, default=17)
    a = ap.parse_args()
    side = json.loads((a.references / f"{a.scene}.json").read_text())
    opts = side["rouge_options"]
    if option(opts, "--mesh") != "builtin:sphere" or float(option(opts, "--eta")) != 1.0:
        sys.exit(f"{a.scene}: the solution here is for builtin:sphere at --eta 1")
    medium_name = option(opts, "--medium")
    medium = json.loads((ROOT / "data" / "media" / f"{medium_name}.json").read_text())
    albedo = json.loads((ROOT / "data" / "reference" / "slab_albedo.json").read_text())["media"][medium_name]["reflectance"]
    ref = mitsuba_ref.read_exr(a.references / side["image"])
    covered = ref[..., 3] > 0.999
    with tempfile.TemporaryDirectory() as tmp:
        out = Path(tmp) / "law.exr"
        cmd = [a.rouge, "render", *opts, "--subsurface", "none", "--diffuse", "half-space", "--no-specular", "--out", str(out)]
        subprocess.run(cmd, check=True, capture_output=True, cwd=ROOT)
        law = mitsuba_ref.read_exr(out)[..., :3]
    hit, normal, facing = normals(ref.shape[0], SPHERE_RADIUS_MM)
    agree = float((hit == covered).mean())
    if agree < 0.99:
        sys.exit(f"the camera model disagrees with the reference's coverage on {100 * (1 - agree):.1f}% of pixels")
    mu = (normal * light_direction(option(opts, "--lights"))).sum(-1)
    sel = covered & hit & (facing > 0.3)
    print(f"{a.scene}: {medium_name}, R = {SPHERE_RADIUS_MM} mm; mean radiance per μ bin (pixels facing the camera by > 0.3)")
    print("| μ | pixels | path tracer R / G / B | diffusion sphere | half-space law | sphere / path tracer | law / path tracer |")
    print("| --- | --- | --- | --- | --- | --- | --- |")
    orders = [
        sphere_orders(medium["sigma_a_per_mm"][c], medium["sigma_s_prime_per_mm"][c], SPHERE_RADIUS_MM, albedo[c])
        for c in range(3)
    ]
    edges = np.linspace(mu[sel].min(), 1.0, a.bins + 1)
    fmt = lambda v: " / ".join(f"{x:.4f}" for x in v)  # noqa: E731
    ratio = lambda p, r: " / ".join(f"{x / y:.2f}" if y > 1e-4 else "-" for x, y in zip(p, r))  # noqa: E731
    for lo, hi in zip(edges[:-1], edges[1:]):
        s = sel & (mu >= lo) & (mu < hi)
        if s.sum() < 20:
            continue
        m = mu[s]
        pt = ref[s][:, :3].mean(0)
        sph = np.array([sphere_exitance(m, orders[c]).mean() for c in range(3)])
        hs = law[s].mean(0)
        print(f"| {m.mean():+.2f} | {int(s.sum())} | {fmt(pt)} | {fmt(sph)} | {fmt(hs)} | {ratio(sph, pt)} | {ratio(hs, pt)} |")


if __name__ == "__main__":
    main()
