//! Discontinuity edges of a mesh for edge-overdraw antialiasing (\[Sander2001\], "Discontinuity
//! Edge Overdraw"): the preprocess of section 3.2 (sharp edges, boundary edges, silhouette
//! candidates without the concave and sharp ones), the orientation of section 3.3 / figure 4,
//! and the per-frame classification of section 3.5 (the CPU twin of `classify` in
//! shaders/edge_overdraw.wgsl), with the back-to-front sort of section 3.4.
//!
//! Printed errors found while deriving section 3.5 (fixed here and in the shader):
//! * The algorithm writes `dleft = dot(n, midpoint − viewpoint)` and skips the edge when
//!   `dleft < 0 and dright < 0` "// backfacing". With that sign a negative dot product means
//!   *front*-facing, so the printed test skips exactly the edges that are seen. Section 3.3 uses
//!   V = eye − midpoint, with which d > 0 is front-facing: that is the form used here, and an edge
//!   is skipped when both faces face away (d ≤ 0).
//! * The printed loop computes β = dR / (dL + dR) for every sharp edge, also when exactly one face
//!   faces the eye (a sharp edge on the silhouette). There β leaves [0, 1]: with dL > 0 > dR and
//!   dL + dR < 0, β > 1 and the edge would get the *back* face's shading. Section 3.3 says a sharp
//!   silhouette is shaded from its front face, so such edges are classified as silhouettes first.
//! * The transfer function of section 3.3 (lost from the text) is reconstructed from section 3.5:
//!   β′ = 0 for β ≤ τ and β′ = (β − τ) / (1 − τ) above, τ = 0.9, so that the left face's shading is
//!   used as long as possible and the right face takes over only as the left face turns edge-on
//!   (β → 1 as dL → 0).

use glam::Vec3;
use rouge_model::mesh::TriangleMesh;
use std::collections::HashMap;

/// The paper's τ: sharp edges with β ≤ τ use the left face's shading only (section 3.5).
pub const BLEND_THRESHOLD: f32 = 0.9;
/// Sharp edges with β < this or β > [`BLEND_THRESHOLD`] are "near the silhouette" and sorted
/// (section 3.4, footnote 1).
pub const NEAR_SILHOUETTE: f32 = 0.1;

/// What makes an edge sharp.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct EdgeOptions {
    /// Dihedral angle between the two faces' normals above which an edge is sharp, degrees.
    pub dihedral_deg: f32,
    /// Whether a UV seam (different texture coordinates on the two sides) makes an edge sharp.
    /// Off by default: Rouge's maps are dilated across seams, so a seam is no shading jump.
    pub uv_seams: bool,
}

impl Default for EdgeOptions {
    fn default() -> EdgeOptions {
        EdgeOptions { dihedral_deg: 40.0, uv_seams: false }
    }
}

/// The category of a preprocessed edge.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
#[repr(u32)]
pub enum EdgeKind {
    /// Smooth, convex or on an open mesh: a silhouette candidate.
    Smooth = 0,
    /// A shading discontinuity (normals, material, UVs, or a dihedral angle over the threshold).
    Sharp = 1,
    /// On the mesh boundary (one face): a silhouette from every viewpoint (section 5).
    Boundary = 2,
}

/// One discontinuity or candidate edge. The left face is the one whose counter-clockwise winding
/// runs `p0 → p1`; seen from its front it lies to the left of the edge.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Edge {
    /// First end, mm.
    pub p0: Vec3,
    /// Second end, mm.
    pub p1: Vec3,
    /// Unit normal of the left face.
    pub n_left: Vec3,
    /// Unit normal of the right face (the left one again for a boundary edge).
    pub n_right: Vec3,
    /// Its category.
    pub kind: EdgeKind,
    /// Where it came from in the triangle mesh: the vertices at `p0` and `p1`, the left and the
    /// right triangle (the left one again for a boundary edge), for [`EdgeSet::reposition`].
    pub source: [u32; 4],
}

impl Edge {
    /// Midpoint, mm.
    pub fn midpoint(&self) -> Vec3 {
        0.5 * (self.p0 + self.p1)
    }
}

