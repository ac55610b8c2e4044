//! Quality control of production batches against a standard: pass/fail in a colour-difference
//! formula (CIEDE2000, CMC(l:c) or CIE 1976 ΔE*ab, `colorimetry::difference`) and the "555"
//! shade number (\[HunterLab2007\]): each of ΔL*, Δa*, Δb* is cut into blocks of a chosen size
//! centred on the standard, numbered 1-9 with the standard's block 5, so that batches with the
//! same three digits can be shipped together. [`tolerance_contour`] traces where a formula's
//! difference equals the tolerance in a plane through the standard (the tolerance ellipses of
//! `rouge qc --png`).

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

/// The a*b* plane through a colour: the unit CIELAB directions of a* and b*.
pub const AB_PLANE: [[f64; 3]; 2] = [[0.0, 1.0, 0.0], [0.0, 0.0, 1.0]];

/// The lightness-chroma plane through `standard`: the unit directions of L* and of the
/// standard's chroma (its hue angle; a* for a neutral standard).
pub fn lightness_chroma_plane(standard: [f64; 3]) -> [[f64; 3]; 2] {
    let c = standard[1].hypot(standard[2]);
    let (ca, cb) = if c > 1e-9 { (standard[1] / c, standard[2] / c) } else { (1.0, 0.0) };
    [[1.0, 0.0, 0.0], [0.0, ca, cb]]
}

/// The tolerance contour of `metric` around `standard` in a plane through it: for each of
/// `points` angles θ (evenly spaced from 0), the colour `standard + r (cos θ u + sin θ v)` whose
/// difference from the standard equals `tolerance`, with `u`, `v` = `plane` (unit CIELAB
/// directions, e.g. [`AB_PLANE`]). Found numerically per angle: the step doubles from 1e-3 ×
/// tolerance until the difference reaches the tolerance, then 60 bisections (the difference
/// grows along each ray near the standard; for ΔE*ab the contour is the circle of radius
/// `tolerance`, for CMC (\[Clarke1984\]) and CIEDE2000 (\[CIE142\]) near-ellipses). A ray on which
/// the difference never reaches the tolerance within 1000 CIELAB units is an error.
///
/// # Examples
///
/// ```
/// use rouge_measure::analysis::qc::{AB_PLANE, Metric, tolerance_contour};
///
/// let ring = tolerance_contour(Metric::Ab, [50.0, 20.0, 10.0], 2.0, AB_PLANE, 8)?;
/// assert!(ring.iter().all(|p| ((p[1] - 20.0).hypot(p[2] - 10.0) - 2.0).abs() < 1e-9 && p[0] == 50.0));
/// # Ok::<(), rouge_measure::analysis::AnalysisError>(())
/// ```
pub fn tolerance_contour(
    metric: Metric,
    standard: [f64; 3],
    tolerance: f64,
    plane: [[f64; 3]; 2],
    points: usize,
) -> Result<Vec<[f64; 3]>, AnalysisError> {
    judge(standard, standard, metric, tolerance, [1.0; 3])?;
    for d in plane {
        let norm_error = (d.iter().map(|x| x * x).sum::<f64>() - 1.0).abs();
        if norm_error.is_nan() || norm_error >= 1e-9 {
            return Err(invalid(format!("plane direction {d:?}: must be a unit vector")));
        }
    }
    (0..points.max(3))
        .map(|i| {
            let theta = std::f64::consts::TAU * i as f64 / points.max(3) as f64;
            let dir: [f64; 3] = std::array::from_fn(|j| theta.cos() * plane[0][j] + theta.sin() * plane[1][j]);
            let at = |r: f64| -> [f64; 3] { std::array::from_fn(|j| standard[j] + r * dir[j]) };
            let de = |r: f64| metric.delta_e(standard, at(r));
            let (mut lo, mut hi) = (0.0, 1e-3 * tolerance);
            while de(hi) < tolerance {
                (lo, hi) = (hi, 2.0 * hi);
                if hi > 1000.0 {
                    return Err(invalid(format!(
                        "{} never reaches {tolerance} within 1000 CIELAB units of {standard:?} at {:.1}°",
                        metric.name(),
                        theta.to_degrees()
                    )));
                }
            }
            for _ in 0..60 {
                let mid = 0.5 * (lo + hi);
                if de(mid) < tolerance { lo = mid } else { hi = mid }
            }
            Ok(at(0.5 * (lo + hi)))
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn contours_reach_the_tolerance_and_cmc_follows_its_chroma_weight() {
        let std = [60.0, 25.0, 15.0];
        for metric in [Metric::De2000, Metric::Cmc { l: 2.0, c: 1.0 }, Metric::Ab] {
            for plane in [AB_PLANE, lightness_chroma_plane(std)] {
                let ring = tolerance_contour(metric, std, 1.5, plane, 36).expect("reachable");
                assert_eq!(ring.len(), 36);
                for p in &ring {
                    assert!((metric.delta_e(std, *p) - 1.5).abs() < 1e-9, "{metric:?} {p:?}");
                }
            }
        }
        // Along the chroma direction only ΔC changes: CMC's radius is c·S_C·tolerance
        // (\[Clarke1984\]: S_C = 0.0638 C / (1 + 0.0131 C) + 0.638).
        let c = 25.0f64.hypot(15.0);
        let s_c = 0.0638 * c / (1.0 + 0.0131 * c) + 0.638;
        let ring = tolerance_contour(Metric::Cmc { l: 2.0, c: 1.0 }, std, 1.0, lightness_chroma_plane(std), 4)
            .expect("reachable");
        let r = (ring[1][1] - std[1]).hypot(ring[1][2] - std[2]);
        assert!((r - s_c).abs() < 1e-9, "{r} against {s_c}");
        assert!(tolerance_contour(Metric::Ab, std, -1.0, AB_PLANE, 8).is_err());
        assert!(tolerance_contour(Metric::Ab, std, 1.0, [[0.0, 2.0, 0.0], [0.0, 0.0, 1.0]], 8).is_err());
    }
}
