//! Tables of a cosmetic layer's reflectance over black R0(X) and transmittance T(X) in linear
//! sRGB, for renderers. One owner for both tables Rouge uses:
//! - the preset's interchange table (`preset::derive_tables`: 0-0.2 mm every 5 µm, stored in
//!   preset JSON v1), and
//! - the render table ([`render_table`]): [`TABLE_ENTRIES`] entries at X = X0·u/(1−u),
//!   u = i/(n−1), X0 = [`TABLE_X0_MM`], so half the entries cover 0..X0 where films live; exact
//!   at 0 (R0 = 0, T = 1) and, in the last entry, at the opaque limit (R∞, T = 0).
//!
//! Both convert the spectral R0 and T of [`layer_spectra`] (the layer of \[Huang2013\] eq. 1-2,
//! the hyperbolic solution of \[Kubelka1948\], in the overflow-free form derived in
//! [`crate::km`]) to linear sRGB under D65 with the CIE 1931 observer in one place,
//! [`layer_rgb_at`]. Keys: docs/REFERENCES.md. The renderer samples the render table with
//! [`lookup`]'s formula in WGSL (its constants injected from [`wgsl_constants`]).
//!
//! This module knows nothing of presets: a preset is a [`TableLayer`] (it implements the trait),
//! so the preset module depends on this one and not the other way round.

use crate::colorimetry::{Colorimeter, Viewing};
use crate::km::{self, LayerRt};
use crate::spectrum::{Spectrum, WORKING_LEN};

/// Entries per render-table row.
pub const TABLE_ENTRIES: usize = 64;
/// X0 of the render table's parameterisation X = X0·u/(1−u), mm: half the entries cover 0..X0.
pub const TABLE_X0_MM: f64 = 0.02;

/// Spectral R0 and T of a layer with scattering `s` and absorption `k` (mm⁻¹, on the working
/// grid) and thickness `x_mm`: \[Huang2013\] eq. 1 (R0, the layer over black) and eq. 2 (T) at
/// each wavelength, in the overflow-free form of [`km::layer_r_t`]. Domain: S, K ≥ 0 and
/// thickness ≥ 0 mm (0 gives R0 = 0, T = 1); no check is made here.
///
/// # Examples
///
/// A film of S = 20 /mm, K = 2 /mm and 50 µm: R0 + T < 1 (the film absorbs), and at 0 mm the
/// layer is clear.
///
/// ```
/// use rouge_measure::layer_table::layer_spectra;
/// use rouge_measure::Spectrum;
///
/// let (s, k) = (Spectrum([20.0; 81]), Spectrum([2.0; 81]));
/// let (r0, t) = layer_spectra(&s, &k, 0.05);
/// // Eq. 1-2 with a = (S + K)/S = 1.1, b = √(a² − 1), y = b·S·X = 0.45826:
/// // R0 = sinh y / (a sinh y + b cosh y) = 0.461034, T = b / (a sinh y + b cosh y) = 0.445284.
/// assert!((r0.0[0] - 0.461_034).abs() < 1e-6, "{}", r0.0[0]);
/// assert!((t.0[0] - 0.445_284).abs() < 1e-6, "{}", t.0[0]);
/// let (r0, t) = layer_spectra(&s, &k, 0.0);
/// assert_eq!((r0.0[40], t.0[40]), (0.0, 1.0));
/// ```
pub fn layer_spectra(s: &Spectrum, k: &Spectrum, x_mm: f64) -> (Spectrum, Spectrum) {
    let mut r = [0.0; WORKING_LEN];
    let mut t = [0.0; WORKING_LEN];
    for i in 0..WORKING_LEN {
        let LayerRt { r: ri, t: ti } = km::layer_r_t_unchecked(s.0[i], k.0[i], x_mm);
        r[i] = ri;
        t[i] = ti;
    }
    (Spectrum(r), Spectrum(t))
}

