"""The formulation analyses through the Python package (rouge.SK_to_coverage, match_shades,
fit_mix_Duncan) against the CLI on the same presets, and their errors."""

from __future__ import annotations

import json
import subprocess

import numpy as np
import pytest

import rouge  # noqa: E402  (the package built from py/ by tests/run.sh)


def preset(repo_root, name: str) -> tuple[np.ndarray, np.ndarray]:
    p = json.loads((repo_root / "data" / "presets" / f"{name}.json").read_text())
    return np.array(p["s_per_mm"]), np.array(p["k_per_mm"])


def test_coverage_matches_the_cli(repo_root, rouge_bin, tmp_path) -> None:
    S, K = preset(repo_root, "foundation_02_ivory")
    xs = [0.0, 0.01, 0.02, 0.05]
    py = rouge.SK_to_coverage(S, K, xs)
    out = tmp_path / "c.json"
    subprocess.run([rouge_bin, "analyze", "coverage", "foundation_02_ivory", "--thickness-um", "0,10,20,50",
                    "--json", str(out)], check=True, capture_output=True)
    cli = json.loads(out.read_text())
    assert py["hiding_thickness_mm"] == cli["hiding_thickness_mm"]
    assert py["contrast_ratio"] == [r["contrast_ratio"] for r in cli["rows"]]
    assert py["contrast_ratio"][0] == pytest.approx(0.01 / 0.80, abs=1e-12)


def test_match_and_mix_recover_what_made_the_target(repo_root) -> None:
    shades = [preset(repo_root, n) for n in ("foundation_01_porcelain", "foundation_03_sand", "foundation_05_espresso")]
    skin = np.full(81, 0.35)
    S, K = shades[1]
    target = rouge.SK_to_coverage(S, K, [0.015], skins=[skin])
    # The covered colour of Sand at 15 µm as the target: Sand at 15 µm is the match.
    covered = rouge.SK_to_R_KubelkaMunk(S, K, 0.015, skin)
    lab = rouge.XYZ_to_Lab(rouge.sd_to_XYZ(covered) / 100.0)
    best = rouge.match_shades(shades, [skin], (0.0, 0.05), target_Lab=tuple(lab))[0]
    assert best["shade"] == 1 and abs(best["thickness_mm"] - 0.015) < 1e-6 and best["delta_E"] < 1e-3
    assert target["delta_E_skin"][0][0] > 1.0
    S_mix = 0.3 * shades[0][0] + 0.7 * shades[2][0]
    K_mix = 0.3 * shades[0][1] + 0.7 * shades[2][1]
    lab = rouge.XYZ_to_Lab(rouge.sd_to_XYZ(rouge.SK_to_Rinf_KubelkaMunk(S_mix, K_mix)) / 100.0)
    fit = rouge.fit_mix_Duncan([shades[0], shades[2]], tuple(lab))
    assert fit["concentrations"] == pytest.approx([0.3, 0.7], abs=1e-5)


def test_bad_input_raises_value_errors(repo_root) -> None:
    S, K = preset(repo_root, "foundation_02_ivory")
    with pytest.raises(ValueError, match="81"):
        rouge.SK_to_coverage(S[:40], K, [0.01])
    with pytest.raises(rouge.RougeError, match="black"):
        rouge.SK_to_coverage(S, K, [0.01], black=0.9, white=0.8)
    K_bad = K.copy()
    K_bad[10] = -1.0
    with pytest.raises(rouge.RougeError, match="430 nm"):
        rouge.SK_to_coverage(S, K_bad, [0.01])
    with pytest.raises(ValueError, match="both skin and thickness_mm"):
        rouge.fit_mix_Duncan([(S, K), (S, K)], (50.0, 0.0, 0.0), skin=np.full(81, 0.3))
