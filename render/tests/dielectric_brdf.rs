//! The half-space law under a dielectric boundary ([`rouge_render::dielectric_brdf`]) against
//! adding-doubling off every grid, against Chandrasekhar's exact half-space at η = 1, and at the
//! edges of its domain.

use rouge_render::dielectric_brdf::{GpuLaw, GpuTable, Law, held_out_points};
use rouge_render::half_space::HalfSpace;

fn quantile(mut v: Vec<f64>, q: f64) -> f64 {
    v.sort_by(f64::total_cmp);
    v[((v.len() - 1) as f64 * q).round() as usize]
}

#[test]
fn the_law_and_the_gpu_table_agree_with_adding_doubling_off_every_grid() {
    let points = held_out_points().expect("the reference");
    assert!(points.len() >= 150, "{} check points", points.len());
    let mut tables: Vec<(f64, GpuTable)> = Vec::new();
    let (mut law_f, mut law_r, mut gpu_f, mut gpu_r) = (vec![], vec![], vec![], vec![]);
    for p in &points {
        let law = Law::new(p.albedo, p.eta).expect("in the domain");
        assert!((law.r_normal / p.r_normal - 1.0).abs() < 2e-3, "r_n {} against {}", law.r_normal, p.r_normal);
        law_f.push((law.pi_brdf(p.mu, p.mu0) / p.pi_f - 1.0).abs());
        law_r.push((law.reflectance(p.mu0) / p.r - 1.0).abs());
        if !tables.iter().any(|(e, _)| *e == p.eta) {
            tables.push((p.eta, GpuTable::new(GpuLaw { eta: p.eta, curvature: None }).expect("in the domain")));
        }
        let gpu = &tables.iter().find(|(e, _)| *e == p.eta).expect("made above").1;
        gpu_f.push((gpu.pi_brdf(p.r_normal, p.mu, p.mu0) / p.pi_f - 1.0).abs());
        gpu_r.push((gpu.reflectance(p.r_normal, p.mu0) / p.r - 1.0).abs());
    }
    let report = |name: &str, v: &Vec<f64>| {
        let (median, p95, worst) = (quantile(v.clone(), 0.5), quantile(v.clone(), 0.95), quantile(v.clone(), 1.0));
        eprintln!("{name}: relative error median {median:.2e}, p95 {p95:.2e}, worst {worst:.2e}");
        (median, p95, worst)
    };
    for (name, v, median, p95, worst) in [
        ("law πf", &law_f, 1e-3, 1e-2, 0.05),
        ("law R", &law_r, 1e-3, 2e-3, 5e-3),
        ("GPU table πf", &gpu_f, 3e-3, 1.5e-2, 0.05),
        ("GPU table R", &gpu_r, 3e-3, 5e-3, 1e-2),
    ] {
        let (m, p, w) = report(name, v);
        assert!(m < median && p < p95 && w < worst, "{name}: {m:.2e} / {p:.2e} / {w:.2e}");
    }
}

#[test]
fn at_eta_1_the_law_is_chandrasekhars_half_space() {
    // The albedo is the half-space table's (its error is relative to tiny reflectances at low
    // α′: absolute here); the shape is this module's, relative (worst at μ = 0.05, where H bends
    // between the table's cosines 1/16 apart).
    let (mut worst_albedo, mut worst_shape): (f64, f64) = (0.0, 0.0);
    for alpha in [0.02, 0.3, 0.68, 0.84, 0.959, 0.999] {
        let exact = HalfSpace::new(alpha);
        let law = Law::new(alpha, 1.0).expect("in the domain");
        let exact_rn = exact.directional_reflectance(1.0);
        worst_albedo = worst_albedo.max((law.r_normal - exact_rn).abs());
        let shape =
            |law_value: f64, exact_value: f64| ((law_value / law.r_normal) / (exact_value / exact_rn) - 1.0).abs();
        for mu in [0.05, 0.2, 0.5, 0.8, 1.0] {
            for mu0 in [0.1, 0.45, 0.9] {
                worst_shape = worst_shape.max(shape(law.pi_brdf(mu, mu0), exact.pi_brdf(mu, mu0)));
            }
            worst_shape = worst_shape.max(shape(law.reflectance(mu), exact.directional_reflectance(mu)));
        }
    }
    eprintln!("η = 1 against the H-function: albedo within {worst_albedo:.1e}, shape within {worst_shape:.2e}");
    assert!(worst_albedo < 1e-4 && worst_shape < 1.5e-2, "{worst_albedo} {worst_shape}");
}

