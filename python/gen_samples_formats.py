"""The instrument layouts and the malformed files of python/gen_samples.py: one synthetic
product (FORMAT_SLUG) as X-Rite CGATS, i1Profiler CGATS (380-730 nm), ArgyllCMS .ti3 and .sp and
a Konica Minolta CS-2000 radiance CSV (1 nm), and deliberately broken files for the readers'
error messages (data/measurements/formats/, data/measurements/bad/).
"""

from __future__ import annotations

import sys
import warnings
from pathlib import Path

import numpy as np

with warnings.catch_warnings():
    warnings.simplefilter("ignore")
    import colour

sys.path.insert(0, str(Path(__file__).resolve().parent))
from samples_core import (  # noqa: E402
    BAD, BASO4_REFLECTANCE, CMFS, FINE, FORMATS, Sample, on_grid, rouge_header, rouge_rows, write_text, xyz_of,
)


# ---- instrument formats ---------------------------------------------------

ROLES = (("R_INF", "r_inf"), ("R", "r"), ("RG", "rg"))


def spectra_of(sample: Sample) -> dict[str, np.ndarray]:
    return {"R_INF": sample.r_inf, "R": sample.r, "RG": sample.rg}


def write_cgats(sample: Sample, suffix: str, header: list[str], fields: list[str], idx: list[int],
                decimals: int) -> Path:
    """Writes FORMATS/<slug>_<suffix>.txt: a CGATS.17 `header`, the field list and the three data
    sets (R_INF, R, RG) at grid indices `idx`, tab separated, CRLF."""
    t = "\t"
    spec = spectra_of(sample)
    lines = header + [
        f"NUMBER_OF_FIELDS{t}{len(fields)}",
        "BEGIN_DATA_FORMAT",
        t.join(fields),
        "END_DATA_FORMAT",
        f"NUMBER_OF_SETS{t}3",
        "BEGIN_DATA",
    ]
    for n, (role, _) in enumerate(ROLES, start=1):
        vals = [f"{spec[role][i]:.{decimals}f}" for i in idx]
        lines.append(t.join([str(n), role] + vals))
    lines.append("END_DATA")
    path = FORMATS / f"{sample.product.slug}_{suffix}.txt"
    write_text(path, "\r\n".join(lines) + "\r\n")
    return path


def write_xrite_cgats(sample: Sample) -> Path:
    """X-Rite ProfileMaker / MeasureTool style CGATS.17, tab separated,
    nm380..nm780 at 10 nm, reflectance as fractions."""
    idx = on_grid(sample, 10)
    fields = ["SampleID", "SAMPLE_NAME"] + [f"nm{int(FINE[i])}" for i in idx]
    t = "\t"
    header = [
        "CGATS.17",
        "# SYNTHETIC example written by python/gen_samples.py; not a real instrument export.",
        f"# Product: {sample.product.name}; same values as data/measurements/{sample.product.slug}.csv",
        f"ORIGINATOR{t}\"Rouge gen_samples.py (X-Rite MeasureTool-style layout)\"",
        f"DESCRIPTOR{t}\"{sample.product.name} - R_INF, R over black card, RG\"",
        f"CREATED{t}\"1/15/2025\"  # Time: 10:00",
        f"INSTRUMENTATION{t}\"i1Pro 2 (synthetic)\"",
        f"MEASUREMENT_SOURCE{t}\"Illumination=D50{t}ObserverAngle=2{t}WhiteBase=Abs{t}Filter=No\"",
        f"ILLUMINATION_NAME{t}\"D50\"",
        f"OBSERVER_ANGLE{t}\"2\"",
        f"FILTER{t}\"No\"",
        f"LGOROWLENGTH{t}3",
        f"KEYWORD{t}\"SampleID\"",
        f"KEYWORD{t}\"SAMPLE_NAME\"",
        f"KEYWORD{t}\"ROUGE_THICKNESS_MM\"",
        f"ROUGE_THICKNESS_MM{t}\"{sample.product.thickness_mm:.3f}\"",
    ]
    return write_cgats(sample, "xrite", header, fields, idx, 6)


