//! Unit checks of the scalar Kubelka-Munk reference (`rouge_measure::km`): round trips, the
//! K = 0 limit, the errors of every invalid input, the forward model's edge cases, Saunderson
//! and composition. The 50-digit references are in the workspace tests (`tests/km_reference.rs`).

use rouge_measure::km::{
    KmCoefficients, KmError, LayerRt, Saunderson, compose, duncan_mix, invert_s_k, layer_r_t, r_inf_from_s_k,
    reflectance_over_background, stack,
};

#[test]
fn duncan_mix_weights_and_refuses_bad_components() {
    let a = KmCoefficients { s_per_mm: 10.0, k_per_mm: 1.0 };
    let b = KmCoefficients { s_per_mm: 2.0, k_per_mm: 8.0 };
    let m = duncan_mix([(0.25, a), (0.5, b)]).unwrap();
    assert_eq!(m, KmCoefficients { s_per_mm: 3.5, k_per_mm: 4.25 });
    assert_eq!(duncan_mix([]).unwrap(), KmCoefficients { s_per_mm: 0.0, k_per_mm: 0.0 });
    let e = duncan_mix([(0.5, a), (-0.1, b)]).unwrap_err();
    assert_eq!(e, KmError::BadCoefficient { name: "concentration", value: -0.1 });
    let nan = KmCoefficients { s_per_mm: f64::NAN, k_per_mm: 1.0 };
    assert!(matches!(duncan_mix([(0.5, nan)]), Err(KmError::BadCoefficient { name: "S", .. })));
    let huge = KmCoefficients { s_per_mm: f64::MAX, k_per_mm: 0.0 };
    assert!(duncan_mix([(1.0, huge), (1.0, huge)]).is_err());
}

#[test]
fn invert_round_trips_ordinary_case() {
    let (s, k, x) = (20.0, 2.0, 0.03);
    let r_inf = r_inf_from_s_k(s, k);
    for rg in [0.04, 0.9] {
        let r = reflectance_over_background(s, k, x, rg).unwrap();
        let c = invert_s_k(r_inf, r, rg, x).unwrap();
        assert!((c.s_per_mm / s - 1.0).abs() < 1e-9, "{c:?} rg {rg}");
        assert!((c.k_per_mm / k - 1.0).abs() < 1e-9, "{c:?} rg {rg}");
    }
}

#[test]
fn k_zero_limit() {
    let c = invert_s_k(1.0, 0.5, 0.2, 0.1).unwrap();
    let expect = (0.5 - 0.2) / ((1.0 - 0.5) * (1.0 - 0.2)) / 0.1;
    assert!((c.s_per_mm / expect - 1.0).abs() < 1e-15);
    assert_eq!(c.k_per_mm, 0.0);
}

#[test]
fn invalid_inputs_are_errors() {
    assert!(matches!(invert_s_k(1.2, 0.5, 0.1, 1.0), Err(KmError::RInfOutOfRange(_))));
    assert!(matches!(invert_s_k(0.0, 0.5, 0.1, 1.0), Err(KmError::RInfOutOfRange(_))));
    assert!(matches!(invert_s_k(f64::NAN, 0.5, 0.1, 1.0), Err(KmError::RInfOutOfRange(_))));
    assert!(matches!(invert_s_k(0.5, 0.6, 0.1, 1.0), Err(KmError::OppositeSides { .. })));
    assert!(matches!(invert_s_k(0.5, 0.05, 0.1, 1.0), Err(KmError::BeyondBackground { .. })));
    assert!(matches!(invert_s_k(0.5, 0.5, 0.1, 1.0), Err(KmError::InfinitelyThick { .. })));
    assert!(matches!(invert_s_k(0.5, 0.3, 0.5, 1.0), Err(KmError::BackgroundEqualsRInf { .. })));
    assert!(matches!(invert_s_k(0.5, 0.3, 0.1, 0.0), Err(KmError::BadThickness(_))));
    assert!(matches!(invert_s_k(0.5, 0.3, 0.1, -1.0), Err(KmError::BadThickness(_))));
    assert!(matches!(invert_s_k(0.5, f64::NAN, 0.1, 1.0), Err(KmError::ReflectanceOutOfRange { .. })));
    assert!(layer_r_t(-1.0, 0.0, 1.0).is_err());
    assert!(layer_r_t(1.0, f64::INFINITY, 1.0).is_err());
    assert!(layer_r_t(1.0, 1.0, f64::NAN).is_err());
}

#[test]
fn forward_edge_cases() {
    assert_eq!(layer_r_t(0.0, 0.0, 1.0).unwrap(), LayerRt::CLEAR);
    assert_eq!(layer_r_t(5.0, 5.0, 0.0).unwrap(), LayerRt::CLEAR);
    let l = layer_r_t(2.0, 0.0, 0.5).unwrap();
    assert!((l.r - 0.5).abs() < 1e-16 && (l.t - 0.5).abs() < 1e-16);
    let l = layer_r_t(0.0, 3.0, 0.5).unwrap();
    assert_eq!(l.r, 0.0);
    assert!((l.t / (-1.5f64).exp() - 1.0).abs() < 1e-15);
    let l = layer_r_t(1e300, 1e300, 1e300).unwrap();
    assert!((l.r - r_inf_from_s_k(1.0, 1.0)).abs() < 1e-15 && l.t == 0.0);
    let l = layer_r_t(1.0, 0.0, f64::INFINITY).unwrap();
    assert_eq!((l.r, l.t), (1.0, 0.0));
    let l = layer_r_t(3.0, 1.0, f64::INFINITY).unwrap();
    assert!((l.r - r_inf_from_s_k(3.0, 1.0)).abs() < 1e-16 && l.t == 0.0);
}

#[test]
fn saunderson_round_trips() {
    let c = Saunderson::from_refractive_index(1.5, 0.6, true).unwrap();
    assert!((c.k1 - 0.04).abs() < 1e-15);
    for r in [0.0, 0.1, 0.5, 0.9, 1.0] {
        assert!((c.to_internal(c.to_measured(r)) - r).abs() < 1e-14);
    }
}

#[test]
fn compose_with_clear_is_identity_and_perfect_mirrors_are_finite() {
    let l = LayerRt { r: 0.3, t: 0.5 };
    assert_eq!(compose(l, LayerRt::CLEAR), l);
    assert_eq!(stack(&[LayerRt::CLEAR, l]), l);
    assert_eq!(compose(LayerRt { r: 1.0, t: 0.0 }, LayerRt::opaque(1.0)), LayerRt { r: 1.0, t: 0.0 });
}
