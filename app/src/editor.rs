//! The painting app's editor core: the document, the active layer, the brush and the stroke in
//! progress, with no egui, eframe or wgpu, so that every edit, stroke and undo step can be tested
//! without a window or a device. The GUI turns input into calls here and uploads what each
//! returned [`Change`] names; this never calls the GUI.

use glam::Vec3;
use rouge_measure::preset::Preset;
use rouge_model::TexelRect;
use rouge_model::document::{Change, Document};
use rouge_model::look::{Look, ThicknessMap};
use rouge_model::paint::{Brush, FillRegion, LazyMouse, PaintView, StrokeSpacer, SurfaceMap, apply_dab_in_view, fill};
use rouge_model::skin::edits::apply_skin_dab;
use rouge_model::skin::{ProjectSkin, SkinBrush};
use std::sync::Arc;

/// Why a dab was refused.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
pub enum StrokeError {
    /// The active layer is hidden, so painting it would be invisible.
    #[error("the active layer is hidden: show it to paint")]
    HiddenLayer,
    /// The active layer is locked against paint, fill and clear.
    #[error("the active layer is locked: unlock it to paint, fill or clear")]
    LockedLayer,
    /// A skin brush needs skin maps to paint on.
    #[error("the skin brushes paint skin maps: choose a tone in the Skin panel first")]
    NoSkinMaps,
}

/// Document, active layer, brush and the stroke in progress.
#[derive(Debug)]
pub struct Editor {
    doc: Document,
    /// The brush strokes use.
    pub brush: Brush,
    active: usize,
    surface: Option<Arc<SurfaceMap>>,
    spacer: Option<StrokeSpacer>,
    stroke_dabs: Vec<Vec3>,
    /// Where the painter looks from (facing and occlusion tests); `None` paints unseen.
    pub view: Option<PaintView>,
    /// The lazy-mouse string, mm (0 = off).
    pub stabiliser_mm: f32,
    lazy: Option<LazyMouse>,
    /// Pen or touch pressure of the current input in [0, 1]; `None` for a mouse.
    pub pressure: Option<f32>,
    /// The last dab of the last finished stroke, where a straight stroke starts.
    last_end: Option<Vec3>,
    /// Render only the active layer (the solo view).
    solo: bool,
    /// When set, strokes paint the skin edits with this skin brush (the cosmetic brush's
    /// radius, falloff and mirror) instead of the active layer.
    pub skin_brush: Option<SkinBrush>,
}

impl Editor {
    /// An editor on `doc` with its top layer active and the default brush; no surface yet.
    pub fn new(doc: Document) -> Editor {
        let active = doc.layers.len().saturating_sub(1);
        Editor {
            doc,
            brush: Brush::default(),
            active,
            surface: None,
            spacer: None,
            stroke_dabs: Vec::new(),
            view: None,
            stabiliser_mm: 0.0,
            lazy: None,
            pressure: None,
            last_end: None,
            solo: false,
            skin_brush: None,
        }
    }

    /// The document.
    pub fn document(&self) -> &Document {
        &self.doc
    }

    /// The document, for saving and autosaving (which end an open stroke). Layer edits go
    /// through [`Editor::edit`] so that the active layer stays valid.
    pub fn document_mut(&mut self) -> &mut Document {
        &mut self.doc
    }

    /// Replaces the document (new, opened or recovered project); its top layer becomes active.
    pub fn replace_document(&mut self, doc: Document) -> Change {
        self.spacer = None;
        self.stroke_dabs.clear();
        self.active = doc.layers.len().saturating_sub(1);
        self.doc = doc;
        Change::Layers
    }

    /// The layer strokes go to.
    pub fn active(&self) -> usize {
        self.active
    }

    /// Selects the layer strokes go to (clamped to the layers there are). Returns
    /// [`Change::Layers`] when the solo view must show another layer, else [`Change::Nothing`].
    pub fn set_active_layer(&mut self, i: usize) -> Change {
        let before = self.active;
        self.active = i.min(self.doc.layers.len().saturating_sub(1));
        if self.solo && self.active != before { Change::Layers } else { Change::Nothing }
    }

