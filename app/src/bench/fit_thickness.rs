//! `rouge bench translucency --fit-thickness`: the thickness translucency's parameters
//! (\[BarreBrisebois2011\]) fitted per medium and local-thickness source to the Mitsuba 3
//! references, by least squares on linear radiance over the compared pixels.
//!
//! The frame is linear in the scale s and the ambient a for a fixed distortion δ and power p:
//! `I(s, a) = I₀ + s·B₁ + a·B₂`, with I₀ the frame without the term (s = a = 0), B₁ the back
//! lobe at s = 1 and B₂ the ambient term at a = 1. So δ and p are searched on a grid, and for
//! each cell (s, a) ≥ 0 is the exact minimiser of ‖I₀ + s·B₁ + a·B₂ − R‖² over every scene of
//! the medium (2×2 normal equations, the constraint by checking the faces of the quadrant).

use anyhow::Result;
use rouge_model::medium::Medium;
use rouge_render::SubsurfaceModel;
use rouge_render::job::Prepared;
use rouge_render::local_thickness::{ThicknessSource, TranslucencyParams};
use rouge_render::sss::DiffusionProfile;
use rouge_render::translucency::ReferenceImage;
use rouge_render::translucency::compared_pixels;
use serde::Serialize;
use std::collections::BTreeMap;

/// One reference scene loaded and uploaded, as a configuration sees it.
pub struct Scene<'a> {
    /// The scene's name (its sidecar's).
    pub name: &'a str,
    /// Its medium.
    pub medium: &'a Medium,
    /// Rouge's frame of it.
    pub prepared: &'a mut Prepared,
    /// The reference.
    pub reference: &'a ReferenceImage,
}

/// Distortions δ searched.
pub const DISTORTIONS: [f32; 7] = [0.0, 0.1, 0.2, 0.35, 0.5, 0.75, 1.0];
/// Powers p searched.
pub const POWERS: [f32; 10] = [0.25, 0.5, 1.0, 1.5, 2.0, 3.0, 4.0, 6.0, 8.0, 12.0];
/// Largest scale the fit may choose: ten times three.js's default. Without a bound, a medium
/// whose baked thickness is nearly 0 everywhere (ketchup's σ_tr in green and blue) buys a few
/// pixels with scales in the tens of thousands, a preset no artist could use.
pub const MAX_SCALE: f64 = 100.0;

/// Sums of the normal equations of one grid cell over scenes: with r = R − I₀,
/// `[B₁·B₁ B₁·B₂; B₁·B₂ B₂·B₂] [s a]ᵀ = [B₁·r B₂·r]ᵀ`, and r·r for the residual.
#[derive(Clone, Copy, Debug, Default)]
struct NormalEquations {
    a11: f64,
    a12: f64,
    a22: f64,
    b1: f64,
    b2: f64,
    rr: f64,
    n: f64,
}

impl NormalEquations {
    fn add(
        &mut self,
        base: &[[f32; 3]],
        lobe: &[[f32; 3]],
        ambient: &[[f32; 3]],
        reference: &[[f32; 3]],
        mask: &[bool],
    ) {
        for i in (0..base.len()).filter(|&i| mask[i]) {
            for c in 0..3 {
                let i0 = f64::from(base[i][c]);
                let (x1, x2) = (f64::from(lobe[i][c]) - i0, f64::from(ambient[i][c]) - i0);
                let r = f64::from(reference[i][c]) - i0;
                self.a11 += x1 * x1;
                self.a12 += x1 * x2;
                self.a22 += x2 * x2;
                self.b1 += x1 * r;
                self.b2 += x2 * r;
                self.rr += r * r;
                self.n += 1.0;
            }
        }
    }

    /// Sum of squared residuals at (s, a).
    fn sse(&self, s: f64, a: f64) -> f64 {
        (self.rr - 2.0 * (s * self.b1 + a * self.b2) + s * s * self.a11 + 2.0 * s * a * self.a12 + a * a * self.a22)
            .max(0.0)
    }

