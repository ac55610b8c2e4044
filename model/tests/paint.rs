//! 3D painting of thickness maps on the default head: coverage, brush reach in 3D (across UV
//! seams, mirrored or not), convergence, erasing, smoothing, gap-free strokes, brush validation,
//! and the speed of building a surface map and of one dab (printed, never asserted).

use std::time::Instant;

use glam::{Vec2, Vec3};
use rouge_model::TriangleMesh;
use rouge_model::look::ThicknessMap;
use rouge_model::mesh::load_mesh;
use rouge_model::paint::{Brush, BrushMode, StrokeSpacer, SurfaceMap, TexelRect, apply_dab, apply_dab_split, stroke};

use crate::common;
use common::{SIZE, head};

/// Texel coordinates (x, y), row 0 at the top.
type Texel = (u32, u32);

fn blank(surface: &SurfaceMap) -> ThicknessMap {
    ThicknessMap {
        width: surface.width,
        height: surface.height,
        mm: vec![0.0; surface.width as usize * surface.height as usize],
    }
}

/// Every covered texel: (x, y, position).
fn covered_texels(surface: &SurfaceMap) -> Vec<(u32, u32, Vec3)> {
    let mut out = Vec::new();
    for y in 0..surface.height {
        for x in 0..surface.width {
            if let Some(p) = surface.position(x, y) {
                out.push((x, y, p));
            }
        }
    }
    out
}

/// A point on the left cheek (x > 0 is the head's left; the face looks toward +Z).
fn left_cheek(surface: &SurfaceMap) -> Vec3 {
    let p = surface.nearest_on_surface(Vec3::new(45.0, -30.0, 100.0), 60.0).expect("a cheek");
    assert!(p.x > 30.0 && p.z > 50.0, "cheek point {p} is not on the left cheek");
    p
}

/// The texels at the UVs of the eyeballs' vertices (the head's eye groups): the skin's surface
/// map leaves them uncovered, so paint never reaches them.
fn eye_texels() -> Vec<Texel> {
    let full = rouge_model::mesh::load_mesh(None, 1.0, 1).expect("default head");
    let eyes = full.only(|g| g.is_eye());
    assert!(!eyes.indices.is_empty(), "the head has eyes");
    eyes.indices
        .iter()
        .map(|&v| full.uvs[v as usize])
        .map(|uv| (((uv.x * SIZE as f32) as u32).min(SIZE - 1), (((1.0 - uv.y) * SIZE as f32) as u32).min(SIZE - 1)))
        .collect()
}

fn changed(before: &ThicknessMap, after: &ThicknessMap) -> Vec<(u32, u32)> {
    let w = before.width as usize;
    (0..before.mm.len()).filter(|&i| before.mm[i] != after.mm[i]).map(|i| ((i % w) as u32, (i / w) as u32)).collect()
}

fn contains(rect: TexelRect, x: u32, y: u32) -> bool {
    x >= rect.x0 && x < rect.x1 && y >= rect.y0 && y < rect.y1
}

#[test]
fn a_single_quad_maps_texel_centres_exactly() {
    // Positions (100·u, 100·v, 0): a texel's position gives back its UV centre, v up.
    let uv = [Vec2::new(0.0, 0.0), Vec2::new(1.0, 0.0), Vec2::new(1.0, 1.0), Vec2::new(0.0, 1.0)];
    let mesh = TriangleMesh {
        positions: uv.iter().map(|t| Vec3::new(100.0 * t.x, 100.0 * t.y, 0.0)).collect(),
        normals: vec![Vec3::Z; 4],
        uvs: uv.to_vec(),
        tangents: None,
        indices: vec![0, 1, 2, 0, 2, 3],
        groups: Vec::new(),
        strands: None,
    };
    let (w, h) = (64, 32);
    let surface = SurfaceMap::build(&mesh, w, h);
    assert_eq!(surface.covered(), (w * h) as usize);
    assert!((surface.mirror_x() - 50.0).abs() < 1e-6);
    for (x, y) in [(0, 0), (63, 0), (0, 31), (17, 9), (63, 31)] {
        let p = surface.position(x, y).expect("covered");
        let want = Vec3::new(100.0 * (x as f32 + 0.5) / w as f32, 100.0 * (1.0 - (y as f32 + 0.5) / h as f32), 0.0);
        assert!(p.distance(want) < 1e-3, "texel ({x}, {y}) at {p}, want {want}");
    }
    assert_eq!(surface.position(w, 0), None);
    // An empty mesh or size covers nothing and paints nothing.
    let none = SurfaceMap::build(&TriangleMesh::default(), 16, 16);
    assert_eq!(none.covered(), 0);
    assert_eq!(none.nearest_on_surface(Vec3::ZERO, 1000.0), None);
    let mut map = blank(&none);
    assert!(apply_dab(&mut map, &none, &Brush::default(), Vec3::ZERO).is_empty());
    assert_eq!(SurfaceMap::build(&mesh, 0, 0).covered(), 0);
}

