//! Skin maps: the spectral skin model's varying parameters ([`SkinParams`]) per texel of the
//! mesh's UV space, so that a face is not one flat skin colour (docs/SKIN.md, "Skin maps").
//!
//! - [`SkinMaps`]: melanin fraction, pheomelanin share, blood fraction, oxygen saturation and
//!   epidermis thickness per texel ([`SkinChannel`]); the scattering (a, b) stays the tone's.
//!   Every texel is inside [`SkinParams::RANGES`] and the transport table's reach, always:
//!   constructors clamp ([`clamp_params`]) or refuse ([`SkinMaps::from_planes`]).
//! - [`anatomy`]: the regions of the default head ([`AnatomyRegion`], masks made by
//!   `python/gen_head.py`) and how each departs from the tone, with its sources.
//! - [`conditions`]: [`SkinConditions`], the amounts of freckles, moles, redness, acne,
//!   hyperpigmentation, under-eye darkness and visible veins (`freckles=0.6,redness=0.4`).
//! - [`generate`]: [`SkinMaps::generate`], the tone + anatomy + conditions, deterministic per seed.
//! - [`edits`]: [`SkinEdits`], what the app's skin brushes paint (log factors on melanin and
//!   blood per texel) on top of the generated maps.
//! - [`detail`] and [`wrinkles`]: the skin's microgeometry (pores, fine lines) and the default
//!   head's expression wrinkles and lip furrows, for the renderer's G-buffer pass.
//! - [`table_cache`]: each tone's skin colour table kept on disk between runs.
//! - [`file`](mod@file): the maps as one multi-channel OpenEXR and the project's `skin.json`
//!   ([`SkinRecipe`], [`ProjectSkin`]); docs/FORMATS.md.
//!
//! UV convention: as [`crate::look::ThicknessMap`]: row 0 is the top of the image (v = 1); pixel
//! (x, y) of a w × h map has its centre at u = (x + 0.5)/w, v = 1 − (y + 0.5)/h.

pub mod albedo;
pub mod anatomy;
pub mod blood_flow;
pub mod conditions;
pub mod detail;
pub mod edits;
pub mod file;
pub mod generate;
pub mod table_cache;
pub mod wrinkles;

pub use anatomy::AnatomyRegion;
pub use conditions::{Condition, ConditionError, SkinConditions};
pub use detail::{DetailTile, RegionDetail};
pub use edits::{SkinBrush, SkinBrushKind, SkinEdits};
pub use file::{ProjectSkin, SKIN_FILE, SkinRecipe};
pub use wrinkles::{WrinkleFamily, WrinkleMap, WrinkleWeights};

use crate::TexelRect;
use rouge_measure::skin::SkinParams;

/// One parameter of the skin model that varies over a face: a channel of [`SkinMaps`].
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum SkinChannel {
    /// [`SkinParams::melanin_fraction`].
    Melanin,
    /// [`SkinParams::pheomelanin_share`].
    Pheomelanin,
    /// [`SkinParams::blood_fraction`].
    Blood,
    /// [`SkinParams::oxygen_saturation`].
    Oxygen,
    /// [`SkinParams::epidermis_thickness_mm`].
    Epidermis,
}

impl SkinChannel {
    /// Every channel, in the maps' order.
    pub const ALL: [SkinChannel; 5] = [
        SkinChannel::Melanin,
        SkinChannel::Pheomelanin,
        SkinChannel::Blood,
        SkinChannel::Oxygen,
        SkinChannel::Epidermis,
    ];

    /// Its index in [`SkinParams::to_array`] and [`SkinParams::RANGES`].
    const fn param_index(self) -> usize {
        match self {
            SkinChannel::Melanin => 0,
            SkinChannel::Pheomelanin => 1,
            SkinChannel::Blood => 2,
            SkinChannel::Oxygen => 3,
            SkinChannel::Epidermis => 6,
        }
    }

    /// The parameter's name, as the field of [`SkinParams`] (and the EXR channel).
    pub const fn name(self) -> &'static str {
        SkinParams::RANGES[self.param_index()].name
    }

    /// Its value in `p`.
    pub fn of(self, p: &SkinParams) -> f64 {
        p.to_array()[self.param_index()]
    }

    /// `p` with this parameter set to `v` (unchecked).
    pub fn with(self, p: &SkinParams, v: f64) -> SkinParams {
        let mut a = p.to_array();
        a[self.param_index()] = v;
        SkinParams::from_array(a)
    }

    /// The channel's range: [`SkinParams::RANGES`], and for the epidermis at most
    /// [`SkinParams::max_epidermis_mm`] of `base`'s scattering.
    pub fn range(self, base: &SkinParams) -> (f64, f64) {
        let r = SkinParams::RANGES[self.param_index()];
        match self {
            SkinChannel::Epidermis => (r.min, r.max.min(base.max_epidermis_mm())),
            _ => (r.min, r.max),
        }
    }
}

