//! A screen-space kernel from a physical medium: the medium's diffusion profile (any
//! [`ProfileModel`]) fitted by a sum of Gaussians, the form the separable kernel of
//! [`crate::sss`] integrates exactly. This is \[dEon2007\]'s method (they fitted the multipole):
//! Gaussians of fixed variances in a geometric series spanning the profile's scales, and
//! non-negative weights per channel by least squares on the radial energy density 2πr·R(r).
//! The weights are then divided by the profile's total, so the fitted profile integrates to 1
//! and the skin albedo carries the total diffuse reflectance, as the renderer expects.

// RGB channels are indexed by number.
#![allow(clippy::needless_range_loop)]

use crate::diffusion::{ChannelProfile, ProfileModel, medium_profiles};
use crate::sss::{DiffusionProfile, Gaussian};
use rouge_model::medium::Medium;
use std::f64::consts::PI;

/// Gaussians in a fit.
pub const FIT_GAUSSIANS: usize = 16;

/// A medium's profile as the screen-space kernel needs it.
#[derive(Clone, Debug, PartialEq)]
pub struct FittedProfile {
    /// The model the profile comes from.
    pub model: ProfileModel,
    /// The sum of Gaussians, normalised to 1 per channel.
    pub profile: DiffusionProfile,
    /// Total diffuse reflectance per channel (the skin albedo to use with the profile).
    pub total: [f64; 3],
    /// Relative L2 error of the fit on 2πr·R(r) per channel.
    pub fit_error: [f64; 3],
}

/// Non-negative least squares by cyclic coordinate descent on the normal equations
/// `M w = b` (M symmetric positive semi-definite): each weight in turn is set to its exact
/// minimiser given the others, clamped at 0. Convex, so it converges; `sweeps` bounds the work.
fn nnls(m: &[Vec<f64>], b: &[f64], sweeps: usize) -> Vec<f64> {
    let n = b.len();
    let mut w = vec![0.0; n];
    for _ in 0..sweeps {
        let mut change = 0.0f64;
        for i in 0..n {
            if m[i][i] <= 0.0 {
                continue;
            }
            let mw: f64 = (0..n).map(|j| m[i][j] * w[j]).sum();
            let next = (w[i] + (b[i] - mw) / m[i][i]).max(0.0);
            change = change.max((next - w[i]).abs());
            w[i] = next;
        }
        if change < 1e-15 {
            break;
        }
    }
    w
}

impl FittedProfile {
    /// Fits `model`'s profile of `medium`.
    pub fn of_medium(medium: &Medium, model: ProfileModel) -> FittedProfile {
        Self::fit(&medium_profiles(medium, model), model)
    }

    /// Fits three channel profiles of one model.
    pub fn fit(channels: &[ChannelProfile; 3], model: ProfileModel) -> FittedProfile {
        // Scales: the narrowest Gaussian resolves 3% of the shortest mean free path (Burley's profile
        // keeps its energy density finite at r = 0, which Gaussians can only approach), the
        // widest reaches the longest support.
        let sigma_min = 0.03 * channels.iter().map(ChannelProfile::mean_free_path_mm).fold(f64::INFINITY, f64::min);
        let sigma_max = channels.iter().map(ChannelProfile::support_mm).fold(0.0, f64::max).max(4.0 * sigma_min);
        let ratio = (sigma_max / sigma_min).powf(1.0 / (FIT_GAUSSIANS - 1) as f64);
        let variances: Vec<f64> = (0..FIT_GAUSSIANS).map(|k| (sigma_min * ratio.powi(k as i32)).powi(2)).collect();
        // Radii: geometric from sigma_min/20 to 3·sigma_max, midpoints with their widths.
        let samples = 400;
        let (r0, r1) = (0.05 * sigma_min, 3.0 * sigma_max);
        let step = (r1 / r0).powf(1.0 / samples as f64);
        let radii: Vec<(f64, f64)> = (0..samples)
            .map(|k| {
                let (a, b) = (r0 * step.powi(k), r0 * step.powi(k + 1));
                (0.5 * (a + b), b - a)
            })
            .collect();
        let basis = |v: f64, r: f64| 2.0 * PI * r * (-r * r / (2.0 * v)).exp() / (2.0 * PI * v);
        let mut weights = [[0.0; FIT_GAUSSIANS]; 3];
        let mut fit_error = [0.0; 3];
        let mut total = [0.0; 3];
        for c in 0..3 {
            let profile = &channels[c];
            total[c] = profile.total();
            let target: Vec<f64> = radii.iter().map(|&(r, _)| 2.0 * PI * r * profile.radial(r)).collect();
            let mut m = vec![vec![0.0; FIT_GAUSSIANS]; FIT_GAUSSIANS];
            let mut b = vec![0.0; FIT_GAUSSIANS];
            for (k, &(r, dr)) in radii.iter().enumerate() {
                let phi: Vec<f64> = variances.iter().map(|&v| basis(v, r)).collect();
                for i in 0..FIT_GAUSSIANS {
                    b[i] += dr * phi[i] * target[k];
                    for j in 0..FIT_GAUSSIANS {
                        m[i][j] += dr * phi[i] * phi[j];
                    }
                }
            }
            let w = nnls(&m, &b, 20_000);
            let (mut err, mut norm) = (0.0, 0.0);
            for (k, &(r, dr)) in radii.iter().enumerate() {
                let fit: f64 = variances.iter().zip(&w).map(|(&v, &wi)| wi * basis(v, r)).sum();
                err += dr * (fit - target[k]).powi(2);
                norm += dr * target[k].powi(2);
            }
            fit_error[c] = if norm > 0.0 { (err / norm).sqrt() } else { 0.0 };
            let sum: f64 = w.iter().sum();
            for i in 0..FIT_GAUSSIANS {
                weights[c][i] = if sum > 0.0 {
                    w[i] / sum
                } else if i == 0 {
                    1.0
                } else {
                    0.0
                };
            }
        }
        // Gaussians that carry under 1e-4 of every channel's energy only widen the kernel: drop
        // them and renormalise.
        let kept: Vec<usize> = (0..FIT_GAUSSIANS).filter(|&i| (0..3).any(|c| weights[c][i] > 1e-4)).collect();
        let sums: [f64; 3] = std::array::from_fn(|c| kept.iter().map(|&i| weights[c][i]).sum::<f64>());
        let gaussians = kept
            .iter()
            .map(|&i| Gaussian {
                variance_mm2: variances[i],
                weight: std::array::from_fn(|c| if sums[c] > 0.0 { weights[c][i] / sums[c] } else { 0.0 }),
            })
            .collect();
        FittedProfile { model, profile: DiffusionProfile { gaussians }, total, fit_error }
    }
}
