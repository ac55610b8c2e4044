//! Diffusion profiles of a homogeneous medium under a flat dielectric boundary: the radial
//! reflectance R(r) (per mm², for unit power entering at the origin) and its total
//! Rd = ∫ R(r) 2πr dr, from three models, in double precision:
//!
//! - **Classic dipole** (\[Jensen2001\] eq. 4-5; \[Benmounah2009\] Table 1 prints the same): a real
//!   source at z_r = 1/σt′ and a positive virtual source at z_v = z_r(1 + 4A/3), A = (1 + F_dr)/
//!   (1 − F_dr), F_dr from Egan and Hilgeman's polynomial, σ_tr = √(3σaσt′), and
//!   R(r) = α′/4π [z_r(1 + σ_tr d_r)e^{−σ_tr d_r}/d_r³ + z_v(1 + σ_tr d_v)e^{−σ_tr d_v}/d_v³].
//!   Derivation check: the dipole's flux −D ∂φ/∂z at the surface, with D = 1/(3σt′) and the
//!   virtual source at z = −z_v, is α′/4π [z_r(1+σd_r)e^{−σd_r}/d_r³ + z_v(1+σd_v)e^{−σd_v}/d_v³]:
//!   both terms positive because the virtual source lies *above* the surface at height z_v; the
//!   printed "z_v = z_r + 4AD" is that height. The total integrates in closed form
//!   (∫₀^∞ z(1+σd)e^{−σd}/d³ 2πr dr = 2π e^{−σz}): Rd = α′/2 (e^{−σ_tr z_r} + e^{−σ_tr z_v}),
//!   which is \[Jensen2001\] eq. 5's α′/2 (1 + e^{−(4/3)A√(3(1−α′))}) e^{−√(3(1−α′))}.
//! - **Better dipole** (\[dEon2012\]; the point source of pbrt-v3's photon beam diffusion): Grosjean's
//!   D = (2σa + σs′)/(3σt′²), σ_tr = √(σa/D), the extrapolated boundary z_b = 2AD with
//!   A = (1 + 3C₂)/(1 − 2C₁), the virtual source at −z_r − 2z_b, and the exitance
//!   R = C_φ φ(r) + C_E E(r), C_φ = ¼(1 − 2C₁), C_E = ½(1 − 3C₂). C₁, C₂ are the exact Fresnel
//!   moments of light inside the medium meeting the boundary ([`fresnel_moment`] at 1/η). Totals in
//!   closed form: ∫φ = α′/(2D)·(e^{−σz_r} − e^{−σ|z_v|})/σ (→ α′/(2D)(|z_v| − z_r) as σa → 0),
//!   ∫E = α′/2 (e^{−σz_r} + e^{−σ|z_v|}); at σa = 0 the total is exactly 1 for every η.
//! - **Burley's normalized diffusion** (\[Christensen2015\]): R(r) = A s (e^{−sr} + e^{−sr/3})/(8πr),
//!   whose total is A exactly. A is the better dipole's total and s = σt′·(1.85 − A + 7|A − 0.8|³),
//!   their fit for the searchlight configuration with the mean free path 1/σt′.
//!
//! Domain: σa ≥ 0, σs′ ≥ 0, σa + σs′ > 0, 1 ≤ η ≤ 3, r ≥ 0 (r = 0 is finite for both dipoles;
//! Burley's profile has an integrable 1/r singularity at 0 and returns +∞ there). Diffusion is
//! accurate where scattering dominates (α′ close to 1) and at r beyond a mean free path; the path
//! tracer comparison in docs/BENCHMARKS.md says how far each model is on real media.

use rouge_model::medium::Medium;
use std::f64::consts::PI;

