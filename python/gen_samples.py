#!/usr/bin/env python3
"""Generate Rouge's SYNTHETIC cosmetic measurements (and their true K, S).

No public Kubelka-Munk K and S spectra of real cosmetics exist, so this script
builds products from the representative pigment library in pigments.py
(Duncan two-constant mixing), computes what an instrument would read, adds
seeded measurement noise and writes:

* data/measurements/<slug>.csv          Rouge CSV: r_inf, r (thin layer of
                                        thickness D over the background), rg
* data/measurements/truth/<slug>.csv    the true S and K (mm^-1) on the same grid
* data/measurements/formats/*           one product (Foundation 02 Ivory) in
                                        instrument layouts: X-Rite CGATS,
                                        i1Profiler CGATS (380-730 nm), ArgyllCMS
                                        .ti3 and .sp, Konica Minolta CS-2000
                                        radiance CSV (1 nm)
* data/measurements/bad/*               deliberately malformed files
* data/pigments/pigment_library.csv     the pigment library on 380..780/5 nm

Everything is deterministic: re-running reproduces identical bytes (no dates,
fixed seeds, numpy's PCG64 generator).  Every file says it is synthetic.

Kubelka-Munk (a = 1 + K/S, b = sqrt(a^2 - 1)):
    R_inf = a - b
    R     = (1 - Rg (a - b coth(b S D))) / (a - Rg + b coth(b S D))

Usage: .venv/bin/python python/gen_samples.py [--swatches /tmp/rouge_swatches.png]
"""

from __future__ import annotations

import argparse
import struct
import sys
import warnings
import zlib
from dataclasses import dataclass
from pathlib import Path

import numpy as np

with warnings.catch_warnings():
    warnings.simplefilter("ignore")
    import colour

sys.path.insert(0, str(Path(__file__).resolve().parent))
import pigments  # noqa: E402

ROOT = Path(__file__).resolve().parents[1]
MEAS = ROOT / "data" / "measurements"
TRUTH = MEAS / "truth"
FORMATS = MEAS / "formats"
BAD = MEAS / "bad"
PIGDIR = ROOT / "data" / "pigments"

FINE = np.arange(380, 781, 1).astype(float)  # noise is drawn on this 1 nm grid
SEED_BASE = 1000
NOISE_MULT = 0.003  # 0.3 % multiplicative (1 sigma)
NOISE_ADD = 0.0005  # additive (1 sigma), reflectance units
# After noise, R must lie strictly inside (min(Rg, R_inf), max(Rg, R_inf)) with
# this margin, so that the ordering survives rounding to 4 decimals (fraction).
MARGIN = 1.5e-4
MIN_TRUE_GAP = 0.002  # design criterion on the noise-free data
SYNTHETIC_NOTE = ("true \u2014 generated from literature pigment K and S, "
                  "not a measurement of a real product")
FORMAT_SLUG = "foundation_02_ivory"  # the product shown in instrument formats
BASO4_REFLECTANCE = 0.99


def black_card(wl: np.ndarray) -> np.ndarray:
    """Black half of a contrast (Leneta-style) card: 0.034 -> 0.048."""
    x = (wl - 380.0) / 400.0
    return 0.034 + 0.010 * x + 0.004 * x * x


def white_card(wl: np.ndarray) -> np.ndarray:
    """White half of a contrast card, no optical brightener: ~0.80 in the
    near UV rising to ~0.88."""
    x = (wl - 380.0) / 400.0
    return 0.800 + 0.066 / (1.0 + np.exp(-(wl - 425.0) / 20.0)) + 0.012 * x


BACKGROUNDS = {
    "black": (black_card, "black contrast card (Leneta-style), Rg ~0.034 at 380 nm "
                          "rising to ~0.048 at 780 nm"),
    "white": (white_card, "white contrast card (no optical brightener), Rg ~0.80 at "
                          "380 nm rising to ~0.88; lighter than the layer"),
}


@dataclass
class Product:
    slug: str
    name: str
    kind: str
    recipe: dict[str, float]  # volume fractions in the dry film, binder = rest
    thickness_mm: float
    background: str  # "black" | "white"
    step_nm: int = 5
    percent: bool = False


