//! High-dynamic-range images Rouge reads that are not maps of the face: an environment's
//! radiance as an OpenEXR file (the renderer's `--env`, `rouge_render::env::EnvMap::load_exr`).
//! The decoding lives here, beside the other file readers, so that the fuzz targets (which do
//! not build the renderer) reach it.

use exr::prelude::{ReadChannels, ReadLayers, Vec2 as ExrVec2};

/// The first layer with R, G and B channels of the OpenEXR file `bytes` (scan lines or tiles;
/// f16, f32 or u32 samples; alpha and other channels ignored; the largest mip level): its width,
/// height and texels, row 0 at the top.
///
/// # Errors
/// Why, in words: not a valid OpenEXR file, a header claiming more than `max_side` texels on a
/// side (checked before any texel is decoded: a few bytes of header can claim any size), no
/// layer with R, G and B channels (naming the channels there are), or an empty image.
pub fn decode_rgb_exr(bytes: &[u8], max_side: usize) -> Result<(usize, usize, Vec<[f32; 3]>), String> {
    let meta = exr::meta::MetaData::read_from_buffered(std::io::Cursor::new(bytes), false).map_err(exr_reason)?;
    if let Some(h) = meta.headers.iter().find(|h| h.layer_size.0 > max_side || h.layer_size.1 > max_side) {
        return Err(format!(
            "{} × {} texels: an environment map is at most {max_side} texels on a side",
            h.layer_size.0, h.layer_size.1
        ));
    }
    let has_rgb =
        |h: &exr::meta::header::Header| ["R", "G", "B"].iter().all(|n| h.channels.list.iter().any(|c| c.name.eq(n)));
    if !meta.headers.iter().any(has_rgb) {
        let found: Vec<String> =
            meta.headers.iter().flat_map(|h| h.channels.list.iter().map(|c| c.name.to_string())).collect();
        return Err(format!("no layer has R, G and B channels (channels: {})", found.join(", ")));
    }
    let image = exr::image::read::read()
        .no_deep_data()
        .largest_resolution_level()
        .rgb_channels(
            |size: ExrVec2<usize>, _| (size.0, vec![[0.0f32; 3]; size.0 * size.1]),
            |(w, px): &mut (usize, Vec<[f32; 3]>), pos: ExrVec2<usize>, (r, g, b): (f32, f32, f32)| {
                px[pos.1 * *w + pos.0] = [r, g, b];
            },
        )
        .first_valid_layer()
        .all_attributes()
        .from_buffered(std::io::Cursor::new(bytes))
        .map_err(exr_reason)?;
    let size = image.layer_data.size;
    let (width, height) = (size.0, size.1);
    if width == 0 || height == 0 {
        return Err(format!("the image is empty ({width} × {height} texels)"));
    }
    Ok((width, height, image.layer_data.channel_data.pixels.1))
}

/// An OpenEXR reader's error in words.
fn exr_reason(e: exr::error::Error) -> String {
    match e {
        exr::error::Error::Io(e) => format!("cannot read: {e}"),
        exr::error::Error::Invalid(m) => format!("not a valid OpenEXR file ({m})"),
        exr::error::Error::NotSupported(m) => format!("unsupported OpenEXR feature ({m})"),
        exr::error::Error::Aborted => "reading was aborted".to_string(),
    }
}
