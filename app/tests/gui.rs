//! The painting app driven through egui_kittest with the wgpu renderer (lavapipe on CI): a
//! stroke across a cheek, undo and redo bit for bit, save and reopen, a malformed import, and a
//! snapshot of the window. `UPDATE_SNAPSHOTS=1` rewrites app/tests/snapshots/.

use egui::{Modifiers, Pos2};
use egui_kittest::SnapshotOptions;
use egui_kittest::kittest::Queryable;
use rouge_app::gui::RougeApp;
use std::path::Path;

use crate::common;
use common::{beside_nose_tip, harness, harness_with_mesh};

/// Screen points across the face's right cheek (image left of the nose), found from surface
/// points of the mesh: the nose tip is the frontmost point near the midplane, and the cheek
/// points are the frontmost surface points beside and below it.
fn cheek_stroke(app: &RougeApp) -> Vec<Pos2> {
    let near = |dx: f32, dy: f32| beside_nose_tip(app, dx, dy);
    let a = app.screen_pos_of(near(-42.0, -5.0)).expect("on screen");
    let b = app.screen_pos_of(near(-32.0, -28.0)).expect("on screen");
    (0..=6).map(|i| a + (b - a) * (i as f32 / 6.0)).collect()
}

#[test]
fn paint_a_stroke_undo_redo_save_and_reopen() {
    let data = tempfile::tempdir().expect("tempdir");
    let mut h = harness(data.path());
    let layer = 0; // the foundation, bottom layer
    h.state_mut().set_active_layer(layer);
    {
        let b = h.state_mut().brush_mut();
        b.radius_mm = 6.0;
        b.mirror = false;
        b.thickness_mm = 0.05;
        b.flow = 0.8;
    }
    let before = h.state().document().layers[layer].map.clone();
    let points = cheek_stroke(h.state());

    // Drag through the viewport as a user would.
    h.drag_at(points[0]);
    h.run_steps(2);
    for p in &points[1..] {
        h.hover_at(*p);
        h.run_steps(2);
    }
    h.drop_at(*points.last().expect("points"));
    h.run_steps(3);

    let after = h.state().document().layers[layer].map.clone();
    let dabs = h.state().last_stroke_dabs().to_vec();
    assert!(dabs.len() >= 3, "the stroke made {} dabs", dabs.len());
    let surface = h.state().surface().expect("surface");
    let (mut changed, mut far) = (0usize, 0usize);
    for y in 0..after.height {
        for x in 0..after.width {
            let i = (y * after.width + x) as usize;
            if after.mm[i] != before.mm[i] {
                changed += 1;
                let near = surface.position(x, y).is_some_and(|p| dabs.iter().any(|d| (p - *d).length() <= 6.0 + 0.5));
                if !near {
                    far += 1;
                }
            }
        }
    }
    assert!(changed > 200, "only {changed} texels changed");
    assert_eq!(far, 0, "{far} of {changed} changed texels are farther than the brush radius from every dab");
    // Other layers are untouched.
    assert_eq!(h.state().document().layers.len(), 3);

    h.key_press_modifiers(Modifiers::COMMAND, egui::Key::Z);
    h.run_steps(2);
    assert!(h.state().document().layers[layer].map.mm == before.mm, "undo restores the map bit for bit");
    h.key_press_modifiers(Modifiers::COMMAND | Modifiers::SHIFT, egui::Key::Z);
    h.run_steps(2);
    assert!(h.state().document().layers[layer].map.mm == after.mm, "redo re-applies the stroke bit for bit");

    let project = tempfile::tempdir().expect("tempdir");
    h.state_mut().save_project_to(project.path()).expect("save");
    let saved: Vec<Vec<f32>> = h.state().document().layers.iter().map(|l| l.map.mm.clone()).collect();
    // Clearing a layer is one undo step too.
    h.state_mut().clear_layer(2);
    assert!(h.state().document().layers[2].map.mm.iter().all(|&v| v == 0.0));
    h.state_mut().undo();
    assert!(h.state().document().layers[2].map.mm == saved[2]);
    h.state_mut().open_project_from(project.path()).expect("open");
    h.run_steps(2);
    let reopened: Vec<Vec<f32>> = h.state().document().layers.iter().map(|l| l.map.mm.clone()).collect();
    assert!(saved == reopened, "reopened maps equal the saved ones bit for bit");
}

