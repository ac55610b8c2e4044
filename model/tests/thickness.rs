//! The local-thickness baker ([BarreBrisebois2011]) against closed forms: the sphere's
//! cosine-weighted mean chord 4r/3 and its exponential falloff, the wedge's thin and thick ends,
//! the cube's symmetry, exact monotonicity in the settings, the cache, the UV map and the morph.
//!
//! Tolerances: for a vertex of the sphere the chord depends only on θ, and the baker samples
//! sin²θ with one ray in each stratum of width 1/rays, so a weight w(θ) monotone in θ is
//! integrated within (w_max − w_min)/rays (thickness.rs module docs). On top, the triangulated
//! sphere is inscribed in the true one: its facets lie up to s ≈ 0.03 mm inside (96 × 48, r =
//! 25 mm), which shortens a chord at angle θ by about s/cosθ, 0.06 mm in the cosine-weighted
//! mean; 0.1 mm covers it and the ray origin's 0.009 mm offset.

use glam::{Vec2, Vec3};
use rouge_model::mesh::shapes::{SPHERE_RADIUS_MM, WEDGE_SIZE_MM, sphere, wedge};
use rouge_model::mesh::{Corner, Face, Group, Mesh, TriangleMesh};
use rouge_model::thickness::{
    BakeSettings, CacheUse, Falloff, LocalThickness, ThicknessError, bake_ambient_occlusion, bake_local_thickness,
    bake_local_thickness_cached, morph_to_bounding_sphere, thickness_uv_map,
};

/// Facet and origin-offset bias of the triangulated built-in sphere, mm (see the file docs).
const SPHERE_FACET_MM: f64 = 0.1;

fn bake(mesh: &TriangleMesh, settings: &BakeSettings) -> LocalThickness {
    match bake_local_thickness(mesh, settings) {
        Ok(b) => b,
        Err(e) => panic!("bake failed: {e}"),
    }
}

fn settings(rays: u32, cutoff_mm: f32, falloff: Falloff) -> BakeSettings {
    BakeSettings { rays, cutoff_mm, falloff, seed: 7 }
}

fn builtin_sphere() -> TriangleMesh {
    sphere(SPHERE_RADIUS_MM, 96, 48).triangulate()
}

/// Splits every quad of `mesh` into k × k quads (bilinear in position and UV), so that flat
/// faces get interior vertices away from the sharp edges.
fn grid_quads(mesh: &Mesh, k: u32) -> Mesh {
    let mut out = Mesh { normals: mesh.normals.clone(), ..Mesh::default() };
    for face in &mesh.faces {
        let c = &face.corners;
        assert_eq!(c.len(), 4, "grid_quads takes quads");
        let p = |i: usize| mesh.positions[c[i].position as usize];
        let uv = |i: usize| mesh.uvs[c[i].uv as usize];
        let base = out.positions.len() as u32;
        for j in 0..=k {
            for i in 0..=k {
                let (s, t) = (i as f32 / k as f32, j as f32 / k as f32);
                let bilinear = |a: Vec3, b: Vec3, c: Vec3, d: Vec3| {
                    a * (1.0 - s) * (1.0 - t) + b * s * (1.0 - t) + c * s * t + d * (1.0 - s) * t
                };
                out.positions.push(bilinear(p(0), p(1), p(2), p(3)));
                let q = bilinear(uv(0).extend(0.0), uv(1).extend(0.0), uv(2).extend(0.0), uv(3).extend(0.0));
                out.uvs.push(Vec2::new(q.x, q.y));
            }
        }
        let id = |i: u32, j: u32| base + j * (k + 1) + i;
        for j in 0..k {
            for i in 0..k {
                let corners = [id(i, j), id(i + 1, j), id(i + 1, j + 1), id(i, j + 1)]
                    .map(|v| Corner { position: v, uv: v, normal: c[0].normal })
                    .to_vec();
                out.faces.push(Face { corners });
            }
        }
    }
    out.groups.push(Group { name: "grid".into(), material: None, faces: 0..out.faces.len() });
    out
}

