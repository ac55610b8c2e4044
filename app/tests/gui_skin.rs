//! The painting app's skin maps under egui_kittest with the wgpu renderer (lavapipe on CI): a
//! darker tone from the Skin panel darkens the rendered face (and the split's "before" side and
//! the solo view show the maps), a skin brush dab changes the
//! pixels under it and none far away (and not the makeup layers), undo restores the frame, the
//! blood follows a smile until the "Blood follows expression" switch is turned off, and a saved
//! project reopens with its skin edits and the same frame.

use egui_kittest::Harness;
use egui_kittest::kittest::Queryable;
use glam::Vec3;
use rouge_app::gui::{Options, RougeApp};
use rouge_model::mesh::targets::FacePose;
use rouge_model::skin::{SkinBrush, SkinBrushKind, SkinConditions, SkinRecipe};
use std::path::Path;

use crate::common;
use common::{beside_nose_tip, harness};

/// Skin maps of `tone`, 512² (quick), without conditions.
fn recipe(tone: &str) -> SkinRecipe {
    SkinRecipe::from_tone(tone, SkinConditions::default(), 1, 512).expect("tone")
}

fn set_skin(h: &mut Harness<'static, RougeApp>, recipe: Option<SkinRecipe>) {
    h.state_mut().set_skin_recipe(recipe);
    h.state_mut().wait_skin();
    h.run_steps(3);
    assert!(h.state().message().is_none_or(|(ok, _)| *ok), "{:?}", h.state().message());
}

/// The frame as RGBA8 (the whole window; pixels per point 1).
fn frame(h: &mut Harness<'static, RougeApp>) -> image::RgbaImage {
    h.run_steps(2);
    h.render().expect("render")
}

/// CIE L* of an sRGB pixel (D65).
fn lightness(p: [u8; 4]) -> f64 {
    let lin = |c: u8| {
        let c = f64::from(c) / 255.0;
        if c <= 0.04045 { c / 12.92 } else { ((c + 0.055) / 1.055).powf(2.4) }
    };
    let y = 0.2126 * lin(p[0]) + 0.7152 * lin(p[1]) + 0.0722 * lin(p[2]);
    if y > 216.0 / 24389.0 { 116.0 * y.cbrt() - 16.0 } else { y * 24389.0 / 27.0 }
}

/// The screen points of the face between the mouth and the eyes: a box above the lips.
fn face_box(h: &Harness<'static, RougeApp>) -> (i32, i32, i32, i32) {
    let lips = h.state().screen_pos_of(h.state().lip_point().expect("lips")).expect("on screen");
    (lips.x as i32 - 60, lips.y as i32 - 110, lips.x as i32 + 60, lips.y as i32 - 15)
}

fn mean_lightness(image: &image::RgbaImage, (x0, y0, x1, y1): (i32, i32, i32, i32)) -> f64 {
    let mut sum = 0.0;
    let mut n = 0.0;
    for y in y0..y1 {
        for x in x0..x1 {
            sum += lightness(image.get_pixel(x as u32, y as u32).0);
            n += 1.0;
        }
    }
    sum / n
}

/// Clears every makeup layer, so the skin is seen bare.
fn bare(h: &mut Harness<'static, RougeApp>) {
    for i in 0..h.state().document().layers.len() {
        h.state_mut().clear_layer(i);
    }
    h.run_steps(2);
}

