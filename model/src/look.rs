//! The look document (`"schema": "rouge-look", "version": 1`): the cosmetic layers on a face,
//! bottom to top, each a material preset and a thickness over the mesh's UV space. The renderer
//! and the painting app both read and write it; docs/FORMATS.md ("Look documents") specifies
//! the JSON field by field.
//!
//! A thickness is given as a uniform film, a built-in region of the default head
//! ([`Region`]), a PNG mask times a thickness, or a thickness map (OpenEXR in millimetres, or
//! PNG times a scale). Loading resolves every reference into a [`ThicknessMap`] and a
//! [`Preset`], and checks every value: anything unknown or out of range is an error naming the
//! look file, the layer and, for maps, the pixel.
//!
//! UV and pixel convention (the one `python/gen_head.py` wrote the region masks in): a map is
//! stored like a texture of the mesh, row 0 at the top of the image. For OBJ-convention UVs
//! (v up, as in the default head), pixel (x, y) of a w × h map has its centre at
//! u = (x + 0.5) / w, v = 1 − (y + 0.5) / h. [`ThicknessMap::sample_uv`] takes such UVs.

use crate::error::{ModelError, Result};
use rouge_measure::preset::{Preset, write_atomic};
use serde::{Deserialize, Serialize};
use std::fmt;
use std::path::{Path, PathBuf};
use std::sync::OnceLock;

/// The schema name every look carries.
pub const SCHEMA: &str = "rouge-look";
/// The schema version this build writes and reads.
pub const VERSION: u32 = 1;
/// Largest thickness a look may give anywhere, mm. Cosmetic films are 5-100 µm; anything
/// near this bound is a unit mistake (µm written as mm), caught here rather than rendered.
pub const MAX_THICKNESS_MM: f32 = 10.0;
/// Prefix of a preset reference that names a preset built into the binary.
pub const BUILTIN_PREFIX: &str = "builtin:";

const PNG_SIGNATURE: &[u8] = b"\x89PNG\r\n\x1a\n";
const EXR_MAGIC: &[u8] = &[0x76, 0x2f, 0x31, 0x01];

// ------------------------------------------------------------------------------------------
// Built-in presets

macro_rules! builtin_presets {
    ($($name:literal),* $(,)?) => {
        const BUILTIN_NAMES: &[&str] = &[$($name),*];
        const BUILTIN_JSON: &[&str] = &[$(include_str!(concat!("../../data/presets/", $name, ".json"))),*];
    };
}

builtin_presets!(
    "blush_01_petal",
    "blush_02_coral",
    "eyeshadow_01_smoky",
    "eyeshadow_02_sapphire",
    "eyeshadow_03_bronze",
    "foundation_01_porcelain",
    "foundation_02_ivory",
    "foundation_03_sand",
    "foundation_04_caramel",
    "foundation_05_espresso",
    "lipstick_01_nude",
    "lipstick_02_red",
    "lipstick_03_berry",
);

/// The names of the presets of `data/presets/` built into the binary (their file stems), as
/// used in `"preset": "builtin:<name>"`.
pub fn builtin_preset_names() -> &'static [&'static str] {
    BUILTIN_NAMES
}

/// A preset built into the binary, by file stem (`"foundation_02_ivory"`); `None` if there is
/// no such built-in.
pub fn builtin_preset(name: &str) -> Option<Preset> {
    let i = BUILTIN_NAMES.iter().position(|n| *n == name)?;
    let json = BUILTIN_JSON.get(i)?;
    Preset::from_json(json, &format!("{BUILTIN_PREFIX}{name}")).ok()
}

/// Loads the preset a look refers to: `builtin:<name>`, or a file path, taken relative to
/// `base_dir` (the look file's folder) unless absolute. The error keeps the preset's own
/// message (file, line, field).
pub fn load_preset_ref(preset_ref: &str, base_dir: &Path) -> Result<Preset> {
    resolve_preset(preset_ref, base_dir).map_err(ModelError::Invalid)
}

fn resolve_preset(preset_ref: &str, base_dir: &Path) -> std::result::Result<Preset, String> {
    if let Some(name) = preset_ref.strip_prefix(BUILTIN_PREFIX) {
        return builtin_preset(name).ok_or_else(|| {
            format!("preset {preset_ref:?}: no such built-in preset (built-ins: {})", BUILTIN_NAMES.join(", "))
        });
    }
    if preset_ref.trim().is_empty() {
        return Err("`preset` is empty".into());
    }
    Preset::load(&resolve_path(base_dir, Path::new(preset_ref))).map_err(|e| format!("preset {preset_ref:?}: {e}"))
}

