//! The angular law of a half-space's subsurface reflection under a smooth dielectric boundary
//! (1 ≤ η ≤ 3): how the light a medium returns depends on the light's and the view's angles,
//! every order of scattering and the boundary's refraction and internal reflections included.
//! [`crate::dielectric_half_space`] gives its energy at normal incidence (the albedo); this module
//! gives its shape, and the `half-space` diffuse law renders it (`lighting.wgsl`).
//!
//! With πf(μ, μ₀) the radiance leaving towards exit cosine μ per unit irradiance arriving from
//! cosine μ₀, times π, and R(μ₀) = ∫ πf(μ, μ₀) 2μ dμ the directional-hemispherical reflectance,
//! adding-doubling (\[Prahl1993\], iadpython 0.5.3, `python/gen_dielectric_brdf.py`, derivation
//! there) tabulates, per η and reduced albedo α′,
//! - shape(μ, μ₀) = πf(μ, μ₀)·(μ + μ₀) / (r_n·T(μ)·T(μ₀)) and
//! - exit(μ) = R(μ) / (r_n·T(μ)),
//!
//! with r_n = R(1) the albedo and T = 1 − F the boundary's Fresnel transmittance
//! ([`crate::diffusion::fresnel_dielectric`]). What is left after dividing by T is the radiance
//! just inside the boundary, which varies slowly with the cosines; at η = 1 (T = 1) the shape
//! is α′H(μ)H(μ₀)/(4r_n), Chandrasekhar's ([`crate::half_space`], a second exact route the tests
//! use). Axes: 13 η even in √(η − 1) and 17 albedos even in t = (1 − α′)^¼, those of
//! [`crate::dielectric_half_space`] at half its density, interpolated with the same Catmull-Rom
//! splines; 17 cosines even in [0, 1], bilinear.
//!
//! **On the GPU** ([`GpuTable`], the lighting pass) the albedo is the G-buffer's, per pixel and
//! channel: the law reads it as r_n (so a skin keeps its albedo at normal incidence whichever law
//! draws it) and looks the shape up on a per-frame table over r_n at the skin's η, linear in
//! √r_n and bilinear in the cosines; [`GpuTable::pi_brdf`] and [`GpuTable::reflectance`] are the
//! shader's twins, measured against adding-doubling off every grid in
//! `render/tests/dielectric_brdf.rs` and docs/BENCHMARKS.md.
//!
//! Domain: 0 ≤ α′ ≤ 1, 1 ≤ η ≤ 3, cosines in [0, 1] (clamped); anything else, NaN included, is an
//! error that names the value.

use crate::dielectric_half_space::{ETA_RANGE, reflectance, spline_weights};
use crate::diffusion::fresnel_dielectric;
use crate::error::{RenderError, Result};
use std::sync::OnceLock;

/// The reference file's text, compiled in.
const REFERENCE_JSON: &str = include_str!("../../data/reference/dielectric_brdf.json");
const FILE: &str = "data/reference/dielectric_brdf.json";

/// Albedo nodes of the GPU's table ([`GpuTable`]), even in √(r_n / r_max).
pub const GPU_ALBEDO_NODES: usize = 33;

/// One point of adding-doubling off every grid (`check` in the reference file).
#[derive(Clone, Debug, serde::Deserialize)]
pub struct CheckPoint {
    /// Relative index of refraction.
    pub eta: f64,
    /// Reduced albedo α′.
    pub albedo: f64,
    /// Exit cosine.
    pub mu: f64,
    /// Incidence cosine.
    pub mu0: f64,
    /// πf(μ, μ₀).
    pub pi_f: f64,
    /// R(μ₀).
    pub r: f64,
    /// R(1), the albedo.
    pub r_normal: f64,
}

#[derive(serde::Deserialize)]
struct Reference {
    etas: Vec<f64>,
    albedo_steps: usize,
    mu_nodes: usize,
    shape_values: Vec<f64>,
    exit_values: Vec<f64>,
    check: Vec<CheckPoint>,
}

/// The grid: per (η, albedo) node, the shape's M×M values (full, row-major) then exit's M.
struct Table {
    etas: usize,
    albedo_steps: usize,
    mu_nodes: usize,
    /// (M² + M) values per node, node (e, k) at `(e·(albedo_steps + 1) + k)·(M² + M)`.
    nodes: Vec<f64>,
}