    /// The minimiser over 0 ≤ s ≤ [`MAX_SCALE`], a ≥ 0 and its sum of squared residuals: the
    /// unconstrained solution when it lies in the box, else the best of the box's edges and
    /// corners (the objective is convex, so one of these is the constrained minimum).
    fn solve(&self) -> (f64, f64, f64) {
        let clamp_s = |s: f64| s.clamp(0.0, MAX_SCALE);
        // The best a ≥ 0 for a given s.
        let a_for = |s: f64| if self.a22 > 0.0 { ((self.b2 - s * self.a12) / self.a22).max(0.0) } else { 0.0 };
        let mut candidates = vec![(0.0, 0.0), (MAX_SCALE, 0.0), (0.0, a_for(0.0)), (MAX_SCALE, a_for(MAX_SCALE))];
        if self.a11 > 0.0 {
            candidates.push((clamp_s(self.b1 / self.a11), 0.0));
        }
        let det = self.a11 * self.a22 - self.a12 * self.a12;
        if det > 1e-12 * (self.a11 * self.a22).max(f64::MIN_POSITIVE) {
            let s = (self.b1 * self.a22 - self.b2 * self.a12) / det;
            let a = (self.a11 * self.b2 - self.a12 * self.b1) / det;
            if (0.0..=MAX_SCALE).contains(&s) && a >= 0.0 {
                candidates.push((s, a));
            }
        }
        candidates
            .into_iter()
            .map(|(s, a)| (s, a, self.sse(s, a)))
            .min_by(|x, y| x.2.total_cmp(&y.2))
            .unwrap_or((0.0, 0.0, self.rr))
    }
}

/// The fit of one medium and source.
#[derive(Debug, Serialize)]
pub struct Fitted {
    /// The medium.
    pub medium: String,
    /// `baked` or `shadow-map`.
    pub source: String,
    /// The fitted parameters.
    pub distortion: f32,
    /// Power.
    pub power: f32,
    /// Scale.
    pub scale: f64,
    /// Ambient.
    pub ambient: f64,
    /// RMSE of linear radiance over every compared pixel and channel of the medium's scenes.
    pub rmse: f64,
    /// RMSE without the term (s = a = 0).
    pub rmse_without: f64,
    /// The scenes fitted on.
    pub scenes: Vec<String>,
}

/// The accumulated fit: per (medium, source), the normal equations of every grid cell.
#[derive(Default)]
pub struct Fit {
    cells: BTreeMap<(String, String), (Vec<NormalEquations>, Vec<String>)>,
}

impl Fit {
    /// Renders `scene` over the grid for `source` (under the screen-space `kernel` of the
    /// scene's skin, if given) and adds it to the medium's equations.
    ///
    /// # Errors
    /// The renderer's errors.
    pub fn add_scene(
        &mut self,
        scene: &mut Scene<'_>,
        source: &ThicknessSource,
        kernel: Option<&DiffusionProfile>,
    ) -> Result<()> {
        // (Deformed scenes are for testing the sources, not for fitting: the caller leaves them out.)
        let medium = scene.medium.name.clone();
        // Under a kernel the frame is still linear in s and a (the blur is linear).
        let model = |distortion, power, scale, ambient| SubsurfaceModel::Thickness {
            params: TranslucencyParams { distortion, power, scale, ambient },
            source: source.clone(),
            kernel: kernel.cloned(),
        };
        scene.prepared.scene.skin.subsurface = model(0.0, 1.0, 0.0, 0.0);
        let (base, mask) = compared_pixels(scene.prepared, scene.reference)?;
        let entry = self
            .cells
            .entry((medium, TranslucencyParams::fit_key(source.name(), kernel.is_some())))
            .or_insert_with(|| (vec![NormalEquations::default(); DISTORTIONS.len() * POWERS.len()], Vec::new()));
        entry.1.push(scene.name.to_string());
        for (i, &distortion) in DISTORTIONS.iter().enumerate() {
            // The ambient term does not depend on δ or p: one frame per distortion suffices, but
            // it is cheap enough to keep the cell's three frames together.
            scene.prepared.scene.skin.subsurface = model(distortion, 1.0, 0.0, 1.0);
            let (ambient, _) = compared_pixels(scene.prepared, scene.reference)?;
            for (j, &power) in POWERS.iter().enumerate() {
                scene.prepared.scene.skin.subsurface = model(distortion, power, 1.0, 0.0);
                let (lobe, _) = compared_pixels(scene.prepared, scene.reference)?;
                entry.0[i * POWERS.len() + j].add(&base, &lobe, &ambient, &scene.reference.rgb, &mask);
            }
        }
        Ok(())
    }