    /// Whether only the active layer is rendered.
    pub fn solo(&self) -> bool {
        self.solo
    }

    /// Renders only the active layer (`true`) or every visible layer. A view setting, not an
    /// edit: no undo step. Returns the layers to re-upload.
    pub fn set_solo(&mut self, on: bool) -> Change {
        if self.solo == on {
            return Change::Nothing;
        }
        self.solo = on;
        Change::Layers
    }

    /// The layers the renderer draws, bottom to top: every visible layer, or with the solo view
    /// only the active layer (when visible).
    pub fn render_layers(&self) -> Vec<usize> {
        let layers = &self.doc.layers;
        (0..layers.len()).filter(|&i| layers[i].visible && (!self.solo || i == self.active)).collect()
    }

    /// Whether the active layer takes paint: it exists, is visible and is not locked.
    ///
    /// # Errors
    /// [`StrokeError::HiddenLayer`] or [`StrokeError::LockedLayer`].
    pub fn paintable(&self) -> Result<(), StrokeError> {
        if self.skin_brush.is_some() {
            return if self.doc.skin.is_some() { Ok(()) } else { Err(StrokeError::NoSkinMaps) };
        }
        match self.doc.layers.get(self.active) {
            Some(l) if l.locked => Err(StrokeError::LockedLayer),
            Some(l) if l.visible => Ok(()),
            _ => Err(StrokeError::HiddenLayer),
        }
    }

    /// The surface map of the mesh being painted, once prepared.
    pub fn surface(&self) -> Option<&Arc<SurfaceMap>> {
        self.surface.as_ref()
    }

    /// Sets the surface map of a newly prepared mesh (ending any stroke).
    pub fn set_surface(&mut self, surface: Option<Arc<SurfaceMap>>) {
        self.spacer = None;
        self.lazy = None;
        self.last_end = None;
        self.surface = surface;
    }

    /// Where layer `layer` is among the layers the renderer draws ([`Editor::render_layers`]),
    /// or `None` for a layer not drawn (hidden, missing, or not the active one in the solo view).
    pub fn render_index(&self, layer: usize) -> Option<usize> {
        self.render_layers().iter().position(|&i| i == layer)
    }

    /// Applies a layer edit (one undo step, recorded by the document) and keeps the active
    /// layer valid.
    pub fn edit(&mut self, edit: impl FnOnce(&mut Document) -> Change) -> Change {
        let change = edit(&mut self.doc);
        self.set_active_layer(self.active);
        change
    }

    /// Replaces the skin maps (or, with `None`, goes back to the tone's flat skin) as one undo
    /// step. New maps keep the skin edits painted so far unless they bring their own: the
    /// edits are factors, so they apply to another tone's maps as they did to the old.
    pub fn set_skin(&mut self, skin: Option<ProjectSkin>) -> Change {
        let edits = self.doc.skin.as_ref().and_then(|s| s.edits.clone());
        let skin = skin.map(|mut s| {
            if s.edits.is_none() {
                s.edits = edits;
            }
            Arc::new(s)
        });
        self.doc.set_skin(skin)
    }

    /// Adds a layer of `preset` on top and makes it active.
    pub fn add_layer(&mut self, preset_ref: &str, preset: Preset) -> Change {
        let change = self.doc.add_layer(preset_ref, preset);
        self.active = self.doc.layers.len().saturating_sub(1);
        change
    }

    /// Replaces the layers with `look`'s as one undo step (a look from the library) and makes
    /// its top layer active.
    pub fn apply_look(&mut self, look: &Look) -> Change {
        let change = self.doc.apply_look(look);
        self.active = self.doc.layers.len().saturating_sub(1);
        change
    }

    /// Sets layer `i`'s whole map to zero thickness, as one undo step.
    ///
    /// # Errors
    /// [`StrokeError::LockedLayer`] when the layer is locked (nothing changes).
    pub fn clear_layer(&mut self, i: usize) -> Result<Change, StrokeError> {
        if self.doc.layers.get(i).is_some_and(|l| l.locked) {
            return Err(StrokeError::LockedLayer);
        }
        if let Some(map) = self.doc.begin_stroke(i) {
            map.mm.fill(0.0);
            let rect = TexelRect::whole(map.width, map.height);
            self.doc.note_dirty(rect);
        }
        Ok(self.doc.end_stroke())
    }

