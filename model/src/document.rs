//! The painting app's document: cosmetic layers, each a preset and a painted thickness map of
//! [`MAP_SIZE`]² texels, with undo/redo, project folders, exports, autosave and crash recovery.
//! No GUI and no GPU here: the app draws [`Document::layers`] and re-uploads what each edit's
//! [`Change`] names.
//!
//! **History.** Every layer edit is one undo step that stores the whole layer list before and
//! after; the maps are shared ([`Arc`]), so such a step costs a few kilobytes until a map it holds
//! is painted over (painting copies the map, the step keeps the old one). A brush stroke, from
//! [`Document::begin_stroke`] to [`Document::end_stroke`], is one step that stores only the
//! changed rectangle, before and after. The history has a memory budget
//! ([`HISTORY_BUDGET_BYTES`] by default); past it the oldest steps are dropped.
//!
//! **Projects** are folders: `look.json` (a `rouge-look` v1 document that [`Look::load`] reads),
//! `maps/` (one OpenEXR map per layer, raw painted millimetres) and `presets/` (the presets that
//! are not built in). docs/FORMATS.md ("Project folders") describes them. Map and preset file
//! names carry a hash of their contents, so a save never overwrites a file the previous
//! `look.json` refers to: until the new `look.json` replaces the old one (an atomic rename) the
//! previous project is intact, and a map that did not change is not written again.

use crate::error::{ModelError, Result};
use crate::look::{BUILTIN_PREFIX, Look, LookLayer, MAX_THICKNESS_MM, ThicknessMap, ThicknessSource, builtin_preset};
use rouge_measure::preset::{Preset, PresetError, write_atomic};
use std::collections::{HashSet, VecDeque};
use std::fmt;
use std::path::{Path, PathBuf};
use std::sync::Arc;

/// Width and height of every painted thickness map, texels.
pub const MAP_SIZE: u32 = 2048;
/// Largest thickness multiplier of a layer.
pub const MAX_MULTIPLIER: f32 = 10.0;
/// Default memory budget of the undo history, bytes (1 GiB).
pub const HISTORY_BUDGET_BYTES: usize = 1 << 30;
/// The look document of a project folder.
pub const LOOK_FILE: &str = "look.json";
/// The folder of a project's thickness maps.
pub const MAPS_DIR: &str = "maps";
/// The folder of a project's presets (those not built in).
pub const PRESETS_DIR: &str = "presets";

pub use crate::rect::TexelRect;

const MAP_TEXELS: usize = MAP_SIZE as usize * MAP_SIZE as usize;
/// Rough cost of one layer in a layer-list snapshot (name, preset spectra and tables), bytes.
const LAYER_SNAPSHOT_BYTES: usize = 16 << 10;

// ------------------------------------------------------------------------------------------
// Layers

/// One cosmetic layer of the document.
#[derive(Clone, Debug, PartialEq)]
pub struct PaintLayer {
    /// Display name.
    pub name: String,
    /// Where the preset came from: `builtin:<name>` or a path.
    pub preset_ref: String,
    /// The material.
    pub preset: Preset,
    /// The painted thickness, mm, [`MAP_SIZE`] × [`MAP_SIZE`] (before the multiplier).
    pub map: Arc<ThicknessMap>,
    /// Whether the layer is drawn.
    pub visible: bool,
    /// Global thickness multiplier, 0..=[`MAX_MULTIPLIER`]: the layer is `map × multiplier` thick.
    pub multiplier: f32,
}

impl PaintLayer {
    /// The thickness the layer renders with: the painted map × the multiplier, mm.
    pub fn effective_map(&self) -> ThicknessMap {
        if self.multiplier == 1.0 { (*self.map).clone() } else { self.map.scaled(self.multiplier) }
    }
}

/// A [`MAP_SIZE`]² map of zeros (calloc'd: pages are touched only when painted).
fn empty_map() -> ThicknessMap {
    ThicknessMap { width: MAP_SIZE, height: MAP_SIZE, mm: vec![0.0; MAP_TEXELS] }
}

/// `map` at [`MAP_SIZE`]²: as it is if it has that size, filled if it is one texel, else
/// resampled bilinearly ([`ThicknessMap::resized`]).
fn at_map_size(map: &ThicknessMap) -> ThicknessMap {
    if map.width == 1 && map.height == 1 {
        let v = map.mm.first().copied().unwrap_or(0.0);
        return ThicknessMap { width: MAP_SIZE, height: MAP_SIZE, mm: vec![v; MAP_TEXELS] };
    }
    map.resized(MAP_SIZE, MAP_SIZE)
}

// ------------------------------------------------------------------------------------------
// Changes and history

/// What an edit changed, so the app re-uploads no more than it must.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Change {
    /// The layer list, order, presets, names, visibility or multipliers changed (or a map's
    /// size): re-upload all layers.
    Layers,
    /// Only `rect` of the map of layer `layer` changed.
    Map {
        /// Index into [`Document::layers`].
        layer: usize,
        /// The changed texels.
        rect: TexelRect,
    },
    /// Nothing changed (and no undo step was recorded).
    Nothing,
}

