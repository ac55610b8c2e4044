//! Inversion of the skin model: the parameters of a measured reflectance spectrum.
//!
//! **Method.** Bounded nonlinear least squares (Levenberg-Marquardt with Marquardt's diagonal
//! scaling, steps projected onto the parameters' physiological box, \[Marquardt1963\]) over six
//! free parameters (melanin, its pheomelanin share, blood, oxygen saturation, scattering at
//! 500 nm and its power; the epidermis' thickness is held at [`FitOptions::epidermis_thickness_mm`]).
//! The residuals are the spectral differences on the working grid inside the measured range,
//! weighted by [`SPECTRAL_WEIGHT`], and the CIELAB differences (D65, CIE 1931) weighted by
//! [`LAB_WEIGHT`], so the fit serves both a colour match and the spectrum's shape. The Jacobian is
//! by forward differences; the normal equations are solved by nalgebra's Cholesky (with an LU
//! fallback).
//!
//! **Starts.** A seed table of the model over a coarse grid of melanin, blood, saturation and
//! scattering (built once per [`SkinFitter`]) gives the [`SEEDS`] nearest spectra in CIELAB; the
//! solve runs from each in turn, nearest first, until one ends within [`GOOD_ENOUGH_DELTA_E`],
//! and keeps the best, so a dark skin does not start from a light one.
//!
//! **Never NaN.** A spectrum the model cannot explain (a tattoo, a paint chip) gets its best fit,
//! its ΔE2000 and RMS, and the parameters pinned at a bound are listed in [`SkinFit::at_bounds`].

use super::transport::specular_reflectance;
use super::{SkinError, SkinParams};
use crate::colorimetry::{Colorimeter, Lab, Viewing, delta_e_2000_raw};
use crate::spectrum::{Extrapolation, SampledSpectrum, Spectrum, WORKING_LEN, working_wavelength_nm};
use nalgebra::{DMatrix, DVector, Matrix6, Vector6};

/// Weight of a reflectance difference in the residuals (0.01 in reflectance counts as 0.1).
pub const SPECTRAL_WEIGHT: f64 = 10.0;
/// Weight of a CIELAB unit in the residuals.
pub const LAB_WEIGHT: f64 = 0.5;
/// Starts taken from the seed table.
pub const SEEDS: usize = 3;
/// A start ends when an accepted step lowers the cost by less than this fraction.
pub const RELATIVE_TOLERANCE: f64 = 1e-4;
/// Further starts are skipped once a fit is this close (ΔE2000) to the measurement.
pub const GOOD_ENOUGH_DELTA_E: f64 = 0.3;
/// Number of free parameters.
pub const FREE: usize = 6;

/// Whether the instrument's reflectance includes the surface's specular reflection: a d/8°
/// sphere in SCI mode (specular component included) or SCE (its light trap open).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum Specular {
    /// SCI: the model's total reflectance.
    #[default]
    Included,
    /// SCE: the total minus the smooth surface's Fresnel reflection.
    Excluded,
}

/// How to fit.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FitOptions {
    /// What the measurement includes of the surface's specular reflection.
    pub specular: Specular,
    /// The epidermis' thickness, held fixed, mm.
    pub epidermis_thickness_mm: f64,
    /// Hold the end values out to 380/780 nm when a spectrum does not cover them (the ΔE and the
    /// Lab residuals need the whole working grid; spectral residuals use measured wavelengths only).
    pub extrapolation: Extrapolation,
    /// Iteration cap per start.
    pub max_iterations: usize,
}

impl Default for FitOptions {
    fn default() -> Self {
        FitOptions {
            specular: Specular::Included,
            epidermis_thickness_mm: SkinParams::DEFAULT_EPIDERMIS_MM,
            extrapolation: Extrapolation::Refuse,
            max_iterations: 60,
        }
    }
}

