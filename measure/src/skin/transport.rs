//! Light transport in the two-layer skin slab: adding-doubling, tabulated.
//!
//! The slab is an epidermis of thickness d over a semi-infinite dermis; both scatter with a
//! Henyey-Greenstein phase function of g = [`ANISOTROPY_G`] and have the refractive index
//! [`TISSUE_INDEX`] (index-matched between them), under air, with a smooth surface. What a d/8°
//! spectrophotometer with the specular component included measures is the total reflectance for
//! (nearly) normal collimated light: the surface's Fresnel reflection plus everything that
//! scatters back out.
//!
//! That reflectance is solved exactly (up to 16 quadrature angles) by Prahl's adding-doubling
//! (\[Prahl1993\]; `iadpython`), which `python/gen_skin_transport.py` ran over a grid of the three
//! numbers it depends on for fixed g and n:
//!
//! * τa = μa,epi d, the epidermis' absorption optical thickness,
//! * τs′ = μs′epi d, its reduced scattering optical thickness (0-3),
//! * a′ = μs′derm / (μs′derm + μa,derm), the dermis' reduced albedo (0-1),
//!
//! and this module interpolates it (`data/skin/transport_ad.csv`, embedded): by tricubic (4-point
//! Lagrange) interpolation of ln R on the axes √τa, τs′ and y = √(1 − a′). On
//! √τa, ln R is smooth: its fall is steepest at the first absorption in the epidermis (which takes
//! the long diffuse paths through it) and nearly linear after; on y the semi-infinite reflectance
//! is smooth (R ≈ R₀ − c·y near a′ = 1). Past τa = 8 (only the deepest skins below 400 nm) the
//! last interval's slope in ln R is continued: what comes back is then the epidermis' own top
//! scattering, under 0.5% of the light. How close the interpolation stays to adding-doubling off
//! the grid, and
//! adding-doubling to Mitsuba 3's path tracer, is measured in `measure/tests/skin_transport.rs`
//! and docs/SKIN.md.
//!
//! Why not Kubelka-Munk or diffusion: the epidermis is 0.3-1 reduced mean free paths thick, where
//! both are off by 10-40% (a pure absorber of τa = 0.2 over the dermis takes R from 0.56 to
//! 0.28, a diffuse path-length factor of 3.4 instead of KM's 2).

use std::sync::OnceLock;

/// Refractive index of epidermis and dermis (the table's n).
pub const TISSUE_INDEX: f64 = 1.4;
/// Henyey-Greenstein anisotropy of both layers (the table's g).
pub const ANISOTROPY_G: f64 = 0.8;
/// Largest epidermal reduced scattering optical thickness μs′d the table covers.
pub const MAX_TAU_SCATTER_EPI: f64 = 3.0;

const TABLE_CSV: &str = include_str!("../../../data/skin/transport_ad.csv");

/// Fresnel reflectance of the smooth surface at normal incidence, ((n − 1)/(n + 1))².
pub fn specular_reflectance() -> f64 {
    let r = (TISSUE_INDEX - 1.0) / (TISSUE_INDEX + 1.0);
    r * r
}

struct Table {
    sqrt_tau_a: Vec<f64>,
    tau_s: Vec<f64>,
    y: Vec<f64>,
    /// ln of the diffuse reflectance, indexed [a][s][y].
    ln_r: Vec<f64>,
}

fn axis(line: &str, key: &str) -> Option<Vec<f64>> {
    let rest = line.strip_prefix("# ")?.strip_prefix(key)?.strip_prefix('=')?;
    rest.split(';').map(|v| v.trim().parse().ok()).collect()
}

fn table() -> &'static Table {
    static TABLE: OnceLock<Table> = OnceLock::new();
    TABLE.get_or_init(|| {
        let mut t = Table { sqrt_tau_a: vec![], tau_s: vec![], y: vec![], ln_r: vec![] };
        for line in TABLE_CSV.lines() {
            if let Some(v) = axis(line, "sqrt_tau_a_epi") {
                t.sqrt_tau_a = v;
            } else if let Some(v) = axis(line, "tau_sr_epi") {
                t.tau_s = v;
            } else if let Some(v) = axis(line, "y_derm") {
                t.y = v;
            } else if line.starts_with(|c: char| c.is_ascii_digit()) {
                // Columns 0-1 repeat the row's axes; the rest run over y. A floor keeps ln finite
                // where adding-doubling returns 0 (no light back).
                t.ln_r.extend(line.split(',').skip(2).map(|v| v.trim().parse::<f64>().unwrap_or(0.0).max(1e-300).ln()));
            }
        }
        t
    })
}

/// The first of four nodes around `x` on `axis` and their weights for local cubic (4-point
/// Lagrange) interpolation, accurate to O(h⁴) like a spline (the Hermite form with
/// finite-difference slopes was 5-10× further from adding-doubling). Near an end the stencil
/// shifts inward. Past the last node with `extrapolate`, the last interval is continued linearly;
/// otherwise `x` is clamped to the axis.
fn weights(axis: &[f64], x: f64, extrapolate: bool) -> (usize, [f64; 4]) {
    let n = axis.len();
    let i = axis.partition_point(|&v| v <= x).clamp(1, n - 1) - 1;
    if extrapolate && x > axis[n - 1] {
        let t = (x - axis[n - 2]) / (axis[n - 1] - axis[n - 2]);
        return (n - 4, [0.0, 0.0, 1.0 - t, t]);
    }
    let x = x.clamp(axis[0], axis[n - 1]);
    let first = i.saturating_sub(1).min(n - 4);
    let nodes = &axis[first..first + 4];
    let w =
        std::array::from_fn(|k| (0..4).filter(|&m| m != k).map(|m| (x - nodes[m]) / (nodes[k] - nodes[m])).product());
    (first, w)
}

