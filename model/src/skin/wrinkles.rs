//! Expression wrinkles and lip furrows of the default head: where the furrows lie
//! ([`WrinkleMap`], drawn by `python/gen_wrinkles.py` into `data/heads/masks/wrinkles.png`) and
//! how deep each family is in a pose ([`WrinkleWeights::of`], from the Face Units that make it).
//!
//! Four families, one channel each ([`WrinkleFamily`]): forehead lines (raised brows), crow's
//! feet (a squint or a smile), the nasolabial folds (there at rest, deeper in a smile) and the
//! lips' vertical furrows (there at rest, deeper when the lips purse). The map stores each
//! furrow's depth as a fraction of its family's [`WrinkleFamily::depth_mm`]; the renderer bends
//! the skin's normal by the gradient of Σ weight · depth (the G-buffer pass, with the skin
//! detail). Left and right have their own weights (the Face Units do), blended across the
//! midline.
//!
//! *Choices*, not measurements: the furrows' shapes, sizes and depths follow the usual
//! description of facial wrinkles (frontal lines, lateral canthal lines, nasolabial fold,
//! perioral lines) at the scale of a young adult's dynamic wrinkles, and which Face Units deepen
//! which family follows the muscles that make them (frontalis: `browInnerUp`, `browOuterUp*`;
//! orbicularis oculi: `eyeSquint*`, `cheekSquint*`, and a smile; zygomaticus: `mouthSmile*`;
//! orbicularis oris: `mouthPucker`, `mouthFunnel`, `mouthPress*`). The map covers only the
//! square of the head's UVs where the face lies ([`WrinkleMap::uv_rect`], from
//! `wrinkles.json` beside it), at 2048² texels: about 0.08 mm a texel on the skin.

use crate::mesh::targets::Weights;
use serde::Deserialize;
use std::sync::OnceLock;

/// A family of furrows: one channel of the [`WrinkleMap`].
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum WrinkleFamily {
    /// Horizontal lines across the forehead.
    Forehead,
    /// Rays fanning out from the outer corners of the eyes.
    CrowsFeet,
    /// The folds from the nose's wings to beside the mouth's corners.
    Nasolabial,
    /// Vertical furrows across the lips' vermilion.
    LipFurrows,
}

impl WrinkleFamily {
    /// Every family, in channel order (r, g, b, a).
    pub const ALL: [WrinkleFamily; 4] =
        [WrinkleFamily::Forehead, WrinkleFamily::CrowsFeet, WrinkleFamily::Nasolabial, WrinkleFamily::LipFurrows];

    /// Its name, as `wrinkles.json` lists the channels.
    pub const fn name(self) -> &'static str {
        match self {
            WrinkleFamily::Forehead => "forehead",
            WrinkleFamily::CrowsFeet => "crows_feet",
            WrinkleFamily::Nasolabial => "nasolabial",
            WrinkleFamily::LipFurrows => "lip_furrows",
        }
    }

    /// Depth of the family's deepest furrow at weight 1, mm (*choice*, module doc). The
    /// furrows' half-widths (in the generator) are 0.55, 0.35, 3.0 and 0.22 mm, so their walls
    /// slope 0.2-0.45 at weight 1.
    pub const fn depth_mm(self) -> f32 {
        match self {
            WrinkleFamily::Forehead => 0.15,
            WrinkleFamily::CrowsFeet => 0.08,
            WrinkleFamily::Nasolabial => 0.6,
            WrinkleFamily::LipFurrows => 0.03,
        }
    }

    /// Its weight at rest (a neutral face): the nasolabial folds and the lip furrows are there
    /// without an expression (*choice*).
    pub const fn at_rest(self) -> f32 {
        match self {
            WrinkleFamily::Forehead | WrinkleFamily::CrowsFeet => 0.0,
            WrinkleFamily::Nasolabial => 0.3,
            WrinkleFamily::LipFurrows => 0.5,
        }
    }
}