/// The result of fitting one spectrum.
#[derive(Clone, Debug, PartialEq)]
pub struct SkinFit {
    /// The fitted parameters.
    pub params: SkinParams,
    /// The measured spectrum on the working grid.
    pub measured: Spectrum,
    /// The model's spectrum on the working grid.
    pub fitted: Spectrum,
    /// ΔE2000 between the two (D65, CIE 1931).
    pub delta_e_2000: f64,
    /// Spectral RMS difference over the measured wavelengths inside 380-780 nm.
    pub rms: f64,
    /// The measured range, nm (the working grid outside it holds extrapolated values).
    pub measured_range_nm: (f64, f64),
    /// CIELAB of the measured spectrum.
    pub lab_measured: [f64; 3],
    /// CIELAB of the fit.
    pub lab_fitted: [f64; 3],
    /// Parameters that ended on a bound of their range (the model wanted to go further).
    pub at_bounds: Vec<&'static str>,
    /// Model evaluations spent.
    pub evaluations: usize,
}

impl SkinFit {
    /// Individual Typology Angle of the measured skin, degrees ([`super::ita_deg`]).
    pub fn ita_deg(&self) -> f64 {
        super::ita_deg(&Lab { lab: self.lab_measured, viewing: Viewing::D65_1931 })
    }
}

/// Fits many spectra with one seed table.
#[derive(Debug)]
pub struct SkinFitter {
    options: FitOptions,
    seeds: Vec<(Vector6<f64>, [f64; 3])>,
}

/// The six free parameters as fractions of their ranges, and back.
fn to_unit(p: &SkinParams) -> Vector6<f64> {
    let a = p.to_array();
    Vector6::from_fn(|i, _| {
        (a[i] - SkinParams::RANGES[i].min) / (SkinParams::RANGES[i].max - SkinParams::RANGES[i].min)
    })
}

fn from_unit(u: &Vector6<f64>, thickness_mm: f64) -> SkinParams {
    let mut a = [thickness_mm; 7];
    for i in 0..FREE {
        let r = SkinParams::RANGES[i];
        a[i] = r.min + u[i].clamp(0.0, 1.0) * (r.max - r.min);
    }
    SkinParams::from_array(a)
}

/// The model on the working grid as the instrument reads it, with μs′d kept inside the table
/// (see [`SkinParams::validate`]).
fn model(u: &Vector6<f64>, options: &FitOptions) -> Result<[f64; WORKING_LEN], SkinError> {
    let r = from_unit(u, options.epidermis_thickness_mm).reflectance_on_grid_unchecked()?;
    Ok(match options.specular {
        Specular::Included => r,
        Specular::Excluded => r.map(|v| v - specular_reflectance()),
    })
}

fn lab_of(values: &[f64; WORKING_LEN]) -> [f64; 3] {
    lab_d65(&Spectrum(*values)).lab
}

/// Residuals: the spectral differences where `mask`, then the three Lab differences.
fn residuals(
    model: &[f64; WORKING_LEN],
    target: &[f64; WORKING_LEN],
    mask: &[bool; WORKING_LEN],
    target_lab: [f64; 3],
) -> DVector<f64> {
    let lab = lab_of(model);
    let spectral = (0..WORKING_LEN).filter(|&i| mask[i]).map(|i| SPECTRAL_WEIGHT * (model[i] - target[i]));
    DVector::from_iterator(
        mask.iter().filter(|m| **m).count() + 3,
        spectral.chain((0..3).map(|k| LAB_WEIGHT * (lab[k] - target_lab[k]))),
    )
}

