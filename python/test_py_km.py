"""The `rouge` Python package (py/, PyO3): Kubelka-Munk through the Python API.

* the 50-digit mpmath references of data/reference/km_*.csv, and seeded random valid inputs
  against gen_km_reference's mpmath formulas, to relative 1e-9 (as the CLI is held);
* broadcasting, scalars, float64 out, spectral distributions in and out;
* Saunderson both ways, Duncan mixing against python/pigments.py (the generator of the samples);
* bad input raising KubelkaMunkError (a ValueError) naming the index and the wavelength;
* no copy of contiguous float64 inputs (numpy's allocations seen by tracemalloc).

Needs the wheel installed (tests/run.sh builds it with maturin); a missing package is a failure.
"""

from __future__ import annotations

import tracemalloc

import numpy as np
import pytest
from mpmath import mpf

import gen_km_reference as gen
import pigments
from test_km_reference import F64_MIN_NORMAL, read_reference

import rouge

REL = 1e-9


def assert_rel(got, ref, what: str, rel: float = REL) -> None:
    got = np.asarray(got, dtype=np.float64)
    ref = np.asarray([float(r) for r in np.ravel(ref)], dtype=np.float64).reshape(got.shape)
    normal = np.abs(ref) >= F64_MIN_NORMAL
    assert np.all(np.isfinite(got)), what
    err = np.abs(got[normal] - ref[normal]) / np.abs(ref[normal])
    assert err.size == 0 or err.max() <= rel, f"{what}: max relative error {err.max():.3g}"
    assert np.all(np.abs(got[~normal]) <= 1e-300), f"{what}: below-normal references must come out ~0"


def test_invert_matches_the_50_digit_references(repo_root):
    _, rows = read_reference(repo_root, "km_invert.csv")
    a = {k: np.array([float(r[k]) for r in rows]) for k in ("r_inf", "r", "rg", "thickness_mm")}
    S, K = rouge.R_to_SK_KubelkaMunk(a["r_inf"], a["r"], a["rg"], a["thickness_mm"])
    assert S.dtype == np.float64 and S.shape == (len(rows),)
    assert_rel(S, [r["s_per_mm"] for r in rows], "S")
    assert_rel(K, [r["k_per_mm"] for r in rows], "K")
    # One element at a time: the scalar path gives the same numbers as the batch.
    for i in range(0, len(rows), 7):
        s, k = rouge.R_to_SK_KubelkaMunk(a["r_inf"][i], a["r"][i], a["rg"][i], a["thickness_mm"][i])
        assert isinstance(s, float) and s == S[i] and k == K[i]


def test_forward_and_background_match_the_50_digit_references(repo_root):
    _, rows = read_reference(repo_root, "km_forward.csv")
    a = {k: np.array([float(r[k]) for r in rows]) for k in ("s_per_mm", "k_per_mm", "thickness_mm", "rg")}
    R0, T = rouge.SK_to_R0T_KubelkaMunk(a["s_per_mm"], a["k_per_mm"], a["thickness_mm"])
    assert_rel(R0, [r["r0"] for r in rows], "R0")
    assert_rel(T, [r["t"] for r in rows], "T")
    R = rouge.SK_to_R_KubelkaMunk(a["s_per_mm"], a["k_per_mm"], a["thickness_mm"], a["rg"])
    assert_rel(R, [r["r_over_rg"] for r in rows], "R over Rg")


def test_stack_matches_the_50_digit_references(repo_root):
    _, rows = read_reference(repo_root, "km_stack.csv")
    r = np.array([[float(x["r1"]) for x in rows], [float(x["r2"]) for x in rows]])
    t = np.array([[float(x["t1"]) for x in rows], [float(x["t2"]) for x in rows]])
    R, T = rouge.RT_stack_KubelkaMunk(r, t)
    assert_rel(R, [x["r12"] for x in rows], "R12")
    assert_rel(T, [x["t12"] for x in rows], "T12")


def test_random_valid_inputs_against_mpmath():
    rng = np.random.default_rng(16)
    n = 300
    r_inf = rng.uniform(0.02, 1.0, n)
    rg = rng.uniform(0.0, 1.0, n)
    frac = rng.uniform(0.01, 0.99, n)
    r = rg + frac * (r_inf - rg)
    d = 10.0 ** rng.uniform(-3, 0, n)
    keep = [gen.km_invert_valid(*v) is None for v in zip(r_inf, r, rg, d, strict=True)]
    r_inf, r, rg, d = (x[keep] for x in (r_inf, r, rg, d))
    S, K = rouge.R_to_SK_KubelkaMunk(r_inf, r, rg, d)
    ref = [gen.km_invert_mp(*map(mpf, v)) for v in zip(r_inf, r, rg, d, strict=True)]
    assert_rel(S, [x[0] for x in ref], "S")
    assert_rel(K, [x[1] for x in ref], "K")
    # Three layers: forward each with mpmath, stack with mpmath.
    s = rng.uniform(0, 50, (3, 40))
    k = rng.uniform(0, 20, (3, 40))
    x = rng.uniform(0, 0.05, (3, 40))
    R0, T = rouge.SK_to_R0T_KubelkaMunk(s, k, x)
    R, Tt = rouge.RT_stack_KubelkaMunk(R0, T, 0.3)
    for j in range(40):
        layers = [gen.km_layer_mp(mpf(s[i, j]), mpf(k[i, j]), mpf(x[i, j])) for i in range(3)]
        r12, _ = gen.stack_mp([lay[0] for lay in layers] + [mpf(0.3)], [lay[1] for lay in layers] + [mpf(0)])
        assert_rel(R[j], [r12], f"stack {j}")
    assert np.all(Tt == 0.0), "an opaque background transmits nothing"