/// One undo step.
enum Edit {
    /// A layer edit: the whole list before and after (maps shared).
    Layers { before: Vec<PaintLayer>, after: Vec<PaintLayer> },
    /// A stroke: the changed rectangle of one map, row by row, before and after.
    Stroke { layer: usize, rect: TexelRect, before: Vec<f32>, after: Vec<f32> },
}

struct Entry {
    /// Identifies the document state after this step (for the saved marker).
    id: u64,
    edit: Edit,
}

struct History {
    undo: VecDeque<Entry>,
    redo: Vec<Entry>,
    next_id: u64,
    /// The id of the state with nothing left to undo (changes as the oldest steps are dropped).
    base_id: u64,
    /// The state last saved or opened; `None` if that state is no longer reachable.
    saved_id: Option<u64>,
    budget_bytes: usize,
}

impl History {
    fn new() -> Self {
        History {
            undo: VecDeque::new(),
            redo: Vec::new(),
            next_id: 1,
            base_id: 0,
            saved_id: Some(0),
            budget_bytes: HISTORY_BUDGET_BYTES,
        }
    }

    fn state_id(&self) -> u64 {
        self.undo.back().map_or(self.base_id, |e| e.id)
    }
}

/// The open stroke: the map as it was when the stroke began and the union of the dirty rects.
struct OpenStroke {
    layer: usize,
    start: Arc<ThicknessMap>,
    rect: Option<TexelRect>,
}

// ------------------------------------------------------------------------------------------
// The document

/// The painting app's document. Edit the layers through the methods, which record undo steps;
/// changing [`Document::layers`] directly bypasses the history.
pub struct Document {
    /// Display name.
    pub name: String,
    /// Layers, bottom (on the skin) to top.
    pub layers: Vec<PaintLayer>,
    history: History,
    stroke: Option<OpenStroke>,
}

impl fmt::Debug for Document {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let names: Vec<&str> = self.layers.iter().map(|l| l.name.as_str()).collect();
        f.debug_struct("Document")
            .field("name", &self.name)
            .field("layers", &names)
            .field("undo_steps", &self.history.undo.len())
            .field("redo_steps", &self.history.redo.len())
            .field("stroke_open", &self.stroke.is_some())
            .field("modified", &self.is_modified())
            .finish()
    }
}

impl Document {
    /// A document holding `look`'s layers, each map at [`MAP_SIZE`]² (uniform layers filled,
    /// regions, masks and maps resampled bilinearly with their thickness folded in), multiplier 1.
    /// Unmodified, with an empty history.
    pub fn from_look(look: &Look) -> Document {
        let layers = look
            .layers
            .iter()
            .map(|l| PaintLayer {
                name: l.name.clone(),
                preset_ref: l.preset_ref.clone(),
                preset: l.preset.clone(),
                map: Arc::new(at_map_size(&l.map)),
                visible: l.visible,
                multiplier: 1.0,
            })
            .collect();
        Document { name: look.name.clone(), layers, history: History::new(), stroke: None }
    }

    /// A new project: the default look ([`Look::default_look`]), named "Untitled".
    pub fn default_project() -> Document {
        let mut doc = Document::from_look(&Look::default_look());
        doc.name = "Untitled".into();
        doc
    }

    /// The document as the look its project's `look.json` holds: each layer's thickness is
    /// `{"map": "maps/NN-<slug>-<hash>.exr"}` with `"scale_mm"` = the multiplier (left out when
    /// 1), presets that are not built in refer to `presets/NN-<slug>-<hash>.json`, and each
    /// layer's `map` is what that thickness resolves to: the effective map (painted × multiplier),
    /// so the look renders like the document and equals what [`Look::load`] reads back.
    pub fn to_look(&self) -> Look {
        let layers =
            self.layers.iter().enumerate().map(|(i, l)| look_layer(l, &layer_files(i, l), l.effective_map())).collect();
        Look { name: self.name.clone(), layers }
    }

    // --------------------------------------------------------------------------------------
    // Layer edits

    /// Adds a layer on top with an empty map, named after the preset, visible, multiplier 1.
    pub fn add_layer(&mut self, preset_ref: &str, preset: Preset) -> Change {
        let layer = PaintLayer {
            name: preset.name.clone(),
            preset_ref: preset_ref.to_string(),
            preset,
            map: Arc::new(empty_map()),
            visible: true,
            multiplier: 1.0,
        };
        self.edit_layers(|layers| {
            layers.push(layer);
            true
        })
    }

    /// Removes layer `i`.
    pub fn remove_layer(&mut self, i: usize) -> Change {
        self.edit_layers(|layers| {
            if i >= layers.len() {
                return false;
            }
            layers.remove(i);
            true
        })
    }

