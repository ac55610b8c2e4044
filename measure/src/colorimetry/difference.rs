//! Colour differences on CIELAB: CIE 1976 ΔE*ab, CMC(l:c) and CIEDE2000, one home each.

use super::{ColorError, Lab};

/// CIE 1976 colour difference ΔE*ab, the Euclidean distance in CIELAB (\[CIE15\] §8.2.1,
/// eq. 8.10), on bare `[L*, a*, b*]` triples (the caller guarantees a common white).
///
/// # Examples
///
/// ```
/// use rouge_measure::colorimetry::delta_e_1976_raw;
///
/// assert_eq!(delta_e_1976_raw([50.0, 3.0, 0.0], [50.0, 0.0, 4.0]), 5.0);
/// ```
pub fn delta_e_1976_raw(lab1: [f64; 3], lab2: [f64; 3]) -> f64 {
    let [dl, da, db] = std::array::from_fn(|i| lab1[i] - lab2[i]);
    (dl * dl + da * da + db * db).sqrt()
}

/// CIEDE2000 colour difference (\[CIE142\]; implementation notes of \[Sharma2005\]:
/// hue angles in degrees in [0, 360), the mean hue taken on the shorter arc, `h' = 0` for a
/// neutral colour). Both colours must share a [`Viewing`](super::Viewing).
///
/// # Examples
///
/// The first pair of \[Sharma2005\] Table 1: ΔE00 = 2.0425; colours of different whites are
/// refused.
///
/// ```
/// use rouge_measure::{Illuminant, Lab, Viewing, delta_e_2000};
///
/// let a = Lab { lab: [50.0, 2.6772, -79.7751], viewing: Viewing::D65_1931 };
/// let b = Lab { lab: [50.0, 0.0, -82.7485], viewing: Viewing::D65_1931 };
/// let de = delta_e_2000(&a, &b)?;
/// assert!((de - 2.0425).abs() < 5e-5, "{de}");
/// let under_a = Lab { viewing: Viewing { illuminant: Illuminant::A, ..Viewing::D65_1931 }, ..b };
/// assert!(delta_e_2000(&a, &under_a).is_err());
/// # Ok::<(), rouge_measure::colorimetry::ColorError>(())
/// ```
pub fn delta_e_2000(lab1: &Lab, lab2: &Lab) -> Result<f64, ColorError> {
    if lab1.viewing != lab2.viewing {
        return Err(ColorError::MixedViewing(lab1.viewing, lab2.viewing));
    }
    Ok(delta_e_2000_raw(lab1.lab, lab2.lab))
}

/// CIEDE2000 on bare `[L*, a*, b*]` triples (the caller guarantees a common white).
pub fn delta_e_2000_raw(lab1: [f64; 3], lab2: [f64; 3]) -> f64 {
    let [l1, a1, b1] = lab1;
    let [l2, a2, b2] = lab2;
    let c1 = a1.hypot(b1);
    let c2 = a2.hypot(b2);
    let c_bar = 0.5 * (c1 + c2);
    let c_bar7 = c_bar.powi(7);
    let g = 0.5 * (1.0 - (c_bar7 / (c_bar7 + 25.0f64.powi(7))).sqrt());
    let a1p = (1.0 + g) * a1;
    let a2p = (1.0 + g) * a2;
    let c1p = a1p.hypot(b1);
    let c2p = a2p.hypot(b2);
    let hue = |b: f64, a: f64| {
        if a == 0.0 && b == 0.0 {
            0.0
        } else {
            let h = b.atan2(a).to_degrees();
            if h < 0.0 { h + 360.0 } else { h }
        }
    };
    let h1p = hue(b1, a1p);
    let h2p = hue(b2, a2p);
    let dlp = l2 - l1;
    let dcp = c2p - c1p;
    let dhp_angle = if c1p * c2p == 0.0 {
        0.0
    } else {
        let d = h2p - h1p;
        if d > 180.0 {
            d - 360.0
        } else if d < -180.0 {
            d + 360.0
        } else {
            d
        }
    };
    let dhp = 2.0 * (c1p * c2p).sqrt() * (dhp_angle.to_radians() / 2.0).sin();
    let lp_bar = 0.5 * (l1 + l2);
    let cp_bar = 0.5 * (c1p + c2p);
    let hp_bar = if c1p * c2p == 0.0 {
        h1p + h2p
    } else if (h1p - h2p).abs() <= 180.0 {
        0.5 * (h1p + h2p)
    } else if h1p + h2p < 360.0 {
        0.5 * (h1p + h2p + 360.0)
    } else {
        0.5 * (h1p + h2p - 360.0)
    };
    let t = 1.0 - 0.17 * (hp_bar - 30.0).to_radians().cos()
        + 0.24 * (2.0 * hp_bar).to_radians().cos()
        + 0.32 * (3.0 * hp_bar + 6.0).to_radians().cos()
        - 0.20 * (4.0 * hp_bar - 63.0).to_radians().cos();
    let d_theta = 30.0 * (-((hp_bar - 275.0) / 25.0).powi(2)).exp();
    let cp_bar7 = cp_bar.powi(7);
    let rc = 2.0 * (cp_bar7 / (cp_bar7 + 25.0f64.powi(7))).sqrt();
    let l50 = (lp_bar - 50.0).powi(2);
    let sl = 1.0 + 0.015 * l50 / (20.0 + l50).sqrt();
    let sc = 1.0 + 0.045 * cp_bar;
    let sh = 1.0 + 0.015 * cp_bar * t;
    let rt = -(2.0 * d_theta).to_radians().sin() * rc;
    let (tl, tc, th) = (dlp / sl, dcp / sc, dhp / sh);
    (tl * tl + tc * tc + th * th + rt * tc * th).sqrt()
}

