"""The formulator's bench through the Python package and the CLI, against references Rouge did
not write:

* metamerism indices (rouge.metamerism_index_special, `rouge analyze metamerism`) against the
  same definitions (CIE 15:2018 section 9, ISO 18314-4) computed with colour-science's
  sd_to_XYZ, XYZ_to_Lab and delta_E ("CIE 1976", "CIE 2000");
* the uncertainty of S and K (rouge.SK_uncertainty) against a Monte Carlo of the printed
  inversion ([Huang2013] eq. 6-7 with arccoth, written here in numpy).
"""

from __future__ import annotations

import json
import subprocess
import warnings

import numpy as np
import pytest

with warnings.catch_warnings():
    warnings.simplefilter("ignore")
    import colour

import rouge  # noqa: E402  (the package built from py/ by tests/run.sh)

SHAPE = colour.SpectralShape(380, 780, 5)
WL = np.arange(380, 781, 5)
CMFS = {"1931": "CIE 1931 2 Degree Standard Observer", "1964": "CIE 1964 10 Degree Standard Observer"}


def lab_colour(R: np.ndarray, illuminant: str, cmfs: str) -> tuple[np.ndarray, np.ndarray]:
    """(XYZ, Lab) of a reflectance under an illuminant and observer, by colour-science."""
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        kw = dict(method="Integration", shape=SHAPE)
        c, il = colour.MSDS_CMFS[CMFS[cmfs]], colour.SDS_ILLUMINANTS[illuminant]
        sd = colour.SpectralDistribution(dict(zip(WL, R)))
        xyz = colour.sd_to_XYZ(sd, c, il, **kw)
        white = colour.sd_to_XYZ(colour.SpectralDistribution(dict(zip(WL, np.ones(81)))), c, il, **kw)
    return xyz, colour.XYZ_to_Lab(xyz / 100, colour.XYZ_to_xy(white / 100)), white


def index_colour(std, smp, ill_r, ill_t, obs_r, obs_t, correction):
    """The special metamerism index by its definition, with colour-science's pieces."""
    xyz_std_r, lab_std_r, _ = lab_colour(std, ill_r, obs_r)
    xyz_smp_r, lab_smp_r, _ = lab_colour(smp, ill_r, obs_r)
    _, lab_std_t, white_t = lab_colour(std, ill_t, obs_t)
    xyz_smp_t, lab_smp_t, _ = lab_colour(smp, ill_t, obs_t)
    if correction == "additive":
        lab_corr = lab_smp_t - (lab_smp_r - lab_std_r)
    elif correction == "multiplicative":
        lab_corr = colour.XYZ_to_Lab(xyz_smp_t * xyz_std_r / xyz_smp_r / 100, colour.XYZ_to_xy(white_t / 100))
    else:
        lab_corr = lab_smp_t
    return {m: float(colour.delta_E(lab_std_t, lab_corr, method=m)) for m in ("CIE 1976", "CIE 2000")}


def metameric_pair() -> tuple[np.ndarray, np.ndarray]:
    """A standard and a sample with the same XYZ under D65 / 1931: the sample adds a
    'metameric black' (a curve in the null space of D65's weights)."""
    std = np.asarray(colour.SDS_COLOURCHECKERS["ColorChecker N Ohta"]["light skin"][WL])
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        W = (colour.MSDS_CMFS[CMFS["1931"]][WL] * colour.SDS_ILLUMINANTS["D65"][WL][:, None]).T
    wiggle = 0.06 * np.sin(WL / 18.0)
    black = wiggle - W.T @ np.linalg.solve(W @ W.T, W @ wiggle)
    return std, np.clip(std + black, 0.0, 1.0)


PAIRS = {
    "metameric": metameric_pair,
    "two skins": lambda: tuple(
        np.asarray(colour.SDS_COLOURCHECKERS["ColorChecker N Ohta"][n][WL]) for n in ("light skin", "dark skin")
    ),
}


@pytest.mark.parametrize("pair", list(PAIRS))
@pytest.mark.parametrize("correction", ["none", "additive", "multiplicative"])
@pytest.mark.parametrize("test", [("A", "1931"), ("FL11", "1931"), ("LED-B3", "1931"), ("D65", "1964")])
def test_metamerism_index_matches_colour_science(pair, correction, test) -> None:
    std, smp = PAIRS[pair]()
    ill_t, obs_t = test
    ref = index_colour(std, smp, "D65", ill_t, "1931", obs_t, correction)
    got = rouge.metamerism_index_special(
        std, smp, illuminant_reference="D65", illuminant_test=ill_t, cmfs_test=CMFS[obs_t], correction=correction
    )
    for method in ("CIE 1976", "CIE 2000"):
        assert got[method] == pytest.approx(ref[method], abs=1e-6), (pair, correction, test, method)


