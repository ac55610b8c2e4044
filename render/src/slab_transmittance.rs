//! The light a plane slab lets through, exactly: the law of the `slab` subsurface model
//! ([`crate::scene::SubsurfaceModel::Slab`]), which lights a thin part of the mesh from behind
//! as the slab of its local thickness would be.
//!
//! A slab of reduced optical thickness τ = (σa + σs′)·d and reduced albedo α′ = σs′/(σa + σs′)
//! (isotropic scattering, the media's similarity-relation form), index-matched on both faces
//! (η = 1, as the references of docs/TRANSLUCENCY.md), lit on its far face by collimated light of
//! irradiance E (at normal incidence) arriving at cosine μ_l to that face's normal, sends toward
//! the exit cosine μ_v the scattered radiance
//!
//! ```text
//! L = E · μ_l · T(μ_v, μ_l; α′, τ) / π,   T = T₁ + T_m
//! ```
//!
//! - T₁, light scattered once, in closed form (\[Chandrasekhar1960\] ch. 1, the transmitted
//!   intensity of once-scattered light): α′/4 · (e^{−τ/μ_l} − e^{−τ/μ_v})/(μ_l − μ_v), and
//!   α′/4 · τe^{−τ/μ}/μ² where the cosines meet ([`single_scattering`]).
//! - T_m, every higher order, from adding-doubling (\[Prahl1993\], iadpython 0.5.3):
//!   `python/gen_slab_transmittance.py` writes `data/reference/slab_transmittance.json`, the
//!   grid of G = T_m · e^{κτ} over 25 albedos even in t = (1 − α′)^¼, 32 thicknesses even in
//!   ln(1 + τ) up to τ = 256, and 9 × 9 cosines even in [0, 1]. κ(α′) is Case's discrete
//!   eigenvalue ([`kappa`]), the slowest decay of transport with depth, so G varies slowly and
//!   interpolates linearly: quadrilinear here; the renderer interpolates the albedo once per
//!   medium on the CPU ([`medium_values`]) and the other three axes per pixel
//!   (`shaders/slab.wgsl`), which is the same sum.
//!
//! Accuracy, on the 240 points off the grid the script computes independently (24 quadrature
//! angles, other nodes): within the figures of docs/BENCHMARKS.md ("The slab law"), worst for
//! slabs under 0.2 mean free paths at grazing cosines; `render/tests/slab_transmittance.rs`.
//!
//! Domain: 0 ≤ α′ ≤ 1, τ ≥ 0 (beyond τ = 256 G is held at its last node: an upper bound where
//! the light left is below 10⁻⁶ for every medium of data/media/), 0 ≤ μ ≤ 1; anything else, NaN
//! included, is an error that names the value. The unscattered beam is not in T: a directional
//! light seen through the slab is a delta the camera does not see.

use crate::diffusion::{ChannelProfile, ProfileModel, medium_profiles};
use crate::error::{RenderError, Result};
use rouge_model::medium::Medium;
use std::sync::OnceLock;

/// The table's axes, as the shader indexes it: albedo (t), thickness (ln(1 + τ)), μ_v, μ_l.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Axes {
    /// Albedo nodes, even in t = (1 − α′)^¼.
    pub albedos: usize,
    /// Thickness nodes, even in ln(1 + τ).
    pub taus: usize,
    /// Cosine nodes, even in [0, 1], on both cosine axes.
    pub mus: usize,
    /// The last thickness node's τ.
    pub tau_max: f64,
}

/// One point of the adding-doubling reference off the grid.
#[derive(Clone, Debug, serde::Deserialize)]
pub struct SlabPoint {
    /// Reduced albedo α′.
    pub albedo: f64,
    /// Reduced optical thickness τ.
    pub tau: f64,
    /// Exit cosine.
    pub mu_v: f64,
    /// Incidence cosine.
    pub mu_l: f64,
    /// T(μ_v, μ_l; α′, τ), scattered light only.
    pub t: f64,
}

#[derive(serde::Deserialize)]
struct Reference {
    albedo_nodes: usize,
    tau_nodes: usize,
    tau_max: f64,
    mu_nodes: usize,
    kappa: Vec<f64>,
    g: Vec<f64>,
    check: Vec<SlabPoint>,
}

