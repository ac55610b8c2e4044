//! The editor core without a window or a GPU: strokes, undo/redo, layer edits and the
//! rectangles the GUI uploads.

use glam::Vec3;
use rouge_app::editor::{Editor, StrokeError};
use rouge_model::TexelRect;
use rouge_model::document::{Change, Document, MAP_SIZE};
use rouge_model::mesh::TriangleMesh;
use rouge_model::paint::{BrushMode, SurfaceMap};
use std::sync::{Arc, OnceLock};

/// A 200 mm square in the z = 0 plane facing +Z, UVs 0..1.
fn plane() -> TriangleMesh {
    TriangleMesh::flat_square(200.0)
}

fn surface() -> Arc<SurfaceMap> {
    static SURFACE: OnceLock<Arc<SurfaceMap>> = OnceLock::new();
    SURFACE.get_or_init(|| Arc::new(SurfaceMap::build(&plane(), MAP_SIZE, MAP_SIZE))).clone()
}

fn editor() -> Editor {
    let mut e = Editor::new(Document::default_project());
    e.set_surface(Some(surface()));
    e.brush.mirror = false;
    e.brush.radius_mm = 6.0;
    e
}

fn map_bits(e: &Editor, layer: usize) -> Vec<u32> {
    e.document().layers[layer].map.mm.iter().map(|v| v.to_bits()).collect()
}

fn stroke(e: &mut Editor, points: &[Vec3]) -> Vec<Change> {
    e.begin_stroke();
    let mut changes = Vec::new();
    for &p in points {
        changes.extend(e.stroke_to(p).expect("visible layer"));
    }
    changes.extend(e.end_stroke());
    changes
}

#[test]
fn a_stroke_is_one_undo_step_restored_bit_for_bit() {
    let mut e = editor();
    let layer = e.active();
    let before = map_bits(&e, layer);
    let changes = stroke(&mut e, &[Vec3::new(-30.0, 0.0, 0.0), Vec3::new(30.0, 10.0, 0.0)]);
    let after = map_bits(&e, layer);
    assert_ne!(before, after, "the stroke painted nothing");
    assert!(e.last_stroke_dabs().len() >= 5, "dabs along the way: {}", e.last_stroke_dabs().len());
    assert!(matches!(changes.last(), Some(Change::Map { .. })), "{changes:?}");
    assert!(e.document().can_undo());
    assert!(matches!(e.undo(), Change::Map { .. }));
    assert_eq!(map_bits(&e, layer), before, "undo restores the map bit for bit");
    assert!(!e.document().can_undo(), "the stroke was one step");
    assert!(matches!(e.redo(), Change::Map { .. }));
    assert_eq!(map_bits(&e, layer), after, "redo re-applies it bit for bit");
}

#[test]
fn the_rectangles_cover_every_changed_texel_and_the_step_is_their_bounds() {
    let mut e = editor();
    let layer = e.active();
    let before = map_bits(&e, layer);
    let changes = stroke(&mut e, &[Vec3::new(10.0, -20.0, 0.0), Vec3::new(25.0, -5.0, 0.0)]);
    let after = map_bits(&e, layer);
    let rects: Vec<TexelRect> = changes
        .iter()
        .filter_map(|c| match c {
            Change::Map { layer: l, rect } if *l == layer => Some(*rect),
            _ => None,
        })
        .collect();
    let (dabs, step) = rects.split_at(rects.len() - 1);
    let mut bounds = TexelRect::EMPTY;
    for (i, (b, a)) in before.iter().zip(&after).enumerate() {
        if b != a {
            let (x, y) = ((i % MAP_SIZE as usize) as u32, (i / MAP_SIZE as usize) as u32);
            bounds.include(x, y);
            assert!(
                dabs.iter().any(|r| (r.x0..r.x1).contains(&x) && (r.y0..r.y1).contains(&y)),
                "texel ({x}, {y}) changed outside every uploaded rectangle"
            );
        }
    }
    assert_eq!(step[0], bounds, "the undo step holds exactly the changed texels' bounds");
}

#[test]
fn layer_edits_and_clearing_are_one_step_each() {
    let mut e = editor();
    let n = e.document().layers.len();
    assert_eq!(e.edit(|d| d.rename_layer(0, "base")), Change::Layers);
    assert_eq!(e.document().layers[0].name, "base");
    let top = e.active();
    let before = map_bits(&e, top);
    assert!(before.iter().any(|&b| f32::from_bits(b) > 0.0), "the default look's top layer has lipstick");
    assert!(matches!(e.clear_layer(top), Ok(Change::Map { .. })));
    assert!(map_bits(&e, top).iter().all(|&b| b == 0));
    e.undo();
    assert_eq!(map_bits(&e, top), before);
    e.undo();
    assert_ne!(e.document().layers[0].name, "base");
    assert!(!e.document().can_undo());
    // Removing the active top layer keeps the active index valid.
    e.edit(|d| d.remove_layer(n - 1));
    assert_eq!(e.active(), n - 2);
}