fn resolve_path(base_dir: &Path, path: &Path) -> PathBuf {
    if path.is_absolute() { path.to_path_buf() } else { base_dir.join(path) }
}

fn base_dir_of(look_path: &Path) -> &Path {
    look_path.parent().filter(|d| !d.as_os_str().is_empty()).unwrap_or(Path::new("."))
}

// ------------------------------------------------------------------------------------------
// Thickness maps

/// A thickness in millimetres over the mesh's UV space, stored like a texture: row-major,
/// row 0 = the top of the image. For OBJ-convention UVs (v up), pixel (x, y) has its centre at
/// u = (x + 0.5) / width, v = 1 − (y + 0.5) / height.
#[derive(Clone, Debug, PartialEq)]
pub struct ThicknessMap {
    /// Width in pixels (≥ 1 for a usable map).
    pub width: u32,
    /// Height in pixels (≥ 1 for a usable map).
    pub height: u32,
    /// Thickness per pixel, mm, `width * height` values, row 0 first.
    pub mm: Vec<f32>,
}

impl ThicknessMap {
    /// A 1 × 1 map: the same thickness everywhere.
    pub fn uniform(mm: f32) -> Self {
        ThicknessMap { width: 1, height: 1, mm: vec![mm] }
    }

    /// The thickness of pixel (x, y), with x and y clamped to the map (clamp-to-edge); 0 for an
    /// empty map or where `mm` holds fewer than `width * height` values.
    pub fn texel(&self, x: u32, y: u32) -> f32 {
        if self.width == 0 || self.height == 0 {
            return 0.0;
        }
        let (x, y) = (x.min(self.width - 1) as usize, y.min(self.height - 1) as usize);
        self.mm.get(y * self.width as usize + x).copied().unwrap_or(0.0)
    }

    /// Bilinear sample at continuous pixel coordinates (pixel (x, y) covers [x, x+1) × [y, y+1),
    /// its centre at (x + 0.5, y + 0.5)), clamp-to-edge.
    fn sample_px(&self, px: f32, py: f32) -> f32 {
        let (x, y) = (px - 0.5, py - 0.5);
        let (x0, y0) = (x.floor(), y.floor());
        let (fx, fy) = (x - x0, y - y0);
        // Float-to-int casts saturate (NaN becomes 0), so clamping needs no special cases.
        let clamp = |i: f32, n: u32| (i as i64).clamp(0, i64::from(n.max(1)) - 1) as u32;
        let (xa, xb) = (clamp(x0, self.width), clamp(x0 + 1.0, self.width));
        let (ya, yb) = (clamp(y0, self.height), clamp(y0 + 1.0, self.height));
        // a + (b − a)·t: exact where neighbours are equal (a uniform map stays uniform).
        let lerp = |a: f32, b: f32, t: f32| a + (b - a) * t;
        let top = lerp(self.texel(xa, ya), self.texel(xb, ya), fx);
        let bottom = lerp(self.texel(xa, yb), self.texel(xb, yb), fx);
        lerp(top, bottom, fy)
    }

    /// The thickness at OBJ-convention UV (u right, v up), interpolated bilinearly between pixel
    /// centres with clamp-to-edge addressing: what a GPU sampler (linear filter, clamp-to-edge)
    /// returns for texture coordinate (u, 1 − v), up to the GPU's filtering precision.
    pub fn sample_uv(&self, u: f32, v: f32) -> f32 {
        self.sample_px(u * self.width as f32, (1.0 - v) * self.height as f32)
    }

    /// The largest thickness in the map, mm (0 for an empty map).
    pub fn max_mm(&self) -> f32 {
        self.mm.iter().copied().fold(0.0, f32::max)
    }

    /// The map resampled to `width` × `height` (each at least 1) by bilinear interpolation at
    /// the new pixel centres (same UV convention), e.g. to pack layers of different sizes into
    /// one texture array. Same size returns an exact copy.
    pub fn resized(&self, width: u32, height: u32) -> ThicknessMap {
        let (w, h) = (width.max(1), height.max(1));
        if w == self.width && h == self.height && self.mm.len() == (w as usize) * (h as usize) {
            return self.clone();
        }
        let (sx, sy) = (self.width as f32 / w as f32, self.height as f32 / h as f32);
        let mut mm = Vec::with_capacity(w as usize * h as usize);
        for y in 0..h {
            for x in 0..w {
                mm.push(self.sample_px((x as f32 + 0.5) * sx, (y as f32 + 0.5) * sy));
            }
        }
        ThicknessMap { width: w, height: h, mm }
    }

