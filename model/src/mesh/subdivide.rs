//! Catmull-Clark subdivision with boundary rules and face-varying linear UVs.

use std::collections::HashMap;

use glam::{Vec2, Vec3};

use super::{Corner, Face, Group, Mesh};

/// Undirected edge key (smaller position index first).
fn edge_key(a: u32, b: u32) -> (u32, u32) {
    if a < b { (a, b) } else { (b, a) }
}

impl Mesh {
    /// Applies `levels` steps of Catmull-Clark subdivision and returns the new mesh.
    ///
    /// Each n-gon becomes n quads. Positions follow the Catmull-Clark rules; edges with one
    /// adjacent face (or more than two, treated the same way) are boundary creases: boundary
    /// edge points are midpoints and boundary vertices use the cubic B-spline rule
    /// `(a + 6p + b) / 8`; boundary corners (not exactly two boundary edges) stay fixed.
    /// UVs are subdivided face-varying and linearly (edge midpoints and face centroids per
    /// face), so UV seams stay sharp. Normals are recomputed as area-weighted vertex normals.
    ///
    /// In the result, positions `0..V` are the moved original vertices (same order), then
    /// come one point per edge, then one per face. Groups keep their names, covering the
    /// children of their faces.
    pub fn catmull_clark(&self, levels: u32) -> Mesh {
        let mut mesh = self.clone();
        for _ in 0..levels {
            mesh = mesh.subdivide_once();
        }
        if levels > 0 {
            mesh.recompute_normals();
        }
        mesh
    }

    fn subdivide_once(&self) -> Mesh {
        let nv = self.positions.len();
        // Edges and their adjacent face counts.
        let mut edges: HashMap<(u32, u32), u32> = HashMap::new();
        let mut edge_list: Vec<(u32, u32)> = Vec::new();
        let mut edge_faces: Vec<u32> = Vec::new();
        let mut edge_face_sum: Vec<Vec3> = Vec::new();
        let face_points: Vec<Vec3> = self
            .faces
            .iter()
            .map(|f| {
                f.corners.iter().map(|c| self.positions[c.position as usize]).sum::<Vec3>() / f.corners.len() as f32
            })
            .collect();
        for (fi, f) in self.faces.iter().enumerate() {
            let k = f.corners.len();
            for i in 0..k {
                let key = edge_key(f.corners[i].position, f.corners[(i + 1) % k].position);
                let id = *edges.entry(key).or_insert_with(|| {
                    edge_list.push(key);
                    edge_faces.push(0);
                    edge_face_sum.push(Vec3::ZERO);
                    (edge_list.len() - 1) as u32
                }) as usize;
                edge_faces[id] += 1;
                edge_face_sum[id] += face_points[fi];
            }
        }
        let ne = edge_list.len();
        let is_boundary = |e: usize| edge_faces[e] != 2;

        // Edge points.
        let edge_points: Vec<Vec3> = (0..ne)
            .map(|e| {
                let (a, b) = edge_list[e];
                let mid = (self.positions[a as usize] + self.positions[b as usize]) * 0.5;
                if is_boundary(e) { mid } else { (mid * 2.0 + edge_face_sum[e]) * 0.25 }
            })
            .collect();

        // Vertex accumulators.
        let mut face_sum = vec![Vec3::ZERO; nv];
        let mut face_count = vec![0u32; nv];
        for (fi, f) in self.faces.iter().enumerate() {
            for c in &f.corners {
                face_sum[c.position as usize] += face_points[fi];
                face_count[c.position as usize] += 1;
            }
        }
        let mut mid_sum = vec![Vec3::ZERO; nv];
        let mut valence = vec![0u32; nv];
        let mut bnd_sum = vec![Vec3::ZERO; nv];
        let mut bnd_count = vec![0u32; nv];
        for (e, &(a, b)) in edge_list.iter().enumerate() {
            let (pa, pb) = (self.positions[a as usize], self.positions[b as usize]);
            let mid = (pa + pb) * 0.5;
            for (v, other) in [(a as usize, pb), (b as usize, pa)] {
                mid_sum[v] += mid;
                valence[v] += 1;
                if is_boundary(e) {
                    bnd_sum[v] += other;
                    bnd_count[v] += 1;
                }
            }
        }
        let mut positions: Vec<Vec3> = (0..nv)
            .map(|v| {
                let p = self.positions[v];
                if face_count[v] == 0 || valence[v] == 0 {
                    p
                } else if bnd_count[v] == 2 {
                    (p * 6.0 + bnd_sum[v]) / 8.0
                } else if bnd_count[v] > 0 {
                    p
                } else {
                    let n = valence[v] as f32;
                    let f = face_sum[v] / face_count[v] as f32;
                    let r = mid_sum[v] / valence[v] as f32;
                    (f + 2.0 * r + (n - 3.0) * p) / n
                }
            })
            .collect();
        positions.extend_from_slice(&edge_points);
        positions.extend_from_slice(&face_points);

        // Face-varying linear UVs: original UVs kept, then edge midpoints, then face centroids.
        let mut uvs = self.uvs.clone();
        let mut uv_edges: HashMap<(u32, u32), u32> = HashMap::new();
        let mut faces = Vec::with_capacity(self.corner_count());
        let mut groups = Vec::with_capacity(self.groups.len());
        let mut face_start = vec![0usize; self.faces.len() + 1];
        for (fi, f) in self.faces.iter().enumerate() {
            face_start[fi + 1] = face_start[fi] + f.corners.len();
        }
        for (fi, f) in self.faces.iter().enumerate() {
            let k = f.corners.len();
            let fp = (nv + ne + fi) as u32;
            let fuv = uvs.len() as u32;
            uvs.push(f.corners.iter().map(|c| self.uvs[c.uv as usize]).sum::<Vec2>() / k as f32);
            // Edge child corners: edge i runs from corner i to corner i + 1.
            let mut edge_corner = Vec::with_capacity(k);
            for i in 0..k {
                let (a, b) = (f.corners[i], f.corners[(i + 1) % k]);
                let e = edges.get(&edge_key(a.position, b.position)).copied().unwrap_or(0);
                let uv = *uv_edges.entry(edge_key(a.uv, b.uv)).or_insert_with(|| {
                    uvs.push((self.uvs[a.uv as usize] + self.uvs[b.uv as usize]) * 0.5);
                    (uvs.len() - 1) as u32
                });
                let p = (nv as u32) + e;
                edge_corner.push(Corner { position: p, uv, normal: p });
            }
            for i in 0..k {
                let c = f.corners[i];
                faces.push(Face {
                    corners: vec![
                        Corner { position: c.position, uv: c.uv, normal: c.position },
                        edge_corner[i],
                        Corner { position: fp, uv: fuv, normal: fp },
                        edge_corner[(i + k - 1) % k],
                    ],
                });
            }
        }
        for g in &self.groups {
            let start = face_start[g.faces.start.min(self.faces.len())];
            let end = face_start[g.faces.end.min(self.faces.len())];
            groups.push(Group { name: g.name.clone(), material: g.material.clone(), faces: start..end });
        }
        let normals = vec![Vec3::Z; positions.len()];
        Mesh { positions, normals, uvs, faces, groups }
    }
}
