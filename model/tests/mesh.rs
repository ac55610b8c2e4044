//! Integration tests of mesh loading and preparation on the default head.

use std::collections::{HashMap, HashSet};
use std::path::PathBuf;
use std::time::Instant;

use glam::Vec3;
use rouge_model::{Mesh, MeshError, load_gltf, load_obj};

fn head_path() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../data/heads/hm08_head.obj")
}

fn head() -> Mesh {
    load_obj(head_path(), 1.0).expect("load default head")
}

/// The head's closed surface: the skin and the mouth bag (groups `head` and `mouth`), without
/// the eyes, teeth, tongue and lashes (positions kept, so vertex numbers stay).
fn surface(m: &Mesh) -> Mesh {
    let mut out = Mesh { groups: Vec::new(), faces: Vec::new(), ..m.clone() };
    for g in m.groups.iter().filter(|g| g.name == "head" || g.name == "mouth") {
        out.faces.extend_from_slice(&m.faces[g.faces.clone()]);
    }
    out
}

fn edge_face_counts(m: &Mesh) -> HashMap<(u32, u32), u32> {
    let mut edges = HashMap::new();
    for f in &m.faces {
        let k = f.corners.len();
        for i in 0..k {
            let (a, b) = (f.corners[i].position, f.corners[(i + 1) % k].position);
            *edges.entry((a.min(b), a.max(b))).or_insert(0) += 1;
        }
    }
    edges
}

fn used_vertices(m: &Mesh) -> usize {
    m.faces.iter().flat_map(|f| f.corners.iter().map(|c| c.position)).collect::<HashSet<_>>().len()
}

fn euler(m: &Mesh) -> i64 {
    used_vertices(m) as i64 - edge_face_counts(m).len() as i64 + m.faces.len() as i64
}

/// Number of boundary loops (connected components of boundary edges), and whether every
/// boundary vertex has exactly two boundary edges.
fn boundary_loops(m: &Mesh) -> (usize, bool) {
    let mut adj: HashMap<u32, Vec<u32>> = HashMap::new();
    for (&(a, b), &n) in &edge_face_counts(m) {
        if n == 1 {
            adj.entry(a).or_default().push(b);
            adj.entry(b).or_default().push(a);
        }
    }
    let manifold = adj.values().all(|v| v.len() == 2);
    let mut seen = HashSet::new();
    let mut loops = 0;
    for &start in adj.keys() {
        if !seen.insert(start) {
            continue;
        }
        loops += 1;
        let mut stack = vec![start];
        while let Some(v) = stack.pop() {
            for &w in &adj[&v] {
                if seen.insert(w) {
                    stack.push(w);
                }
            }
        }
    }
    (loops, manifold)
}

fn face_normal(m: &Mesh, f: usize) -> Vec3 {
    let cs = &m.faces[f].corners;
    let mut n = Vec3::ZERO;
    for i in 0..cs.len() {
        let a = m.positions[cs[i].position as usize];
        let b = m.positions[cs[(i + 1) % cs.len()].position as usize];
        n += a.cross(b);
    }
    n.normalize_or_zero()
}

/// Mean angle (radians) between normals of faces sharing an edge.
fn mean_dihedral(m: &Mesh) -> f64 {
    let mut by_edge: HashMap<(u32, u32), Vec<usize>> = HashMap::new();
    for (fi, f) in m.faces.iter().enumerate() {
        let k = f.corners.len();
        for i in 0..k {
            let (a, b) = (f.corners[i].position, f.corners[(i + 1) % k].position);
            by_edge.entry((a.min(b), a.max(b))).or_default().push(fi);
        }
    }
    let (mut sum, mut n) = (0.0f64, 0usize);
    for fs in by_edge.values().filter(|v| v.len() == 2) {
        let d = face_normal(m, fs[0]).dot(face_normal(m, fs[1])).clamp(-1.0, 1.0);
        sum += f64::from(d.acos());
        n += 1;
    }
    sum / n as f64
}