/// The shader's twin of [`transmittance`] (`shaders/slab.wgsl`, `//#insert slab`): it reads the
/// table from a storage array `slab_table` the including shader declares.
pub const WGSL: &str = include_str!("shaders/slab.wgsl");

const REFERENCE_JSON: &str = include_str!("../../data/reference/slab_transmittance.json");
const FILE: &str = "data/reference/slab_transmittance.json";

/// The table unfolded: `g[((a · taus + k) · mus + v) · mus + l]`.
struct Table {
    axes: Axes,
    g: Vec<f32>,
}

fn load() -> std::result::Result<Table, String> {
    let r: Reference = serde_json::from_str(REFERENCE_JSON).map_err(|e| e.to_string())?;
    let (a, n, m) = (r.albedo_nodes, r.tau_nodes, r.mu_nodes);
    let upper = m * (m + 1) / 2;
    if a < 2 || n < 2 || m < 2 || r.g.len() != a * n * upper || r.kappa.len() != a {
        return Err(format!("{} values for {a} albedos × {n} thicknesses × {upper} cosine pairs", r.g.len()));
    }
    if let Some(i) = r.g.iter().position(|v| !v.is_finite()) {
        return Err(format!("value {i} is not finite"));
    }
    // The file's κ per node is the script's; ours must be the same function.
    for (i, k) in r.kappa.iter().enumerate() {
        let t = i as f64 / (a - 1) as f64;
        let ours = kappa(1.0 - t.powi(4));
        if (k - ours).abs() > 1e-9 {
            return Err(format!("κ at albedo node {i} is {k}, this module's {ours}"));
        }
    }
    let mut g = vec![0.0f32; a * n * m * m];
    for (block, values) in r.g.chunks(upper).enumerate() {
        let mut pair = values.iter();
        for v in 0..m {
            for l in v..m {
                let x = *pair.next().expect("the chunk holds the upper triangle") as f32;
                g[(block * m + v) * m + l] = x;
                g[(block * m + l) * m + v] = x;
            }
        }
    }
    Ok(Table { axes: Axes { albedos: a, taus: n, mus: m, tau_max: r.tau_max }, g })
}

fn table() -> Result<&'static Table> {
    static TABLE: OnceLock<std::result::Result<Table, String>> = OnceLock::new();
    TABLE.get_or_init(load).as_ref().map_err(|e| RenderError::Invalid(format!("{FILE}: {e}")))
}

/// The reference's points off the grid, on which the interpolation is judged.
///
/// # Errors
/// [`RenderError::Invalid`] if the compiled-in file does not parse.
pub fn held_out_points() -> Result<Vec<SlabPoint>> {
    serde_json::from_str::<Reference>(REFERENCE_JSON)
        .map(|r| r.check)
        .map_err(|e| RenderError::Invalid(format!("{FILE}: {e}")))
}

/// The table's axes.
///
/// # Errors
/// [`RenderError::Invalid`] if the compiled-in table is malformed.
pub fn axes() -> Result<Axes> {
    Ok(table()?.axes)
}

/// The grid at one medium's three reduced albedos, as the shader reads it:
/// `[channel][thickness][μ_v][μ_l]`, each channel's block interpolated linearly in t between the
/// albedo nodes around it (the first of [`transmittance`]'s four interpolations, so the shader's
/// remaining three give the same value).
///
/// # Errors
/// [`RenderError::Invalid`] naming an albedo outside [0, 1], or a malformed table.
pub fn medium_values(alpha_prime: [f64; 3]) -> Result<Vec<f32>> {
    let t = table()?;
    let ax = t.axes;
    let block = ax.taus * ax.mus * ax.mus;
    let mut out = Vec::with_capacity(3 * block);
    for a in alpha_prime {
        check("albedo", a, (0.0..=1.0).contains(&a), "is outside [0, 1]")?;
        let (ia, fa) = cell((1.0 - a).powf(0.25), ax.albedos);
        let (lo, hi) = (&t.g[ia * block..(ia + 1) * block], &t.g[(ia + 1) * block..(ia + 2) * block]);
        out.extend(lo.iter().zip(hi).map(|(l, h)| ((1.0 - fa) * *l as f64 + fa * *h as f64) as f32));
    }
    Ok(out)
}