/// Errors of the transport lookup: an input outside the slab's domain, named.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum TransportError {
    /// An optical thickness or albedo that is negative, non-finite or past the table.
    #[error("{what} = {value} is outside {domain}")]
    OutOfDomain {
        /// Which input.
        what: &'static str,
        /// Its value.
        value: f64,
        /// The range it must lie in.
        domain: &'static str,
    },
}

/// Total reflectance (specular + diffuse) of the two-layer slab for normal collimated light
/// (see the module documentation): `tau_a_epi` = μa,epi·d ≥ 0, `tau_sr_epi` = μs′epi·d in
/// [0, 3], `reduced_albedo_derm` = μs′/(μs′ + μa) of the dermis in [0, 1].
pub fn two_layer_reflectance(tau_a_epi: f64, tau_sr_epi: f64, reduced_albedo_derm: f64) -> Result<f64, TransportError> {
    if !(tau_a_epi >= 0.0 && tau_a_epi.is_finite()) {
        return Err(TransportError::OutOfDomain { what: "μa,epi·d", value: tau_a_epi, domain: "[0, ∞)" });
    }
    if !(0.0..=MAX_TAU_SCATTER_EPI).contains(&tau_sr_epi) {
        return Err(TransportError::OutOfDomain { what: "μs′epi·d", value: tau_sr_epi, domain: "[0, 3]" });
    }
    if !(0.0..=1.0).contains(&reduced_albedo_derm) {
        return Err(TransportError::OutOfDomain {
            what: "the dermis' reduced albedo",
            value: reduced_albedo_derm,
            domain: "[0, 1]",
        });
    }
    let t = table();
    let (ia, wa) = weights(&t.sqrt_tau_a, tau_a_epi.sqrt(), true);
    let (is, ws) = weights(&t.tau_s, tau_sr_epi, false);
    let (iy, wy) = weights(&t.y, (1.0 - reduced_albedo_derm).sqrt(), false);
    let (ns, ny) = (t.tau_s.len(), t.y.len());
    let mut ln_r = 0.0;
    for (ka, &wa) in wa.iter().enumerate().filter(|(_, w)| **w != 0.0) {
        for (ks, &ws) in ws.iter().enumerate().filter(|(_, w)| **w != 0.0) {
            let row = ((ia + ka) * ns + is + ks) * ny;
            for (ky, &wy) in wy.iter().enumerate().filter(|(_, w)| **w != 0.0) {
                ln_r += wa * ws * wy * t.ln_r[row + iy + ky];
            }
        }
    }
    Ok(specular_reflectance() + ln_r.exp())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_embedded_table_is_whole() {
        let t = table();
        assert_eq!(t.ln_r.len(), t.sqrt_tau_a.len() * t.tau_s.len() * t.y.len());
        assert!(t.ln_r.iter().all(|v| v.is_finite()));
        assert_eq!(*t.tau_s.last().unwrap_or(&0.0), MAX_TAU_SCATTER_EPI);
        assert_eq!((t.y[0], *t.y.last().unwrap_or(&0.0)), (0.0, 1.0));
    }

    #[test]
    fn limits() {
        // No absorption anywhere: everything comes back.
        let r = two_layer_reflectance(0.0, 0.5, 1.0).unwrap();
        assert!((r - 1.0).abs() < 2e-3, "{r}");
        // A black dermis under no epidermis: only the surface reflects.
        let r = two_layer_reflectance(0.0, 0.0, 0.0).unwrap();
        assert!((r - specular_reflectance()).abs() < 1e-9, "{r}");
        // An opaque epidermis: the specular reflection and the little light its top scatters back.
        let r = two_layer_reflectance(40.0, 0.5, 0.99).unwrap();
        assert!(r >= specular_reflectance() && r < specular_reflectance() + 1e-3, "{r}");
        assert!(two_layer_reflectance(-1.0, 0.5, 0.9).is_err());
        assert!(two_layer_reflectance(f64::NAN, 0.5, 0.9).is_err());
        assert!(two_layer_reflectance(0.1, 3.5, 0.9).is_err());
        assert!(two_layer_reflectance(0.1, 0.5, 1.1).is_err());
    }

    #[test]
    fn monotone_in_each_input() {
        let mut last = f64::INFINITY;
        for i in 0..200 {
            let r = two_layer_reflectance(i as f64 * 0.05, 0.4, 0.95).unwrap();
            assert!(r <= last + 1e-12);
            last = r;
        }
        let mut last = 0.0;
        for i in 0..=100 {
            let r = two_layer_reflectance(0.3, 0.4, i as f64 / 100.0).unwrap();
            assert!(r >= last - 1e-12);
            last = r;
        }
    }
}
