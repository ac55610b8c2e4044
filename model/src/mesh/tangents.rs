//! MikkTSpace tangents for triangle meshes.

use std::collections::HashMap;

use glam::{Vec3, Vec4};

use super::{MeshError, TriangleMesh};

struct Geometry<'a> {
    mesh: &'a TriangleMesh,
    /// Tangent per triangle corner (index into `mesh.indices`).
    corner_tangents: Vec<Vec4>,
}

impl Geometry<'_> {
    fn vertex(&self, face: usize, vert: usize) -> usize {
        self.mesh.indices[face * 3 + vert] as usize
    }
}

impl mikktspace::Geometry for Geometry<'_> {
    fn num_faces(&self) -> usize {
        self.mesh.indices.len() / 3
    }

    fn num_vertices_of_face(&self, _face: usize) -> usize {
        3
    }

    fn position(&self, face: usize, vert: usize) -> [f32; 3] {
        self.mesh.positions[self.vertex(face, vert)].to_array()
    }

    fn normal(&self, face: usize, vert: usize) -> [f32; 3] {
        self.mesh.normals[self.vertex(face, vert)].to_array()
    }

    fn tex_coord(&self, face: usize, vert: usize) -> [f32; 2] {
        self.mesh.uvs[self.vertex(face, vert)].to_array()
    }

    fn set_tangent_encoded(&mut self, tangent: [f32; 4], face: usize, vert: usize) {
        self.corner_tangents[face * 3 + vert] = Vec4::from_array(tangent);
    }
}

/// Makes `t` a unit vector orthogonal to the unit normal `n`, falling back to any
/// perpendicular direction when `t` is degenerate (zero, NaN or parallel to `n`).
fn orthonormalize(t: Vec3, n: Vec3) -> Vec3 {
    let t = if t.is_finite() { t - n * n.dot(t) } else { Vec3::ZERO };
    t.try_normalize().unwrap_or_else(|| n.any_orthonormal_vector())
}

impl TriangleMesh {
    /// Generates MikkTSpace tangents into [`TriangleMesh::tangents`].
    ///
    /// Where MikkTSpace gives different tangents to the corners sharing a vertex, that vertex
    /// is split. Every tangent is then re-orthonormalised against the (unit) normal, so
    /// `xyz` is unit length and orthogonal to the normal, and `w` is ±1. Degenerate triangles
    /// (zero UV or zero area) get an arbitrary perpendicular tangent instead of NaN.
    ///
    /// # Errors
    /// [`MeshError::Empty`] if there are no triangles, [`MeshError::Tangents`] if MikkTSpace
    /// reports failure.
    pub fn generate_tangents(&mut self) -> Result<(), MeshError> {
        if self.indices.len() < 3 {
            return Err(MeshError::Empty);
        }
        let mut geo = Geometry { mesh: self, corner_tangents: vec![Vec4::ZERO; self.indices.len()] };
        if !mikktspace::generate_tangents(&mut geo) {
            return Err(MeshError::Tangents("mikktspace::generate_tangents returned false".into()));
        }
        let corner_tangents = geo.corner_tangents;

        // One vertex per (old vertex, tangent) pair; usually no split is needed.
        let old = self.positions.len();
        let mut tangents: Vec<Option<Vec4>> = vec![None; old];
        let mut splits: HashMap<(u32, [u32; 4]), u32> = HashMap::new();
        for (corner, &t) in corner_tangents.iter().enumerate() {
            let v = self.indices[corner] as usize;
            let n = self.normals[v];
            let w = if t.w < 0.0 { -1.0 } else { 1.0 };
            let t = orthonormalize(t.truncate(), n).extend(w);
            match tangents[v] {
                None => tangents[v] = Some(t),
                Some(existing) if existing.abs_diff_eq(t, 1e-5) => {}
                Some(_) => {
                    let key = (v as u32, t.to_array().map(f32::to_bits));
                    let new = *splits.entry(key).or_insert_with(|| {
                        self.positions.push(self.positions[v]);
                        self.normals.push(self.normals[v]);
                        self.uvs.push(self.uvs[v]);
                        tangents.push(Some(t));
                        (self.positions.len() - 1) as u32
                    });
                    self.indices[corner] = new;
                }
            }
        }
        let tangents = tangents
            .into_iter()
            .zip(&self.normals)
            .map(|(t, n)| t.unwrap_or_else(|| n.any_orthonormal_vector().extend(1.0)))
            .collect();
        self.tangents = Some(tangents);
        Ok(())
    }
}
