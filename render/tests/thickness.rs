//! The thickness translucency ([BarreBrisebois2011]) on a real wgpu device: the backlit head's
//! ear glows with it, the per-light scale multiplies it exactly, and the shadow-map source
//! follows the light.

use rouge_model::look::Look;
use rouge_model::medium::Medium;
use rouge_model::mesh::{TriangleMesh, load_mesh};
use rouge_model::thickness::{bake_local_thickness, thickness_uv_map};
use rouge_render::local_thickness::{ThicknessSource, TranslucencyParams};
use rouge_render::renderer::FrameCapture;
use rouge_render::{Camera, Gpu, LightRig, Renderer, Scene, Skin, SubsurfaceModel};

const SIZE: u32 = 160;

fn head() -> TriangleMesh {
    load_mesh(None, 1.0, 1).expect("default head")
}

/// A renderer with `mesh`, a bare look and, for the baked source, the mesh's baked thickness.
fn renderer(gpu: &Gpu, mesh: &TriangleMesh, skin: &Skin) -> Renderer {
    let mut r = Renderer::new(&gpu.device, &gpu.queue);
    r.set_mesh(mesh, skin.albedo).expect("mesh");
    r.set_look(&Look::bare()).expect("look");
    if let SubsurfaceModel::Thickness { source: ThicknessSource::Baked(settings), .. } = &skin.subsurface {
        let bake = bake_local_thickness(mesh, settings).expect("bake");
        let map = thickness_uv_map(mesh, &bake.value, 256, 256).expect("map");
        r.set_local_thickness(Some((map.width, map.height, &map.texels))).expect("upload");
    }
    r
}

fn capture(gpu: &Gpu, mesh: &TriangleMesh, scene: &Scene) -> (FrameCapture, Renderer) {
    let mut r = renderer(gpu, mesh, &scene.skin);
    let camera = Camera::framing(&r.mesh_bounds().expect("bounds"), 0.0, 0.0);
    r.render(scene, &camera, SIZE, SIZE, false).expect("render");
    (r.capture().expect("capture"), r)
}

/// The backlit head in skin1 with `subsurface`.
fn backlit(subsurface: SubsurfaceModel) -> Scene {
    let mut scene = Scene::rig(LightRig::Back);
    let medium = Medium::builtin("skin1").expect("skin1");
    let (skin, _) = Skin::from_medium(&medium, rouge_render::diffusion::ProfileModel::BetterDipole);
    scene.skin = Skin { subsurface, ..skin };
    scene.specular = false;
    scene
}

fn thickness(baked: bool, params: TranslucencyParams) -> SubsurfaceModel {
    let medium = Medium::builtin("skin1").expect("skin1");
    SubsurfaceModel::Thickness {
        params,
        source: ThicknessSource::for_medium(baked, Some(&medium), 16, 30.0),
        kernel: None,
    }
}

/// Mean red diffuse radiance of the skin pixels within 6 px of the right ear (the vertices
/// farthest along +x, toward the light).
fn ear_red(cap: &FrameCapture, r: &Renderer, mesh: &TriangleMesh) -> f32 {
    let mut xs: Vec<usize> = (0..mesh.vertex_count()).collect();
    xs.sort_by(|&a, &b| mesh.positions[b].x.total_cmp(&mesh.positions[a].x));
    let ear = xs[..40].iter().map(|&i| mesh.positions[i]).sum::<glam::Vec3>() / 40.0;
    let (px, py) = r.project(ear).expect("the ear is in view");
    let (mut sum, mut n) = (0.0, 0);
    for y in (py as i32 - 6).max(0)..(py as i32 + 6).min(SIZE as i32) {
        for x in (px as i32 - 6).max(0)..(px as i32 + 6).min(SIZE as i32) {
            let d = cap.diffuse[(y as u32 * SIZE + x as u32) as usize];
            if d[3] > 0.5 {
                sum += d[0];
                n += 1;
            }
        }
    }
    assert!(n > 10, "too few skin pixels around the ear at ({px}, {py})");
    sum / n as f32
}

#[test]
fn the_backlit_ear_glows_with_the_model_and_not_without() {
    let gpu = Gpu::headless().expect("a wgpu adapter (install mesa-vulkan-drivers for lavapipe)");
    let mesh = head();
    let fitted = |source| TranslucencyParams::for_medium(Medium::builtin("skin1").ok().as_ref(), source).0;
    let (none, r) = capture(&gpu, &mesh, &backlit(SubsurfaceModel::None));
    let without = ear_red(&none, &r, &mesh);
    for (baked, source) in [(true, "baked"), (false, "shadow-map")] {
        let (cap, r) = capture(&gpu, &mesh, &backlit(thickness(baked, fitted(source))));
        let with = ear_red(&cap, &r, &mesh);
        assert!(with > 1.5 * without + 0.01, "{source}: ear {with} with the model, {without} without");
        assert!(cap.diffuse.iter().all(|d| d.iter().all(|v| v.is_finite())), "{source}: a non-finite pixel");
    }
}