#[test]
fn head_counts_bounds_groups() {
    let m = head();
    assert_eq!(m.positions.len(), 11626);
    assert_eq!(m.faces.len(), 7340);
    assert!(m.faces.iter().all(|f| f.corners.len() == 4));
    let names: Vec<&str> = m.groups.iter().map(|g| g.name.as_str()).collect();
    assert_eq!(
        names,
        [
            "head",
            "mouth",
            "eye_l",
            "eye_r",
            "teeth_upper",
            "teeth_lower",
            "tongue",
            "lashes_l",
            "lashes_r",
            "brow_l",
            "brow_r"
        ]
    );
    assert_eq!(m.group("head").unwrap().faces.len() + m.group("mouth").unwrap().faces.len(), 4262);
    assert_eq!(m.group("eye_l").unwrap().faces.len(), 70);
    assert_eq!(m.group("tongue").unwrap().faces.len(), 224);
    assert_eq!(m.group("eye_r").unwrap().material.as_deref(), Some("eye"));
    let b = m.bounds().unwrap();
    let size = b.size();
    println!("head bounds {:?} .. {:?}, size {size:?} mm", b.min, b.max);
    assert!((200.0..350.0).contains(&size.y), "height {}", size.y);
    assert!(m.normals.iter().all(|n| (n.length() - 1.0).abs() < 1e-4));
    let (loops, manifold) = boundary_loops(&surface(&m));
    assert_eq!(loops, 1, "the skin and the mouth bag close the head but at the neck");
    assert!(manifold);
}

#[test]
fn catmull_clark_one_level() {
    let m = surface(&head());
    let t = Instant::now();
    let s = m.catmull_clark(1);
    println!("catmull_clark(1) on head: {:?}", t.elapsed());
    assert_eq!(s.faces.len(), 4 * m.faces.len());
    assert_eq!(euler(&s), euler(&m));
    let (loops, manifold) = boundary_loops(&s);
    assert_eq!(loops, 1, "neck boundary must stay a single loop");
    assert!(manifold);
    let max_move = m.positions.iter().zip(&s.positions).map(|(a, b)| a.distance(*b)).fold(0.0f32, f32::max);
    let mut moves: Vec<(f32, usize)> =
        m.positions.iter().zip(&s.positions).map(|(a, b)| a.distance(*b)).zip(0..).collect();
    moves.sort_by(|a, b| a.0.total_cmp(&b.0));
    let mean = moves.iter().map(|m| m.0).sum::<f32>() / moves.len() as f32;
    let p99 = moves[moves.len() * 99 / 100].0;
    let worst = moves[moves.len() - 1].1;
    println!("vertex displacement: mean {mean} mm, p99 {p99} mm, max {max_move} mm at {:?}", m.positions[worst]);
    // The worst case is inside the narrow mouth bag; the visible surface moves far less.
    assert!(mean < 1.0 && p99 < 3.0 && max_move < 6.0, "moved mean {mean} p99 {p99} max {max_move} mm");
    let (d0, d1) = (mean_dihedral(&m), mean_dihedral(&s));
    println!("mean adjacent-normal angle: {:.2}° -> {:.2}°", d0.to_degrees(), d1.to_degrees());
    assert!(d1 < d0 * 0.75);
    assert!(s.positions.iter().all(|p| p.is_finite()));
    assert!(s.normals.iter().all(|n| (n.length() - 1.0).abs() < 1e-4));
    // Groups cover the children of their faces.
    let full = head();
    let sf = full.catmull_clark(1);
    assert_eq!(sf.group("eye_l").unwrap().faces.len(), 280);
    assert_eq!(sf.groups.last().unwrap().faces.end, sf.faces.len());
    // UVs: original UVs unchanged (linear, face-varying).
    assert_eq!(&s.uvs[..m.uvs.len()], &m.uvs[..]);

    let t = Instant::now();
    let s2 = m.catmull_clark(2);
    println!("catmull_clark(2) on head: {:?}", t.elapsed());
    assert_eq!(s2.faces.len(), 16 * m.faces.len());
    assert_eq!(euler(&s2), euler(&m));
}

