"""Rouge against Mitsuba 3 on small scenes (64×64, scalar_rgb, seconds each): the camera, the
lights and the units match before any subsurface model is judged, a deliberately wrong camera
or light fails the same check, a non-absorbing medium conserves energy in both renderers, and
`rouge bench translucency` runs on the committed references.

Run from the repository root:  .venv/bin/python -m pytest python/test_mitsuba_match.py
"""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np
import pytest

import mitsuba_ref

mi = pytest.importorskip("mitsuba", reason="mitsuba is in python/requirements.txt; install it")

SMALL = ["--width", "64", "--height", "64"]
REFERENCES = Path(__file__).resolve().parent.parent / "data" / "reference" / "translucency"


@pytest.fixture(scope="module", autouse=True)
def scalar_variant():
    mitsuba_ref.pick_variant("scalar_rgb")


def rouge_linear(rouge, args: list[str], out: Path) -> np.ndarray:
    p = rouge("render", *args, "--out", str(out), timeout=300)
    assert p.returncode == 0, p.stderr
    return mitsuba_ref.read_exr(out)


def mitsuba_image(rouge_bin: str, args: list[str], interior: str, out: Path, spp: int, seed: int = 0):
    xml = mitsuba_ref.export(rouge_bin, args, interior, out)
    return mitsuba_ref.render_halves(xml, spp, max(1, spp // 2), seed0=seed)


def interior_mask(alpha: np.ndarray) -> np.ndarray:
    """Fully covered pixels whose 4-neighbours are covered too (the silhouette differs: Rouge
    samples pixel centres, the film averages the pixel)."""
    m = alpha > 0.999
    inner = m.copy()
    inner[1:] &= m[:-1]
    inner[:-1] &= m[1:]
    inner[:, 1:] &= m[:, :-1]
    inner[:, :-1] &= m[:, 1:]
    return inner


def relative_error(rouge_img: np.ndarray, ref, mask: np.ndarray) -> tuple[float, float]:
    """Mean |Rouge − Mitsuba| over the mask relative to the mean reference radiance, and the
    reference's own relative noise (standard error from its two halves)."""
    r = rouge_img[..., :3][mask]
    m = ref.mean[..., :3][mask]
    noise = 0.5 * np.abs(ref.a - ref.b)[..., :3][mask]
    scale = max(float(m.mean()), 1e-9)
    return float(np.abs(r - m).mean()) / scale, float(noise.mean()) / scale


@pytest.mark.parametrize(
    "mesh",
    [["--mesh", "builtin:sphere"], ["--mesh", "builtin:head", "--subdiv", "1"]],
    ids=["sphere", "head"],
)
def test_opaque_lambertian_matches_and_a_wrong_camera_or_light_fails(rouge, rouge_bin, tmp_path, mesh):
    scene = [*mesh, "--look", "bare", "--lights", "front-left", *SMALL]
    ref = mitsuba_image(rouge_bin, scene, "lambert", tmp_path / "lambert", spp=64)
    mask = interior_mask(ref.mean[..., 3])
    assert mask.sum() > 300, "the object covers too few pixels to compare"
    # --flat-skin: the export has the tone's uniform colour; render draws skin maps by default.
    flat = ["--subsurface", "none", "--no-specular", "--flat-skin"]
    ours = rouge_linear(rouge, [*scene, *flat], tmp_path / "rouge.exr")
    err, noise = relative_error(ours, ref, mask)
    # Shadow maps (PCF) against exact shadows and pixel-centre against box-filtered sampling
    # leave a few per cent at shadow edges; the bulk agrees within the reference's noise.
    assert err < noise + 0.04, f"Rouge vs Mitsuba: mean relative error {err:.4f} (noise {noise:.4f})"
    wrong_light = [a if a != "front-left" else "front" for a in scene]
    bad = rouge_linear(rouge, [*wrong_light, *flat], tmp_path / "wrong_light.exr")
    err_light, _ = relative_error(bad, ref, mask)
    assert err_light > 3 * (noise + 0.04), f"a wrong light passed: {err_light:.4f}"
    bad = rouge_linear(rouge, [*scene, *flat, "--yaw", "12"], tmp_path / "wrong_camera.exr")
    err_cam, _ = relative_error(bad, ref, mask)
    assert err_cam > 2 * (noise + 0.04), f"a wrong camera passed: {err_cam:.4f}"


def test_non_absorbing_medium_conserves_energy_in_both(rouge, rouge_bin, tmp_path):
    """A sphere of a non-absorbing medium under a uniform environment of radiance 1 returns
    every photon: radiance 1 everywhere. Through a smooth boundary Mitsuba must give 1 within
    its noise; through the references' rough boundary (α = 0.1) it loses a little to its
    single-scattering microfacet model (measured 1.5%, docs/TRANSLUCENCY.md). Rouge, drawn
    without its specular lobe, must give what the boundary lets in: the medium's albedo is the
    half-space's subsurface reflectance (render/src/dielectric_half_space.rs), which without
    absorption is 1 − F(0), the Fresnel reflectance at normal incidence going to the specular
    part."""
    env = tmp_path / "white.exr"
    mitsuba_ref.write_exr(env, np.ones((16, 32, 4)), half=False)
    medium = ["--sigma-a", "0,0,0", "--sigma-s", "0.2,0.2,0.2", "--eta", "1.3"]
    scene = ["--mesh", "builtin:sphere", "--look", "bare", "--lights", "none", "--env", str(env), *medium, *SMALL]
    smooth = mitsuba_image(rouge_bin, [*scene, "--boundary-alpha", "0"], "medium", tmp_path / "smooth", spp=32)
    mask = interior_mask(smooth.mean[..., 3])
    mean = float(smooth.mean[..., :3][mask].mean())
    assert abs(mean - 1.0) < 0.02, f"Mitsuba furnace, smooth boundary: mean radiance {mean:.4f}"
    rough = mitsuba_image(rouge_bin, scene, "medium", tmp_path / "rough", spp=32)
    mean = float(rough.mean[..., :3][mask].mean())
    assert 0.95 < mean < 1.01, f"Mitsuba furnace, rough boundary: mean radiance {mean:.4f}"
    ours = rouge_linear(rouge, [*scene, "--no-specular", "--diffuse", "lambert"], tmp_path / "furnace.exr")
    rouge_mean = float(ours[..., :3][mask].mean())
    transmitted = 1.0 - ((1.3 - 1.0) / (1.3 + 1.0)) ** 2
    assert abs(rouge_mean - transmitted) < 0.01, f"Rouge furnace: mean radiance {rouge_mean:.4f}, not {transmitted:.4f}"
    # A medium's default law, the half-space under its boundary, lets in 1 − F(μ) at each exit
    # cosine: the same at the centre of the disc, less towards the rim, where Fresnel sends more to
    # the specular part (render/src/dielectric_brdf.rs).
    law = rouge_linear(rouge, [*scene, "--no-specular"], tmp_path / "furnace_law.exr")
    ys, xs = np.nonzero(mask)
    r = np.hypot(ys - ys.mean(), xs - xs.mean()) / np.sqrt((smooth.mean[..., 3] > 0.5).sum() / np.pi)
    centre = float(law[..., :3][ys[r < 0.3], xs[r < 0.3]].mean())
    rim = float(law[..., :3][ys[r > 0.85], xs[r > 0.85]].mean())
    assert abs(centre - transmitted) < 0.01, f"half-space law, centre: {centre:.4f}, not {transmitted:.4f}"
    assert rim < centre - 0.02, f"half-space law: the rim ({rim:.4f}) is not darker than the centre ({centre:.4f})"


def test_export_is_a_loadable_scene_of_the_same_size(rouge_bin, tmp_path):
    xml = mitsuba_ref.export(rouge_bin, ["--mesh", "builtin:wedge", "--medium", "marble", *SMALL], "medium", tmp_path)
    scene = mi.load_file(str(xml), spp=1)
    assert tuple(scene.sensors()[0].film().size()) == (64, 64)
    text = xml.read_text()
    assert 'name="max_depth" value="-1"' in text and "roughdielectric" in text and "homogeneous" in text


def test_export_without_a_medium_says_why(rouge):
    p = rouge("export", "mitsuba", "--mesh", "builtin:sphere", "--out", "/nonexistent/never", "--interior", "medium")
    assert p.returncode == 2 and "--medium" in p.stderr, p.stderr


def test_references_have_sidecars_with_a_noise_floor():
    sidecars = sorted(REFERENCES.glob("*.json"))
    assert sidecars, f"no references in {REFERENCES}"
    for s in sidecars:
        meta = json.loads(s.read_text())
        assert (REFERENCES / meta["image"]).is_file(), s
        assert meta["mitsuba"] == "3.9.1" and meta["spp"] >= 256 and meta["noise_rms"] > 0, s
        img = mitsuba_ref.read_exr(REFERENCES / meta["image"])
        assert np.isfinite(img).all() and img.shape[2] == 4, s


def test_bench_translucency_runs_on_a_tiny_configuration(rouge, tmp_path):
    out = tmp_path / "rows.json"
    p = rouge("bench", "translucency", "--references", str(REFERENCES), "--only", "sphere-skimmilk",
              "--samples", "5", "--profiles", "better-dipole", "--frames", "1", "--json", str(out),
              "--plot", str(tmp_path / "plot.png"), timeout=600)
    assert p.returncode == 0, p.stderr
    png = (tmp_path / "plot.png").read_bytes()
    assert png[:8] == b"\x89PNG\r\n\x1a\n" and len(png) > 5000, "the plot is not a PNG with content"
    rows = json.loads(out.read_text())
    models = {"none", "screen-space", "thickness", "screen-space+thickness", "slab", "screen-space+slab",
              "slab-gather", "screen-space+slab-gather", "screen-space+slab+bounce", "screen-space+slab-gather+bounce",
              "directional-dipole", "directional-dipole-mfp", "standard-dipole", "cube-atlas"}
    assert {r["model"] for r in rows} == models
    for r in rows:
        assert r["pixels"] > 1000 and np.isfinite([r["rmse"], r["delta_e_mean"], r["delta_e_p95"]]).all(), r
    none = next(r for r in rows if r["model"] == "none")
    kernel = next(r for r in rows if r["model"] == "screen-space")
    assert kernel["rmse"] != none["rmse"]
    # The exact half-space under the same kernel (docs/BENCHMARKS.md: RMSE 0.033 → 0.023 here).
    half = next(r for r in rows if r["model"] == "screen-space" and r["params"].get("diffuse") == "half-space")
    assert "diffuse" not in kernel["params"] and half["rmse"] < 0.85 * kernel["rmse"], (half["rmse"], kernel["rmse"])
    # The thickness model: both sources, three.js's and the fitted parameters; fitted per light,
    # skim milk's sphere comes closer to the path tracer than with no term.
    thickness = {(r["params"]["source"], r["params"]["params"]): r for r in rows if r["model"] == "thickness"}
    assert set(thickness) == {(s, p) for s in ("baked", "shadow-map") for p in ("three.js", "fitted")}
    assert thickness[("shadow-map", "fitted")]["rmse"] < none["rmse"]
    # With timestamp queries (lavapipe has them) the thickness pass has its own time.
    assert all("thickness" in r["pass_ms"] for r in thickness.values() if r["pass_ms"]), "no thickness pass time"
    assert thickness[("baked", "three.js")]["params"]["bake_s"] >= 0
    # The kernel with the term (fitted under the kernel for skim milk): both passes run, and it
    # comes closer than the term alone (docs/BENCHMARKS.md: RMSE 0.0329 → 0.0226 per light).
    combined = {r["params"]["source"]: r for r in rows if r["model"] == "screen-space+thickness"}
    assert set(combined) == {"baked", "shadow-map"} and all(r["params"]["params"] == "fitted" for r in combined.values())
    assert combined["shadow-map"]["rmse"] < thickness[("shadow-map", "fitted")]["rmse"]
    assert all({"thickness", "sss horizontal"} <= set(r["pass_ms"]) for r in combined.values() if r["pass_ms"])
    # The slab law (nothing fitted): its pass timed, closer than no term, and the kernel with it
    # closer still (docs/BENCHMARKS.md "The slab law": RMSE 0.034 → 0.025 → 0.023 here).
    slab = {r["params"]["diffuse"]: r for r in rows if r["model"] == "slab"}
    assert set(slab) == {"lambert", "half-space"}, slab.keys()
    assert all("thickness" in r["pass_ms"] for r in slab.values() if r["pass_ms"]), "no thickness pass time"
    # Its single scattering is marched to the back faces' depth: that pass runs for the slab law
    # alone (docs/BENCHMARKS.md "Single scattering along the view ray").
    assert all("back depth" in r["pass_ms"] for r in slab.values() if r["pass_ms"]), "no back-face depth pass"
    assert not any("back depth" in r["pass_ms"] for r in thickness.values()), "a back-face depth pass for the talk's term"
    kernel_slab = next(r for r in rows if r["model"] == "screen-space+slab")
    assert kernel_slab["rmse"] < slab["half-space"]["rmse"] < none["rmse"], (kernel_slab["rmse"], slab, none["rmse"])
    # The transmission gather in the slab law's place: timed in the same pass; on a sphere, as wide
    # as skim milk's light spreads, the law's plane is there and the law is closer
    # (docs/BENCHMARKS.md "The transmission gather": RMSE 0.018 against 0.033).
    gather = next(r for r in rows if r["model"] == "slab-gather")
    kernel_gather = next(r for r in rows if r["model"] == "screen-space+slab-gather")
    assert gather["params"] == {"diffuse": "half-space"}, gather["params"]
    assert all("thickness" in r["pass_ms"] for r in (gather, kernel_gather) if r["pass_ms"]), "no thickness pass time"
    assert kernel_slab["rmse"] < kernel_gather["rmse"], (kernel_slab["rmse"], kernel_gather["rmse"])
    # The light between surfaces: its two dispatches timed; a sphere is convex, no two of its
    # points face each other, so it adds nothing (docs/BENCHMARKS.md "Light between surfaces").
    for base, bounced in ((kernel_slab, "screen-space+slab+bounce"), (kernel_gather, "screen-space+slab-gather+bounce")):
        row = next(r for r in rows if r["model"] == bounced)
        assert row["params"]["bounce"]["samples"] == 64, row["params"]
        assert not row["pass_ms"] or {"bounce gather", "bounce add"} <= set(row["pass_ms"]), row["pass_ms"]
        assert abs(row["delta_e_mean"] - base["delta_e_mean"]) < 0.01, (row["delta_e_mean"], base["delta_e_mean"])
    # The plot again from the rows alone (--replot), without a run.
    again = tmp_path / "again.png"
    p = rouge("bench", "translucency", "--replot", str(out), "--plot", str(again), timeout=120)
    assert p.returncode == 0, p.stderr
    assert again.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    # The cube atlas at its defaults: its two passes timed (the six faces summed), and on skim
    # milk's sphere within the noise of the standard dipole (docs/BENCHMARKS.md: 3.4 and 2.8 ΔE).
    atlas = next(r for r in rows if r["model"] == "cube-atlas")
    assert atlas["params"]["global"] == "slab" and atlas["params"]["reach"] == "support", atlas["params"]
    if atlas["pass_ms"]:
        assert {"atlas irradiance", "atlas gather"} <= set(atlas["pass_ms"]), atlas["pass_ms"]
    assert atlas["delta_e_mean"] < none["delta_e_mean"], (atlas["delta_e_mean"], none["delta_e_mean"])
