//! The per-vertex values rasterised into the mesh's UV space.

use std::fmt;

use glam::Vec3;

use super::ThicknessError;
use crate::mesh::TriangleMesh;
use crate::paint::{dilate_and_collect, rasterise};

/// Most texels a [`UvMap`] may have (16384²).
const MAX_UV_TEXELS: usize = 1 << 28;

/// u = (x + 0.5)/width, v = 1 − (y + 0.5)/height, as [`crate::paint::SurfaceMap`] and the
/// looks' maps.
#[derive(Clone, PartialEq)]
pub struct UvMap {
    /// Width in texels.
    pub width: u32,
    /// Height in texels.
    pub height: u32,
    /// Row-major texels, `width × height`, row 0 at the top.
    pub texels: Vec<[f32; 4]>,
}

impl fmt::Debug for UvMap {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let covered = self.texels.iter().filter(|t| t[3] > 0.0).count();
        f.debug_struct("UvMap")
            .field("width", &self.width)
            .field("height", &self.height)
            .field("covered", &covered)
            .finish()
    }
}

impl UvMap {
    /// Texel (x, y) (row 0 at the top); `None` outside the map.
    pub fn texel(&self, x: u32, y: u32) -> Option<[f32; 4]> {
        if x >= self.width || y >= self.height {
            return None;
        }
        self.texels.get(y as usize * self.width as usize + x as usize).copied()
    }
}

// UV map

/// The per-vertex values rasterised into the mesh's UV space (`width` × `height`, row 0 at top =
/// v = 1, like [`crate::paint::SurfaceMap`]), dilated across seams, RGBA f32 with alpha 1 where
/// covered, 0 elsewhere.
///
/// Values are interpolated barycentrically at texel centres; texels in the two-texel ring around
/// a UV island take the value of the nearest covered texel (alpha 1 too), so bilinear sampling
/// at seams reads baked values. Uncovered texels are [0, 0, 0, 0]. Triangles with no area in UV
/// space are skipped; where islands overlap the later triangle wins.
///
/// # Errors
/// [`ThicknessError::Map`] when `values` does not hold one finite value per vertex, the mesh has
/// fewer UVs than vertices, or the size is zero or over 16384² texels.
pub fn thickness_uv_map(
    mesh: &TriangleMesh,
    values: &[[f32; 3]],
    width: u32,
    height: u32,
) -> Result<UvMap, ThicknessError> {
    let n = mesh.vertex_count();
    if values.len() != n {
        return Err(ThicknessError::Map(format!("{} values for {n} vertices", values.len())));
    }
    if mesh.uvs.len() != n {
        return Err(ThicknessError::Map(format!("{} UVs for {n} vertices", mesh.uvs.len())));
    }
    if let Some((i, v)) = values.iter().enumerate().find(|(_, v)| !v.iter().all(|c| c.is_finite())) {
        return Err(ThicknessError::Map(format!("vertex {i}: non-finite value {v:?}")));
    }
    let (w, h) = (width as usize, height as usize);
    if w == 0 || h == 0 || w.checked_mul(h).is_none_or(|t| t > MAX_UV_TEXELS) {
        return Err(ThicknessError::Map(format!("size {width}×{height}: must be at least 1×1 and at most 16384²")));
    }
    let attribute: Vec<Vec3> = values.iter().map(|&v| Vec3::from_array(v)).collect();
    let raster = rasterise(mesh, &attribute, w, h);
    let mut texels = vec![[0.0; 4]; w * h];
    for (i, v) in dilate_and_collect(&raster, w, h) {
        texels[i as usize] = [v.x, v.y, v.z, 1.0];
    }
    Ok(UvMap { width, height, texels })
}