impl SkinFitter {
    /// Builds the seed table (about 150 model spectra) for `options`.
    pub fn new(options: FitOptions) -> Result<Self, SkinError> {
        let probe = SkinParams { epidermis_thickness_mm: options.epidermis_thickness_mm, ..SkinParams::LIGHT };
        probe.validate()?;
        let mut seeds = vec![];
        for mel in [0.005, 0.02, 0.05, 0.1, 0.2, 0.35] {
            for blood in [0.005, 0.02, 0.05, 0.1] {
                for sat in [0.5, 0.9] {
                    for scatter in [1.5, 3.0, 6.0] {
                        let p = SkinParams {
                            melanin_fraction: mel,
                            blood_fraction: blood,
                            oxygen_saturation: sat,
                            scattering_500nm_per_mm: scatter,
                            ..probe
                        };
                        let u = to_unit(&p);
                        seeds.push((u, lab_of(&model(&u, &options)?)));
                    }
                }
            }
        }
        Ok(SkinFitter { options, seeds })
    }

    /// The options it fits with.
    pub fn options(&self) -> &FitOptions {
        &self.options
    }

    /// Fits one measured spectrum given on its own wavelengths (nm, increasing). Errors name the
    /// wavelength of a reflectance outside [0, 1] or not finite, and a grid the working grid
    /// cannot be made from.
    pub fn fit(&self, wavelengths_nm: &[f64], reflectance: &[f64]) -> Result<SkinFit, SkinError> {
        for (&w, &r) in wavelengths_nm.iter().zip(reflectance) {
            if !(0.0..=1.0).contains(&r) {
                return Err(SkinError::Measurement {
                    wavelength_nm: Some(w),
                    message: format!("reflectance {r} is outside [0, 1]"),
                });
            }
        }
        let sampled = SampledSpectrum::new(wavelengths_nm.to_vec(), reflectance.to_vec())
            .map_err(|e| SkinError::Measurement { wavelength_nm: None, message: e.to_string() })?;
        let measured = sampled
            .to_working_grid(self.options.extrapolation)
            .map_err(|e| SkinError::Measurement {
                wavelength_nm: None,
                message: format!("{e} (--extrapolate holds the end values)"),
            })?
            .spectrum;
        let target = measured.0.map(|v| v.clamp(0.0, 1.0));
        let (first, last) = (wavelengths_nm[0], wavelengths_nm[wavelengths_nm.len() - 1]);
        let mask: [bool; WORKING_LEN] = std::array::from_fn(|i| (first..=last).contains(&working_wavelength_nm(i)));
        let target_lab = lab_of(&target);
        let dist: Vec<f64> = self.seeds.iter().map(|(_, lab)| delta_e_2000_raw(*lab, target_lab)).collect();
        let mut order: Vec<usize> = (0..self.seeds.len()).collect();
        order.sort_by(|&a, &b| dist[a].total_cmp(&dist[b]));
        let mut best: Option<(f64, Vector6<f64>)> = None;
        let mut evaluations = 0;
        for &s in order.iter().take(SEEDS) {
            let (cost, u, lab, evals) = self.solve(self.seeds[s].0, &target, &mask, target_lab)?;
            evaluations += evals;
            if best.as_ref().is_none_or(|(c, _)| cost < *c) {
                best = Some((cost, u));
                if delta_e_2000_raw(lab, target_lab) < GOOD_ENOUGH_DELTA_E {
                    break;
                }
            }
        }
        let Some((_, u)) = best else {
            return Err(SkinError::Measurement { wavelength_nm: None, message: "no seed to start from".into() });
        };
        let t = self.options.epidermis_thickness_mm;
        let fitted = model(&u, &self.options)?;
        let lab_fitted = lab_of(&fitted);
        let n = mask.iter().filter(|m| **m).count().max(1);
        let rms = ((0..WORKING_LEN).filter(|&i| mask[i]).map(|i| (fitted[i] - target[i]).powi(2)).sum::<f64>()
            / n as f64)
            .sqrt();
        let at_bounds = (0..FREE)
            .filter(|&i| (u[i] <= 1e-6 && SkinParams::RANGES[i].min > 0.0) || u[i] >= 1.0 - 1e-6)
            .map(|i| SkinParams::RANGES[i].name)
            .collect();
        Ok(SkinFit {
            params: from_unit(&u, t),
            measured,
            fitted: Spectrum(fitted),
            delta_e_2000: delta_e_2000_raw(target_lab, lab_fitted),
            rms,
            measured_range_nm: (first, last),
            lab_measured: target_lab,
            lab_fitted,
            at_bounds,
            evaluations,
        })
    }

