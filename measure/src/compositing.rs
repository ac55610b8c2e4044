//! How much colour a renderer loses by compositing cosmetic layers in fewer channels than the
//! spectrum: linear RGB (what a real-time renderer does) or a few spectral bands, against the
//! reference of composing every layer at every wavelength (\[Huang2013\] eq. 1-4).
//!
//! For every ordered pair of presets (top over bottom), every pair of thicknesses and every skin,
//! the stack `top / bottom / skin` is composed:
//! * **spectral** (reference): R0(λ), T(λ) of each layer from its S and K, composed per
//!   wavelength over the skin's reflectance, then XYZ and CIELAB (D65, 1931 observer);
//! * **linear RGB**: each layer's R0 and T converted to linear sRGB (the colour of the R0 and T
//!   spectra, as the preset's derived tables hold them), the skin likewise, composed per channel;
//!   the result is taken back to XYZ through the inverse sRGB matrix;
//! * **N bands**: R0, T and skin averaged over N equal bands of the working grid, composed per
//!   band, and the result expanded back to a piecewise-constant spectrum.
//!
//! The error is CIEDE2000 between the reference and each method. `rouge bench compositing`
//! prints the table; docs/BENCHMARKS.md records it.

use crate::colorimetry::{Colorimeter, Viewing, XYZ_TO_SRGB, delta_e_2000_raw, mat_inv};
use crate::km::{self, LayerRt};
use crate::layer_table::layer_spectra;
use crate::preset::Preset;
use crate::spectrum::{Spectrum, WORKING_LEN};

/// A compositing method.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Method {
    /// Per-channel in linear sRGB.
    LinearRgb,
    /// Per band, N equal bands over 380-780 nm.
    Bands(usize),
}

impl Method {
    /// Channels composed per pixel.
    pub fn channels(self) -> usize {
        match self {
            Method::LinearRgb => 3,
            Method::Bands(n) => n,
        }
    }

    /// Name for tables.
    pub fn name(self) -> String {
        match self {
            Method::LinearRgb => "linear sRGB".into(),
            Method::Bands(n) => format!("{n} spectral bands"),
        }
    }
}

/// Error statistics of one method.
#[derive(Clone, Debug, PartialEq, serde::Serialize)]
pub struct ErrorStats {
    /// Method name.
    pub method: String,
    /// Channels per pixel.
    pub channels: usize,
    /// Number of stacks compared.
    pub cases: usize,
    /// Mean ΔE2000.
    pub mean: f64,
    /// 95th percentile ΔE2000.
    pub p95: f64,
    /// Largest ΔE2000.
    pub max: f64,
    /// The worst case: "top (x mm) / bottom (x mm) / skin".
    pub worst_case: String,
}

/// One layer at one thickness, precomputed for every method.
struct LayerAt {
    spectral: (Spectrum, Spectrum),
}

fn band_average(s: &Spectrum, n: usize) -> Vec<f64> {
    let mut sum = vec![0.0; n];
    let mut count = vec![0usize; n];
    for (i, v) in s.0.iter().enumerate() {
        let b = i * n / WORKING_LEN;
        sum[b] += v;
        count[b] += 1;
    }
    sum.iter().zip(&count).map(|(s, c)| s / *c as f64).collect()
}

fn compose3(top: LayerRt, bottom: LayerRt, skin: f64) -> f64 {
    km::stack(&[top, bottom, LayerRt::opaque(skin)]).r
}

