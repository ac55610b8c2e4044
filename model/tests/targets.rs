//! The default head's morph targets: parsing, what each target moves, presets, the subdivision
//! plan that deforming frames reuse.

use std::collections::{BTreeMap, HashMap, HashSet};
use std::path::Path;

use glam::Vec3;
use rouge_model::look::Region;
use rouge_model::mesh::deform::SubdivisionPlan;
use rouge_model::mesh::targets::{EXPRESSION_PRESETS, FacePose, TargetError, TargetSet, expression_cycle};
use rouge_model::mesh::{Mesh, default_head, load_mesh};

fn targets() -> &'static TargetSet {
    TargetSet::default_head().expect("embedded targets")
}

fn pose(expression: &[(&str, f32)], shape: &[(&str, f32)]) -> FacePose {
    let map = |v: &[(&str, f32)]| v.iter().map(|&(n, w)| (n.to_string(), w)).collect::<BTreeMap<_, _>>();
    FacePose { expression: map(expression), shape: map(shape) }
}

fn deformed(p: &FacePose) -> Vec<Vec3> {
    let mut pos = default_head().expect("head").positions;
    targets().apply(p, &mut pos).expect("apply");
    pos
}

#[test]
fn the_file_holds_52_units_and_the_shapes_for_the_head() {
    let t = targets();
    let head = default_head().expect("head");
    assert_eq!(t.vertex_count, head.positions.len());
    assert_eq!(t.expressions.len(), 52);
    for unit in ["jawOpen", "mouthSmileLeft", "eyeBlinkRight", "browInnerUp", "cheekPuff"] {
        assert!(t.expression(unit).is_some_and(|o| !o.vertices.is_empty()), "{unit}");
    }
    assert!(t.expression("tongueOut").is_some_and(|o| !o.vertices.is_empty()), "tongueOut moves the tongue");
    assert_eq!(t.shapes.len(), 32);
    assert_eq!(t.shape("age").expect("age").range(), (-1.0, 1.0));
    assert_eq!(t.shape("head-oval").expect("oval").range(), (0.0, 1.0));
    for p in EXPRESSION_PRESETS {
        for (u, _) in p.units {
            assert!(t.expression(u).is_some(), "preset {} names unknown unit {u}", p.name);
        }
    }
}

#[test]
fn zero_weights_give_the_neutral_head_bit_for_bit() {
    let base = default_head().expect("head").positions;
    let all_units: Vec<(&str, f32)> = targets().expressions.iter().map(|(n, _)| (n.as_str(), 0.0)).collect();
    let all_shapes: Vec<(&str, f32)> = targets().shapes.iter().map(|s| (s.name.as_str(), 0.0)).collect();
    let p = pose(&all_units, &all_shapes);
    assert!(p.is_neutral());
    let got = deformed(&p);
    assert!(got.iter().zip(&base).all(|(a, b)| a.to_array().map(f32::to_bits) == b.to_array().map(f32::to_bits)));
}

#[test]
fn each_target_moves_only_the_vertices_it_names() {
    let base = default_head().expect("head").positions;
    for (name, offsets) in &targets().expressions {
        let got = deformed(&pose(&[(name, 1.0)], &[]));
        let named: HashSet<u32> = offsets.vertices.iter().copied().collect();
        for (v, (a, b)) in got.iter().zip(&base).enumerate() {
            if !named.contains(&(v as u32)) {
                assert_eq!(a, b, "{name} moved vertex {v}, which it does not name");
            }
        }
        for (&v, &d) in offsets.vertices.iter().zip(&offsets.offsets_mm) {
            assert!((got[v as usize] - base[v as usize] - d).length() < 1e-4, "{name} vertex {v}");
        }
    }
}

#[test]
fn weights_add_linearly() {
    let base = default_head().expect("head").positions;
    let one = deformed(&pose(&[("jawOpen", 1.0)], &[("age", 1.0)]));
    let part = deformed(&pose(&[("jawOpen", 0.3)], &[("age", 0.3)]));
    let smile = deformed(&pose(&[("mouthSmileLeft", 0.5)], &[]));
    let both = deformed(&pose(&[("jawOpen", 0.3), ("mouthSmileLeft", 0.5)], &[("age", 0.3)]));
    for v in 0..base.len() {
        assert!((part[v] - base[v] - 0.3 * (one[v] - base[v])).length() < 1e-4, "scaling at {v}");
        let sum = base[v] + (part[v] - base[v]) + (smile[v] - base[v]);
        assert!((both[v] - sum).length() < 1e-4, "sum at {v}");
    }
    // A two-sided shape at -w applies its decr side.
    let young = deformed(&pose(&[], &[("age", -1.0)]));
    let old = deformed(&pose(&[], &[("age", 1.0)]));
    assert!(young.iter().zip(&old).any(|(a, b)| (*a - *b).length() > 1.0));
}