/// A cube of side `side_mm` centred on the origin, six flat quads with outward normals.
fn cube(side_mm: f32) -> Mesh {
    let h = 0.5 * side_mm;
    let mut mesh = Mesh::default();
    for axis in 0..3 {
        for sign in [1.0f32, -1.0] {
            let mut n = Vec3::ZERO;
            n[axis] = sign;
            let (u, v) = {
                let mut u = Vec3::ZERO;
                u[(axis + 1) % 3] = 1.0;
                (u, n.cross(u))
            };
            mesh.normals.push(n);
            let normal = mesh.normals.len() as u32 - 1;
            let mut corners = Vec::new();
            for (a, b) in [(-1.0, -1.0), (1.0, -1.0), (1.0, 1.0), (-1.0, 1.0)] {
                let id = mesh.positions.len() as u32;
                mesh.positions.push((n + u * a + v * b) * h);
                mesh.uvs.push(Vec2::new(0.5 + 0.5 * a, 0.5 + 0.5 * b));
                corners.push(Corner { position: id, uv: id, normal });
            }
            mesh.faces.push(Face { corners });
        }
    }
    mesh.groups.push(Group { name: "cube".into(), material: None, faces: 0..mesh.faces.len() });
    mesh
}

fn mean(xs: impl Iterator<Item = f64>) -> f64 {
    let (sum, n) = xs.fold((0.0, 0usize), |(s, n), x| (s + x, n + 1));
    sum / n as f64
}

#[test]
fn sphere_mean_chord_is_four_thirds_radius() {
    let mesh = builtin_sphere();
    let rays = 32;
    let b = bake(&mesh, &settings(rays, 60.0, Falloff::Power { exponent: 1.0 }));
    let r = f64::from(SPHERE_RADIUS_MM);
    let expected = 4.0 * r / 3.0;
    // Per vertex: the stratification bound 2r/rays plus the facet bias.
    let tolerance = 2.0 * r / f64::from(rays) + SPHERE_FACET_MM;
    for (i, &c) in b.mean_chord_mm.iter().enumerate() {
        assert!((f64::from(c) - expected).abs() <= tolerance, "vertex {i}: {c} mm, expected {expected} ± {tolerance}");
    }
    // On average the per-vertex rotations cancel: what is left is the facet bias (chords only
    // shorter) and the residual of the mean of ~4500 rotated estimates.
    let average = mean(b.mean_chord_mm.iter().map(|&c| f64::from(c)));
    assert!((average - expected).abs() <= SPHERE_FACET_MM, "average {average} mm, expected {expected}");
    // The linear falloff has the closed form 1 − (2r/c)·E[cosθ] = 1 − (2r/c)·(2/3).
    let value_expected = 1.0 - 2.0 * r / 60.0 * 2.0 / 3.0;
    let value_tolerance = 2.0 * r / 60.0 / f64::from(rays) + SPHERE_FACET_MM / 60.0;
    for (i, v) in b.value.iter().enumerate() {
        assert!((f64::from(v[0]) - value_expected).abs() <= value_tolerance, "vertex {i}: value {v:?}");
        assert!(v[0] == v[1] && v[1] == v[2], "grey falloff gives equal channels");
    }
}

#[test]
fn ambient_occlusion_is_one_outside_a_sphere_and_the_chord_inside_it() {
    let mut mesh = builtin_sphere();
    let (rays, cutoff) = (32, 60.0);
    let s = settings(rays, cutoff, Falloff::Power { exponent: 1.0 });
    // Outside a convex body every outward ray leaves: no occlusion at all.
    let outside = bake_ambient_occlusion(&mesh, &s).expect("bake");
    assert!(outside.iter().all(|&a| a == 1.0), "min {}", outside.iter().fold(1.0f32, |a, &b| a.min(b)));
    // Inside it (normals turned in: the view from within a dome), every ray hits the far wall
    // at 2r·cosθ: the occlusion 1 − E[1 − 2r cosθ / c] = (2r/c)(2/3), the local thickness's
    // closed form turned over.
    mesh.normals.iter_mut().for_each(|n| *n = -*n);
    let inside = bake_ambient_occlusion(&mesh, &s).expect("bake");
    let r = f64::from(SPHERE_RADIUS_MM);
    let expected = 2.0 * r / f64::from(cutoff) * 2.0 / 3.0;
    let tolerance = 2.0 * r / f64::from(cutoff) / f64::from(rays) + SPHERE_FACET_MM / f64::from(cutoff);
    for (i, &a) in inside.iter().enumerate() {
        assert!((f64::from(a) - expected).abs() <= tolerance, "vertex {i}: {a}, expected {expected} ± {tolerance}");
    }
    // Its errors are the thickness bake's.
    let bad = bake_ambient_occlusion(&mesh, &BakeSettings { rays: 0, ..s });
    assert!(matches!(bad, Err(ThicknessError::Setting { parameter: "rays", .. })), "{bad:?}");
}

