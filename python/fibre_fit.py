"""Would fitting the fibre's azimuthal terms to PBRT-v4 help? (docs/BENCHMARKS.md, the hair fibre.)

Rouge's fibre model (render/src/fibre.rs) takes Karis 2016's azimuthal terms for TT and TRT,
N = exp(a cos φ + b). This script fits (a, b) of both lobes, and optionally a power of cos θd on
each, to PBRT-v4's HairBxDF (data/hair/pbrt_v4_hair.csv) on the rows with |θi|, |θo| ≤ 30°
(coordinate search on the mean relative RMS over σa), and reports the relative RMS per σa on those
rows and on the rows it did not fit (|θ| = 60°). The model here is a numpy port of
`fibre::scattering` with those terms free; with Karis's constants it reproduces `rouge bench
fibre`'s figures.

    .venv/bin/python python/fibre_fit.py
"""

from pathlib import Path

import numpy as np

ETA, TILT, BETA = 1.55, 0.035, 0.15
KARIS = (-3.65, -3.98, 17.0, -16.78, 0.0, 0.0)  # a_TT, b_TT, a_TRT, b_TRT, cos θd power TT, TRT
SIGMAS = (0.0, 0.25, 1.0, 4.0)


def load(path: Path):
    lines = [line for line in path.read_text().splitlines() if line and not line.startswith("#")]
    rows = np.array([line.split(",") for line in lines[1:]], dtype=float)
    return rows


def fresnel(c):
    f0 = ((1 - ETA) / (1 + ETA)) ** 2
    return f0 + (1 - f0) * (1 - np.clip(c, 0, 1)) ** 5


def gaussian(b, x):
    return np.exp(-0.5 * x * x / (b * b)) / (np.sqrt(2 * np.pi) * b)


def scattering(rows, p):
    """fibre::scattering for every row (tangent −x: PBRT's tilt sign), azimuthal terms `p`."""
    a_tt, b_tt, a_trt, b_trt, e_tt, e_trt = p
    sigma, t = rows[:, 0], np.array([-1.0, 0.0, 0.0])
    l = rows[:, 4:7] / np.linalg.norm(rows[:, 4:7], axis=1)[:, None]
    v = rows[:, 7:10] / np.linalg.norm(rows[:, 7:10], axis=1)[:, None]
    sl, sv = l @ t, v @ t
    ti, to = np.arcsin(np.clip(sl, -1, 1)), np.arcsin(np.clip(sv, -1, 1))
    cd = np.maximum(np.cos(0.5 * (to - ti)), 1e-3)
    lp, vp = l - np.outer(sl, t), v - np.outer(sv, t)
    cphi = np.sum(lp * vp, 1) / np.sqrt(np.sum(lp * lp, 1) * np.sum(vp * vp, 1) + 1e-4)
    chp = np.sqrt(np.clip(0.5 + 0.5 * cphi, 0, 1))
    m = lambda width, shift: gaussian(width, ti + to - shift) / cd  # noqa: E731
    r = m(BETA, -2 * TILT) * 0.25 * chp * fresnel(np.sqrt(np.clip(0.5 + 0.5 * np.sum(l * v, 1), 0, 1)))
    a = 1 / (1.19 / cd + 0.36 * cd)
    h = chp * (1 + a * (0.6 - 0.8 * cphi))
    f_tt, f_trt = fresnel(cd * np.sqrt(np.clip(1 - h * h, 0, 1))), fresnel(cd * 0.5)
    tt = (m(0.5 * BETA, TILT) * np.exp(a_tt * cphi + b_tt) * cd**e_tt * (1 - f_tt) ** 2
          * np.exp(-sigma * 2 * np.sqrt(np.clip(1 - (h * a) ** 2, 0, 1)) / cd))
    trt = (m(2 * BETA, 4 * TILT) * np.exp(a_trt * cphi + b_trt) * cd**e_trt * (1 - f_trt) ** 2 * f_trt
           * np.exp(-sigma * 3.2 / cd))
    return r + tt + trt


def relative_rms(rows, p, mask):
    q, ref = scattering(rows, p), rows[:, 10]
    return np.array([np.sqrt(((q - ref)[k] ** 2).sum() / (ref[k] ** 2).sum())
                     for k in (mask & (rows[:, 0] == s) for s in SIGMAS)])


def fit(rows, mask, free):
    """Coordinate search from Karis's terms over the parameters in `free`."""
    p, step = np.array(KARIS), np.array([0.5, 0.5, 2.0, 2.0, 1.0, 1.0])
    best = relative_rms(rows, p, mask).mean()
    for _ in range(80):
        improved = False
        for i in free:
            for d in (-1, 1):
                q = p.copy()
                q[i] += d * step[i]
                c = relative_rms(rows, q, mask).mean()
                if c < best:
                    best, p, improved = c, q, True
        if not improved:
            step *= 0.5
    return p


def main():
    rows = load(Path(__file__).resolve().parent.parent / "data" / "hair" / "pbrt_v4_hair.csv")
    train = (np.abs(rows[:, 1]) <= 30) & (np.abs(rows[:, 2]) <= 30)
    print("relative RMS per σa", SIGMAS, "on the fitted rows | on the others")
    for name, p in [("Karis 2016 (Rouge)", KARIS),
                    ("fit a, b", fit(rows, train, (0, 1, 2, 3))),
                    ("fit a, b, cos θd power", fit(rows, train, range(6)))]:
        print(f"  {name:<24} {np.round(p, 3)}: {relative_rms(rows, p, train).round(3)} | "
              f"{relative_rms(rows, p, ~train).round(3)}")


if __name__ == "__main__":
    main()
