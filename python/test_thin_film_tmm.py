"""The thin-film reflectance of TiO2-coated mica (rouge_measure::thin_film, Airy's formula)
against the `tmm` package's transfer matrices ([Byrnes2016]) on the same stack: binder 1.50 |
rutile (DeVore 1951) | mica 1.58, films 40-200 nm, 0-80 degrees in the binder, unpolarised.
Spectra agree to 1e-9 and their colours under D65 within 0.5 CIEDE2000 (docs/FINISHES.md)."""

from __future__ import annotations

import math

import numpy as np
import pytest

tmm = pytest.importorskip("tmm", reason="tmm (python/requirements.txt) is the reference")

import rouge  # noqa: E402

WAVELENGTHS = np.arange(380.0, 781.0, 5.0)


def rutile(nm: float) -> float:
    um2 = (nm / 1000.0) ** 2
    return math.sqrt(5.913 + 0.2441 / (um2 - 0.0803))


def tmm_reflectance(film_nm: float, theta_deg: float) -> np.ndarray:
    th = math.radians(theta_deg)
    out = []
    for nm in WAVELENGTHS:
        n_list = [1.50, rutile(nm), 1.58]
        d_list = [math.inf, film_nm, math.inf]
        rs = tmm.coh_tmm("s", n_list, d_list, th, nm)["R"]
        rp = tmm.coh_tmm("p", n_list, d_list, th, nm)["R"]
        out.append(0.5 * (rs + rp))
    return np.array(out)


@pytest.mark.parametrize("film_nm", [40.0, 80.0, 120.0, 160.0, 200.0])
def test_thin_film_reflectance_matches_tmm(film_nm):
    worst_de = 0.0
    for theta in range(0, 81, 10):
        ours = np.array(rouge.reflectance_thin_film_TiO2(film_nm, float(theta)))
        theirs = tmm_reflectance(film_nm, float(theta))
        assert np.max(np.abs(ours - theirs)) < 1e-9, (film_nm, theta)
        de = rouge.delta_E_CIE2000(rouge.sd_to_Lab(ours), rouge.sd_to_Lab(theirs))
        worst_de = max(worst_de, float(de))
    assert worst_de <= 0.5


def test_the_interference_colour_shifts_with_angle_and_bad_input_is_refused():
    # A quarter-wave film at 550 nm: the peak moves to shorter wavelengths as the angle grows.
    film = 550.0 / (4.0 * rutile(550.0))
    peak = [WAVELENGTHS[int(np.argmax(rouge.reflectance_thin_film_TiO2(film, t)))] for t in (0.0, 60.0)]
    assert peak[0] > peak[1], peak
    with pytest.raises(ValueError, match="theta_deg"):
        rouge.reflectance_thin_film_TiO2(100.0, 95.0)
    with pytest.raises(ValueError, match="film_nm"):
        rouge.reflectance_thin_film_TiO2(-1.0, 0.0)
    with pytest.raises(ValueError, match="wavelength"):
        rouge.reflectance_thin_film_TiO2(100.0, 0.0, wavelengths=[100.0])