#[test]
fn a_darker_tone_darkens_the_face_and_no_skin_maps_brings_the_flat_skin_back() {
    let data = tempfile::tempdir().expect("tempdir");
    let mut h = harness(data.path());
    let area = face_box(&h);
    bare(&mut h);
    let flat = frame(&mut h);
    set_skin(&mut h, Some(recipe("very-light")));
    let light = frame(&mut h);
    // The deep tone chosen in the Skin panel's Tone list.
    h.get_by_label("Blood follows expression").scroll_to_me();
    h.run_steps(2);
    h.get_by_role_and_label(egui::accesskit::Role::ComboBox, "Tone").click_accesskit();
    h.run_steps(2);
    h.get_by_label("deep (Fitzpatrick V-VI)").click_accesskit();
    h.run_steps(2);
    h.state_mut().wait_skin();
    let recipe_now = h.state().document().skin.as_ref().map(|s| s.recipe.clone()).expect("skin maps");
    assert_eq!((recipe_now.tone.as_deref(), recipe_now.size_px), (Some("deep"), 512), "the panel keeps the size");
    let deep = frame(&mut h);
    let (l_flat, l_light, l_deep) =
        (mean_lightness(&flat, area), mean_lightness(&light, area), mean_lightness(&deep, area));
    assert!(l_deep < l_light - 15.0, "L* very light {l_light:.1}, deep {l_deep:.1}");
    assert!((l_light - l_flat).abs() > 0.5, "the maps are drawn: L* flat {l_flat:.1}, very light {l_light:.1}");
    eprintln!("skin bake: {:?}", h.state().skin_bake_times());
    // The split's "before" side is the bare skin with its maps, and the solo view keeps them.
    let (x0, y0, x1, y1) = area;
    let left = (x0, y0, (x0 + x1) / 2 - 5, y1);
    h.state_mut().set_split(true, 0.5);
    let split = frame(&mut h);
    let (l_split, l_deep_left, l_flat_left) =
        (mean_lightness(&split, left), mean_lightness(&deep, left), mean_lightness(&flat, left));
    assert!(
        (l_split - l_deep_left).abs() < 1.0,
        "before side L* {l_split:.1}, deep {l_deep_left:.1}, flat {l_flat_left:.1}"
    );
    h.state_mut().set_split(false, 0.5);
    h.state_mut().set_solo(true);
    let solo = frame(&mut h);
    assert!((mean_lightness(&solo, area) - l_deep).abs() < 1.0, "the solo view keeps the skin maps");
    h.state_mut().set_solo(false);
    // The tone is one undo step; undo brings the very light skin back, then the flat one.
    h.state_mut().undo();
    h.state_mut().wait_skin();
    assert!((mean_lightness(&frame(&mut h), area) - l_light).abs() < 0.2);
    set_skin(&mut h, None);
    assert!(h.state().document().skin.is_none());
    assert!((mean_lightness(&frame(&mut h), area) - l_flat).abs() < 0.2);
}

/// A point on a cheek (`side` −1: the face's right, image left of the nose): the frontmost
/// surface point near 42 mm beside and 12 mm above the nose tip, inside the cheeks' mask.
fn cheek_point(app: &RougeApp, side: f32) -> Vec3 {
    beside_nose_tip(app, side * 42.0, 12.0)
}