    /// Every value multiplied by `factor`.
    pub fn scaled(&self, factor: f32) -> ThicknessMap {
        ThicknessMap { width: self.width, height: self.height, mm: self.mm.iter().map(|v| v * factor).collect() }
    }

    /// Writes the map as a single-channel (`Y`, 32-bit float) OpenEXR file in millimetres, the
    /// form a look's `"map"` reads back exactly; atomic (temporary file, then rename).
    pub fn save_exr(&self, path: &Path) -> Result<()> {
        use exr::prelude::{AnyChannel, AnyChannels, FlatSamples, Image, SmallVec, WritableImage};
        let n = self.width as usize * self.height as usize;
        if n == 0 || self.mm.len() != n {
            return Err(ModelError::file(
                path,
                format!("cannot write a {}×{} map holding {} values", self.width, self.height, self.mm.len()),
            ));
        }
        let channels =
            AnyChannels::sort(SmallVec::from_vec(vec![AnyChannel::new("Y", FlatSamples::F32(self.mm.clone()))]));
        let image = Image::from_channels((self.width as usize, self.height as usize), channels);
        let mut bytes = std::io::Cursor::new(Vec::new());
        image.write().to_buffered(&mut bytes).map_err(|e| ModelError::file(path, format!("OpenEXR: {e}")))?;
        write_atomic(path, bytes.get_ref()).map_err(|e| ModelError::file(path, e))
    }
}

/// The first channel of a PNG as values in [0, 1] (value / max for 8- and 16-bit images).
fn decode_png_unit(bytes: &[u8]) -> std::result::Result<ThicknessMap, String> {
    use image::DynamicImage as D;
    if !bytes.starts_with(PNG_SIGNATURE) {
        let signature = if bytes.is_empty() || bytes.starts_with(EXR_MAGIC) {
            ""
        } else {
            "; a PNG starts with 89 50 4E 47 0D 0A 1A 0A"
        };
        return Err(format!("not a PNG file ({}{signature})", describe_start(bytes)));
    }
    let img = image::load_from_memory_with_format(bytes, image::ImageFormat::Png)
        .map_err(|e| format!("not a readable PNG file ({e})"))?;
    let (width, height) = (img.width(), img.height());
    fn first<T: Copy + Into<f32>>(raw: &[T], channels: usize, max: f32) -> Vec<f32> {
        raw.iter().step_by(channels).map(|&v| v.into() / max).collect()
    }
    let mm = match &img {
        D::ImageLuma8(b) => first(b.as_raw(), 1, 255.0),
        D::ImageLumaA8(b) => first(b.as_raw(), 2, 255.0),
        D::ImageRgb8(b) => first(b.as_raw(), 3, 255.0),
        D::ImageRgba8(b) => first(b.as_raw(), 4, 255.0),
        D::ImageLuma16(b) => first(b.as_raw(), 1, 65535.0),
        D::ImageLumaA16(b) => first(b.as_raw(), 2, 65535.0),
        D::ImageRgb16(b) => first(b.as_raw(), 3, 65535.0),
        D::ImageRgba16(b) => first(b.as_raw(), 4, 65535.0),
        other => return Err(format!("unsupported PNG pixel format {:?}", other.color())),
    };
    if mm.len() != width as usize * height as usize || mm.is_empty() {
        return Err(format!("PNG of {width}×{height} pixels decoded to {} values", mm.len()));
    }
    Ok(ThicknessMap { width, height, mm })
}

fn describe_start(bytes: &[u8]) -> String {
    if bytes.is_empty() {
        "the file is empty".into()
    } else if bytes.starts_with(EXR_MAGIC) {
        "it is an OpenEXR file".into()
    } else {
        let head: Vec<String> = bytes.iter().take(8).map(|b| format!("{b:02X}")).collect();
        format!("it starts with {}", head.join(" "))
    }
}

