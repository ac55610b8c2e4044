//! Blood that follows the face's expression (after \[Jimenez2010\], who measured haemoglobin
//! maps of faces moving through expressions and found blood pooling where skin is compressed and
//! leaving where it is stretched or pressed): the skin maps' blood, scaled per region by the
//! Face Units the pose drives. A smile bunches the cheeks, which flush; pressed, rolled or
//! puckered lips blanch. Only the blood channel moves, by region masks (soft, seam-free), so an
//! expression never changes melanin or the epidermis.
//!
//! The sizes are choices, bounded like the anatomy's (docs/SKIN.md): a full smile flushes the
//! cheeks by one regional step of blood ([`BLOOD_STEP`], ×1.88: the database's √(p95/p50)),
//! pressed lips lose half their blood (the vermilion's blood over a whole step down, ×0.53). The
//! paper reports the directions and where, not amounts on our scale.

use super::anatomy::{AnatomyRegion, BLOOD_STEP};
use super::{SkinChannel, SkinMaps};
use crate::mesh::targets::Weights;

/// Blood on the lips at full press, ×.
pub const PRESSED_LIPS_BLOOD: f64 = 1.0 / BLOOD_STEP;

/// One region's blood factor from the pose's Face Unit weights (0 to 1 each).
struct Flow {
    region: AnatomyRegion,
    /// Units that drive it, each with its weight, the strongest taken.
    units: &'static [(&'static str, f64)],
    /// The factor at full drive.
    factor: f64,
}

/// Which units move blood where.
const FLOWS: [Flow; 2] = [
    Flow {
        region: AnatomyRegion::Cheeks,
        units: &[
            ("mouthSmileLeft", 1.0),
            ("mouthSmileRight", 1.0),
            ("cheekSquintLeft", 1.0),
            ("cheekSquintRight", 1.0),
        ],
        factor: BLOOD_STEP,
    },
    Flow {
        region: AnatomyRegion::Lips,
        units: &[
            ("mouthPressLeft", 1.0),
            ("mouthPressRight", 1.0),
            ("mouthRollLower", 1.0),
            ("mouthRollUpper", 1.0),
            ("mouthPucker", 0.5),
        ],
        factor: PRESSED_LIPS_BLOOD,
    },
];

/// The regions whose blood `units` (a pose's resolved expression weights,
/// [`crate::mesh::targets::TargetSet::resolve`]) move, each with its factor: the strongest of its
/// units times the full factor, in log space (half a smile, half the step). Empty for a neutral
/// pose.
pub fn blood_factors(units: &Weights) -> Vec<(AnatomyRegion, f64)> {
    FLOWS
        .iter()
        .filter_map(|f| {
            let drive = f
                .units
                .iter()
                .map(|(name, w)| f64::from(units.get(*name).copied().unwrap_or(0.0)).clamp(0.0, 1.0) * w)
                .fold(0.0, f64::max);
            (drive > 0.0).then(|| (f.region, f.factor.powf(drive)))
        })
        .collect()
}

impl SkinMaps {
    /// The maps with the blood of `units`'s expression ([`blood_factors`]): each texel's blood
    /// × Πᵣ fᵣ^wᵣ over the regions' mask weights wᵣ, kept inside the blood's range. The same maps
    /// for a neutral pose.
    pub fn with_blood_flow(&self, units: &Weights) -> SkinMaps {
        let factors = blood_factors(units);
        if factors.is_empty() {
            return self.clone();
        }
        let (w, h) = (self.width() as usize, self.height() as usize);
        let (lo, hi) = SkinChannel::Blood.range(self.base());
        let mut out = self.clone();
        let blood = &mut out.planes[SkinChannel::Blood as usize];
        for (i, b) in blood.iter_mut().enumerate() {
            let u = ((i % w) as f32 + 0.5) / w as f32;
            let v = 1.0 - ((i / w) as f32 + 0.5) / h as f32;
            let log: f64 = factors.iter().map(|(r, f)| r.weight_uv(u, v) * f.ln()).sum();
            if log != 0.0 {
                *b = (f64::from(*b) * log.exp()).clamp(lo, hi) as f32;
            }
        }
        out
    }
}
