//! The brush stays on the surface (issue 15): a dab on one lip leaves the other, one on an
//! upper lid leaves the lower lid, front faces only, occlusion in the painter's frame, fills,
//! the symmetry plane on an off-centre mesh, the stabiliser and the presets.

use std::collections::HashSet;
use std::sync::Arc;

use glam::Vec3;
use rouge_model::TriangleMesh;
use rouge_model::look::{Region, ThicknessMap};
use rouge_model::paint::{
    Axis, BRUSH_PRESETS, Brush, DepthImage, FillRegion, LazyMouse, MirrorPlane, PaintView, Reach, SurfaceMap,
    apply_dab, apply_dab_in_view, fill,
};

use crate::common;
use common::{SIZE, head};

fn blank() -> ThicknessMap {
    ThicknessMap { width: SIZE, height: SIZE, mm: vec![0.0; (SIZE * SIZE) as usize] }
}

/// Covered texels as (x, y, position, normal).
fn texels(surface: &SurfaceMap) -> Vec<(u32, u32, Vec3, Vec3)> {
    let mut out = Vec::new();
    for y in 0..surface.height {
        for x in 0..surface.width {
            if let (Some(p), Some(n)) = (surface.position(x, y), surface.normal(x, y)) {
                out.push((x, y, p, n));
            }
        }
    }
    out
}

fn changed(map: &ThicknessMap) -> HashSet<(u32, u32)> {
    let w = map.width as usize;
    (0..map.mm.len()).filter(|&i| map.mm[i] != 0.0).map(|i| ((i % w) as u32, (i / w) as u32)).collect()
}

/// One dab seen from 600 mm in front of the face (as the app paints: through a view).
fn dab(brush: &Brush, centre: Vec3) -> HashSet<(u32, u32)> {
    let mut map = blank();
    let view = PaintView { eye: Vec3::new(0.0, -20.0, 600.0), depth: None };
    apply_dab_in_view(&mut map, &head().1, brush, centre, Some(&view));
    changed(&map)
}

/// The lips mask's front-facing texels split at the mouth line (the widest gap in height among
/// the lip texels near the midline): (upper lip, lower lip, the mouth line's height).
/// Texels (x, y, position) of one lip.
type LipTexels = Vec<(u32, u32, Vec3)>;

fn lips() -> (LipTexels, LipTexels, f32) {
    let (_, surface) = head();
    let mask = Region::Lips.mask().resized(SIZE, SIZE);
    let lip: Vec<(u32, u32, Vec3)> = texels(surface)
        .into_iter()
        .filter(|&(x, y, _, n)| mask.mm[(y * SIZE + x) as usize] > 0.5 && n.z > 0.3)
        .map(|(x, y, p, _)| (x, y, p))
        .collect();
    let mut heights: Vec<f32> = lip.iter().filter(|t| t.2.x.abs() < 3.0).map(|t| t.2.y).collect();
    heights.sort_by(f32::total_cmp);
    let (gap, at) = heights
        .windows(2)
        .map(|w| (w[1] - w[0], 0.5 * (w[0] + w[1])))
        .fold((0.0, 0.0), |a, b| if b.0 > a.0 { b } else { a });
    println!("{} lip texels; mouth line at y = {at:.2} mm, opening {gap:.2} mm at the midline", lip.len());
    assert!(gap > 0.3, "no mouth line among the lip texels");
    let (upper, lower) = lip.into_iter().partition(|t| t.2.y > at);
    (upper, lower, at)
}

