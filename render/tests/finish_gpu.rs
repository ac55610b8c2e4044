//! Finishes on a real device (lavapipe on CI): the same foundation on the default head with a
//! matte, a satin, a dewy and a gloss finish (`rouge_measure::finish`), lit by the studio rig.
//! The surface radiance (stack reflectance + specular) is read from the lighting pass's target.
//! With the skin's microgeometry (`rouge_model::skin::detail`): pores show in the highlights of
//! bare skin and a levelling film fills them as it thickens.

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
    surface_of(gpu, |preset| preset.set_finish(finish.map(FinishKind::defaults)))
}

/// [`surface`] with the foundation's preset changed by `change`.
fn surface_of(gpu: &Gpu, change: impl FnOnce(&mut rouge_measure::Preset)) -> Vec<f32> {
    let text = r#"{"schema": "rouge-look", "version": 1, "name": "finish",
        "layers": [{"preset": "builtin:foundation_02_ivory", "thickness": {"uniform_mm": 0.03}}]}"#;
    let mut look = Look::from_json(text, Path::new("finish-look.json")).expect("look");
    change(&mut look.layers[0].preset);
    let scene = Scene::studio();
    let mut r = Renderer::new(&gpu.device, &gpu.queue);
    r.set_mesh(head(), scene.skin.albedo).expect("mesh");
    r.set_look(&look).expect("look");
    let camera = Camera::framing(&r.mesh_bounds().expect("bounds"), 20.0, 0.0);
    r.render(&scene, &camera, 160, 120, false).expect("render");
    let cap = r.capture().expect("capture");
    cap.surface.iter().filter(|s| s[3] > 0.0).map(|s| s[0]).collect()
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
    let powdered = surface_of(&gpu, |preset| {
        let (_, mut matte) = FinishKind::Matte.defaults();
        matte.levelling = 0.0;
        preset.set_finish(Some((preset.specular, matte)));
    });
    assert_eq!(powdered.len(), clear.len(), "same pixels");
    let (sum_clear, sum_powder) = (clear.iter().sum::<f32>(), powdered.iter().sum::<f32>());
    assert!(sum_powder < sum_clear, "powder {sum_powder} against a clear film {sum_clear}");
    assert!(powdered.iter().zip(&clear).all(|(p, c)| *p <= *c + 1e-4), "nowhere brighter");
}

/// High-frequency content of the surface radiance over the skin: the mean absolute difference
/// between each pixel and the mean of its 3 × 3 neighbourhood (pores are a few pixels across in
/// the test's view), relative to the mean radiance.
fn speckle(surface: &[[f32; 4]], w: usize, h: usize) -> f64 {
    let (mut sum, mut mean, mut count) = (0.0f64, 0.0f64, 0usize);
    for y in 1..h - 1 {
        for x in 1..w - 1 {
            let window: Vec<&[f32; 4]> = (0..9).map(|k| &surface[(y + k / 3 - 1) * w + x + k % 3 - 1]).collect();
            if window.iter().any(|p| p[3] == 0.0) {
                continue;
            }
            let centre = f64::from(surface[y * w + x][1]);
            let around = window.iter().map(|p| f64::from(p[1])).sum::<f64>() / 9.0;
            sum += (centre - around).abs();
            mean += centre;
            count += 1;
        }
    }
    assert!(count > 1000, "{count} skin pixels");
    sum / mean.max(1e-9)
}

