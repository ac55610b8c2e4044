//! The spectral skin model: its limits, monotonicity, the inversion of synthetic spectra with
//! noise, and bad inputs (docs/SKIN.md).

use rouge_measure::skin::fit::SkinFitter;
use rouge_measure::skin::optics::rgb_medium;
use rouge_measure::skin::transport::specular_reflectance;
use rouge_measure::skin::{FitOptions, SkinError, SkinParams};
use rouge_measure::spectrum::Extrapolation;

fn grid(from: f64, to: f64, step: f64) -> Vec<f64> {
    let n = ((to - from) / step).round() as usize;
    (0..=n).map(|i| from + step * i as f64).collect()
}

fn light() -> SkinParams {
    SkinParams::LIGHT
}

#[test]
fn limits_of_the_model() {
    let wl = grid(380.0, 780.0, 5.0);
    // No melanin, no blood: only the baseline absorbs; the skin is paler at every wavelength.
    let pale = SkinParams { melanin_fraction: 0.0, blood_fraction: 0.0, ..light() }.reflectance_at(&wl).unwrap();
    let skin = light().reflectance_at(&wl).unwrap();
    assert!(pale.iter().all(|r| (0.0..=1.0).contains(r)));
    assert!(pale.iter().zip(&skin).all(|(p, s)| p > s), "{pale:?}");
    // No epidermis: melanin does nothing.
    let bare = |mel: f64| {
        SkinParams { melanin_fraction: mel, epidermis_thickness_mm: 0.0, ..light() }.reflectance_at(&wl).unwrap()
    };
    let (a, b) = (bare(0.0), bare(0.5));
    assert!(a.iter().zip(&b).all(|(x, y)| (x - y).abs() < 1e-12));
    // All melanin, a thick epidermis: little but the surface's reflection comes back in the blue.
    let dark =
        SkinParams { melanin_fraction: 0.6, epidermis_thickness_mm: 0.2, ..light() }.reflectance_at(&wl).unwrap();
    assert!(dark[0] < specular_reflectance() + 0.005, "{}", dark[0]);
    assert!(dark.iter().all(|r| *r >= specular_reflectance() - 1e-12));
}

#[test]
fn monotone_in_each_chromophore() {
    let wl = grid(380.0, 780.0, 10.0);
    let at = |p: SkinParams| p.reflectance_at(&wl).unwrap();
    for k in 1..=10 {
        let lo = f64::from(k - 1) * 0.05;
        let hi = f64::from(k) * 0.05;
        let (a, b) =
            (at(SkinParams { melanin_fraction: lo, ..light() }), at(SkinParams { melanin_fraction: hi, ..light() }));
        assert!(a.iter().zip(&b).all(|(x, y)| y <= x), "melanin {lo}->{hi}");
        let (a, b) = (
            at(SkinParams { blood_fraction: lo * 0.5, ..light() }),
            at(SkinParams { blood_fraction: hi * 0.5, ..light() }),
        );
        assert!(a.iter().zip(&b).all(|(x, y)| y <= x), "blood {lo}->{hi}");
    }
    // More scattering, more light back at every wavelength.
    let (a, b) = (
        at(SkinParams { scattering_500nm_per_mm: 2.0, ..light() }),
        at(SkinParams { scattering_500nm_per_mm: 4.0, ..light() }),
    );
    assert!(a.iter().zip(&b).all(|(x, y)| y >= x));
    // Deoxygenated blood is darker in the red (Hb absorbs more than HbO2 above 600 nm).
    let (oxy, deoxy) =
        (at(SkinParams { oxygen_saturation: 1.0, ..light() }), at(SkinParams { oxygen_saturation: 0.0, ..light() }));
    let i660 = wl.iter().position(|w| *w == 660.0).unwrap();
    assert!(deoxy[i660] < oxy[i660]);
}

#[test]
fn bad_parameters_are_named() {
    let e = SkinParams { melanin_fraction: 0.9, ..light() }.reflectance_at(&[500.0]).unwrap_err();
    assert!(matches!(e, SkinError::Parameter { name: "melanin_fraction", .. }), "{e}");
    let e = SkinParams { blood_fraction: f64::NAN, ..light() }.reflectance_at(&[500.0]).unwrap_err();
    assert!(e.to_string().contains("blood_fraction"), "{e}");
    let e = light().reflectance_at(&[370.0]).unwrap_err();
    assert!(e.to_string().contains("370 nm"), "{e}");
    let e = SkinParams { scattering_500nm_per_mm: 10.0, scattering_power: 4.0, epidermis_thickness_mm: 0.3, ..light() }
        .reflectance_at(&[500.0])
        .unwrap_err();
    assert!(matches!(e, SkinError::EpidermisTooThick { .. }), "{e}");
}

/// A small deterministic generator for the noise (no dependency).
struct Lcg(u64);
impl Lcg {
    fn uniform(&mut self) -> f64 {
        self.0 = self.0.wrapping_mul(6364136223846793005).wrapping_add(1442695040888963407);
        (self.0 >> 11) as f64 / (1u64 << 53) as f64
    }
}

