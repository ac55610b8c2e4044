"""Colorimetry: data/cie tables and ``rouge color`` against colour-science.

Conventions checked (what the Rust side implements):

* XYZ: plain sum on the 380..780/5 nm grid, k = 100 / sum(y_bar S), i.e.
  colour.sd_to_XYZ(..., method="Integration", shape=SpectralShape(380, 780, 5)).
* Lab relative to the perfect reflector under the same illuminant/observer:
  colour.XYZ_to_Lab(XYZ / 100, illuminant=colour.XYZ_to_xy(white / 100)).
* sRGB: D65 -> IEC matrix on XYZ / 100, no adaptation; other illuminants ->
  Bradford from the computed white (xy, Y = 1) to the sRGB whitepoint first:
  colour.XYZ_to_sRGB(XYZ / 100, illuminant=<xy>, chromatic_adaptation_transform=
  "Bradford", apply_cctf_encoding=False/True).  No clipping: colour's
  eotf_inverse_sRGB gives 12.92 L for L <= 0.0031308 (negatives included) and
  1.055 L^(1/2.4) - 0.055 above (values > 1 stay > 1).

Spectra: the 24 "ColorChecker N Ohta" spectra (tabulated 380..780/5 nm, no
alignment needed) and 1000 seeded random smooth spectra.
"""

from __future__ import annotations

import csv
import json
import warnings

import numpy as np
import pytest

with warnings.catch_warnings():
    warnings.simplefilter("ignore")
    import colour

import gen_cie

ATOL = 1e-6
SHAPE = colour.SpectralShape(380, 780, 5)
WL = np.arange(380, 781, 5)
ILLUMINANTS = gen_cie.ILLUMINANTS
OBSERVERS = {
    "1931": "CIE 1931 2 Degree Standard Observer",
    "1964": "CIE 1964 10 Degree Standard Observer",
}
COLOURCHECKER = "ColorChecker N Ohta"
N_RANDOM = 1000
SEED = 20240612


# --------------------------------------------------------------------------
# Spectra and colour-science references.


def colourchecker_spectra() -> tuple[list[str], np.ndarray]:
    cc = colour.SDS_COLOURCHECKERS[COLOURCHECKER]
    names, rows = [], []
    for name, sd in cc.items():
        assert sd.shape == SHAPE, (name, sd.shape)
        names.append(name)
        rows.append(np.asarray(sd[WL], dtype=np.float64))
    return names, np.array(rows)


def random_smooth_spectra(n: int = N_RANDOM, seed: int = SEED) -> np.ndarray:
    """Sums of 1-4 Gaussians on a baseline, clipped to [0, 1]."""
    rng = np.random.default_rng(seed)
    x = WL.astype(np.float64)
    out = np.empty((n, WL.size))
    for i in range(n):
        r = np.full(WL.size, rng.uniform(0.0, 0.6))
        for _ in range(int(rng.integers(1, 5))):
            r += rng.uniform(-0.5, 0.9) * np.exp(
                -0.5 * ((x - rng.uniform(360, 800)) / rng.uniform(10, 120)) ** 2
            )
        out[i] = np.clip(r, 0.0, 1.0)
    # A few exact edge spectra: perfect reflector, perfect absorber.
    out[0] = 1.0
    out[1] = 0.0
    return out


def reference(spectra: np.ndarray, illuminant: str, observer: str, use_sd_objects: bool):
    """colour-science XYZ, Lab, linear and encoded sRGB for rows of spectra."""
    cmfs = colour.MSDS_CMFS[OBSERVERS[observer]]
    illum = colour.SDS_ILLUMINANTS[illuminant]
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        if use_sd_objects:
            xyz = np.array(
                [
                    colour.sd_to_XYZ(
                        colour.SpectralDistribution(dict(zip(WL.tolist(), r, strict=True))),
                        cmfs,
                        illum,
                        method="Integration",
                        shape=SHAPE,
                    )
                    for r in spectra
                ]
            )
        else:
            # Array path: same alignment of cmfs/illuminant (checked below).
            xyz = colour.sd_to_XYZ(spectra, cmfs, illum, method="Integration", shape=SHAPE)
        white = colour.sd_to_XYZ(np.ones(WL.size), cmfs, illum, method="Integration", shape=SHAPE)
        assert abs(white[1] - 100.0) < 1e-12
        white_xy = colour.XYZ_to_xy(white / 100)
        lab = colour.XYZ_to_Lab(xyz / 100, illuminant=white_xy)
        src_xy = colour.models.RGB_COLOURSPACE_sRGB.whitepoint if illuminant == "D65" else white_xy
        kw = dict(illuminant=src_xy, chromatic_adaptation_transform="Bradford")
        lin = colour.XYZ_to_sRGB(xyz / 100, apply_cctf_encoding=False, **kw)
        enc = colour.XYZ_to_sRGB(xyz / 100, apply_cctf_encoding=True, **kw)
    return {"xyz": xyz, "lab": lab, "srgb_linear": lin, "srgb": enc}


def write_input_csv(path, names: list[str], spectra: np.ndarray) -> None:
    with path.open("w", newline="") as f:
        w = csv.writer(f)
        w.writerow(["wavelength_nm", *names])
        for j, wl in enumerate(WL):
            w.writerow([int(wl), *(repr(float(v)) for v in spectra[:, j])])


