//! Skin edits: what the app's skin brushes paint (more or less melanin, more or less blood, a
//! spot), kept apart from the cosmetic layers and from the generated maps. Per texel of the
//! painted maps' UV space ([`crate::document::MAP_SIZE`]², row 0 at v = 1), the natural log of a
//! factor on the melanin fraction and one on the blood fraction: 0 leaves the texel as generated.
//! [`SkinMaps::with_edits`] applies them on top of the generated maps and clamps each value into
//! its channel's range ([`SkinChannel::range`]), so edited maps are always valid.
//!
//! Factors, not offsets: regenerating the maps from another tone, other conditions or another
//! seed keeps the edits (a spot painted twice as dark stays twice as dark on the new skin).

use super::{SkinChannel, SkinMaps};
use crate::TexelRect;
use crate::paint::{Brush, PaintView, SurfaceMap, dab_weights};
use glam::Vec3;

/// The largest factor an edit holds either way (its natural log is bounded by
/// [`MAX_LN_FACTOR`]): ×4, past the database's spread of melanin (p95/p5 = 3.2, docs/SKIN.md)
/// and the anatomy's largest regional blood factor (×3.5, the lips). A choice.
pub const MAX_FACTOR: f64 = 4.0;
/// ln [`MAX_FACTOR`].
pub const MAX_LN_FACTOR: f32 = std::f32::consts::LN_2 * 2.0;

/// A channel the skin brushes paint.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum EditChannel {
    /// The melanin fraction ([`SkinChannel::Melanin`]).
    Melanin,
    /// The blood fraction ([`SkinChannel::Blood`]).
    Blood,
}

impl EditChannel {
    /// Both, in the order of [`SkinEdits`]' planes.
    pub const ALL: [EditChannel; 2] = [EditChannel::Melanin, EditChannel::Blood];

    /// The maps' channel it scales.
    pub const fn skin_channel(self) -> SkinChannel {
        match self {
            EditChannel::Melanin => SkinChannel::Melanin,
            EditChannel::Blood => SkinChannel::Blood,
        }
    }

    /// The name of its plane in the edits' EXR: `melanin_ln_factor`, `blood_ln_factor`.
    pub const fn plane_name(self) -> &'static str {
        match self {
            EditChannel::Melanin => "melanin_ln_factor",
            EditChannel::Blood => "blood_ln_factor",
        }
    }
}

/// What a skin brush does ([`apply_skin_dab`]).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum SkinBrushKind {
    /// Melanin × the brush's factor.
    MoreMelanin,
    /// Melanin ÷ the factor.
    LessMelanin,
    /// Blood × the factor.
    MoreBlood,
    /// Blood ÷ the factor.
    LessBlood,
    /// A spot: melanin and blood × the factor (a freckle's pigment with a blemish's redness).
    Spot,
}

impl SkinBrushKind {
    /// Every kind, in the Skin panel's order.
    pub const ALL: [SkinBrushKind; 5] = [
        SkinBrushKind::MoreMelanin,
        SkinBrushKind::LessMelanin,
        SkinBrushKind::MoreBlood,
        SkinBrushKind::LessBlood,
        SkinBrushKind::Spot,
    ];

    /// Its label.
    pub const fn label(self) -> &'static str {
        match self {
            SkinBrushKind::MoreMelanin => "More melanin",
            SkinBrushKind::LessMelanin => "Less melanin",
            SkinBrushKind::MoreBlood => "More blood",
            SkinBrushKind::LessBlood => "Less blood",
            SkinBrushKind::Spot => "Spot",
        }
    }

    /// The sign of the log factor it paints toward on each of [`EditChannel::ALL`] (0: leaves
    /// the channel alone).
    const fn signs(self) -> [f32; 2] {
        match self {
            SkinBrushKind::MoreMelanin => [1.0, 0.0],
            SkinBrushKind::LessMelanin => [-1.0, 0.0],
            SkinBrushKind::MoreBlood => [0.0, 1.0],
            SkinBrushKind::LessBlood => [0.0, -1.0],
            SkinBrushKind::Spot => [1.0, 1.0],
        }
    }
}

