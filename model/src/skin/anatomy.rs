//! The regions of the default head and how the skin in each departs from the tone
//! (docs/SKIN.md, "Skin maps"; citations are keys of docs/REFERENCES.md).
//!
//! **Where the sizes come from.** Three kinds of number appear here, each doc comment says which:
//!
//! * *measured*: a ratio of two measurements of one study (epidermal thickness per facial site);
//! * *database*: a ratio of percentiles of the skin model's parameters fitted to the 4,252
//!   spectra of \[Xiao2016\] (nine body areas of 482 people; docs/SKIN.md, "Fitted parameters"):
//!   the spread of real skin as this model sees it;
//! * *choice*: where the literature ranks regions or describes a difference without a size, the
//!   size is a stated modelling choice bounded by the database's spread, never past it.
//!
//! A region's factors apply in full where its mask is 1 and not at all where it is 0, in log
//! space: a texel under masks of weights wᵣ has each parameter × Πᵣ fᵣ^wᵣ, so the soft masks
//! give smooth transitions and overlapping regions combine without an order.

use crate::look::{Region, ThicknessMap, decode_png_unit};
use rouge_measure::skin::SkinParams;
use std::sync::OnceLock;

// ------------------------------------------------------------------------------------------
// The database's spread (docs/SKIN.md, "Fitted parameters": 5th / 50th / 95th percentiles of the
// parameters fitted to [Xiao2016] by `python/gen_skin_tones.py`)

/// Melanin volume fraction, 5th percentile of the fitted database (docs/SKIN.md).
pub const MELANIN_P5: f64 = 0.017;
/// Melanin volume fraction, median of the fitted database (docs/SKIN.md).
pub const MELANIN_P50: f64 = 0.032;
/// Melanin volume fraction, 95th percentile of the fitted database (docs/SKIN.md).
pub const MELANIN_P95: f64 = 0.054;
/// Blood volume fraction, median of the fitted database (docs/SKIN.md).
pub const BLOOD_P50: f64 = 0.011;
/// Blood volume fraction, 95th percentile of the fitted database (docs/SKIN.md).
pub const BLOOD_P95: f64 = 0.039;
/// Oxygen saturation, 5th percentile of the fitted database (docs/SKIN.md).
pub const SATURATION_P5: f64 = 0.33;
/// Oxygen saturation, median of the fitted database (docs/SKIN.md).
pub const SATURATION_P50: f64 = 0.75;

/// *Database*: the median-to-95th-percentile ratio of the blood fraction (3.5): skin this much
/// redder than the median is as red as measured skin gets.
pub const BLOOD_SPREAD: f64 = BLOOD_P95 / BLOOD_P50;
/// *Choice*: one "step" of regional vascularity, the square root of [`BLOOD_SPREAD`] (1.9): half
/// the database's spread above the median, in log terms. Used where a study ranks facial units
/// by redness without a size (\[Kim2023\]).
pub const BLOOD_STEP: f64 = 1.882_937_743_382_543_6; // √(0.039 / 0.011)
/// *Database*: the median-to-95th-percentile ratio of the melanin fraction (1.7).
pub const MELANIN_SPREAD: f64 = MELANIN_P95 / MELANIN_P50;
/// *Choice*: one step of regional pigmentation, √[`MELANIN_SPREAD`] (1.3), as [`BLOOD_STEP`].
pub const MELANIN_STEP: f64 = 1.299_038_105_676_658; // √(0.054 / 0.032)
/// *Database*: the 5th-percentile-to-median ratio of the melanin fraction (0.53): skin this
/// much lighter than the median is as light as measured skin gets.
pub const MELANIN_LOW: f64 = MELANIN_P5 / MELANIN_P50;
/// *Database*: the 5th-to-95th-percentile ratio of the melanin fraction (3.2): the whole
/// measured range, the contrast of the darkest spots ([`super::Condition::Moles`]).
pub const MELANIN_RANGE: f64 = MELANIN_P95 / MELANIN_P5;
/// *Database*: the median-to-5th-percentile ratio of the oxygen saturation (0.44): blood this
/// much less oxygenated is as venous as the database's fitted skin gets.
pub const SATURATION_LOW: f64 = SATURATION_P5 / SATURATION_P50;

