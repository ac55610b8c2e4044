"""Diffusion-profile references: data/reference/profiles.json.

* The file is exactly what gen_profile_reference.py generates, and generating
  twice gives the same text.
* No NaN/Infinity anywhere.
* Each quantity is recomputed by an independent double-precision route:
  Fresnel reflectance in the Snell-angle (sin/tan) form integrated with
  scipy.integrate.quad, profiles re-implemented in numpy, totals by scipy
  quadrature and (better dipole) by a closed form derived separately.
"""

from __future__ import annotations

import json
import math

import numpy as np
import pytest
from scipy.integrate import quad

import gen_profile_reference as gen


def _no_nonfinite(name):
    raise ValueError(f"non-finite constant {name} in profiles.json")


@pytest.fixture(scope="module")
def ref_text(repo_root) -> str:
    return (repo_root / "data" / "reference" / "profiles.json").read_text()


@pytest.fixture(scope="module")
def ref(ref_text) -> dict:
    return json.loads(ref_text, parse_constant=_no_nonfinite)


def media(ref):
    return {m["name"]: m for m in ref["media"]}


def rel_close(a, b, rel, abs_=0.0):
    return abs(a - b) <= max(rel * max(abs(a), abs(b)), abs_)


# ------------------------------------------------------------ regeneration
def test_regenerates_byte_identical(ref_text):
    first = gen.render()
    second = gen.render()
    assert first == second, "generator is not deterministic"
    assert first == ref_text, "data/reference/profiles.json is stale: rerun the generator"


def test_layout(ref):
    assert ref["generated_by"] == "python/gen_profile_reference.py"
    assert ref["dps"] == 50
    assert [m["name"] for m in ref["media"]] == [m[0] for m in gen.MEDIA]
    for m in ref["media"]:
        assert [p[0] for p in m["classic"]["radial"]] == gen.RADII
        assert [p[0] for p in m["better"]["radial"]] == gen.RADII
        assert [p[0] for p in m["burley"]["radial"]] == [r for r in gen.RADII if r > 0]
        for model in ("classic", "better", "burley"):
            for _, v in m[model]["radial"]:
                assert math.isfinite(v) and v >= 0.0


# ------------------------------------------------------------ (a) Fresnel
def fresnel_snell(eta: float, mu: float) -> float:
    """Same physical quantity as gen.fresnel, written with Snell angles."""
    if eta == 1.0:
        return 0.0
    ti = math.acos(min(1.0, mu))
    st = math.sin(ti) / eta
    if st >= 1.0:
        return 1.0
    tt = math.asin(st)
    if ti == 0.0:
        return ((eta - 1) / (eta + 1)) ** 2
    rs = (math.sin(ti - tt) / math.sin(ti + tt)) ** 2
    rp = (math.tan(ti - tt) / math.tan(ti + tt)) ** 2
    return 0.5 * (rs + rp)


def moment_scipy(i: int, eta: float) -> float:
    pts = [math.sqrt(1 - eta * eta)] if eta < 1 else None
    v, _ = quad(lambda m: fresnel_snell(eta, m) * m**i, 0.0, 1.0, points=pts,
                epsabs=1e-15, epsrel=1e-13, limit=200)
    return v


def test_fresnel_moments(ref):
    for m in ref["media"]:
        eta = m["eta"]
        for key, i, e in (("fm1", 1, eta), ("fm2", 2, eta),
                          ("fm1_inv", 1, 1 / eta), ("fm2_inv", 2, 1 / eta)):
            got = moment_scipy(i, e)
            assert rel_close(m[key], got, 1e-10, 1e-14), (m["name"], key, m[key], got)


def test_f_dr(ref):
    for m in ref["media"]:
        eta = m["eta"]
        assert m["f_dr_exact"] == pytest.approx(2 * m["fm1_inv"], rel=1e-15, abs=1e-300)
        poly = -1.440 / eta**2 + 0.710 / eta + 0.668 + 0.0636 * eta
        assert m["f_dr_poly"] == pytest.approx(poly, rel=1e-14)
        # Jensen's polynomial fits the INTERNAL diffuse reflectance ...
        assert abs(m["f_dr_poly"] - m["f_dr_exact"]) < 2e-3, m["name"]
        # ... and not the external one.
        if eta > 1:
            assert abs(m["f_dr_poly"] - 2 * m["fm1"]) > 0.3, m["name"]