#[test]
fn a_dab_on_the_upper_lip_leaves_the_lower_lip_alone() {
    // The default head's lips are one sheet welded along the mouth line. Closed lips that touch
    // without being joined (an expression, a scan): the triangles across the middle 30 mm of the
    // mouth line cut away, leaving a slit under a millimetre wide.
    let (head_mesh, _) = head();
    let (_, _, mouth_y) = lips();
    let mut mesh = head_mesh.clone();
    let across = |t: &[u32]| {
        let p = t.iter().map(|&v| head_mesh.positions[v as usize]).collect::<Vec<_>>();
        let (lo, hi) = p.iter().fold((f32::INFINITY, f32::NEG_INFINITY), |(lo, hi), q| (lo.min(q.y), hi.max(q.y)));
        lo < mouth_y && hi > mouth_y && p.iter().all(|q| q.x.abs() < 15.0 && q.z > 105.0)
    };
    let before = mesh.indices.len() / 3;
    mesh.indices = mesh.indices.chunks_exact(3).filter(|t| !across(t)).flatten().copied().collect();
    mesh.groups.clear();
    println!("{} triangles cut along the mouth line", before - mesh.indices.len() / 3);
    let surface = SurfaceMap::build(&mesh, SIZE, SIZE);
    let mask = Region::Lips.mask().resized(SIZE, SIZE);
    let lip: Vec<(u32, u32, Vec3)> = texels(&surface)
        .into_iter()
        .filter(|&(x, y, p, n)| mask.mm[(y * SIZE + x) as usize] > 0.0 && n.z > 0.3 && p.x.abs() < 15.0)
        .map(|(x, y, p, _)| (x, y, p))
        .collect();
    let (upper, lower): (Vec<_>, Vec<_>) = lip.into_iter().partition(|t| t.2.y > mouth_y);
    // A point of the upper lip 1.5 mm above the mouth line, on the midline.
    let centre = upper
        .iter()
        .map(|t| t.2)
        .filter(|p| p.x.abs() < 1.0)
        .min_by(|a, b| (a.y - mouth_y - 1.5).abs().total_cmp(&(b.y - mouth_y - 1.5).abs()))
        .expect("an upper-lip point");
    let nearest_lower = lower.iter().map(|t| t.2.distance(centre)).fold(f32::INFINITY, f32::min);
    // A brush that reaches well past the other lip through the air.
    let brush = Brush { radius_mm: nearest_lower + 4.0, mirror: false, ..Brush::default() };
    let lower: HashSet<(u32, u32)> = lower.iter().map(|t| (t.0, t.1)).collect();
    let upper: HashSet<(u32, u32)> = upper.iter().map(|t| (t.0, t.1)).collect();
    let run = |brush: &Brush| {
        let mut map = blank();
        let view = PaintView { eye: Vec3::new(0.0, -20.0, 600.0), depth: None };
        apply_dab_in_view(&mut map, &surface, brush, centre, Some(&view));
        changed(&map)
    };
    let on_surface = run(&brush);
    let through_air = run(&Brush { reach: Reach::Ball, ..brush });
    let leaked = |c: &HashSet<(u32, u32)>| c.intersection(&lower).count();
    println!(
        "radius {:.1} mm (lower lip {nearest_lower:.2} mm away in 3D): along the surface {} texels, {} of the \
         upper lip, {} of the lower; through the air {} texels, {} of the lower lip",
        brush.radius_mm,
        on_surface.len(),
        on_surface.intersection(&upper).count(),
        leaked(&on_surface),
        through_air.len(),
        leaked(&through_air)
    );
    assert_eq!(leaked(&on_surface), 0, "paint reached the lower lip");
    assert!(on_surface.intersection(&upper).count() > 20, "the upper lip was painted");
    assert!(leaked(&through_air) > 10, "the 3D ball reaches the lower lip (the old behaviour)");
}