// ------------------------------------------------------------------------------------------
// Epidermal thickness per facial site ([Meng2022] Table 2, women, high-frequency ultrasound;
// [Chopra2015], histology). Ultrasound's epidermis includes the entry echo, so only ratios
// between sites are taken, relative to the zygoma (the cheek), the face's usual skin.

/// *Measured*: eyelid epidermis over zygoma epidermis, 0.17 mm / 0.20 mm (\[Meng2022\] Table 2,
/// women): the periorbital skin is the face's thinnest (\[Chopra2015\], \[Ha2005\]).
pub const EPIDERMIS_EYELID: f64 = 0.17 / 0.20;
/// *Measured*: temple over zygoma, 0.18 mm / 0.20 mm (\[Meng2022\] Table 2, women).
pub const EPIDERMIS_TEMPLE: f64 = 0.18 / 0.20;
/// *Measured*: nasal dorsum over zygoma, 0.19 mm / 0.20 mm (\[Meng2022\] Table 2, women).
pub const EPIDERMIS_NOSE: f64 = 0.19 / 0.20;
/// *Measured*, with one assumption: the posterior auricular epidermis, 29.6 µm, is the face's
/// thinnest, the upper lip's 62.6 µm its thickest (\[Chopra2015\], 39 sites); over the middle of
/// that range, 46.1 µm (the assumption: the face's usual skin lies mid-range), 0.64.
pub const EPIDERMIS_EAR: f64 = 29.6 / ((29.6 + 62.6) / 2.0);
/// *Choice*: the vermilion's keratinised surface is thinner than the facial skin's, with a far
/// weaker barrier (\[Kobayashi2004\]); how much thinner the model's melanin-bearing layer
/// should be is not measured there: half.
pub const EPIDERMIS_LIPS: f64 = 0.5;

// ------------------------------------------------------------------------------------------
// Regions

/// A region of the default head: a soft UV mask (1024², weights in [0, 1], made from the 3D head
/// by `python/gen_head.py`; lips, cheeks and eyelids are the look regions' own masks).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum AnatomyRegion {
    /// The vermilion of both lips ([`Region::Lips`]).
    Lips,
    /// Both cheeks over the cheekbones ([`Region::Cheeks`]).
    Cheeks,
    /// Both upper eyelids ([`Region::Eyelids`]).
    Eyelids,
    /// The external nose, bridge to alae.
    Nose,
    /// The forehead (the T-zone's forehead ellipse).
    Forehead,
    /// The lower lids and the infraorbital skin below them.
    UnderEye,
    /// Both auricles.
    Ears,
    /// The mental prominence.
    Chin,
    /// Both temples.
    Temples,
}

const ANATOMY_PNGS: [&[u8]; 6] = [
    include_bytes!("../../../data/heads/masks/nose.png"),
    include_bytes!("../../../data/heads/masks/forehead.png"),
    include_bytes!("../../../data/heads/masks/under_eye.png"),
    include_bytes!("../../../data/heads/masks/ears.png"),
    include_bytes!("../../../data/heads/masks/chin.png"),
    include_bytes!("../../../data/heads/masks/temples.png"),
];

static ANATOMY_MASKS: [OnceLock<ThicknessMap>; 6] = [const { OnceLock::new() }; 6];

impl AnatomyRegion {
    /// Every region.
    pub const ALL: [AnatomyRegion; 9] = [
        AnatomyRegion::Lips,
        AnatomyRegion::Cheeks,
        AnatomyRegion::Eyelids,
        AnatomyRegion::Nose,
        AnatomyRegion::Forehead,
        AnatomyRegion::UnderEye,
        AnatomyRegion::Ears,
        AnatomyRegion::Chin,
        AnatomyRegion::Temples,
    ];