    /// Moves layer `from` so that it ends up at index `to` (both must be layers; 0 is the bottom).
    pub fn move_layer(&mut self, from: usize, to: usize) -> Change {
        self.edit_layers(|layers| {
            if from >= layers.len() || to >= layers.len() || from == to {
                return false;
            }
            let layer = layers.remove(from);
            layers.insert(to, layer);
            true
        })
    }

    /// Renames layer `i`. An empty or blank name, or the same name, changes nothing.
    pub fn rename_layer(&mut self, i: usize, name: &str) -> Change {
        self.edit_layers(|layers| match layers.get_mut(i) {
            Some(l) if !name.trim().is_empty() && l.name != name => {
                l.name = name.to_string();
                true
            }
            _ => false,
        })
    }

    /// Shows or hides layer `i`.
    pub fn set_visible(&mut self, i: usize, v: bool) -> Change {
        self.edit_layers(|layers| match layers.get_mut(i) {
            Some(l) if l.visible != v => {
                l.visible = v;
                true
            }
            _ => false,
        })
    }

    /// Sets layer `i`'s thickness multiplier, clamped to 0..=[`MAX_MULTIPLIER`]; a non-finite
    /// `m` changes nothing. Each call is one undo step: call it when a slider drag ends.
    pub fn set_multiplier(&mut self, i: usize, m: f32) -> Change {
        if !m.is_finite() {
            return Change::Nothing;
        }
        let m = m.clamp(0.0, MAX_MULTIPLIER);
        self.edit_layers(|layers| match layers.get_mut(i) {
            Some(l) if l.multiplier != m => {
                l.multiplier = m;
                true
            }
            _ => false,
        })
    }

    /// Gives layer `i` another preset. A layer still named after its old preset takes the new
    /// preset's name; a renamed layer keeps its name.
    pub fn set_preset(&mut self, i: usize, preset_ref: &str, preset: Preset) -> Change {
        self.edit_layers(|layers| match layers.get_mut(i) {
            Some(l) if l.preset_ref != preset_ref || l.preset != preset => {
                if l.name == l.preset.name {
                    l.name = preset.name.clone();
                }
                l.preset_ref = preset_ref.to_string();
                l.preset = preset;
                true
            }
            _ => false,
        })
    }

    /// Runs a layer edit as one undo step. `edit` returns whether it changed anything, and
    /// must leave the list as it was when it returns false.
    fn edit_layers(&mut self, edit: impl FnOnce(&mut Vec<PaintLayer>) -> bool) -> Change {
        self.finish_stroke();
        let before = self.layers.clone();
        if !edit(&mut self.layers) {
            return Change::Nothing;
        }
        let after = self.layers.clone();
        self.push(Edit::Layers { before, after });
        Change::Layers
    }

    // --------------------------------------------------------------------------------------
    // Strokes

    /// Opens a stroke on layer `layer` (ending any open stroke) and returns its map to paint;
    /// `None` if there is no such layer. The map as it was is kept (shared, no copy) until
    /// [`Document::end_stroke`]; the returned map is the document's own copy.
    pub fn begin_stroke(&mut self, layer: usize) -> Option<&mut ThicknessMap> {
        self.finish_stroke();
        let start = Arc::clone(&self.layers.get(layer)?.map);
        self.stroke = Some(OpenStroke { layer, start, rect: None });
        self.layers.get_mut(layer).map(|l| Arc::make_mut(&mut l.map))
    }

    /// The map being painted: `Some` only while a stroke is open on `layer`.
    pub fn stroke_map(&mut self, layer: usize) -> Option<&mut ThicknessMap> {
        if self.stroke.as_ref().is_none_or(|s| s.layer != layer) {
            return None;
        }
        self.layers.get_mut(layer).map(|l| Arc::make_mut(&mut l.map))
    }

    /// Reports texels the painter changed during the open stroke (half-open, clamped to the
    /// map); the document keeps the union. Ignored when no stroke is open.
    pub fn note_dirty(&mut self, rect: TexelRect) {
        let Some(stroke) = self.stroke.as_mut() else { return };
        let (w, h) = (stroke.start.width, stroke.start.height);
        let rect = rect.clamped(w, h);
        if rect.is_empty() {
            return;
        }
        stroke.rect = Some(stroke.rect.map_or(rect, |r| r.union(rect)));
    }

    /// Ends the open stroke: one undo step holding the changed texels' bounding box before and
    /// after, and `Change::Map` naming it; `Change::Nothing` if no texel changed (or no stroke
    /// was open). Without any [`Document::note_dirty`] the whole map is compared.
    pub fn end_stroke(&mut self) -> Change {
        self.finish_stroke()
    }

