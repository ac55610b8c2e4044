#!/usr/bin/env python3
"""High-precision Kubelka-Munk references for the Rust side.

Writes data/reference/km_invert.csv, km_forward.csv and km_stack.csv.
Inputs are Python floats written with repr() (exact binary64 values); every
reference is computed with mpmath at 60 significant digits from mpf(input)
and written with 30 significant digits.

Notation (per unit thickness; X = D = layer thickness in mm, S, K in 1/mm):

    a = 1 + K/S,   b = sqrt(a^2 - 1),   R_inf = a - b,   1/R_inf = a + b
    so a = (1/R_inf + R_inf)/2,  b = (1/R_inf - R_inf)/2,  K/S = (1 - R_inf)^2 / (2 R_inf)

Forward (layer over an ideal black background / transmittance):

    R0 = sinh(bSX) / (a sinh(bSX) + b cosh(bSX))
    T  = b         / (a sinh(bSX) + b cosh(bSX))
    limits: K = 0: R0 = SX/(1+SX), T = 1/(1+SX);  S = 0: R0 = 0, T = exp(-KX)

Layer over a background of reflectance Rg (Kubelka):

    R = (1 - Rg (a - b coth(bSX))) / (a - Rg + b coth(bSX))
      = R0 + T^2 Rg / (1 - R0 Rg)                      (both checked below)

Inversion (the arcoth form of Kubelka's solution, written as a log):

    S D = 1/(2b) ln[ (1/R_inf - R)(Rg - R_inf) / ((1/R_inf - Rg)(R - R_inf)) ]
        = log1p(2b y) / (2b),   y = (Rg - R) / ((1/R_inf - Rg)(R - R_inf))
    K   = S (a - 1) = S (1 - R_inf)^2 / (2 R_inf)
    R_inf == 1 (K = 0):  S D = (R - Rg) / ((1 - R)(1 - Rg))
    R == Rg:  S = K = 0.
    Valid iff 0 < R_inf <= 1 and R lies in [Rg, R_inf) (or (R_inf, Rg]).

Two layers (top 1 over 2, symmetric layers), from the geometric series of
inter-reflections T1 R2 T1 sum (R1 R2)^n:

    R12 = R1 + T1^2 R2 / (1 - R1 R2),   T12 = T1 T2 / (1 - R1 R2)

Run: ``.venv/bin/python python/gen_km_reference.py``.
"""

from __future__ import annotations

import sys
from pathlib import Path

import mpmath
from mpmath import mp, mpf

REPO = Path(__file__).resolve().parent.parent
OUT_DIR = REPO / "data" / "reference"

DPS = 60  # working precision, significant decimal digits
DIGITS = 30  # significant digits written


def fmt(x) -> str:
    """30 significant digits; exact zero as 0.0."""
    x = mpf(x)
    if x == 0:
        return "0.0"
    return mpmath.nstr(x, DIGITS)


def _in(x: float) -> str:
    x = float(x)
    return repr(x)


# --------------------------------------------------------------------------
# Kubelka-Munk in mpmath (callers must run under mp.workdps(DPS)).


def km_layer_mp(s, k, x):
    """(R0, T) of a layer with S, K (per mm) and thickness x (mm)."""
    s, k, x = mpf(s), mpf(k), mpf(x)
    if s < 0 or k < 0 or x < 0:
        raise ValueError("negative S, K or thickness")
    if s == 0:
        return mpf(0), mpmath.exp(-k * x)
    if k == 0:
        sx = s * x
        return sx / (1 + sx), 1 / (1 + sx)
    a = 1 + k / s
    b = mpmath.sqrt(a * a - 1)
    z = b * s * x
    # exp(-2z) form: no overflow of sinh/cosh; mpmath exponents are unbounded.
    e2 = mpmath.exp(-2 * z)
    den = a * (1 - e2) + b * (1 + e2)
    return (1 - e2) / den, 2 * b * mpmath.exp(-z) / den


