//! The glTF 2.0 document ([glTF2]): meshes as binary accessors, materials, textures, and the two
//! containers: one .glb (JSON and binary chunks, images in the binary buffer) or a .gltf with its
//! .bin and PNG images beside it. Every file is written atomically (temporary file, rename); a
//! .gltf's companions are named by their content and written before it, and the previous
//! export's removed after it (`rouge_measure::file_set`), so a kill or a full disk at any point
//! leaves a .gltf whose files are all there and all its own.
//!
//! [glTF2]: https://registry.khronos.org/glTF/specs/2.0/glTF-2.0.html

use crate::error::{RenderError, Result};
use rouge_measure::file_set::write_atomic;
use rouge_measure::file_set::{content_tagged, write_file_set};
use serde_json::{Value, json};
use std::path::{Path, PathBuf};

/// glTF's `ARRAY_BUFFER` and `ELEMENT_ARRAY_BUFFER` buffer-view targets.
const ARRAY_BUFFER: u32 = 34962;
const ELEMENT_ARRAY_BUFFER: u32 = 34963;
/// glTF's component types.
const FLOAT: u32 = 5126;
const UNSIGNED_INT: u32 = 5125;

/// One triangle primitive in glTF's conventions: positions in metres, UVs with v down.
#[derive(Clone, Debug, Default)]
pub struct Primitive {
    /// The glTF mesh's name (the repo's loader names its group after it: "eyes" stays an eye).
    pub name: String,
    /// Index into [`Document::materials`].
    pub material: usize,
    /// Positions, metres.
    pub positions_m: Vec<[f32; 3]>,
    /// Unit normals.
    pub normals: Vec<[f32; 3]>,
    /// MikkTSpace tangents, w = ±1, where the material has a normal texture (glTF viewers
    /// need them only there).
    pub tangents: Option<Vec<[f32; 4]>>,
    /// TEXCOORD_0 (glTF: v down).
    pub uvs: Vec<[f32; 2]>,
    /// COLOR_0, linear, when the primitive has colours per vertex (the eyes).
    pub colors: Option<Vec<[f32; 3]>>,
    /// Triangles, counter-clockwise.
    pub indices: Vec<u32>,
}

/// A PNG image of the document.
#[derive(Clone, Debug)]
pub struct Image {
    /// What it holds, one of [`IMAGE_NAMES`], also in its file's name beside a .gltf
    /// (`face_base_color.<hash>.png`).
    pub name: &'static str,
    /// The PNG file.
    pub png: Vec<u8>,
}

/// A glTF document before it is put in a container.
#[derive(Clone, Debug, Default)]
pub struct Document {
    /// One node and one mesh each.
    pub primitives: Vec<Primitive>,
    /// Material objects; textures are named by index into `images` (texture i shows image i).
    pub materials: Vec<Value>,
    /// Images, one texture each.
    pub images: Vec<Image>,
    /// Extensions the materials use (none is required: a viewer without one still draws).
    pub extensions_used: Vec<&'static str>,
    /// `asset.extras`: what made the file.
    pub extras: Value,
}

/// The binary buffer being filled: buffer views and accessors.
struct Bin {
    bytes: Vec<u8>,
    views: Vec<Value>,
    accessors: Vec<Value>,
}

impl Bin {
    fn view(&mut self, data: &[u8], target: Option<u32>) -> usize {
        while !self.bytes.len().is_multiple_of(4) {
            self.bytes.push(0);
        }
        let mut v = json!({"buffer": 0, "byteOffset": self.bytes.len(), "byteLength": data.len()});
        if let Some(t) = target {
            v["target"] = json!(t);
        }
        self.bytes.extend_from_slice(data);
        self.views.push(v);
        self.views.len() - 1
    }

    fn floats<const N: usize>(&mut self, data: &[[f32; N]], kind: &str, bounds: bool) -> usize {
        let view = self.view(bytemuck::cast_slice(data), Some(ARRAY_BUFFER));
        let mut a = json!({"bufferView": view, "componentType": FLOAT, "count": data.len(), "type": kind});
        if bounds {
            let (mut lo, mut hi) = ([f32::INFINITY; N], [f32::NEG_INFINITY; N]);
            for p in data {
                for c in 0..N {
                    lo[c] = lo[c].min(p[c]);
                    hi[c] = hi[c].max(p[c]);
                }
            }
            (a["min"], a["max"]) = (json!(lo.to_vec()), json!(hi.to_vec()));
        }
        self.accessors.push(a);
        self.accessors.len() - 1
    }

