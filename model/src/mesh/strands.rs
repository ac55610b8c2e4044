//! Hairs as strands: the lash and brow ribbons of a mesh found once on its polygon mesh, kept
//! through subdivision and triangulation, so that the renderer can draw each hair as a fibre
//! (a centre line and a radius) rather than as the triangles of its ribbon.
//!
//! A hair ribbon (`python/gen_head_parts.py`) is a strip of quads from root to tip whose first
//! and third edges (corners 0-1 and 2-3) are its *rungs*, the two vertices across the ribbon;
//! quads sharing a rung are neighbours along the strip. `strips` walks them; [`HairStrands::of`]
//! keeps one strip per hair (the lashes are written twice, front and back faces with their own
//! vertices at the same places), and [`HairStrands::on_triangles`] renames the rungs' vertices to
//! those of the subdivided, triangulated mesh: Catmull-Clark keeps a parent vertex's index
//! ([`Mesh::catmull_clark`]), so a rung of the polygon mesh is a rung of every level (its ends
//! moved by the boundary rule along the ribbon's edges).

use std::collections::HashMap;

use glam::Vec3;

use super::lashes::{centre, eye_vertices, root_first};
use super::{Mesh, Part, TriangleMesh};

/// One strip of quads chained by their rungs, in walking order (either end first), and the
/// lowest index among its faces (which says which end the file wrote first).
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct Strip {
    /// The rungs, end to end: the two vertex (position) indices across the ribbon.
    pub rungs: Vec<[u32; 2]>,
    /// The face index of the strip's first quad in the walk.
    pub first_face: usize,
    /// The face index of its last quad.
    pub last_face: usize,
}

/// The strips of `mesh`'s groups that are `part`: quads chained by shared rungs. Faces that are
/// not quads are left out; a closed loop of quads is walked once from an arbitrary rung.
pub(crate) fn strips(mesh: &Mesh, part: Part) -> Vec<Strip> {
    let key = |a: u32, b: u32| if a < b { [a, b] } else { [b, a] };
    let mut quads_of: HashMap<[u32; 2], Vec<usize>> = HashMap::new();
    let mut quads: Vec<([[u32; 2]; 2], usize)> = Vec::new();
    for g in mesh.groups.iter().filter(|g| g.part() == part) {
        for (fi, f) in mesh.faces[g.faces.clone()].iter().enumerate() {
            let [a, b, c, d] = match f.corners.as_slice() {
                [a, b, c, d] => [a.position, b.position, c.position, d.position],
                _ => continue,
            };
            let q = [key(a, b), key(c, d)];
            for r in q {
                quads_of.entry(r).or_default().push(quads.len());
            }
            quads.push((q, g.faces.start + fi));
        }
    }
    let other = |q: usize, r: [u32; 2]| if quads[q].0[0] == r { quads[q].0[1] } else { quads[q].0[0] };
    let mut seen = vec![false; quads.len()];
    let mut out = Vec::new();
    for start in 0..quads.len() {
        if seen[start] {
            continue;
        }
        // Walk to one end of the strip, then along it.
        let mut end = (start, quads[start].0[0]);
        loop {
            let (q, r) = end;
            match quads_of[&r].iter().find(|&&o| o != q) {
                Some(&o) => end = (o, other(o, r)),
                None => break,
            }
            if end.0 == start {
                break; // a loop: walked from here
            }
        }
        let (mut q, first) = end;
        let mut rungs = vec![first];
        let first_face = quads[q].1;
        let mut last_face;
        loop {
            seen[q] = true;
            last_face = quads[q].1;
            let next = other(q, *rungs.last().expect("a rung"));
            rungs.push(next);
            match quads_of[&next].iter().find(|&&o| o != q && !seen[o]) {
                Some(&o) => q = o,
                None => break,
            }
        }
        out.push(Strip { rungs, first_face, last_face });
    }
    out
}

/// One hair: its rungs from root to tip (vertex indices of the mesh it was found on, or of its
/// triangle mesh after [`HairStrands::on_triangles`]).
#[derive(Debug, Clone, PartialEq)]
pub struct HairStrand {
    /// [`Part::Lash`] or [`Part::Brow`].
    pub part: Part,
    /// The two vertices across the ribbon at each station, root first.
    pub rungs: Vec<[u32; 2]>,
}

impl HairStrand {
    /// The centre line (mm) and radius (mm, half the ribbon's width) at each station, from
    /// `positions`.
    pub fn stations(&self, positions: &[Vec3]) -> Vec<(Vec3, f32)> {
        self.rungs
            .iter()
            .map(|r| {
                let (a, b) = (positions[r[0] as usize], positions[r[1] as usize]);
                ((a + b) * 0.5, 0.5 * a.distance(b))
            })
            .collect()
    }
}

/// The hairs of a mesh.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct HairStrands {
    /// One per hair.
    pub strands: Vec<HairStrand>,
}

/// Two strips are one hair when their rungs' centres agree within this (mm): the lashes' front
/// and back ribbons share their places exactly.
const SAME_HAIR_MM: f32 = 1e-4;

