//! Integration tests of the painting app's document: the default project, strokes and layer edits
//! with undo/redo, project save/open (bit-for-bit maps, failures that leave the previous project
//! readable, stale files), exports, autosave and recovery.

use std::collections::BTreeSet;
use std::path::Path;
use std::sync::Arc;

use rouge_model::document::{Change, Document, MAP_SIZE, PaintLayer, TexelRect};
use rouge_model::look::{Look, Region, ThicknessMap, ThicknessSource, builtin_preset};

const N: usize = MAP_SIZE as usize;

fn bits(map: &ThicknessMap) -> Vec<u32> {
    map.mm.iter().map(|v| v.to_bits()).collect()
}

/// Paints `value(x, y)` into `rect` of `layer` as one stroke of two dabs (top half, bottom half),
/// reporting each dab's rect.
fn paint(doc: &mut Document, layer: usize, rect: TexelRect, value: impl Fn(u32, u32) -> f32) -> Change {
    let TexelRect { x0, y0, x1, y1 } = rect;
    let ym = (y0 + y1) / 2;
    for (i, (ya, yb)) in [(y0, ym), (ym, y1)].into_iter().enumerate() {
        let map = if i == 0 { doc.begin_stroke(layer) } else { doc.stroke_map(layer) }.expect("the layer exists");
        for y in ya..yb {
            for x in x0..x1 {
                map.mm[y as usize * N + x as usize] = value(x, y);
            }
        }
        doc.note_dirty(TexelRect::new(x0, ya, x1, yb));
    }
    doc.end_stroke()
}

/// A distinctive value per texel (different low bits everywhere).
fn pattern(x: u32, y: u32) -> f32 {
    0.001 + (x * 7 + y * 13) as f32 * 1.0e-7
}

fn files_in(dir: &Path) -> BTreeSet<String> {
    std::fs::read_dir(dir)
        .map(|d| d.flatten().map(|e| e.file_name().to_string_lossy().into_owned()).collect())
        .unwrap_or_default()
}

fn map_files(look: &Look) -> BTreeSet<String> {
    look.layers
        .iter()
        .map(|l| match &l.thickness {
            ThicknessSource::Map { path, .. } => path.file_name().expect("a file name").to_string_lossy().into_owned(),
            other => panic!("a project layer's thickness is a map, not {other:?}"),
        })
        .collect()
}

fn assert_same_layers(a: &[PaintLayer], b: &[PaintLayer]) {
    assert_eq!(a.len(), b.len(), "layer count");
    for (i, (x, y)) in a.iter().zip(b).enumerate() {
        assert_eq!(x.name, y.name, "layer {i} name");
        assert_eq!(x.preset, y.preset, "layer {i} preset");
        assert_eq!(x.visible, y.visible, "layer {i} visibility");
        assert_eq!(x.multiplier.to_bits(), y.multiplier.to_bits(), "layer {i} multiplier");
        assert_eq!((x.map.width, x.map.height), (y.map.width, y.map.height), "layer {i} map size");
        assert!(bits(&x.map) == bits(&y.map), "layer {i} map differs");
    }
}

#[test]
fn default_project_has_three_full_size_layers_with_lipstick_on_the_lips_only() {
    let doc = Document::default_project();
    assert_eq!(doc.name, "Untitled");
    assert_eq!(doc.layers.len(), 3);
    for l in &doc.layers {
        assert_eq!((l.map.width, l.map.height, l.map.mm.len()), (MAP_SIZE, MAP_SIZE, N * N), "{}", l.name);
        assert!(l.visible && l.multiplier == 1.0);
    }
    assert!(doc.layers[0].map.mm.iter().all(|&v| v == 0.015), "the foundation is 15 µm everywhere");
    assert!(!doc.is_modified() && !doc.can_undo() && !doc.can_redo());

    // The lipstick: non-zero exactly near the lips mask (1024², bilinear to 2048²), 20 µm at most.
    let lips = Region::Lips.mask();
    assert_eq!((lips.width, lips.height), (1024, 1024));
    let mask_near = |x: usize, y: usize| {
        let (cx, cy) = (x / 2, y / 2);
        (cx.saturating_sub(1)..=(cx + 1).min(1023))
            .any(|mx| (cy.saturating_sub(1)..=(cy + 1).min(1023)).any(|my| lips.mm[my * 1024 + mx] > 0.0))
    };
    let lipstick = &doc.layers[2].map;
    let mut painted = 0;
    for (k, &v) in lipstick.mm.iter().enumerate() {
        if v != 0.0 {
            painted += 1;
            assert!(mask_near(k % N, k / N), "lipstick at texel ({}, {}) outside the lips", k % N, k / N);
            assert!(v > 0.0 && v <= 0.02 + 1e-7, "lipstick {v} mm");
        }
    }
    assert!(painted > 1000 && painted < N * N / 10, "{painted} lipstick texels");
    // And inside the lips (mask 1 around a texel) the lipstick is the full 20 µm.
    let inside = (1025..1023 * 1024)
        .find(|&k| (0..9).all(|d| lips.mm.get(k + d % 3 + (d / 3) * 1024 - 1025) == Some(&1.0)))
        .expect("the lips mask has an inside");
    let (mx, my) = (inside % 1024, inside / 1024);
    assert!((lipstick.mm[(2 * my) * N + 2 * mx] - 0.02).abs() < 1e-6);
}