/// ∫₀¹ 2μ·exp(−aμ) dμ = 2(1 − (1 + a)e^{−a})/a², the cosine-weighted mean of exp(−k·2r·cosθ)
/// with a = 2kr (μ = cosθ has density 2μ under the cosine lobe); the series
/// 1 − 2a/3 + a²/4 − a³/15 + … for small a, where the closed form cancels.
fn exponential_sphere_mean(k_per_mm: f64, r_mm: f64) -> f64 {
    let a = 2.0 * k_per_mm * r_mm;
    if a < 1.0e-3 {
        1.0 - 2.0 * a / 3.0 + a * a / 4.0 - a * a * a / 15.0
    } else {
        2.0 * (1.0 - (1.0 + a) * (-a).exp()) / (a * a)
    }
}

#[test]
fn sphere_exponential_falloff_matches_closed_form() {
    let mesh = builtin_sphere();
    let rays = 32;
    let per_mm = [0.0f32, 0.04, 0.5];
    let b = bake(&mesh, &settings(rays, 60.0, Falloff::Exponential { per_mm }));
    let r = f64::from(SPHERE_RADIUS_MM);
    for c in 0..3 {
        let k = f64::from(per_mm[c]);
        let expected = exponential_sphere_mean(k, r);
        // Stratification bound (w ranges over [e^{−2kr}, 1]) plus the facet bias's effect.
        let tolerance = (1.0 - (-2.0 * k * r).exp()) / f64::from(rays) + k * SPHERE_FACET_MM + 1.0e-6;
        for (i, v) in b.value.iter().enumerate() {
            let got = f64::from(v[c]);
            assert!(
                (got - expected).abs() <= tolerance,
                "vertex {i} channel {c}: {got}, expected {expected} ± {tolerance}"
            );
        }
        let average = mean(b.value.iter().map(|v| f64::from(v[c])));
        assert!(
            (average - expected).abs() <= k * SPHERE_FACET_MM + 1.0e-4,
            "channel {c}: average {average} vs {expected}"
        );
    }
    // Rate 0: every ray hits within the cutoff (chords ≤ 2r = 50 < 60), so the value is 1.
    assert!(b.value.iter().all(|v| v[0] == 1.0));
}

#[test]
fn wedge_front_face_is_thinner_at_the_thin_end() {
    let mesh = grid_quads(&wedge(), 8).triangulate();
    let b = bake(&mesh, &settings(32, 30.0, Falloff::Power { exponent: 1.0 }));
    let (w, h, _, thick) = WEDGE_SIZE_MM;
    // Front-face vertices away from the sharp edges (whose rays leave through the sides).
    let front = |i: usize| {
        let p = mesh.positions[i];
        mesh.normals[i].z > 0.99 && (p.z - 0.5 * thick).abs() < 1.0e-4 && p.y.abs() < 0.3 * h
    };
    let within = |i: usize, lo: f32, hi: f32| front(i) && (lo * w..=hi * w).contains(&mesh.positions[i].x);
    let thin: Vec<usize> = (0..mesh.vertex_count()).filter(|&i| within(i, -0.45, -0.2)).collect();
    let thick_end: Vec<usize> = (0..mesh.vertex_count()).filter(|&i| within(i, 0.2, 0.45)).collect();
    assert!(thin.len() >= 3 && thick_end.len() >= 3, "{} thin, {} thick vertices", thin.len(), thick_end.len());
    let max_thick_value = thick_end.iter().map(|&i| b.value[i][0]).fold(f32::MIN, f32::max);
    let min_thin_value = thin.iter().map(|&i| b.value[i][0]).fold(f32::MAX, f32::min);
    assert!(min_thin_value > max_thick_value, "thin end {min_thin_value} vs thick end {max_thick_value}");
    let max_thin_chord = thin.iter().map(|&i| b.mean_chord_mm[i]).fold(f32::MIN, f32::max);
    let min_thick_chord = thick_end.iter().map(|&i| b.mean_chord_mm[i]).fold(f32::MAX, f32::min);
    assert!(max_thin_chord < min_thick_chord, "thin end {max_thin_chord} mm vs thick end {min_thick_chord} mm");
    // Along x the front face reads monotonically thinner toward the thin end (the middle row,
    // away from the end walls: near x = +30 the rays toward +x leave through the end face).
    let mut row: Vec<(f32, f32)> = (0..mesh.vertex_count())
        .filter(|&i| front(i) && mesh.positions[i].y.abs() < 1.0e-3 && mesh.positions[i].x.abs() < 0.3 * w)
        .map(|i| (mesh.positions[i].x, b.mean_chord_mm[i]))
        .collect();
    row.sort_by(|a, b| a.0.total_cmp(&b.0));
    assert!(row.len() >= 5);
    assert!(row.windows(2).all(|p| p[0].1 < p[1].1), "chord along x: {row:?}");
}