#[test]
fn a_dab_on_the_upper_lid_leaves_the_lower_lid_alone() {
    let (mesh, surface) = head();
    // The left eyeball's bounds: its centre and radius (of the whole head: `head()` is its skin).
    let full = rouge_model::mesh::load_mesh(None, 1.0, 1).expect("default head");
    let eye: Vec<Vec3> = full
        .groups
        .iter()
        .filter(|g| g.name == "eye_l")
        .flat_map(|g| full.indices[3 * g.triangles.start..3 * g.triangles.end].iter())
        .map(|&i| full.positions[i as usize])
        .collect();
    assert!(!eye.is_empty(), "the head has a left eye");
    let (lo, hi) = eye.iter().fold((Vec3::INFINITY, Vec3::NEG_INFINITY), |(lo, hi), &p| (lo.min(p), hi.max(p)));
    let eye_c = 0.5 * (lo + hi);
    let eye_front = hi.z;
    let mask = Region::Eyelids.mask().resized(SIZE, SIZE);
    let skin = texels(surface);
    let eye_texels: HashSet<(u32, u32)> = {
        let mut only = mesh.clone();
        only.indices = mesh
            .groups
            .iter()
            .filter(|g| g.name.contains("eye"))
            .flat_map(|g| mesh.indices[3 * g.triangles.start..3 * g.triangles.end].iter().copied())
            .collect();
        texels(&SurfaceMap::build(&only, SIZE, SIZE)).into_iter().map(|t| (t.0, t.1)).collect()
    };
    // The upper lid: the eyelid mask's front-facing skin just above the eye's centre.
    let centre = skin
        .iter()
        .filter(|t| mask.mm[(t.1 * SIZE + t.0) as usize] > 0.5 && t.3.z > 0.3 && !eye_texels.contains(&(t.0, t.1)))
        .map(|t| t.2)
        .filter(|p| (p.x - eye_c.x).abs() < 2.0 && p.y > eye_c.y)
        .min_by(|a, b| a.y.total_cmp(&b.y))
        .expect("an upper-lid point above the eye");
    // The lower lid: front-facing skin (no eyeball) below the eye, in front of its centre.
    let lower: HashSet<(u32, u32)> = skin
        .iter()
        .filter(|t| {
            let p = t.2;
            !eye_texels.contains(&(t.0, t.1))
                && t.3.z > 0.3
                && (p.x - eye_c.x).abs() < 6.0
                && p.y < eye_c.y - 2.0
                && p.y > eye_c.y - 12.0
                && p.z > eye_front - 6.0
        })
        .map(|t| (t.0, t.1))
        .collect();
    let nearest_lower =
        skin.iter().filter(|t| lower.contains(&(t.0, t.1))).map(|t| t.2.distance(centre)).fold(f32::INFINITY, f32::min);
    let brush = Brush { radius_mm: nearest_lower + 3.0, mirror: false, ..Brush::default() };
    let on_surface = dab(&brush, centre);
    let through_air = dab(&Brush { reach: Reach::Ball, ..brush }, centre);
    let (leak, old) = (on_surface.intersection(&lower).count(), through_air.intersection(&lower).count());
    let eyeball = on_surface.intersection(&eye_texels).count();
    println!(
        "upper lid at {centre}, lower lid {nearest_lower:.1} mm away, radius {:.1} mm: along the surface {} \
         texels ({leak} on the lower lid, {eyeball} on the eyeball), through the air {} ({old} on the lower lid, {} \
         on the eyeball)",
        brush.radius_mm,
        on_surface.len(),
        through_air.len(),
        through_air.intersection(&eye_texels).count()
    );
    assert_eq!(leak, 0, "paint reached the lower lid");
    assert_eq!(eyeball, 0, "paint reached the eyeball");
    assert!(on_surface.len() > 100);
    assert!(old > 10, "the 3D ball reaches the lower lid");
}

#[test]
fn front_faces_only_paints_what_faces_the_painter() {
    let (_, surface) = head();
    // The bridge of the nose, seen from far to the head's left: its right side faces away.
    let centre = surface.nearest_on_surface(Vec3::new(0.0, 10.0, 120.0), 40.0).expect("the nose");
    let eye = Vec3::new(600.0, 10.0, 100.0);
    let view = PaintView { eye, depth: None };
    let brush = Brush { radius_mm: 10.0, mirror: false, ..Brush::default() };
    let facing = |x: u32, y: u32| {
        let (p, n) = (surface.position(x, y).expect("covered"), surface.normal(x, y).expect("a normal"));
        n.dot(eye - p) > 0.0
    };
    let run = |brush: &Brush| {
        let mut map = blank();
        apply_dab_in_view(&mut map, surface, brush, centre, Some(&view));
        changed(&map)
    };
    let front = run(&brush);
    let all = run(&Brush { front_faces_only: false, ..brush });
    let away = all.iter().filter(|&&(x, y)| !facing(x, y)).count();
    println!("front faces only: {} texels; without: {} ({away} facing away)", front.len(), all.len());
    assert!(front.len() > 100);
    assert!(front.iter().all(|&(x, y)| facing(x, y)), "a texel facing away was painted");
    assert!(away > 100, "the dab without the test reaches the far side of the nose");
}

