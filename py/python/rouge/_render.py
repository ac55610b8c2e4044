"""Rendering from Python (the wheel's ``render`` feature): ``rouge.render`` draws a frame as
``rouge render`` does on one ``Renderer`` (one GPU device) kept for the process, and returns a
numpy array (height, width, 4); ``rouge.Renderer`` is that device, for whoever wants their own
(one per thread or per Dask worker); ``rouge.Look`` a look document to load, edit and save.

A wheel built without the feature (the default: the spectral core builds without wgpu) has
``rouge.HAS_RENDER = False``, and ``rouge.render`` then raises ``RenderingError`` saying how to
build one with it."""

from __future__ import annotations

import threading
from typing import Any

from . import _rouge
from ._rouge import RougeError

HAS_RENDER: bool = bool(getattr(_rouge, "HAS_RENDER", False))

if HAS_RENDER:
    from ._rouge import Look, Renderer, RenderingError
else:

    class RenderingError(RougeError):  # type: ignore[no-redef]
        """A frame that cannot be drawn (here: a wheel built without the renderer)."""

    _WHY = (
        "this `rouge` wheel was built without the renderer: build it with "
        "`maturin build --release -m py/Cargo.toml --features render` (README, \"Python\")"
    )

    class Renderer:  # type: ignore[no-redef]
        def __init__(self, *args: Any, **kwargs: Any) -> None:
            raise RenderingError(_WHY)

    class Look:  # type: ignore[no-redef]
        def __init__(self, *args: Any, **kwargs: Any) -> None:
            raise RenderingError(_WHY)

        @staticmethod
        def load(path: Any) -> Look:
            raise RenderingError(_WHY)


_shared: Renderer | None = None
_lock = threading.Lock()


def default_renderer() -> Renderer:
    """The process's renderer, opened on first use (one GPU device for every ``rouge.render``)."""
    global _shared
    with _lock:
        if _shared is None:
            _shared = Renderer()
        return _shared


def render(
    mesh: str | None = None,
    look: Look | str | None = None,
    skin_tone: str | None = None,
    expression: str | None = None,
    width: int = 640,
    height: int = 480,
    linear: bool = False,
    **options: Any,
):
    """A frame as ``rouge render`` draws it, as a numpy array (height, width, 4): uint8 sRGB, or
    float32 linear radiance with ``linear=True``. ``mesh``: a file or None (the default head,
    painted from skin maps of ``skin_tone``); ``look``: a ``Look``, ``"default"``, ``"bare"`` or a
    look file; ``skin_tone``: a name of ``rouge.skin_tones()`` or an ITA°; ``expression``:
    ``"smile"`` or weights ``"smile=0.5,blink=1"``; ``options``: ``subdiv``, ``yaw``, ``pitch``.
    The GIL is released while the frame is drawn."""
    return default_renderer().render(
        mesh=mesh, look=look, skin_tone=skin_tone, expression=expression, width=width, height=height,
        linear=linear, **options,
    )