/// `p` with every parameter inside [`SkinParams::RANGES`] and the epidermis inside the table's
/// reach ([`SkinParams::max_epidermis_mm`]): a non-finite value becomes [`SkinParams::LIGHT`]'s, then each is
/// clamped, the scattering first (the epidermis' bound depends on it). The result always passes
/// [`SkinParams::validate`].
pub fn clamp_params(p: &SkinParams) -> SkinParams {
    let light = SkinParams::LIGHT.to_array();
    let mut a = p.to_array();
    for ((v, r), fallback) in a.iter_mut().zip(SkinParams::RANGES).zip(light) {
        let finite = if v.is_finite() { *v } else { fallback };
        *v = finite.clamp(r.min, r.max);
    }
    let clamped = SkinParams::from_array(a);
    let (lo, hi) = SkinChannel::Epidermis.range(&clamped);
    SkinChannel::Epidermis.with(&clamped, clamped.epidermis_thickness_mm.clamp(lo, hi))
}

/// `v` (inside [lo, hi]) as the nearest f32 whose value is still inside [lo, hi].
fn f32_within(v: f64, lo: f64, hi: f64) -> f32 {
    let f = v as f32;
    if f64::from(f) > hi {
        f.next_down()
    } else if f64::from(f) < lo {
        f.next_up()
    } else {
        f
    }
}

/// The skin model's varying parameters over the mesh's UV space: one plane of f32 per
/// [`SkinChannel`], `width × height` texels, row 0 at the top (v = 1), like
/// [`crate::look::ThicknessMap`]; the scattering and any other parameter from `base`.
///
/// Invariant: every texel, with `base`'s scattering, passes [`SkinParams::validate`].
#[derive(Clone, PartialEq)]
pub struct SkinMaps {
    width: u32,
    height: u32,
    base: SkinParams,
    planes: [Vec<f32>; 5],
}

impl std::fmt::Debug for SkinMaps {
    /// The size, the base and each channel's range (not millions of values).
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let mut d = f.debug_struct("SkinMaps");
        d.field("width", &self.width).field("height", &self.height).field("base", &self.base);
        for c in SkinChannel::ALL {
            let (lo, hi) =
                self.plane(c).iter().fold((f32::INFINITY, f32::NEG_INFINITY), |(a, b), &v| (a.min(v), b.max(v)));
            d.field(c.name(), &(lo..=hi));
        }
        d.finish()
    }
}

impl SkinMaps {
    /// A 1 × 1 map: `params` everywhere, clamped as by [`clamp_params`] (which the base is too).
    pub fn uniform(params: &SkinParams) -> SkinMaps {
        let base = clamp_params(params);
        let planes = SkinChannel::ALL.map(|c| {
            let (lo, hi) = c.range(&base);
            vec![f32_within(c.of(&base), lo, hi)]
        });
        SkinMaps { width: 1, height: 1, base, planes }
    }

    /// Maps from planes of f32 values in the order of [`SkinChannel::ALL`], each `width ×
    /// height` long, checked: `base` must pass [`SkinParams::validate`], and every value must be
    /// inside its channel's [`SkinChannel::range`]. Errors name the channel, texel and value.
    pub fn from_planes(
        width: u32,
        height: u32,
        base: &SkinParams,
        planes: [Vec<f32>; 5],
    ) -> std::result::Result<SkinMaps, String> {
        base.validate().map_err(|e| format!("base parameters: {e}"))?;
        let n = width as usize * height as usize;
        if n == 0 {
            return Err(format!("a {width}×{height} map has no texels"));
        }
        for (c, plane) in SkinChannel::ALL.iter().zip(&planes) {
            if plane.len() != n {
                return Err(format!("channel {} has {} values for {width}×{height} texels", c.name(), plane.len()));
            }
            let (lo, hi) = c.range(base);
            if let Some(i) = plane.iter().position(|&v| !(lo..=hi).contains(&f64::from(v))) {
                let w = width as usize;
                return Err(format!(
                    "texel ({}, {}) of channel {} is {}: outside [{lo}, {hi}]",
                    i % w,
                    i / w,
                    c.name(),
                    plane[i]
                ));
            }
        }
        Ok(SkinMaps { width, height, base: *base, planes })
    }

    /// Width in texels.
    pub fn width(&self) -> u32 {
        self.width
    }

    /// Height in texels.
    pub fn height(&self) -> u32 {
        self.height
    }

    /// The parameters that do not vary (the scattering), and the values the maps were made from.
    pub fn base(&self) -> &SkinParams {
        &self.base
    }

    /// One channel's values, row 0 first (`width × height`).
    pub fn plane(&self, channel: SkinChannel) -> &[f32] {
        &self.planes[channel as usize]
    }