def pbrt_fm1(e):
    if e < 1:
        return 0.45966 - 1.73965 * e + 3.37668 * e**2 - 3.904945 * e**3 + 2.49277 * e**4 - 0.68441 * e**5
    return -4.61686 + 11.1136 * e - 10.4646 * e**2 + 5.11455 * e**3 - 1.27198 * e**4 + 0.12746 * e**5


def pbrt_fm2(e):
    if e < 1:
        return 0.27614 - 0.87350 * e + 1.12077 * e**2 - 0.65095 * e**3 + 0.07883 * e**4 + 0.04860 * e**5
    r = 1 / e
    return (-547.033 + 45.3087 * r**3 - 218.725 * r**2 + 458.843 * r + 404.557 * e
            - 189.519 * e**2 + 54.9327 * e**3 - 9.00603 * e**4 + 0.63942 * e**5)


def test_pbrt_moment_fits_are_internal_moments(ref):
    """pbrt-v3 FresnelMoment{1,2}(eta) ~ our fm{1,2}_inv, the basis of better.A."""
    for m in ref["media"]:
        if m["eta"] == 1.0:
            continue
        assert abs(pbrt_fm1(m["eta"]) - m["fm1_inv"]) < 2e-3, m["name"]
        assert abs(pbrt_fm2(m["eta"]) - m["fm2_inv"]) < 2e-3, m["name"]
        assert abs(pbrt_fm1(m["eta"]) - m["fm1"]) > 0.1, m["name"]


# ------------------------------------------------------------ profiles (numpy)
def classic_np(m):
    sa, ssp = m["sigma_a_per_mm"], m["sigma_s_prime_per_mm"]
    st = sa + ssp
    alpha = ssp / st
    A = (1 + m["f_dr_poly"]) / (1 - m["f_dr_poly"])
    s = math.sqrt(3 * sa * st)
    zr = 1 / st
    zv = zr * (1 + 4 * A / 3)

    def R(r):
        dr, dv = np.hypot(r, zr), np.hypot(r, zv)
        return alpha / (4 * np.pi) * (zr * (1 + s * dr) * np.exp(-s * dr) / dr**3
                                      + zv * (1 + s * dv) * np.exp(-s * dv) / dv**3)
    return R, (zr, zv)


def better_np(m):
    sa, ssp = m["sigma_a_per_mm"], m["sigma_s_prime_per_mm"]
    st = sa + ssp
    alpha = ssp / st
    D = (2 * sa + ssp) / (3 * st**2)
    s = math.sqrt(sa / D)
    A = (1 + 3 * m["fm2_inv"]) / (1 - 2 * m["fm1_inv"])
    zr = 1 / st
    zb = 2 * A * D
    zv = -zr - 2 * zb
    cphi = 0.25 * (1 - 2 * m["fm1_inv"])
    ce = 0.5 * (1 - 3 * m["fm2_inv"])

    def R(r):
        dr, dv = np.hypot(r, zr), np.hypot(r, zv)
        phi = alpha / (4 * np.pi * D) * (np.exp(-s * dr) / dr - np.exp(-s * dv) / dv)
        E = alpha / (4 * np.pi) * (zr * (1 + s * dr) * np.exp(-s * dr) / dr**3
                                   - zv * (1 + s * dv) * np.exp(-s * dv) / dv**3)
        return cphi * phi + ce * E

    def R_quad(r):
        # as R, with e^{-s dr}/dr - e^{-s dv}/dv rewritten without cancellation
        # (needed for the 1/r^2 tail of the non-absorbing medium in binary64)
        dr, dv = np.hypot(r, zr), np.hypot(r, zv)
        delta = (zv * zv - zr * zr) / (dv + dr)
        phi = alpha / (4 * np.pi * D) * np.exp(-s * dr) * (delta - dr * np.expm1(-s * delta)) / (dr * dv)
        E = alpha / (4 * np.pi) * (zr * (1 + s * dr) * np.exp(-s * dr) / dr**3
                                   - zv * (1 + s * dv) * np.exp(-s * dv) / dv**3)
        return cphi * phi + ce * E

    # Closed form: int_0^inf e^{-s d}/d r dr = e^{-s z}/s and
    # int_0^inf z(1+s d)e^{-s d}/d^3 r dr = sign(z) e^{-s|z|}, with d = sqrt(r^2+z^2).
    a, b = zr, -zv
    diff = (b - a) if s == 0 else (math.exp(-s * a) - math.exp(-s * b)) / s
    total = 0.5 * alpha * (cphi / D * diff + ce * (math.exp(-s * a) + math.exp(-s * b)))
    return R, R_quad, (zr, -zv), A, total