#[test]
fn occluded_texels_are_not_painted() {
    let (_, surface) = head();
    let centre = surface.nearest_on_surface(Vec3::new(45.0, -30.0, 100.0), 60.0).expect("a cheek");
    let eye = Vec3::new(0.0, 0.0, 600.0);
    let (w, h) = (200u32, 200u32);
    let view_proj = glam::camera::rh::proj::directx::perspective(0.5, 1.0, 10.0, 2000.0)
        * glam::camera::rh::view::look_at_mat4(eye, Vec3::ZERO, Vec3::Y);
    // A wall 100 mm in front of the eye over the pixels left of the dab's centre, background
    // elsewhere.
    let clip = view_proj * centre.extend(1.0);
    let centre_px = ((clip.x / clip.w + 1.0) * 0.5 * w as f32) as u32;
    let wall = view_proj * Vec3::new(0.0, 0.0, 500.0).extend(1.0);
    let wall_depth = wall.z / wall.w;
    let depth: Vec<f32> = (0..w * h).map(|i| if i % w < centre_px { wall_depth } else { 1.0 }).collect();
    let image = Arc::new(DepthImage::new(view_proj, w, h, Arc::new(depth)).expect("a depth image"));
    let view = PaintView { eye, depth: Some(image.clone()) };
    let brush = Brush { radius_mm: 8.0, mirror: false, ..Brush::default() };
    let mut map = blank();
    apply_dab_in_view(&mut map, surface, &brush, centre, Some(&view));
    let painted = changed(&map);
    let mut open = blank();
    apply_dab_in_view(&mut open, surface, &Brush { occlusion: false, ..brush }, centre, Some(&view));
    let all = changed(&open);
    let hidden = |&(x, y): &(u32, u32)| image.hides(eye, surface.position(x, y).expect("covered"), 1.5);
    println!(
        "occlusion on: {} texels; off: {} ({} hidden)",
        painted.len(),
        all.len(),
        all.iter().filter(|t| hidden(t)).count()
    );
    assert!(!painted.iter().any(hidden), "a hidden texel was painted");
    assert!(all.iter().filter(|t| hidden(t)).count() > 30, "part of the dab lies behind the wall");
    assert!(painted.len() > 100);
    assert!(DepthImage::new(view_proj, w, h + 1, Arc::new(vec![1.0; (w * h) as usize])).is_none());
}

#[test]
fn fill_a_mask_an_island_or_everything() {
    let (_, surface) = head();
    let mask = Region::Lips.mask().resized(SIZE, SIZE);
    let mut map = blank();
    let rect = fill(&mut map, surface, FillRegion::Mask(Region::Lips.mask()), 0.02).expect("a fill");
    let got = changed(&map);
    let want: HashSet<(u32, u32)> = texels(surface)
        .into_iter()
        .filter(|t| mask.mm[(t.1 * SIZE + t.0) as usize] > 0.0)
        .map(|t| (t.0, t.1))
        .collect();
    assert_eq!(got, want, "the fill changed exactly the mask's covered texels");
    for &(x, y) in &got {
        let i = (y * SIZE + x) as usize;
        assert!((map.mm[i] - 0.02 * mask.mm[i].min(1.0)).abs() < 1e-7);
        assert!(x >= rect.x0 && x < rect.x1 && y >= rect.y0 && y < rect.y1);
    }
    // The whole head, then the island under a cheek texel (the face's island, not the ears').
    let mut whole = blank();
    fill(&mut whole, surface, FillRegion::Whole, 0.01).expect("a fill");
    assert_eq!(changed(&whole).len(), surface.covered());
    let cheek = surface.nearest_on_surface(Vec3::new(45.0, -30.0, 100.0), 60.0).expect("a cheek");
    let (x, y) = surface.nearest_texel(cheek, 1.0).expect("a texel");
    let mut island = blank();
    fill(&mut island, surface, FillRegion::Island { x, y }, 0.01).expect("a fill");
    let n = changed(&island).len();
    println!("lips fill {} texels, whole {} texels, the cheek's island {n} texels", got.len(), surface.covered());
    assert!(n > 1000 && n < surface.covered(), "{n} texels in the cheek's island");
    // Errors name the value.
    let e = fill(&mut blank(), surface, FillRegion::Whole, f32::NAN).unwrap_err();
    assert!(e.contains("NaN mm"), "{e}");
    let e = fill(&mut blank(), surface, FillRegion::Island { x: 0, y: 0 }, 0.01).unwrap_err();
    assert!(e.contains("(0, 0)") && e.contains("not on the mesh"), "{e}");
    let e = fill(&mut ThicknessMap::uniform(0.0), surface, FillRegion::Whole, 0.01).unwrap_err();
    assert!(e.contains("1×1"), "{e}");
}

