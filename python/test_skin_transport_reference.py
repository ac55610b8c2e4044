"""Checks data/skin/transport_reference.csv (python/gen_skin_transport_reference.py): the two-layer
skin slab's total reflectance (specular + diffuse, normal incidence) by Mitsuba 3 against Scott
Prahl's adding-doubling (iadpython).

(a) r_iad in the file is what iadpython computes now (to 1e-6): the table and the library agree.
(b) |r_mitsuba - r_iad| <= 4 stderr + 0.003 on every row: two independent transport computations
    (Monte Carlo path tracing and adding-doubling) agree, so the layer order, the Fresnel boundary,
    the specular term and the units are the same in both.

Run from the repository root:  .venv/bin/python -m pytest python/test_skin_transport_reference.py
(a couple of seconds; it does not run Mitsuba).
"""

from __future__ import annotations

import csv
from pathlib import Path

import numpy as np
import pytest

CSV = Path(__file__).resolve().parent.parent / "data" / "skin" / "transport_reference.csv"
QUAD_PTS = 16  # as in gen_skin_transport_reference.py

try:
    import iadpython as iad
except ImportError:  # pragma: no cover - depends on the environment
    iad = None


def rows() -> list[dict]:
    lines = [ln for ln in CSV.read_text().splitlines() if ln.strip() and not ln.startswith("#")]
    return list(csv.DictReader(lines))


def r_iad(r: dict) -> float:
    """Total reflectance for normal collimated incidence (UR1, specular included) by iadpython;
    layers listed bottom first (iadpython's stack reflects light coming from the last layer)."""
    f = {k: float(v) for k, v in r.items() if k not in ("name", "samples")}
    a_d = f["mus_derm_per_mm"] / (f["mus_derm_per_mm"] + f["mua_derm_per_mm"])
    if f["thickness_epi_mm"] == 0.0:
        s = iad.Sample(a=a_d, b=1e4, g=f["g"], d=1, n=f["n"], quad_pts=QUAD_PTS)
    else:
        mut_e = f["mus_epi_per_mm"] + f["mua_epi_per_mm"]
        s = iad.Sample(a=np.array([a_d, f["mus_epi_per_mm"] / mut_e]),
                       b=np.array([1e4, mut_e * f["thickness_epi_mm"]]),
                       g=np.array([f["g"], f["g"]]), d=1, n=f["n"], quad_pts=QUAD_PTS)
    R, _, T, _ = s.rt_matrices()
    return float(s.UX1_and_UXU(R, T)[0])


@pytest.fixture(scope="module")
def table() -> list[dict]:
    assert CSV.is_file(), f"{CSV} is missing; run python/gen_skin_transport_reference.py"
    t = rows()
    assert len(t) >= 10, "expected the single-layer checks and the two-layer cases"
    return t


def test_table_covers_both_kinds(table):
    single = [r for r in table if float(r["thickness_epi_mm"]) == 0.0]
    double = [r for r in table if float(r["thickness_epi_mm"]) > 0.0]
    assert len(single) >= 2 and len(double) >= 8
    assert {float(r["n"]) for r in single} >= {1.0, 1.4}, "single layer with and without the boundary"


def test_iad_column_is_iadpython(table):
    if iad is None:
        pytest.skip("iadpython is not importable (pip install iadpython, see python/requirements.txt); "
                    "cannot recompute the adding-doubling column")
    for r in table:
        got = r_iad(r)
        assert abs(got - float(r["r_iad"])) <= 1e-6, f"{r['name']}: iadpython gives {got}, file has {r['r_iad']}"


def test_iad_includes_specular():
    if iad is None:
        pytest.skip("iadpython is not importable (pip install iadpython, see python/requirements.txt)")
    black = {"name": "black", "mua_epi_per_mm": "1e4", "mus_epi_per_mm": "1", "g": "0.8", "thickness_epi_mm": "0",
             "mua_derm_per_mm": "1e4", "mus_derm_per_mm": "1", "n": "1.4", "samples": "0"}
    assert r_iad(black) == pytest.approx(((1.4 - 1) / (1.4 + 1)) ** 2, abs=1e-5)


def test_mitsuba_matches_adding_doubling(table):
    bad = []
    for r in table:
        m, se, a = float(r["r_mitsuba"]), float(r["r_mitsuba_stderr"]), float(r["r_iad"])
        assert 0.0 < se < 0.01, f"{r['name']}: implausible standard error {se}"
        assert int(r["samples"]) > 0
        if abs(m - a) > 4.0 * se + 0.003:
            bad.append(f"{r['name']}: mitsuba {m:.4f} +- {se:.4f} vs iad {a:.4f} (diff {m - a:+.4f})")
    assert not bad, "Mitsuba and adding-doubling disagree:\n" + "\n".join(bad)
