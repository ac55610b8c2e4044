//! The painting app's document: cosmetic layers, each a preset and a painted thickness map of
//! [`MAP_SIZE`]² texels, with undo/redo, project folders, exports, autosave and crash recovery.
//! No GUI and no GPU here: the app draws [`Document::layers`] and re-uploads what each edit's
//! [`Change`] names.
//!
//! **History.** Every layer edit is one undo step that stores the whole layer list before and
//! after; the maps are shared ([`Arc`]), so such a step costs a few kilobytes until a map it holds
//! is painted over (painting copies the map, the step keeps the old one). A brush stroke, from
//! [`Document::begin_stroke`] to [`Document::end_stroke`], is one step that stores only the
//! changed rectangle, before and after. Other skin maps ([`Document::set_skin`]) are one step
//! holding the skin before and after (shared), and a skin brush stroke
//! ([`Document::begin_skin_stroke`]) one step holding the changed rectangle of the skin edits.
//! The history has a memory budget
//! ([`HISTORY_BUDGET_BYTES`] by default); past it the oldest steps are dropped.
//!
//! **Projects** are folders: `look.json` (a `rouge-look` v1 document that [`Look::load`] reads,
//! with a `project` part naming the face and skin files), `maps/` (one OpenEXR map per layer, raw
//! painted millimetres, and the skin maps' EXR), `presets/` (the presets that are not built in),
//! the face file and, with skin maps, the skin file. docs/FORMATS.md ("Project folders")
//! describes them. Every file but `look.json` is named by its contents, so a save never
//! overwrites a file the previous `look.json` refers to: replacing `look.json` (an atomic rename)
//! is the save's one commit point, before which the folder opens as the previous project and
//! after which as the new one, and a file that did not change is not written again.

mod history;
mod project;

use crate::mesh::brow_gel::BrowGel;
use crate::mesh::lashes::Mascara;
use crate::mesh::targets::FacePose;
use crate::skin::{ProjectSkin, SkinEdits};
pub(crate) use project::{floats_hash, read_versioned};
use project::{layer_files, look_layer};

use crate::error::{ModelError, Result};
use crate::look::{BUILTIN_PREFIX, Look, LookLayer, MAX_THICKNESS_MM, ThicknessMap, ThicknessSource, builtin_preset};
use rouge_measure::file_set::write_atomic;
use rouge_measure::preset::{Preset, PresetError};
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
/// The name of a new project ([`Document::default_project`]).
pub const UNTITLED: &str = "Untitled";
/// The look document of a project folder.
pub const LOOK_FILE: &str = "look.json";

/// The file that held the face's expression and shape ([`FacePose`], `rouge-face` v1) in projects
/// saved before the content-named `face-<hash>.json` that `look.json` names (read from such
/// projects; without it they open with the neutral head).
pub const FACE_FILE: &str = "face.json";
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
    /// Whether painting, filling and clearing are refused (the app checks; saved in the look).
    pub locked: bool,
}

impl PaintLayer {
    /// The thickness the layer renders with: the painted map × the multiplier, mm.
    pub fn effective_map(&self) -> ThicknessMap {
        if self.multiplier == 1.0 { (*self.map).clone() } else { self.map.scaled(self.multiplier) }
    }
}

/// `look`'s layers as paint layers, each map at [`MAP_SIZE`]², multiplier 1.
fn paint_layers(look: &Look) -> Vec<PaintLayer> {
    look.layers
        .iter()
        .map(|l| PaintLayer {
            name: l.name.clone(),
            preset_ref: l.preset_ref.clone(),
            preset: l.preset.clone(),
            map: Arc::new(at_map_size(&l.map)),
            visible: l.visible,
            multiplier: 1.0,
            locked: l.locked,
        })
        .collect()
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
    /// The skin changed: other maps or no maps (`rect` `None`), or the skin edits inside `rect`
    /// (texels of [`SkinEdits`], [`MAP_SIZE`]²).
    Skin {
        /// The edited texels, or `None` for the whole skin.
        rect: Option<TexelRect>,
    },
    /// The hair products changed ([`Document::set_mascara`], [`Document::set_brow_gel`]): pose
    /// the lashes again and recolour the hairs.
    Hair,
    /// Nothing changed (and no undo step was recorded).
    Nothing,
}

/// One undo step.
enum Edit {
    /// A layer edit: the whole list before and after (maps shared).
    Layers { before: Vec<PaintLayer>, after: Vec<PaintLayer> },
    /// A stroke: the changed rectangle of one map, row by row, before and after.
    Stroke { layer: usize, rect: TexelRect, before: Vec<f32>, after: Vec<f32> },
    /// Other skin maps (or none): the skin before and after (shared).
    Skin { before: Option<Arc<ProjectSkin>>, after: Option<Arc<ProjectSkin>> },
    /// A skin brush stroke: the changed rectangle of the skin edits, both planes, before and after.
    SkinStroke { rect: TexelRect, before: [Vec<f32>; 2], after: [Vec<f32>; 2] },
    /// Other hair products: the mascara and the brow gel before and after.
    Hair { before: HairProducts, after: HairProducts },
}

