"""`rouge export materialx` checked by MaterialX itself (PyPI `materialx`, python/requirements.txt):
the .mtlx passes `Document.validate()` against MaterialX's standard libraries (every node and
input matches its declaration, `open_pbr_surface` included), names only files that were written,
and a look with a gloss layer gets OpenPBR's coat where the gloss lies (the lips) and nowhere else.
Skipped, saying so, where `materialx` is not installed."""

import json
import re
import subprocess

import numpy as np
import pytest

mx = pytest.importorskip("MaterialX", reason="SKIPPED: PyPI materialx is not installed (pip install -r python/requirements.txt)")


def export(rouge_bin, out, *options):
    cmd = [rouge_bin, "export", "materialx", "--subdiv", "0", "--flat-skin", "--textures", "256", *options, "--out", str(out)]
    done = subprocess.run(cmd, capture_output=True, text=True)
    assert done.returncode == 0, done.stderr
    return done.stderr


def plain(name):
    """A texture's name without its content tag: skin_base_color.<16 hex>.png -> skin_base_color.png."""
    return re.sub(r"\.[0-9a-f]{16}\.png$", ".png", name)


def texture(out, name):
    """The texture `name` (plain) in `out`, named by its content."""
    (found,) = [p for p in out.iterdir() if plain(p.name) == name]
    return found


def validated(path):
    doc = mx.createDocument()
    mx.readFromXmlFile(doc, str(path))
    lib = mx.createDocument()
    mx.loadLibraries(mx.getDefaultDataLibraryFolders(), mx.getDefaultDataSearchPath(), lib)
    doc.importLibrary(lib)
    valid, message = doc.validate()
    assert valid, message
    return doc


def test_the_default_look_validates_and_names_only_written_files(rouge_bin, tmp_path):
    export(rouge_bin, tmp_path)
    doc = validated(tmp_path / "face.mtlx")
    skin = doc.getNode("skin_surface")
    assert skin.getNodeDef().getName() == "ND_open_pbr_surface_surfaceshader"
    assert skin.getInput("subsurface_weight").getValue() == 1.0
    assert skin.getInput("coat_weight").getValue() == 0.0, "the default look has no gloss"
    assert skin.getInput("specular_ior").getValue() == pytest.approx(1.4)
    scale = skin.getInput("subsurface_radius_scale").getValue()
    assert scale[0] == 1.0 and scale[0] > scale[1] > scale[2], "red scatters farthest"
    files = {n.getInputValue("file") for n in doc.getNodes() if n.getCategory() == "image"}
    assert {plain(f) for f in files} == {"skin_base_color.png", "skin_specular_roughness.png", "skin_specular_weight.png"}
    for f in files:
        assert (tmp_path / f).is_file(), f
    assert {m.getName() for m in doc.getMaterialNodes()} == {"skin", "eyes"}
    obj = (tmp_path / "face.obj").read_text()
    assert "usemtl skin" in obj and "usemtl eyes" in obj


def test_a_gloss_layer_becomes_the_coat_where_it_lies(rouge_bin, repo_root, tmp_path):
    look = {
        "schema": "rouge-look",
        "version": 1,
        "name": "Gloss lips",
        "layers": [
            {"preset": "builtin:foundation_02_ivory", "thickness": {"uniform_mm": 0.015}},
            {"preset": str(repo_root / "data/finishes/lipstick_02_red_gloss.json"),
             "thickness": {"region": "lips", "thickness_mm": 0.02}},
        ],
    }
    (tmp_path / "look.json").write_text(json.dumps(look))
    out = tmp_path / "out"
    assert "coat from a gloss layer" in export(rouge_bin, out, "--look", str(tmp_path / "look.json"))
    doc = validated(out / "face.mtlx")
    skin = doc.getNode("skin_surface")
    assert skin.getInput("coat_weight").getNodeName() == "skin_coat_weight"
    gloss = json.loads((repo_root / "data/finishes/lipstick_02_red_gloss.json").read_text())
    assert skin.getInput("coat_ior").getValue() == pytest.approx(gloss["specular"]["ior"], abs=1e-5)
    assert skin.getInput("coat_roughness").getValue() == pytest.approx(gloss["specular"]["roughness"] ** 0.5, abs=1e-5)

    from PIL import Image

    coat = np.asarray(Image.open(texture(out, "skin_coat_weight.png")), dtype=float) / 255
    base = np.asarray(Image.open(texture(out, "skin_base_color.png")).convert("RGB"), dtype=float)
    covered = coat > 0.5
    assert 0.001 < covered.mean() < 0.1, f"the lips are a small part of the UV square: {covered.mean()}"
    red = base[..., 0] - base[..., 1]
    assert red[covered].mean() > red[~covered].mean() + 40, "the coat lies on the red lips"
