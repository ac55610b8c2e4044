# Type stubs of the `rouge` package (the public API of __init__.py and the compiled _rouge).
# `ArrayLike` arguments are converted to float64 and broadcast; spectra have wavelength last.
# Where a colour-science SpectralDistribution / MultiSpectralDistributions is passed (`Spectral`),
# functions returning spectra return the same kind of object.
from os import PathLike
from typing import Any

import numpy as np
import numpy.typing as npt

ArrayLike = npt.ArrayLike
Spectral = Any  # colour.SpectralDistribution | colour.MultiSpectralDistributions
Array = npt.NDArray[np.float64]
Result = Array | float | Spectral
Path = str | PathLike[str]

__version__: str
DETACH_MIN_LEN: int
ILLUMINANTS: tuple[str, ...]
OBSERVERS: tuple[str, ...]

class RougeError(ValueError): ...
class KubelkaMunkError(RougeError):
    index: tuple[int, ...] | None
    wavelength: float | None
class MeasurementImportError(RougeError):
    path: str
    line: int | None
    column: int | None
class PresetError(RougeError):
    path: str
    wavelength: float | None
    line: int | None
    column: int | None
class SpectrumError(RougeError): ...

def R_to_SK_KubelkaMunk(
    R_inf: ArrayLike | Spectral, R: ArrayLike | Spectral, R_g: ArrayLike | Spectral, thickness_mm: ArrayLike,
    *, wavelengths: ArrayLike | None = None,
) -> tuple[Result, Result]: ...
def SK_to_R0T_KubelkaMunk(
    S: ArrayLike | Spectral, K: ArrayLike | Spectral, thickness_mm: ArrayLike, *, wavelengths: ArrayLike | None = None
) -> tuple[Result, Result]: ...
def SK_to_R_KubelkaMunk(
    S: ArrayLike | Spectral, K: ArrayLike | Spectral, thickness_mm: ArrayLike, R_g: ArrayLike | Spectral,
    *, wavelengths: ArrayLike | None = None,
) -> Result: ...
def SK_to_Rinf_KubelkaMunk(
    S: ArrayLike | Spectral, K: ArrayLike | Spectral, *, wavelengths: ArrayLike | None = None
) -> Result: ...
def RT_stack_KubelkaMunk(
    R0: ArrayLike, T: ArrayLike, R_g: ArrayLike | None = None, *, wavelengths: ArrayLike | None = None
) -> tuple[Result, Result]: ...
def R_measured_to_internal_Saunderson(
    R: ArrayLike | Spectral, n: float = 1.5, K2: float = 0.6, specular_included: bool = True,
    *, K1: float | None = None, wavelengths: ArrayLike | None = None,
) -> Result: ...
def R_internal_to_measured_Saunderson(
    R: ArrayLike | Spectral, n: float = 1.5, K2: float = 0.6, specular_included: bool = True,
    *, K1: float | None = None, wavelengths: ArrayLike | None = None,
) -> Result: ...
def SK_mix_Duncan(
    S: ArrayLike, K: ArrayLike, concentrations: ArrayLike, *, wavelengths: ArrayLike | None = None
) -> tuple[Result, Result]: ...

def working_wavelengths() -> Array: ...
def resample_to_working_grid(wavelengths: ArrayLike, values: ArrayLike, *, extrapolate: bool = False) -> Array: ...
def sd_to_XYZ(
    R: ArrayLike | Spectral, illuminant: str = "D65", observer: str = "CIE 1931 2 Degree Standard Observer",
    *, wavelengths: ArrayLike | None = None, extrapolate: bool = False,
) -> Array: ...
def sd_to_Lab(
    R: ArrayLike | Spectral, illuminant: str = "D65", observer: str = "CIE 1931 2 Degree Standard Observer",
    *, wavelengths: ArrayLike | None = None, extrapolate: bool = False,
) -> Array: ...
def sd_to_sRGB(
    R: ArrayLike | Spectral, illuminant: str = "D65", observer: str = "CIE 1931 2 Degree Standard Observer",
    apply_cctf_encoding: bool = True, *, wavelengths: ArrayLike | None = None, extrapolate: bool = False,
) -> Array: ...
def XYZ_to_Lab(XYZ: ArrayLike, illuminant: str = "D65", observer: str = "CIE 1931 2 Degree Standard Observer") -> Array: ...
def XYZ_to_sRGB(
    XYZ: ArrayLike, illuminant: str = "D65", observer: str = "CIE 1931 2 Degree Standard Observer",
    apply_cctf_encoding: bool = True,
) -> Array: ...
def delta_E_CIE2000(Lab_1: ArrayLike, Lab_2: ArrayLike) -> Array | float: ...