/// Unpolarised Fresnel reflectance for light in a medium meeting an interface to a medium of
/// relative index `eta` (the far side over the near side) at incidence cosine `cos_i` ∈ [0, 1].
/// Total internal reflection (η < 1 past the critical angle) gives 1. [Born and Wolf] 1.5.
pub fn fresnel_dielectric(cos_i: f64, eta: f64) -> f64 {
    let cos_i = cos_i.clamp(0.0, 1.0);
    let sin2_t = (1.0 - cos_i * cos_i) / (eta * eta);
    if sin2_t >= 1.0 {
        return 1.0;
    }
    let cos_t = (1.0 - sin2_t).sqrt();
    let rs = (cos_i - eta * cos_t) / (cos_i + eta * cos_t);
    let rp = (eta * cos_i - cos_t) / (eta * cos_i + cos_t);
    0.5 * (rs * rs + rp * rp)
}

/// The Fresnel moment `∫₀¹ F(μ, η) μ^i dμ` of [`fresnel_dielectric`], exact to ~1e-12: composite
/// Simpson over 2048 panels, split at the critical cosine μ_c = √(1 − η²) when η < 1 and with
/// μ = μ_c + (1 − μ_c)t² on the transmitting side, which removes the square-root kink there.
pub fn fresnel_moment(eta: f64, i: i32) -> f64 {
    let f = |mu: f64| fresnel_dielectric(mu, eta) * mu.powi(i);
    let simpson = |g: &dyn Fn(f64) -> f64, a: f64, b: f64| {
        let n = 2048;
        let h = (b - a) / n as f64;
        let mut s = g(a) + g(b);
        for k in 1..n {
            s += g(a + k as f64 * h) * if k % 2 == 1 { 4.0 } else { 2.0 };
        }
        s * h / 3.0
    };
    let mu_c = if eta < 1.0 { (1.0 - eta * eta).sqrt() } else { 0.0 };
    // Below the critical cosine everything is reflected: ∫₀^μc μ^i dμ.
    let tir = mu_c.powi(i + 1) / f64::from(i + 1);
    let transmitting = |t: f64| {
        let mu = mu_c + (1.0 - mu_c) * t * t;
        f(mu) * 2.0 * (1.0 - mu_c) * t
    };
    tir + simpson(&transmitting, 0.0, 1.0)
}

/// Egan and Hilgeman's polynomial fit of the diffuse internal reflectance of a boundary of
/// relative index η (\[Jensen2001\] eq. 5 text): F_dr = −1.440/η² + 0.710/η + 0.668 + 0.0636η.
/// It approximates `2·fresnel_moment(1/η, 1)` (light inside meeting the boundary) to ~1% for
/// 1 ≤ η ≤ 1.5.
pub fn f_dr_polynomial(eta: f64) -> f64 {
    -1.440 / (eta * eta) + 0.710 / eta + 0.668 + 0.0636 * eta
}

/// Which diffusion model a profile comes from.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ProfileModel {
    /// \[Jensen2001\]'s dipole.
    ClassicDipole,
    /// \[dEon2012\]'s better dipole.
    BetterDipole,
    /// \[Christensen2015\]'s normalized diffusion with the searchlight fit.
    Burley,
}

/// z(1 + σ_tr·d)e^{−σ_tr·d}/d³: the flux through a surface of a unit point source of the
/// diffusion equation at depth (or height) `z_mm` below it and `d_mm` > 0 away, the term of
/// \[Jensen2001\]'s dipole (the shaders' twin: `point_source_flux` in shaders/diffusion.wgsl).
pub fn point_source_flux(z_mm: f64, d_mm: f64, sigma_tr: f64) -> f64 {
    z_mm * (1.0 + sigma_tr * d_mm) * (-sigma_tr * d_mm).exp() / (d_mm * d_mm * d_mm)
}

impl ProfileModel {
    /// Every model, in the order of the benchmark table.
    pub const ALL: [ProfileModel; 3] = [ProfileModel::ClassicDipole, ProfileModel::BetterDipole, ProfileModel::Burley];

    /// The name on the command line and in benchmark rows.
    pub fn name(self) -> &'static str {
        match self {
            ProfileModel::ClassicDipole => "dipole",
            ProfileModel::BetterDipole => "better-dipole",
            ProfileModel::Burley => "burley",
        }
    }
}

