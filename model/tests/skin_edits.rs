//! Skin edits (what the app's skin brushes paint): a dab changes only its channel and only under
//! the brush, edited maps stay in range, regenerated maps keep the edits, strokes and skin
//! changes are undo steps, and the edits survive save → reopen and autosave → recovery bit for
//! bit; a project saved with skin maps but before skin edits opens without them.

use std::path::Path;

use crate::common::project;
use project::project_file;
use std::sync::Arc;

use glam::Vec3;
use rouge_model::TexelRect;
use rouge_model::document::{Change, Document, MAP_SIZE};
use rouge_model::mesh::TriangleMesh;
use rouge_model::paint::{Brush, SurfaceMap};
use rouge_model::skin::edits::{EditChannel, MAX_LN_FACTOR, apply_skin_dab};
use rouge_model::skin::{ProjectSkin, SkinBrush, SkinBrushKind, SkinChannel, SkinEdits, SkinMaps, SkinRecipe};

fn skin(tone: &str, seed: u64) -> ProjectSkin {
    let recipe = SkinRecipe::from_tone(tone, "freckles=0.5".parse().expect("conditions"), seed, 128).expect("recipe");
    ProjectSkin::generate(recipe).expect("generate")
}

fn bits(p: &[f32]) -> Vec<u32> {
    p.iter().map(|v| v.to_bits()).collect()
}

fn assert_same_maps(a: &SkinMaps, b: &SkinMaps) {
    assert_eq!((a.width(), a.height()), (b.width(), b.height()));
    for c in SkinChannel::ALL {
        assert!(bits(a.plane(c)) == bits(b.plane(c)), "channel {} differs", c.name());
    }
}

fn assert_same_edits(a: &SkinEdits, b: &SkinEdits) {
    assert_eq!((a.width(), a.height()), (b.width(), b.height()));
    for c in EditChannel::ALL {
        assert!(bits(a.plane(c)) == bits(b.plane(c)), "plane {} differs", c.plane_name());
    }
}

/// A flat 100 mm square mapped onto `n`² texels, and a 10 mm brush at its centre, unmirrored.
fn square(n: u32) -> (SurfaceMap, Brush) {
    let surface = SurfaceMap::build(&TriangleMesh::flat_square(100.0), n, n);
    let brush = Brush { radius_mm: 10.0, mirror: false, flow: 1.0, ..Brush::default() };
    (surface, brush)
}

#[test]
fn a_dab_moves_only_its_channels_under_the_brush_toward_its_factor() {
    let (surface, brush) = square(64);
    let centre = surface.position(32, 32).expect("centre on the square");
    for kind in SkinBrushKind::ALL {
        let mut edits = SkinEdits::new(64, 64);
        let skin = SkinBrush { kind, factor: 2.0 };
        let [rect, mirror] = apply_skin_dab(&mut edits, &surface, &brush, &skin, centre, None);
        assert!(!rect.is_empty() && mirror.is_empty(), "{kind:?}");
        for c in EditChannel::ALL {
            let plane = edits.plane(c);
            let moves = matches!(
                (kind, c),
                (SkinBrushKind::Spot, _)
                    | (SkinBrushKind::MoreMelanin | SkinBrushKind::LessMelanin, EditChannel::Melanin)
                    | (SkinBrushKind::MoreBlood | SkinBrushKind::LessBlood, EditChannel::Blood)
            );
            let centre_value = plane[32 * 64 + 32];
            if moves {
                let sign =
                    if matches!(kind, SkinBrushKind::LessMelanin | SkinBrushKind::LessBlood) { -1.0 } else { 1.0 };
                // Flow 1 at the centre: the target, ln 2, in one dab.
                assert!((centre_value - sign * 2f32.ln()).abs() < 1e-6, "{kind:?} {c:?}: {centre_value}");
            } else {
                assert!(plane.iter().all(|&v| v == 0.0), "{kind:?} moved {c:?}");
            }
            // Nothing beyond the radius (10 mm = 6.4 texels): the corners are untouched.
            for (x, y) in [(0, 0), (63, 0), (0, 63), (63, 63), (32, 10), (10, 32)] {
                assert_eq!(plane[y * 64 + x], 0.0, "{kind:?} {c:?} at ({x}, {y})");
            }
            // Every changed texel is inside the returned rectangle.
            for (i, &v) in plane.iter().enumerate() {
                let (x, y) = ((i % 64) as u32, (i / 64) as u32);
                if v != 0.0 {
                    assert!(x >= rect.x0 && x < rect.x1 && y >= rect.y0 && y < rect.y1);
                }
            }
        }
    }
    // Repeated dabs never pass the factor; the factor is bounded.
    let mut edits = SkinEdits::new(64, 64);
    let huge = SkinBrush { kind: SkinBrushKind::MoreBlood, factor: 1000.0 };
    for _ in 0..20 {
        apply_skin_dab(&mut edits, &surface, &brush, &huge, centre, None);
    }
    assert!(edits.plane(EditChannel::Blood).iter().all(|&v| (0.0..=MAX_LN_FACTOR).contains(&v)));
    // A NaN factor or centre changes nothing.
    let mut none = SkinEdits::new(64, 64);
    apply_skin_dab(&mut none, &surface, &brush, &SkinBrush { factor: f32::NAN, ..huge }, centre, None);
    apply_skin_dab(&mut none, &surface, &brush, &huge, Vec3::NAN, None);
    assert!(none.is_empty());
}