def km_layer_sinh_mp(s, k, x):
    """Literal eq. 1-2 (sinh/cosh), for cross-checking km_layer_mp."""
    s, k, x = mpf(s), mpf(k), mpf(x)
    a = 1 + k / s
    b = mpmath.sqrt(a * a - 1)
    z = b * s * x
    den = a * mpmath.sinh(z) + b * mpmath.cosh(z)
    return mpmath.sinh(z) / den, b / den


def over_background_mp(r0, t, rg):
    r0, t, rg = mpf(r0), mpf(t), mpf(rg)
    return r0 + t * t * rg / (1 - r0 * rg)


def over_background_coth_mp(s, k, x, rg):
    """Kubelka's hyperbolic form R = (1 - Rg(a - b coth)) / (a - Rg + b coth)."""
    s, k, x, rg = mpf(s), mpf(k), mpf(x), mpf(rg)
    a = 1 + k / s
    b = mpmath.sqrt(a * a - 1)
    c = mpmath.coth(b * s * x)
    return (1 - rg * (a - b * c)) / (a - rg + b * c)


def km_invert_valid(r_inf, r, rg, d) -> str | None:
    """None when the inputs are valid, else the reason."""
    r_inf, r, rg, d = mpf(r_inf), mpf(r), mpf(rg), mpf(d)
    if not (0 < r_inf <= 1):
        return "R_inf must be in (0, 1]"
    if not (0 <= r <= 1 and 0 <= rg <= 1):
        return "R and Rg must be in [0, 1]"
    if not d > 0:
        return "thickness must be > 0"
    if r == rg:
        return None
    if r == r_inf:
        return "R == R_inf needs an infinitely thick layer"
    if not (min(rg, r_inf) <= r <= max(rg, r_inf)):
        return "R must lie between Rg and R_inf"
    return None


def km_invert_mp(r_inf, r, rg, d):
    """(S, K) per mm from R_inf, R over Rg and thickness d (mm)."""
    why = km_invert_valid(r_inf, r, rg, d)
    if why is not None:
        raise ValueError(why)
    r_inf, r, rg, d = mpf(r_inf), mpf(r), mpf(rg), mpf(d)
    if r == rg:
        return mpf(0), mpf(0)
    if r_inf == 1:
        return (r - rg) / ((1 - r) * (1 - rg)) / d, mpf(0)
    u = 1 / r_inf
    a = (u + r_inf) / 2
    b = (u - r_inf) / 2
    arg = (u - r) * (rg - r_inf) / ((u - rg) * (r - r_inf))
    sd = mpmath.log(arg) / (2 * b)
    s = sd / d
    return s, s * (a - 1)


def stack2_mp(r1, t1, r2, t2):
    r1, t1, r2, t2 = mpf(r1), mpf(t1), mpf(r2), mpf(t2)
    den = 1 - r1 * r2
    return r1 + t1 * t1 * r2 / den, t1 * t2 / den


def stack_mp(rs, ts):
    """Top layer first; fold from the bottom (the reflectance of a sub-stack
    seen from above is what the layer on top of it needs)."""
    r, t = mpf(rs[-1]), mpf(ts[-1])
    for ri, ti in zip(reversed(rs[:-1]), reversed(ts[:-1]), strict=True):
        r, t = stack2_mp(ri, ti, r, t)
    return r, t


def stack_series_mp(r1, t1, r2, t2, terms=4000):
    """Explicit sum of the inter-reflection series (derivation check)."""
    r1, t1, r2, t2 = mpf(r1), mpf(t1), mpf(r2), mpf(t2)
    rr = mpf(0)
    tt = mpf(0)
    p = mpf(1)
    for _ in range(terms):
        rr += t1 * r2 * t1 * p  # down through 1, off 2, back up through 1
        tt += t1 * t2 * p  # down through 1 and 2
        p *= r1 * r2
    return r1 + rr, tt


# --------------------------------------------------------------------------
# Cases (all inputs are Python floats).