/// One channel of a medium, with every derived constant of the three models.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ChannelProfile {
    /// Which model [`ChannelProfile::radial`] evaluates.
    pub model: ProfileModel,
    alpha_prime: f64,
    sigma_t_prime: f64,
    sigma_tr: f64,
    z_r: f64,
    /// Height of the virtual source above the surface for the classic dipole; depth below it
    /// (negative z) for the better dipole, stored as |z_v|.
    z_v: f64,
    d: f64,
    c_phi: f64,
    c_e: f64,
    burley_a: f64,
    burley_s: f64,
}

impl ChannelProfile {
    /// The constants of `model` for one channel: absorption and reduced scattering in mm⁻¹ and
    /// the relative index η (domain in the module doc; the caller checks it, as [`Medium`] does).
    pub fn new(model: ProfileModel, sigma_a: f64, sigma_s_prime: f64, eta: f64) -> ChannelProfile {
        let sigma_t_prime = sigma_a + sigma_s_prime;
        let alpha_prime = sigma_s_prime / sigma_t_prime;
        let z_r = 1.0 / sigma_t_prime;
        let mut p = ChannelProfile {
            model,
            alpha_prime,
            sigma_t_prime,
            sigma_tr: 0.0,
            z_r,
            z_v: 0.0,
            d: 0.0,
            c_phi: 0.0,
            c_e: 0.0,
            burley_a: 0.0,
            burley_s: 0.0,
        };
        match model {
            ProfileModel::ClassicDipole => {
                let f_dr = f_dr_polynomial(eta);
                let a = (1.0 + f_dr) / (1.0 - f_dr);
                p.sigma_tr = (3.0 * sigma_a * sigma_t_prime).sqrt();
                p.z_v = z_r * (1.0 + 4.0 * a / 3.0);
            }
            ProfileModel::BetterDipole | ProfileModel::Burley => {
                let (c1, c2) = (fresnel_moment(1.0 / eta, 1), fresnel_moment(1.0 / eta, 2));
                let d = (2.0 * sigma_a + sigma_s_prime) / (3.0 * sigma_t_prime * sigma_t_prime);
                let a = (1.0 + 3.0 * c2) / (1.0 - 2.0 * c1);
                p.d = d;
                p.sigma_tr = (sigma_a / d).sqrt();
                p.z_v = z_r + 4.0 * a * d;
                p.c_phi = 0.25 * (1.0 - 2.0 * c1);
                p.c_e = 0.5 * (1.0 - 3.0 * c2);
                if model == ProfileModel::Burley {
                    let a_total = p.better_total();
                    p.burley_a = a_total;
                    p.burley_s = sigma_t_prime * (1.85 - a_total + 7.0 * (a_total - 0.8).abs().powi(3));
                }
            }
        }
        p
    }

    /// `(e^{−σa} − e^{−σb})/σ` for 0 ≤ a ≤ b, stable as σ → 0 (limit b − a).
    fn exp_difference_over_sigma(sigma: f64, a: f64, b: f64) -> f64 {
        if sigma * (b - a) < 1e-12 {
            return (b - a) * (-sigma * a).exp();
        }
        (-sigma * a).exp() * -(-sigma * (b - a)).exp_m1() / sigma
    }

    fn better_total(&self) -> f64 {
        let s = self.sigma_tr;
        let phi = self.alpha_prime / (2.0 * self.d) * Self::exp_difference_over_sigma(s, self.z_r, self.z_v);
        let e = 0.5 * self.alpha_prime * ((-s * self.z_r).exp() + (-s * self.z_v).exp());
        self.c_phi * phi + self.c_e * e
    }

    /// The classic dipole's GPU constants: α′, σ_tr (mm⁻¹), z_r and z_v (mm) (the standard dipole
    /// of shaders/dipole_common.wgsl).
    pub fn classic_constants(&self) -> [f64; 4] {
        [self.alpha_prime, self.sigma_tr, self.z_r, self.z_v]
    }

