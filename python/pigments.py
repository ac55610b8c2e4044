#!/usr/bin/env python3
"""Representative Kubelka-Munk pigment library for Rouge's SYNTHETIC samples.

There are no public K and S spectra of real cosmetic products, so Rouge's test
data are synthesised from this small library.  Every pigment is a smooth
analytic model (logistic absorption edges, Gaussian bands, power laws) whose
*shape* follows published spectra of the mineral or colorant, and whose
*magnitude* is a representative order of magnitude, **not a measurement**.

Units
-----
``k(wl)`` and ``s(wl)`` are the Kubelka-Munk absorption and scattering
coefficients, in mm^-1, of a film that would contain the component at volume
fraction 1 ("specific" coefficients).  A dry film holding the components at
volume fractions ``c_i`` (sum c_i = 1, the binder taking the remainder) then
has, by Duncan's two-constant mixing rule,

    K_mix(wl) = sum_i c_i k_i(wl),     S_mix(wl) = sum_i c_i s_i(wl).

Linear mixing ignores dependent scattering (crowding) of TiO2 above ~10 vol%,
which is fine for the low loadings used here.

Shapes and their sources (all magnitudes representative, chosen so that the
products in gen_samples.py have realistic colours and partially hide a 10-40
um film):

* rutile TiO2 - band gap ~3.0 eV, so an absorption edge near 400-410 nm and
  K ~ 0 above ~420 nm [Diebold 2003, Surf. Sci. Rep. 48:53]; KM scattering
  falling with wavelength as a power law S ~ wl^-beta with beta ~ 1-2 for
  pigmentary rutile in paints [Wavelength dependence of Kubelka-Munk
  scattering spectra for studies of TiO2 microstructure and aggregation in
  paints, J. Coat. Technol. Res.].  S magnitude: a white paint film of
  ~40 um at 15-20 vol% TiO2 reaches a contrast ratio ~0.98, which needs
  S*D ~ 10, i.e. S ~ 250 mm^-1 of film -> ~1.5e3 mm^-1 per unit fraction.
* hematite (red iron oxide, alpha-Fe2O3) - strong Fe3+ ligand-field / pair
  absorption below ~580 nm with a steep edge, band near 530 nm, weak band
  near 640-650 nm [Sherman & Waite 1985, Am. Mineral. 70:1262; Scheinost et
  al. 1998, Clays Clay Miner. 46:528 (hematite band 521-565 nm)].
* goethite (yellow iron oxide, alpha-FeOOH) - absorption edge near ~500 nm
  (pair band 480-499 nm), weak 6A1->4T2 band near 650 nm [same refs; Torrent
  & Barron 2002, Encycl. Surface Colloid Sci.].
* magnetite (black iron oxide, Fe3O4) - Fe2+/Fe3+ intervalence charge
  transfer: broad, nearly flat, very strong absorption across the visible
  [Sherman 1987; reflectance of magnetite is flat ~5-7 %].
* ultramarine blue - S3^- radical-anion band centred ~600 nm (~16 500 cm^-1),
  weak S2^- band ~390-400 nm; low refractive index (~1.50) so it scatters
  little in oil [Reinen & Lindner 1999, Chem. Soc. Rev. 28:75].
* organic red lake (D&C Red 7 Ca lake, C.I. Pigment Red 57:1; carmine-like) -
  broad visible band with maximum ~520-560 nm and a shoulder near 480-500 nm,
  transparent above ~600 nm; organic pigment, n ~1.6-1.7, weak scatterer
  [Colour Index; carminic acid Al/Ca lake maxima ~530 and ~565 nm].
* carbon black - flat, very high absorption with an absorption Angstrom
  exponent ~1 (K ~ wl^-1); mass absorption cross-section ~7.5 m^2/g at
  550 nm and density ~1.8 g/cm^3 give alpha ~1.35e4 mm^-1 per unit fraction,
  K_KM ~ 2 alpha for diffuse light [Bond & Bergstrom 2006, Aerosol Sci.
  Technol. 40:27].
* mica / talc filler - refractive index ~1.54-1.59 against a binder at
  ~1.40-1.48: a weak, nearly wavelength-independent scatterer with a trace
  of Fe absorption in the blue.
* binder (silicone / ester oil) - nearly transparent, tiny K rising into the
  near UV, very small S.

Run ``.venv/bin/python python/pigments.py`` to print the library at a few
wavelengths; gen_samples.py writes it to data/pigments/pigment_library.csv.
"""

from __future__ import annotations

import numpy as np

REF_NM = 550.0

