#!/usr/bin/env python3
"""Figures and numbers of the skin model's fit to the Xiao et al. 2016 database for docs/SKIN.md,
from the JSON ``rouge skin fit --json`` wrote (python/gen_skin_tones.py leaves it in
build/skin/xiao2016_fit.json; the database itself is read at run time, never committed).

Writes docs/images/skin_fit_errors.png (ΔE2000 against ITA, and its distribution),
docs/images/skin_fit_params.png (the fitted parameters' distributions) and
docs/images/skin_fit_worst.png (the six worst fits, measured against fitted), and prints the
summary table.

    .venv/bin/python python/skin_fit_report.py [build/skin/xiao2016_fit.json]
"""

from __future__ import annotations

import json
import sys
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

ROOT = Path(__file__).resolve().parent.parent
IMAGES = ROOT / "docs" / "images"
PARAMS = [
    ("melanin_fraction", "melanin volume fraction"),
    ("pheomelanin_share", "pheomelanin share"),
    ("blood_fraction", "blood volume fraction"),
    ("oxygen_saturation", "oxygen saturation"),
    ("scattering_500nm_per_mm", "μs′ at 500 nm (/mm)"),
    ("scattering_power", "scattering power b"),
]
RANGES = {"melanin_fraction": (0, 0.6), "pheomelanin_share": (0, 1), "blood_fraction": (0, 0.3),
          "oxygen_saturation": (0, 1), "scattering_500nm_per_mm": (0.5, 10), "scattering_power": (0, 4)}


def main() -> int:
    path = Path(sys.argv[1]) if len(sys.argv) > 1 else ROOT / "build" / "skin" / "xiao2016_fit.json"
    fits = json.loads(path.read_text())
    de = np.array([f["delta_e"] for f in fits])
    rms = np.array([f["rms"] for f in fits])
    ita = np.array([f["ita_deg"] for f in fits])
    P = {k: np.array([f["params"][k] for f in fits]) for k, _ in PARAMS}
    print(f"{len(fits)} spectra: ΔE2000 median {np.median(de):.2f}, p95 {np.percentile(de, 95):.2f}, max {de.max():.2f}; "
          f"RMS median {np.median(rms):.4f}, p95 {np.percentile(rms, 95):.4f}")
    for lo, hi in [(45, 90), (28, 45), (10, 28), (-30, 10), (-90, -30)]:
        sel = (ita >= lo) & (ita < hi)
        if sel.any():
            print(f"  ITA {lo:>4}..{hi:<4}: {sel.sum():5d} spectra, ΔE2000 median {np.median(de[sel]):.2f}, p95 {np.percentile(de[sel], 95):.2f}")
    print("parameters (5th / 50th / 95th percentile; share at a bound):")
    for k, label in PARAMS:
        lo, hi = RANGES[k]
        at = np.mean((np.abs(P[k] - lo) < 1e-6 * max(1, hi)) | (np.abs(P[k] - hi) < 1e-6 * max(1, hi)))
        q = np.percentile(P[k], [5, 50, 95])
        print(f"  {label:26s} {q[0]:8.4f} {q[1]:8.4f} {q[2]:8.4f}   {100 * at:5.1f}% at a bound")
    IMAGES.mkdir(parents=True, exist_ok=True)

    fig, ax = plt.subplots(1, 2, figsize=(11, 4))
    ax[0].scatter(ita, de, s=3, alpha=0.4, color="#7a4a3a")
    ax[0].set_xlabel("ITA of the measured skin (°)")
    ax[0].set_ylabel("ΔE2000 of the fit (D65, CIE 1931)")
    ax[0].invert_xaxis()
    ax[0].axhline(1.0, color="grey", lw=0.8, ls="--")
    ax[0].set_title("Fit error across the database, light to deep")
    ax[1].hist(de, bins=60, color="#7a4a3a")
    for q, ls in [(50, "-"), (95, "--")]:
        ax[1].axvline(np.percentile(de, q), color="k", ls=ls, lw=0.8, label=f"{q}th percentile {np.percentile(de, q):.2f}")
    ax[1].set_xlabel("ΔE2000")
    ax[1].set_ylabel("spectra")
    ax[1].legend()
    ax[1].set_title(f"{len(fits)} spectra of [Xiao2016]")
    fig.tight_layout()
    fig.savefig(IMAGES / "skin_fit_errors.png", dpi=90)

    fig, axes = plt.subplots(2, 3, figsize=(12, 6.5))
    for a, (k, label) in zip(axes.ravel(), PARAMS):
        a.hist(P[k], bins=50, color="#a0705a")
        a.set_xlabel(label)
        a.set_xlim(*RANGES[k]) if k not in ("melanin_fraction", "blood_fraction") else None
    axes[0, 0].set_ylabel("spectra")
    axes[1, 0].set_ylabel("spectra")
    fig.suptitle("Fitted parameters over the Xiao 2016 database (epidermis 0.1 mm)")
    fig.tight_layout()
    fig.savefig(IMAGES / "skin_fit_params.png", dpi=90)

    worst = np.argsort(-de)[:6]
    fig, axes = plt.subplots(2, 3, figsize=(12, 6.5))
    for a, i in zip(axes.ravel(), worst):
        f = fits[i]
        wl = np.array(f["wavelengths_nm"])
        a.plot(wl, f["fitted_reflectance"], "k-", label="fitted")
        lab = f["lab_measured"]
        bounds = ", ".join(b.replace("_500nm_per_mm", "").replace("_", " ") for b in f["at_bounds"]) or "none"
        a.set_title(f"{f['name']}: ITA {f['ita_deg']:.0f}°, L*a*b* {lab[0]:.0f} {lab[1]:.0f} {lab[2]:.0f}, ΔE {f['delta_e']:.2f}\n"
                    f"at bounds: {bounds}", fontsize=8)
        a.set_xlabel("wavelength (nm)")
        if "measured_reflectance" in f:
            a.plot(wl, f["measured_reflectance"], "o", ms=3, color="#a0705a", label="measured")
    axes[0, 0].legend()
    fig.suptitle("The six worst fits")
    fig.tight_layout()
    fig.savefig(IMAGES / "skin_fit_worst.png", dpi=90)
    print("wrote docs/images/skin_fit_errors.png, skin_fit_params.png, skin_fit_worst.png")
    return 0


if __name__ == "__main__":
    sys.exit(main())