/// The thickness channel of an OpenEXR file: `Y`, else `R`, else the first channel (EXR stores
/// channels sorted by name), of the first layer at full resolution.
fn decode_exr(bytes: &[u8]) -> std::result::Result<(ThicknessMap, String), String> {
    use exr::prelude::{ReadChannels, ReadLayers, read};
    let image = read()
        .no_deep_data()
        .largest_resolution_level()
        .all_channels()
        .first_valid_layer()
        .all_attributes()
        .from_buffered(std::io::Cursor::new(bytes))
        .map_err(|e| format!("not a readable OpenEXR file ({e})"))?;
    let layer = image.layer_data;
    let (w, h) = (layer.size.width(), layer.size.height());
    let list = &layer.channel_data.list;
    let channel = list
        .iter()
        .find(|c| c.name == *"Y")
        .or_else(|| list.iter().find(|c| c.name == *"R"))
        .or_else(|| list.first())
        .ok_or("the OpenEXR file has no channels")?;
    let name = channel.name.to_string();
    if channel.sample_data.len() != w * h {
        return Err(format!(
            "channel {name:?} is subsampled ({} samples for {w}×{h} pixels)",
            channel.sample_data.len()
        ));
    }
    let too_big = |_| format!("{w}×{h} pixels is too large");
    let (width, height) = (u32::try_from(w).map_err(too_big)?, u32::try_from(h).map_err(too_big)?);
    let mm = channel.sample_data.values().map(|s| s.to_f32()).collect();
    Ok((ThicknessMap { width, height, mm }, name))
}

/// Checks that a thickness is finite, ≥ 0 and ≤ [`MAX_THICKNESS_MM`].
fn thickness_ok(mm: f32) -> bool {
    mm.is_finite() && (0.0..=MAX_THICKNESS_MM).contains(&mm)
}

fn range_rule() -> String {
    format!("thickness must be finite, ≥ 0 and ≤ {MAX_THICKNESS_MM} mm")
}

fn check_field(field: &str, mm: f32) -> std::result::Result<f32, String> {
    if thickness_ok(mm) { Ok(mm) } else { Err(format!("`{field}` = {mm}: {}", range_rule())) }
}

/// Checks every pixel of a map, naming the first bad one.
fn check_map(map: &ThicknessMap, what: &str) -> std::result::Result<(), String> {
    let w = map.width.max(1) as usize;
    match map.mm.iter().position(|&v| !thickness_ok(v)) {
        None => Ok(()),
        Some(i) => {
            let v = map.mm[i];
            let unit = if v.is_finite() { " mm" } else { "" };
            Err(format!("pixel ({}, {}){what} is {v}{unit}: {}", i % w, i / w, range_rule()))
        }
    }
}

// ------------------------------------------------------------------------------------------
// Regions of the default head

/// A built-in UV mask of the default head (`data/heads/hm08_head.obj`), made by
/// `python/gen_head.py` from the 3D geometry: 1024 × 1024, weights in [0, 1], soft edges.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Region {
    /// The vermilion of both lips (mouth interior excluded).
    Lips,
    /// An ellipse on each cheekbone, tilted up towards the temple.
    Cheeks,
    /// Both upper eyelids, from the lash line up towards the brow.
    Eyelids,
    /// Forehead and nose.
    Tzone,
}

const REGION_PNGS: [&[u8]; 4] = [
    include_bytes!("../../data/heads/masks/lips.png"),
    include_bytes!("../../data/heads/masks/cheeks.png"),
    include_bytes!("../../data/heads/masks/eyelids.png"),
    include_bytes!("../../data/heads/masks/tzone.png"),
];

static REGION_MASKS: [OnceLock<ThicknessMap>; 4] = [const { OnceLock::new() }; 4];

impl Region {
    /// Every region, in the order lips, cheeks, eyelids, tzone.
    pub const fn all() -> [Region; 4] {
        [Region::Lips, Region::Cheeks, Region::Eyelids, Region::Tzone]
    }

    /// The name used in look files: `lips`, `cheeks`, `eyelids`, `tzone`.
    pub const fn name(self) -> &'static str {
        match self {
            Region::Lips => "lips",
            Region::Cheeks => "cheeks",
            Region::Eyelids => "eyelids",
            Region::Tzone => "tzone",
        }
    }

    /// The region with this name (exact, lower case), if any.
    pub fn parse(name: &str) -> Option<Region> {
        Region::all().into_iter().find(|r| r.name() == name)
    }

    const fn index(self) -> usize {
        self as usize
    }

    /// The region's mask as the thickness map of a 1 mm layer: the weights in [0, 1]
    /// (PNG value / 255), 1024 × 1024, in the default head's UVs. Decoded on first use, once.
    pub fn mask(self) -> &'static ThicknessMap {
        REGION_MASKS[self.index()].get_or_init(|| {
            // The masks are embedded and checked by the tests; a failed decode would leave the
            // region empty rather than abort a render.
            decode_png_unit(REGION_PNGS[self.index()]).unwrap_or_else(|_| ThicknessMap::uniform(0.0))
        })
    }
}

