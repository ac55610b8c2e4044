//! Catmull-Clark subdivision with boundary rules and face-varying linear UVs, split into what
//! depends on the connectivity ([`StepTopology`], computed once) and what depends on the
//! positions ([`StepTopology::positions`]), so a deforming mesh re-runs only the latter
//! ([`super::deform::SubdivisionPlan`]).

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
            let step = StepTopology::new(&mesh);
            let positions = step.positions(&mesh.positions);
            mesh = Mesh { positions, ..step.children(&mesh) };
        }
        if levels > 0 {
            mesh.recompute_normals();
        }
        mesh
    }
}

/// The Catmull-Clark rule of a moved parent vertex at `p`: from the sum of the face points of
/// its `face_count` faces, the sum of the midpoints of its `valence` edges, and the sum of the
/// far ends of its `bnd_count` boundary edges (a crease: the cubic B-spline rule with two, fixed
/// with another count; fixed where isolated).
pub(crate) fn vertex_point(
    p: Vec3,
    face_sum: Vec3,
    face_count: u32,
    mid_sum: Vec3,
    valence: u32,
    bnd_sum: Vec3,
    bnd_count: u32,
) -> Vec3 {
    if face_count == 0 || valence == 0 {
        p
    } else if bnd_count == 2 {
        (p * 6.0 + bnd_sum) / 8.0
    } else if bnd_count > 0 {
        p
    } else {
        let n = valence as f32;
        let f = face_sum / face_count as f32;
        let r = mid_sum / valence as f32;
        (f + 2.0 * r + (n - 3.0) * p) / n
    }
}

/// The Catmull-Clark rule of the point of edge `pa`-`pb`: its midpoint on a boundary, else
/// the mean of its ends and of its two faces' points (`face_sum`).
pub(crate) fn edge_point(pa: Vec3, pb: Vec3, boundary: bool, face_sum: Vec3) -> Vec3 {
    let mid = (pa + pb) * 0.5;
    if boundary { mid } else { (mid * 2.0 + face_sum) * 0.25 }
}

/// The connectivity of one subdivision step: the parent's faces, edges and which faces each
/// edge borders, in the order the position rules sum them.
#[derive(Debug, Clone)]
pub(crate) struct StepTopology {
    /// Parent vertex count.
    pub(crate) nv: usize,
    /// Parent faces' corner positions, flattened; face `f` is `corners[face_start[f]..face_start[f + 1]]`.
    pub(crate) corners: Vec<u32>,
    pub(crate) face_start: Vec<usize>,
    /// Edge of each flattened corner: from that corner to the next one of its face.
    pub(crate) corner_edge: Vec<u32>,
    /// Edges (smaller position first), in the order first met.
    pub(crate) edges: Vec<(u32, u32)>,
    /// Faces bordering each edge.
    pub(crate) edge_faces: Vec<u32>,
}

impl StepTopology {
    pub(crate) fn new(mesh: &Mesh) -> StepTopology {
        let mut ids: HashMap<(u32, u32), u32> = HashMap::new();
        let (mut corners, mut corner_edge, mut edges, mut edge_faces) =
            (Vec::new(), Vec::new(), Vec::new(), Vec::new());
        let mut face_start = Vec::with_capacity(mesh.faces.len() + 1);
        face_start.push(0);
        for f in &mesh.faces {
            let k = f.corners.len();
            for i in 0..k {
                let key = edge_key(f.corners[i].position, f.corners[(i + 1) % k].position);
                let id = *ids.entry(key).or_insert_with(|| {
                    edges.push(key);
                    edge_faces.push(0);
                    (edges.len() - 1) as u32
                });
                edge_faces[id as usize] += 1;
                corners.push(f.corners[i].position);
                corner_edge.push(id);
            }
            face_start.push(corners.len());
        }
        StepTopology { nv: mesh.positions.len(), corners, face_start, corner_edge, edges, edge_faces }
    }

    fn face(&self, f: usize) -> std::ops::Range<usize> {
        self.face_start[f]..self.face_start[f + 1]
    }