#[test]
fn symmetry_follows_an_off_centre_plane() {
    let (head_mesh, _) = head();
    // The head moved 25 mm to its left, plus a lopsided "shoulder" far out on that side.
    let shift = Vec3::new(25.0, 0.0, 0.0);
    let mut mesh = head_mesh.clone();
    for p in &mut mesh.positions {
        *p += shift;
    }
    let base = mesh.positions.len() as u32;
    mesh.positions.extend([
        Vec3::new(220.0, -150.0, 0.0),
        Vec3::new(230.0, -150.0, 0.0),
        Vec3::new(225.0, -140.0, 0.0),
    ]);
    mesh.normals.extend([Vec3::Z; 3]);
    mesh.uvs.extend([glam::Vec2::new(0.001, 0.001), glam::Vec2::new(0.004, 0.001), glam::Vec2::new(0.002, 0.004)]);
    mesh.indices.extend([base, base + 1, base + 2]);
    let surface = SurfaceMap::build(&mesh, SIZE, SIZE);
    let fitted = MirrorPlane::fit(Axis::X, &surface);
    let bounds = MirrorPlane::fitted(Axis::X, &surface);
    println!("plane fitted at x = {:.2} mm (bounds centre {:.2} mm)", fitted.offset_mm, bounds.offset_mm);
    assert!((fitted.offset_mm - 25.0).abs() < 1.0, "fitted plane at {}", fitted.offset_mm);
    assert!((bounds.offset_mm - 25.0).abs() > 20.0, "the bounds' centre is off");
    let centre = surface.nearest_on_surface(Vec3::new(45.0, -30.0, 100.0) + shift, 60.0).expect("a cheek");
    let brush = Brush { radius_mm: 6.0, mirror: true, mirror_plane: Some(fitted), ..Brush::default() };
    let mut map = blank();
    apply_dab(&mut map, &surface, &brush, centre);
    let image = fitted.reflect(centre);
    let (mut near, mut sum, mut n) = (0, Vec3::ZERO, 0.0);
    for (x, y) in changed(&map) {
        let p = surface.position(x, y).expect("covered");
        if fitted.distance(p) < 0.0 {
            sum += p;
            n += 1.0;
            near += usize::from(p.distance(image) < brush.radius_mm + 1.0);
        }
    }
    let mean = sum / n;
    println!("mirror side: {n} texels centred at {mean}, the mirror image of the dab at {image}");
    assert!(n > 100.0 && near as f32 == n, "{near} of {n} mirrored texels near the image");
    assert!(mean.distance(image) < 2.0, "mirrored dab centred at {mean}, want {image}");
    // A plane through the bounds' centre would have put it elsewhere.
    assert!(bounds.reflect(centre).distance(image) > 20.0);
    let bad = Brush { mirror_plane: Some(MirrorPlane { axis: Axis::X, offset_mm: f32::NAN }), ..brush };
    assert!(bad.validate().unwrap_err().contains("offset NaN mm along x"));
}