#[test]
fn the_head_covers_its_uv_islands_and_positions_match_the_mesh() {
    let (mesh, surface) = head();
    let share = surface.covered() as f64 / f64::from(SIZE * SIZE);
    println!(
        "covered {} of {}² texels ({:.1} %); mirror plane x = {}",
        surface.covered(),
        SIZE,
        100.0 * share,
        surface.mirror_x()
    );
    // hm08 gives the head and neck about 21 % of the UV square (the rest is the body's).
    assert!(share > 0.18 && share < 0.5, "coverage {share}");
    assert!(surface.mirror_x().abs() < 1e-3, "mirror plane at x = {}", surface.mirror_x());
    // The texel nearest each triangle's UV centroid, where its centre lies inside the triangle,
    // holds the triangle's barycentric interpolation of its corners.
    let (mut worst, mut checked) = (0.0f32, 0);
    for t in mesh.indices.chunks_exact(3).step_by(7) {
        let [a, b, c] = [t[0], t[1], t[2]].map(|i| i as usize);
        let px = |i: usize| Vec2::new(mesh.uvs[i].x, 1.0 - mesh.uvs[i].y) * SIZE as f32;
        let centroid = (px(a) + px(b) + px(c)) / 3.0;
        let (x, y) = (centroid.x.floor(), centroid.y.floor());
        let q = Vec2::new(x + 0.5, y + 0.5);
        let area = (px(b) - px(a)).perp_dot(px(c) - px(a));
        let la = (px(c) - px(b)).perp_dot(q - px(b)) / area;
        let lb = (px(a) - px(c)).perp_dot(q - px(c)) / area;
        let lc = 1.0 - la - lb;
        if la.min(lb).min(lc) < 0.01 {
            continue;
        }
        let want = mesh.positions[a] * la + mesh.positions[b] * lb + mesh.positions[c] * lc;
        let p = surface.position(x as u32, y as u32).expect("triangle interior covered");
        worst = worst.max(p.distance(want));
        checked += 1;
    }
    println!("{checked} triangle interiors: worst distance from the interpolated position {worst:.2e} mm");
    assert!(checked > 1000 && worst < 1e-3, "{worst} mm over {checked} triangles");
}

#[test]
fn nearest_on_surface_matches_brute_force() {
    let (_, surface) = head();
    let texels = covered_texels(surface);
    let probes = [
        Vec3::new(45.0, -30.0, 100.0),
        Vec3::new(0.0, 0.0, 0.0),
        Vec3::new(-70.0, 10.0, 20.0),
        Vec3::new(3.0, 130.0, -10.0),
    ];
    for p in probes {
        let want = texels.iter().map(|t| t.2.distance(p)).fold(f32::INFINITY, f32::min);
        let got = surface.nearest_on_surface(p, 200.0).map(|q| q.distance(p));
        assert_eq!(got, Some(want), "nearest to {p}");
        assert_eq!(surface.nearest_on_surface(p, want * 0.99), None, "nothing within less than {want} of {p}");
    }
    assert_eq!(surface.nearest_on_surface(Vec3::splat(f32::NAN), 10.0), None);
    assert_eq!(surface.nearest_on_surface(Vec3::new(0.0, 0.0, 1000.0), 10.0), None);
}

