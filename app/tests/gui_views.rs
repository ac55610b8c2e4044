//! The painting app's layer views and radius drag under egui_kittest with the wgpu renderer
//! (lavapipe on CI): the heat map of the active layer's rendered thickness with its legend
//! (snapshot), the F radius drag kept by a click and cancelled by Esc and by a right click, a
//! locked layer refusing a stroke in the window, a look applied from the library in one click, and a
//! finish chosen for the active layer (one undo step).
//! `UPDATE_SNAPSHOTS=1` rewrites app/tests/snapshots/.

use egui::{Event, Key, Modifiers, PointerButton, Pos2};
use egui_kittest::kittest::Queryable;
use egui_kittest::{Harness, SnapshotOptions};
use rouge_app::gui::RougeApp;

use crate::common;
use common::harness;

fn button(h: &Harness<'static, RougeApp>, pos: Pos2, button: PointerButton, pressed: bool) {
    h.event(Event::PointerButton { pos, button, pressed, modifiers: Modifiers::NONE });
}

#[test]
fn the_heat_map_shows_the_active_layers_thickness_with_a_legend() {
    let data = tempfile::tempdir().expect("tempdir");
    let mut h = harness(data.path());
    let lips = h.state().screen_pos_of(h.state().lip_point().expect("lips")).expect("on screen");
    h.state_mut().set_active_layer(2); // the lipstick: 20 µm inside the lips mask
    h.state_mut().set_heat_map(true);
    h.run_steps(3);
    let heat = h.state().heat_map().expect("a heat map").clone();
    assert_eq!((heat.layer, heat.scale.top_um, heat.scale.step_um), (2, 20.0, 5.0));
    let (w, hgt) = heat.size;
    assert_eq!(heat.rgba.len(), (w * hgt * 4) as usize);
    let painted: Vec<&[u8]> = heat.rgba.chunks_exact(4).filter(|p| p[3] == 255).collect();
    // The lips only: a small part of the frame, and most of it at the full 20 µm (the top colour).
    let share = painted.len() as f64 / f64::from(w * hgt);
    assert!(share > 0.001 && share < 0.1, "painted share {share}");
    let top = heat.scale.colour(0.02).expect("painted");
    let at_top = painted.iter().filter(|p| p[..3] == top).count();
    assert!(at_top * 2 > painted.len(), "{at_top} of {} at the top colour", painted.len());
    // The lip point is painted (frame pixels = points here: pixels_per_point 1).
    let lip_px = ((lips.x - h.state().viewport_rect().min.x) as u32, (lips.y - h.state().viewport_rect().min.y) as u32);
    assert_eq!(heat.rgba[((lip_px.1 * w + lip_px.0) * 4 + 3) as usize], 255, "the lips at {lip_px:?}");
    h.snapshot_options("app_heat_map", &SnapshotOptions::new().threshold(2.0).max_failed_pixels(4000));

    // The foundation covers the whole face evenly at 15 µm: one colour nearly everywhere.
    h.state_mut().set_active_layer(0);
    h.run_steps(3);
    let heat = h.state().heat_map().expect("a heat map");
    assert_eq!((heat.layer, heat.scale.top_um), (0, 15.0));
    let painted = heat.rgba.chunks_exact(4).filter(|p| p[3] == 255).count();
    assert!(painted as f64 / f64::from(w * hgt) > 0.15, "the foundation covers the face: {painted}");
    h.state_mut().set_heat_map(false);
    h.run_steps(2);
    assert!(h.state().heat_map().is_none());
}