fn load() -> std::result::Result<Table, String> {
    let r: Reference = serde_json::from_str(REFERENCE_JSON).map_err(|e| e.to_string())?;
    let m = r.mu_nodes;
    let count = r.etas.len() * (r.albedo_steps + 1);
    let upper = m * (m + 1) / 2;
    if m < 2 || r.albedo_steps < 3 || r.etas.len() < 2 {
        return Err(format!("{} η, {} albedo steps and {m} cosines are too few", r.etas.len(), r.albedo_steps));
    }
    if r.shape_values.len() != count * upper || r.exit_values.len() != count * m {
        return Err(format!(
            "{} shape and {} exit values for {count} nodes of {m} cosines",
            r.shape_values.len(),
            r.exit_values.len()
        ));
    }
    let steps = (r.etas.len() - 1) as f64;
    for (j, eta) in r.etas.iter().enumerate() {
        let u = j as f64 / steps;
        let rule = ETA_RANGE.start() + (ETA_RANGE.end() - ETA_RANGE.start()) * u * u;
        if (eta - rule).abs() > 1e-9 {
            return Err(format!("η node {j} is {eta}, not {rule} (even in √(η − 1))"));
        }
    }
    if let Some(i) = r.shape_values.iter().chain(&r.exit_values).position(|v| !(v.is_finite() && *v >= 0.0)) {
        return Err(format!("value {i} is negative or not finite"));
    }
    let mut nodes = Vec::with_capacity(count * (m * m + m));
    for n in 0..count {
        let tri = &r.shape_values[n * upper..(n + 1) * upper];
        let mut full = vec![0.0; m * m];
        let mut at = 0;
        for i in 0..m {
            for j in i..m {
                full[i * m + j] = tri[at];
                full[j * m + i] = tri[at];
                at += 1;
            }
        }
        nodes.extend(full);
        nodes.extend(&r.exit_values[n * m..(n + 1) * m]);
    }
    Ok(Table { etas: r.etas.len(), albedo_steps: r.albedo_steps, mu_nodes: m, nodes })
}

fn table() -> Result<&'static Table> {
    static TABLE: OnceLock<std::result::Result<Table, String>> = OnceLock::new();
    TABLE.get_or_init(load).as_ref().map_err(|e| RenderError::Invalid(format!("{FILE}: {e}")))
}

/// The reference's points off every grid (other η, random albedos, the cosines of another
/// quadrature), on which the law is judged.
///
/// # Errors
/// [`RenderError::Invalid`] if the compiled-in file does not parse.
pub fn held_out_points() -> Result<Vec<CheckPoint>> {
    serde_json::from_str::<Reference>(REFERENCE_JSON)
        .map(|r| r.check)
        .map_err(|e| RenderError::Invalid(format!("{FILE}: {e}")))
}

/// `x` clamped to [0, 1], NaN read as 0.
fn unit(x: f64) -> f64 {
    if x.is_nan() { 0.0 } else { x.clamp(0.0, 1.0) }
}

fn check_domain(alpha_prime: f64, eta: f64) -> Result<()> {
    if !(0.0..=1.0).contains(&alpha_prime) {
        return Err(RenderError::Invalid(format!("reduced albedo {alpha_prime}: the half-space law needs 0 ≤ α′ ≤ 1")));
    }
    if !ETA_RANGE.contains(&eta) {
        return Err(RenderError::Invalid(format!(
            "η {eta}: the half-space law is tabulated for {} ≤ η ≤ {}",
            ETA_RANGE.start(),
            ETA_RANGE.end()
        )));
    }
    Ok(())
}

/// The law of one medium: its albedo r_n and its shape on the table's cosines.
#[derive(Clone, Debug)]
pub struct Law {
    eta: f64,
    /// R(1).
    pub r_normal: f64,
    mu_nodes: usize,
    /// shape (M×M, row-major) then exit (M).
    values: Vec<f64>,
}

impl Law {
    /// The half-space of reduced albedo `alpha_prime` under a boundary of `eta`.
    ///
    /// # Errors
    /// [`RenderError::Invalid`] naming the value outside the domain (module doc).
    pub fn new(alpha_prime: f64, eta: f64) -> Result<Law> {
        check_domain(alpha_prime, eta)?;
        let t = table()?;
        let per = t.mu_nodes * t.mu_nodes + t.mu_nodes;
        let e_at = ((eta - ETA_RANGE.start()) / (ETA_RANGE.end() - ETA_RANGE.start())).sqrt() * (t.etas - 1) as f64;
        let a_at = (1.0 - alpha_prime).sqrt().sqrt() * t.albedo_steps as f64;
        let mut values = vec![0.0; per];
        for (e, we) in spline_weights(e_at, t.etas - 1) {
            for (k, wk) in spline_weights(a_at, t.albedo_steps) {
                let w = we * wk;
                if w == 0.0 {
                    continue;
                }
                let node = &t.nodes[(e * (t.albedo_steps + 1) + k) * per..][..per];
                values.iter_mut().zip(node).for_each(|(v, n)| *v += w * n);
            }
        }
        values.iter_mut().for_each(|v| *v = v.max(0.0));
        Ok(Law { eta, r_normal: reflectance(alpha_prime, eta)?.normal, mu_nodes: t.mu_nodes, values })
    }