impl fmt::Display for Region {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

// ------------------------------------------------------------------------------------------
// Thickness sources: the "thickness" object

/// Where a layer's thickness comes from: the `"thickness"` object of a look layer. Paths are
/// kept as written (relative to the look file unless absolute).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(try_from = "ThicknessJson", into = "ThicknessJson")]
pub enum ThicknessSource {
    /// `{"uniform_mm": t}`: `t` mm everywhere.
    Uniform {
        /// Thickness, mm.
        mm: f32,
    },
    /// `{"region": "cheeks", "thickness_mm": t}`: a built-in mask of the default head × `t`.
    Region {
        /// The region.
        region: Region,
        /// Thickness where the mask is 1, mm.
        mm: f32,
    },
    /// `{"mask": "m.png", "thickness_mm": t}`: a PNG mask (first channel, value / max) × `t`.
    Mask {
        /// The PNG, as written.
        path: PathBuf,
        /// Thickness where the mask is at its maximum, mm.
        mm: f32,
    },
    /// `{"map": "m.exr"}` or `{"map": "m.png", "scale_mm": s}`: an OpenEXR map in mm (times `s`
    /// if given), or a PNG map, value / max × `s` (`s` required).
    Map {
        /// The EXR or PNG file, as written.
        path: PathBuf,
        /// Scale, mm: required for PNG, optional for EXR.
        scale_mm: Option<f32>,
    },
}

/// The JSON shape of [`ThicknessSource`]: one of four keys plus its companion.
#[derive(Clone, Debug, Default, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
struct ThicknessJson {
    #[serde(default, skip_serializing_if = "Option::is_none")]
    uniform_mm: Option<f32>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    region: Option<String>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    mask: Option<String>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    map: Option<String>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    thickness_mm: Option<f32>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    scale_mm: Option<f32>,
}

impl TryFrom<ThicknessJson> for ThicknessSource {
    type Error = String;