#[test]
fn a_malformed_import_shows_an_error_and_changes_nothing() {
    let data = tempfile::tempdir().expect("tempdir");
    let mut h = harness(data.path());
    let count = h.state_mut().library_mut().materials.len();
    let bad = Path::new(env!("CARGO_MANIFEST_DIR")).join("../data/measurements/bad/non_numeric.csv");
    h.state_mut().library_mut().import_path = bad.display().to_string();
    h.get_by_label("Import").click();
    h.run_steps(2);
    h.state_mut().library_mut().wait();
    h.run_steps(2);
    let lib = h.state_mut().library_mut();
    assert_eq!(lib.materials.len(), count, "a failed import adds nothing");
    let (ok, msg) = lib.last_message.clone().expect("a message");
    assert!(!ok && msg.contains("non_numeric.csv:27:3"), "{msg}");
    // Several good files at once (as the file dialog gives them) add one material each, saved
    // into the user preset folder, with progress.
    let m = Path::new(env!("CARGO_MANIFEST_DIR")).join("../data/measurements");
    lib.import_path =
        format!("{}; {}", m.join("blush_02_coral.csv").display(), m.join("lipstick_03_berry.csv").display());
    h.get_by_label("Import").click();
    h.run_steps(2);
    h.state_mut().library_mut().wait();
    let lib = h.state_mut().library_mut();
    assert_eq!(lib.materials.len(), count + 2);
    assert_eq!(lib.progress(), (2, 2));
    assert!(lib.last_message.as_ref().is_some_and(|(ok, _)| *ok));
    assert_eq!(std::fs::read_dir(data.path().join("presets")).expect("user presets").count(), 2);
}

#[test]
fn window_snapshot() {
    let data = tempfile::tempdir().expect("tempdir");
    let mut h = harness(data.path());
    h.run_steps(2);
    h.snapshot_options("app_default", &SnapshotOptions::new().threshold(2.0).max_failed_pixels(4000));
}

#[test]
fn before_after_split_shows_bare_skin_left_of_the_line() {
    let data = tempfile::tempdir().expect("tempdir");
    let mut h = harness(data.path());
    h.state_mut().set_split(true, 0.5);
    h.run_steps(3);
    let image = h.render().expect("render");
    let lips = h.state().screen_pos_of(h.state().lip_point().expect("lips")).expect("on screen");
    // The lips straddle the midline: left of the split line bare, right of it lipstick.
    let ppp = 1.0;
    let px = |x: f32, y: f32| image.get_pixel((x * ppp) as u32, (y * ppp) as u32).0;
    let redness = |p: [u8; 4]| p[0] as i32 - p[1] as i32;
    // The reddest pixel in a window around the mouth on each side of the line.
    let reddest = |x0: f32, x1: f32| {
        let mut best = [0u8; 4];
        for dy in -30..=30 {
            for dx in 0..=((x1 - x0) as i32) {
                let p = px(x0 + dx as f32, lips.y + dy as f32);
                if redness(p) > redness(best) {
                    best = p;
                }
            }
        }
        best
    };
    let (left, right) = (reddest(lips.x - 45.0, lips.x - 8.0), reddest(lips.x + 8.0, lips.x + 45.0));
    assert!(redness(right) > redness(left) + 40, "left {left:?} right {right:?}");
    h.snapshot_options("app_split", &SnapshotOptions::new().threshold(2.0).max_failed_pixels(4000));
}

