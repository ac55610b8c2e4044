//! Special metamerism indices of a pair of spectra: how far a match made under one illuminant
//! and observer (the reference viewing) comes apart under another (the test viewing).
//!
//! # Definitions (\[CIE15-2018\] §9.2-9.3, \[ISO18314-4\], after \[CIE80\])
//!
//! A *standard* and a *sample* that match under the reference viewing (or nearly) are compared
//! under the test viewing. When they do not match exactly under the reference, the sample is first
//! **corrected** so that it does, and the difference is taken between the standard and the
//! corrected sample under the test viewing:
//!
//! * **additive** (in CIELAB): `L*a*b*_corr = L*a*b*_smp,t − (L*a*b*_smp,r − L*a*b*_std,r)`, so
//!   with ΔE*ab the index is `|(Lab_smp,t − Lab_std,t) − (Lab_smp,r − Lab_std,r)|`;
//! * **multiplicative** (in XYZ): `X_corr = X_smp,t · X_std,r / X_smp,r` (and Y, Z alike), then
//!   CIELAB of `XYZ_corr` against the test white;
//! * **none**: the plain difference under the test viewing (for pairs that match exactly).
//!
//! The index is given as ΔE*ab (\[CIE15\] eq. 8.10, what CIE 15 and ISO 18314-4 define it with)
//! and as ΔE2000 (\[CIE142\], the difference formulators tolerance in) of the same corrected pair.
//! A change of **illuminant** keeps the observer (`M_t`, \[CIE15-2018\] §9.2); a change of
//! **observer** keeps the illuminant (CIE 1931 2° → CIE 1964 10°, `M_obs`; \[CIE15-2018\] §9.3
//! defines it with the standard deviate observer, whose data Rouge does not carry: the 10°
//! observer stands in as the second observer, a common practice that this doc states).
//!
//! Checked against colour-science computations of the same definitions
//! (`python/test_py_analysis.py`).

use crate::colorimetry::{Colorimeter, Illuminant, Viewing, delta_e_1976_raw, delta_e_2000_raw, xyz_to_lab_raw};
use crate::spectrum::Spectrum;

use super::{AnalysisError, check_reflectance};

/// How the sample is made to match the standard under the reference viewing before the test.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, serde::Serialize, serde::Deserialize)]
pub enum Correction {
    /// No correction: the plain difference under the test viewing.
    None,
    /// Additive correction in CIELAB (\[CIE15-2018\] §9.2, \[ISO18314-4\]).
    Additive,
    /// Multiplicative correction of the tristimulus values (\[CIE15-2018\] §9.2, \[ISO18314-4\]).
    Multiplicative,
}

impl Correction {
    /// All corrections, in report order.
    pub const ALL: [Correction; 3] = [Correction::None, Correction::Additive, Correction::Multiplicative];

    /// The name used on the command line, in JSON and in Python.
    pub fn name(self) -> &'static str {
        match self {
            Correction::None => "none",
            Correction::Additive => "additive",
            Correction::Multiplicative => "multiplicative",
        }
    }

    /// Parses `none`, `additive`, `multiplicative` (case-insensitive).
    pub fn parse(s: &str) -> Option<Self> {
        Self::ALL.into_iter().find(|c| c.name().eq_ignore_ascii_case(s.trim()))
    }
}

/// A metamerism index: the standard against the corrected sample under the test viewing.
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize)]
pub struct MetamerismIndex {
    /// The viewing the pair is matched under.
    pub reference: Viewing,
    /// The viewing the match is tested under.
    pub test: Viewing,
    /// The correction applied.
    pub correction: Correction,
    /// The index as CIE 1976 ΔE*ab.
    pub delta_e_ab: f64,
    /// The index as CIEDE2000.
    pub delta_e_2000: f64,
    /// The standard's CIELAB under the test viewing.
    pub standard_lab: [f64; 3],
    /// The corrected sample's CIELAB under the test viewing.
    pub sample_lab_corrected: [f64; 3],
}

/// The mismatch of the pair under the reference viewing itself (what a correction removes).
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize)]
pub struct ReferenceMatch {
    /// ΔE*ab under the reference viewing.
    pub delta_e_ab: f64,
    /// ΔE2000 under the reference viewing.
    pub delta_e_2000: f64,
    /// CIELAB of the standard under the reference viewing.
    pub standard_lab: [f64; 3],
    /// CIELAB of the sample under the reference viewing.
    pub sample_lab: [f64; 3],
}

