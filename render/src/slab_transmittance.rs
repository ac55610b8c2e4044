//! The light a plane slab lets through, exactly: the law of the `slab` subsurface model
//! ([`crate::scene::SubsurfaceModel::Slab`]), which lights a thin part of the mesh from behind
//! as the slab of its local thickness would be.
//!
//! A slab of reduced optical thickness τ = (σa + σs′)·d and reduced albedo α′ = σs′/(σa + σs′)
//! (isotropic scattering, the media's similarity-relation form), under a smooth boundary of
//! relative index η on both faces (air outside; η = 1 is index-matched, as the references of
//! docs/TRANSLUCENCY.md), lit on its far face by collimated light of irradiance E (at normal
//! incidence) arriving at the external cosine μ_l to that face's normal, sends toward the external
//! exit cosine μ_v the scattered radiance
//!
//! ```text
//! L = E · μ_l · T(μ_v, μ_l; α′, τ, η) / π,   T = T₁ + T_m
//! ```
//!
//! - T₁, light scattered once, in closed form ([`single_scattering`]): it enters through the
//!   face (Fresnel transmittance T_F(μ_l)), refracts to ν = √(1 − (1 − μ²)/η²), scatters once
//!   (\[Chandrasekhar1960\] ch. 1, the transmitted intensity of once-scattered light:
//!   α′/4 · (e^{−τ/ν_l} − e^{−τ/ν_v})/(ν_l − ν_v), and α′/4 · τe^{−τ/ν}/ν² where the cosines
//!   meet) and leaves (T_F(μ_v), and 1/η² as the radiance's solid angle widens):
//!   T₁ = T_F(μ_v)·T_F(μ_l)·(T₁ᵢₙ(ν_v, ν_l) + T₁ᵣ)/η². T₁ᵣ holds the two once-scattered paths that
//!   meet one internal reflection (the beam reflected by the exit face, F(μ_l), then scattered
//!   back toward it; the light scattered toward the entry face and reflected there, F(μ_v)):
//!   α′/4 · (1 − e^{−τ(1/ν_v + 1/ν_l)})/(ν_v + ν_l) · (F(μ_l)e^{−τ/ν_l} + F(μ_v)e^{−τ/ν_v}). At
//!   η = 1, ν = μ, T_F = 1 and F = 0.
//! - T_m, every higher order and every internal reflection, from adding-doubling
//!   (\[Prahl1993\], iadpython 0.5.3, its matrices over internal cosines taken to external ones):
//!   `python/gen_slab_transmittance.py` writes `data/reference/slab_transmittance.json`, the
//!   grid of G = T_m · e^{κτ}/(T_F(μ_v)·T_F(μ_l)) over 7 η even in √(η − 1) from 1 to 1.6,
//!   25 albedos even in t = (1 − α′)^¼, 32 thicknesses even in ln(1 + τ) up to τ = 256, and
//!   9 × 9 external cosines even in [0, 1]. κ(α′) is Case's discrete eigenvalue ([`kappa`]), the
//!   slowest decay of transport with depth, and the faces' transmittances fall steeply toward
//!   grazing, so with both taken out G varies slowly: Catmull-Rom in √(η − 1) (as the dielectric
//!   tables, [`crate::dielectric_half_space`]), linear in the other four axes. The renderer
//!   interpolates η and the albedo once per medium on the CPU ([`medium_values`]) and the other
//!   three axes per pixel (`shaders/slab.wgsl`), which is the same sum.
//!
//! Accuracy, on the 420 points off the grid the script computes independently (24 quadrature
//! angles, other nodes; 60 per η at η = 1, 1.05, 1.2, 1.33, 1.37, 1.44 and 1.55): within the
//! figures of docs/BENCHMARKS.md ("The slab law" and "The slab law under a dielectric
//! boundary"), worst for slabs under 0.2 mean free paths at grazing cosines and just above η = 1;
//! `render/tests/slab_transmittance.rs`.
//!
//! Domain: 0 ≤ α′ ≤ 1, 1 ≤ η ≤ 1.6 (every medium of data/media/ is at 1.3), τ ≥ 0 (beyond
//! τ = 256 G is held at its last node: an upper bound where the light left is below 10⁻⁶ for
//! every medium of data/media/), 0 ≤ μ ≤ 1; anything else, NaN included, is an error that names
//! the value. The unscattered beam is not in T: a directional light seen through the slab is a
//! delta the camera does not see.

