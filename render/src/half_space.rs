//! The exact reflectance of a homogeneous, isotropically scattering half-space under an
//! index-matched boundary (η = 1): every order of scattering, single scattering included, from
//! Chandrasekhar's H-function. This is what the diffusion profiles' totals fall short of at low
//! albedo (docs/BENCHMARKS.md, "Translucency"), and what the screen-space kernel's
//! `half-space` diffuse law renders (`lighting.wgsl`).
//!
//! With single-scattering albedo ϖ (here the reduced albedo α′ = σs′/σt′ of a medium under the
//! similarity relation, g = 0), γ = √(1 − ϖ), and cosines μ₀ (incidence) and μ (exit) from the
//! normal, \[Chandrasekhar1960\] chapter V:
//! - the H-function solves 1/H(μ) = γ + (ϖ/2) ∫₀¹ μ′H(μ′)/(μ + μ′) dμ′ (eq. V.21 in the form of
//!   its §37; H(0) = 1, and H grows with μ and ϖ to H(1) = 2.9078 at ϖ = 1);
//! - the BRDF is f(μ, μ₀) = ϖ H(μ) H(μ₀) / (4π (μ + μ₀)) (eq. V.60 for a semi-infinite
//!   atmosphere, written per unit irradiance), so radiance leaving a surface of irradiance E is
//!   E f: [`HalfSpace::pi_brdf`] is π f, the "albedo" a Lambertian of the same radiance would have;
//! - its integral over exit directions is the directional-hemispherical reflectance
//!   R(μ₀) = 1 − γ H(μ₀) (by the H-equation itself), and under uniform light the radiance
//!   leaving towards μ is E R(μ)/π (reciprocity);
//! - averaged over uniform incidence, the white-sky albedo 2∫₀¹ R(μ)μ dμ.
//!
//! [`HalfSpace`] evaluates H by the Nyström method: the H-equation on 80 composite
//! Gauss-Legendre nodes (geometric panels towards μ = 0, where μ′/(μ + μ′) bends), iterated to
//! a fixed point, then the same quadrature evaluates H anywhere. Against 50-digit values of the
//! closed integral representation (`python/gen_h_function_reference.py`,
//! data/reference/h_function.json) it is within 2·10⁻¹⁰ for 0 ≤ ϖ ≤ 1, 0 ≤ μ ≤ 1, and π f(1, 1)
//! agrees with Mitsuba 3's half-space radiance (data/reference/slab_albedo.json) within the
//! path tracer's standard error on all twelve channels of four media (render/tests/half_space.rs).
//!
//! The GPU renders the law of any η from [`crate::dielectric_brdf`]'s adding-doubling table,
//! which this module checks at η = 1 (`render/tests/dielectric_brdf.rs`).
//!
//! Domain: 0 ≤ ϖ ≤ 1, 0 ≤ μ, μ₀ ≤ 1 (arguments are clamped there). η = 1 only: a dielectric
//! boundary changes both the H-equation and the exit distribution ([`crate::dielectric_half_space`]
//! and [`crate::dielectric_brdf`] give them).

/// Composite Gauss-Legendre panels on [0, 1] for the H-equation: geometric towards 0.
const PANELS: [(f64, f64); 5] = [(0.0, 1e-3), (1e-3, 1e-2), (1e-2, 0.1), (0.1, 0.4), (0.4, 1.0)];
/// Gauss-Legendre nodes per panel.
const NODES_PER_PANEL: usize = 16;

/// `x` clamped to [0, 1], NaN read as 0 (`f64::clamp` keeps a NaN): the module's domain.
fn unit_interval(x: f64) -> f64 {
    if x.is_nan() { 0.0 } else { x.clamp(0.0, 1.0) }
}

/// The nodes and weights of an n-point Gauss-Legendre rule on [−1, 1] (Newton on Pₙ from the
/// Chebyshev guesses; |Δx| < 1e-15 within a few steps for n ≤ 64).
fn gauss_legendre(n: usize) -> Vec<(f64, f64)> {
    (0..n)
        .map(|i| {
            let mut x = (std::f64::consts::PI * (i as f64 + 0.75) / (n as f64 + 0.5)).cos();
            let mut dp = 1.0;
            for _ in 0..100 {
                // P_n(x) and P_n'(x) by the three-term recurrence.
                let (mut p0, mut p1) = (1.0, x);
                for k in 2..=n {
                    let p2 = ((2 * k - 1) as f64 * x * p1 - (k - 1) as f64 * p0) / k as f64;
                    p0 = p1;
                    p1 = p2;
                }
                dp = n as f64 * (x * p1 - p0) / (x * x - 1.0);
                let step = p1 / dp;
                x -= step;
                if step.abs() < 1e-16 {
                    break;
                }
            }
            (x, 2.0 / ((1.0 - x * x) * dp * dp))
        })
        .collect()
}