#: component key -> (display name, source note)
PIGMENTS: dict[str, tuple[str, str]] = {
    "tio2": (
        "titanium dioxide (rutile), C.I. 77891",
        "UV edge ~400-410 nm (band gap ~3.0 eV, Diebold 2003); S ~ wl^-1.5 "
        "(KM scattering exponent beta ~1-2 for pigmentary rutile in paints)",
    ),
    "goethite": (
        "yellow iron oxide (goethite), C.I. 77492",
        "edge ~500 nm + weak band ~650 nm (Sherman & Waite 1985; Scheinost et al. 1998)",
    ),
    "hematite": (
        "red iron oxide (hematite), C.I. 77491",
        "steep edge ~570 nm, band ~530 nm, weak band ~645 nm (Sherman & Waite 1985; "
        "Scheinost et al. 1998)",
    ),
    "magnetite": (
        "black iron oxide (magnetite), C.I. 77499",
        "flat strong intervalence absorption across the visible (Sherman 1987)",
    ),
    "ultramarine": (
        "ultramarine blue, C.I. 77007",
        "S3- band centred ~600 nm, weak S2- band ~395 nm, n~1.50 weak scatterer "
        "(Reinen & Lindner 1999)",
    ),
    "red_lake": (
        "organic red lake (D&C Red 7 Ca lake, C.I. 15850:1 / Pigment Red 57:1; carmine-like)",
        "band max ~535 nm, shoulder ~490 nm, transparent above ~600 nm (Colour Index; "
        "carmine lake maxima ~530/565 nm)",
    ),
    "carbon_black": (
        "carbon black, C.I. 77266",
        "flat high K ~ wl^-1, MAC ~7.5 m2/g at 550 nm (Bond & Bergstrom 2006)",
    ),
    "filler": (
        "mica / talc filler, C.I. 77019 / talc",
        "weak wavelength-independent scatterer (n ~1.55 vs binder ~1.45), trace Fe in blue",
    ),
    "binder": (
        "binder (dimethicone / ester oil / wax)",
        "nearly transparent: tiny K rising into the near UV, tiny S",
    ),
}


def _logistic_low(wl: np.ndarray, edge: float, width: float) -> np.ndarray:
    """1 well below ``edge``, 0 well above it (absorption edge)."""
    return 1.0 / (1.0 + np.exp((wl - edge) / width))


def _gauss(wl: np.ndarray, centre: float, sigma: float) -> np.ndarray:
    return np.exp(-0.5 * ((wl - centre) / sigma) ** 2)


def _power(wl: np.ndarray, exponent: float) -> np.ndarray:
    return (wl / REF_NM) ** exponent


def k_specific(name: str, wl) -> np.ndarray:
    """Specific KM absorption coefficient (mm^-1 per unit volume fraction)."""
    wl = np.asarray(wl, dtype=float)
    if name == "tio2":
        return 700.0 * _logistic_low(wl, 395.0, 8.0) + 0.3
    if name == "goethite":
        return (5000.0 * _logistic_low(wl, 500.0, 20.0)
                + 110.0 * _gauss(wl, 650.0, 40.0)
                + 20.0 * _power(wl, -2.0))
    if name == "hematite":
        return (8000.0 * _logistic_low(wl, 568.0, 13.0)
                + 1500.0 * _gauss(wl, 530.0, 25.0)
                + 600.0 * _gauss(wl, 640.0, 45.0)
                + 60.0 * _power(wl, -2.0))
    if name == "magnetite":
        return 2500.0 * _power(wl, -0.25)
    if name == "ultramarine":
        return (1400.0 * _gauss(wl, 600.0, 55.0)
                + 250.0 * _gauss(wl, 395.0, 25.0)
                + 8.0)
    if name == "red_lake":
        return (5200.0 * _gauss(wl, 535.0, 38.0)
                + 2300.0 * _gauss(wl, 488.0, 30.0)
                + 900.0 * _logistic_low(wl, 405.0, 15.0)
                + 6.0)
    if name == "carbon_black":
        return 20000.0 * _power(wl, -1.0)
    if name == "filler":
        return 0.25 + 1.2 * _logistic_low(wl, 420.0, 30.0)
    if name == "binder":
        return 0.03 + 0.4 * _logistic_low(wl, 390.0, 12.0)
    raise KeyError(name)


def s_specific(name: str, wl) -> np.ndarray:
    """Specific KM scattering coefficient (mm^-1 per unit volume fraction)."""
    wl = np.asarray(wl, dtype=float)
    if name == "tio2":
        return 1500.0 * _power(wl, -1.5)
    if name == "goethite":
        return 700.0 * _power(wl, -1.0)
    if name == "hematite":
        return 700.0 * _power(wl, -1.0)
    if name == "magnetite":
        return 200.0 * _power(wl, -0.5)
    if name == "ultramarine":
        return 60.0 * _power(wl, -1.0)
    if name == "red_lake":
        return 90.0 * _power(wl, -1.0)
    if name == "carbon_black":
        return 150.0 * _power(wl, -1.0)
    if name == "filler":
        return 28.0 * _power(wl, -0.3)
    if name == "binder":
        return 0.4 * np.ones_like(wl)
    raise KeyError(name)


def mix(recipe: dict[str, float], wl) -> tuple[np.ndarray, np.ndarray]:
    """Duncan mixture: ``recipe`` maps pigment -> volume fraction (the binder
    fills the rest).  Returns (K, S) in mm^-1."""
    wl = np.asarray(wl, dtype=float)
    pig = {k: v for k, v in recipe.items() if k != "binder"}
    total = sum(pig.values())
    if not 0.0 < total < 1.0:
        raise ValueError(f"pigment volume fractions sum to {total}")
    fractions = dict(pig, binder=1.0 - total)
    k = np.zeros_like(wl)
    s = np.zeros_like(wl)
    for name, c in fractions.items():
        k += c * k_specific(name, wl)
        s += c * s_specific(name, wl)
    return k, s


if __name__ == "__main__":
    grid = np.array([380.0, 420.0, 450.0, 500.0, 550.0, 600.0, 650.0, 700.0, 780.0])
    print("pigment".ljust(15), " ".join(f"{w:>9.0f}" for w in grid))
    for key in PIGMENTS:
        print(f"{key:<13}K", " ".join(f"{v:9.2f}" for v in k_specific(key, grid)))
        print(f"{'':<13}S", " ".join(f"{v:9.2f}" for v in s_specific(key, grid)))
