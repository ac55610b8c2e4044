"""Speed against error per scene from `rouge bench translucency --json F`.

  python python/plot_translucency.py rows.json --out docs/images/translucency.png

One panel per reference scene: GPU ms per frame (x) against mean ΔE2000 to the Mitsuba 3
reference (y); one line per screen-space profile through its sample counts, a cross for no
subsurface scattering, a star for today's skin (ColorChecker albedo, d'Eon's profile). Needs
matplotlib (python/requirements-plot.txt).
"""

from __future__ import annotations

import argparse
import json
import math
from collections import defaultdict
from pathlib import Path


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("rows", type=Path)
    ap.add_argument("--out", type=Path, required=True)
    ap.add_argument("--metric", default="delta_e_mean", choices=["delta_e_mean", "delta_e_p95", "rmse"])
    a = ap.parse_args()
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    rows = json.loads(a.rows.read_text())
    scenes = sorted({r["scene"] for r in rows})
    cols = min(4, len(scenes))
    nrows = math.ceil(len(scenes) / cols)
    fig, axes = plt.subplots(nrows, cols, figsize=(4.2 * cols, 3.6 * nrows), squeeze=False)
    x_of = lambda r: r["gpu_ms"] if r["gpu_ms"] is not None else r["wall_ms"]  # noqa: E731
    colours = {"dipole": "tab:blue", "better-dipole": "tab:orange", "burley": "tab:green"}
    for ax, scene in zip(axes.flat, scenes):
        lines = defaultdict(list)
        for r in rows:
            if r["scene"] != scene:
                continue
            if r["model"] == "none":
                ax.scatter([x_of(r)], [r[a.metric]], marker="x", color="black", label="none", zorder=3)
            elif r["params"].get("profile") == "deon-skin":
                ax.scatter([x_of(r)], [r[a.metric]], marker="*", s=90, color="tab:red", label="today's skin", zorder=3)
            else:
                lines[r["params"]["profile"]].append((r["params"]["samples"], x_of(r), r[a.metric]))
        for profile, pts in lines.items():
            pts.sort()
            ax.plot([p[1] for p in pts], [p[2] for p in pts], "o-", ms=3, color=colours.get(profile), label=profile)
            for n, x, y in (pts[0], pts[-1]):
                ax.annotate(str(n), (x, y), fontsize=7, xytext=(2, 2), textcoords="offset points")
        noise = next((r["reference_noise_rms"] for r in rows if r["scene"] == scene), None)
        ax.set_title(f"{scene}" + (f"  (ref. noise {noise:.1e})" if noise else ""), fontsize=9)
        ax.set_xlabel("GPU ms per frame" if rows[0]["gpu_ms"] is not None else "wall ms per frame", fontsize=8)
        ax.set_ylabel({"delta_e_mean": "mean ΔE2000", "delta_e_p95": "p95 ΔE2000", "rmse": "RMSE"}[a.metric], fontsize=8)
        ax.tick_params(labelsize=7)
        ax.grid(alpha=0.3)
    for ax in list(axes.flat)[len(scenes):]:
        ax.axis("off")
    handles, labels = {}, []
    for ax in axes.flat:
        for h, l in zip(*ax.get_legend_handles_labels()):
            handles.setdefault(l, h)
    fig.legend(handles.values(), handles.keys(), loc="lower center", ncol=len(handles), fontsize=8)
    device = rows[0]["device"] if rows else ""
    fig.suptitle(f"Subsurface models against Mitsuba 3 (speed vs error) — {device}", fontsize=10)
    fig.tight_layout(rect=(0, 0.05, 1, 0.96))
    a.out.parent.mkdir(parents=True, exist_ok=True)
    fig.savefig(a.out, dpi=110)
    print(f"wrote {a.out}")


if __name__ == "__main__":
    main()