/// CMC(l:c) colour difference (\[Clarke1984\]; BS 6923, ISO 105-J03), of `lab2` from the
/// reference `lab1` (the formula is not symmetric: the weights come from the standard), on bare
/// `[L*, a*, b*]` triples: `√((ΔL/(l S_L))² + (ΔC/(c S_C))² + (ΔH/S_H)²)` with
/// `S_L = 0.040975 L/(1 + 0.01765 L)` (0.511 below L = 16), `S_C = 0.0638 C/(1 + 0.0131 C) +
/// 0.638`, `S_H = S_C (f T + 1 − f)`, `f = √(C⁴/(C⁴ + 1900))`, `T = 0.56 + |0.2 cos(h + 168°)|`
/// for 164° ≤ h ≤ 345°, else `0.36 + |0.4 cos(h + 35°)|`. `l = 2, c = 1` for acceptability,
/// `1:1` for perceptibility.
///
/// # Examples
///
/// \[Sharma2005\]'s first pair: CMC(2:1) = 1.738736 as colour-science 0.4.7's
/// `delta_E(..., method="CMC", l=2, c=1)` gives it.
///
/// ```
/// use rouge_measure::colorimetry::delta_e_cmc_raw;
///
/// let de = delta_e_cmc_raw([50.0, 2.6772, -79.7751], [50.0, 0.0, -82.7485], 2.0, 1.0);
/// assert!((de - 1.738_736_105_726_153).abs() < 1e-12, "{de}");
/// ```
pub fn delta_e_cmc_raw(lab1: [f64; 3], lab2: [f64; 3], l: f64, c: f64) -> f64 {
    let [l1, a1, b1] = lab1;
    let [l2, a2, b2] = lab2;
    let (c1, c2) = (a1.hypot(b1), a2.hypot(b2));
    let s_l = if l1 < 16.0 { 0.511 } else { 0.040975 * l1 / (1.0 + 0.01765 * l1) };
    let s_c = 0.0638 * c1 / (1.0 + 0.0131 * c1) + 0.638;
    let h1 = b1.atan2(a1).to_degrees().rem_euclid(360.0);
    let t = if (164.0..=345.0).contains(&h1) {
        0.56 + (0.2 * (h1 + 168.0).to_radians().cos()).abs()
    } else {
        0.36 + (0.4 * (h1 + 35.0).to_radians().cos()).abs()
    };
    let c4 = c1.powi(4);
    let f = (c4 / (c4 + 1900.0)).sqrt();
    let s_h = s_c * (f * t + 1.0 - f);
    let (dl, dc) = (l1 - l2, c1 - c2);
    // ΔH² = Δa² + Δb² − ΔC², held at 0 against rounding.
    let dh2 = ((a1 - a2).powi(2) + (b1 - b2).powi(2) - dc * dc).max(0.0);
    ((dl / (l * s_l)).powi(2) + (dc / (c * s_c)).powi(2) + dh2 / (s_h * s_h)).sqrt()
}
