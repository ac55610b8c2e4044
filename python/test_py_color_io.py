"""The `rouge` Python package: colorimetry against colour-science, measurement import, presets.

* sd_to_XYZ / XYZ_to_Lab / XYZ_to_sRGB / delta_E_CIE2000 agree with colour-science 0.4.7 to 1e-6
  for every illuminant and observer, on the ColorChecker N Ohta and 1000 random spectra, from
  arrays and from SpectralDistribution / MultiSpectralDistributions;
* every format `rouge import` reads, through read_measurement, gives the preset the CLI writes
  (byte for byte), and a preset saved from Python loads back equal;
* every bad file raises MeasurementImportError with the CLI's message, file, line and column;
* `rouge color` and read_spectra read colour-science's own CSV files, in both layouts.
"""

from __future__ import annotations

import warnings
from pathlib import Path

import numpy as np
import pytest

import test_colorimetry as tc

import rouge

with warnings.catch_warnings():
    warnings.simplefilter("ignore")
    import colour

COLOUR_IO = Path(colour.__file__).parent / "io" / "tests" / "resources"


@pytest.fixture(scope="module")
def spectra():
    _, cc = tc.colourchecker_spectra()
    return np.vstack([cc, tc.random_smooth_spectra()])


@pytest.mark.parametrize("observer", ["1931", "1964"])
@pytest.mark.parametrize("illuminant", tc.ILLUMINANTS)
def test_colorimetry_matches_colour_science(spectra, illuminant, observer):
    ref = tc.reference(spectra, illuminant, observer, use_sd_objects=False)
    obs = tc.OBSERVERS[observer]
    xyz = rouge.sd_to_XYZ(spectra, illuminant, obs)
    np.testing.assert_allclose(xyz, ref["xyz"], rtol=0, atol=tc.ATOL)
    lab = rouge.XYZ_to_Lab(xyz / 100, illuminant, obs)
    np.testing.assert_allclose(lab, ref["lab"], rtol=0, atol=tc.ATOL)
    np.testing.assert_allclose(rouge.sd_to_Lab(spectra, illuminant, observer), ref["lab"], rtol=0, atol=tc.ATOL)
    lin = rouge.XYZ_to_sRGB(xyz / 100, illuminant, obs, apply_cctf_encoding=False)
    np.testing.assert_allclose(lin, ref["srgb_linear"], rtol=0, atol=tc.ATOL)
    np.testing.assert_allclose(rouge.sd_to_sRGB(spectra, illuminant, obs), ref["srgb"], rtol=0, atol=tc.ATOL)
    de = rouge.delta_E_CIE2000(lab[:-1], lab[1:])
    np.testing.assert_allclose(de, colour.delta_E(ref["lab"][:-1], ref["lab"][1:], method="CIE 2000"), atol=tc.ATOL)


def test_spectral_distributions_on_their_own_grid():
    cmfs = colour.MSDS_CMFS[tc.OBSERVERS["1931"]]
    msds = colour.SDS_COLOURCHECKERS[tc.COLOURCHECKER]
    sd = msds["dark skin"]
    ref = colour.sd_to_XYZ(sd, cmfs, colour.SDS_ILLUMINANTS["D50"], method="Integration", shape=tc.SHAPE)
    np.testing.assert_allclose(rouge.sd_to_XYZ(sd, "D50"), ref, atol=tc.ATOL)
    both = colour.MultiSpectralDistributions({k: v for k, v in list(msds.items())[:3]})
    xyz = rouge.sd_to_XYZ(both, "D65")
    assert xyz.shape == (3, 3)
    # A 10 nm grid is resampled as colour-science aligns uniform data (Sprague, CIE 167).
    coarse = sd.copy().align(colour.SpectralShape(380, 780, 10))
    ref = colour.sd_to_XYZ(coarse, cmfs, colour.SDS_ILLUMINANTS["D65"], method="Integration", shape=tc.SHAPE)
    np.testing.assert_allclose(rouge.sd_to_XYZ(coarse), ref, atol=tc.ATOL)
    with pytest.raises(rouge.SpectrumError, match="380"):
        rouge.sd_to_XYZ(sd.copy().align(colour.SpectralShape(400, 700, 10)))
    assert rouge.sd_to_XYZ(sd.copy().align(colour.SpectralShape(400, 700, 10)), extrapolate=True).shape == (3,)
    with pytest.raises(ValueError, match="wavelengths="):
        rouge.sd_to_XYZ(np.ones(80))
    with pytest.raises(ValueError, match="unknown illuminant `F3`"):
        rouge.sd_to_XYZ(np.ones(81), "F3")


@pytest.fixture
def cli(request):
    """The conftest's `rouge` fixture (the CLI), under a name that leaves the module `rouge` be."""
    return request.getfixturevalue("rouge")


def _cli_preset(rouge_cli, tmp_path, path: Path, *extra: str) -> Path:
    out = tmp_path / f"{path.stem}_cli.json"
    p = rouge_cli("import", str(path), "--out", str(out), *extra)
    assert p.returncode == 0, p.stderr
    return out


FORMATS = [
    ("measurements/lipstick_02_red.csv", {}, ()),
    ("measurements/formats/foundation_02_ivory.ti3", {}, ()),
    ("measurements/formats/foundation_02_ivory_i1profiler.txt", {"extrapolate": True}, ("--extrapolate",)),
    ("measurements/formats/foundation_02_ivory_xrite.txt", {}, ()),
    ("measurements/formats/foundation_02_ivory_cs2000.csv", {}, ()),
]


