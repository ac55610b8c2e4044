//! Single scattering along the view ray through the mesh: the slab law's once-scattered light
//! where the mesh is not a plane slab (shaders/slab_march.wgsl, whose CPU twin this is).
//!
//! The slab law ([`crate::slab_transmittance`]) takes the light scattered once, T₁, in closed
//! form for a plane slab. Near a lit side face (a wedge's top face, a finger's rim) the camera's
//! ray passes through the beam entering that face a few millimetres from the exit point, and the
//! plane's T₁, whose slab is the one plane the light entered, misses it (docs/BENCHMARKS.md "The
//! slab's side faces": the ketchup wedge's top rows, path tracer 0.118, the law 0.034, single
//! scattering alone 0.081). Marched along the refracted view ray from the exit point to where
//! the ray leaves the mesh (the back-face depth pass, `passes/back_depth.rs`), with the light's
//! path to each point read from its shadow map, it is \[Jensen2001\]'s L⁽¹⁾ (eq. 4):
//!
//! ```text
//! L₁ = E/π · T_F(μ_v)·T_F(μ_l)/η² · σs′/4 · ∫₀^{c′} e^{−σt′(s + ℓ′(s))} ds
//! ```
//!
//! s along the refracted view ray, c′ = c·μ_v/ν_v the chord c of the camera's ray taken to the
//! same depth below the exit face, ℓ′ = ℓ·μ_l/ν_l the straight path ℓ of the light from the map
//! taken to the refracted one (\[Jensen2001\]'s s′ᵢ, exact below a plane entry face), ν the
//! refracted cosines (isotropic scattering, the media's similarity-relation form). A point the
//! light reaches without crossing the mesh is outside it and adds nothing. In a plane slab it is
//! T₁'s unreflected share exactly (the test below): `μ_l·T₁ = σs′/4 · ∫`, per unit E/π.
//!
//! The integral is sampled at [`VIEW_MARCH_SAMPLES`] stratified points, distributed as
//! e^{−k s} with k = σt′_min·(1 − a/ν_l), a = the refracted view ray's cosine toward the face the
//! light entered (ν_v in a plane slab, 0 where that face is a side face at right angles): the
//! integrand below that face in the channel that reaches deepest, so that in a plane that channel
//! is exact at any count (k may be negative: a grazing light makes the deeper points brighter).
//!
//! Domain: σt′ > 0 and finite, c ≥ 0, 0 < ν ≤ 1. Exact at η = 1 for a convex part whose light
//! map and back-face depth are exact; at η ≠ 1 the refracted paths are a plane's. Light reflected
//! once inside (T₁'s reflected paths, at η ≠ 1) stays with the law.

/// Points per pixel and light of the march (shaders/slab_march.wgsl `VIEW_MARCH_SAMPLES`).
pub const VIEW_MARCH_SAMPLES: usize = 16;

/// The largest |k·c| the sampling takes (beyond it e^{k c} leaves f32): k is held there.
const MAX_DECAYS: f64 = 60.0;

/// The sampling's decay rate k (mm⁻¹) for extinctions `sigma_t_per_mm`, the view ray's cosine
/// `approach` toward the entry face and the light's refracted cosine `nu_l` there, held so that
/// |k·c| ≤ 60 over a chord `chord_mm`.
pub fn sampling_rate_per_mm(sigma_t_per_mm: [f64; 3], approach: f64, nu_l: f64, chord_mm: f64) -> f64 {
    let sigma = sigma_t_per_mm.iter().copied().fold(f64::INFINITY, f64::min);
    let k = sigma * (1.0 - approach / nu_l.max(1e-4));
    let limit = MAX_DECAYS / chord_mm.max(1e-6);
    k.clamp(-limit, limit)
}