#[test]
fn the_fit_recovers_synthetic_skins_with_noise() {
    // Xiao's grid (360-740 nm would need --extrapolate; the model starts at 380).
    let wl = grid(380.0, 740.0, 10.0);
    let fitter =
        SkinFitter::new(FitOptions { extrapolation: Extrapolation::Constant, ..FitOptions::default() }).unwrap();
    let truths = [
        SkinParams { melanin_fraction: 0.015, blood_fraction: 0.015, oxygen_saturation: 0.8, ..light() },
        SkinParams { melanin_fraction: 0.08, pheomelanin_share: 0.2, blood_fraction: 0.04, ..light() },
        SkinParams {
            melanin_fraction: 0.3,
            blood_fraction: 0.03,
            scattering_500nm_per_mm: 2.2,
            scattering_power: 1.1,
            ..light()
        },
    ];
    let mut rng = Lcg(7);
    for (k, truth) in truths.into_iter().enumerate() {
        let clean = truth.reflectance_at(&wl).unwrap();
        // Without noise every skin is recovered, the deep one included.
        let exact = fitter.fit(&wl, &clean).unwrap();
        assert!(exact.delta_e_2000 < 0.05, "{truth:?}: ΔE {}", exact.delta_e_2000);
        let p = exact.params;
        assert!(
            (p.melanin_fraction - truth.melanin_fraction).abs() < 0.05 * truth.melanin_fraction,
            "{p:?} vs {truth:?}"
        );
        assert!((p.blood_fraction - truth.blood_fraction).abs() < 0.1 * truth.blood_fraction, "{p:?} vs {truth:?}");
        // With noise of ±0.002 in reflectance (a good spectrophotometer's repeatability) the colour
        // is always recovered; the parameters of light and medium skins too. Under the deep skin's
        // melanin the blood's bands are within the noise: its blood is not identifiable.
        let noisy: Vec<f64> = clean.iter().map(|r| r + 0.002 * (rng.uniform() - 0.5) * 2.0).collect();
        let fit = fitter.fit(&wl, &noisy).unwrap();
        assert!(fit.delta_e_2000 < 0.5, "{truth:?}: ΔE {}", fit.delta_e_2000);
        assert!(fit.rms < 0.003, "{truth:?}: rms {}", fit.rms);
        if k == 2 {
            assert!((fit.params.melanin_fraction - truth.melanin_fraction).abs() < 0.35 * truth.melanin_fraction);
            continue;
        }
        let p = fit.params;
        assert!(
            (p.melanin_fraction - truth.melanin_fraction).abs() < 0.15 * truth.melanin_fraction + 0.003,
            "{p:?} vs {truth:?}"
        );
        assert!(
            (p.blood_fraction - truth.blood_fraction).abs() < 0.25 * truth.blood_fraction + 0.003,
            "{p:?} vs {truth:?}"
        );
        assert!((p.oxygen_saturation - truth.oxygen_saturation).abs() < 0.15, "{p:?} vs {truth:?}");
    }
}

#[test]
fn a_spectrum_the_model_cannot_explain_gets_its_best_fit() {
    // A saturated blue (a paint chip, not skin): the fit ends, finite, far, and says which
    // parameters hit their bounds.
    let wl = grid(380.0, 780.0, 10.0);
    let blue: Vec<f64> = wl.iter().map(|w| if *w < 500.0 { 0.6 } else { 0.05 }).collect();
    let fit = SkinFitter::new(FitOptions::default()).unwrap().fit(&wl, &blue).unwrap();
    assert!(fit.delta_e_2000.is_finite() && fit.delta_e_2000 > 10.0, "{}", fit.delta_e_2000);
    assert!(fit.params.to_array().iter().all(|v| v.is_finite()));
    assert!(fit.fitted.0.iter().all(|v| v.is_finite()));
}

#[test]
fn bad_measurements_are_errors_that_name_the_wavelength() {
    let fitter = SkinFitter::new(FitOptions::default()).unwrap();
    let wl = grid(380.0, 780.0, 10.0);
    let mut r = vec![0.4; wl.len()];
    r[5] = -0.01;
    let e = fitter.fit(&wl, &r).unwrap_err().to_string();
    assert!(e.contains("430 nm") && e.contains("-0.01"), "{e}");
    r[5] = 1.2;
    let e = fitter.fit(&wl, &r).unwrap_err().to_string();
    assert!(e.contains("430 nm") && e.contains("1.2"), "{e}");
    r[5] = f64::NAN;
    assert!(fitter.fit(&wl, &r).unwrap_err().to_string().contains("430 nm"));
    // A grid that goes backwards, and one that stops short without extrapolation.
    let mut back = wl.clone();
    back.swap(3, 4);
    assert!(fitter.fit(&back, &vec![0.4; wl.len()]).is_err());
    let short = grid(400.0, 700.0, 10.0);
    let e = fitter.fit(&short, &vec![0.4; short.len()]).unwrap_err().to_string();
    assert!(e.contains("--extrapolate"), "{e}");
}

#[test]
fn the_rgb_medium_reproduces_the_skin_colour() {
    for p in [light(), SkinParams { melanin_fraction: 0.35, ..light() }] {
        let m = rgb_medium(&p).unwrap();
        assert!(m.sigma_a_per_mm.iter().chain(&m.sigma_s_prime_per_mm).all(|v| v.is_finite() && *v > 0.0), "{m:?}");
        // Red scatters less but absorbs far less than blue in skin.
        assert!(m.sigma_a_per_mm[0] < m.sigma_a_per_mm[2] && m.sigma_s_prime_per_mm[0] < m.sigma_s_prime_per_mm[2]);
        // The semi-infinite medium's reflectance is the skin's colour, channel by channel.
        for c in 0..3 {
            let a = m.sigma_s_prime_per_mm[c] / (m.sigma_s_prime_per_mm[c] + m.sigma_a_per_mm[c]);
            let r = rouge_measure::skin::transport::two_layer_reflectance(0.0, 0.0, a).unwrap();
            assert!((r - m.albedo_linear_srgb[c]).abs() < 1e-6, "{c}: {r} vs {:?}", m.albedo_linear_srgb);
        }
    }
}