    /// Projected Levenberg-Marquardt from `u0`: (cost, parameters, the model's CIELAB there, model
    /// evaluations).
    fn solve(
        &self,
        u0: Vector6<f64>,
        target: &[f64; WORKING_LEN],
        mask: &[bool; WORKING_LEN],
        target_lab: [f64; 3],
    ) -> Result<(f64, Vector6<f64>, [f64; 3], usize), SkinError> {
        let eval = |u: &Vector6<f64>| -> Result<DVector<f64>, SkinError> {
            Ok(residuals(&model(u, &self.options)?, target, mask, target_lab))
        };
        let mut u = u0;
        let mut r = eval(&u)?;
        let mut cost = r.norm_squared();
        let mut lambda: f64 = 1e-3;
        let mut evaluations = 1;
        const H: f64 = 1e-6;
        for _ in 0..self.options.max_iterations {
            let mut jac = DMatrix::zeros(r.len(), FREE);
            for k in 0..FREE {
                // Step inward at the upper bound so the difference stays inside the box.
                let h = if u[k] + H > 1.0 { -H } else { H };
                let mut up = u;
                up[k] += h;
                let rk = eval(&up)?;
                jac.set_column(k, &((rk - &r) / h));
            }
            evaluations += FREE;
            let jtj: Matrix6<f64> = (jac.transpose() * &jac).fixed_view::<6, 6>(0, 0).into_owned();
            let jtr: Vector6<f64> = (jac.transpose() * &r).fixed_rows::<6>(0).into_owned();
            let mut improved = false;
            for _ in 0..12 {
                let mut a = jtj;
                for k in 0..FREE {
                    a[(k, k)] += lambda * jtj[(k, k)].max(1e-12);
                }
                let step = match a.cholesky() {
                    Some(c) => c.solve(&(-jtr)),
                    None => a.lu().solve(&(-jtr)).unwrap_or_else(Vector6::zeros),
                };
                let trial = (u + step).map(|v| v.clamp(0.0, 1.0));
                let rt = eval(&trial)?;
                evaluations += 1;
                let ct = rt.norm_squared();
                if ct.is_finite() && ct < cost {
                    let gain = cost - ct;
                    u = trial;
                    r = rt;
                    cost = ct;
                    lambda = f64::max(lambda / 3.0, 1e-9);
                    improved = gain > RELATIVE_TOLERANCE * cost.max(1e-12);
                    break;
                }
                lambda *= 4.0;
            }
            if !improved {
                break;
            }
        }
        // The last three residuals are LAB_WEIGHT·(Lab − target): the model's Lab without
        // evaluating it again.
        let n = r.len();
        let lab = std::array::from_fn(|k| target_lab[k] + r[n - 3 + k] / LAB_WEIGHT);
        Ok((cost, u, lab, evaluations))
    }
}

/// Fits one spectrum with default seeds (builds a [`SkinFitter`]; for many spectra make one and
/// call [`SkinFitter::fit`]).
pub fn fit_reflectance(wavelengths_nm: &[f64], reflectance: &[f64], options: FitOptions) -> Result<SkinFit, SkinError> {
    SkinFitter::new(options)?.fit(wavelengths_nm, reflectance)
}

/// The CIELAB of a working-grid spectrum under D65 / CIE 1931 (the fit's colour space).
pub fn lab_d65(spectrum: &Spectrum) -> Lab {
    let c = Colorimeter::get(Viewing::D65_1931);
    c.lab(&c.xyz(spectrum))
}