/// The half-space of one single-scattering albedo, with its H-function solved.
#[derive(Clone, Debug)]
pub struct HalfSpace {
    albedo: f64,
    gamma: f64,
    /// Quadrature nodes μⱼ, weights wⱼ and H(μⱼ).
    nodes: Vec<(f64, f64, f64)>,
}

impl HalfSpace {
    /// Solves the H-equation for single-scattering albedo `albedo` (clamped to [0, 1]).
    pub fn new(albedo: f64) -> HalfSpace {
        let albedo = unit_interval(albedo);
        let gamma = (1.0 - albedo).sqrt();
        let rule = gauss_legendre(NODES_PER_PANEL);
        let mut nodes: Vec<(f64, f64, f64)> = PANELS
            .iter()
            .flat_map(|&(a, b)| {
                rule.iter().map(move |&(x, w)| (0.5 * (a + b) + 0.5 * (b - a) * x, 0.5 * (b - a) * w, 1.0))
            })
            .collect();
        // Fixed-point iteration of 1/H = γ + (ϖ/2)Σ wⱼμⱼHⱼ/(μ + μⱼ). It contracts for ϖ < 1; at
        // ϖ = 1 it converges too, but slowly, so past the first sweeps each step averages
        // the new iterate with the old (a damped step that keeps the fixed point).
        for sweep in 0..5000 {
            let next: Vec<f64> = nodes.iter().map(|&(mu, _, _)| Self::h_from(albedo, gamma, &nodes, mu)).collect();
            let mut change: f64 = 0.0;
            for (node, h) in nodes.iter_mut().zip(next) {
                let h = if sweep > 20 { 0.5 * (node.2 + h) } else { h };
                change = change.max((h - node.2).abs());
                node.2 = h;
            }
            if change < 1e-15 {
                break;
            }
        }
        HalfSpace { albedo, gamma, nodes }
    }

    fn h_from(albedo: f64, gamma: f64, nodes: &[(f64, f64, f64)], mu: f64) -> f64 {
        let sum: f64 = nodes.iter().map(|&(m, w, h)| w * m * h / (mu + m)).sum();
        1.0 / (gamma + 0.5 * albedo * sum)
    }

    /// The single-scattering albedo ϖ this half-space was solved for.
    pub fn albedo(&self) -> f64 {
        self.albedo
    }

    /// H(μ) for `mu` ∈ [0, 1] (clamped).
    pub fn h(&self, mu: f64) -> f64 {
        let mu = unit_interval(mu);
        if mu == 0.0 {
            return 1.0;
        }
        Self::h_from(self.albedo, self.gamma, &self.nodes, mu)
    }

    /// π f(μ, μ₀) = ϖ H(μ) H(μ₀) / (4 (μ + μ₀)): the radiance leaving towards `mu` per unit
    /// irradiance from `mu0`, times π. 0 when both cosines are 0.
    pub fn pi_brdf(&self, mu: f64, mu0: f64) -> f64 {
        let (mu, mu0) = (unit_interval(mu), unit_interval(mu0));
        if mu + mu0 <= 0.0 {
            return 0.0;
        }
        self.albedo * self.h(mu) * self.h(mu0) / (4.0 * (mu + mu0))
    }

    /// R(μ₀) = 1 − γ H(μ₀): the fraction of light arriving from `mu0` that the half-space
    /// returns (the directional-hemispherical reflectance).
    pub fn directional_reflectance(&self, mu0: f64) -> f64 {
        1.0 - self.gamma * self.h(mu0)
    }

    /// The white-sky albedo 2∫₀¹ R(μ)μ dμ: the fraction returned of uniform diffuse light.
    pub fn white_sky_albedo(&self) -> f64 {
        let moment: f64 = self.nodes.iter().map(|&(m, w, h)| w * m * h).sum();
        1.0 - 2.0 * self.gamma * moment
    }
}