def test_a_metameric_pair_needs_no_correction_and_fails_under_fl11() -> None:
    std, smp = metameric_pair()
    plain = rouge.metamerism_index_special(std, smp, illuminant_test="FL11", correction="none")
    mult = rouge.metamerism_index_special(std, smp, illuminant_test="FL11", correction="multiplicative")
    assert plain["CIE 1976"] == pytest.approx(mult["CIE 1976"], abs=1e-6)
    assert plain["CIE 2000"] > 0.5
    same = rouge.metamerism_index_special(std, smp, illuminant_test="D65", correction="none")
    assert same["CIE 1976"] < 1e-6


def test_cli_metamerism_matches_the_package(repo_root, rouge_bin, tmp_path) -> None:
    csv = tmp_path / "pair.csv"
    std, smp = metameric_pair()
    csv.write_text("wavelength_nm,standard,sample\n" + "".join(f"{w},{a!r},{b!r}\n" for w, a, b in zip(WL, std, smp)))
    out = tmp_path / "m.json"
    subprocess.run([rouge_bin, "analyze", "metamerism", f"{csv}#standard", f"{csv}#sample", "--test", "A,F11,LED-B3",
                    "--json", str(out)], check=True, capture_output=True)
    cli = json.loads(out.read_text())
    rows = {(r["illuminant"], r["correction"]): r for r in cli["illuminant"]}
    assert set(i for i, _ in rows) == {"A", "FL11", "LED-B3"}
    for (ill, corr), row in rows.items():
        py = rouge.metamerism_index_special(std, smp, illuminant_test=ill, correction=corr)
        assert row["delta_e_ab"] == pytest.approx(py["CIE 1976"], abs=1e-9)
        assert row["delta_e_2000"] == pytest.approx(py["CIE 2000"], abs=1e-9)
    obs = {r["correction"]: r for r in cli["observer"]}
    py = rouge.metamerism_index_special(std, smp, illuminant_test="D65", cmfs_test=CMFS["1964"], correction="additive")
    assert obs["additive"]["delta_e_ab"] == pytest.approx(py["CIE 1976"], abs=1e-9)
    bad = subprocess.run([rouge_bin, "analyze", "metamerism", str(csv), f"{csv}#sample"], capture_output=True, text=True)
    assert bad.returncode != 0 and "pick one" in bad.stderr and "standard, sample" in bad.stderr


def invert_printed(r_inf, r, rg, d):
    """[Huang2013] eq. 6-7 as printed (arccoth), for a background darker than the layer."""
    a = 0.5 * (1 / r_inf + r_inf)
    b = np.sqrt(a * a - 1)
    acoth = lambda u: 0.5 * np.log((u + 1) / (u - 1))  # noqa: E731
    with np.errstate(invalid="ignore", divide="ignore"):  # draws outside the domain: NaN, dropped
        s = (acoth((a - r) / b) - acoth((a - rg) / b)) / (b * d)
    return s, s * (a - 1)


@pytest.mark.parametrize("name", ["foundation_02_ivory", "lipstick_02_red", "foundation_04_caramel"])
def test_sk_uncertainty_agrees_with_a_monte_carlo_of_the_printed_inversion(repo_root, name) -> None:
    p = json.loads((repo_root / "data" / "presets" / f"{name}.json").read_text())
    m, d = p["measurement"], p["thickness_mm"]
    r_inf, r, rg = (np.array(m[k]) for k in ("r_inf", "r", "rg"))
    u_r, u_d = 0.001, 0.0002
    lin = rouge.SK_uncertainty(r_inf, r, rg, d, [u_r], u_thickness_mm=u_d)
    assert np.allclose(lin["S"], p["s_per_mm"], rtol=1e-9)
    rng = np.random.default_rng(29)
    n = 1000
    draws = [x[None, :] + u_r * rng.standard_normal((n, 81)) for x in (r_inf, r, rg)]
    s, k = invert_printed(*draws, d + u_d * rng.standard_normal((n, 1)))
    u_s, u_k = np.array(lin["u_S"]), np.array(lin["u_K"])
    rel = np.maximum(u_s / lin["S"], u_k / np.array(lin["K"]))
    ok = (rel <= 0.05) & np.all(np.isfinite(s) & np.isfinite(k), axis=0)
    assert ok.sum() >= 20, f"{name}: only {ok.sum()} wavelengths in the linear regime"
    assert np.all(np.abs(s.std(axis=0, ddof=1)[ok] / u_s[ok] - 1) <= 0.10)
    assert np.all(np.abs(k.std(axis=0, ddof=1)[ok] / u_k[ok] - 1) <= 0.10)