use crate::dielectric_half_space::spline_weights;
use crate::diffusion::{ChannelProfile, ProfileModel, fresnel_dielectric, medium_profiles};
use crate::error::{RenderError, Result};
use rouge_model::medium::Medium;
use std::sync::OnceLock;

/// The table's axes, as the shader indexes it: (η and albedo, interpolated on the CPU per
/// medium), thickness (ln(1 + τ)), μ_v, μ_l.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Axes {
    /// Index nodes, even in √(η − 1) from 1 to [`Axes::eta_max`].
    pub etas: usize,
    /// The last index node's η.
    pub eta_max: f64,
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
    /// The faces' relative index η.
    pub eta: f64,
    /// Reduced albedo α′.
    pub albedo: f64,
    /// Reduced optical thickness τ.
    pub tau: f64,
    /// Exit cosine.
    pub mu_v: f64,
    /// Incidence cosine.
    pub mu_l: f64,
    /// T(μ_v, μ_l; α′, τ, η), scattered light only.
    pub t: f64,
}

#[derive(serde::Deserialize)]
struct Reference {
    etas: Vec<f64>,
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

/// The table unfolded: `g[(((e · albedos + a) · taus + k) · mus + v) · mus + l]`.
struct Table {
    axes: Axes,
    g: Vec<f32>,
}

fn load() -> std::result::Result<Table, String> {
    let r: Reference = serde_json::from_str(REFERENCE_JSON).map_err(|e| e.to_string())?;
    let (e, a, n, m) = (r.etas.len(), r.albedo_nodes, r.tau_nodes, r.mu_nodes);
    let upper = m * (m + 1) / 2;
    if e < 2 || a < 2 || n < 2 || m < 2 || r.g.len() != e * a * n * upper || r.kappa.len() != a {
        return Err(format!("{} values for {e} η × {a} albedos × {n} thicknesses × {upper} cosine pairs", r.g.len()));
    }
    let eta_max = r.etas[e - 1];
    // The nodes must be those the interpolation assumes: even in √(η − 1) from 1.
    for (i, eta) in r.etas.iter().enumerate() {
        let ours = 1.0 + (eta_max - 1.0) * (i as f64 / (e - 1) as f64).powi(2);
        if (eta - ours).abs() > 1e-9 {
            return Err(format!("η node {i} is {eta}, not {ours} (even in √(η − 1) from 1 to {eta_max})"));
        }
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
    let mut g = vec![0.0f32; e * a * n * m * m];
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
    Ok(Table { axes: Axes { etas: e, eta_max, albedos: a, taus: n, mus: m, tau_max: r.tau_max }, g })
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

/// The grid at one medium's three reduced albedos and its index η, as the shader reads it:
/// `[channel][thickness][μ_v][μ_l]`, each channel's block interpolated in η (Catmull-Rom in
/// √(η − 1)) and linearly in t between the albedo nodes around it (the first two of
/// [`transmittance`]'s interpolations, so the shader's remaining three give the same value).
///
/// # Errors
/// [`RenderError::Invalid`] naming an albedo outside [0, 1] or an η outside the table, or a
/// malformed table.
pub fn medium_values(alpha_prime: [f64; 3], eta: f64) -> Result<Vec<f32>> {
    let t = table()?;
    let ax = t.axes;
    let block = ax.taus * ax.mus * ax.mus;
    let mut out = Vec::with_capacity(3 * block);
    for a in alpha_prime {
        let mut values = vec![0.0f64; block];
        for (b, w) in block_weights(a, eta, ax)? {
            for (v, g) in values.iter_mut().zip(&t.g[b * block..(b + 1) * block]) {
                *v += w * f64::from(*g);
            }
        }
        out.extend(values.iter().map(|v| *v as f32));
    }
    Ok(out)
}

/// The (η, albedo) blocks of the table around `alpha_prime` and `eta`, as block indices
/// e·albedos + a, and their weights: Catmull-Rom in √(η − 1) times linear in t = (1 − α′)^¼,
/// the weights that are 0 (at a node, or the spline's doubled end nodes) left out. The first two
/// of [`transmittance`]'s interpolations, which [`medium_values`] does once per medium.
fn block_weights(alpha_prime: f64, eta: f64, ax: Axes) -> Result<Vec<(usize, f64)>> {
    check("albedo", alpha_prime, (0.0..=1.0).contains(&alpha_prime), "is outside [0, 1]")?;
    check("index η", eta, (1.0..=ax.eta_max).contains(&eta), &format!("is outside the table's [1, {}]", ax.eta_max))?;
    let x = ((eta - 1.0) / (ax.eta_max - 1.0)).sqrt() * (ax.etas - 1) as f64;
    let (ia, fa) = cell((1.0 - alpha_prime).powf(0.25), ax.albedos);
    Ok(spline_weights(x, ax.etas - 1)
        .into_iter()
        .filter(|(_, we)| *we != 0.0)
        .flat_map(|(e, we)| [(e * ax.albedos + ia, we * (1.0 - fa)), (e * ax.albedos + ia + 1, we * fa)])
        .collect())
}

/// The internal cosine of light refracted into index `eta` at the external cosine `mu`, held at
/// 10⁻⁴ and above as the shader's (whose f32 loses it to cancellation at grazing just above η = 1,
/// where the faces pass nothing).
fn refracted(mu: f64, eta: f64) -> f64 {
    (1.0 - (1.0 - mu * mu) / (eta * eta)).max(0.0).sqrt().max(1e-4)
}

/// The slab's faces as the light meets them: the internal cosines ν and the Fresnel
/// reflectances F of the exit (v) and the entry (l); computed once per point for T₁ and the
/// table's T_F(μ_v)·T_F(μ_l) (the shader's `SlabFaces`). At η = 1: ν = μ and F = 0, grazing
/// included.
#[derive(Clone, Copy)]
struct Faces {
    nu_v: f64,
    nu_l: f64,
    f_v: f64,
    f_l: f64,
}

impl Faces {
    fn new(eta: f64, mu_v: f64, mu_l: f64) -> Faces {
        if eta == 1.0 {
            return Faces { nu_v: mu_v, nu_l: mu_l, f_v: 0.0, f_l: 0.0 };
        }
        Faces {
            nu_v: refracted(mu_v, eta),
            nu_l: refracted(mu_l, eta),
            f_v: fresnel_dielectric(mu_v, eta),
            f_l: fresnel_dielectric(mu_l, eta),
        }
    }

    /// T_F(μ_v)·T_F(μ_l): the light's Fresnel transmittance into the slab and out of it.
    fn boundary(&self) -> f64 {
        (1.0 - self.f_v) * (1.0 - self.f_l)
    }
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

/// T₁: the once-scattered share of T in closed form (see the module's doc), at external cosines
/// under a boundary of index `eta`. 0 at a cosine of 0.
pub fn single_scattering(alpha_prime: f64, eta: f64, tau: f64, mu_v: f64, mu_l: f64) -> f64 {
    single_under(alpha_prime, eta, tau, &Faces::new(eta, mu_v, mu_l))
}

/// The share of [`single_scattering`] that meets no internal reflection,
/// T_F(μ_v)·T_F(μ_l)·T₁(ν_v, ν_l)/η² (all of it at η = 1): what the renderer marches along the
/// view ray through the mesh instead where it can ([`crate::slab_march`]).
pub fn single_unreflected(alpha_prime: f64, eta: f64, tau: f64, mu_v: f64, mu_l: f64) -> f64 {
    let faces = Faces::new(eta, mu_v, mu_l);
    if faces.nu_v <= 0.0 || faces.nu_l <= 0.0 {
        return 0.0;
    }
    faces.boundary() * single_inside(alpha_prime, tau, faces.nu_v, faces.nu_l) / (eta * eta)
}

/// [`single_scattering`] with the faces already met.
fn single_under(alpha_prime: f64, eta: f64, tau: f64, faces: &Faces) -> f64 {
    let Faces { nu_v, nu_l, f_v, f_l } = *faces;
    // A cosine of 0 (ν = μ at η = 1; at η > 1 ν ≥ 10⁻⁴ and F = 1 there, so the faces pass nothing).
    if nu_v <= 0.0 || nu_l <= 0.0 {
        return 0.0;
    }
    if eta == 1.0 {
        return single_inside(alpha_prime, tau, nu_v, nu_l);
    }
    // The two paths with one internal reflection (module doc); ν ≥ 10⁻⁴ here.
    let back = alpha_prime / 4.0 * -(-tau * (1.0 / nu_v + 1.0 / nu_l)).exp_m1() / (nu_v + nu_l);
    let reflected = back * (f_l * (-tau / nu_l).exp() + f_v * (-tau / nu_v).exp());
    faces.boundary() * (single_inside(alpha_prime, tau, nu_v, nu_l) + reflected) / (eta * eta)
}

/// Single scattering between internal cosines (\[Chandrasekhar1960\] ch. 1).
fn single_inside(alpha_prime: f64, tau: f64, mu_v: f64, mu_l: f64) -> f64 {
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

/// T(μ_v, μ_l; α′, τ, η), the scattered transmission (see the module's doc): T₁ exactly, T_m
/// from the table, Catmull-Rom in η and quadrilinear in the rest, as the renderer.
///
/// # Errors
/// [`RenderError::Invalid`] naming the value outside the domain.
pub fn transmittance(alpha_prime: f64, eta: f64, tau: f64, mu_v: f64, mu_l: f64) -> Result<f64> {
    check("albedo", alpha_prime, (0.0..=1.0).contains(&alpha_prime), "is outside [0, 1]")?;
    check("optical thickness", tau, tau >= 0.0 && tau.is_finite(), "must be finite and ≥ 0")?;
    check("exit cosine", mu_v, (0.0..=1.0).contains(&mu_v), "is outside [0, 1]")?;
    check("incidence cosine", mu_l, (0.0..=1.0).contains(&mu_l), "is outside [0, 1]")?;
    let t = table()?;
    let ax = t.axes;
    let blocks = block_weights(alpha_prime, eta, ax)?;
    let (ik, fk) = cell(tau.ln_1p() / ax.tau_max.ln_1p(), ax.taus);
    let (iv, fv) = cell(mu_v, ax.mus);
    let (il, fl) = cell(mu_l, ax.mus);
    let mut g = 0.0;
    for (b, wb) in blocks {
        for (dk, wk) in [(0, 1.0 - fk), (1, fk)] {
            for (dv, wv) in [(0, 1.0 - fv), (1, fv)] {
                for (dl, wl) in [(0, 1.0 - fl), (1, fl)] {
                    let i = ((b * ax.taus + ik + dk) * ax.mus + iv + dv) * ax.mus + il + dl;
                    g += wb * wk * wv * wl * f64::from(t.g[i]);
                }
            }
        }
    }
    let faces = Faces::new(eta, mu_v, mu_l);
    let multiple = g * (-kappa(alpha_prime) * tau).exp() * faces.boundary();
    Ok(single_under(alpha_prime, eta, tau, &faces) + multiple)
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
/// the medium's exact albedo, as the kernel's is (issue 31 item 1), and by
/// [`exit_normalisation`], so that all of the flux that reaches the exit leaves it.
pub fn hidden_entry_constants(medium: &Medium, samples: u32) -> ([[f32; 4]; 3], [f32; 4]) {
    let profiles = medium_profiles(medium, ProfileModel::ClassicDipole);
    let scale = hidden_entry_albedo_scale(medium, &profiles);
    let exit = exit_normalisation(medium.eta);
    let constants: [[f32; 4]; 3] = std::array::from_fn(|c| {
        let mut k = profiles[c].classic_constants();
        k[0] *= scale[c] * exit;
        k.map(|v| v as f32)
    });
    let sigma_tr = profiles.iter().map(|p| p.classic_constants()[1]).fold(f64::INFINITY, f64::min);
    let reach = (HIDDEN_ENTRY_REACH_LENGTHS / sigma_tr).min(HIDDEN_ENTRY_MAX_REACH_MM);
    let rate = sigma_tr.max(HIDDEN_ENTRY_REACH_LENGTHS / reach);
    (constants, [medium.eta as f32, reach as f32, samples as f32, rate as f32])
}

/// 1/(1 − 2C₁), C₁ = ∫₀¹ F(μ, η)μ dμ ([`crate::diffusion::fresnel_moment`]): the gathers leave
/// through the exit face with the Fresnel transmittance 1 − F(μ_o) of the view's cosine
/// (`hidden_entry` in shaders/thickness.wgsl), which over the hemisphere passes 1 − 2C₁ of a
/// diffuse flux; the diffusion flux R already left the medium (its extrapolated boundary holds
/// the light the face reflects back), so the exit's angular law is normalised to pass all of it,
/// as pbrt-v3's separable BSSRDF's S_ω = (1 − F)/(cπ), c = 1 − 2C₁, is (\[Pharr2016\] §11.4;
/// Jensen's original T_F(μ_o)/π, \[Jensen2001\], loses 2C₁: 6.1% at η 1.3). 1 at η = 1. Against adding-doubling at skin1's η 1.3
/// it brings the transmission gather's red from 8.7% short of what it carries at η = 1 to 2%
/// over (docs/BENCHMARKS.md "The slab law under a dielectric boundary").
pub fn exit_normalisation(eta: f64) -> f64 {
    if eta == 1.0 {
        return 1.0;
    }
    1.0 / (1.0 - 2.0 * crate::diffusion::fresnel_moment(eta, 1))
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
    fn under_a_boundary_the_gather_s_exit_passes_all_the_diffusion_flux() {
        // The exit's law 1 − F(μ_o), times the normalisation, over the hemisphere (2μ dμ) is 1.
        for eta in [1.0, 1.3, 1.5] {
            let n = 4096;
            let passed: f64 = (0..n)
                .map(|i| {
                    let mu = (i as f64 + 0.5) / n as f64;
                    (1.0 - fresnel_dielectric(mu, eta)) * 2.0 * mu / n as f64
                })
                .sum();
            let total = passed * exit_normalisation(eta);
            assert!((total - 1.0).abs() < 1e-5, "η {eta}: {total}");
        }
        assert_eq!(exit_normalisation(1.0), 1.0);
        // The constants carry it beside the albedo's scale, in the prefactor α′ (at skin1's
        // η 1.3: 1/(1 − 2C₁) = 1.065).
        let medium = Medium::builtin("skin1").expect("skin1");
        assert_eq!(medium.eta, 1.3);
        let (k, _) = hidden_entry_constants(&medium, HIDDEN_ENTRY_SAMPLES);
        let profiles = medium_profiles(&medium, ProfileModel::ClassicDipole);
        let scale = hidden_entry_albedo_scale(&medium, &profiles);
        let exit = exit_normalisation(1.3);
        assert!((1.06..1.07).contains(&exit), "{exit}");
        for c in 0..3 {
            let ratio = f64::from(k[c][0]) / (profiles[c].classic_constants()[0] * scale[c]);
            assert!((ratio / exit - 1.0).abs() < 1e-6, "channel {c}: {ratio}");
        }
    }

    #[test]
    fn the_table_loads_and_its_kappa_is_this_module_s() {
        let ax = axes().expect("table");
        assert_eq!(table().expect("table").g.len(), ax.etas * ax.albedos * ax.taus * ax.mus * ax.mus);
        let medium = medium_values([1.0, 0.5, 0.0], 1.3).expect("in the domain");
        assert_eq!(medium.len(), 3 * ax.taus * ax.mus * ax.mus);
        assert!(medium_values([0.5, f64::NAN, 0.5], 1.3).is_err());
        assert!(medium_values([0.5, 0.5, 0.5], 0.9).expect_err("η < 1").to_string().contains("index η 0.9"));
        // At an η node the spline is that node's block: η = 1 is the index-matched table.
        let block = ax.taus * ax.mus * ax.mus;
        let first = medium_values([1.0, 1.0, 1.0], 1.0).expect("η 1");
        assert_eq!(&first[..block], &table().expect("table").g[..block]);
        let last = medium_values([1.0, 1.0, 1.0], ax.eta_max).expect("last η");
        let start = (ax.etas - 1) * ax.albedos * block;
        let stored = &table().expect("table").g[start..start + block];
        assert!(last[..block].iter().zip(stored).all(|(a, b)| (a - b).abs() <= 1e-6 * b.abs().max(1e-6)));
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
        for (a, eta, tau, mv, ml, word) in [
            (f64::NAN, 1.0, 1.0, 0.5, 0.5, "albedo"),
            (0.5, 1.0, -1.0, 0.5, 0.5, "optical thickness"),
            (0.5, 1.0, f64::INFINITY, 0.5, 0.5, "optical thickness"),
            (0.5, 1.0, 1.0, 1.5, 0.5, "exit cosine"),
            (0.5, 1.0, 1.0, 0.5, f64::NAN, "incidence cosine"),
            (0.5, 1.61, 1.0, 0.5, 0.5, "index η 1.61"),
            (0.5, f64::NAN, 1.0, 0.5, 0.5, "index η NaN"),
        ] {
            let e = transmittance(a, eta, tau, mv, ml).expect_err("outside").to_string();
            assert!(e.contains(word), "{e}");
        }
    }
}