    /// Total diffuse reflectance Rd = ∫ R(r) 2πr dr, closed form (module doc).
    pub fn total(&self) -> f64 {
        match self.model {
            ProfileModel::ClassicDipole => {
                0.5 * self.alpha_prime * ((-self.sigma_tr * self.z_r).exp() + (-self.sigma_tr * self.z_v).exp())
            }
            ProfileModel::BetterDipole => self.better_total(),
            ProfileModel::Burley => self.burley_a,
        }
    }

    /// The classic dipole between surface points, \[Benmounah2009\] Table 1 with its two slips
    /// corrected (module doc of [`crate::cube_atlas`]): the real source at `x_i − z_r·n_i`, the
    /// virtual one at `x_i + z_v·n_i` (the table prints `x_i − z_v·n_i`), and
    /// R = α′/4π Σ z(1 + σ_tr S)e^{−σ_tr S}/S³ over both, per mm², for light entering at `x_i`
    /// (outward normal `n_i`) and leaving at `x_o`. On a plane (x_o in x_i's tangent plane) it is
    /// [`ChannelProfile::radial`] of |x_o − x_i|. Classic constants whatever `self.model`.
    pub fn classic_between(&self, x_i: [f64; 3], n_i: [f64; 3], x_o: [f64; 3]) -> f64 {
        let flux = |z: f64, side: f64| {
            let d2: f64 = (0..3).map(|k| (x_i[k] + side * z * n_i[k] - x_o[k]).powi(2)).sum();
            point_source_flux(z, d2.sqrt().max(1e-12), self.sigma_tr)
        };
        self.alpha_prime / (4.0 * PI) * (flux(self.z_r, -1.0) + flux(self.z_v, 1.0))
    }

    /// ∫ R(r) 2πr dr over the disk r ≤ `a_mm` of the classic dipole, closed form: with
    /// d_a = √(a² + z²), ∫₀^a z(1 + σd)e^{−σd}/d³ 2πr dr = 2π(e^{−σz} − z e^{−σd_a}/d_a) (substitute
    /// d, r dr = d dd, and d/dd(−e^{−σd}/d) = (1 + σd)e^{−σd}/d²), so the disk holds
    /// α′/2 Σ_{z ∈ {z_r, z_v}} (e^{−σz} − z e^{−σd_a}/d_a). 0 at a = 0, [`ChannelProfile::total`]
    /// (classic) as a → ∞. The cube atlas integrates its centre texel with it.
    pub fn classic_disk_total(&self, a_mm: f64) -> f64 {
        let s = self.sigma_tr;
        let part = |z: f64| {
            let d = (a_mm * a_mm + z * z).sqrt();
            (-s * z).exp() - z * (-s * d).exp() / d
        };
        0.5 * self.alpha_prime * (part(self.z_r) + part(self.z_v))
    }

    /// \[Benmounah2009\] eq. 9 (the real source alone) integrated over a plane of sources at
    /// perpendicular distance `z_mm` from the exit point: α′/2 · e^{−σ_tr z} (the integral in the
    /// module doc with z the distance). The radiosity of the global term per unit irradiance of
    /// a locally uniform lit surface behind. Finite for every z ≥ 0 (α′/2 at z = 0).
    pub fn real_source_plane(&self, z_mm: f64) -> f64 {
        0.5 * self.alpha_prime * (-self.sigma_tr * z_mm.max(0.0)).exp()
    }