#[test]
fn triangulate_and_tangents() {
    let m = head();
    let mut tm = m.triangulate();
    assert_eq!(tm.triangle_count(), 2 * m.faces.len());
    assert!(tm.vertex_count() >= m.positions.len());
    let t = Instant::now();
    tm.generate_tangents().unwrap();
    println!("tangents: {} vertices, {:?}", tm.vertex_count(), t.elapsed());
    let tangents = tm.tangents.as_ref().unwrap();
    assert_eq!(tangents.len(), tm.vertex_count());
    for (t, n) in tangents.iter().zip(&tm.normals) {
        assert!((t.truncate().length() - 1.0).abs() < 1e-3, "{t:?}");
        assert!(t.truncate().dot(*n).abs() < 1e-3, "{t:?} {n:?}");
        assert!(t.w == 1.0 || t.w == -1.0);
    }
    assert!(tm.indices.iter().all(|&i| (i as usize) < tm.vertex_count()));

    // Subdivided mesh too.
    let mut ts = m.catmull_clark(1).triangulate();
    ts.generate_tangents().unwrap();
    assert!(ts.tangents.unwrap().iter().all(|t| t.is_finite()));
}

fn write(dir: &tempfile::TempDir, name: &str, text: &str) -> PathBuf {
    let p = dir.path().join(name);
    std::fs::write(&p, text).expect("write temp file");
    p
}

fn parse_err(e: MeshError) -> (usize, usize, String) {
    match e {
        MeshError::Parse(e) => (e.line.unwrap_or(0), e.column.unwrap_or(0), e.message),
        other => panic!("expected parse error, got {other}"),
    }
}

#[test]
fn obj_errors_name_line_and_column() {
    let dir = tempfile::tempdir().unwrap();
    let p = write(&dir, "bad_index.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 4\n");
    let e = load_obj(&p, 1.0).unwrap_err();
    assert!(e.to_string().contains("bad_index.obj:4:7"), "{e}");
    assert_eq!(parse_err(e).0, 4);

    let p = write(&dir, "nan.obj", "# comment\nv 0 0 0\nv 1 abc 0\n");
    let (line, col, msg) = parse_err(load_obj(&p, 1.0).unwrap_err());
    assert_eq!((line, col), (3, 5), "{msg}");
    assert!(msg.contains("abc"));

    let p = write(&dir, "vt.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nf 1/1 2/2 3/1\n");
    let (line, col, _) = parse_err(load_obj(&p, 1.0).unwrap_err());
    assert_eq!((line, col), (5, 9));

    let p = write(&dir, "zero.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 0 1 2\n");
    assert_eq!(parse_err(load_obj(&p, 1.0).unwrap_err()).1, 3);

    let p = write(&dir, "two.obj", "v 0 0 0\nv 1 0 0\nf 1 2\n");
    assert_eq!(parse_err(load_obj(&p, 1.0).unwrap_err()).0, 3);

    let e = load_obj(dir.path().join("missing.obj"), 1.0).unwrap_err();
    assert!(matches!(e, MeshError::Io { .. }), "{e}");
    assert!(e.to_string().contains("missing.obj"));

    assert!(matches!(load_obj(head_path(), f32::NAN), Err(MeshError::InvalidScale(_))));
    assert!(matches!(load_obj(head_path(), 0.0), Err(MeshError::InvalidScale(_))));
}

#[test]
fn obj_polygons_groups_and_degenerate_faces() {
    let dir = tempfile::tempdir().unwrap();
    // A pentagon, a degenerate (zero-area) triangle, no normals, groups and materials.
    let src = "o thing\ng a\nusemtl m1\nv 0 0 0\nv 1 0 0\nv 1.5 1 0\nv 0.5 1.5 0\nv -0.5 1 0\n\
               vt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\nvt 0.5 0.5\n\
               f 1/1 2/2 3/3 4/4 5/5\ng b\nusemtl m2\nf 1/1 1/1 1/1\nf 1/1 2/2 2/2\n";
    let p = write(&dir, "poly.obj", src);
    let m = load_obj(&p, 25.4).unwrap();
    assert_eq!(m.faces.len(), 3);
    assert_eq!(m.faces[0].corners.len(), 5);
    let names: Vec<_> = m.groups.iter().map(|g| (g.name.as_str(), g.material.as_deref())).collect();
    assert_eq!(names, [("a", Some("m1")), ("b", Some("m2"))]);
    assert!(m.normals.iter().all(|n| n.is_finite() && (n.length() - 1.0).abs() < 1e-5));
    assert!((m.bounds().unwrap().size().x - 2.0 * 25.4).abs() < 1e-3);
    let s = m.catmull_clark(2);
    assert!(s.positions.iter().all(|p| p.is_finite()));
    assert!(s.normals.iter().all(|n| n.is_finite()));
    let mut t = s.triangulate();
    t.generate_tangents().unwrap();
    assert!(t.tangents.unwrap().iter().all(|t| t.is_finite() && (t.truncate().length() - 1.0).abs() < 1e-3));
}

