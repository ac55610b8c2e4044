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
}