    /// Diffuse transmittance of a slab `d_mm` thick lit evenly on its far side, from the classic
    /// dipole's constants: a plane source of strength α′ at depth z₀ = min(z_r, d) under the lit
    /// face, zero fluence at both extrapolated boundaries (z_b = 2AD = (z_v − z_r)/2 outside each
    /// face). With u measured from the lit side's extrapolated boundary, L = d + 2z_b and
    /// u₀ = z₀ + z_b, the Green's function of −Dφ″ + σaφ = α′δ(u − u₀) is φ = α′ sinh(σu₀)
    /// sinh(σ(L − u))/(Dσ sinh σL) beyond the source (σ = σ_tr), and the flux −Dφ′ at the far
    /// face (u = L − z_b) is
    /// T(d) = α′ sinh(σ(z₀ + z_b)) cosh(σz_b) / sinh(σ(d + 2z_b)).
    /// Limits: α′(z₀ + z_b)/(d + 2z_b) as σ → 0 (pure scattering: 1/d), and the semi-infinite
    /// medium's e^{−σd} decay for thick slabs. The cube atlas's global term uses it in place of
    /// \[Benmounah2009\] eq. 9's lone real source ([`ChannelProfile::real_source_plane`]), which
    /// ignores both faces. Diffusion needs d beyond a mean free path; thinner slabs clamp z₀ = d.
    pub fn slab_transmittance(&self, d_mm: f64) -> f64 {
        let d = d_mm.max(0.0);
        let z_b = 0.5 * (self.z_v - self.z_r);
        let z0 = self.z_r.min(d);
        let s = self.sigma_tr;
        if s * (d + 2.0 * z_b) < 1e-6 {
            return self.alpha_prime * (z0 + z_b) / (d + 2.0 * z_b);
        }
        // sinh a cosh b / sinh c in exponentials of non-positive arguments, finite for any c.
        let (a, b, c) = (s * (z0 + z_b), s * z_b, s * (d + 2.0 * z_b));
        let ratio = (a + b - c).exp() * -(-2.0 * a).exp_m1() * (1.0 + (-2.0 * b).exp()) / (2.0 * -(-2.0 * c).exp_m1());
        self.alpha_prime * ratio
    }

    /// R(r), per mm², at distance `r_mm` ≥ 0 from the point of entry.
    pub fn radial(&self, r_mm: f64) -> f64 {
        let r2 = r_mm * r_mm;
        let s = self.sigma_tr;
        let flux = |z: f64| point_source_flux(z, (r2 + z * z).sqrt(), s);
        let fluence = |z: f64| {
            let d = (r2 + z * z).sqrt();
            (-s * d).exp() / d
        };
        match self.model {
            ProfileModel::ClassicDipole => self.alpha_prime / (4.0 * PI) * (flux(self.z_r) + flux(self.z_v)),
            ProfileModel::BetterDipole => {
                let phi = self.alpha_prime / (4.0 * PI * self.d) * (fluence(self.z_r) - fluence(self.z_v));
                // The virtual source lies at z = −|z_v| (above the surface): its term −z_v(…) of
                // E is +|z_v|(…), which `flux(self.z_v)` gives since `z_v` holds |z_v|.
                let e = self.alpha_prime / (4.0 * PI) * (flux(self.z_r) + flux(self.z_v));
                self.c_phi * phi + self.c_e * e
            }
            ProfileModel::Burley => {
                if r_mm <= 0.0 {
                    return f64::INFINITY;
                }
                let sr = self.burley_s * r_mm;
                self.burley_a * self.burley_s * ((-sr).exp() + (-sr / 3.0).exp()) / (8.0 * PI * r_mm)
            }
        }
    }

    /// Length beyond which the profile is negligible for a screen-space kernel, mm: three decay
    /// lengths 1/σ_tr (1/s for Burley), capped at 40 mean free paths when absorption is tiny.
    pub fn support_mm(&self) -> f64 {
        let decay = match self.model {
            ProfileModel::Burley => 3.0 / self.burley_s,
            _ => 1.0 / self.sigma_tr.max(1e-300),
        };
        (3.0 * decay).min(40.0 * self.z_r.max(1.0 / self.sigma_t_prime))
    }

    /// Mean free path 1/σt′, mm.
    pub fn mean_free_path_mm(&self) -> f64 {
        self.z_r
    }
}

/// The three channels of a medium under one model.
pub fn medium_profiles(medium: &Medium, model: ProfileModel) -> [ChannelProfile; 3] {
    std::array::from_fn(|c| {
        ChannelProfile::new(model, medium.sigma_a_per_mm[c], medium.sigma_s_prime_per_mm[c], medium.eta)
    })
}