/// The products on the hairs: the mascara and the brow gel.
type HairProducts = (Option<Mascara>, Option<BrowGel>);

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

/// The open skin stroke: the edits as they were when it began and the union of the dirty rects.
struct OpenSkinStroke {
    start: Arc<SkinEdits>,
    rect: Option<TexelRect>,
}

// ------------------------------------------------------------------------------------------
// The document

/// The viewport's subsurface model, chosen in the app's Subsurface panel and saved with the
/// project (`look.json`'s `project.subsurface`, by [`SubsurfaceChoice::name`]); the renderer's
/// models behind them are `rouge_render::SubsurfaceModel`.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash, serde::Serialize, serde::Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum SubsurfaceChoice {
    /// d'Eon's skin profile through the separable screen-space kernel (the default).
    #[default]
    ScreenSpace,
    /// Thickness translucency with the baked local thickness.
    ThicknessBaked,
    /// Thickness translucency with the per-light shadow-map thickness (follows deformation).
    ThicknessPerLight,
    /// The screen-space kernel and the per-light thickness translucency together, with the
    /// term's parameters fitted under the kernel (the best model on the front-lit head).
    ScreenSpaceThickness,
    /// The screen-space kernel and skin1's light through thin parts by the slab law (exact slab
    /// transport per light, no fitted parameter).
    ScreenSpaceSlab,
    /// As [`SubsurfaceChoice::ScreenSpaceSlab`], with the transmission gather in the slab law's
    /// place for light that crossed the mesh (every entry in the light's map, no plane assumed:
    /// better through fingers and ears).
    ScreenSpaceSlabGather,
    /// The directional dipole of skin1 (\[Frisvad2014\]), accumulated over frames while still.
    DirectionalDipole,
    /// Jensen's dipole of skin1 through the cube-map atlas redrawn every frame (\[Benmounah2009\]).
    CubeAtlas,
    /// No subsurface scattering.
    None,
}

impl SubsurfaceChoice {
    /// Every choice, in the order the app lists them.
    pub const ALL: [SubsurfaceChoice; 9] = [
        SubsurfaceChoice::ScreenSpace,
        SubsurfaceChoice::ThicknessBaked,
        SubsurfaceChoice::ThicknessPerLight,
        SubsurfaceChoice::ScreenSpaceThickness,
        SubsurfaceChoice::ScreenSpaceSlab,
        SubsurfaceChoice::ScreenSpaceSlabGather,
        SubsurfaceChoice::DirectionalDipole,
        SubsurfaceChoice::CubeAtlas,
        SubsurfaceChoice::None,
    ];

    /// The name a project file gives it (`screen-space`, `thickness-baked`, `thickness-per-light`,
    /// `screen-space-thickness`, `screen-space-slab`, `screen-space-slab-gather`,
    /// `directional-dipole`, `cube-atlas`, `none`).
    pub fn name(self) -> &'static str {
        match self {
            SubsurfaceChoice::ScreenSpace => "screen-space",
            SubsurfaceChoice::ThicknessBaked => "thickness-baked",
            SubsurfaceChoice::ThicknessPerLight => "thickness-per-light",
            SubsurfaceChoice::ScreenSpaceThickness => "screen-space-thickness",
            SubsurfaceChoice::ScreenSpaceSlab => "screen-space-slab",
            SubsurfaceChoice::ScreenSpaceSlabGather => "screen-space-slab-gather",
            SubsurfaceChoice::DirectionalDipole => "directional-dipole",
            SubsurfaceChoice::CubeAtlas => "cube-atlas",
            SubsurfaceChoice::None => "none",
        }
    }
}

/// How the viewport's skin returns light by angle, chosen in the app's Subsurface panel and saved
/// with the project (`look.json`'s `project.diffuse`); the renderer's laws behind them are
/// `rouge_render::DiffuseLaw`.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash, serde::Serialize, serde::Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum DiffuseChoice {
    /// The albedo in every direction (the default).
    #[default]
    Lambert,
    /// The exact half-space under the skin's boundary (adding-doubling; darker towards grazing
    /// exits, where the surface reflects more), with the same albedo at normal incidence.
    HalfSpace,
}

