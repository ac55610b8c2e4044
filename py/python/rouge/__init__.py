"""Rouge's spectral core in Python: stable Kubelka-Munk, CIE colorimetry, measurement import and
material presets for cosmetics, compiled from the Rust crate ``rouge-measure``.

Conventions (colour-science's): names ``X_to_Y`` with the method in the name; reflectances as
fractions; thickness in mm, S and K in mm⁻¹; float64 numpy arrays in and out, broadcast as numpy
does; spectra with wavelength on the **last** axis (380-780 nm every 5 nm unless
``wavelengths=`` says otherwise). colour-science ``SpectralDistribution`` and
``MultiSpectralDistributions`` are accepted wherever spectra are, and come back where spectra
are returned. Every error is a ``ValueError`` subclass (``RougeError``) with the message the
``rouge`` command line prints, naming the wavelength, file, line and column.

References (keys of docs/REFERENCES.md): [Huang2013] eq. 1-4, 6-8; [Kubelka1948];
[Kubelka1954]; [Saunderson1942]; [Duncan1940]; [CIE15]; [CIE142]; [Sharma2005]; [IEC61966];
[Lam1985]; [Sprague1880]; [CIE167].
"""

from __future__ import annotations

from typing import Any

import numpy as np

from . import _rouge
from ._rouge import (
    DETACH_MIN_LEN,
    ILL_CONDITIONED_ABOVE,
    KubelkaMunkError,
    Measurement,
    MeasurementImportError,
    Preset,
    PresetError,
    RougeError,
    SpectrumError,
    XYZ_to_Lab,
    SK_thickness_optimal,
    SK_to_coverage,
    SK_uncertainty,
    XYZ_to_sRGB,
    correct_batch_KubelkaMunk,
    delta_E_CIE2000,
    fit_gloss_ISO2813,
    gloss_units_ISO2813,
    fit_mix_Duncan,
    match_shades,
    metamerism_index_special,
    qc_pass_fail,
    qc_tolerance_contour,
    read_measurement,
    reflectance_thin_film_TiO2,
    read_measurement_files,
    recipe_search_KubelkaMunk,
    resample_to_working_grid,
    specular_BRDF_Kelemen,
    working_wavelengths,
)
from ._render import HAS_RENDER, Look, Renderer, RenderingError, render
from ._spectral import is_sd, spectra_in, spectral, to_msds

__version__: str = _rouge.__version__

ILLUMINANTS = ("D65", "D55", "D50", "A", "E", "FL2", "FL7", "FL11", "LED-B3")
"""Illuminants with tables on the working grid."""
OBSERVERS = ("CIE 1931 2 Degree Standard Observer", "CIE 1964 10 Degree Standard Observer")
"""Observers (also accepted: ``"1931"``, ``"1964"``, ``"2"``, ``"10"``)."""
_OBSERVER = OBSERVERS[0]

# Kubelka-Munk (rouge_measure::km): spectral distributions in, spectral distributions out.
R_to_SK_KubelkaMunk = spectral("S", "K")(_rouge.R_to_SK_KubelkaMunk)
SK_to_R0T_KubelkaMunk = spectral("R0", "T")(_rouge.SK_to_R0T_KubelkaMunk)
SK_to_R_KubelkaMunk = spectral("R")(_rouge.SK_to_R_KubelkaMunk)
SK_to_Rinf_KubelkaMunk = spectral("R_inf")(_rouge.SK_to_Rinf_KubelkaMunk)
RT_stack_KubelkaMunk = spectral("R", "T")(_rouge.RT_stack_KubelkaMunk)
R_measured_to_internal_Saunderson = spectral("R internal")(_rouge.R_measured_to_internal_Saunderson)
R_internal_to_measured_Saunderson = spectral("R measured")(_rouge.R_internal_to_measured_Saunderson)
SK_mix_Duncan = spectral("S", "K")(_rouge.SK_mix_Duncan)

# Colorimetry (rouge_measure::colorimetry).
sd_to_XYZ = spectra_in(_rouge.sd_to_XYZ)


def sd_to_Lab(
    R: Any, illuminant: str = "D65", observer: str = _OBSERVER, *, wavelengths: Any = None, extrapolate: bool = False
) -> Any:
    """CIELAB of spectra: ``XYZ_to_Lab(sd_to_XYZ(R) / 100)`` under one illuminant and observer
    (see both for the equations)."""
    XYZ = sd_to_XYZ(R, illuminant, observer, wavelengths=wavelengths, extrapolate=extrapolate)
    return XYZ_to_Lab(np.asarray(XYZ) / 100.0, illuminant, observer)


def sd_to_sRGB(
    R: Any,
    illuminant: str = "D65",
    observer: str = _OBSERVER,
    apply_cctf_encoding: bool = True,
    *,
    wavelengths: Any = None,
    extrapolate: bool = False,
) -> Any:
    """sRGB of spectra: ``XYZ_to_sRGB(sd_to_XYZ(R) / 100)`` (see both for the equations)."""
    XYZ = sd_to_XYZ(R, illuminant, observer, wavelengths=wavelengths, extrapolate=extrapolate)
    return XYZ_to_sRGB(np.asarray(XYZ) / 100.0, illuminant, observer, apply_cctf_encoding)


