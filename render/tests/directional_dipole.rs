//! The directional dipole BSSRDF ([Frisvad2014]) on the CPU: its source term against the
//! fluence and flux of a ray source differentiated numerically, a hand-derived planar case,
//! reciprocity, positivity and no NaN over the domain, the jump between the front- and back-lit
//! branches, and the energy of a half-space against Mitsuba 3's path tracer
//! (data/reference/slab_albedo.json, python/gen_slab_reference.py).

use glam::DVec3;
use rouge_model::medium::Medium;
use rouge_render::directional_dipole::{
    DipoleChannel, DipoleSource, DirectionalDipole, Geometry, standard_dipole_bssrdf, standard_dipole_profiles,
};
use std::f64::consts::PI;

fn medium(name: &str, eta: f64) -> Medium {
    Medium::builtin(name).expect("medium").with_eta(eta).expect("eta")
}

/// A tiny deterministic generator (SplitMix64) for the random configurations.
struct Rng(u64);
impl Rng {
    fn next(&mut self) -> f64 {
        self.0 = self.0.wrapping_add(0x9e37_79b9_7f4a_7c15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
        (z ^ (z >> 31)) as f64 / u64::MAX as f64
    }
    fn unit(&mut self) -> DVec3 {
        loop {
            let v = DVec3::new(2.0 * self.next() - 1.0, 2.0 * self.next() - 1.0, 2.0 * self.next() - 1.0);
            if v.length_squared() > 1e-4 && v.length_squared() <= 1.0 {
                return v.normalize();
            }
        }
    }
}

#[test]
fn s_infinite_is_the_fluence_and_flux_of_a_ray_source() {
    // φ(x) = e^{−σr}/(4πr³)(r²/D + 3(1+σr) x·ω) from the monopole and its first moment; the
    // exitance C_φ φ + C_E E·n with E = −D∇φ, the gradient by central differences.
    let ch = DipoleChannel::new(0.05, 1.2, 1.3);
    let phi = |x: DVec3, w: DVec3| {
        let r = x.length();
        let s = ch.sigma_tr * r;
        (-s).exp() / (4.0 * PI * r * r * r) * (r * r / ch.d + 3.0 * (1.0 + s) * x.dot(w))
    };
    let mut rng = Rng(7);
    for _ in 0..200 {
        let x = rng.unit() * (0.2 + 5.0 * rng.next());
        let (w, n) = (rng.unit(), rng.unit());
        let h = 1e-5;
        let grad = DVec3::new(
            phi(x + DVec3::X * h, w) - phi(x - DVec3::X * h, w),
            phi(x + DVec3::Y * h, w) - phi(x - DVec3::Y * h, w),
            phi(x + DVec3::Z * h, w) - phi(x - DVec3::Z * h, w),
        ) / (2.0 * h);
        let expected = (ch.c_phi * phi(x, w) - ch.c_e * ch.d * grad.dot(n)) / PI;
        let got = ch.s_infinite(x, w, x.length(), n);
        assert!((got - expected).abs() <= 1e-6 * expected.abs().max(1e-3), "x {x} w {w} n {n}: {got} vs {expected}");
    }
}

#[test]
fn a_flat_surface_under_normal_light_matches_the_hand_derived_form() {
    // Flat, normal incidence and exit, η = 1 (no Fresnel): ω₁₂ = −n, n* = n, x ⟂ n, so
    // x·ω₁₂ = 0, μ₀ = 1, cos β = −r/√(r² + d_e²), d_r² = r² + D(D + 2d_e r/√(r² + d_e²)); the
    // real source gives e^{−σd_r}/(4π²d_r³)(C_φ d_r²/D + 3C_E D(1+σd_r)). The virtual source at
    // x_v = x − 2Ad_e n with ω_v = +n: x_v·ω_v = −2Ad_e, ω_v·n = 1, x_v·n = −2Ad_e, so its flux
    // term is 3D(1+σd_v) − ((1+σd_v) − 3D(3(1+σd_v) + σ²d_v²)·2Ad_e/d_v²)(−2Ad_e).
    let m = medium("skimmilk", 1.0);
    let dipole = DirectionalDipole::new(&m);
    for (c, ch) in dipole.channels.iter().enumerate() {
        for r in [0.05, 0.3, 1.0, 3.0, 10.0] {
            let g = Geometry::planar(r);
            let (d, s, de, a) = (ch.d, ch.sigma_tr, ch.de, ch.a);
            let dr = (r * r + d * (d + 2.0 * de * r / (r * r + de * de).sqrt())).sqrt();
            let real = (-s * dr).exp() / (4.0 * PI * PI * dr.powi(3))
                * (ch.c_phi * dr * dr / d + 3.0 * ch.c_e * d * (1.0 + s * dr));
            let h = 2.0 * a * de;
            let dv = (r * r + h * h).sqrt();
            let s1 = 1.0 + s * dv;
            let fluence = dv * dv / d + 3.0 * s1 * -h;
            let flux = 3.0 * d * s1 - (s1 + 3.0 * d * (3.0 * s1 + s * s * dv * dv) / (dv * dv) * -h) * -h;
            let virtual_ = (-s * dv).exp() / (4.0 * PI * PI * dv.powi(3)) * (ch.c_phi * fluence - ch.c_e * flux);
            let expected = dipole.exit_norm * (real - virtual_).max(0.0);
            let got = dipole.bssrdf(&g)[c];
            assert!((got - expected).abs() <= 1e-12 * expected.max(1e-30), "channel {c} r {r}: {got} vs {expected}");
            // Reciprocal in this symmetric configuration.
            let back = dipole.bssrdf(&g.swapped())[c];
            assert!((got - back).abs() <= 1e-12 * got.max(1e-30), "r {r}: {got} vs reversed {back}");
        }
    }
}

#[test]
fn positive_finite_and_symmetric_form_reciprocal_everywhere() {
    let mut rng = Rng(11);
    let media: Vec<Medium> = ["skin1", "marble", "ketchup", "apple"]
        .iter()
        .flat_map(|n| [1.0, 1.3, 2.0].map(|eta| medium(n, eta)))
        .chain([Medium::from_coefficients("no absorption", [0.0; 3], [1.0, 2.0, 0.5], 1.4).expect("medium")])
        .collect();
    for (m, source) in media.iter().flat_map(|m| [DipoleSource::Published, DipoleSource::MeanFreePath].map(|s| (m, s)))
    {
        let dipole = DirectionalDipole::with_source(m, source);
        for k in 0..400 {
            let ni = rng.unit();
            let mut g = Geometry {
                xi: DVec3::ZERO,
                ni,
                wi: rng.unit(),
                xo: rng.unit() * (10f64.powf(-6.0 + 7.5 * rng.next())),
                no: rng.unit(),
                wo: rng.unit(),
            };
            match k % 5 {
                0 => g.xo = DVec3::ZERO,                          // r = 0
                1 => g.xo = ni * 2.0,                             // x ∥ n_i
                2 => g.wi = (ni + rng.unit() * 1e-9).normalize(), // grazing to normal
                _ => {}
            }
            let s = dipole.bssrdf(&g);
            assert!(s.iter().all(|v| v.is_finite() && *v >= 0.0), "{} {source:?}: {g:?} -> {s:?}", m.name);
            let (a, b) = (dipole.bssrdf_symmetric(&g), dipole.bssrdf_symmetric(&g.swapped()));
            assert_eq!(a, b, "the symmetric form is reciprocal");
        }
    }
}

#[test]
fn the_front_and_back_lit_branches_meet_within_ten_percent_beyond_a_mean_free_path() {
    // μ₀ = −n_o·ω₁₂ crosses 0 when the exit normal turns past the refracted ray: the front-lit
    // d_r² → r² while the back-lit one is r² + (3σ′_t)⁻².
    for name in ["skin1", "marble", "skimmilk"] {
        let m = medium(name, 1.0);
        let dipole = DirectionalDipole::new(&m);
        for c in 0..3 {
            let mfp = 1.0 / m.sigma_t_prime_per_mm()[c];
            for r in [1.0, 2.0, 5.0].map(|k| k * mfp) {
                let at = |tilt: f64| {
                    let no = DVec3::new(0.0, tilt.sin(), tilt.cos());
                    let g = Geometry {
                        xi: DVec3::ZERO,
                        ni: DVec3::Z,
                        wi: DVec3::Z,
                        xo: DVec3::new(r, 0.0, 0.0),
                        no,
                        wo: no,
                    };
                    dipole.bssrdf(&g)[c]
                };
                let half_pi = std::f64::consts::FRAC_PI_2;
                let (front, back) = (at(half_pi - 1e-9), at(half_pi + 1e-9));
                let jump = (front - back).abs() / front.max(back).max(1e-300);
                assert!(jump < 0.1, "{name} channel {c} r {r:.3} mm: front {front:e} back {back:e}");
            }
        }
    }
}

/// π ∫ S dA over a flat half-space at normal incidence and exit (η = 1): the total diffuse
/// reflectance a path tracer measures with a radiance meter looking straight down.
fn planar_albedo(s: impl Fn(f64) -> f64, sigma_tr: f64) -> f64 {
    radial_integral(s, sigma_tr, 20000)
}

/// π ∫ s(r) 2πr dr over the half-line on `n` points, r = u/(1 − u) · L (dense near 0), L the
/// diffusion length 1/σ_tr.
fn radial_integral(s: impl Fn(f64) -> f64, sigma_tr: f64, n: usize) -> f64 {
    let l = 1.0 / sigma_tr.max(0.05);
    let mut sum = 0.0;
    for k in 0..n {
        let u = (k as f64 + 0.5) / n as f64;
        let r = u / (1.0 - u) * l;
        let dr_du = l / ((1.0 - u) * (1.0 - u));
        sum += s(r) * 2.0 * PI * r * dr_du / n as f64;
    }
    PI * sum
}

#[test]
fn half_space_energy_against_the_path_tracer() {
    let text = std::fs::read_to_string(concat!(env!("CARGO_MANIFEST_DIR"), "/../data/reference/slab_albedo.json"))
        .expect("data/reference/slab_albedo.json");
    let reference: serde_json::Value = serde_json::from_str(&text).expect("json");
    let mut failures = Vec::new();
    for (name, entry) in reference["media"].as_object().expect("media") {
        let m = medium(name, 1.0);
        let dipole = DirectionalDipole::new(&m);
        let corrected = DirectionalDipole::with_source(&m, DipoleSource::MeanFreePath);
        let standard = standard_dipole_profiles(&m);
        for c in 0..3 {
            let mc = entry["reflectance"][c].as_f64().expect("reflectance");
            let at = Geometry::planar;
            let sigma_tr = dipole.channels[c].sigma_tr;
            let dir = planar_albedo(|r| dipole.bssrdf(&at(r))[c], sigma_tr);
            let mfp = planar_albedo(|r| corrected.bssrdf(&at(r))[c], sigma_tr);
            let std = planar_albedo(|r| standard_dipole_bssrdf(&standard, 1.0, &at(r))[c], sigma_tr);
            eprintln!(
                "{name} {c}: path tracer {mc:.4}, directional {dir:.4} ({:.2}×), with the mean-free-path source \
                 {mfp:.4} ({:.2}×), standard {std:.4}",
                dir / mc,
                mfp / mc
            );
            // Measured (docs/BENCHMARKS.md): the standard dipole is within 10% of the path tracer
            // where scattering dominates (α′ > 0.9); the directional dipole as published
            // overshoots there, by 1.3× (marble, skim milk) to 1.6× (skin1's red), and far more
            // as α′ falls. The bands below pin those findings, so a change in either shows.
            let alpha = m.reduced_albedo()[c];
            // The corrected source (power α′, the real source at the mean free path's depth):
            // measured 0.81-0.95× of the radiance meter's where α′ > 0.6 (its own share of the
            // total below, against the exact hemispherical albedo, at every incidence); where
            // α′ < 0.1 (ketchup's green and blue, reflectances under 0.01) diffusion has little
            // to say.
            if alpha > 0.6 && !(0.8 * mc..1.0 * mc).contains(&mfp) {
                failures.push(format!("{name} channel {c}: corrected directional {mfp} vs path tracer {mc}"));
            }
            if alpha > 0.9 {
                if (std - mc).abs() >= 0.1 * mc {
                    failures.push(format!("{name} channel {c}: standard {std} vs path tracer {mc}"));
                }
                if !(1.1 * mc..1.8 * mc).contains(&dir) {
                    failures.push(format!("{name} channel {c}: directional {dir} vs path tracer {mc}"));
                }
            }
            assert!(dir.is_finite() && mfp.is_finite() && std.is_finite() && dir > 0.0 && mfp > 0.0);
        }
    }
    assert!(failures.is_empty(), "{failures:#?}");
}

/// π ∫ S dA over a flat half-space lit from `mu0` (η = 1, so the exit direction does not matter):
/// the directional-hemispherical albedo, integrated over the plane in polar coordinates.
fn oblique_albedo(dipole: &DirectionalDipole, c: usize, mu0: f64) -> f64 {
    let wi = DVec3::new((1.0 - mu0 * mu0).sqrt(), 0.0, mu0);
    let n_phi = 96;
    // The exit point's angle averaged at each radius.
    let around = |r: f64| {
        (0..n_phi)
            .map(|j| {
                let phi = (j as f64 + 0.5) / n_phi as f64 * 2.0 * PI;
                let g = Geometry { wi, xo: DVec3::new(r * phi.cos(), r * phi.sin(), 0.0), ..Geometry::planar(0.0) };
                dipole.bssrdf(&g)[c]
            })
            .sum::<f64>()
            / n_phi as f64
    };
    radial_integral(around, dipole.channels[c].sigma_tr, 600)
}

/// The published model's excess holds at every incidence (1.3-2.2×), and the corrected source
/// keeps its total near the exact half-space's at every incidence: the exact directional-
/// hemispherical albedo 1 − H(μ₀)√(1 − α′) of an isotropic half-space at η = 1
/// (`half_space::HalfSpace`, Chandrasekhar's H). Putting the real source a mean free path away
/// whatever the light's angle (d_r² = r² + σ′t⁻²) was right at normal incidence and 0.3-0.5× at
/// grazing incidence: the depth must follow μ₀.
#[test]
fn the_corrected_source_keeps_the_half_space_s_energy_at_every_incidence() {
    let mut failures = Vec::new();
    for (name, channels) in [("marble", &[0usize, 2][..]), ("skimmilk", &[0]), ("skin1", &[0, 1, 2]), ("ketchup", &[0])]
    {
        let m = medium(name, 1.0);
        let (published, corrected) =
            (DirectionalDipole::new(&m), DirectionalDipole::with_source(&m, DipoleSource::MeanFreePath));
        for &c in channels {
            let alpha = m.reduced_albedo()[c];
            let exact = rouge_render::half_space::HalfSpace::new(alpha);
            for mu0 in [1.0, 0.7, 0.4, 0.15] {
                let want = exact.directional_reflectance(mu0);
                let (p, k) = (oblique_albedo(&published, c, mu0) / want, oblique_albedo(&corrected, c, mu0) / want);
                eprintln!("{name} {c} (α′ {alpha:.3}) μ₀ {mu0}: published {p:.3}×, corrected {k:.3}× of {want:.4}");
                // Measured: the corrected 0.91-0.99× where α′ ≥ 0.95, down to 0.71× at normal
                // incidence as α′ falls to 0.68 (diffusion's deficit at low albedo); published
                // 1.29-2.18×.
                let band = if alpha >= 0.95 { 0.88..1.05 } else { 0.65..1.1 };
                if !band.contains(&k) || p < 1.25 {
                    failures.push(format!("{name} {c} μ₀ {mu0}: published {p:.3}×, corrected {k:.3}×"));
                }
            }
        }
    }
    assert!(failures.is_empty(), "{failures:#?}");
}