/// Counts of the preprocess (the first rows of \[Sander2001\] table 1).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, serde::Serialize)]
pub struct EdgeCounts {
    /// Triangles.
    pub faces: usize,
    /// Distinct edges (vertices welded by position).
    pub edges: usize,
    /// Sharp edges.
    pub sharp: usize,
    /// Boundary edges.
    pub boundary: usize,
    /// Concave or flat smooth edges (outer dihedral angle ≤ 180°) left out of the silhouette
    /// search (closed meshes only).
    pub concave: usize,
    /// Smooth edges searched for silhouettes each frame.
    pub candidates: usize,
}

/// The preprocessed edges of a mesh: sharp edges first (consistently oriented), then boundary
/// edges, then the silhouette candidates.
#[derive(Clone, Debug, Default)]
pub struct EdgeSet {
    /// The edges that may be drawn.
    pub edges: Vec<Edge>,
    /// Whether the mesh is closed (every edge has two faces); then faces seen from behind are
    /// hidden, concave edges are never silhouettes and back-facing sharp edges are skipped.
    pub closed: bool,
    /// The counts.
    pub counts: EdgeCounts,
    /// The mesh's triangles, to tell a posed copy of it (same triangles) from another mesh.
    indices: Vec<u32>,
}

/// Per-edge accumulation while welding: the faces on each side.
struct Sides {
    a: u32,
    /// (face, the vertex index at `a`, the vertex index at `b`, the face's third vertex) for the
    /// face whose winding runs a → b, and for the one that runs b → a.
    forward: Vec<[u32; 4]>,
    backward: Vec<[u32; 4]>,
}

