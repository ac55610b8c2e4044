#!/usr/bin/env python3
"""numpy baseline for the Rust benchmarks (single core, best of 5).

(a) KM inversion of 10^6 wavelength samples (R_inf, R, Rg random valid,
    D = 0.05 mm), the ln formula vectorised; the log1p form as well.
(b) KM forward R0 and T of 10^6 samples (sinh/cosh form).
(c) spectrum -> XYZ of 10^5 spectra on the 81-sample grid: one call of
    colour.msds_to_XYZ on the (N, 81) array (method "Integration", D65,
    CIE 1931, shape 380-780-5, colour's caches disabled so every repeat does
    the work), and a plain numpy matmul with precomputed 81x3 weights.

Prints a human table on stderr and one JSON object on stdout.
Run: .venv/bin/python python/bench_km.py [--json-only]
"""

from __future__ import annotations

import os

# Single-threaded BLAS/OpenMP: must be set before numpy is imported.
for _var in (
    "OMP_NUM_THREADS",
    "OPENBLAS_NUM_THREADS",
    "MKL_NUM_THREADS",
    "BLIS_NUM_THREADS",
    "NUMEXPR_NUM_THREADS",
    "VECLIB_MAXIMUM_THREADS",
):
    os.environ[_var] = "1"

import json  # noqa: E402
import platform  # noqa: E402
import sys  # noqa: E402
import time  # noqa: E402
import warnings  # noqa: E402

import numpy as np  # noqa: E402

with warnings.catch_warnings():
    warnings.simplefilter("ignore")
    import colour  # noqa: E402

REPEATS = 5
N_KM = 1_000_000
N_SPECTRA = 100_000
THICKNESS_MM = 0.05
SEED = 12345


def pin_to_one_core() -> str:
    if hasattr(os, "sched_setaffinity"):
        cpus = sorted(os.sched_getaffinity(0))
        os.sched_setaffinity(0, {cpus[-1]})
        return f"pinned to cpu {cpus[-1]}"
    return "not pinned (no sched_setaffinity)"


def best_of(fn, repeats: int = REPEATS) -> tuple[float, object]:
    best, out = float("inf"), None
    for _ in range(repeats):
        t0 = time.perf_counter()
        out = fn()
        best = min(best, time.perf_counter() - t0)
    return best, out


# ---------------------------------------------------------------- KM kernels


def km_invert_ln(r_inf, r, rg, d):
    inv = 1.0 / r_inf
    a = 0.5 * (inv + r_inf)
    b = 0.5 * (inv - r_inf)
    sd = np.log((inv - r) * (rg - r_inf) / ((inv - rg) * (r - r_inf))) / (2.0 * b)
    s = sd / d
    return s, s * (a - 1.0)


def km_invert_log1p(r_inf, r, rg, d):
    inv = 1.0 / r_inf
    om = 1.0 - r_inf
    b = om * (1.0 + r_inf) / (2.0 * r_inf)
    y = (rg - r) / ((inv - rg) * (r - r_inf))
    s = np.log1p(2.0 * b * y) / (2.0 * b) / d
    return s, s * (om * om / (2.0 * r_inf))


def km_forward(s, k, x):
    kap = k / s
    a = 1.0 + kap
    b = np.sqrt(kap * (kap + 2.0))
    z = b * s * x
    sh, ch = np.sinh(z), np.cosh(z)
    den = a * sh + b * ch
    return sh / den, b / den


# ---------------------------------------------------------------- inputs


def km_inputs(rng):
    r_inf = rng.uniform(0.05, 0.95, N_KM)
    rg = np.where(rng.random(N_KM) < 0.5, rng.uniform(0.02, 0.06, N_KM), rng.uniform(0.8, 0.9, N_KM))
    r = rg + rng.uniform(0.05, 0.95, N_KM) * (r_inf - rg)
    s = 10 ** rng.uniform(0, 3, N_KM)
    k = 10 ** rng.uniform(-2, 2, N_KM)
    x = 10 ** rng.uniform(-3, -1, N_KM)
    return r_inf, r, rg, s, k, x


