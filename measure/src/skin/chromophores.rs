//! Absorption and scattering spectra of skin's constituents, per millimetre, 380-780 nm.
//!
//! Each function is one published spectrum, named by its source (full citations in
//! docs/REFERENCES.md; the data's origin in data/SOURCES.md):
//!
//! * haemoglobin: \[Prahl1999\], the molar extinction coefficients of HbO₂ and Hb compiled from
//!   Gratzer and Kollias, tabulated every 2 nm (`data/skin/hemoglobin_prahl.csv`, embedded),
//!   interpolated linearly;
//! * eu- and pheomelanin: the power laws of \[Jacques1998\] as used by \[Donner2006\] (eq. in its
//!   section 3.1), fitted to melanosome absorption measured by laser ablation thresholds and
//!   in-vivo spectra; valid through the visible;
//! * the baseline absorption of bloodless, melanin-free tissue: \[Jacques1998\];
//! * reduced scattering: the power law μs′ = a (λ/500 nm)^−b of \[Jacques2013\] (its eq. 2, Table 2:
//!   skin a = 4.6 /mm, b = 1.42), with a and b parameters of the model.

use std::sync::OnceLock;

/// Shortest wavelength the skin spectra cover, nm (the haemoglobin table's first row).
pub const MIN_WAVELENGTH_NM: f64 = 380.0;
/// Longest wavelength the skin spectra cover, nm (the haemoglobin table's last row).
pub const MAX_WAVELENGTH_NM: f64 = 780.0;

/// Haemoglobin concentration of whole blood, g/L (\[Prahl1999\]'s example, \[Jacques2013\]).
pub const HAEMOGLOBIN_G_PER_L: f64 = 150.0;
/// Gram molecular weight of haemoglobin, g/mol (\[Prahl1999\]).
pub const HAEMOGLOBIN_G_PER_MOL: f64 = 64_500.0;

const HAEMOGLOBIN_CSV: &str = include_str!("../../../data/skin/hemoglobin_prahl.csv");

struct HaemoglobinTable {
    wavelengths_nm: Vec<f64>,
    oxy_per_cm_per_molar: Vec<f64>,
    deoxy_per_cm_per_molar: Vec<f64>,
}

fn haemoglobin_table() -> &'static HaemoglobinTable {
    static TABLE: OnceLock<HaemoglobinTable> = OnceLock::new();
    TABLE.get_or_init(|| {
        let mut t =
            HaemoglobinTable { wavelengths_nm: vec![], oxy_per_cm_per_molar: vec![], deoxy_per_cm_per_molar: vec![] };
        for line in HAEMOGLOBIN_CSV.lines().filter(|l| l.starts_with(|c: char| c.is_ascii_digit())) {
            let v: Vec<f64> = line.split(',').filter_map(|c| c.trim().parse().ok()).collect();
            // The embedded table is checked by `the_embedded_tables_are_whole` below.
            if let [w, oxy, deoxy] = v[..] {
                t.wavelengths_nm.push(w);
                t.oxy_per_cm_per_molar.push(oxy);
                t.deoxy_per_cm_per_molar.push(deoxy);
            }
        }
        t
    })
}

fn interpolate(xs: &[f64], ys: &[f64], x: f64) -> f64 {
    let i = xs.partition_point(|&v| v <= x).clamp(1, xs.len() - 1);
    let t = ((x - xs[i - 1]) / (xs[i] - xs[i - 1])).clamp(0.0, 1.0);
    ys[i - 1] + t * (ys[i] - ys[i - 1])
}

/// μa of whole blood (150 g/L haemoglobin) at oxygen saturation 1 and 0, per mm, at `wavelength_nm`
/// in 380-780 nm: μa = ln(10) ε c / M (\[Prahl1999\]; ε decadic, per cm, so /10 per mm).
pub fn blood_mu_a_per_mm(wavelength_nm: f64) -> (f64, f64) {
    let t = haemoglobin_table();
    let per_mm = std::f64::consts::LN_10 * HAEMOGLOBIN_G_PER_L / HAEMOGLOBIN_G_PER_MOL / 10.0;
    (
        per_mm * interpolate(&t.wavelengths_nm, &t.oxy_per_cm_per_molar, wavelength_nm),
        per_mm * interpolate(&t.wavelengths_nm, &t.deoxy_per_cm_per_molar, wavelength_nm),
    )
}

