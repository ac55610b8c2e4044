//! The directional dipole BSSRDF of Frisvad, Hachisuka and Kjeldsen (\[Frisvad2014\]) and, for
//! comparison in the same pipeline, Jensen's standard dipole BSSRDF (\[Jensen2001\] eq. 6), in
//! double precision. The WGSL twins are in shaders/dipole_radiance.wgsl. [`DipoleKind`] and
//! [`DipoleSettings`] choose the BSSRDF and the sampling of the dipole passes that gather it.
//!
//! # The directional dipole, derived
//! Light of direction ω_i (toward the light) enters at x_i with normal n_i and is refracted to
//! ω₁₂ (the direction of travel inside, relative index η = n_inside/n_outside). Diffusion theory
//! with a *ray* source (a point source with a first-moment term along ω₁₂) gives the fluence of an
//! infinite medium at offset x from the source (φ₀ the monopole, D the diffusion coefficient):
//!
//! ```text
//! φ(x) = φ₀(r) − 3D ω·∇φ₀ = e^{−σ_tr r}/(4π r³) · (r²/D + 3(1 + σ_tr r) x·ω),   φ₀ = e^{−σ_tr r}/(4πD r)
//! ```
//!
//! (∇φ₀ = −(1 + σ_tr r)/r² · φ₀ · x). The light leaving through a boundary of normal n_o is the
//! better dipole's combination of fluence and flux (\[dEon2012\]), C_φ φ + C_E E·n_o with
//! E = −D∇φ; differentiating φ (the test `s_infinite_is_the_fluence_and_flux_of_a_ray_source`
//! checks it against finite differences):
//!
//! ```text
//! S∞(x, ω, r) = e^{−σ_tr r}/(4π² r³) · [ C_φ (r²/D + 3(1+σ_tr r) x·ω)
//!               − C_E (3D(1+σ_tr r) ω·n_o − ((1+σ_tr r) + 3D(3(1+σ_tr r) + (σ_tr r)²) x·ω/r²) x·n_o) ]
//! ```
//!
//! (the extra 1/π turns exitance into radiance). The BSSRDF is a real source minus a virtual
//! one mirrored in the *modified tangent plane* of normal n_i* = x̂ × (n_i × x)^, which contains
//! x = x_o − x_i, so that the configuration is planar whatever the geometry:
//!
//! ```text
//! S_d = (S∞(x_o − x_i, ω₁₂, d_r) − S∞(x_o − x_v, ω_v, d_v)) / (4 C_φ(1/η)),   clamped at 0,
//! x_v = x_i + 2A d_e n_i*,   ω_v = ω₁₂ − 2(ω₁₂·n_i*) n_i*,   d_v = |x_o − x_v|,
//! d_r² = r² + Dμ₀(Dμ₀ − 2 d_e cos β)   if μ₀ = −n_o·ω₁₂ > 0 (front-lit),
//! d_r² = r² + (3σ′_t)⁻²                 otherwise (back-lit),
//! cos β = −√((r² − (x·ω₁₂)²)/(r² + d_e²)),
//! ```
//!
//! with D = (2σa + σ′s)/(3σ′_t²) (Grosjean), σ_tr = √(σa/D), d_e = 2.131 D/√α′, A = (1 − C_E)/(2C_φ),
//! C_φ(η) = ¼(1 − 2C₁), C_E(η) = ½(1 − 3C₂), C_i the Fresnel moments of light inside meeting the
//! boundary ([`fresnel_moment`] at 1/η), and 1/(4C_φ(1/η)) = 1/(1 − 2C₁(1/η)) the normalisation of
//! the exit direction's distribution. The full BSSRDF multiplies the Fresnel transmittances
//! T₁₂(ω_i)·T₂₁(ω_o). Found on the way, where implementations in the wild differ:
//! - Mitsuba 0.6's `dirpole` plugin (after the paper's sample code) takes D = 1/(3σ′_t) and the
//!   back-lit term (3σ_t)⁻² with the *unreduced* σ_t; Rouge follows the published model
//!   (Grosjean's D, the reduced σ′_t), as Frisvad et al.'s own text gives them.
//! - The branch on μ₀ is discontinuous at μ₀ = 0 by (3σ′_t)⁻² in d_r²: at r of a mean free
//!   path or more the jump in S is below 10% (tested); at r → 0 it is the model's.
//! - r → 0 or x ∥ n_i leaves n_i* undefined: Rouge takes n_i* = n_i there (the flat limit).
//!
//! Domain: σa ≥ 0, σ′s > 0, 1 ≤ η ≤ 3; any geometry (light from below the tangent plane at x_i,
//! ω_i·n_i ≤ 0, gives 0). Diffusion is accurate for α′ near 1 and beyond a mean free path.
//!
//! # Its energy, and Rouge's correction ([`DipoleSource`])
//! As published, the model reflects 1.3× the path tracer's energy from a flat half-space where
//! α′ ≥ 0.99 and up to 54× as α′ falls (normal incidence, η = 1), and 1.3-2.2× the exact
//! half-space's albedo at every incidence (docs/BENCHMARKS.md). Two causes, each measured
//! (`render/tests/directional_dipole.rs`):
//! - **The source's power.** A ray entering the medium scatters ∫σ′s e^{−σ′t s} ds = α′ of its
//!   power; the fluence term C_φ e^{−σ_tr r}/(4π² D r) is that of a unit source. Multiplying by α′
//!   takes the excess from 1.3-54× to 1.1-1.6×.
//! - **The real source's depth.** S∞ grows as 1/d_r³ near the entry point, and the published d_r
//!   falls to D·μ₀ there (D ≈ 1/(3σ′t) where α′ → 1): the first-moment expansion of the ray source
//!   about its entry point, valid where r ≫ 3D, is used where r → 0. The ray's first scattering is
//!   on average a mean free path along it, at depth μ₀/σ′t.
//!
//! [`DipoleSource::MeanFreePath`] multiplies by α′ and puts the real source at that depth:
//! d_r² = r² + (μ₀/σ′t)² − 2Dμ₀ d_e cos β (the published (Dμ₀)² replaced, the cross term kept). Its
//! total is 0.91-0.99× the exact half-space's at μ₀ from 1 to 0.15 where α′ ≥ 0.95, and 0.71-1.03×
//! for α′ down to 0.68. The back-lit branch (light heading toward the exit surface, through thin
//! parts) keeps the published r² + (3σ′t)⁻²: σ′t⁻² there cost the backlit wedges 1.7-5.5 ΔE2000
//! (docs/BENCHMARKS.md). Two other front-lit placements were measured and not kept:
//! d_r² = r² + σ′t⁻² whatever μ₀ (1.00-1.04× at normal incidence, 0.3-0.5× at grazing incidence),
//! and μ₀/σ′t in both terms (0.5-0.9×). [`DipoleSource::Published`] keeps the model as published.

