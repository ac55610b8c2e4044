"""A finished foundation over skin, Rouge's flat-sample reflectance against Mitsuba 3
(docs/FINISHES.md, "A film over skin against Mitsuba 3").

The sample: 30 um of the ivory foundation (data/presets/foundation_02_ivory.json, its S and K)
fully covering the light skin tone of Rouge's spectral skin model (`rouge.skin_reflectance`),
with each named finish (rouge_measure::finish: the film's Beckmann roughness, index and clarity).
Its diffuse reflectance is the Kubelka-Munk composition R = R0 + T² Rg / (1 - R0 Rg) of the layer
(`SK_to_R0T_KubelkaMunk`) over the skin, per wavelength (380-780 nm).

- **Rouge** (the lighting pass, `shaders/lighting.wgsl`, on a flat sample without subsurface
  transport): Lambertian R, plus the film's Kelemen lobe, plus the skin's two lobes under the film
  × clarity × T² (`render/src/specular.rs`, skin roughness 0.35, index 1.4). Its directional
  reflectance at incidence θ: R(λ) + A_film(θ) + clarity · A_skin(θ) · T(λ)².
- **Mitsuba 3** `roughplastic` (Beckmann, the film's alpha and interior index, `nonlinear` false):
  a rough dielectric interface over a diffuse base of reflectance R, with exact Fresnel, Smith
  shadowing and the Fresnel transmission in and out of the diffuse part. Its directional
  reflectance is linear in the base's, so two `scalar_rgb` runs (base 0 and base 1) give it for
  every wavelength: S(θ) + R(λ) · D(θ).

Both by importance sampling Mitsuba's BSDF (64² stratified samples, the same samples weigh
Rouge's lobes). Compared as colours (CIELAB, D65, 2°) at θ = 0, 30, 60 and 75°: ΔE2000, and the
luminance factor Y of each.

Usage: python python/finish_over_skin_mitsuba.py [--plot docs/images/finish_over_skin_mitsuba.png]
(prints a Markdown table; about a minute).
"""

from __future__ import annotations

import argparse
import math
from pathlib import Path

import numpy as np

import rouge
from finish_mitsuba import _interaction, _mi, _unit

ROOT = Path(__file__).resolve().parent.parent
# rouge_measure::finish::FinishKind::defaults: (roughness, index, clarity)
FINISHES = {"matte": (0.45, 1.45, 0.3), "satin": (0.25, 1.45, 0.7), "dewy": (0.12, 1.48, 0.9), "gloss": (0.04, 1.50, 1.0)}
THICKNESS_MM = 0.030
SKIN_ROUGHNESS, SKIN_IOR = 0.35, 1.4
SKIN_LOBES = ((0.75, 0.85), (1.30, 0.15))  # render/src/specular.rs: roughness × m, mix
ANGLES = (0, 30, 60, 75)
WAVELENGTHS: np.ndarray | None = None
SIDE = 64


def sample_spectra() -> tuple[np.ndarray, np.ndarray]:
    """(R, T²) of the sample per wavelength of the working grid."""
    preset = rouge.Preset.load(str(ROOT / "data/presets/foundation_02_ivory.json"))
    global WAVELENGTHS
    wl = np.asarray(preset.wavelengths, dtype=float)
    WAVELENGTHS = wl
    r0, t = rouge.SK_to_R0T_KubelkaMunk(np.asarray(preset.S), np.asarray(preset.K), THICKNESS_MM)
    rg = np.asarray(rouge.skin_reflectance(tone="light", wavelengths=wl))
    return r0 + t * t * rg / (1.0 - r0 * rg), t * t


def albedos(roughness: float, ior: float) -> dict[int, tuple[float, float, float, float]]:
    """Per angle: (A_film, A_skin, S, D): Rouge's film lobe and skin lobes (m, F0 of index 1.4)
    and Mitsuba's specular part and diffuse factor, by importance sampling Mitsuba's BSDF."""
    mi = _mi()

    def plastic(base: float):
        return mi.load_dict({"type": "roughplastic", "distribution": "beckmann", "alpha": roughness,
                             "int_ior": ior, "ext_ior": 1.0, "nonlinear": False,
                             "diffuse_reflectance": {"type": "rgb", "value": [base] * 3}})

    black, white = plastic(0.0), plastic(1.0)
    ctx = mi.BSDFContext()
    rng = np.random.default_rng(11)
    out = {}
    for theta in ANGLES:
        t = math.radians(theta)
        wi = (math.sin(t), 0.0, math.cos(t))
        si = _interaction(wi)
        a_film = a_skin = s = d_plus_s = 0.0
        for i in range(SIDE):
            for j in range(SIDE):
                u = mi.Point2f((i + rng.random()) / SIDE, (j + rng.random()) / SIDE)
                lobe = float(rng.random())
                # Mitsuba: each BSDF with its own sampler.
                for bsdf, acc in ((black, "s"), (white, "d")):
                    bs, weight = bsdf.sample(ctx, si, lobe, u)
                    if bs.pdf > 0.0 and bs.wo[2] > 0.0:
                        if acc == "s":
                            s += float(weight[0])
                        else:
                            d_plus_s += float(weight[0])
                # Rouge's lobes, weighed by the black plastic's (specular-only) samples; a cosine
                # sample of the hemisphere for the broad skin lobes.
                bs, _ = black.sample(ctx, si, lobe, u)
                if bs.pdf > 0.0 and bs.wo[2] > 0.0:
                    wo = _unit((float(bs.wo[0]), float(bs.wo[1]), float(bs.wo[2])))
                    a_film += rouge.specular_BRDF_Kelemen(wi, wo, roughness, ior) * wo[2] / float(bs.pdf)
                r = math.sqrt(u[0])
                phi = 2.0 * math.pi * u[1]
                wo = (r * math.cos(phi), r * math.sin(phi), math.sqrt(max(0.0, 1.0 - r * r)))
                if wo[2] > 1e-6:
                    f = sum(w * rouge.specular_BRDF_Kelemen(wi, wo, k * SKIN_ROUGHNESS, SKIN_IOR) for k, w in SKIN_LOBES)
                    a_skin += f * math.pi  # f cos / (cos / π)
        n = SIDE * SIDE
        out[theta] = (a_film / n, a_skin / n, s / n, (d_plus_s - s) / n)
    return out