    fn finish_stroke(&mut self) -> Change {
        let Some(stroke) = self.stroke.take() else { return Change::Nothing };
        let Some(layer) = self.layers.get(stroke.layer) else { return Change::Nothing };
        let (old, new) = (&*stroke.start, &*layer.map);
        if (old.width, old.height, old.mm.len()) != (new.width, new.height, new.mm.len()) {
            // The painter replaced the map by one of another size: record the whole layer list.
            let mut before = self.layers.clone();
            if let Some(l) = before.get_mut(stroke.layer) {
                l.map = stroke.start;
            }
            let after = self.layers.clone();
            self.push(Edit::Layers { before, after });
            return Change::Layers;
        }
        let search = stroke.rect.unwrap_or(TexelRect::whole(old.width, old.height));
        let Some(rect) = changed_bounds(old, new, search) else {
            // Nothing changed: give the layer its old map back, so that history steps sharing
            // it do not keep a second copy alive.
            if let Some(l) = self.layers.get_mut(stroke.layer) {
                l.map = stroke.start;
            }
            return Change::Nothing;
        };
        let (before, after) = (read_rect(old, rect), read_rect(new, rect));
        self.push(Edit::Stroke { layer: stroke.layer, rect, before, after });
        Change::Map { layer: stroke.layer, rect }
    }

    // --------------------------------------------------------------------------------------
    // Undo / redo

    /// Whether there is a step to undo (an open stroke counts: undo ends and undoes it).
    pub fn can_undo(&self) -> bool {
        !self.history.undo.is_empty() || self.stroke.as_ref().is_some_and(|s| s.rect.is_some())
    }

    /// Whether there is a step to redo.
    pub fn can_redo(&self) -> bool {
        !self.history.redo.is_empty()
    }

    /// Undoes the last step (ending an open stroke first); maps come back bit for bit.
    pub fn undo(&mut self) -> Change {
        self.finish_stroke();
        let Some(entry) = self.history.undo.pop_back() else { return Change::Nothing };
        let change = self.apply(&entry.edit, false);
        self.history.redo.push(entry);
        change
    }

    /// Redoes the last undone step.
    pub fn redo(&mut self) -> Change {
        self.finish_stroke();
        let Some(entry) = self.history.redo.pop() else { return Change::Nothing };
        let change = self.apply(&entry.edit, true);
        self.history.undo.push_back(entry);
        change
    }

    fn apply(&mut self, edit: &Edit, forward: bool) -> Change {
        match edit {
            Edit::Layers { before, after } => {
                self.layers = if forward { after.clone() } else { before.clone() };
                Change::Layers
            }
            Edit::Stroke { layer, rect, before, after } => {
                let Some(l) = self.layers.get_mut(*layer) else { return Change::Nothing };
                write_rect(Arc::make_mut(&mut l.map), *rect, if forward { after } else { before });
                Change::Map { layer: *layer, rect: *rect }
            }
        }
    }

    /// Records a new step: clears the redo steps and drops the oldest steps past the budget.
    fn push(&mut self, edit: Edit) {
        let h = &mut self.history;
        h.redo.clear();
        h.undo.push_back(Entry { id: h.next_id, edit });
        h.next_id += 1;
        self.trim_history();
    }

    /// Bytes each undo step keeps alive, oldest first. A map no longer in the document is
    /// counted once, with the newest step holding it (dropping older steps does not free it).
    fn step_costs(&self) -> Vec<usize> {
        let live: HashSet<*const ThicknessMap> = self.layers.iter().map(|l| Arc::as_ptr(&l.map)).collect();
        let mut seen = HashSet::new();
        let mut costs: Vec<usize> = self
            .history
            .undo
            .iter()
            .rev()
            .map(|e| match &e.edit {
                Edit::Stroke { before, after, .. } => (before.len() + after.len()) * std::mem::size_of::<f32>(),
                Edit::Layers { before, after } => before
                    .iter()
                    .chain(after)
                    .map(|l| {
                        let p = Arc::as_ptr(&l.map);
                        let map = if !live.contains(&p) && seen.insert(p) {
                            l.map.mm.len() * std::mem::size_of::<f32>()
                        } else {
                            0
                        };
                        LAYER_SNAPSHOT_BYTES + map
                    })
                    .sum(),
            })
            .collect();
        costs.reverse();
        costs
    }

    fn trim_history(&mut self) {
        let costs = self.step_costs();
        let mut total: usize = costs.iter().sum();
        let mut drop = 0;
        // The newest step always stays.
        while total > self.history.budget_bytes && drop + 1 < costs.len() {
            total -= costs[drop];
            drop += 1;
        }
        for _ in 0..drop {
            if let Some(e) = self.history.undo.pop_front() {
                self.history.base_id = e.id;
            }
        }
    }

    /// Memory the undo and redo steps keep alive beyond the document itself, bytes (estimated
    /// for names and presets; maps and stroke rectangles exactly).
    pub fn history_bytes(&self) -> usize {
        let redo: usize = self
            .history
            .redo
            .iter()
            .map(|e| match &e.edit {
                Edit::Stroke { before, after, .. } => (before.len() + after.len()) * std::mem::size_of::<f32>(),
                Edit::Layers { before, after } => (before.len() + after.len()) * LAYER_SNAPSHOT_BYTES,
            })
            .sum();
        self.step_costs().iter().sum::<usize>() + redo
    }