def invert_cases() -> list[tuple[str, float, float, float, float]]:
    """(case, r_inf, r, rg, thickness_mm)."""
    c: list[tuple[str, float, float, float, float]] = []
    # Ordinary: black backgrounds (R, Rg below R_inf) and white backgrounds
    # (Rg > R > R_inf, or both below for the lightest layer).
    for r_inf in (0.2, 0.35, 0.5, 0.65, 0.8, 0.9):
        for tag, rg in (("black03", 0.03), ("black05", 0.05), ("white80", 0.8), ("white90", 0.9)):
            if rg == r_inf:
                continue
            r = rg + 0.6 * (r_inf - rg)
            c.append((f"ordinary_rinf{r_inf}_{tag}", r_inf, r, rg, 0.05))
    c.append(("ordinary_ideal_black_bg", 0.5, 0.3, 0.0, 0.05))
    c.append(("ordinary_ideal_black_bg_thin", 0.7, 0.01, 0.0, 0.001))
    c.append(("ordinary_white_bg_one", 0.4, 0.8, 1.0, 0.2))
    # Background lighter than the layer: Rg > R > R_inf.
    c.append(("bg_lighter_powder", 0.3, 0.55, 0.85, 0.03))
    c.append(("bg_lighter_dark_layer", 0.05, 0.2, 0.9, 0.01))
    c.append(("bg_lighter_close", 0.8, 0.82, 0.9, 0.1))
    # R_inf -> 1 and exactly 1 (K = 0).
    for tag, r_inf in (("1e-3", 1 - 1e-3), ("1e-6", 1 - 1e-6), ("1e-9", 1 - 1e-9), ("1e-12", 1 - 1e-12), ("0", 1.0)):
        c.append((f"rinf_one_minus_{tag}_black", r_inf, 0.5, 0.04, 0.05))
        c.append((f"rinf_one_minus_{tag}_white", r_inf, 0.9, 0.85, 0.05))
        c.append((f"rinf_one_minus_{tag}_bright", r_inf, 0.99, 0.2, 1.0))
    # Small R_inf.
    for tag, r_inf in (("1e-2", 1e-2), ("1e-4", 1e-4), ("1e-6", 1e-6)):
        c.append((f"rinf_small_{tag}_black", r_inf, 0.5 * r_inf, 0.0, 0.05))
        c.append((f"rinf_small_{tag}_grey", r_inf, 0.02, 0.04, 0.05))
        c.append((f"rinf_small_{tag}_white", r_inf, 0.3, 0.85, 0.05))
    # R very close to Rg (very thin layer).
    for tag, g in (("1e-3", 1e-3), ("1e-6", 1e-6), ("1e-9", 1e-9), ("1e-12", 1e-12)):
        c.append((f"r_near_rg_{tag}_black", 0.6, 0.04 * (1 + g), 0.04, 0.05))
        c.append((f"r_near_rg_{tag}_white", 0.6, 0.85 * (1 - g), 0.85, 0.05))
    # R very close to R_inf (thick layer).
    for tag, g in (("1e-3", 1e-3), ("1e-6", 1e-6), ("1e-9", 1e-9), ("1e-12", 1e-12)):
        c.append((f"r_near_rinf_{tag}_black", 0.6, 0.6 * (1 - g), 0.04, 0.05))
        c.append((f"r_near_rinf_{tag}_white", 0.6, 0.6 * (1 + g), 0.85, 0.05))
    # Tiny and huge thickness.
    for tag, d in (("1e-6", 1e-6), ("1e3", 1e3)):
        c.append((f"thickness_{tag}_black", 0.5, 0.3, 0.04, d))
        c.append((f"thickness_{tag}_white", 0.5, 0.7, 0.85, d))
    # R == Rg exactly: S = K = 0.
    c.append(("r_eq_rg_black", 0.5, 0.04, 0.04, 0.05))
    c.append(("r_eq_rg_white", 0.3, 0.85, 0.85, 0.05))
    c.append(("r_eq_rg_rinf_one", 1.0, 0.5, 0.5, 0.05))
    return c