#[test]
fn a_skin_dab_changes_the_pixels_under_it_only_and_undo_restores_the_frame() {
    let data = tempfile::tempdir().expect("tempdir");
    let mut h = harness(data.path());
    bare(&mut h);
    set_skin(&mut h, Some(recipe("light")));
    let layers: Vec<Vec<f32>> = h.state().document().layers.iter().map(|l| l.map.mm.clone()).collect();
    h.state_mut().set_skin_brush(Some(SkinBrush { kind: SkinBrushKind::Spot, factor: 4.0 }));
    {
        let b = h.state_mut().brush_mut();
        (b.radius_mm, b.mirror, b.flow, b.hardness) = (6.0, false, 1.0, 0.8);
    }
    let before = frame(&mut h);
    let at = h.state().screen_pos_of(cheek_point(h.state(), -1.0)).expect("on screen");
    h.state_mut().paint_stroke_screen(&[at, at]);
    let after = frame(&mut h);
    if let Ok(dir) = std::env::var("ROUGE_SKIN_DEBUG") {
        before.save(format!("{dir}/before.png")).unwrap();
        after.save(format!("{dir}/after.png")).unwrap();
    }
    let rect = h.state().skin_bake_times().rect;
    eprintln!("rect re-bake after the dab (texels, ms): {rect:?}");
    assert!(rect.is_some(), "the dab re-baked its rectangle only");
    let skin = h.state().document().skin.clone().expect("skin");
    assert!(skin.edits.as_ref().is_some_and(|e| e.edited_texels() > 100), "the dab is a skin edit");
    let layers_after: Vec<Vec<f32>> = h.state().document().layers.iter().map(|l| l.map.mm.clone()).collect();
    assert!(layers_after == layers, "the makeup layers are untouched");
    // Pixels under the dab darken and redden; none far from it changes.
    let (mut near, mut far_changed, mut far) = (0.0f64, 0u32, 0u32);
    let mut near_n = 0.0;
    let view = h.state().viewport_rect();
    for y in view.min.y as u32 + 1..view.max.y as u32 - FRAME_TEXT_PX {
        for x in view.min.x as u32 + 1..view.max.x as u32 - 1 {
            let (a, b) = (before.get_pixel(x, y).0, after.get_pixel(x, y).0);
            let d = ((x as f32 - at.x).powi(2) + (y as f32 - at.y).powi(2)).sqrt();
            if d < 5.0 {
                near += lightness(a) - lightness(b);
                near_n += 1.0;
            } else if d > 80.0 {
                far += 1;
                far_changed += u32::from(a.iter().zip(b).any(|(p, q)| p.abs_diff(q) > 2));
            }
        }
    }
    assert!(near / near_n > 3.0, "the spot darkens the skin under it by {:.2} L*", near / near_n);
    assert!(far_changed * 1000 < far, "{far_changed} of {far} far pixels changed");
    // Undo takes the spot back: the frame as before.
    h.state_mut().undo();
    h.state_mut().wait_skin();
    let undone = frame(&mut h);
    let worst = worst_in(&before, &undone, view);
    assert!(worst <= 1, "undo left a difference of {worst}");

    // Save, reopen: the skin and its edits come back and draw the same frame.
    h.state_mut().redo();
    h.state_mut().wait_skin();
    let painted = frame(&mut h);
    let dir = data.path().join("project");
    h.state_mut().save_project_to(&dir).expect("save");
    set_skin(&mut h, None);
    h.state_mut().open_project_from(&dir).expect("open");
    h.state_mut().wait_skin();
    let reopened = frame(&mut h);
    let doc_skin = h.state().document().skin.clone().expect("the skin comes back");
    assert!(doc_skin.edits == skin.edits, "the edits come back bit for bit");
    let worst = worst_in(&painted, &reopened, view);
    assert!(worst <= 1, "the reopened frame differs by {worst}");
    // Started on the project (`rouge --project DIR`): the same skin from the first frame on.
    drop(h);
    let (data_dir, project) = (data.path().to_owned(), dir.clone());
    let mut h = Harness::builder().with_size(egui::vec2(1200.0, 760.0)).wgpu().build_eframe(move |cc| {
        let options = Options {
            data_dir,
            project: Some(project),
            autosave: false,
            mesh: None,
            window_screenshot: None,
            recover: false,
        };
        RougeApp::new(cc, options).expect("the app opens the project")
    });
    h.state_mut().wait_ready();
    h.state_mut().wait_skin();
    h.state_mut().brush_mut().mirror = false; // no symmetry plane drawn, as in `painted`
    let started = frame(&mut h);
    let worst = worst_in(&painted, &started, view);
    assert!(worst <= 1, "the frame of the app started on the project differs by {worst}");
}

/// The strip at the bottom of the viewport where the frame time is printed, points.
const FRAME_TEXT_PX: u32 = 30;

/// The largest channel difference between two frames inside the viewport `view`.
fn worst_in(a: &image::RgbaImage, b: &image::RgbaImage, view: egui::Rect) -> u8 {
    let mut worst = 0;
    for y in view.min.y as u32 + 1..view.max.y as u32 - FRAME_TEXT_PX {
        for x in view.min.x as u32 + 1..view.max.x as u32 - 1 {
            let (p, q) = (a.get_pixel(x, y).0, b.get_pixel(x, y).0);
            worst = p.iter().zip(q).map(|(s, t)| s.abs_diff(t)).fold(worst, u8::max);
        }
    }
    worst
}

/// Mean red minus green over a window of the frame around `at`.
fn redness(image: &image::RgbaImage, at: egui::Pos2) -> f64 {
    let (mut sum, mut n) = (0.0, 0.0);
    for dy in -12..=12 {
        for dx in -12..=12 {
            let p = image.get_pixel((at.x as i32 + dx) as u32, (at.y as i32 + dy) as u32).0;
            sum += f64::from(p[0]) - f64::from(p[1]);
            n += 1.0;
        }
    }
    sum / n
}