/// Base vertices with the region's mask above one half at their UV (the first corner that uses them).
fn region_vertices(head: &Mesh, region: Region) -> Vec<usize> {
    let mask = region.mask();
    let mut uv_of = vec![None; head.positions.len()];
    for f in &head.faces {
        for c in &f.corners {
            uv_of[c.position as usize].get_or_insert(head.uvs[c.uv as usize]);
        }
    }
    (0..head.positions.len()).filter(|&v| uv_of[v].is_some_and(|uv| mask.sample_uv(uv.x, uv.y) > 0.5)).collect()
}

fn centroid(p: &[Vec3], vs: &[usize]) -> Vec3 {
    vs.iter().map(|&v| p[v]).sum::<Vec3>() / vs.len() as f32
}

#[test]
fn jaw_open_moves_the_lips_apart() {
    let head = default_head().expect("head");
    let lips = region_vertices(&head, Region::Lips);
    assert!(lips.len() > 50, "{} lip vertices", lips.len());
    let mid = centroid(&head.positions, &lips).y;
    let (upper, lower): (Vec<usize>, Vec<usize>) = lips.iter().partition(|&&v| head.positions[v].y > mid);
    let gap = |p: &[Vec3]| centroid(p, &upper).y - centroid(p, &lower).y;
    let open = deformed(&pose(&[("jawOpen", 1.0)], &[]));
    let (before, after) = (gap(&head.positions), gap(&open));
    assert!(after > before + 8.0, "lip centroids {before:.1} mm apart, {after:.1} mm with the jaw open");
}

#[test]
fn eye_blink_left_closes_the_left_eye_only() {
    let head = default_head().expect("head");
    let lids = region_vertices(&head, Region::Eyelids);
    let (left, right): (Vec<usize>, Vec<usize>) = lids.iter().partition(|&&v| head.positions[v].x > 0.0);
    let blink = deformed(&pose(&[("eyeBlinkLeft", 1.0)], &[]));
    let drop = |vs: &[usize]| centroid(&head.positions, vs).y - centroid(&blink, vs).y;
    assert!(drop(&left) > 2.0, "left lid centroid drops {:.2} mm", drop(&left));
    assert_eq!(drop(&right), 0.0);
    // Within 15 mm of each eyeball's centre (the lid margins; the file's header gives the
    // centres): the left lid travels over 10 mm, nothing of the right eye moves.
    let near = |x: f32| {
        let c = Vec3::new(x, 0.015, 79.535);
        head.positions.iter().zip(&blink).filter(move |(a, _)| a.distance(c) < 15.0).map(|(a, b)| a.distance(*b))
    };
    let (left_max, right_max) = (near(30.775).fold(0.0, f32::max), near(-30.775).fold(0.0, f32::max));
    assert!(right_max == 0.0 && left_max > 10.0, "right side moves {right_max} mm, left {left_max} mm");
}

#[test]
fn shapes_keep_the_mesh_whole_and_the_uvs() {
    let head = default_head().expect("head");
    for s in &targets().shapes {
        let (lo, hi) = s.range();
        for w in [lo, hi] {
            let mut m = head.clone();
            targets().apply(&pose(&[], &[(&s.name, w)]), &mut m.positions).expect("apply");
            assert_eq!((m.faces.len(), &m.uvs), (head.faces.len(), &head.uvs));
            for f in &m.faces {
                let p: Vec<Vec3> = f.corners.iter().map(|c| m.positions[c.position as usize]).collect();
                let area = (p[1] - p[0]).cross(p[2] - p[0]).length() + (p[2] - p[0]).cross(p[3] - p[0]).length();
                assert!(area.is_finite() && area > 1e-4, "{}={w}: a face collapses", s.name);
            }
        }
    }
}

