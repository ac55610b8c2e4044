//! The skin maps' colour as the renderer's albedo texture: per texel the linear sRGB of the
//! spectral skin model (D65, CIE 1931, the colour `rouge render --skin-tone` gives the whole
//! skin), read from the tone's [`SkinColorTable`] and encoded as 8-bit sRGB. Baked on the CPU
//! when the maps change; the renderer samples it like any albedo map.

use super::SkinMaps;
use rouge_measure::colorimetry::srgb_encode;
use rouge_measure::skin::SkinColorTable;

impl SkinMaps {
    /// The albedo texture of the maps (RGBA8, sRGB-encoded, alpha 255, row 0 at v = 1, the
    /// maps' size). `table` is made for the maps' [`SkinMaps::base`] (`SkinColorTable::new`);
    /// it holds that tone's scattering, which the maps do not vary. Rows are shared over the
    /// machine's cores.
    pub fn albedo_image(&self, table: &SkinColorTable) -> image::RgbaImage {
        let (w, h) = (self.width() as usize, self.height() as usize);
        let mut bytes = vec![0u8; w * h * 4];
        let threads = std::thread::available_parallelism().map_or(1, |n| n.get()).clamp(1, 16);
        let rows_per = h.div_ceil(threads).max(1);
        std::thread::scope(|s| {
            for (chunk, out) in bytes.chunks_mut(rows_per * w * 4).enumerate() {
                s.spawn(move || {
                    for (i, texel) in out.chunks_exact_mut(4).enumerate() {
                        let (x, y) = (i % w, chunk * rows_per + i / w);
                        let rgb = table.linear_srgb(&self.texel(x as u32, y as u32));
                        for (o, c) in texel.iter_mut().zip(rgb) {
                            *o = (srgb_encode(f64::from(c).clamp(0.0, 1.0)) * 255.0).round() as u8;
                        }
                        texel[3] = 255;
                    }
                });
            }
        });
        // The buffer has exactly width × height × 4 bytes, so this cannot fail.
        image::RgbaImage::from_raw(self.width(), self.height(), bytes).unwrap_or_default()
    }
}