def smooth_spectra(rng, n):
    wl = np.arange(380, 781, 5, dtype=np.float64)
    c = rng.uniform(400, 760, (n, 1))
    w = rng.uniform(20, 120, (n, 1))
    base = rng.uniform(0.02, 0.5, (n, 1))
    amp = rng.uniform(0.0, 0.5, (n, 1))
    return np.clip(base + amp * np.exp(-0.5 * ((wl - c) / w) ** 2), 0.0, 1.0)


def main() -> int:
    json_only = "--json-only" in sys.argv
    pinned = pin_to_one_core()
    rng = np.random.default_rng(SEED)
    results = {}

    def record(name, n, seconds, unit="samples"):
        results[name] = {
            "n": n,
            "unit": unit,
            "best_s": seconds,
            "per_s": n / seconds,
            "ns_per": seconds / n * 1e9,
        }

    r_inf, r, rg, s, k, x = km_inputs(rng)
    t, (s_ln, k_ln) = best_of(lambda: km_invert_ln(r_inf, r, rg, THICKNESS_MM))
    record("km_invert_ln_1e6", N_KM, t)
    t, (s_lp, k_lp) = best_of(lambda: km_invert_log1p(r_inf, r, rg, THICKNESS_MM))
    record("km_invert_log1p_1e6", N_KM, t)
    assert np.all(np.isfinite(s_ln)) and np.all(s_ln > 0)
    assert np.max(np.abs(s_ln - s_lp) / s_lp) < 1e-9
    t, (r0, tt) = best_of(lambda: km_forward(s, k, x))
    record("km_forward_r0_t_1e6", N_KM, t)
    assert np.all((r0 >= 0) & (tt >= 0) & (r0 + tt <= 1 + 1e-12))

    spectra = smooth_spectra(rng, N_SPECTRA)
    shape = colour.SpectralShape(380, 780, 5)
    cmfs = colour.MSDS_CMFS["CIE 1931 2 Degree Standard Observer"]
    illum = colour.SDS_ILLUMINANTS["D65"]
    colour.utilities.set_caching_enable(False)
    try:

        def via_colour():
            with warnings.catch_warnings():
                warnings.simplefilter("ignore")
                return colour.msds_to_XYZ(spectra, cmfs, illum, method="Integration", shape=shape)

        t, xyz_colour = best_of(via_colour)
        record("xyz_colour_msds_to_XYZ_1e5", N_SPECTRA, t, "spectra")
    finally:
        colour.utilities.set_caching_enable(True)
    cmfs_g = np.asarray(cmfs[shape.wavelengths])
    S = np.asarray(illum[shape.wavelengths])
    weights = (100.0 / np.sum(cmfs_g[:, 1] * S)) * S[:, None] * cmfs_g  # (81, 3)
    t, xyz_np = best_of(lambda: spectra @ weights)
    record("xyz_numpy_matmul_1e5", N_SPECTRA, t, "spectra")
    assert xyz_colour.shape == (N_SPECTRA, 3)
    assert np.max(np.abs(xyz_np - xyz_colour)) < 1e-10

    report = {
        "tool": "python/bench_km.py",
        "python": platform.python_version(),
        "numpy": np.__version__,
        "colour": colour.__version__,
        "machine": platform.machine(),
        "cpu_affinity": pinned,
        "threads_env": os.environ["OPENBLAS_NUM_THREADS"],
        "repeats": REPEATS,
        "timing": "best of 5, time.perf_counter, inputs generated outside the timed region",
        "results": results,
    }
    if not json_only:
        print(f"{'benchmark':32} {'n':>9} {'best s':>10} {'samples/s':>12} {'ns/sample':>10}", file=sys.stderr)
        for name, v in results.items():
            print(
                f"{name:32} {v['n']:>9} {v['best_s']:>10.4f} {v['per_s']:>12.4g} {v['ns_per']:>10.2f}",
                file=sys.stderr,
            )
    print(json.dumps(report, indent=2))
    return 0


if __name__ == "__main__":
    sys.exit(main())