use crate::diffusion::{ChannelProfile, ProfileModel, fresnel_dielectric, fresnel_moment};
use crate::error::{RenderError, Result};
use glam::{DVec3, Vec3};
use rouge_model::medium::Medium;
use std::f64::consts::PI;

/// d_e = DE_FACTOR · D/√α′: the extrapolation distance of \[Frisvad2014\] (after Davison).
pub const DE_FACTOR: f64 = 2.131;

/// One channel's constants of the directional dipole.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct DipoleChannel {
    /// Grosjean's diffusion coefficient D, mm.
    pub d: f64,
    /// σ_tr = √(σa/D), mm⁻¹.
    pub sigma_tr: f64,
    /// Extrapolation distance d_e, mm.
    pub de: f64,
    /// A = (1 − C_E)/(2C_φ).
    pub a: f64,
    /// C_φ(η).
    pub c_phi: f64,
    /// C_E(η).
    pub c_e: f64,
    /// The back-lit offset (3σ′_t)⁻², mm², of either source; [`DipoleSource::MeanFreePath`]'s
    /// front-lit depth² (μ₀/σ′_t)² is 9μ₀² times it.
    pub backlit_sq: f64,
    /// The source's power: 1 as published, α′ for [`DipoleSource::MeanFreePath`].
    pub power: f64,
    /// Which source.
    pub source: DipoleSource,
}

