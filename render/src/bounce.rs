//! Light between surfaces: one bounce of the skin's own glow from one part of the mesh to another
//! that faces it (a finger's far side lit by the next finger's glow, the nose by the cheek). The
//! path tracer carries it; no subsurface model does, since each sees the mesh only as light
//! entering and leaving one body (docs/TRANSLUCENCY.md, "Light between surfaces";
//! docs/BENCHMARKS.md, "Light between surfaces, as a pass").
//!
//! **The estimate** (shaders/bounce.wgsl, run by render/src/passes/bounce.rs): the skin pixels the
//! camera sees are Lambertian sources of the radiance L_q the frame gave them (the lighting pass's
//! and the subsurface model's, through the cosmetic stack's T; before the screen-space blur, which
//! moves light but keeps its total), and each skin pixel p receives their irradiance with no
//! occlusion test
//!
//! ```text
//! E_p = Σ_q L_q · cos θ_p · cos θ_q · dA_q / |x_q − x_p|²,   cos θ_p, cos θ_q > 0, |x_q − x_p| > near
//! ```
//!
//! and sends back E_p · ρ_p · T_p / π (added before the blur, which spreads it as it spreads the
//! lights' light, and averages the samples' per-pixel noise), ρ_p its albedo (for a medium, its half-space reflectance
//! at normal incidence) and T_p the stack's transmittance where the light goes in. dA_q is the
//! pixel's area on the surface: a pixel's solid angle (z/ℓ)³/f² at distance ℓ and view depth z
//! (f the focal length in pixels), times ℓ², over its cosine toward the camera (held at
//! [`BounceSettings::least_view_cosine`] or more: silhouette pixels stand for no more surface).
//!
//! The sum runs over N screen samples around p, log-uniform in radius from half a pixel to
//! `reach` (in pixels at p's depth), each turned by a per-pixel angle: the density
//! 1/(2π r² ln(r₁/r₀)) per screen pixel cancels the 1/r² of the kernel, so each sample weighs
//! about the same. `near` is a distance in the world, not on screen: in a crease the facing wall
//! is a few pixels away on screen and centimetres in depth (starting at `near` on screen lost 8%
//! of the head's bounce against the full sum). The
//! facing parts are narrow on screen (a finger's side), so few samples find them and each pixel's
//! estimate is noisy: the irradiance is averaged over the 5×5 pixels around p that lie on its
//! surface (within `near` plus two pixels of its plane, normals within 60°) before it is sent
//! back, and is added before the blur. On the backlit hand (mean ΔE2000 against Mitsuba 3, the
//! kernel with the transmission gather): 2.17 without the bounce, 1.97 / 1.96 / 1.98 at 32 / 64 / 128 samples
//! (docs/BENCHMARKS.md "Light between surfaces, as a pass", which also has it unaveraged and
//! after the blur).
//!
//! **Domain.** One bounce, of the light the camera sees: faces the camera does not see glow too,
//! so the estimate is a lower bound of the path tracer's (on the backlit hand it is 7-12 of the
//! 17-30 ×10⁻³ missing at the fingers' far-side rims, docs/BENCHMARKS.md "The next try,
//! measured"); no occlusion between the two points; no surface (specular) light; points closer
//! than `near` are left to the subsurface model (whose kernel already carries light within a
//! millimetre or two). A convex body gets exactly nothing: no two of its points face each other.

use crate::error::{RenderError, Result};

/// The bounce's settings.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct BounceSettings {
    /// Screen samples per pixel: 1 to [`BounceSettings::MAX_SAMPLES`].
    pub samples: u32,
    /// The farthest source, mm from the receiving point (on screen, at its depth).
    pub reach_mm: f32,
    /// The nearest source, mm: nearer light is the subsurface model's.
    pub near_mm: f32,
    /// The least cosine toward the camera a source pixel's area is divided by.
    pub least_view_cosine: f32,
}

impl BounceSettings {
    /// The most samples a pixel takes.
    pub const MAX_SAMPLES: u32 = 256;

    /// Checks the settings.
    ///
    /// # Errors
    /// [`RenderError::Invalid`] naming the setting out of its range.
    pub fn check(&self) -> Result<()> {
        if !(1..=Self::MAX_SAMPLES).contains(&self.samples) {
            return Err(RenderError::Invalid(format!(
                "bounce samples {}: must be 1 to {}",
                self.samples,
                Self::MAX_SAMPLES
            )));
        }
        if !(self.near_mm.is_finite() && self.near_mm > 0.0) {
            return Err(RenderError::Invalid(format!("bounce near distance {} mm: must be > 0", self.near_mm)));
        }
        if !(self.reach_mm.is_finite() && self.reach_mm > self.near_mm) {
            return Err(RenderError::Invalid(format!(
                "bounce reach {} mm: must be finite and beyond the near distance ({} mm)",
                self.reach_mm, self.near_mm
            )));
        }
        if !(self.least_view_cosine > 0.0 && self.least_view_cosine <= 1.0) {
            return Err(RenderError::Invalid(format!(
                "bounce least view cosine {}: must be in (0, 1]",
                self.least_view_cosine
            )));
        }
        Ok(())
    }
}

impl Default for BounceSettings {
    fn default() -> Self {
        BounceSettings { samples: 64, reach_mm: 100.0, near_mm: 1.0, least_view_cosine: 0.1 }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn settings_out_of_range_are_refused_by_name() {
        assert!(BounceSettings::default().check().is_ok());
        let bad = [
            (BounceSettings { samples: 0, ..Default::default() }, "samples"),
            (BounceSettings { samples: 257, ..Default::default() }, "samples"),
            (BounceSettings { near_mm: 0.0, ..Default::default() }, "near"),
            (BounceSettings { near_mm: f32::NAN, ..Default::default() }, "near"),
            (BounceSettings { reach_mm: 1.0, ..Default::default() }, "reach"),
            (BounceSettings { reach_mm: f32::INFINITY, ..Default::default() }, "reach"),
            (BounceSettings { least_view_cosine: 0.0, ..Default::default() }, "cosine"),
            (BounceSettings { least_view_cosine: 1.5, ..Default::default() }, "cosine"),
        ];
        for (settings, word) in bad {
            let e = settings.check().expect_err("out of range").to_string();
            assert!(e.contains(word), "{e}");
        }
    }
}
