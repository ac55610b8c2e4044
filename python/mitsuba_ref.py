"""Mitsuba 3 references of Rouge's own scenes: export with `rouge export mitsuba`, render in
passes with independent seeds, split the passes into two halves for a noise estimate.

Used by python/render_reference.py (the committed references) and python/test_mitsuba_match.py
(the small CI checks). The subsurface part of a scene is the image with the medium inside minus
the image with a black absorber behind the same boundary (docs/TRANSLUCENCY.md).
"""

from __future__ import annotations

import hashlib
import subprocess
import time
from dataclasses import dataclass
from pathlib import Path

import numpy as np


def pick_variant(preferred: str | None = None) -> str:
    """`preferred`, else cuda_ad_rgb where a CUDA device answers, else scalar_rgb."""
    import mitsuba as mi

    if preferred:
        mi.set_variant(preferred)
        return preferred
    for v in ("cuda_ad_rgb", "scalar_rgb"):
        try:
            mi.set_variant(v)
            if v.startswith("cuda"):
                import drjit as dr

                dr.zeros(mi.Float, 4)  # touches the device: raises without one
                dr.eval()
            return v
        except Exception:  # noqa: BLE001 - any failure means: not this variant
            continue
    raise RuntimeError("no Mitsuba variant runs here (need scalar_rgb at least)")


def export(rouge: str, args: list[str], interior: str, out: Path) -> Path:
    """Runs `rouge export mitsuba ARGS --interior I --out OUT`; returns OUT/scene.xml."""
    cmd = [rouge, "export", "mitsuba", *args, "--interior", interior, "--out", str(out)]
    p = subprocess.run(cmd, capture_output=True, text=True, check=False)
    if p.returncode != 0:
        raise RuntimeError(f"{' '.join(cmd)} failed ({p.returncode}):\n{p.stderr}")
    return out / "scene.xml"


@dataclass
class SceneView:
    """What Mitsuba 3 sees of a scene, per pixel: shading normals `n` and positions `p` (mm), unit
    directions to the camera `v`, the unit direction to its light `l`, and its single scattering
    `single` (RGB)."""

    n: np.ndarray
    p: np.ndarray
    v: np.ndarray
    l: np.ndarray
    single: np.ndarray


def scene_view(rouge: str, options: list[str], spp: int) -> SceneView:
    """The [`SceneView`] of the medium scene `rouge export mitsuba --without-parts` writes from
    `options` (the head as its references were rendered, before it had lashes, brows, teeth and
    tongue; as `rouge bench translucency` draws it), on `scalar_rgb`: an `aov` render of the
    shading normals and positions, and a `volpathmis` render with `max_depth` 2 at `spp`."""
    import tempfile

    import mitsuba as mi

    mi.set_variant("scalar_rgb")
    with tempfile.TemporaryDirectory() as tmp:
        xml = export(rouge, [*options, "--without-parts"], "medium", Path(tmp) / "medium")
        scene = mi.load_file(str(xml))
        aovs = mi.load_dict({"type": "aov", "aovs": "nn:sh_normal,pp:position"})
        aov = np.array(mi.render(scene, integrator=aovs, spp=4))
        once = mi.load_dict({"type": "volpathmis", "max_depth": 2, "hide_emitters": True})
        single = np.array(mi.render(scene, integrator=once, spp=spp))[..., :3]
        camera = np.array(scene.sensors()[0].world_transform().translation())
        emitter = next(e for e in scene.emitters() if not e.is_environment())
        l = -np.array(emitter.world_transform() @ mi.Vector3f(0, 0, 1))
    n, p = aov[..., :3], aov[..., 3:6]
    v = camera - p
    v /= np.maximum(np.linalg.norm(v, axis=-1, keepdims=True), 1e-9)
    return SceneView(n=n, p=p, v=v, l=l / np.linalg.norm(l), single=single)


def scene_hash(scene_dir: Path) -> str:
    """SHA-256 over scene.xml and the files beside it, in name order."""
    h = hashlib.sha256()
    for f in sorted(scene_dir.iterdir()):
        if f.is_file():
            h.update(f.name.encode())
            h.update(f.read_bytes())
    return h.hexdigest()


@dataclass
class Halves:
    """Two independent estimates of one image (H×W×4, linear RGB + coverage)."""

    a: np.ndarray
    b: np.ndarray
    spp: int
    seconds: float

    @property
    def mean(self) -> np.ndarray:
        return 0.5 * (self.a + self.b)