/// A skin brush: what it does and the factor it paints toward at full weight.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SkinBrush {
    /// What it does.
    pub kind: SkinBrushKind,
    /// The factor a texel tends to under repeated dabs at the centre, in (1, [`MAX_FACTOR`]];
    /// others are clamped into it.
    pub factor: f32,
}

impl Default for SkinBrush {
    /// More melanin, ×1.69 (the freckles' factor, the database's p95/p50 of melanin).
    fn default() -> Self {
        SkinBrush { kind: SkinBrushKind::MoreMelanin, factor: 1.69 }
    }
}

/// The skin edits of a document: per texel, ln of the factor on melanin and on blood
/// ([`EditChannel::ALL`]), each in [−[`MAX_LN_FACTOR`], [`MAX_LN_FACTOR`]], row 0 at v = 1.
#[derive(Clone, PartialEq)]
pub struct SkinEdits {
    width: u32,
    height: u32,
    planes: [Vec<f32>; 2],
}

impl std::fmt::Debug for SkinEdits {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("SkinEdits")
            .field("width", &self.width)
            .field("height", &self.height)
            .field("edited_texels", &self.edited_texels())
            .finish()
    }
}

impl SkinEdits {
    /// No edit, `width × height` texels (at least 1 × 1).
    pub fn new(width: u32, height: u32) -> SkinEdits {
        let (width, height) = (width.max(1), height.max(1));
        let n = width as usize * height as usize;
        SkinEdits { width, height, planes: [vec![0.0; n], vec![0.0; n]] }
    }

    /// Edits from planes in the order of [`EditChannel::ALL`], checked: each `width × height`
    /// long, every value finite and within ±[`MAX_LN_FACTOR`]. Errors name the plane and texel.
    pub fn from_planes(width: u32, height: u32, planes: [Vec<f32>; 2]) -> Result<SkinEdits, String> {
        let n = width as usize * height as usize;
        if n == 0 {
            return Err(format!("{width}×{height} edits have no texels"));
        }
        for (c, plane) in EditChannel::ALL.iter().zip(&planes) {
            if plane.len() != n {
                return Err(format!("plane {} has {} values for {width}×{height} texels", c.plane_name(), plane.len()));
            }
            if let Some(i) = plane.iter().position(|v| !(-MAX_LN_FACTOR..=MAX_LN_FACTOR).contains(v)) {
                return Err(format!(
                    "texel ({}, {}) of plane {} is {}: outside ±{MAX_LN_FACTOR} (a factor of at most {MAX_FACTOR})",
                    i % width as usize,
                    i / width as usize,
                    c.plane_name(),
                    plane[i]
                ));
            }
        }
        Ok(SkinEdits { width, height, planes })
    }

    /// Width in texels.
    pub fn width(&self) -> u32 {
        self.width
    }

    /// Height in texels.
    pub fn height(&self) -> u32 {
        self.height
    }

    /// One plane's ln factors, row 0 first.
    pub fn plane(&self, channel: EditChannel) -> &[f32] {
        &self.planes[channel as usize]
    }

    /// How many texels any plane edits (a non-zero log factor).
    pub fn edited_texels(&self) -> usize {
        (0..self.planes[0].len()).filter(|&i| self.planes.iter().any(|p| p[i] != 0.0)).count()
    }

    /// Whether no texel is edited.
    pub fn is_empty(&self) -> bool {
        self.planes.iter().all(|p| p.iter().all(|&v| v == 0.0))
    }

    /// The values of `rect` (clamped to the edits), plane after plane, row by row.
    pub fn read_rect(&self, rect: TexelRect) -> [Vec<f32>; 2] {
        let rect = rect.clamped(self.width, self.height);
        let w = self.width as usize;
        self.planes.each_ref().map(|p| {
            let mut out = Vec::with_capacity(rect.area());
            for y in rect.y0 as usize..rect.y1 as usize {
                out.extend_from_slice(&p[y * w + rect.x0 as usize..y * w + rect.x1 as usize]);
            }
            out
        })
    }