/// The directional dipole's real source (module doc, "Its energy").
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Default)]
pub enum DipoleSource {
    /// As \[Frisvad2014\] publishes it: unit power; d_r² = r² + Dμ₀(Dμ₀ − 2d_e cos β) front-lit,
    /// r² + (3σ′_t)⁻² back-lit.
    #[default]
    Published,
    /// Rouge's correction: power α′; d_r² = r² + (μ₀/σ′_t)² − 2Dμ₀ d_e cos β front-lit (the real
    /// source at the depth of the ray's mean free path), back-lit as published.
    MeanFreePath,
}

/// The directional dipole of a medium.
#[derive(Clone, Debug, PartialEq)]
pub struct DirectionalDipole {
    /// Per linear RGB channel.
    pub channels: [DipoleChannel; 3],
    /// Relative index of the boundary.
    pub eta: f64,
    /// 1/(4 C_φ(1/η)).
    pub exit_norm: f64,
}

/// The geometry of one BSSRDF evaluation: entry point, its normal, the direction toward the
/// light, exit point, its normal, the direction toward the viewer. Normals and directions unit.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Geometry {
    /// Entry point x_i, mm.
    pub xi: DVec3,
    /// Normal at x_i.
    pub ni: DVec3,
    /// Toward the light, from x_i.
    pub wi: DVec3,
    /// Exit point x_o, mm.
    pub xo: DVec3,
    /// Normal at x_o.
    pub no: DVec3,
    /// Toward the viewer, from x_o.
    pub wo: DVec3,
}

impl Geometry {
    /// Light entering at the origin straight down a flat surface (z = 0, normal +Z) and leaving
    /// straight up at `r` mm along x: the half-space configuration of the energy checks.
    pub fn planar(r: f64) -> Geometry {
        Geometry {
            xi: DVec3::ZERO,
            ni: DVec3::Z,
            wi: DVec3::Z,
            xo: DVec3::new(r, 0.0, 0.0),
            no: DVec3::Z,
            wo: DVec3::Z,
        }
    }

    /// The reverse path: light entering at x_o from ω_o, leaving at x_i toward ω_i.
    pub fn swapped(self) -> Geometry {
        Geometry { xi: self.xo, ni: self.no, wi: self.wo, xo: self.xi, no: self.ni, wo: self.wi }
    }
}

/// The direction of travel of light from `toward_light` refracted into a medium of relative
/// index `eta` through a surface of normal `n`; `None` when the light is below the tangent plane.
pub fn refract_in(toward_light: DVec3, n: DVec3, eta: f64) -> Option<DVec3> {
    let cos_i = toward_light.dot(n);
    if cos_i <= 0.0 {
        return None;
    }
    let k = 1.0 / eta;
    let cos_t = (1.0 - k * k * (1.0 - cos_i * cos_i)).max(0.0).sqrt();
    Some((-k * toward_light + n * (k * cos_i - cos_t)).normalize_or(-n))
}

impl DipoleChannel {
    /// The published model's constants for σa, σ′s (mm⁻¹) and η.
    pub fn new(sigma_a: f64, sigma_s_prime: f64, eta: f64) -> DipoleChannel {
        DipoleChannel::with_source(sigma_a, sigma_s_prime, eta, DipoleSource::Published)
    }

