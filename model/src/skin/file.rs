//! Skin maps on disk (docs/FORMATS.md, "Skin maps in a project"): the maps as one OpenEXR with a
//! 32-bit float channel per [`SkinChannel`] (named as the parameter, lossless), and the project's
//! `skin.json` (`rouge-skin` v1): the [`SkinRecipe`] they were generated from and the EXR's path.

use super::edits::SkinEdits;
use super::{SkinChannel, SkinConditions, SkinMaps};
use crate::document::read_versioned;
use crate::error::{ModelError, Result};
use crate::look::read_exr_channels;
use rouge_measure::skin::{SkinParams, skin_tone};
use std::path::Path;
use std::sync::Arc;

/// The file that held the skin maps' recipe and named their EXR in projects saved before the
/// content-named `skin-<hash>.json` that `look.json` names (read from such projects).
pub const SKIN_FILE: &str = "skin.json";
/// The `format` of [`SKIN_FILE`].
pub const SKIN_FORMAT: &str = "rouge-skin";

/// How skin maps were made, enough to make them again ([`SkinRecipe::generate`]).
#[derive(Clone, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SkinRecipe {
    /// The built-in tone `base` came from (`rouge skin tones`), if it came from one.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub tone: Option<String>,
    /// The skin model's parameters before the anatomy and the conditions.
    pub base: SkinParams,
    /// The conditions and their amounts.
    #[serde(default)]
    pub conditions: SkinConditions,
    /// The seed of the conditions' random placement.
    #[serde(default)]
    pub seed: u64,
    /// Width and height of the maps, texels.
    pub size_px: u32,
}

impl SkinRecipe {
    /// The default size of generated maps, texels a side: the painted maps' (2 texels per mm on
    /// the default head, so a 1-2 mm freckle covers a few texels).
    pub const DEFAULT_SIZE_PX: u32 = crate::document::MAP_SIZE;

    /// A recipe from a built-in tone's name.
    ///
    /// # Errors
    /// [`ModelError::Invalid`] naming the tone and the tones there are.
    pub fn from_tone(tone: &str, conditions: SkinConditions, seed: u64, size_px: u32) -> Result<SkinRecipe> {
        let t = skin_tone(tone).map_err(|e| ModelError::Invalid(e.to_string()))?;
        Ok(SkinRecipe { tone: Some(t.name.clone()), base: t.params, conditions, seed, size_px })
    }

    /// The maps this recipe makes ([`SkinMaps::generate`]).
    ///
    /// # Errors
    /// As [`SkinMaps::generate`].
    pub fn generate(&self) -> Result<SkinMaps> {
        SkinMaps::generate(&self.base, &self.conditions, self.seed, self.size_px)
    }
}

/// A project's skin: the maps, the recipe they came from (the maps are data: they are saved
/// and reopened as they are, whatever the recipe would give today) and the skin brushes' edits
/// painted over them ([`SkinEdits`], shared until painted).
#[derive(Clone, Debug, PartialEq)]
pub struct ProjectSkin {
    /// How the maps were made.
    pub recipe: SkinRecipe,
    /// The maps as generated.
    pub maps: SkinMaps,
    /// The skin brushes' edits on top of `maps` (`None`: none painted).
    pub edits: Option<Arc<SkinEdits>>,
}

impl ProjectSkin {
    /// The recipe and the maps it makes.
    ///
    /// # Errors
    /// As [`SkinMaps::generate`].
    pub fn generate(recipe: SkinRecipe) -> Result<ProjectSkin> {
        let maps = recipe.generate()?;
        Ok(ProjectSkin { recipe, maps, edits: None })
    }

    /// The maps the skin shows: the generated maps with the edits on top
    /// ([`SkinMaps::with_edits`]).
    pub fn edited_maps(&self) -> SkinMaps {
        match &self.edits {
            Some(e) => self.maps.with_edits(e),
            None => self.maps.clone(),
        }
    }
}

/// `skin.json`'s schema.
#[derive(serde::Serialize, serde::Deserialize)]
#[serde(deny_unknown_fields)]
struct SkinFile {
    format: String,
    version: u32,
    /// The EXR, relative to the project folder.
    maps: String,
    /// The skin edits' EXR, relative to the project folder (absent: no edits).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    edits: Option<String>,
    recipe: SkinRecipe,
}

impl SkinMaps {
    /// The maps as an OpenEXR file's bytes: one 32-bit float channel per [`SkinChannel`], named
    /// as [`SkinChannel::name`], ZIP-compressed (lossless: read back bit for bit).
    pub fn to_exr_bytes(&self) -> std::result::Result<Vec<u8>, String> {
        use exr::prelude::{AnyChannel, AnyChannels, Encoding, FlatSamples, Image, SmallVec, WritableImage};
        let channels =
            SkinChannel::ALL.map(|c| AnyChannel::new(c.name(), FlatSamples::F32(self.plane(c).to_vec()))).to_vec();
        let channels = AnyChannels::sort(SmallVec::from_vec(channels));
        let size = (self.width() as usize, self.height() as usize);
        let image = Image::from_encoded_channels(size, Encoding::SMALL_LOSSLESS, channels);
        let mut bytes = std::io::Cursor::new(Vec::new());
        image.write().to_buffered(&mut bytes).map_err(|e| format!("OpenEXR: {e}"))?;
        Ok(bytes.into_inner())
    }

