"""The synthetic cosmetic products of python/gen_samples.py: the pigment mixtures, their true
K and S, what an instrument would read over each background (Kubelka-Munk), the seeded noise,
and the Rouge CSV, truth and pigment-library writers. Deterministic (fixed seeds, PCG64).
"""

from __future__ import annotations

import sys
import warnings
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


