//! Mixing bases: Duncan's rule for the S and K of a mixture, and the concentrations of two to
//! four bases that reach a target colour.
//!
//! **Duncan's rule** (\[Duncan1940\]; the two-constant mixing law of colour matching,
//! \[Allen1980\]): a mixture of components at concentrations `c_i` has
//! `S = Σ c_i S_i` and `K = Σ c_i K_i` per wavelength. Valid while the components scatter
//! independently (no crowding: pigment volume fractions well below ~10-20 % for TiO2) and the
//! film stays homogeneous; with whole products as bases, `c_i` are the fractions of each in the
//! blend and sum to 1. The synthetic sample products were themselves made by this rule from
//! `data/pigments/pigment_library.csv` (`python/gen_samples.py`), which the tests use.

use super::optimize::simplex_search;
use super::{AnalysisError, Layer, check_reflectance, check_thickness, invalid, lab_of};
use crate::colorimetry::{Colorimeter, delta_e_2000_raw};
use crate::km::{self, KmCoefficients};
use crate::spectrum::{Spectrum, WORKING_LEN, working_wavelength_nm};

/// S and K of a mixture per wavelength by Duncan's rule, [`km::duncan_mix`] (`S = Σ c_i S_i`,
/// `K = Σ c_i K_i`, \[Duncan1940\]). One concentration per base, finite and ≥ 0; they need not sum
/// to 1 (a pigment library's coefficients are per unit volume fraction, the binder adding
/// nothing).
pub fn duncan_mix(name: &str, bases: &[Layer], concentrations: &[f64]) -> Result<Layer, AnalysisError> {
    if bases.is_empty() || bases.len() != concentrations.len() {
        return Err(invalid(format!(
            "{} concentrations for {} bases: give one concentration per base",
            concentrations.len(),
            bases.len()
        )));
    }
    let (mut s, mut k) = ([0.0; WORKING_LEN], [0.0; WORKING_LEN]);
    for w in 0..WORKING_LEN {
        let parts = bases
            .iter()
            .zip(concentrations)
            .map(|(b, &c)| (c, KmCoefficients { s_per_mm: b.s.0[w], k_per_mm: b.k.0[w] }));
        let mix = km::duncan_mix(parts).map_err(|error| AnalysisError::Km {
            what: format!("mixture `{name}`"),
            wavelength_nm: working_wavelength_nm(w),
            error,
        })?;
        (s[w], k[w]) = (mix.s_per_mm, mix.k_per_mm);
    }
    Layer::new(name, Spectrum(s), Spectrum(k))
}

/// The colour a mixture should reach.
#[derive(Clone, Debug, PartialEq)]
pub enum MixTarget {
    /// The colour of an opaque layer (R∞), CIELAB.
    RInf([f64; 3]),
    /// The colour of a skin covered by `thickness_mm` of the mixture, CIELAB.
    Covered {
        /// The skin's reflectance.
        skin: Box<Spectrum>,
        /// Film thickness, mm.
        thickness_mm: f64,
        /// The target colour.
        lab: [f64; 3],
    },
}

/// Concentrations found for a target.
#[derive(Clone, Debug, PartialEq)]
pub struct MixFit {
    /// One per base, ≥ 0, summing to 1.
    pub concentrations: Vec<f64>,
    /// CIEDE2000 between the mixture and the target.
    pub delta_e: f64,
    /// CIELAB of the mixture (R∞, or over the skin).
    pub lab: [f64; 3],
    /// The mixture's S and K.
    pub mixture: Layer,
}

/// The concentrations (≥ 0, summing to 1) of 2-4 `bases` that minimise the squared CIEDE2000
/// between the mixture and `target`: constrained least squares over the simplex by
/// [`simplex_search`] from the best point of a 1/20 lattice, to 1e-10 in concentration. When the
/// target lies outside what the bases can reach, the result is the closest reachable colour
/// (`delta_e` says how far). With more bases than the colour has dimensions the answer need
/// not be unique (metamers); the search returns one.
pub fn fit_mix(bases: &[Layer], target: &MixTarget, colorimeter: &Colorimeter) -> Result<MixFit, AnalysisError> {
    if !(2..=4).contains(&bases.len()) {
        return Err(invalid(format!("{} bases given: mixing takes 2 to 4", bases.len())));
    }
    let target_lab = match target {
        MixTarget::RInf(lab) => *lab,
        MixTarget::Covered { skin, thickness_mm, lab } => {
            check_reflectance("skin", skin)?;
            check_thickness("thickness", *thickness_mm)?;
            *lab
        }
    };
    if target_lab.iter().any(|v| !v.is_finite()) {
        return Err(invalid(format!("target colour {target_lab:?} is not finite")));
    }
    let lab_of_mix = |m: &Layer| match target {
        MixTarget::RInf(_) => lab_of(colorimeter, &m.r_inf()),
        MixTarget::Covered { skin, thickness_mm, .. } => lab_of(colorimeter, &m.reflectance_over(*thickness_mm, skin)),
    };
    let objective = |c: &[f64]| match duncan_mix("mixture", bases, c) {
        Ok(m) => delta_e_2000_raw(lab_of_mix(&m), target_lab).powi(2),
        Err(_) => f64::INFINITY,
    };
    let (concentrations, _) = simplex_search(objective, bases.len(), 20, 1e-10);
    let mixture = duncan_mix("mixture", bases, &concentrations)?;
    let lab = lab_of_mix(&mixture);
    Ok(MixFit { delta_e: delta_e_2000_raw(lab, target_lab), concentrations, lab, mixture })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::colorimetry::Viewing;

    fn base(name: &str, s: f64, k: impl Fn(f64) -> f64) -> Layer {
        Layer::new(name, Spectrum::constant(s), Spectrum::from_fn(k)).unwrap()
    }

    #[test]
    fn duncan_mix_sums_and_refuses_bad_concentrations() {
        let a = base("a", 10.0, |_| 1.0);
        let b = base("b", 30.0, |_| 3.0);
        let m = duncan_mix("m", &[a.clone(), b.clone()], &[0.25, 0.75]).unwrap();
        assert_eq!(m.s.0[0], 0.25 * 10.0 + 0.75 * 30.0);
        assert_eq!(m.k.0[40], 0.25 * 1.0 + 0.75 * 3.0);
        assert!(duncan_mix("m", &[a.clone(), b.clone()], &[0.5]).is_err());
        assert!(duncan_mix("m", &[a.clone(), b.clone()], &[0.5, -0.1]).is_err());
        assert!(duncan_mix("m", &[a.clone(), b], &[0.5, f64::NAN]).is_err());
        let c = Colorimeter::get(Viewing::D65_1931);
        assert!(fit_mix(&[a], &MixTarget::RInf([50.0, 0.0, 0.0]), c).is_err());
    }
}
