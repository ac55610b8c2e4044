//! Batch correction: the amounts of a standard's colorants that bring a production batch back
//! to the standard, from the batch's measured reflectance.
//!
//! # Method (after \[Allen1980\], "correction of production batches", and \[Kuehni1975\])
//!
//! The batch was made to a recipe `c_b` (usually the standard's `c_s`) but does not look like the
//! standard: its colorants are stronger or weaker than the library says, the dispersion differs.
//! The model predicts the batch as `R_pred(c_b)` (Duncan's rule, then R∞ or the layer over its
//! background); the measured `R_batch` differs from it by the model's error, which is assumed to
//! be the same for nearby recipes and carried as a correction:
//!
//! * opaque layers, in the Kubelka-Munk function `f(R) = (1 − R)²/(2R) = K/S` (linear in the
//!   concentrations by Duncan's rule, where Allen applies it):
//!   `f̂(c) = f(R_pred(c)) + [f(R_batch) − f(R_pred(c_b))]`;
//! * layers over a background, in reflectance: `R̂(c) = R_pred(c) + [R_batch − R_pred(c_b)]`.
//!
//! Then the recipe is corrected by Gauss-Newton steps on CIELAB, `Δc = J⁺ (Lab_std − Lab(R̂(c)))`
//! with `J = ∂Lab(R̂)/∂c` by central differences and `J⁺` its pseudo-inverse (nalgebra SVD: the
//! smallest change when there are more colorants than the three colour coordinates),
//! concentrations held ≥ 0, until the predicted CIEDE2000 stops falling. The batch made to the
//! corrected recipe is measured again and corrected again: each round removes most of what is
//! left, since the error carried is that of the last batch. `measure/tests/analysis.rs`: batches
//! whose colorants are ±10 % off in strength come within 0.1 ΔE2000 of the standard in 2 rounds.

use super::mixing::duncan_mix;
use super::{AnalysisError, Layer, check_reflectance, check_thickness, invalid, lab_of};
use crate::colorimetry::{Colorimeter, delta_e_2000_raw};
use crate::km;
use crate::spectrum::{Spectrum, WORKING_LEN};
use nalgebra::{DMatrix, DVector};

/// How the product is seen.
#[derive(Clone, Debug, PartialEq)]
pub enum Presentation {
    /// An opaque layer (R∞).
    Opaque,
    /// A layer of `thickness_mm` over an opaque background of reflectance `background`.
    Over {
        /// The background (skin, a card).
        background: Box<Spectrum>,
        /// Film thickness, mm.
        thickness_mm: f64,
    },
}

impl Presentation {
    /// The reflectance of `layer` seen this way.
    pub fn reflectance(&self, layer: &Layer) -> Spectrum {
        match self {
            Presentation::Opaque => layer.r_inf(),
            Presentation::Over { background, thickness_mm } => layer.reflectance_over(*thickness_mm, background),
        }
    }
}

/// The Kubelka-Munk function `f(R) = (1 − R)²/(2R)` (K/S of an opaque layer, \[Kubelka1948\]),
/// with R held at 1e-9 from 0.
fn km_function(r: f64) -> f64 {
    let r = r.max(1e-9);
    (1.0 - r) * (1.0 - r) / (2.0 * r)
}

/// The reflectance of an opaque layer with K/S = `f`: `R∞ = 1 + f − √(f² + 2f)`, as
/// [`km::r_inf_from_s_k`] with S = 1, K = f (negative f, from a correction, held at 0).
fn from_km_function(f: f64) -> f64 {
    km::r_inf_from_s_k(1.0, f.max(0.0))
}

/// A corrected recipe.
#[derive(Clone, Debug, PartialEq)]
pub struct Correction {
    /// The corrected concentrations, one per colorant.
    pub concentrations: Vec<f64>,
    /// Corrected minus batch recipe.
    pub change: Vec<f64>,
    /// CIEDE2000 of the batch as measured against the standard.
    pub delta_e_before: f64,
    /// CIEDE2000 predicted for the corrected batch (with the batch's model error carried).
    pub delta_e_predicted: f64,
    /// CIELAB of the standard.
    pub standard_lab: [f64; 3],
    /// CIELAB of the batch as measured.
    pub batch_lab: [f64; 3],
    /// Gauss-Newton steps taken.
    pub steps: usize,
}

fn check_recipe(what: &str, colorants: &[Layer], c: &[f64]) -> Result<(), AnalysisError> {
    if c.len() != colorants.len() {
        return Err(invalid(format!("{what}: {} amounts for {} colorants", c.len(), colorants.len())));
    }
    if let Some((i, v)) = c.iter().enumerate().find(|(_, v)| !(**v >= 0.0 && v.is_finite())) {
        return Err(invalid(format!("{what}: the amount of `{}` is {v}: must be finite and ≥ 0", colorants[i].name)));
    }
    Ok(())
}

