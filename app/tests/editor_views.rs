//! The editor core's layer lock, solo view and looks library (issue 15) without a window: a
//! locked layer refuses paint, fill and clear and the lock is an undo step saved with the
//! project; the solo view renders the active layer alone; a library look is applied as one undo
//! step and undone bit for bit.

use glam::Vec3;
use rouge_app::editor::{Editor, StrokeError};
use rouge_app::looks::LIBRARY;
use rouge_model::document::{Change, Document, MAP_SIZE};
use rouge_model::mesh::TriangleMesh;
use rouge_model::paint::{FillRegion, SurfaceMap};
use std::sync::{Arc, OnceLock};

fn editor() -> Editor {
    static SURFACE: OnceLock<Arc<SurfaceMap>> = OnceLock::new();
    let surface = SURFACE
        .get_or_init(|| Arc::new(SurfaceMap::build(&TriangleMesh::flat_square(200.0), MAP_SIZE, MAP_SIZE)))
        .clone();
    let mut e = Editor::new(Document::default_project());
    e.set_surface(Some(surface));
    e.brush.mirror = false;
    e.brush.radius_mm = 6.0;
    // Thicker than any layer of the default look, so a dab changes every layer it reaches.
    e.brush.thickness_mm = 0.05;
    e
}

fn bits(e: &Editor, layer: usize) -> Vec<u32> {
    e.document().layers[layer].map.mm.iter().map(|v| v.to_bits()).collect()
}

#[test]
fn a_locked_layer_refuses_paint_fill_and_clear_until_the_lock_is_undone() {
    let mut e = editor();
    let layer = e.active();
    let before = bits(&e, layer);
    assert_eq!(e.edit(|d| d.set_locked(layer, true)), Change::Layers);
    assert!(e.document().layers[layer].locked);
    assert_eq!(e.edit(|d| d.set_locked(layer, true)), Change::Nothing, "locking twice is no step");

    e.begin_stroke();
    assert_eq!(e.stroke_to(Vec3::ZERO), Err(StrokeError::LockedLayer));
    assert_eq!(e.end_stroke(), vec![Change::Nothing]);
    let fill = e.fill(FillRegion::Whole).expect_err("a locked layer refuses a fill");
    assert!(fill.contains("locked"), "{fill}");
    assert_eq!(e.clear_layer(layer), Err(StrokeError::LockedLayer));
    assert!(bits(&e, layer) == before, "nothing reached the locked map");
    // Other layers still take paint.
    e.set_active_layer(0);
    let base = bits(&e, 0);
    e.begin_stroke();
    e.stroke_to(Vec3::ZERO).expect("an unlocked layer");
    e.end_stroke();
    assert!(bits(&e, 0) != base, "the unlocked layer took paint");
    e.undo();

    // The lock was one undo step: undone, the layer paints again.
    e.set_active_layer(layer);
    assert_eq!(e.undo(), Change::Layers);
    assert!(!e.document().layers[layer].locked);
    e.begin_stroke();
    e.stroke_to(Vec3::ZERO).expect("unlocked");
    e.end_stroke();
    assert!(bits(&e, layer) != before, "unlocked, the layer takes paint");
    assert!(matches!(e.clear_layer(layer), Ok(Change::Map { .. })));
}

#[test]
fn the_lock_is_saved_with_the_project() {
    let mut e = editor();
    e.edit(|d| d.set_locked(1, true));
    let dir = tempfile::tempdir().expect("tempdir");
    e.document_mut().save_project(dir.path()).expect("save");
    let look = std::fs::read_to_string(dir.path().join("look.json")).expect("look.json");
    assert_eq!(look.matches("\"locked\": true").count(), 1, "{look}");
    let reopened = Document::open_project(dir.path()).expect("open");
    let locks: Vec<bool> = reopened.layers.iter().map(|l| l.locked).collect();
    assert_eq!(locks, [false, true, false]);
}

#[test]
fn the_solo_view_renders_the_active_layer_alone() {
    let mut e = editor();
    assert_eq!(e.render_layers(), [0, 1, 2]);
    assert_eq!(e.set_solo(true), Change::Layers);
    assert_eq!(e.set_solo(true), Change::Nothing);
    assert_eq!(e.render_layers(), [2]);
    assert_eq!((e.render_index(2), e.render_index(0)), (Some(0), None));
    // Choosing another layer re-uploads: the view follows the selection.
    assert_eq!(e.set_active_layer(1), Change::Layers);
    assert_eq!(e.render_layers(), [1]);
    assert_eq!(e.set_active_layer(1), Change::Nothing);
    // A stroke's change names the solo layer, uploaded at render index 0.
    e.begin_stroke();
    let mut changes = e.stroke_to(Vec3::ZERO).expect("paint");
    changes.extend(e.end_stroke().into_iter().filter(|c| *c != Change::Nothing));
    assert!(!changes.is_empty());
    assert!(changes.iter().all(|c| matches!(c, Change::Map { layer: 1, .. })), "{changes:?}");
    assert_eq!(e.render_index(1), Some(0));
    // A hidden active layer: nothing renders.
    e.edit(|d| d.set_visible(1, false));
    assert!(e.render_layers().is_empty());
    assert_eq!(e.set_solo(false), Change::Layers);
    assert_eq!(e.render_layers(), [0, 2]);
    assert!(!e.document().can_redo());
}

#[test]
fn every_library_look_loads_and_applies_as_one_undo_step() {
    let mut e = editor();
    let before: Vec<(String, Vec<u32>)> =
        (0..e.document().layers.len()).map(|i| (e.document().layers[i].name.clone(), bits(&e, i))).collect();
    let ids: Vec<&str> = LIBRARY.iter().map(|l| l.id).collect();
    assert_eq!(ids, ["natural", "evening", "editorial", "bold_lip"]);
    for entry in LIBRARY {
        let look = entry.look().unwrap_or_else(|err| panic!("{}: {err:#}", entry.id));
        assert!(look.layers.len() >= 3, "{}: a complete look", entry.id);
        let img = image::load_from_memory(entry.thumbnail_png).expect("a PNG thumbnail").to_rgb8();
        assert_eq!((img.width(), img.height()), (192, 192), "{}", entry.id);
        assert_eq!(e.apply_look(&look), Change::Layers);
        let names: Vec<&str> = e.document().layers.iter().map(|l| l.name.as_str()).collect();
        let expected: Vec<&str> = look.layers.iter().map(|l| l.name.as_str()).collect();
        assert_eq!(names, expected);
        assert_eq!(e.active(), look.layers.len() - 1, "the look's top layer is active");
        // The maps are the look's, at the document's size.
        let lips = look.layers.iter().position(|l| l.preset.kind == rouge_measure::Kind::Lipstick).expect("a lip");
        let max = e.document().layers[lips].map.max_mm();
        assert!((max - look.layers[lips].map.max_mm()).abs() < 1e-6, "{}: {max}", entry.id);
        assert_eq!(e.undo(), Change::Layers);
        let after: Vec<(String, Vec<u32>)> =
            (0..e.document().layers.len()).map(|i| (e.document().layers[i].name.clone(), bits(&e, i))).collect();
        assert!(after == before, "{}: one undo restores the layers bit for bit", entry.id);
        assert!(!e.document().can_undo());
        e.redo();
        assert_eq!(e.document().layers.len(), look.layers.len());
        e.undo();
    }
}