#[test]
fn the_light_scale_multiplies_the_term_exactly_and_light_in_front_adds_nothing() {
    let gpu = Gpu::headless().expect("gpu");
    let mesh = head();
    let params = TranslucencyParams { distortion: 0.2, power: 2.0, scale: 1.5, ambient: 0.0 };
    let (base, _) = capture(&gpu, &mesh, &backlit(SubsurfaceModel::None));
    let (one, _) = capture(&gpu, &mesh, &backlit(thickness(false, params)));
    let mut doubled = backlit(thickness(false, params));
    doubled.lights[0].translucency_scale = 2.0;
    let (two, _) = capture(&gpu, &mesh, &doubled);
    let (mut checked, mut worst) = (0, 0.0f32);
    for i in 0..base.diffuse.len() {
        for c in 0..3 {
            let (t1, t2) = (one.diffuse[i][c] - base.diffuse[i][c], two.diffuse[i][c] - base.diffuse[i][c]);
            if t1 > 0.01 {
                checked += 1;
                // Half-float targets: 2⁻¹⁰ relative per value.
                worst = worst.max((t2 - 2.0 * t1).abs() / (2.0 * t1 + base.diffuse[i][c]));
            }
        }
    }
    assert!(checked > 100 && worst < 4e-3, "{checked} values, worst relative error {worst}");
    // The light in front of the viewer and no ambient: the term is zero everywhere.
    let mut front = backlit(thickness(false, params));
    front.lights = Scene::rig(LightRig::Front).lights;
    let mut plain = front.clone();
    plain.skin.subsurface = SubsurfaceModel::None;
    let (a, _) = capture(&gpu, &mesh, &front);
    let (b, _) = capture(&gpu, &mesh, &plain);
    assert_eq!(a.diffuse, b.diffuse);
}

#[test]
fn parameters_come_from_the_medium_its_fit_under_the_kernel_or_its_nearest_fitted_neighbour() {
    use rouge_render::local_thickness::FitOrigin;
    let skin1 = Medium::builtin("skin1").expect("skin1");
    let own = |key| TranslucencyParams::for_medium(Some(&skin1), key).0;
    // skin1's own fits, alone and under the kernel.
    assert_eq!(TranslucencyParams::fitted(Some(&skin1), "baked", false), (own("baked"), FitOrigin::Fitted));
    assert_eq!(TranslucencyParams::fitted(Some(&skin1), "baked", true), (own("baked+kernel"), FitOrigin::Fitted));
    assert_ne!(own("baked"), own("baked+kernel"));
    // Under a kernel without a fit under it: the fit alone.
    let mut alone = skin1.clone();
    alone.translucency.retain(|t| !t.source.ends_with("+kernel"));
    assert_eq!(TranslucencyParams::fitted(Some(&alone), "shadow-map", true).1, FitOrigin::FittedAlone);
    // skin2 (nobody fitted it) gets skin1's; a copy of marble without its fits gets marble's; the
    // apple (very little absorption) a milk's or marble's, never skin's or ketchup's.
    let skin2 = Medium::builtin("skin2").expect("skin2");
    assert!(skin2.translucency.is_empty(), "the test needs an unfitted medium");
    assert_eq!(
        TranslucencyParams::fitted(Some(&skin2), "shadow-map", true),
        (own("shadow-map+kernel"), FitOrigin::Nearest("skin1".into()))
    );
    let mut marble = Medium::builtin("marble").expect("marble");
    let marble_fit = TranslucencyParams::for_medium(Some(&marble), "baked").0;
    marble.translucency.clear();
    marble.name = "marble, unfitted".into();
    assert_eq!(
        TranslucencyParams::fitted(Some(&marble), "baked", false),
        (marble_fit, FitOrigin::Nearest("marble".into()))
    );
    let apple = Medium::builtin("apple").expect("apple");
    let (_, origin) = TranslucencyParams::fitted(Some(&apple), "baked", false);
    assert!(matches!(&origin, FitOrigin::Nearest(n) if n == "skimmilk" || n == "marble"), "{origin:?}");
    // No medium: the three.js defaults.
    assert_eq!(TranslucencyParams::fitted(None, "baked", true), (TranslucencyParams::THREE_JS, FitOrigin::Defaults));
}