/// Case's discrete eigenvalue of isotropic scattering at albedo α′ as a decay rate κ = 1/ν₀
/// (\[Case1967\], the dispersion relation of the discrete eigenvalue ν₀ with c = α′): the root in [0, 1) of α′/(2κ) · ln((1 + κ)/(1 − κ)) = 1, the rate per optical depth
/// at which transport decays deep in an absorbing medium (diffusion's √(3(1 − α′)) as α′ → 1).
/// 0 at α′ ≥ 1, 1 at α′ ≤ 0 (and within 10⁻¹⁵ of it below α′ ≈ 0.06). Solved for
/// u = atanh κ: u·coth u = 1/α′ is convex and increasing in u, so Newton's method from u = 1/α′
/// (above the root) falls to it monotonically, to 10⁻¹⁴ relative (2-24 steps; the series of
/// u·coth u − 1 below u = 0.2 keeps the cancellation out).
pub fn kappa(alpha_prime: f64) -> f64 {
    if alpha_prime >= 1.0 {
        return 0.0;
    }
    if alpha_prime <= 0.0 {
        return 1.0;
    }
    // u·coth u − 1 and its derivative; below 0.2 their Taylor series to u¹⁰ (error < 10⁻¹⁴
    // relative).
    let excess = |u: f64| {
        if u < 0.2 {
            let u2 = u * u;
            u2 * (1.0 / 3.0 + u2 * (-1.0 / 45.0 + u2 * (2.0 / 945.0 + u2 * (-1.0 / 4725.0 + u2 * 2.0 / 93555.0))))
        } else {
            u / u.tanh() - 1.0
        }
    };
    let slope = |u: f64| {
        if u < 0.2 {
            let u2 = u * u;
            u * (2.0 / 3.0 + u2 * (-4.0 / 45.0 + u2 * (12.0 / 945.0 + u2 * (-8.0 / 4725.0 + u2 * 20.0 / 93555.0))))
        } else {
            let t = u.tanh();
            (t - u * (1.0 - t * t)) / (t * t)
        }
    };
    let target = 1.0 / alpha_prime - 1.0;
    let mut u = 1.0 / alpha_prime;
    for _ in 0..100 {
        let next = u - (excess(u) - target) / slope(u);
        if !(next.is_finite() && next > 0.0) {
            break;
        }
        if (next - u).abs() <= 1e-14 * u {
            return next.tanh();
        }
        u = next;
    }
    u.tanh()
}

/// T₁: the once-scattered share of T in closed form (see the module's doc). 0 at a cosine of 0.
pub fn single_scattering(alpha_prime: f64, tau: f64, mu_v: f64, mu_l: f64) -> f64 {
    if mu_v <= 0.0 || mu_l <= 0.0 {
        return 0.0;
    }
    let (ev, el) = ((-tau / mu_v).exp(), (-tau / mu_l).exp());
    let d = mu_l - mu_v;
    let t = if d.abs() < 1e-6 * mu_v.max(mu_l) {
        // The limit, with the first-order term of the difference kept.
        let mu = 0.5 * (mu_v + mu_l);
        tau * (-tau / mu).exp() / (mu * mu)
    } else {
        (el - ev) / d
    };
    alpha_prime / 4.0 * t
}

fn check(what: &str, value: f64, ok: bool, rule: &str) -> Result<()> {
    if ok { Ok(()) } else { Err(RenderError::Invalid(format!("slab transmittance: {what} {value} {rule}"))) }
}

/// The node below `x` ∈ [0, 1] on `n` even nodes and the weight of the one above.
fn cell(x: f64, n: usize) -> (usize, f64) {
    let s = x.clamp(0.0, 1.0) * (n - 1) as f64;
    let i = (s.floor() as usize).min(n - 2);
    (i, s - i as f64)
}