    /// Fills the active layer inside `region` with the brush's thickness, as one undo step
    /// (`rouge_model::paint::fill`). Returns the document's change.
    ///
    /// # Errors
    /// No surface map yet, a hidden or locked active layer, or what the fill refuses (a texel off the
    /// mesh, a thickness out of range), as a message.
    pub fn fill(&mut self, region: FillRegion<'_>) -> Result<Change, String> {
        let surface = self.surface.clone().ok_or("fill: the mesh is still being prepared")?;
        self.paintable().map_err(|e| e.to_string())?;
        let thickness = self.brush.thickness_mm;
        let rect = match self.doc.begin_stroke(self.active) {
            Some(map) => fill(map, &surface, region, thickness),
            None => Ok(TexelRect::EMPTY),
        };
        match rect {
            Ok(rect) => {
                self.doc.note_dirty(rect);
                Ok(self.doc.end_stroke())
            }
            Err(e) => {
                self.doc.end_stroke();
                Err(e)
            }
        }
    }

    /// The active layer's thickness under the surface point `world` (the painted map × the
    /// layer's multiplier, what renders), mm; `None` without a surface map or off the mesh.
    pub fn thickness_at(&self, world: Vec3) -> Option<f32> {
        let (x, y) = self.surface.as_ref()?.nearest_texel(world, 2.0)?;
        let layer = self.doc.layers.get(self.active)?;
        let map: &ThicknessMap = &layer.map;
        Some(map.texel(x, y) * layer.multiplier)
    }

    /// A straight stroke from the end of the last stroke to the surface point `to` (Shift-click):
    /// evenly spaced dabs on the segment, each moved onto the surface, as one undo step. With no
    /// earlier stroke it is a single dab at `to`.
    ///
    /// # Errors
    /// As [`Editor::paintable`].
    pub fn straight_stroke(&mut self, to: Vec3) -> Result<Vec<Change>, StrokeError> {
        let from = self.last_end;
        let stabiliser = std::mem::replace(&mut self.stabiliser_mm, 0.0);
        self.begin_stroke();
        let mut changes = Vec::new();
        let mut result = Ok(());
        for p in from.into_iter().chain([to]) {
            match self.stroke_to(p) {
                Ok(c) => changes.extend(c),
                Err(e) => result = Err(e),
            }
        }
        changes.extend(self.end_stroke());
        self.stabiliser_mm = stabiliser;
        result.map(|()| changes)
    }

    /// Undoes the last stroke or layer edit.
    pub fn undo(&mut self) -> Change {
        let change = self.doc.undo();
        self.set_active_layer(self.active);
        change
    }

    /// Redoes the last undone step.
    pub fn redo(&mut self) -> Change {
        let change = self.doc.redo();
        self.set_active_layer(self.active);
        change
    }

    /// Opens a stroke on the active layer (ending any open one).
    pub fn begin_stroke(&mut self) {
        self.spacer = None;
        self.lazy = (self.stabiliser_mm > 0.0).then(|| LazyMouse::new(self.stabiliser_mm));
        self.stroke_dabs.clear();
        if self.skin_brush.is_some() {
            let _ = self.doc.begin_skin_stroke();
        } else {
            let _ = self.doc.begin_stroke(self.active);
        }
    }

    /// Whether a stroke has dabbed since [`Editor::begin_stroke`].
    pub fn stroking(&self) -> bool {
        self.spacer.is_some()
    }

