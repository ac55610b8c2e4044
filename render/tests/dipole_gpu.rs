//! The dipole models' passes on a real wgpu device: the gather over the light G-buffer converges
//! to the CPU BSSRDF's integral on a flat face, progressive accumulation converges, a point seen
//! from no direction gets nothing (and no NaN), and the passes exist only when a material uses a
//! dipole (frame plan).

use rouge_model::look::Look;
use rouge_model::medium::Medium;
use rouge_model::mesh::{TriangleMesh, load_mesh};
use rouge_render::directional_dipole::{DirectionalDipole, Geometry, standard_dipole_bssrdf, standard_dipole_profiles};
use rouge_render::{Camera, Gpu, LightRig, Renderer, Scene, Skin, SubsurfaceModel};
use rouge_render::{DipoleKind, DipoleSettings};
use std::f64::consts::PI;
use std::path::Path;

const SIZE: u32 = 96;

fn wedge() -> TriangleMesh {
    load_mesh(Some(Path::new("builtin:wedge")), 1.0, 0).expect("wedge")
}

fn marble() -> Medium {
    Medium::builtin("marble").expect("marble").with_eta(1.0).expect("eta")
}

fn scene(kind: DipoleKind, settings: DipoleSettings, rig: LightRig) -> Scene {
    let mut scene = Scene::rig(rig);
    let (skin, _) = Skin::from_medium(&marble(), rouge_render::diffusion::ProfileModel::BetterDipole);
    scene.skin = Skin { subsurface: SubsurfaceModel::Dipole { kind, settings }, ..skin };
    scene.specular = false;
    scene
}

/// Linear frames of `scene` after each of `frames` frames, on the wedge seen from +Z (yaw `yaw`).
fn frames(gpu: &Gpu, scene: &Scene, yaw: f32, frames: u32) -> Vec<Vec<[f32; 4]>> {
    let mesh = wedge();
    let mut r = Renderer::new(&gpu.device, &gpu.queue);
    r.set_mesh(&mesh, scene.skin.albedo).expect("mesh");
    r.set_look(&Look::bare()).expect("look");
    let camera = Camera::framing(&r.mesh_bounds().expect("bounds"), yaw, 0.0);
    (0..frames)
        .map(|_| {
            r.render(scene, &camera, SIZE, SIZE, false).expect("render");
            r.read_linear().expect("read")
        })
        .collect()
}

/// π ∫ S dA on a flat half-space at normal incidence and exit: what a front-lit flat face shows.
fn planar(s: impl Fn(f64) -> f64) -> f64 {
    let n = 20000;
    (0..n)
        .map(|k| {
            let u = (k as f64 + 0.5) / n as f64;
            let r = u / (1.0 - u) * 10.0;
            s(r) * 2.0 * PI * r * 10.0 / ((1.0 - u) * (1.0 - u)) / n as f64
        })
        .sum::<f64>()
        * PI
}

#[test]
fn the_gather_converges_to_the_bssrdf_integral_on_a_front_lit_face() {
    let gpu = Gpu::headless().expect("a wgpu adapter (install mesa-vulkan-drivers for lavapipe)");
    let m = marble();
    let standard = standard_dipole_profiles(&m);
    let settings = DipoleSettings { directions: 4, samples: 32, ..Default::default() };
    for kind in [DipoleKind::Standard, DipoleKind::Directional, DipoleKind::DirectionalMeanFreePath] {
        let images = frames(&gpu, &scene(kind, settings, LightRig::Front), 0.0, 12);
        let last = images.last().expect("frames");
        // The middle of the front face, 8×8 pixels.
        let c = SIZE as usize / 2;
        let mut mean = [0.0f64; 3];
        for y in c - 4..c + 4 {
            for x in c - 4..c + 4 {
                for ch in 0..3 {
                    mean[ch] += f64::from(last[y * SIZE as usize + x][ch]) / 64.0;
                }
            }
        }
        for (ch, got) in mean.iter().enumerate() {
            let expected = match kind.source() {
                None => planar(|r| standard_dipole_bssrdf(&standard, 1.0, &Geometry::planar(r))[ch]),
                Some(source) => {
                    let directional = DirectionalDipole::with_source(&m, source);
                    planar(|r| directional.bssrdf(&Geometry::planar(r))[ch])
                }
            };
            // The face is 60 × 40 mm, so a little of the far tail is missing; Monte Carlo noise.
            assert!((got - expected).abs() < 0.06 * expected, "{kind:?} channel {ch}: GPU {got}, CPU {expected}");
        }
    }
}