/// R0 and T of a layer with scattering `s` and absorption `k` (per mm) at each thickness of
/// `thickness_mm`, as linear sRGB (D65, CIE 1931): \[Huang2013\] eq. 1 (R0, over black) and eq. 2
/// (T) per wavelength, then XYZ by summation (\[CIE15\]) and the \[IEC61966\] matrix. Domain:
/// S, K ≥ 0 and thickness ≥ 0 mm (0 gives R0 = 0, T = 1); colours are not clipped.
pub fn layer_rgb_at(s: &Spectrum, k: &Spectrum, thickness_mm: &[f64]) -> (Vec<[f64; 3]>, Vec<[f64; 3]>) {
    let c = Colorimeter::get(Viewing::D65_1931);
    thickness_mm
        .iter()
        .map(|&x| {
            let (r, t) = layer_spectra(s, k, x);
            (c.srgb_linear(&c.xyz(&r)), c.srgb_linear(&c.xyz(&t)))
        })
        .unzip()
}

/// Thickness (mm) of render-table entry `i`: X0·u/(1−u), u = i/(n−1); infinite for the last.
pub fn entry_thickness_mm(i: usize) -> f64 {
    if i + 1 >= TABLE_ENTRIES {
        return f64::INFINITY;
    }
    let u = i as f64 / (TABLE_ENTRIES - 1) as f64;
    TABLE_X0_MM * u / (1.0 - u)
}

/// A layer's render table: [`TABLE_ENTRIES`] rows of R0 and T, linear sRGB, as f32.
#[derive(Clone, Debug, PartialEq)]
pub struct RenderTable {
    /// R0 per entry.
    pub r0: Vec<[f32; 3]>,
    /// T per entry.
    pub t: Vec<[f32; 3]>,
}

/// What a render table is made of: a layer's S and K and its R∞ in linear sRGB (D65, CIE 1931),
/// the table's opaque end. A preset is one (its R∞ is the one its JSON stores).
pub trait TableLayer {
    /// Scattering S and absorption K per wavelength of the working grid, mm⁻¹.
    fn s_k(&self) -> (Spectrum, Spectrum);
    /// R∞, linear sRGB (D65, CIE 1931).
    fn r_inf_linear_srgb(&self) -> [f64; 3];
}

/// The render table of a layer (a preset): entry 0 is exactly clear (R0 = 0, T = 1), the last
/// entry the opaque limit (the layer's R∞, T = 0), the others from [`layer_rgb_at`].
pub fn render_table(layer: &impl TableLayer) -> RenderTable {
    let (s, k) = layer.s_k();
    let inner: Vec<f64> = (1..TABLE_ENTRIES - 1).map(entry_thickness_mm).collect();
    let (r_mid, t_mid) = layer_rgb_at(&s, &k, &inner);
    let f32s = |v: &[f64; 3]| v.map(|x| x as f32);
    let mut r0 = vec![[0.0; 3]];
    let mut t = vec![[1.0; 3]];
    r0.extend(r_mid.iter().map(f32s));
    t.extend(t_mid.iter().map(f32s));
    r0.push(f32s(&layer.r_inf_linear_srgb()));
    t.push([0.0; 3]);
    RenderTable { r0, t }
}

/// The renderer's table lookup on the CPU (the WGSL in lighting.wgsl does the same): entry
/// position u·(n−1) with u = x/(x + X0), linear interpolation between neighbours. Exact at the
/// nodes; between them, within 2e-3 of [`layer_rgb_at`] for the films Rouge renders (tested).
/// Negative thickness reads as 0, infinite or NaN as the opaque limit.
pub fn lookup(row: &[[f32; 3]], x_mm: f32) -> [f32; 3] {
    let n = row.len();
    if n < 2 {
        return row.first().copied().unwrap_or([0.0; 3]);
    }
    let x = if x_mm.is_finite() { x_mm.max(0.0) } else { f32::MAX };
    let u = x / (x + TABLE_X0_MM as f32);
    let f = u * (n - 1) as f32;
    let i = (f as usize).min(n - 2);
    let w = f - i as f32;
    std::array::from_fn(|c| row[i][c] + (row[i + 1][c] - row[i][c]) * w)
}

