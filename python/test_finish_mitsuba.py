"""Rouge's finish lobes against Mitsuba 3's `roughplastic` (python/finish_mitsuba.py): gloss
units at the ISO 2813 geometries, the directional albedo of the lobe, and Rouge's own gloss
integral against an independent integration of the same lobe (docs/FINISHES.md)."""

from __future__ import annotations

import pytest

mi = pytest.importorskip("mitsuba", reason="Mitsuba 3 (python/requirements.txt) is needed for the reference")

import finish_mitsuba as fm  # noqa: E402

import rouge  # noqa: E402


@pytest.mark.parametrize("name", list(fm.FINISHES))
def test_gloss_units_match_mitsuba_at_20_and_60_degrees(name):
    m, ior = fm.FINISHES[name]
    for angle in (20, 60, 85):
        here, theirs = fm.gloss_units(m, ior, angle)
        own = rouge.gloss_units_ISO2813(m, ior, angle)
        # Rouge's slope-space integral against this view-angle integral of the same lobe.
        assert own == pytest.approx(here, rel=0.02, abs=0.01), (name, angle)
        if angle < 85:
            assert here == pytest.approx(theirs, rel=0.05, abs=0.05), (name, angle, here, theirs)
        else:
            # The Kelemen lobe has no shadowing: at 85 degrees it reads rough films too glossy.
            assert here >= 0.95 * theirs, (name, here, theirs)


@pytest.mark.parametrize("name", list(fm.FINISHES))
def test_the_lobe_reflects_about_what_a_full_microfacet_model_does(name):
    m, ior = fm.FINISHES[name]
    for theta in (0, 30, 60):
        ours, theirs = fm.directional_albedo(m, ior, theta, samples=1600)
        assert 0.0 < ours <= theirs * 1.05, (name, theta, ours, theirs)
        assert ours > 0.7 * theirs, (name, theta, ours, theirs)


def test_bad_arguments_are_value_errors():
    with pytest.raises(ValueError, match="20, 60 or 85"):
        rouge.gloss_units_ISO2813(0.2, 1.5, 45)
    with pytest.raises(ValueError, match="roughness"):
        rouge.specular_BRDF_Kelemen((0, 0, 1), (0, 0, 1), 0.0, 1.5)
    with pytest.raises(ValueError, match="unit"):
        rouge.specular_BRDF_Kelemen((0, 0, 2), (0, 0, 1), 0.2, 1.5)
    fit = rouge.fit_gloss_ISO2813({60: 12.0}, 1.5)
    assert fit["nearest_finish"] == "dewy" and fit["fitted"][60] == pytest.approx(12.0, rel=1e-3)
    with pytest.raises(ValueError, match="no gloss"):
        rouge.fit_gloss_ISO2813({}, 1.5)
