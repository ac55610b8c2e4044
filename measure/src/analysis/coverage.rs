//! How much a layer covers: the contrast ratio of paint standards against thickness, the hiding
//! thickness, and the colour difference a layer makes on a given skin.
//!
//! **Contrast ratio** (\[ISO6504-3\], \[ASTMD2805\]): `CR = Y_b / Y_w`, the luminance factor Y of the
//! film over the black part of a contrast chart divided by Y over the white part, both computed
//! here from the spectral KM reflectance over flat backgrounds of reflectance `Rb`, `Rw`
//! (parameters; ISO 6504-3's chart has Y_w = 80 ± 2 and a black of a few percent at most).
//! CR = Rb/Rw with no film, rises with thickness, and is 1 for an opaque film. **Hiding
//! thickness**: where CR reaches 0.98 (ISO 6504-3's "complete hiding"). A film with no
//! scattering never reaches it: over black it stays black at any finite thickness, so the
//! ratio stays 0 even though it darkens everything beneath it.

use super::{AnalysisError, Layer, check_reflectance, check_thickness, invalid, lab_of};
use crate::colorimetry::{Colorimeter, delta_e_2000_raw};
use crate::spectrum::Spectrum;

/// The contrast ratio at which a film counts as hiding (\[ISO6504-3\]).
pub const HIDING_CONTRAST_RATIO: f64 = 0.98;

/// A contrast chart: spectrally flat black and white backgrounds (reflectances, 0-1).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ContrastChart {
    /// Reflectance of the black part.
    pub black: f64,
    /// Reflectance of the white part.
    pub white: f64,
}

impl Default for ContrastChart {
    /// White 0.80 (ISO 6504-3's Y_w = 80), black 0.01 (a good black; the standard allows a few
    /// percent).
    fn default() -> Self {
        ContrastChart { black: 0.01, white: 0.80 }
    }
}

impl ContrastChart {
    /// A chart with `0 ≤ black < white ≤ 1`.
    pub fn new(black: f64, white: f64) -> Result<Self, AnalysisError> {
        if (0.0..=1.0).contains(&black) && (0.0..=1.0).contains(&white) && black < white {
            Ok(ContrastChart { black, white })
        } else {
            Err(invalid(format!(
                "contrast chart black = {black}, white = {white}: both must lie in [0, 1] and black below white"
            )))
        }
    }
}

/// Y over black and over white and their ratio at one thickness.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Contrast {
    /// Y of the film over the black background (white = 100).
    pub y_black: f64,
    /// Y of the film over the white background.
    pub y_white: f64,
    /// `y_black / y_white`; 1 when both are 0 (a black opaque film: nothing shows through).
    pub contrast_ratio: f64,
}

/// The contrast of `layer` at `thickness_mm` (∞ allowed) on `chart` under the colorimeter's
/// viewing (Y by summation, \[CIE15\] §7.1).
pub fn contrast(
    layer: &Layer,
    thickness_mm: f64,
    chart: ContrastChart,
    colorimeter: &Colorimeter,
) -> Result<Contrast, AnalysisError> {
    check_thickness("thickness", thickness_mm)?;
    let y = |bg: f64| colorimeter.xyz(&layer.reflectance_over(thickness_mm, &Spectrum::constant(bg))).xyz[1];
    let (y_black, y_white) = (y(chart.black), y(chart.white));
    let contrast_ratio = if y_white > 0.0 { (y_black / y_white).min(1.0) } else { 1.0 };
    Ok(Contrast { y_black, y_white, contrast_ratio })
}

