//! The CPU twin, in double precision, of the specular lobes of shaders/lighting.wgsl: one
//! Kelemen/Szirmay-Kalos lobe for the skin and one per cosmetic layer (\[Huang2013\] eq. 5,
//! \[Kelemen2001\]), with a Beckmann distribution \[Beckmann1963\] and Schlick's Fresnel
//! \[Schlick1994\]. Tests check it (energy, Fresnel at grazing angles, the order in which layers
//! attenuate the lobes below them), and render/tests/specular_gpu.rs checks the shader against it.
//!
//! **The lobe.** Kelemen and Szirmay-Kalos replace the Cook-Torrance geometry and
//! foreshortening terms G/(4 (n·l)(n·v)) by 1/(4 (h·l)²). With h = (l + v)/|l + v|,
//! (h·l)² = (1 + l·v)/2, so 4 (h·l)² = 2 (1 + l·v) and
//!   f_r(l, v) = D(h) F(h·l) / (2 (1 + l·v)),
//! where D is the Beckmann distribution normalised so that ∫ D(h) (n·h) dω_h = 1:
//!   D(h) = exp(−tan²θ_h / m²) / (π m² cos⁴θ_h),  tan²θ_h = (1 − cos²θ_h)/cos²θ_h.
//! Domain: m in (0, 1] (preset schema), unit n, l, v. The lobe is 0 when l = −v (h undefined)
//! and when n·h ≤ 0; the shader skips lights with n·l ≤ 0.
//!
//! **Layers.** Bottom to top: lobes = lobes · T_i² + coverage_i · f_r(layer i), starting from the
//! skin's lobe. Light reaching a lower interface crosses layer i twice (in and out), hence T²
//! where \[Huang2013\] writes T. A layer's own lobe fades in over its first
//! `LAYER_FULL_COVERAGE_MM` (the renderer's look upload), so a layer of zero thickness adds nothing.

use glam::DVec3;

/// Beckmann distribution of half vectors with RMS slope `m`, at cos θ_h = `n_dot_h`, normalised
/// so that ∫ D (n·h) dω = 1. `n_dot_h` is clamped below at 1e-3 (cos² at 1e-6), as in WGSL.
pub fn beckmann(n_dot_h: f64, m: f64) -> f64 {
    let c2 = (n_dot_h * n_dot_h).max(1e-6);
    let m2 = m * m;
    ((c2 - 1.0) / (m2 * c2)).exp() / (std::f64::consts::PI * m2 * c2 * c2)
}

/// Schlick's Fresnel reflectance at cos θ = `cos`, from the normal-incidence reflectance `f0`:
/// F = F0 + (1 − F0)(1 − cos)⁵; `cos` is clamped to [0, 1].
pub fn schlick(f0: f64, cos: f64) -> f64 {
    f0 + (1.0 - f0) * (1.0 - cos.clamp(0.0, 1.0)).powi(5)
}

/// The Kelemen/Szirmay-Kalos BRDF f_r(l, v) at normal `n` (unit vectors; see the module doc).
pub fn kelemen(n: DVec3, l: DVec3, v: DVec3, m: f64, f0: f64) -> f64 {
    let h_un = l + v;
    let len2 = h_un.length_squared();
    if len2 < 1e-8 {
        return 0.0;
    }
    let h = h_un / len2.sqrt();
    let n_dot_h = n.dot(h);
    if n_dot_h <= 0.0 {
        return 0.0;
    }
    beckmann(n_dot_h, m) * schlick(f0, h.dot(l)) / (2.0 * (1.0 + l.dot(v)))
}

/// One cosmetic layer's specular parameters at a point, as the lighting pass sees them.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LayerLobe {
    /// Beckmann roughness of the layer's surface.
    pub roughness: f64,
    /// Schlick F0 of the layer's surface.
    pub f0: f64,
    /// Thickness of the layer here, mm.
    pub thickness_mm: f64,
    /// Thickness at which the layer's lobe is fully formed, mm.
    pub full_coverage_mm: f64,
    /// The layer's transmittance here, linear RGB.
    pub t: [f64; 3],
}

