//! Named skin tones from very light to very deep: the skin model's parameters fitted to real
//! spectra of the Xiao et al. 2016 database (\[Xiao2016\]) where it has them, and extended past its
//! deepest skins by melanin. The tones are data (`data/skin/tones.json`, embedded; made by
//! `python/gen_skin_tones.py`, which names for each tone the spectra it came from).

use super::{SkinError, SkinParams};
use crate::colorimetry::Lab;
use std::sync::OnceLock;

const TONES_JSON: &str = include_str!("../../../data/skin/tones.json");

/// One named tone.
#[derive(Clone, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SkinTone {
    /// Short name (`very-light`, ..., `very-deep`): what `--skin-tone` takes.
    pub name: String,
    /// The Fitzpatrick type it is typical of (I-VI), for orientation only.
    pub fitzpatrick: String,
    /// The model's parameters.
    pub params: SkinParams,
    /// Where the parameters come from.
    pub source: String,
}

#[derive(serde::Deserialize)]
#[serde(deny_unknown_fields)]
struct TonesFile {
    schema: String,
    version: u32,
    #[allow(dead_code)]
    description: String,
    tones: Vec<SkinTone>,
}

/// The built-in tones, light to deep.
pub fn skin_tones() -> &'static [SkinTone] {
    static TONES: OnceLock<Vec<SkinTone>> = OnceLock::new();
    TONES.get_or_init(|| {
        // Checked by `the_tones_load_and_span_the_ita_range`; an unreadable embedded file would be
        // a build error caught there, so an empty list stands in rather than a panic.
        match serde_json::from_str::<TonesFile>(TONES_JSON) {
            Ok(f) if f.schema == "rouge-skin-tones" && f.version == 1 => f.tones,
            _ => Vec::new(),
        }
    })
}

/// The tone called `name`, or an error listing the names.
pub fn skin_tone(name: &str) -> Result<&'static SkinTone, SkinError> {
    skin_tones().iter().find(|t| t.name == name).ok_or_else(|| SkinError::UnknownTone {
        name: name.to_string(),
        known: skin_tones().iter().map(|t| t.name.as_str()).collect::<Vec<_>>().join(", "),
    })
}

/// The skin of a given Individual Typology Angle (degrees, as [`ita_deg`] computes it) between
/// the built-in tones: on the straight line in parameter space between the two tones whose ITAs
/// bracket it, at the point whose ITA is `ita_deg` (bisection; the ITA falls monotonically
/// along each segment of the light-to-deep tones). A tone's own ITA gives that tone.
///
/// # Errors
/// [`SkinError::ItaOutOfRange`] outside the tones' span (or for NaN), the model's errors.
pub fn skin_at_ita(ita: f64) -> Result<SkinParams, SkinError> {
    let tones = skin_tones();
    let itas = tone_itas();
    let (Some(&lightest), Some(&deepest)) = (itas.first(), itas.last()) else {
        return Err(SkinError::ItaOutOfRange { ita_deg: ita, deepest: f64::NAN, lightest: f64::NAN });
    };
    if !(deepest..=lightest).contains(&ita) {
        return Err(SkinError::ItaOutOfRange { ita_deg: ita, deepest, lightest });
    }
    // The segment [k, k + 1] with itas[k] ≥ ita ≥ itas[k + 1].
    let k = itas.windows(2).position(|w| w[0] >= ita && ita >= w[1]).unwrap_or(0);
    let (a, b) = (tones[k].params.to_array(), tones[(k + 1).min(tones.len() - 1)].params.to_array());
    let at = |t: f64| SkinParams::from_array(std::array::from_fn(|i| a[i] + (b[i] - a[i]) * t));
    let (mut lo, mut hi) = (0.0f64, 1.0f64);
    for _ in 0..40 {
        let mid = 0.5 * (lo + hi);
        if ita_deg(&crate::skin::fit::lab_d65(&at(mid).reflectance()?)) > ita {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    Ok(at(0.5 * (lo + hi)))
}

/// The built-in tones' ITAs, light to deep (computed once).
fn tone_itas() -> &'static [f64] {
    static ITAS: OnceLock<Vec<f64>> = OnceLock::new();
    ITAS.get_or_init(|| {
        skin_tones()
            .iter()
            .map_while(|t| t.params.reflectance().ok().map(|r| ita_deg(&crate::skin::fit::lab_d65(&r))))
            .collect()
    })
}

/// A named tone (`rouge skin tones`) or an ITA in degrees (a number): what `--skin-tone` takes.
///
/// # Errors
/// An unknown name, an ITA outside the tones' span.
pub fn skin_tone_or_ita(spec: &str) -> Result<SkinParams, SkinError> {
    match spec.trim().parse::<f64>() {
        Ok(ita) => skin_at_ita(ita),
        Err(_) => Ok(skin_tone(spec)?.params),
    }
}

/// Individual Typology Angle, degrees: atan2(L* − 50, b*) (\[Chardon1991\]; D65, CIE 1931 in Rouge).
/// > 55° very light, 41-55 light, 28-41 intermediate, 10-28 tan, −30-10 brown, < −30 dark.
pub fn ita_deg(lab: &Lab) -> f64 {
    (lab.lab[0] - 50.0).atan2(lab.lab[2]).to_degrees()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::skin::fit::lab_d65;

    #[test]
    fn the_tones_load_and_span_the_ita_range() {
        let tones = skin_tones();
        assert!(tones.len() >= 10, "{}", tones.len());
        let itas: Vec<f64> = tones.iter().map(|t| ita_deg(&lab_d65(&t.params.reflectance().unwrap()))).collect();
        assert!(itas[0] > 55.0 && *itas.last().unwrap() < -55.0, "{itas:?}");
        assert!(itas.windows(2).all(|w| w[1] < w[0]), "light to deep: {itas:?}");
        assert!(skin_tone(&tones[0].name).is_ok());
        assert_eq!(skin_tone("light").unwrap().params, SkinParams::LIGHT, "SkinParams::LIGHT is the light tone");
        let e = skin_tone("mauve").unwrap_err().to_string();
        assert!(e.contains("mauve") && e.contains(&tones[0].name), "{e}");
    }

    #[test]
    fn an_ita_gives_the_skin_of_that_angle_between_the_tones() {
        for ita in [57.0, 35.0, 0.0, -20.0, -50.0] {
            let p = skin_at_ita(ita).unwrap();
            let got = ita_deg(&lab_d65(&p.reflectance().unwrap()));
            assert!((got - ita).abs() < 0.01, "{ita}: {got}");
        }
        // A tone's own angle gives (nearly) the tone.
        let light = skin_tone("light").unwrap().params;
        let own = ita_deg(&lab_d65(&light.reflectance().unwrap()));
        let p = skin_at_ita(own).unwrap();
        assert!((p.melanin_fraction - light.melanin_fraction).abs() < 1e-6, "{p:?}");
        for bad in [80.0, -80.0, f64::NAN] {
            let e = skin_at_ita(bad).unwrap_err().to_string();
            assert!(e.contains("ITA") && e.contains("span"), "{e}");
        }
        assert_eq!(skin_tone_or_ita("tan").unwrap(), skin_tone("tan").unwrap().params);
        assert!(skin_tone_or_ita("30").is_ok() && skin_tone_or_ita("ochre").is_err());
    }
}
