//! The slab law's table against adding-doubling's own values off its grid
//! (`render/src/slab_transmittance.rs`, `data/reference/slab_transmittance.json`, made by
//! `python/gen_slab_transmittance.py` with iadpython): the points were computed at 24
//! quadrature angles, whose cosines are none of the table's nodes, at random albedos and
//! thicknesses.

use rouge_render::slab_transmittance::{held_out_points, kappa, single_scattering, transmittance};

fn median(mut v: Vec<f64>) -> f64 {
    v.sort_by(f64::total_cmp);
    v[v.len() / 2]
}

#[test]
fn the_table_follows_adding_doubling_off_its_grid() {
    let points = held_out_points().expect("reference");
    assert!(points.len() >= 200, "{} points", points.len());
    // The radiance error per unit E/π is μ_l·|ΔT|.
    let mut radiance = Vec::new();
    let mut relative = Vec::new();
    let mut relative_thick = Vec::new();
    for p in &points {
        let t = transmittance(p.albedo, p.tau, p.mu_v, p.mu_l).expect("in the domain");
        assert!(t.is_finite() && t >= 0.0, "{p:?}: {t}");
        radiance.push(p.mu_l * (t - p.t).abs());
        if p.t > 1e-3 {
            relative.push((t - p.t).abs() / p.t);
            if p.tau >= 0.2 && p.mu_v >= 0.2 && p.mu_l >= 0.2 {
                relative_thick.push((t - p.t).abs() / p.t);
            }
        }
    }
    let worst = radiance.iter().copied().fold(0.0, f64::max);
    let worst_thick = relative_thick.iter().copied().fold(0.0, f64::max);
    println!(
        "{} points: μ_l·|ΔT| worst {worst:.2e}, median {:.2e}; relative (T > 10⁻³) median {:.2e}; \
         τ ≥ 0.2 and cosines ≥ 0.2 ({} points): median {:.2e}, worst {worst_thick:.2e}",
        points.len(),
        median(radiance.clone()),
        median(relative.clone()),
        relative_thick.len(),
        median(relative_thick.clone()),
    );
    assert!(worst < 0.01, "worst radiance error {worst}");
    assert!(median(relative) < 0.01);
    assert!(worst_thick < 0.05, "worst relative error past 0.2 mean free paths {worst_thick}");
}

#[test]
fn without_the_multiple_scattering_table_thick_slabs_are_far_off() {
    // The check above can fail: single scattering alone, or the table without its κ, miss the
    // reference by far on slabs a few mean free paths thick.
    let points = held_out_points().expect("reference");
    let thick: Vec<_> = points.iter().filter(|p| p.tau > 2.0 && p.t > 1e-3 && p.albedo > 0.5).collect();
    assert!(thick.len() > 20);
    let off = thick.iter().filter(|p| single_scattering(p.albedo, p.tau, p.mu_v, p.mu_l) < 0.8 * p.t).count();
    assert!(off * 2 > thick.len(), "single scattering alone within 20% on {} of {}", thick.len() - off, thick.len());
    // Doubling the decay rate leaves thick slabs orders of magnitude dark.
    let p = thick.iter().max_by(|a, b| a.tau.total_cmp(&b.tau)).expect("one");
    let t = transmittance(p.albedo, p.tau, p.mu_v, p.mu_l).expect("in the domain");
    let wrong = t * (-kappa(p.albedo) * p.tau).exp();
    assert!((t - p.t).abs() < 0.05 * p.t && (wrong - p.t).abs() > 0.2 * p.t, "{p:?}: {t} / {wrong}");
}

#[test]
fn the_edges_of_the_domain_are_finite() {
    for a in [0.0, 1e-9, 0.5, 1.0 - 1e-12, 1.0] {
        for tau in [0.0, 1e-9, 1.0, 255.9, 256.0, 1e4, 1e300] {
            for mu in [0.0, 1e-9, 0.5, 1.0] {
                let t = transmittance(a, tau, mu, 1.0 - mu).expect("in the domain");
                assert!(t.is_finite() && t >= 0.0, "α′ {a} τ {tau} μ {mu}: {t}");
            }
        }
    }
    assert_eq!(transmittance(0.0, 3.0, 0.5, 0.7).expect("in"), 0.0);
    assert_eq!(transmittance(0.7, 0.0, 0.5, 0.7).expect("in"), 0.0);
}
