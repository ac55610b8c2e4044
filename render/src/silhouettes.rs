//! Which discontinuity edges a frame draws, in which order (\[Sander2001\] sections 3.2, 3.4, 3.5):
//! the per-edge classification (the CPU twin of `classify` in shaders/edge_overdraw.wgsl), the
//! silhouette search (brute force over every candidate, or a search that skips clusters of
//! edges that cannot hold a silhouette), and the back-to-front sort by midpoint distance.
//! See [`crate::edges`] for the preprocess and the printed errors fixed here.

use crate::edges::{BLEND_THRESHOLD, Edge, EdgeKind, EdgeSet, NEAR_SILHOUETTE};
use glam::Vec3;

/// How an edge is drawn from one viewpoint.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum EdgeClass {
    /// Not drawn: a smooth edge off the silhouette, or a sharp edge whose faces both face away
    /// on a closed mesh.
    Hidden,
    /// A silhouette (a smooth or sharp edge with one face toward the eye, or a boundary edge),
    /// shaded from the front face (section 3.3): the left one when `front_left`.
    Silhouette {
        /// The left face faces the eye (always true for a boundary edge: its only face).
        front_left: bool,
    },
    /// A sharp edge with both faces toward the eye (or both away, on an open mesh): shaded by
    /// β = dR / (dL + dR) of section 3.3, in [0, 1].
    Sharp {
        /// The blend parameter β.
        beta: f32,
    },
}

/// Classifies `edge` seen from `eye` (\[Sander2001\] section 3.5 with the corrections listed in
/// [`crate::edges`]): d = n · (eye − midpoint) > 0 means the face is toward the eye.
pub fn classify(edge: &Edge, eye: Vec3, closed: bool) -> EdgeClass {
    let v = eye - edge.midpoint();
    let (dl, dr) = (edge.n_left.dot(v), edge.n_right.dot(v));
    match edge.kind {
        EdgeKind::Boundary => EdgeClass::Silhouette { front_left: true },
        EdgeKind::Smooth => {
            if (dl > 0.0) != (dr > 0.0) {
                EdgeClass::Silhouette { front_left: dl > 0.0 }
            } else {
                EdgeClass::Hidden
            }
        }
        EdgeKind::Sharp => {
            if (dl > 0.0) != (dr > 0.0) {
                EdgeClass::Silhouette { front_left: dl > 0.0 }
            } else if dl <= 0.0 && closed {
                EdgeClass::Hidden
            } else {
                // Same sign: β is the same whether both face the eye or both face away (an open
                // mesh seen from behind); dL + dR = 0 only when both are 0 (edge-on).
                let sum = dl + dr;
                let beta = if sum == 0.0 { 0.5 } else { (dr / sum).clamp(0.0, 1.0) };
                EdgeClass::Sharp { beta }
            }
        }
    }
}

/// Whether a classified edge goes into the sorted set of section 3.4: silhouettes and sharp
/// edges near the silhouette (β < 0.1 or β > 0.9).
pub fn is_sorted(class: EdgeClass) -> bool {
    match class {
        EdgeClass::Hidden => false,
        EdgeClass::Silhouette { .. } => true,
        EdgeClass::Sharp { beta } => !(NEAR_SILHOUETTE < beta && beta < BLEND_THRESHOLD),
    }
}

/// The asymmetric transfer of section 3.3: β′ = 0 up to τ = [`BLEND_THRESHOLD`], then linear
/// to 1 at β = 1 (reconstructed from section 3.5; the printed formula is lost from our copy).
pub fn beta_prime(beta: f32) -> f32 {
    ((beta - BLEND_THRESHOLD) / (1.0 - BLEND_THRESHOLD)).clamp(0.0, 1.0)
}

/// One edge as the overdraw pass reads it (a per-instance vertex buffer; keep in sync with
/// `EdgeIn` in shaders/edge_overdraw.wgsl).
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq, bytemuck::Pod, bytemuck::Zeroable)]
pub struct EdgeInstance {
    /// First end, mm.
    pub p0: [f32; 3],
    /// [`EdgeKind`] as u32.
    pub kind: u32,
    /// Second end, mm.
    pub p1: [f32; 3],
    /// Left face normal.
    pub n_left: [f32; 3],
    /// Right face normal.
    pub n_right: [f32; 3],
}

