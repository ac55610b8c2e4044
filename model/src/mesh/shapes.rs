//! Built-in test objects for translucency references (`--mesh builtin:NAME`): closed, with
//! outward normals, in millimetres, centred on the origin. A path tracer needs a closed
//! boundary to know what is inside the medium; these are, exactly.

use super::{Corner, Face, Group, Mesh};
use glam::{Vec2, Vec3};
use std::f32::consts::PI;

/// The names `builtin:NAME` accepts.
pub const BUILTIN_SHAPES: [&str; 3] = ["head", "sphere", "wedge"];

/// Radius of the built-in sphere, mm.
pub const SPHERE_RADIUS_MM: f32 = 25.0;

/// A built-in shape by name: `sphere` ([`sphere`]) or `wedge` ([`wedge`]); `None` for another
/// name (`head`, the default head, is loaded by [`super::load_mesh`]).
pub fn builtin_shape(name: &str) -> Option<Mesh> {
    match name {
        "sphere" => Some(sphere(SPHERE_RADIUS_MM, 96, 48)),
        "wedge" => Some(wedge()),
        _ => None,
    }
}

/// A UV sphere of `radius_mm` with smooth normals: `segments` around, `rings` from pole to pole
/// (quads, triangles at the poles). Positions lie exactly on the sphere.
pub fn sphere(radius_mm: f32, segments: u32, rings: u32) -> Mesh {
    let mut mesh = Mesh::default();
    // Vertex (i, j): i around (0..segments, wrapping), j from the north pole (0) to the south (rings).
    let index = |i: u32, j: u32| -> u32 {
        if j == 0 {
            0
        } else if j == rings {
            1 + (rings - 1) * segments
        } else {
            1 + (j - 1) * segments + (i % segments)
        }
    };
    let mut push = |d: Vec3| {
        mesh.positions.push(d * radius_mm);
        mesh.normals.push(d);
    };
    push(Vec3::Y);
    for j in 1..rings {
        let theta = PI * j as f32 / rings as f32;
        for i in 0..segments {
            let phi = 2.0 * PI * i as f32 / segments as f32;
            push(Vec3::new(theta.sin() * phi.sin(), theta.cos(), theta.sin() * phi.cos()));
        }
    }
    push(-Vec3::Y);
    for d in &mesh.normals {
        mesh.uvs.push(Vec2::new(0.5 + d.x.atan2(d.z) / (2.0 * PI), 0.5 + 0.5 * d.y));
    }
    let corner = |v: u32| Corner { position: v, uv: v, normal: v };
    for j in 0..rings {
        for i in 0..segments {
            // Counter-clockwise seen from outside: down the meridian, then along increasing φ.
            let mut ids = vec![index(i, j), index(i, j + 1), index(i + 1, j + 1), index(i + 1, j)];
            ids.dedup();
            if ids.first() == ids.last() && ids.len() > 3 {
                ids.pop();
            }
            mesh.faces.push(Face { corners: ids.into_iter().map(corner).collect() });
        }
    }
    mesh.groups.push(Group { name: "sphere".into(), material: None, faces: 0..mesh.faces.len() });
    mesh
}

/// Width (x), height (y) and the thin and thick ends (z) of the wedge, mm.
pub const WEDGE_SIZE_MM: (f32, f32, f32, f32) = (60.0, 40.0, 1.0, 15.0);

/// A wedge: a box 60 mm wide (x) and 40 mm tall (y) whose thickness along z grows linearly from
/// 1 mm at x = −30 to 15 mm at x = +30. The flat front face lies at z = +7.5 and faces the
/// default camera (+Z); the back face slants from z = 6.5 (thin end) to z = −7.5 (thick end).
/// Flat normals per face. Shows how translucency depends on thickness under one light.
pub fn wedge() -> Mesh {
    let (w, h, thin, thick) = WEDGE_SIZE_MM;
    let (x0, x1, y0, y1) = (-0.5 * w, 0.5 * w, -0.5 * h, 0.5 * h);
    let zf = 0.5 * thick;
    let zb = |x: f32| zf - (thin + (thick - thin) * (x - x0) / (x1 - x0));
    let p = |x: f32, y: f32, z: f32| Vec3::new(x, y, z);
    let (a, b, c, d) = (p(x0, y0, zf), p(x1, y0, zf), p(x1, y1, zf), p(x0, y1, zf));
    let (e, f, g, hh) = (p(x0, y0, zb(x0)), p(x1, y0, zb(x1)), p(x1, y1, zb(x1)), p(x0, y1, zb(x0)));
    // Quads counter-clockwise seen from outside.
    let quads = [[a, b, c, d], [f, e, hh, g], [e, a, d, hh], [b, f, g, c], [d, c, g, hh], [e, f, b, a]];
    let mut mesh = Mesh::default();
    for q in quads {
        let normal = (q[1] - q[0]).cross(q[2] - q[0]).normalize();
        let n = mesh.normals.len() as u32;
        mesh.normals.push(normal);
        let mut corners = Vec::new();
        for (k, v) in q.iter().enumerate() {
            let id = mesh.positions.len() as u32;
            mesh.positions.push(*v);
            mesh.uvs.push(Vec2::new((k == 1 || k == 2) as u32 as f32, (k >= 2) as u32 as f32));
            corners.push(Corner { position: id, uv: id, normal: n });
        }
        mesh.faces.push(Face { corners });
    }
    mesh.groups.push(Group { name: "wedge".into(), material: None, faces: 0..mesh.faces.len() });
    mesh
}