/// How deep each family is on each side of the face, 0-1 of its [`WrinkleFamily::depth_mm`],
/// in [`WrinkleFamily::ALL`]'s order.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct WrinkleWeights {
    /// The subject's left (+x).
    pub left: [f32; 4],
    /// The subject's right (−x).
    pub right: [f32; 4],
}

impl Default for WrinkleWeights {
    /// A neutral face's.
    fn default() -> WrinkleWeights {
        WrinkleWeights::of(&Weights::new())
    }
}

impl WrinkleWeights {
    /// The weights of a pose from its resolved Face Unit weights (`TargetSet::resolve`): each
    /// family's rest weight raised toward 1 by the units that deepen it (module doc); unknown
    /// names and non-finite values count as 0.
    pub fn of(units: &Weights) -> WrinkleWeights {
        let w = |name: &str| units.get(name).copied().filter(|v| v.is_finite()).unwrap_or(0.0).clamp(0.0, 1.0);
        let side = |s: &str| {
            let drive = [
                w("browInnerUp").max(w(&format!("browOuterUp{s}"))),
                w(&format!("eyeSquint{s}")).max(w(&format!("cheekSquint{s}"))).max(0.8 * w(&format!("mouthSmile{s}"))),
                w(&format!("mouthSmile{s}")).max(w(&format!("cheekSquint{s}"))).max(0.8 * w(&format!("noseSneer{s}"))),
                w("mouthPucker").max(w("mouthFunnel")).max(0.5 * w(&format!("mouthPress{s}"))),
            ];
            let mut out = [0.0; 4];
            for ((o, d), f) in out.iter_mut().zip(drive).zip(WrinkleFamily::ALL) {
                *o = f.at_rest() + (1.0 - f.at_rest()) * d;
            }
            out
        };
        WrinkleWeights { left: side("Left"), right: side("Right") }
    }

    /// Each family's depth at weight × [`WrinkleFamily::depth_mm`], left then right, mm: what
    /// the G-buffer pass takes.
    pub fn depths_mm(&self) -> [[f32; 4]; 2] {
        let scale = |w: [f32; 4]| {
            let mut out = [0.0; 4];
            for ((o, w), f) in out.iter_mut().zip(w).zip(WrinkleFamily::ALL) {
                *o = w * f.depth_mm();
            }
            out
        };
        [scale(self.left), scale(self.right)]
    }
}

impl std::fmt::Display for WrinkleWeights {
    /// `forehead 0.00 / 0.00, crow's feet ..., lip furrows 0.50 / 0.50` (left / right).
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        for (i, family) in WrinkleFamily::ALL.into_iter().enumerate() {
            let name = family.name().replace('_', " ").replace("crows", "crow's");
            let sep = if i == 0 { "" } else { ", " };
            write!(f, "{sep}{name} {:.2} / {:.2}", self.left[i], self.right[i])?;
        }
        Ok(())
    }
}

/// Where the map lies in the head's UVs: the square from (u0, v0) with side `side`.
#[derive(Clone, Copy, Debug, PartialEq, Deserialize)]
pub struct UvRect {
    /// Lowest u.
    pub u0: f32,
    /// Lowest v.
    pub v0: f32,
    /// Side, in UV units.
    pub side: f32,
}

#[derive(Deserialize)]
struct MapFile {
    format: String,
    version: u32,
    uv_rect: UvRect,
    channels: Vec<String>,
}

/// The default head's furrows: RGBA8, one [`WrinkleFamily`] per channel, each texel the depth
/// as a fraction of the family's [`WrinkleFamily::depth_mm`]; row 0 at the rectangle's top
/// (v = v0 + side).
#[derive(Clone, Debug)]
pub struct WrinkleMap {
    /// The map, 2048² texels.
    pub image: image::RgbaImage,
    /// Where it lies in the head's UVs.
    pub uv_rect: UvRect,
}