#[test]
fn a_stroke_undoes_and_redoes_bit_for_bit_and_a_new_stroke_clears_redo() {
    let mut doc = Document::default_project();
    let original = bits(&doc.layers[1].map);
    let rect = TexelRect::new(100, 200, 180, 260);
    let change = paint(&mut doc, 1, rect, pattern);
    assert_eq!(change, Change::Map { layer: 1, rect });
    let painted = bits(&doc.layers[1].map);
    assert_ne!(painted, original);
    assert_eq!(painted[250 * N + 150], pattern(150, 250).to_bits());
    assert!(doc.can_undo() && !doc.can_redo() && doc.is_modified());

    assert_eq!(doc.undo(), Change::Map { layer: 1, rect });
    assert!(bits(&doc.layers[1].map) == original, "undo must restore the map bit for bit");
    assert!(!doc.can_undo() && doc.can_redo() && !doc.is_modified());

    assert_eq!(doc.redo(), Change::Map { layer: 1, rect });
    assert!(bits(&doc.layers[1].map) == painted, "redo must re-apply the stroke bit for bit");

    doc.undo();
    assert!(doc.can_redo());
    let other = paint(&mut doc, 0, TexelRect::new(0, 0, 4, 4), |_, _| 0.05);
    assert_eq!(other, Change::Map { layer: 0, rect: TexelRect::new(0, 0, 4, 4) });
    assert!(!doc.can_redo(), "a new stroke clears the redo stack");
    assert_eq!(doc.redo(), Change::Nothing);
    assert!(bits(&doc.layers[1].map) == original);
}

#[test]
fn stroke_records_only_changed_texels_and_nothing_for_no_change() {
    let mut doc = Document::default_project();
    // Writes the same value the foundation already has: no step.
    assert_eq!(paint(&mut doc, 0, TexelRect::new(10, 10, 50, 50), |_, _| 0.015), Change::Nothing);
    assert!(!doc.can_undo() && !doc.is_modified());
    // Dirty rect larger than the change: the step covers the changed texels only.
    let map = doc.begin_stroke(0).expect("layer 0");
    map.mm[20 * N + 30] = 0.03;
    map.mm[25 * N + 12] = 0.03;
    doc.note_dirty(TexelRect::new(0, 0, 100, 100));
    assert_eq!(doc.end_stroke(), Change::Map { layer: 0, rect: TexelRect::new(12, 20, 31, 26) });
    // No stroke open: nothing to paint, note_dirty is ignored.
    assert!(doc.stroke_map(0).is_none());
    doc.note_dirty(TexelRect::new(0, 0, 10, 10));
    assert_eq!(doc.end_stroke(), Change::Nothing);
    assert!(doc.begin_stroke(7).is_none());
    assert_eq!(doc.undo(), Change::Map { layer: 0, rect: TexelRect::new(12, 20, 31, 26) });
    assert!(doc.layers[0].map.mm.iter().all(|&v| v == 0.015));
}

