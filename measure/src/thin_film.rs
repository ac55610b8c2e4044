//! Thin-film interference of pearlescent (shimmer) pigments: platelets of mica coated with a film
//! of titanium dioxide, lying in a cosmetic's binder. Light reflected at the film's two faces
//! interferes, so the platelet's reflectance is coloured and its colour shifts with the angle:
//! the silver, gold, red, violet, blue and green "interference" pearls of eyeshadows are one
//! mica with TiO₂ films of increasing thickness (with this model at normal incidence: about 50,
//! 70, 90, 105, 125 and 145 nm; CIELAB hue of the reflectance 218°, 97°, 0°, 319°, 244°, 155°).
//!
//! **Model** (Airy's formula for one film between two half-spaces, \[BornWolf1999\] §1.6.4):
//! with Fresnel amplitude coefficients r₀₁ (binder → film) and r₁₂ (film → mica) for s and p
//! polarisation and the film's phase thickness δ = 2π n₁ d cos θ₁ / λ,
//!   r = (r₀₁ + r₁₂ e^{2iδ}) / (1 + r₀₁ r₁₂ e^{2iδ}),  R = |r|²,
//! unpolarised R = (R_s + R_p)/2. Angles follow Snell's law from the binder (θ₀, measured in
//! the binder: light from air at θ reaches the platelets at asin(sin θ / n_binder)); cosines are
//! complex past a critical angle, so nothing is NaN. The mica is taken as a half-space (its
//! back face, 0.3-0.5 µm further, adds an incoherent reflection this model leaves out), the film
//! as lossless (rutile absorbs below ~410 nm, where the model overstates R).
//!
//! **Indices.** Rutile TiO₂, ordinary ray: n² = 5.913 + 0.2441 / (λ² − 0.0803), λ in µm
//! (\[DeVore1951\]); mica (muscovite) 1.58 and a binder of 1.50 (*choices*: typical values,
//! constant over the visible).
//!
//! Checked against the `tmm` package (transfer matrices, \[Byrnes2016\]) over 0-80° and film
//! thicknesses 40-200 nm: `python/test_thin_film_tmm.py`.

use crate::spectrum::Spectrum;
use nalgebra::Complex;

/// Index of rutile TiO₂ (ordinary ray) at `wavelength_nm` (\[DeVore1951\]; fitted 430-1530 nm,
/// used over 380-780 nm).
pub fn rutile_index(wavelength_nm: f64) -> f64 {
    let um2 = (wavelength_nm / 1000.0).powi(2);
    (5.913 + 0.2441 / (um2 - 0.0803)).sqrt()
}

/// Index of mica (muscovite), *choice*.
pub const MICA_INDEX: f64 = 1.58;
/// Index of a cosmetic binder, *choice*.
pub const BINDER_INDEX: f64 = 1.50;

/// A coated platelet in its binder: the film's thickness and the three indices (the film's by
/// wavelength).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CoatedPlatelet {
    /// Thickness of the TiO₂ film, nm.
    pub film_nm: f64,
    /// Index of the binder the light comes from.
    pub binder_index: f64,
    /// Index of the platelet's core.
    pub core_index: f64,
}

impl CoatedPlatelet {
    /// Mica with a rutile film `film_nm` thick, in a binder of [`BINDER_INDEX`].
    pub fn mica_tio2(film_nm: f64) -> CoatedPlatelet {
        CoatedPlatelet { film_nm, binder_index: BINDER_INDEX, core_index: MICA_INDEX }
    }

