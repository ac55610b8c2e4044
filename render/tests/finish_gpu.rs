//! Finishes on a real device (lavapipe on CI): the same foundation on the default head with a
//! matte, a satin, a dewy and a gloss finish (`rouge_measure::finish`), lit by the studio rig.
//! The surface radiance (stack reflectance + specular) is read from the lighting pass's target.

use rouge_measure::finish::FinishKind;
use rouge_model::look::Look;
use rouge_model::mesh::{TriangleMesh, load_mesh};
use rouge_render::{Camera, Gpu, Renderer, Scene};
use std::path::Path;
use std::sync::OnceLock;

fn head() -> &'static TriangleMesh {
    static HEAD: OnceLock<TriangleMesh> = OnceLock::new();
    HEAD.get_or_init(|| load_mesh(None, 1.0, 1).expect("default head"))
}

/// The default head under a uniform foundation (0.03 mm) with `finish` (or none), and the
/// surface radiance of every pixel on the skin (red channel, linear).
fn surface(gpu: &Gpu, finish: Option<FinishKind>) -> Vec<f32> {
    let text = r#"{"schema": "rouge-look", "version": 1, "name": "finish",
        "layers": [{"preset": "builtin:foundation_02_ivory", "thickness": {"uniform_mm": 0.03}}]}"#;
    let mut look = Look::from_json(text, Path::new("finish-look.json")).expect("look");
    look.layers[0].preset.set_finish(finish.map(FinishKind::defaults));
    let scene = Scene::studio();
    let mut r = Renderer::new(&gpu.device, &gpu.queue);
    r.set_mesh(head(), scene.skin.albedo).expect("mesh");
    r.set_look(&look).expect("look");
    let camera = Camera::framing(&r.mesh_bounds().expect("bounds"), 20.0, 0.0);
    r.render(&scene, &camera, 160, 120, false).expect("render");
    let cap = r.capture().expect("capture");
    cap.surface.iter().zip(&cap.exit_t).filter(|(s, _)| s[3] > 0.0).map(|(s, _)| s[0]).collect()
}

fn peak(v: &[f32]) -> f32 {
    v.iter().copied().fold(0.0, f32::max)
}

#[test]
fn a_matte_foundation_shines_less_than_a_gloss_on_the_same_face() {
    let gpu = Gpu::headless().expect("a wgpu adapter (install mesa-vulkan-drivers for lavapipe)");
    let peaks: Vec<(FinishKind, f32)> =
        FinishKind::ALL.into_iter().map(|k| (k, peak(&surface(&gpu, Some(k))))).collect();
    eprintln!("peak surface radiance per finish: {peaks:?}");
    for w in peaks.windows(2) {
        assert!(w[0].1 < w[1].1, "{:?} peaks at {} but {:?} at {}", w[0].0, w[0].1, w[1].0, w[1].1);
    }
    let (matte, gloss) = (peaks[0].1, peaks[3].1);
    assert!(gloss > 2.0 * matte, "gloss {gloss} against matte {matte}");
    // Every pixel is finite and none is negative.
    for k in FinishKind::ALL {
        assert!(surface(&gpu, Some(k)).iter().all(|v| v.is_finite() && *v >= 0.0), "{k:?}");
    }
}

#[test]
fn a_preset_without_a_finish_renders_as_before_and_a_powder_hides_the_skins_shine() {
    let gpu = Gpu::headless().expect("a wgpu adapter (install mesa-vulkan-drivers for lavapipe)");
    // Without a finish the film is clear (clarity 1): the skin's lobes pass it as T² alone. A
    // matte finish with the same lobe as the preset's own lets less of the skin's shine through.
    let clear = surface(&gpu, None);
    let text = r#"{"schema": "rouge-look", "version": 1, "name": "finish",
        "layers": [{"preset": "builtin:foundation_02_ivory", "thickness": {"uniform_mm": 0.03}}]}"#;
    let mut look = Look::from_json(text, Path::new("finish-look.json")).expect("look");
    let own = look.layers[0].preset.specular;
    let (_, mut matte) = FinishKind::Matte.defaults();
    matte.levelling = 0.0;
    look.layers[0].preset.set_finish(Some((own, matte)));
    let scene = Scene::studio();
    let mut r = Renderer::new(&gpu.device, &gpu.queue);
    r.set_mesh(head(), scene.skin.albedo).expect("mesh");
    r.set_look(&look).expect("look");
    let camera = Camera::framing(&r.mesh_bounds().expect("bounds"), 20.0, 0.0);
    r.render(&scene, &camera, 160, 120, false).expect("render");
    let cap = r.capture().expect("capture");
    let powdered: Vec<f32> = cap.surface.iter().filter(|s| s[3] > 0.0).map(|s| s[0]).collect();
    assert_eq!(powdered.len(), clear.len(), "same pixels");
    let (sum_clear, sum_powder) = (clear.iter().sum::<f32>(), powdered.iter().sum::<f32>());
    assert!(sum_powder < sum_clear, "powder {sum_powder} against a clear film {sum_clear}");
    assert!(powdered.iter().zip(&clear).all(|(p, c)| *p <= *c + 1e-4), "nowhere brighter");
}
