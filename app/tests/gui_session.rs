//! The session around the document in the real app (egui_kittest, lavapipe): recovering an
//! autosave, a project that cannot be opened at start, the status line that must not move the
//! viewport, and the symmetry plane that is drawn only on request (issue 30's rough edges).

use egui_kittest::Harness;
use egui_kittest::kittest::Queryable;
use rouge_app::gui::{Options, RougeApp};
use rouge_model::document::Document;
use std::path::{Path, PathBuf};

mod common;
use common::beside_nose_tip;

fn app(data_dir: &Path, project: Option<PathBuf>, autosave: bool) -> Harness<'static, RougeApp> {
    let data_dir = data_dir.to_owned();
    let mut h = Harness::builder().with_size(egui::vec2(1200.0, 760.0)).wgpu().build_eframe(move |cc| {
        RougeApp::new(cc, Options { data_dir, project, autosave, mesh: None, window_screenshot: None })
            .expect("the app opens")
    });
    h.state_mut().wait_ready();
    h.run_steps(4);
    h
}

#[test]
fn recovered_work_is_unsaved_names_its_layer_and_stays_in_its_project() {
    let data = tempfile::tempdir().expect("tempdir");
    let recovery = data.path().join("recovery");
    let project = data.path().join("my project");
    let mut doc = Document::default_project();
    let top = doc.layers.len() - 1;
    doc.rename_layer(top, "Recovered lips");
    doc.save_project(&project).expect("save");
    doc.rename_layer(0, "Base, renamed after the save");
    // What the app leaves after a crash: the autosave and the project it belongs to.
    doc.autosave(&recovery).expect("autosave");
    std::fs::write(recovery.join("project-folder.txt"), project.display().to_string()).expect("write");

    let mut h = app(data.path(), None, true);
    h.get_by_label("Recover").click();
    h.run_steps(4);
    let app = h.state();
    assert_eq!(app.document().layers[top].name, "Recovered lips");
    assert!(app.document().is_modified(), "recovered work is unsaved (it looked saved: no •)");
    assert_eq!(app.rename_field(), "Recovered lips", "the Rename field names the active layer");
    assert_eq!(app.project_folder(), Some(project.as_path()), "Save goes back to the project");
}

#[test]
fn a_project_that_cannot_be_opened_at_start_is_said_in_a_dialog_in_the_apps_words() {
    let data = tempfile::tempdir().expect("tempdir");
    let project = data.path().join("bad");
    Document::default_project().save_project(&project).expect("save");
    std::fs::write(project.join("face.json"), r#"{"format": "rouge-face", "version": 1, "expression": {"smle": 1}}"#)
        .expect("write");
    let mut h = app(data.path(), Some(project.clone()), false);
    let text = h.state().error_dialog().expect("a dialog").to_string();
    assert!(text.contains(&project.display().to_string()) && text.contains("smle"), "{text}");
    assert!(!text.contains("--"), "no command-line option in the app's words: {text}");
    assert_eq!(h.state().project_folder(), None, "saving must not write into the bad project");
    h.get_by_label("OK").click();
    h.run_steps(2);
    assert!(h.state().error_dialog().is_none());
}

#[test]
fn the_viewport_keeps_its_size_as_the_status_line_changes_and_no_plane_is_drawn() {
    let data = tempfile::tempdir().expect("tempdir");
    let mut h = app(data.path(), None, false);
    h.hover_at(egui::pos2(5.0, 700.0));
    h.run_steps(3);
    let away = h.state().viewport_size();
    let cheek = beside_nose_tip(h.state(), -40.0, -10.0);
    let on_face = h.state().screen_pos_of(cheek).expect("on screen");
    h.hover_at(on_face);
    h.run_steps(3);
    assert!(h.state().thickness_under_cursor().is_some(), "the readout is shown");
    assert_eq!(h.state().viewport_size(), away, "the viewport moved as the thickness readout came");
    // An error on the status line: a stroke on the locked lipstick.
    h.get_all_by_label("Lock").next().expect("lock buttons").click();
    h.run_steps(2);
    let lips = h.state().screen_pos_of(h.state().lip_point().expect("lips")).expect("on screen");
    h.state_mut().paint_stroke_screen(&[lips, lips + egui::vec2(6.0, 0.0)]);
    h.run_steps(3);
    assert!(h.state().message().is_some_and(|(ok, _)| !ok));
    assert_eq!(h.state().viewport_size(), away, "the viewport moved as a message came");

    // The symmetry plane (cyan dots, 120 220 255) is not drawn until asked for.
    h.hover_at(egui::pos2(5.0, 700.0));
    let image = h.render().expect("render");
    let centre = image.enumerate_pixels().filter(|(x, y, _)| (400..800).contains(x) && (80..680).contains(y));
    let cyan = centre.filter(|(_, _, p)| p[0] < 160 && p[1] > 190 && p[2] > 230).count();
    assert_eq!(cyan, 0, "{cyan} cyan pixels on the face: the symmetry plane is drawn by default");
}
