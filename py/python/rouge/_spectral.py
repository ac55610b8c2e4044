"""colour-science interop: spectral distributions in, spectral distributions out.

Rouge's functions take plain arrays whose **last axis** runs over wavelength. Where a user passes
colour-science's ``SpectralDistribution`` (one spectrum) or ``MultiSpectralDistributions``
(wavelength first, one column per spectrum), the wrappers here hand Rouge the values with
``wavelengths=`` and give back the same kind of object. colour-science is optional: it is only
imported when such an object is passed or asked for. No formula lives here.
"""

from __future__ import annotations

import functools
from typing import Any, Callable

import numpy as np


def is_sd(x: Any) -> bool:
    """A colour-science (multi-)spectral distribution, recognised by its interface."""
    return hasattr(x, "wavelengths") and hasattr(x, "values") and hasattr(x, "domain")


def is_msds(x: Any) -> bool:
    return is_sd(x) and hasattr(x, "labels")


def unwrap(x: Any) -> tuple[Any, np.ndarray | None]:
    """``(values with wavelength last, wavelengths)``; anything else comes back as it is."""
    if not is_sd(x):
        return x, None
    values = np.asarray(x.values, dtype=np.float64)
    if is_msds(x):
        values = values.T
    return values, np.asarray(x.wavelengths, dtype=np.float64)


def wrap(values: np.ndarray, wavelengths: np.ndarray, like: Any, name: str) -> Any:
    """``values`` (wavelength last) as the kind of object ``like`` is, named ``name``."""
    import colour

    if is_msds(like):
        return colour.MultiSpectralDistributions(
            np.asarray(values).T, wavelengths, labels=list(like.labels), name=name
        )
    return colour.SpectralDistribution(np.asarray(values), wavelengths, name=name)


def to_msds(values: np.ndarray, wavelengths: np.ndarray, labels: list[str], name: str = "") -> Any:
    """Rows of spectra (wavelength last) as a colour-science ``MultiSpectralDistributions``."""
    import colour

    return colour.MultiSpectralDistributions(
        np.asarray(values, dtype=np.float64).T, np.asarray(wavelengths), labels=list(labels), name=name
    )


def _common_wavelengths(grids: list[np.ndarray]) -> np.ndarray | None:
    if not grids:
        return None
    for g in grids[1:]:
        if g.shape != grids[0].shape or not np.array_equal(g, grids[0]):
            raise ValueError(
                "the spectral distributions passed together must share one wavelength grid "
                f"({grids[0][0]}-{grids[0][-1]} nm, {grids[0].size} samples vs "
                f"{g[0]}-{g[-1]} nm, {g.size} samples); align them first"
            )
    return grids[0]


def spectral(*names: str) -> Callable[[Callable[..., Any]], Callable[..., Any]]:
    """Decorates a Rouge function whose results are spectra named ``names``: spectral
    distributions among the arguments are unwrapped (their grid becomes ``wavelengths=``, so
    errors name the wavelength) and the results wrapped back like the first of them."""

    def decorate(fn: Callable[..., Any]) -> Callable[..., Any]:
        @functools.wraps(fn)
        def call(*args: Any, **kwargs: Any) -> Any:
            like = next((a for a in (*args, *kwargs.values()) if is_sd(a)), None)
            if like is None:
                return fn(*args, **kwargs)
            grids: list[np.ndarray] = []
            plain_args = []
            for a in args:
                v, w = unwrap(a)
                plain_args.append(v)
                if w is not None:
                    grids.append(w)
            plain_kwargs = {}
            for k, a in kwargs.items():
                v, w = unwrap(a)
                plain_kwargs[k] = v
                if w is not None:
                    grids.append(w)
            wavelengths = _common_wavelengths(grids)
            if plain_kwargs.get("wavelengths") is None:
                plain_kwargs["wavelengths"] = wavelengths
            out = fn(*plain_args, **plain_kwargs)
            if isinstance(out, tuple):
                return tuple(wrap(o, wavelengths, like, n) for o, n in zip(out, names, strict=True))
            return wrap(out, wavelengths, like, names[0])

        return call

    return decorate


def spectra_in(fn: Callable[..., Any]) -> Callable[..., Any]:
    """Decorates a function of spectra whose result is not a spectrum (``sd_to_XYZ``): a
    spectral distribution passed as the first argument is unwrapped, its grid passed on."""

    @functools.wraps(fn)
    def call(R: Any, *args: Any, **kwargs: Any) -> Any:
        values, wavelengths = unwrap(R)
        if wavelengths is not None and kwargs.get("wavelengths") is None:
            kwargs["wavelengths"] = wavelengths
        return fn(values, *args, **kwargs)

    return call