def forward_cases() -> list[tuple[str, float, float, float, float]]:
    """(case, s_per_mm, k_per_mm, thickness_mm, rg)."""
    c: list[tuple[str, float, float, float, float]] = []
    ordinary = [(10.0, 1.0, 0.05), (50.0, 0.5, 0.02), (2.0, 3.0, 0.1), (100.0, 10.0, 0.5), (0.5, 0.05, 1.0), (20.0, 20.0, 0.03)]
    for i, (s, k, x) in enumerate(ordinary):
        for tag, rg in (("black", 0.04), ("white", 0.85), ("ideal_black", 0.0)):
            c.append((f"ordinary{i}_{tag}", s, k, x, rg))
    c.append(("ordinary_rg_one", 10.0, 1.0, 0.05, 1.0))
    c += [
        ("k_zero", 10.0, 0.0, 0.05, 0.04),
        ("k_zero_thick", 1e3, 0.0, 1.0, 0.5),
        ("k_zero_rg_one", 10.0, 0.0, 0.05, 1.0),
        ("s_zero", 0.0, 2.0, 0.1, 0.5),
        ("s_zero_thick", 0.0, 1e3, 1.0, 0.5),
        ("s_zero_k_zero", 0.0, 0.0, 0.1, 0.5),
        ("s_zero_k_zero_rg_one", 0.0, 0.0, 0.1, 1.0),
    ]
    for tag, sx in (("1e-12", 1e-12), ("1e-9", 1e-9), ("1e-6", 1e-6)):
        c.append((f"sx_tiny_{tag}_k_lt_s", sx, 0.1 * sx, 1.0, 0.5))
        c.append((f"sx_tiny_{tag}_k_gt_s", sx, 10 * sx, 1.0, 0.5))
        c.append((f"sx_tiny_{tag}_thin", 10.0, 1.0, sx / 10, 0.04))
    for tag, sx in (("1e3", 1e3), ("1e6", 1e6), ("1e100", 1e100), ("1e300", 1e300)):
        c.append((f"sx_huge_{tag}", sx, 0.1 * sx, 1.0, 0.5))
        c.append((f"sx_huge_{tag}_k_eq_s", sx, sx, 1.0, 0.04))
        c.append((f"sx_huge_{tag}_thick", 10.0, 1.0, sx / 10, 0.85))
        c.append((f"kx_huge_{tag}_s_zero", 0.0, sx, 1.0, 0.5))
        c.append((f"sx_huge_{tag}_k_zero", sx, 0.0, 1.0, 0.5))
    # S*X beyond the f64 range (product overflows when formed in f64).
    c.append(("sx_overflow_f64", 1e200, 1e199, 1e200, 0.5))
    for tag, ratio in (("1e2", 1e2), ("1e4", 1e4), ("1e8", 1e8), ("1e12", 1e12)):
        c.append((f"k_gg_s_{tag}", 1.0 / ratio, 1.0, 0.1, 0.5))
        c.append((f"s_gg_k_{tag}", 1.0, 1.0 / ratio, 0.1, 0.5))
    c.append(("s_gg_k_thick", 1e4, 1e-6, 10.0, 0.04))
    c.append(("k_gg_s_thin", 1e-6, 1e4, 1e-4, 0.85))
    return c


