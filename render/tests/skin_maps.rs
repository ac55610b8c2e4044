//! Skin maps on a real device (lavapipe on CI): their colour through the spectral skin model is
//! the skin's albedo texture ([`rouge_render::job::RenderJob::skin_maps`]). A redness condition
//! raises the rendered a* where it is placed (cheeks, nose) and nowhere else; a darker tone
//! lowers L* of the whole face. Skin under a foundation is drawn within the skin issue's accuracy
//! target of the spectral composition, and a spot's contrast under it follows what `rouge
//! analyze coverage` predicts ([`rouge_render::skin_study`]).

use glam::Vec3;
use rouge_measure::colorimetry::{delta_e_2000_raw, linear_srgb_to_lab, srgb_decode};
use rouge_model::skin::{Condition, SkinConditions, SkinRecipe};
use rouge_render::Scene;
use rouge_render::job::{FacePose, LookChoice, RenderJob};
use rouge_render::skin_study::{SkinColour, SkinPatch, reference_lab, spot_coverage};

const SIZE: (u32, u32) = (200, 200);

/// The display image of the bare default head lit from the front with the skin maps of `recipe`,
/// as CIELAB per pixel (`None` on the background).
fn render(recipe: SkinRecipe) -> Vec<Option<[f64; 3]>> {
    render_posed(recipe, FacePose::default(), true)
}

/// [`render`] with the default head in `face`'s pose, its blood following the expression or not.
fn render_posed(recipe: SkinRecipe, face: FacePose, blood_flow: bool) -> Vec<Option<[f64; 3]>> {
    let mut scene = Scene::white_light(Vec3::new(0.0, 0.0, 1.0));
    scene.specular = false;
    scene.background = [0.0; 3];
    let job = RenderJob {
        subdivision: 0,
        look: LookChoice::Bare,
        width: SIZE.0,
        height: SIZE.1,
        scene,
        skin_maps: Some(recipe),
        face,
        blood_flow,
        ..RenderJob::default()
    };
    let mut p = job.prepare().expect("a wgpu adapter (install mesa-vulkan-drivers for lavapipe)");
    p.renderer.render(&p.scene, &p.camera, SIZE.0, SIZE.1, true).expect("render");
    let bytes = p.renderer.read_display().expect("read");
    bytes
        .chunks_exact(4)
        .map(|px| {
            let rgb = [0, 1, 2].map(|c| srgb_decode(f64::from(px[c]) / 255.0));
            (rgb.iter().sum::<f64>() > 0.0).then(|| linear_srgb_to_lab(rgb))
        })
        .collect()
}

fn recipe(tone: &str, conditions: &str) -> SkinRecipe {
    let conditions: SkinConditions = conditions.parse().expect("conditions");
    SkinRecipe::from_tone(tone, conditions, 3, 256).expect("recipe")
}

#[test]
fn redness_raises_a_star_on_cheeks_and_nose_and_nowhere_else() {
    let plain = render(recipe("light", "none"));
    let red = render(recipe("light", "redness=1"));
    let (w, h) = (SIZE.0 as usize, SIZE.1 as usize);
    // The head's rows: from its first to its last pixel.
    let rows: Vec<usize> = (0..h).filter(|y| (0..w).any(|x| plain[y * w + x].is_some())).collect();
    let (top, bottom) = (rows[0], rows[rows.len() - 1]);
    let (mut raised, mut forehead_worst) = (0usize, 0.0f64);
    for y in 0..h {
        for x in 0..w {
            let (Some(a), Some(b)) = (plain[y * w + x], red[y * w + x]) else { continue };
            let da = b[1] - a[1];
            if da > 2.0 {
                raised += 1;
            }
            // The upper third of the head (scalp and forehead) has no redness.
            if y < top + (bottom - top) / 3 {
                forehead_worst = forehead_worst.max(da.abs());
            }
            // More blood never makes skin greener (8-bit display quantisation and the blur's
            // edges allow a little).
            assert!(da > -1.0, "redness lowered a* by {da} at ({x}, {y})");
        }
    }
    assert!(raised > 300, "only {raised} pixels got redder");
    assert!(forehead_worst < 0.5, "the forehead's a* moved by {forehead_worst}");
}

#[test]
fn a_darker_tone_lowers_the_lightness_of_the_whole_face() {
    let light = render(recipe("light", "none"));
    let brown = render(recipe("brown", "none"));
    let (mut sum, mut n) = (0.0, 0usize);
    for (a, b) in light.iter().zip(&brown) {
        let (Some(a), Some(b)) = (a, b) else { continue };
        // Eyes keep their colour; skin gets darker, never lighter.
        assert!(b[0] <= a[0] + 0.5, "a pixel got lighter: L* {} -> {}", a[0], b[0]);
        sum += a[0] - b[0];
        n += 1;
    }
    let mean = sum / n as f64;
    assert!(mean > 8.0, "mean L* drop {mean}");
}