def burley_np(m):
    st = m["sigma_a_per_mm"] + m["sigma_s_prime_per_mm"]
    A = m["better"]["total"]
    s = st * (1.85 - A + 7 * abs(A - 0.8) ** 3)

    def R(r):
        return A * s * (np.exp(-s * r) + np.exp(-s * r / 3)) / (8 * np.pi * r)
    return R, (1 / s, 3 / s), s


def total_scipy(R, scales):
    """2 pi int_0^inf R(r) r dr in pieces [0, a/4, a, 4a, ..., big, inf)."""
    lo, hi = min(scales) / 4, max(scales) * 4**12
    edges = [0.0] + list(np.geomspace(lo, hi, 15))
    tot = 0.0
    for a, b in zip(edges[:-1], edges[1:]):
        v, _ = quad(lambda r: float(R(r)) * r, a, b, epsabs=0.0, epsrel=1e-12, limit=200)
        tot += v
    # tail [hi, inf) as hi^2 int_1^inf R(hi x) x dx (QUADPACK's qagi needs O(1) scale)
    v, _ = quad(lambda x: float(R(hi * x)) * x, 1.0, math.inf, epsabs=0.0, epsrel=1e-12, limit=200)
    tot += hi * hi * v
    return 2 * math.pi * tot


def check_radial(name, R, radial, rel):
    for r, v in radial:
        got = float(R(r))
        if v < 1e-290:  # below binary64 normal range (or 0): only require tiny
            assert got < 1e-280, (name, r, v, got)
        else:
            assert rel_close(v, got, rel), (name, r, v, got)


def test_classic(ref):
    for m in ref["media"]:
        c = m["classic"]
        R, scales = classic_np(m)
        check_radial(m["name"], R, c["radial"], 1e-12)
        assert rel_close(c["total_quad"], c["total_closed"], 4e-16), m["name"]
        assert rel_close(total_scipy(R, scales), c["total_closed"], 1e-9), m["name"]


def test_better(ref):
    for m in ref["media"]:
        b = m["better"]
        R, R_quad, scales, A, closed = better_np(m)
        assert rel_close(b["A"], A, 1e-14), m["name"]
        check_radial(m["name"], R, b["radial"], 1e-9)  # naive phi difference in binary64
        check_radial(m["name"], R_quad, b["radial"], 1e-12)
        assert rel_close(b["total"], b["total_closed"], 4e-16), m["name"]
        assert rel_close(b["total"], closed, 1e-12), m["name"]
        assert rel_close(total_scipy(R_quad, scales), b["total"], 1e-9), m["name"]


def test_burley(ref):
    for m in ref["media"]:
        u = m["burley"]
        R, scales, s = burley_np(m)
        assert rel_close(u["s_per_mm"], s, 1e-14), m["name"]
        check_radial(m["name"], R, u["radial"], 1e-12)
        assert u["total"] == m["better"]["total"], m["name"]
        assert rel_close(total_scipy(R, scales), u["total"], 1e-10), m["name"]


def test_physical_limits(ref):
    ms = media(ref)
    # no absorption: everything that enters comes back out
    assert ms["non_absorbing"]["classic"]["total_closed"] == 1.0
    assert ms["non_absorbing"]["better"]["total"] == pytest.approx(1.0, abs=1e-15)
    # index-matched boundary reflects nothing: A = 1
    im = ms["index_matched"]
    assert im["fm1"] == im["fm2"] == im["fm1_inv"] == im["fm2_inv"] == 0.0
    assert im["better"]["A"] == 1.0
    for m in ref["media"]:
        # the better dipole's total is close to the classic one (same physics)
        assert abs(m["better"]["total"] - m["classic"]["total_closed"]) < 0.04, m["name"]