def read_spectra(path: Any, *, as_msds: bool = False) -> Any:
    """A table of spectra, as ``rouge color`` reads it: a ``wavelength_nm`` or ``wavelength``
    column and one column per sample, or one spectrum per row with the wavelengths in the header
    (colour-science's transposed layout); commas or tabs; or a CGATS file (X-Rite, i1Profiler,
    ArgyllCMS .ti3) with its spectral fields, recognised from the content.

    Returns ``(wavelengths, values, names)``, ``values`` of shape ``(samples, wavelengths)`` as
    fractions, or with ``as_msds`` a colour-science ``MultiSpectralDistributions``. Raises
    ``MeasurementImportError`` naming the file, line and column."""
    wavelengths, values, names = _rouge.read_spectra(path)
    if as_msds:
        return to_msds(values, wavelengths, names, name=str(path))
    return wavelengths, values, names


def skin_reflectance(*, tone: str | None = None, wavelengths: Any = None, as_sd: bool = False, **params: float) -> Any:
    """Reflectance of Rouge's spectral skin model (docs/SKIN.md): an epidermis with melanin over
    a dermis with blood, by tabulated adding-doubling, specular included. Start from the named
    ``tone`` (``skin_tones()``) or the light default and override parameters by keyword
    (``melanin_fraction``, ``pheomelanin_share``, ``blood_fraction``, ``oxygen_saturation``,
    ``scattering_500nm_per_mm``, ``scattering_power``, ``epidermis_thickness_mm``). Returns a
    numpy array at ``wavelengths`` (nm, default 380-780 / 5), or a colour-science
    ``SpectralDistribution`` with ``as_sd``. Raises ``RougeError`` naming a parameter out of range."""
    wl = None if wavelengths is None else [float(w) for w in np.asarray(wavelengths, dtype=np.float64).ravel()]
    values = np.asarray(_rouge.skin_reflectance(tone=tone, wavelengths=wl, **params))
    if as_sd:
        import colour

        grid = np.asarray(wl if wl is not None else working_wavelengths())
        return colour.SpectralDistribution(values, grid, name=tone or "skin")
    return values


def skin_fit(
    R: Any, wavelengths: Any = None, *, epidermis_thickness_mm: float = 0.1, extrapolate: bool = False,
    specular: str = "included",
) -> Any:
    """Fits the skin model to measured reflectance (rows of ``R`` with wavelength last, at
    ``wavelengths`` nm; or a colour-science ``SpectralDistribution`` /
    ``MultiSpectralDistributions``). Returns a dict per spectrum (a list for several): ``params``,
    ``wavelengths``, ``fitted_reflectance``, ``delta_E`` (CIEDE2000, D65, CIE 1931), ``rms``,
    ``Lab_measured``, ``Lab_fitted``, ``at_bounds``. ``specular``: ``"included"`` (SCI) or
    ``"excluded"`` (SCE)."""
    from ._spectral import unwrap

    values, sd_wl = unwrap(R)
    if sd_wl is not None:
        wavelengths = sd_wl
    if wavelengths is None:
        wavelengths = working_wavelengths()
    values = np.asarray(values, dtype=np.float64)
    single = values.ndim == 1
    rows = np.atleast_2d(values)
    out = _rouge.skin_fit(rows.tolist(), [float(w) for w in np.asarray(wavelengths).ravel()],
                          epidermis_thickness_mm=epidermis_thickness_mm, extrapolate=extrapolate, specular=specular)
    return out[0] if single else out


def skin_tones() -> list[dict[str, Any]]:
    """Rouge's named skin tones, very light to very deep: ``name``, ``fitzpatrick``, ``params``, ``source``."""
    return _rouge.skin_tones_list()


def measurement_to_msds(measurement: Measurement) -> Any:
    """A measurement's R∞, R and Rg as a colour-science ``MultiSpectralDistributions``."""
    m = measurement
    values = np.stack([m.R_inf, m.R, m.R_g])
    return to_msds(values, m.wavelengths, ["R_inf", "R", "R_g"], name=m.name)


__all__ = [
    "HAS_RENDER",
    "Look",
    "Renderer",
    "RenderingError",
    "render",
    "DETACH_MIN_LEN",
    "ILL_CONDITIONED_ABOVE",
    "ILLUMINANTS",
    "OBSERVERS",
    "KubelkaMunkError",
    "Measurement",
    "MeasurementImportError",
    "Preset",
    "PresetError",
    "RT_stack_KubelkaMunk",
    "R_internal_to_measured_Saunderson",
    "R_measured_to_internal_Saunderson",
    "R_to_SK_KubelkaMunk",
    "RougeError",
    "SK_mix_Duncan",
    "SK_thickness_optimal",
    "SK_to_coverage",
    "SK_uncertainty",
    "SK_to_R0T_KubelkaMunk",
    "SK_to_R_KubelkaMunk",
    "SK_to_Rinf_KubelkaMunk",
    "SpectrumError",
    "XYZ_to_Lab",
    "XYZ_to_sRGB",
    "correct_batch_KubelkaMunk",
    "delta_E_CIE2000",
    "fit_gloss_ISO2813",
    "fit_mix_Duncan",
    "gloss_units_ISO2813",
    "match_shades",
    "metamerism_index_special",
    "qc_pass_fail",
    "qc_tolerance_contour",
    "recipe_search_KubelkaMunk",
    "is_sd",
    "measurement_to_msds",
    "read_measurement",
    "read_measurement_files",
    "read_spectra",
    "reflectance_thin_film_TiO2",
    "resample_to_working_grid",
    "sd_to_Lab",
    "sd_to_XYZ",
    "sd_to_sRGB",
    "skin_fit",
    "skin_reflectance",
    "specular_BRDF_Kelemen",
    "skin_tones",
    "working_wavelengths",
]