fn dab_reach(mirror: bool) {
    let (_, surface) = head();
    let centre = left_cheek(surface);
    let brush = Brush { radius_mm: 10.0, mirror, ..Brush::default() };
    let mut map = blank(surface);
    let before = map.clone();
    let rect = apply_dab(&mut map, surface, &brush, centre);
    // The mirrored dab is centred on the surface point nearest the mirror image.
    let image = surface.nearest_on_surface(surface.mirror(centre), brush.radius_mm).expect("a mirror side");
    let changed = changed(&before, &map);
    // The split form changes the same texels and gives one rectangle per side.
    let mut again = blank(surface);
    let [this_side, other_side] = apply_dab_split(&mut again, surface, &brush, centre);
    assert_eq!(again.mm, map.mm);
    assert_eq!(this_side.union(other_side), rect);
    assert_eq!(other_side.is_empty(), !mirror);
    assert!(this_side.area() + other_side.area() < rect.area() || !mirror);
    assert!(!changed.is_empty());
    let (mut left, mut right) = (0, 0);
    for &(x, y) in &changed {
        let p = surface.position(x, y).expect("only covered texels change");
        let (d, dm) = (p.distance(centre), p.distance(image));
        assert!(contains(if d <= dm { this_side } else { other_side }, x, y));
        assert!(d < brush.radius_mm || (mirror && dm < brush.radius_mm), "texel ({x}, {y}) at {p} changed");
        assert!(contains(rect, x, y), "texel ({x}, {y}) outside {rect:?}");
        let t = map.mm[y as usize * SIZE as usize + x as usize];
        assert!(t > 0.0 && t <= brush.thickness_mm);
        if p.x > 0.0 { left += 1 } else { right += 1 }
    }
    println!("mirror {mirror}: {left} texels on the left, {right} on the right, rect {rect:?}");
    // Every covered texel well inside the brush got paint.
    for (x, y, p) in covered_texels(surface) {
        let inside =
            p.distance(centre) < 0.9 * brush.radius_mm || (mirror && p.distance(image) < 0.9 * brush.radius_mm);
        if inside {
            assert!(map.mm[y as usize * SIZE as usize + x as usize] > 0.0, "texel ({x}, {y}) at {p} missed");
        }
    }
    assert!(left > 100);
    if mirror {
        assert!(right > left / 2 && right < left * 2, "{right} texels on the mirror side, {left} on this side");
    } else {
        assert_eq!(right, 0);
    }
}

#[test]
fn a_dab_changes_only_texels_within_the_radius_and_mirrors() {
    dab_reach(true);
}

#[test]
fn a_dab_without_mirror_stays_on_its_side() {
    dab_reach(false);
}

#[test]
fn mirrored_dabs_overlapping_at_the_midline_count_once() {
    let (_, surface) = head();
    // On the bridge of the nose, 1 mm off the midplane: the dab and its image overlap.
    let centre = surface.nearest_on_surface(Vec3::new(1.0, 10.0, 120.0), 40.0).expect("the nose");
    assert!(centre.x.abs() < 3.0, "{centre}");
    let brush = Brush { radius_mm: 6.0, flow: 0.35, hardness: 1.0, mirror: true, ..Brush::default() };
    let mut map = blank(surface);
    apply_dab(&mut map, surface, &brush, centre);
    let once = brush.flow * brush.thickness_mm;
    let max = map.mm.iter().copied().fold(0.0f32, f32::max);
    // Applied twice, texels under both dabs would hold (1 − 0.65²)·target = 0.58·target.
    assert!((max - once).abs() < 1e-7, "max {max}, one dab gives {once}");
    let both_sides = covered_texels(surface)
        .into_iter()
        .filter(|&(x, y, p)| p.x < -1.5 && map.mm[(y * SIZE + x) as usize] > 0.0)
        .count();
    assert!(both_sides > 10, "{both_sides} texels painted across the midline");
}