def write_i1profiler_cgats(sample: Sample) -> Path:
    """i1Profiler 'CGATS Spectral' style: SPECTRAL_NM380..SPECTRAL_NM730 at
    10 nm, fractions with 4 decimals.  Does NOT cover 740-780 nm."""
    idx = [i for i in on_grid(sample, 10) if FINE[i] <= 730]
    fields = ["SAMPLE_ID", "SAMPLE_NAME"] + [f"SPECTRAL_NM{int(FINE[i])}" for i in idx]
    t = "\t"
    header = [
        "CGATS.17",
        "# SYNTHETIC example written by python/gen_samples.py; layout follows i1Profiler",
        "# 'CGATS Spectral' exports (SPECTRAL_NMxxx fields, fractions, 4 decimals, 380-730 nm).",
        f"# Product: {sample.product.name}; same values as data/measurements/{sample.product.slug}.csv",
        f"ORIGINATOR{t}\"Rouge gen_samples.py (i1Profiler-style layout)\"",
        f"CREATED{t}\"January 15, 2025\"",
        f"INSTRUMENTATION{t}\"i1Pro 2 (synthetic)\"",
        f"MEASUREMENT_SOURCE{t}\"Illumination=D50{t}ObserverAngle=2{t}WhiteBase=Abs{t}Filter=No\"",
        f"MEASUREMENT_CONDITION{t}\"M0\"",
    ]
    return write_cgats(sample, "i1profiler", header, fields, idx, 4)


def write_ti3(sample: Sample) -> Path:
    """ArgyllCMS .ti3 (CTI3), SPEC_380..SPEC_780 at 10 nm, percent."""
    idx = on_grid(sample, 10)
    spec = spectra_of(sample)
    wl10 = FINE[idx]
    bands = len(idx)
    fields = (["SAMPLE_ID", "SAMPLE_LOC", "RGB_R", "RGB_G", "RGB_B",
               "XYZ_X", "XYZ_Y", "XYZ_Z"] + [f"SPEC_{int(w)}" for w in wl10])
    lines = [
        "CTI3   ",
        "",
        "# SYNTHETIC example written by python/gen_samples.py; layout follows ArgyllCMS chartread .ti3.",
        f"# Product: {sample.product.name}; same values as data/measurements/{sample.product.slug}.csv",
        "# RGB_* are placeholders (no device was printed); XYZ_* are D50/2-degree, Y = 100 scale.",
        'DESCRIPTOR "Argyll Calibration Target chart information 3"',
        'ORIGINATOR "Rouge gen_samples.py (Argyll chartread-style layout)"',
        'CREATED "Wed Jan 15 10:00:00 2025"',
        'DEVICE_CLASS "OUTPUT"',
        'COLOR_REP "RGB_XYZ"',
        'TARGET_INSTRUMENT "X-Rite i1 Pro 2"',
        'INSTRUMENT_TYPE_SPECTRAL "YES"',
        'KEYWORD "SPECTRAL_BANDS"',
        f'SPECTRAL_BANDS "{bands}"',
        'KEYWORD "SPECTRAL_START_NM"',
        f'SPECTRAL_START_NM "{wl10[0]:.6f}"',
        'KEYWORD "SPECTRAL_END_NM"',
        f'SPECTRAL_END_NM "{wl10[-1]:.6f}"',
        'KEYWORD "ROUGE_THICKNESS_MM"',
        f'ROUGE_THICKNESS_MM "{sample.product.thickness_mm:.3f}"',
        "",
        f"NUMBER_OF_FIELDS {len(fields)}",
        "BEGIN_DATA_FORMAT",
        " ".join(fields) + " ",
        "END_DATA_FORMAT",
        "",
        "NUMBER_OF_SETS 3",
        "BEGIN_DATA",
    ]
    for n, (role, _) in enumerate(ROLES, start=1):
        xyz = xyz_of(wl10, spec[role][idx], "D50")
        vals = ([str(n), f'"{role}"', "0.000000", "0.000000", "0.000000"]
                + [f"{v:.6f}" for v in xyz]
                + [f"{100.0 * spec[role][i]:.4f}" for i in idx])
        lines.append(" ".join(vals) + " ")
    lines.append("END_DATA")
    path = FORMATS / f"{sample.product.slug}.ti3"
    write_text(path, "\n".join(lines) + "\n")
    return path


def write_sp(sample: Sample) -> list[Path]:
    """ArgyllCMS .sp single-spectrum files (one per role), 380..780 at 5 nm,
    SPECTRAL_NORM 100 (values in percent; reflectance = value / norm)."""
    idx = on_grid(sample, 5)
    spec = spectra_of(sample)
    wl5 = FINE[idx]
    paths = []
    for role, suffix in ROLES:
        fields = [f"SPEC_{int(w)}" for w in wl5]
        lines = [
            "SPECT",
            "",
            "# SYNTHETIC example written by python/gen_samples.py; layout follows ArgyllCMS .sp.",
            f"# Product: {sample.product.name}; role {role}; same values as "
            f"data/measurements/{sample.product.slug}.csv",
            'DESCRIPTOR "Argyll Spectral power/reflectance information"',
            'ORIGINATOR "Rouge gen_samples.py (Argyll spotread-style layout)"',
            'CREATED "Wed Jan 15 10:00:00 2025"',
            'KEYWORD "MEAS_TYPE"',
            'MEAS_TYPE "REFLECTIVE"',
            'KEYWORD "SPECTRAL_BANDS"',
            f'SPECTRAL_BANDS "{len(wl5)}"',
            'KEYWORD "SPECTRAL_START_NM"',
            f'SPECTRAL_START_NM "{wl5[0]:.6f}"',
            'KEYWORD "SPECTRAL_END_NM"',
            f'SPECTRAL_END_NM "{wl5[-1]:.6f}"',
            'KEYWORD "SPECTRAL_NORM"',
            'SPECTRAL_NORM "100.000000"',
            'KEYWORD "ROUGE_ROLE"',
            f'ROUGE_ROLE "{role}"',
            "",
            f"NUMBER_OF_FIELDS {len(fields)}",
            "BEGIN_DATA_FORMAT",
            " ".join(fields) + " ",
            "END_DATA_FORMAT",
            "",
            "NUMBER_OF_SETS 1",
            "BEGIN_DATA",
            " ".join(f"{100.0 * spec[role][i]:.4f}" for i in idx) + " ",
            "END_DATA",
        ]
        path = FORMATS / f"{sample.product.slug}_{suffix}.sp"
        write_text(path, "\n".join(lines) + "\n")
        paths.append(path)
    return paths


