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
//! * **the compositing basis** ([`CompositingBasis`], what the renderer does): linear RGB taken
//!   into the basis c = A·rgb, composed per channel of c, and taken back by A⁻¹.
//!
//! The error is CIEDE2000 between the reference and each method. `rouge bench compositing`
//! prints the table; docs/BENCHMARKS.md records it.

use crate::colorimetry::{Colorimeter, Mat3, Viewing, XYZ_TO_SRGB, delta_e_2000_raw, mat_inv, mat_vec};
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
    /// Per channel of the renderer's [`CompositingBasis`].
    Basis,
}

impl Method {
    /// Channels composed per pixel.
    pub fn channels(self) -> usize {
        match self {
            Method::LinearRgb | Method::Basis => 3,
            Method::Bands(n) => n,
        }
    }

    /// Name for tables.
    pub fn name(self) -> String {
        match self {
            Method::LinearRgb => "linear sRGB".into(),
            Method::Bands(n) => format!("{n} spectral bands"),
            Method::Basis => "compositing basis (A·linear sRGB)".into(),
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
                                Method::LinearRgb | Method::Basis => {
                                    let basis = match method {
                                        Method::Basis => CompositingBasis::get(),
                                        _ => &CompositingBasis::IDENTITY,
                                    };
                                    let of = |s: &Spectrum| basis.from_linear_srgb(rgb_of(s));
                                    let (ra, ta) = (of(&la.spectral.0), of(&la.spectral.1));
                                    let (rb, tb) = (of(&lb.spectral.0), of(&lb.spectral.1));
                                    let sk = of(skin);
                                    let rgb = basis.to_linear_srgb(std::array::from_fn(|ch| {
                                        compose3(
                                            LayerRt { r: ra[ch], t: ta[ch] },
                                            LayerRt { r: rb[ch], t: tb[ch] },
                                            sk[ch],
                                        )
                                    }));
                                    lab_of_xyz(mat_vec(&inv, rgb).map(|v| 100.0 * v))
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

/// The renderer's compositing basis: a linear transform of linear sRGB in which cosmetic layers
/// are composed over skin per channel (render/src/shaders/lighting.wgsl).
///
/// Kubelka-Munk composition (\[Huang2013\] eq. 3-4) multiplies spectra, and the colour of a
/// product is not the product of colours: composed in linear sRGB, skin under one foundation is
/// 0.64 ΔE2000 from the spectral composition on average (1.73 at the 95th percentile). Composed
/// per channel of c = A·rgb and taken back by A⁻¹, it comes closer, for a well-chosen A: the
/// idea of spectral sharpening (\[Finlayson1994\]) and of rendering in sharpened primaries
/// (\[Ward2002\]), a transform chosen so that per-channel products behave like spectral ones.
/// Fitted for composition over skin, the transform comes out *broadening* rather than sharpening:
/// each channel takes a little of the other two, which shrinks the sRGB sensors' negative lobes
/// (red −0.21 of its positive area against −0.33, green −0.02 against −0.11). A's rows sum to
/// one, so grey stays grey: a bare surface under white light is unchanged, only products of
/// colours move.
///
/// A is fitted by `python/fit_compositing_basis.py` (least squares on ΔE2000; the file
/// data/compositing_basis.json holds A, what it was fitted on and its errors) on random
/// pigment-library layers over random skins of the skin model, and reported on data it was not
/// fitted on: the ten tones under the five sample foundations at 0-60 µm (0.22 mean, 0.61 p95,
/// against 0.64 and 1.73 in linear sRGB), 200 measured skins of \[Xiao2016\] under the same
/// (0.24, 0.58 against 0.82, 1.91) and stacked pairs of the sample presets over the ColorChecker
/// skins (0.48, 1.35 against 1.37, 3.78). Domain: reflectances and transmittances in 0..1 near
/// the sRGB gamut; the composition stays finite for any colour, only less accurate far outside.
#[derive(Clone, Debug, PartialEq)]
pub struct CompositingBasis {
    /// A: linear sRGB → basis, rows first (each row sums to one).
    pub from_srgb: Mat3,
    /// A⁻¹: basis → linear sRGB.
    pub to_srgb: Mat3,
}

const BASIS_JSON: &str = include_str!("../../data/compositing_basis.json");

#[derive(serde::Deserialize)]
struct BasisFile {
    schema: String,
    version: u32,
    matrix_from_linear_srgb: Mat3,
}

impl CompositingBasis {
    /// Linear sRGB itself (A = I): today's compositing before the basis, for comparison.
    pub const IDENTITY: CompositingBasis = CompositingBasis {
        from_srgb: [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]],
        to_srgb: [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]],
    };

    /// The fitted basis (data/compositing_basis.json, embedded).
    ///
    /// # Examples
    /// ```
    /// use rouge_measure::compositing::CompositingBasis;
    /// let basis = CompositingBasis::get();
    /// // Grey is unchanged; a colour goes there and back.
    /// let grey = basis.from_linear_srgb([0.5; 3]);
    /// assert!(grey.iter().all(|v| (v - 0.5).abs() < 1e-6));
    /// let back = basis.to_linear_srgb(basis.from_linear_srgb([0.45, 0.3, 0.2]));
    /// assert!((back[0] - 0.45).abs() < 1e-12 && (back[2] - 0.2).abs() < 1e-12);
    /// ```
    pub fn get() -> &'static CompositingBasis {
        static BASIS: std::sync::OnceLock<CompositingBasis> = std::sync::OnceLock::new();
        // `the_embedded_basis_loads` checks the file; were it unreadable, linear sRGB stands in
        // rather than a panic.
        BASIS.get_or_init(|| Self::parse(BASIS_JSON).unwrap_or(Self::IDENTITY))
    }

    /// A basis from its JSON (schema `rouge-compositing-basis` v1), or why not: rows that do not
    /// sum to one (grey would change colour), a non-finite entry or a near-singular matrix.
    pub fn parse(json: &str) -> Result<CompositingBasis, String> {
        let f: BasisFile = serde_json::from_str(json).map_err(|e| format!("compositing basis: {e}"))?;
        if f.schema != "rouge-compositing-basis" || f.version != 1 {
            return Err(format!(
                "compositing basis: schema {} v{} is not rouge-compositing-basis v1",
                f.schema, f.version
            ));
        }
        let a = f.matrix_from_linear_srgb;
        if let Some((i, _)) = a
            .iter()
            .enumerate()
            .find(|(_, r)| r.iter().any(|v| !v.is_finite()) || (r.iter().sum::<f64>() - 1.0).abs() > 1e-6)
        {
            return Err(format!("compositing basis: row {i} is not finite or does not sum to one"));
        }
        let det = a[0][0] * (a[1][1] * a[2][2] - a[1][2] * a[2][1]) - a[0][1] * (a[1][0] * a[2][2] - a[1][2] * a[2][0])
            + a[0][2] * (a[1][0] * a[2][1] - a[1][1] * a[2][0]);
        if det.abs() < 0.1 {
            return Err(format!("compositing basis: determinant {det:.3} (near singular)"));
        }
        Ok(CompositingBasis { from_srgb: a, to_srgb: mat_inv(&a) })
    }

    /// A·rgb: a linear sRGB colour (a reflectance's or transmittance's) in the basis.
    pub fn from_linear_srgb(&self, rgb: [f64; 3]) -> [f64; 3] {
        mat_vec(&self.from_srgb, rgb)
    }

    /// A⁻¹·c: a colour composed in the basis, back in linear sRGB.
    pub fn to_linear_srgb(&self, c: [f64; 3]) -> [f64; 3] {
        mat_vec(&self.to_srgb, c)
    }

    /// The diffuse reflectance of cosmetic layers over an opaque skin, composed per channel of
    /// the basis as the renderer's lighting pass composes them (render/src/shaders/lighting.wgsl,
    /// whose `r_top + T²·a / (1 − R_below·a)` is this fold): each layer's R0 and T (linear sRGB,
    /// from its render table, [`crate::layer_table::lookup`]) and the skin's albedo `skin`
    /// (linear sRGB) taken into the basis, the layers put over the skin bottom to top with
    /// \[Huang2013\] eq. 3-4 ([`km::compose`]), the result back in linear sRGB. What a surface
    /// under white light shows with no subsurface scattering; the glTF bake's base colour.
    ///
    /// With no layers the skin comes back unchanged (as the shader keeps the albedo where no
    /// layer covers a pixel). Domain: as the basis's; finite for finite inputs with R0 < 1.
    ///
    /// # Examples
    /// ```
    /// use rouge_measure::compositing::CompositingBasis;
    /// let basis = CompositingBasis::get();
    /// let skin = [0.45, 0.3, 0.2];
    /// assert_eq!(basis.reflectance_over_skin(&[], skin), skin);
    /// // A clear layer (R0 = 0, T = 1) changes nothing; an opaque one (T = 0) shows its R0.
    /// let clear = basis.reflectance_over_skin(&[([0.0; 3], [1.0; 3])], skin);
    /// assert!(clear.iter().zip(skin).all(|(a, b)| (a - b).abs() < 1e-12));
    /// let opaque = basis.reflectance_over_skin(&[([0.6, 0.1, 0.1], [0.0; 3])], skin);
    /// assert!((opaque[0] - 0.6).abs() < 1e-6 && (opaque[2] - 0.1).abs() < 1e-6);
    /// ```
    pub fn reflectance_over_skin(&self, layers_bottom_first: &[([f32; 3], [f32; 3])], skin: [f64; 3]) -> [f64; 3] {
        if layers_bottom_first.is_empty() {
            return skin;
        }
        let a = self.from_linear_srgb(skin);
        let of = |v: &[f32; 3]| self.from_linear_srgb(v.map(f64::from));
        let layers: Vec<([f64; 3], [f64; 3])> = layers_bottom_first.iter().map(|(r, t)| (of(r), of(t))).collect();
        self.to_linear_srgb(std::array::from_fn(|ch| {
            let mut top_first: Vec<LayerRt> =
                layers.iter().rev().map(|(r, t)| LayerRt { r: r[ch], t: t[ch] }).collect();
            top_first.push(LayerRt::opaque(a[ch]));
            km::stack(&top_first).r
        }))
    }

    /// The matrices as WGSL constants `BASIS_FROM_SRGB` and `BASIS_TO_SRGB` (`mat3x3<f32>`, so
    /// `BASIS_FROM_SRGB * rgb` is A·rgb), for the renderer's shaders.
    pub fn wgsl_constants(&self) -> String {
        let mat = |m: &Mat3| {
            let col = |j: usize| format!("vec3<f32>({:?}, {:?}, {:?})", m[0][j] as f32, m[1][j] as f32, m[2][j] as f32);
            format!("mat3x3<f32>({}, {}, {})", col(0), col(1), col(2))
        };
        format!(
            "const BASIS_FROM_SRGB: mat3x3<f32> = {};\nconst BASIS_TO_SRGB: mat3x3<f32> = {};\n",
            mat(&self.from_srgb),
            mat(&self.to_srgb)
        )
    }
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

    #[test]
    fn the_embedded_basis_loads_and_keeps_grey() {
        let basis = CompositingBasis::parse(BASIS_JSON).expect("data/compositing_basis.json");
        assert_eq!(&basis, CompositingBasis::get());
        assert_ne!(basis, CompositingBasis::IDENTITY, "the fitted basis is not linear sRGB");
        for v in [0.0, 0.18, 1.0] {
            let c = basis.from_linear_srgb([v; 3]);
            assert!(c.iter().all(|x| (x - v).abs() < 1e-6), "{v}: {c:?}");
        }
        let rgb = [0.41, 0.25, 0.17];
        let back = basis.to_linear_srgb(basis.from_linear_srgb(rgb));
        assert!(back.iter().zip(rgb).all(|(a, b)| (a - b).abs() < 1e-12), "{back:?}");
    }

    #[test]
    fn a_bad_basis_says_why() {
        let doc = |m: &str| {
            format!(r#"{{"schema": "rouge-compositing-basis", "version": 1, "matrix_from_linear_srgb": {m}}}"#)
        };
        let e = CompositingBasis::parse(&doc("[[1, 0.5, 0], [0, 1, 0], [0, 0, 1]]")).unwrap_err();
        assert!(e.contains("row 0") && e.contains("sum to one"), "{e}");
        let e = CompositingBasis::parse(&doc("[[0.5, 0.5, 0], [0.5, 0.5, 0], [0, 0, 1]]")).unwrap_err();
        assert!(e.contains("singular"), "{e}");
        assert!(CompositingBasis::parse("{").unwrap_err().contains("compositing basis"));
    }

    #[test]
    fn the_basis_beats_linear_srgb_on_skin_under_foundation() {
        // Held-out data of the fit: the built-in foundations over the ColorChecker skins.
        let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../data/presets");
        let presets: Vec<Preset> = ["foundation_01_porcelain", "foundation_04_caramel", "blush_02_coral"]
            .iter()
            .map(|n| Preset::load(&dir.join(format!("{n}.json"))).expect("sample preset"))
            .collect();
        let skins = crate::import::colorchecker_skin().expect("embedded ColorChecker skins");
        let stats = compositing_error(&presets, &skins, &[0.005, 0.02, 0.06], &[Method::LinearRgb, Method::Basis]);
        assert!(stats[1].mean < 0.7 * stats[0].mean, "basis {:?} vs linear sRGB {:?}", stats[1], stats[0]);
        assert!(stats[1].p95 < stats[0].p95, "basis {:?} vs linear sRGB {:?}", stats[1], stats[0]);
    }
}