#[test]
fn repeated_dabs_converge_to_the_target_and_never_exceed_it() {
    let (_, surface) = head();
    let centre = left_cheek(surface);
    let brush =
        Brush { radius_mm: 8.0, thickness_mm: 0.02, flow: 0.5, hardness: 0.5, mirror: false, ..Brush::default() };
    let mut map = blank(surface);
    let centre_texel = |map: &ThicknessMap| {
        covered_texels(surface)
            .into_iter()
            .min_by(|a, b| a.2.distance_squared(centre).total_cmp(&b.2.distance_squared(centre)))
            .map(|(x, y, _)| map.mm[y as usize * SIZE as usize + x as usize])
            .expect("a texel")
    };
    let mut previous = 0.0;
    for dab in 0..30 {
        apply_dab(&mut map, surface, &brush, centre);
        let t = centre_texel(&map);
        assert!(t >= previous && t <= brush.thickness_mm, "dab {dab}: {t}");
        assert!(map.mm.iter().all(|&v| (0.0..=brush.thickness_mm).contains(&v)));
        previous = t;
    }
    assert!((previous - brush.thickness_mm).abs() < 1e-6, "after 30 dabs at flow 0.5: {previous}");
    // Erase returns toward 0, never below.
    let erase = Brush { mode: BrushMode::Erase, ..brush };
    let mut previous = centre_texel(&map);
    for dab in 0..30 {
        apply_dab(&mut map, surface, &erase, centre);
        let t = centre_texel(&map);
        assert!(t <= previous && t >= 0.0, "erase dab {dab}: {t}");
        previous = t;
    }
    assert!(previous < 1e-6, "after 30 erase dabs: {previous}");
    // Painting over a thicker film brings it down to the target, not up.
    let mut thick = map.clone();
    thick.mm.iter_mut().for_each(|v| *v = 0.05);
    apply_dab(&mut thick, surface, &brush, centre);
    let t = centre_texel(&thick);
    assert!(t < 0.05 && t >= brush.thickness_mm, "{t}");
}

#[test]
fn smoothing_reduces_the_variance_of_a_noisy_patch() {
    let (_, surface) = head();
    let centre = left_cheek(surface);
    let brush = Brush { mode: BrushMode::Smooth, radius_mm: 8.0, flow: 0.8, mirror: false, ..Brush::default() };
    let mut map = blank(surface);
    // Deterministic noise in [0, 0.04] mm.
    let mut state = 0x2545_f491_u32;
    for v in &mut map.mm {
        state ^= state << 13;
        state ^= state >> 17;
        state ^= state << 5;
        *v = 0.04 * (state as f32 / u32::MAX as f32);
    }
    let patch: Vec<usize> = covered_texels(surface)
        .into_iter()
        .filter(|t| t.2.distance(centre) < 0.5 * brush.radius_mm)
        .map(|(x, y, _)| y as usize * SIZE as usize + x as usize)
        .collect();
    let stats = |map: &ThicknessMap| {
        let n = patch.len() as f64;
        let mean = patch.iter().map(|&i| f64::from(map.mm[i])).sum::<f64>() / n;
        let var = patch.iter().map(|&i| (f64::from(map.mm[i]) - mean).powi(2)).sum::<f64>() / n;
        (mean, var)
    };
    let (mean0, var0) = stats(&map);
    apply_dab(&mut map, surface, &brush, centre);
    let (mean1, var1) = stats(&map);
    println!("smooth: {} texels, mean {mean0:.5} → {mean1:.5} mm, variance {var0:.3e} → {var1:.3e}", patch.len());
    assert!(var1 < 0.2 * var0, "variance {var0} → {var1}");
    assert!((mean1 - mean0).abs() < 0.002, "mean {mean0} → {mean1}");
    // A uniform film stays exactly as it is.
    let mut flat = blank(surface);
    flat.mm.iter_mut().for_each(|v| *v = 0.02);
    let before = flat.clone();
    let rect = apply_dab(&mut flat, surface, &brush, centre);
    assert!(changed(&before, &flat).iter().all(|&(x, y)| (flat.mm[(y * SIZE + x) as usize] - 0.02).abs() < 1e-8));
    assert!(rect.area() <= (SIZE * SIZE) as usize);
}