    /// Its name, as its mask's file name in `data/heads/masks/`.
    pub const fn name(self) -> &'static str {
        match self {
            AnatomyRegion::Lips => "lips",
            AnatomyRegion::Cheeks => "cheeks",
            AnatomyRegion::Eyelids => "eyelids",
            AnatomyRegion::Nose => "nose",
            AnatomyRegion::Forehead => "forehead",
            AnatomyRegion::UnderEye => "under_eye",
            AnatomyRegion::Ears => "ears",
            AnatomyRegion::Chin => "chin",
            AnatomyRegion::Temples => "temples",
        }
    }

    /// The region's mask in the default head's UVs (weights in [0, 1], 1024 × 1024), decoded on
    /// first use. The masks are embedded and checked by the tests; a failed decode would leave
    /// the region empty rather than abort.
    pub fn mask(self) -> &'static ThicknessMap {
        let own = |i: usize| {
            ANATOMY_MASKS[i]
                .get_or_init(|| decode_png_unit(ANATOMY_PNGS[i]).unwrap_or_else(|_| ThicknessMap::uniform(0.0)))
        };
        match self {
            AnatomyRegion::Lips => Region::Lips.mask(),
            AnatomyRegion::Cheeks => Region::Cheeks.mask(),
            AnatomyRegion::Eyelids => Region::Eyelids.mask(),
            AnatomyRegion::Nose => own(0),
            AnatomyRegion::Forehead => own(1),
            AnatomyRegion::UnderEye => own(2),
            AnatomyRegion::Ears => own(3),
            AnatomyRegion::Chin => own(4),
            AnatomyRegion::Temples => own(5),
        }
    }

    /// The mask's weight at OBJ-convention UV (bilinear).
    pub fn weight_uv(self, u: f32, v: f32) -> f64 {
        f64::from(self.mask().sample_uv(u, v).clamp(0.0, 1.0))
    }

    /// How the healthy skin of the region departs from the tone, at full weight.
    pub const fn factors(self) -> Factors {
        match self {
            AnatomyRegion::Lips => LIPS,
            AnatomyRegion::Cheeks => CHEEKS,
            AnatomyRegion::Eyelids => EYELIDS,
            AnatomyRegion::Nose => NOSE,
            AnatomyRegion::Forehead => FOREHEAD,
            AnatomyRegion::UnderEye => UNDER_EYE,
            AnatomyRegion::Ears => EARS,
            AnatomyRegion::Chin => CHIN,
            AnatomyRegion::Temples => TEMPLES,
        }
    }
}

/// Factors on the tone's parameters (1 = as the tone); the pheomelanin share and the scattering
/// are the tone's everywhere.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Factors {
    /// On the melanin fraction.
    pub melanin: f64,
    /// On the blood fraction.
    pub blood: f64,
    /// On the oxygen saturation.
    pub oxygen: f64,
    /// On the epidermis thickness.
    pub epidermis: f64,
}

impl Factors {
    /// No change.
    pub const NONE: Factors = Factors { melanin: 1.0, blood: 1.0, oxygen: 1.0, epidermis: 1.0 };
}

/// The vermilion: the face's reddest surface, its blood seen through a thin, poorly keratinised
/// surface layer (\[Kobayashi2004\]). Blood × [`BLOOD_SPREAD`] (*database*:
/// the lips as red as the reddest measured skin), melanin × [`MELANIN_LOW`] (*choice*: lighter
/// than the skin around them where melanin sets the colour; no measured melanin content of the
/// vermilion was found), epidermis × [`EPIDERMIS_LIPS`].
pub const LIPS: Factors = Factors { melanin: MELANIN_LOW, blood: BLOOD_SPREAD, oxygen: 1.0, epidermis: EPIDERMIS_LIPS };

/// The cheeks: with the nose and the perinasal skin the most hypervascular facial units of 198
/// people scored on haemoglobin images (\[Kim2023\]); blood × [`BLOOD_STEP`].
pub const CHEEKS: Factors = Factors { blood: BLOOD_STEP, ..Factors::NONE };

/// The nose: among the most hypervascular units (\[Kim2023\]), blood × [`BLOOD_STEP`]; epidermis ×
/// [`EPIDERMIS_NOSE`] (\[Meng2022\]).
pub const NOSE: Factors = Factors { blood: BLOOD_STEP, epidermis: EPIDERMIS_NOSE, ..Factors::NONE };

/// The upper eyelids: the face's thinnest skin (\[Ha2005\], \[Chopra2015\]), epidermis ×
/// [`EPIDERMIS_EYELID`] (\[Meng2022\]).
pub const EYELIDS: Factors = Factors { epidermis: EPIDERMIS_EYELID, ..Factors::NONE };

/// The infraorbital skin: as thin as the lids (epidermis × [`EPIDERMIS_EYELID`], \[Meng2022\]) and
/// darker than the cheek below it, melanin the main cause (\[Matsui2015\]): melanin ×
/// √[`MELANIN_STEP`] (*choice*: half a step in healthy skin; the condition
/// [`super::Condition::UnderEye`] adds the rest).
pub const UNDER_EYE: Factors =
    Factors { melanin: 1.139_753_528_477_388_8, epidermis: EPIDERMIS_EYELID, ..Factors::NONE }; // √1.299