class Measurement:
    path: str
    format: str
    name: str
    kind: str | None
    thickness_mm: float | None
    instrument: str | None
    metadata: dict[str, str]
    scale: str
    wavelengths: Array
    R_inf: Array
    R: Array
    R_g: Array
    def to_working_grid(self, extrapolate: bool = False) -> Measurement: ...

def read_measurement(
    path: Path, *, samples: tuple[str, str, str] | None = None,
    white_reflectance: float | tuple[ArrayLike, ArrayLike] | None = None,
) -> Measurement: ...
def read_measurement_files(R_inf: Path, R: Path, R_g: Path) -> Measurement: ...
def read_spectra(path: Path, *, as_msds: bool = False) -> Any: ...
def measurement_to_msds(measurement: Measurement) -> Spectral: ...
def is_sd(x: Any) -> bool: ...

class Preset:
    name: str
    kind: str
    thickness_mm: float
    wavelengths: Array
    S: Array
    K: Array
    specular: dict[str, float]
    measurement: dict[str, Any] | None
    derived: dict[str, Any]
    @staticmethod
    def load(path: Path) -> Preset: ...
    @staticmethod
    def from_json(text: str, path: str = "<preset>") -> Preset: ...
    @staticmethod
    def from_SK(S: ArrayLike, K: ArrayLike, thickness_mm: float, name: str, kind: str = "other") -> Preset: ...
    @staticmethod
    def from_measurement(
        measurement: Measurement, *, thickness_mm: float | None = None, name: str | None = None,
        kind: str | None = None, saunderson: dict[str, Any] | None = None, extrapolate: bool = False,
        u_reflectance: float | None = None, u_thickness_mm: float = 0.0005,
    ) -> tuple[Preset, dict[str, Any]]: ...
    def save(self, path: Path) -> None: ...
    def to_json(self) -> str: ...
    def to_dict(self) -> dict[str, Any]: ...

# Formulation analyses (rouge_measure::analysis, docs/FORMULATION.md). Spectra: 81 values on
# the working grid 380-780 nm / 5 nm; thickness in mm.
def metamerism_index_special(
    sd_standard: ArrayLike, sd_sample: ArrayLike, *, illuminant_reference: str = "D65", illuminant_test: str = "A",
    cmfs_reference: str = "CIE 1931 2 Degree Standard Observer", cmfs_test: str | None = None,
    correction: str = "multiplicative",
) -> dict[str, Any]: ...
def correct_batch_KubelkaMunk(
    colorants: list[tuple[ArrayLike, ArrayLike]], recipe: ArrayLike, batch: ArrayLike, standard: ArrayLike, *,
    skin: ArrayLike | None = None, thickness_mm: float | None = None, illuminant: str = "D65",
    observer: str = "CIE 1931 2 Degree Standard Observer",
) -> dict[str, Any]: ...
def recipe_search_KubelkaMunk(
    colorants: list[tuple[ArrayLike, ArrayLike]], target: ArrayLike, k: int, *, names: list[str] | None = None,
    min: dict[str, float] | None = None, max: dict[str, float] | None = None,
    fixed: list[tuple[str, str, float]] | None = None, cost: dict[str, float] | None = None,
    illuminants: list[str] = ..., weights: list[float] | None = None,
    observer: str = "CIE 1931 2 Degree Standard Observer", skin: ArrayLike | None = None,
    thickness_mm: float | None = None, cost_weight: float = 0.0, top: int = 10,
) -> list[dict[str, Any]]: ...
def qc_pass_fail(
    Lab_standard: ArrayLike, Lab_sample: ArrayLike, tolerance: float, *, method: str = "CIE 2000", l: float = 2.0,
    c: float = 1.0, block: tuple[float, float, float] | None = None,
) -> dict[str, Any]: ...
def qc_tolerance_contour(
    Lab_standard: ArrayLike, tolerance: float, *, method: str = "CIE 2000", l: float = 2.0, c: float = 1.0,
    plane: str = "ab", points: int = 72,
) -> list[list[float]]: ...
ILL_CONDITIONED_ABOVE: float
def SK_uncertainty(
    R_inf: ArrayLike, R: ArrayLike, Rg: ArrayLike, thickness_mm: float, u_R: ArrayLike, *,
    u_thickness_mm: float = 0.0, reading_correlation: float = 0.0,
) -> dict[str, list[Any]]: ...
def SK_thickness_optimal(
    S: ArrayLike, K: ArrayLike, Rg: ArrayLike, u_R: ArrayLike, *, u_thickness_mm: float = 0.0,
    bounds_mm: tuple[float, float] = (0.001, 1.0),
) -> dict[str, float] | None: ...
def SK_to_coverage(
    S: ArrayLike, K: ArrayLike, thickness_mm: ArrayLike, *, skins: ArrayLike | None = None,
    black: float = 0.01, white: float = 0.80, illuminant: str = "D65",
    observer: str = "CIE 1931 2 Degree Standard Observer",
) -> dict[str, Any]: ...
def match_shades(
    shades: list[tuple[ArrayLike, ArrayLike]], skins: ArrayLike, thickness_mm: tuple[float, float], *,
    target_Lab: tuple[float, float, float] | None = None, gap_delta_E: float = 2.0, illuminant: str = "D65",
    observer: str = "CIE 1931 2 Degree Standard Observer",
) -> list[dict[str, Any]]: ...
def fit_mix_Duncan(
    bases: list[tuple[ArrayLike, ArrayLike]], target_Lab: tuple[float, float, float], *,
    skin: ArrayLike | None = None, thickness_mm: float | None = None, illuminant: str = "D65",
    observer: str = "CIE 1931 2 Degree Standard Observer",
) -> dict[str, Any]: ...

