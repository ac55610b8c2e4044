//! The slab law's table against adding-doubling's own values off its grid
//! (`render/src/slab_transmittance.rs`, `data/reference/slab_transmittance.json`, made by
//! `python/gen_slab_transmittance.py` with iadpython): the points were computed at 24
//! quadrature angles, whose cosines are none of the table's nodes, at random albedos and
//! thicknesses, 60 at each of seven indices η (six of them between the table's η nodes).

use rouge_render::slab_transmittance::{SlabPoint, axes, held_out_points, kappa, single_scattering, transmittance};

fn median(mut v: Vec<f64>) -> f64 {
    v.sort_by(f64::total_cmp);
    v[v.len() / 2]
}

fn worst(v: &[f64]) -> f64 {
    v.iter().copied().fold(0.0, f64::max)
}

/// The errors of the table over `points`: μ_l·|ΔT| (the radiance error per unit E/π), the
/// relative error where T > 10⁻³, and that relative error past 0.2 mean free paths at cosines
/// ≥ 0.2 where the albedo is at least 0.5 (every skin channel's; darker media transmit little).
fn errors(points: &[&SlabPoint]) -> (Vec<f64>, Vec<f64>, Vec<f64>) {
    let (mut radiance, mut relative, mut thick) = (Vec::new(), Vec::new(), Vec::new());
    for p in points {
        let t = transmittance(p.albedo, p.eta, p.tau, p.mu_v, p.mu_l).expect("in the domain");
        assert!(t.is_finite() && t >= 0.0, "{p:?}: {t}");
        radiance.push(p.mu_l * (t - p.t).abs());
        if p.t > 1e-3 {
            relative.push((t - p.t).abs() / p.t);
            if p.tau >= 0.2 && p.mu_v >= 0.2 && p.mu_l >= 0.2 && p.albedo >= 0.5 {
                thick.push((t - p.t).abs() / p.t);
            }
        }
    }
    (radiance, relative, thick)
}

#[test]
fn the_table_follows_adding_doubling_off_its_grid() {
    let points = held_out_points().expect("reference");
    assert!(points.len() >= 400, "{} points", points.len());
    let mut etas: Vec<f64> = points.iter().map(|p| p.eta).collect();
    etas.dedup();
    assert!(etas.len() >= 7 && etas.contains(&1.0), "{etas:?}");
    for eta in etas {
        let at: Vec<&SlabPoint> = points.iter().filter(|p| p.eta == eta).collect();
        let (radiance, relative, thick) = errors(&at);
        println!(
            "η {eta}: {} points: μ_l·|ΔT| worst {:.2e}, median {:.2e}; relative (T > 10⁻³) median {:.2e}, \
             worst {:.2e}; τ ≥ 0.2, cosines ≥ 0.2, α′ ≥ 0.5 ({} points): median {:.2e}, worst {:.2e}",
            at.len(),
            worst(&radiance),
            median(radiance.clone()),
            median(relative.clone()),
            worst(&relative),
            thick.len(),
            median(thick.clone()),
            worst(&thick),
        );
        assert!(worst(&radiance) < 0.006, "η {eta}: worst radiance error {}", worst(&radiance));
        assert!(median(relative) < 0.01, "η {eta}");
        // (This machine: 1.5% at η 1, 5.7% at η 1.33 — equal cosines of 0.2, τ 0.27 — and 5.0% at
        // 1.37; no denser η grid lowers them: 13 η nodes give the same, so they are the cosine and
        // thickness grid's, and the 24-angle reference's own.)
        assert!(worst(&thick) < 0.07, "η {eta}: worst relative error past 0.2 mean free paths {}", worst(&thick));
    }
}

#[test]
fn without_the_multiple_scattering_table_thick_slabs_are_far_off() {
    // The check above can fail: single scattering alone, or the table without its κ, miss the
    // reference by far on slabs a few mean free paths thick.
    let points = held_out_points().expect("reference");
    let thick: Vec<_> = points.iter().filter(|p| p.tau > 2.0 && p.t > 1e-3 && p.albedo > 0.5).collect();
    assert!(thick.len() > 40);
    let off = thick.iter().filter(|p| single_scattering(p.albedo, p.eta, p.tau, p.mu_v, p.mu_l) < 0.8 * p.t).count();
    assert!(off * 2 > thick.len(), "single scattering alone within 20% on {} of {}", thick.len() - off, thick.len());
    // Doubling the decay rate leaves thick slabs orders of magnitude dark.
    let p = thick.iter().max_by(|a, b| a.tau.total_cmp(&b.tau)).expect("one");
    let t = transmittance(p.albedo, p.eta, p.tau, p.mu_v, p.mu_l).expect("in the domain");
    let wrong = t * (-kappa(p.albedo) * p.tau).exp();
    assert!((t - p.t).abs() < 0.05 * p.t && (wrong - p.t).abs() > 0.2 * p.t, "{p:?}: {t} / {wrong}");
}

#[test]
fn a_dielectric_boundary_changes_what_a_slab_lets_through() {
    // The index-matched law on slabs whose faces are dielectric (η ≥ 1.3, skin's and the
    // media's): the Fresnel losses at both faces, the light the faces hold inside and the
    // refracted cosines move T by far more than the table's error.
    let points = held_out_points().expect("reference");
    let dielectric: Vec<_> = points.iter().filter(|p| p.eta >= 1.3 && p.t > 1e-3).collect();
    assert!(dielectric.len() > 100);
    let relative = |eta_of: &dyn Fn(&SlabPoint) -> f64| {
        let errors: Vec<f64> = dielectric
            .iter()
            .map(|p| (transmittance(p.albedo, eta_of(p), p.tau, p.mu_v, p.mu_l).expect("in") - p.t).abs() / p.t)
            .collect();
        median(errors)
    };
    let (right, matched) = (relative(&|p| p.eta), relative(&|_| 1.0));
    println!("{} points at η ≥ 1.3: relative error median {right:.2e}; with η = 1, {matched:.2e}", dielectric.len());
    assert!(matched > 0.1 && matched > 20.0 * right, "{matched} against {right}");
}

#[test]
fn the_edges_of_the_domain_are_finite() {
    let eta_max = axes().expect("table").eta_max;
    for eta in [1.0, 1.0 + 1e-9, 1.3, eta_max] {
        for a in [0.0, 1e-9, 0.5, 1.0 - 1e-12, 1.0] {
            for tau in [0.0, 1e-9, 1.0, 255.9, 256.0, 1e4, 1e300] {
                for mu in [0.0, 1e-9, 0.5, 1.0] {
                    let t = transmittance(a, eta, tau, mu, 1.0 - mu).expect("in the domain");
                    assert!(t.is_finite() && t >= 0.0, "η {eta} α′ {a} τ {tau} μ {mu}: {t}");
                }
            }
        }
        assert_eq!(transmittance(0.0, eta, 3.0, 0.5, 0.7).expect("in"), 0.0);
        assert_eq!(transmittance(0.7, eta, 0.0, 0.5, 0.7).expect("in"), 0.0);
    }
    // Outside it: an error that names the index.
    for eta in [0.99, eta_max + 0.01, f64::NAN, f64::INFINITY] {
        let e = transmittance(0.9, eta, 1.0, 0.5, 0.5).expect_err("outside the table").to_string();
        assert!(e.contains("index η"), "{e}");
    }
}