def illuminant_a(wl: np.ndarray) -> np.ndarray:
    """CIE standard illuminant A (CIE 015:2018 eq. 2.1), 100 at 560 nm."""
    c2 = 1.435e7
    return 100.0 * (560.0 / wl) ** 5 * (
        (np.exp(c2 / (2848.0 * 560.0)) - 1.0) / (np.exp(c2 / (2848.0 * wl)) - 1.0))


def write_cs2000(sample: Sample) -> Path:
    """Konica Minolta CS-2000 radiance export, 380..780 nm at 1 nm, as a
    CS-S10w-like CSV (layout reconstructed, see docs/FORMATS.md)."""
    wl = FINE
    ybar = CMFS.copy().align(colour.SpectralShape(380, 780, 1)).values
    lamp = illuminant_a(wl)
    # scale so that the BaSO4 plate reads Lv = 600 cd/m^2 (about 1900 lx)
    lv_unit = 683.0 * float(np.sum(BASO4_REFLECTANCE * lamp * ybar[:, 1]))
    scale = 600.0 / lv_unit
    white = BASO4_REFLECTANCE * lamp * scale
    rows = [("WHITE_BASO4", white)]
    for name, r in (("SAMPLE_RINF", sample.r_inf), ("SAMPLE_R", sample.r),
                    ("BACKGROUND_RG", sample.rg)):
        rows.append((name, r * lamp * scale))
    header = ["No.", "Data Name", "Date", "Time", "Le[W/(sr*m^2)]", "Lv[cd/m^2]",
              "x", "y"] + [f"{int(w)}nm" for w in wl]
    lines = [
        "Instrument,CS-2000",
        "Software,CS-S10w-like export (SYNTHETIC; layout reconstructed by Rouge gen_samples.py)",
        f"Comment,\"{sample.product.name}: opaque layer, thin layer over black card, "
        "black card, BaSO4 white standard; same lamp and geometry\"",
        "Measurement Angle,1 deg",
        "Speed Mode,NORMAL",
        "Observer,2 deg",
        "Light Source,CIE illuminant A (tungsten halogen 2856 K) at 45 deg",
        f"White Standard,BaSO4,{BASO4_REFLECTANCE:.3f}",
        "Spectral Radiance Unit,W/(sr*m^2*nm)",
        "Wavelength,380-780nm,1nm",
        "",
        ",".join(header),
    ]
    for n, (name, rad) in enumerate(rows, start=1):
        le = float(np.sum(rad))
        xyz = 683.0 * (rad @ ybar)
        lv = float(xyz[1])
        x, y = xyz[0] / xyz.sum(), xyz[1] / xyz.sum()
        cells = [str(n), name, "2025/01/15", f"10:{n:02d}:00", f"{le:.5E}", f"{lv:.4f}",
                 f"{x:.4f}", f"{y:.4f}"] + [f"{v:.5E}" for v in rad]
        lines.append(",".join(cells))
    path = FORMATS / f"{sample.product.slug}_cs2000.csv"
    write_text(path, "\r\n".join(lines) + "\r\n")
    return path


# ---- malformed files ----------------------------------------------------