#[test]
fn unknown_names_and_bad_weights_are_named() {
    let t = targets();
    let err = t.resolve(&pose(&[("jawOpn", 0.5)], &[])).expect_err("typo");
    match &err {
        TargetError::Unknown { name, near, .. } => {
            assert_eq!(name, "jawOpn");
            assert!(near.iter().any(|n| n == "jawOpen"), "{near:?}");
        }
        e => panic!("{e}"),
    }
    assert!(err.to_string().contains("--expression") && err.to_string().contains("jawOpen"), "{err}");
    let err = t.resolve(&pose(&[], &[("nose-hmp", 0.5)])).expect_err("typo").to_string();
    assert!(err.contains("--shape") && err.contains("nose-hump"), "{err}");
    let err = t.resolve(&pose(&[("smile", 1.5)], &[])).expect_err("range").to_string();
    assert!(err.contains("smile=1.5") && err.contains("0 to 1"), "{err}");
    let err = t.resolve(&pose(&[], &[("head-oval", -0.5)])).expect_err("one-sided").to_string();
    assert!(err.contains("head-oval=-0.5"), "{err}");
    let err = FacePose::parse_weights("smile=0.8,=0.3", "--expression").expect_err("syntax").to_string();
    assert!(err.contains("--expression") && err.contains("`=0.3`"), "{err}");
    let bare = FacePose::parse_weights("blink, jawOpen=0.25", "--expression").expect("bare name");
    assert_eq!((bare["blink"], bare["jawOpen"]), (1.0, 0.25));
    let err = FacePose::parse_weights("smile=lots", "--expression").expect_err("number").to_string();
    assert!(err.contains("`lots`"), "{err}");
    let mut few = default_head().expect("head").positions;
    few.pop();
    assert!(matches!(t.apply(&FacePose::preset("smile"), &mut few), Err(TargetError::WrongMesh { .. })));
}

#[test]
fn presets_expand_and_saturate() {
    let t = targets();
    let (units, _) = t.resolve(&pose(&[("smile", 0.8), ("mouthSmileLeft", 0.5)], &[])).expect("resolve");
    assert_eq!(units["mouthSmileLeft"], 1.0, "0.8 + 0.5 saturates");
    assert!((units["mouthSmileRight"] - 0.8).abs() < 1e-6);
    assert!(FacePose::preset("neutral").is_neutral());
    let cycle_start = expression_cycle(0.0);
    assert!(cycle_start.is_empty(), "{cycle_start:?}");
    let mid = expression_cycle(1.5);
    assert_eq!(mid.len(), 2);
    assert!((mid["smile"] - 0.5).abs() < 1e-6 && (mid["blink"] - 0.5).abs() < 1e-6);
    assert_eq!(expression_cycle(5.0), expression_cycle(0.0));
}

#[test]
fn parse_errors_name_line_and_column() {
    let bad = "# c\nvertices 3\nexpression a 2\n0 1 2 3\n1 4 x 6\n";
    let err = TargetSet::parse(bad, Path::new("t.txt")).expect_err("bad").to_string();
    assert!(err.starts_with("t.txt:5:5:"), "{err}");
    let short = "vertices 3\nexpression a 2\n0 1 2 3\n";
    assert!(TargetSet::parse(short, Path::new("t.txt")).expect_err("short").to_string().contains("t.txt:2:"));
    let range = "vertices 3\nexpression a 1\n3 1 2 3\n";
    assert!(TargetSet::parse(range, Path::new("t.txt")).expect_err("range").to_string().contains("t.txt:3:1"));
}

#[test]
fn the_subdivision_plan_matches_a_fresh_subdivision() {
    let head = default_head().expect("head");
    for levels in [0, 1] {
        let plan = SubdivisionPlan::new(&head, levels);
        assert_eq!(plan.rest(), &load_mesh(None, 1.0, levels).expect("load"), "rest at {levels}");
    }
    let plan = SubdivisionPlan::new(&head, 1);
    assert_eq!(&plan.mesh(&head.positions), plan.rest(), "the rest positions give the rest mesh bit for bit");
    let moved = deformed(&pose(&[("jawOpen", 0.7), ("smile", 0.5)], &[("age", 0.4)]));
    let mut fresh = head.clone();
    fresh.positions = moved.clone();
    let fresh = fresh.catmull_clark(1);
    let got = plan.mesh(&moved);
    let bits = |p: Vec3| p.to_array().map(f32::to_bits);
    let known: HashSet<[u32; 3]> = fresh.positions.iter().map(|&p| bits(p)).collect();
    assert!(got.positions.iter().all(|&p| known.contains(&bits(p))), "positions are the fresh subdivision's");
    assert_eq!((got.indices.len(), &got.uvs), (plan.rest().indices.len(), &plan.rest().uvs));
    assert!(got.normals.iter().all(|n| (n.length() - 1.0).abs() < 1e-5));
}

