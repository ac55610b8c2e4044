//! The subsurface reflectance of a half-space under a smooth dielectric boundary (η ≥ 1): what
//! a medium's albedo is, every order of scattering and the boundary's internal reflections
//! included, where [`crate::half_space`] is exact only for η = 1 and the diffusion profiles'
//! totals ([`crate::diffusion::ChannelProfile::total`]) are approximations.
//!
//! The values come from adding-doubling (\[Prahl1993\], iadpython 0.5.3), an exact method for
//! plane-parallel media with mismatched boundaries: `python/gen_dielectric_half_space.py` writes
//! `data/reference/dielectric_half_space.json`, a grid of 25 η from 1 to 3 evenly spaced in
//! √(η − 1) (the critical angle opens as √(η − 1), so the reflectances bend sharply just above
//! η = 1 and are smooth in that variable) and 49 reduced albedos α′ evenly spaced in
//! t = (1 − α′)^¼ (from α′ = 1 they fall as √(1 − α′) times a factor that grows with η, so the
//! nodes crowd there), for an isotropically scattering (g = 0, the media's
//! similarity-relation form) semi-infinite medium under air:
//! - `r_normal`: the directional-hemispherical reflectance at normal incidence less the
//!   boundary's specular reflection, the quantity a profile's total Rd = ∫ R(r) 2πr dr stands
//!   for (the light of a normally incident beam that leaves after scattering);
//! - `r_diffuse`: the same under uniform incidence.
//!
//! [`reflectance`] interpolates the grid with Catmull-Rom splines in t and in √(η − 1). On the
//! 207 points off the grid that the script also writes (other η, random albedos, the media of
//! data/media/),
//! it is within the figure in docs/BENCHMARKS.md ("The dielectric half-space"), far below the
//! profiles' own errors; `render/tests/dielectric_half_space.rs` checks that, and that at η = 1
//! the table agrees with Chandrasekhar's H-function ([`crate::half_space`]), a second, independent
//! exact route.
//!
//! Domain: 0 ≤ α′ ≤ 1 and 1 ≤ η ≤ 3, a medium file's (`rouge_model::medium`); anything else,
//! NaN included, is an error that names the value.

use crate::error::{RenderError, Result};
use std::ops::RangeInclusive;
use std::sync::OnceLock;

/// The relative indices of refraction the table covers.
pub const ETA_RANGE: RangeInclusive<f64> = 1.0..=3.0;

/// The subsurface reflectances of a half-space of one reduced albedo and index.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Reflectance {
    /// Directional-hemispherical at normal incidence, specular reflection excluded.
    pub normal: f64,
    /// Under uniform incidence, specular reflection excluded.
    pub diffuse: f64,
}

/// One point of the adding-doubling reference (`data/reference/dielectric_half_space.json`).
#[derive(Clone, Debug, serde::Deserialize)]
pub struct ReferencePoint {
    /// Relative index of refraction.
    pub eta: f64,
    /// Reduced albedo α′.
    pub albedo: f64,
    /// Subsurface reflectance at normal incidence.
    pub r_normal: f64,
    /// Subsurface reflectance under uniform incidence.
    pub r_diffuse: f64,
    /// The medium and channel of data/media/ it is, for those points.
    #[serde(default)]
    pub medium: Option<String>,
}

#[derive(serde::Deserialize)]
struct Reference {
    grid_etas: Vec<f64>,
    grid_steps: usize,
    grid: Vec<ReferencePoint>,
    check: Vec<ReferencePoint>,
}

/// The reference file's text, compiled in.
const REFERENCE_JSON: &str = include_str!("../../data/reference/dielectric_half_space.json");

/// The reference's points off the table's grid (other η, random albedos, the media), on which
/// the interpolation is judged (`render/tests/dielectric_half_space.rs`, the bench).
///
/// # Errors
/// [`RenderError::Invalid`] if the compiled-in file does not parse.
pub fn held_out_points() -> Result<Vec<ReferencePoint>> {
    serde_json::from_str::<Reference>(REFERENCE_JSON)
        .map(|r| r.check)
        .map_err(|e| RenderError::Invalid(format!("data/reference/dielectric_half_space.json: {e}")))
}

