//! A deformation for re-bake tests: the mesh morphed toward its bounding sphere.

use glam::Vec3;

use super::{ThicknessError, smooth_normals_per_position};
use crate::mesh::{Bounds, TriangleMesh};

/// A morph of the mesh toward its bounding sphere (a deformation for testing re-bakes):
/// p′ = lerp(p, c + R·(p − c)/|p − c|, t), c = the centre of the positions' bounding box,
/// R = max |p − c|. For t > 0 the normals are recomputed as area-weighted smooth normals, equal
/// for every vertex at the same position (a [`TriangleMesh`] has one vertex per (position, uv,
/// normal)); tangents are dropped (regenerate them). t = 0 returns the mesh unchanged, normals
/// included. A vertex exactly at c has no direction and stays where it is.
///
/// # Errors
/// [`ThicknessError::MorphT`] for t outside [0, 1] (or NaN); [`ThicknessError::Mesh`] for a
/// non-finite position.
pub fn morph_to_bounding_sphere(mesh: &TriangleMesh, t: f32) -> Result<TriangleMesh, ThicknessError> {
    if !(0.0..=1.0).contains(&t) {
        return Err(ThicknessError::MorphT(t));
    }
    if let Some((i, p)) = mesh.positions.iter().enumerate().find(|(_, p)| !p.is_finite()) {
        return Err(ThicknessError::Mesh(format!("vertex {i}: non-finite position {p}")));
    }
    if t == 0.0 {
        return Ok(mesh.clone());
    }
    let Some(bounds) = Bounds::of(&mesh.positions) else { return Ok(mesh.clone()) };
    let c = bounds.center();
    let radius = mesh.positions.iter().map(|p| p.distance(c)).fold(0.0f32, f32::max);
    let mut out = mesh.clone();
    for p in &mut out.positions {
        if let Some(dir) = (*p - c).try_normalize() {
            let on_sphere = c + dir * radius;
            *p = if t == 1.0 { on_sphere } else { p.lerp(on_sphere, t) };
        }
    }
    let smooth = smooth_normals_per_position(&out);
    out.normals = smooth.iter().map(|n| if *n == Vec3::ZERO { Vec3::Z } else { *n }).collect();
    out.tangents = None;
    Ok(out)
}
