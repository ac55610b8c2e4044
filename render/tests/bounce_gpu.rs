//! The bounce between facing parts on a real device (lavapipe on CI): nothing on a convex body;
//! on the head and the hand the shader's screen samples against the full sum over every visible
//! pixel (`python/translucency_pixel_bins.py`'s `bounce_estimate`, written again here), and the
//! shader's source areas against the positions' finite differences.

use glam::Vec3;
use rouge_model::look::Look;
use rouge_model::mesh::load_mesh;
use rouge_render::bounce::BounceSettings;
use rouge_render::renderer::FrameCapture;
use rouge_render::{Camera, Gpu, Renderer, Scene, SubsurfaceModel};
use std::path::Path;

const SIZE: u32 = 160;
const ALBEDO: [f32; 3] = [0.8, 0.5, 0.3];

/// A frame of `mesh` (Lambert skin of [`ALBEDO`], no subsurface model, no specular) lit from the
/// front left, with the bounce of `settings`: its capture, world positions and the eye.
fn frame(gpu: &Gpu, mesh: &str, settings: BounceSettings) -> (FrameCapture, Vec<Vec3>, Vec3) {
    let mesh = load_mesh(Some(Path::new(mesh)), 1.0, 0).expect("built-in mesh");
    let mut r = Renderer::new(&gpu.device, &gpu.queue);
    r.set_mesh(&mesh, ALBEDO).expect("mesh");
    r.set_look(&Look::bare()).expect("look");
    let camera = Camera::framing(&r.mesh_bounds().expect("bounds"), 0.0, 0.0);
    let mut scene = Scene::white_light(Vec3::new(-0.6, 0.35, 0.72));
    scene.skin.albedo = ALBEDO;
    scene.skin.subsurface = SubsurfaceModel::None;
    scene.specular = false;
    scene.bounce = Some(settings);
    r.render(&scene, &camera, SIZE, SIZE, false).expect("render");
    let cap = r.capture().expect("capture");
    // The background's pixels have no position (never read: they are not covered).
    let positions = (0..SIZE * SIZE).map(|i| r.pick(i % SIZE, i / SIZE).expect("pick").unwrap_or(Vec3::ZERO)).collect();
    (cap, positions, camera.position())
}

/// What the shader added at each pixel.
fn added(cap: &FrameCapture) -> Vec<[f32; 3]> {
    let bounced = cap.bounced.as_ref().expect("the bounce pass ran");
    bounced.iter().zip(&cap.diffuse).map(|(b, s)| std::array::from_fn(|c| b[c] - s[c])).collect()
}

#[test]
fn a_convex_body_gets_no_bounce() {
    let gpu = Gpu::headless().expect("a wgpu adapter (install mesa-vulkan-drivers for lavapipe)");
    let (cap, _, _) = frame(&gpu, "builtin:sphere", BounceSettings::default());
    let add = added(&cap);
    let (mut most, mut lit) = (0.0f32, 0.0f32);
    for (a, s) in add.iter().zip(&cap.scattered) {
        assert!(a.iter().all(|v| v.is_finite()), "{a:?}");
        most = most.max(a.iter().fold(0.0, |m, v| m.max(v.abs())));
        lit = lit.max(s[0]);
    }
    // No two points of a sphere face each other; the tessellation's facets bend the normals by
    // under a degree (half-float rounding of an unchanged radiance: 2⁻¹¹ of it).
    eprintln!("the sphere's largest bounce {most:.2e} against its brightest radiance {lit:.3}");
    assert!(lit > 0.1 && most < 2e-3 * lit, "{most} against {lit}");
}

