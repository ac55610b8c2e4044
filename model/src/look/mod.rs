//! The look document (`"schema": "rouge-look", "version": 1`): the cosmetic layers on a face,
//! bottom to top, each a material preset and a thickness over the mesh's UV space. The renderer
//! and the painting app both read and write it; docs/FORMATS.md ("Look documents") specifies
//! the JSON field by field.
//!
//! A thickness is given as a uniform film, a built-in region of the default head
//! ([`Region`]), a PNG mask times a thickness, or a thickness map (OpenEXR in millimetres, or
//! PNG times a scale). Loading resolves every reference into a [`ThicknessMap`] and a
//! [`Preset`], and checks every value: anything unknown or out of range is an error naming the
//! look file, the layer and, for maps, the pixel.
//!
//! UV and pixel convention (the one `python/gen_head.py` wrote the region masks in): a map is
//! stored like a texture of the mesh, row 0 at the top of the image. For OBJ-convention UVs
//! (v up, as in the default head), pixel (x, y) of a w × h map has its centre at
//! u = (x + 0.5) / w, v = 1 − (y + 0.5) / h. [`ThicknessMap::sample_uv`] takes such UVs.

mod maps;
mod source;

pub use maps::*;
pub use source::*;

use crate::error::{ModelError, Result};
use rouge_measure::file_set::write_atomic;
use rouge_measure::preset::Preset;
use serde::{Deserialize, Serialize};
use std::fmt;
use std::path::{Path, PathBuf};
use std::sync::OnceLock;

/// The schema name every look carries.
pub const SCHEMA: &str = "rouge-look";
/// The schema version this build writes and reads.
pub const VERSION: u32 = 1;
/// Largest thickness a look may give anywhere, mm. Cosmetic films are 5-100 µm; anything
/// near this bound is a unit mistake (µm written as mm), caught here rather than rendered.
pub const MAX_THICKNESS_MM: f32 = 10.0;
/// Most cosmetic layers a look may have (the renderer's two RGBA16F thickness targets). Checked
/// before any layer's preset or map is loaded, so a small file cannot ask for gigabytes.
pub const MAX_LAYERS: usize = 8;
/// Prefix of a preset reference that names a preset built into the binary.
pub const BUILTIN_PREFIX: &str = "builtin:";

const PNG_SIGNATURE: &[u8] = b"\x89PNG\r\n\x1a\n";
const EXR_MAGIC: &[u8] = &[0x76, 0x2f, 0x31, 0x01];

// ------------------------------------------------------------------------------------------
// Built-in presets

macro_rules! builtin_presets {
    ($($name:literal),* $(,)?) => {
        const BUILTIN_NAMES: &[&str] = &[$($name),*];
        const BUILTIN_JSON: &[&str] = &[$(include_str!(concat!("../../../data/presets/", $name, ".json"))),*];
    };
}

builtin_presets!(
    "blush_01_petal",
    "blush_02_coral",
    "eyeshadow_01_smoky",
    "eyeshadow_02_sapphire",
    "eyeshadow_03_bronze",
    "foundation_01_porcelain",
    "foundation_02_ivory",
    "foundation_03_sand",
    "foundation_04_caramel",
    "foundation_05_espresso",
    "lipstick_01_nude",
    "lipstick_02_red",
    "lipstick_03_berry",
);

/// The names of the presets of `data/presets/` built into the binary (their file stems), as
/// used in `"preset": "builtin:<name>"`.
pub fn builtin_preset_names() -> &'static [&'static str] {
    BUILTIN_NAMES
}

/// A preset built into the binary, by file stem (`"foundation_02_ivory"`); `None` if there is
/// no such built-in.
pub fn builtin_preset(name: &str) -> Option<Preset> {
    let i = BUILTIN_NAMES.iter().position(|n| *n == name)?;
    let json = BUILTIN_JSON.get(i)?;
    Preset::from_json(json, &format!("{BUILTIN_PREFIX}{name}")).ok()
}

/// Loads the preset a look refers to: `builtin:<name>`, or a file path, taken relative to
/// `base_dir` (the look file's folder) unless absolute. The error keeps the preset's own
/// message (file, line, field).
pub fn load_preset_ref(preset_ref: &str, base_dir: &Path) -> Result<Preset> {
    resolve_preset(preset_ref, base_dir).map_err(ModelError::Invalid)
}