#[test]
fn layer_edits_each_undo_and_redo() {
    let mut doc = Document::default_project();
    let berry = builtin_preset("lipstick_03_berry").expect("built-in");
    let nude = builtin_preset("lipstick_01_nude").expect("built-in");
    type Edit = Box<dyn Fn(&mut Document) -> Change>;
    let edits: Vec<(&str, Edit)> = vec![
        ("add", Box::new(move |d| d.add_layer("builtin:lipstick_03_berry", berry.clone()))),
        ("remove", Box::new(|d| d.remove_layer(1))),
        ("move", Box::new(|d| d.move_layer(0, 2))),
        ("rename", Box::new(|d| d.rename_layer(2, "Gloss"))),
        ("hide", Box::new(|d| d.set_visible(0, false))),
        ("multiplier", Box::new(|d| d.set_multiplier(1, 2.5))),
        ("preset", Box::new(move |d| d.set_preset(2, "builtin:lipstick_01_nude", nude.clone()))),
    ];
    for (what, edit) in &edits {
        let before = doc.layers.clone();
        assert_eq!(edit(&mut doc), Change::Layers, "{what}");
        let after = doc.layers.clone();
        assert_ne!(before, after, "{what} changed nothing");
        assert_eq!(doc.undo(), Change::Layers, "{what}");
        assert_same_layers(&doc.layers, &before);
        assert_eq!(doc.redo(), Change::Layers, "{what}");
        assert_same_layers(&doc.layers, &after);
    }
    // [foundation, blush, lipstick] + berry, − blush, foundation to the top, renamed "Gloss",
    // lipstick hidden, berry × 2.5, Gloss → nude.
    let refs: Vec<&str> = doc.layers.iter().map(|l| l.preset_ref.as_str()).collect();
    assert_eq!(refs, ["builtin:lipstick_02_red", "builtin:lipstick_03_berry", "builtin:lipstick_01_nude"]);
    assert_eq!(doc.layers[0].name, doc.layers[0].preset.name);
    assert_eq!(doc.layers[2].name, "Gloss", "a renamed layer keeps its name with a new preset");
    assert!(!doc.layers[0].visible && doc.layers[1].visible && doc.layers[2].visible);
    assert_eq!(doc.layers.iter().map(|l| l.multiplier).collect::<Vec<_>>(), [1.0, 2.5, 1.0]);
    assert!(doc.layers[0].map.mm.iter().any(|&v| v > 0.0), "the lipstick kept its map");
    assert!(doc.layers[1].map.mm.iter().all(|&v| v == 0.0), "an added layer starts empty");
    // A layer named after its preset takes the new preset's name.
    let coral = builtin_preset("blush_02_coral").expect("built-in");
    doc.set_preset(1, "builtin:blush_02_coral", coral.clone());
    assert_eq!(doc.layers[1].name, coral.name);
    doc.undo();
    assert_eq!(doc.layers[1].preset_ref, "builtin:lipstick_03_berry");
    // Maps are shared with the history, not copied.
    let before_all = doc.layers.clone();
    doc.set_visible(0, true);
    assert!(Arc::ptr_eq(&doc.layers[0].map, &before_all[0].map));
    // Undo all the way, then redo all the way.
    while doc.can_undo() {
        doc.undo();
    }
    assert_same_layers(&doc.layers, &Document::default_project().layers);
    assert!(!doc.is_modified());
    while doc.can_redo() {
        doc.redo();
    }
    assert_eq!(doc.layers.len(), 3);
    assert!(doc.layers[0].visible && doc.layers[2].name == "Gloss");

    // Out-of-range indices and no-op edits record nothing.
    let steps = count_undo_steps(&mut doc);
    for change in [
        doc.remove_layer(9),
        doc.move_layer(0, 9),
        doc.move_layer(1, 1),
        doc.rename_layer(9, "x"),
        doc.rename_layer(0, "  "),
        doc.set_visible(9, true),
        doc.set_visible(0, true),
        doc.set_multiplier(9, 1.0),
        doc.set_multiplier(0, f32::NAN),
        doc.set_multiplier(1, 2.5),
    ] {
        assert_eq!(change, Change::Nothing);
    }
    assert_eq!(count_undo_steps(&mut doc), steps);
    doc.set_multiplier(0, 50.0);
    assert_eq!(doc.layers[0].multiplier, 10.0, "the multiplier is clamped to 10");
}

/// Undoes everything, counting, then redoes it all.
fn count_undo_steps(doc: &mut Document) -> usize {
    let mut n = 0;
    while doc.can_undo() {
        doc.undo();
        n += 1;
    }
    for _ in 0..n {
        doc.redo();
    }
    n
}