impl EdgeSet {
    /// Preprocesses `mesh` (\[Sander2001\] section 3.2 and 3.3): welds vertices by position, finds
    /// sharp and boundary edges, orients the sharp edges into consistent chains, and keeps as
    /// silhouette candidates the smooth edges, without the concave ones on a closed mesh.
    /// Degenerate triangles (zero area) are left out.
    pub fn new(mesh: &TriangleMesh, options: EdgeOptions) -> EdgeSet {
        let positions = &mesh.positions;
        let mut weld: HashMap<[u32; 3], u32> = HashMap::new();
        let canon: Vec<u32> = positions
            .iter()
            .map(|p| {
                let key = [p.x.to_bits(), p.y.to_bits(), p.z.to_bits()];
                let next = weld.len() as u32;
                *weld.entry(key).or_insert(next)
            })
            .collect();
        let mut material = vec![0u32; mesh.indices.len() / 3];
        for (g, group) in mesh.groups.iter().enumerate() {
            for t in group.triangles.clone() {
                if let Some(m) = material.get_mut(t) {
                    *m = g as u32;
                }
            }
        }
        let mut face_normals = Vec::with_capacity(mesh.indices.len() / 3);
        let mut map: HashMap<(u32, u32), usize> = HashMap::new();
        let mut sides: Vec<Sides> = Vec::new();
        let mut faces = 0;
        // Hairs drawn as fibres (the hair pass, when the mesh has strands) have no edges here.
        let mut fibre = vec![false; mesh.indices.len() / 3];
        if mesh.strands.is_some() {
            for g in mesh.groups.iter().filter(|g| g.part().is_hair()) {
                fibre.get_mut(g.triangles.clone()).into_iter().flatten().for_each(|f| *f = true);
            }
        }
        for (t, tri) in mesh.indices.chunks_exact(3).enumerate() {
            let [i0, i1, i2] = [tri[0], tri[1], tri[2]];
            let p = |i: u32| positions[i as usize];
            let n = (p(i1) - p(i0)).cross(p(i2) - p(i0));
            face_normals.push(n.normalize_or_zero());
            if n.length_squared() <= f32::MIN_POSITIVE || fibre[t] {
                continue;
            }
            faces += 1;
            for (u, v, w) in [(i0, i1, i2), (i1, i2, i0), (i2, i0, i1)] {
                let (cu, cv) = (canon[u as usize], canon[v as usize]);
                let key = (cu.min(cv), cu.max(cv));
                let next = sides.len();
                let k = *map.entry(key).or_insert(next);
                if k == next {
                    sides.push(Sides { a: cu.min(cv), forward: vec![], backward: vec![] });
                }
                let s = &mut sides[k];
                if cu == s.a {
                    s.forward.push([t as u32, u, v, w]);
                } else {
                    s.backward.push([t as u32, v, u, w]);
                }
            }
        }
        let closed = sides.iter().all(|s| s.forward.len() == 1 && s.backward.len() == 1);
        let cos_sharp = options.dihedral_deg.to_radians().cos();
        let mut sharp = Vec::new();
        let mut boundary = Vec::new();
        let mut candidates = Vec::new();
        let mut concave = 0;
        for s in &sides {
            let vertex = |i: u32| positions[i as usize];
            if s.forward.len() == 1 && s.backward.len() == 1 {
                let (l, r) = (s.forward[0], s.backward[0]);
                let (nl, nr) = (face_normals[l[0] as usize], face_normals[r[0] as usize]);
                let attr_jump = |a: u32, b: u32| {
                    let (a, b) = (a as usize, b as usize);
                    mesh.normals[a].dot(mesh.normals[b]) < 0.9998
                        || (options.uv_seams && mesh.uvs[a].distance(mesh.uvs[b]) > 1e-6)
                };
                let is_sharp = nl.dot(nr) < cos_sharp
                    || material[l[0] as usize] != material[r[0] as usize]
                    || attr_jump(l[1], r[1])
                    || attr_jump(l[2], r[2]);
                let edge = Edge {
                    p0: vertex(l[1]),
                    p1: vertex(l[2]),
                    n_left: nl,
                    n_right: nr,
                    kind: EdgeKind::Smooth,
                    source: [l[1], l[2], l[0], r[0]],
                };
                if is_sharp {
                    sharp.push(Edge { kind: EdgeKind::Sharp, ..edge });
                } else if closed && nl.dot(vertex(r[3]) - edge.p0) >= -1e-4 * edge.p0.distance(edge.p1) {
                    // The right face's far vertex lies in front of the left face's plane or on it
                    // (to rounding): an outer dihedral angle ≤ 180°, a valley or flat, hidden
                    // whenever it would be a silhouette of a closed mesh (section 3.2).
                    concave += 1;
                } else {
                    candidates.push(edge);
                }
            } else {
                // A boundary (or non-manifold) edge: each of its faces gives a boundary edge
                // shaded from that face alone (section 5).
                let own = |f: &[u32; 4], forward: bool| if forward { (f[1], f[2]) } else { (f[2], f[1]) };
                let faces = s.forward.iter().map(|f| (f, true)).chain(s.backward.iter().map(|f| (f, false)));
                for (f, forward) in faces {
                    let n = face_normals[f[0] as usize];
                    let (q0, q1) = own(f, forward);
                    boundary.push(Edge {
                        p0: vertex(q0),
                        p1: vertex(q1),
                        n_left: n,
                        n_right: n,
                        kind: EdgeKind::Boundary,
                        source: [q0, q1, f[0], f[0]],
                    });
                }
            }
        }
        orient_chains(&mut sharp);
        let counts = EdgeCounts {
            faces,
            edges: sides.len(),
            sharp: sharp.len(),
            boundary: boundary.len(),
            concave,
            candidates: candidates.len(),
        };
        let mut edges = sharp;
        edges.extend(boundary);
        edges.extend(candidates);
        EdgeSet { edges, closed, counts, indices: mesh.indices.clone() }
    }

    /// Moves the edges to the positions of `mesh` when it has the same triangles as the mesh
    /// they were found on (a posed or deformed copy: the app's expressions), without the
    /// preprocess; returns false, changing nothing, for another mesh. Which edges are sharp,
    /// boundary or left out stays as found on the first mesh (attribute seams do not move; a
    /// deformation that turns an edge concave or convex is not followed).
    pub fn reposition(&mut self, mesh: &TriangleMesh) -> bool {
        if mesh.indices != self.indices {
            return false;
        }
        let p = |i: u32| mesh.positions.get(i as usize).copied().unwrap_or(Vec3::ZERO);
        let normal = |t: u32| {
            let i = 3 * t as usize;
            match mesh.indices.get(i..i + 3) {
                Some(&[a, b, c]) => (p(b) - p(a)).cross(p(c) - p(a)).normalize_or_zero(),
                _ => Vec3::ZERO,
            }
        };
        for e in &mut self.edges {
            let [v0, v1, fl, fr] = e.source;
            (e.p0, e.p1, e.n_left, e.n_right) = (p(v0), p(v1), normal(fl), normal(fr));
        }
        true
    }
}