#[test]
fn the_stabiliser_smooths_a_jittery_stroke() {
    // A line along x with ±1.5 mm of jitter across it (a fixed pseudo-random sequence).
    let mut seed = 0x2545_f491_u32;
    let mut jitter = || {
        seed ^= seed << 13;
        seed ^= seed >> 17;
        seed ^= seed << 5;
        (seed as f32 / u32::MAX as f32 - 0.5) * 3.0
    };
    let input: Vec<Vec3> = (0..400).map(|i| Vec3::new(i as f32 * 0.25, jitter(), 0.0)).collect();
    let mut lazy = LazyMouse::new(4.0);
    let output: Vec<Vec3> = input.iter().filter_map(|&p| lazy.follow(p)).collect();
    // Roughness: mean |second difference| across the line, per unit of length along it.
    let wobble = |pts: &[Vec3]| {
        let off: f32 = pts.iter().map(|p| p.y.abs()).sum::<f32>() / pts.len() as f32;
        let path: f32 = pts.windows(2).map(|w| w[0].distance(w[1])).sum();
        let straight = pts[0].distance(pts[pts.len() - 1]);
        (off, path / straight)
    };
    let (off_in, len_in) = wobble(&input);
    let (off_out, len_out) = wobble(&output[1..]);
    println!(
        "input: mean offset {off_in:.2} mm, path {len_in:.2}× the chord; stabilised ({} points): {off_out:.2} mm, {len_out:.3}×",
        output.len()
    );
    assert!(off_out < 0.5 * off_in, "the stabilised path stays nearer the line");
    assert!(len_out < 1.1 && len_in > 1.5, "the stabilised path is nearly straight");
    // It still gets there, a string behind.
    let end = lazy.brush().expect("a brush");
    assert!((end.x - input[input.len() - 1].x).abs() < 4.5);
    // Off (no string) the brush follows exactly; non-finite points are ignored.
    let mut off = LazyMouse::new(f32::NAN);
    assert_eq!(off.follow(Vec3::ONE), Some(Vec3::ONE));
    assert_eq!(off.follow(Vec3::new(2.0, 1.0, 1.0)), Some(Vec3::new(2.0, 1.0, 1.0)));
    assert_eq!(off.follow(Vec3::NAN), None);
}

#[test]
fn presets_are_valid_brushes_and_keep_the_painters_settings() {
    let mine = Brush { mirror: false, reach: Reach::Ball, occlusion: false, ..Brush::default() };
    for p in BRUSH_PRESETS {
        let b = p.apply(&mine);
        b.validate().unwrap_or_else(|e| panic!("{}: {e}", p.name));
        assert!((!b.mirror, b.reach, b.occlusion) == (true, Reach::Ball, false), "{}", p.name);
        assert!(p.matches(&b) && !p.matches(&mine));
    }
    let names: Vec<&str> = BRUSH_PRESETS.iter().map(|p| p.name).collect();
    for want in ["Foundation sponge", "Blush brush", "Contour brush", "Liner", "Lipstick"] {
        assert!(names.contains(&want), "{want} missing");
    }
    // Pressure scales radius and flow; full pressure is the brush itself.
    let b = Brush::default();
    assert_eq!(b.with_pressure(1.0), b);
    assert_eq!(b.with_pressure(f32::NAN), b);
    let light = b.with_pressure(0.0);
    assert!((light.radius_mm - 0.25 * b.radius_mm).abs() < 1e-6 && (light.flow - 0.25 * b.flow).abs() < 1e-6);
}

#[test]
fn the_surface_map_welds_its_uv_seams() {
    let (_, surface) = head();
    println!("{surface:?}");
    // Welding joins the copies UV seams make.
    assert!(surface.welded_vertices() < head().0.vertex_count(), "the head's UV seams are welded");
    assert_eq!(SurfaceMap::build(&TriangleMesh::flat_square(10.0), 32, 32).welded_vertices(), 4);
}