#[test]
fn the_history_budget_drops_the_oldest_steps() {
    let mut doc = Document::default_project();
    // Each stroke stores 2 × 64 × 64 × 4 bytes = 32 KiB.
    doc.set_history_budget(100 << 10);
    for k in 0..6 {
        paint(&mut doc, 2, TexelRect::new(k * 64, 0, k * 64 + 64, 64), |_, _| 0.01);
        assert!(doc.history_bytes() <= 100 << 10, "{} bytes after stroke {k}", doc.history_bytes());
    }
    assert_eq!(count_undo_steps(&mut doc), 3);
    // A removed layer's map lives in the history: it counts (16 MiB), and the newest step stays.
    doc.set_history_budget(1 << 30);
    doc.remove_layer(0);
    assert!(doc.history_bytes() >= 16 << 20);
    doc.set_history_budget(0);
    assert_eq!(count_undo_steps(&mut doc), 1);
    assert_eq!(doc.undo(), Change::Layers);
    assert_eq!(doc.layers.len(), 3);
}

#[test]
fn save_then_open_gives_identical_maps_and_layers() {
    let tmp = tempfile::tempdir().expect("temp dir");
    let dir = tmp.path().join("My Look");
    let mut doc = Document::default_project();
    paint(&mut doc, 1, TexelRect::new(500, 600, 700, 640), pattern);
    doc.set_multiplier(1, 1.7);
    doc.set_visible(0, false);
    doc.rename_layer(2, "Red lips");
    // A preset that is not built in goes into the project's presets/.
    let mut custom = builtin_preset("eyeshadow_02_sapphire").expect("built-in");
    custom.name = "My sapphire".into();
    doc.add_layer("/somewhere/else/sapphire.json", custom.clone());
    paint(&mut doc, 3, TexelRect::new(0, 0, 2048, 3), |x, _| x as f32 * 1e-6);
    assert!(doc.is_modified());

    doc.save_project(&dir).expect("save");
    assert!(!doc.is_modified(), "saving marks the document unmodified");

    // look.json is a rouge-look document that loads to what to_look() says, maps included.
    let look = Look::load(&dir.join("look.json")).expect("look.json loads");
    assert_eq!(look, doc.to_look());
    assert_eq!(files_in(&dir.join("maps")), map_files(&look));
    assert_eq!(files_in(&dir.join("presets")).len(), 1);
    assert!(matches!(look.layers[1].thickness, ThicknessSource::Map { scale_mm: Some(s), .. } if s == 1.7));
    assert!(matches!(look.layers[0].thickness, ThicknessSource::Map { scale_mm: None, .. }));
    assert_eq!(look.layers[3].preset, custom);

    let opened = Document::open_project(&dir).expect("open");
    assert_eq!(opened.name, "Untitled");
    assert_same_layers(&opened.layers, &doc.layers);
    assert!(!opened.is_modified() && !opened.can_undo());

    // Saving again with nothing changed writes nothing new; a removed layer's map is deleted
    // once the new look.json is written.
    let maps_before = files_in(&dir.join("maps"));
    doc.save_project(&dir).expect("save again");
    assert_eq!(files_in(&dir.join("maps")), maps_before);
    doc.remove_layer(3);
    paint(&mut doc, 2, TexelRect::new(10, 10, 20, 20), |_, _| 0.004);
    doc.save_project(&dir).expect("save after removing a layer");
    let look = Look::load(&dir.join("look.json")).expect("look.json loads");
    assert_eq!(look.layers.len(), 3);
    assert_eq!(files_in(&dir.join("maps")), map_files(&look), "stale maps are deleted");
    assert!(files_in(&dir.join("presets")).is_empty(), "the removed layer's preset is deleted");
    assert_same_layers(&Document::open_project(&dir).expect("open").layers, &doc.layers);
}