def test_broadcasting_scalars_and_wavelength_axis():
    wl = rouge.working_wavelengths()
    assert wl.shape == (81,) and wl[0] == 380 and wl[-1] == 780
    r_inf = np.linspace(0.3, 0.8, 81)
    R = np.stack([0.5 * r_inf, 0.7 * r_inf])  # two thicknesses' worth of R over a black card
    S, K = rouge.R_to_SK_KubelkaMunk(r_inf, R, 0.0, np.array([[0.01], [0.02]]))
    assert S.shape == K.shape == (2, 81)
    back = rouge.SK_to_R_KubelkaMunk(S, K, np.array([[0.01], [0.02]]), 0.0)
    np.testing.assert_allclose(back, R, rtol=1e-12)
    with pytest.raises(ValueError, match="do not broadcast"):
        rouge.R_to_SK_KubelkaMunk(np.ones(3) * 0.5, np.ones(4) * 0.3, 0.1, 0.02)
    # Lists and integers are read as float64.
    s, k = rouge.R_to_SK_KubelkaMunk([0.5], [0.3], [0], 1)
    assert s.dtype == np.float64 and s.shape == (1,)


def test_spectral_distributions_in_and_out():
    colour = pytest.importorskip("colour")
    wl = np.arange(400, 701, 10.0)
    sd = lambda v, n: colour.SpectralDistribution(v, wl, name=n)  # noqa: E731
    r_inf, r, rg = sd(np.linspace(0.4, 0.8, wl.size), "R_inf"), sd(np.linspace(0.2, 0.5, wl.size), "R"), sd(np.full(wl.size, 0.05), "Rg")
    S, K = rouge.R_to_SK_KubelkaMunk(r_inf, r, rg, 0.02)
    assert isinstance(S, colour.SpectralDistribution) and S.name == "S"
    np.testing.assert_array_equal(S.wavelengths, wl)
    s_plain, _ = rouge.R_to_SK_KubelkaMunk(r_inf.values, r.values, rg.values, 0.02)
    np.testing.assert_array_equal(S.values, s_plain)
    msds = colour.MultiSpectralDistributions(np.stack([r.values, r.values * 1.1], axis=1), wl, labels=["a", "b"])
    R0, T = rouge.SK_to_R0T_KubelkaMunk(colour.MultiSpectralDistributions(np.stack([S.values] * 2, axis=1), wl, labels=["a", "b"]), 1.0, 0.01)
    assert isinstance(R0, colour.MultiSpectralDistributions) and list(R0.labels) == ["a", "b"]
    with pytest.raises(rouge.KubelkaMunkError) as e:
        bad = sd(np.where(wl == 550, 0.9, r.values), "R")
        rouge.R_to_SK_KubelkaMunk(r_inf, bad, rg, 0.02)
    assert e.value.wavelength == 550.0 and "at 550 nm (index (15,))" in str(e.value)
    with pytest.raises(ValueError, match="share one wavelength grid"):
        rouge.R_to_SK_KubelkaMunk(r_inf, msds.align(colour.SpectralShape(400, 700, 5)), rg, 0.02)


def test_saunderson_both_ways():
    r = np.linspace(0.0, 1.0, 101)
    internal = rouge.R_measured_to_internal_Saunderson(r, 1.5, 0.6, True)
    assert internal.min() == 0.0, "below the surface reflection K1 = 0.04 clamps to 0"
    mid = r[(r > 0.05)]
    back = rouge.R_internal_to_measured_Saunderson(rouge.R_measured_to_internal_Saunderson(mid, 1.5), 1.5)
    np.testing.assert_allclose(back, mid, rtol=1e-14)
    # Saunderson's equation at one point in exact rationals: n = 1.5 gives K1 = 1/25.
    k1, k2, ri = mpf(1) / 25, mpf("0.6"), mpf("0.5")
    rm = k1 + (1 - k1) * (1 - k2) * ri / (1 - k2 * ri)
    assert_rel(rouge.R_internal_to_measured_Saunderson(0.5, 1.5, 0.6), [rm], "R_m", rel=1e-15)
    assert rouge.R_internal_to_measured_Saunderson(0.5, K1=0.0, specular_included=False) == pytest.approx(0.4 * 0.5 / 0.7)
    with pytest.raises(rouge.KubelkaMunkError, match="K2"):
        rouge.R_measured_to_internal_Saunderson(0.5, 1.5, 1.2)
    with pytest.raises(rouge.KubelkaMunkError, match="at index \\(1,\\)"):
        rouge.R_measured_to_internal_Saunderson([0.5, np.nan])


