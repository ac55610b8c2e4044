//! Project folders, exports and recovery of the [`Document`] (docs/FORMATS.md, "Project
//! folders"): every file but `look.json` named by its contents and written before it, so that
//! replacing `look.json` (one atomic rename) is the save's one commit point; files no
//! `look.json` refers to are removed after it.

use super::*;
use crate::look::ProjectPart;
use crate::mesh::targets::TargetSet;
use crate::skin::SKIN_FILE;
use crate::skin::file::{is_maps_file_name, project_skin_files, read_project_skin};
pub(super) use rouge_measure::file_set::{HASH_DIGITS, bytes_hash, mix64};

impl Document {
    // --------------------------------------------------------------------------------------
    // Projects

    /// Saves the project into the folder `dir` (created if missing), ending an open stroke
    /// first: the maps, the presets, the face and the skin files, then `look.json`, which names
    /// them all, each atomically (temporary file, then rename). Every file but `look.json` is
    /// named by its contents, so nothing the previous `look.json` refers to is overwritten and
    /// unchanged files are not written again: until `look.json` is replaced the folder opens as
    /// the previous project, after it as the new one, whenever the process dies. Files that the
    /// new `look.json` does not refer to are deleted after it is written. On error (naming the
    /// file) the previous project is left as it was, and the files this save wrote are deleted.
    /// Marks the document unmodified.
    pub fn save_project(&mut self, dir: &Path) -> Result<()> {
        self.finish_stroke();
        write_project(self, dir)?;
        self.history.saved_id = Some(self.history.state_id());
        self.saved_face = self.face.clone();
        self.saved_skin = self.skin.clone();
        self.saved_name = self.name.clone();
        self.saved_subsurface = self.subsurface;
        self.saved_diffuse = self.diffuse;
        Ok(())
    }