PRODUCTS = [
    Product("foundation_01_porcelain", "Foundation 01 Porcelain", "foundation",
            dict(tio2=0.027, goethite=0.0046, hematite=0.0006, magnetite=0.0010,
                 filler=0.20), 0.022, "black"),
    Product("foundation_02_ivory", "Foundation 02 Ivory", "foundation",
            dict(tio2=0.017, goethite=0.0065, hematite=0.0011, magnetite=0.0020,
                 filler=0.15), 0.020, "black"),
    Product("foundation_03_sand", "Foundation 03 Sand", "foundation",
            dict(tio2=0.0096, goethite=0.0089, hematite=0.0016, magnetite=0.0031,
                 filler=0.12), 0.020, "black"),
    Product("foundation_04_caramel", "Foundation 04 Caramel", "foundation",
            dict(tio2=0.0029, goethite=0.0079, hematite=0.0018, magnetite=0.0032,
                 filler=0.03), 0.020, "black"),
    Product("foundation_05_espresso", "Foundation 05 Espresso", "foundation",
            dict(tio2=0.0005, goethite=0.0107, hematite=0.0050, magnetite=0.0093,
                 filler=0.05), 0.020, "white"),
    Product("blush_01_petal", "Blush 01 Petal Pink", "blush",
            dict(tio2=0.020, red_lake=0.006, goethite=0.0045, filler=0.45),
            0.015, "black"),
    Product("blush_02_coral", "Blush 02 Coral", "blush",
            dict(tio2=0.020, red_lake=0.003, goethite=0.006, hematite=0.002,
                 filler=0.45), 0.012, "black", percent=True),
    Product("eyeshadow_01_smoky", "Eyeshadow 01 Smoky Charcoal", "eyeshadow",
            dict(carbon_black=0.005, magnetite=0.020, ultramarine=0.003,
                 filler=0.45), 0.010, "white"),
    Product("eyeshadow_02_sapphire", "Eyeshadow 02 Sapphire Blue", "eyeshadow",
            dict(ultramarine=0.045, tio2=0.010, filler=0.45), 0.012, "black",
            step_nm=10),
    Product("eyeshadow_03_bronze", "Eyeshadow 03 Bronze", "eyeshadow",
            dict(goethite=0.012, hematite=0.004, magnetite=0.003, tio2=0.005,
                 filler=0.45), 0.010, "black"),
    Product("lipstick_01_nude", "Lipstick 01 Nude", "lipstick",
            dict(tio2=0.015, goethite=0.006, hematite=0.0018, red_lake=0.0019,
                 filler=0.05), 0.015, "black", step_nm=10),
    Product("lipstick_02_red", "Lipstick 02 Classic Red", "lipstick",
            dict(red_lake=0.009, goethite=0.012, hematite=0.002, tio2=0.005,
                 filler=0.05), 0.010, "black"),
    Product("lipstick_03_berry", "Lipstick 03 Deep Berry", "lipstick",
            dict(red_lake=0.020, ultramarine=0.004, magnetite=0.004, tio2=0.002,
                 filler=0.05), 0.015, "white"),
]


# --------------------------------------------------------------------------
# Kubelka-Munk forward model
# --------------------------------------------------------------------------

def km_rinf(k: np.ndarray, s: np.ndarray) -> np.ndarray:
    q = k / s
    return 1.0 + q - np.sqrt(q * q + 2.0 * q)


def km_layer(k: np.ndarray, s: np.ndarray, d: float, rg: np.ndarray) -> np.ndarray:
    a = 1.0 + k / s
    b = np.sqrt(a * a - 1.0)
    coth = 1.0 / np.tanh(b * s * d)
    return (1.0 - rg * (a - b * coth)) / (a - rg + b * coth)


# --------------------------------------------------------------------------
# Colour helpers (colour-science)
# --------------------------------------------------------------------------

CMFS = colour.MSDS_CMFS["CIE 1931 2 Degree Standard Observer"]
WP_D65 = colour.CCS_ILLUMINANTS["CIE 1931 2 Degree Standard Observer"]["D65"]
WP_D50 = colour.CCS_ILLUMINANTS["CIE 1931 2 Degree Standard Observer"]["D50"]


def xyz_of(wl: np.ndarray, r: np.ndarray, illuminant: str = "D65") -> np.ndarray:
    sd = colour.SpectralDistribution(dict(zip(wl.tolist(), r.tolist())))
    step = float(wl[1] - wl[0])
    shape = colour.SpectralShape(float(wl[0]), float(wl[-1]), step)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        return colour.sd_to_XYZ(sd, CMFS, colour.SDS_ILLUMINANTS[illuminant],
                                method="Integration", shape=shape)


def srgb_hex_lab(wl: np.ndarray, r: np.ndarray) -> tuple[str, np.ndarray, np.ndarray]:
    xyz = xyz_of(wl, r) / 100.0
    rgb = np.clip(colour.XYZ_to_sRGB(xyz), 0.0, 1.0)
    lab = colour.XYZ_to_Lab(xyz, WP_D65)
    code = "#" + "".join(f"{int(round(v * 255)):02X}" for v in rgb)
    return code, lab, rgb


