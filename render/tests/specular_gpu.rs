//! The lighting shader's specular lobes (the skin's two, a shimmer's) against their CPU twin
//! (`rouge_render::specular`), on a real device (lavapipe on CI): a flat skin plane under one
//! directional light, no environment, no subsurface model, so the surface radiance is
//! E (n·l) f_r(l, v) exactly (bare look), and a shimmer adds exactly its lobe.

use glam::{DVec3, Vec3};
use rouge_model::look::Look;
use rouge_model::mesh::TriangleMesh;
use rouge_render::specular::skin_lobes;
use rouge_render::{Camera, Gpu, Renderer, Scene, SubsurfaceModel};

/// A 200 mm square in the z = 0 plane facing +Z, UVs 0..1.
fn plane() -> TriangleMesh {
    TriangleMesh::flat_square(200.0)
}

/// The device, one white directional light from `toward` with specular on and no subsurface
/// model, and a camera close and oblique to the plane, so that the view direction sweeps through
/// the highlight.
fn lit_plane() -> (Gpu, Scene, Vec3, Camera) {
    let gpu = Gpu::headless().expect("a wgpu adapter (install mesa-vulkan-drivers for lavapipe)");
    let toward = Vec3::new(0.35, 0.25, 1.0).normalize();
    let mut scene = Scene::white_light(toward);
    scene.skin.subsurface = SubsurfaceModel::None;
    scene.specular = true;
    let camera = Camera { target: Vec3::ZERO, distance: 260.0, yaw_deg: -20.0, pitch_deg: -10.0, fov_y_deg: 40.0 };
    (gpu, scene, toward, camera)
}

/// Every third pixel of a `w` × `h` frame of `r` that shows the plane: its index in the frame and
/// the unit direction from its surface point toward the camera.
fn plane_pixels(r: &Renderer, camera: &Camera, (w, h): (u32, u32)) -> Vec<(usize, DVec3)> {
    let eye = camera.position().as_dvec3();
    let mut out = Vec::new();
    for y in (0..h).step_by(3) {
        for x in (0..w).step_by(3) {
            if let Some(world) = r.pick(x, y).expect("pick") {
                out.push(((y * w + x) as usize, (eye - world.as_dvec3()).normalize()));
            }
        }
    }
    out
}

#[test]
fn the_shader_lobe_matches_its_cpu_twin() {
    let (gpu, scene, toward, camera) = lit_plane();
    let mut r = Renderer::new(&gpu.device, &gpu.queue);
    r.set_mesh(&plane(), scene.skin.albedo).expect("mesh");
    r.set_look(&Look::bare()).expect("look");
    let (w, h) = (96u32, 72u32);
    r.render(&scene, &camera, w, h, false).expect("render");
    let cap = r.capture().expect("capture");
    let (m, f0) = (scene.skin.roughness as f64, scene.skin.f0() as f64);
    let l = toward.as_dvec3();
    let e = scene.lights[0].irradiance[0] as f64 * l.z;
    let (mut checked, mut worst, mut peak) = (0, 0.0f64, 0.0f64);
    for (i, v) in plane_pixels(&r, &camera, (w, h)) {
        let want = e * skin_lobes(DVec3::Z, l, v, m, f0);
        let got = cap.surface[i][0] as f64;
        let err = (got - want).abs() / want.max(1e-3);
        worst = worst.max(err);
        peak = peak.max(want);
        checked += 1;
    }
    eprintln!("{checked} pixels, peak E·f_r {peak:.4}, worst relative error {worst:.2e}");
    assert!(checked > 300, "only {checked} pixels on the plane");
    assert!(peak > 0.05, "the highlight is not in view (peak {peak})");
    // Tolerance: the surface target is Rgba16Float, whose rounding alone is up to 2⁻¹¹ ≈ 4.9e-4
    // relative; the shader's f32 exp and pow add ~1e-6, and the view vector comes from the
    // position reconstructed from Depth32Float (the CPU side uses the same depth through `pick`).
    // Lavapipe measured 9.4e-4; 5e-3 (ten f16 roundings) leaves room for drivers with looser
    // transcendentals, and is still far below a wrong term (a factor 2, π or n·l is off by
    // tens of percent over this view).
    assert!(worst < 5e-3, "worst relative error {worst} over {checked} pixels");
}

#[test]
fn a_shimmers_lobe_matches_its_cpu_twin() {
    use rouge_measure::finish::{FinishKind, Shimmer};
    use rouge_render::specular::ShimmerLobe;
    let (gpu, scene, toward, camera) = lit_plane();
    let (w, h) = (96u32, 72u32);
    let gold = Shimmer { film_nm: 110.0, strength: 0.6, spread: 0.25 };
    // The same eyeshadow, 20 µm, with and without the shimmer: the difference is the shimmer's lobe.
    let render = |shimmer: Option<Shimmer>| {
        let text = r#"{"schema": "rouge-look", "version": 1, "name": "shimmer",
            "layers": [{"preset": "builtin:eyeshadow_03_bronze", "thickness": {"uniform_mm": 0.02}}]}"#;
        let mut look = Look::from_json(text, std::path::Path::new("shimmer.json")).expect("look");
        let (lobe, mut film) = FinishKind::Satin.defaults();
        film.shimmer = shimmer;
        look.layers[0].preset.set_finish(Some((lobe, film)));
        let mut r = Renderer::new(&gpu.device, &gpu.queue);
        r.set_mesh(&plane(), scene.skin.albedo).expect("mesh");
        r.set_look(&look).expect("look");
        r.render(&scene, &camera, w, h, false).expect("render");
        (r.capture().expect("capture"), r)
    };
    let (plain, _) = render(None);
    let (shiny, r) = render(Some(gold));
    let table = gold.interference_table(rouge_measure::layer_table::TABLE_ENTRIES);
    let lobe = ShimmerLobe { strength: gold.strength, spread: gold.spread, table: &table };
    let l = toward.as_dvec3();
    let e = scene.lights[0].irradiance[0] as f64 * l.z;
    let (mut checked, mut worst, mut peak) = (0, 0.0f64, 0.0f64);
    for (i, v) in plane_pixels(&r, &camera, (w, h)) {
        let want = lobe.eval(DVec3::Z, l, v).map(|c| e * c);
        for (c, want) in want.into_iter().enumerate() {
            let got = f64::from(shiny.surface[i][c] - plain.surface[i][c]);
            worst = worst.max((got - want).abs() / want.max(5e-2));
            peak = peak.max(want);
        }
        checked += 1;
    }
    eprintln!("{checked} pixels, peak shimmer {peak:.4}, worst relative error {worst:.2e}");
    assert!(checked > 300 && peak > 0.05, "{checked} pixels, peak {peak}");
    // Two f16 targets subtracted (each rounded to 2⁻¹¹ of values up to ~1: a few 1e-4 absolute),
    // and the table's f32 entries; a wrong term would be off by tens of percent.
    assert!(worst < 1e-2, "worst relative error {worst}");
}