    /// Opens a project folder: `dir/look.json` by [`Look::from_project_json`], then
    /// [`Document::from_look`], with the painted maps read back unscaled (bit for bit) and each
    /// layer's multiplier from its `scale_mm`, the face and the skin maps (bit for bit) from the
    /// files its `project` part names, and the subsurface model it gives. A project saved before
    /// that part (without it) takes them from `face.json` and `skin.json`: neutral without the
    /// one, no skin maps without the other, and the default subsurface model. Errors name the
    /// file at fault.
    pub fn open_project(dir: &Path) -> Result<Document> {
        let look_path = dir.join(LOOK_FILE);
        let text = std::fs::read_to_string(&look_path).map_err(|e| ModelError::file(&look_path, e))?;
        let (look, part) = Look::from_project_json(&text, &look_path)?;
        let (face_path, skin_path) = match &part {
            Some(part) => {
                let skin = part.skin.as_deref().map(|s| project_file(dir, &look_path, "skin", s)).transpose()?;
                (project_file(dir, &look_path, "face", &part.face)?, skin)
            }
            None => (dir.join(FACE_FILE), Some(dir.join(SKIN_FILE))),
        };
        let mut doc = Document::from_look(&look);
        doc.face = read_face(&face_path)?;
        doc.saved_face = doc.face.clone();
        doc.skin = match skin_path {
            Some(path) => read_project_skin(dir, &path)?.map(Arc::new),
            None => None,
        };
        doc.saved_skin = doc.skin.clone();
        doc.subsurface = part.as_ref().and_then(|p| p.subsurface).unwrap_or_default();
        doc.saved_subsurface = doc.subsurface;
        doc.diffuse = part.as_ref().and_then(|p| p.diffuse).unwrap_or_default();
        doc.saved_diffuse = doc.diffuse;
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

    /// Opens the autosave in `dir` as [`Document::open_project`] does, as unsaved work: the
    /// document is modified (its title says so, and closing without saving keeps it for the
    /// next recovery) until it is saved.
    pub fn open_recovery(dir: &Path) -> Result<Document> {
        let mut doc = Document::open_project(dir)?;
        doc.history.saved_id = None;
        Ok(doc)
    }

    /// Whether `dir` holds an autosave that was not cleared (open it with
    /// [`Document::open_project`]).
    pub fn recovery_available(dir: &Path) -> bool {
        dir.join(LOOK_FILE).is_file()
    }

    /// Deletes the autosave in `dir`: `look.json` first (so that a partial clear is no longer
    /// offered for recovery), then the project's map, preset, face and skin files (the skin
    /// maps' EXR included) and what interrupted saves left, then the two folders if empty.
    /// Nothing to delete is not an error.
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
// Project files

/// A file name part from a display name: lower-case ASCII letters and digits, runs of anything
/// else as one `-`, at most 40 characters; `layer` if nothing is left.
pub(super) fn slug(name: &str) -> String {
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
pub(super) fn map_hash(map: &ThicknessMap) -> u64 {
    floats_hash(u64::from(map.width) << 32 | u64::from(map.height), map.mm.iter().copied())
}

/// 64-bit hash of `header` (a size) and `values` (bit patterns), what names a map's file in a
/// project ([`map_hash`], the skin maps). Multiply-rotate mixing with SplitMix64's finaliser
/// ([`mix64`], as [`bytes_hash`] of bytes);
/// not cryptographic, only to tell maps apart.
pub(crate) fn floats_hash(header: u64, values: impl Iterator<Item = f32>) -> u64 {
    let mut h = 0x9E37_79B9_7F4A_7C15u64 ^ header;
    let mut n = 0u64;
    for v in values {
        h = (h.rotate_left(23) ^ u64::from(v.to_bits())).wrapping_mul(0xD6E8_FEB8_6659_FD93);
        n += 1;
    }
    mix64(h ^ n)
}

/// `NN-<slug>-<hash>.<ext>`.
pub(super) fn hashed_name(i: usize, name: &str, hash: u64, ext: &str) -> String {
    format!("{i:02}-{}-{hash:016x}.{ext}", slug(name))
}

/// Whether `file` is named as [`hashed_name`] names files with extension `ext`.
pub(super) fn is_hashed_name(file: &str, ext: &str) -> bool {
    let Some(stem) = file.strip_suffix(ext).and_then(|s| s.strip_suffix('.')) else { return false };
    let stem = stem.as_bytes();
    let Some(split) = stem.len().checked_sub(HASH_DIGITS + 1) else { return false };
    let (head, hash) = stem.split_at(split);
    head.first().is_some_and(u8::is_ascii_digit)
        && hash.first() == Some(&b'-')
        && hash.iter().skip(1).all(|b| b.is_ascii_digit() || (b'a'..=b'f').contains(b))
}

/// Where a layer's preset goes in a project.
pub(super) enum PresetFile {
    /// A built-in preset, unchanged: referred to as `builtin:<name>`.
    Builtin(String),
    /// Written to `presets/<file>`.
    File { file: String, json: String },
}

pub(super) fn preset_file(i: usize, layer: &PaintLayer) -> PresetFile {
    if let Some(name) = layer.preset_ref.strip_prefix(BUILTIN_PREFIX)
        && builtin_preset(name).as_ref() == Some(&layer.preset)
    {
        return PresetFile::Builtin(layer.preset_ref.clone());
    }
    let json = layer.preset.to_json();
    PresetFile::File { file: hashed_name(i, &layer.preset.name, bytes_hash(json.as_bytes()), "json"), json }
}

/// The files a layer has in a project: its map (in `maps/`) and its preset.
pub(super) struct LayerFiles {
    map: String,
    preset: PresetFile,
}

pub(super) fn layer_files(i: usize, layer: &PaintLayer) -> LayerFiles {
    LayerFiles { map: hashed_name(i, &layer.name, map_hash(&layer.map), "exr"), preset: preset_file(i, layer) }
}

/// A layer as its project's `look.json` has it, with `map` as its map.
pub(super) fn look_layer(layer: &PaintLayer, files: &LayerFiles, map: ThicknessMap) -> LookLayer {
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
        locked: layer.locked,
    }
}

pub(super) fn base_dir(dir: &Path) -> &Path {
    if dir.as_os_str().is_empty() { Path::new(".") } else { dir }
}

pub(super) fn create_dir(dir: &Path) -> Result<()> {
    std::fs::create_dir_all(dir).map_err(|e| ModelError::file(dir, format!("cannot create the folder: {e}")))
}

/// Checks that every layer can be written as a look that [`Look::load`] reads back: maps of
/// [`MAP_SIZE`]², painted values and values × multiplier finite, ≥ 0 and ≤ 10 mm.
pub(super) fn check_layers(doc: &Document, look_path: &Path) -> Result<()> {
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

/// Writes `doc` as a project into `dir`: the maps, presets, face file, skin maps and skin file
/// that are not there yet (all named by content), then `look.json`, which names them (the
/// commit point), then deletes the files no longer referred to and what interrupted saves left
/// (`face.json` and `skin.json` of projects saved before content-named ones included). On an
/// error before the commit, the files this save wrote are deleted again (a full disk gets its
/// space back) and the previous project is as it was.
pub(super) fn write_project(doc: &Document, dir: &Path) -> Result<()> {
    let look_path = dir.join(LOOK_FILE);
    check_layers(doc, &look_path)?;
    create_dir(dir)?;
    let mut new_files = NewFiles::default();
    let result = write_project_files(doc, dir, &look_path, &mut new_files);
    let keep = match result {
        Ok(keep) => keep,
        Err(e) => {
            new_files.remove();
            return Err(e);
        }
    };
    // The project is saved; a file that cannot be deleted now is deleted by a later save.
    let _ = remove_unreferenced(dir, &keep);
    Ok(())
}

/// The files a save wrote that were not there before it (deleted again if it fails).
#[derive(Default)]
struct NewFiles(Vec<PathBuf>);

impl NewFiles {
    /// Writes `path` atomically with `bytes()` unless it exists (content-named: an existing
    /// file already holds these bytes).
    fn write(&mut self, path: &Path, bytes: impl FnOnce() -> Result<Vec<u8>>) -> Result<()> {
        if path.is_file() {
            return Ok(());
        }
        write_atomic(path, &bytes()?).map_err(|e| ModelError::file(path, e))?;
        self.0.push(path.to_owned());
        Ok(())
    }

    fn remove(&self) {
        for path in &self.0 {
            let _ = std::fs::remove_file(path);
        }
    }
}

/// Everything of [`write_project`] up to and including the commit; returns the files the new
/// `look.json` refers to (relative to `dir`).
fn write_project_files(doc: &Document, dir: &Path, look_path: &Path, new: &mut NewFiles) -> Result<HashSet<PathBuf>> {
    let maps_dir = dir.join(MAPS_DIR);
    create_dir(&maps_dir)?;
    let files: Vec<LayerFiles> = doc.layers.iter().enumerate().map(|(i, l)| layer_files(i, l)).collect();
    let mut keep = HashSet::new();
    for (layer, files) in doc.layers.iter().zip(&files) {
        let path = maps_dir.join(&files.map);
        new.write(&path, || layer.map.exr_bytes(&path))?;
        keep.insert(PathBuf::from(MAPS_DIR).join(&files.map));
    }
    let presets_dir = dir.join(PRESETS_DIR);
    for files in &files {
        if let PresetFile::File { file, json } = &files.preset {
            create_dir(&presets_dir)?;
            new.write(&presets_dir.join(file), || Ok(json.clone().into_bytes()))?;
            keep.insert(PathBuf::from(PRESETS_DIR).join(file));
        }
    }
    let face_text = face_json(&doc.face, &dir.join(FACE_FILE))?;
    let face = content_name(FACE_PREFIX, &face_text);
    new.write(&dir.join(&face), || Ok(face_text.into_bytes()))?;
    keep.insert(PathBuf::from(&face));
    let skin = match &doc.skin {
        Some(skin) => {
            let files = project_skin_files(skin, MAPS_DIR).map_err(|e| ModelError::file(dir, e))?;
            for (name, exr) in &files.exrs {
                let path = maps_dir.join(name);
                new.write(&path, || exr.bytes().map_err(|e| ModelError::file(&path, e)))?;
                keep.insert(PathBuf::from(MAPS_DIR).join(name));
            }
            let name = content_name(SKIN_PREFIX, &files.json);
            new.write(&dir.join(&name), || Ok(files.json.into_bytes()))?;
            keep.insert(PathBuf::from(&name));
            Some(name)
        }
        None => None,
    };
    // What the new look.json names must be on disk before it: the renames above, then it.
    for d in [&maps_dir, &presets_dir, dir] {
        sync_dir(d);
    }
    // `look.json` needs only the references; the maps themselves are in the files.
    let layers = doc.layers.iter().zip(&files).map(|(l, f)| look_layer(l, f, ThicknessMap::uniform(0.0))).collect();
    let look = Look { name: doc.name.clone(), layers, mascara: doc.mascara, brow_gel: doc.brow_gel };
    let part = ProjectPart { face, skin, subsurface: Some(doc.subsurface), diffuse: Some(doc.diffuse) };
    write_atomic(look_path, look.to_project_json(Some(&part)).as_bytes())
        .map_err(|e| ModelError::file(look_path, e))?;
    sync_dir(dir);
    Ok(keep)
}

/// Makes a folder's entries (renames into it) durable, as far as the file system lets it:
/// best effort, since some refuse to sync a folder.
fn sync_dir(dir: &Path) {
    if let Ok(d) = std::fs::File::open(dir) {
        let _ = d.sync_all();
    }
}

/// The prefix of a project's content-named face files.
const FACE_PREFIX: &str = "face-";
/// The prefix of a project's content-named skin files (`skin.json`'s contents).
const SKIN_PREFIX: &str = "skin-";

/// `<prefix><hash>.json`: a project's face or skin file, named by its contents.
fn content_name(prefix: &str, text: &str) -> String {
    format!("{prefix}{:016x}.json", bytes_hash(text.as_bytes()))
}

/// Whether `file` is named as [`content_name`] names files with `prefix`.
fn is_content_name(file: &str, prefix: &str) -> bool {
    file.strip_prefix(prefix)
        .and_then(|s| s.strip_suffix(".json"))
        .is_some_and(|h| h.len() == HASH_DIGITS && h.bytes().all(|b| b.is_ascii_digit() || (b'a'..=b'f').contains(&b)))
}

/// The project file that `look.json`'s `project.<field>` names: a file name in `dir`, nothing
/// else (no folder, no `..`).
fn project_file(dir: &Path, look_path: &Path, field: &str, name: &str) -> Result<PathBuf> {
    let plain = !name.is_empty() && name != "." && name != ".." && !name.contains(['/', '\\']);
    if !plain {
        return Err(ModelError::file(
            look_path,
            format!("`project.{field}` is {name:?}: expected the name of a file in the project folder"),
        ));
    }
    Ok(dir.join(name))
}

/// The face file's schema: `{"format": "rouge-face", "version": 1, "expression": {NAME: W},
/// "shape": {NAME: W}}` (docs/FORMATS.md).
#[derive(serde::Serialize, serde::Deserialize)]
struct FaceFile {
    format: String,
    version: u32,
    #[serde(flatten)]
    face: FacePose,
}

const FACE_FORMAT: &str = "rouge-face";

/// The face file's text (also when neutral, so a reopened project says so); `path` names it
/// in an error.
fn face_json(face: &FacePose, path: &Path) -> Result<String> {
    let file = FaceFile { format: FACE_FORMAT.into(), version: 1, face: face.clone() };
    Ok(serde_json::to_string_pretty(&file).map_err(|e| ModelError::file(path, e))? + "\n")
}

/// Reads a project's face: neutral when the file is absent (projects saved before faces);
/// errors name the file, line and column, or the unknown target (with near names).
pub(super) fn read_face(path: &Path) -> Result<FacePose> {
    let Some(file) = read_versioned::<FaceFile>(path, FACE_FORMAT, |f| (&f.format, f.version))? else {
        return Ok(FacePose::default());
    };
    let targets = TargetSet::default_head().map_err(|e| ModelError::file(path, e))?;
    targets.resolve_named(&file.face, ["`expression`", "`shape`"]).map_err(|e| ModelError::file(path, e))?;
    Ok(file.face)
}

/// Reads a project's versioned JSON file, `{"format": FORMAT, "version": 1, ...}` (`header`
/// gives a parsed file's format and version): `None` when the file is absent; errors name the
/// file and the line and column, or the format and version it holds.
pub(crate) fn read_versioned<T: serde::de::DeserializeOwned>(
    path: &Path,
    format: &str,
    header: impl Fn(&T) -> (&str, u32),
) -> Result<Option<T>> {
    let text = match std::fs::read_to_string(path) {
        Ok(t) => t,
        Err(e) if e.kind() == std::io::ErrorKind::NotFound => return Ok(None),
        Err(e) => return Err(ModelError::file(path, e)),
    };
    let file: T = serde_json::from_str(&text)
        .map_err(|e| ModelError::file(path, format!("line {}, column {}: {e}", e.line(), e.column())))?;
    let (found, version) = header(&file);
    if found != format || version != 1 {
        return Err(ModelError::file(
            path,
            format!("format {found:?} version {version}: expected {format:?} version 1"),
        ));
    }
    Ok(Some(file))
}

/// Deletes the files of the project in `dir` that are not in `keep` (paths relative to `dir`)
/// and are named as Rouge names them: a layer's map or preset, the skin maps' and skin edits'
/// EXR, the content-named face and skin files, `face.json` and `skin.json` (projects saved
/// before content-named ones), and the temporary files of interrupted atomic writes of any of
/// these or of `look.json`. Other files are left alone. Returns the first error, after trying
/// all.
pub(super) fn remove_unreferenced(dir: &Path, keep: &HashSet<PathBuf>) -> Result<()> {
    let mut first_error = None;
    for sub in ["", MAPS_DIR, PRESETS_DIR] {
        let Ok(entries) = std::fs::read_dir(dir.join(sub)) else { continue };
        for entry in entries.flatten() {
            let name = entry.file_name().to_string_lossy().into_owned();
            let rel = PathBuf::from(sub).join(&name);
            let ours = is_project_file(sub, &name) || interrupted_write(&name).is_some_and(|n| is_temp_target(sub, n));
            if !ours || keep.contains(&rel) || !entry.path().is_file() {
                continue;
            }
            if let Err(e) = std::fs::remove_file(entry.path()) {
                first_error.get_or_insert_with(|| ModelError::file(&entry.path(), format!("cannot delete: {e}")));
            }
        }
    }
    first_error.map_or(Ok(()), Err)
}

/// Whether `name` in the project's folder `sub` (`""`: the project folder) is a file a save
/// writes and a later one may delete.
fn is_project_file(sub: &str, name: &str) -> bool {
    match sub {
        MAPS_DIR => is_hashed_name(name, "exr") || is_maps_file_name(name),
        PRESETS_DIR => is_hashed_name(name, "json"),
        _ => {
            name == FACE_FILE
                || name == SKIN_FILE
                || is_content_name(name, FACE_PREFIX)
                || is_content_name(name, SKIN_PREFIX)
        }
    }
}

/// Whether an interrupted write's temporary file for `target` in `sub` is Rouge's to delete.
fn is_temp_target(sub: &str, target: &str) -> bool {
    is_project_file(sub, target) || (sub.is_empty() && target == LOOK_FILE)
}

/// The file an atomic write's temporary file `.NAME.tmp-PID` (`write_atomic`'s) was for.
fn interrupted_write(file: &str) -> Option<&str> {
    let (head, pid) = file.strip_prefix('.')?.rsplit_once(".tmp-")?;
    (!pid.is_empty() && pid.bytes().all(|b| b.is_ascii_digit())).then_some(head)
}

/// `map` as a 16-bit grey PNG: round(value / max_mm · 65535), all 0 when `max_mm` is 0.
pub(super) fn encode_png16(map: &ThicknessMap, max_mm: f32, path: &Path) -> Result<Vec<u8>> {
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