    /// Sets the history's memory budget (default [`HISTORY_BUDGET_BYTES`]); the oldest steps
    /// past it are dropped now and as new steps come (the newest step always stays).
    pub fn set_history_budget(&mut self, bytes: usize) {
        self.history.budget_bytes = bytes;
        self.trim_history();
    }

    /// Whether the document differs from the last save or open (a stroke in progress that
    /// reported a dirty rect counts).
    pub fn is_modified(&self) -> bool {
        self.history.saved_id != Some(self.history.state_id()) || self.stroke.as_ref().is_some_and(|s| s.rect.is_some())
    }

    // --------------------------------------------------------------------------------------
    // Projects

    /// Saves the project into the folder `dir` (created if missing), ending an open stroke
    /// first: the maps, then the presets, then `look.json`, each atomically (temporary file,
    /// then rename). Files are named by their contents, so nothing the previous `look.json`
    /// refers to is overwritten, and unchanged maps are not written again; map and preset files
    /// that the new `look.json` does not refer to are deleted after it is written. On error
    /// (naming the file) the previous project is left as it was. Marks the document unmodified.
    pub fn save_project(&mut self, dir: &Path) -> Result<()> {
        self.finish_stroke();
        write_project(self, dir)?;
        self.history.saved_id = Some(self.history.state_id());
        Ok(())
    }

    /// Opens a project folder: `dir/look.json` by [`Look::load`], then [`Document::from_look`],
    /// with the painted maps read back unscaled (bit for bit) and each layer's multiplier from
    /// its `scale_mm`. Errors name the file at fault.
    pub fn open_project(dir: &Path) -> Result<Document> {
        let look_path = dir.join(LOOK_FILE);
        let look = Look::load(&look_path)?;
        let mut doc = Document::from_look(&look);
        for (look_layer, layer) in look.layers.iter().zip(doc.layers.iter_mut()) {
            let ThicknessSource::Map { path, scale_mm: Some(scale) } = &look_layer.thickness else { continue };
            // The look holds map × scale_mm, and dividing by it again is not exact: read the
            // painted values themselves. (A PNG map cannot be read without its scale: it stays
            // as the look resolved it, with multiplier 1.)
            let unscaled = ThicknessSource::Map { path: path.clone(), scale_mm: None };
            if let Ok(raw) = unscaled.load_map(base_dir(dir)) {
                layer.map = Arc::new(at_map_size(&raw));
                layer.multiplier = *scale;
            }
        }
        Ok(doc)
    }

    // --------------------------------------------------------------------------------------
    // Exports

    /// Writes each layer's effective thickness (painted × multiplier) into `dir` (created if
    /// missing), named `NN-<slug>`: `.exr` (single channel `Y`, mm, exact), `.png` (16-bit grey,
    /// value / max · 65535) and `.thickness.json`, the look thickness that reads the PNG back,
    /// `{"map": "NN-<slug>.png", "scale_mm": max}`. Atomic writes; returns the files written.
    pub fn export_maps(&self, dir: &Path) -> Result<Vec<PathBuf>> {
        create_dir(dir)?;
        let mut written = Vec::with_capacity(self.layers.len() * 3);
        for (i, layer) in self.layers.iter().enumerate() {
            let stem = format!("{i:02}-{}", slug(&layer.name));
            let map = layer.effective_map();
            let exr = dir.join(format!("{stem}.exr"));
            map.save_exr(&exr)?;
            written.push(exr);

            let max_mm = map.max_mm();
            let png_name = format!("{stem}.png");
            let png = dir.join(&png_name);
            write_atomic(&png, &encode_png16(&map, max_mm, &png)?).map_err(|e| ModelError::file(&png, e))?;
            written.push(png);

            let sidecar = dir.join(format!("{stem}.thickness.json"));
            let json = serde_json::json!({ "map": png_name, "scale_mm": max_mm });
            let text = serde_json::to_string_pretty(&json).map_err(|e| ModelError::file(&sidecar, e))? + "\n";
            write_atomic(&sidecar, text.as_bytes()).map_err(|e| ModelError::file(&sidecar, e))?;
            written.push(sidecar);
        }
        Ok(written)
    }

    /// Writes layer `i`'s preset as a preset file (`rouge-preset` JSON), atomically.
    pub fn export_preset(&self, i: usize, path: &Path) -> Result<()> {
        let layer = self
            .layers
            .get(i)
            .ok_or_else(|| ModelError::Invalid(format!("no layer {i}: the document has {}", self.layers.len())))?;
        layer.preset.save(path).map_err(|e| match e {
            PresetError::Io { source, .. } => ModelError::file(path, source),
            other => ModelError::Invalid(other.to_string()),
        })
    }

