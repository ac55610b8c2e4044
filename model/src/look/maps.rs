//! Thickness maps (mm over the mesh's UV space): reading PNG/EXR, resampling, writing EXR; the
//! region masks of the default head.

use super::*;

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
    pub(super) fn sample_px(&self, px: f32, py: f32) -> f32 {
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
        let bytes = self.exr_bytes(path)?;
        write_atomic(path, &bytes).map_err(|e| ModelError::file(path, e))
    }

    /// The bytes [`ThicknessMap::save_exr`] writes; `path` names the file in an error.
    pub fn exr_bytes(&self, path: &Path) -> Result<Vec<u8>> {
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
        Ok(bytes.into_inner())
    }
}

/// Widest and tallest thickness map, mask or skin map read (pixels), checked in the file's header
/// before its pixels are decoded: maps are resampled to the document's 2048² anyway.
pub const MAX_MAP_SIDE_PX: u32 = 8192;
/// Largest map, mask or skin-map file read (bytes), checked before it is read: 8192² texels
/// of five 32-bit channels, uncompressed, fit.
pub const MAX_MAP_FILE_BYTES: u64 = 1 << 31;

/// Reads a map file named by a look or a project ([`rouge_measure::file_set::read_bounded`] with
/// [`MAX_MAP_FILE_BYTES`]).
pub(crate) fn read_map_file(path: &Path) -> std::io::Result<Vec<u8>> {
    rouge_measure::file_set::read_bounded(path, MAX_MAP_FILE_BYTES)
}

/// Refuses a `width × height` image past [`MAX_MAP_SIDE_PX`].
fn check_side(width: u32, height: u32) -> std::result::Result<(), String> {
    if width > MAX_MAP_SIDE_PX || height > MAX_MAP_SIDE_PX {
        return Err(format!("{width}×{height} pixels: a map is at most {MAX_MAP_SIDE_PX} pixels on a side"));
    }
    Ok(())
}

