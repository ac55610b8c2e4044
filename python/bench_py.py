#!/usr/bin/env python3
"""Throughput of the `rouge` Python package against vectorised numpy of the same formulas.

The numpy side is the textbook vectorised form (the only place the formulas are written in
Python, as a speed baseline): inversion [Huang2013] eq. 6-7 in the ln form, forward eq. 1-2 with
sinh/cosh, XYZ as a matrix product with the same weights. Both run on the same float64 arrays; the figure is
elements (or spectra) per second, best of 5. Prints a Markdown table for docs/BENCHMARKS.md.

    .venv/bin/python python/bench_py.py            # after tests/run.sh built the wheel
"""

from __future__ import annotations

import os
import platform
import time

import numpy as np

import rouge


def best(f, repeat: int = 5) -> float:
    f()
    t = []
    for _ in range(repeat):
        t0 = time.perf_counter()
        f()
        t.append(time.perf_counter() - t0)
    return min(t)


def np_invert(r_inf, r, rg, d):
    a = 0.5 * (1 / r_inf + r_inf)
    b = 0.5 * (1 / r_inf - r_inf)
    s = np.log((1 - r * r_inf) * (rg - r_inf) / ((1 - rg * r_inf) * (r - r_inf))) / (2 * b * d)
    return s, s * (a - 1)


def np_layer(s, k, x):
    a = 1 + k / s
    b = np.sqrt(a * a - 1)
    sh, ch = np.sinh(b * s * x), np.cosh(b * s * x)
    den = a * sh + b * ch
    return sh / den, b / den


def main() -> None:
    rng = np.random.default_rng(0)
    rows = []
    for n in (81, 81 * 100, 81 * 10_000):
        r_inf = rng.uniform(0.2, 0.9, n)
        rg = rng.uniform(0.0, 0.1, n)
        r = rg + rng.uniform(0.1, 0.9, n) * (r_inf - rg)
        d = np.full(n, 0.02)
        s, k = rouge.R_to_SK_KubelkaMunk(r_inf, r, rg, d)
        err = np.max(np.abs(np_invert(r_inf, r, rg, d)[0] - s) / s)
        rows.append(("R_to_SK_KubelkaMunk", n, n / best(lambda: rouge.R_to_SK_KubelkaMunk(r_inf, r, rg, d)),
                     n / best(lambda: np_invert(r_inf, r, rg, d)), err))
        r0, _ = rouge.SK_to_R0T_KubelkaMunk(s, k, d)
        err = np.max(np.abs(np_layer(s, k, d)[0] - r0) / r0)
        rows.append(("SK_to_R0T_KubelkaMunk", n, n / best(lambda: rouge.SK_to_R0T_KubelkaMunk(s, k, d)),
                     n / best(lambda: np_layer(s, k, d)), err))
    w = rouge.sd_to_XYZ(np.eye(81))  # the weights k·cmf·illuminant, one row per wavelength
    for m in (1, 100, 10_000):
        spectra = rng.uniform(0, 1, (m, 81))
        xyz = rouge.sd_to_XYZ(spectra)
        err = np.max(np.abs(spectra @ w - xyz) / np.abs(xyz))
        rows.append(("sd_to_XYZ (spectra)", m, m / best(lambda: rouge.sd_to_XYZ(spectra)),
                     m / best(lambda: spectra @ w), err))
    print(f"{platform.processor() or platform.machine()}, {os.cpu_count()} cores, numpy {np.__version__}, rouge {rouge.__version__}\n")
    print("| call | elements | rouge (per s) | numpy (per s) | rouge / numpy | max rel. diff |")
    print("| --- | ---: | ---: | ---: | ---: | ---: |")
    for name, n, a, b, e in rows:
        print(f"| `{name}` | {n:,} | {a:.3g} | {b:.3g} | {a / b:.1f}× | {e:.1e} |")


if __name__ == "__main__":
    main()