def render_halves(
    xml: Path, spp: int, spp_per_pass: int, seed0: int = 0, max_seconds: float | None = None
) -> Halves:
    """Renders `spp` samples per pixel in passes of `spp_per_pass` with seeds seed0, seed0+1, ...;
    even passes go to half a, odd to half b (so `spp` should be a multiple of 2·spp_per_pass).
    With `max_seconds`, stops after the first pair of passes that ends past it."""
    import mitsuba as mi

    scene = mi.load_file(str(xml), spp=spp_per_pass)
    passes = max(2, spp // spp_per_pass)
    passes += passes % 2
    acc = [None, None]
    t0 = time.perf_counter()
    done = 0
    for k in range(passes):
        img = np.array(mi.render(scene, seed=seed0 + k, spp=spp_per_pass), dtype=np.float64)
        half = k % 2
        acc[half] = img if acc[half] is None else acc[half] + img
        done = k + 1
        if max_seconds is not None and half == 1 and time.perf_counter() - t0 > max_seconds:
            break
    seconds = time.perf_counter() - t0
    n = done // 2
    return Halves(acc[0] / n, acc[1] / n, done * spp_per_pass, seconds)


def gray_channel_scenes(xml: Path) -> list[Path]:
    """Three copies of a scene whose interior medium is gray: copy c has channel c's albedo and
    extinction in all three channels. Rendering channel c from copy c gives the same expected
    image as the chromatic medium, without the path weights that differ per channel (in a
    bright chromatic medium, after hundreds of scattering events those ratios reach
    hundreds: single bright coloured pixels that converge very slowly, even with spectral MIS)."""
    import xml.etree.ElementTree as ET

    out = []
    for c in range(3):
        tree = ET.parse(xml)
        medium = tree.getroot().find("medium[@id='interior']")
        if medium is None:
            raise ValueError(f"{xml}: no medium with id 'interior'")
        for rgb in medium.findall("rgb"):
            v = [x.strip() for x in rgb.get("value", "").split(",")]
            rgb.set("value", ", ".join([v[c]] * 3))
        path = xml.with_name(f"scene_channel{c}.xml")
        tree.write(path)
        out.append(path)
    return out


def render_halves_per_channel(
    xml: Path, spp: int, spp_per_pass: int, seed0: int = 0, max_seconds: float | None = None
) -> Halves:
    """[`render_halves`] of the three gray-channel copies of `xml` (each with a third of the time
    budget), channel c taken from copy c; alpha from the first. `spp` is the smallest count."""
    parts = [
        render_halves(x, spp, spp_per_pass, seed0, None if max_seconds is None else max_seconds / 3)
        for x in gray_channel_scenes(xml)
    ]
    a, b = parts[0].a.copy(), parts[0].b.copy()
    for c in (1, 2):
        a[..., c], b[..., c] = parts[c].a[..., c], parts[c].b[..., c]
    return Halves(a, b, min(p.spp for p in parts), sum(p.seconds for p in parts))


def subsurface(medium: Halves, absorber: Halves) -> tuple[np.ndarray, float, np.ndarray]:
    """The subsurface image (medium − absorber, RGB, coverage in alpha from the medium render),
    the RMS standard error of its pixels over fully covered pixels, and that mask."""
    img = medium.mean - absorber.mean
    # Coverage: where the absorber stops the camera ray (with an index-matched boundary a ray can
    # cross a thin, clear medium without an interaction, so the medium's alpha is not coverage).
    img[..., 3] = np.maximum(medium.mean[..., 3], absorber.mean[..., 3])
    # Standard error of the mean of two halves: |a − b| / 2 per pixel and channel.
    diff = (medium.a - medium.b) - (absorber.a - absorber.b)
    mask = img[..., 3] > 0.999
    se = 0.5 * diff[..., :3][mask]
    noise = float(np.sqrt(np.mean(se**2))) if se.size else 0.0
    return img, noise, mask


def write_exr(path: Path, rgba: np.ndarray, half: bool = True) -> None:
    """Writes an RGBA EXR (half floats by default, Mitsuba's default compression)."""
    import mitsuba as mi

    bmp = mi.Bitmap(np.ascontiguousarray(rgba, dtype=np.float32), mi.Bitmap.PixelFormat.RGBA)
    if half:
        bmp = bmp.convert(mi.Bitmap.PixelFormat.RGBA, mi.Struct.Type.Float16, False)
    path.parent.mkdir(parents=True, exist_ok=True)
    tmp = path.with_suffix(".tmp.exr")
    bmp.write(str(tmp))
    tmp.replace(path)


def read_exr(path: Path) -> np.ndarray:
    """An EXR as a float64 H×W×C array."""
    import mitsuba as mi

    return np.array(mi.Bitmap(str(path)), dtype=np.float64)