@pytest.fixture(scope="module")
def inputs(tmp_path_factory):
    d = tmp_path_factory.mktemp("rouge_color")
    cc_names, cc = colourchecker_spectra()
    rnd = random_smooth_spectra()
    rnd_names = [f"random_{i:04d}" for i in range(len(rnd))]
    cc_csv = d / "colourchecker_ohta.csv"
    rnd_csv = d / "random_smooth.csv"
    write_input_csv(cc_csv, cc_names, cc)
    write_input_csv(rnd_csv, rnd_names, rnd)
    return {
        "colourchecker": (cc_csv, cc_names, cc, True),
        "random": (rnd_csv, rnd_names, rnd, False),
    }


def check_output(out, names, ref, label):
    assert isinstance(out, list) and len(out) == len(names), f"{label}: expected {len(names)} objects"
    for i, (obj, name) in enumerate(zip(out, names, strict=True)):
        assert set(obj) == {"name", "xyz", "lab", "srgb_linear", "srgb"}, (label, obj.keys())
        assert obj["name"] == name, (label, i, obj["name"], name)
    worst = {}
    for key in ("xyz", "lab", "srgb_linear", "srgb"):
        got = np.array([o[key] for o in out], dtype=np.float64)
        assert got.shape == (len(names), 3), (label, key, got.shape)
        err = np.abs(got - ref[key])
        i = int(np.argmax(np.max(err, axis=1)))
        worst[key] = float(err.max())
        assert worst[key] <= ATOL, (
            f"{label} {key}: max |error| {worst[key]:.3g} > {ATOL} at sample {names[i]!r}: "
            f"got {got[i].tolist()}, colour {ref[key][i].tolist()}"
        )
    # Visible with `pytest -s`: the figures quoted in docs/BENCHMARKS.md.
    print(f"\nACCURACY {label}: " + ", ".join(f"{k} {v:.2e}" for k, v in worst.items()))
    return worst


# --------------------------------------------------------------------------
# Tables (no binary needed).


def test_cie_tables_regenerate_exactly(repo_root):
    fresh = gen_cie.render_all()
    for rel, text in fresh.items():
        assert (repo_root / rel).read_text() == text, (
            f"{rel} differs from gen_cie.py output; run .venv/bin/python python/gen_cie.py"
        )


def test_cie_tables_sum_reproduces_colour(repo_root):
    texts = {rel: (repo_root / rel).read_text() for rel in gen_cie.render_all()}
    assert gen_cie.verify(texts) < 1e-10


@pytest.mark.parametrize("observer", sorted(OBSERVERS))
@pytest.mark.parametrize("illuminant", ILLUMINANTS)
def test_cie_tables_reproduce_colour_on_all_spectra(repo_root, illuminant, observer):
    """Plain sum over data/cie + the documented conventions == colour, 1e-10."""
    _, cmfs, illum, srgb = gen_cie.load_tables()
    names, cc = colourchecker_spectra()
    spectra = np.vstack([cc, random_smooth_spectra()])
    ref = reference(spectra, illuminant, observer, use_sd_objects=False)
    xyz = gen_cie.xyz_by_sum(spectra, cmfs[observer], illum[illuminant])
    assert np.max(np.abs(xyz - ref["xyz"])) < 1e-10
    # The array path and the SpectralDistribution path agree.
    ref_sd = reference(cc, illuminant, observer, use_sd_objects=True)
    assert np.max(np.abs(ref_sd["xyz"] - ref["xyz"][: len(cc)])) < 1e-10
    # Linear sRGB for D65 is just the matrix (no adaptation).
    if illuminant == "D65":
        lin = (xyz / 100) @ srgb["xyz_to_srgb"].T
        assert np.max(np.abs(lin - ref["srgb_linear"])) < 1e-12


def test_colour_eotf_inverse_behaviour():
    """What colour does outside [0, 1] (the CLI must match it: no clipping)."""
    L = np.array([-0.5, -1e-3, 0.0, 0.0031308, 0.5, 1.0, 1.5])
    V = colour.models.eotf_inverse_sRGB(L)
    np.testing.assert_allclose(V[:2], 12.92 * L[:2], rtol=0, atol=1e-15)
    assert V[5] == pytest.approx(1.0, abs=1e-12)
    assert V[6] == pytest.approx(1.055 * 1.5 ** (1 / 2.4) - 0.055, abs=1e-15)
    assert V[6] > 1


# --------------------------------------------------------------------------
# CLI.


@pytest.mark.parametrize("observer", sorted(OBSERVERS))
@pytest.mark.parametrize("illuminant", ILLUMINANTS)
@pytest.mark.parametrize("dataset", ["colourchecker", "random"])
def test_cli_color_matches_colour(rouge, inputs, dataset, illuminant, observer):
    path, names, spectra, use_sd = inputs[dataset]
    out = rouge.json("color", str(path), f"--illuminant={illuminant}", f"--observer={observer}")
    ref = reference(spectra, illuminant, observer, use_sd_objects=use_sd)
    check_output(out, names, ref, f"{dataset} {illuminant}/{observer}")


def test_cli_color_defaults_are_d65_1931(rouge, inputs):
    path, names, spectra, use_sd = inputs["colourchecker"]
    out = rouge.json("color", str(path))
    check_output(out, names, reference(spectra, "D65", "1931", use_sd), "defaults")


def test_cli_color_output_is_json_array(rouge, inputs):
    path, names, _, _ = inputs["colourchecker"]
    p = rouge("color", str(path))
    assert p.returncode == 0, p.stderr
    assert isinstance(json.loads(p.stdout), list)