    /// The constants for σa, σ′s (mm⁻¹) and η with the real source `source`.
    pub fn with_source(sigma_a: f64, sigma_s_prime: f64, eta: f64, source: DipoleSource) -> DipoleChannel {
        let sigma_t_prime = sigma_a + sigma_s_prime;
        let alpha_prime = sigma_s_prime / sigma_t_prime;
        let d = (2.0 * sigma_a + sigma_s_prime) / (3.0 * sigma_t_prime * sigma_t_prime);
        let (c1, c2) = (fresnel_moment(1.0 / eta, 1), fresnel_moment(1.0 / eta, 2));
        let c_phi = 0.25 * (1.0 - 2.0 * c1);
        let c_e = 0.5 * (1.0 - 3.0 * c2);
        DipoleChannel {
            d,
            sigma_tr: (sigma_a / d).sqrt(),
            de: DE_FACTOR * d / alpha_prime.sqrt(),
            a: (1.0 - c_e) / (2.0 * c_phi),
            c_phi,
            c_e,
            backlit_sq: 1.0 / (9.0 * sigma_t_prime * sigma_t_prime),
            power: match source {
                DipoleSource::Published => 1.0,
                DipoleSource::MeanFreePath => alpha_prime,
            },
            source,
        }
    }

    /// S∞ of the module doc without the 1/(4C_φ(1/η)): a ray source of direction `w` seen at
    /// offset `x` through a boundary of normal `no`, at the (modified) distance `r`.
    pub fn s_infinite(&self, x: DVec3, w: DVec3, r: f64, no: DVec3) -> f64 {
        let r = r.max(1e-9);
        let r2 = r * r;
        let s = self.sigma_tr * r;
        let s1 = 1.0 + s;
        let x_dot_w = x.dot(w);
        let fluence = r2 / self.d + 3.0 * s1 * x_dot_w;
        let flux = 3.0 * self.d * s1 * w.dot(no) - (s1 + 3.0 * self.d * (3.0 * s1 + s * s) / r2 * x_dot_w) * x.dot(no);
        (-s).exp() / (4.0 * PI * PI * r2 * r) * (self.c_phi * fluence - self.c_e * flux)
    }

    /// The diffuse part S_d (clamped at 0, times the source's power) for refracted direction
    /// `w12`, before the exit normalisation and the Fresnel transmittances.
    pub fn s_d(&self, g: &Geometry, w12: DVec3) -> f64 {
        let x = g.xo - g.xi;
        let r2 = x.length_squared();
        let ni_star = modified_normal(x, g.ni);
        let x_dot_w = x.dot(w12);
        let mu0 = -g.no.dot(w12);
        let dr2 = if mu0 > 0.0 {
            let cos_beta = -((r2 - x_dot_w * x_dot_w).max(0.0) / (r2 + self.de * self.de)).sqrt();
            let dmu = self.d * mu0;
            // The real source's depth below the exit point: D·μ₀ as published, μ₀/σ′t (the
            // mean free path along the refracted ray) corrected; the cross term as published.
            let depth_sq = match self.source {
                DipoleSource::Published => dmu * dmu,
                DipoleSource::MeanFreePath => 9.0 * mu0 * mu0 * self.backlit_sq,
            };
            r2 + depth_sq - 2.0 * dmu * self.de * cos_beta
        } else {
            r2 + self.backlit_sq
        };
        let wv = w12 - 2.0 * w12.dot(ni_star) * ni_star;
        let xv = x - 2.0 * self.a * self.de * ni_star;
        let real = self.s_infinite(x, w12, dr2.sqrt(), g.no);
        let virtual_ = self.s_infinite(xv, wv, xv.length(), g.no);
        self.power * (real - virtual_).max(0.0)
    }
}

/// n_i* = x̂ × (n_i × x)^, the normal of the plane through x that is closest to n_i's tangent
/// plane; n_i where x is (nearly) zero or parallel to n_i.
pub fn modified_normal(x: DVec3, ni: DVec3) -> DVec3 {
    let c = ni.cross(x);
    if x.length_squared() < 1e-18 || c.length_squared() < 1e-18 * x.length_squared() {
        return ni;
    }
    x.normalize().cross(c.normalize())
}

impl DirectionalDipole {
    /// The directional dipole of `medium` (its σa, σ′s and η) as published.
    pub fn new(medium: &Medium) -> DirectionalDipole {
        DirectionalDipole::with_source(medium, DipoleSource::Published)
    }