    /// Maps from an OpenEXR file's bytes as [`SkinMaps::to_exr_bytes`] writes them, with `base`
    /// for the parameters that do not vary; every channel must be there, full size, every value
    /// in its range ([`SkinMaps::from_planes`]).
    pub fn from_exr_bytes(bytes: &[u8], base: &SkinParams) -> std::result::Result<SkinMaps, String> {
        let mut exr = read_exr_channels(bytes)?;
        let mut planes: [Vec<f32>; 5] = Default::default();
        for (c, plane) in SkinChannel::ALL.iter().zip(planes.iter_mut()) {
            let Some(k) = exr.channels.iter().position(|(name, _)| name == c.name()) else {
                let names: Vec<String> = exr.channels.iter().map(|(name, _)| format!("{name:?}")).collect();
                return Err(format!("no channel {:?} (the file has {})", c.name(), names.join(", ")));
            };
            *plane = std::mem::take(&mut exr.channels[k].1);
        }
        SkinMaps::from_planes(exr.width, exr.height, base, planes)
    }

    /// A 64-bit hash of the size and every value (bit patterns), for the file's name in a
    /// project.
    pub(crate) fn content_hash(&self) -> u64 {
        let header = u64::from(self.width()) << 32 | u64::from(self.height());
        crate::document::floats_hash(header, SkinChannel::ALL.iter().flat_map(|&c| self.plane(c).iter().copied()))
    }
}

/// The name of a project's skin EXR: `skin-<hash>.exr` (16 hex digits, by content).
pub(crate) fn maps_file_name(maps: &SkinMaps) -> String {
    format!("skin-{:016x}.exr", maps.content_hash())
}

/// The name of a project's skin edits EXR: `skin-edits-<hash>.exr` (16 hex digits, by content).
pub(crate) fn edits_file_name(edits: &SkinEdits) -> String {
    format!("skin-edits-{:016x}.exr", edits.content_hash())
}

/// Whether `file` is named as [`maps_file_name`] or [`edits_file_name`] name files.
pub(crate) fn is_maps_file_name(file: &str) -> bool {
    file.strip_prefix("skin-edits-")
        .or_else(|| file.strip_prefix("skin-"))
        .and_then(|s| s.strip_suffix(".exr"))
        .is_some_and(|h| h.len() == 16 && h.bytes().all(|b| b.is_ascii_digit() || (b'a'..=b'f').contains(&b)))
}

/// An EXR of a project's skin: the maps or the edits.
pub(crate) enum SkinExr<'a> {
    Maps(&'a SkinMaps),
    Edits(&'a SkinEdits),
}

impl SkinExr<'_> {
    /// The file's bytes.
    pub(crate) fn bytes(&self) -> std::result::Result<Vec<u8>, String> {
        match self {
            SkinExr::Maps(m) => m.to_exr_bytes(),
            SkinExr::Edits(e) => e.to_exr_bytes(),
        }
    }
}

/// A project's skin files: the EXRs by name (in the maps folder) and the skin file's text,
/// which names them.
pub(crate) struct SkinFiles<'a> {
    pub(crate) exrs: Vec<(String, SkinExr<'a>)>,
    pub(crate) json: String,
}

/// The files that hold `skin` in a project whose maps folder is `maps_rel`: the maps' EXR, the
/// edits' EXR when there are edits, and the skin file (`rouge-skin` v1) naming them. Nothing is
/// encoded until [`SkinExr::bytes`] (a file of that name already holds those values).
pub(crate) fn project_skin_files<'a>(
    skin: &'a ProjectSkin,
    maps_rel: &str,
) -> std::result::Result<SkinFiles<'a>, String> {
    let name = maps_file_name(&skin.maps);
    let mut exrs = vec![(name.clone(), SkinExr::Maps(&skin.maps))];
    let edits = skin.edits.as_deref().filter(|e| !e.is_empty());
    let edits_name = edits.map(|e| (edits_file_name(e), e));
    if let Some((n, e)) = &edits_name {
        exrs.push((n.clone(), SkinExr::Edits(e)));
    }
    let file = SkinFile {
        format: SKIN_FORMAT.into(),
        version: 1,
        maps: format!("{maps_rel}/{name}"),
        edits: edits_name.map(|(n, _)| format!("{maps_rel}/{n}")),
        recipe: skin.recipe.clone(),
    };
    let json = serde_json::to_string_pretty(&file).map_err(|e| format!("the skin file: {e}"))? + "\n";
    Ok(SkinFiles { exrs, json })
}

/// Reads a project's skin: `None` when `skin.json` is absent (projects saved before skin maps,
/// or without them). Errors name `skin.json` (line, column, field) or the EXR (channel, texel).
pub(crate) fn read_project_skin(dir: &Path, json_path: &Path) -> Result<Option<ProjectSkin>> {
    let Some(file) = read_versioned::<SkinFile>(json_path, SKIN_FORMAT, |f| (&f.format, f.version))? else {
        return Ok(None);
    };
    let recipe = file.recipe;
    recipe.base.validate().map_err(|e| ModelError::file(json_path, format!("recipe.base: {e}")))?;
    let exr = dir.join(&file.maps);
    let bytes = crate::look::read_map_file(&exr).map_err(|e| ModelError::file(&exr, e))?;
    let maps = SkinMaps::from_exr_bytes(&bytes, &recipe.base).map_err(|e| ModelError::file(&exr, e))?;
    let edits = match &file.edits {
        Some(rel) => {
            let path = dir.join(rel);
            let bytes = crate::look::read_map_file(&path).map_err(|e| ModelError::file(&path, e))?;
            Some(Arc::new(SkinEdits::from_exr_bytes(&bytes).map_err(|e| ModelError::file(&path, e))?))
        }
        None => None,
    };
    Ok(Some(ProjectSkin { recipe, maps, edits }))
}