static DEFAULT_HEAD: OnceLock<WrinkleMap> = OnceLock::new();

impl WrinkleMap {
    /// The default head's map, decoded on first use. The map and its `wrinkles.json` are
    /// embedded and checked by the tests; a failed decode would leave the skin without
    /// wrinkles (an empty map), never a panic.
    pub fn default_head() -> &'static WrinkleMap {
        DEFAULT_HEAD.get_or_init(|| {
            WrinkleMap::decode(
                include_bytes!("../../../data/heads/masks/wrinkles.png"),
                include_str!("../../../data/heads/masks/wrinkles.json"),
            )
            .unwrap_or(WrinkleMap {
                image: image::RgbaImage::new(1, 1),
                uv_rect: UvRect { u0: 0.0, v0: 0.0, side: 1.0 },
            })
        })
    }

    /// A map from its PNG and its `wrinkles.json`.
    ///
    /// # Errors
    /// A PNG that does not decode, a JSON of another format, version or channel list, or a
    /// rectangle outside the UV square.
    pub fn decode(png: &[u8], json: &str) -> Result<WrinkleMap, String> {
        let file: MapFile = serde_json::from_str(json).map_err(|e| format!("wrinkles.json: {e}"))?;
        let names: Vec<&str> = WrinkleFamily::ALL.iter().map(|f| f.name()).collect();
        if file.format != "rouge-wrinkles" || file.version != 1 || file.channels != names {
            return Err(format!(
                "wrinkles.json: expected format rouge-wrinkles version 1 with channels {names:?}, got {} {} {:?}",
                file.format, file.version, file.channels
            ));
        }
        let r = file.uv_rect;
        let inside = |x: f32| x.is_finite() && (0.0..=1.0).contains(&x);
        if !(inside(r.u0) && inside(r.v0) && r.side > 0.0 && inside(r.u0 + r.side) && inside(r.v0 + r.side)) {
            return Err(format!("wrinkles.json: uv_rect {r:?} is not a square inside the UVs"));
        }
        let image = image::load_from_memory(png).map_err(|e| format!("wrinkles.png: {e}"))?.to_rgba8();
        Ok(WrinkleMap { image, uv_rect: r })
    }

    /// The depth fraction (0-1) of `family` at UV (u, v), nearest texel; 0 outside the map.
    pub fn depth_at(&self, family: WrinkleFamily, u: f32, v: f32) -> f32 {
        let r = self.uv_rect;
        let (s, t) = ((u - r.u0) / r.side, 1.0 - (v - r.v0) / r.side);
        if !((0.0..1.0).contains(&s) && (0.0..1.0).contains(&t)) {
            return 0.0;
        }
        let (w, h) = self.image.dimensions();
        let c = WrinkleFamily::ALL.iter().position(|f| *f == family).unwrap_or(0);
        let p = self.image.get_pixel((s * w as f32) as u32, (t * h as f32) as u32);
        f32::from(p[c]) / 255.0
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::skin::AnatomyRegion;

    #[test]
    fn a_smile_deepens_the_folds_and_crows_feet_on_its_side_and_raised_brows_the_forehead() {
        let rest = WrinkleWeights::default();
        assert_eq!(rest.left, [0.0, 0.0, 0.3, 0.5]);
        assert_eq!(rest.left, rest.right);
        let units = |pairs: &[(&str, f32)]| pairs.iter().map(|(k, v)| (k.to_string(), *v)).collect::<Weights>();
        let smile = WrinkleWeights::of(&units(&[("mouthSmileLeft", 1.0)]));
        assert!(smile.left[2] == 1.0 && smile.left[1] > 0.7, "{smile:?}");
        assert_eq!(smile.right, rest.right, "the right side does not smile");
        let brows = WrinkleWeights::of(&units(&[("browInnerUp", 0.5)]));
        assert_eq!((brows.left[0], brows.right[0]), (0.5, 0.5));
        let pucker = WrinkleWeights::of(&units(&[("mouthPucker", 1.0)]));
        assert_eq!(pucker.left[3], 1.0);
        assert_eq!(
            rest.to_string(),
            "forehead 0.00 / 0.00, crow's feet 0.00 / 0.00, nasolabial 0.30 / 0.30, lip furrows 0.50 / 0.50"
        );
        // Bad values count as nothing.
        let bad = WrinkleWeights::of(&units(&[("browInnerUp", f32::NAN), ("mouthPucker", 7.0)]));
        assert_eq!((bad.left[0], bad.left[3]), (0.0, 1.0));
        let d = smile.depths_mm();
        assert!((d[0][2] - WrinkleFamily::Nasolabial.depth_mm()).abs() < 1e-6 && d[1][0] == 0.0);
    }

    #[test]
    fn each_family_lies_in_its_region_of_the_default_head() {
        let map = WrinkleMap::default_head();
        assert_eq!(map.image.dimensions(), (2048, 2048), "decoded");
        // For each family, the share of its furrowed texels that lie where the region says.
        let side = 512;
        let share = |family: WrinkleFamily, region: AnatomyRegion| {
            let (mut inside, mut all) = (0.0, 0.0);
            let r = map.uv_rect;
            for y in 0..side {
                for x in 0..side {
                    let u = r.u0 + r.side * (x as f32 + 0.5) / side as f32;
                    let v = r.v0 + r.side * (1.0 - (y as f32 + 0.5) / side as f32);
                    let d = map.depth_at(family, u, v);
                    if d > 0.3 {
                        all += 1.0;
                        inside += (region.weight_uv(u, v) > 0.05) as u8 as f64;
                    }
                }
            }
            assert!(all > 50.0, "{family:?}: {all} furrowed texels");
            inside / all
        };
        assert!(share(WrinkleFamily::Forehead, AnatomyRegion::Forehead) > 0.95);
        assert!(share(WrinkleFamily::LipFurrows, AnatomyRegion::Lips) > 0.95);
        // Crow's feet fan out from the eyes' outer corners: partly over the ends of the lids'
        // masks, never on the lips, the nose, the forehead or the cheeks.
        let lids = share(WrinkleFamily::CrowsFeet, AnatomyRegion::Eyelids)
            + share(WrinkleFamily::CrowsFeet, AnatomyRegion::UnderEye);
        assert!(lids > 0.3, "{lids}");
        for elsewhere in [AnatomyRegion::Lips, AnatomyRegion::Nose, AnatomyRegion::Forehead, AnatomyRegion::Cheeks] {
            assert_eq!(share(WrinkleFamily::CrowsFeet, elsewhere), 0.0, "{elsewhere:?}");
        }
        assert!(share(WrinkleFamily::Nasolabial, AnatomyRegion::Lips) < 0.2, "the folds lie beside the lips");
        // Outside the rectangle there is nothing.
        assert_eq!(map.depth_at(WrinkleFamily::Forehead, 0.1, 0.1), 0.0);
    }

    #[test]
    fn a_bad_sidecar_is_an_error_naming_it() {
        let png = include_bytes!("../../../data/heads/masks/wrinkles.png");
        let e = WrinkleMap::decode(
            png,
            r#"{"format":"rouge-wrinkles","version":2,"uv_rect":{"u0":0,"v0":0,"side":1},"channels":[]}"#,
        )
        .expect_err("version 2");
        assert!(e.contains("version 1"), "{e}");
        let e = WrinkleMap::decode(
            png,
            r#"{"format":"rouge-wrinkles","version":1,"uv_rect":{"u0":0.9,"v0":0,"side":0.5},"channels":["forehead","crows_feet","nasolabial","lip_furrows"]}"#,
        )
        .expect_err("outside");
        assert!(e.contains("uv_rect"), "{e}");
    }
}
