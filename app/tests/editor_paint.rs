//! The editor core's painting tools (issue 15) without a window: fills as one undo step, the
//! straight Shift-click stroke, the stabiliser, pen pressure and the thickness readout.

use glam::Vec3;
use rouge_app::editor::Editor;
use rouge_model::document::{Change, Document, MAP_SIZE};
use rouge_model::look::Region;
use rouge_model::mesh::{TriangleMesh, load_mesh};
use rouge_model::paint::{FillRegion, SurfaceMap};
use std::sync::{Arc, OnceLock};

fn head() -> Arc<SurfaceMap> {
    static SURFACE: OnceLock<Arc<SurfaceMap>> = OnceLock::new();
    SURFACE
        .get_or_init(|| Arc::new(SurfaceMap::build(&load_mesh(None, 1.0, 1).expect("head"), MAP_SIZE, MAP_SIZE)))
        .clone()
}

fn plane() -> Arc<SurfaceMap> {
    static SURFACE: OnceLock<Arc<SurfaceMap>> = OnceLock::new();
    SURFACE.get_or_init(|| Arc::new(SurfaceMap::build(&TriangleMesh::flat_square(200.0), MAP_SIZE, MAP_SIZE))).clone()
}

fn editor(surface: Arc<SurfaceMap>) -> Editor {
    let mut e = Editor::new(Document::default_project());
    e.set_surface(Some(surface));
    e.brush.mirror = false;
    e
}

fn bits(e: &Editor) -> Vec<u32> {
    e.document().layers[e.active()].map.mm.iter().map(|v| v.to_bits()).collect()
}

#[test]
fn a_fill_inside_the_lips_mask_is_one_step_undone_bit_for_bit() {
    let surface = head();
    let mut e = editor(surface.clone());
    e.set_active_layer(0);
    let before = bits(&e);
    e.brush.thickness_mm = 0.03;
    let change = e.fill(FillRegion::Mask(Region::Lips.mask())).expect("a fill");
    assert!(matches!(change, Change::Map { layer: 0, .. }), "{change:?}");
    let after = bits(&e);
    let mask = Region::Lips.mask().resized(MAP_SIZE, MAP_SIZE);
    let mut changed = 0;
    for i in 0..after.len() {
        let (x, y) = (i as u32 % MAP_SIZE, i as u32 / MAP_SIZE);
        let inside = mask.mm[i] > 0.0 && surface.position(x, y).is_some();
        if after[i] != before[i] {
            changed += 1;
            assert!(inside, "texel ({x}, {y}) outside the lips mask changed");
        } else if inside {
            // Unchanged inside only where the layer already held the mask's value.
            let old = f32::from_bits(before[i]);
            assert!((old - (old + (0.03 - old) * mask.mm[i].min(1.0))).abs() < 1e-9, "texel ({x}, {y}) missed");
        }
    }
    println!("lips fill changed {changed} texels");
    assert!(changed > 1000);
    assert!(matches!(e.undo(), Change::Map { .. }));
    assert_eq!(bits(&e), before, "undo restores the layer bit for bit");
    assert!(matches!(e.redo(), Change::Map { .. }));
    assert_eq!(bits(&e), after);
    // A hidden layer refuses the fill and keeps its map.
    e.edit(|d| d.set_visible(0, false));
    assert!(e.fill(FillRegion::Whole).unwrap_err().contains("hidden"));
    assert_eq!(bits(&e), after);
}

#[test]
fn a_straight_stroke_lays_dabs_on_the_segment() {
    let mut e = editor(plane());
    e.brush.radius_mm = 4.0;
    let (a, b) = (Vec3::new(-40.0, -10.0, 0.0), Vec3::new(50.0, 20.0, 0.0));
    // The first Shift-click dabs once; the second draws from the end of the last stroke.
    e.straight_stroke(a).expect("visible layer");
    assert_eq!(e.last_stroke_dabs(), &[a]);
    let steps_before = e.document().can_undo();
    e.straight_stroke(b).expect("visible layer");
    let dabs = e.last_stroke_dabs().to_vec();
    let (dir, len) = ((b - a).normalize(), a.distance(b));
    let spacing = e.brush.spacing * e.brush.radius_mm;
    for d in &dabs {
        let t = (*d - a).dot(dir);
        let off = (*d - a - dir * t).length();
        // Each dab sits on a texel centre of the surface map (0.1 mm apart).
        assert!(off < 0.1 && t >= -0.1 && t <= len + 0.1, "dab {d} is {off} mm off the segment");
    }
    let want = (len / spacing).floor() as usize;
    assert!(dabs.len() >= want && dabs.len() <= want + 2, "{} dabs, {want} spacings", dabs.len());
    // One undo step each: the stroke, then the single dab.
    let before_undo = bits(&e);
    assert!(matches!(e.undo(), Change::Map { .. }));
    assert_ne!(bits(&e), before_undo);
    assert!(matches!(e.undo(), Change::Map { .. }));
    assert!(e.document().layers[e.active()].map.mm.iter().all(|v| *v == 0.0) || steps_before);
}