    fn try_from(j: ThicknessJson) -> std::result::Result<Self, String> {
        let kinds: Vec<&str> = [
            ("uniform_mm", j.uniform_mm.is_some()),
            ("region", j.region.is_some()),
            ("mask", j.mask.is_some()),
            ("map", j.map.is_some()),
        ]
        .into_iter()
        .filter_map(|(k, present)| present.then_some(k))
        .collect();
        let one_of = "give exactly one of `uniform_mm`, `region`, `mask` or `map`";
        match kinds.as_slice() {
            [] => return Err(format!("thickness: {one_of}")),
            [_] => {}
            [a, b, ..] => return Err(format!("thickness: has both `{a}` and `{b}`: {one_of}")),
        }
        let no = |field: &str, present: bool, with: &str| {
            if present { Err(format!("thickness: `{field}` does not go with `{with}`")) } else { Ok(()) }
        };
        let path = |field: &str, p: String| {
            if p.trim().is_empty() { Err(format!("thickness: `{field}` is empty")) } else { Ok(PathBuf::from(p)) }
        };
        let with_thickness = |field: &str| {
            j.thickness_mm
                .ok_or_else(|| format!("thickness: `{field}` needs `thickness_mm`"))
                .and_then(|t| check_field("thickness_mm", t).map_err(|e| format!("thickness: {e}")))
        };
        let checked = |field: &str, v: f32| check_field(field, v).map_err(|e| format!("thickness: {e}"));
        if let Some(mm) = j.uniform_mm {
            no("thickness_mm", j.thickness_mm.is_some(), "uniform_mm")?;
            no("scale_mm", j.scale_mm.is_some(), "uniform_mm")?;
            return Ok(ThicknessSource::Uniform { mm: checked("uniform_mm", mm)? });
        }
        if let Some(name) = j.region {
            no("scale_mm", j.scale_mm.is_some(), "region")?;
            let region = Region::parse(&name)
                .ok_or_else(|| format!("thickness: unknown region {name:?} (regions: lips, cheeks, eyelids, tzone)"))?;
            return Ok(ThicknessSource::Region { region, mm: with_thickness("region")? });
        }
        if let Some(p) = j.mask {
            no("scale_mm", j.scale_mm.is_some(), "mask")?;
            return Ok(ThicknessSource::Mask { path: path("mask", p)?, mm: with_thickness("mask")? });
        }
        if let Some(p) = j.map {
            no("thickness_mm", j.thickness_mm.is_some(), "map (a map uses `scale_mm`)")?;
            let scale_mm = j.scale_mm.map(|s| checked("scale_mm", s)).transpose()?;
            return Ok(ThicknessSource::Map { path: path("map", p)?, scale_mm });
        }
        Err(format!("thickness: {one_of}"))
    }
}

impl From<ThicknessSource> for ThicknessJson {
    fn from(s: ThicknessSource) -> Self {
        let text = |p: PathBuf| Some(p.to_string_lossy().into_owned());
        match s {
            ThicknessSource::Uniform { mm } => ThicknessJson { uniform_mm: Some(mm), ..Default::default() },
            ThicknessSource::Region { region, mm } => {
                ThicknessJson { region: Some(region.name().into()), thickness_mm: Some(mm), ..Default::default() }
            }
            ThicknessSource::Mask { path, mm } => {
                ThicknessJson { mask: text(path), thickness_mm: Some(mm), ..Default::default() }
            }
            ThicknessSource::Map { path, scale_mm } => {
                ThicknessJson { map: text(path), scale_mm, ..Default::default() }
            }
        }
    }
}

impl ThicknessSource {
    /// Resolves the source into a thickness map, reading mask and map files relative to
    /// `base_dir` (the look file's folder). Checks every pixel.
    pub fn load_map(&self, base_dir: &Path) -> Result<ThicknessMap> {
        self.resolve(base_dir).map_err(ModelError::Invalid)
    }

    fn resolve(&self, base_dir: &Path) -> std::result::Result<ThicknessMap, String> {
        let read = |what: &str, p: &Path| {
            let full = resolve_path(base_dir, p);
            std::fs::read(&full)
                .map_err(|e| format!("{what} {:?}: cannot read {}: {e}", p.display().to_string(), full.display()))
        };
        match self {
            ThicknessSource::Uniform { mm } => {
                check_field("uniform_mm", *mm)?;
                Ok(ThicknessMap::uniform(*mm))
            }
            ThicknessSource::Region { region, mm } => {
                check_field("thickness_mm", *mm)?;
                Ok(region.mask().scaled(*mm))
            }
            ThicknessSource::Mask { path, mm } => {
                check_field("thickness_mm", *mm)?;
                let what = format!("thickness mask {:?}", path.display().to_string());
                let bytes = read("thickness mask", path)?;
                let map = decode_png_unit(&bytes).map_err(|e| {
                    let hint = if bytes.starts_with(EXR_MAGIC) { "; use `map` for OpenEXR thickness maps" } else { "" };
                    format!("{what}: {e}{hint}")
                })?;
                Ok(map.scaled(*mm))
            }
            ThicknessSource::Map { path, scale_mm } => {
                let what = format!("thickness map {:?}", path.display().to_string());
                if let Some(s) = scale_mm {
                    check_field("scale_mm", *s)?;
                }
                let bytes = read("thickness map", path)?;
                if bytes.starts_with(EXR_MAGIC) {
                    let (map, channel) = decode_exr(&bytes).map_err(|e| format!("{what}: {e}"))?;
                    let (map, after) = match scale_mm {
                        Some(s) => (map.scaled(*s), " × `scale_mm`"),
                        None => (map, ""),
                    };
                    check_map(&map, &format!(" of channel {channel:?}{after}")).map_err(|e| format!("{what}: {e}"))?;
                    Ok(map)
                } else if bytes.starts_with(PNG_SIGNATURE) {
                    let s = scale_mm.ok_or_else(|| {
                        format!("{what}: a PNG map needs `scale_mm` (its values run 0..max, not millimetres)")
                    })?;
                    let map = decode_png_unit(&bytes).map_err(|e| format!("{what}: {e}"))?;
                    Ok(map.scaled(s))
                } else {
                    Err(format!("{what}: neither an OpenEXR nor a PNG file ({})", describe_start(&bytes)))
                }
            }
        }
    }
}

// ------------------------------------------------------------------------------------------
// The document

/// One cosmetic layer: a preset, where it lies and how thick.
#[derive(Clone, Debug, PartialEq)]
pub struct LookLayer {
    /// Display name; the preset's name unless the file gives one.
    pub name: String,
    /// The preset as written: `builtin:<name>` or a path relative to the look file.
    pub preset_ref: String,
    /// The preset it refers to.
    pub preset: Preset,
    /// Where the thickness comes from, as written.
    pub thickness: ThicknessSource,
    /// The thickness, resolved (mm over UV).
    pub map: ThicknessMap,
    /// Whether the layer is drawn (hidden layers stay in the document).
    pub visible: bool,
}

/// A look: cosmetic layers, bottom (on the skin) to top.
#[derive(Clone, Debug, PartialEq)]
pub struct Look {
    /// Display name.
    pub name: String,
    /// Layers, bottom to top.
    pub layers: Vec<LookLayer>,
}

/// The document's shape with the layers left untyped: errors here are not about a layer.
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct LookIn<L> {
    #[serde(rename = "schema")]
    _schema: String,
    #[serde(rename = "version")]
    _version: u32,
    #[serde(default)]
    name: Option<String>,
    layers: Vec<L>,
}

fn yes() -> bool {
    true
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct LayerIn {
    #[serde(default)]
    name: Option<String>,
    preset: String,
    thickness: ThicknessSource,
    #[serde(default = "yes")]
    visible: bool,
}

#[derive(Serialize)]
struct LookOut<'a> {
    schema: &'a str,
    version: u32,
    name: &'a str,
    layers: Vec<LayerOut<'a>>,
}

fn is_true(b: &bool) -> bool {
    *b
}

#[derive(Serialize)]
struct LayerOut<'a> {
    #[serde(skip_serializing_if = "Option::is_none")]
    name: Option<&'a str>,
    preset: &'a str,
    thickness: &'a ThicknessSource,
    #[serde(skip_serializing_if = "is_true")]
    visible: bool,
}

