//! The per-frame half of a deforming mesh in gather form, on every core: each Catmull-Clark
//! child position and each vertex normal is computed by one thread from lists made once
//! ([`StepGather`], [`NormalGather`]), summing in exactly the order the serial scatter of
//! [`super::subdivide::StepTopology::positions`] and [`super::vertex_normals`] sums, so the
//! result is theirs bit for bit on any number of threads (`model/tests/targets.rs`).

use glam::Vec3;

use super::Face;
use super::subdivide::{StepTopology, edge_point, vertex_point};

/// Items below which a phase runs on the calling thread (a thread's start costs about as much
/// as a few thousand of these sums).
const SERIAL_BELOW: usize = 16_384;

/// Compressed lists: list `i` is `items[start[i]..start[i + 1]]`.
#[derive(Debug, Clone, Default)]
struct Lists {
    start: Vec<u32>,
    items: Vec<u32>,
}

impl Lists {
    /// Lists `0..n` from `(list, item)` pairs, each list keeping its pairs' order.
    fn from_pairs(n: usize, pairs: impl Iterator<Item = (u32, u32)> + Clone) -> Lists {
        let mut start = vec![0u32; n + 1];
        for (l, _) in pairs.clone() {
            start[l as usize + 1] += 1;
        }
        for i in 0..n {
            start[i + 1] += start[i];
        }
        let mut next: Vec<u32> = start[..n].to_vec();
        let mut items = vec![0u32; start[n] as usize];
        for (l, item) in pairs {
            items[next[l as usize] as usize] = item;
            next[l as usize] += 1;
        }
        Lists { start, items }
    }

    fn get(&self, i: usize) -> &[u32] {
        &self.items[self.start[i] as usize..self.start[i + 1] as usize]
    }
}

/// Fills `out[i] = f(i)` on up to `threads` threads (contiguous chunks, one each).
pub(crate) fn par_fill<T: Send>(out: &mut [T], threads: usize, f: impl Fn(usize) -> T + Sync) {
    if threads <= 1 || out.len() < SERIAL_BELOW {
        out.iter_mut().enumerate().for_each(|(i, o)| *o = f(i));
        return;
    }
    let chunk = out.len().div_ceil(threads);
    std::thread::scope(|s| {
        for (c, part) in out.chunks_mut(chunk).enumerate() {
            let f = &f;
            s.spawn(move || part.iter_mut().enumerate().for_each(|(i, o)| *o = f(c * chunk + i)));
        }
    });
}

/// Threads to use: the machine's cores, at most 16.
pub(crate) fn threads() -> usize {
    std::thread::available_parallelism().map_or(1, |n| n.get().min(16))
}

/// One subdivision step's position rules as gathers: which faces each parent vertex and each
/// edge borders, and which edges meet at each vertex, in the scatter's order.
#[derive(Debug, Clone)]
pub(crate) struct StepGather {
    vertex_faces: Lists,
    edge_faces: Lists,
    vertex_edges: Lists,
}

impl StepGather {
    pub(crate) fn new(t: &StepTopology) -> StepGather {
        let nf = t.face_start.len() - 1;
        let corner_face = (0..nf).flat_map(|f| (t.face_start[f]..t.face_start[f + 1]).map(move |i| (i, f as u32)));
        let vertex_faces = Lists::from_pairs(t.nv, corner_face.clone().map(|(i, f)| (t.corners[i], f)));
        let edge_faces = Lists::from_pairs(t.edges.len(), corner_face.map(|(i, f)| (t.corner_edge[i], f)));
        let ends = t.edges.iter().enumerate().flat_map(|(e, &(a, b))| [(a, e as u32), (b, e as u32)]);
        let vertex_edges = Lists::from_pairs(t.nv, ends);
        StepGather { vertex_faces, edge_faces, vertex_edges }
    }

    /// [`StepTopology::positions`] of `parent`, gathered on `threads` threads.
    pub(crate) fn positions(&self, t: &StepTopology, parent: &[Vec3], threads: usize) -> Vec<Vec3> {
        let (nv, ne, nf) = (t.nv, t.edges.len(), t.face_start.len() - 1);
        let mut out = vec![Vec3::ZERO; nv + ne + nf];
        let (moved, rest) = out.split_at_mut(nv);
        let (edge_points, face_points) = rest.split_at_mut(ne);
        par_fill(face_points, threads, |f| {
            let r = t.face_start[f]..t.face_start[f + 1];
            let k = r.len() as f32;
            t.corners[r].iter().map(|&c| parent[c as usize]).sum::<Vec3>() / k
        });
        let face_points = &*face_points;
        let sum_faces = |faces: &[u32]| faces.iter().fold(Vec3::ZERO, |acc, &f| acc + face_points[f as usize]);
        par_fill(edge_points, threads, |e| {
            let (a, b) = t.edges[e];
            let boundary = t.edge_faces[e] != 2;
            edge_point(parent[a as usize], parent[b as usize], boundary, sum_faces(self.edge_faces.get(e)))
        });
        par_fill(moved, threads, |v| {
            let (mut mid_sum, mut bnd_sum, mut bnd_count) = (Vec3::ZERO, Vec3::ZERO, 0u32);
            let edges = self.vertex_edges.get(v);
            // A loop edge (a = b) is listed twice, as the scatter visits it twice.
            for &e in edges {
                let (a, b) = t.edges[e as usize];
                let (pa, pb) = (parent[a as usize], parent[b as usize]);
                mid_sum += (pa + pb) * 0.5;
                if t.edge_faces[e as usize] != 2 {
                    bnd_sum += if a as usize == v { pb } else { pa };
                    bnd_count += 1;
                }
            }
            let faces = self.vertex_faces.get(v);
            let valence = edges.len() as u32;
            vertex_point(parent[v], sum_faces(faces), faces.len() as u32, mid_sum, valence, bnd_sum, bnd_count)
        });
        out
    }
}

/// Area-weighted vertex normals ([`super::vertex_normals`]) as gathers over fixed faces.
#[derive(Debug, Clone)]
pub(crate) struct NormalGather {
    vertex_faces: Lists,
}

impl NormalGather {
    pub(crate) fn new(vertex_count: usize, faces: &[Face]) -> NormalGather {
        let pairs =
            faces.iter().enumerate().flat_map(|(f, face)| face.corners.iter().map(move |c| (c.position, f as u32)));
        NormalGather { vertex_faces: Lists::from_pairs(vertex_count, pairs) }
    }

    /// [`super::vertex_normals`] of `positions` over `faces` (those this was made with).
    pub(crate) fn normals(&self, positions: &[Vec3], faces: &[Face], threads: usize) -> Vec<Vec3> {
        let mut areas = vec![Vec3::ZERO; faces.len()];
        par_fill(&mut areas, threads, |f| super::polygon_vector_area(positions, &faces[f].corners));
        let mut out = vec![Vec3::ZERO; positions.len()];
        par_fill(&mut out, threads, |v| {
            let acc = self.vertex_faces.get(v).iter().map(|&f| areas[f as usize]).filter(|n| n.is_finite());
            acc.fold(Vec3::ZERO, |a, n| a + n).try_normalize().unwrap_or(Vec3::Z)
        });
        out
    }
}