#[test]
fn f_drags_the_brush_radius_a_click_keeps_it_and_esc_or_a_right_click_cancel() {
    let data = tempfile::tempdir().expect("tempdir");
    let mut h = harness(data.path());
    let maps: Vec<Vec<f32>> = h.state().document().layers.iter().map(|l| l.map.mm.clone()).collect();
    let at = h.state().screen_pos_of(h.state().lip_point().expect("lips")).expect("on screen");
    h.state_mut().brush_mut().radius_mm = 8.0;
    h.hover_at(at);
    h.run_steps(2);
    h.key_press(Key::F);
    h.run_steps(2);
    let drag = *h.state().radius_drag().expect("F starts a radius drag");
    assert_eq!(drag.start_mm(), 8.0);
    // Twice as far from the circle's centre: twice the radius.
    let centre = Pos2::new(drag.centre()[0], drag.centre()[1]);
    let out = centre + (at - centre) * 2.0;
    h.hover_at(out);
    h.run_steps(2);
    assert!((h.state_mut().brush_mut().radius_mm - 16.0).abs() < 0.01, "{}", h.state_mut().brush_mut().radius_mm);
    button(&h, out, PointerButton::Primary, true);
    h.run_steps(1);
    button(&h, out, PointerButton::Primary, false);
    h.run_steps(2);
    assert!(h.state().radius_drag().is_none(), "the click keeps the radius");
    assert!((h.state_mut().brush_mut().radius_mm - 16.0).abs() < 0.01);
    let after: Vec<Vec<f32>> = h.state().document().layers.iter().map(|l| l.map.mm.clone()).collect();
    assert!(after == maps, "the confirming click painted nothing");
    assert!(!h.state().document().can_undo());

    // Esc puts the radius back.
    h.key_press(Key::F);
    h.run_steps(1);
    h.hover_at(centre + (out - centre) * 0.25);
    h.run_steps(2);
    assert!(h.state_mut().brush_mut().radius_mm < 8.0);
    h.key_press(Key::Escape);
    h.run_steps(2);
    assert!(h.state().radius_drag().is_none());
    assert!((h.state_mut().brush_mut().radius_mm - 16.0).abs() < 0.01);
    // So does a right click.
    h.key_press(Key::F);
    h.run_steps(1);
    h.hover_at(out + egui::vec2(60.0, 0.0));
    h.run_steps(2);
    assert!(h.state_mut().brush_mut().radius_mm > 16.0);
    button(&h, out, PointerButton::Secondary, true);
    h.run_steps(1);
    button(&h, out, PointerButton::Secondary, false);
    h.run_steps(2);
    assert!(h.state().radius_drag().is_none());
    assert!((h.state_mut().brush_mut().radius_mm - 16.0).abs() < 0.01);
}

#[test]
fn a_locked_layer_refuses_a_stroke_with_a_message_and_a_look_applies_in_one_click() {
    let data = tempfile::tempdir().expect("tempdir");
    let mut h = harness(data.path());
    let lips = h.state().screen_pos_of(h.state().lip_point().expect("lips")).expect("on screen");
    // Lock the top layer (the lipstick) with its lock button, as a user would.
    // The list shows the top layer first.
    h.get_all_by_label(rouge_app::gui::layers::UNLOCKED).next().expect("lock buttons").click();
    h.run_steps(2);
    assert!(h.state().document().layers[2].locked);
    assert_eq!(h.query_all_by_label(rouge_app::gui::layers::LOCKED).count(), 1, "the lock shows it is locked");
    let before = h.state().document().layers[2].map.mm.clone();
    h.state_mut().paint_stroke_screen(&[lips, lips + egui::vec2(6.0, 0.0)]);
    assert!(h.state().document().layers[2].map.mm == before, "the locked layer took no paint");
    let (ok, message) = h.state().message().expect("a message").clone();
    assert!(!ok && message.contains("locked"), "{message}");

    // The looks library: open it and click the evening look.
    h.get_by_label("Looks library").click();
    h.run_steps(2);
    h.get_by_label("evening").click();
    h.run_steps(3);
    let names: Vec<String> = h.state().document().layers.iter().map(|l| l.name.clone()).collect();
    assert_eq!(names, ["Foundation 02 Ivory", "Smoky lids", "Blush 01 Petal Pink", "Lipstick 03 Deep Berry"]);
    h.key_press_modifiers(Modifiers::COMMAND, Key::Z);
    h.run_steps(2);
    assert_eq!(h.state().document().layers.len(), 3, "one undo step brings the default look back");
    assert!(h.state().document().layers[2].locked);

    // A finish for the active layer (the lipstick, on top): gloss from the list, one undo step.
    use rouge_measure::finish::FinishKind;
    assert_eq!(h.state().document().layers[2].preset.finish, None);
    h.get_by_role_and_label(egui::accesskit::Role::ComboBox, "finish").click_accesskit();
    h.run_steps(2);
    h.get_by_label("gloss").click_accesskit();
    h.run_steps(2);
    let layer = &h.state().document().layers[2];
    assert_eq!(layer.preset.finish.map(|f| f.kind), Some(FinishKind::Gloss));
    assert_eq!((layer.preset.version, layer.preset.specular), (2, FinishKind::Gloss.defaults().0));
    h.key_press_modifiers(Modifiers::COMMAND, Key::Z);
    h.run_steps(2);
    assert_eq!(h.state().document().layers[2].preset.finish, None, "one undo step takes it back");
}

