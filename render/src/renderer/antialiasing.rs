//! The frame's antialiasing as `rouge render --aa` chooses it: the edge overdraw of a mode, and
//! supersampling (the same frame at k× the size, box-filtered down in linear light).

use super::Renderer;
use crate::aa::{self, AaMode, EdgeCoverage};
use crate::error::Result;
use crate::scene::{Camera, Scene};

impl Renderer {
    /// Sets the edge overdraw of the following frames for `mode` (with `coverage`), the hairs'
    /// coverage (on for every mode but `none`, [`Renderer::set_hair_aa`]), and returns
    /// the mode's supersampling factor k (1 for the modes that do not supersample).
    ///
    /// # Errors
    /// As [`AaMode::frame`].
    pub fn set_aa_mode(&mut self, mode: AaMode, coverage: EdgeCoverage) -> Result<u32> {
        let (edge, k) = mode.frame(coverage)?;
        self.set_edge_aa(edge);
        self.set_hair_aa(mode != AaMode::None);
        Ok(k)
    }

    /// The display image of `scene` from `camera` at `w` × `h`, in linear sRGB, supersampled
    /// k×k (k = 1: as it is).
    ///
    /// # Errors
    /// As [`Renderer::render`] and [`aa::box_downsample`].
    pub fn render_linear_srgb(
        &mut self,
        scene: &Scene,
        camera: &Camera,
        (w, h): (u32, u32),
        k: u32,
    ) -> Result<Vec<[f32; 3]>> {
        self.render(scene, camera, w * k, h * k, true)?;
        let linear = aa::decode_srgb8(&self.read_display()?);
        if k == 1 { Ok(linear) } else { aa::box_downsample(&linear, (w as usize, h as usize), k as usize) }
    }
}
