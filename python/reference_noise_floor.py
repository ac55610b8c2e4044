"""How much of a translucency score is the reference's own noise (issue 31; docs/BENCHMARKS.md
"The slab law").

`rouge bench translucency` scores a model by the mean ΔE2000 of the tone-mapped images (Khronos
PBR Neutral at exposure 1, then sRGB; `render/src/study.rs`) against a Mitsuba 3 reference that
carries Monte Carlo noise. On dark, noisy references that noise alone is a large share of the
score: a perfect model would not reach 0. This script estimates it per scene:

- floor: ΔE2000 between the reference and the reference smoothed by a Gaussian of `--sigma-px`
  pixels (coverage-weighted), over the interior pixels (the whole kernel covered), so the
  smoothing's own bias at silhouettes stays out;
- with `--model` (rouge render options, e.g. "--subsurface slab"): the model's ΔE against the
  reference and against the smoothed reference on the same interior pixels.

    python python/reference_noise_floor.py --scenes wedge-marble,wedge-skimmilk --model "--subsurface slab"

With `--bin N` both the reference (and its smoothed self) and the model are first averaged over
N×N blocks whose pixels are all covered, as `rouge bench translucency`'s `delta_e_binned` is
(`rouge_render::translucency::binned`, N = 4): the floor there is what the reference's noise
leaves in the blocked score.

Smoothing also blurs real gradients; on the wedges and spheres they are gentle (a few percent per
pixel), so the smoothed image stands for the noise-free one there; on the hand and heads, read
the floor as an upper bound.
"""

from __future__ import annotations

import argparse
import json
import shlex
import subprocess
import sys
import tempfile
from pathlib import Path

import numpy as np

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE))

import mitsuba_ref  # noqa: E402


def pbr_neutral(c: np.ndarray) -> np.ndarray:
    """Khronos PBR Neutral ([KhronosNeutral]), as `rouge_render::study::pbr_neutral`."""
    start, desat = 0.76, 0.15
    x = c.min(axis=-1, keepdims=True)
    c = c - np.where(x < 0.08, x - 6.25 * x * x, 0.04)
    peak = c.max(axis=-1, keepdims=True)
    d = 1.0 - start
    new_peak = 1.0 - d * d / np.maximum(peak + d - start, 1e-12)
    g = 1.0 - 1.0 / (desat * (peak - new_peak) + 1.0)
    compressed = c * new_peak / np.maximum(peak, 1e-12)
    compressed = compressed + (new_peak - compressed) * g
    return np.where(peak < start, c, compressed)


def lab(rgb: np.ndarray) -> np.ndarray:
    import colour

    srgb = colour.cctf_encoding(np.clip(pbr_neutral(rgb), 0.0, 1.0))
    return colour.XYZ_to_Lab(colour.sRGB_to_XYZ(srgb, apply_cctf_decoding=True))


def delta_e(a: np.ndarray, b: np.ndarray) -> float:
    import colour

    return float(colour.delta_E(lab(a), lab(b), method="CIE 2000").mean())


def smoothed(rgb: np.ndarray, covered: np.ndarray, sigma: float) -> tuple[np.ndarray, np.ndarray]:
    """The coverage-weighted Gaussian smoothing of `rgb`, and the pixels whose kernel is covered."""
    from scipy.ndimage import gaussian_filter

    w = gaussian_filter(covered.astype(np.float64), sigma)
    out = np.stack([gaussian_filter(rgb[..., c] * covered, sigma) for c in range(3)], axis=-1)
    return out / np.maximum(w, 1e-12)[..., None], covered & (w > 0.999)


def binned(rgb: np.ndarray, mask: np.ndarray, n: int) -> tuple[np.ndarray, np.ndarray]:
    """`rgb` averaged over n×n blocks, and the blocks whose pixels are all in `mask` (a partial
    block at the right or bottom edge is dropped), as `rouge_render::translucency::binned`."""
    h, w = mask.shape[0] // n, mask.shape[1] // n
    blocks = rgb[: h * n, : w * n].reshape(h, n, w, n, 3).mean(axis=(1, 3))
    return blocks, mask[: h * n, : w * n].reshape(h, n, w, n).all(axis=(1, 3))


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--references", type=Path, default=HERE.parent / "data" / "reference" / "translucency")
    ap.add_argument("--scenes", default="", help="comma-separated sidecar names (default: all)")
    ap.add_argument("--sigma-px", type=float, default=2.0)
    ap.add_argument("--model", default="", help="rouge render options of a model to score too")
    ap.add_argument("--bin", type=int, default=1, help="score over N×N blocks (1: per pixel)")
    ap.add_argument("--rouge", default=str(HERE.parent / "target" / "release" / "rouge"))
    a = ap.parse_args()
    names = [s for s in a.scenes.split(",") if s] or sorted(p.stem for p in a.references.glob("*.json"))
    print("| scene | reference noise (RMS) | interior pixels (blocks) | floor: ΔE(reference, smoothed) |"
          + (" model: ΔE against the reference / the smoothed reference |" if a.model else ""))
    print("| --- | --- | --- | --- |" + (" --- |" if a.model else ""))
    with tempfile.TemporaryDirectory() as tmp:
        for name in names:
            side = json.loads((a.references / f"{name}.json").read_text())
            ref = mitsuba_ref.read_exr(a.references / side["image"])
            covered = ref[..., 3] > 0.999
            rgb = ref[..., :3]
            smooth, inner = smoothed(rgb, covered, a.sigma_px)
            smooth, _ = binned(smooth, inner, a.bin)
            blocks, inner = binned(rgb, inner, a.bin)
            row = f"| {name} | {side['noise_rms']:.2e} | {int(inner.sum())} | {delta_e(blocks[inner], smooth[inner]):.2f} |"
            if a.model:
                out = Path(tmp) / f"{name}.exr"
                cmd = [a.rouge, "render", *side["rouge_options"], *shlex.split(a.model), "--no-specular", "--out", str(out)]
                subprocess.run(cmd, check=True, capture_output=True, cwd=HERE.parent)
                img, _ = binned(mitsuba_ref.read_exr(out)[..., :3], np.ones(covered.shape, bool), a.bin)
                row += f" {delta_e(img[inner], blocks[inner]):.2f} / {delta_e(img[inner], smooth[inner]):.2f} |"
            print(row, flush=True)


if __name__ == "__main__":
    main()