    // --------------------------------------------------------------------------------------
    // Autosave and recovery

    /// Saves the document into the recovery folder `dir` as [`Document::save_project`] does,
    /// but leaves an open stroke open and the document's modified state as it is.
    pub fn autosave(&mut self, dir: &Path) -> Result<()> {
        write_project(self, dir)
    }

    /// Whether `dir` holds an autosave that was not cleared (open it with
    /// [`Document::open_project`]).
    pub fn recovery_available(dir: &Path) -> bool {
        dir.join(LOOK_FILE).is_file()
    }

    /// Deletes the autosave in `dir`: `look.json` first (so that a partial clear is no longer
    /// offered for recovery), then the project's map and preset files, then their folders if
    /// empty. Nothing to delete is not an error.
    pub fn clear_recovery(dir: &Path) -> Result<()> {
        let look = dir.join(LOOK_FILE);
        match std::fs::remove_file(&look) {
            Ok(()) => {}
            Err(e) if e.kind() == std::io::ErrorKind::NotFound => {}
            Err(e) => return Err(ModelError::file(&look, e)),
        }
        remove_unreferenced(dir, &HashSet::new())?;
        for sub in [MAPS_DIR, PRESETS_DIR] {
            // Only if empty: files that are not Rouge's stay, and so does their folder.
            let _ = std::fs::remove_dir(dir.join(sub));
        }
        Ok(())
    }
}

// ------------------------------------------------------------------------------------------
// Rectangles

/// The bounding box of the texels inside `search` whose bits differ between `old` and `new`
/// (same size), or `None`.
fn changed_bounds(old: &ThicknessMap, new: &ThicknessMap, search: TexelRect) -> Option<TexelRect> {
    let w = old.width as usize;
    let (x0, y0, x1, y1) = (search.x0 as usize, search.y0 as usize, search.x1 as usize, search.y1 as usize);
    let mut bounds: Option<(usize, usize, usize, usize)> = None;
    for y in y0..y1 {
        let (Some(a), Some(b)) = (old.mm.get(y * w + x0..y * w + x1), new.mm.get(y * w + x0..y * w + x1)) else {
            continue;
        };
        let differs = |(p, q): (&f32, &f32)| p.to_bits() != q.to_bits();
        let Some(first) = a.iter().zip(b).position(differs) else { continue };
        let last = a.iter().zip(b).rposition(differs).unwrap_or(first);
        let (lo, hi) = (x0 + first, x0 + last + 1);
        bounds = Some(match bounds {
            None => (lo, y, hi, y + 1),
            Some((bx0, by0, bx1, _)) => (bx0.min(lo), by0, bx1.max(hi), y + 1),
        });
    }
    // The bounds lie inside `search`, which holds u32s.
    bounds.map(|(x0, y0, x1, y1)| TexelRect { x0: x0 as u32, y0: y0 as u32, x1: x1 as u32, y1: y1 as u32 })
}

/// The texels of `rect`, row by row.
fn read_rect(map: &ThicknessMap, rect: TexelRect) -> Vec<f32> {
    let w = map.width as usize;
    let (x0, x1) = (rect.x0 as usize, rect.x1 as usize);
    let mut out = Vec::with_capacity(rect.area());
    for y in rect.y0 as usize..rect.y1 as usize {
        if let Some(row) = map.mm.get(y * w + x0..y * w + x1) {
            out.extend_from_slice(row);
        }
    }
    out
}

/// Writes `values` (row by row, as [`read_rect`] gives them) into `rect`.
fn write_rect(map: &mut ThicknessMap, rect: TexelRect, values: &[f32]) {
    let w = map.width as usize;
    let (x0, x1) = (rect.x0 as usize, rect.x1 as usize);
    if x1 <= x0 {
        return;
    }
    let rows = values.chunks_exact(x1 - x0);
    for (y, row) in (rect.y0 as usize..rect.y1 as usize).zip(rows) {
        if let Some(dst) = map.mm.get_mut(y * w + x0..y * w + x1) {
            dst.copy_from_slice(row);
        }
    }
}

// ------------------------------------------------------------------------------------------
// Project files

/// A file name part from a display name: lower-case ASCII letters and digits, runs of anything
/// else as one `-`, at most 40 characters; `layer` if nothing is left.
fn slug(name: &str) -> String {
    let mut s = String::new();
    for c in name.chars() {
        if c.is_ascii_alphanumeric() {
            s.push(c.to_ascii_lowercase());
        } else if !s.is_empty() && !s.ends_with('-') {
            s.push('-');
        }
    }
    s.truncate(40);
    let s = s.trim_end_matches('-');
    if s.is_empty() { "layer".into() } else { s.into() }
}