impl HairStrands {
    /// The lash and brow strips of `mesh` (found by `strips`), one per hair, each from root to tip: a
    /// lash's root is the end nearer an eye's centre (its lid margin, as the lash rig orders it),
    /// a brow hair's the end the file wrote first (the generator writes each hair from the skin it grows from). Strips of
    /// fewer than two rungs are left out.
    pub fn of(mesh: &Mesh) -> HairStrands {
        let eyes: Vec<Vec3> = eye_vertices(mesh).iter().map(|v| centre(&mesh.positions, v)).collect();
        let mid = |r: [u32; 2]| (mesh.positions[r[0] as usize] + mesh.positions[r[1] as usize]) * 0.5;
        let mut strands: Vec<HairStrand> = Vec::new();
        let mut seen: Vec<(Vec3, Vec3)> = Vec::new();
        for part in [Part::Lash, Part::Brow] {
            for strip in strips(mesh, part) {
                if strip.rungs.len() < 2 {
                    continue;
                }
                let mut rungs = strip.rungs;
                if part == Part::Lash && !eyes.is_empty() {
                    root_first(&mut rungs, &mesh.positions, &eyes);
                } else if strip.last_face < strip.first_face {
                    rungs.reverse();
                }
                let ends = (mid(rungs[0]), mid(*rungs.last().expect("two rungs")));
                if seen.iter().any(|s| s.0.distance(ends.0) < SAME_HAIR_MM && s.1.distance(ends.1) < SAME_HAIR_MM) {
                    continue;
                }
                seen.push(ends);
                strands.push(HairStrand { part, rungs });
            }
        }
        HairStrands { strands }
    }

    /// The strands with their vertices renamed to those of the triangle mesh whose vertex `i`
    /// came from position `sources[i]` ([`Mesh::triangulate`]'s sources) of a subdivision of
    /// the mesh they were found on. A rung whose vertex no triangle uses drops its strand.
    pub fn on_triangles(&self, sources: &[u32]) -> HairStrands {
        let mut first: HashMap<u32, u32> = HashMap::new();
        for (i, &s) in sources.iter().enumerate() {
            first.entry(s).or_insert(i as u32);
        }
        let strands = self
            .strands
            .iter()
            .filter_map(|s| {
                let rungs: Option<Vec<[u32; 2]>> =
                    s.rungs.iter().map(|r| Some([*first.get(&r[0])?, *first.get(&r[1])?])).collect();
                Some(HairStrand { part: s.part, rungs: rungs? })
            })
            .collect();
        HairStrands { strands }
    }

    /// Whether there is no hair.
    pub fn is_empty(&self) -> bool {
        self.strands.is_empty()
    }
}

/// `mesh` subdivided `levels` times and triangulated, with its hairs
/// ([`TriangleMesh::strands`]); exactly `mesh.catmull_clark(levels).triangulate()` otherwise.
pub fn subdivided_with_strands(mesh: &Mesh, levels: u32) -> TriangleMesh {
    let strands = HairStrands::of(mesh);
    let fine = if levels > 0 { mesh.catmull_clark(levels) } else { mesh.clone() };
    let (mut out, sources) = fine.triangulate_with_sources();
    out.strands = attach(&strands, &sources);
    out
}

/// The strands on a triangle mesh with these `sources`, shared, or none without hairs.
pub(crate) fn attach(strands: &HairStrands, sources: &[u32]) -> Option<std::sync::Arc<HairStrands>> {
    let on = strands.on_triangles(sources);
    (!on.is_empty()).then(|| std::sync::Arc::new(on))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_default_heads_hairs_are_found_once_each_root_first() {
        let head = crate::mesh::default_head().expect("the default head");
        let hairs = HairStrands::of(&head);
        let lashes = hairs.strands.iter().filter(|s| s.part == Part::Lash).count();
        let brows = hairs.strands.iter().filter(|s| s.part == Part::Brow).count();
        // 180 lashes written twice (front and back ribbons): one strand each; 440 brow hairs.
        assert_eq!((lashes, brows), (180, 440));
        let tri = subdivided_with_strands(&head, 2);
        let on = tri.strands.as_deref().expect("strands on the triangle mesh");
        assert_eq!(on.strands.len(), 620);
        for (base, fine) in hairs.strands.iter().zip(&on.strands) {
            // Same stations (the end ones pulled along the strand by up to a segment's quarter); the ends, moved by the boundary rule along the ribbon's edges, keep
            // about its width (more where a taper averages with a wider neighbour; at the ends, where the rule
            // pulls the rung's two ends together, 3/4 of it per level).
            let (b, f) = (base.stations(&head.positions), fine.stations(&tri.positions));
            assert_eq!(b.len(), f.len());
            for ((pb, rb), (pf, rf)) in b.iter().zip(&f) {
                assert!(pb.distance(*pf) < 1.0, "{pb} {pf}");
                assert!(*rf > 0.5 * rb && *rf < 1.5 * rb, "radius {rf} against {rb}");
            }
        }
        // Lash roots sit nearer the eye than their tips.
        let eyes: Vec<Vec3> = eye_vertices(&head).iter().map(|v| centre(&head.positions, v)).collect();
        let near = |p: Vec3| eyes.iter().map(|e| e.distance(p)).fold(f32::INFINITY, f32::min);
        for s in hairs.strands.iter().filter(|s| s.part == Part::Lash) {
            let st = s.stations(&head.positions);
            assert!(near(st[0].0) < near(st[st.len() - 1].0));
        }
    }

    #[test]
    fn a_mesh_without_hair_has_no_strands() {
        let cube = crate::mesh::shapes::builtin_shape("wedge").expect("wedge");
        assert!(HairStrands::of(&cube).is_empty());
        assert!(subdivided_with_strands(&cube, 1).strands.is_none());
    }
}