# --------------------------------------------------------------------------
# Synthesis
# --------------------------------------------------------------------------

@dataclass
class Sample:
    product: Product
    seed: int
    k: np.ndarray  # on FINE
    s: np.ndarray
    r_inf: np.ndarray  # canonical noisy values, rounded to 6 decimals, on FINE
    r: np.ndarray
    rg: np.ndarray
    true_gap: float
    true_gap_nm: float
    reduced: list  # wavelengths (nm) where the noise had to be reduced


def synthesise(p: Product, seed: int) -> Sample:
    k, s = pigments.mix(p.recipe, FINE)
    rg_true = BACKGROUNDS[p.background][0](FINE)
    rinf_true = km_rinf(k, s)
    r_true = km_layer(k, s, p.thickness_mm, rg_true)
    gap = np.minimum(np.abs(rinf_true - r_true), np.abs(r_true - rg_true))
    true_gap = float(gap.min())
    assert true_gap >= MIN_TRUE_GAP, (
        f"{p.slug}: layer not partially hiding enough (min gap {true_gap:.5f} at "
        f"{FINE[gap.argmin()]:.0f} nm); adjust D or the recipe")

    rng = np.random.default_rng(seed)
    truth = np.vstack([rinf_true, r_true, rg_true])
    noise = (truth * NOISE_MULT * rng.standard_normal(truth.shape)
             + NOISE_ADD * rng.standard_normal(truth.shape))
    out = np.empty_like(truth)
    reduced = []
    for i in range(FINE.size):
        for factor in (1.0, 0.5, 0.25, 0.125, 0.0):
            vals = np.round(truth[:, i] + factor * noise[:, i], 6)
            ri, rr, rgv = vals
            lo, hi = min(ri, rgv), max(ri, rgv)
            if lo + MARGIN < rr < hi - MARGIN and lo > 0.0 and hi < 1.0:
                break
        else:  # pragma: no cover - guarded by MIN_TRUE_GAP
            raise AssertionError(f"{p.slug}: cannot order R at {FINE[i]} nm")
        if factor < 1.0:
            reduced.append(int(FINE[i]))
        out[:, i] = vals
    # the assertion the brief asks for: strictly between, at every wavelength
    lo = np.minimum(out[0], out[2])
    hi = np.maximum(out[0], out[2])
    assert np.all((out[1] > lo) & (out[1] < hi)), p.slug
    return Sample(p, seed, k, s, out[0], out[1], out[2], true_gap,
                  float(FINE[gap.argmin()]), reduced)


def on_grid(sample: Sample, step: int) -> np.ndarray:
    idx = np.arange(0, FINE.size, step)
    assert np.all(FINE[idx] % step == 0)
    return idx


def fmt_recipe(recipe: dict[str, float]) -> str:
    parts = [f"{k}={v:g}" for k, v in recipe.items()]
    binder = 1.0 - sum(recipe.values())
    return ", ".join(parts + [f"binder={binder:.4f}"])


# --------------------------------------------------------------------------
# Writers
# --------------------------------------------------------------------------

def write_text(path: Path, text: str) -> None:
    path.parent.mkdir(parents=True, exist_ok=True)
    path.write_bytes(text.encode("utf-8"))


def rouge_header(sample: Sample) -> list[str]:
    p = sample.product
    lines = [
        f"# name: {p.name}",
        f"# kind: {p.kind}",
        f"# thickness_mm: {p.thickness_mm:.3f}",
        f"# instrument: synthetic (python/gen_samples.py, seed {sample.seed})",
        f"# synthetic: {SYNTHETIC_NOTE}",
        f"# background: {BACKGROUNDS[p.background][1]}",
        f"# recipe: {fmt_recipe(p.recipe)} (dry-film volume fractions, pigments from python/pigments.py)",
        f"# truth: truth/{p.slug}.csv",
    ]
    if p.percent:
        lines.append("# note: reflectance columns are in percent (0-100), 4 decimals")
    return lines


def rouge_rows(sample: Sample, step: int, percent: bool) -> list[str]:
    rows = []
    for i in on_grid(sample, step):
        vals = (sample.r_inf[i], sample.r[i], sample.rg[i])
        if percent:
            cells = [f"{100.0 * v:.4f}" for v in vals]
        else:
            cells = [f"{v:.6f}" for v in vals]
        rows.append(f"{int(FINE[i])}," + ",".join(cells))
    return rows


