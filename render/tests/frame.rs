//! Whole frames on a real wgpu device (Mesa lavapipe on CI): physics checks and golden images.
//!
//! `UPDATE_SNAPSHOTS=1 cargo test -p rouge-render --test render frame::` rewrites the golden PNGs in
//! render/tests/golden/ (look at them before committing).

#![allow(clippy::needless_range_loop)] // RGB channels are indexed by number.

use glam::Vec3;
use rouge_measure::colorimetry::{delta_e_2000_raw, linear_srgb_to_lab, srgb_decode};
use rouge_model::look::{Look, builtin_preset};
use rouge_model::mesh::TriangleMesh;
use rouge_model::mesh::load_mesh;
use rouge_render::renderer::FrameCapture;
use rouge_render::sss::{SeparableKernel, SkinImage, separable_pass_cpu};
use rouge_render::{Camera, Gpu, Renderer, Scene};
use std::path::{Path, PathBuf};
use std::sync::OnceLock;

fn head() -> &'static TriangleMesh {
    static HEAD: OnceLock<TriangleMesh> = OnceLock::new();
    HEAD.get_or_init(|| load_mesh(None, 1.0, 1).expect("default head"))
}

fn renderer(mesh: &TriangleMesh, look: &Look, scene: &Scene) -> (Gpu, Renderer) {
    let gpu = Gpu::headless().expect("a wgpu adapter (install mesa-vulkan-drivers for lavapipe)");
    // tests/run.sh runs the golden test again with WGPU_BACKEND=gl: make sure it got GL.
    if std::env::var("WGPU_BACKEND").is_ok_and(|b| b.eq_ignore_ascii_case("gl")) {
        assert_eq!(gpu.adapter.get_info().backend, wgpu::Backend::Gl, "WGPU_BACKEND=gl gave {}", gpu.describe());
    }
    let mut r = Renderer::new(&gpu.device, &gpu.queue);
    r.set_mesh(mesh, scene.skin.albedo).expect("mesh");
    r.set_look(look).expect("look");
    (gpu, r)
}

fn camera(r: &Renderer) -> Camera {
    Camera::framing(&r.mesh_bounds().expect("bounds"), 0.0, 0.0)
}