#[test]
fn cube_faces_agree_by_symmetry() {
    let mesh = grid_quads(&cube(20.0), 4).triangulate();
    let b = bake(&mesh, &settings(64, 30.0, Falloff::Power { exponent: 1.0 }));
    // Per face (by its normal), the mean value and chord over its vertices.
    let mut faces: Vec<(Vec3, f64, f64)> = Vec::new();
    for axis in 0..3 {
        for sign in [1.0f32, -1.0] {
            let mut n = Vec3::ZERO;
            n[axis] = sign;
            let ids: Vec<usize> = (0..mesh.vertex_count()).filter(|&i| mesh.normals[i].dot(n) > 0.99).collect();
            assert_eq!(ids.len(), 25);
            let value = mean(ids.iter().map(|&i| f64::from(b.value[i][0])));
            let chord = mean(ids.iter().map(|&i| f64::from(b.mean_chord_mm[i])));
            faces.push((n, value, chord));
        }
    }
    let all_value = mean(faces.iter().map(|f| f.1));
    let all_chord = mean(faces.iter().map(|f| f.2));
    // Each face mean averages 25 vertices of independent rotations; the per-vertex spread at 64
    // rays is below 0.02 in value and 0.4 mm in chord, so 0.01 and 0.2 mm are several σ.
    for (n, value, chord) in &faces {
        assert!((value - all_value).abs() < 0.01, "face {n}: value {value} vs {all_value}");
        assert!((chord - all_chord).abs() < 0.2, "face {n}: chord {chord} vs {all_chord}");
    }
    // The centre of each face sees the 20 mm wall opposite: chord ≈ 2·20 mm cosine-weighted, but
    // clipped by the cutoff and the side walls; at least it is thicker than the edges' vertices.
    let centre = |n: Vec3| {
        (0..mesh.vertex_count())
            .find(|&i| mesh.normals[i].dot(n) > 0.99 && mesh.positions[i].distance(n * 10.0) < 1.0e-3)
            .map(|i| b.mean_chord_mm[i])
    };
    let centres: Vec<f32> = faces.iter().filter_map(|f| centre(f.0)).collect();
    assert_eq!(centres.len(), 6);
    let spread = centres.iter().fold(f32::MIN, |a, &b| a.max(b)) - centres.iter().fold(f32::MAX, |a, &b| a.min(b));
    assert!(spread < 1.0, "face centres' chords {centres:?}");
}

#[test]
fn value_in_unit_range_and_exactly_monotone_in_cutoff_and_exponent() {
    let mesh = grid_quads(&wedge(), 3).triangulate();
    let power = |cutoff: f32, exponent: f32| bake(&mesh, &settings(16, cutoff, Falloff::Power { exponent }));
    let cutoffs = [2.0, 5.0, 12.0, 30.0, 80.0];
    let by_cutoff: Vec<LocalThickness> = cutoffs.iter().map(|&c| power(c, 1.0)).collect();
    for b in &by_cutoff {
        assert!(b.value.iter().flatten().all(|v| (0.0..=1.0).contains(v)));
        assert!(b.mean_chord_mm.iter().all(|&c| c >= 0.0 && c <= b.settings.cutoff_mm));
    }
    for pair in by_cutoff.windows(2) {
        for i in 0..mesh.vertex_count() {
            // A longer cutoff: the same rays, each hit weighs more and misses may become hits.
            assert!(pair[0].value[i][0] <= pair[1].value[i][0], "vertex {i}: value falls with cutoff");
            assert!(pair[0].mean_chord_mm[i] <= pair[1].mean_chord_mm[i], "vertex {i}: chord falls with cutoff");
        }
    }
    let by_exponent: Vec<LocalThickness> = [0.25, 0.5, 1.0, 2.0, 4.0].iter().map(|&e| power(30.0, e)).collect();
    for pair in by_exponent.windows(2) {
        for i in 0..mesh.vertex_count() {
            // (1 − t/c)^e with a base in [0, 1] can only fall as e grows.
            assert!(pair[0].value[i][0] >= pair[1].value[i][0], "vertex {i}: value rises with exponent");
            assert_eq!(pair[0].mean_chord_mm[i], pair[1].mean_chord_mm[i], "the chord ignores the falloff");
        }
    }
    // The rate: a faster exponential falloff never raises the value.
    let rates = bake(&mesh, &settings(16, 30.0, Falloff::Exponential { per_mm: [0.01, 0.1, 1.0] }));
    assert!(rates.value.iter().all(|v| v[0] >= v[1] && v[1] >= v[2] && v.iter().all(|c| (0.0..=1.0).contains(c))));
    // Same seed, same bake; another seed, another (unbiased) estimate.
    assert_eq!(power(30.0, 1.0).value, by_cutoff[3].value);
    let other = bake(&mesh, &BakeSettings { seed: 8, ..by_cutoff[3].settings });
    assert_ne!(other.value, by_cutoff[3].value);
}