#[test]
fn a_boundary_darkens_grazing_exits_and_the_law_keeps_reciprocity_and_energy() {
    let law = Law::new(0.9, 1.4).expect("in the domain");
    // Reciprocity.
    for (mu, mu0) in [(0.2, 0.7), (0.05, 1.0), (0.5, 0.33)] {
        let (a, b) = (law.pi_brdf(mu, mu0), law.pi_brdf(mu0, mu));
        assert!((a / b - 1.0).abs() < 1e-9, "{a} {b}");
    }
    // ∫ πf 2μ dμ over the exits is R(μ₀) (midpoint rule).
    for mu0 in [0.3, 1.0] {
        let n = 2000;
        let sum: f64 =
            (0..n).map(|i| (i as f64 + 0.5) / n as f64).map(|mu| law.pi_brdf(mu, mu0) * 2.0 * mu / n as f64).sum();
        assert!((sum / law.reflectance(mu0) - 1.0).abs() < 0.01, "μ₀ {mu0}: {sum} against {}", law.reflectance(mu0));
    }
    // Towards grazing the boundary transmits nothing.
    assert!(law.reflectance(0.0) == 0.0 && law.pi_brdf(0.0, 0.5) == 0.0);
    assert!(law.reflectance(0.2) < 0.8 * law.reflectance(1.0));
    let matched = Law::new(0.9, 1.0).expect("in the domain");
    assert!(matched.reflectance(0.0) > 0.0);
}

#[test]
fn the_edges_of_the_domain_are_finite_or_errors_that_name_the_value() {
    for (alpha, eta) in [(0.0, 1.0), (1.0, 1.0), (0.0, 3.0), (1.0, 3.0), (1.0, 1.0001)] {
        let law = Law::new(alpha, eta).expect("in the domain");
        for (mu, mu0) in [(0.0, 0.0), (0.0, 1.0), (1.0, 1.0), (f64::NAN, 0.5), (-3.0, 7.0)] {
            let (f, r) = (law.pi_brdf(mu, mu0), law.reflectance(mu0));
            assert!(
                f.is_finite() && f >= 0.0 && r.is_finite() && r >= 0.0,
                "α′ {alpha} η {eta} ({mu}, {mu0}): {f} {r}"
            );
        }
    }
    for (alpha, eta, word) in [(1.2, 1.3, "1.2"), (f64::NAN, 1.3, "NaN"), (0.5, 3.5, "3.5"), (0.5, 0.9, "0.9")] {
        let e = Law::new(alpha, eta).expect_err("outside").to_string();
        assert!(e.contains(word), "{e}");
    }
    let e = GpuTable::new(GpuLaw { eta: f64::NAN, curvature: None }).expect_err("outside").to_string();
    assert!(e.contains("NaN"), "{e}");
    let t = GpuTable::new(GpuLaw { eta: 1.3, curvature: None }).expect("in the domain");
    for a in [0.0, 1e-9, 0.5, 0.983, 1.0, 5.0, -1.0, f64::NAN] {
        for mu in [0.0, 0.5, 1.0] {
            let (f, r) = (t.pi_brdf(a, mu, 1.0 - mu), t.reflectance(a, mu));
            assert!(f.is_finite() && f >= 0.0 && r.is_finite() && r >= 0.0, "a {a} μ {mu}: {f} {r}");
        }
    }
}