fn resolve_preset(preset_ref: &str, base_dir: &Path) -> std::result::Result<Preset, String> {
    if let Some(name) = preset_ref.strip_prefix(BUILTIN_PREFIX) {
        return builtin_preset(name).ok_or_else(|| {
            format!("preset {preset_ref:?}: no such built-in preset (built-ins: {})", BUILTIN_NAMES.join(", "))
        });
    }
    if preset_ref.trim().is_empty() {
        return Err("`preset` is empty".into());
    }
    Preset::load(&resolve_path(base_dir, Path::new(preset_ref))).map_err(|e| format!("preset {preset_ref:?}: {e}"))
}

fn resolve_path(base_dir: &Path, path: &Path) -> PathBuf {
    if path.is_absolute() { path.to_path_buf() } else { base_dir.join(path) }
}

fn base_dir_of(look_path: &Path) -> &Path {
    look_path.parent().filter(|d| !d.as_os_str().is_empty()).unwrap_or(Path::new("."))
}

// ------------------------------------------------------------------------------------------
// The document

/// One cosmetic layer: a preset, where it lies and how thick.
#[derive(Clone, Debug, PartialEq)]
pub struct LookLayer {
    /// Display name; the preset's name unless the file gives one.
    pub name: String,
    /// The preset as written: `builtin:<name>` or a path relative to the look file.
    pub preset_ref: String,
    /// The preset it refers to.
    pub preset: Preset,
    /// Where the thickness comes from, as written.
    pub thickness: ThicknessSource,
    /// The thickness, resolved (mm over UV).
    pub map: ThicknessMap,
    /// Whether the layer is drawn (hidden layers stay in the document).
    pub visible: bool,
    /// Whether the painting app refuses to paint, fill or clear the layer.
    pub locked: bool,
}

/// A look: cosmetic layers, bottom (on the skin) to top.
#[derive(Clone, Debug, PartialEq)]
pub struct Look {
    /// Display name.
    pub name: String,
    /// Layers, bottom to top.
    pub layers: Vec<LookLayer>,
    /// The mascara on the lashes, if any (`"mascara"`: [`crate::mesh::lashes::Mascara`]).
    pub mascara: Option<crate::mesh::lashes::Mascara>,
    /// A tinted brow gel on the brow hairs, if any (`"brow_gel"`: [`crate::mesh::brow_gel::BrowGel`]).
    pub brow_gel: Option<crate::mesh::brow_gel::BrowGel>,
}

/// The document's shape with the layers left untyped: errors here are not about a layer.
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct LookIn<L> {
    #[serde(rename = "schema")]
    _schema: String,
    #[serde(rename = "version")]
    _version: u32,
    #[serde(default)]
    name: Option<String>,
    layers: Vec<L>,
    #[serde(default)]
    mascara: Option<crate::mesh::lashes::Mascara>,
    #[serde(default)]
    brow_gel: Option<crate::mesh::brow_gel::BrowGel>,
    #[serde(default)]
    project: Option<ProjectPart>,
}

/// What a project folder's `look.json` adds to its look (docs/FORMATS.md 5.1, "project"): the
/// project's other files, named by their contents, so that replacing `look.json` (one atomic
/// rename) commits the whole project at once, and the app's settings saved with the project.
/// Looks outside projects have none, and [`Look::load`] reads a project's look without it.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ProjectPart {
    /// The face file (`rouge-face` v1), `face-<hash>.json`, in the project folder.
    pub face: String,
    /// The skin file (`rouge-skin` v1), `skin-<hash>.json`, in the project folder; `None`
    /// without skin maps.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub skin: Option<String>,
    /// The viewport's subsurface model (`screen-space`, `thickness-baked`, ...); `None`: the
    /// default (projects saved before it).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub subsurface: Option<crate::document::SubsurfaceChoice>,
    /// The skin's diffuse law in the viewport (`lambert`, `half-space`); `None`: Lambert
    /// (projects saved before it).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub diffuse: Option<crate::document::DiffuseChoice>,
}

fn yes() -> bool {
    true
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct LayerIn {
    #[serde(default)]
    name: Option<String>,
    preset: String,
    thickness: ThicknessSource,
    #[serde(default = "yes")]
    visible: bool,
    #[serde(default)]
    locked: bool,
}

#[derive(Serialize)]
struct LookOut<'a> {
    schema: &'a str,
    version: u32,
    name: &'a str,
    layers: Vec<LayerOut<'a>>,
    #[serde(skip_serializing_if = "Option::is_none")]
    mascara: Option<crate::mesh::lashes::Mascara>,
    #[serde(skip_serializing_if = "Option::is_none")]
    brow_gel: Option<crate::mesh::brow_gel::BrowGel>,
    #[serde(skip_serializing_if = "Option::is_none")]
    project: Option<&'a ProjectPart>,
}