    /// The directional dipole of `medium` with the real source `source`.
    pub fn with_source(medium: &Medium, source: DipoleSource) -> DirectionalDipole {
        let eta = medium.eta;
        DirectionalDipole {
            channels: std::array::from_fn(|c| {
                DipoleChannel::with_source(medium.sigma_a_per_mm[c], medium.sigma_s_prime_per_mm[c], eta, source)
            }),
            eta,
            exit_norm: 1.0 / (1.0 - 2.0 * fresnel_moment(eta, 1)),
        }
    }

    /// S(x_i, ω_i; x_o, ω_o) per channel, mm⁻² sr⁻¹: T₁₂ T₂₁ S_d/(4C_φ(1/η)); 0 when the light
    /// or the viewer is below its tangent plane.
    pub fn bssrdf(&self, g: &Geometry) -> [f64; 3] {
        let Some(w12) = refract_in(g.wi, g.ni, self.eta) else { return [0.0; 3] };
        let cos_o = g.wo.dot(g.no);
        if cos_o <= 0.0 {
            return [0.0; 3];
        }
        let t = (1.0 - fresnel_dielectric(g.wi.dot(g.ni), self.eta)) * (1.0 - fresnel_dielectric(cos_o, self.eta));
        self.channels.map(|ch| t * self.exit_norm * ch.s_d(g, w12))
    }

    /// The reciprocal form ½(S(i → o) + S(o → i)) (\[Frisvad2014\] section 5).
    pub fn bssrdf_symmetric(&self, g: &Geometry) -> [f64; 3] {
        let (a, b) = (self.bssrdf(g), self.bssrdf(&g.swapped()));
        std::array::from_fn(|c| 0.5 * (a[c] + b[c]))
    }
}

/// Jensen's standard dipole BSSRDF (\[Jensen2001\] eq. 6 with the diffusion term of eq. 4):
/// S = T₁₂(ω_i) R_d(|x_o − x_i|) T₂₁(ω_o)/π per channel, with the classic dipole profile of
/// [`crate::diffusion`]. Ignores the directions but for the Fresnel terms and the tangent planes.
pub fn standard_dipole_bssrdf(profiles: &[ChannelProfile; 3], eta: f64, g: &Geometry) -> [f64; 3] {
    let (cos_i, cos_o) = (g.wi.dot(g.ni), g.wo.dot(g.no));
    if cos_i <= 0.0 || cos_o <= 0.0 {
        return [0.0; 3];
    }
    let t = (1.0 - fresnel_dielectric(cos_i, eta)) * (1.0 - fresnel_dielectric(cos_o, eta));
    let r = (g.xo - g.xi).length();
    profiles.map(|p| t * p.radial(r) / PI)
}

/// The classic dipole profiles of `medium`, for [`standard_dipole_bssrdf`].
pub fn standard_dipole_profiles(medium: &Medium) -> [ChannelProfile; 3] {
    crate::diffusion::medium_profiles(medium, ProfileModel::ClassicDipole)
}

/// Most radiance-map directions.
pub const MAX_DIRECTIONS: usize = 32;

/// Which BSSRDF the dipole passes gather.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum DipoleKind {
    /// \[Frisvad2014\]'s directional dipole, as published.
    Directional,
    /// The directional dipole with Rouge's correction of its source ([`DipoleSource::MeanFreePath`]).
    DirectionalMeanFreePath,
    /// \[Jensen2001\]'s standard (classic) dipole.
    Standard,
}

impl DipoleKind {
    /// The `--subsurface` name.
    pub fn name(self) -> &'static str {
        match self {
            DipoleKind::Directional => "directional-dipole",
            DipoleKind::DirectionalMeanFreePath => "directional-dipole-mfp",
            DipoleKind::Standard => "standard-dipole",
        }
    }

    /// The directional dipole's source; `None` for the standard dipole.
    pub fn source(self) -> Option<DipoleSource> {
        match self {
            DipoleKind::Directional => Some(DipoleSource::Published),
            DipoleKind::DirectionalMeanFreePath => Some(DipoleSource::MeanFreePath),
            DipoleKind::Standard => None,
        }
    }
}

