//! Shade matching: which preset, at which thickness, brings a skin closest to a target colour
//! (the bare skin itself for a "your shade" match, or any colour); and for a range of skins,
//! which shades of a product line cover them and where the gaps are.
//!
//! The criterion is CIEDE2000 (\[CIE142\]) between the covered skin (KM layer over the skin as an
//! opaque background, see the module [`super`]) and the target, under one viewing. For a
//! "your shade" match the thickness is the one the product is worn at (a range collapses to its
//! thinnest end: with the bare skin as the target, less product is always closer), so a shade
//! suits a skin when it stays invisible at the wear thickness.

use super::optimize::golden_section;
use super::{AnalysisError, Layer, check_reflectance, check_thickness, invalid, lab_of};
use crate::colorimetry::{Colorimeter, delta_e_2000_raw};
use crate::spectrum::Spectrum;

/// What the covered skin should look like.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Target {
    /// The bare skin itself ("your shade").
    BareSkin,
    /// A CIELAB colour under the analysis' viewing.
    Lab([f64; 3]),
}

/// The best thickness of one shade on one skin.
#[derive(Clone, Debug, PartialEq)]
pub struct ShadeFit {
    /// Index of the shade in the list given.
    pub shade: usize,
    /// Thickness, mm.
    pub thickness_mm: f64,
    /// CIEDE2000 from the target.
    pub delta_e: f64,
    /// CIELAB of the covered skin.
    pub lab: [f64; 3],
}

/// The thickness at which a film, worn over `skin`, comes closest to the colour `target_lab`
/// between `min_mm` and `max_mm`: CIEDE2000 on a grid of 64 thicknesses (denser near `min_mm`,
/// where colour changes fastest), then golden-section search around the best grid point.
/// Returns `(thickness_mm, ΔE2000, Lab)`.
pub fn closest_thickness(
    layer: &Layer,
    skin: &Spectrum,
    target_lab: [f64; 3],
    (min_mm, max_mm): (f64, f64),
    colorimeter: &Colorimeter,
) -> Result<(f64, f64, [f64; 3]), AnalysisError> {
    check_thickness("minimum thickness", min_mm)?;
    if !(max_mm >= min_mm && max_mm.is_finite()) {
        return Err(invalid(format!(
            "thickness range {min_mm}..{max_mm} mm: the maximum must be finite and ≥ the minimum"
        )));
    }
    let lab_at = |x: f64| lab_of(colorimeter, &layer.reflectance_over(x, skin));
    let de = |x: f64| delta_e_2000_raw(lab_at(x), target_lab);
    if max_mm == min_mm {
        return Ok((min_mm, de(min_mm), lab_at(min_mm)));
    }
    const N: usize = 64;
    let at = |i: usize| min_mm + (max_mm - min_mm) * (i as f64 / N as f64).powi(2);
    let (mut best_i, mut best) = (0, f64::INFINITY);
    for i in 0..=N {
        let v = de(at(i));
        if v < best {
            (best_i, best) = (i, v);
        }
    }
    let (lo, hi) = (at(best_i.saturating_sub(1)), at((best_i + 1).min(N)));
    let (x, v) = golden_section(de, lo, hi, 1e-12 * max_mm.max(1e-9));
    let (x, v) = if v <= best { (x, v) } else { (at(best_i), best) };
    Ok((x, v, lab_at(x)))
}

/// Every shade's best thickness in `range_mm` on `skin` for `target`, best first (ties keep the
/// order given).
pub fn match_shades(
    shades: &[Layer],
    skin: &Spectrum,
    target: Target,
    range_mm: (f64, f64),
    colorimeter: &Colorimeter,
) -> Result<Vec<ShadeFit>, AnalysisError> {
    if shades.is_empty() {
        return Err(invalid("no shades to match"));
    }
    check_reflectance("skin", skin)?;
    let target_lab = match target {
        Target::BareSkin => lab_of(colorimeter, skin),
        Target::Lab(lab) => lab,
    };
    if target_lab.iter().any(|v| !v.is_finite()) {
        return Err(invalid(format!("target colour {target_lab:?} is not finite")));
    }
    let mut fits = shades
        .iter()
        .enumerate()
        .map(|(shade, layer)| {
            let (thickness_mm, delta_e, lab) = closest_thickness(layer, skin, target_lab, range_mm, colorimeter)?;
            Ok(ShadeFit { shade, thickness_mm, delta_e, lab })
        })
        .collect::<Result<Vec<_>, AnalysisError>>()?;
    fits.sort_by(|a, b| a.delta_e.total_cmp(&b.delta_e));
    Ok(fits)
}