@pytest.mark.parametrize("name, kwargs, cli_args", FORMATS, ids=[Path(f[0]).name for f in FORMATS])
def test_every_format_gives_the_cli_preset(repo_root, cli, tmp_path, name, kwargs, cli_args):
    path = repo_root / "data" / name
    m = rouge.read_measurement(path)
    assert m.R_inf.shape == m.R.shape == m.R_g.shape == m.wavelengths.shape
    assert m.path == str(path) and m.format
    thickness = [] if m.thickness_mm else ["--thickness-mm", "0.02"]
    out = _cli_preset(cli, tmp_path, path, *thickness, *cli_args)
    preset, report = rouge.Preset.from_measurement(m, thickness_mm=m.thickness_mm or 0.02, **kwargs)
    assert preset.to_json() == out.read_text(), "Python and the CLI write the same preset"
    assert rouge.Preset.load(out) == preset
    assert report["delta_e_2000_r"] < 1e-6
    mine = tmp_path / "py.json"
    preset.save(mine)
    assert mine.read_text() == out.read_text()
    # S and K of the preset are those of R_to_SK_KubelkaMunk on the working grid.
    w = m.to_working_grid(**kwargs)
    np.testing.assert_array_equal(w.wavelengths, rouge.working_wavelengths())
    S, K = rouge.R_to_SK_KubelkaMunk(w.R_inf, w.R, w.R_g, preset.thickness_mm)
    np.testing.assert_allclose(preset.S, S, rtol=1e-15)
    np.testing.assert_allclose(preset.K, K, rtol=1e-15)


def test_three_sp_files_and_presets_from_arrays(repo_root, cli, tmp_path):
    d = repo_root / "data" / "measurements" / "formats"
    files = [d / f"foundation_02_ivory_{r}.sp" for r in ("r_inf", "r", "rg")]
    m = rouge.read_measurement_files(*files)
    out = tmp_path / "cli.json"
    p = cli("import", "--r-inf", str(files[0]), "--r", str(files[1]), "--rg", str(files[2]),
              "--thickness-mm", "0.02", "--out", str(out))
    assert p.returncode == 0, p.stderr
    preset, _ = rouge.Preset.from_measurement(m, thickness_mm=0.02)
    assert preset.to_json() == out.read_text()
    hand = rouge.Preset.from_SK(preset.S, preset.K, 0.02, "by hand", "foundation")
    assert hand.derived == preset.derived and hand.measurement is None
    again = rouge.Preset.from_json(hand.to_json())
    assert again == hand and again.to_dict()["schema"] == "rouge-preset"
    with pytest.raises(rouge.PresetError, match="K = -1 at 400 nm"):
        rouge.Preset.from_SK(preset.S, np.where(rouge.working_wavelengths() == 400, -1.0, preset.K), 0.02, "x")
    broken = tmp_path / "broken.json"
    broken.write_text(out.read_text().replace('"version": 1', '"version": "one"', 1))
    with pytest.raises(rouge.PresetError) as e:
        rouge.Preset.load(broken)
    assert e.value.path == str(broken) and e.value.line is not None and e.value.column is not None


def _bad_files(repo_root):
    return sorted((repo_root / "data" / "measurements" / "bad").iterdir())


def test_bad_files_raise_the_cli_message(repo_root, cli, tmp_path):
    seen = 0
    for path in _bad_files(repo_root):
        run = cli("import", str(path), "--out", str(tmp_path / "x.json"))
        assert run.returncode != 0, path.name
        try:
            m = rouge.read_measurement(path)
            rouge.Preset.from_measurement(m)
        except (rouge.MeasurementImportError, rouge.PresetError) as e:
            assert isinstance(e, ValueError)
            if path.name == "missing_thickness.csv":  # the CLI names its option, Python its argument
                assert "gives no thickness: pass --thickness-mm" in run.stderr
                assert "gives no thickness: pass thickness_mm" in str(e)
            else:
                assert str(e) in run.stderr, f"{path.name}: Python says {e}; the CLI says {run.stderr}"
            assert e.path == str(path)
            if isinstance(e, rouge.MeasurementImportError) and e.line is not None:
                where = f"{path}:{e.line}" + (f":{e.column}" if e.column is not None else "")
                assert str(e).startswith(where + ": "), (where, str(e))
            seen += 1
        else:
            pytest.fail(f"{path.name} imported and inverted")
    assert seen >= 10


@pytest.mark.parametrize("name", ["colorchecker_n_ohta.csv", "colorchecker_n_ohta_transposed.csv"])
def test_colour_science_csv_files(cli, name):
    path = COLOUR_IO / name
    wl, values, names = rouge.read_spectra(path)
    assert values.shape == (24, 81) and names[:2] == ["1", "2"]
    ref = colour.SDS_COLOURCHECKERS[tc.COLOURCHECKER]
    np.testing.assert_allclose(values[0], ref["dark skin"][wl], atol=1e-12)
    msds = rouge.read_spectra(path, as_msds=True)
    assert isinstance(msds, colour.MultiSpectralDistributions) and len(msds.labels) == 24
    out = cli.json("color", str(path))
    assert [c["name"] for c in out] == names
    np.testing.assert_allclose([c["xyz"] for c in out], rouge.sd_to_XYZ(values), atol=1e-9)


def test_spectra_table_errors_name_line_and_column(tmp_path):
    p = tmp_path / "t.csv"
    p.write_text("wavelength,380,390,400\na,0.1,0.2,0.3\nb,0.1,oops,0.3\n")
    with pytest.raises(rouge.MeasurementImportError) as e:
        rouge.read_spectra(p)
    assert (e.value.line, e.value.column) == (3, 3)
    assert str(e.value) == f"{p}:3:3: `b` at 390 nm `oops` is not a number"