    /// πf(μ, μ₀) for exit cosine `mu` and incidence cosine `mu0` (clamped to [0, 1]); 0 when
    /// both are 0.
    pub fn pi_brdf(&self, mu: f64, mu0: f64) -> f64 {
        let (mu, mu0) = (unit(mu), unit(mu0));
        if mu + mu0 <= 0.0 {
            return 0.0;
        }
        let m = self.mu_nodes;
        let shape = bilinear(&self.values[..m * m], m, mu, mu0);
        self.r_normal * shape * transmittance(mu, self.eta) * transmittance(mu0, self.eta) / (mu + mu0)
    }

    /// R(μ₀) for incidence cosine `mu0` (clamped), the light returned in every direction; by
    /// reciprocity also the radiance towards μ₀ under a uniform sky of radiance 1.
    pub fn reflectance(&self, mu0: f64) -> f64 {
        let m = self.mu_nodes;
        self.r_normal * linear(&self.values[m * m..], unit(mu0)) * transmittance(unit(mu0), self.eta)
    }
}

/// The boundary's Fresnel transmittance 1 − F at external cosine `mu`: 1 at η = 1, where there
/// is no boundary (F's formula is 0/0 at grazing there).
fn transmittance(mu: f64, eta: f64) -> f64 {
    if eta <= 1.0 { 1.0 } else { 1.0 - fresnel_dielectric(mu, eta) }
}

/// `values` (n nodes even in [0, 1]) at `x` ∈ [0, 1], linearly.
fn linear<T: Copy + Into<f64>>(values: &[T], x: f64) -> f64 {
    let n = values.len();
    let at = x * (n - 1) as f64;
    let i = (at.floor() as usize).min(n - 2);
    let f = at - i as f64;
    values[i].into() * (1.0 - f) + values[i + 1].into() * f
}

/// `values` (m×m nodes even in [0, 1]², row-major by the first cosine) at (`x`, `y`), bilinearly.
fn bilinear<T: Copy + Into<f64>>(values: &[T], m: usize, x: f64, y: f64) -> f64 {
    let (ax, ay) = (x * (m - 1) as f64, y * (m - 1) as f64);
    let (i, j) = ((ax.floor() as usize).min(m - 2), (ay.floor() as usize).min(m - 2));
    let (fx, fy) = (ax - i as f64, ay - j as f64);
    let v = |a: usize, b: usize| values[a * m + b].into();
    (v(i, j) * (1.0 - fy) + v(i, j + 1) * fy) * (1.0 - fx) + (v(i + 1, j) * (1.0 - fy) + v(i + 1, j + 1) * fy) * fx
}