/// μa of eumelanin inside melanosomes, per mm: 6.6·10¹⁰ λ^−3.33 (λ in nm; \[Jacques1998\],
/// \[Donner2006\] section 3.1). About 68 /mm at 500 nm.
pub fn eumelanin_mu_a_per_mm(wavelength_nm: f64) -> f64 {
    6.6e10 * wavelength_nm.powf(-3.33)
}

/// μa of pheomelanin inside melanosomes, per mm: 2.9·10¹⁴ λ^−4.75 (λ in nm; \[Jacques1998\],
/// \[Donner2006\] section 3.1). About 44 /mm at 500 nm, falling faster into the red than eumelanin.
pub fn pheomelanin_mu_a_per_mm(wavelength_nm: f64) -> f64 {
    2.9e14 * wavelength_nm.powf(-4.75)
}

/// Baseline μa of skin without blood or melanin, per mm: 0.0244 + 8.53 exp(−(λ − 154)/66.2)
/// (\[Jacques1998\], given there per cm as 0.244 + 85.3 exp(...)).
pub fn baseline_mu_a_per_mm(wavelength_nm: f64) -> f64 {
    0.0244 + 8.53 * (-(wavelength_nm - 154.0) / 66.2).exp()
}

/// Reduced scattering coefficient μs′ = a (λ/500 nm)^−b, per mm (\[Jacques2013\] eq. 2), for
/// `at_500nm_per_mm` = a and `power` = b.
pub fn reduced_scattering_per_mm(wavelength_nm: f64, at_500nm_per_mm: f64, power: f64) -> f64 {
    reduced_scattering_from_ln_ratio((wavelength_nm / 500.0).ln(), at_500nm_per_mm, power)
}

/// [`reduced_scattering_per_mm`] given ln(λ/500 nm) (cached on the working grid): a·exp(−b·ln(λ/500)).
pub fn reduced_scattering_from_ln_ratio(ln_over_500: f64, at_500nm_per_mm: f64, power: f64) -> f64 {
    at_500nm_per_mm * (-power * ln_over_500).exp()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_embedded_tables_are_whole() {
        let t = haemoglobin_table();
        assert_eq!(t.wavelengths_nm.len(), 201);
        assert_eq!(t.wavelengths_nm[0], MIN_WAVELENGTH_NM);
        assert_eq!(t.wavelengths_nm[200], MAX_WAVELENGTH_NM);
        assert!(t.wavelengths_nm.windows(2).all(|w| (w[1] - w[0] - 2.0).abs() < 1e-12));
    }

    #[test]
    fn published_values() {
        // Prahl's table at 542 nm: HbO2 53292, Hb 48148 cm^-1/M.
        let (oxy, deoxy) = blood_mu_a_per_mm(542.0);
        let k = std::f64::consts::LN_10 * 150.0 / 64_500.0 / 10.0;
        assert!((oxy - 53292.0 * k).abs() < 1e-9 && (deoxy - 48148.0 * k).abs() < 1e-9);
        // Between rows: linear.
        let (mid, _) = blood_mu_a_per_mm(541.0);
        assert!((mid - 0.5 * (53236.0 + 53292.0) * k).abs() < 1e-9);
        // Isosbestic near 800 nm is outside; near 500 nm the two are within 1%.
        let (o, d) = blood_mu_a_per_mm(500.0);
        assert!((o / d - 1.0).abs() < 0.01);
        assert!((eumelanin_mu_a_per_mm(500.0) - 68.0).abs() < 1.0);
        assert!((baseline_mu_a_per_mm(700.0) - (0.0244 + 8.53 * (-546.0f64 / 66.2).exp())).abs() < 1e-15);
        assert!((reduced_scattering_per_mm(500.0, 4.6, 1.42) - 4.6).abs() < 1e-15);
    }
}