    /// Writes `values` (as [`SkinEdits::read_rect`] gives them for the same `rect`) back.
    pub fn write_rect(&mut self, rect: TexelRect, values: &[Vec<f32>; 2]) {
        let rect = rect.clamped(self.width, self.height);
        let (w, rw) = (self.width as usize, rect.width() as usize);
        if rw == 0 {
            return;
        }
        for (p, v) in self.planes.iter_mut().zip(values) {
            for (y, row) in (rect.y0 as usize..rect.y1 as usize).zip(v.chunks_exact(rw)) {
                p[y * w + rect.x0 as usize..y * w + rect.x1 as usize].copy_from_slice(row);
            }
        }
    }

    /// As an OpenEXR file's bytes: one 32-bit float channel per plane, named
    /// [`EditChannel::plane_name`], ZIP-compressed (lossless).
    pub fn to_exr_bytes(&self) -> Result<Vec<u8>, String> {
        use exr::prelude::{AnyChannel, AnyChannels, Encoding, FlatSamples, Image, SmallVec, WritableImage};
        let channels = EditChannel::ALL
            .map(|c| AnyChannel::new(c.plane_name(), FlatSamples::F32(self.plane(c).to_vec())))
            .to_vec();
        let channels = AnyChannels::sort(SmallVec::from_vec(channels));
        let size = (self.width as usize, self.height as usize);
        let image = Image::from_encoded_channels(size, Encoding::SMALL_LOSSLESS, channels);
        let mut bytes = std::io::Cursor::new(Vec::new());
        image.write().to_buffered(&mut bytes).map_err(|e| format!("OpenEXR: {e}"))?;
        Ok(bytes.into_inner())
    }

    /// Edits from an OpenEXR file's bytes as [`SkinEdits::to_exr_bytes`] writes them, checked as
    /// [`SkinEdits::from_planes`].
    pub fn from_exr_bytes(bytes: &[u8]) -> Result<SkinEdits, String> {
        let mut exr = crate::look::read_exr_channels(bytes)?;
        let mut planes: [Vec<f32>; 2] = Default::default();
        for (c, plane) in EditChannel::ALL.iter().zip(planes.iter_mut()) {
            let Some(k) = exr.channels.iter().position(|(name, _)| name == c.plane_name()) else {
                let names: Vec<String> = exr.channels.iter().map(|(name, _)| format!("{name:?}")).collect();
                return Err(format!("no channel {:?} (the file has {})", c.plane_name(), names.join(", ")));
            };
            *plane = std::mem::take(&mut exr.channels[k].1);
        }
        SkinEdits::from_planes(exr.width, exr.height, planes)
    }

    /// A 64-bit hash of the size and every value, for the file's name in a project.
    pub(crate) fn content_hash(&self) -> u64 {
        let header = u64::from(self.width) << 32 | u64::from(self.height);
        crate::document::floats_hash(header, self.planes.iter().flat_map(|p| p.iter().copied()))
    }

    /// The edit texel over map texel (x, y) of a `w × h` map (the texel whose area holds the
    /// map texel's centre).
    fn index_for(&self, x: u32, y: u32, w: u32, h: u32) -> usize {
        let ex = ((u64::from(x) * 2 + 1) * u64::from(self.width) / (2 * u64::from(w))) as usize;
        let ey = ((u64::from(y) * 2 + 1) * u64::from(self.height) / (2 * u64::from(h))) as usize;
        ey.min(self.height as usize - 1) * self.width as usize + ex.min(self.width as usize - 1)
    }

    /// The texels of a `w × h` map whose values `rect` of the edits can change (rounded out).
    pub fn map_rect(&self, rect: TexelRect, w: u32, h: u32) -> TexelRect {
        let scale = |v: u32, from: u32, to: u32, up: bool| {
            let n = u64::from(v) * u64::from(to);
            (if up { n.div_ceil(u64::from(from)) } else { n / u64::from(from) }) as u32
        };
        TexelRect {
            x0: scale(rect.x0, self.width, w, false),
            y0: scale(rect.y0, self.height, h, false),
            x1: scale(rect.x1, self.width, w, true),
            y1: scale(rect.y1, self.height, h, true),
        }
        .clamped(w, h)
    }
}