/// Which vertices the (skin) triangles use: the other parts' vertices are kept in the mesh but
/// not painted.
fn used_vertices(mesh: &TriangleMesh) -> Vec<bool> {
    let mut used = vec![false; mesh.positions.len()];
    mesh.indices.iter().for_each(|&v| used[v as usize] = true);
    used
}

/// A UV seam on the face: two covered texels far apart in UV whose 3D positions are within 1 mm,
/// found from the mesh's vertices that share a position but not a UV.
fn seam(mesh: &TriangleMesh, surface: &SurfaceMap) -> (Texel, Texel, Vec3) {
    let texel_of = |uv: Vec2| ((uv.x * SIZE as f32) as u32, ((1.0 - uv.y) * SIZE as f32) as u32);
    let mut best: Option<(Texel, Texel, Vec3, f32)> = None;
    let used = used_vertices(mesh);
    for i in (0..mesh.positions.len()).filter(|&i| used[i]) {
        let p = mesh.positions[i];
        // On the front of the face, off the midline, away from the eyes' spheres and the lid
        // margins (centres at x = ±30.8, y = 0, z = 79.5 mm; radius 15 mm).
        if p.z < 60.0 || p.x.abs() < 10.0 || Vec3::new(30.8, 0.0, 79.5).distance(p.with_x(p.x.abs())) < 20.0 {
            continue;
        }
        for j in (i + 1..mesh.positions.len()).filter(|&j| used[j]) {
            if mesh.positions[j] != p || mesh.uvs[i].distance(mesh.uvs[j]) < 0.1 {
                continue;
            }
            // Texels near each UV, on each island, within 1 mm of the seam point.
            let near = |uv: Vec2| {
                let (cx, cy) = texel_of(uv);
                let mut found: Option<((u32, u32), f32)> = None;
                for y in cy.saturating_sub(3)..(cy + 4).min(SIZE) {
                    for x in cx.saturating_sub(3)..(cx + 4).min(SIZE) {
                        if let Some(q) = surface.position(x, y) {
                            let d = q.distance(p);
                            if d < 1.0 && found.is_none_or(|f| d < f.1) {
                                found = Some(((x, y), d));
                            }
                        }
                    }
                }
                found
            };
            if let (Some(a), Some(b)) = (near(mesh.uvs[i]), near(mesh.uvs[j])) {
                let score = p.z;
                if best.is_none_or(|b| score > b.3) {
                    best = Some((a.0, b.0, p, score));
                }
            }
        }
    }
    let (a, b, p, _) = best.expect("a UV seam on the face");
    (a, b, p)
}

#[test]
fn a_dab_across_a_uv_seam_paints_both_sides() {
    let (mesh, surface) = head();
    let (a, b, p) = seam(mesh, surface);
    let uv_distance = Vec2::new(a.0 as f32 - b.0 as f32, a.1 as f32 - b.1 as f32).length();
    println!("seam at {p}: texels {a:?} and {b:?}, {uv_distance:.0} texels apart in UV");
    assert!(uv_distance > 50.0);
    let brush = Brush { radius_mm: 4.0, mirror: false, ..Brush::default() };
    let mut map = blank(surface);
    let rect = apply_dab(&mut map, surface, &brush, p);
    for (x, y) in [a, b] {
        assert!(map.mm[(y * SIZE + x) as usize] > 0.0, "texel ({x}, {y}) on one side of the seam got no paint");
        assert!(contains(rect, x, y));
    }
    // Thanks to the dilation, bilinear sampling at the seam's UVs on either island reads the
    // full film: a flat, full-flow dab covers the island edges and the texels just outside.
    let flat = Brush { radius_mm: 5.0, flow: 1.0, hardness: 1.0, mirror: false, ..Brush::default() };
    let mut map = blank(surface);
    apply_dab(&mut map, surface, &flat, p);
    let mut sampled = 0;
    let used = used_vertices(mesh);
    for (i, q) in mesh.positions.iter().enumerate() {
        if used[i] && q.distance(p) < 0.5 {
            let uv = mesh.uvs[i];
            let t = map.sample_uv(uv.x, uv.y);
            assert!((t - flat.thickness_mm).abs() < 1e-6, "bilinear sample {t} mm at UV {uv} of the seam");
            sampled += 1;
        }
    }
    assert!(sampled >= 2, "{sampled} seam UVs sampled");
}