#[test]
fn a_failed_save_names_the_path_and_leaves_the_previous_project_readable() {
    let tmp = tempfile::tempdir().expect("temp dir");

    // `maps` is a regular file: the folder cannot be made.
    let dir = tmp.path().join("blocked");
    std::fs::create_dir_all(&dir).expect("mkdir");
    Look::bare().save(&dir.join("look.json")).expect("a previous look");
    std::fs::write(dir.join("maps"), "not a folder").expect("write");
    let mut doc = Document::default_project();
    let e = doc.save_project(&dir).expect_err("maps/ cannot be created").to_string();
    assert!(e.contains(&dir.join("maps").display().to_string()), "{e}");
    assert_eq!(Look::load(&dir.join("look.json")).expect("still loads"), Look::bare());

    // A project saved before; then the file a changed map must go to cannot be written.
    let dir = tmp.path().join("project");
    doc.save_project(&dir).expect("first save");
    let saved_layers = doc.layers.clone();
    paint(&mut doc, 2, TexelRect::new(300, 300, 340, 340), |_, _| 0.03);
    let ThicknessSource::Map { path, .. } = &doc.to_look().layers[2].thickness else { panic!("a map") };
    let blocked = dir.join(path);
    std::fs::create_dir_all(&blocked).expect("a folder where the map must go");
    let e = doc.save_project(&dir).expect_err("the map cannot be written").to_string();
    assert!(e.contains(&blocked.display().to_string()), "{e}");
    assert!(doc.is_modified());
    let previous = Document::open_project(&dir).expect("the previous project still opens");
    assert_same_layers(&previous.layers, &saved_layers);

    // A thickness × multiplier over 10 mm is refused before anything is written.
    paint(&mut doc, 0, TexelRect::new(0, 0, 1, 1), |_, _| 2.0);
    doc.set_multiplier(0, 6.0);
    let e = doc.save_project(&tmp.path().join("too thick")).expect_err("12 mm").to_string();
    assert!(e.contains("look.json") && e.contains("layer 0"), "{e}");
    assert!(!tmp.path().join("too thick").exists());
}

#[test]
fn open_project_without_look_json_names_it() {
    let tmp = tempfile::tempdir().expect("temp dir");
    let e = Document::open_project(tmp.path()).expect_err("no look.json").to_string();
    assert!(e.contains(&tmp.path().join("look.json").display().to_string()), "{e}");
}

#[test]
fn exported_maps_read_back() {
    let tmp = tempfile::tempdir().expect("temp dir");
    let mut doc = Document::default_project();
    paint(&mut doc, 1, TexelRect::new(1000, 1000, 1100, 1010), pattern);
    doc.set_multiplier(1, 1.3);
    let files = doc.export_maps(tmp.path()).expect("export");
    assert_eq!(files.len(), 9);
    for (i, layer) in doc.layers.iter().enumerate() {
        let effective = layer.effective_map();
        let max = effective.max_mm();
        let stem = files[3 * i].file_stem().expect("stem").to_string_lossy().into_owned();
        assert!(stem.starts_with(&format!("{i:02}-")), "{stem}");

        let exr = ThicknessSource::Map { path: files[3 * i].clone(), scale_mm: None };
        let back = exr.load_map(tmp.path()).expect("the EXR reads back");
        assert!(bits(&back) == bits(&effective), "layer {i}: EXR values differ");

        // The sidecar is the thickness object that reads the PNG back.
        let sidecar = std::fs::read_to_string(&files[3 * i + 2]).expect("sidecar");
        let source: ThicknessSource = serde_json::from_str(&sidecar).expect("a thickness object");
        assert!(matches!(&source, ThicknessSource::Map { scale_mm: Some(s), .. } if *s == max), "{sidecar}");
        let png = source.load_map(tmp.path()).expect("the PNG reads back");
        assert_eq!((png.width, png.height), (MAP_SIZE, MAP_SIZE));
        let worst = png.mm.iter().zip(&effective.mm).map(|(a, b)| (a - b).abs()).fold(0.0, f32::max);
        assert!(worst <= max / 65535.0, "layer {i}: PNG off by {worst} mm (max {max})");
    }

    let preset_path = tmp.path().join("blush.json");
    doc.export_preset(1, &preset_path).expect("export preset");
    let preset = rouge_measure::preset::Preset::load(&preset_path).expect("loads");
    assert_eq!(preset, doc.layers[1].preset);
    assert!(doc.export_preset(5, &preset_path).is_err());
}

#[test]
fn autosave_recovery_cycle() {
    let tmp = tempfile::tempdir().expect("temp dir");
    let recovery = tmp.path().join("recovery");
    assert!(!Document::recovery_available(&recovery));
    Document::clear_recovery(&recovery).expect("nothing to clear is fine");

    let mut doc = Document::default_project();
    paint(&mut doc, 2, TexelRect::new(800, 1500, 900, 1600), pattern);
    doc.autosave(&recovery).expect("autosave");
    assert!(doc.is_modified(), "an autosave does not mark the document saved");
    assert!(Document::recovery_available(&recovery));

    // Painting on and autosaving again replaces the autosave; unchanged maps stay.
    paint(&mut doc, 2, TexelRect::new(0, 0, 8, 8), |_, _| 0.01);
    doc.autosave(&recovery).expect("autosave again");
    let mut recovered = Document::open_recovery(&recovery).expect("recover");
    assert_same_layers(&recovered.layers, &doc.layers);
    assert_eq!(files_in(&recovery.join("maps")).len(), 3);
    // Recovered work is unsaved work (it opened looking saved: no "•", and a close dropped it).
    assert!(recovered.is_modified(), "a recovered document is modified until saved");
    recovered.save_project(&tmp.path().join("saved")).expect("save");
    assert!(!recovered.is_modified());

    Document::clear_recovery(&recovery).expect("clear");
    assert!(!Document::recovery_available(&recovery));
    assert!(!recovery.join("maps").exists(), "the autosave's maps are deleted");
}