    /// Unpolarised reflectance at `wavelength_nm` for light at `theta_binder_rad` from the
    /// platelet's normal, in the binder (module doc). In [0, 1] for every angle in [0, π/2] and
    /// every film thickness ≥ 0.
    pub fn reflectance(&self, wavelength_nm: f64, theta_binder_rad: f64) -> f64 {
        let n = [self.binder_index, rutile_index(wavelength_nm), self.core_index].map(|v| Complex::new(v, 0.0));
        let sin0 = Complex::new(theta_binder_rad.sin(), 0.0);
        let cos = n.map(|nj| {
            let s = n[0] * sin0 / nj;
            let c = (Complex::new(1.0, 0.0) - s * s).sqrt();
            // The forward-going wave: decaying (Im > 0) past a critical angle.
            if c.im < 0.0 { -c } else { c }
        });
        let r_s = |i: usize, j: usize| (n[i] * cos[i] - n[j] * cos[j]) / (n[i] * cos[i] + n[j] * cos[j]);
        let r_p = |i: usize, j: usize| (n[j] * cos[i] - n[i] * cos[j]) / (n[j] * cos[i] + n[i] * cos[j]);
        let delta = n[1] * cos[1] * (std::f64::consts::TAU * self.film_nm / wavelength_nm);
        let phase = (Complex::new(0.0, 2.0) * delta).exp();
        let airy = |r01: Complex<f64>, r12: Complex<f64>| {
            let r = (r01 + r12 * phase) / (Complex::new(1.0, 0.0) + r01 * r12 * phase);
            r.norm_sqr()
        };
        let rs = airy(r_s(0, 1), r_s(1, 2));
        let rp = airy(r_p(0, 1), r_p(1, 2));
        (0.5 * (rs + rp)).clamp(0.0, 1.0)
    }

    /// The reflectance spectrum on the working grid at `theta_binder_rad`.
    pub fn spectrum(&self, theta_binder_rad: f64) -> Spectrum {
        Spectrum::from_fn(|nm| self.reflectance(nm, theta_binder_rad))
    }
}

/// The angle in the binder, radians, of light at `theta_air_rad` from the normal in air (Snell).
pub fn angle_in_binder(theta_air_rad: f64, binder_index: f64) -> f64 {
    (theta_air_rad.sin() / binder_index).clamp(-1.0, 1.0).asin()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rutile_is_about_2_6_and_disperses() {
        let n550 = rutile_index(550.0);
        assert!((n550 - 2.65).abs() < 0.02, "{n550}");
        assert!(rutile_index(450.0) > n550 && n550 > rutile_index(700.0));
    }

    #[test]
    fn no_film_is_the_binder_mica_interface_and_quarter_waves_peak() {
        // Without a film: the bare binder/mica Fresnel reflectance at normal incidence.
        let bare = CoatedPlatelet::mica_tio2(0.0).reflectance(550.0, 0.0);
        let fresnel = ((BINDER_INDEX - MICA_INDEX) / (BINDER_INDEX + MICA_INDEX)).powi(2);
        assert!((bare - fresnel).abs() < 1e-12, "{bare} against {fresnel}");
        // A quarter-wave film at 550 nm (n d = λ/4) reflects most there, far more than bare mica.
        let d = 550.0 / (4.0 * rutile_index(550.0));
        let film = CoatedPlatelet::mica_tio2(d);
        let at = |nm| film.reflectance(nm, 0.0);
        assert!(at(550.0) > 0.2 && at(550.0) > at(400.0) && at(550.0) > at(750.0), "{}", at(550.0));
        // Tilting shifts the peak to shorter wavelengths (cos θ₁ shortens the optical path).
        let peak = |theta: f64| {
            (380..=780)
                .step_by(2)
                .map(f64::from)
                .max_by(|a, b| film.reflectance(*a, theta).total_cmp(&film.reflectance(*b, theta)))
        };
        assert!(peak(0.9).unwrap_or(0.0) < peak(0.0).unwrap_or(0.0));
    }

    #[test]
    fn reflectance_stays_in_0_1_everywhere() {
        let glassy = CoatedPlatelet { film_nm: 120.0, binder_index: 1.7, core_index: 1.3 };
        for film_nm in [0.0, 10.0, 60.0, 140.0, 400.0] {
            for p in [CoatedPlatelet::mica_tio2(film_nm), CoatedPlatelet { film_nm, ..glassy }] {
                for i in 0..=90 {
                    let theta = f64::from(i).to_radians();
                    for nm in [380.0, 500.0, 780.0] {
                        let r = p.reflectance(nm, theta);
                        assert!((0.0..=1.0).contains(&r), "{p:?} {i}° {nm} nm: {r}");
                    }
                }
            }
        }
        // Past the critical angle (binder 1.7 over a 1.3 core, total reflection): R → 1.
        assert!(glassy.reflectance(550.0, 1.4) > 0.99);
        assert!((angle_in_binder(std::f64::consts::FRAC_PI_2, 1.5) - (1.0f64 / 1.5).asin()).abs() < 1e-12);
    }
}