/// How a product line serves one skin.
#[derive(Clone, Debug, PartialEq)]
pub struct SkinCoverage {
    /// Index of the skin in the list given.
    pub skin: usize,
    /// CIELAB of the bare skin.
    pub skin_lab: [f64; 3],
    /// The best shade (thickness, ΔE2000 from the target).
    pub best: ShadeFit,
    /// Whether even the best shade is farther than the gap threshold from the target.
    pub gap: bool,
}

/// For each skin, the shade of `shades` that best matches `target` in `range_mm`, and whether
/// the skin falls in a gap of the line (best ΔE2000 above `gap_delta_e`).
pub fn product_line_coverage(
    shades: &[Layer],
    skins: &[(String, Spectrum)],
    target: Target,
    range_mm: (f64, f64),
    gap_delta_e: f64,
    colorimeter: &Colorimeter,
) -> Result<Vec<SkinCoverage>, AnalysisError> {
    if !(gap_delta_e >= 0.0 && gap_delta_e.is_finite()) {
        return Err(invalid(format!("gap threshold ΔE2000 = {gap_delta_e} must be finite and ≥ 0")));
    }
    skins
        .iter()
        .enumerate()
        .map(|(i, (name, r))| {
            check_reflectance(&format!("skin `{name}`"), r)?;
            let best = match_shades(shades, r, target, range_mm, colorimeter)?.swap_remove(0);
            Ok(SkinCoverage { skin: i, skin_lab: lab_of(colorimeter, r), gap: best.delta_e > gap_delta_e, best })
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::analysis::grey_layer as layer;
    use crate::colorimetry::Viewing;

    #[test]
    fn closest_thickness_recovers_a_thickness() {
        let c = Colorimeter::get(Viewing::D65_1931);
        let l = layer(80.0, 6.0);
        let skin = Spectrum::from_fn(|nm| 0.2 + 0.3 * (nm - 380.0) / 400.0);
        let target = lab_of(c, &l.reflectance_over(0.0137, &skin));
        let (x, de, _) = closest_thickness(&l, &skin, target, (0.0, 0.1), c).unwrap();
        assert!((x - 0.0137).abs() < 1e-7 && de < 1e-4, "{x} {de}");
        assert!(closest_thickness(&l, &skin, target, (0.02, 0.01), c).is_err());
    }

    #[test]
    fn bare_skin_target_prefers_the_thinnest_film_and_edges_are_errors() {
        let c = Colorimeter::get(Viewing::D65_1931);
        let skin = Spectrum::constant(0.3);
        let fits = match_shades(&[layer(80.0, 6.0)], &skin, Target::BareSkin, (0.0, 0.05), c).unwrap();
        assert_eq!(fits[0].thickness_mm, 0.0);
        assert_eq!(fits[0].delta_e, 0.0);
        assert!(match_shades(&[], &skin, Target::BareSkin, (0.0, 0.05), c).is_err());
        assert!(match_shades(&[layer(1.0, 1.0)], &Spectrum::constant(1.2), Target::BareSkin, (0.0, 0.05), c).is_err());
        let nan = Target::Lab([f64::NAN, 0.0, 0.0]);
        assert!(match_shades(&[layer(1.0, 1.0)], &skin, nan, (0.0, 0.05), c).is_err());
        assert!(product_line_coverage(&[layer(1.0, 1.0)], &[], Target::BareSkin, (0.0, 0.0), -1.0, c).is_err());
    }
}