#[test]
fn bad_settings_and_meshes_are_errors_naming_the_parameter() {
    let mesh = sphere(10.0, 12, 6).triangulate();
    let power = Falloff::Power { exponent: 1.0 };
    let cases = [
        (BakeSettings { rays: 0, ..BakeSettings::default() }, "rays"),
        (settings(8, 0.0, power), "cutoff_mm"),
        (settings(8, -1.0, power), "cutoff_mm"),
        (settings(8, f32::NAN, power), "cutoff_mm"),
        (settings(8, f32::INFINITY, power), "cutoff_mm"),
        (settings(8, 10.0, Falloff::Power { exponent: 0.0 }), "falloff.exponent"),
        (settings(8, 10.0, Falloff::Power { exponent: -2.0 }), "falloff.exponent"),
        (settings(8, 10.0, Falloff::Power { exponent: f32::NAN }), "falloff.exponent"),
        (settings(8, 10.0, Falloff::Exponential { per_mm: [0.1, -0.1, 0.1] }), "falloff.per_mm"),
        (settings(8, 10.0, Falloff::Exponential { per_mm: [0.1, 0.1, f32::INFINITY] }), "falloff.per_mm"),
    ];
    for (s, name) in cases {
        match bake_local_thickness(&mesh, &s) {
            Err(ThicknessError::Setting { parameter, .. }) => assert_eq!(parameter, name, "{s:?}"),
            other => panic!("{s:?}: expected a {name} error, got {other:?}"),
        }
        assert!(matches!(bake_local_thickness_cached(&mesh, &s, None), Err(ThicknessError::Setting { .. })));
    }
    let good = settings(8, 10.0, power);
    let mut nan = mesh.clone();
    nan.positions[3].y = f32::NAN;
    let message = bake_local_thickness(&nan, &good).map(|_| ()).err().map(|e| e.to_string()).unwrap_or_default();
    assert!(message.contains("vertex 3") && message.contains("position"), "{message}");
    let mut nan_normal = mesh.clone();
    nan_normal.normals[5] = Vec3::new(f32::INFINITY, 0.0, 0.0);
    let message = bake_local_thickness(&nan_normal, &good).map(|_| ()).err().map(|e| e.to_string()).unwrap_or_default();
    assert!(message.contains("vertex 5") && message.contains("normal"), "{message}");
    let mut no_triangles = mesh.clone();
    no_triangles.indices.clear();
    assert!(matches!(bake_local_thickness(&no_triangles, &good), Err(ThicknessError::Mesh(_))));
    let mut out_of_range = mesh.clone();
    out_of_range.indices[4] = 1_000_000;
    assert!(matches!(bake_local_thickness(&out_of_range, &good), Err(ThicknessError::Mesh(_))));
}