#[test]
fn edited_maps_scale_their_channel_stay_in_range_and_survive_regeneration() {
    let (surface, brush) = square(128);
    let centre = surface.position(64, 64).expect("centre");
    let mut edits = SkinEdits::new(128, 128);
    let more = SkinBrush { kind: SkinBrushKind::Spot, factor: 4.0 };
    for _ in 0..10 {
        apply_skin_dab(&mut edits, &surface, &brush, &more, centre, None);
    }
    let light = skin("light", 1);
    let edited = light.maps.with_edits(&edits);
    let i = 64 * 128 + 64;
    for c in [SkinChannel::Melanin, SkinChannel::Blood] {
        let (lo, hi) = c.range(light.maps.base());
        let (was, now) = (f64::from(light.maps.plane(c)[i]), f64::from(edited.plane(c)[i]));
        assert!((now - (was * 4.0).min(hi)).abs() <= 1e-6 * was.max(1e-3), "{}: {was} → {now}", c.name());
        assert!(edited.plane(c).iter().all(|&v| (lo..=hi).contains(&f64::from(v))));
        // Far from the dab, as generated.
        assert_eq!(edited.plane(c)[5 * 128 + 5].to_bits(), light.maps.plane(c)[5 * 128 + 5].to_bits());
    }
    // The other channels are the generated ones.
    for c in [SkinChannel::Pheomelanin, SkinChannel::Oxygen, SkinChannel::Epidermis] {
        assert!(bits(edited.plane(c)) == bits(light.maps.plane(c)));
    }
    // The edits apply to another tone's maps as factors, and to maps of another size.
    let deep = skin("deep", 1);
    let deep_edited = deep.maps.with_edits(&edits);
    let ratio = deep_edited.plane(SkinChannel::Melanin)[i] / deep.maps.plane(SkinChannel::Melanin)[i];
    assert!(
        (ratio - 4.0).abs() < 1e-3
            || deep_edited.plane(SkinChannel::Melanin)[i] as f64 == SkinChannel::Melanin.range(deep.maps.base()).1,
        "{ratio}"
    );
    let recipe = SkinRecipe { size_px: 64, ..light.recipe.clone() };
    let small = recipe.generate().expect("64²").with_edits(&edits);
    assert!(
        small.plane(SkinChannel::Blood)[32 * 64 + 32]
            > recipe.generate().unwrap().plane(SkinChannel::Blood)[32 * 64 + 32]
    );
    // Re-applying the edits in a rectangle gives the same bits as applying them everywhere.
    let mut partial = light.maps.clone();
    partial.reapply_edits_in(&light.maps, &edits, TexelRect::whole(128, 128));
    assert_same_maps(&partial, &edited);
}

#[test]
fn skin_changes_and_skin_strokes_are_undo_steps() {
    let mut doc = Document::default_project();
    let first = Arc::new(skin("light", 1));
    assert_eq!(doc.set_skin(Some(first.clone())), Change::Skin { rect: None });
    assert_eq!(doc.set_skin(Some(first.clone())), Change::Nothing, "the same skin is no step");
    assert!(doc.is_modified() && doc.can_undo());

    // A stroke paints the edits (MAP_SIZE², made on the first stroke).
    let edits = doc.begin_skin_stroke().expect("a skin to paint");
    assert_eq!((edits.width(), edits.height()), (MAP_SIZE, MAP_SIZE));
    let rect = TexelRect::new(100, 200, 110, 205);
    let mut values = edits.read_rect(rect);
    values[0].iter_mut().for_each(|v| *v = 0.5);
    edits.write_rect(rect, &values);
    doc.note_dirty(rect);
    assert_eq!(doc.end_stroke(), Change::Skin { rect: Some(rect) });
    let painted = doc.skin.as_ref().and_then(|s| s.edits.clone()).expect("edits");
    assert_eq!(painted.edited_texels(), 50);
    assert_same_maps(&doc.skin.as_ref().unwrap().maps, &first.maps);

    // Another tone keeps the edits when the caller carries them over.
    let mut second = skin("deep", 1);
    second.edits = doc.skin.as_ref().unwrap().edits.clone();
    doc.set_skin(Some(Arc::new(second)));
    assert_eq!(doc.skin.as_ref().unwrap().recipe.tone.as_deref(), Some("deep"));

    assert_eq!(doc.undo(), Change::Skin { rect: None });
    assert_eq!(doc.skin.as_ref().unwrap().recipe.tone.as_deref(), Some("light"));
    assert_eq!(doc.undo(), Change::Skin { rect: Some(rect) });
    assert!(doc.skin.as_ref().unwrap().edits.as_ref().is_none_or(|e| e.is_empty()), "the stroke is undone");
    assert_eq!(doc.undo(), Change::Skin { rect: None });
    assert!(doc.skin.is_none() && !doc.is_modified());
    doc.redo();
    doc.redo();
    assert_same_edits(doc.skin.as_ref().unwrap().edits.as_ref().unwrap(), &painted);
    doc.redo();
    assert_eq!(doc.skin.as_ref().unwrap().recipe.tone.as_deref(), Some("deep"));
    // A stroke without skin maps has nothing to paint.
    doc.set_skin(None);
    assert!(doc.begin_skin_stroke().is_none());
}

