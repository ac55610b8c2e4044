//! The specular lobe every surface of Rouge reflects with, in double precision: the
//! Kelemen/Szirmay-Kalos BRDF (\[Huang2013\] eq. 5, \[Kelemen2001\]) with a Beckmann
//! distribution \[Beckmann1963\] and Schlick's Fresnel \[Schlick1994\]. The preset's
//! [`crate::preset::Specular`] holds its parameters; the renderer's lighting pass
//! (render/src/shaders/lighting.wgsl) evaluates the same lobe in WGSL and rouge-render's
//! `specular` module layers it; [`crate::finish`] integrates it over a gloss meter's aperture.
//!
//! **The lobe.** Kelemen and Szirmay-Kalos replace the Cook-Torrance geometry and
//! foreshortening terms G/(4 (n·l)(n·v)) by 1/(4 (h·l)²). With h = (l + v)/|l + v|,
//! (h·l)² = (1 + l·v)/2, so 4 (h·l)² = 2 (1 + l·v) and
//!   f_r(l, v) = D(h) F(h·l) / (2 (1 + l·v)),
//! where D is the Beckmann distribution normalised so that ∫ D(h) (n·h) dω_h = 1:
//!   D(h) = exp(−tan²θ_h / m²) / (π m² cos⁴θ_h),  tan²θ_h = (1 − cos²θ_h)/cos²θ_h.
//! Domain: m in (0, 1] (preset schema), unit n, l, v. The lobe is 0 when l = −v (h undefined)
//! and when n·h ≤ 0. As m → 0 its directional albedo tends to F(θ): a mirror of Schlick's
//! reflectance, which is what a gloss meter's standard is.

use glam::DVec3;

/// Schlick's normal-incidence reflectance F0 = ((n − 1)/(n + 1))² of a dielectric of index
/// `ior` in air.
pub fn fresnel_f0(ior: f64) -> f64 {
    let r = (ior - 1.0) / (ior + 1.0);
    r * r
}

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

/// ∫ f(l) (n·l) dω_l over the hemisphere around n = +Z, by the midpoint rule on `cells` × `cells`
/// cells of (θ, φ): the directional albedo of a BRDF `f` of the light direction (tests and
/// studies; 400-600 cells resolve lobes down to roughness ~0.05).
pub fn hemisphere_integral(f: impl Fn(DVec3) -> f64, cells: usize) -> f64 {
    use std::f64::consts::PI;
    let (dt, dp) = (0.5 * PI / cells as f64, 2.0 * PI / cells as f64);
    let mut sum = 0.0;
    for i in 0..cells {
        let theta = (i as f64 + 0.5) * dt;
        let w = theta.sin() * theta.cos() * dt * dp;
        for j in 0..cells {
            let phi = (j as f64 + 0.5) * dp;
            sum += f(DVec3::new(theta.sin() * phi.cos(), theta.sin() * phi.sin(), theta.cos())) * w;
        }
    }
    sum
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::f64::consts::PI;

    fn dir(theta: f64, phi: f64) -> DVec3 {
        DVec3::new(theta.sin() * phi.cos(), theta.sin() * phi.sin(), theta.cos())
    }

    fn directional_albedo(v: DVec3, m: f64, f0: f64) -> f64 {
        hemisphere_integral(|l| kelemen(DVec3::Z, l, v, m, f0), 600)
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