#[test]
fn degenerate_normal_gets_a_defined_value() {
    let mut mesh = sphere(10.0, 12, 6).triangulate();
    mesh.normals[7] = Vec3::ZERO;
    // A vertex used by no triangle, with no normal either: nothing to aim by.
    mesh.positions.push(Vec3::new(100.0, 0.0, 0.0));
    mesh.normals.push(Vec3::ZERO);
    mesh.uvs.push(Vec2::ZERO);
    let b = bake(&mesh, &settings(16, 30.0, Falloff::Power { exponent: 1.0 }));
    assert!(b.value.iter().flatten().all(|v| v.is_finite()) && b.mean_chord_mm.iter().all(|c| c.is_finite()));
    // Vertex 7 aims by its triangles' normal: it reads like its neighbours (a sphere: 4r/3).
    assert!((b.mean_chord_mm[7] - 40.0 / 3.0).abs() < 2.0, "{}", b.mean_chord_mm[7]);
    let last = mesh.vertex_count() - 1;
    assert_eq!((b.mean_chord_mm[last], b.value[last]), (30.0, [0.0; 3]));
}

#[test]
fn cache_round_trip_and_corrupt_files_rebake() {
    let dir = tempfile::tempdir().unwrap_or_else(|e| panic!("tempdir: {e}"));
    let mesh = sphere(10.0, 16, 8).triangulate();
    let s = settings(8, 30.0, Falloff::Exponential { per_mm: [0.1, 0.2, 0.3] });
    let run = |s: &BakeSettings| match bake_local_thickness_cached(&mesh, s, Some(dir.path())) {
        Ok(r) => r,
        Err(e) => panic!("cached bake: {e}"),
    };
    let (first, use1) = run(&s);
    assert_eq!(use1, CacheUse::Miss);
    let (second, use2) = run(&s);
    assert_eq!(use2, CacheUse::Hit);
    assert_eq!(first, second, "a hit returns the stored bake bit for bit");
    let files: Vec<_> =
        std::fs::read_dir(dir.path()).map(|d| d.flatten().map(|e| e.path()).collect()).unwrap_or_default();
    assert_eq!(files.len(), 1, "one file, no temporary left: {files:?}");
    let file = &files[0];
    let name = file.file_name().and_then(|n| n.to_str()).unwrap_or_default().to_owned();
    assert!(name.len() == 36 && name.ends_with(".bin") && name[..32].chars().all(|c| c.is_ascii_hexdigit()), "{name}");

    // Another seed is another key: a miss, and a second file.
    let (_, use3) = run(&BakeSettings { seed: 99, ..s });
    assert_eq!(use3, CacheUse::Miss);

    // A flipped byte, a truncated file, garbage and an empty file are rebaked and replaced.
    let bytes = std::fs::read(file).unwrap_or_default();
    let mut flipped = bytes.clone();
    flipped[bytes.len() / 2] ^= 0x40;
    for corrupt in [flipped, bytes[..bytes.len() - 5].to_vec(), b"not a cache".to_vec(), Vec::new()] {
        std::fs::write(file, &corrupt).unwrap_or_else(|e| panic!("write: {e}"));
        let (again, use4) = run(&s);
        assert_eq!(use4, CacheUse::Miss);
        assert_eq!(again.value, first.value);
        assert_eq!(again.mean_chord_mm, first.mean_chord_mm);
        assert_eq!(run(&s).1, CacheUse::Hit, "the rebake replaced the corrupt file");
    }
    // Moving one vertex changes the key.
    let mut moved = mesh.clone();
    moved.positions[0].x += 0.01;
    let moved_use = bake_local_thickness_cached(&moved, &s, Some(dir.path())).map(|r| r.1);
    assert_eq!(moved_use.ok(), Some(CacheUse::Miss));
    // No directory: no cache.
    assert_eq!(bake_local_thickness_cached(&mesh, &s, None).map(|r| r.1).ok(), Some(CacheUse::Off));
}