#[test]
fn pores_show_on_bare_skin_and_a_levelling_film_fills_them() {
    use rouge_model::skin::AnatomyRegion;
    use rouge_model::skin::detail::tiles_per_uv;
    let gpu = Gpu::headless().expect("a wgpu adapter (install mesa-vulkan-drivers for lavapipe)");
    let scene = Scene::studio();
    // Closer than the close-up (about 9 mm across the image's height, 0.05 mm a pixel), so that a
    // pore spans pixels.
    let mut camera = Camera::close_up(head(), AnatomyRegion::Nose, 25.0, 5.0).expect("the nose");
    camera.distance *= 0.15;
    let (w, h) = (256usize, 192usize);
    let scale = tiles_per_uv(head()).expect("UVs");
    let render = |detail: bool, thickness_mm: f32, levelling: f64| {
        let text = format!(
            r#"{{"schema": "rouge-look", "version": 1, "name": "primer",
            "layers": [{{"preset": "builtin:foundation_02_ivory", "thickness": {{"uniform_mm": {thickness_mm}}}}}]}}"#
        );
        let mut look = Look::from_json(&text, Path::new("primer.json")).expect("look");
        let (lobe, mut film) = FinishKind::Gloss.defaults();
        film.levelling = levelling;
        look.layers[0].preset.set_finish(Some((lobe, film)));
        let mut r = Renderer::new(&gpu.device, &gpu.queue);
        r.set_mesh(head(), scene.skin.albedo).expect("mesh");
        r.set_look(&look).expect("look");
        if detail {
            let (tile, regions) = rouge_render::job::default_skin_detail();
            r.set_skin_detail(Some((tile, regions, scale))).expect("detail");
        }
        r.render(&scene, &camera, w as u32, h as u32, false).expect("render");
        let cap = r.capture().expect("capture");
        assert!(cap.surface.iter().all(|p| p.iter().all(|v| v.is_finite())), "finite");
        speckle(&cap.surface, w, h)
    };
    let smooth = render(false, 0.0, 1.0);
    let bare = render(true, 0.0, 1.0);
    eprintln!("speckle without detail {smooth:.4}, bare skin with detail {bare:.4}");
    assert!(bare > 10.0 * smooth, "pores on bare skin: {bare} against {smooth} without detail");
    // A formed gloss film (its own sharp lobe, the same at every thickness here) shows less of the
    // relief as it thickens when it levels, and keeps it when it does not (a thicker film still
    // hides more of the skin's own speckled lobe below it, so the conformal film is compared with
    // the levelling one at the same thickness).
    let thin = render(true, 0.005, 1.0);
    let mut last = thin;
    for um in [15.0, 40.0] {
        let filled = render(true, um / 1000.0, 1.0);
        eprintln!("{um} µm of a levelling film: {filled:.4} (5 µm: {thin:.4})");
        assert!(filled < last, "{um} µm: {filled} after {last}");
        last = filled;
    }
    assert!(last < 0.5 * thin, "40 µm fills most of the relief: {last} against {thin}");
    let conformal = render(true, 0.040, 0.0);
    eprintln!("40 µm of a film that follows the relief: {conformal:.4}");
    assert!(conformal > 3.0 * last, "a film with levelling 0 keeps the pores: {conformal} against {last} levelled");
}

/// The mean absolute difference of the skin's diffuse radiance (green) between two captures,
/// relative to the mean, over the pixels of `columns` (half-open, of a `w`-wide frame) where
/// both show the skin.
fn change(a: &[[f32; 4]], b: &[[f32; 4]], w: usize, columns: std::ops::Range<usize>) -> f64 {
    let (mut diff, mut mean) = (0.0f64, 0.0f64);
    for (i, (p, q)) in a.iter().zip(b).enumerate() {
        if columns.contains(&(i % w)) && p[3] > 0.0 && q[3] > 0.0 {
            diff += f64::from((p[1] - q[1]).abs());
            mean += f64::from(p[1]);
        }
    }
    diff / mean.max(1e-9)
}