/// How well the pair matches under `reference` (ΔE*ab and ΔE2000).
///
/// # Examples
///
/// ```
/// use rouge_measure::analysis::metamerism::reference_match;
/// use rouge_measure::{Spectrum, Viewing};
///
/// let m = reference_match(&Spectrum::constant(0.18), &Spectrum::constant(0.18), Viewing::D65_1931);
/// assert_eq!((m.delta_e_ab, m.delta_e_2000), (0.0, 0.0));
/// ```
pub fn reference_match(standard: &Spectrum, sample: &Spectrum, reference: Viewing) -> ReferenceMatch {
    let c = Colorimeter::get(reference);
    let std = c.lab(&c.xyz(standard)).lab;
    let smp = c.lab(&c.xyz(sample)).lab;
    ReferenceMatch {
        delta_e_ab: delta_e_1976_raw(std, smp),
        delta_e_2000: delta_e_2000_raw(std, smp),
        standard_lab: std,
        sample_lab: smp,
    }
}

/// The special metamerism index of a `standard` and a `sample` reflectance (or transmittance)
/// spectrum for a change from the `reference` viewing to the `test` viewing, after
/// `correction` (module documentation: \[CIE15-2018\] §9.2-9.3, \[ISO18314-4\]).
///
/// Domain: both spectra finite in [0, 1] at every wavelength (an error names the spectrum and
/// the wavelength). The multiplicative correction needs the sample's X, Y, Z under the
/// reference to be positive: a sample that is black there (X, Y or Z = 0) is refused.
///
/// # Examples
///
/// Two spectra that match under D65 (the sample is the standard plus a curve that D65's XYZ
/// cannot see) come apart under FL11; an identical pair has index 0 under any light.
///
/// ```
/// use rouge_measure::analysis::metamerism::{Correction, metamerism_index};
/// use rouge_measure::{Illuminant, Spectrum, Viewing};
///
/// let grey = Spectrum::constant(0.4);
/// let test = Viewing { illuminant: Illuminant::Fl11, ..Viewing::D65_1931 };
/// let same = metamerism_index(&grey, &grey, Viewing::D65_1931, test, Correction::Multiplicative)?;
/// assert!(same.delta_e_ab.abs() < 1e-12 && same.delta_e_2000.abs() < 1e-12);
/// let wavy = Spectrum(std::array::from_fn(|i| 0.4 + 0.1 * (i as f64 * 0.6).sin()));
/// let m = metamerism_index(&grey, &wavy, Viewing::D65_1931, test, Correction::Additive)?;
/// assert!(m.delta_e_ab > 0.0 && m.delta_e_2000 > 0.0);
/// # Ok::<(), rouge_measure::analysis::AnalysisError>(())
/// ```
pub fn metamerism_index(
    standard: &Spectrum,
    sample: &Spectrum,
    reference: Viewing,
    test: Viewing,
    correction: Correction,
) -> Result<MetamerismIndex, AnalysisError> {
    check_reflectance("the standard", standard)?;
    check_reflectance("the sample", sample)?;
    let (cr, ct) = (Colorimeter::get(reference), Colorimeter::get(test));
    let (std_r, smp_r) = (cr.xyz(standard).xyz, cr.xyz(sample).xyz);
    let (std_t, smp_t) = (ct.xyz(standard).xyz, ct.xyz(sample).xyz);
    let white_r = cr.white().xyz;
    let white_t = ct.white().xyz;
    let std_lab_t = xyz_to_lab_raw(std_t, white_t);
    let sample_lab_corrected = match correction {
        Correction::None => xyz_to_lab_raw(smp_t, white_t),
        Correction::Additive => {
            let (std_lab_r, smp_lab_r) = (xyz_to_lab_raw(std_r, white_r), xyz_to_lab_raw(smp_r, white_r));
            let smp_lab_t = xyz_to_lab_raw(smp_t, white_t);
            std::array::from_fn(|i| smp_lab_t[i] - (smp_lab_r[i] - std_lab_r[i]))
        }
        Correction::Multiplicative => {
            if let Some(i) = (0..3).find(|&i| smp_r[i].partial_cmp(&0.0) != Some(std::cmp::Ordering::Greater)) {
                return Err(AnalysisError::Invalid(format!(
                    "the multiplicative correction divides by the sample's {} under {reference}, which is {}: \
                     use the additive correction for a black sample",
                    ["X", "Y", "Z"][i],
                    smp_r[i]
                )));
            }
            let corrected: [f64; 3] = std::array::from_fn(|i| smp_t[i] * std_r[i] / smp_r[i]);
            xyz_to_lab_raw(corrected, white_t)
        }
    };
    Ok(MetamerismIndex {
        reference,
        test,
        correction,
        delta_e_ab: delta_e_1976_raw(std_lab_t, sample_lab_corrected),
        delta_e_2000: delta_e_2000_raw(std_lab_t, sample_lab_corrected),
        standard_lab: std_lab_t,
        sample_lab_corrected,
    })
}

