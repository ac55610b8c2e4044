"""Recipe search and QC tolerances through the Python package, against references Rouge did not
write:

* rouge.recipe_search_KubelkaMunk recovers the recipe of a synthetic mixture of sample presets
  with measurement noise, and the CIEDE2000 it reports per illuminant agrees with colour-science
  (sd_to_XYZ by integration, XYZ_to_Lab, delta_E "CIE 2000") on the recipe's R-infinity;
* rouge.qc_pass_fail and the points of rouge.qc_tolerance_contour against colour-science's
  delta_E ("CIE 2000", "CMC", "CIE 1976"): every contour point lies at the tolerance.
"""

from __future__ import annotations

import json
import warnings

import numpy as np
import pytest

with warnings.catch_warnings():
    warnings.simplefilter("ignore")
    import colour

import rouge  # noqa: E402  (the package built from py/ by tests/run.sh)
from test_py_formulate import lab_colour  # noqa: E402

LIBRARY = ("foundation_02_ivory", "foundation_05_espresso", "blush_02_coral", "eyeshadow_02_sapphire",
           "eyeshadow_03_bronze", "lipstick_02_red", "lipstick_03_berry")


def library(repo_root):
    out = []
    for name in LIBRARY:
        p = json.loads((repo_root / "data" / "presets" / f"{name}.json").read_text())
        out.append((np.array(p["s_per_mm"]), np.array(p["k_per_mm"])))
    return out


def r_inf(S, K):
    """R-infinity of Kubelka-Munk, written out here: 1 + K/S - sqrt((K/S)^2 + 2 K/S)."""
    a = K / S
    return 1 + a - np.sqrt(a * a + 2 * a)


def test_recipe_search_recovers_a_noisy_mixture_and_its_delta_e_matches_colour(repo_root) -> None:
    lib = library(repo_root)
    truth = {"foundation_02_ivory": 0.6, "blush_02_coral": 0.25, "eyeshadow_03_bronze": 0.15}
    S = sum(a * lib[LIBRARY.index(n)][0] for n, a in truth.items())
    K = sum(a * lib[LIBRARY.index(n)][1] for n, a in truth.items())
    rng = np.random.default_rng(3)
    target = np.clip(r_inf(S, K) + rng.uniform(-0.003, 0.003, 81), 0, 1)
    recipes = rouge.recipe_search_KubelkaMunk(lib, target, 3, names=list(LIBRARY), illuminants=["D65", "A", "FL11"],
                                               top=3)
    best = recipes[0]
    assert best["names"] == list(truth), recipes
    assert np.allclose(best["amounts"], list(truth.values()), atol=0.01), best
    assert recipes[1]["objective"] > 2 * best["objective"]
    Sr = sum(a * lib[LIBRARY.index(n)][0] for n, a in zip(best["names"], best["amounts"]))
    Kr = sum(a * lib[LIBRARY.index(n)][1] for n, a in zip(best["names"], best["amounts"]))
    for i, ill in enumerate(["D65", "A", "FL11"]):
        ref = float(colour.delta_E(lab_colour(target, ill, "1931")[1], lab_colour(r_inf(Sr, Kr), ill, "1931")[1],
                                   method="CIE 2000"))
        assert best["delta_E"][i] == pytest.approx(ref, abs=0.01), ill


def test_recipe_constraints_hold_and_impossible_ones_are_named(repo_root) -> None:
    lib = library(repo_root)
    target = np.full(81, 0.35)
    recipes = rouge.recipe_search_KubelkaMunk(
        lib, target, 3, names=list(LIBRARY), illuminants=["D65"], min={"foundation_02_ivory": 0.5},
        max={"blush_02_coral": 0.1}, fixed=[("lipstick_02_red", "lipstick_03_berry", 2.0)],
        cost={"eyeshadow_03_bronze": 20.0}, top=100)
    # 7 combinations (ivory + the red:berry pair, or ivory + two of four others), one recipe per
    # set of colorants used.
    used = [frozenset(n for n, a in zip(r["names"], r["amounts"]) if a > 1e-7) for r in recipes]
    assert 0 < len(recipes) <= 7 and len(set(used)) == len(used)
    for r in recipes:
        amount = dict(zip(r["names"], r["amounts"]))
        assert amount["foundation_02_ivory"] >= 0.5 - 1e-12
        assert amount.get("blush_02_coral", 0) <= 0.1 + 1e-12
        if "lipstick_02_red" in amount:
            assert amount["lipstick_02_red"] == pytest.approx(2 * amount["lipstick_03_berry"])
        assert r["cost"] == pytest.approx(20 * amount.get("eyeshadow_03_bronze", 0))
    with pytest.raises(rouge.RougeError, match="colorant `blush_02_coral`: min 0.6 > max 0.2"):
        rouge.recipe_search_KubelkaMunk(lib, target, 2, names=list(LIBRARY), min={"blush_02_coral": 0.6},
                                        max={"blush_02_coral": 0.2})
    with pytest.raises(ValueError, match="no colorant named `nothing`"):
        rouge.recipe_search_KubelkaMunk(lib, target, 2, names=list(LIBRARY), max={"nothing": 0.2})
    with pytest.raises(ValueError, match="colorant `foundation_02_ivory` S"):
        rouge.recipe_search_KubelkaMunk([(lib[0][0][:60], lib[0][1])] + lib[1:], target, 2, names=list(LIBRARY))


@pytest.mark.parametrize("method,kw", [("CIE 2000", {}), ("CMC", dict(l=2.0, c=1.0)), ("CMC", dict(l=1.0, c=1.0)),
                                       ("CIE 1976", {})])
def test_qc_contours_and_verdicts_agree_with_colour_science(method, kw) -> None:
    standard = np.array([55.0, 18.0, 22.0])
    for plane in ("ab", "LC"):
        ring = np.array(rouge.qc_tolerance_contour(standard, 1.5, method=method, plane=plane, points=24, **kw))
        assert ring.shape == (24, 3)
        de = colour.delta_E(np.tile(standard, (24, 1)), ring, method=method, **kw)
        assert np.allclose(de, 1.5, atol=1e-8), (plane, de)
    for sample in ([55.5, 19.0, 21.0], [57.0, 15.0, 25.0]):
        got = rouge.qc_pass_fail(standard, sample, 1.5, method=method, **kw)
        ref = float(colour.delta_E(standard, np.array(sample), method=method, **kw))
        assert got["delta_E"] == pytest.approx(ref, abs=1e-9)
        assert got["pass"] == (ref <= 1.5)
    with pytest.raises(ValueError, match="method"):
        rouge.qc_pass_fail(standard, standard, 1.0, method="DIN99")