def test_duncan_mixing_matches_the_sample_generator():
    wl = rouge.working_wavelengths()
    recipe = {"red_lake": 0.009, "goethite": 0.012, "hematite": 0.002, "tio2": 0.005, "filler": 0.05}
    recipe["binder"] = 1.0 - sum(recipe.values())  # the binder (slightly absorbing) fills the rest
    names = list(recipe)
    k = np.array([pigments.k_specific(n, wl) for n in names])
    s = np.array([pigments.s_specific(n, wl) for n in names])
    c = np.array([recipe[n] for n in names])
    S, K = rouge.SK_mix_Duncan(s, k, c)
    k_ref, s_ref = pigments.mix(recipe, wl)
    np.testing.assert_allclose(K, k_ref, rtol=1e-12, atol=1e-300)
    np.testing.assert_allclose(S, s_ref, rtol=1e-12, atol=1e-300)
    bad = c.copy()
    bad[1] = -0.5
    with pytest.raises(rouge.KubelkaMunkError, match="concentration = -0.5") as e:
        rouge.SK_mix_Duncan(s, k, bad, wavelengths=wl)
    assert e.value.index == (1, 0) and e.value.wavelength == 380.0


@pytest.mark.parametrize(
    "call, message",
    [
        (lambda: rouge.R_to_SK_KubelkaMunk(0.5, 0.7, 0.1, 0.02), "opposite sides of R∞ = 0.5"),
        (lambda: rouge.R_to_SK_KubelkaMunk(0.0, 0.0, 0.1, 0.02), "R∞ = 0 is outside (0, 1]"),
        (lambda: rouge.R_to_SK_KubelkaMunk(0.5, 0.3, 0.1, 0.0), "thickness D = 0 mm"),
        (lambda: rouge.R_to_SK_KubelkaMunk(0.5, np.nan, 0.1, 0.02), "R = NaN is outside [0, 1]"),
        (lambda: rouge.SK_to_R0T_KubelkaMunk(-1.0, 1.0, 0.01), "S = -1 must be finite and ≥ 0"),
        (lambda: rouge.SK_to_R_KubelkaMunk(1.0, 1.0, 0.01, 1.5), "Rg = 1.5 is outside [0, 1]"),
        (lambda: rouge.SK_to_Rinf_KubelkaMunk(1.0, np.inf), "K = inf must be finite"),
        (lambda: rouge.RT_stack_KubelkaMunk([[0.6], [0.1]], [[0.6], [0.1]]), "add up to more than 1"),
    ],
)
def test_bad_input_raises_kubelka_munk_error(call, message):
    with pytest.raises(rouge.KubelkaMunkError) as e:
        call()
    assert isinstance(e.value, ValueError) and isinstance(e.value, rouge.RougeError)
    assert message in str(e.value), str(e.value)


def test_error_names_index_and_wavelength():
    r_inf = np.full((2, 81), 0.5)
    r = np.full((2, 81), 0.3)
    r[1, 34] = 0.6
    with pytest.raises(rouge.KubelkaMunkError) as e:
        rouge.R_to_SK_KubelkaMunk(r_inf, r, 0.1, 0.02, wavelengths=rouge.working_wavelengths())
    assert e.value.index == (1, 34) and e.value.wavelength == 550.0
    assert str(e.value).startswith("at 550 nm (index (1, 34)): R = 0.6 and Rg = 0.1 lie on opposite sides")


def _peak_numpy_bytes(call) -> int:
    tracemalloc.start()
    try:
        tracemalloc.reset_peak()
        before = tracemalloc.get_traced_memory()[0]
        out = call()
        peak = tracemalloc.get_traced_memory()[1] - before
        del out
    finally:
        tracemalloc.stop()
    return peak


def test_no_copy_for_contiguous_float64_inputs():
    n = 1 << 20  # 8 MiB per array
    rng = np.random.default_rng(1)
    r_inf = rng.uniform(0.3, 0.9, n)
    rg = np.zeros(n)
    r = 0.5 * r_inf
    d = np.full(n, 0.02)
    mib = 8 * n
    peak = _peak_numpy_bytes(lambda: rouge.R_to_SK_KubelkaMunk(r_inf, r, rg, d))
    # Two outputs; an input copy would add at least another 8 MiB.
    assert 2 * mib <= peak < 2.5 * mib, f"peak {peak / mib:.2f} arrays"
    # The measurement can fail: a strided view is copied once, and that shows.
    big = np.empty(2 * n)
    big[::2] = r
    peak = _peak_numpy_bytes(lambda: rouge.R_to_SK_KubelkaMunk(r_inf, big[::2], rg, d))
    assert peak >= 3 * mib, f"a strided input must be copied (peak {peak / mib:.2f} arrays)"
    rows = r_inf[: 81 * 10000].reshape(10000, 81)
    peak = _peak_numpy_bytes(lambda: rouge.sd_to_XYZ(rows))
    assert peak < 0.1 * mib, f"sd_to_XYZ reads its rows in place (peak {peak / mib:.2f} arrays)"