#[test]
fn a_fast_stroke_leaves_no_gaps() {
    let (_, surface) = head();
    let brush = Brush { radius_mm: 5.0, mirror: false, ..Brush::default() };
    // 60 mm across the left cheek, both ends on the surface.
    let from = left_cheek(surface);
    let to = surface.nearest_on_surface(from + Vec3::new(0.0, 60.0, 0.0), 30.0).expect("surface above the cheek");
    let gap = from.distance(to);
    println!("stroke from {from} to {to}: {gap:.1} mm");
    assert!(gap > 50.0);
    let mut map = blank(surface);
    let rect = stroke(&mut map, surface, &brush, &[from, to]);
    // The segment's projection onto the surface, every 0.25 mm.
    let steps = (gap / 0.25) as usize;
    let path: Vec<Vec3> = (0..=steps)
        .filter_map(|i| surface.nearest_on_surface(from.lerp(to, i as f32 / steps as f32), brush.radius_mm))
        .collect();
    assert!(path.len() > steps * 9 / 10);
    // The stroke passes the corner of the eye: the brush keeps to the skin and leaves the
    // eyeball and the inside of the lids (other pieces of surface, close in 3D but facing
    // elsewhere or far along the surface) alone.
    let normal_at = |p: Vec3| {
        let (x, y) = surface.nearest_texel(p, 1.0).expect("a path point is a texel");
        surface.normal(x, y).expect("the head has normals")
    };
    let path: Vec<(Vec3, Vec3)> = path.into_iter().map(|q| (q, normal_at(q))).collect();
    let (mut checked, mut skipped) = (0, 0);
    for (x, y, p) in covered_texels(surface) {
        let near = path.iter().find(|(q, _)| q.distance(p) < 0.5 * brush.radius_mm);
        let Some(&(_, n)) = near else { continue };
        if surface.normal(x, y).is_none_or(|m| m.dot(n) < 0.5) {
            skipped += 1;
            continue;
        }
        checked += 1;
        assert!(map.mm[(y * SIZE + x) as usize] > 0.0, "gap at texel ({x}, {y}), {p}");
        assert!(contains(rect, x, y));
    }
    println!("{checked} texels within r/2 of the stroke all painted ({skipped} facing elsewhere left alone)");
    for (x, y) in eye_texels() {
        assert_eq!(map.mm[(y * SIZE + x) as usize], 0.0, "paint on the eyeball at texel ({x}, {y})");
    }
    assert!(checked > 200);
}

#[test]
fn the_spacer_keeps_even_spacing_over_many_small_moves() {
    let (_, surface) = head();
    let brush = Brush { radius_mm: 4.0, ..Brush::default() };
    let spacing = brush.spacing * brush.radius_mm;
    let from = left_cheek(surface);
    let to = surface.nearest_on_surface(from + Vec3::new(0.0, 20.0, 0.0), 20.0).expect("surface");
    // One move, and the same line in 100 small moves: the same dab count, evenly spaced.
    let mut one = StrokeSpacer::new(&brush);
    let mut dabs_one = one.start(from);
    dabs_one.extend(one.move_to(to, surface));
    let mut many = StrokeSpacer::new(&brush);
    let mut dabs_many = many.start(from);
    for i in 1..=100 {
        dabs_many.extend(many.move_to(from.lerp(to, i as f32 / 100.0), surface));
    }
    let expected = (from.distance(to) / spacing) as usize + 1;
    assert_eq!(dabs_one.len(), expected);
    assert!(dabs_many.len().abs_diff(expected) <= 1, "{} dabs over small moves, {expected} in one", dabs_many.len());
    for pair in dabs_many.windows(2) {
        let d = pair[0].distance(pair[1]);
        // Projection onto the surface moves points a little; the steps stay near the spacing.
        assert!(d > 0.5 * spacing && d < 1.5 * spacing, "dab step {d} mm, spacing {spacing} mm");
    }
    // The first point is not repeated; finish reaches the end when it is far enough.
    assert!(dabs_one[1].distance(dabs_one[0]) > 0.5 * spacing);
    let end = one.finish(surface);
    assert!(end.len() <= 1);
    // A move with no surface near it gives no dabs.
    let mut off = StrokeSpacer::new(&brush);
    off.start(Vec3::new(0.0, 0.0, 1000.0));
    assert!(off.move_to(Vec3::new(0.0, 50.0, 1000.0), surface).is_empty());
}

