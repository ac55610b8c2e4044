//! Built-in shapes are closed; the default head has exactly one open loop (the neck), which
//! `close_boundary_loops` closes into a watertight surface with outward caps.

use rouge_model::mesh::{TriangleMesh, close_boundary_loops, load_mesh};
use std::collections::HashMap;
use std::path::Path;

/// Directed edges over welded positions: (edges used once without their reverse, edges whose
/// direction repeats).
fn open_and_bad_edges(mesh: &TriangleMesh) -> (usize, usize) {
    let key = |v: u32| {
        let p = mesh.positions[v as usize];
        [p.x.to_bits(), p.y.to_bits(), p.z.to_bits()]
    };
    let mut ids: HashMap<[u32; 3], usize> = HashMap::new();
    let mut count: HashMap<(usize, usize), usize> = HashMap::new();
    for t in mesh.indices.chunks(3) {
        let w: Vec<usize> = t
            .iter()
            .map(|&v| {
                let next = ids.len();
                *ids.entry(key(v)).or_insert(next)
            })
            .collect();
        for k in 0..3 {
            *count.entry((w[k], w[(k + 1) % 3])).or_default() += 1;
        }
    }
    let open = count.keys().filter(|(a, b)| !count.contains_key(&(*b, *a))).count();
    let repeated = count.values().filter(|&&c| c > 1).count();
    (open, repeated)
}

#[test]
fn sphere_and_wedge_are_closed_and_consistently_wound() {
    for name in ["builtin:sphere", "builtin:wedge"] {
        let mesh = load_mesh(Some(Path::new(name)), 1.0, 2).expect(name);
        assert_eq!(open_and_bad_edges(&mesh), (0, 0), "{name}");
        let all: Vec<usize> = (0..mesh.triangle_count()).collect();
        let (_, loops) = close_boundary_loops(&mesh, &all);
        assert_eq!(loops, 0, "{name} has nothing to close");
    }
    let e = load_mesh(Some(Path::new("builtin:cube")), 1.0, 0).expect_err("unknown");
    assert!(e.to_string().contains("builtin:sphere"), "{e}");
}

#[test]
fn the_default_head_closes_at_the_neck_only() {
    let head = load_mesh(None, 1.0, 1).expect("head");
    // The tissue's surface: the skin and the mouth bag (the eyes, teeth, tongue and lashes
    // are parts of their own, as the Mitsuba export treats them).
    let skin: Vec<usize> = (0..head.triangle_count())
        .filter(|t| head.groups.iter().any(|g| g.triangles.contains(t) && g.is_tissue()))
        .collect();
    let (closed, loops) = close_boundary_loops(&head, &skin);
    assert_eq!(loops, 1, "the neck is the one open loop");
    assert_eq!(open_and_bad_edges(&closed), (0, 0), "capped head is watertight and consistently wound");
    // The cap faces down, away from the face.
    let cap_normal = *closed.normals.last().expect("cap vertices");
    assert!(cap_normal.y < -0.5, "cap normal {cap_normal}");
}

#[test]
fn the_built_in_sphere_and_wedge_take_the_mesh_scale_and_the_head_keeps_its_size() {
    let radius = |m: &TriangleMesh| m.positions.iter().map(|p| p.length()).fold(0.0f32, f32::max);
    let sphere = load_mesh(Some(Path::new("builtin:sphere")), 1.0, 0).expect("sphere");
    let big = load_mesh(Some(Path::new("builtin:sphere")), 4.0, 0).expect("sphere");
    assert!((radius(&sphere) - 25.0).abs() < 0.01 && (radius(&big) - 100.0).abs() < 0.05, "{}", radius(&big));
    assert_eq!(sphere.normals, big.normals, "the shape's normals stay");
    let extent = |m: &TriangleMesh| rouge_model::mesh::Bounds::of(&m.positions).map(|b| b.size());
    let wedge = load_mesh(Some(Path::new("builtin:wedge")), 0.5, 0).expect("wedge");
    let full = load_mesh(Some(Path::new("builtin:wedge")), 1.0, 0).expect("wedge");
    assert_eq!(extent(&wedge).map(|s| s * 2.0), extent(&full));
    let head = load_mesh(Some(Path::new("builtin:head")), 3.0, 0).expect("head");
    let rest = load_mesh(None, 1.0, 0).expect("head");
    assert_eq!(head.positions, rest.positions, "the head's targets are in mm: not scaled");
}
