//! The per-frame half of a deforming mesh in gather form, on every core: each Catmull-Clark
//! child position and each vertex normal is computed by one thread from lists made once
//! ([`StepGather`], [`NormalGather`]), summing in exactly the order the serial scatter of
//! [`super::subdivide::StepTopology::positions`] and [`super::vertex_normals`] sums, so the
//! result is theirs bit for bit on any number of threads (`model/tests/targets.rs`).

use glam::Vec3;

use std::sync::{Mutex, PoisonError};

use super::Face;
use super::pool::Pool;
use super::subdivide::{StepTopology, edge_point, vertex_point};

/// Items a chunk holds at least (handing a chunk to a worker costs about as much as a few
/// thousand of these sums).
const PER_CHUNK_MIN: usize = 8_192;

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

/// Fills `out[i] = f(i)` on up to `threads` threads of the [`Pool`] (contiguous chunks of at
/// least [`PER_CHUNK_MIN`] items, two a thread so that a slow thread holds nobody up long).
pub(crate) fn par_fill<T: Send>(out: &mut [T], threads: usize, f: impl Fn(usize) -> T + Sync) {
    let size = chunk_size(out.len(), threads);
    run_parts(out.chunks_mut(size).collect(), |c, part: &mut [T]| {
        part.iter_mut().enumerate().for_each(|(i, o)| *o = f(c * size + i));
    });
}

/// [`par_fill`] of two slices of one length at once: `(a[i], b[i]) = f(i)`.
pub(crate) fn par_fill_pair<A: Send, B: Send>(
    a: &mut [A],
    b: &mut [B],
    threads: usize,
    f: impl Fn(usize) -> (A, B) + Sync,
) {
    assert_eq!(a.len(), b.len(), "par_fill_pair: slices of two lengths");
    let size = chunk_size(a.len(), threads);
    run_parts(a.chunks_mut(size).zip(b.chunks_mut(size)).collect(), |c, (pa, pb): (&mut [A], &mut [B])| {
        for (i, (oa, ob)) in pa.iter_mut().zip(pb.iter_mut()).enumerate() {
            (*oa, *ob) = f(c * size + i);
        }
    });
}

/// Items a chunk of `len` gets on up to `threads` threads of the pool (all of them when one
/// thread does the work).
fn chunk_size(len: usize, threads: usize) -> usize {
    let threads = threads.min(Pool::global().threads());
    let chunks = if threads <= 1 { 1 } else { (2 * threads).min(len / PER_CHUNK_MIN).max(1) };
    len.div_ceil(chunks).max(1)
}

/// Calls `work(i, part)` for every part, on the pool when there are several.
fn run_parts<P: Send>(parts: Vec<P>, work: impl Fn(usize, P) + Sync) {
    if parts.len() <= 1 {
        parts.into_iter().for_each(|p| work(0, p));
        return;
    }
    let parts: Vec<Mutex<Option<P>>> = parts.into_iter().map(|p| Mutex::new(Some(p))).collect();
    Pool::global().run(parts.len(), &|c| {
        if let Some(part) = parts[c].lock().unwrap_or_else(PoisonError::into_inner).take() {
            work(c, part);
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

    /// [`StepTopology::positions`] of `parent` into `out` (resized; its allocation is kept
    /// from frame to frame), gathered on `threads` threads: the face points, then the moved
    /// vertices and the edge points together.
    pub(crate) fn positions_into(&self, t: &StepTopology, parent: &[Vec3], out: &mut Vec<Vec3>, threads: usize) {
        let (nv, ne, nf) = (t.nv, t.edges.len(), t.face_start.len() - 1);
        out.resize(nv + ne + nf, Vec3::ZERO);
        let (moved_and_edges, face_points) = out.split_at_mut(nv + ne);
        par_fill(face_points, threads, |f| {
            let r = t.face_start[f]..t.face_start[f + 1];
            let k = r.len() as f32;
            t.corners[r].iter().map(|&c| parent[c as usize]).sum::<Vec3>() / k
        });
        let face_points = &*face_points;
        let sum_faces = |faces: &[u32]| faces.iter().fold(Vec3::ZERO, |acc, &f| acc + face_points[f as usize]);
        par_fill(moved_and_edges, threads, |i| {
            if i >= nv {
                let e = i - nv;
                let (a, b) = t.edges[e];
                let boundary = t.edge_faces[e] != 2;
                return edge_point(parent[a as usize], parent[b as usize], boundary, sum_faces(self.edge_faces.get(e)));
            }
            let v = i;
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
    }
}

/// Area-weighted vertex normals ([`super::vertex_normals`]) as gathers over fixed faces.
#[derive(Debug, Clone)]
pub(crate) struct NormalGather {
    vertex_faces: Lists,
    /// Each face's corner positions, in winding order.
    face_corners: Lists,
}

impl NormalGather {
    pub(crate) fn new(vertex_count: usize, faces: &[Face]) -> NormalGather {
        let pairs =
            faces.iter().enumerate().flat_map(|(f, face)| face.corners.iter().map(move |c| (c.position, f as u32)));
        let corners =
            faces.iter().enumerate().flat_map(|(f, face)| face.corners.iter().map(move |c| (f as u32, c.position)));
        NormalGather {
            vertex_faces: Lists::from_pairs(vertex_count, pairs),
            face_corners: Lists::from_pairs(faces.len(), corners),
        }
    }

    /// The faces' vector areas ([`super::newell_area`]) into
    /// `areas` (resized, its allocation kept).
    pub(crate) fn areas_into(&self, positions: &[Vec3], areas: &mut Vec<Vec3>, threads: usize) {
        areas.resize(self.face_corners.start.len() - 1, Vec3::ZERO);
        par_fill(areas, threads, |f| {
            let c = self.face_corners.get(f);
            super::newell_area(positions, c.len(), |i| c[i])
        });
    }

    /// The unit normal of vertex `v` from the faces' vector `areas` ([`super::vertex_normals`]'s
    /// for that vertex, bit for bit).
    pub(crate) fn normal(&self, v: usize, areas: &[Vec3]) -> Vec3 {
        let acc = self.vertex_faces.get(v).iter().map(|&f| areas[f as usize]).filter(|n| n.is_finite());
        acc.fold(Vec3::ZERO, |a, n| a + n).try_normalize().unwrap_or(Vec3::Z)
    }
}