def stack_cases() -> list[tuple[str, float, float, float, float]]:
    """(case, r1, t1, r2, t2)."""
    c: list[tuple[str, float, float, float, float]] = [
        ("ordinary_a", 0.3, 0.5, 0.4, 0.4),
        ("ordinary_b", 0.05, 0.9, 0.6, 0.2),
        ("ordinary_c", 0.7, 0.2, 0.1, 0.85),
        ("ordinary_d", 0.45, 0.45, 0.45, 0.45),
        ("top_transparent", 0.0, 1.0, 0.5, 0.3),
        ("top_opaque", 0.6, 0.0, 0.5, 0.3),
        ("bottom_black_opaque", 0.3, 0.5, 0.0, 0.0),
        ("bottom_transparent", 0.3, 0.5, 0.0, 1.0),
        ("top_mirror", 1.0, 0.0, 0.5, 0.3),
        ("bottom_mirror", 0.3, 0.5, 1.0, 0.0),
        ("both_lossless", 0.25, 0.75, 0.6, 0.4),
    ]
    for tag, g in (("1e-3", 1e-3), ("1e-6", 1e-6), ("1e-9", 1e-9), ("1e-12", 1e-12)):
        c.append((f"r1r2_to_one_{tag}", 1 - g, 0.5 * g, 1 - g, 0.5 * g))
        c.append((f"r1r2_to_one_{tag}_asym", 1 - g, 0.1 * g, 1 - 2 * g, g))
        c.append((f"r1r2_to_one_{tag}_bottom_mirror", 1 - g, 0.5 * g, 1.0, 0.0))
    # Pairs of real KM layers (R0, T rounded to f64).
    with mp.workdps(DPS):
        for i, ((s1, k1, x1), (s2, k2, x2)) in enumerate(
            [((10.0, 1.0, 0.05), (50.0, 0.5, 0.02)), ((2.0, 3.0, 0.1), (100.0, 10.0, 0.5)), ((500.0, 0.01, 0.2), (400.0, 0.02, 0.3))]
        ):
            r1, t1 = (float(v) for v in km_layer_mp(s1, k1, x1))
            r2, t2 = (float(v) for v in km_layer_mp(s2, k2, x2))
            c.append((f"km_layers_{i}", r1, t1, r2, t2))
    return c


# --------------------------------------------------------------------------
# Rendering.


def _header(title: str, columns: str, extra: list[str]) -> list[str]:
    return [
        f"# {title}",
        f"# Generated by python/gen_km_reference.py with mpmath {mpmath.__version__} "
        f"(mp.dps = {DPS}); results printed with {DIGITS} significant digits. Do not edit.",
        "# Inputs are Python floats written with repr() (exact binary64 values); references are "
        "computed from mpf(input), i.e. from the exact binary64 inputs.",
        *extra,
        columns,
    ]


def render_invert_csv() -> str:
    lines = _header(
        "Kubelka-Munk inversion: S and K (per mm) from R_inf, R over background Rg, thickness.",
        "case,r_inf,r,rg,thickness_mm,s_per_mm,k_per_mm",
        [
            "# S*D = ln[(1/R_inf - R)(Rg - R_inf) / ((1/R_inf - Rg)(R - R_inf))] / (1/R_inf - R_inf); "
            "K = S (1 - R_inf)^2 / (2 R_inf); R_inf == 1: S*D = (R - Rg)/((1 - R)(1 - Rg)), K = 0; "
            "R == Rg: S = K = 0.",
            "# Each row round-trips through the forward model R = R0 + T^2 Rg/(1 - R0 Rg) in mpmath.",
        ],
    )
    with mp.workdps(DPS):
        for case, r_inf, r, rg, d in invert_cases():
            s, k = km_invert_mp(r_inf, r, rg, d)
            lines.append(f"{case},{_in(r_inf)},{_in(r)},{_in(rg)},{_in(d)},{fmt(s)},{fmt(k)}")
    return "\n".join(lines) + "\n"