/// 64-bit hash of a map's size and values (bit patterns): names its file in a project.
/// Multiply-rotate mixing with a SplitMix64 finaliser; not cryptographic, only to tell maps apart.
fn map_hash(map: &ThicknessMap) -> u64 {
    let mut h = 0x9E37_79B9_7F4A_7C15u64 ^ (u64::from(map.width) << 32 | u64::from(map.height));
    for v in &map.mm {
        h = (h.rotate_left(23) ^ u64::from(v.to_bits())).wrapping_mul(0xD6E8_FEB8_6659_FD93);
    }
    splitmix64(h ^ map.mm.len() as u64)
}

fn bytes_hash(bytes: &[u8]) -> u64 {
    let mut h = 0x9E37_79B9_7F4A_7C15u64;
    for &b in bytes {
        h = (h.rotate_left(23) ^ u64::from(b)).wrapping_mul(0xD6E8_FEB8_6659_FD93);
    }
    splitmix64(h ^ bytes.len() as u64)
}

fn splitmix64(mut z: u64) -> u64 {
    z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
    z ^ (z >> 31)
}

const HASH_DIGITS: usize = 16;

/// `NN-<slug>-<hash>.<ext>`.
fn hashed_name(i: usize, name: &str, hash: u64, ext: &str) -> String {
    format!("{i:02}-{}-{hash:016x}.{ext}", slug(name))
}

/// Whether `file` is named as [`hashed_name`] names files with extension `ext`.
fn is_hashed_name(file: &str, ext: &str) -> bool {
    let Some(stem) = file.strip_suffix(ext).and_then(|s| s.strip_suffix('.')) else { return false };
    let stem = stem.as_bytes();
    let Some(split) = stem.len().checked_sub(HASH_DIGITS + 1) else { return false };
    let (head, hash) = stem.split_at(split);
    head.first().is_some_and(u8::is_ascii_digit)
        && hash.first() == Some(&b'-')
        && hash.iter().skip(1).all(|b| b.is_ascii_digit() || (b'a'..=b'f').contains(b))
}

/// Where a layer's preset goes in a project.
enum PresetFile {
    /// A built-in preset, unchanged: referred to as `builtin:<name>`.
    Builtin(String),
    /// Written to `presets/<file>`.
    File { file: String, json: String },
}

fn preset_file(i: usize, layer: &PaintLayer) -> PresetFile {
    if let Some(name) = layer.preset_ref.strip_prefix(BUILTIN_PREFIX)
        && builtin_preset(name).as_ref() == Some(&layer.preset)
    {
        return PresetFile::Builtin(layer.preset_ref.clone());
    }
    let json = layer.preset.to_json();
    PresetFile::File { file: hashed_name(i, &layer.preset.name, bytes_hash(json.as_bytes()), "json"), json }
}

/// The files a layer has in a project: its map (in `maps/`) and its preset.
struct LayerFiles {
    map: String,
    preset: PresetFile,
}

fn layer_files(i: usize, layer: &PaintLayer) -> LayerFiles {
    LayerFiles { map: hashed_name(i, &layer.name, map_hash(&layer.map), "exr"), preset: preset_file(i, layer) }
}

/// A layer as its project's `look.json` has it, with `map` as its map.
fn look_layer(layer: &PaintLayer, files: &LayerFiles, map: ThicknessMap) -> LookLayer {
    let preset_ref = match &files.preset {
        PresetFile::Builtin(r) => r.clone(),
        PresetFile::File { file, .. } => format!("{PRESETS_DIR}/{file}"),
    };
    LookLayer {
        name: layer.name.clone(),
        preset_ref,
        preset: layer.preset.clone(),
        thickness: ThicknessSource::Map {
            path: PathBuf::from(format!("{MAPS_DIR}/{}", files.map)),
            scale_mm: (layer.multiplier != 1.0).then_some(layer.multiplier),
        },
        map,
        visible: layer.visible,
    }
}

fn base_dir(dir: &Path) -> &Path {
    if dir.as_os_str().is_empty() { Path::new(".") } else { dir }
}

fn create_dir(dir: &Path) -> Result<()> {
    std::fs::create_dir_all(dir).map_err(|e| ModelError::file(dir, format!("cannot create the folder: {e}")))
}