/// The first channel of a PNG as values in [0, 1] (value / max for 8- and 16-bit images).
pub(crate) fn decode_png_unit(bytes: &[u8]) -> std::result::Result<ThicknessMap, String> {
    use image::DynamicImage as D;
    if !bytes.starts_with(PNG_SIGNATURE) {
        let signature = if bytes.is_empty() || bytes.starts_with(EXR_MAGIC) {
            ""
        } else {
            "; a PNG starts with 89 50 4E 47 0D 0A 1A 0A"
        };
        return Err(format!("not a PNG file ({}{signature})", describe_start(bytes)));
    }
    let unreadable = |e: image::ImageError| format!("not a readable PNG file ({e})");
    let reader = || image::ImageReader::with_format(std::io::Cursor::new(bytes), image::ImageFormat::Png);
    let (w, h) = reader().into_dimensions().map_err(unreadable)?;
    check_side(w, h)?;
    let mut limits = image::Limits::default();
    limits.max_image_width = Some(MAX_MAP_SIDE_PX);
    limits.max_image_height = Some(MAX_MAP_SIDE_PX);
    let mut reader = reader();
    reader.limits(limits);
    let img = reader.decode().map_err(unreadable)?;
    let (width, height) = (img.width(), img.height());
    pub(super) fn first<T: Copy + Into<f32>>(raw: &[T], channels: usize, max: f32) -> Vec<f32> {
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

pub(super) fn describe_start(bytes: &[u8]) -> String {
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
pub(super) fn decode_exr(bytes: &[u8]) -> std::result::Result<(ThicknessMap, String), String> {
    let exr = read_exr_channels(bytes)?;
    let list = &exr.channels;
    let (name, mm) = list
        .iter()
        .find(|c| c.0 == "Y")
        .or_else(|| list.iter().find(|c| c.0 == "R"))
        .or_else(|| list.first())
        .ok_or("the OpenEXR file has no channels")?;
    let (w, h) = (exr.width, exr.height);
    if mm.len() != w as usize * h as usize {
        return Err(format!("channel {name:?} is subsampled ({} samples for {w}×{h} pixels)", mm.len()));
    }
    Ok((ThicknessMap { width: w, height: h, mm: mm.clone() }, name.clone()))
}

/// The channels of an OpenEXR file's first layer at full resolution.
pub(crate) struct ExrChannels {
    /// Width in pixels.
    pub width: u32,
    /// Height in pixels.
    pub height: u32,
    /// Each channel's name and values (row 0 first; fewer than `width × height` for a
    /// subsampled channel), sorted by name as EXR stores them; 16-bit and 32-bit float and
    /// 32-bit integer samples as f32.
    pub channels: Vec<(String, Vec<f32>)>,
}

/// Reads every channel of an OpenEXR file's first layer at full resolution; errors say why the
/// file is unreadable.
pub(crate) fn read_exr_channels(bytes: &[u8]) -> std::result::Result<ExrChannels, String> {
    use exr::prelude::{ReadChannels, ReadLayers, read};
    let unreadable = |e: exr::error::Error| format!("not a readable OpenEXR file ({e})");
    let meta = exr::meta::MetaData::read_from_buffered(std::io::Cursor::new(bytes), false).map_err(unreadable)?;
    for header in &meta.headers {
        let side = |n: usize| u32::try_from(n).unwrap_or(u32::MAX);
        check_side(side(header.layer_size.width()), side(header.layer_size.height()))?;
    }
    let image = read()
        .no_deep_data()
        .largest_resolution_level()
        .all_channels()
        .first_valid_layer()
        .all_attributes()
        .from_buffered(std::io::Cursor::new(bytes))
        .map_err(unreadable)?;
    let layer = image.layer_data;
    let (w, h) = (layer.size.width(), layer.size.height());
    let mut channels = Vec::with_capacity(layer.channel_data.list.len());
    for c in &layer.channel_data.list {
        channels.push((c.name.to_string(), c.sample_data.values().map(|s| s.to_f32()).collect()));
    }
    let too_big = |_| format!("{w}×{h} pixels is too large");
    let (width, height) = (u32::try_from(w).map_err(too_big)?, u32::try_from(h).map_err(too_big)?);
    Ok(ExrChannels { width, height, channels })
}

/// Checks that a thickness is finite, ≥ 0 and ≤ [`MAX_THICKNESS_MM`].
pub(super) fn thickness_ok(mm: f32) -> bool {
    mm.is_finite() && (0.0..=MAX_THICKNESS_MM).contains(&mm)
}

pub(super) fn range_rule() -> String {
    format!("thickness must be finite, ≥ 0 and ≤ {MAX_THICKNESS_MM} mm")
}

pub(super) fn check_field(field: &str, mm: f32) -> std::result::Result<f32, String> {
    if thickness_ok(mm) { Ok(mm) } else { Err(format!("`{field}` = {mm}: {}", range_rule())) }
}

/// Checks every pixel of a map, naming the first bad one.
pub(super) fn check_map(map: &ThicknessMap, what: &str) -> std::result::Result<(), String> {
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
    /// Where the brows grow (from the brow hairs' roots and shafts, `python/gen_brow_mask.py`):
    /// the skin a brow pencil, powder or gel fills.
    Brows,
}

pub(super) const REGION_PNGS: [&[u8]; 5] = [
    include_bytes!("../../../data/heads/masks/lips.png"),
    include_bytes!("../../../data/heads/masks/cheeks.png"),
    include_bytes!("../../../data/heads/masks/eyelids.png"),
    include_bytes!("../../../data/heads/masks/tzone.png"),
    include_bytes!("../../../data/heads/masks/brows.png"),
];

pub(super) static REGION_MASKS: [OnceLock<ThicknessMap>; 5] = [const { OnceLock::new() }; 5];

impl Region {
    /// Every region, in the order lips, cheeks, eyelids, tzone, brows.
    pub const fn all() -> [Region; 5] {
        [Region::Lips, Region::Cheeks, Region::Eyelids, Region::Tzone, Region::Brows]
    }

    /// The name used in look files: `lips`, `cheeks`, `eyelids`, `tzone`, `brows`.
    pub const fn name(self) -> &'static str {
        match self {
            Region::Lips => "lips",
            Region::Cheeks => "cheeks",
            Region::Eyelids => "eyelids",
            Region::Tzone => "tzone",
            Region::Brows => "brows",
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