fn is_true(b: &bool) -> bool {
    *b
}

#[derive(Serialize)]
struct LayerOut<'a> {
    #[serde(skip_serializing_if = "Option::is_none")]
    name: Option<&'a str>,
    preset: &'a str,
    thickness: &'a ThicknessSource,
    #[serde(skip_serializing_if = "is_true")]
    visible: bool,
    #[serde(skip_serializing_if = "is_false")]
    locked: bool,
}

fn is_false(b: &bool) -> bool {
    !*b
}

/// How a layer is named in messages: its `name`, else its preset reference.
fn layer_label(v: &serde_json::Value) -> String {
    let s = |k: &str| v.get(k).and_then(|x| x.as_str()).filter(|x| !x.is_empty());
    s("name").or_else(|| s("preset")).unwrap_or("?").to_string()
}

impl Look {
    /// A look without layers: bare skin.
    pub fn bare() -> Look {
        Look { name: "Bare".into(), layers: Vec::new(), mascara: None, brow_gel: None }
    }

    /// The default look on the default head, bottom to top: Foundation 02 Ivory, 15 µm
    /// everywhere; Blush 01 Petal, 8 µm on the cheeks; Lipstick 02 Classic Red, 20 µm on the
    /// lips (all built-in). Same as `data/looks/default.json`.
    ///
    /// Thicknesses from the presets' KM coefficients over the ColorChecker "light skin" patch
    /// (`data/skin/colorchecker_skin.csv`), CIELAB D65: 15 µm of foundation moves the skin
    /// ΔE*ab 5.0 of the 8.0 to its opaque colour (evens the tone, skin shows through; its T is
    /// 0.68/0.49/0.28 in linear RGB); 8 µm of blush over it is ΔE 12.7 from the foundation and
    /// 9.2 short of opaque (clearly visible, still sheer); 20 µm of lipstick is ΔE 31.7 from the
    /// base and 5.2 from opaque (nearly opaque; T 0.74/0.17/0.09).
    pub fn default_look() -> Look {
        let layer = |name: &str, thickness: ThicknessSource| {
            let preset = builtin_preset(name)?;
            let map = thickness.resolve(Path::new(".")).ok()?;
            Some(LookLayer {
                name: preset.name.clone(),
                preset_ref: format!("{BUILTIN_PREFIX}{name}"),
                preset,
                thickness,
                map,
                visible: true,
                locked: false,
            })
        };
        let layers = [
            layer("foundation_02_ivory", ThicknessSource::Uniform { mm: 0.015 }),
            layer("blush_01_petal", ThicknessSource::Region { region: Region::Cheeks, mm: 0.008 }),
            layer("lipstick_02_red", ThicknessSource::Region { region: Region::Lips, mm: 0.02 }),
        ];
        Look { name: "Default".into(), layers: layers.into_iter().flatten().collect(), mascara: None, brow_gel: None }
    }

    /// Reads a look file; presets, masks and maps are resolved relative to its folder.
    pub fn load(path: &Path) -> Result<Look> {
        let text = std::fs::read_to_string(path).map_err(|e| ModelError::file(path, e))?;
        Look::from_json(&text, path)
    }

    /// Parses and resolves look JSON. `path` names the document in messages, and its folder is
    /// where relative presets, masks and maps are looked up.
    pub fn from_json(text: &str, path: &Path) -> Result<Look> {
        Look::from_project_json(text, path).map(|(look, _)| look)
    }