/// The shader's bounce on `mesh` against the full sum over every covered pixel, receivers every
/// other pixel: the two totals' ratio. Sources' areas as the shader takes them (z³/(ℓf²μ), μ ≥
/// 0.1), and, on the pixels whose neighbours are all covered, from the positions' finite
/// differences, whose total over those pixels is also returned against the formula's.
fn against_the_full_sum(gpu: &Gpu, mesh: &str, near_mm: f32) -> (f64, f64) {
    let settings = BounceSettings { samples: 256, reach_mm: 2000.0, near_mm, ..BounceSettings::default() };
    let (cap, x, eye) = frame(gpu, mesh, settings);
    let n = SIZE as usize;
    // Skin pixels (the diffuse radiance's alpha is the skin flag; the eyes are not skin).
    let covered = |i: usize| cap.normal[i][3] != 0.0 && cap.diffuse[i][3] >= 0.5;
    let normal = |i: usize| Vec3::from_slice(&cap.normal[i][..3]).normalize();
    let mut area_ratios = Vec::new();
    let mut sources = Vec::new();
    for i in (0..n * n).filter(|&i| covered(i)) {
        let to_eye = eye - x[i];
        let ell = to_eye.length();
        let mu = (normal(i).dot(to_eye) / ell).max(settings.least_view_cosine);
        let area = cap.depth_mm[i].powi(3) / (ell * cap.focal_px * cap.focal_px * mu);
        let (px, py) = (i % n, i / n);
        if (1..n - 1).contains(&px) && (1..n - 1).contains(&py) && [i - 1, i + 1, i - n, i + n].into_iter().all(covered)
        {
            let differences = ((x[i + 1] - x[i - 1]) * 0.5).cross((x[i + n] - x[i - n]) * 0.5).length();
            area_ratios.push(f64::from(differences / area));
        }
        sources.push((x[i], normal(i), Vec3::from_slice(&cap.diffuse[i][..3]) * area));
    }
    area_ratios.sort_by(f64::total_cmp);
    let areas = area_ratios[area_ratios.len() / 2];
    let add = added(&cap);
    let (mut want, mut got) = (0.0f64, 0.0f64);
    for i in (0..n * n).filter(|&i| covered(i) && (i % n) % 2 == 1 && (i / n) % 2 == 1) {
        let nr = normal(i);
        let mut e = Vec3::ZERO;
        for &(xs, ns, flux) in &sources {
            let d = xs - x[i];
            let dist = d.length();
            let w = d / dist.max(1e-9);
            let (cr, cs) = (nr.dot(w), -ns.dot(w));
            if dist > near_mm && cr > 0.0 && cs > 0.0 {
                e += flux * (cr * cs / (dist * dist));
            }
        }
        want += f64::from(e.x * ALBEDO[0] / std::f32::consts::PI);
        got += f64::from(add[i][0]);
    }
    eprintln!(
        "{mesh}: the shader's red bounce sums to {got:.4}, the full sum {want:.4} (ratio {:.3}); the median over \
         pixels with covered neighbours of the source's area by finite differences over the formula's: {areas:.3}",
        got / want
    );
    assert!(want > 0.0);
    (got / want, areas)
}

#[test]
fn the_bounce_matches_the_full_sum_over_the_visible_pixels() {
    let gpu = Gpu::headless().expect("a wgpu adapter");
    let hand = format!("{}/../data/hands/hm08_hand.obj", env!("CARGO_MANIFEST_DIR"));
    // The shader's total is 2-5% under the sum (lavapipe: head 0.954, hand 0.978; 0.918 and
    // 1.035 without the 5×5 average): the average over a pixel's neighbours on its own surface
    // leaves out, near creases, neighbours across the crease.
    let got: Vec<_> = [("builtin:head", 1.0, 0.06), (hand.as_str(), 1.0, 0.06)]
        .map(|(mesh, near_mm, tolerance)| (mesh, tolerance, against_the_full_sum(&gpu, mesh, near_mm)))
        .into();
    for (mesh, tolerance, (ratio, areas)) in got {
        assert!((ratio - 1.0).abs() < tolerance, "{mesh}: ratio {ratio}");
        assert!((areas - 1.0).abs() < 0.05, "{mesh}: areas {areas}");
    }
}