/// A document with skin maps and a painted skin edit.
fn painted_document() -> Document {
    let mut doc = Document::default_project();
    doc.set_skin(Some(Arc::new(skin("medium", 7))));
    let edits = doc.begin_skin_stroke().expect("skin");
    let rect = TexelRect::new(900, 800, 1000, 860);
    let mut values = edits.read_rect(rect);
    for (i, v) in values[1].iter_mut().enumerate() {
        *v = (i % 97) as f32 / 97.0 * MAX_LN_FACTOR - 0.3;
    }
    values[0].iter_mut().for_each(|v| *v = -0.123_456_7);
    edits.write_rect(rect, &values);
    doc.note_dirty(rect);
    doc.end_stroke();
    doc
}

fn assert_same_skin(a: &ProjectSkin, b: &ProjectSkin) {
    assert_eq!(a.recipe, b.recipe);
    assert_same_maps(&a.maps, &b.maps);
    assert_same_edits(a.edits.as_ref().expect("edits"), b.edits.as_ref().expect("edits come back"));
}

#[test]
fn skin_edits_survive_save_reopen_and_recovery_bit_for_bit() {
    let tmp = tempfile::tempdir().expect("temp dir");
    let dir = tmp.path().join("Edited skin");
    let mut doc = painted_document();
    doc.save_project(&dir).expect("save");
    assert!(!doc.is_modified());
    let text = std::fs::read_to_string(project_file(&dir, "skin")).expect("the skin file");
    assert!(text.contains("\"edits\": \"maps/skin-edits-"), "{text}");
    let opened = Document::open_project(&dir).expect("open");
    assert_same_skin(doc.skin.as_ref().unwrap(), opened.skin.as_ref().unwrap());
    assert!(!opened.is_modified());

    let recovery = tmp.path().join("recovery");
    doc.autosave(&recovery).expect("autosave");
    let recovered = Document::open_project(&recovery).expect("recover");
    assert_same_skin(doc.skin.as_ref().unwrap(), recovered.skin.as_ref().unwrap());
    Document::clear_recovery(&recovery).expect("clear");
    assert!(!recovery.join("maps").exists());

    // Undoing the stroke and saving drops the edits' file.
    doc.undo();
    doc.save_project(&dir).expect("save without edits");
    let names: Vec<String> = std::fs::read_dir(dir.join("maps"))
        .unwrap()
        .flatten()
        .map(|e| e.file_name().to_string_lossy().into_owned())
        .collect();
    assert!(!names.iter().any(|n| n.starts_with("skin-edits-")), "{names:?}");
    assert!(names.iter().any(|n| n.starts_with("skin-")), "{names:?}");
    assert!(Document::open_project(&dir).unwrap().skin.unwrap().edits.is_none());
}

#[test]
fn bad_edits_files_are_named() {
    let tmp = tempfile::tempdir().expect("temp dir");
    let dir = tmp.path().join("p");
    let mut doc = painted_document();
    doc.save_project(&dir).expect("save");
    let edits_file = |dir: &Path| {
        std::fs::read_dir(dir.join("maps"))
            .unwrap()
            .flatten()
            .map(|e| e.path())
            .find(|p| p.file_name().unwrap().to_string_lossy().starts_with("skin-edits-"))
            .expect("edits file")
    };
    let path = edits_file(&dir);
    // Out of range values are refused, naming the file and the plane.
    let mut planes = [vec![0.0f32; 4], vec![0.0f32; 4]];
    planes[1][3] = 5.0;
    assert!(SkinEdits::from_planes(2, 2, planes.clone()).unwrap_err().contains("blood_ln_factor"));
    planes[1][3] = 0.0;
    let fine = SkinEdits::from_planes(2, 2, planes).expect("in range");
    let mut bytes = fine.to_exr_bytes().expect("exr");
    bytes.truncate(bytes.len() / 2);
    std::fs::write(&path, &bytes).expect("write");
    let err = Document::open_project(&dir).unwrap_err().to_string();
    assert!(err.contains("skin-edits-"), "{err}");
    // A missing edits file is named too.
    std::fs::remove_file(&path).expect("remove");
    let err = Document::open_project(&dir).unwrap_err().to_string();
    assert!(err.contains("skin-edits-"), "{err}");
}
