//! The occlusion plane of an export: the head's ambient occlusion (the eye sockets, the
//! nostrils, the corners of the mouth and the folds under the chin see less of the sky) baked
//! per vertex by the thickness baker's rays turned outward
//! ([`rouge_model::thickness::bake_ambient_occlusion`]) and rasterised into the skin's UV space.
//!
//! glTF's `occlusionTexture` darkens the indirect light only (glTF 2.0, `material.occlusionTexture`:
//! areas that receive less indirect lighting; direct lighting is not affected), so a viewer with
//! one light draws the same
//! frame with or without it; it is what Rouge's frame has no term for (the renderer's ambient is
//! unshadowed), and the base colour stays free of it, as glTF asks.

use crate::error::{RenderError, Result};
use rouge_model::look::ThicknessMap;
use rouge_model::mesh::TriangleMesh;
use rouge_model::thickness::{BakeSettings, Falloff, bake_ambient_occlusion, thickness_uv_map};

/// The bake's rays: 32 per vertex (the stratified pattern's error is at most 1/32 per vertex,
/// and the texture interpolates between vertices); a hit within 30 mm (an eye socket's depth, not
/// the far side of the face) occludes its ray: the weight (1 − t/30 mm)^0.01 is within 1 % of a
/// step until 29.7 mm, the classic ambient occlusion of a bounded distance. (The local thickness
/// bake's linear falloff, tried first, left the eye sockets at 0.94 against the cheeks' 0.98.)
pub const OCCLUSION_BAKE: BakeSettings =
    BakeSettings { rays: 32, cutoff_mm: 30.0, falloff: Falloff::Power { exponent: 0.01 }, seed: 0 };

/// The occlusion is rasterised at most this many texels a side and sampled bilinearly above: it
/// is smooth at the scale of the 30 mm rays, and a 4096² raster of f32 RGBA takes 256 MB.
const MAX_RASTER_PX: u32 = 1024;

/// The occlusion of the skin of `mesh` (mm) as a plane of `side_px`² values in [0, 1] (1 = open
/// sky), row 0 at v = 1 like every plane of [`super::SurfaceMaps`]; 1 where no skin triangle
/// maps. The other parts (eyes, lashes, mouth) occlude the skin but have no texels of their own.
///
/// # Errors
/// [`RenderError::Invalid`] naming the bake's or the raster's complaint.
pub fn occlusion_plane(mesh: &TriangleMesh, side_px: u32) -> Result<Vec<f32>> {
    let fail = |e: rouge_model::thickness::ThicknessError| RenderError::Invalid(format!("glTF export: occlusion: {e}"));
    let per_vertex = bake_ambient_occlusion(mesh, &OCCLUSION_BAKE).map_err(fail)?;
    // The skin's triangles, as the brush's surface map takes them.
    let skin = mesh.only(|g| g.is_skin());
    let raster_px = side_px.min(MAX_RASTER_PX);
    let values: Vec<[f32; 3]> = per_vertex.iter().map(|&a| [a; 3]).collect();
    let map = thickness_uv_map(&skin, &values, raster_px, raster_px).map_err(fail)?;
    let plane = ThicknessMap {
        width: raster_px,
        height: raster_px,
        mm: map.texels.iter().map(|t| if t[3] > 0.0 { t[0] } else { 1.0 }).collect(),
    };
    // Larger sides sampled bilinearly between the raster's texel centres, clamped at its edges,
    // as the looks' maps are resampled.
    Ok(plane.resized(side_px, side_px).mm)
}