# The spectral skin model (docs/SKIN.md).
def skin_reflectance(
    *, tone: str | None = None, wavelengths: ArrayLike | None = None, as_sd: bool = False, **params: float,
) -> Array | Any: ...
def skin_fit(
    R: ArrayLike | Spectral, wavelengths: ArrayLike | None = None, *, epidermis_thickness_mm: float = 0.1,
    extrapolate: bool = False, specular: str = "included",
) -> dict[str, Any] | list[dict[str, Any]]: ...
def skin_tones() -> list[dict[str, Any]]: ...

# Finishes (docs/FINISHES.md).
def specular_BRDF_Kelemen(
    wi: tuple[float, float, float], wo: tuple[float, float, float], roughness: float, ior: float,
) -> float: ...
def gloss_units_ISO2813(roughness: float, ior: float, angle: float) -> float: ...
def fit_gloss_ISO2813(readings: dict[int, float], ior: float) -> dict[str, Any]: ...
def reflectance_thin_film_TiO2(
    film_nm: float, theta_deg: float, *, wavelengths: ArrayLike | None = None, binder_index: float = 1.5,
    core_index: float = 1.58,
) -> list[float]: ...

# Rendering (the wheel's `render` feature; HAS_RENDER says whether this wheel has it).
HAS_RENDER: bool

class RenderingError(RougeError): ...

class Look:
    """A look document: layers bottom to top (preset, thickness, visible)."""
    @staticmethod
    def load(path: str | PathLike[str]) -> Look: ...
    @staticmethod
    def default_look() -> Look: ...
    @staticmethod
    def bare() -> Look: ...
    name: str
    @property
    def layers(self) -> list[dict[str, Any]]: ...
    def set_visible(self, index: int, visible: bool) -> None: ...
    def set_thickness(self, index: int, thickness: dict[str, Any]) -> None: ...
    def add_layer(self, preset: str, thickness: dict[str, Any], name: str | None = None) -> None: ...
    def remove_layer(self, index: int) -> None: ...
    def to_json(self) -> str: ...
    def save(self, path: str | PathLike[str]) -> None: ...
    def __len__(self) -> int: ...

class Renderer:
    """One GPU device, kept: every `render` draws on it (GIL released while drawing)."""
    def __init__(self) -> None: ...
    @property
    def adapter(self) -> str: ...
    def render(
        self,
        *,
        mesh: str | PathLike[str] | None = None,
        look: Look | str | PathLike[str] | None = None,
        skin_tone: str | None = None,
        expression: str | None = None,
        width: int = 640,
        height: int = 480,
        linear: bool = False,
        subdiv: int = 2,
        yaw: float = 0.0,
        pitch: float = 0.0,
    ) -> npt.NDArray[Any]: ...

def render(
    mesh: str | PathLike[str] | None = None,
    look: Look | str | PathLike[str] | None = None,
    skin_tone: str | None = None,
    expression: str | None = None,
    width: int = 640,
    height: int = 480,
    linear: bool = False,
    **options: Any,
) -> npt.NDArray[Any]: ...
