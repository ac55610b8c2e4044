//! The thickness heat map of the painting app's viewport: a layer's rendered thickness per
//! pixel, as the G-buffer read it, in colour, with a scale in µm for the legend. No egui here, so
//! the colours and the scale are tested without a window.

use crate::ticks;

/// The viridis colour map (matplotlib's, perceptually uniform, readable in greyscale and by
/// most colour-blind viewers) at 0, 1/8, ..., 1, sRGB.
const VIRIDIS: [[u8; 3]; 9] = [
    [68, 1, 84],
    [71, 44, 122],
    [59, 81, 139],
    [44, 113, 142],
    [33, 144, 141],
    [39, 173, 129],
    [92, 200, 99],
    [170, 220, 50],
    [253, 231, 37],
];

/// The colour of `t` in [0, 1] (clamped; NaN is 0), linear between the map's nine stops.
pub fn colour_map(t: f32) -> [u8; 3] {
    let t = if t.is_nan() { 0.0 } else { t.clamp(0.0, 1.0) } * (VIRIDIS.len() - 1) as f32;
    let i = (t.floor() as usize).min(VIRIDIS.len() - 2);
    let f = t - i as f32;
    std::array::from_fn(|c| {
        let (a, b) = (f32::from(VIRIDIS[i][c]), f32::from(VIRIDIS[i + 1][c]));
        (a + (b - a) * f).round() as u8
    })
}

/// A heat map's scale: 0 to `top_um`, ticks every `step_um`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct HeatScale {
    /// The thickness of the top colour, µm: a tick at or above the layer's thickest texel.
    pub top_um: f64,
    /// The legend's tick step, µm.
    pub step_um: f64,
}

/// Texels at or below this thickness (µm) count as unpainted: the heat map leaves them clear.
pub const UNPAINTED_UM: f64 = 0.05;

impl HeatScale {
    /// The scale for a layer whose thickest texel is `max_mm` (its map × its multiplier): about
    /// five ticks, the top one at or above the maximum; 0 to 1 µm for an unpainted layer.
    pub fn for_max_mm(max_mm: f32) -> HeatScale {
        let max_um = (f64::from(max_mm) * 1000.0).max(1.0);
        let step_um = ticks::nice_step(max_um, 5);
        HeatScale { top_um: (max_um / step_um - 1e-9).ceil() * step_um, step_um }
    }

    /// The legend's ticks, µm, 0 to the top.
    pub fn ticks_um(&self) -> Vec<f64> {
        ticks::ticks_with_step(0.0, self.top_um, self.step_um)
    }

    /// A tick's label.
    pub fn label(&self, um: f64) -> String {
        ticks::label(um, self.step_um)
    }

    /// The colour of a thickness in mm, opaque; `None` for an unpainted texel.
    pub fn colour(&self, mm: f32) -> Option<[u8; 3]> {
        let um = f64::from(mm) * 1000.0;
        (um > UNPAINTED_UM).then(|| colour_map((um / self.top_um) as f32))
    }

    /// The heat map of a frame: per pixel the colour of `thickness_mm[i]`, alpha 255, or clear
    /// (0, 0, 0, 0) where unpainted, as RGBA bytes in the frame's order.
    pub fn image(&self, thickness_mm: impl IntoIterator<Item = f32>) -> Vec<u8> {
        thickness_mm
            .into_iter()
            .flat_map(|mm| match self.colour(mm) {
                Some([r, g, b]) => [r, g, b, 255],
                None => [0; 4],
            })
            .collect()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_colour_map_runs_from_dark_violet_to_yellow_and_brightens() {
        assert_eq!(colour_map(0.0), [68, 1, 84]);
        assert_eq!(colour_map(1.0), [253, 231, 37]);
        assert_eq!(colour_map(f32::NAN), [68, 1, 84]);
        assert_eq!(colour_map(2.0), [253, 231, 37]);
        let luma = |c: [u8; 3]| 0.2126 * f32::from(c[0]) + 0.7152 * f32::from(c[1]) + 0.0722 * f32::from(c[2]);
        let steps: Vec<f32> = (0..=32).map(|i| luma(colour_map(i as f32 / 32.0))).collect();
        assert!(steps.windows(2).all(|w| w[1] > w[0]), "{steps:?}");
    }

    #[test]
    fn the_scale_tops_the_thickest_texel_with_a_tick() {
        let s = HeatScale::for_max_mm(0.02);
        assert_eq!((s.top_um, s.step_um), (20.0, 5.0));
        assert_eq!(s.ticks_um(), vec![0.0, 5.0, 10.0, 15.0, 20.0]);
        let s = HeatScale::for_max_mm(0.0123);
        assert_eq!((s.top_um, s.step_um), (15.0, 5.0));
        assert_eq!(s.label(15.0), "15");
        let s = HeatScale::for_max_mm(0.0);
        assert_eq!((s.top_um, s.step_um), (1.0, 0.2));
        assert_eq!(s.label(0.4), "0.4");
    }

    #[test]
    fn unpainted_pixels_are_clear_and_painted_ones_opaque() {
        let s = HeatScale::for_max_mm(0.02);
        let img = s.image([0.0, 0.00001, 0.01, 0.02, 0.05]);
        assert_eq!(&img[0..8], &[0; 8]);
        assert_eq!(&img[8..12], &[33, 144, 141, 255]);
        assert_eq!(&img[12..16], &[253, 231, 37, 255]);
        // Above the top (another layer's scale) saturates.
        assert_eq!(&img[16..20], &[253, 231, 37, 255]);
    }
}