/// ∫₀^{c′} e^{−σt′(s + ℓ′(s))} ds per channel (mm), sampled as the shader does: `light_path_mm`
/// gives ℓ′ at s, or `None` where the point is outside the mesh (it adds nothing).
pub fn view_march(
    sigma_t_per_mm: [f64; 3],
    rate_per_mm: f64,
    chord_mm: f64,
    light_path_mm: impl Fn(f64) -> Option<f64>,
) -> [f64; 3] {
    let c = chord_mm.max(0.0);
    let k = rate_per_mm;
    let mut sum = [0.0; 3];
    for j in 0..VIEW_MARCH_SAMPLES {
        let u = (j as f64 + 0.5) / VIEW_MARCH_SAMPLES as f64;
        // s distributed as e^{−ks} on [0, c], and 1/p(s).
        let (s, inv_p) = if (k * c).abs() < 1e-3 {
            (u * c, c)
        } else {
            let span = -(-k * c).exp_m1();
            let s = -(-u * span).ln_1p() / k;
            (s, span / (k * (-k * s).exp()))
        };
        if let Some(l) = light_path_mm(s) {
            for (ch, total) in sum.iter_mut().enumerate() {
                *total += (-sigma_t_per_mm[ch] * (s + l)).exp() * inv_p;
            }
        }
    }
    sum.map(|t| t / VIEW_MARCH_SAMPLES as f64)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::slab_transmittance::single_scattering;

    /// A plane slab of thickness `d` (mm) seen at μ_v and lit at μ_l (η = 1): the march against
    /// the closed form μ_l·T₁ = σs′/4 · ∫, per channel.
    fn plane(sigma_a: [f64; 3], sigma_s: [f64; 3], d: f64, mu_v: f64, mu_l: f64) -> f64 {
        let sigma_t: [f64; 3] = std::array::from_fn(|c| sigma_a[c] + sigma_s[c]);
        let chord = d / mu_v;
        let k = sampling_rate_per_mm(sigma_t, mu_v, mu_l, chord);
        let got = view_march(sigma_t, k, chord, |s| Some((d - s * mu_v) / mu_l));
        let mut worst = 0.0f64;
        for c in 0..3 {
            let alpha = sigma_s[c] / sigma_t[c];
            let want = mu_l * single_scattering(alpha, 1.0, sigma_t[c] * d, mu_v, mu_l);
            let march = sigma_s[c] / 4.0 * got[c];
            assert!(march.is_finite() && march >= 0.0, "{march}");
            // Relative, against a floor of 10⁻⁶ of a thin slab's α′/4 (where the light is gone,
            // held sampling rates may miss a value that small by more).
            worst = worst.max((march - want).abs() / want.max(1e-6 * alpha / 4.0));
        }
        worst
    }

    #[test]
    fn in_a_plane_slab_the_march_is_the_closed_form() {
        // Ketchup, skim milk and marble (data/media), thin to thick, normal to grazing, light
        // more grazing than the view and less.
        let media = [
            ([0.061, 0.97, 1.45], [0.18, 0.07, 0.03]),
            ([0.0014, 0.0025, 0.0142], [0.70, 1.22, 1.90]),
            ([0.0021, 0.0041, 0.0071], [2.19, 2.62, 3.00]),
        ];
        let mut worst = 0.0f64;
        for (sa, ss) in media {
            for d in [0.3, 2.0, 8.0, 15.0] {
                for (mu_v, mu_l) in [(1.0, 1.0), (0.95, 0.3), (0.3, 0.95), (0.6, 0.61), (1.0, 0.05)] {
                    worst = worst.max(plane(sa, ss, d, mu_v, mu_l));
                }
            }
        }
        // The channel that reaches deepest is exact; the others are sampled 16 times off their
        // own decay (measured: 0.69% at worst, ketchup's blue 15 mm deep at μ_l 0.05).
        assert!(worst < 0.01, "worst relative error {worst}");
    }

    #[test]
    fn points_outside_the_mesh_add_nothing_and_a_zero_chord_is_zero() {
        let sigma_t = [1.0, 2.0, 3.0];
        let k = sampling_rate_per_mm(sigma_t, 1.0, 0.5, 4.0);
        assert_eq!(view_march(sigma_t, k, 4.0, |_| None), [0.0; 3]);
        assert_eq!(view_march(sigma_t, k, 0.0, |_| Some(1.0)), [0.0; 3]);
        // Half the ray outside: less than the whole, more than nothing.
        let half = view_march(sigma_t, k, 4.0, |s| (s < 2.0).then_some(1.0));
        let whole = view_march(sigma_t, k, 4.0, |_| Some(1.0));
        assert!((0..3).all(|c| half[c] > 0.0 && half[c] < whole[c]), "{half:?} {whole:?}");
    }

    #[test]
    fn the_sampling_rate_stays_within_f32_over_any_chord() {
        for chord in [1e-9, 0.1, 10.0, 1e6] {
            for (nu_v, nu_l) in [(1.0, 1e-4), (1e-4, 1.0), (0.5, 0.5)] {
                let k = sampling_rate_per_mm([1e3, 2e3, 3e3], nu_v, nu_l, chord);
                assert!(k.is_finite() && (k * chord.max(1e-6)).abs() <= MAX_DECAYS + 1e-9, "{k} {chord}");
                let got = view_march([1e3, 2e3, 3e3], k, chord, |_| Some(0.0));
                assert!(got.iter().all(|g| g.is_finite() && *g >= 0.0), "{got:?}");
            }
        }
    }
}