#[test]
fn the_stabiliser_steadies_a_stroke_and_pressure_thins_it() {
    let mut e = editor(plane());
    e.brush.radius_mm = 2.0;
    e.stabiliser_mm = 5.0;
    e.begin_stroke();
    // A zigzag of ±2 mm along x: the string never lets the wobble through.
    for i in 0..200 {
        let y = if i % 2 == 0 { 2.0 } else { -2.0 };
        e.stroke_to(Vec3::new(-60.0 + i as f32 * 0.5, y, 0.0)).expect("visible layer");
    }
    e.end_stroke();
    let dabs = e.last_stroke_dabs().to_vec();
    let worst = dabs.iter().skip(5).map(|d| d.y.abs()).fold(0.0f32, f32::max);
    println!("{} dabs, worst offset from the line after the start {worst:.2} mm", dabs.len());
    assert!(dabs.len() > 20 && worst < 0.75, "the stabilised stroke wobbles {worst} mm, the input ±2 mm");
    // Light pressure paints a narrower line than full pressure.
    let width = |pressure: f32| {
        let mut e = editor(plane());
        e.pressure = Some(pressure);
        let before = bits(&e);
        e.begin_stroke();
        e.stroke_to(Vec3::ZERO).expect("visible layer");
        e.end_stroke();
        bits(&e).iter().zip(&before).filter(|(a, b)| a != b).count()
    };
    assert!(width(0.2) * 3 < width(1.0));
    // The readout: the active layer's thickness under a point.
    let mut e = editor(plane());
    e.brush.thickness_mm = 0.02;
    e.fill(FillRegion::Whole).expect("a fill");
    let t = e.thickness_at(Vec3::new(3.0, 4.0, 0.0)).expect("on the plane");
    assert!((t - 0.02 * e.document().layers[e.active()].multiplier).abs() < 1e-7);
    assert_eq!(e.thickness_at(Vec3::new(0.0, 0.0, 500.0)), None);
}

#[test]
fn a_skin_brush_paints_skin_edits_not_layers_one_step_per_stroke_and_needs_skin_maps() {
    use rouge_app::editor::StrokeError;
    use rouge_model::skin::edits::EditChannel;
    use rouge_model::skin::{ProjectSkin, SkinBrush, SkinBrushKind, SkinRecipe};
    let surface = plane();
    let mut e = editor(surface.clone());
    let layers: Vec<Vec<u32>> =
        e.document().layers.iter().map(|l| l.map.mm.iter().map(|v| v.to_bits()).collect()).collect();
    e.skin_brush = Some(SkinBrush { kind: SkinBrushKind::LessBlood, factor: 2.0 });
    let centre = surface.position(MAP_SIZE / 2, MAP_SIZE / 2).expect("centre");
    // Without skin maps there is nothing to paint, and the message says what to do.
    e.begin_stroke();
    assert_eq!(e.stroke_to(centre), Err(StrokeError::NoSkinMaps));
    e.end_stroke();
    assert!(!e.document().can_undo());

    let recipe = SkinRecipe::from_tone("olive", Default::default(), 1, 64).expect("tone");
    assert_eq!(e.set_skin(Some(ProjectSkin::generate(recipe.clone()).expect("maps"))), Change::Skin { rect: None });
    e.begin_stroke();
    let changes = e.stroke_to(centre).expect("paints");
    assert!(matches!(changes.as_slice(), [Change::Skin { rect: Some(_) }]), "{changes:?}");
    let step = e.end_stroke();
    let Some(&Change::Skin { rect: Some(stroke_rect) }) = step.last() else { panic!("one skin step: {step:?}") };
    let edits = e.document().skin.as_ref().and_then(|s| s.edits.clone()).expect("edits");
    let blood = edits.plane(EditChannel::Blood);
    let i = (MAP_SIZE / 2 * MAP_SIZE + MAP_SIZE / 2) as usize;
    assert!(blood[i] < 0.0 && edits.plane(EditChannel::Melanin).iter().all(|&v| v == 0.0));
    let after: Vec<Vec<u32>> =
        e.document().layers.iter().map(|l| l.map.mm.iter().map(|v| v.to_bits()).collect()).collect();
    assert!(after == layers, "no makeup layer is painted");

    // New maps (another tone) keep the edits; undo takes the tone back, then the stroke.
    let deep = SkinRecipe::from_tone("deep", Default::default(), 1, 64).expect("tone");
    e.set_skin(Some(ProjectSkin::generate(deep).expect("maps")));
    assert!(e.document().skin.as_ref().and_then(|s| s.edits.clone()).is_some_and(|x| *x == *edits));
    e.undo();
    assert_eq!(e.document().skin.as_ref().map(|s| &s.recipe), Some(&recipe));
    assert_eq!(e.undo(), Change::Skin { rect: Some(stroke_rect) });
    assert!(e.document().skin.as_ref().and_then(|s| s.edits.clone()).is_none_or(|x| x.is_empty()));
}