#[test]
fn invalid_brushes_are_refused_naming_the_field() {
    let ok = Brush::default();
    assert_eq!(ok.validate(), Ok(()));
    let cases = [
        (Brush { radius_mm: 0.0, ..ok }, "radius_mm"),
        (Brush { radius_mm: 100.5, ..ok }, "radius_mm"),
        (Brush { radius_mm: f32::NAN, ..ok }, "radius_mm"),
        (Brush { thickness_mm: -0.001, ..ok }, "thickness_mm"),
        (Brush { thickness_mm: 11.0, ..ok }, "thickness_mm"),
        (Brush { flow: 1.5, ..ok }, "flow"),
        (Brush { flow: f32::NAN, ..ok }, "flow"),
        (Brush { hardness: -0.1, ..ok }, "hardness"),
        (Brush { spacing: 0.01, ..ok }, "spacing"),
        (Brush { spacing: 2.5, ..ok }, "spacing"),
    ];
    let (_, surface) = head();
    let centre = left_cheek(surface);
    for (brush, field) in cases {
        let message = brush.validate().expect_err(field);
        assert!(message.contains(field), "{message:?} does not name {field}");
        // An invalid brush paints nothing.
        let mut map = blank(surface);
        assert!(apply_dab(&mut map, surface, &brush, centre).is_empty());
        assert!(map.mm.iter().all(|&v| v == 0.0));
    }
    // Boundary values are valid.
    for b in [
        Brush { radius_mm: 100.0, thickness_mm: 10.0, flow: 1.0, hardness: 1.0, spacing: 2.0, ..ok },
        Brush { thickness_mm: 0.0, flow: 0.0, hardness: 0.0, spacing: 0.05, ..ok },
    ] {
        assert_eq!(b.validate(), Ok(()));
    }
}

#[test]
fn brush_weight_follows_the_documented_curve() {
    let hard = Brush { radius_mm: 10.0, hardness: 1.0, ..Brush::default() };
    assert_eq!(hard.weight(0.0), 1.0);
    assert_eq!(hard.weight(9.99), 1.0);
    assert_eq!(hard.weight(10.0), 0.0);
    let soft = Brush { radius_mm: 10.0, hardness: 0.0, ..Brush::default() };
    assert_eq!(soft.weight(0.0), 1.0);
    assert!((soft.weight(5.0) - 0.5).abs() < 1e-6);
    let half = Brush { radius_mm: 10.0, hardness: 0.5, ..Brush::default() };
    assert_eq!(half.weight(5.0), 1.0);
    assert!((half.weight(7.5) - 0.5).abs() < 1e-6);
    let mut previous = 1.0;
    for i in 0..=120 {
        let w = half.weight(i as f32 * 0.1);
        assert!((0.0..=previous).contains(&w), "weight {w} at {} mm", i as f32 * 0.1);
        previous = w;
    }
    assert_eq!(half.weight(f32::NAN), 0.0);
    assert_eq!(Brush { radius_mm: f32::NAN, ..half }.weight(1.0), 0.0);
}

#[test]
fn dirty_rects_union_and_measure() {
    let a = TexelRect { x0: 2, y0: 3, x1: 5, y1: 7 };
    let b = TexelRect { x0: 4, y0: 1, x1: 9, y1: 4 };
    assert_eq!(a.area(), 12);
    assert_eq!(a.union(b), TexelRect { x0: 2, y0: 1, x1: 9, y1: 7 });
    assert!(TexelRect::EMPTY.is_empty());
    assert_eq!(TexelRect::EMPTY.area(), 0);
    assert_eq!(TexelRect::EMPTY.union(a), a);
    assert_eq!(a.union(TexelRect { x0: 50, y0: 50, x1: 50, y1: 60 }), a);
}

