//! The skin model on arbitrary inputs: a result that is physical, or an error that says why;
//! never NaN, never a panic (docs/SKIN.md).

use proptest::prelude::*;
use rouge_measure::skin::fit::SkinFitter;
use rouge_measure::skin::transport::{specular_reflectance, two_layer_reflectance};
use rouge_measure::skin::{FitOptions, SkinParams};
use rouge_measure::spectrum::Extrapolation;
use std::sync::OnceLock;

/// Any f64, the awkward ones often.
fn any_number() -> impl Strategy<Value = f64> {
    prop_oneof![
        4 => -1.0..2.0f64,
        1 => Just(f64::NAN),
        1 => Just(f64::INFINITY),
        1 => Just(f64::NEG_INFINITY),
        1 => Just(0.0),
        1 => Just(1e308),
        1 => Just(-1e-300),
    ]
}

fn fitter() -> &'static SkinFitter {
    static F: OnceLock<SkinFitter> = OnceLock::new();
    F.get_or_init(|| {
        SkinFitter::new(FitOptions {
            extrapolation: Extrapolation::Constant,
            max_iterations: 15,
            ..FitOptions::default()
        })
        .expect("the default options build a fitter")
    })
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 256, ..ProptestConfig::default() })]

    #[test]
    fn the_forward_model_is_physical_or_refuses(a in prop::array::uniform7(any_number()), w in 300.0..900.0f64) {
        let scaled = [a[0] * 0.6, a[1], a[2] * 0.3, a[3], 0.5 + a[4] * 9.5, a[5] * 4.0, a[6] * 0.3];
        let p = SkinParams::from_array(scaled);
        match p.reflectance_at(&[w]) {
            Ok(r) => prop_assert!(r[0].is_finite() && r[0] >= specular_reflectance() - 1e-12 && r[0] <= 1.0 + 1e-9, "{p:?} at {w}: {r:?}"),
            Err(e) => prop_assert!(!e.to_string().is_empty()),
        }
    }

    #[test]
    fn the_transport_is_physical_or_refuses(ta in any_number(), ts in any_number(), al in any_number()) {
        match two_layer_reflectance(ta * 20.0, ts * 3.0, al) {
            Ok(r) => prop_assert!(r.is_finite() && (specular_reflectance() - 1e-12..=1.0 + 2e-3).contains(&r), "{r}"),
            Err(e) => prop_assert!(e.to_string().contains("outside")),
        }
    }

    #[test]
    fn the_fit_never_panics_and_never_returns_nan(
        values in prop::collection::vec(any_number(), 2..12),
        start in 350.0..500.0f64,
        step in prop_oneof![Just(-10.0), Just(0.0), 1.0..60.0f64],
    ) {
        let wl: Vec<f64> = (0..values.len()).map(|i| start + step * i as f64).collect();
        if let Ok(f) = fitter().fit(&wl, &values) {
            prop_assert!(f.delta_e_2000.is_finite() && f.rms.is_finite());
            prop_assert!(f.params.to_array().iter().all(|v| v.is_finite()));
            prop_assert!(f.fitted.0.iter().all(|v| v.is_finite()));
        }
    }

    #[test]
    fn any_spectrum_in_range_gets_a_finite_fit(
        values in prop::collection::vec(0.0..=1.0f64, 3..40),
        start in 360.0..450.0f64,
        step in 2.0..40.0f64,
    ) {
        let wl: Vec<f64> = (0..values.len()).map(|i| start + step * i as f64).collect();
        // Inside 380-780 nm somewhere, so the model has a wavelength to compare.
        prop_assume!(wl.iter().any(|w| (380.0..=780.0).contains(w)));
        let f = fitter().fit(&wl, &values);
        prop_assert!(f.is_ok(), "{f:?}");
        let f = f.unwrap();
        prop_assert!(f.delta_e_2000.is_finite() && f.rms.is_finite());
        prop_assert!(f.params.validate().is_ok(), "{:?}", f.params);
    }
}