    fn indices(&mut self, data: &[u32]) -> usize {
        let view = self.view(bytemuck::cast_slice(data), Some(ELEMENT_ARRAY_BUFFER));
        self.accessors
            .push(json!({"bufferView": view, "componentType": UNSIGNED_INT, "count": data.len(), "type": "SCALAR"}));
        self.accessors.len() - 1
    }
}

/// Where the images and the buffer go.
enum Container<'a> {
    /// In the binary chunk.
    Glb,
    /// Files beside the .gltf, named after its stem.
    Beside { stem: &'a str },
}

impl Document {
    /// The JSON and the binary buffer for `container`.
    fn build(&self, container: &Container<'_>) -> (Value, Vec<u8>) {
        let mut bin = Bin { bytes: Vec::new(), views: Vec::new(), accessors: Vec::new() };
        let mut meshes = Vec::new();
        for p in &self.primitives {
            let mut attributes = json!({
                "POSITION": bin.floats(&p.positions_m, "VEC3", true),
                "NORMAL": bin.floats(&p.normals, "VEC3", false),
                "TEXCOORD_0": bin.floats(&p.uvs, "VEC2", false),
            });
            if let Some(t) = &p.tangents {
                attributes["TANGENT"] = json!(bin.floats(t, "VEC4", false));
            }
            if let Some(c) = &p.colors {
                attributes["COLOR_0"] = json!(bin.floats(c, "VEC3", false));
            }
            let indices = bin.indices(&p.indices);
            meshes.push(json!({"name": p.name, "primitives": [{
                "attributes": attributes, "indices": indices, "material": p.material, "mode": 4
            }]}));
        }
        let images: Vec<Value> = self
            .images
            .iter()
            .map(|img| match container {
                Container::Glb => {
                    json!({"name": img.name, "mimeType": "image/png", "bufferView": bin.view(&img.png, None)})
                }
                Container::Beside { stem } => json!({"name": img.name, "uri": image_file_name(stem, img)}),
            })
            .collect();
        while !bin.bytes.len().is_multiple_of(4) {
            bin.bytes.push(0);
        }
        let mut buffer = json!({"byteLength": bin.bytes.len()});
        if let Container::Beside { stem } = container {
            // Named by its content by `write`, which knows the bytes.
            buffer["uri"] = json!(format!("{stem}.bin"));
        }
        let nodes: Vec<Value> =
            self.primitives.iter().enumerate().map(|(i, p)| json!({"name": p.name, "mesh": i})).collect();
        let mut doc = json!({
            "asset": {"version": "2.0", "generator": format!("Rouge {} (rouge export gltf)", env!("CARGO_PKG_VERSION")), "extras": self.extras},
            "scene": 0,
            "scenes": [{"name": "rouge", "nodes": (0..nodes.len()).collect::<Vec<_>>()}],
            "nodes": nodes,
            "meshes": meshes,
            "materials": self.materials,
            "buffers": [buffer],
            "bufferViews": bin.views,
            "accessors": bin.accessors,
        });
        if !self.images.is_empty() {
            // Clamp to edge, as the renderer samples its maps; trilinear.
            doc["samplers"] = json!([{"magFilter": 9729, "minFilter": 9987, "wrapS": 33071, "wrapT": 33071}]);
            doc["textures"] = json!((0..images.len()).map(|i| json!({"sampler": 0, "source": i})).collect::<Vec<_>>());
            doc["images"] = json!(images);
        }
        if !self.extensions_used.is_empty() {
            doc["extensionsUsed"] = json!(self.extensions_used);
        }
        (doc, bin.bytes)
    }

    /// The document as one binary glTF file (.glb): a 12-byte header, the JSON chunk (padded with
    /// spaces) and the binary chunk (padded with zeros), each 4-byte aligned.
    pub fn glb_bytes(&self) -> Vec<u8> {
        let (doc, bin) = self.build(&Container::Glb);
        let mut json = doc.to_string().into_bytes();
        while !json.len().is_multiple_of(4) {
            json.push(b' ');
        }
        let total = 12 + 8 + json.len() + 8 + bin.len();
        let mut out = Vec::with_capacity(total);
        out.extend_from_slice(b"glTF");
        out.extend_from_slice(&2u32.to_le_bytes());
        out.extend_from_slice(&(total as u32).to_le_bytes());
        out.extend_from_slice(&(json.len() as u32).to_le_bytes());
        out.extend_from_slice(b"JSON");
        out.extend_from_slice(&json);
        out.extend_from_slice(&(bin.len() as u32).to_le_bytes());
        out.extend_from_slice(b"BIN\0");
        out.extend_from_slice(&bin);
        out
    }