    /// Moves the brush to the surface point `world`: the first point of a stroke dabs there,
    /// later ones fill the way with evenly spaced dabs. Returns the changed rectangles, one per
    /// side of the face (the two sides of a mirrored dab lie far apart in UV). Nothing happens
    /// without a surface map or with an invalid brush.
    ///
    /// # Errors
    /// As [`Editor::paintable`]: a hidden or locked active layer.
    pub fn stroke_to(&mut self, world: Vec3) -> Result<Vec<Change>, StrokeError> {
        let Some(surface) = self.surface.clone() else { return Ok(Vec::new()) };
        if self.brush.validate().is_err() {
            return Ok(Vec::new());
        }
        self.paintable()?;
        // The stabiliser's brush point, moved onto the surface by the spacer.
        let world = match &mut self.lazy {
            Some(lazy) => match lazy.follow(world) {
                Some(p) => p,
                None => return Ok(Vec::new()),
            },
            None => world,
        };
        let dabs = match &mut self.spacer {
            Some(s) => s.move_to(world, &surface),
            None => {
                let mut s = StrokeSpacer::new(&self.brush);
                let d = s.start(world);
                self.spacer = Some(s);
                d
            }
        };
        Ok(self.dab(&dabs, &surface))
    }

    /// Ends the stroke: the spacer's last dab, then one undo step for the whole stroke. Returns
    /// the rectangles the last dab changed, then the document's change for the step.
    pub fn end_stroke(&mut self) -> Vec<Change> {
        let mut changes = Vec::new();
        if let (Some(mut spacer), Some(surface)) = (self.spacer.take(), self.surface.clone()) {
            let last = spacer.finish(&surface);
            if self.paintable().is_ok() {
                changes = self.dab(&last, &surface);
            }
        }
        self.lazy = None;
        if let Some(&last) = self.stroke_dabs.last() {
            self.last_end = Some(last);
        }
        changes.push(self.doc.end_stroke());
        changes
    }

    /// Surface points of the dabs of the last stroke.
    pub fn last_stroke_dabs(&self) -> &[Vec3] {
        &self.stroke_dabs
    }

    /// The mean surface point of the first lipstick layer's painted texels (every 4th texel
    /// each way), or `None` without a surface map or a painted lipstick layer: a point on the
    /// lips of the default look.
    pub fn lip_point(&self) -> Option<Vec3> {
        let surface = self.surface.as_deref()?;
        let lips = self.doc.layers.iter().find(|l| l.preset.kind == rouge_measure::Kind::Lipstick)?;
        let (mut sum, mut n) = (Vec3::ZERO, 0.0f32);
        for y in (0..lips.map.height).step_by(4) {
            for x in (0..lips.map.width).step_by(4) {
                if lips.map.mm[(y * lips.map.width + x) as usize] > 0.0
                    && let Some(p) = surface.position(x, y)
                {
                    sum += p;
                    n += 1.0;
                }
            }
        }
        (n > 0.0).then(|| sum / n)
    }

    fn dab(&mut self, dabs: &[Vec3], surface: &SurfaceMap) -> Vec<Change> {
        if dabs.is_empty() {
            return Vec::new();
        }
        let layer = self.active;
        let brush = match self.pressure {
            Some(p) => self.brush.with_pressure(p),
            None => self.brush,
        };
        let mut sides = [TexelRect::EMPTY; 2];
        if let Some(skin) = self.skin_brush {
            if let Some(edits) = self.doc.skin_stroke_edits() {
                for &c in dabs {
                    let [a, b] = apply_skin_dab(edits, surface, &brush, &skin, c, self.view.as_ref());
                    sides = [sides[0].union(a), sides[1].union(b)];
                }
            }
            self.stroke_dabs.extend_from_slice(dabs);
            return sides
                .into_iter()
                .filter(|r| !r.is_empty())
                .map(|rect| {
                    self.doc.note_dirty(rect);
                    Change::Skin { rect: Some(rect) }
                })
                .collect();
        }
        if let Some(map) = self.doc.stroke_map(layer) {
            for &c in dabs {
                let [a, b] = apply_dab_in_view(map, surface, &brush, c, self.view.as_ref());
                sides = [sides[0].union(a), sides[1].union(b)];
            }
        }
        self.stroke_dabs.extend_from_slice(dabs);
        sides
            .into_iter()
            .filter(|r| !r.is_empty())
            .map(|rect| {
                self.doc.note_dirty(rect);
                Change::Map { layer, rect }
            })
            .collect()
    }
}