def render_forward_csv() -> str:
    lines = _header(
        "Kubelka-Munk forward model: one layer (S, K per mm, thickness mm).",
        "case,s_per_mm,k_per_mm,thickness_mm,rg,r0,t,r_over_rg",
        [
            "# r0 = R over an ideal black background = sinh(bSX)/(a sinh(bSX) + b cosh(bSX)); "
            "t = b/(a sinh(bSX) + b cosh(bSX)); a = 1 + K/S, b = sqrt(a^2 - 1); "
            "K = 0: r0 = SX/(1+SX), t = 1/(1+SX); S = 0: r0 = 0, t = exp(-KX).",
            "# r_over_rg = r0 + t^2 rg/(1 - r0 rg). Values far below the binary64 range (t for huge "
            "S*X) are printed exactly anyway; compare relatively only where the reference is a "
            "normal binary64.",
        ],
    )
    with mp.workdps(DPS):
        for case, s, k, x, rg in forward_cases():
            r0, t = km_layer_mp(s, k, x)
            r = over_background_mp(r0, t, rg)
            lines.append(
                f"{case},{_in(s)},{_in(k)},{_in(x)},{_in(rg)},{fmt(r0)},{fmt(t)},{fmt(r)}"
            )
    return "\n".join(lines) + "\n"


def render_stack_csv() -> str:
    lines = _header(
        "Two symmetric layers, layer 1 on top of layer 2.",
        "case,r1,t1,r2,t2,r12,t12",
        [
            "# r12 = r1 + t1^2 r2/(1 - r1 r2); t12 = t1 t2/(1 - r1 r2) (sum of the inter-reflection "
            "series t1 r2 t1 (r1 r2)^n; the numerator is t1^2 r2, not t1 r1 t1).",
        ],
    )
    with mp.workdps(DPS):
        for case, r1, t1, r2, t2 in stack_cases():
            r12, t12 = stack2_mp(r1, t1, r2, t2)
            lines.append(
                f"{case},{_in(r1)},{_in(t1)},{_in(r2)},{_in(t2)},{fmt(r12)},{fmt(t12)}"
            )
    return "\n".join(lines) + "\n"


def render_all() -> dict[str, str]:
    return {
        "data/reference/km_invert.csv": render_invert_csv(),
        "data/reference/km_forward.csv": render_forward_csv(),
        "data/reference/km_stack.csv": render_stack_csv(),
    }


# --------------------------------------------------------------------------
# Self-checks.


def _rel(a, b):
    a, b = mpf(a), mpf(b)
    if a == b:
        return mpf(0)
    return abs(a - b) / max(abs(a), abs(b))