#[test]
fn a_dab_far_from_the_surface_or_on_a_wrong_map_changes_nothing() {
    let (_, surface) = head();
    let brush = Brush { radius_mm: 100.0, ..Brush::default() };
    let mut map = blank(surface);
    for centre in [Vec3::new(0.0, 0.0, 1000.0), Vec3::new(1000.0, 0.0, 0.0), Vec3::splat(f32::NAN), Vec3::splat(1e30)] {
        assert!(apply_dab(&mut map, surface, &brush, centre).is_empty(), "{centre}");
    }
    assert!(map.mm.iter().all(|&v| v == 0.0));
    // A map of another size is left alone.
    let mut small = ThicknessMap { width: 16, height: 16, mm: vec![0.0; 256] };
    assert!(apply_dab(&mut small, surface, &brush, left_cheek(surface)).is_empty());
    // NaN texels under the brush are replaced by finite values.
    let mut bad = blank(surface);
    bad.mm.iter_mut().for_each(|v| *v = f32::NAN);
    apply_dab(&mut bad, surface, &Brush { mode: BrushMode::Smooth, ..brush }, left_cheek(surface));
    let painted = bad.mm.iter().filter(|v| v.is_finite()).count();
    assert!(painted > 1000 && bad.mm.iter().all(|v| v.is_nan() || (0.0..=10.0).contains(v)));
}

/// Speed at the app's size: the subdivided head (two levels) at 2048². Printed, never asserted;
/// run with `--release` for meaningful numbers.
#[test]
fn timing_build_dab_and_stroke_at_2048() {
    let mesh = load_mesh(None, 1.0, 2).expect("default head");
    let start = Instant::now();
    let surface = SurfaceMap::build(&mesh, 2048, 2048);
    let build = start.elapsed();
    println!(
        "SurfaceMap::build: {} triangles at 2048²: {:.1} ms, {} texels covered",
        mesh.triangle_count(),
        build.as_secs_f64() * 1e3,
        surface.covered()
    );
    let centre = left_cheek(&surface);
    let mut map = blank(&surface);
    for (mode, mirror) in [(BrushMode::Paint, false), (BrushMode::Paint, true), (BrushMode::Smooth, true)] {
        let brush = Brush { mode, radius_mm: 10.0, mirror, ..Brush::default() };
        let n = 200;
        let mut texels = 0;
        let start = Instant::now();
        for i in 0..n {
            let c = centre + Vec3::new(0.0, 0.05 * i as f32, 0.0);
            texels += apply_dab(&mut map, &surface, &brush, c).area();
        }
        let per = start.elapsed().as_secs_f64() * 1e3 / f64::from(n);
        println!(
            "apply_dab {mode:?}, 10 mm, mirror {mirror}: {per:.3} ms per dab (dirty rect {} texels)",
            texels / n as usize
        );
    }
    let brush = Brush { radius_mm: 10.0, ..Brush::default() };
    let to = surface.nearest_on_surface(centre + Vec3::new(0.0, 60.0, 0.0), 30.0).expect("surface");
    let mut spacer = StrokeSpacer::new(&brush);
    let dabs = spacer.start(centre).len() + spacer.move_to(to, &surface).len() + spacer.finish(&surface).len();
    // The first stroke writes texels never touched before (fresh pages of the map), the second
    // the same texels again.
    for pass in ["first", "second"] {
        let start = Instant::now();
        let rect = stroke(&mut map, &surface, &brush, &[centre, to]);
        println!(
            "stroke of {:.0} mm, 10 mm brush, mirror, {dabs} dabs (each mirrored), {pass} pass: {:.2} ms, dirty rect {} texels",
            centre.distance(to),
            start.elapsed().as_secs_f64() * 1e3,
            rect.area()
        );
    }
    let start = Instant::now();
    let n = 1000;
    for i in 0..n {
        std::hint::black_box(surface.nearest_on_surface(centre + Vec3::new(0.0, 0.06 * i as f32, -3.0), 10.0));
    }
    println!("nearest_on_surface: {:.1} µs per query", start.elapsed().as_secs_f64() * 1e6 / f64::from(n));
}