#[test]
fn the_subsurface_panel_switches_to_translucency_once_the_bake_lands() {
    use rouge_app::gui::SubsurfaceChoice;
    let data = tempfile::tempdir().expect("tempdir");
    let mut h = harness(data.path());
    assert_eq!(h.state().subsurface_in_use().0, "screen-space");
    // The exact skin surface: the panel's checkbox, on and off again.
    assert_eq!(h.state().diffuse_in_use(), "lambert");
    h.get_by_label("Exact skin surface (half-space)").click_accesskit();
    h.run_steps(2);
    assert_eq!(h.state().diffuse_in_use(), "half-space");
    assert!(h.state().document().is_modified() && h.state().message().is_none_or(|(ok, _)| *ok));
    h.get_by_label("Exact skin surface (half-space)").click_accesskit();
    h.run_steps(2);
    assert_eq!(h.state().diffuse_in_use(), "lambert");
    // The light between surfaces: a view setting, drawn without error, not a change to the
    // document.
    let modified = h.state().document().is_modified();
    assert!(!h.state().bounce_in_use());
    h.get_by_label("Light between surfaces").click_accesskit();
    h.run_steps(2);
    assert!(h.state().bounce_in_use() && h.state().message().is_none_or(|(ok, _)| *ok));
    assert_eq!(h.state().document().is_modified(), modified);
    h.get_by_label("Light between surfaces").click_accesskit();
    h.run_steps(2);
    assert!(!h.state().bounce_in_use());
    h.state_mut().set_subsurface(SubsurfaceChoice::ThicknessPerLight);
    h.run_steps(2);
    assert_eq!(h.state().subsurface_in_use(), ("thickness", false));
    // The slab law under the kernel: skin1's medium, drawn without error.
    h.state_mut().set_subsurface(SubsurfaceChoice::ScreenSpaceSlab);
    h.run_steps(2);
    assert_eq!(h.state().subsurface_in_use(), ("screen-space+slab", false));
    assert!(h.state().message().is_none_or(|(ok, _)| *ok), "{:?}", h.state().message());
    h.state_mut().set_subsurface(SubsurfaceChoice::ThicknessBaked);
    h.run_steps(2);
    // Until the bake lands the viewport keeps the screen-space kernel.
    let start = std::time::Instant::now();
    while h.state().subsurface_in_use().1 {
        assert_eq!(h.state().subsurface_in_use().0, "screen-space");
        assert!(start.elapsed().as_secs() < 120, "the bake did not land in 2 minutes");
        std::thread::sleep(std::time::Duration::from_millis(50));
        h.run_steps(1);
    }
    h.run_steps(2);
    assert_eq!(h.state().subsurface_in_use(), ("thickness", false));
    assert!(h.state().message().is_none_or(|(ok, _)| *ok), "{:?}", h.state().message());
}

#[test]
fn the_cube_atlas_follows_the_morph_and_restores_the_mesh() {
    use rouge_app::gui::SubsurfaceChoice;
    let data = tempfile::tempdir().expect("tempdir");
    let mut h = harness(data.path());
    h.state_mut().set_subsurface(SubsurfaceChoice::CubeAtlas);
    h.run_steps(2);
    assert_eq!(h.state().subsurface_in_use().0, "cube-atlas");
    h.state_mut().set_morph(0.6);
    h.run_steps(2);
    assert_eq!(h.state().morph(), 0.6);
    assert!(h.state().message().is_none_or(|(ok, _)| *ok), "{:?}", h.state().message());
    // A pose under the preview stays morphed: the posed mesh is morphed by the same t (before,
    // the pose showed unmorphed while the slider still read 0.6).
    let (rest, morphed) = {
        h.state_mut().set_morph(0.0);
        h.run_steps(1);
        let rest = h.state().shown_mesh_bounds().expect("bounds");
        h.state_mut().set_morph(0.6);
        h.run_steps(1);
        (rest, h.state().shown_mesh_bounds().expect("bounds"))
    };
    h.state_mut().set_face(rouge_model::mesh::targets::FacePose::preset("smile")).expect("smile");
    h.run_steps(2);
    let posed = h.state().shown_mesh_bounds().expect("bounds");
    let gap = |a: rouge_model::mesh::Bounds, b: rouge_model::mesh::Bounds| (a.size() - b.size()).length();
    assert!(gap(rest, morphed) > 5.0, "the morph did not change the bounds: {rest:?} {morphed:?}");
    assert!(gap(posed, morphed) < 0.25 * gap(rest, morphed), "posed {posed:?}, morphed {morphed:?}, rest {rest:?}");
    assert_eq!(h.state().morph(), 0.6);
    // Leaving the model puts the mesh back.
    h.state_mut().set_subsurface(SubsurfaceChoice::ScreenSpace);
    h.run_steps(2);
    assert_eq!(h.state().morph(), 0.0);
    assert_eq!(h.state().subsurface_in_use().0, "screen-space");
}

#[test]
fn paint_on_the_scanned_head_when_available() {
    let Some(path) = std::env::var_os("ROUGE_SCAN_HEAD") else {
        eprintln!(
            "skipped: set ROUGE_SCAN_HEAD to ../shared/data/heads/LeePerrySmith.glb to paint on the scanned head"
        );
        return;
    };
    let scale: f32 = std::env::var("ROUGE_SCAN_SCALE_TO_MM").ok().and_then(|s| s.parse().ok()).unwrap_or(25.0);
    let data = tempfile::tempdir().expect("tempdir");
    let mut h = harness_with_mesh(data.path(), Some((path.into(), scale)));
    assert!(h.state().ready(), "{:?}", h.state().message());
    h.state_mut().set_active_layer(0);
    // The default project's foundation is already 15 µm everywhere: paint 50 µm.
    h.state_mut().brush_mut().thickness_mm = 0.05;
    let before = h.state().document().layers[0].map.clone();
    let points = cheek_stroke(h.state());
    h.state_mut().paint_stroke_screen(&points);
    h.run_steps(2);
    let after = &h.state().document().layers[0].map;
    let changed = before.mm.iter().zip(&after.mm).filter(|(a, b)| a != b).count();
    let dabs = h.state().last_stroke_dabs().len();
    assert!(
        changed > 100,
        "{changed} texels painted on the scan ({dabs} dabs, stroke {points:?}, message {:?})",
        h.state().message()
    );
}