impl From<&Edge> for EdgeInstance {
    fn from(e: &Edge) -> EdgeInstance {
        EdgeInstance {
            p0: e.p0.to_array(),
            kind: e.kind as u32,
            p1: e.p1.to_array(),
            n_left: e.n_left.to_array(),
            n_right: e.n_right.to_array(),
        }
    }
}

/// Edge counts of one frame (the middle rows of \[Sander2001\] table 1).
#[derive(Clone, Copy, Debug, Default, PartialEq, serde::Serialize)]
pub struct FrameEdgeStats {
    /// Silhouettes found among the smooth candidates (not counting sharp or boundary edges).
    pub extracted_silhouettes: usize,
    /// Edges drawn (every class but hidden).
    pub rendered: usize,
    /// Edges in the back-to-front sort.
    pub sorted: usize,
    /// Sharp edges drawn twice, blended by β′ > 0.
    pub blended: usize,
}

/// A cluster of silhouette candidates with a bound on where its faces face: a sphere around its
/// edges and a cone around its face normals.
#[derive(Clone, Copy, Debug)]
struct Cluster {
    range: (usize, usize),
    center: Vec3,
    radius: f32,
    axis: Vec3,
    /// Half-angle of the normal cone, radians (≥ π/2: never skipped).
    half_angle: f32,
}

/// Edges per cluster of the skipping search.
const CLUSTER: usize = 32;

/// The per-frame edge work of a mesh: its [`EdgeSet`], with the candidates in spatial order and
/// clustered for the skipping search.
#[derive(Clone, Debug, Default)]
pub struct EdgeFrames {
    /// The preprocessed edges (candidates reordered by a Morton code of their midpoints).
    pub set: EdgeSet,
    /// Index of the first candidate in `set.edges`.
    first_candidate: usize,
    clusters: Vec<Cluster>,
}

impl EdgeFrames {
    /// Orders the candidates of `set` along a Morton curve and clusters them.
    pub fn new(mut set: EdgeSet) -> EdgeFrames {
        let first = set.edges.len() - set.counts.candidates;
        let candidates = &mut set.edges[first..];
        if let Some(bounds) = rouge_model::mesh::Bounds::of(&candidates.iter().map(Edge::midpoint).collect::<Vec<_>>())
        {
            let scale = 1023.0 / bounds.size().max_element().max(f32::MIN_POSITIVE);
            candidates.sort_by_cached_key(|e| morton(((e.midpoint() - bounds.min) * scale).to_array()));
        }
        let mut frames = EdgeFrames { set, first_candidate: first, clusters: Vec::new() };
        frames.cluster();
        frames
    }

    fn cluster(&mut self) {
        let first = self.first_candidate;
        self.clusters = self.set.edges[first..]
            .chunks(CLUSTER)
            .enumerate()
            .map(|(i, chunk)| cluster(first + i * CLUSTER, chunk))
            .collect();
    }

    /// Moves the edges to a posed copy of their mesh ([`EdgeSet::reposition`]) and bounds the
    /// clusters again; false, changing nothing, for another mesh.
    pub fn reposition(&mut self, mesh: &rouge_model::mesh::TriangleMesh) -> bool {
        let moved = self.set.reposition(mesh);
        if moved {
            self.cluster();
        }
        moved
    }

    /// The silhouettes among the candidates seen from `eye`, by testing every candidate.
    pub fn silhouettes_brute_force(&self, eye: Vec3) -> Vec<usize> {
        (self.first_candidate..self.set.edges.len())
            .filter(|&i| matches!(classify(&self.set.edges[i], eye, self.set.closed), EdgeClass::Silhouette { .. }))
            .collect()
    }