#[test]
fn a_hidden_layer_refuses_paint_and_keeps_its_map() {
    let mut e = editor();
    let layer = e.active();
    e.edit(|d| d.set_visible(layer, false));
    assert_eq!(e.render_index(layer), None);
    let before = map_bits(&e, layer);
    e.begin_stroke();
    assert_eq!(e.stroke_to(Vec3::ZERO), Err(StrokeError::HiddenLayer));
    assert_eq!(e.end_stroke(), vec![Change::Nothing]);
    assert_eq!(map_bits(&e, layer), before);
}

#[test]
fn replacing_the_document_resets_the_stroke_and_selects_the_top_layer() {
    let mut e = editor();
    e.set_active_layer(0);
    e.begin_stroke();
    e.stroke_to(Vec3::ZERO).expect("paint");
    assert!(e.stroking());
    assert_eq!(e.replace_document(Document::default_project()), Change::Layers);
    assert!(!e.stroking() && e.last_stroke_dabs().is_empty());
    assert_eq!(e.active(), e.document().layers.len() - 1);
    assert!(!e.document().can_undo());
}

/// Strokes `points` in `mode` on the active layer and checks the step: something changed, the
/// uploaded rectangles cover every changed texel, undo restores the map bit for bit and redo
/// re-applies it.
fn check_stroke_step(e: &mut Editor, mode: BrushMode, points: &[Vec3]) {
    e.brush.mode = mode;
    let layer = e.active();
    let before = map_bits(e, layer);
    let changes = stroke(e, points);
    let after = map_bits(e, layer);
    let changed: Vec<usize> = (0..before.len()).filter(|&i| before[i] != after[i]).collect();
    assert!(!changed.is_empty(), "{mode:?} changed nothing");
    for i in changed {
        let (x, y) = ((i % MAP_SIZE as usize) as u32, (i / MAP_SIZE as usize) as u32);
        assert!(
            changes.iter().any(|c| matches!(c, Change::Map { layer: l, rect }
                if *l == layer && (rect.x0..rect.x1).contains(&x) && (rect.y0..rect.y1).contains(&y))),
            "{mode:?}: texel ({x}, {y}) changed outside every uploaded rectangle"
        );
    }
    e.undo();
    assert_eq!(map_bits(e, layer), before, "{mode:?}: undo restores the map bit for bit");
    e.redo();
    assert_eq!(map_bits(e, layer), after, "{mode:?}: redo re-applies it bit for bit");
    e.undo();
}

#[test]
fn erasing_and_smoothing_are_one_step_each_undone_bit_for_bit() {
    let mut e = editor();
    let lips = e.lip_point().expect("the default look paints the lips");
    assert!(lips.z.abs() < 1e-3 && lips.x.abs() <= 100.0 && lips.y.abs() <= 100.0, "{lips} is on the plane");
    // The top layer is the lipstick: erase across its middle, then smooth across its edge with
    // a brush wide enough to reach past it.
    e.brush.flow = 1.0;
    check_stroke_step(&mut e, BrushMode::Erase, &[lips - Vec3::X * 5.0, lips + Vec3::X * 5.0]);
    e.brush.radius_mm = 30.0;
    check_stroke_step(&mut e, BrushMode::Smooth, &[lips - Vec3::Y * 10.0, lips + Vec3::Y * 10.0]);
    assert!(!e.document().can_undo(), "every stroke was undone");
}

#[test]
fn the_document_is_modified_from_the_first_dab_until_undone_or_saved() {
    let mut e = editor();
    assert!(!e.document().is_modified());
    e.begin_stroke();
    assert!(!e.document().is_modified(), "an open stroke without dabs changes nothing");
    e.stroke_to(Vec3::ZERO).expect("paint");
    assert!(e.document().is_modified(), "a dab marks the document for autosave");
    e.end_stroke();
    assert!(e.document().is_modified());
    e.undo();
    assert!(!e.document().is_modified(), "undone back to the opened state");
    e.redo();
    let dir = tempfile::tempdir().expect("tempdir");
    e.document_mut().save_project(dir.path()).expect("save");
    assert!(!e.document().is_modified(), "saved");
}