#[test]
fn expression_wrinkles_follow_their_face_units_and_a_levelling_film_fills_them() {
    use rouge_model::skin::detail::tiles_per_uv;
    use rouge_model::skin::{AnatomyRegion, WrinkleMap, WrinkleWeights};
    let gpu = Gpu::headless().expect("a wgpu adapter (install mesa-vulkan-drivers for lavapipe)");
    let scene = Scene::studio();
    let (w, h) = (192usize, 144usize);
    let scale = tiles_per_uv(head()).expect("UVs");
    let units = |pairs: &[(&str, f32)]| pairs.iter().map(|(k, v)| (k.to_string(), *v)).collect();
    let render = |camera: &Camera, weights: WrinkleWeights, film_mm: f32| {
        let text = format!(
            r#"{{"schema": "rouge-look", "version": 1, "name": "film",
            "layers": [{{"preset": "builtin:foundation_02_ivory", "thickness": {{"uniform_mm": {film_mm}}}}}]}}"#
        );
        let mut look = Look::from_json(&text, Path::new("film.json")).expect("look");
        look.layers[0].preset.set_finish(Some(FinishKind::Gloss.defaults()));
        let mut r = Renderer::new(&gpu.device, &gpu.queue);
        r.set_mesh(head(), scene.skin.albedo).expect("mesh");
        r.set_look(&look).expect("look");
        let (tile, regions) = rouge_render::job::default_skin_detail();
        r.set_skin_detail(Some((tile, regions, scale))).expect("detail");
        r.set_wrinkle_map(Some(WrinkleMap::default_head())).expect("wrinkles");
        r.set_wrinkle_weights(weights);
        r.render(&scene, camera, w as u32, h as u32, false).expect("render");
        let cap = r.capture().expect("capture");
        assert!(cap.diffuse.iter().all(|p| p.iter().all(|v| v.is_finite())), "finite");
        cap.diffuse
    };
    // The forehead, from the front: raised brows draw its lines; a smile leaves it as it is.
    let forehead = Camera::close_up(head(), AnatomyRegion::Forehead, 0.0, 10.0).expect("the forehead");
    let rest = render(&forehead, WrinkleWeights::default(), 0.0);
    let raised = render(&forehead, WrinkleWeights::of(&units(&[("browInnerUp", 1.0)])), 0.0);
    let smiling = render(&forehead, WrinkleWeights::of(&units(&[("mouthSmileLeft", 1.0)])), 0.0);
    let lines = change(&raised, &rest, w, 0..w);
    let none = change(&smiling, &rest, w, 0..w);
    eprintln!("forehead: raised brows change the diffuse by {lines:.4}, a smile by {none:.6}");
    assert!(lines > 0.001, "forehead lines: {lines}");
    assert!(none < 0.05 * lines, "a smile draws no forehead lines: {none}");
    // Under 0.1 mm of a levelling film (gloss: levelling 1) the lines are shallower,
    // exp(−0.1 / 0.15) ≈ half as deep.
    let (rest_film, raised_film) = (
        render(&forehead, WrinkleWeights::default(), 0.1),
        render(&forehead, WrinkleWeights::of(&units(&[("browInnerUp", 1.0)])), 0.1),
    );
    let filled = change(&raised_film, &rest_film, w, 0..w);
    eprintln!("under 0.1 mm of a levelling gloss film: {filled:.4}");
    assert!(filled < 0.75 * lines, "a film fills the lines: {filled} against {lines}");
    // The mouth from the front: a smile on the subject's left (+x: the image's right half)
    // deepens the fold there and not on the other side.
    let mouth = Camera::close_up(head(), AnatomyRegion::Lips, 0.0, 0.0).expect("the lips");
    let rest = render(&mouth, WrinkleWeights::default(), 0.0);
    let smile = render(&mouth, WrinkleWeights::of(&units(&[("mouthSmileLeft", 1.0)])), 0.0);
    let (left, right) = (change(&smile, &rest, w, w / 2 + 8..w), change(&smile, &rest, w, 0..w / 2 - 8));
    eprintln!("a left smile changes the subject's left by {left:.4}, the right by {right:.6}");
    assert!(left > 0.005 && right < 0.1 * left, "left {left} right {right}");
}