#[test]
fn the_blood_follows_a_smile_until_the_switch_turns_it_off() {
    let data = tempfile::tempdir().expect("tempdir");
    let mut h = harness(data.path());
    bare(&mut h);
    set_skin(&mut h, Some(recipe("light")));
    let mut smile = FacePose::default();
    smile.expression.insert("smile".into(), 1.0);
    h.state_mut().set_face(smile).expect("smile");
    h.state_mut().refresh_surface();
    h.state_mut().wait_skin();
    assert!(h.state().blood_follows(), "on by default");
    let cheeks = [-1.0, 1.0].map(|s| h.state().screen_pos_of(cheek_point(h.state(), s)).expect("on screen"));
    let flushed = frame(&mut h);
    eprintln!("blood flow + bake per pose: {:?}", h.state().skin_bake_times().full);
    // The switch, clicked in the Skin panel.
    h.get_by_label("Blood follows expression").scroll_to_me();
    h.run_steps(2);
    h.get_by_label("Blood follows expression").click_accesskit();
    h.run_steps(2);
    assert!(!h.state().blood_follows());
    h.state_mut().wait_skin();
    let still = frame(&mut h);
    if let Ok(dir) = std::env::var("ROUGE_SKIN_DEBUG") {
        flushed.save(format!("{dir}/flushed.png")).unwrap();
        still.save(format!("{dir}/still.png")).unwrap();
    }
    for c in cheeks {
        let (a, b) = (redness(&flushed, c), redness(&still, c));
        assert!(a > b + 2.0, "the smiling cheek at {c:?}: red − green {a:.1} flushed, {b:.1} still");
    }
}

/// The app with the Skin panel open, the default look's blush and lipstick on freckled, reddened light-medium skin
/// maps with a painted spot and the blood following a smile, written to `ROUGE_APP_SKIN_FIGURE`
/// (docs/images/app_skin.png); a no-op without it.
#[test]
fn figure() {
    let Ok(out) = std::env::var("ROUGE_APP_SKIN_FIGURE") else { return };
    let data = tempfile::tempdir().expect("tempdir");
    let dir = data.path().to_owned();
    let mut h = Harness::builder().with_size(egui::vec2(1440.0, 900.0)).wgpu().build_eframe(move |cc| {
        let options = Options {
            data_dir: dir,
            project: None,
            autosave: false,
            mesh: None,
            window_screenshot: None,
            recover: false,
        };
        RougeApp::new(cc, options).expect("the app opens")
    });
    h.state_mut().wait_ready();
    h.run_steps(4);
    // The foundation off, so that the skin shows under the blush and lipstick.
    h.state_mut().clear_layer(0);
    let conditions: SkinConditions = "freckles=0.7,redness=0.4,under_eye=0.5".parse().expect("conditions");
    set_skin(&mut h, Some(SkinRecipe::from_tone("light-medium", conditions, 3, 1024).expect("tone")));
    let spot = h.state().screen_pos_of(cheek_point(h.state(), 1.0)).expect("on screen");
    h.state_mut().set_skin_brush(Some(SkinBrush { kind: SkinBrushKind::Spot, factor: 2.5 }));
    {
        let b = h.state_mut().brush_mut();
        (b.radius_mm, b.mirror, b.flow, b.hardness) = (2.5, false, 1.0, 0.5);
    }
    h.state_mut().paint_stroke_screen(&[spot]);
    let mut smile = FacePose::default();
    smile.expression.insert("smile".into(), 0.8);
    h.state_mut().set_face(smile).expect("smile");
    h.state_mut().wait_skin();
    h.get_by_label("Blood follows expression").scroll_to_me();
    h.run_steps(4);
    h.state_mut().wait_skin();
    frame(&mut h).save(&out).expect("write the figure");
}

#[test]
fn a_measured_spectrum_is_fitted_into_skin_maps_and_a_bad_file_is_named() {
    let data = tempfile::tempdir().expect("tempdir");
    let mut h = harness(data.path());
    let missing = data.path().join("no such skin.csv");
    h.state_mut().load_skin_spectrum(&missing);
    h.state_mut().wait_skin();
    let (ok, text) = h.state().message().cloned().expect("a message");
    assert!(!ok && text.contains("no such skin.csv"), "{text}");
    assert!(h.state().document().skin.is_none() && !h.state().document().can_undo());

    let file = Path::new(env!("CARGO_MANIFEST_DIR")).join("../data/skin/colorchecker_skin.csv");
    h.state_mut().load_skin_spectrum(&file);
    h.state_mut().wait_skin();
    assert!(
        h.state().message().is_some_and(|(ok, m)| *ok && m.contains("colorchecker_skin.csv")),
        "{:?}",
        h.state().message()
    );
    let skin = h.state().document().skin.clone().expect("skin maps of the fitted skin");
    assert!(skin.recipe.tone.is_none(), "a measured skin is no named tone");
    skin.recipe.base.validate().expect("fitted parameters in range");
    assert_eq!(skin.maps.width(), rouge_app::gui::DEFAULT_SKIN_PX);
}