/// The forehead: the darkest of seven facial sites measured in 157 women (\[Choi2017\]), melanin ×
/// [`MELANIN_STEP`]; its epidermis as the zygoma's (0.20 mm both, \[Meng2022\]).
pub const FOREHEAD: Factors = Factors { melanin: MELANIN_STEP, ..Factors::NONE };

/// The chin: the reddest of the seven sites of \[Choi2017\], blood × [`BLOOD_STEP`].
pub const CHIN: Factors = Factors { blood: BLOOD_STEP, ..Factors::NONE };

/// The ears: the thinnest epidermis of the face (posterior auricular skin, \[Chopra2015\]),
/// epidermis × [`EPIDERMIS_EAR`]; blood × [`BLOOD_STEP`] (*choice*: the auricle's thin skin shows
/// its vessels; no measured redness of the ear was found).
pub const EARS: Factors = Factors { blood: BLOOD_STEP, epidermis: EPIDERMIS_EAR, ..Factors::NONE };

/// The temples: among the least erythematous units (\[Kim2023\]), blood ÷ [`BLOOD_STEP`]; epidermis
/// × [`EPIDERMIS_TEMPLE`] (\[Meng2022\]).
pub const TEMPLES: Factors = Factors { blood: 0.531_085_004_543_794_4, epidermis: EPIDERMIS_TEMPLE, ..Factors::NONE }; // 1/1.883

/// Log-space weights of the regions at one texel: Σᵣ wᵣ ln fᵣ per parameter.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct LogFactors {
    /// Σ w ln f on the melanin fraction.
    pub melanin: f64,
    /// Σ w ln f on the blood fraction.
    pub blood: f64,
    /// Σ w ln f on the oxygen saturation.
    pub oxygen: f64,
    /// Σ w ln f on the epidermis thickness.
    pub epidermis: f64,
}

impl LogFactors {
    /// Adds `factors` at weight `w`.
    pub fn add(&mut self, factors: Factors, w: f64) {
        self.melanin += w * factors.melanin.ln();
        self.blood += w * factors.blood.ln();
        self.oxygen += w * factors.oxygen.ln();
        self.epidermis += w * factors.epidermis.ln();
    }

    /// `base` with these factors applied: each parameter × exp(Σ w ln f).
    pub fn apply(&self, base: &SkinParams) -> SkinParams {
        SkinParams {
            melanin_fraction: base.melanin_fraction * self.melanin.exp(),
            blood_fraction: base.blood_fraction * self.blood.exp(),
            oxygen_saturation: base.oxygen_saturation * self.oxygen.exp(),
            epidermis_thickness_mm: base.epidermis_thickness_mm * self.epidermis.exp(),
            ..*base
        }
    }

    /// The healthy anatomy at OBJ-convention UV: every region at its mask's weight.
    pub fn anatomy_at(u: f32, v: f32) -> LogFactors {
        let mut l = LogFactors::default();
        for r in AnatomyRegion::ALL {
            let w = r.weight_uv(u, v);
            if w > 0.0 {
                l.add(r.factors(), w);
            }
        }
        l
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_written_out_constants_are_their_formulas() {
        let close = |a: f64, b: f64| (a - b).abs() < 1e-12 * b.abs().max(1.0);
        assert!(close(BLOOD_STEP, BLOOD_SPREAD.sqrt()));
        assert!(close(MELANIN_STEP, MELANIN_SPREAD.sqrt()));
        assert!(close(UNDER_EYE.melanin, MELANIN_STEP.sqrt()));
        assert!(close(TEMPLES.blood, 1.0 / BLOOD_STEP));
    }

    #[test]
    fn every_mask_decodes_at_full_size_with_an_inside_and_an_outside() {
        for r in AnatomyRegion::ALL {
            let m = r.mask();
            assert_eq!((m.width, m.height), (1024, 1024), "{}", r.name());
            assert!(m.mm.iter().all(|v| (0.0..=1.0).contains(v)), "{}", r.name());
            assert!(m.max_mm() == 1.0, "{} reaches full weight", r.name());
            assert!(m.mm.iter().filter(|&&v| v == 0.0).count() > m.mm.len() / 2, "{} is mostly outside", r.name());
        }
    }
}