/// A textured unit quad (two triangles) in a .gltf with a base64 data-URI buffer,
/// under a node that scales by 2 and translates by (0, 0, 1).
fn quad_gltf(with_uvs: bool) -> String {
    let mut bytes = Vec::new();
    for p in [[0.0f32, 0.0, 0.0], [1.0, 0.0, 0.0], [1.0, 1.0, 0.0], [0.0, 1.0, 0.0]] {
        bytes.extend(p.iter().flat_map(|v| v.to_le_bytes()));
    }
    for uv in [[0.0f32, 1.0], [1.0, 1.0], [1.0, 0.0], [0.0, 0.0]] {
        bytes.extend(uv.iter().flat_map(|v| v.to_le_bytes()));
    }
    for i in [0u16, 1, 2, 0, 2, 3] {
        bytes.extend(i.to_le_bytes());
    }
    let b64 = base64(&bytes);
    let texcoord = if with_uvs { r#", "TEXCOORD_0": 1"# } else { "" };
    format!(
        r#"{{
  "asset": {{"version": "2.0"}},
  "scene": 0,
  "scenes": [{{"nodes": [0]}}],
  "nodes": [{{"mesh": 0, "scale": [2, 2, 2], "translation": [0, 0, 1]}}],
  "meshes": [{{"name": "quad", "primitives": [{{"attributes": {{"POSITION": 0{texcoord}}}, "indices": 2}}]}}],
  "buffers": [{{"byteLength": {len}, "uri": "data:application/octet-stream;base64,{b64}"}}],
  "bufferViews": [
    {{"buffer": 0, "byteOffset": 0, "byteLength": 48}},
    {{"buffer": 0, "byteOffset": 48, "byteLength": 32}},
    {{"buffer": 0, "byteOffset": 80, "byteLength": 12}}
  ],
  "accessors": [
    {{"bufferView": 0, "componentType": 5126, "count": 4, "type": "VEC3", "min": [0, 0, 0], "max": [1, 1, 0]}},
    {{"bufferView": 1, "componentType": 5126, "count": 4, "type": "VEC2"}},
    {{"bufferView": 2, "componentType": 5123, "count": 6, "type": "SCALAR"}}
  ]
}}"#,
        len = bytes.len()
    )
}

fn base64(data: &[u8]) -> String {
    const T: &[u8; 64] = b"ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    let mut s = String::new();
    for chunk in data.chunks(3) {
        let b = [chunk[0], *chunk.get(1).unwrap_or(&0), *chunk.get(2).unwrap_or(&0)];
        let n = (u32::from(b[0]) << 16) | (u32::from(b[1]) << 8) | u32::from(b[2]);
        for i in 0..4 {
            if i <= chunk.len() {
                s.push(T[(n >> (18 - 6 * i)) as usize & 63] as char);
            } else {
                s.push('=');
            }
        }
    }
    s
}