/// The illuminant metamerism index `M_t` for each test illuminant and each correction (the
/// observer of `reference` throughout), in the order given: the table `rouge analyze
/// metamerism` prints.
///
/// # Examples
///
/// ```
/// use rouge_measure::analysis::metamerism::{Correction, illuminant_metamerism};
/// use rouge_measure::{Illuminant, Spectrum, Viewing};
///
/// let (a, b) = (Spectrum::constant(0.3), Spectrum::from_fn(|nm| 0.3 + 0.05 * (nm / 20.0).sin()));
/// let rows = illuminant_metamerism(&a, &b, Viewing::D65_1931, &[Illuminant::A, Illuminant::Fl11], &Correction::ALL)?;
/// assert_eq!(rows.len(), 6);
/// # Ok::<(), rouge_measure::analysis::AnalysisError>(())
/// ```
pub fn illuminant_metamerism(
    standard: &Spectrum,
    sample: &Spectrum,
    reference: Viewing,
    tests: &[Illuminant],
    corrections: &[Correction],
) -> Result<Vec<MetamerismIndex>, AnalysisError> {
    let mut out = Vec::with_capacity(tests.len() * corrections.len());
    for &illuminant in tests {
        for &correction in corrections {
            let test = Viewing { illuminant, ..reference };
            out.push(metamerism_index(standard, sample, reference, test, correction)?);
        }
    }
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::colorimetry::Observer;

    fn pair() -> (Spectrum, Spectrum) {
        let std = Spectrum(std::array::from_fn(|i| 0.2 + 0.4 * (i as f64 / 80.0)));
        let smp = Spectrum(std::array::from_fn(|i| std.0[i] + 0.05 * (i as f64 * 0.45).sin()));
        (std, smp)
    }

    #[test]
    fn the_additive_index_is_the_difference_of_differences() {
        let (std, smp) = pair();
        let r = Viewing::D65_1931;
        let t = Viewing { illuminant: Illuminant::A, ..r };
        let m = metamerism_index(&std, &smp, r, t, Correction::Additive).expect("in range");
        let (a, b) = (reference_match(&std, &smp, r), reference_match(&std, &smp, t));
        let d: [f64; 3] =
            std::array::from_fn(|i| (b.sample_lab[i] - b.standard_lab[i]) - (a.sample_lab[i] - a.standard_lab[i]));
        assert!((m.delta_e_ab - delta_e_1976_raw(d, [0.0; 3])).abs() < 1e-12, "{m:?}");
    }

    #[test]
    fn corrections_vanish_under_the_reference_itself() {
        let (std, smp) = pair();
        let r = Viewing { illuminant: Illuminant::D50, observer: Observer::Cie1964 };
        for c in [Correction::Additive, Correction::Multiplicative] {
            let m = metamerism_index(&std, &smp, r, r, c).expect("in range");
            assert!(m.delta_e_ab < 1e-10 && m.delta_e_2000 < 1e-10, "{c:?} {m:?}");
        }
        let plain = metamerism_index(&std, &smp, r, r, Correction::None).expect("in range");
        assert!((plain.delta_e_2000 - reference_match(&std, &smp, r).delta_e_2000).abs() < 1e-12);
    }

    #[test]
    fn bad_inputs_say_what_and_where() {
        let (std, mut smp) = pair();
        smp.0[10] = 1.5;
        let e = metamerism_index(&std, &smp, Viewing::D65_1931, Viewing::D65_1931, Correction::None)
            .expect_err("out of range")
            .to_string();
        assert!(e.contains("the sample") && e.contains("430 nm"), "{e}");
        let black = Spectrum::constant(0.0);
        let e = metamerism_index(&std, &black, Viewing::D65_1931, Viewing::D65_1931, Correction::Multiplicative)
            .expect_err("black")
            .to_string();
        assert!(e.contains("additive"), "{e}");
    }
}
