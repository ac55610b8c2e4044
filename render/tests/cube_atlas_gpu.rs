//! The cube-atlas model ([Benmounah2009]) on a real wgpu device: the gather converges to the
//! dipole's total diffuse reflectance on a flat face as the kernel grows; face selection on a
//! sphere; a point under a fold fails the self-occlusion test on its first face and passes on the
//! next; a deformed mesh shows no stale atlas data; the passes exist only when a material uses
//! the model.

use glam::{Vec2, Vec3};
use rouge_model::look::Look;
use rouge_model::medium::Medium;
use rouge_model::mesh::{TriangleMesh, load_mesh};
use rouge_render::cube_atlas::{AtlasSettings, GlobalTerm, OcclusionTest, Reach, face_axes};
use rouge_render::diffusion::{ChannelProfile, ProfileModel};
use rouge_render::{Camera, Gpu, LightRig, Renderer, Scene, Skin, SubsurfaceModel};
use std::path::Path;

const SIZE: u32 = 96;

fn gpu() -> Gpu {
    Gpu::headless().expect("a wgpu adapter (install mesa-vulkan-drivers for lavapipe)")
}

fn builtin(name: &str) -> TriangleMesh {
    load_mesh(Some(Path::new(&format!("builtin:{name}"))), 1.0, 0).expect("builtin mesh")
}

/// A dense medium (decay length 1/σ_tr ≈ 0.7 mm) with a matched boundary, so that a kernel of
/// a few mm holds nearly all of R_d.
fn dense() -> Medium {
    Medium::from_coefficients("dense", [0.2, 0.3, 0.4], [3.0, 2.5, 2.0], 1.0).expect("medium")
}

fn scene(medium: &Medium, settings: AtlasSettings, rig: LightRig) -> Scene {
    let mut scene = Scene::rig(rig);
    let (skin, _) = Skin::from_medium(medium, ProfileModel::ClassicDipole);
    scene.skin = Skin { subsurface: SubsurfaceModel::CubeAtlas { settings }, ..skin };
    scene.specular = false;
    scene
}

fn renderer(gpu: &Gpu, mesh: &TriangleMesh, scene: &Scene) -> Renderer {
    let mut r = Renderer::new(&gpu.device, &gpu.queue);
    r.set_mesh(mesh, scene.skin.albedo).expect("mesh");
    r.set_look(&Look::bare()).expect("look");
    r
}

fn render(r: &mut Renderer, scene: &Scene, yaw: f32) -> Vec<[f32; 4]> {
    let camera = Camera::framing(&r.mesh_bounds().expect("bounds"), yaw, 0.0);
    r.render(scene, &camera, SIZE, SIZE, false).expect("render");
    let img = r.read_linear().expect("read");
    assert!(img.iter().all(|p| p.iter().all(|v| v.is_finite())), "a non-finite pixel");
    img
}

/// The mean of the 8×8 pixels at the image's centre.
fn centre_mean(img: &[[f32; 4]]) -> [f64; 3] {
    let c = SIZE as usize / 2;
    let mut mean = [0.0f64; 3];
    for y in c - 4..c + 4 {
        for x in c - 4..c + 4 {
            for (ch, m) in mean.iter_mut().enumerate() {
                *m += f64::from(img[y * SIZE as usize + x][ch]) / 64.0;
            }
        }
    }
    mean
}

#[test]
fn the_gather_converges_to_the_total_diffuse_reflectance_on_a_flat_face() {
    let gpu = gpu();
    let m = dense();
    let wedge = builtin("wedge");
    let centre = |settings: AtlasSettings| {
        let s = scene(&m, AtlasSettings { adaptive: false, global: GlobalTerm::Off, ..settings }, LightRig::Front);
        let mut r = renderer(&gpu, &wedge, &s);
        centre_mean(&render(&mut r, &s, 0.0))
    };
    // Front light of irradiance π at normal incidence, seen head-on, η = 1: L = E·R_d/π = R_d.
    let e = f64::from(scene(&m, AtlasSettings::default(), LightRig::Front).lights[0].irradiance[0]);
    let expected: Vec<f64> = (0..3)
        .map(|ch| {
            let p =
                ChannelProfile::new(ProfileModel::ClassicDipole, m.sigma_a_per_mm[ch], m.sigma_s_prime_per_mm[ch], 1.0);
            e * p.total() / std::f64::consts::PI
        })
        .collect();
    // The kernel's reach grows: the radiosity grows to R_d.
    let mut last = [0.0f64; 3];
    for reach_mfp in [0.5f32, 1.0, 2.0, 4.0, 8.0] {
        let mean =
            centre(AtlasSettings { kernel_max: 31, reach: Reach::MeanFreePaths(reach_mfp), ..Default::default() });
        println!("reach {reach_mfp} mfp: {mean:?}");
        for ch in 0..3 {
            assert!(mean[ch] > last[ch], "reach {reach_mfp} channel {ch}: {} after {}", mean[ch], last[ch]);
        }
        last = mean;
    }
    for ch in 0..3 {
        println!("channel {ch}: R_d·E/π {}", expected[ch]);
        assert!(
            (last[ch] - expected[ch]).abs() < 0.02 * expected[ch],
            "channel {ch}: {} against {}",
            last[ch],
            expected[ch]
        );
    }
    // At a fixed reach the taps change the quadrature: a single centre disk is exact on a flat,
    // evenly lit face, and fine cells agree with it; coarse cells (5 over 3.3 mm, 1.3 mm each,
    // longer than the decay length) miss the steep part of R_d.
    let one = centre(AtlasSettings { kernel_max: 1, reach: Reach::MeanFreePaths(8.0), ..Default::default() });
    for kernel_max in [5u32, 15, 63] {
        let mean = centre(AtlasSettings { kernel_max, reach: Reach::MeanFreePaths(8.0), ..Default::default() });
        println!("{kernel_max} taps over 8 mfp: {mean:?} (one disk {one:?})");
        if kernel_max == 63 {
            for ch in 0..3 {
                assert!((mean[ch] - one[ch]).abs() < 0.02 * one[ch], "63 taps {mean:?}, one disk {one:?}");
            }
        }
    }
    for ch in 0..3 {
        assert!((one[ch] - expected[ch]).abs() < 0.02 * expected[ch], "one disk {one:?}, R_d {expected:?}");
    }
}

