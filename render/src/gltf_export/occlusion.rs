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
    let parts: Vec<_> = mesh.groups.iter().filter(|g| !g.is_skin()).map(|g| g.triangles.clone()).collect();
    let skin = TriangleMesh {
        indices: mesh
            .indices
            .chunks_exact(3)
            .enumerate()
            .filter(|(t, _)| !parts.iter().any(|r| r.contains(t)))
            .flat_map(|(_, tri)| tri.iter().copied())
            .collect(),
        groups: Vec::new(),
        tangents: None,
        ..mesh.clone()
    };
    let raster_px = side_px.min(MAX_RASTER_PX);
    let values: Vec<[f32; 3]> = per_vertex.iter().map(|&a| [a; 3]).collect();
    let map = thickness_uv_map(&skin, &values, raster_px, raster_px).map_err(fail)?;
    let at = |x: u32, y: u32| map.texel(x, y).map_or(1.0, |t| if t[3] > 0.0 { t[0] } else { 1.0 });
    if raster_px == side_px {
        return Ok((0..side_px).flat_map(|y| (0..side_px).map(move |x| (x, y))).map(|(x, y)| at(x, y)).collect());
    }
    // Bilinear between the raster's texel centres, clamped at its edges.
    let scale = raster_px as f32 / side_px as f32;
    let last = raster_px as f32 - 1.0;
    Ok((0..side_px)
        .flat_map(|y| (0..side_px).map(move |x| (x, y)))
        .map(|(x, y)| {
            let (fx, fy) =
                (((x as f32 + 0.5) * scale - 0.5).clamp(0.0, last), ((y as f32 + 0.5) * scale - 0.5).clamp(0.0, last));
            let (x0, y0) = (fx.floor() as u32, fy.floor() as u32);
            let (x1, y1) = ((x0 + 1).min(raster_px - 1), (y0 + 1).min(raster_px - 1));
            let (tx, ty) = (fx - x0 as f32, fy - y0 as f32);
            let top = at(x0, y0) * (1.0 - tx) + at(x1, y0) * tx;
            let bottom = at(x0, y1) * (1.0 - tx) + at(x1, y1) * tx;
            top * (1.0 - ty) + bottom * ty
        })
        .collect())
}