def self_check() -> dict[str, float]:
    """Assert the identities the references rely on; return worst errors."""
    worst = {"invert_roundtrip": 0.0, "forward_forms": 0.0, "limits": 0.0, "stack_series": 0.0}
    with mp.workdps(DPS):
        tol = mpf(10) ** (-40)
        # invert(forward) and forward(invert).
        for case, r_inf, r, rg, d in invert_cases():
            s, k = km_invert_mp(r_inf, r, rg, d)
            r0, t = km_layer_mp(s, k, d)
            back = over_background_mp(r0, t, rg)
            e = _rel(back, r)
            assert e < tol, (case, e)
            worst["invert_roundtrip"] = max(worst["invert_roundtrip"], float(e))
            if r_inf < 1 and r != rg:
                # Cancellation-free form of the log argument (what an f64
                # implementation should use, with log1p):
                #   arg - 1 = 2b (Rg - R) / ((1/R_inf - Rg)(R - R_inf))
                # and S D = log1p(2b y)/(2b) -> y = (R-Rg)/((1-R)(1-Rg)) as b -> 0.
                u, ri, rr, gg = 1 / mpf(r_inf), mpf(r_inf), mpf(r), mpf(rg)
                b = (u - ri) / 2
                arg = (u - rr) * (gg - ri) / ((u - gg) * (rr - ri))
                y = (gg - rr) / ((u - gg) * (rr - ri))
                e3 = _rel(arg - 1, 2 * b * y)
                assert e3 < mpf(10) ** (-30), (case, e3)
                e3 = _rel(mpmath.log1p(2 * b * y) / (2 * b) / mpf(d), s)
                assert e3 < mpf(10) ** (-30), (case, e3)
            if s > 0 and k > 0:
                # R_inf implied by K/S.
                a = 1 + k / s
                e2 = _rel(a - mpmath.sqrt(a * a - 1), r_inf)
                assert e2 < tol, (case, e2)
        for case, s, k, x, rg in forward_cases():
            r0, t = km_layer_mp(s, k, x)
            assert 0 <= r0 <= 1 and 0 <= t <= 1 and r0 + t <= 1 + tol, case
            if s > 0 and k > 0 and s * x < 1e6:
                r0b, tb = km_layer_sinh_mp(s, k, x)
                e = max(_rel(r0, r0b), _rel(t, tb))
                rb = over_background_coth_mp(s, k, x, rg)
                e = max(e, _rel(over_background_mp(r0, t, rg), rb))
                assert e < tol, (case, e)
                worst["forward_forms"] = max(worst["forward_forms"], float(e))
                # forward -> invert round trip (when R is distinguishable).
                r = over_background_mp(r0, t, rg)
                r_inf = a_minus_b(s, k)
                if r != rg and abs(r - r_inf) > mpf(10) ** (-50):
                    s2, k2 = km_invert_mp(r_inf, r, rg, x)
                    e = max(_rel(s2, s), _rel(k2, k))
                    assert e < mpf(10) ** (-30), (case, e)
        # Limits: K -> 0 and S -> 0 agree with the closed forms; R_inf -> 1.
        for s, x in ((10, mpf("0.05")), (mpf("0.3"), 2)):
            k = mpf(10) ** (-45)
            e = max(_rel(a, b) for a, b in zip(km_layer_mp(s, k, x), km_layer_mp(s, 0, x), strict=True))
            assert e < mpf(10) ** (-35), e
            worst["limits"] = max(worst["limits"], float(e))
            r0, t = km_layer_mp(mpf(10) ** (-45), s, x)
            assert abs(r0) < mpf(10) ** (-40) and _rel(t, mpmath.exp(-s * x)) < mpf(10) ** (-35)
        with mp.workdps(2 * DPS):  # the log form loses ~40 digits at b ~ 1e-40
            for r, rg in ((mpf("0.5"), mpf("0.04")), (mpf("0.9"), mpf("0.85"))):
                s_lim, _ = km_invert_mp(1, r, rg, 1)
                s_eps, k_eps = km_invert_mp(1 - mpf(10) ** (-40), r, rg, 1)
                e = _rel(s_lim, s_eps)
                assert e < mpf(10) ** (-35) and k_eps < mpf(10) ** (-70), e
                worst["limits"] = max(worst["limits"], float(e))
        # Stack: closed form == explicit series (R1 R2 bounded away from 1).
        for case, r1, t1, r2, t2 in stack_cases():
            if r1 * r2 < 0.9:
                a = stack2_mp(r1, t1, r2, t2)
                b = stack_series_mp(r1, t1, r2, t2)
                e = max(abs(a[0] - b[0]), abs(a[1] - b[1]))
                assert e < tol, (case, e)
                worst["stack_series"] = max(worst["stack_series"], float(e))
        # Stacking two halves of a KM layer gives the whole layer.
        for s, k, x in ((10, 1, mpf("0.05")), (2, 3, mpf("0.1"))):
            h = km_layer_mp(s, k, x / 2)
            whole = km_layer_mp(s, k, x)
            e = max(_rel(u, v) for u, v in zip(stack2_mp(*h, *h), whole, strict=True))
            assert e < tol, e
    return worst


def a_minus_b(s, k):
    a = 1 + mpf(k) / mpf(s)
    return a - mpmath.sqrt(a * a - 1)


def main() -> int:
    worst = self_check()
    texts = render_all()
    OUT_DIR.mkdir(parents=True, exist_ok=True)
    for rel, text in texts.items():
        (REPO / rel).write_text(text)
        n = sum(1 for ln in text.splitlines() if ln and not ln.startswith("#")) - 1
        print(f"wrote {rel} ({n} rows)")
    print("self-check worst relative errors:", {k: f"{v:.2g}" for k, v in worst.items()})
    return 0


if __name__ == "__main__":
    sys.exit(main())
