//! The dielectric half-space's table (render/src/dielectric_half_space.rs) against what it was
//! not built from: the adding-doubling points off its grid, and at η = 1 Chandrasekhar's
//! H-function (render/src/half_space.rs, itself checked against 50-digit values).

use rouge_render::dielectric_half_space::{ETA_RANGE, held_out_points, reflectance};
use rouge_render::half_space::HalfSpace;

#[test]
fn off_the_grid_the_table_is_within_a_ten_thousandth_of_adding_doubling() {
    let check = held_out_points().expect("the reference");
    assert!(check.len() > 100);
    let mut errors: Vec<(f64, f64, f64)> = Vec::new();
    for e in &check {
        let got = reflectance(e.albedo, e.eta).expect("in the domain");
        for err in [(got.normal - e.r_normal).abs(), (got.diffuse - e.r_diffuse).abs()] {
            errors.push((err, e.albedo, e.eta));
        }
    }
    errors.sort_by(|a, b| b.0.total_cmp(&a.0));
    let median = errors[errors.len() / 2].0;
    eprintln!("off the grid: median absolute error {median:.1e}; worst {:?}", &errors[..4]);
    let worst = errors[0];
    // Measured: worst 3.9e-5 (α′ 0.02, η 1), median 2.6e-6; with the albedos evenly spaced in
    // √(1 − α′) instead of its square root, 9.7e-4 at cream's red (α′ 0.99997, η 1.4) and 1.4e-2
    // at η 2.7.
    assert!(worst.0 < 1e-4 && median < 1e-5, "{worst:?}, median {median}");
}

#[test]
fn at_eta_one_the_table_is_chandrasekhars_half_space() {
    // Adding-doubling and the H-function are independent exact routes to the same numbers:
    // R(1) = 1 − γH(1), and the white-sky albedo.
    for k in 0..=40 {
        let alpha = 1.0 - (f64::from(k) / 40.0).powi(2);
        let hs = HalfSpace::new(alpha);
        let got = reflectance(alpha, 1.0).expect("in the domain");
        assert!((got.normal - hs.directional_reflectance(1.0)).abs() < 5e-5, "α′ {alpha}: {got:?}");
        assert!((got.diffuse - hs.white_sky_albedo()).abs() < 5e-5, "α′ {alpha}: {got:?}");
    }
}

#[test]
fn the_ends_of_the_domain_are_exact_and_outside_it_is_an_error() {
    for eta in [1.0, 1.33, 1.4, 1.6, 3.0] {
        // Nothing scatters: nothing comes back but the specular reflection, excluded.
        let black = reflectance(0.0, eta).expect("black");
        assert!(black.normal.abs() < 1e-9 && black.diffuse.abs() < 1e-9, "{eta}: {black:?}");
        // Nothing absorbs: everything that entered leaves, 1 − F(0) at normal incidence.
        let white = reflectance(1.0, eta).expect("white");
        let f0 = ((eta - 1.0) / (eta + 1.0)).powi(2);
        assert!((white.normal - (1.0 - f0)).abs() < 1e-4, "{eta}: {white:?} against {}", 1.0 - f0);
        // Monotonic in the albedo.
        let mut last = black;
        for k in 1..=100 {
            let r = reflectance(f64::from(k) / 100.0, eta).expect("in the domain");
            assert!(r.normal >= last.normal - 1e-9 && r.diffuse >= last.diffuse - 1e-9, "{eta} {k}");
            last = r;
        }
    }
    for (alpha, eta, named) in [
        (-0.1, 1.4, "-0.1"),
        (1.5, 1.4, "1.5"),
        (f64::NAN, 1.4, "NaN"),
        (0.5, 0.9, "0.9"),
        (0.5, 3.5, "3.5"),
        (0.5, f64::NAN, "NaN"),
        (0.5, f64::INFINITY, "inf"),
    ] {
        let err = reflectance(alpha, eta).expect_err("outside the domain").to_string();
        assert!(err.contains(named), "{alpha} {eta}: {err}");
    }
    assert_eq!(*ETA_RANGE.start(), 1.0);
}
