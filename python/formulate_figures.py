#!/usr/bin/env python3
"""The figures and tables of docs/FORMULATION.md sections 5-9 (metamerism, the uncertainty of S
and K, batch correction, QC, recipe search), made by driving the `rouge` binary on the sample
measurements and presets and on three Xiao 2016 skins (`python/skin_gamut.py --count 3 --out
build/skin/xiao2016_3.csv` first); the QC batches are mixed with the `rouge` package.

    .venv/bin/python python/formulate_figures.py --rouge target/debug/rouge --out build/formulate

Writes `uncertainty.md` (a table per sample measurement), `metamerism_skin.md`, `qc.txt`,
`recipe.txt`, and the PNGs `docs/images/metamerism_foundation_on_skin.png` and
`docs/images/qc_foundation_03_sand.png`, `docs/images/recipe_lipstick_01_nude.png` (with
`--images`).
"""

from __future__ import annotations

import argparse
import json
import subprocess
from pathlib import Path

import numpy as np

REPO = Path(__file__).resolve().parent.parent
FOUNDATIONS = [f"foundation_0{i}_{n}" for i, n in enumerate(["porcelain", "ivory", "sand", "caramel", "espresso"], 1)]


def run(rouge: str, *args: str) -> str:
    return subprocess.run([rouge, *args], check=True, capture_output=True, text=True).stdout


def uncertainty_table(rouge: str, out: Path) -> str:
    rows = ["| measurement | D (µm) | median u(S)/S | max u(S)/S (nm) | median u(K)/K | ill-conditioned λ | best D (µm) | RMS rel. u at D | at best D |",
            "|---|---:|---:|---:|---:|---:|---:|---:|---:|"]
    for csv in sorted((REPO / "data" / "measurements").glob("*.csv")):
        text = run(rouge, "import", str(csv), "--out", str(out / f"{csv.stem}.json"), "--json")
        u = json.loads(text)["uncertainty"]
        s, k = u["relative_u_s"], u["relative_u_k"]
        best = u["best_thickness"]
        rows.append(
            f"| {csv.stem} | {json.loads(text)['thickness_mm'] * 1e3:.0f} | {100 * s[0]:.1f} % | {100 * s[1]:.0f} % ({s[2]:.0f}) "
            f"| {100 * k[0]:.1f} % | {len(u['ill_conditioned_nm'])} | {best['thickness_mm'] * 1e3:.0f} "
            f"| {100 * u['criterion_at_measured_thickness']:.1f} % | {100 * best['relative_uncertainty']:.1f} % |"
        )
    return "\n".join(rows) + "\n"


def metamerism_on_skin(rouge: str, out: Path, skins: Path, images: Path | None) -> str:
    """Each skin against each foundation worn over it at 20 µm: does 'your shade' hold in
    other lights? Index per test illuminant, multiplicative correction, ΔE2000."""
    names = [ln.split(",")[1:] for ln in skins.read_text().splitlines() if ln.startswith("wavelength_nm")][0]
    tests = ["A", "FL11", "LED-B3"]
    rows = ["| skin | foundation at 20 µm | ΔE2000 under D65 | A | FL11 | LED-B3 | 10° observer |",
            "|---|---|---:|---:|---:|---:|---:|"]
    grid = {}
    for skin in names:
        for f in FOUNDATIONS:
            js = out / f"m_{skin}_{f}.json"
            run(rouge, "analyze", "metamerism", f"{skins}#{skin}", f, "--thickness-um", "20", "--skin", str(skins),
                "--skin-sample", skin, "--extrapolate", "--test", ",".join(tests), "--json", str(js))
            m = json.loads(js.read_text())
            by = {r["illuminant"]: r["delta_e_2000"] for r in m["illuminant"] if r["correction"] == "multiplicative"}
            obs = [r["delta_e_2000"] for r in m["observer"] if r["correction"] == "multiplicative"][0]
            grid[(skin, f)] = [m["reference_match"]["delta_e_2000"], *[by[t] for t in tests], obs]
            rows.append(f"| {skin} | {f} | " + " | ".join(f"{v:.2f}" for v in grid[(skin, f)]) + " |")
    if images is not None:
        import matplotlib

        matplotlib.use("Agg")
        import matplotlib.pyplot as plt

        fig, axes = plt.subplots(1, len(names), figsize=(4.2 * len(names), 3.6), sharey=True)
        labels = ["D65: the pair itself", "A", "FL11", "LED-B3", "10° obs."]
        x = np.arange(len(FOUNDATIONS))
        for ax, skin in zip(np.atleast_1d(axes), names):
            for j, lab in enumerate(labels):
                ax.bar(x + (j - 2) * 0.16, [grid[(skin, f)][j] for f in FOUNDATIONS], 0.16, label=lab)
            ax.set_xticks(x, [f.split("_")[2] for f in FOUNDATIONS], rotation=30)
            ax.set_title(skin)
            ax.grid(axis="y", alpha=0.3)
        np.atleast_1d(axes)[0].set_ylabel("ΔE2000, bare skin vs covered (mult. corr.)")
        np.atleast_1d(axes)[0].legend(fontsize=8)
        fig.suptitle("Foundations worn at 20 µm on three Xiao 2016 skins: the mismatch under D65 and the "
                     "metamerism index under other lights", fontsize=10)
        fig.tight_layout()
        fig.savefig(images / "metamerism_foundation_on_skin.png", dpi=110)
    return "\n".join(rows) + "\n"


