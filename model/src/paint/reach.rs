//! Which texels a dab reaches: along the surface, not through the air; facing the painter; not
//! hidden from the camera.
//!
//! **Along the surface.** The mesh's vertices, welded by position (so UV seams join and holes
//! such as the mouth stay open), form a graph whose edges are the triangles' edges. A dab runs
//! Dijkstra's shortest paths from the corners of the triangle under its centre, pruned at
//! [`PATH_STRETCH`] × the radius, and a covered texel's path length is the shortest over its
//! triangle's corners of (corner's path + straight distance from the corner). Edge paths
//! overestimate geodesics on a triangulated surface; dividing by [`PATH_STRETCH`] gives a bound
//! that stays below the straight distance on smooth skin, so the distance for the falloff,
//! `max(3D distance, path / PATH_STRETCH)`, is the 3D distance there (a round brush, as before)
//! and grows past the radius wherever the surface folds away: between closed lips the only paths
//! run round the corners of the mouth.

use super::*;
use std::cmp::Ordering;
use std::collections::{BinaryHeap, HashMap, HashSet};
use std::hash::{BuildHasherDefault, Hasher};

/// How much longer than the geodesic a path along the mesh's edges (plus the last straight
/// step to a texel) may be on well-shaped triangles: 2/√3 ≈ 1.155 for a zigzag across
/// equilateral ones, a little more for the head's split quads.
pub const PATH_STRETCH: f32 = 1.25;
/// A texel is hidden when the frame's surface at its pixel lies this much nearer the eye, mm.
pub const OCCLUSION_TOLERANCE_MM: f32 = 1.5;

/// How far a dab reaches.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Reach {
    /// Along the surface (the default): texels joined to the centre by a path on the surface no
    /// longer than the radius (see the module documentation).
    Surface,
    /// Every covered texel within the radius in 3D, through the air: wherever two surfaces come
    /// closer than the radius (closed lips, lids, nostrils, ear folds) a dab on one reaches the
    /// other.
    Ball,
}

/// Where the painter looks from, for the brush's facing and occlusion tests.
#[derive(Clone, Debug)]
pub struct PaintView {
    /// The camera position, mm.
    pub eye: Vec3,
    /// The frame the painter sees, for the occlusion test; `None` skips it.
    pub depth: Option<Arc<DepthImage>>,
}

/// A frame's depth buffer and the matrix that made it.
#[derive(Clone, Debug)]
pub struct DepthImage {
    view_proj: Mat4,
    inverse: Mat4,
    width: u32,
    height: u32,
    /// Normalised device depth per pixel, row 0 at the top; 1 = background.
    depth: Arc<Vec<f32>>,
}

impl DepthImage {
    /// A depth image of `width` × `height` pixels (row 0 at the top; NDC depth, 0 near, 1 far)
    /// rendered with `view_proj`; `None` when the sizes disagree or the matrix is not invertible.
    pub fn new(view_proj: Mat4, width: u32, height: u32, depth: Arc<Vec<f32>>) -> Option<DepthImage> {
        let inverse = view_proj.inverse();
        let ok = depth.len() == width as usize * height as usize && inverse.is_finite() && view_proj.is_finite();
        ok.then_some(DepthImage { view_proj, inverse, width, height, depth })
    }

    /// Whether the surface seen at `p`'s pixel lies more than `tolerance_mm` nearer `eye` than
    /// `p`. A point off screen, behind the camera or over background is not hidden.
    pub fn hides(&self, eye: Vec3, p: Vec3, tolerance_mm: f32) -> bool {
        let clip = self.view_proj * p.extend(1.0);
        if clip.w <= 0.0 || !clip.is_finite() {
            return false;
        }
        let ndc = clip.truncate() / clip.w;
        let (fx, fy) = ((ndc.x + 1.0) * 0.5 * self.width as f32, (1.0 - ndc.y) * 0.5 * self.height as f32);
        if !(fx >= 0.0 && fy >= 0.0 && fx < self.width as f32 && fy < self.height as f32) {
            return false;
        }
        let (x, y) = (fx as u32, fy as u32);
        let d = self.depth[(y * self.width + x) as usize];
        // The far plane (background) or a NaN depth: nothing there to occlude with.
        if d.is_nan() || d >= 1.0 {
            return false;
        }
        let pixel = Vec4::new(
            (x as f32 + 0.5) / self.width as f32 * 2.0 - 1.0,
            1.0 - (y as f32 + 0.5) / self.height as f32 * 2.0,
            d,
            1.0,
        );
        let q = self.inverse * pixel;
        if q.w == 0.0 {
            return false;
        }
        eye.distance(q.truncate() / q.w) + tolerance_mm < eye.distance(p)
    }
}