def lab(spectrum: np.ndarray) -> np.ndarray:
    return rouge.sd_to_Lab(spectrum)


def table() -> list[dict]:
    r, t2 = sample_spectra()
    rows = []
    for name, (m, ior, clarity) in FINISHES.items():
        a = albedos(m, ior)
        row = {"finish": name}
        for theta in ANGLES:
            a_film, a_skin, s, d = a[theta]
            ours = r + a_film + clarity * a_skin * t2
            theirs = s + r * d
            de = float(rouge.delta_E_CIE2000(lab(ours), lab(theirs)))
            # Rouge's R read as a measurement without the specular (SCE): Mitsuba's base is then
            # the internal reflectance Saunderson's correction gives, at the film's index.
            internal = np.asarray(rouge.R_measured_to_internal_Saunderson(r, n=ior, specular_included=False,
                                                                          wavelengths=WAVELENGTHS))
            de_s = float(rouge.delta_E_CIE2000(lab(ours), lab(s + internal * d)))
            y = (float(rouge.sd_to_XYZ(ours)[1]), float(rouge.sd_to_XYZ(theirs)[1]))
            row[theta] = {"dE": de, "dE_saunderson": de_s, "Y": y, "film": a_film, "skin": clarity * a_skin, "S": s, "D": d}
        rows.append(row)
    return rows


def markdown(rows: list[dict]) -> str:
    head = "| finish | " + " | ".join(f"θ {t}°: ΔE2000 (Saunderson base), Y Rouge / Mitsuba" for t in ANGLES) + " |"
    lines = [head, "| --- |" + " --- |" * len(ANGLES)]
    for row in rows:
        cells = [f"{row[t]['dE']:.2f} ({row[t]['dE_saunderson']:.2f}), {row[t]['Y'][0]:.1f} / {row[t]['Y'][1]:.1f}"
                 for t in ANGLES]
        lines.append(f"| {row['finish']} | " + " | ".join(cells) + " |")
    lines.append("")
    lines.append("| finish | " + " | ".join(f"θ {t}°: film lobe, skin lobes × clarity (Rouge); specular S, diffuse factor D (Mitsuba)" for t in ANGLES) + " |")
    lines.append("| --- |" + " --- |" * len(ANGLES))
    for row in rows:
        cells = [f"{row[t]['film']:.3f}, {row[t]['skin']:.3f}; {row[t]['S']:.3f}, {row[t]['D']:.3f}" for t in ANGLES]
        lines.append(f"| {row['finish']} | " + " | ".join(cells) + " |")
    return "\n".join(lines)


def plot(rows: list[dict], path: Path) -> None:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, (ax1, ax2) = plt.subplots(1, 2, figsize=(9, 3.4))
    for row in rows:
        ys = [row[t]["Y"] for t in ANGLES]
        line, = ax1.plot(ANGLES, [y[0] for y in ys], "o-", label=f"{row['finish']} Rouge")
        ax1.plot(ANGLES, [y[1] for y in ys], "s--", color=line.get_color(), label=f"{row['finish']} Mitsuba")
        ax2.plot(ANGLES, [row[t]["dE"] for t in ANGLES], "o-", color=line.get_color(), label=row["finish"])
    ax1.set_xlabel("incidence θ (°)")
    ax1.set_ylabel("luminance factor Y (%)")
    ax1.set_title("directional reflectance")
    ax1.legend(fontsize=6, ncol=2)
    ax2.set_xlabel("incidence θ (°)")
    ax2.set_ylabel("ΔE2000 Rouge vs Mitsuba")
    ax2.set_title("30 µm ivory foundation over light skin")
    ax2.legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(path, dpi=110)


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--plot", type=Path)
    a = ap.parse_args()
    rows = table()
    print(markdown(rows))
    if a.plot:
        plot(rows, a.plot)


if __name__ == "__main__":
    main()