/// Compares `methods` against spectral compositing for all ordered pairs of distinct presets,
/// all pairs of `thicknesses_mm`, and all `skins`. Presets with invalid S or K are skipped.
pub fn compositing_error(
    presets: &[Preset],
    skins: &[(String, Spectrum)],
    thicknesses_mm: &[f64],
    methods: &[Method],
) -> Vec<ErrorStats> {
    let c = Colorimeter::get(Viewing::D65_1931);
    let inv = mat_inv(&XYZ_TO_SRGB);
    let lab_of_xyz = |xyz: [f64; 3]| {
        let x = crate::colorimetry::Xyz { xyz, viewing: Viewing::D65_1931 };
        c.lab(&x).lab
    };
    let rgb_of = |s: &Spectrum| c.srgb_linear(&c.xyz(s));
    let layers: Vec<Vec<LayerAt>> = presets
        .iter()
        .map(|p| thicknesses_mm.iter().map(|&x| LayerAt { spectral: layer_spectra(&p.s(), &p.k(), x) }).collect())
        .collect();
    let mut errors: Vec<Vec<(f64, String)>> = vec![Vec::new(); methods.len()];
    for (a, pa) in presets.iter().enumerate() {
        for (b, pb) in presets.iter().enumerate() {
            if a == b {
                continue;
            }
            for (xa, la) in layers[a].iter().enumerate() {
                for (xb, lb) in layers[b].iter().enumerate() {
                    for (skin_name, skin) in skins {
                        let reference = Spectrum(std::array::from_fn(|i| {
                            compose3(
                                LayerRt { r: la.spectral.0.0[i], t: la.spectral.1.0[i] },
                                LayerRt { r: lb.spectral.0.0[i], t: lb.spectral.1.0[i] },
                                skin.0[i],
                            )
                        }));
                        let lab_ref = c.lab(&c.xyz(&reference)).lab;
                        let case = format!(
                            "{} ({} mm) over {} ({} mm) over {skin_name}",
                            pa.name, thicknesses_mm[xa], pb.name, thicknesses_mm[xb]
                        );
                        for (m, method) in methods.iter().enumerate() {
                            let lab = match *method {
                                Method::LinearRgb => {
                                    let (ra, ta) = (rgb_of(&la.spectral.0), rgb_of(&la.spectral.1));
                                    let (rb, tb) = (rgb_of(&lb.spectral.0), rgb_of(&lb.spectral.1));
                                    let sk = rgb_of(skin);
                                    let rgb: [f64; 3] = std::array::from_fn(|ch| {
                                        compose3(
                                            LayerRt { r: ra[ch], t: ta[ch] },
                                            LayerRt { r: rb[ch], t: tb[ch] },
                                            sk[ch],
                                        )
                                    });
                                    let xyz: [f64; 3] = std::array::from_fn(|i| {
                                        100.0 * (inv[i][0] * rgb[0] + inv[i][1] * rgb[1] + inv[i][2] * rgb[2])
                                    });
                                    lab_of_xyz(xyz)
                                }
                                Method::Bands(n) => {
                                    let [ra, ta, rb, tb, sk] =
                                        [&la.spectral.0, &la.spectral.1, &lb.spectral.0, &lb.spectral.1, skin]
                                            .map(|s| band_average(s, n));
                                    let per_band: Vec<f64> = (0..n)
                                        .map(|k| {
                                            compose3(
                                                LayerRt { r: ra[k], t: ta[k] },
                                                LayerRt { r: rb[k], t: tb[k] },
                                                sk[k],
                                            )
                                        })
                                        .collect();
                                    let s = Spectrum(std::array::from_fn(|i| per_band[i * n / WORKING_LEN]));
                                    c.lab(&c.xyz(&s)).lab
                                }
                            };
                            errors[m].push((delta_e_2000_raw(lab_ref, lab), case.clone()));
                        }
                    }
                }
            }
        }
    }
    methods
        .iter()
        .zip(errors)
        .map(|(method, mut e)| {
            e.sort_by(|x, y| x.0.total_cmp(&y.0));
            let n = e.len();
            let mean = e.iter().map(|x| x.0).sum::<f64>() / n.max(1) as f64;
            let p95 = e.get((n * 95 / 100).min(n.saturating_sub(1))).map_or(0.0, |x| x.0);
            let (max, worst_case) = e.last().cloned().unwrap_or((0.0, String::new()));
            ErrorStats { method: method.name(), channels: method.channels(), cases: n, mean, p95, max, worst_case }
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::import::Kind;

    #[test]
    fn many_bands_converge_to_spectral() {
        let s = Spectrum::from_fn(|nm| 20.0 + nm / 50.0);
        let k1 = Spectrum::from_fn(|nm| if nm < 560.0 { 10.0 } else { 0.3 });
        let k2 = Spectrum::from_fn(|nm| 1.0 + ((nm - 380.0) / 60.0).sin().abs() * 5.0);
        let presets = [
            Preset::from_s_k("a", Kind::Lipstick, 0.02, &s, &k1),
            Preset::from_s_k("b", Kind::Foundation, 0.02, &s, &k2),
        ];
        let skins = [("grey".to_string(), Spectrum::constant(0.4))];
        let stats = compositing_error(
            &presets,
            &skins,
            &[0.0, 0.01, 0.05],
            &[Method::LinearRgb, Method::Bands(3), Method::Bands(81)],
        );
        assert_eq!(stats[0].cases, 2 * 9);
        // 81 bands of one sample each is the spectral computation itself.
        assert!(stats[2].max < 1e-9, "{:?}", stats[2]);
        assert!(stats[0].max > 1e-3, "RGB compositing should lose something: {:?}", stats[0]);
        assert!(stats.iter().all(|s| s.mean.is_finite() && s.max >= s.p95 && s.p95 >= 0.0));
    }
}