#[test]
fn skin_maps_and_an_albedo_map_are_refused_together() {
    let job = RenderJob {
        albedo_map: Some("albedo.png".into()),
        skin_maps: Some(recipe("light", "none")),
        ..RenderJob::default()
    };
    let e = match job.prepare() {
        Ok(_) => panic!("an albedo map with skin maps was accepted"),
        Err(e) => e.to_string(),
    };
    assert!(e.contains("albedo map and skin maps"), "{e}");
}

#[test]
fn blood_follows_a_smile() {
    let smile =
        || FacePose::parse_weights("smile", "--expression").map(|e| FacePose { expression: e, ..Default::default() });
    let still = render_posed(recipe("light", "none"), smile().expect("smile"), false);
    let flushed = render_posed(recipe("light", "none"), smile().expect("smile"), true);
    // The same geometry: only the cheeks' blood differs, and it can only redden them.
    let (mut redder, mut greener) = (0usize, 0usize);
    for (a, b) in still.iter().zip(&flushed) {
        let (Some(a), Some(b)) = (a, b) else { continue };
        let da = b[1] - a[1];
        redder += usize::from(da > 1.5);
        greener += usize::from(da < -1.0);
    }
    assert!(redder > 200 && greener == 0, "{redder} pixels redder, {greener} greener");
}

/// The skin issue's accuracy target on a subset of `rouge bench skin`'s grid (a light, a medium
/// and a deep tone, the five foundations, three thicknesses): skin-map colour under one layer,
/// rendered, within ΔE2000 0.5 on average and 1.0 at the 95th percentile of the composition at
/// every wavelength.
#[test]
fn skin_under_foundation_is_within_the_accuracy_target() {
    let gpu = rouge_render::Gpu::headless().expect("a wgpu adapter");
    let mut patch = SkinPatch::new(&gpu).expect("patch");
    let mut errors = Vec::new();
    for tone in ["light", "tan", "deep"] {
        let params = rouge_measure::skin::skin_tone(tone).expect("tone").params;
        let skin = patch.set_skin(&params, SkinColour::Maps).expect("skin");
        for name in rouge_model::look::builtin_preset_names().iter().filter(|n| n.starts_with("foundation_")) {
            let preset = rouge_model::look::builtin_preset(name).expect("preset");
            for um in [5.0, 20.0, 60.0] {
                let rendered = linear_srgb_to_lab(patch.render(&preset, um).expect("render"));
                errors.push(delta_e_2000_raw(rendered, reference_lab(&preset, um, &skin)));
            }
        }
    }
    errors.sort_by(f64::total_cmp);
    let mean = errors.iter().sum::<f64>() / errors.len() as f64;
    let p95 = errors[errors.len() * 95 / 100];
    assert!(mean < 0.5 && p95 < 1.0, "ΔE2000 mean {mean:.3}, p95 {p95:.3} over {} cases", errors.len());
}

/// Coverage on screen agrees with coverage on paper: a mole and an acne papule on a light and a
/// deep skin under a foundation of the skin's depth, 0-60 µm: the rendered ΔE2000 between spot and
/// skin is within 1 of what the coverage analysis predicts, and falls as the layer thickens.
#[test]
fn coverage_on_screen_follows_coverage_on_paper() {
    let gpu = rouge_render::Gpu::headless().expect("a wgpu adapter");
    let mut patch = SkinPatch::new(&gpu).expect("patch");
    let thicknesses = [0.0, 10.0, 20.0, 40.0, 60.0];
    for (tone, foundation) in [("light", "foundation_02_ivory"), ("deep", "foundation_05_espresso")] {
        let params = rouge_measure::skin::skin_tone(tone).expect("tone").params;
        let preset = rouge_model::look::builtin_preset(foundation).expect("preset");
        for spot in [Condition::Moles, Condition::Acne] {
            let rows = spot_coverage(&mut patch, &params, spot, &preset, &thicknesses, SkinColour::Maps).expect("rows");
            for r in &rows {
                assert!(
                    (r.screen_delta_e - r.paper_delta_e).abs() < 1.0,
                    "{} on {tone} under {foundation}: {r:?}",
                    spot.key()
                );
            }
            assert!(rows[0].paper_delta_e > 2.0, "the spot shows on bare skin: {rows:?}");
            assert!(rows[4].screen_delta_e < rows[0].screen_delta_e, "the foundation covers it: {rows:?}");
        }
    }
}