def write_rouge_csv(sample: Sample) -> Path:
    p = sample.product
    lines = rouge_header(sample) + ["wavelength_nm,r_inf,r,rg"]
    lines += rouge_rows(sample, p.step_nm, p.percent)
    path = MEAS / f"{p.slug}.csv"
    write_text(path, "\n".join(lines) + "\n")
    return path


def write_truth(sample: Sample) -> Path:
    p = sample.product
    lines = [
        f"# name: {p.name}",
        f"# synthetic: {SYNTHETIC_NOTE}",
        "# true Kubelka-Munk coefficients of the film (mm^-1) used to synthesise "
        f"../{p.slug}.csv (before noise)",
        f"# thickness_mm: {p.thickness_mm:.3f}",
        f"# recipe: {fmt_recipe(p.recipe)}",
        "wavelength_nm,s_per_mm,k_per_mm",
    ]
    for i in on_grid(sample, p.step_nm):
        lines.append(f"{int(FINE[i])},{sample.s[i]:.6f},{sample.k[i]:.6f}")
    path = TRUTH / f"{p.slug}.csv"
    write_text(path, "\n".join(lines) + "\n")
    return path


def write_pigment_library() -> Path:
    wl = np.arange(380, 781, 5).astype(float)
    keys = list(pigments.PIGMENTS)
    lines = [
        "# Rouge pigment library (SYNTHETIC, representative magnitudes; not measured).",
        "# Generated by python/gen_samples.py from python/pigments.py. Do not edit; regenerate.",
        "# Columns: specific Kubelka-Munk coefficients in mm^-1 per unit dry-film volume",
        "# fraction; mixture K = sum c_i k_i, S = sum c_i s_i (Duncan), binder fills the rest.",
    ]
    for key in keys:
        name, src = pigments.PIGMENTS[key]
        lines.append(f"# {key}: {name}. Shape: {src}")
    lines.append("wavelength_nm," + ",".join(f"k_{k},s_{k}" for k in keys))
    for w in wl:
        cells = []
        for key in keys:
            cells.append(f"{float(pigments.k_specific(key, w)):.6g}")
            cells.append(f"{float(pigments.s_specific(key, w)):.6g}")
        lines.append(f"{int(w)}," + ",".join(cells))
    path = PIGDIR / "pigment_library.csv"
    write_text(path, "\n".join(lines) + "\n")
    return path


# ---- instrument formats ---------------------------------------------------

ROLES = (("R_INF", "r_inf"), ("R", "r"), ("RG", "rg"))


def spectra_of(sample: Sample) -> dict[str, np.ndarray]:
    return {"R_INF": sample.r_inf, "R": sample.r, "RG": sample.rg}


def write_xrite_cgats(sample: Sample) -> Path:
    """X-Rite ProfileMaker / MeasureTool style CGATS.17, tab separated,
    nm380..nm780 at 10 nm, reflectance as fractions."""
    idx = on_grid(sample, 10)
    spec = spectra_of(sample)
    fields = ["SampleID", "SAMPLE_NAME"] + [f"nm{int(FINE[i])}" for i in idx]
    t = "\t"
    lines = [
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
        f"NUMBER_OF_FIELDS{t}{len(fields)}",
        "BEGIN_DATA_FORMAT",
        t.join(fields),
        "END_DATA_FORMAT",
        f"NUMBER_OF_SETS{t}3",
        "BEGIN_DATA",
    ]
    for n, (role, _) in enumerate(ROLES, start=1):
        vals = [f"{spec[role][i]:.6f}" for i in idx]
        lines.append(t.join([str(n), role] + vals))
    lines.append("END_DATA")
    path = FORMATS / f"{sample.product.slug}_xrite.txt"
    write_text(path, "\r\n".join(lines) + "\r\n")
    return path