def write_bad_files(sample: Sample) -> list[Path]:
    """Derived from the 10 nm subsample of FORMAT_SLUG (fraction).  Every
    file starts with a '# BAD FILE:' line naming what is wrong, and where
    (1-based line and column of the file as written)."""
    base_header = rouge_header(sample)
    base_header = [h for h in base_header if not h.startswith("# truth:")]
    rows = rouge_rows(sample, 10, percent=False)
    col_header = "wavelength_nm,r_inf,r,rg"
    n_head = 1 + len(base_header)  # BAD FILE line + header comments

    def line_of(row_index: int) -> int:
        return n_head + 1 + row_index + 1  # + column-header line, 1-based

    def row_at(wl: int) -> int:
        return next(i for i, r in enumerate(rows) if r.startswith(f"{wl},"))

    out = []

    def emit(name: str, what: str, body_rows: list[str], header: str = col_header,
             header_lines: list[str] | None = None) -> None:
        hl = base_header if header_lines is None else header_lines
        text = "\n".join([f"# BAD FILE: {what}"] + hl + [header] + body_rows) + "\n"
        path = BAD / name
        write_text(path, text)
        out.append(path)

    def replace_cell(r: list[str], wl: int, col: int, value: str) -> list[str]:
        r = list(r)
        i = row_at(wl)
        cells = r[i].split(",")
        cells[col - 1] = value
        r[i] = ",".join(cells)
        return r

    i = row_at(550)
    emit("non_numeric.csv",
         f"non-numeric cell '0.4o1234' at line {line_of(i)}, column 3 (r)",
         replace_cell(rows, 550, 3, "0.4o1234"))
    i = row_at(600)
    emit("nan_value.csv", f"NaN at line {line_of(i)}, column 2 (r_inf)",
         replace_cell(rows, 600, 2, "NaN"))
    i = row_at(500)
    emit("missing_wavelength.csv",
         f"empty wavelength cell at line {line_of(i)}, column 1 (wavelength_nm)",
         replace_cell(rows, 500, 1, ""))
    i = row_at(500)
    dup = list(rows)
    dup.insert(i + 1, rows[i])
    emit("duplicate_wavelength.csv",
         f"wavelength 500 repeated at line {line_of(i + 1)}, column 1 "
         f"(first at line {line_of(i)})", dup)
    i = row_at(600)
    swap = list(rows)
    swap[i], swap[i + 1] = swap[i + 1], swap[i]
    emit("non_monotonic.csv",
         f"wavelengths not increasing: 610 then 600 at lines {line_of(i)}-{line_of(i + 1)}, "
         "column 1", swap)
    i = row_at(650)
    emit("reflectance_too_high.csv",
         f"reflectance 1.720000 > 1.5 in a fraction file at line {line_of(i)}, column 2 (r_inf)",
         replace_cell(rows, 650, 2, "1.720000"))
    i = row_at(450)
    emit("negative_value.csv", f"negative reflectance -0.012000 at line {line_of(i)}, column 4 (rg)",
         replace_cell(rows, 450, 4, "-0.012000"))
    emit("header_missing_column.csv",
         f"column header lacks the rg column (data rows have 4 fields): header at line {n_head + 1}",
         rows, header="wavelength_nm,r_inf,r")
    i = row_at(700)
    short = list(rows)
    short[i] = ",".join(short[i].split(",")[:3])
    emit("wrong_field_count.csv",
         f"data row with 3 fields instead of 4 at line {line_of(i)} (column 4, rg, missing)", short)
    emit("no_data_rows.csv", f"comment lines and column header only, no data rows "
         f"(header at line {n_head + 1})", [])
    i = row_at(550)
    cells = rows[i].split(",")
    too_bright = f"{float(cells[1]) + 0.05:.6f}"
    emit("r_outside_bounds.csv",
         f"parses, but r {too_bright} > r_inf {cells[1]} over a black card at line {line_of(i)}, "
         "column 3: no KM solution at 550 nm (inversion must reject)",
         replace_cell(rows, 550, 3, too_bright))
    no_thick = [h for h in base_header if not h.startswith("# thickness_mm:")]
    n_head2 = 1 + len(no_thick)
    emit("missing_thickness.csv",
         f"no '# thickness_mm:' key in the comment block, lines 1-{n_head2} (no column)",
         rows, header_lines=no_thick)
    # empty file: 0 bytes, so it cannot carry its own comment (see docs/FORMATS.md)
    path = BAD / "empty.csv"
    write_text(path, "")
    out.append(path)

    # CGATS with END_DATA missing (from the X-Rite example)
    good = (FORMATS / f"{sample.product.slug}_xrite.txt").read_bytes().decode("utf-8")
    glines = good.split("\r\n")
    assert glines[-1] == "" and glines[-2] == "END_DATA"
    glines = glines[:-2] + [""]
    last = len(glines) - 1  # 1-based number of the last text line
    begin = glines.index("BEGIN_DATA") + 2  # 1-based, after the inserted comment
    glines.insert(1, f"# BAD FILE: END_DATA missing: BEGIN_DATA at line {begin}, last data row "
                     f"at line {last + 1}, END_DATA expected at line {last + 2}, column 1")
    path = BAD / "cgats_missing_end_data.txt"
    write_text(path, "\r\n".join(glines))
    out.append(path)
    return out