/// The table constants as WGSL declarations, injected ahead of every shader.
pub fn wgsl_constants() -> String {
    format!("const TABLE_X0_MM: f32 = {TABLE_X0_MM:?};\nconst TABLE_ENTRIES: u32 = {TABLE_ENTRIES}u;\n")
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A film whose R∞ comes from its S and K, as a preset's does (`km::r_inf_from_s_k`).
    struct Film {
        s: Spectrum,
        k: Spectrum,
    }

    impl TableLayer for Film {
        fn s_k(&self) -> (Spectrum, Spectrum) {
            (self.s, self.k)
        }
        fn r_inf_linear_srgb(&self) -> [f64; 3] {
            let c = Colorimeter::get(Viewing::D65_1931);
            let r_inf = Spectrum(std::array::from_fn(|i| km::r_inf_from_s_k(self.s.0[i], self.k.0[i])));
            c.srgb_linear(&c.xyz(&r_inf))
        }
    }

    fn film() -> Film {
        let s = Spectrum(std::array::from_fn(|i| 30.0 + i as f64 * 0.2));
        let k = Spectrum(std::array::from_fn(|i| 1.0 + (i % 7) as f64));
        Film { s, k }
    }

    #[test]
    fn ends_are_exact_and_transmittance_falls() {
        let p = film();
        let t = render_table(&p);
        assert_eq!((t.r0.len(), t.t.len()), (TABLE_ENTRIES, TABLE_ENTRIES));
        assert_eq!((t.r0[0], t.t[0]), ([0.0; 3], [1.0; 3]));
        assert_eq!(t.t[TABLE_ENTRIES - 1], [0.0; 3]);
        assert_eq!(t.r0[TABLE_ENTRIES - 1], p.r_inf_linear_srgb().map(|v| v as f32));
        for w in t.t.windows(2) {
            for c in 0..3 {
                assert!(w[1][c] <= w[0][c] + 1e-6, "T must not grow with thickness: {w:?}");
            }
        }
    }

    #[test]
    fn lookup_is_exact_at_nodes_and_close_between() {
        let p = film();
        let t = render_table(&p);
        for i in [0, 1, 10, 31, 62] {
            let x = entry_thickness_mm(i) as f32;
            let got = lookup(&t.r0, x);
            for c in 0..3 {
                assert!((got[c] - t.r0[i][c]).abs() < 2e-5, "node {i}: {got:?} vs {:?}", t.r0[i]);
            }
        }
        // Between nodes, against the exact spectral value: the interpolation error stays small.
        let (s, k) = p.s_k();
        for x in [0.0013, 0.007, 0.019, 0.05, 0.3] {
            let (r, tr) = layer_rgb_at(&s, &k, &[x]);
            let (gr, gt) = (lookup(&t.r0, x as f32), lookup(&t.t, x as f32));
            for c in 0..3 {
                assert!((gr[c] as f64 - r[0][c]).abs() < 2e-3, "R0 at {x} mm: {gr:?} vs {:?}", r[0]);
                assert!((gt[c] as f64 - tr[0][c]).abs() < 2e-3, "T at {x} mm: {gt:?} vs {:?}", tr[0]);
            }
        }
        assert_eq!(lookup(&t.t, f32::INFINITY), [0.0; 3]);
        assert_eq!(lookup(&t.t, -1.0), [1.0; 3]);
    }

    #[test]
    fn wgsl_constants_match_the_rust_ones() {
        let text = wgsl_constants();
        assert!(text.contains("const TABLE_X0_MM: f32 = 0.02;"), "{text}");
        assert!(text.contains("const TABLE_ENTRIES: u32 = 64u;"), "{text}");
    }
}