/// How a layer is named in messages: its `name`, else its preset reference.
fn layer_label(v: &serde_json::Value) -> String {
    let s = |k: &str| v.get(k).and_then(|x| x.as_str()).filter(|x| !x.is_empty());
    s("name").or_else(|| s("preset")).unwrap_or("?").to_string()
}

impl Look {
    /// A look without layers: bare skin.
    pub fn bare() -> Look {
        Look { name: "Bare".into(), layers: Vec::new() }
    }

    /// The default look on the default head, bottom to top: Foundation 02 Ivory, 15 µm
    /// everywhere; Blush 01 Petal, 8 µm on the cheeks; Lipstick 02 Classic Red, 20 µm on the
    /// lips (all built-in). Same as `data/looks/default.json`.
    ///
    /// Thicknesses from the presets' KM coefficients over the ColorChecker "light skin" patch
    /// (`data/skin/colorchecker_skin.csv`), CIELAB D65: 15 µm of foundation moves the skin
    /// ΔE*ab 5.0 of the 8.0 to its opaque colour (evens the tone, skin shows through; its T is
    /// 0.68/0.49/0.28 in linear RGB); 8 µm of blush over it is ΔE 12.7 from the foundation and
    /// 9.2 short of opaque (clearly visible, still sheer); 20 µm of lipstick is ΔE 31.7 from the
    /// base and 5.2 from opaque (nearly opaque; T 0.74/0.17/0.09).
    pub fn default_look() -> Look {
        let layer = |name: &str, thickness: ThicknessSource| {
            let preset = builtin_preset(name)?;
            let map = thickness.resolve(Path::new(".")).ok()?;
            Some(LookLayer {
                name: preset.name.clone(),
                preset_ref: format!("{BUILTIN_PREFIX}{name}"),
                preset,
                thickness,
                map,
                visible: true,
            })
        };
        let layers = [
            layer("foundation_02_ivory", ThicknessSource::Uniform { mm: 0.015 }),
            layer("blush_01_petal", ThicknessSource::Region { region: Region::Cheeks, mm: 0.008 }),
            layer("lipstick_02_red", ThicknessSource::Region { region: Region::Lips, mm: 0.02 }),
        ];
        Look { name: "Default".into(), layers: layers.into_iter().flatten().collect() }
    }