    /// Writes the document to `path` by its extension: `.glb` (one file) or `.gltf` (with
    /// `STEM.<hash>.bin` and `STEM_NAME.<hash>.png` beside it, named by their content and written
    /// before the .gltf that names them; an earlier export's companions are removed after it).
    /// Every file goes through a temporary file and a rename, so a failed write leaves the
    /// previous export whole. Returns the files written, the .gltf last.
    ///
    /// # Errors
    /// [`RenderError::File`] naming the file that could not be written, or `path` for another
    /// extension or a file name that is not UTF-8.
    pub fn write(&self, path: &Path) -> Result<Vec<PathBuf>> {
        let write = write_file;
        match path.extension().and_then(|e| e.to_str()).map(str::to_ascii_lowercase).as_deref() {
            Some("glb") => {
                write(path, &self.glb_bytes())?;
                Ok(vec![path.to_path_buf()])
            }
            Some("gltf") => {
                let stem = path.file_stem().and_then(|s| s.to_str()).ok_or_else(|| {
                    RenderError::file(path, "the file name must be UTF-8 (it names the .bin and images)")
                })?;
                let (mut doc, bin) = self.build(&Container::Beside { stem });
                let bin_name = content_tagged(stem, "bin", &bin);
                doc["buffers"][0]["uri"] = json!(bin_name);
                let mut companions = vec![(bin_name, bin)];
                companions.extend(self.images.iter().map(|img| (image_file_name(stem, img), img.png.clone())));
                let text = serde_json::to_string_pretty(&doc)
                    .map_err(|e| RenderError::file(path, format!("cannot encode JSON: {e}")))?;
                // This export's companions: its .bin, and its images `STEM_NAME` for exactly the
                // names an export gives them (another export's beside it, `face_closeup.gltf`
                // beside `face.gltf`, is not this one's).
                let ours = |s: &str, ext: &str| match ext {
                    "bin" => s == stem,
                    "png" => {
                        s.strip_prefix(stem).and_then(|r| r.strip_prefix('_')).is_some_and(|n| IMAGE_NAMES.contains(&n))
                    }
                    _ => false,
                };
                write_file_set(path.parent().unwrap_or(Path::new("")), &companions, path, text.as_bytes(), &ours)
                    .map_err(file_set_error)
            }
            _ => Err(RenderError::file(path, "unknown glTF container: use .glb (one file) or .gltf (files beside it)")),
        }
    }
}

/// Writes `bytes` to `path` through a temporary file beside it and a rename (every exported
/// file): a failed write leaves the previous file whole and no partial file.
///
/// # Errors
/// [`RenderError::File`] naming `path`.
pub fn write_file(path: &Path, bytes: &[u8]) -> Result<()> {
    write_atomic(path, bytes).map_err(|e| file_set_error((path.to_path_buf(), e)))
}

/// [`write_file_set`]'s error (the file and why) as the exports say it.
pub(crate) fn file_set_error((file, e): (PathBuf, std::io::Error)) -> RenderError {
    RenderError::file(&file, format!("cannot write: {e}"))
}

/// The names an export gives its images ([`Image::name`]).
pub const IMAGE_NAMES: [&str; 6] =
    ["base_color", "metallic_roughness", "occlusion_roughness_metallic", "specular", "clearcoat", "normal"];

/// An image's file beside a .gltf: `STEM_NAME.<hash>.png`, named by its content.
fn image_file_name(stem: &str, img: &Image) -> String {
    content_tagged(&format!("{stem}_{}", img.name), "png", &img.png)
}

/// 8-bit texels (row 0 first) of `channels` 1 (grey), 3 (RGB) or 4 (RGBA) per texel as a PNG file.
///
/// # Errors
/// [`RenderError::Invalid`] when the encoder refuses the image.
pub fn encode_png((width, height): (u32, u32), texels: &[u8], channels: u8) -> Result<Vec<u8>> {
    let kind = match channels {
        1 => image::ExtendedColorType::L8,
        3 => image::ExtendedColorType::Rgb8,
        _ => image::ExtendedColorType::Rgba8,
    };
    let mut bytes = Vec::new();
    let encoder = image::codecs::png::PngEncoder::new(&mut bytes);
    image::ImageEncoder::write_image(encoder, texels, width, height, kind)
        .map_err(|e| RenderError::Invalid(format!("cannot encode a {width}×{height} PNG texture: {e}")))?;
    Ok(bytes)
}