    /// [`Look::from_json`], with the [`ProjectPart`] a project's `look.json` has (`None` in a
    /// look outside a project, or in a project saved before the part existed).
    pub fn from_project_json(text: &str, path: &Path) -> Result<(Look, Option<ProjectPart>)> {
        let err = |m: String| ModelError::file(path, m);
        let value: serde_json::Value = serde_json::from_str(text).map_err(|e| err(e.to_string()))?;
        let Some(obj) = value.as_object() else {
            return Err(err(format!("a look is a JSON object with \"schema\": {SCHEMA:?}")));
        };
        // Check the schema and version before the shape, so that another document or a future
        // version gets the right message rather than a complaint about its fields.
        match obj.get("schema").and_then(|s| s.as_str()) {
            Some(SCHEMA) => {}
            Some(other) => return Err(err(format!("`schema` is `{other}`, expected `{SCHEMA}`"))),
            None => return Err(err(format!("missing `schema`: expected `{SCHEMA}`"))),
        }
        if let Some(v) = obj.get("version").and_then(|v| v.as_u64())
            && v != u64::from(VERSION)
        {
            return Err(err(format!("look schema version {v} is not supported: this Rouge reads version {VERSION}")));
        }
        // First the document without looking into the layers, then the layers: serde's message
        // has the line and column, and a layer's error is prefixed with the layer.
        let shape: LookIn<serde_json::Value> = serde_json::from_str(text).map_err(|e| err(e.to_string()))?;
        if shape.layers.len() > MAX_LAYERS {
            return Err(err(format!("{} layers: a look has at most {MAX_LAYERS}", shape.layers.len())));
        }
        let doc: LookIn<LayerIn> = serde_json::from_str(text).map_err(|e| {
            let bad =
                shape.layers.iter().enumerate().find(|(_, l)| serde_json::from_value::<LayerIn>((*l).clone()).is_err());
            match bad {
                Some((i, l)) => err(format!("layer {i} ({:?}): {e}", layer_label(l))),
                None => err(e.to_string()),
            }
        })?;
        let base = base_dir_of(path);
        let mut layers = Vec::with_capacity(doc.layers.len());
        for (i, l) in doc.layers.into_iter().enumerate() {
            let label = l.name.clone().filter(|n| !n.is_empty()).unwrap_or_else(|| l.preset.clone());
            let at = |m: String| err(format!("layer {i} ({label:?}): {m}"));
            if l.name.as_ref().is_some_and(|n| n.trim().is_empty()) {
                return Err(at("`name` is empty (leave it out to use the preset's name)".into()));
            }
            let preset = resolve_preset(&l.preset, base).map_err(at)?;
            let map = l.thickness.resolve(base).map_err(at)?;
            layers.push(LookLayer {
                name: l.name.unwrap_or_else(|| preset.name.clone()),
                preset_ref: l.preset,
                preset,
                thickness: l.thickness,
                map,
                visible: l.visible,
                locked: l.locked,
            });
        }
        let name = doc.name.unwrap_or_else(|| {
            path.file_stem().map_or_else(|| "Look".to_string(), |s| s.to_string_lossy().into_owned())
        });
        if let Some(m) = &doc.mascara {
            m.validate().map_err(|e| err(e.to_string()))?;
        }
        if let Some(g) = &doc.brow_gel {
            g.validate().map_err(|e| err(e.to_string()))?;
        }
        Ok((Look { name, layers, mascara: doc.mascara, brow_gel: doc.brow_gel }, doc.project))
    }

    /// Pretty JSON that [`Look::from_json`] reads back to an equal look (from the same folder:
    /// presets, masks and maps stay references, as written). A layer's name is written only
    /// where it differs from its preset's name, `visible` only where false, `locked` only where true.
    pub fn to_json(&self) -> String {
        self.to_project_json(None)
    }

    /// [`Look::to_json`] with a project's part (read back by [`Look::from_project_json`]).
    pub fn to_project_json(&self, project: Option<&ProjectPart>) -> String {
        let doc = LookOut {
            schema: SCHEMA,
            version: VERSION,
            name: &self.name,
            layers: self
                .layers
                .iter()
                .map(|l| LayerOut {
                    name: (l.name != l.preset.name).then_some(l.name.as_str()),
                    preset: &l.preset_ref,
                    thickness: &l.thickness,
                    visible: l.visible,
                    locked: l.locked,
                })
                .collect(),
            mascara: self.mascara,
            brow_gel: self.brow_gel,
            project,
        };
        serde_json::to_string_pretty(&doc).map(|s| s + "\n").unwrap_or_default()
    }

    /// Writes the look atomically (temporary file, then rename). Relative references are written
    /// as they are, so they must hold from the new file's folder too.
    pub fn save(&self, path: &Path) -> Result<()> {
        write_atomic(path, self.to_json().as_bytes()).map_err(|e| ModelError::file(path, e))
    }

    /// The layers to draw, bottom to top.
    pub fn visible_layers(&self) -> impl Iterator<Item = &LookLayer> {
        self.layers.iter().filter(|l| l.visible)
    }
}