/// The summed lobes of the skin (`skin` = roughness, F0) under `layers` (bottom to top), per
/// RGB channel, for light from `l` seen from `v` at normal `n`: what lighting.wgsl multiplies
/// by the irradiance E·(n·l).
pub fn layered_lobes(n: DVec3, l: DVec3, v: DVec3, skin: (f64, f64), layers: &[LayerLobe]) -> [f64; 3] {
    let mut lobes = [kelemen(n, l, v, skin.0, skin.1); 3];
    for layer in layers {
        let coverage = (layer.thickness_mm / layer.full_coverage_mm).clamp(0.0, 1.0);
        let own = coverage * kelemen(n, l, v, layer.roughness, layer.f0);
        for (c, lobe) in lobes.iter_mut().enumerate() {
            *lobe = *lobe * layer.t[c] * layer.t[c] + own;
        }
    }
    lobes
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::f64::consts::PI;

    fn dir(theta: f64, phi: f64) -> DVec3 {
        DVec3::new(theta.sin() * phi.cos(), theta.sin() * phi.sin(), theta.cos())
    }

    /// ∫ f_r(l, v) (n·l) dω_l over the hemisphere, midpoint rule in (θ, φ).
    fn directional_albedo(v: DVec3, m: f64, f0: f64) -> f64 {
        let (nt, np) = (600, 600);
        let (dt, dp) = (0.5 * PI / nt as f64, 2.0 * PI / np as f64);
        let mut sum = 0.0;
        for i in 0..nt {
            let theta = (i as f64 + 0.5) * dt;
            let w = theta.sin() * theta.cos() * dt * dp;
            for j in 0..np {
                let l = dir(theta, (j as f64 + 0.5) * dp);
                sum += kelemen(DVec3::Z, l, v, m, f0) * w;
            }
        }
        sum
    }

    #[test]
    fn beckmann_is_normalised() {
        // ∫ D(θ) cos θ sin θ dθ dφ = 1 over the hemisphere of half vectors.
        for m in [0.15, 0.35, 0.6, 1.0] {
            let n = 20_000;
            let dt = 0.5 * PI / n as f64;
            let integral: f64 = (0..n)
                .map(|i| {
                    let t = (i as f64 + 0.5) * dt;
                    beckmann(t.cos(), m) * t.cos() * t.sin() * dt * 2.0 * PI
                })
                .sum();
            assert!((integral - 1.0).abs() < 2e-3, "m = {m}: ∫ D cos = {integral}");
        }
    }

    #[test]
    fn the_lobe_never_reflects_more_than_it_receives() {
        for m in [0.05, 0.1, 0.2, 0.35, 0.55, 1.0] {
            for view_deg in [0.0, 30.0, 60.0, 80.0, 89.0] {
                let v = dir(f64::to_radians(view_deg), 0.0);
                let a = directional_albedo(v, m, 1.0);
                assert!(a <= 1.0 + 1e-3, "m {m}, view {view_deg}°: albedo {a} with F = 1");
                assert!(a > 0.0);
                if view_deg <= 60.0 {
                    let skin = directional_albedo(v, m, 0.028);
                    assert!(skin < 0.1, "m {m}, view {view_deg}°: skin albedo {skin}");
                }
            }
        }
    }

    #[test]
    fn fresnel_is_f0_at_normal_incidence_and_one_at_grazing() {
        for f0 in [0.0, 0.028, 0.04, 1.0] {
            assert_eq!(schlick(f0, 1.0), f0);
            assert_eq!(schlick(f0, 0.0), 1.0);
            assert_eq!(schlick(f0, -0.5), 1.0, "cos clamped at 0");
        }
        // Mirror configuration near grazing incidence: h = n, so h·l = cos θ and the lobe's
        // Fresnel factor is Schlick's at θ, which tends to 1.
        let theta = f64::to_radians(89.9);
        let (l, v) = (dir(theta, 0.0), dir(theta, PI));
        let f = kelemen(DVec3::Z, l, v, 0.3, 0.028) * 2.0 * (1.0 + l.dot(v)) / beckmann(1.0, 0.3);
        assert!((f - schlick(0.028, theta.cos())).abs() < 1e-9, "F in the lobe = {f}");
        assert!(schlick(0.028, f64::to_radians(89.999).cos()) > 0.9999);
    }

    #[test]
    fn layers_attenuate_the_lobes_below_them_twice() {
        let (n, l, v) = (DVec3::Z, dir(0.4, 0.0), dir(0.3, PI));
        let skin = kelemen(n, l, v, 0.35, 0.028);
        let layer = |thickness_mm, t| LayerLobe { roughness: 0.15, f0: 0.04, thickness_mm, full_coverage_mm: 0.002, t };
        // A zero-thickness layer with T = 1 changes nothing.
        assert_eq!(layered_lobes(n, l, v, (0.35, 0.028), &[layer(0.0, [1.0; 3])]), [skin; 3]);
        // T = 0.5 scales the skin's lobe by 0.25 (in and out) and adds the layer's own lobe.
        let top = kelemen(n, l, v, 0.15, 0.04);
        let got = layered_lobes(n, l, v, (0.35, 0.028), &[layer(0.01, [0.5, 0.5, 0.5])]);
        assert!((got[0] - (0.25 * skin + top)).abs() < 1e-12);
        // Order: the top layer's lobe is not attenuated; the lower one is, by the top's T².
        let lower = LayerLobe { roughness: 0.5, ..layer(0.01, [1.0; 3]) };
        let upper = layer(0.01, [0.5, 1.0, 0.0]);
        let got = layered_lobes(n, l, v, (0.35, 0.028), &[lower, upper]);
        let below = skin + kelemen(n, l, v, 0.5, 0.04);
        for (c, t) in [0.5, 1.0, 0.0].into_iter().enumerate() {
            assert!((got[c] - (below * t * t + top)).abs() < 1e-12, "channel {c}");
        }
        // Half coverage: a 1 µm film has half its lobe.
        let half = layered_lobes(n, l, v, (0.35, 0.028), &[layer(0.001, [1.0; 3])]);
        assert!((half[0] - (skin + 0.5 * top)).abs() < 1e-12);
    }

    #[test]
    fn no_nan_anywhere_in_the_domain() {
        let dirs = [DVec3::Z, -DVec3::Z, DVec3::X, dir(0.5 * PI - 1e-4, 0.3), dir(0.0001, 1.0), dir(2.0, 4.0)];
        for &l in &dirs {
            for &v in &dirs {
                for m in [1e-4, 0.01, 0.35, 1.0] {
                    let f = kelemen(DVec3::Z, l, v, m, 0.028);
                    assert!(f.is_finite() && f >= 0.0, "l {l} v {v} m {m}: {f}");
                }
            }
        }
        assert_eq!(kelemen(DVec3::Z, DVec3::X, -DVec3::X, 0.3, 0.04), 0.0, "l = −v");
    }
}