def test_sk_uncertainty_errors_name_the_index() -> None:
    with pytest.raises(rouge.RougeError, match="index 1"):
        rouge.SK_uncertainty([0.5, 0.5], [0.3, 0.6], [0.03, 0.03], 0.01, [0.001])
    with pytest.raises(ValueError, match="u_R"):
        rouge.SK_uncertainty([0.5, 0.5], [0.3, 0.3], [0.03, 0.03], 0.01, [0.001, 0.001, 0.001])
    best = rouge.SK_thickness_optimal(np.full(81, 20.0), np.full(81, 2.0), [0.03], [0.001], u_thickness_mm=0.001)
    assert 0.01 < best["thickness_mm"] < 0.5


def test_correct_batch_brings_a_weak_batch_back(repo_root) -> None:
    lib = [tuple(np.array(json.loads((repo_root / "data" / "presets" / f"{n}.json").read_text())[k])
                 for k in ("s_per_mm", "k_per_mm")) for n in ("foundation_01_porcelain", "foundation_04_caramel", "lipstick_02_red")]
    recipe = [0.5, 0.35, 0.15]
    S = lambda lib, c: sum(ci * l[0] for ci, l in zip(c, lib))  # noqa: E731  Duncan's rule
    K = lambda lib, c: sum(ci * l[1] for ci, l in zip(c, lib))  # noqa: E731
    weak = [(0.9 * lib[0][0], 0.9 * lib[0][1]), lib[1], lib[2]]
    standard = rouge.SK_to_Rinf_KubelkaMunk(S(lib, recipe), K(lib, recipe))
    batch = rouge.SK_to_Rinf_KubelkaMunk(S(weak, recipe), K(weak, recipe))
    fix = rouge.correct_batch_KubelkaMunk(lib, recipe, np.asarray(batch), np.asarray(standard))
    assert fix["delta_E_before"] > 0.3 and fix["delta_E_predicted"] < 0.01
    made = rouge.SK_to_Rinf_KubelkaMunk(S(weak, fix["concentrations"]), K(weak, fix["concentrations"]))
    lab = lambda r: rouge.XYZ_to_Lab(rouge.sd_to_XYZ(np.asarray(r)) / 100.0)  # noqa: E731
    assert float(colour.delta_E(lab(made), lab(standard), method="CIE 2000")) < 0.1
    with pytest.raises(ValueError, match="both skin and thickness_mm"):
        rouge.correct_batch_KubelkaMunk(lib, recipe, np.asarray(batch), np.asarray(standard), skin=np.full(81, 0.3))


@pytest.mark.parametrize("metric,method,kw", [("cmc", "CMC", dict(l=2, c=1)), ("de2000", "CIE 2000", {}),
                                              ("ab", "CIE 1976", {})])
def test_cli_qc_differences_match_colour_science(rouge_bin, tmp_path, metric, method, kw) -> None:
    out = tmp_path / "qc.json"
    subprocess.run([rouge_bin, "qc", "foundation_03_sand", "foundation_02_ivory", "foundation_04_caramel",
                    "data/skin/colorchecker_skin.csv", "--metric", metric, "--tolerance", "5", "--json", str(out)],
                   check=True, capture_output=True, cwd=str(__import__("pathlib").Path(__file__).resolve().parent.parent))
    qc = json.loads(out.read_text())
    assert len(qc["batches"]) == 4
    for b in qc["batches"]:
        ref = float(colour.delta_E(np.array(qc["standard_lab"]), np.array(b["lab"]), method=method, **kw))
        assert b["judgement"]["delta_e"] == pytest.approx(ref, abs=1e-9), b["batch"]
        assert b["judgement"]["pass"] == (ref <= 5.0)