#[test]
fn light_reaches_the_skin_through_the_makeup_both_ways() {
    // A uniform foundation over the front-lit wedge: the atlas's skin light (before the
    // composite's exit T) is the bare skin's times the stack's T, the way in.
    let gpu = gpu();
    let wedge = builtin("wedge");
    let s = scene(&dense(), AtlasSettings::default(), LightRig::Front);
    let foundation = Look::from_json(
        r#"{"schema": "rouge-look", "version": 1, "name": "f", "layers": [{"preset": "builtin:foundation_02_ivory", "thickness": {"uniform_mm": 0.01}}]}"#,
        Path::new("f.json"),
    )
    .expect("look");
    let centre = |look: &Look| {
        let mut r = renderer(&gpu, &wedge, &s);
        r.set_look(look).expect("look");
        let camera = Camera::framing(&r.mesh_bounds().expect("bounds"), 0.0, 0.0);
        r.render(&s, &camera, SIZE, SIZE, false).expect("render");
        let cap = r.capture().expect("capture");
        let i = (SIZE / 2 * SIZE + SIZE / 2) as usize;
        (cap.diffuse[i], cap.exit_t[i])
    };
    let (bare, _) = centre(&Look::bare());
    let (made_up, t) = centre(&foundation);
    for c in 0..3 {
        assert!(t[c] > 0.05 && t[c] < 0.95, "the foundation's T {t:?}");
        let ratio = made_up[c] / bare[c];
        assert!((ratio - t[c]).abs() < 0.02 * t[c], "channel {c}: skin light ×{ratio} under T {}", t[c]);
    }
}

#[test]
fn face_selection_on_a_sphere_picks_the_most_aligned_face_and_finds_the_point_there() {
    let gpu = gpu();
    let sphere = builtin("sphere");
    let s = scene(&dense(), AtlasSettings { atlas_px: 256, ..Default::default() }, LightRig::Front);
    let mut r = renderer(&gpu, &sphere, &s);
    render(&mut r, &s, 0.0);
    let atlas = r.atlas_image().expect("atlas");
    let mut checked = 0;
    for (i, (&x, &n)) in sphere.positions.iter().zip(&sphere.normals).enumerate().step_by(7) {
        let chosen = atlas.frame.chosen_faces(x, n);
        let mut by_sp: Vec<(usize, f32)> = (0..6).map(|f| (f, n.dot(face_axes(f).0))).collect();
        by_sp.sort_by(|a, b| b.1.total_cmp(&a.1));
        if by_sp[0].1 - by_sp[1].1 < 1e-3 {
            continue; // a tie (the normal halfway between two faces): either is right
        }
        let best = by_sp[0].0;
        assert_eq!(chosen[0].0, best, "vertex {i} normal {n}");
        assert!(chosen.windows(2).all(|w| w[0].1 >= w[1].1));
        // A convex object hides nothing: the best face holds every point.
        for test in [OcclusionTest::TangentPlane, OcclusionTest::PlaneOffset] {
            assert!(atlas.holds(best, test, x, n), "vertex {i} at {x} not on face {best} ({test:?})");
        }
        checked += 1;
    }
    assert!(checked > 50);
}