/// The reduced albedo whose half-space under `eta` has normal-incidence reflectance `r_normal`
/// (bisection: R(1) rises with α′); α′ = 1 for anything at or above the most it can be.
fn albedo_of(r_normal: f64, eta: f64) -> Result<f64> {
    let (mut lo, mut hi) = (0.0f64, 1.0f64);
    for _ in 0..60 {
        let mid = 0.5 * (lo + hi);
        if reflectance(mid, eta)?.normal < r_normal {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    Ok(0.5 * (lo + hi))
}

/// What the half-space law's GPU table is made for: the skin's η, and for the curvature of its
/// environment term ([`crate::curved_half_space`]) the medium's α′ and σt′ (mm⁻¹) per channel.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct GpuLaw {
    /// The boundary's relative index.
    pub eta: f64,
    /// α′ and σt′ (mm⁻¹) per channel; none: no curvature term.
    pub curvature: Option<[[f64; 2]; 3]>,
}

/// The half-space law of one η over the albedo r_n, for the lighting pass: a header of eight
/// floats (node count K, cosine count M, r_max, η, curvature node count J (0 without the term),
/// the largest |H| in mm⁻¹, 0, 0), then per albedo node k (r_n = r_max·(k/(K − 1))², r_max = R(1)
/// at α′ = 1) the shape's M×M values and exit's M (module doc), then the curvature ratios per
/// channel at J curvatures even in ±|H|max ([`crate::curved_half_space::gpu_ratios`]). The shader
/// (`lighting.wgsl`, `half_space_*`) interpolates linearly in √(r_n / r_max) and bilinearly in the
/// cosines, as [`GpuTable::pi_brdf`] does here.
#[derive(Clone, Debug, PartialEq)]
pub struct GpuTable {
    /// The header and values, as uploaded.
    pub values: Vec<f32>,
}

/// Floats before the law's nodes.
const HEADER: usize = 8;

impl GpuTable {
    /// The table of `law`.
    ///
    /// # Errors
    /// [`RenderError::Invalid`] naming η outside [1, 3] or a medium the curvature term cannot take,
    /// or if the reference does not load.
    pub fn new(law: GpuLaw) -> Result<GpuTable> {
        let eta = law.eta;
        check_domain(1.0, eta)?;
        let r_max = reflectance(1.0, eta)?.normal;
        let m = table()?.mu_nodes;
        let ratios = match law.curvature {
            Some(c) => crate::curved_half_space::gpu_ratios(c.map(|[a, _]| a), c.map(|[_, s]| s), eta)?,
            None => Vec::new(),
        };
        let j = ratios.len() / 3;
        let h_max = crate::curved_half_space::MAX_CURVATURE_PER_MM as f32;
        let mut values = vec![GPU_ALBEDO_NODES as f32, m as f32, r_max as f32, eta as f32, j as f32, h_max, 0.0, 0.0];
        for k in 0..GPU_ALBEDO_NODES {
            let s = k as f64 / (GPU_ALBEDO_NODES - 1) as f64;
            // At r_n = 0 the shape is single scattering's, the table's α′ → 0 limit.
            let alpha = if k == 0 { 0.0 } else { albedo_of(r_max * s * s, eta)? };
            values.extend(Law::new(alpha, eta)?.values.iter().map(|&v| v as f32));
        }
        values.extend(ratios);
        Ok(GpuTable { values })
    }

    fn header(&self) -> (usize, usize, f64, f64) {
        let h = &self.values[..4];
        (h[0] as usize, h[1] as usize, f64::from(h[2]), f64::from(h[3]))
    }

    /// The shape (or with `exit`, the exit values) at albedo `r_normal`, interpolated linearly
    /// in √(r_n / r_max) between two nodes: (node values below, above, weight of above).
    fn nodes(&self, r_normal: f64) -> (&[f32], &[f32], f64) {
        let (k_count, m, r_max, _) = self.header();
        let per = m * m + m;
        let at = (unit(r_normal / r_max)).sqrt() * (k_count - 1) as f64;
        let k = (at.floor() as usize).min(k_count - 2);
        let node = |k: usize| &self.values[HEADER + k * per..][..per];
        (node(k), node(k + 1), at - k as f64)
    }

    /// πf(μ, μ₀) of a pixel of albedo `r_normal`, as the shader computes it.
    pub fn pi_brdf(&self, r_normal: f64, mu: f64, mu0: f64) -> f64 {
        let (_, m, _, eta) = self.header();
        let (mu, mu0) = (unit(mu), unit(mu0));
        if mu + mu0 <= 0.0 {
            return 0.0;
        }
        let (lo, hi, f) = self.nodes(r_normal);
        let at = |n: &[f32]| bilinear(&n[..m * m], m, mu, mu0);
        let shape = at(lo) * (1.0 - f) + at(hi) * f;
        r_normal.max(0.0) * shape * transmittance(mu, eta) * transmittance(mu0, eta) / (mu + mu0)
    }

    /// R(μ) of a pixel of albedo `r_normal`, as the shader computes it.
    pub fn reflectance(&self, r_normal: f64, mu: f64) -> f64 {
        let (_, m, _, eta) = self.header();
        let mu = unit(mu);
        let (lo, hi, f) = self.nodes(r_normal);
        let at = |n: &[f32]| linear(&n[m * m..], mu);
        r_normal.max(0.0) * (at(lo) * (1.0 - f) + at(hi) * f) * transmittance(mu, eta)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_table_loads_and_its_interpolants_go_through_their_nodes() {
        let t = table().expect("the committed table");
        assert_eq!(t.nodes.len(), t.etas * (t.albedo_steps + 1) * (t.mu_nodes * t.mu_nodes + t.mu_nodes));
        let v = [0.0, 1.0, 4.0, 9.0];
        assert_eq!(linear(&v, 2.0 / 3.0), 4.0);
        assert!((linear(&v, 0.5) - 2.5).abs() < 1e-12);
        let g = [1.0, 2.0, 3.0, 4.0];
        assert_eq!(bilinear(&g, 2, 1.0, 0.0), 3.0);
        assert!((bilinear(&g, 2, 0.5, 0.5) - 2.5).abs() < 1e-12);
    }
}
