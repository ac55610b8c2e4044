"""Rendering from Python (the `rouge` wheel built with its `render` feature): `rouge.render` draws
the frame `rouge render` draws with the same options, on one GPU device kept for the process,
with the GIL released; `rouge.Look` loads, edits and saves looks; errors name the option, and no
adapter gives the CLI's hint. Skipped, saying so, where the installed wheel has no renderer (CI
builds the spectral core only: `maturin develop -m py/Cargo.toml --features render` for these)."""

import os
import subprocess
import sys
import threading

import numpy as np
import pytest

rouge = pytest.importorskip("rouge")
if not rouge.HAS_RENDER:
    pytest.skip(
        "SKIPPED: the installed `rouge` wheel was built without the renderer "
        "(maturin develop -m py/Cargo.toml --features render)",
        allow_module_level=True,
    )

SMALL = dict(width=160, height=120, subdiv=1)


def test_the_frame_is_rouge_renders(rouge_bin, tmp_path):
    from PIL import Image

    img = rouge.render(look="bare", skin_tone="medium", **SMALL)
    assert img.shape == (120, 160, 4) and img.dtype == np.uint8
    out = tmp_path / "cli.png"
    subprocess.run([rouge_bin, "render", "--look", "bare", "--skin-tone", "medium", "--width", "160",
                    "--height", "120", "--subdiv", "1", "--out", str(out)], check=True, capture_output=True)
    cli = np.asarray(Image.open(out).convert("RGBA"))
    # The same job on the same kind of device: equal but for rounding between the wheel's
    # optimised renderer and the binary's.
    diff = np.abs(cli.astype(int) - img.astype(int))
    assert diff.max() <= 2, f"largest difference {diff.max()} at {np.unravel_index(diff.argmax(), diff.shape)}"
    lin = rouge.render(look="bare", skin_tone="medium", linear=True, **SMALL)
    assert lin.dtype == np.float32 and lin.shape == (120, 160, 4)


def test_one_device_is_kept_and_the_gil_is_released():
    assert rouge._render.default_renderer() is rouge._render.default_renderer()
    done = threading.Event()
    frames = []

    def draw():
        frames.append(rouge.render(expression="smile", **SMALL))
        done.set()

    t = threading.Thread(target=draw)
    t.start()
    spins = 0
    while not done.is_set():
        spins += 1
    t.join()
    # With the GIL held through the frame (seconds on lavapipe) this thread could not run.
    assert spins > 10_000, spins
    neutral = rouge.render(**SMALL)
    assert np.abs(frames[0].astype(int) - neutral.astype(int)).sum() > 0, "the smile changed the face"


def test_a_look_is_loaded_edited_saved_and_drawn(repo_root, tmp_path):
    look = rouge.Look.load(str(repo_root / "data/looks/default.json"))
    assert len(look) == 3 and look.layers[2]["preset"] == "builtin:lipstick_02_red"
    with_lips = rouge.render(look=look, **SMALL)
    look.set_visible(2, False)
    without = rouge.render(look=look, **SMALL)
    red = lambda img: (img[..., 0].astype(int) - img[..., 1]).clip(0).sum()
    assert red(with_lips) > red(without), "hiding the lipstick takes red off the lips"
    look.set_thickness(0, {"uniform_mm": 0.005})
    look.add_layer("builtin:blush_02_coral", {"region": "cheeks", "thickness_mm": 0.01}, name="Coral")
    look.name = "Edited"
    look.save(str(tmp_path / "edited.json"))
    back = rouge.Look.load(str(tmp_path / "edited.json"))
    assert back.name == "Edited" and len(back) == 4
    assert back.layers[0]["thickness"] == {"uniform_mm": 0.005}
    assert back.layers[2]["visible"] is False and back.layers[3]["name"] == "Coral"
    with pytest.raises(rouge.RenderingError, match="layer 9"):
        back.set_visible(9, True)


def test_errors_name_the_option_and_no_adapter_gives_the_hint():
    with pytest.raises(rouge.RenderingError, match="width=0"):
        rouge.render(width=0)
    with pytest.raises(rouge.RenderingError, match="skin_tone=purple"):
        rouge.render(skin_tone="purple", **SMALL)
    with pytest.raises(rouge.RenderingError, match="expression"):
        rouge.render(expression="frown=2=3", **SMALL)
    # A backend this machine does not have: no adapter at all.
    code = "import rouge\ntry:\n    rouge.Renderer()\nexcept rouge.RenderingError as e:\n    print(e)"
    env = dict(os.environ, WGPU_BACKEND="dx12")
    out = subprocess.run([sys.executable, "-c", code], env=env, capture_output=True, text=True, check=True).stdout
    assert "no GPU adapter found" in out and "mesa-vulkan-drivers" in out, out