    /// The best cell of every (medium, source).
    pub fn solve(&self) -> Vec<Fitted> {
        self.cells
            .iter()
            .map(|((medium, source), (cells, scenes))| {
                let (best, (scale, ambient, sse)) = cells
                    .iter()
                    .enumerate()
                    .map(|(k, e)| (k, e.solve()))
                    .min_by(|x, y| x.1.2.total_cmp(&y.1.2))
                    .unwrap_or((0, (0.0, 0.0, f64::NAN)));
                let n = cells[best].n.max(1.0);
                Fitted {
                    medium: medium.clone(),
                    source: source.clone(),
                    distortion: DISTORTIONS[best / POWERS.len()],
                    power: POWERS[best % POWERS.len()],
                    scale,
                    ambient,
                    rmse: (sse / n).sqrt(),
                    rmse_without: (cells[best].rr / n).sqrt(),
                    scenes: scenes.clone(),
                }
            })
            .collect()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_normal_equations_recover_a_known_mixture() {
        // R = I₀ + 2·B₁ + 0.5·B₂ exactly.
        let base = vec![[0.1, 0.2, 0.3], [0.0, 0.1, 0.0], [0.3, 0.3, 0.1]];
        let b1 = [[0.2, 0.0, 0.1], [0.3, 0.1, 0.0], [0.0, 0.05, 0.2]];
        let b2 = [[0.1, 0.1, 0.1], [0.0, 0.2, 0.3], [0.1, 0.0, 0.1]];
        let add = |k: f32, b: &[[f32; 3]; 3]| -> Vec<[f32; 3]> {
            base.iter().zip(b).map(|(x, y)| std::array::from_fn(|c| x[c] + k * y[c])).collect()
        };
        let (lobe, ambient) = (add(1.0, &b1), add(1.0, &b2));
        let reference: Vec<[f32; 3]> = base
            .iter()
            .zip(b1.iter().zip(&b2))
            .map(|(x, (p, q))| std::array::from_fn(|c| x[c] + 2.0 * p[c] + 0.5 * q[c]))
            .collect();
        let mut e = NormalEquations::default();
        e.add(&base, &lobe, &ambient, &reference, &[true; 3]);
        let (s, a, sse) = e.solve();
        assert!((s - 2.0).abs() < 1e-5 && (a - 0.5).abs() < 1e-5 && sse < 1e-9, "{s} {a} {sse}");
        // A reference darker than the frame without the term: the constraint holds s = a = 0.
        let dark: Vec<[f32; 3]> = base.iter().map(|x| x.map(|v| v * 0.5)).collect();
        let mut e = NormalEquations::default();
        e.add(&base, &lobe, &ambient, &dark, &[true; 3]);
        let (s, a, _) = e.solve();
        assert_eq!((s, a), (0.0, 0.0));
        // A reference that asks for more than the largest scale gets the largest scale.
        let bright: Vec<[f32; 3]> =
            base.iter().zip(&b1).map(|(x, p)| std::array::from_fn(|c| x[c] + 500.0 * p[c])).collect();
        let mut e = NormalEquations::default();
        e.add(&base, &lobe, &ambient, &bright, &[true; 3]);
        assert_eq!(e.solve().0, MAX_SCALE);
    }
}