    /// The child positions from the parent's: the moved parent vertices, then one point per
    /// edge, then one per face (the Catmull-Clark rules of [`Mesh::catmull_clark`]).
    pub(crate) fn positions(&self, parent: &[Vec3]) -> Vec<Vec3> {
        let (nv, ne, nf) = (self.nv, self.edges.len(), self.face_start.len() - 1);
        let face_points: Vec<Vec3> = (0..nf)
            .map(|f| {
                let r = self.face(f);
                let k = r.len() as f32;
                self.corners[r].iter().map(|&c| parent[c as usize]).sum::<Vec3>() / k
            })
            .collect();
        let mut edge_face_sum = vec![Vec3::ZERO; ne];
        let mut face_sum = vec![Vec3::ZERO; nv];
        let mut face_count = vec![0u32; nv];
        for (f, fp) in face_points.iter().enumerate() {
            for i in self.face(f) {
                edge_face_sum[self.corner_edge[i] as usize] += *fp;
                face_sum[self.corners[i] as usize] += *fp;
                face_count[self.corners[i] as usize] += 1;
            }
        }
        let is_boundary = |e: usize| self.edge_faces[e] != 2;
        let mut out = Vec::with_capacity(nv + ne + nf);
        let mut mid_sum = vec![Vec3::ZERO; nv];
        let mut valence = vec![0u32; nv];
        let mut bnd_sum = vec![Vec3::ZERO; nv];
        let mut bnd_count = vec![0u32; nv];
        for (e, &(a, b)) in self.edges.iter().enumerate() {
            let (pa, pb) = (parent[a as usize], parent[b as usize]);
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
        out.extend((0..nv).map(|v| {
            vertex_point(parent[v], face_sum[v], face_count[v], mid_sum[v], valence[v], bnd_sum[v], bnd_count[v])
        }));
        out.extend(
            self.edges.iter().enumerate().map(|(e, &(a, b))| {
                edge_point(parent[a as usize], parent[b as usize], is_boundary(e), edge_face_sum[e])
            }),
        );
        out.extend_from_slice(&face_points);
        out
    }

    /// The child mesh's faces, UVs and groups (positions empty, normals +Z: the caller fills
    /// them). Face-varying linear UVs: the parent's kept, then edge midpoints, then face centroids.
    pub(crate) fn children(&self, parent: &Mesh) -> Mesh {
        let (nv, ne) = (self.nv, self.edges.len());
        let mut uvs = parent.uvs.clone();
        let mut uv_edges: HashMap<(u32, u32), u32> = HashMap::new();
        let mut faces = Vec::with_capacity(self.corners.len());
        for (fi, f) in parent.faces.iter().enumerate() {
            let k = f.corners.len();
            let fp = (nv + ne + fi) as u32;
            let fuv = uvs.len() as u32;
            uvs.push(f.corners.iter().map(|c| parent.uvs[c.uv as usize]).sum::<Vec2>() / k as f32);
            // Edge child corners: edge i runs from corner i to corner i + 1.
            let mut edge_corner = Vec::with_capacity(k);
            for i in 0..k {
                let (a, b) = (f.corners[i], f.corners[(i + 1) % k]);
                let e = self.corner_edge[self.face_start[fi] + i];
                let uv = *uv_edges.entry(edge_key(a.uv, b.uv)).or_insert_with(|| {
                    uvs.push((parent.uvs[a.uv as usize] + parent.uvs[b.uv as usize]) * 0.5);
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
        let groups = parent
            .groups
            .iter()
            .map(|g| {
                let at = |f: usize| self.face_start[f.min(parent.faces.len())];
                Group { name: g.name.clone(), material: g.material.clone(), faces: at(g.faces.start)..at(g.faces.end) }
            })
            .collect();
        let count = nv + ne + parent.faces.len();
        Mesh { positions: Vec::new(), normals: vec![Vec3::Z; count], uvs, faces, groups }
    }
}