/// Orients sharp edges so that along every chain (a path through vertices where exactly two
/// sharp edges meet) each edge starts where the previous one ends; then the left faces lie on
/// one side of the whole chain, and the left-face shading of section 3.5 does not switch sides
/// from edge to edge (\[Sander2001\] section 3.3, figure 4). Flipping an edge swaps its faces.
pub fn orient_chains(edges: &mut [Edge]) {
    let key = |p: Vec3| [p.x.to_bits(), p.y.to_bits(), p.z.to_bits()];
    let mut at: HashMap<[u32; 3], Vec<usize>> = HashMap::new();
    for (i, e) in edges.iter().enumerate() {
        at.entry(key(e.p0)).or_default().push(i);
        at.entry(key(e.p1)).or_default().push(i);
    }
    let mut done = vec![false; edges.len()];
    for start in 0..edges.len() {
        if done[start] {
            continue;
        }
        done[start] = true;
        // Walk forward from p1, then backward from p0, through vertices of degree two.
        for forward in [true, false] {
            let mut current = start;
            loop {
                let e = edges[current];
                let end = if forward { e.p1 } else { e.p0 };
                let Some(next) = at
                    .get(&key(end))
                    .filter(|v| v.len() == 2)
                    .and_then(|v| v.iter().copied().find(|&n| n != current && !done[n]))
                else {
                    break;
                };
                let n = edges[next];
                // Forward: the next edge must start at `end`; backward: it must end there.
                let starts_here = key(n.p0) == key(end);
                if starts_here != forward {
                    edges[next] = flipped(n);
                }
                done[next] = true;
                current = next;
            }
        }
    }
}

fn flipped(e: Edge) -> Edge {
    let [v0, v1, fl, fr] = e.source;
    Edge { p0: e.p1, p1: e.p0, n_left: e.n_right, n_right: e.n_left, kind: e.kind, source: [v1, v0, fr, fl] }
}

/// A cube of side `side_mm` centred on the origin with flat normals and each face's UVs over
/// 0..1 (the textured cube of \[Sander2001\] figure 6): 12 sharp edges, closed. A test object of
/// edge antialiasing (`rouge bench aa`).
pub fn cube(side_mm: f32) -> rouge_model::mesh::Mesh {
    use rouge_model::mesh::{Corner, Face, Group, Mesh};
    let h = 0.5 * side_mm;
    let uvs = [(0.0, 0.0), (1.0, 0.0), (1.0, 1.0), (0.0, 1.0)];
    let mut mesh = Mesh { uvs: uvs.map(|(u, v)| glam::Vec2::new(u, v)).to_vec(), ..Mesh::default() };
    for i in 0..8u32 {
        let s = |bit: u32| if i & bit != 0 { h } else { -h };
        mesh.positions.push(Vec3::new(s(1), s(2), s(4)));
    }
    // Each face: its normal and its corners counter-clockwise seen from outside.
    let faces: [(Vec3, [u32; 4]); 6] = [
        (Vec3::X, [1, 3, 7, 5]),
        (Vec3::NEG_X, [0, 4, 6, 2]),
        (Vec3::Y, [2, 6, 7, 3]),
        (Vec3::NEG_Y, [0, 1, 5, 4]),
        (Vec3::Z, [4, 5, 7, 6]),
        (Vec3::NEG_Z, [0, 2, 3, 1]),
    ];
    for (f, (normal, corners)) in faces.iter().enumerate() {
        mesh.normals.push(*normal);
        let corners = corners.iter().enumerate().map(|(k, &p)| Corner { position: p, uv: k as u32, normal: f as u32 });
        mesh.faces.push(Face { corners: corners.collect() });
    }
    mesh.groups.push(Group { name: "cube".into(), material: None, faces: 0..6 });
    mesh
}