fn look(json_layers: &str) -> Look {
    let text = format!(r#"{{"schema": "rouge-look", "version": 1, "name": "test", "layers": [{json_layers}]}}"#);
    Look::from_json(&text, Path::new("test-look.json")).expect("look")
}

fn render_display(mesh: &TriangleMesh, look: &Look, scene: &Scene, w: u32, h: u32) -> Vec<u8> {
    let (_gpu, mut r) = renderer(mesh, look, scene);
    let cam = camera(&r);
    r.render(scene, &cam, w, h, true).expect("render");
    r.read_display().expect("read")
}

fn render_linear(mesh: &TriangleMesh, look: &Look, scene: &Scene, w: u32, h: u32) -> (Vec<[f32; 4]>, FrameCapture) {
    let (_gpu, mut r) = renderer(mesh, look, scene);
    let cam = camera(&r);
    r.render(scene, &cam, w, h, false).expect("render");
    (r.read_linear().expect("read"), r.capture().expect("capture"))
}

/// A 200 mm square in the z = 0 plane facing +Z, UVs 0..1.
fn plane() -> TriangleMesh {
    TriangleMesh::flat_square(200.0)
}

#[test]
fn layers_of_zero_thickness_render_exactly_as_bare_skin() {
    let scene = Scene::studio();
    let zero = look(
        r#"{"preset": "builtin:foundation_02_ivory", "thickness": {"uniform_mm": 0}},
           {"preset": "builtin:blush_01_petal", "thickness": {"region": "cheeks", "thickness_mm": 0}},
           {"preset": "builtin:lipstick_02_red", "thickness": {"uniform_mm": 0}}"#,
    );
    let bare = render_display(head(), &Look::bare(), &scene, 256, 192);
    let zeroed = render_display(head(), &zero, &scene, 256, 192);
    let differing = bare.chunks(4).zip(zeroed.chunks(4)).filter(|(a, b)| a != b).count();
    assert_eq!(differing, 0, "{differing} pixels differ between bare skin and zero-thickness layers");
    // And the layers do show once they have thickness.
    let thick = look(r#"{"preset": "builtin:foundation_02_ivory", "thickness": {"uniform_mm": 0.02}}"#);
    let covered = render_display(head(), &thick, &scene, 256, 192);
    assert!(bare.chunks(4).zip(covered.chunks(4)).filter(|(a, b)| a != b).count() > 5000);
}

#[test]
fn thick_opaque_layer_under_white_light_shows_its_r_inf() {
    let mut scene = Scene::white_light(Vec3::Z);
    scene.specular = false;
    for name in
        ["foundation_02_ivory", "foundation_05_espresso", "lipstick_02_red", "eyeshadow_02_sapphire", "blush_01_petal"]
    {
        let preset = builtin_preset(name).expect("builtin preset");
        let one = look(&format!(r#"{{"preset": "builtin:{name}", "thickness": {{"uniform_mm": 5}}}}"#));
        let (linear, _) = render_linear(&plane(), &one, &scene, 64, 64);
        let centre = linear[32 * 64 + 32];
        let rendered = linear_srgb_to_lab([centre[0] as f64, centre[1] as f64, centre[2] as f64]);
        let expected = linear_srgb_to_lab(preset.derived.r_inf_linear_srgb);
        let de = delta_e_2000_raw(rendered, expected);
        assert!(de < 2.0, "{name}: rendered {centre:?} vs R∞ {:?}: ΔE2000 {de:.3}", preset.derived.r_inf_linear_srgb);
        eprintln!("{name}: ΔE2000 {de:.4}");
    }
}

fn srgb8_to_lab(p: &[u8]) -> [f64; 3] {
    linear_srgb_to_lab([0, 1, 2].map(|i| srgb_decode(p[i] as f64 / 255.0)))
}

#[test]
fn sss_at_width_zero_is_the_identity() {
    let mut scene = Scene::studio();
    scene.sss.width = 0.0;
    scene.sss.run_at_zero_width = true;
    let (_, cap) = render_linear(head(), &Look::default_look(), &scene, 256, 192);
    // The weights sum to 1 within f32 rounding, and the passes store half floats, which the
    // driver may round toward zero: each pass may move a value by one f16 step.
    let mut worst_steps = 0.0f32;
    for (a, b) in cap.diffuse.iter().zip(&cap.scattered) {
        for ch in 0..3 {
            let step = 2f32.powi(a[ch].abs().max(6.1e-5).log2().floor() as i32 - 10);
            worst_steps = worst_steps.max((a[ch] - b[ch]).abs() / step);
        }
    }
    assert!(worst_steps <= 2.0, "a value moved by {worst_steps} half-float steps");
}

#[test]
fn gpu_blur_matches_its_cpu_twin() {
    let scene = Scene::studio();
    let (_, cap) = render_linear(head(), &Look::default_look(), &scene, 256, 192);
    let (w, h) = (cap.width, cap.height);
    let rgb: Vec<[f32; 3]> = cap.diffuse.iter().map(|p| [p[0], p[1], p[2]]).collect();
    let skin: Vec<bool> = cap.diffuse.iter().map(|p| p[3] > 0.5).collect();
    let img =
        SkinImage { width: w, height: h, rgb: &rgb, skin: &skin, depth_mm: &cap.depth_mm, focal_px: cap.focal_px };
    let kernel = SeparableKernel::new(
        scene.skin.subsurface.profile().expect("screen-space model"),
        scene.sss.samples,
        scene.sss.range_sigmas as f64,
    )
    .expect("kernel");
    let hpass = separable_pass_cpu(&img, &kernel, scene.sss.width, scene.sss.follow_mm, true);
    let hpass_img = SkinImage { rgb: &hpass, ..img };
    let cpu = separable_pass_cpu(&hpass_img, &kernel, scene.sss.width, scene.sss.follow_mm, false);
    let (mut sum, mut n, mut worst) = (0.0f64, 0usize, 0.0f32);
    for i in 0..w * h {
        if !skin[i] {
            continue;
        }
        for ch in 0..3 {
            let d = (cap.scattered[i][ch] - cpu[i][ch]).abs();
            sum += d as f64;
            worst = worst.max(d);
            n += 1;
        }
    }
    let mean = sum / n as f64;
    let peak = rgb.iter().flat_map(|p| p.iter().copied()).fold(0.0f32, f32::max);
    // Half-float storage of the intermediate and the hardware's bilinear weights (8 bits of
    // sub-texel precision on lavapipe) account for the difference.
    assert!(mean < 2e-3 * peak as f64, "mean |GPU − CPU| {mean} (peak radiance {peak})");
    assert!(worst < 0.05 * peak, "worst |GPU − CPU| {worst} (peak radiance {peak})");
    // And the blur does something: it changes skin pixels.
    let changed = (0..w * h).filter(|&i| skin[i] && (cap.scattered[i][0] - rgb[i][0]).abs() > 1e-3 * peak).count();
    assert!(changed > 1000, "{changed} pixels changed by the blur");
}

#[test]
fn lipstick_changes_pixels_only_inside_the_lip_mask() {
    let lipstick =
        look(r#"{"preset": "builtin:lipstick_02_red", "thickness": {"region": "lips", "thickness_mm": 0.02}}"#);
    for sss_on in [false, true] {
        let mut scene = Scene::studio();
        if !sss_on {
            scene.sss.width = 0.0;
        }
        let (w, h) = (320, 240);
        let (bare, _) = render_linear(head(), &Look::bare(), &scene, w, h);
        let (lips, cap) = render_linear(head(), &lipstick, &scene, w, h);
        let in_mask: Vec<bool> = cap.thickness.iter().map(|t| t[0] > 0.0).collect();
        let mask_pixels = in_mask.iter().filter(|&&m| m).count();
        assert!(mask_pixels > 150, "the lip mask covers only {mask_pixels} pixels");
        // Scattered light may leave the skin up to the profile's support away from the lips.
        let support_px = if sss_on {
            let z = cap.depth_mm[in_mask.iter().position(|&m| m).expect("mask pixel")];
            (3.0 * scene.skin.subsurface.profile().expect("screen-space model").max_sigma_mm() as f32 * cap.focal_px
                / z)
                .ceil() as i64
        } else {
            1
        };
        let near_mask = dilate(&in_mask, w as usize, h as usize, support_px);
        let (mut inside_changed, mut outside_changed) = (0, 0);
        for i in 0..(w * h) as usize {
            let changed = (0..3).any(|c| bare[i][c] != lips[i][c]);
            if changed && near_mask[i] {
                inside_changed += 1;
            } else if changed {
                outside_changed += 1;
            }
        }
        assert_eq!(outside_changed, 0, "sss {sss_on}: {outside_changed} pixels changed away from the lips");
        assert!(inside_changed > mask_pixels / 2, "sss {sss_on}: only {inside_changed} pixels changed");
        // The lips sit below the middle of the face: the mask's centroid is in the lower half.
        let cy = (0..(w * h) as usize).filter(|&i| in_mask[i]).map(|i| i / w as usize).sum::<usize>() / mask_pixels;
        assert!(cy > h as usize / 2, "lip centroid row {cy}");
    }
}

fn dilate(mask: &[bool], w: usize, h: usize, r: i64) -> Vec<bool> {
    let mut out = vec![false; mask.len()];
    for y in 0..h as i64 {
        for x in 0..w as i64 {
            if !mask[(y * w as i64 + x) as usize] {
                continue;
            }
            for dy in -r..=r {
                for dx in -r..=r {
                    let (qx, qy) = (x + dx, y + dy);
                    if qx >= 0 && qy >= 0 && qx < w as i64 && qy < h as i64 {
                        out[(qy * w as i64 + qx) as usize] = true;
                    }
                }
            }
        }
    }
    out
}

fn golden_dir() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("tests/golden")
}

/// Compares a frame with its golden PNG by ΔE2000 per pixel: mean < 0.5, 99th percentile < 3,
/// and at most 0.2% of pixels over 5 (rasterisation and driver differences move a few edge
/// pixels, not colours; a missing lipstick alone is ~0.5% of the pixels at ΔE > 20).
fn check_golden(name: &str, rgba: &[u8], w: u32, h: u32) {
    let path = golden_dir().join(format!("{name}.png"));
    if std::env::var_os("UPDATE_SNAPSHOTS").is_some_and(|v| v == "1") {
        std::fs::create_dir_all(golden_dir()).expect("golden dir");
        rouge_render::job::write_png(&path, w, h, rgba).expect("write golden");
        eprintln!("updated {}", path.display());
        return;
    }
    let golden = image::open(&path)
        .unwrap_or_else(|e| panic!("{}: {e} (run with UPDATE_SNAPSHOTS=1 to create it)", path.display()))
        .to_rgba8();
    assert_eq!((golden.width(), golden.height()), (w, h), "{name}: golden size");
    let mut de: Vec<f64> = rgba
        .chunks(4)
        .zip(golden.as_raw().chunks(4))
        .map(|(a, b)| delta_e_2000_raw(srgb8_to_lab(a), srgb8_to_lab(b)))
        .collect();
    de.sort_by(f64::total_cmp);
    let mean = de.iter().sum::<f64>() / de.len() as f64;
    let p99 = de[de.len() * 99 / 100];
    let large = de.iter().filter(|&&d| d > 5.0).count();
    if mean >= 0.5 || p99 >= 3.0 || large * 500 > de.len() {
        let out = std::env::temp_dir().join(format!("rouge-{name}-actual.png"));
        let _ = rouge_render::job::write_png(&out, w, h, rgba);
        panic!(
            "{name}: mean ΔE2000 {mean:.3}, p99 {p99:.3}, {large} pixels over 5, against {}; this frame: {}",
            path.display(),
            out.display()
        );
    }
}

#[test]
fn golden_default_look_and_bare_skin() {
    let scene = Scene::studio();
    let (w, h) = (320, 240);
    check_golden("default_look", &render_display(head(), &Look::default_look(), &scene, w, h), w, h);
    check_golden("bare", &render_display(head(), &Look::bare(), &scene, w, h), w, h);
}

#[test]
fn bad_requests_are_errors_not_panics() {
    let scene = Scene::studio();
    let (_gpu, mut r) = renderer(head(), &Look::bare(), &scene);
    let cam = camera(&r);
    assert!(r.render(&scene, &cam, 0, 10, true).is_err());
    let mut even = scene.clone();
    even.sss.samples = 16;
    let e = r.render(&even, &cam, 32, 32, true).expect_err("even sample count");
    assert!(e.to_string().contains("odd"), "{e}");
    let mut many = scene.clone();
    many.lights = vec![scene.lights[0]; 5];
    assert!(r.render(&many, &cam, 32, 32, true).is_err());
    let gpu = Gpu::headless().expect("gpu");
    let mut empty = Renderer::new(&gpu.device, &gpu.queue);
    assert!(empty.render(&scene, &cam, 32, 32, true).is_err(), "no mesh");
}

#[test]
fn albedo_texture_and_normal_map_reach_the_frame() {
    let mut scene = Scene::white_light(Vec3::Z);
    scene.specular = false;
    scene.sss.width = 0.0;
    let mut mesh = plane();
    mesh.generate_tangents().expect("tangents");
    let gpu = Gpu::headless().expect("gpu");
    let mut r = Renderer::new(&gpu.device, &gpu.queue);
    r.set_mesh(&mesh, [0.5; 3]).expect("mesh");
    r.set_look(&Look::bare()).expect("look");
    let cam = camera(&r);
    // Left half of the texture red, right half green (sRGB 255 = linear 1).
    let albedo = image::RgbaImage::from_fn(2, 1, |x, _| {
        if x == 0 { image::Rgba([255, 0, 0, 255]) } else { image::Rgba([0, 255, 0, 255]) }
    });
    r.set_textures(Some(&albedo), None).expect("textures");
    r.render(&scene, &cam, 64, 64, false).expect("render");
    let flat = r.read_linear().expect("read");
    let (left, right) = (flat[32 * 64 + 8], flat[32 * 64 + 56]);
    assert!(left[0] > 0.9 && left[1] < 0.05, "left {left:?}");
    assert!(right[1] > 0.9 && right[0] < 0.05, "right {right:?}");
    // A normal map tilting every normal 30° about V: n·l = cos 30° under the frontal light.
    let tilt = image::RgbaImage::from_pixel(4, 4, image::Rgba([191, 128, 238, 255]));
    r.set_textures(Some(&albedo), Some(&tilt)).expect("textures");
    r.render(&scene, &cam, 64, 64, false).expect("render");
    let tilted = r.read_linear().expect("read");
    let ratio = tilted[32 * 64 + 8][0] / left[0];
    let m = [191.0f32, 128.0, 238.0].map(|c| c / 255.0 * 2.0 - 1.0);
    let expected = m[2] / (m[0] * m[0] + m[1] * m[1] + m[2] * m[2]).sqrt();
    assert!((ratio - expected).abs() < 0.02, "lit by n·l {ratio} vs {expected}");
    // Without tangents a normal map is refused.
    let mut plain = Renderer::new(&gpu.device, &gpu.queue);
    plain.set_mesh(&plane(), [0.5; 3]).expect("mesh");
    assert!(plain.set_textures(None, Some(&tilt)).is_err());
}

#[test]
fn point_light_shadows_and_an_exr_environment_render() {
    use rouge_render::{Light, LightKind};
    let mut scene = Scene::studio();
    scene.lights = vec![Light {
        kind: LightKind::Point { position: Vec3::new(-300.0, 200.0, 400.0) },
        irradiance: [3.0; 3],
        shadows: true,
        translucency_scale: 1.0,
    }];
    // An environment from an EXR file: bright above, dark below.
    let dir = tempfile::tempdir().expect("tempdir");
    let exr = dir.path().join("sky.exr");
    let (w, h) = (32, 16);
    let texels: Vec<[f32; 4]> =
        (0..w * h).map(|i| if i / w < h / 2 { [0.4, 0.45, 0.5, 1.0] } else { [0.02, 0.02, 0.02, 1.0] }).collect();
    rouge_render::job::write_exr(&exr, w as u32, h as u32, &texels).expect("write exr");
    scene.environment = Some(rouge_render::env::EnvMap::load_exr(&exr).expect("load exr").sh_irradiance());
    let (linear, cap) = render_linear(head(), &Look::default_look(), &scene, 160, 120);
    let skin = cap.diffuse.iter().filter(|p| p[3] > 0.5).count();
    assert!(skin > 2000, "{skin} skin pixels");
    assert!(linear.iter().all(|p| p.iter().all(|v| v.is_finite())), "non-finite radiance");
    // The point light at the upper left casts the nose's shadow to the lower right: the face's
    // left (image right) is darker than its right (image left) on average.
    let mean_x = |lo: usize, hi: usize| {
        let px: Vec<f32> = (0..160 * 120)
            .filter(|i| (lo..hi).contains(&(i % 160)) && cap.diffuse[*i][3] > 0.5)
            .map(|i| linear[i][1])
            .collect();
        px.iter().sum::<f32>() / px.len().max(1) as f32
    };
    assert!(mean_x(50, 80) > mean_x(80, 110), "lit side {} vs far side {}", mean_x(50, 80), mean_x(80, 110));
}

#[test]
fn the_scanned_head_renders_when_available() {
    let Some(path) = std::env::var_os("ROUGE_SCAN_HEAD") else {
        eprintln!("skipped: set ROUGE_SCAN_HEAD to ../shared/data/heads/LeePerrySmith.glb to render the scanned head");
        return;
    };
    let scale: f32 = std::env::var("ROUGE_SCAN_SCALE_TO_MM").ok().and_then(|s| s.parse().ok()).unwrap_or(25.0);
    let mesh = load_mesh(Some(Path::new(&path)), scale, 0).expect("scan loads");
    let (_, cap) = render_linear(&mesh, &Look::bare(), &Scene::studio(), 160, 120);
    let skin = cap.diffuse.iter().filter(|p| p[3] > 0.5).count();
    assert!(skin > 3000, "{skin} skin pixels of the scan");
}

#[test]
fn picking_and_captures_read_depth_on_every_backend() {
    // On GL, depth cannot be copied to a buffer: the renderer reads it through the depth copy
    // pass (tests/run.sh runs this test with WGPU_BACKEND=gl too).
    let scene = Scene::studio();
    let (_gpu, mut r) = renderer(head(), &Look::bare(), &scene);
    let cam = camera(&r);
    let (w, h) = (160, 120);
    r.render(&scene, &cam, w, h, false).expect("render");
    let hit = r.pick(w / 2, h / 2).expect("pick").expect("the face is under the centre");
    let (px, py) = r.project(hit).expect("in front of the camera");
    assert!((px - (w / 2) as f32 - 0.5).abs() < 0.6 && (py - (h / 2) as f32 - 0.5).abs() < 0.6, "{px}, {py}");
    assert_eq!(r.pick(0, 0).expect("pick"), None, "the corner is background");
    let cap = r.capture().expect("capture");
    let z = cap.depth_mm[(h / 2 * w + w / 2) as usize];
    let expected = (hit - cam.position()).dot((cam.target - cam.position()).normalize());
    assert!((z - expected).abs() < 0.5, "view depth {z} mm vs {expected} mm");
}

#[test]
fn a_still_frame_keeps_its_shadow_map_and_a_moved_light_or_mesh_draws_it_again() {
    use rouge_render::frame::Step;
    use rouge_render::scene::LightKind;
    let (w, h) = (96, 72);
    let scene = Scene::studio();
    let bare = Look::bare();
    let (_gpu, mut r) = renderer(head(), &bare, &scene);
    let cam = camera(&r);
    let shadow_passes = |r: &Renderer, scene: &Scene| {
        let plan = r.plan(scene, w, h, true).expect("plan");
        plan.passes.iter().filter(|p| matches!(p.step, Step::Shadow(_))).count()
    };
    let frame = |r: &mut Renderer, scene: &Scene| {
        r.render(scene, &cam, w, h, true).expect("render");
        r.read_display().expect("read")
    };
    assert_eq!(shadow_passes(&r, &scene), 1, "the first frame draws the studio's shadow map");
    let first = frame(&mut r, &scene);
    assert_eq!(shadow_passes(&r, &scene), 0, "a still frame keeps it");
    let explained = r.plan(&scene, w, h, true).expect("plan").explain();
    assert!(explained.contains("shadow map 0 is kept"), "{explained}");
    assert_eq!(frame(&mut r, &scene), first, "a kept shadow map gives the same frame");

    // Another light direction: drawn again, and the frame is a fresh renderer's.
    let mut turned = scene.clone();
    turned.lights[0].kind = LightKind::Directional { toward: Vec3::new(0.5, 0.45, 0.75).normalize() };
    assert_eq!(shadow_passes(&r, &turned), 1);
    let after_turn = frame(&mut r, &turned);
    assert_eq!(after_turn, render_display(head(), &bare, &turned, w, h), "the moved light's shadow is current");
    assert_ne!(after_turn, first, "the shadow moved");
    // Back to the first light: drawn again (the map holds the turned light's depths).
    assert_eq!(shadow_passes(&r, &scene), 1);
    assert_eq!(frame(&mut r, &scene), first);

    // A moved mesh (the app's expressions): drawn again, also at the same positions.
    r.move_mesh(head(), scene.skin.albedo).expect("move");
    assert_eq!(shadow_passes(&r, &scene), 1, "a posed mesh draws its shadow map");
    assert_eq!(frame(&mut r, &scene), first);

    // Told to redraw every frame (`rouge bench render`'s moving-light row).
    r.set_keep_shadow_maps(false);
    assert_eq!(shadow_passes(&r, &scene), 1);
    assert_eq!(frame(&mut r, &scene), first);
}