impl SkinMaps {
    /// The maps with `edits` on top: each texel's melanin and blood × e^(the edit's log factor
    /// over it), clamped into the channel's range ([`SkinChannel::range`]). Edits of another
    /// size are read at the texel whose area holds each map texel's centre. The same maps
    /// without edits.
    pub fn with_edits(&self, edits: &SkinEdits) -> SkinMaps {
        let mut out = self.clone();
        out.apply_edits_in(edits, TexelRect::whole(self.width(), self.height()));
        out
    }

    /// Applies `edits` to the texels of `rect` (of these maps) as [`SkinMaps::with_edits`] does,
    /// reading the generated values from `generated` (the same size; these maps elsewhere).
    pub fn reapply_edits_in(&mut self, generated: &SkinMaps, edits: &SkinEdits, rect: TexelRect) {
        if (generated.width(), generated.height()) != (self.width(), self.height()) {
            return;
        }
        let rect = rect.clamped(self.width(), self.height());
        let w = self.width() as usize;
        for c in EditChannel::ALL {
            let ch = c.skin_channel() as usize;
            for y in rect.y0 as usize..rect.y1 as usize {
                let r = y * w + rect.x0 as usize..y * w + rect.x1 as usize;
                self.planes[ch][r.clone()].copy_from_slice(&generated.planes[ch][r]);
            }
        }
        self.apply_edits_in(edits, rect);
    }

    fn apply_edits_in(&mut self, edits: &SkinEdits, rect: TexelRect) {
        let (w, h) = (self.width(), self.height());
        let rect = rect.clamped(w, h);
        for c in EditChannel::ALL {
            let (lo, hi) = c.skin_channel().range(self.base());
            let plane = &mut self.planes[c.skin_channel() as usize];
            let ln = edits.plane(c);
            for y in rect.y0..rect.y1 {
                for x in rect.x0..rect.x1 {
                    let e = ln[edits.index_for(x, y, w, h)];
                    if e != 0.0 {
                        let v = &mut plane[y as usize * w as usize + x as usize];
                        *v = super::f32_within(f64::from(*v) * f64::from(e).exp(), lo, hi);
                    }
                }
            }
        }
    }
}

/// Paints one skin dab at the surface point `centre` into `edits` (the surface map's size):
/// the texels and weights a of `brush` ([`dab_weights`]: radius along the skin, falloff, mirror,
/// facing and occlusion as for cosmetics), then on each channel `skin` moves, the log factor
/// e += (target − e)·a with target ±ln(factor) (never past it). Returns the changed rectangles
/// near `centre` and near its mirror image; nothing changes for edits of another size than the
/// surface map, an invalid brush or a non-finite centre.
pub fn apply_skin_dab(
    edits: &mut SkinEdits,
    surface: &SurfaceMap,
    brush: &Brush,
    skin: &SkinBrush,
    centre: Vec3,
    view: Option<&PaintView>,
) -> [TexelRect; 2] {
    let mut dirty = [TexelRect::EMPTY; 2];
    if (edits.width, edits.height) != (surface.width, surface.height) {
        return dirty;
    }
    let factor = if skin.factor.is_finite() { f64::from(skin.factor).clamp(1.0, MAX_FACTOR) } else { 1.0 };
    let ln = (factor.ln() as f32).min(MAX_LN_FACTOR);
    let targets = skin.kind.signs().map(|s| s * ln);
    let width = edits.width as usize;
    for (i, a, k) in dab_weights(surface, brush, centre, view) {
        let mut changed = false;
        for (c, target) in EditChannel::ALL.iter().zip(targets) {
            if target == 0.0 {
                continue;
            }
            let e = &mut edits.planes[*c as usize][i];
            let step = *e + (target - *e) * a;
            let new = if target >= *e { step.min(target) } else { step.max(target) };
            let new = new.clamp(-MAX_LN_FACTOR, MAX_LN_FACTOR);
            if new.to_bits() != e.to_bits() {
                *e = new;
                changed = true;
            }
        }
        if changed {
            dirty[k as usize].include((i % width) as u32, (i / width) as u32);
        }
    }
    dirty
}