    /// Reads a look file; presets, masks and maps are resolved relative to its folder.
    pub fn load(path: &Path) -> Result<Look> {
        let text = std::fs::read_to_string(path).map_err(|e| ModelError::file(path, e))?;
        Look::from_json(&text, path)
    }

    /// Parses and resolves look JSON. `path` names the document in messages, and its folder is
    /// where relative presets, masks and maps are looked up.
    pub fn from_json(text: &str, path: &Path) -> Result<Look> {
        let err = |m: String| ModelError::file(path, m);
        let value: serde_json::Value = serde_json::from_str(text).map_err(|e| err(e.to_string()))?;
        let Some(obj) = value.as_object() else {
            return Err(err(format!("a look is a JSON object with \"schema\": {SCHEMA:?}")));
        };
        // Check the schema and version before the shape, so that another document or a future
        // version gets the right message rather than a complaint about its fields.
        match obj.get("schema").and_then(|s| s.as_str()) {
            Some(SCHEMA) => {}
            Some(other) => return Err(err(format!("`schema` is `{other}`, expected `{SCHEMA}`"))),
            None => return Err(err(format!("missing `schema`: expected `{SCHEMA}`"))),
        }
        if let Some(v) = obj.get("version").and_then(|v| v.as_u64())
            && v != u64::from(VERSION)
        {
            return Err(err(format!("look schema version {v} is not supported: this Rouge reads version {VERSION}")));
        }
        // First the document without looking into the layers, then the layers: serde's message
        // has the line and column, and a layer's error is prefixed with the layer.
        let shape: LookIn<serde_json::Value> = serde_json::from_str(text).map_err(|e| err(e.to_string()))?;
        let doc: LookIn<LayerIn> = serde_json::from_str(text).map_err(|e| {
            let bad =
                shape.layers.iter().enumerate().find(|(_, l)| serde_json::from_value::<LayerIn>((*l).clone()).is_err());
            match bad {
                Some((i, l)) => err(format!("layer {i} ({:?}): {e}", layer_label(l))),
                None => err(e.to_string()),
            }
        })?;
        let base = base_dir_of(path);
        let mut layers = Vec::with_capacity(doc.layers.len());
        for (i, l) in doc.layers.into_iter().enumerate() {
            let label = l.name.clone().filter(|n| !n.is_empty()).unwrap_or_else(|| l.preset.clone());
            let at = |m: String| err(format!("layer {i} ({label:?}): {m}"));
            if l.name.as_ref().is_some_and(|n| n.trim().is_empty()) {
                return Err(at("`name` is empty (leave it out to use the preset's name)".into()));
            }
            let preset = resolve_preset(&l.preset, base).map_err(at)?;
            let map = l.thickness.resolve(base).map_err(at)?;
            layers.push(LookLayer {
                name: l.name.unwrap_or_else(|| preset.name.clone()),
                preset_ref: l.preset,
                preset,
                thickness: l.thickness,
                map,
                visible: l.visible,
            });
        }
        let name = doc.name.unwrap_or_else(|| {
            path.file_stem().map_or_else(|| "Look".to_string(), |s| s.to_string_lossy().into_owned())
        });
        Ok(Look { name, layers })
    }

    /// Pretty JSON that [`Look::from_json`] reads back to an equal look (from the same folder:
    /// presets, masks and maps stay references, as written). A layer's name is written only
    /// where it differs from its preset's name, `visible` only where false.
    pub fn to_json(&self) -> String {
        let doc = LookOut {
            schema: SCHEMA,
            version: VERSION,
            name: &self.name,
            layers: self
                .layers
                .iter()
                .map(|l| LayerOut {
                    name: (l.name != l.preset.name).then_some(l.name.as_str()),
                    preset: &l.preset_ref,
                    thickness: &l.thickness,
                    visible: l.visible,
                })
                .collect(),
        };
        serde_json::to_string_pretty(&doc).map(|s| s + "\n").unwrap_or_default()
    }

    /// Writes the look atomically (temporary file, then rename). Relative references are written
    /// as they are, so they must hold from the new file's folder too.
    pub fn save(&self, path: &Path) -> Result<()> {
        write_atomic(path, self.to_json().as_bytes()).map_err(|e| ModelError::file(path, e))
    }

    /// The layers to draw, bottom to top.
    pub fn visible_layers(&self) -> impl Iterator<Item = &LookLayer> {
        self.layers.iter().filter(|l| l.visible)
    }
}