/// The settings of the dipole passes (\[DirDipoleThesis\] sections 4.2 and 4.4).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct DipoleSettings {
    /// Disk samples N per radiance-map texel and light (1 to 256).
    pub samples: u32,
    /// Radiance-map directions K (1 to [`MAX_DIRECTIONS`]), spread on the sphere.
    pub directions: u32,
    /// Radiance-map side, texels.
    pub map_px: u32,
    /// Light G-buffer side, texels.
    pub light_map_px: u32,
    /// Fix 1 (section 4.4.1): the exit point looked up ε_g inside, across the light.
    pub shrink: bool,
    /// Fix 2 (section 4.4.2): the pixel looked up ε_c inside along its normal.
    pub intrusion: bool,
    /// Fix 3 (section 4.4.3): visibility compared in mm with a bias ε_b.
    pub world_bias: bool,
    /// Keep blending new samples into the maps while lights, mesh and settings stay.
    pub progressive: bool,
}

impl Default for DipoleSettings {
    fn default() -> Self {
        DipoleSettings {
            samples: 16,
            directions: 8,
            map_px: 256,
            light_map_px: 512,
            shrink: true,
            intrusion: true,
            world_bias: true,
            progressive: true,
        }
    }
}

impl DipoleSettings {
    /// Checks the ranges.
    ///
    /// # Errors
    /// [`RenderError::Invalid`] naming the setting.
    pub fn check(&self) -> Result<()> {
        let bad = |what: &str, v: u32, range: &str| Err(RenderError::Invalid(format!("dipole {what} {v}: {range}")));
        if !(1..=256).contains(&self.samples) {
            return bad("samples", self.samples, "1 to 256");
        }
        if !(1..=MAX_DIRECTIONS as u32).contains(&self.directions) {
            return bad("directions", self.directions, "1 to 32");
        }
        if !(16..=4096).contains(&self.map_px) {
            return bad("radiance map size", self.map_px, "16 to 4096 texels");
        }
        if !(16..=4096).contains(&self.light_map_px) {
            return bad("light map size", self.light_map_px, "16 to 4096 texels");
        }
        Ok(())
    }
}

/// `k` of `count` directions spread evenly on the unit sphere (the Fibonacci lattice through both
/// poles; a single direction is +Z, the default camera's).
pub fn direction(k: u32, count: u32) -> Vec3 {
    if count <= 1 {
        return Vec3::Z;
    }
    let golden = std::f32::consts::PI * (3.0 - 5f32.sqrt());
    let y = 1.0 - 2.0 * k as f32 / (count - 1) as f32;
    let r = (1.0 - y * y).max(0.0).sqrt();
    let phi = golden * k as f32;
    Vec3::new(r * phi.cos(), y, r * phi.sin())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn directions_cover_the_sphere_evenly() {
        for k in [1u32, 4, 8, 16, 32] {
            let ds: Vec<Vec3> = (0..k).map(|i| direction(i, k)).collect();
            assert!(ds.iter().all(|d| (d.length() - 1.0).abs() < 1e-5));
            if k >= 8 {
                // Every direction of the sphere is within 60° of one of them.
                for i in 0..200 {
                    let probe = direction(i, 200);
                    let best = ds.iter().map(|d| d.dot(probe)).fold(-1.0f32, f32::max);
                    assert!(best > 0.5, "{k} directions leave {probe} uncovered");
                }
            }
        }
    }

    #[test]
    fn settings_out_of_range_are_errors() {
        assert!(DipoleSettings::default().check().is_ok());
        for bad in [
            DipoleSettings { samples: 0, ..Default::default() },
            DipoleSettings { directions: 33, ..Default::default() },
            DipoleSettings { map_px: 8, ..Default::default() },
        ] {
            assert!(bad.check().is_err());
        }
    }
}