def write_i1profiler_cgats(sample: Sample) -> Path:
    """i1Profiler 'CGATS Spectral' style: SPECTRAL_NM380..SPECTRAL_NM730 at
    10 nm, fractions with 4 decimals.  Does NOT cover 740-780 nm."""
    idx = [i for i in on_grid(sample, 10) if FINE[i] <= 730]
    spec = spectra_of(sample)
    fields = ["SAMPLE_ID", "SAMPLE_NAME"] + [f"SPECTRAL_NM{int(FINE[i])}" for i in idx]
    t = "\t"
    lines = [
        "CGATS.17",
        "# SYNTHETIC example written by python/gen_samples.py; layout follows i1Profiler",
        "# 'CGATS Spectral' exports (SPECTRAL_NMxxx fields, fractions, 4 decimals, 380-730 nm).",
        f"# Product: {sample.product.name}; same values as data/measurements/{sample.product.slug}.csv",
        f"ORIGINATOR{t}\"Rouge gen_samples.py (i1Profiler-style layout)\"",
        f"CREATED{t}\"January 15, 2025\"",
        f"INSTRUMENTATION{t}\"i1Pro 2 (synthetic)\"",
        f"MEASUREMENT_SOURCE{t}\"Illumination=D50{t}ObserverAngle=2{t}WhiteBase=Abs{t}Filter=No\"",
        f"MEASUREMENT_CONDITION{t}\"M0\"",
        f"NUMBER_OF_FIELDS{t}{len(fields)}",
        "BEGIN_DATA_FORMAT",
        t.join(fields),
        "END_DATA_FORMAT",
        f"NUMBER_OF_SETS{t}3",
        "BEGIN_DATA",
    ]
    for n, (role, _) in enumerate(ROLES, start=1):
        vals = [f"{spec[role][i]:.4f}" for i in idx]
        lines.append(t.join([str(n), role] + vals))
    lines.append("END_DATA")
    path = FORMATS / f"{sample.product.slug}_i1profiler.txt"
    write_text(path, "\r\n".join(lines) + "\r\n")
    return path


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


# --------------------------------------------------------------------------
# Swatch sheet (tiny PNG writer, numpy + zlib only)
# --------------------------------------------------------------------------

def write_png(path: Path, img: np.ndarray) -> None:
    h, w, _ = img.shape
    raw = b"".join(b"\x00" + img[y].astype(np.uint8).tobytes() for y in range(h))

    def chunk(tag: bytes, data: bytes) -> bytes:
        return (struct.pack(">I", len(data)) + tag + data
                + struct.pack(">I", zlib.crc32(tag + data) & 0xFFFFFFFF))

    png = (b"\x89PNG\r\n\x1a\n"
           + chunk(b"IHDR", struct.pack(">IIBBBBB", w, h, 8, 2, 0, 0, 0))
           + chunk(b"IDAT", zlib.compress(raw, 9)) + chunk(b"IEND", b""))
    path.write_bytes(png)


def swatch_sheet(samples: list[Sample], path: Path) -> None:
    """Row per product: R_inf | R over its background | background."""
    cell, gap = 60, 6
    h = len(samples) * (cell + gap) + gap
    w = 3 * (cell + gap) + gap
    img = np.full((h, w, 3), 128, dtype=np.uint8)
    for row, smp in enumerate(samples):
        for col, spec in enumerate((smp.r_inf, smp.r, smp.rg)):
            _, _, rgb = srgb_hex_lab(FINE, spec)
            y0 = gap + row * (cell + gap)
            x0 = gap + col * (cell + gap)
            img[y0:y0 + cell, x0:x0 + cell] = np.round(rgb * 255)
    write_png(path, img)


# --------------------------------------------------------------------------

def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--swatches", type=Path, help="also write a PNG swatch sheet here")
    args = ap.parse_args()

    samples = [synthesise(p, SEED_BASE + i) for i, p in enumerate(PRODUCTS, start=1)]
    written = [write_pigment_library()]
    print(f"{'slug':26s} {'R_inf sRGB':10s} {'L*':>5s} {'a*':>6s} {'b*':>6s} "
          f"{'D/mm':>6s} {'bg':5s} grid  min-true-gap  noise-reduced-at")
    for smp in samples:
        p = smp.product
        written.append(write_rouge_csv(smp))
        written.append(write_truth(smp))
        code, lab, _ = srgb_hex_lab(FINE, smp.r_inf)
        red = ",".join(map(str, smp.reduced)) if smp.reduced else "-"
        grid = f"{p.step_nm}nm" + ("%" if p.percent else "")
        print(f"{p.slug:26s} {code:10s} {lab[0]:5.1f} {lab[1]:6.1f} {lab[2]:6.1f} "
              f"{p.thickness_mm:6.3f} {p.background:5s} {grid:5s} "
              f"{smp.true_gap:.4f}@{smp.true_gap_nm:.0f}  {red}")
    fmt = next(s for s in samples if s.product.slug == FORMAT_SLUG)
    written.append(write_xrite_cgats(fmt))
    written.append(write_i1profiler_cgats(fmt))
    written.append(write_ti3(fmt))
    written += write_sp(fmt)
    written.append(write_cs2000(fmt))
    written += write_bad_files(fmt)
    if args.swatches:
        swatch_sheet(samples, args.swatches)
        print(f"swatch sheet: {args.swatches}")
    print(f"wrote {len(written)} files")
    return 0


if __name__ == "__main__":
    sys.exit(main())