/// The planned update runs its rules in gather form on several threads: on any number of them
/// each vertex is the serial fresh subdivision's (position and normal bit for bit), at the level
/// the app animates. (A fresh subdivision triangulates the posed quads, whose diagonals can
/// differ from the plan's rest-pose ones, so vertices are matched by position.)
#[test]
fn the_threaded_plan_is_the_fresh_subdivision_bit_for_bit() {
    let head = default_head().expect("head");
    let moved = deformed(&pose(&[("mouthSmileLeft", 0.9), ("eyeBlinkRight", 0.6), ("jawOpen", 0.3)], &[]));
    let plan = SubdivisionPlan::new(&head, 2);
    let mut fresh = head.clone();
    fresh.positions = moved.clone();
    let fresh = fresh.catmull_clark(2);
    let bits = |p: Vec3| p.to_array().map(f32::to_bits);
    let mut normals_at: HashMap<[u32; 3], HashSet<[u32; 3]>> = HashMap::new();
    for (p, n) in fresh.positions.iter().zip(&fresh.normals) {
        normals_at.entry(bits(*p)).or_default().insert(bits(n.try_normalize().unwrap_or(Vec3::Z)));
    }
    let mut first: Option<rouge_model::mesh::TriangleMesh> = None;
    for threads in [1, 3, 8] {
        let mut got = plan.rest().clone();
        plan.update_on(&moved, &mut got, threads);
        for (p, n) in got.positions.iter().zip(&got.normals) {
            let normals = normals_at.get(&bits(*p)).expect("a position of the fresh subdivision");
            assert!(normals.contains(&bits(*n)), "the normal at {p} on {threads} threads");
        }
        if let Some(f) = &first {
            assert!(f == &got, "1 and {threads} threads differ");
        }
        first.get_or_insert(got);
    }
}

#[test]
fn the_face_is_saved_with_the_project() {
    use rouge_model::document::{Document, FACE_FILE, LOOK_FILE};
    let dir = tempfile::tempdir().expect("tempdir");
    let mut doc = Document::default_project();
    assert!(!doc.is_modified());
    doc.face = pose(&[("smile", 0.8), ("jawOpen", 0.3)], &[("age", -0.4), ("head-oval", 1.0)]);
    assert!(doc.is_modified(), "a new face is unsaved work");
    doc.save_project(dir.path()).expect("save");
    assert!(!doc.is_modified());
    let back = Document::open_project(dir.path()).expect("open");
    assert_eq!(back.face, doc.face);
    assert!(!back.is_modified());
    // The face file is the one `look.json` names, named by its contents.
    let look_path = dir.path().join(LOOK_FILE);
    let (_, part) =
        rouge_model::look::Look::from_project_json(&std::fs::read_to_string(&look_path).expect("read"), &look_path)
            .expect("look.json");
    let path = dir.path().join(part.expect("a project part").face);
    assert!(!dir.path().join(FACE_FILE).exists(), "face.json is the name of projects saved before");
    // A project saved before faces (look.json without a project part, no face.json) opens with
    // the neutral head; one saved before content-named faces reads face.json.
    let look = rouge_model::look::Look::load(&look_path).expect("look");
    std::fs::write(&look_path, look.to_json()).expect("an old look.json");
    assert!(Document::open_project(dir.path()).expect("old project").face.is_neutral());
    std::fs::copy(&path, dir.path().join(FACE_FILE)).expect("an old face.json");
    assert_eq!(Document::open_project(dir.path()).expect("old project").face, doc.face);
    // A bad face file is named, with the line or the unknown target.
    let path = dir.path().join(FACE_FILE);
    std::fs::write(&path, "{\"format\": \"rouge-face\", \"version\": 1, \"expression\": {\"smle\": 1}}").expect("w");
    let err = Document::open_project(dir.path()).expect_err("unknown").to_string();
    assert!(err.contains(FACE_FILE) && err.contains("smile"), "{err}");
    // In the file's words, not the command line's (it said `--expression`).
    assert!(err.contains("`expression`") && !err.contains("--"), "{err}");
    std::fs::write(&path, "{\"format\": \"rouge-face\", \"version\": 1, \"shape\": {\"age\": 7}}").expect("w");
    let err = Document::open_project(dir.path()).expect_err("range").to_string();
    assert!(err.contains("`shape`: age=7") && !err.contains("--"), "{err}");
    std::fs::write(&path, "{\"format\": \"rouge-face\",\n \"version\": 2}").expect("w");
    let err = Document::open_project(dir.path()).expect_err("version").to_string();
    assert!(err.contains("version 2"), "{err}");
    std::fs::write(&path, "{\"format\": \"rouge-face\",\n \"version\": 1, \"shape\": {\"age\": \"old\"}}").expect("w");
    let err = Document::open_project(dir.path()).expect_err("syntax").to_string();
    assert!(err.contains("line 2"), "{err}");
    assert!(dir.path().join(LOOK_FILE).is_file());
}