/// A dab's reached texels: (index into the surface's points, distance for the falloff, mm).
pub(super) type Reached = Vec<(u32, f32)>;

/// The covered texels a dab of `brush` centred at `centre` reaches, with the distance its
/// falloff uses, by `brush.reach`, leaving out texels facing away from `view.eye` (with
/// `brush.front_faces_only`) and those hidden in `view.depth` (with `brush.occlusion`).
/// Back-facing texels also stop the walk along the surface; hidden ones do not.
pub(super) fn reached(surface: &SurfaceMap, brush: &Brush, centre: Vec3, view: Option<&PaintView>) -> Reached {
    let r = brush.radius_mm;
    let facing = |s: usize| match view {
        Some(v) if brush.front_faces_only => {
            let n = surface.normals[s];
            !n.is_finite() || n.dot(v.eye - surface.points[s]) > 0.0
        }
        _ => true,
    };
    let seen = |s: usize| match (view, brush.occlusion) {
        (Some(PaintView { eye, depth: Some(d) }), true) => !d.hides(*eye, surface.points[s], OCCLUSION_TOLERANCE_MM),
        _ => true,
    };
    let mut out = Vec::new();
    match brush.reach {
        Reach::Ball => {
            let Some(cells) = surface.grid.range(centre - Vec3::splat(r), centre + Vec3::splat(r)) else {
                return out;
            };
            surface.grid.for_each_run(cells, |run| {
                for s in run {
                    let d2 = surface.points[s].distance_squared(centre);
                    if d2 < r * r && facing(s) && seen(s) {
                        out.push((s as u32, d2.sqrt()));
                    }
                }
            });
        }
        Reach::Surface => {
            let Some(seed) = surface.nearest_slot(centre, r) else { return out };
            let graph = &surface.graph;
            let Some(&seed_tri) = graph.triangles.get(surface.tri[seed] as usize) else { return out };
            let open = |v: u32| match view {
                Some(view) if brush.front_faces_only => {
                    let n = graph.normals[v as usize];
                    !n.is_finite() || n.dot(view.eye - graph.positions[v as usize]) > 0.0
                }
                _ => true,
            };
            let path = graph.paths(centre, seed_tri, r * PATH_STRETCH, |v| seed_tri.contains(&v) || open(v));
            let Some(cells) = surface.grid.range(centre - Vec3::splat(r), centre + Vec3::splat(r)) else {
                return out;
            };
            surface.grid.for_each_run(cells, |run| {
                for s in run {
                    let p = surface.points[s];
                    let e2 = p.distance_squared(centre);
                    if e2 >= r * r {
                        continue;
                    }
                    let Some(corners) = graph.triangles.get(surface.tri[s] as usize) else { continue };
                    let along = if *corners == seed_tri {
                        0.0
                    } else {
                        corners.iter().fold(f32::INFINITY, |best, &v| match path.get(&v) {
                            Some(g) => best.min(g + p.distance(graph.positions[v as usize])),
                            None => best,
                        })
                    };
                    let d = e2.sqrt().max(along / PATH_STRETCH);
                    if d < r && facing(s) && seen(s) {
                        out.push((s as u32, d));
                    }
                }
            });
        }
    }
    out
}

/// A heap entry: path length so far and the texel's slot; the shortest pops first.
#[derive(PartialEq)]
struct Open(f32, u32);

impl Eq for Open {}

impl Ord for Open {
    fn cmp(&self, other: &Self) -> Ordering {
        other.0.total_cmp(&self.0).then(other.1.cmp(&self.1))
    }
}

impl PartialOrd for Open {
    fn partial_cmp(&self, other: &Self) -> Option<Ordering> {
        Some(self.cmp(other))
    }
}

/// Fibonacci hashing of a slot index (the walk's map sees thousands of lookups per dab).
#[derive(Default)]
pub(super) struct SlotHasher(u64);

impl Hasher for SlotHasher {
    fn finish(&self) -> u64 {
        self.0
    }
    fn write(&mut self, bytes: &[u8]) {
        for &b in bytes {
            self.0 = (self.0.rotate_left(8) ^ u64::from(b)).wrapping_mul(0x9E37_79B9_7F4A_7C15);
        }
    }
    fn write_u32(&mut self, v: u32) {
        self.0 = u64::from(v).wrapping_mul(0x9E37_79B9_7F4A_7C15);
    }
}

