"""A catalogue of renders: lipstick shades × skin tones × expressions, each a PNG as `rouge render`
draws it, and a CSV of per-image colour figures, rendered in this process or on a Dask cluster
(`dask.distributed`), where each worker process holds one `rouge.Renderer` (one GPU device).

Each image is the default look's blush (no foundation, so the tone shows) with the shade on the
lips region (20 µm). The colour figures are display-referred: the image's sRGB decoded to CIELAB (D65) over the
lips, the pixels the shade changes against the same frame without the shade (drawn once per tone
and expression on each worker, then cached), with the mean ΔE2000 between the two there.

    .venv/bin/python python/catalogue.py --out cat/                         # here, one renderer
    .venv/bin/python python/catalogue.py --out cat/ --workers 2             # a LocalCluster of 2
    .venv/bin/python python/catalogue.py --out cat/ --scheduler tcp://HOST:8786   # a cluster

Needs the `rouge` wheel with its renderer (`maturin develop -m py/Cargo.toml --features render`),
Pillow, and for --workers/--scheduler `dask` and `distributed`. The workers send back PNG bytes
and figures and this process writes them, so the cluster needs no shared file system.
"""

from __future__ import annotations

import argparse
import csv
import io
import itertools
import pathlib
import sys
import time

SHADES = ["builtin:lipstick_01_nude", "builtin:lipstick_02_red", "builtin:lipstick_03_berry"]
TONES = ["light", "medium", "deep"]
EXPRESSIONS = ["neutral", "smile"]
FIELDS = ["file", "shade", "tone", "expression", "lips_pixels", "lips_L", "lips_a", "lips_b",
          "delta_E00_vs_bare_lips", "seconds", "worker"]

# Per process (so per Dask worker): the frames without a shade, by (tone, expression, size).
_BARE_LIPS: dict = {}


def _lab(srgb8):
    """CIELAB (D65) of 8-bit sRGB pixels (…, 3)."""
    import numpy as np
    import rouge

    v = srgb8.astype(np.float64) / 255.0
    lin = np.where(v <= 0.04045, v / 12.92, ((v + 0.055) / 1.055) ** 2.4)
    m = np.array([[0.4124, 0.3576, 0.1805], [0.2126, 0.7152, 0.0722], [0.0193, 0.1192, 0.9505]])
    return rouge.XYZ_to_Lab(lin @ m.T)


def blush_only():
    """The default look without its foundation (so the tone shows) and without its lipstick."""
    import rouge

    look = rouge.Look.default_look()
    look.remove_layer(2)
    look.remove_layer(0)
    return look


def render_one(shade: str, tone: str, expression: str, width: int, height: int, subdiv: int) -> tuple[dict, bytes]:
    """One image and its figures (runs on a worker: the process's one renderer draws it)."""
    import socket

    import numpy as np
    import rouge
    from PIL import Image

    t = time.perf_counter()
    renderer = rouge._render.default_renderer()
    frame = dict(skin_tone=tone, expression=None if expression == "neutral" else expression,
                 width=width, height=height, subdiv=subdiv)
    key = (tone, expression, width, height, subdiv)
    if key not in _BARE_LIPS:
        _BARE_LIPS[key] = renderer.render(look=blush_only(), **frame)
    look = blush_only()
    look.add_layer(shade, {"region": "lips", "thickness_mm": 0.02})
    img = renderer.render(look=look, **frame)
    bare = _BARE_LIPS[key]
    lips = np.abs(img[..., :3].astype(int) - bare[..., :3].astype(int)).sum(axis=-1) > 6
    lab, lab_bare = _lab(img[..., :3][lips]), _lab(bare[..., :3][lips])
    de = rouge.delta_E_CIE2000(lab, lab_bare) if lips.any() else np.zeros(0)
    name = f"{shade.split(':')[-1]}_{tone}_{expression}.png"
    buf = io.BytesIO()
    Image.fromarray(img, "RGBA").save(buf, format="PNG")
    mean = lab.mean(axis=0) if lips.any() else [float("nan")] * 3
    row = {
        "file": name, "shade": shade, "tone": tone, "expression": expression,
        "lips_pixels": int(lips.sum()), "lips_L": round(float(mean[0]), 3), "lips_a": round(float(mean[1]), 3),
        "lips_b": round(float(mean[2]), 3), "delta_E00_vs_bare_lips": round(float(np.mean(de)) if de.size else float("nan"), 3),
        "seconds": round(time.perf_counter() - t, 3), "worker": socket.gethostname() + f":{__import__('os').getpid()}",
    }
    return row, buf.getvalue()