/// The grid: `values[e * (steps + 1) + k]` at η = `etas[e]` and t = (1 − α′)^¼ = k / steps.
struct Table {
    etas: Vec<f64>,
    steps: usize,
    values: Vec<[f64; 2]>,
}

/// The reference's grid, read once and checked: every η and t in place, every value finite.
fn load() -> std::result::Result<Table, String> {
    let r: Reference = serde_json::from_str(REFERENCE_JSON).map_err(|e| e.to_string())?;
    let nodes = r.grid_steps + 1;
    let eta_steps = r.grid_etas.len().saturating_sub(1);
    if r.grid_steps < 3 || eta_steps < 1 || r.grid.len() != nodes * r.grid_etas.len() {
        return Err(format!("{} entries for {} η × {nodes} albedos", r.grid.len(), r.grid_etas.len()));
    }
    for (j, eta) in r.grid_etas.iter().enumerate() {
        let u = j as f64 / eta_steps as f64;
        let rule = ETA_RANGE.start() + (ETA_RANGE.end() - ETA_RANGE.start()) * u * u;
        if (eta - rule).abs() > 1e-9 {
            return Err(format!("η node {j} is {eta}, not {rule} (even in √(η − 1))"));
        }
    }
    for (i, e) in r.grid.iter().enumerate() {
        let (eta, k) = (r.grid_etas[i / nodes], i % nodes);
        let t = k as f64 / r.grid_steps as f64;
        let in_place = (e.eta - eta).abs() < 1e-12 && (e.albedo - (1.0 - t.powi(4))).abs() < 1e-12;
        if !(in_place && e.r_normal.is_finite() && e.r_diffuse.is_finite()) {
            return Err(format!("entry {i} (η {}, α′ {}) is not the grid's", e.eta, e.albedo));
        }
    }
    Ok(Table {
        etas: r.grid_etas,
        steps: r.grid_steps,
        values: r.grid.iter().map(|e| [e.r_normal, e.r_diffuse]).collect(),
    })
}

fn table() -> Result<&'static Table> {
    static TABLE: OnceLock<std::result::Result<Table, String>> = OnceLock::new();
    TABLE
        .get_or_init(load)
        .as_ref()
        .map_err(|e| RenderError::Invalid(format!("data/reference/dielectric_half_space.json: {e}")))
}

/// Catmull-Rom weights of the four nodes around `t` ∈ [0, 1] between the middle two.
fn catmull_rom(t: f64) -> [f64; 4] {
    let (t2, t3) = (t * t, t * t * t);
    [-0.5 * t3 + t2 - 0.5 * t, 1.5 * t3 - 2.5 * t2 + 1.0, -1.5 * t3 + 2.0 * t2 + 0.5 * t, 0.5 * t3 - 0.5 * t2]
}

/// The Catmull-Rom spline through nodes `0..=n` (n ≥ 1 intervals, spaced one apart) at `x` ∈
/// [0, n], as weights of the nodes: Σ w·node(i) over the pairs (i, w), a node may appear twice.
/// The missing outer node at an end is extrapolated linearly (2·node(0) − node(1)), which keeps
/// the spline exact for straight lines there. Shared with [`crate::dielectric_brdf`], whose
/// table has the same axes.
pub(crate) fn spline_weights(x: f64, n: usize) -> [(usize, f64); 6] {
    let i = (x.floor().max(0.0) as usize).min(n - 1);
    let w = catmull_rom(x - i as f64);
    // The nodes before and after the interval, each as two weighted nodes (the second with
    // weight 0 inside the grid).
    let before = if i == 0 { [(0, 2.0), (1, -1.0)] } else { [(i - 1, 1.0), (i - 1, 0.0)] };
    let after = if i + 1 == n { [(n, 2.0), (n - 1, -1.0)] } else { [(i + 2, 1.0), (i + 2, 0.0)] };
    [
        (before[0].0, w[0] * before[0].1),
        (before[1].0, w[0] * before[1].1),
        (i, w[1]),
        (i + 1, w[2]),
        (after[0].0, w[3] * after[0].1),
        (after[1].0, w[3] * after[1].1),
    ]
}