/// The mesh as a graph for [`Reach::Surface`]: vertices welded by exact position, joined along
/// the triangles' edges.
#[derive(Clone, Debug, Default)]
pub(super) struct MeshGraph {
    /// Welded vertex positions, mm.
    pub(super) positions: Vec<Vec3>,
    /// A unit normal per welded vertex (the first copy's; NaN where the mesh has none).
    pub(super) normals: Vec<Vec3>,
    /// Each triangle's welded corners (indexed like the mesh's triangles).
    pub(super) triangles: Vec<[u32; 3]>,
    /// Neighbours of vertex v: `neighbours[starts[v]..starts[v + 1]]`.
    starts: Vec<u32>,
    neighbours: Vec<u32>,
}

impl MeshGraph {
    /// The graph of `mesh`. Vertices at the same position (the copies a UV seam makes) become
    /// one, so paths cross seams; a hole's rims (the mouth, the neck) share no edge, so paths
    /// never jump across it however close its rims come. Triangles with an index out of range
    /// get no corners (`u32::MAX`) and join nothing.
    pub(super) fn of(mesh: &TriangleMesh) -> MeshGraph {
        let key = |p: Vec3| p.to_array().map(|v| if v == 0.0 { 0 } else { v.to_bits() });
        let mut weld: HashMap<[u32; 3], u32> = HashMap::new();
        let mut graph = MeshGraph::default();
        let welded: Vec<u32> = mesh
            .positions
            .iter()
            .enumerate()
            .map(|(i, &p)| {
                let next = weld.len() as u32;
                let id = *weld.entry(key(p)).or_insert(next);
                if id == next {
                    graph.positions.push(p);
                    let n = mesh.normals.get(i).copied().unwrap_or(Vec3::NAN);
                    graph.normals.push(n.normalize_or(Vec3::NAN));
                }
                id
            })
            .collect();
        let mut edges: Vec<(u32, u32)> = Vec::with_capacity(mesh.indices.len() * 2);
        for t in mesh.indices.chunks_exact(3) {
            let corners = [t[0], t[1], t[2]].map(|v| welded.get(v as usize).copied().unwrap_or(u32::MAX));
            graph.triangles.push(corners);
            if corners.contains(&u32::MAX) {
                continue;
            }
            for (a, b) in [(corners[0], corners[1]), (corners[1], corners[2]), (corners[2], corners[0])] {
                if a != b {
                    edges.push((a, b));
                    edges.push((b, a));
                }
            }
        }
        edges.sort_unstable();
        edges.dedup();
        graph.starts = vec![0; graph.positions.len() + 1];
        for &(a, _) in &edges {
            graph.starts[a as usize + 1] += 1;
        }
        for v in 0..graph.positions.len() {
            graph.starts[v + 1] += graph.starts[v];
        }
        graph.neighbours = edges.into_iter().map(|(_, b)| b).collect();
        graph
    }

    /// Number of welded vertices.
    pub(super) fn vertices(&self) -> usize {
        self.positions.len()
    }

    /// Shortest path lengths along the edges from `centre` (a point on triangle `start`, whose
    /// corners are reached straight from it) to every vertex reachable within `limit_mm`,
    /// through vertices that pass `open` (others are not entered).
    pub(super) fn paths(
        &self,
        centre: Vec3,
        start: [u32; 3],
        limit_mm: f32,
        open: impl Fn(u32) -> bool,
    ) -> HashMap<u32, f32, BuildHasherDefault<SlotHasher>> {
        let mut best: HashMap<u32, f32, BuildHasherDefault<SlotHasher>> = HashMap::default();
        let mut heap = BinaryHeap::new();
        for v in start {
            if let Some(&p) = self.positions.get(v as usize) {
                let g = p.distance(centre);
                if g < limit_mm && best.get(&v).is_none_or(|&b| g < b) {
                    best.insert(v, g);
                    heap.push(Open(g, v));
                }
            }
        }
        let mut walls: HashSet<u32, BuildHasherDefault<SlotHasher>> = HashSet::default();
        while let Some(Open(g, v)) = heap.pop() {
            if best.get(&v).is_some_and(|&b| g > b) {
                continue;
            }
            if !open(v) {
                best.remove(&v);
                walls.insert(v);
                continue;
            }
            let p = self.positions[v as usize];
            let range = self.starts[v as usize] as usize..self.starts[v as usize + 1] as usize;
            for &u in &self.neighbours[range] {
                let g2 = g + p.distance(self.positions[u as usize]);
                if g2 < limit_mm && !walls.contains(&u) && best.get(&u).is_none_or(|&b| g2 < b) {
                    best.insert(u, g2);
                    heap.push(Open(g2, u));
                }
            }
        }
        best
    }
}