#[test]
fn the_material_plots_have_ticks_axis_labels_and_legends_under_them() {
    let data = tempfile::tempdir().expect("tempdir");
    let library = rouge_app::gui::materials::Library::load(data.path().join("presets"));
    let blush = library.materials.iter().find(|m| m.preset.name == "Blush 01 Petal Pink").expect("built in").clone();
    let mut h = Harness::builder().with_size(egui::vec2(340.0, 760.0)).wgpu().build_ui(move |ui| {
        egui::ScrollArea::vertical().show(ui, |ui| rouge_app::gui::materials::plots(ui, &blush));
    });
    h.run_steps(2);
    // Every panel's title, every axis label and every legend entry is in the window.
    for label in ["Reflectance", "S, scattering", "K, absorption", "R0(X) solid, T(X) dashed, linear sRGB"] {
        h.get_by_label(label);
    }
    for label in ["R∞ measured", "R measured", "Rg background", "R∞ from S, K", "S", "K", "R0 R", "T B"] {
        h.get_by_label(label);
    }
    h.snapshot_options("material_plots", &SnapshotOptions::new().threshold(2.0).max_failed_pixels(2000));
}

/// The lash tips' mean distance from the lash roots' plane, as the viewport shows them: the
/// span of the lash vertices along their largest extent, mm.
fn lash_extent_mm(app: &RougeApp) -> f32 {
    let mesh = app.posed_mesh().expect("a posed head");
    let (mut lo, mut hi) = (glam::Vec3::splat(f32::MAX), glam::Vec3::splat(f32::MIN));
    for g in mesh.groups.iter().filter(|g| g.part() == rouge_model::mesh::Part::Lash) {
        for &i in &mesh.indices[3 * g.triangles.start..3 * g.triangles.end] {
            let p = mesh.positions[i as usize];
            (lo, hi) = (lo.min(p), hi.max(p));
        }
    }
    (hi - lo).max_element()
}

#[test]
fn the_mascara_switch_and_sliders_coat_the_lashes_as_one_undo_step_each() {
    let data = tempfile::tempdir().expect("tempdir");
    let mut h = harness(data.path());
    assert!(h.state().document().mascara.is_none());
    h.get_by_label("Lashes and brows").scroll_to_me();
    h.run_steps(1);
    h.get_by_label("Lashes and brows").click_accesskit();
    h.run_steps(2);
    h.get_by_label("Mascara").scroll_to_me();
    h.run_steps(1);
    h.get_by_label("Mascara").click_accesskit();
    h.run_steps(2);
    let coated = h.state().document().mascara.expect("the switch puts a mascara on");
    assert!(coated.length > 1.0 && coated.volume > 1.0, "{coated:?}");
    let long = lash_extent_mm(h.state());
    assert!(h.state().document().is_modified());

    // Undo takes the mascara off the document and the viewport's lashes.
    h.key_press_modifiers(Modifiers::COMMAND, Key::Z);
    h.run_steps(2);
    assert!(h.state().document().mascara.is_none());
    let natural = lash_extent_mm(h.state());
    assert!(long > natural + 0.5, "the coated lashes reach {long} mm, the natural {natural} mm");

    // Redo, then a longer mascara through the state the slider writes: the lashes grow again.
    h.key_press_modifiers(Modifiers::COMMAND | Modifiers::SHIFT, Key::Z);
    h.run_steps(2);
    assert_eq!(h.state().document().mascara, Some(coated));
    let longest = rouge_model::mesh::lashes::Mascara { length: 2.0, ..coated };
    h.state_mut().commit_mascara(Some(longest));
    h.run_steps(2);
    assert_eq!(h.state().document().mascara, Some(longest));
    assert!(lash_extent_mm(h.state()) > long, "length 2 reaches past length {}", coated.length);
}