/// T(μ_v, μ_l; α′, τ), the scattered transmission (see the module's doc): T₁ exactly, T_m from
/// the table, quadrilinear as the shader.
///
/// # Errors
/// [`RenderError::Invalid`] naming the value outside the domain.
pub fn transmittance(alpha_prime: f64, tau: f64, mu_v: f64, mu_l: f64) -> Result<f64> {
    check("albedo", alpha_prime, (0.0..=1.0).contains(&alpha_prime), "is outside [0, 1]")?;
    check("optical thickness", tau, tau >= 0.0 && tau.is_finite(), "must be finite and ≥ 0")?;
    check("exit cosine", mu_v, (0.0..=1.0).contains(&mu_v), "is outside [0, 1]")?;
    check("incidence cosine", mu_l, (0.0..=1.0).contains(&mu_l), "is outside [0, 1]")?;
    let t = table()?;
    let ax = t.axes;
    let (ia, fa) = cell((1.0 - alpha_prime).powf(0.25), ax.albedos);
    let (ik, fk) = cell(tau.ln_1p() / ax.tau_max.ln_1p(), ax.taus);
    let (iv, fv) = cell(mu_v, ax.mus);
    let (il, fl) = cell(mu_l, ax.mus);
    let mut g = 0.0;
    for (da, wa) in [(0, 1.0 - fa), (1, fa)] {
        for (dk, wk) in [(0, 1.0 - fk), (1, fk)] {
            for (dv, wv) in [(0, 1.0 - fv), (1, fv)] {
                for (dl, wl) in [(0, 1.0 - fl), (1, fl)] {
                    let i = (((ia + da) * ax.taus + ik + dk) * ax.mus + iv + dv) * ax.mus + il + dl;
                    g += wa * wk * wv * wl * t.g[i] as f64;
                }
            }
        }
    }
    Ok(single_scattering(alpha_prime, tau, mu_v, mu_l) + g * (-kappa(alpha_prime) * tau).exp())
}

/// Samples per pixel and light of the hidden-entry gather.
pub const HIDDEN_ENTRY_SAMPLES: u32 = 32;
/// Samples per pixel and light of the transmission gather ([`crate::scene::SlabThrough::Gather`]):
/// all the light a pixel facing away from the light gets comes from them, and its spiral turns
/// per point, so fewer leave noise that costs the score (the backlit hand, mean ΔE2000 at 32 /
/// 64 / 128 / 256 samples: 2.26 / 2.20 / 2.17 / 2.16; docs/BENCHMARKS.md).
pub const TRANSMISSION_GATHER_SAMPLES: u32 = 128;
/// The gather's reach in diffusion lengths 1/σ_tr of the medium's most penetrating channel: the
/// dipole there has fallen to e^{−4} of its near-field share.
pub const HIDDEN_ENTRY_REACH_LENGTHS: f64 = 4.0;
/// The most the gather reaches (mm), for media that barely absorb (σ_tr → 0). The media here
/// reach at most 74 mm (skim milk's red); capped at 20 mm the skim-milk sphere scored 2.56 ΔE,
/// at 40 mm 2.35, at 80 mm 2.31 (docs/BENCHMARKS.md).
pub const HIDDEN_ENTRY_MAX_REACH_MM: f64 = 80.0;

/// The hidden-entry gather's constants for `medium` (shaders/thickness.wgsl `hidden_entry`, run
/// with the slab law): the classic dipole per channel (α′, σ_tr, z_r, z_v), and (η, reach mm,
/// `samples` per pixel and light, the radii's sampling rate mm⁻¹). The gather takes the light that entered the mesh
/// near a pixel on faces the camera does not see, and on faces it sees that the screen-space
/// kernel does not carry (beyond its reach or depth, or all of them where no kernel runs) or
/// undercounts (by the view's cosine), beyond what the lighting pass's law already assumed
/// there (the pixel's own irradiance all around), from the light's shadow map.
///
/// The dipole's prefactor α′ is scaled by [`hidden_entry_albedo_scale`], so that R(r)'s total is
/// the medium's exact albedo, as the kernel's is (issue 31 item 1).
pub fn hidden_entry_constants(medium: &Medium, samples: u32) -> ([[f32; 4]; 3], [f32; 4]) {
    let profiles = medium_profiles(medium, ProfileModel::ClassicDipole);
    let scale = hidden_entry_albedo_scale(medium, &profiles);
    let constants: [[f32; 4]; 3] = std::array::from_fn(|c| {
        let mut k = profiles[c].classic_constants();
        k[0] *= scale[c];
        k.map(|v| v as f32)
    });
    let sigma_tr = profiles.iter().map(|p| p.classic_constants()[1]).fold(f64::INFINITY, f64::min);
    let reach = (HIDDEN_ENTRY_REACH_LENGTHS / sigma_tr).min(HIDDEN_ENTRY_MAX_REACH_MM);
    let rate = sigma_tr.max(HIDDEN_ENTRY_REACH_LENGTHS / reach);
    (constants, [medium.eta as f32, reach as f32, samples as f32, rate as f32])
}