#[test]
fn a_smile_slider_poses_the_face_and_painting_lands_on_the_deformed_face() {
    let data = tempfile::tempdir().expect("tempdir");
    let mut h = harness(data.path());
    let lips_before = h.state().lip_point().expect("lipstick on the lips");
    // The panel is folded at the bottom of the left column: scroll to it, open it.
    h.get_by_label("Expression").scroll_to_me();
    h.run_steps(2);
    h.get_by_label("Expression").click_accesskit();
    h.run_steps(2);
    let slider = || egui::accesskit::Role::Slider;
    h.get_by_role_and_label(slider(), "smile").scroll_to_me();
    h.run_steps(2);
    h.get_by_role_and_label(slider(), "smile").set_value_accesskit(1.0);
    h.run_steps(3);
    assert_eq!(h.state().face().expression.get("smile"), Some(&1.0), "{:?}", h.state().face());
    assert!(h.state().message().is_none_or(|(ok, _)| *ok), "{:?}", h.state().message());
    // The brush's surface follows the pose: the lipstick's texels now sit on the smiling lips.
    h.state_mut().refresh_surface();
    let lips_after = h.state().lip_point().expect("lipstick on the lips");
    assert!(lips_after.distance(lips_before) > 0.5, "lips at {lips_before} and {lips_after}");

    // Paint across the posed cheek: dabs are picked on the deformed face and land in the UV map.
    let layer = 0;
    h.state_mut().set_active_layer(layer);
    {
        let b = h.state_mut().brush_mut();
        (b.radius_mm, b.mirror, b.thickness_mm, b.flow) = (6.0, false, 0.05, 0.8);
    }
    let before = h.state().document().layers[layer].map.clone();
    let points = cheek_stroke(h.state());
    h.state_mut().paint_stroke_screen(&points);
    h.run_steps(2);
    let after = h.state().document().layers[layer].map.clone();
    let dabs = h.state().last_stroke_dabs().to_vec();
    assert!(dabs.len() >= 3, "{} dabs", dabs.len());
    let surface = h.state().surface().expect("surface");
    let (mut changed, mut far) = (0, 0);
    for y in 0..after.height {
        for x in 0..after.width {
            let i = (y * after.width + x) as usize;
            if after.mm[i] != before.mm[i] {
                changed += 1;
                far += usize::from(!surface.position(x, y).is_some_and(|p| dabs.iter().any(|d| p.distance(*d) <= 6.5)));
            }
        }
    }
    assert!(changed > 200 && far == 0, "{changed} texels changed, {far} far from the posed dabs");

    // The project keeps the face; the animation plays without touching it.
    h.state_mut().set_animation(true);
    std::thread::sleep(std::time::Duration::from_millis(200));
    h.run_steps(3);
    h.state_mut().set_animation(false);
    let project = tempfile::tempdir().expect("tempdir");
    h.state_mut().save_project_to(project.path()).expect("save");
    h.state_mut().set_face(Default::default()).expect("neutral");
    h.state_mut().open_project_from(project.path()).expect("open");
    assert_eq!(h.state().face().expression.get("smile"), Some(&1.0));

    // A neutral project puts the smiling head back at rest (it kept smiling under the neutral
    // document before).
    let neutral = tempfile::tempdir().expect("tempdir");
    rouge_model::document::Document::default_project().save_project(neutral.path()).expect("save");
    h.state_mut().open_project_from(neutral.path()).expect("open");
    h.run_steps(2);
    assert!(h.state().face().is_neutral());
    let rest = rouge_model::mesh::load_mesh(None, 1.0, 2).expect("the default head");
    let shown = h.state().posed_mesh().expect("the head, posed back to rest");
    let off_mm = rest.positions.iter().zip(&shown.positions).map(|(a, b)| a.distance(*b)).fold(0.0f32, f32::max);
    assert_eq!(rest.positions.len(), shown.positions.len());
    assert!(off_mm < 1e-3, "the neutral project's head is {off_mm} mm from rest");
}