/// [`spline_weights`] applied to the pairs `node(0..=n)`.
fn spline(x: f64, n: usize, node: impl Fn(usize) -> [f64; 2]) -> [f64; 2] {
    spline_weights(x, n).iter().fold([0.0; 2], |sum, &(i, w)| {
        let v = node(i);
        [sum[0] + w * v[0], sum[1] + w * v[1]]
    })
}

/// The subsurface reflectances of a half-space of reduced albedo `alpha_prime` under a smooth
/// boundary of relative index `eta` (module doc).
///
/// # Errors
/// [`RenderError::Invalid`] naming the value for α′ outside [0, 1], η outside [`ETA_RANGE`], or
/// NaN.
pub fn reflectance(alpha_prime: f64, eta: f64) -> Result<Reflectance> {
    if !(0.0..=1.0).contains(&alpha_prime) {
        return Err(RenderError::Invalid(format!(
            "reduced albedo {alpha_prime}: the dielectric half-space needs 0 ≤ α′ ≤ 1"
        )));
    }
    if !ETA_RANGE.contains(&eta) {
        return Err(RenderError::Invalid(format!(
            "η {eta}: the dielectric half-space is tabulated for {} ≤ η ≤ {}",
            ETA_RANGE.start(),
            ETA_RANGE.end()
        )));
    }
    let t = table()?;
    let nodes = t.steps + 1;
    let t_at = (1.0 - alpha_prime).sqrt().sqrt() * t.steps as f64;
    // The η nodes are even in √(η − 1), where the critical angle opens (module doc).
    let e_at = ((eta - ETA_RANGE.start()) / (ETA_RANGE.end() - ETA_RANGE.start())).sqrt() * (t.etas.len() - 1) as f64;
    let sum = spline(e_at, t.etas.len() - 1, |e| spline(t_at, t.steps, |k| t.values[e * nodes + k]));
    Ok(Reflectance { normal: sum[0].clamp(0.0, 1.0), diffuse: sum[1].clamp(0.0, 1.0) })
}

/// The albedo of `medium` per channel: the [`Reflectance::normal`] of the half-space of its
/// reduced albedo under its own η, which the skin's albedo and the diffusion models' totals
/// stand for; `None` for a channel the table does not reach.
pub fn medium_normal_reflectance(medium: &rouge_model::medium::Medium) -> [Option<f64>; 3] {
    let alpha = medium.reduced_albedo();
    std::array::from_fn(|c| reflectance(alpha[c], medium.eta).ok().map(|r| r.normal))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_spline_goes_through_the_nodes_and_keeps_straight_lines_to_the_ends() {
        for n in [1usize, 2, 6, 32] {
            let line = |k: usize| [k as f64, 3.0 - 0.5 * k as f64];
            for x in [0.0, 0.3, 0.5, 1.0, n as f64 - 0.2, n as f64] {
                let v = spline(x, n, line);
                assert!((v[0] - x).abs() < 1e-12 && (v[1] - (3.0 - 0.5 * x)).abs() < 1e-12, "{n} {x}: {v:?}");
            }
            let bumpy = |k: usize| [((k * 7) % 5) as f64, 0.0];
            for k in 0..=n {
                assert!((spline(k as f64, n, bumpy)[0] - bumpy(k)[0]).abs() < 1e-12, "{n} {k}");
            }
        }
    }

    #[test]
    fn the_table_loads() {
        let t = table().expect("the committed table");
        assert_eq!(t.values.len(), t.etas.len() * (t.steps + 1));
    }
}
