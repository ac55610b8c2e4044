//! What each fuzz target feeds its parser, in one place: the libFuzzer targets
//! (`fuzz/fuzz_targets/*.rs`, `cargo +nightly fuzz run TARGET`) call these, and so does the
//! stable replay test (`tests/fuzz_replay.rs`), which runs every file of `fuzz/corpus/TARGET/`
//! through them in the normal test suite (CI's short fuzz run).
//!
//! Each function takes arbitrary bytes and must return: an `Err` from the parser is the expected
//! answer to a malformed file, a panic, an abort or a hang is a finding. Parsers that read files
//! get the bytes written into a scratch folder of this process first.
#![allow(clippy::missing_panics_doc)]

use std::path::{Path, PathBuf};
use std::sync::OnceLock;

/// A target's function: arbitrary bytes in, nothing out (a panic is the finding).
pub type Target = fn(&[u8]);

/// Every target: its name (the folder of its corpus) and the function it runs.
pub const TARGETS: &[(&str, Target)] = &[
    ("measurement", measurement),
    ("preset", preset),
    ("look", look),
    ("face", face),
    ("medium", medium),
    ("skin_exr", skin_exr),
    ("obj", obj),
    ("gltf", gltf),
    ("map", map),
    ("project", project),
    ("env", env),
];

/// The scratch folder of this process (in /dev/shm where there is one: the targets write a
/// file per execution).
fn scratch() -> &'static Path {
    static DIR: OnceLock<PathBuf> = OnceLock::new();
    DIR.get_or_init(|| {
        let shm = Path::new("/dev/shm");
        let root = if shm.is_dir() { shm.to_path_buf() } else { std::env::temp_dir() };
        let dir = root.join(format!("rouge-fuzz-{}", std::process::id()));
        std::fs::create_dir_all(&dir).expect("scratch folder");
        dir
    })
}

/// Deletes this process's scratch folder (the replay test, when it is done; a fuzzer's stays
/// until it ends, in /dev/shm).
pub fn remove_scratch() {
    let _ = std::fs::remove_dir_all(scratch());
}

/// A fresh, empty sub-folder `name` of the scratch folder.
fn fresh_dir(name: &str) -> PathBuf {
    let dir = scratch().join(name);
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).expect("scratch sub-folder");
    dir
}

fn write(dir: &Path, name: &str, data: &[u8]) -> PathBuf {
    let path = dir.join(name);
    if let Some(parent) = path.parent() {
        std::fs::create_dir_all(parent).expect("scratch sub-folder");
    }
    std::fs::write(&path, data).expect("scratch file");
    path
}

/// A measurement file of any format (Rouge CSV, CGATS/.ti3, radiance exports): the importer
/// picks the format from the content.
pub fn measurement(data: &[u8]) {
    let dir = fresh_dir("measurement");
    let path = write(&dir, "m.txt", data);
    if let Ok(input) = rouge_measure::import::SpectralInput::read(&path) {
        let _ = input.measurement(&rouge_measure::ImportOptions::default());
        let _ = input.spectra();
        let _ = input.single_spectrum();
    }
}

/// A material preset (`rouge-preset` JSON).
pub fn preset(data: &[u8]) {
    let _ = rouge_measure::Preset::from_json(&String::from_utf8_lossy(data), "fuzz.json");
}

/// A look (`rouge-look` JSON); presets, masks and maps are looked up beside it (there are none).
pub fn look(data: &[u8]) {
    let dir = fresh_dir("look");
    let path = write(&dir, "look.json", data);
    let _ = rouge_model::look::Look::load(&path);
}

/// A project's `face.json`, opened with a project of one uniform layer.
pub fn face(data: &[u8]) {
    let dir = fresh_dir("face");
    write(&dir, "look.json", MINIMAL_LOOK.as_bytes());
    write(&dir, rouge_model::document::FACE_FILE, data);
    let _ = rouge_model::document::Document::open_project(&dir);
}

/// A `rouge-medium` JSON file.
pub fn medium(data: &[u8]) {
    let dir = fresh_dir("medium");
    let path = write(&dir, "medium.json", data);
    let _ = rouge_model::medium::Medium::load(&path);
}

/// A project's skin maps and skin edits (OpenEXR).
pub fn skin_exr(data: &[u8]) {
    let base = rouge_measure::skin::SkinParams::from_tone(None, [None; 7]).expect("the default skin");
    let _ = rouge_model::skin::SkinMaps::from_exr_bytes(data, &base);
    let _ = rouge_model::skin::SkinEdits::from_exr_bytes(data);
}

/// A Wavefront OBJ mesh.
pub fn obj(data: &[u8]) {
    let _ = rouge_model::mesh::parse_obj(&String::from_utf8_lossy(data), Path::new("fuzz.obj"), 1.0);
}

/// A glTF 2.0 mesh (.glb binary or .gltf JSON: the reader tells them apart by content).
pub fn gltf(data: &[u8]) {
    let dir = fresh_dir("gltf");
    let path = write(&dir, "mesh.glb", data);
    let _ = rouge_model::mesh::load_gltf(&path, 1.0);
}

/// A thickness map (OpenEXR or 16-bit PNG) and a thickness mask (PNG).
pub fn map(data: &[u8]) {
    use rouge_model::look::ThicknessSource;
    let dir = fresh_dir("map");
    write(&dir, "m", data);
    let _ = ThicknessSource::Map { path: "m".into(), scale_mm: Some(0.01) }.load_map(&dir);
    let _ = ThicknessSource::Mask { path: "m".into(), mm: 0.01 }.load_map(&dir);
}

/// An environment map (OpenEXR radiance, `--env`): the renderer's decoder, which lives in
/// rouge-model (`hdr::decode_rgb_exr`) so that this crate reaches it without the renderer.
pub fn env(data: &[u8]) {
    let _ = rouge_model::hdr::decode_rgb_exr(data, 4096);
}

/// Files a project folder may hold, in the order [`project`] numbers them.
pub const PROJECT_FILES: &[&str] = &[
    "look.json",
    "face.json",
    "skin.json",
    "maps/layer.exr",
    "maps/layer.png",
    "presets/p.json",
    "maps/skin.exr",
    "maps/edits.exr",
];

/// A project folder. The input is a sequence of files: one byte choosing the name
/// (`PROJECT_FILES[b % len]`), two bytes of length (little endian), then the contents.
pub fn project(data: &[u8]) {
    let dir = fresh_dir("project");
    for (name, contents) in split_project(data) {
        write(&dir, name, contents);
    }
    let _ = rouge_model::document::Document::open_project(&dir);
}

/// The files of a [`project`] input.
pub fn split_project(mut data: &[u8]) -> Vec<(&'static str, &[u8])> {
    let mut files = Vec::new();
    while let [which, lo, hi, rest @ ..] = data {
        let len = usize::from(u16::from_le_bytes([*lo, *hi])).min(rest.len());
        files.push((PROJECT_FILES[usize::from(*which) % PROJECT_FILES.len()], &rest[..len]));
        data = &rest[len..];
    }
    files
}

/// A look of one uniform foundation layer (for the targets that need a project around a file).
pub const MINIMAL_LOOK: &str = r#"{"schema": "rouge-look", "version": 1,
 "layers": [{"preset": "builtin:foundation_02_ivory", "thickness": {"uniform_mm": 0.01}}]}"#;