/// Checks that every layer can be written as a look that [`Look::load`] reads back: maps of
/// [`MAP_SIZE`]², painted values and values × multiplier finite, ≥ 0 and ≤ 10 mm.
fn check_layers(doc: &Document, look_path: &Path) -> Result<()> {
    for (i, l) in doc.layers.iter().enumerate() {
        let at = |m: String| ModelError::file(look_path, format!("layer {i} ({:?}): {m}", l.name));
        let map = &*l.map;
        if (map.width, map.height, map.mm.len()) != (MAP_SIZE, MAP_SIZE, MAP_TEXELS) {
            return Err(at(format!(
                "the map is {}×{} with {} values, not {MAP_SIZE}×{MAP_SIZE}",
                map.width,
                map.height,
                map.mm.len()
            )));
        }
        if !(l.multiplier.is_finite() && (0.0..=MAX_MULTIPLIER).contains(&l.multiplier)) {
            return Err(at(format!("multiplier {} is not in 0..={MAX_MULTIPLIER}", l.multiplier)));
        }
        let ok = |v: f32| v.is_finite() && (0.0..=MAX_THICKNESS_MM).contains(&v);
        if let Some(k) = map.mm.iter().position(|&v| !ok(v)) {
            let (x, y) = (k % MAP_SIZE as usize, k / MAP_SIZE as usize);
            return Err(at(format!(
                "texel ({x}, {y}) is {} mm: thickness must be finite, ≥ 0 and ≤ {MAX_THICKNESS_MM} mm",
                map.mm[k]
            )));
        }
        // Rounding is monotonic, so the largest product is the product of the largest value.
        let max = map.max_mm() * l.multiplier;
        if !ok(max) {
            return Err(at(format!(
                "the thickness × multiplier {} reaches {max} mm, more than the {MAX_THICKNESS_MM} mm a look allows",
                l.multiplier
            )));
        }
    }
    Ok(())
}

/// Writes `doc` as a project into `dir`: maps, presets, `look.json`, then deletes files of
/// earlier saves that it no longer refers to.
fn write_project(doc: &Document, dir: &Path) -> Result<()> {
    let look_path = dir.join(LOOK_FILE);
    check_layers(doc, &look_path)?;
    create_dir(dir)?;
    let maps_dir = dir.join(MAPS_DIR);
    create_dir(&maps_dir)?;
    let files: Vec<LayerFiles> = doc.layers.iter().enumerate().map(|(i, l)| layer_files(i, l)).collect();
    let mut keep = HashSet::new();
    for (layer, files) in doc.layers.iter().zip(&files) {
        let path = maps_dir.join(&files.map);
        // Named by content: an existing file already holds these values.
        if !path.is_file() {
            layer.map.save_exr(&path)?;
        }
        keep.insert(PathBuf::from(MAPS_DIR).join(&files.map));
    }
    for files in &files {
        if let PresetFile::File { file, json } = &files.preset {
            let presets_dir = dir.join(PRESETS_DIR);
            create_dir(&presets_dir)?;
            let path = presets_dir.join(file);
            if !path.is_file() {
                write_atomic(&path, json.as_bytes()).map_err(|e| ModelError::file(&path, e))?;
            }
            keep.insert(PathBuf::from(PRESETS_DIR).join(file));
        }
    }
    // `look.json` needs only the references; the maps themselves are in the files.
    let layers = doc.layers.iter().zip(&files).map(|(l, f)| look_layer(l, f, ThicknessMap::uniform(0.0))).collect();
    let look = Look { name: doc.name.clone(), layers };
    look.save(&look_path)?;
    // The project is saved; a file that cannot be deleted now is deleted by a later save.
    let _ = remove_unreferenced(dir, &keep);
    Ok(())
}

/// Deletes the map and preset files of the project in `dir` (named as Rouge names them) that
/// are not in `keep` (paths relative to `dir`). Returns the first error, after trying all.
fn remove_unreferenced(dir: &Path, keep: &HashSet<PathBuf>) -> Result<()> {
    let mut first_error = None;
    for (sub, ext) in [(MAPS_DIR, "exr"), (PRESETS_DIR, "json")] {
        let Ok(entries) = std::fs::read_dir(dir.join(sub)) else { continue };
        for entry in entries.flatten() {
            let name = entry.file_name().to_string_lossy().into_owned();
            let rel = PathBuf::from(sub).join(&name);
            if !is_hashed_name(&name, ext) || keep.contains(&rel) || !entry.path().is_file() {
                continue;
            }
            if let Err(e) = std::fs::remove_file(entry.path()) {
                first_error.get_or_insert_with(|| ModelError::file(&entry.path(), format!("cannot delete: {e}")));
            }
        }
    }
    first_error.map_or(Ok(()), Err)
}

/// `map` as a 16-bit grey PNG: round(value / max_mm · 65535), all 0 when `max_mm` is 0.
fn encode_png16(map: &ThicknessMap, max_mm: f32, path: &Path) -> Result<Vec<u8>> {
    let scale = if max_mm > 0.0 { 65535.0 / f64::from(max_mm) } else { 0.0 };
    let data: Vec<u16> = map.mm.iter().map(|&v| (f64::from(v) * scale).round().clamp(0.0, 65535.0) as u16).collect();
    let image =
        image::ImageBuffer::<image::Luma<u16>, Vec<u16>>::from_raw(map.width, map.height, data).ok_or_else(|| {
            ModelError::file(path, format!("a {}×{} map has the wrong number of values", map.width, map.height))
        })?;
    let mut bytes = std::io::Cursor::new(Vec::new());
    image.write_to(&mut bytes, image::ImageFormat::Png).map_err(|e| ModelError::file(path, format!("PNG: {e}")))?;
    Ok(bytes.into_inner())
}
