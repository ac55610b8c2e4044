//! Closing the open boundary loops of a mesh (the default head's neck) with flat fans, so that a
//! path tracer sees a closed boundary around a medium. Rouge's own renderer draws the mesh as it
//! is; the caps only serve exports.

use super::TriangleMesh;
use glam::Vec3;
use std::collections::HashMap;

/// The triangles `mesh.indices[3t..3t+3]` for `t` in `triangles`, plus one fan per boundary loop
/// (edges used by one triangle only, after welding vertices at equal positions), as a new
/// triangle mesh. A fan joins the loop to its centroid with the loop's own winding reversed, so
/// its normal points out of the closed surface; its vertices get that flat normal. Returns the
/// mesh and the number of loops closed. Loops that do not close (non-manifold edges) are left
/// open.
pub fn close_boundary_loops(mesh: &TriangleMesh, triangles: &[usize]) -> (TriangleMesh, usize) {
    let key = |v: u32| {
        let p = mesh.positions[v as usize];
        [p.x.to_bits(), p.y.to_bits(), p.z.to_bits()]
    };
    let mut weld: HashMap<[u32; 3], u32> = HashMap::new();
    let canon: Vec<u32> = (0..mesh.positions.len() as u32).map(|v| *weld.entry(key(v)).or_insert(v)).collect();
    // Directed edges by welded ids; a boundary edge is one whose reverse never appears.
    let mut directed: HashMap<(u32, u32), usize> = HashMap::new();
    for &t in triangles {
        for k in 0..3 {
            let (a, b) = (canon[mesh.indices[3 * t + k] as usize], canon[mesh.indices[3 * t + (k + 1) % 3] as usize]);
            *directed.entry((a, b)).or_default() += 1;
        }
    }
    let mut next: HashMap<u32, u32> = HashMap::new();
    for (&(a, b), &count) in &directed {
        if count == 1 && !directed.contains_key(&(b, a)) {
            next.insert(a, b);
        }
    }
    let mut out = TriangleMesh {
        positions: Vec::new(),
        normals: Vec::new(),
        uvs: Vec::new(),
        tangents: None,
        indices: Vec::new(),
        groups: Vec::new(),
        strands: None,
    };
    let mut remap: HashMap<u32, u32> = HashMap::new();
    for &t in triangles {
        for k in 0..3 {
            let v = mesh.indices[3 * t + k];
            let id = *remap.entry(v).or_insert_with(|| {
                out.positions.push(mesh.positions[v as usize]);
                out.normals.push(mesh.normals[v as usize]);
                out.uvs.push(mesh.uvs[v as usize]);
                (out.positions.len() - 1) as u32
            });
            out.indices.push(id);
        }
    }
    let mut loops = 0;
    let mut starts: Vec<u32> = next.keys().copied().collect();
    starts.sort_unstable();
    for start in starts {
        let mut chain = vec![start];
        let mut v = start;
        let closed = loop {
            let Some(&n) = next.get(&v) else { break false };
            if n == start {
                break true;
            }
            if chain.len() > next.len() {
                break false;
            }
            chain.push(n);
            v = n;
        };
        for c in &chain {
            next.remove(c);
        }
        if !closed || chain.len() < 3 {
            continue;
        }
        let points: Vec<Vec3> = chain.iter().map(|&c| mesh.positions[c as usize]).collect();
        let centre = points.iter().copied().sum::<Vec3>() / points.len() as f32;
        // The loop runs along the open triangles' winding; the fan runs against it.
        let mut area = Vec3::ZERO;
        for i in 0..points.len() {
            area += (points[(i + 1) % points.len()] - centre).cross(points[i] - centre);
        }
        let normal = area.normalize_or_zero();
        let base = out.positions.len() as u32;
        out.positions.push(centre);
        out.positions.extend(&points);
        out.normals.extend(std::iter::repeat_n(normal, points.len() + 1));
        out.uvs.extend(std::iter::repeat_n(glam::Vec2::ZERO, points.len() + 1));
        let n = points.len() as u32;
        for i in 0..n {
            out.indices.extend([base, base + 1 + (i + 1) % n, base + 1 + i]);
        }
        loops += 1;
    }
    (out, loops)
}