    /// The parameters of texel (x, y), x and y clamped to the map (clamp-to-edge): valid.
    pub fn texel(&self, x: u32, y: u32) -> SkinParams {
        let i = self.index(x, y);
        let mut a = self.base.to_array();
        for c in SkinChannel::ALL {
            a[c.param_index()] = f64::from(self.planes[c as usize][i]);
        }
        SkinParams::from_array(a)
    }

    /// The parameters at OBJ-convention UV (u right, v up), interpolated bilinearly between
    /// texel centres with clamp-to-edge addressing (what a GPU sampler returns for texture
    /// coordinate (u, 1 − v)); valid (clamped after interpolating, against rounding), never
    /// NaN (a NaN coordinate reads the first texel).
    pub fn sample_uv(&self, u: f32, v: f32) -> SkinParams {
        let (x, y) = (u * self.width as f32 - 0.5, (1.0 - v) * self.height as f32 - 0.5);
        let (x0, y0) = (x.floor(), y.floor());
        let (fx, fy) = (f64::from(x - x0), f64::from(y - y0));
        let (fx, fy) = (if fx.is_finite() { fx } else { 0.0 }, if fy.is_finite() { fy } else { 0.0 });
        // Float-to-int casts saturate (NaN becomes 0), so clamping needs no special cases.
        let clamp = |i: f32, n: u32| (i as i64).clamp(0, i64::from(n) - 1) as u32;
        let (xa, xb) = (clamp(x0, self.width), clamp(x0 + 1.0, self.width));
        let (ya, yb) = (clamp(y0, self.height), clamp(y0 + 1.0, self.height));
        let [a, b, c, d] = [(xa, ya), (xb, ya), (xa, yb), (xb, yb)].map(|(x, y)| self.index(x, y));
        let mut out = self.base;
        for ch in SkinChannel::ALL {
            let p = &self.planes[ch as usize];
            let at = |i: usize| f64::from(p[i]);
            let lerp = |s: f64, t: f64, f: f64| s + (t - s) * f;
            let v = lerp(lerp(at(a), at(b), fx), lerp(at(c), at(d), fx), fy);
            let (lo, hi) = ch.range(&self.base);
            out = ch.with(&out, v.clamp(lo, hi));
        }
        out
    }

    /// The texels of `rect` (clamped to the maps; at least one texel) as maps of their own, with
    /// the same base: for baking the colour of a changed rectangle only.
    pub fn crop(&self, rect: TexelRect) -> SkinMaps {
        let r = rect.clamped(self.width, self.height);
        let r = if r.is_empty() { TexelRect::new(0, 0, 1, 1) } else { r };
        let w = self.width as usize;
        let planes = self.planes.each_ref().map(|p| {
            let mut out = Vec::with_capacity(r.area());
            for y in r.y0 as usize..r.y1 as usize {
                out.extend_from_slice(&p[y * w + r.x0 as usize..y * w + r.x1 as usize]);
            }
            out
        });
        SkinMaps { width: r.width(), height: r.height(), base: self.base, planes }
    }

    /// Index of texel (x, y) clamped to the map.
    fn index(&self, x: u32, y: u32) -> usize {
        let (x, y) = (x.min(self.width - 1) as usize, y.min(self.height - 1) as usize);
        y * self.width as usize + x
    }

    /// Maps `width × height` texels large from `texel(x, y)` per texel, each clamped as by
    /// [`clamp_params`] against `base`'s scattering (which `base` must have validly).
    pub(crate) fn from_fn(
        width: u32,
        height: u32,
        base: &SkinParams,
        texel: impl Fn(u32, u32) -> SkinParams + Sync,
    ) -> SkinMaps {
        let (w, h) = (width as usize, height as usize);
        let rows = crate::paint::par_rows(h, |range| {
            let mut planes: [Vec<f32>; 5] = std::array::from_fn(|_| Vec::with_capacity(range.len() * w));
            for y in range {
                for x in 0..w {
                    let p = texel(x as u32, y as u32);
                    // The scattering is the base's: the epidermis' bound follows from it.
                    let p = SkinParams {
                        scattering_500nm_per_mm: base.scattering_500nm_per_mm,
                        scattering_power: base.scattering_power,
                        ..p
                    };
                    let p = clamp_params(&p);
                    for c in SkinChannel::ALL {
                        let (lo, hi) = c.range(base);
                        planes[c as usize].push(f32_within(c.of(&p), lo, hi));
                    }
                }
            }
            planes
        });
        let mut planes: [Vec<f32>; 5] = std::array::from_fn(|_| Vec::with_capacity(w * h));
        for band in rows {
            for (all, part) in planes.iter_mut().zip(band) {
                all.extend(part);
            }
        }
        SkinMaps { width, height, base: *base, planes }
    }
}

#[cfg(test)]
mod tests;