/// Per channel, the medium's exact albedo (its half-space's reflectance at normal incidence by
/// adding-doubling, [`crate::dielectric_half_space::medium_normal_reflectance`], the albedo the
/// lighting pass and the kernel use) over the total Rd of `classic`, the medium's classic
/// dipole ([`medium_profiles`]): the factor that closes the dipole's albedo gap (short by 15-37%
/// for ketchup at η = 1, under 1% for marble and skim milk; docs/BENCHMARKS.md). 1 where the
/// table does not reach the medium or Rd is 0.
pub fn hidden_entry_albedo_scale(medium: &Medium, classic: &[ChannelProfile; 3]) -> [f64; 3] {
    let exact = crate::dielectric_half_space::medium_normal_reflectance(medium);
    std::array::from_fn(|c| {
        let rd = classic[c].total();
        match exact[c] {
            Some(albedo) if rd > 0.0 => albedo / rd,
            _ => 1.0,
        }
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_gather_s_dipole_totals_the_exact_albedo() {
        for (name, lo, hi) in [("ketchup", 1.1, 1.7), ("marble", 1.0, 1.01), ("skimmilk", 1.0, 1.01)] {
            let medium = Medium::builtin(name).expect("built in").with_eta(1.0).expect("η 1");
            let scale = hidden_entry_albedo_scale(&medium, &medium_profiles(&medium, ProfileModel::ClassicDipole));
            eprintln!("{name}: {scale:?}");
            assert!(scale.iter().all(|s| (lo..hi).contains(s)), "{name}: {scale:?}");
        }
        // The constants carry it in the prefactor α′.
        let medium = Medium::builtin("ketchup").expect("ketchup").with_eta(1.0).expect("η 1");
        let (k, _) = hidden_entry_constants(&medium, HIDDEN_ENTRY_SAMPLES);
        let alpha = medium.reduced_albedo();
        let scale = hidden_entry_albedo_scale(&medium, &medium_profiles(&medium, ProfileModel::ClassicDipole));
        for c in 0..3 {
            assert!((k[c][0] as f64 / (alpha[c] * scale[c]) - 1.0).abs() < 1e-6);
        }
    }

    #[test]
    fn the_table_loads_and_its_kappa_is_this_module_s() {
        let ax = axes().expect("table");
        assert_eq!(table().expect("table").g.len(), ax.albedos * ax.taus * ax.mus * ax.mus);
        let medium = medium_values([1.0, 0.5, 0.0]).expect("in the domain");
        assert_eq!(medium.len(), 3 * ax.taus * ax.mus * ax.mus);
        assert!(medium_values([0.5, f64::NAN, 0.5]).is_err());
    }

    #[test]
    fn kappa_meets_diffusion_near_albedo_one_and_its_equation_everywhere() {
        for a in [1e-3, 0.1, 0.5, 0.9, 0.99, 0.9999] {
            let k = kappa(a);
            let lhs = a / (2.0 * k) * ((1.0 + k) / (1.0 - k)).ln();
            // Below α′ ≈ 0.15, 1 − κ ≈ 2e^{−2/α′} < 10⁻⁶ and f64 resolves the equation no better.
            assert!((lhs - 1.0).abs() < 1e-9 || k > 1.0 - 1e-6, "α′ {a}: κ {k}, lhs {lhs}");
        }
        let a: f64 = 0.9999;
        assert!((kappa(a) / (3.0 * (1.0 - a)).sqrt() - 1.0).abs() < 1e-3);
    }

    #[test]
    fn outside_the_domain_is_an_error_naming_the_value() {
        for (a, tau, mv, ml, word) in [
            (f64::NAN, 1.0, 0.5, 0.5, "albedo"),
            (0.5, -1.0, 0.5, 0.5, "optical thickness"),
            (0.5, f64::INFINITY, 0.5, 0.5, "optical thickness"),
            (0.5, 1.0, 1.5, 0.5, "exit cosine"),
            (0.5, 1.0, 0.5, f64::NAN, "incidence cosine"),
        ] {
            let e = transmittance(a, tau, mv, ml).expect_err("outside").to_string();
            assert!(e.contains(word), "{e}");
        }
    }
}