/// The painting app's document. Edit the layers through the methods, which record undo steps;
/// changing [`Document::layers`] directly bypasses the history.
pub struct Document {
    /// Display name, saved as the project's `look.json` `name` (not part of the undo history, but
    /// a change makes the document modified).
    pub name: String,
    /// The name as last saved (or opened), for [`Document::is_modified`].
    saved_name: String,
    /// The viewport's subsurface model, saved with the project (not part of the undo history,
    /// but a change makes the document modified); projects saved before it open with the default.
    pub subsurface: SubsurfaceChoice,
    /// The subsurface model as last saved (or opened), for [`Document::is_modified`].
    saved_subsurface: SubsurfaceChoice,
    /// The skin's diffuse law in the viewport, saved with the project like
    /// [`Document::subsurface`]; projects saved before it open with Lambert.
    pub diffuse: DiffuseChoice,
    /// The diffuse law as last saved (or opened), for [`Document::is_modified`].
    saved_diffuse: DiffuseChoice,
    /// Layers, bottom (on the skin) to top.
    pub layers: Vec<PaintLayer>,
    /// The default head's expression and face shape the look is shown on (saved in the
    /// project's `face.json`; not part of the undo history, but a change makes the document
    /// modified).
    pub face: FacePose,
    /// The face as last saved (or opened), for [`Document::is_modified`].
    saved_face: FacePose,
    /// The look's mascara on the default head's lashes, saved with the project's `look.json`.
    /// Change it through [`Document::set_mascara`] (one undo step); `None` is natural lashes.
    pub mascara: Option<Mascara>,
    /// The look's tinted brow gel on the default head's brows, saved with the project's
    /// `look.json`. Change it through [`Document::set_brow_gel`] (one undo step).
    pub brow_gel: Option<BrowGel>,
    /// The skin maps, their recipe and the skin edits (saved in the project's `skin.json` and
    /// `maps/`; `None`: the tone's flat skin, as projects saved before skin maps). Change it
    /// through [`Document::set_skin`] and skin strokes ([`Document::begin_skin_stroke`]), which
    /// record undo steps; putting another `Arc` here directly bypasses the history but still
    /// makes the document modified (compared by pointer, not by value: the maps are large).
    pub skin: Option<Arc<ProjectSkin>>,
    /// The skin as last saved (or opened), for [`Document::is_modified`].
    saved_skin: Option<Arc<ProjectSkin>>,
    history: History,
    stroke: Option<OpenStroke>,
    skin_stroke: Option<OpenSkinStroke>,
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
        Document {
            name: look.name.clone(),
            saved_name: look.name.clone(),
            subsurface: SubsurfaceChoice::default(),
            saved_subsurface: SubsurfaceChoice::default(),
            diffuse: DiffuseChoice::default(),
            saved_diffuse: DiffuseChoice::default(),
            layers: paint_layers(look),
            face: FacePose::default(),
            saved_face: FacePose::default(),
            mascara: look.mascara,
            brow_gel: look.brow_gel,
            skin: None,
            saved_skin: None,
            history: History::new(),
            stroke: None,
            skin_stroke: None,
        }
    }

    /// A new project: the default look ([`Look::default_look`]), named [`UNTITLED`].
    pub fn default_project() -> Document {
        let mut doc = Document::from_look(&Look::default_look());
        doc.name = UNTITLED.into();
        doc.saved_name = UNTITLED.into();
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
        Look { name: self.name.clone(), layers, mascara: self.mascara, brow_gel: self.brow_gel }
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
            locked: false,
        };
        self.edit_layers(|layers| {
            layers.push(layer);
            true
        })
    }

    /// Duplicates layer `i` just above it: the same material, map (shared until either is
    /// painted), visibility and multiplier, named "NAME copy".
    pub fn duplicate_layer(&mut self, i: usize) -> Change {
        self.edit_layers(|layers| {
            let Some(layer) = layers.get(i) else { return false };
            let mut copy = layer.clone();
            copy.name = format!("{} copy", layer.name);
            layers.insert(i + 1, copy);
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
        self.set_flag(i, v, |l| &mut l.visible)
    }

    /// Locks or unlocks layer `i` (a locked layer refuses paint, fill and clear).
    pub fn set_locked(&mut self, i: usize, locked: bool) -> Change {
        self.set_flag(i, locked, |l| &mut l.locked)
    }

    /// Sets one switch of layer `i` (one undo step; none when it already has that value).
    fn set_flag(&mut self, i: usize, value: bool, flag: fn(&mut PaintLayer) -> &mut bool) -> Change {
        self.edit_layers(|layers| match layers.get_mut(i).map(flag) {
            Some(f) if *f != value => {
                *f = value;
                true
            }
            _ => false,
        })
    }

    /// Replaces every layer with `look`'s (maps at [`MAP_SIZE`]², multiplier 1), as one undo
    /// step: a look from the library applied in one click. The document keeps its name and face.
    pub fn apply_look(&mut self, look: &Look) -> Change {
        let layers = paint_layers(look);
        self.edit_layers(|current| {
            *current = layers;
            true
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
}