#[test]
fn uv_map_of_flat_square_holds_interpolated_values() {
    let mesh = TriangleMesh::flat_square(10.0);
    // Values affine in (u, v) are reproduced exactly by barycentric interpolation.
    let f = |uv: Vec2| [uv.x, uv.y, 0.25 + 0.5 * uv.x - 0.25 * uv.y];
    let values: Vec<[f32; 3]> = mesh.uvs.iter().map(|&uv| f(uv)).collect();
    let (w, h) = (16u32, 8u32);
    let map = thickness_uv_map(&mesh, &values, w, h).unwrap_or_else(|e| panic!("{e}"));
    assert_eq!((map.width, map.height, map.texels.len()), (w, h, (w * h) as usize));
    for y in 0..h {
        for x in 0..w {
            // Row 0 at the top: v = 1 − (y + 0.5)/h.
            let uv = Vec2::new((x as f32 + 0.5) / w as f32, 1.0 - (y as f32 + 0.5) / h as f32);
            let want = f(uv);
            let got = map.texel(x, y).unwrap_or_default();
            assert_eq!(got[3], 1.0, "texel ({x}, {y}) covered");
            for c in 0..3 {
                assert!((got[c] - want[c]).abs() < 1.0e-5, "texel ({x}, {y}) channel {c}: {got:?} vs {want:?}");
            }
        }
    }
    assert_eq!(map.texel(w, 0), None);

    // Squeezed into the lower-left quarter of UV space: covered there (and in the two-texel
    // dilation ring, with the edge's value), alpha 0 and zero beyond.
    let mut small = mesh.clone();
    small.uvs.iter_mut().for_each(|uv| *uv *= 0.5);
    let corner_values: Vec<[f32; 3]> = vec![[1.0, 0.0, 0.0]; 4];
    let map = thickness_uv_map(&small, &corner_values, 16, 16).unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(map.texel(0, 15), Some([1.0, 0.0, 0.0, 1.0]), "bottom-left is v = 0");
    assert_eq!(map.texel(9, 15), Some([1.0, 0.0, 0.0, 1.0]), "dilation ring");
    assert_eq!(map.texel(10, 15), Some([0.0; 4]), "beyond the ring");
    assert_eq!(map.texel(0, 0), Some([0.0; 4]), "top-left is v = 1: uncovered");

    // Errors: wrong value count, non-finite value, zero size.
    assert!(matches!(thickness_uv_map(&mesh, &values[..3], 4, 4), Err(ThicknessError::Map(_))));
    let mut nan = values.clone();
    nan[1][2] = f32::NAN;
    assert!(matches!(thickness_uv_map(&mesh, &nan, 4, 4), Err(ThicknessError::Map(_))));
    assert!(matches!(thickness_uv_map(&mesh, &values, 0, 4), Err(ThicknessError::Map(_))));
}

#[test]
fn uv_map_of_a_bake_is_in_unit_range() {
    let mesh = sphere(10.0, 16, 8).triangulate();
    let b = bake(&mesh, &settings(8, 30.0, Falloff::Power { exponent: 2.0 }));
    let map = thickness_uv_map(&mesh, &b.value, 64, 32).unwrap_or_else(|e| panic!("{e}"));
    assert!(map.texels.iter().flatten().all(|c| (0.0..=1.0).contains(c)));
    assert!(map.texels.iter().filter(|t| t[3] == 1.0).count() > 64 * 32 * 9 / 10);
}

#[test]
fn morph_to_bounding_sphere_identity_sphere_and_errors() {
    let mesh = grid_quads(&wedge(), 2).triangulate();
    let same = morph_to_bounding_sphere(&mesh, 0.0).unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(same, mesh, "t = 0 is the identity");

    let centre = rouge_model::Bounds::of(&mesh.positions).map(|b| b.center()).unwrap_or_default();
    let radius = mesh.positions.iter().map(|p| p.distance(centre)).fold(0.0f32, f32::max);
    let round = morph_to_bounding_sphere(&mesh, 1.0).unwrap_or_else(|e| panic!("{e}"));
    for (i, p) in round.positions.iter().enumerate() {
        assert!((p.distance(centre) - radius).abs() <= 1.0e-4 * radius, "vertex {i} at {p}, radius {radius}");
    }
    // Normals: unit, and equal for every vertex at the same position (seams split vertices).
    for i in 0..round.vertex_count() {
        assert!((round.normals[i].length() - 1.0).abs() < 1.0e-5);
        for j in 0..i {
            if round.positions[i] == round.positions[j] {
                assert_eq!(round.normals[i], round.normals[j], "vertices {i} and {j} share a position");
            }
        }
    }
    let half = morph_to_bounding_sphere(&mesh, 0.5).unwrap_or_else(|e| panic!("{e}"));
    for i in 0..mesh.vertex_count() {
        let mid = 0.5 * (mesh.positions[i] + round.positions[i]);
        assert!(half.positions[i].distance(mid) < 1.0e-4, "vertex {i}: halfway");
    }
    assert_eq!((half.indices.clone(), half.uvs.clone()), (mesh.indices.clone(), mesh.uvs.clone()));
    for t in [1.5, -0.1, f32::NAN] {
        assert!(matches!(morph_to_bounding_sphere(&mesh, t), Err(ThicknessError::MorphT(_))), "t = {t}");
    }
}