/// A patch tilted toward +X under a flap at z = 4 mm: the patch's centre is hidden from +Z by the
/// flap and seen from +X.
fn fold() -> TriangleMesh {
    let n = Vec3::new(0.3, 0.0, 1.0).normalize();
    let (t, b) = (Vec3::Y.cross(n).normalize(), Vec3::Y);
    let mut m = TriangleMesh::flat_square(1.0);
    let quad = |c: Vec3, u: Vec3, v: Vec3| [c - u - v, c + u - v, c + u + v, c - u + v];
    m.positions = quad(Vec3::ZERO, t * 5.0, b * 5.0)
        .into_iter()
        .chain(quad(Vec3::new(-2.0, 0.0, 4.0), Vec3::X * 6.0, Vec3::Y * 8.0))
        .collect();
    m.normals = vec![n, n, n, n, Vec3::Z, Vec3::Z, Vec3::Z, Vec3::Z];
    m.uvs = vec![Vec2::ZERO; 8];
    m.indices = vec![0, 1, 2, 0, 2, 3, 4, 5, 6, 4, 6, 7];
    m
}

#[test]
fn a_point_under_a_fold_fails_on_its_first_face_and_passes_on_the_next() {
    let gpu = gpu();
    let mesh = fold();
    let s = scene(&dense(), AtlasSettings { atlas_px: 256, ..Default::default() }, LightRig::Front);
    let mut r = renderer(&gpu, &mesh, &s);
    render(&mut r, &s, 0.0);
    let atlas = r.atlas_image().expect("atlas");
    let (x, n) = (Vec3::ZERO, mesh.normals[0]);
    let chosen: Vec<usize> = atlas.frame.chosen_faces(x, n).iter().map(|c| c.0).collect();
    assert_eq!(&chosen[..2], &[4, 0], "+Z first, then +X");
    for test in [OcclusionTest::TangentPlane, OcclusionTest::PlaneOffset] {
        assert!(!atlas.holds(4, test, x, n), "{test:?}: the flap hides the point from +Z");
        assert!(atlas.holds(0, test, x, n), "{test:?}: +X sees the point");
    }
    // The flap's own points are on +Z.
    assert!(atlas.holds(4, OcclusionTest::TangentPlane, Vec3::new(-2.0, 0.0, 4.0), Vec3::Z));
}

#[test]
fn a_deformed_mesh_renders_without_stale_atlas_data() {
    let gpu = gpu();
    let wedge = builtin("wedge");
    let morphed = rouge_model::thickness::morph_to_bounding_sphere(&wedge, 0.6).expect("morph");
    let s = scene(&Medium::builtin("marble").expect("marble"), AtlasSettings::default(), LightRig::Back);
    let mut r = renderer(&gpu, &wedge, &s);
    let before = render(&mut r, &s, 30.0);
    r.set_mesh(&morphed, s.skin.albedo).expect("deform");
    let after = render(&mut r, &s, 30.0);
    let fresh = render(&mut renderer(&gpu, &morphed, &s), &s, 30.0);
    let diff = |a: &[[f32; 4]], b: &[[f32; 4]]| {
        a.iter().zip(b).map(|(p, q)| (0..3).map(|c| (p[c] - q[c]).abs()).fold(0.0f32, f32::max)).fold(0.0, f32::max)
    };
    assert!(diff(&before, &after) > 1e-2, "the deformation changed nothing");
    assert!(diff(&after, &fresh) < 1e-5, "deformed frame differs from a fresh render by {}", diff(&after, &fresh));
}

#[test]
fn the_atlas_passes_exist_only_when_a_material_uses_the_model() {
    let gpu = gpu();
    let wedge = builtin("wedge");
    let mut s = scene(&dense(), AtlasSettings::default(), LightRig::Studio);
    let r = renderer(&gpu, &wedge, &s);
    let steps =
        |plan: &rouge_render::frame::FramePlan| -> Vec<String> { plan.passes.iter().map(|p| p.step.name()).collect() };
    let plan = r.plan(&s, 64, 64, true).expect("plan");
    assert!(steps(&plan).ends_with(&["atlas irradiance".to_string(), "atlas gather".into(), "composite".into()]));
    assert!(plan.variant.atlas && plan.variant.dipole && plan.kernel.is_none());
    assert!(plan.explain().contains("atlas 6×512²"), "{}", plan.explain());
    s.skin.subsurface = SubsurfaceModel::skin_screen_space();
    let plan = r.plan(&s, 64, 64, true).expect("plan");
    assert!(!steps(&plan).iter().any(|n| n.starts_with("atlas")) && !plan.variant.atlas);
    assert!(plan.explain().contains("no material uses the cube-atlas model"));
    let mut no_medium = scene(&dense(), AtlasSettings::default(), LightRig::Back);
    no_medium.skin.medium = None;
    let err = r.plan(&no_medium, 64, 64, true).expect_err("no medium");
    assert!(err.to_string().contains("--medium"), "{err}");
    let bad = scene(&dense(), AtlasSettings { kernel_max: 4, ..Default::default() }, LightRig::Back);
    assert!(r.plan(&bad, 64, 64, true).expect_err("even kernel").to_string().contains("odd"));
}