#[test]
fn the_brow_gel_switch_tints_the_brows_as_one_undo_step() {
    let data = tempfile::tempdir().expect("tempdir");
    let mut h = harness(data.path());
    let natural = h.state().hair_albedo().brow;
    h.get_by_label("Lashes and brows").scroll_to_me();
    h.run_steps(1);
    h.get_by_label("Lashes and brows").click_accesskit();
    h.run_steps(2);
    h.get_by_label("Brow gel").scroll_to_me();
    h.run_steps(1);
    h.get_by_label("Brow gel").click_accesskit();
    h.run_steps(2);
    let gel = h.state().document().brow_gel.expect("the switch puts a gel on");
    assert_eq!(h.state().hair_albedo().brow, gel.tint(natural), "the viewport's brows take the gel's tint");
    assert_ne!(h.state().hair_albedo().brow, natural);
    assert!(h.state().document().is_modified());
    // Undo takes it off the document and the brows; redo puts it back.
    h.key_press_modifiers(Modifiers::COMMAND, Key::Z);
    h.run_steps(2);
    assert!(h.state().document().brow_gel.is_none());
    assert_eq!(h.state().hair_albedo().brow, natural);
    h.key_press_modifiers(Modifiers::COMMAND | Modifiers::SHIFT, Key::Z);
    h.run_steps(2);
    assert_eq!(h.state().document().brow_gel, Some(gel));
    // A gel out of range is refused with a message and changes nothing.
    h.state_mut().commit_brow_gel(Some(rouge_model::mesh::brow_gel::BrowGel { strength: 2.0, ..gel }));
    assert_eq!(h.state().document().brow_gel, Some(gel));
    let (ok, message) = h.state().message().expect("a message").clone();
    assert!(!ok && message.contains("strength 2"), "{message}");
    // The fill slider is there; a fill reaches the viewport's hairs as one undo step.
    assert!(h.query_all_by_label("brow fill").next().is_some(), "the panel has a brow fill slider");
    let filled = rouge_model::mesh::brow_gel::BrowGel { fill: 0.6, ..gel };
    h.state_mut().commit_brow_gel(Some(filled));
    h.run_steps(2);
    assert_eq!(h.state().hair_albedo().brow_fill, 0.6);
    h.key_press_modifiers(Modifiers::COMMAND, Key::Z);
    h.run_steps(2);
    assert_eq!((h.state().document().brow_gel, h.state().hair_albedo().brow_fill), (Some(gel), 0.0));
}

#[test]
fn a_close_up_of_the_lips_fills_the_viewport_and_home_goes_back() {
    use rouge_model::skin::AnatomyRegion;
    let data = tempfile::tempdir().expect("tempdir");
    let mut h = harness(data.path());
    let lips = h.state().lip_point().expect("lips");
    // Pixels per 10 mm across the lips, and how far the lips are from the viewport's centre.
    let measure = |app: &RougeApp| {
        let rect = app.viewport_rect();
        let a = app.screen_pos_of(lips).expect("on screen");
        let b = app.screen_pos_of(lips + glam::Vec3::X * 10.0).expect("on screen");
        ((b - a).length() / rect.height(), (a - rect.center()).length() / rect.height())
    };
    let (whole_scale, _) = measure(h.state());
    h.state_mut().view_close_up(AnatomyRegion::Lips);
    h.run_steps(2);
    let (close_scale, off_centre) = measure(h.state());
    assert!(close_scale > 4.0 * whole_scale, "10 mm: {close_scale} of the height up close, {whole_scale} whole");
    assert!(close_scale > 0.1 && off_centre < 0.1, "10 mm {close_scale} of the height, {off_centre} off centre");
    h.key_press(Key::Home);
    h.run_steps(2);
    assert!((measure(h.state()).0 - whole_scale).abs() < 1e-3 * whole_scale, "Home frames the whole face again");
}

/// Issue 30: a long layer name widened the left panel (its row of buttons after the name) until
/// the viewport was a sliver. The viewport keeps its width whatever the names, and every row's
/// buttons (Up, Down, Dup, Del) lie inside the panel, left of the viewport.
#[test]
fn a_long_layer_name_neither_widens_the_panel_nor_pushes_the_buttons_out() {
    let data = tempfile::tempdir().expect("tempdir");
    let mut h = harness(data.path());
    let before = h.state().viewport_rect();
    h.state_mut().rename_layer(0, "A foundation with a very long name indeed, as users write them");
    h.run_steps(3);
    if let Ok(path) = std::env::var("ROUGE_SHOT") {
        h.render().expect("render").save(path).expect("save");
    }
    let after = h.state().viewport_rect();
    assert!(
        (after.width() - before.width()).abs() < 1.0,
        "the viewport went from {:.0} to {:.0} points wide",
        before.width(),
        after.width()
    );
    let layers = h.state().document().layers.len();
    use rouge_app::gui::layers::{DOWN, DUPLICATE, REMOVE, UP};
    for label in [UP, DOWN, DUPLICATE, REMOVE] {
        let nodes: Vec<_> = h.query_all_by_label(label).collect();
        assert_eq!(nodes.len(), layers, "one {label} button a layer");
        for n in nodes {
            let r = n.rect();
            assert!(
                r.max.x <= after.min.x + 0.5,
                "{label} ends at x = {:.1}, past the panel's edge at {:.1}",
                r.max.x,
                after.min.x
            );
        }
    }
}