#[test]
fn progressive_accumulation_converges_and_unseen_points_get_nothing() {
    let gpu = Gpu::headless().expect("gpu");
    let settings = DipoleSettings { directions: 4, samples: 4, ..Default::default() };
    let images = frames(&gpu, &scene(DipoleKind::Standard, settings, LightRig::Front), 0.0, 24);
    let reference = images.last().expect("frames");
    let rms = |img: &[[f32; 4]]| -> f64 {
        let sum: f64 =
            img.iter().zip(reference).map(|(a, b)| (0..3).map(|c| f64::from(a[c] - b[c]).powi(2)).sum::<f64>()).sum();
        (sum / img.len() as f64).sqrt()
    };
    let (e1, e4, e12) = (rms(&images[0]), rms(&images[3]), rms(&images[11]));
    assert!(e1 > e4 && e4 > e12, "error against frame 24 after 1, 4, 12 frames: {e1} {e4} {e12}");
    assert!(images.iter().flatten().all(|p| p.iter().all(|v| v.is_finite())), "a non-finite pixel");
    // One direction (+Z) and the camera behind: the back faces it sees are seen by no direction.
    let one = DipoleSettings { directions: 1, samples: 4, ..Default::default() };
    let behind = frames(&gpu, &scene(DipoleKind::Directional, one, LightRig::Front), 180.0, 1);
    assert!(behind[0].iter().all(|p| p.iter().all(|v| v.is_finite())));
    let lit = behind[0].iter().filter(|p| p[0] > 1e-4).count();
    assert_eq!(lit, 0, "{lit} pixels lit behind the only direction");
}

#[test]
fn the_passes_exist_only_when_a_material_uses_a_dipole() {
    let gpu = Gpu::headless().expect("gpu");
    let mut r = Renderer::new(&gpu.device, &gpu.queue);
    r.set_mesh(&wedge(), [0.5; 3]).expect("mesh");
    let mut s = scene(DipoleKind::Directional, DipoleSettings::default(), LightRig::Back);
    let steps =
        |plan: &rouge_render::frame::FramePlan| -> Vec<String> { plan.passes.iter().map(|p| p.step.name()).collect() };
    let plan = r.plan(&s, 64, 64, true).expect("plan");
    assert!(steps(&plan).ends_with(&[
        "dipole light".to_string(),
        "dipole radiance".into(),
        "dipole combine".into(),
        "composite".into()
    ]));
    assert!(plan.variant.dipole && plan.kernel.is_none());
    s.skin.subsurface = SubsurfaceModel::None;
    let plan = r.plan(&s, 64, 64, true).expect("plan");
    assert!(!steps(&plan).iter().any(|n| n.starts_with("dipole")) && !plan.variant.dipole);
    assert!(plan.explain().contains("no material uses a dipole model"));
    // A dipole without a medium is an error that says what to give.
    let mut no_medium = scene(DipoleKind::Standard, DipoleSettings::default(), LightRig::Back);
    no_medium.skin.medium = None;
    let err = r.plan(&no_medium, 64, 64, true).expect_err("no medium");
    assert!(err.to_string().contains("--medium"), "{err}");
    // Point lights take no part, and the plan says so.
    let mut studio = scene(DipoleKind::Directional, DipoleSettings::default(), LightRig::Studio);
    studio.skin.medium = Some(marble());
    let text = r.plan(&studio, 64, 64, true).expect("plan").explain();
    assert!(text.contains("dipole light G-buffer of light 1 (point)"), "{text}");
}