    /// The same silhouettes, skipping every cluster whose faces all face the eye or all face
    /// away (the idea of \[Sander2000\]'s hierarchy, one level deep): for a face of the cluster
    /// with normal n and a point p within `radius` of the centre c, n · (eye − p) ≥ |eye − c|
    /// cos(θ + α) − r, where θ is the angle between the cone axis and eye − c and α the cone's
    /// half-angle; all face the eye when that bound is positive, and symmetrically all face away
    /// when |eye − c| cos(θ − α) + r < 0.
    pub fn silhouettes_skipping(&self, eye: Vec3) -> Vec<usize> {
        let mut out = Vec::new();
        for c in &self.clusters {
            let d = eye - c.center;
            let dist = d.length();
            if dist > c.radius && c.half_angle < std::f32::consts::FRAC_PI_2 {
                let theta = (c.axis.dot(d) / dist).clamp(-1.0, 1.0).acos();
                let front =
                    theta + c.half_angle < std::f32::consts::PI && dist * (theta + c.half_angle).cos() > c.radius;
                let back = dist * (theta - c.half_angle).max(0.0).cos() + c.radius < 0.0;
                if front || back {
                    continue;
                }
            }
            out.extend((c.range.0..c.range.1).filter(|&i| {
                matches!(classify(&self.set.edges[i], eye, self.set.closed), EdgeClass::Silhouette { .. })
            }));
        }
        out
    }

    /// The edges to draw from `eye`, in drawing order, and the frame's counts. Unsorted: every
    /// sharp and boundary edge, then the silhouettes. Sorted (section 3.4): the sharp edges away
    /// from the silhouette first, then silhouettes and near-silhouette sharp edges back to front
    /// by the distance from the eye to their midpoints.
    pub fn frame(&self, eye: Vec3, sorted: bool) -> (Vec<EdgeInstance>, FrameEdgeStats) {
        let mut stats = FrameEdgeStats::default();
        let mut first = Vec::new();
        let mut later: Vec<(f32, usize)> = Vec::new();
        let silhouettes = self.silhouettes_skipping(eye);
        stats.extracted_silhouettes = silhouettes.len();
        let discontinuities = 0..self.first_candidate;
        for i in discontinuities.chain(silhouettes) {
            let edge = &self.set.edges[i];
            let class = classify(edge, eye, self.set.closed);
            if class == EdgeClass::Hidden {
                continue;
            }
            stats.rendered += 1;
            if let EdgeClass::Sharp { beta } = class {
                stats.blended += usize::from(beta_prime(beta) > 0.0);
            }
            if sorted && is_sorted(class) {
                later.push((edge.midpoint().distance(eye), i));
            } else {
                first.push(i);
            }
        }
        stats.sorted = later.len();
        later.sort_unstable_by(|a, b| b.0.total_cmp(&a.0));
        let order = first.into_iter().chain(later.into_iter().map(|(_, i)| i));
        (order.map(|i| EdgeInstance::from(&self.set.edges[i])).collect(), stats)
    }

    /// Every edge that may be drawn, for the GPU's brute-force path (the shader classifies each
    /// instance and collapses the hidden ones): sharp, boundary, then every candidate.
    pub fn all_instances(&self) -> Vec<EdgeInstance> {
        self.set.edges.iter().map(EdgeInstance::from).collect()
    }
}

fn cluster(start: usize, edges: &[Edge]) -> Cluster {
    let points: Vec<Vec3> = edges.iter().flat_map(|e| [e.p0, e.p1]).collect();
    let center = points.iter().copied().sum::<Vec3>() / points.len().max(1) as f32;
    let radius = points.iter().map(|p| p.distance(center)).fold(0.0, f32::max);
    let normals = || edges.iter().flat_map(|e| [e.n_left, e.n_right]);
    let axis = normals().sum::<Vec3>().normalize_or_zero();
    let half_angle = if axis == Vec3::ZERO {
        std::f32::consts::PI
    } else {
        normals().map(|n| axis.dot(n).clamp(-1.0, 1.0).acos()).fold(0.0, f32::max)
    };
    Cluster { range: (start, start + edges.len()), center, radius, axis, half_angle }
}

/// Interleaves the bits of three coordinates in 0..1024.
fn morton(p: [f32; 3]) -> u32 {
    let spread = |v: f32| {
        let mut x = (v.clamp(0.0, 1023.0) as u32) & 0x3ff;
        x = (x | (x << 16)) & 0x0300_00ff;
        x = (x | (x << 8)) & 0x0300_f00f;
        x = (x | (x << 4)) & 0x030c_30c3;
        (x | (x << 2)) & 0x0924_9249
    };
    spread(p[0]) | (spread(p[1]) << 1) | (spread(p[2]) << 2)
}