def progress(done: int, total: int, start: float) -> None:
    width = 30
    filled = width * done // max(total, 1)
    rate = done / max(time.perf_counter() - start, 1e-9)
    print(f"\r[{'#' * filled}{'.' * (width - filled)}] {done}/{total} images, {rate:.2f} images/s",
          end="" if done < total else "\n", file=sys.stderr, flush=True)


def run(jobs, out: pathlib.Path, workers: int = 0, scheduler: str | None = None) -> dict:
    """Renders `jobs` (tuples of render_one's arguments), writes the PNGs and catalogue.csv into
    `out`, and returns how long it took."""
    out.mkdir(parents=True, exist_ok=True)
    rows, start = [], time.perf_counter()

    def keep(row, png):
        (out / row["file"]).write_bytes(png)
        rows.append(row)
        progress(len(rows), len(jobs), start)

    if workers or scheduler:
        from dask.distributed import Client, LocalCluster, as_completed

        cluster = None if scheduler else LocalCluster(n_workers=workers, threads_per_worker=1, processes=True,
                                                      dashboard_address=None)
        with Client(scheduler or cluster) as client:
            # One task per image; a worker renders its tasks one after another on its renderer.
            futures = [client.submit(render_one, *job, pure=False) for job in jobs]
            for future in as_completed(futures):
                keep(*future.result())
        if cluster is not None:
            cluster.close()
    else:
        for job in jobs:
            keep(*render_one(*job))
    seconds = time.perf_counter() - start
    rows.sort(key=lambda r: r["file"])
    with open(out / "catalogue.csv", "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=FIELDS)
        w.writeheader()
        w.writerows(rows)
    return {"images": len(rows), "seconds": seconds, "images_per_second": len(rows) / seconds}


def main(argv=None) -> None:
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--out", type=pathlib.Path, required=True)
    p.add_argument("--shades", default=",".join(SHADES), help="comma-separated presets")
    p.add_argument("--tones", default=",".join(TONES), help="comma-separated tones or ITA°")
    p.add_argument("--expressions", default=",".join(EXPRESSIONS), help="comma-separated; neutral for none")
    p.add_argument("--width", type=int, default=320)
    p.add_argument("--height", type=int, default=240)
    p.add_argument("--subdiv", type=int, default=1)
    p.add_argument("--workers", type=int, default=0, help="a LocalCluster of this many worker processes")
    p.add_argument("--scheduler", help="address of a running Dask scheduler")
    a = p.parse_args(argv)
    split = lambda s: [x.strip() for x in s.split(",") if x.strip()]
    jobs = [(s, t, e, a.width, a.height, a.subdiv)
            for s, t, e in itertools.product(split(a.shades), split(a.tones), split(a.expressions))]
    if not jobs:
        p.error("--shades, --tones and --expressions must each name at least one")
    stats = run(jobs, a.out, a.workers, a.scheduler)
    print(f"{stats['images']} images in {stats['seconds']:.1f} s: {stats['images_per_second']:.2f} images/s "
          f"({'scheduler ' + a.scheduler if a.scheduler else f'LocalCluster of {a.workers}' if a.workers else 'this process'})")


if __name__ == "__main__":
    main()
