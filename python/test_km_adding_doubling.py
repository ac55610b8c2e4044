"""Kubelka-Munk against adding-doubling on a small set (the full study:
python/km_adding_doubling.py, tables in docs/FORMULATION.md). Drives the real `rouge` binary."""

from __future__ import annotations

import os

import numpy as np
import pytest

import km_adding_doubling as kad


@pytest.fixture(autouse=True)
def _binary(rouge_bin: str) -> None:
    os.environ["ROUGE_BIN"] = rouge_bin


def chandrasekhar_h(albedo: float, mu: np.ndarray, nodes: int = 96) -> np.ndarray:
    """Chandrasekhar's H-function for isotropic scattering by iterating
    1/H(mu) = sqrt(1 - a) + (a/2) int_0^1 mu' H(mu') / (mu + mu') dmu' (Gauss-Legendre)."""
    x, w = np.polynomial.legendre.leggauss(nodes)
    x, w = 0.5 * (x + 1.0), 0.5 * w
    h = np.ones_like(x)
    for _ in range(2000):
        new = 1.0 / (np.sqrt(1.0 - albedo) + 0.5 * albedo * np.sum(w * x * h / (x[:, None] + x), axis=1))
        if np.max(np.abs(new - h)) < 1e-15:
            break
        h = new
    return 1.0 / (np.sqrt(1.0 - albedo) + 0.5 * albedo * np.sum(w * x * h / (np.asarray(mu)[:, None] + x), axis=1))


@pytest.mark.parametrize("albedo", [0.5, 0.9, 0.99])
def test_adding_doubling_matches_chandrasekhar_for_a_semi_infinite_medium(albedo: float) -> None:
    # Albedo of a semi-infinite isotropic medium for normal incidence: 1 - H(1) sqrt(1 - a).
    exact = 1.0 - chandrasekhar_h(albedo, np.array([1.0]))[0] * np.sqrt(1.0 - albedo)
    got = kad.ad(sigma_a=(1 - albedo) * 100.0, sigma_s_red=albedo * 100.0, d_mm=np.inf, g=0.0)["ur1"]
    assert abs(got - exact) < 2e-4, (got, exact)


def test_diffusive_layers_follow_the_classical_relations() -> None:
    r = kad.regime(0.999, 10.0)
    assert abs(r["k_ratio"] - 2.0) < 0.03, r  # K = 2 sigma_a
    assert abs(r["s_ratio"] - 0.75) < 0.02, r  # S = 3/4 sigma_s' - 1/4 sigma_a
    assert abs(r["dr_white"]) < 1e-3 and abs(r["dt"]) < 1e-3, r


def test_thin_layers_depart_from_them_and_km_still_predicts_reflectance() -> None:
    thin, thick = kad.regime(0.95, 0.1), kad.regime(0.95, 10.0)
    assert thin["s_ratio"] - thick["s_ratio"] > 0.1, (thin, thick)
    assert thin["k_ratio"] > 2.2, thin
    for a, tau in [(0.5, 0.3), (0.9, 1.0), (0.99, 3.0)]:
        r = kad.regime(a, tau)
        assert abs(r["dr_white"]) < 0.03 and abs(r["dr0_2d"]) < 0.03 and abs(r["dt"]) < 0.03, r


def test_an_air_interface_needs_saunderson() -> None:
    r = kad.regime(0.95, 10.0)
    # Read through a glossy n = 1.5 surface, K is doubled without the correction...
    assert r["k_raw_ratio"] > 2.0, r
    # ...and Saunderson restores S and K of a thick layer to within 3 % and 35 %.
    assert abs(r["s_saunderson_ratio"] - 1.0) < 0.03 and abs(r["k_saunderson_ratio"] - 1.0) < 0.35, r