#[test]
fn duplicating_a_layer_copies_it_above_and_painting_the_copy_leaves_the_original() {
    let mut doc = Document::default_project();
    let n = doc.layers.len();
    let rect = TexelRect::new(10, 10, 40, 30);
    paint(&mut doc, 0, rect, pattern);
    let original = bits(&doc.layers[0].map);
    assert_eq!(doc.duplicate_layer(0), Change::Layers);
    assert_eq!(doc.layers.len(), n + 1);
    let copy = &doc.layers[1];
    assert_eq!(copy.name, format!("{} copy", doc.layers[0].name));
    assert_eq!(copy.preset, doc.layers[0].preset);
    assert!(bits(&copy.map) == original, "the copy starts with the original's map");
    // Painting the copy changes the copy only.
    paint(&mut doc, 1, rect, |_, _| 0.5);
    assert!(bits(&doc.layers[0].map) == original, "the original changed with its copy");
    assert!(doc.layers[1].map.mm[10 * N + 10] == 0.5);
    // One undo step each: the stroke, then the duplicate.
    doc.undo();
    doc.undo();
    assert_eq!(doc.layers.len(), n);
    assert!(bits(&doc.layers[0].map) == original);
    // A layer that is not there: nothing, and no undo step.
    assert_eq!(doc.duplicate_layer(99), Change::Nothing);
}

#[test]
fn a_looks_mascara_survives_the_project() {
    use rouge_model::mesh::lashes::Mascara;
    let dir = tempfile::tempdir().expect("tempdir");
    let mut look = Look::bare();
    look.mascara = Some(Mascara { length: 1.3, volume: 2.0, curl_deg: 15.0, color: None });
    look.brow_gel = Some(rouge_model::mesh::brow_gel::BrowGel { color: [0.01, 0.01, 0.011], strength: 0.6, fill: 0.5 });
    let mut doc = Document::from_look(&look);
    assert_eq!(doc.to_look().mascara, look.mascara);
    doc.save_project(dir.path()).expect("save");
    let opened = Document::open_project(dir.path()).expect("open");
    assert_eq!(opened.mascara, look.mascara, "saved and reopened with the project's look.json");
    assert_eq!(opened.brow_gel, look.brow_gel, "the brow gel too, its fill included");
}

#[test]
fn a_mascara_is_one_undo_step_and_a_bad_one_changes_nothing() {
    use rouge_model::document::Change;
    use rouge_model::mesh::lashes::Mascara;
    let mut doc = Document::from_look(&Look::bare());
    let m = Mascara { length: 1.5, volume: 3.0, curl_deg: 20.0, color: None };
    assert_eq!(doc.set_mascara(Some(m)).expect("valid"), Change::Hair);
    assert!(doc.is_modified() && doc.can_undo());
    assert_eq!(doc.set_mascara(Some(m)).expect("valid"), Change::Nothing, "the same mascara is no step");
    // Out of range: an error naming the field, and the document keeps its mascara.
    let e = doc.set_mascara(Some(Mascara { volume: 9.0, ..m })).expect_err("volume 9");
    assert!(e.to_string().contains("volume"), "{e}");
    assert_eq!(doc.mascara, Some(m));
    // A mascara that changes nothing is natural lashes.
    assert_eq!(doc.set_mascara(Some(Mascara::default())).expect("valid"), Change::Hair);
    assert_eq!(doc.mascara, None);
    assert_eq!(doc.undo(), Change::Hair);
    assert_eq!(doc.mascara, Some(m));
    assert_eq!(doc.undo(), Change::Hair);
    assert_eq!((doc.mascara, doc.is_modified()), (None, false), "back to the opened state");
    assert_eq!(doc.redo(), Change::Hair);
    assert_eq!(doc.mascara, Some(m));
}