/// Corrects the recipe `batch_recipe` of a batch measured as `batch` so that it matches
/// `standard` (a measured reflectance) under `colorimeter`'s viewing (module documentation).
///
/// Errors: no colorants, amounts not one per colorant or negative, reflectances outside [0, 1]
/// (named with the wavelength), a negative thickness.
///
/// # Examples
///
/// A two-colorant batch made with a white 10 % weaker than the library says: the correction
/// adds white, and the predicted difference falls from about 1 to near 0.
///
/// ```
/// use rouge_measure::analysis::correction::{Presentation, correct_batch};
/// use rouge_measure::analysis::{Layer, mixing::duncan_mix};
/// use rouge_measure::{Colorimeter, Spectrum, Viewing};
///
/// let white = Layer::new("white", Spectrum::constant(40.0), Spectrum::constant(0.4))?;
/// let red = Layer::new("red", Spectrum::from_fn(|_| 5.0), Spectrum::from_fn(|nm| if nm < 590.0 { 20.0 } else { 0.5 }))?;
/// let lib = [white.clone(), red.clone()];
/// let weak = [Layer::new("white", Spectrum::constant(36.0), Spectrum::constant(0.36))?, red];
/// let recipe = [0.6, 0.4];
/// let c = Colorimeter::get(Viewing::D65_1931);
/// let standard = duncan_mix("std", &lib, &recipe)?.r_inf();
/// let batch = duncan_mix("batch", &weak, &recipe)?.r_inf();
/// let fix = correct_batch(&lib, &recipe, &batch, &standard, &Presentation::Opaque, c)?;
/// assert!(fix.change[0] > 0.0 && fix.delta_e_predicted < 0.01 && fix.delta_e_before > 0.5, "{fix:?}");
/// # Ok::<(), rouge_measure::analysis::AnalysisError>(())
/// ```
pub fn correct_batch(
    colorants: &[Layer],
    batch_recipe: &[f64],
    batch: &Spectrum,
    standard: &Spectrum,
    presentation: &Presentation,
    colorimeter: &Colorimeter,
) -> Result<Correction, AnalysisError> {
    if colorants.is_empty() {
        return Err(invalid("no colorants: give the colorants of the recipe"));
    }
    check_recipe("the batch recipe", colorants, batch_recipe)?;
    check_reflectance("the batch", batch)?;
    check_reflectance("the standard", standard)?;
    if let Presentation::Over { background, thickness_mm } = presentation {
        check_reflectance("the background", background)?;
        check_thickness("the thickness", *thickness_mm)?;
    }
    let predict = |c: &[f64]| -> Result<Spectrum, AnalysisError> {
        Ok(presentation.reflectance(&duncan_mix("recipe", colorants, c)?))
    };
    let at_batch = predict(batch_recipe)?;
    let opaque = matches!(presentation, Presentation::Opaque);
    let delta: [f64; WORKING_LEN] = std::array::from_fn(|i| {
        if opaque { km_function(batch.0[i]) - km_function(at_batch.0[i]) } else { batch.0[i] - at_batch.0[i] }
    });
    let corrected = |c: &[f64]| -> Result<[f64; 3], AnalysisError> {
        let r = predict(c)?;
        let fixed = Spectrum(std::array::from_fn(|i| {
            if opaque { from_km_function(km_function(r.0[i]) + delta[i]) } else { (r.0[i] + delta[i]).clamp(0.0, 1.0) }
        }));
        Ok(lab_of(colorimeter, &fixed))
    };
    let standard_lab = lab_of(colorimeter, standard);
    let batch_lab = lab_of(colorimeter, batch);
    let n = colorants.len();
    let mut c = batch_recipe.to_vec();
    let mut lab = corrected(&c)?;
    let mut de = delta_e_2000_raw(lab, standard_lab);
    let mut steps = 0;
    let scale = c.iter().sum::<f64>().max(1e-3);
    for _ in 0..30 {
        if de < 1e-9 {
            break;
        }
        let h = 1e-6 * scale;
        let mut j = DMatrix::<f64>::zeros(3, n);
        for col in 0..n {
            let (mut up, mut down) = (c.clone(), c.clone());
            up[col] += h;
            down[col] = (down[col] - h).max(0.0);
            let (lu, ld) = (corrected(&up)?, corrected(&down)?);
            for row in 0..3 {
                j[(row, col)] = (lu[row] - ld[row]) / (up[col] - down[col]);
            }
        }
        let residual = DVector::from_fn(3, |i, _| standard_lab[i] - lab[i]);
        // Singular values below 1e-6 of the largest are directions the colour cannot see (for an
        // opaque layer, scaling every amount at once): no step along them.
        let svd = j.svd(true, true);
        let threshold = 1e-6 * svd.singular_values.max();
        let Ok(step) = svd.solve(&residual, threshold) else { break };
        // Damped: halve the step until the predicted difference falls.
        let mut t = 1.0;
        let mut improved = false;
        while t > 1e-4 {
            let trial: Vec<f64> = c.iter().zip(step.iter()).map(|(ci, si)| (ci + t * si).max(0.0)).collect();
            let lab_t = corrected(&trial)?;
            let de_t = delta_e_2000_raw(lab_t, standard_lab);
            if de_t < de {
                (c, lab, de) = (trial, lab_t, de_t);
                improved = true;
                break;
            }
            t *= 0.5;
        }
        steps += 1;
        if !improved {
            break;
        }
    }
    Ok(Correction {
        change: c.iter().zip(batch_recipe).map(|(a, b)| a - b).collect(),
        concentrations: c,
        delta_e_before: delta_e_2000_raw(batch_lab, standard_lab),
        delta_e_predicted: de,
        standard_lab,
        batch_lab,
        steps,
    })
}
