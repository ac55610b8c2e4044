//! Quality control of production batches against a standard: pass/fail in a colour-difference
//! formula (CIEDE2000, CMC(l:c) or CIE 1976 ΔE*ab, `colorimetry::difference`) and the "555"
//! shade number (\[HunterLab2007\]): each of ΔL*, Δa*, Δb* is cut into blocks of a chosen size
//! centred on the standard, numbered 1-9 with the standard's block 5, so that batches with the
//! same three digits can be shipped together.

use super::{AnalysisError, invalid};
use crate::colorimetry::{delta_e_1976_raw, delta_e_2000_raw, delta_e_cmc_raw};

/// The colour-difference formula a tolerance is written in.
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize)]
pub enum Metric {
    /// CIEDE2000.
    De2000,
    /// CMC(l:c).
    Cmc {
        /// Lightness weight (2 for acceptability).
        l: f64,
        /// Chroma weight.
        c: f64,
    },
    /// CIE 1976 ΔE*ab.
    Ab,
}

impl Metric {
    /// The difference of `sample` from `standard` (CMC weights come from the standard).
    pub fn delta_e(self, standard: [f64; 3], sample: [f64; 3]) -> f64 {
        match self {
            Metric::De2000 => delta_e_2000_raw(standard, sample),
            Metric::Cmc { l, c } => delta_e_cmc_raw(standard, sample, l, c),
            Metric::Ab => delta_e_1976_raw(standard, sample),
        }
    }

    /// Name for reports: `ΔE2000`, `CMC(2:1)`, `ΔE*ab`.
    pub fn name(self) -> String {
        match self {
            Metric::De2000 => "ΔE2000".into(),
            Metric::Cmc { l, c } => format!("CMC({l}:{c})"),
            Metric::Ab => "ΔE*ab".into(),
        }
    }
}

/// One batch judged against the standard.
#[derive(Clone, Debug, PartialEq, serde::Serialize)]
pub struct Judgement {
    /// The difference in the tolerance's formula.
    pub delta_e: f64,
    /// Within the tolerance.
    pub pass: bool,
    /// ΔL*, Δa*, Δb* (sample − standard).
    pub delta_lab: [f64; 3],
    /// The 555 shade number.
    pub shade: String,
}

/// The 555 shade number of a difference `delta_lab` with blocks `block` wide in L*, a*, b*:
/// each digit `5 + round(Δ/block)`, held to 1-9 (\[HunterLab2007\]).
///
/// # Examples
///
/// ```
/// use rouge_measure::analysis::qc::shade_555;
///
/// assert_eq!(shade_555([0.2, -0.1, 0.0], [1.0; 3]), "555");
/// assert_eq!(shade_555([-2.1, 0.6, 9.0], [1.0; 3]), "369");
/// ```
pub fn shade_555(delta_lab: [f64; 3], block: [f64; 3]) -> String {
    delta_lab
        .iter()
        .zip(block)
        .map(|(d, b)| (5.0 + (d / b).round()).clamp(1.0, 9.0) as u8)
        .map(|d| d.to_string())
        .collect()
}

/// Judges a batch of CIELAB `sample` against `standard`: pass when the difference in `metric` is
/// at most `tolerance`; the 555 shade number with `block` (ΔL*, Δa*, Δb* widths, > 0).
///
/// # Examples
///
/// \[Sharma2005\]'s first pair is 2.04 ΔE2000 and 1.74 CMC(2:1) apart: it fails a 2.0 ΔE2000
/// tolerance and passes 2.0 in CMC(2:1).
///
/// ```
/// use rouge_measure::analysis::qc::{Metric, judge};
///
/// let (std, smp) = ([50.0, 2.6772, -79.7751], [50.0, 0.0, -82.7485]);
/// assert!(!judge(std, smp, Metric::De2000, 2.0, [1.0; 3])?.pass);
/// assert!(judge(std, smp, Metric::Cmc { l: 2.0, c: 1.0 }, 2.0, [1.0; 3])?.pass);
/// # Ok::<(), rouge_measure::analysis::AnalysisError>(())
/// ```
pub fn judge(
    standard: [f64; 3],
    sample: [f64; 3],
    metric: Metric,
    tolerance: f64,
    block: [f64; 3],
) -> Result<Judgement, AnalysisError> {
    if !(tolerance > 0.0 && tolerance.is_finite()) {
        return Err(invalid(format!("tolerance {tolerance}: must be positive and finite")));
    }
    if let Metric::Cmc { l, c } = metric
        && !(l > 0.0 && c > 0.0 && l.is_finite() && c.is_finite())
    {
        return Err(invalid(format!("CMC({l}:{c}): l and c must be positive")));
    }
    if let Some(b) = block.iter().find(|b| !(**b > 0.0 && b.is_finite())) {
        return Err(invalid(format!("555 block width {b}: must be positive and finite")));
    }
    if standard.iter().chain(&sample).any(|v| !v.is_finite()) {
        return Err(invalid("a CIELAB value is not finite"));
    }
    let delta_e = metric.delta_e(standard, sample);
    let delta_lab = std::array::from_fn(|i| sample[i] - standard[i]);
    Ok(Judgement { delta_e, pass: delta_e <= tolerance, delta_lab, shade: shade_555(delta_lab, block) })
}