#[test]
fn gltf_synthetic_quad() {
    let dir = tempfile::tempdir().unwrap();
    let p = write(&dir, "quad.gltf", &quad_gltf(true));
    let m = load_gltf(&p, 10.0).unwrap();
    assert_eq!(m.faces.len(), 2);
    assert_eq!(m.positions.len(), 4);
    assert_eq!(m.uvs.len(), 4);
    let b = m.bounds().unwrap();
    assert!((b.min - Vec3::new(0.0, 0.0, 10.0)).length() < 1e-4, "{b:?}");
    assert!((b.max - Vec3::new(20.0, 20.0, 10.0)).length() < 1e-4, "{b:?}");
    assert_eq!(m.groups[0].name, "quad");
    // Normals computed (none in file): +Z.
    assert!(m.normals.iter().all(|n| (*n - Vec3::Z).length() < 1e-5));
    let mut t = m.triangulate();
    t.generate_tangents().unwrap();
    let tan = t.tangents.unwrap();
    // U increases along +X.
    assert!(tan.iter().all(|t| (t.truncate() - Vec3::X).length() < 1e-4), "{tan:?}");

    let p = write(&dir, "nouv.gltf", &quad_gltf(false));
    assert!(matches!(load_gltf(&p, 1.0), Err(MeshError::MissingUvs { .. })));
    let p = write(&dir, "junk.gltf", "{ not json");
    assert!(matches!(load_gltf(&p, 1.0), Err(MeshError::Gltf { .. })));
}

#[test]
fn gltf_scanned_head_if_available() {
    let Some(path) = std::env::var_os("ROUGE_SCAN_HEAD") else {
        println!("skipping: set ROUGE_SCAN_HEAD to a .glb scanned head to run this test");
        return;
    };
    // The scan is in model units, not metric; the scale is declared, not guessed from its size.
    // Lee Perry-Smith's head is about 8.5 units wide, so ~25 mm per unit. Override with
    // ROUGE_SCAN_SCALE_TO_MM for another scan.
    let scale: f32 = std::env::var("ROUGE_SCAN_SCALE_TO_MM").ok().and_then(|s| s.parse().ok()).unwrap_or(25.0);
    let t = Instant::now();
    let m = load_gltf(&path, scale).unwrap();
    println!("loaded {} faces, {} positions in {:?}", m.faces.len(), m.positions.len(), t.elapsed());
    assert!(!m.uvs.is_empty());
    let size = m.bounds().unwrap().size();
    println!("scan size {size:?} mm (scale_to_mm {scale})");
    assert!((150.0..400.0).contains(&size.max_element()), "{size:?}");
    assert!(size.min_element() > 50.0, "{size:?}");
    let mut tm = m.triangulate();
    tm.generate_tangents().unwrap();
    assert!(tm.tangents.unwrap().iter().all(|t| t.is_finite()));
    let t = Instant::now();
    let s = m.catmull_clark(1);
    println!("catmull_clark(1) on scan: {:?}", t.elapsed());
    assert_eq!(s.faces.len(), 3 * m.faces.len());
    assert!(s.positions.iter().all(|p| p.is_finite()));
}

/// Issue 30: malformed glTF files panicked (exit 101) inside the gltf crate, looped for ever, or
/// took half a minute; each is now an error that names the file and the fault.
#[test]
fn malformed_gltf_files_are_errors_not_panics_or_hangs() {
    let dir = tempfile::tempdir().unwrap();
    let good: serde_json::Value = serde_json::from_str(&quad_gltf(true)).unwrap();
    type Breakage = fn(&mut serde_json::Value);
    let cases: [(&str, Breakage, &str); 5] = [
        // POSITION names an accessor that does not exist (gltf-json's validation indexed it).
        ("missing.gltf", |d| d["meshes"][0]["primitives"][0]["attributes"]["POSITION"] = 99.into(), "accessor 99"),
        ("none.gltf", |d| d["accessors"] = serde_json::json!([]), "there are 0"),
        // Indices on a float VEC3 accessor (the reader's `unreachable!`).
        ("float_indices.gltf", |d| d["meshes"][0]["primitives"][0]["indices"] = 0.into(), "indices accessor 0"),
        // A node that is its own grandchild.
        ("cycle.gltf", |d| d["nodes"] = serde_json::json!([{"mesh": 0, "children": [1]}, {"children": [0]}]), "cycle"),
        // One node placed 100,000 times.
        ("many.gltf", |d| d["scenes"][0]["nodes"] = serde_json::json!(vec![0; 100_000]), "more than 10000 nodes"),
    ];
    for (name, break_it, says) in cases {
        let mut doc = good.clone();
        break_it(&mut doc);
        let p = write(&dir, name, &doc.to_string());
        let e = load_gltf(&p, 1.0).expect_err(name).to_string();
        assert!(e.contains(name) && e.contains(says), "{name}: {e}");
    }
}