def preset_sk(name: str) -> tuple[np.ndarray, np.ndarray]:
    p = json.loads((REPO / "data" / "presets" / f"{name}.json").read_text())
    return np.array(p["s_per_mm"]), np.array(p["k_per_mm"])


def qc_figure(rouge: str, out: Path, images: Path | None) -> str:
    """Production batches of Sand with 2-12 % of another foundation or a blush mixed in (Duncan's
    rule, by the `rouge` package), judged in CMC(2:1) at 1 with the PNG report."""
    import rouge as rg

    others = {"ivory": "foundation_02_ivory", "caramel": "foundation_04_caramel", "coral": "blush_02_coral",
              "espresso": "foundation_05_espresso"}
    sand = preset_sk("foundation_03_sand")
    columns = {}
    for short, name in others.items():
        other = preset_sk(name)
        for pct in (2, 5, 8, 12):
            c = pct / 100
            S, K = rg.SK_mix_Duncan(np.stack([sand[0], other[0]]), np.stack([sand[1], other[1]]), [1 - c, c])
            columns[f"{short}_{pct}pct"] = np.asarray(rg.SK_to_Rinf_KubelkaMunk(np.asarray(S), np.asarray(K)))
    table = out / "qc_batches.csv"
    lines = ["wavelength_nm," + ",".join(columns)]
    for i, nm in enumerate(range(380, 781, 5)):
        lines.append(f"{nm}," + ",".join(f"{v[i]:.6f}" for v in columns.values()))
    table.write_text("\n".join(lines) + "\n")
    args = ["qc", "foundation_03_sand", str(table), "--metric", "cmc", "--cmc", "2:1", "--tolerance", "1",
            "--json", str(out / "qc.json")]
    if images is not None:
        args += ["--png", str(images / "qc_foundation_03_sand.png")]
    return run(rouge, *args)


def recipe_runs(rouge: str, images: Path | None) -> str:
    """The recipe search of section 9 and its bench."""
    base = ["analyze", "recipe", "lipstick_01_nude", "--library", str(REPO / "data" / "presets"),
            "--max", "lipstick_01_nude=0", "--k", "3", "--top", "3"]
    png = [] if images is None else ["--png", str(images / "recipe_lipstick_01_nude.png")]
    text = run(rouge, *base, *png) + run(rouge, *base, "--illuminants", "D65")
    return text + run(rouge, "bench", "recipe", "--presets", str(REPO / "data" / "presets"))


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--rouge", default=str(REPO / "target" / "debug" / "rouge"))
    ap.add_argument("--out", type=Path, default=REPO / "build" / "formulate")
    ap.add_argument("--skins", type=Path, default=REPO / "build" / "skin" / "xiao2016_3.csv")
    ap.add_argument("--images", action="store_true", help="write docs/images/*.png")
    a = ap.parse_args()
    a.out.mkdir(parents=True, exist_ok=True)
    (a.out / "uncertainty.md").write_text(uncertainty_table(a.rouge, a.out))
    images = REPO / "docs" / "images" if a.images else None
    (a.out / "metamerism_skin.md").write_text(metamerism_on_skin(a.rouge, a.out, a.skins, images))
    (a.out / "qc.txt").write_text(qc_figure(a.rouge, a.out, images))
    (a.out / "recipe.txt").write_text(recipe_runs(a.rouge, images))
    print((a.out / "uncertainty.md").read_text())
    print((a.out / "metamerism_skin.md").read_text())
    print((a.out / "qc.txt").read_text())
    print((a.out / "recipe.txt").read_text())
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
