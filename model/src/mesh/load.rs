//! Loading a mesh by its file's extension, ready to paint and render.

use std::path::Path;

use super::shapes::{BUILTIN_SHAPES, builtin_shape};
use super::{TriangleMesh, default_head, load_gltf, load_obj};
use crate::error::{ModelError, Result};

/// Loads a mesh by extension (or the default head for `None`), subdivides it `subdivision`
/// times (Catmull-Clark) and triangulates it. `builtin:head`, `builtin:sphere` and
/// `builtin:wedge` name the built-in objects ([`super::shapes`]); the sphere and the wedge are
/// exact shapes in mm times `scale_mm` (a 100 mm sphere is `builtin:sphere` at 4), never
/// subdivided; the head keeps its size (its morph targets are in mm).
///
/// # Errors
/// The loader's error naming the file; an unknown extension or built-in name.
pub fn load_mesh(path: Option<&Path>, scale_mm: f32, subdivision: u32) -> Result<TriangleMesh> {
    if let Some(name) = path.and_then(|p| p.to_str()).and_then(|p| p.strip_prefix("builtin:")) {
        if name == "head" {
            return load_mesh(None, scale_mm, subdivision);
        }
        let shape = builtin_shape(name).ok_or_else(|| {
            ModelError::Invalid(format!(
                "--mesh builtin:{name}: no such built-in mesh; use builtin:{}",
                BUILTIN_SHAPES.join(", builtin:")
            ))
        })?;
        let mut mesh = shape.triangulate();
        if scale_mm != 1.0 {
            mesh.positions.iter_mut().for_each(|p| *p *= scale_mm);
        }
        return Ok(mesh);
    }
    let mesh = match path {
        None => default_head()?,
        Some(p) => match p.extension().and_then(|e| e.to_str()).map(str::to_ascii_lowercase).as_deref() {
            Some("obj") => load_obj(p, scale_mm)?,
            Some("gltf" | "glb") => load_gltf(p, scale_mm)?,
            _ => return Err(ModelError::file(p, "unknown mesh format: use .obj, .gltf or .glb")),
        },
    };
    Ok(super::strands::subdivided_with_strands(&mesh, subdivision))
}