/// The thinnest film whose contrast ratio reaches `target` (use [`HIDING_CONTRAST_RATIO`]), in
/// mm, or `None` if none up to 1 m does (no scattering, or a target of 1, which only an infinitely
/// thick film reaches) or Y over white underflows to 0 first (0/0). The first crossing on a log grid from 10 nm to 1 m (30 points a
/// decade), then bisection of that bracket to 1e-12 relative, so a ratio that were not monotone
/// would still give its first crossing to the grid's resolution.
pub fn hiding_thickness_mm(
    layer: &Layer,
    chart: ContrastChart,
    colorimeter: &Colorimeter,
    target: f64,
) -> Result<Option<f64>, AnalysisError> {
    if !(target > 0.0 && target <= 1.0) {
        return Err(invalid(format!("contrast ratio target {target} must lie in (0, 1]")));
    }
    // A film so absorbing that Y over white underflows to 0 has hidden nothing it could show:
    // its ratio is 0/0, counted as not reaching the target (a film without scattering).
    let cr = |x: f64| {
        contrast(layer, x, chart, colorimeter).map(|c| if c.y_white > 0.0 { c.contrast_ratio } else { f64::NAN })
    };
    if cr(0.0)? >= target {
        return Ok(Some(0.0));
    }
    let (lo_exp, hi_exp, per_decade) = (-5.0, 3.0, 30.0);
    let n = ((hi_exp - lo_exp) * per_decade) as i32;
    let mut prev = 0.0;
    for i in 0..=n {
        let x = 10f64.powf(lo_exp + f64::from(i) / per_decade);
        let v = cr(x)?;
        if v.is_nan() {
            return Ok(None);
        }
        if v >= target {
            let (mut lo, mut hi) = (prev, x);
            while hi - lo > 1e-12 * hi {
                let mid = 0.5 * (lo + hi);
                if cr(mid)? >= target { hi = mid } else { lo = mid }
            }
            return Ok(Some(hi));
        }
        prev = x;
    }
    Ok(None)
}

/// One row of a coverage table.
#[derive(Clone, Debug, PartialEq)]
pub struct CoverageRow {
    /// Film thickness, mm.
    pub thickness_mm: f64,
    /// Contrast on the chart.
    pub contrast: Contrast,
    /// CIELAB of the film over each skin.
    pub lab_on_skin: Vec<[f64; 3]>,
    /// CIEDE2000 between each bare skin and the same skin under the film.
    pub delta_e_on_skin: Vec<f64>,
}

/// The coverage table of `layer`: contrast and, for each skin (opaque background reflectance),
/// the colour under the film and its CIEDE2000 from the bare skin, at each thickness.
pub fn coverage_table(
    layer: &Layer,
    thicknesses_mm: &[f64],
    chart: ContrastChart,
    skins: &[(String, Spectrum)],
    colorimeter: &Colorimeter,
) -> Result<Vec<CoverageRow>, AnalysisError> {
    for (name, r) in skins {
        check_reflectance(&format!("skin `{name}`"), r)?;
    }
    let bare: Vec<[f64; 3]> = skins.iter().map(|(_, r)| lab_of(colorimeter, r)).collect();
    thicknesses_mm
        .iter()
        .map(|&x| {
            let contrast = contrast(layer, x, chart, colorimeter)?;
            let lab_on_skin: Vec<[f64; 3]> =
                skins.iter().map(|(_, r)| lab_of(colorimeter, &layer.reflectance_over(x, r))).collect();
            let delta_e_on_skin = lab_on_skin.iter().zip(&bare).map(|(a, b)| delta_e_2000_raw(*b, *a)).collect();
            Ok(CoverageRow { thickness_mm: x, contrast, lab_on_skin, delta_e_on_skin })
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::analysis::grey_layer as layer;
    use crate::colorimetry::Viewing;

    #[test]
    fn contrast_limits_and_edges() {
        let c = Colorimeter::get(Viewing::D65_1931);
        let chart = ContrastChart::default();
        let l = layer(100.0, 5.0);
        let bare = contrast(&l, 0.0, chart, c).unwrap();
        assert!((bare.contrast_ratio - chart.black / chart.white).abs() < 1e-12);
        assert_eq!(contrast(&l, f64::INFINITY, chart, c).unwrap().contrast_ratio, 1.0);
        // K = 0 (R∞ = 1): hides eventually; S = 0: never; a clear layer: never.
        assert!(hiding_thickness_mm(&layer(100.0, 0.0), chart, c, 0.98).unwrap().is_some());
        assert_eq!(hiding_thickness_mm(&layer(0.0, 10.0), chart, c, 0.98).unwrap(), None);
        assert_eq!(hiding_thickness_mm(&layer(0.0, 0.0), chart, c, 0.98).unwrap(), None);
        assert_eq!(contrast(&layer(0.0, 10.0), f64::INFINITY, chart, c).unwrap().contrast_ratio, 1.0);
        assert!(contrast(&l, -1.0, chart, c).is_err());
        assert!(contrast(&l, f64::NAN, chart, c).is_err());
        assert!(ContrastChart::new(0.9, 0.8).is_err());
        assert!(hiding_thickness_mm(&l, chart, c, 1.5).is_err());
    }
}
