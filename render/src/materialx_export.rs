//! `rouge export materialx`: the head as drawn (an OBJ, millimetres) with an OpenPBR Surface
//! material (\[OpenPBR\] 1.1, MaterialX 1.39's `open_pbr_surface`) over the look baked into
//! textures (docs/FORMATS.md, "rouge export materialx").
//!
//! What each OpenPBR input holds:
//! - `base_color` and `subsurface_color`: the bake's base colour (`gltf_export::bake`): the
//!   diffuse reflectance of the look over the skin, which OpenPBR's subsurface colour is (the
//!   albedo after multiple scattering); `subsurface_weight` 1 on the skin (the layers' colour is in
//!   the colour; their opacity does not shorten the scattering).
//! - `subsurface_radius` (mm) × `subsurface_radius_scale` (per channel): the skin medium's mean
//!   free path 1/σt per channel where the scene names a medium (`--medium`); otherwise the mean
//!   radius of the diffusion profile the renderer blurs with, Σ w σ√(π/2) / Σ w per channel (a
//!   Gaussian of variance σ² per axis has mean radius σ√(π/2)).
//! - `specular_roughness`, `specular_ior`, `specular_weight`: the bake's one lobe for the skin and
//!   every layer that is not a gloss (roughness √m, F0 relative to the skin's index).
//! - `coat_*`: a gloss layer (finish `gloss`): weight its coverage per texel, roughness √m and
//!   index of its lobe, colour white (a clear film; its colour stays in the base).
//! - `fuzz_weight` 0: no finish of Rouge has a sheen lobe (docs/FINISHES.md), so none is drawn.
//!
//! \[OpenPBR\]: Andersson et al., "OpenPBR Surface" specification 1.1, Academy Software
//! Foundation, 2024.

use crate::error::Result;
use crate::gltf_export::bake::{SurfaceMaps, bake_surface};
use crate::gltf_export::coat::split_coat;
use crate::gltf_export::document::{encode_png, file_set_error};
use crate::gltf_export::{base_color_texels, checked, gltf_roughness, layer_input, skin_surface};
use crate::job::{Loaded, SkinTextureImages};
use crate::renderer::LayerInput;
use crate::scene::{Skin, SubsurfaceModel, fresnel_f0};
use crate::sss::DiffusionProfile;
use rouge_measure::file_set::{content_tagged, write_file_set};
use rouge_model::mesh::TriangleMesh;
use std::fmt::Write as _;
use std::path::{Path, PathBuf};

/// The material document's file name.
pub const MTLX_FILE: &str = "face.mtlx";
/// The mesh's file name.
pub const OBJ_FILE: &str = "face.obj";
/// The textures an export writes, without their content tag and `.png`: an earlier export's
/// are known by them.
pub const TEXTURE_STEMS: [&str; 5] =
    ["skin_base_color", "skin_specular_roughness", "skin_specular_weight", "skin_coat_weight", "skin_normal"];

/// An exported material and mesh, ready to write.
#[derive(Clone, Debug)]
pub struct MaterialxExport {
    /// File names and contents: the textures (named by their content), the OBJ, the .mtlx last
    /// (it names the textures).
    pub files: Vec<(String, Vec<u8>)>,
    /// Triangles of the OBJ.
    pub triangles: usize,
    /// Whether a gloss layer became OpenPBR's coat.
    pub coat: bool,
}

impl MaterialxExport {
    /// Writes every file into `dir` (which must exist), each through a temporary file and a
    /// rename: the textures (named by their content) and the OBJ, then the .mtlx that names the
    /// textures, then the previous export's textures ([`TEXTURE_STEMS`]`.<hash>.png`, and the plain
    /// `STEM.png` of exports before content names that the previous .mtlx names) are removed
    /// (`rouge_measure::file_set`). A kill or a full disk at any point leaves a .mtlx whose
    /// textures are all there and its own; the OBJ beside it may be the next export's (each file
    /// whole). Returns the files written, the .mtlx last.
    ///
    /// # Errors
    /// [`crate::RenderError::File`] naming the file that could not be written.
    pub fn write(&self, dir: &Path) -> Result<Vec<PathBuf>> {
        let Some(((_, mtlx), companions)) = self.files.split_last() else { return Ok(Vec::new()) };
        let ours = |stem: &str, ext: &str| ext == "png" && TEXTURE_STEMS.contains(&stem);
        write_file_set(dir, companions, &dir.join(MTLX_FILE), mtlx, &ours).map_err(file_set_error)
    }
}

/// The scene `loaded` (its mesh, look and skin, with the skin textures `images`) as an OBJ and an
/// OpenPBR material with textures of `texture_px`² texels.
///
/// # Errors
/// A mesh without triangles or UVs, and what [`bake_surface`] refuses.
pub fn export_materialx(loaded: &Loaded, images: &SkinTextureImages, texture_px: u32) -> Result<MaterialxExport> {
    let mesh = checked(&loaded.mesh)?;
    let skin = skin_surface(loaded, images);
    let all: Vec<LayerInput<'_>> = loaded.look.visible_layers().map(layer_input).collect();
    let surface = bake_surface(&skin, &all, texture_px)?;
    let (under, coat) = split_coat(&all, texture_px);
    // The specular lobe below the coat: every layer but the glosses.
    let below = if coat.is_some() { Some(bake_surface(&skin, &under, texture_px)?) } else { None };
    let lobe = below.as_ref().unwrap_or(&surface);
    let side = (texture_px, texture_px);

    let mut files = Vec::new();
    let mut skin_inputs = Vec::new();
    files.push(("skin_base_color.png".to_string(), encode_png(side, &base_color_texels(&surface), 3)?));
    skin_inputs.push(("base_color", "color3", Source::Image("skin_base_color.png", "srgb_texture", None)));
    skin_inputs.push(("subsurface_color", "color3", Source::Image("skin_base_color.png", "srgb_texture", None)));
    let roughness: Vec<u8> = lobe.beckmann_roughness.iter().map(|&m| unit_u8(gltf_roughness(m))).collect();
    files.push(("skin_specular_roughness.png".to_string(), encode_png(side, &roughness, 1)?));
    skin_inputs.push(("specular_roughness", "float", Source::Image("skin_specular_roughness.png", "", None)));
    let ior = loaded.scene.skin.ior;
    skin_inputs.push(("specular_ior", "float", Source::Value(num(ior))));
    if let Some((texels, factor)) = specular_weight(lobe, ior) {
        files.push(("skin_specular_weight.png".to_string(), encode_png(side, &texels, 1)?));
        skin_inputs.push(("specular_weight", "float", Source::Image("skin_specular_weight.png", "", Some(factor))));
    }
    let (radius_mm, scale) = subsurface_radius_mm(&loaded.scene.skin);
    skin_inputs.push(("subsurface_weight", "float", Source::Value("1".into())));
    skin_inputs.push(("subsurface_radius", "float", Source::Distance(num(radius_mm))));
    skin_inputs.push(("subsurface_radius_scale", "color3", Source::Value(color(scale))));
    if let Some(coat) = &coat {
        files.push(("skin_coat_weight.png".to_string(), encode_png(side, &coat.texels(), 1)?));
        skin_inputs.push(("coat_weight", "float", Source::Image("skin_coat_weight.png", "", None)));
        skin_inputs.push(("coat_color", "color3", Source::Value("1, 1, 1".into())));
        skin_inputs.push(("coat_roughness", "float", Source::Value(num(gltf_roughness(coat.beckmann_roughness)))));
        skin_inputs.push(("coat_ior", "float", Source::Value(num(coat.ior))));
    } else {
        skin_inputs.push(("coat_weight", "float", Source::Value("0".into())));
    }
    skin_inputs.push(("fuzz_weight", "float", Source::Value("0".into())));
    if let Some(n) = images.normal.as_ref() {
        files.push(("skin_normal.png".to_string(), encode_png(n.dimensions(), n.as_raw(), 4)?));
        skin_inputs.push(("geometry_normal", "vector3", Source::Normal("skin_normal.png")));
    }

    let eye_color = mean_eye_color(&mesh, loaded.scene.skin.albedo);
    let mut eye_inputs = vec![
        ("base_color", "color3", Source::Value(color(eye_color.map(f64::from)))),
        ("specular_roughness", "float", Source::Value(num(gltf_roughness(loaded.scene.skin.roughness)))),
        ("specular_ior", "float", Source::Value(num(ior))),
    ];
    if eye_color == [0.0; 3] {
        eye_inputs.clear();
    }
    let (obj, triangles, has_eyes) = obj_text(&mesh);
    let mut mtlx = mtlx_text(&loaded.look.name, &skin_inputs, has_eyes.then_some(&eye_inputs[..]));
    // The textures named by their content (`skin_base_color.<hash>.png`), as the .mtlx names them:
    // a new export never replaces a file the previous .mtlx still names.
    for (name, bytes) in &mut files {
        let tagged = content_tagged(name.trim_end_matches(".png"), "png", bytes);
        mtlx = mtlx.replace(&format!("value=\"{name}\""), &format!("value=\"{tagged}\""));
        *name = tagged;
    }
    files.push((OBJ_FILE.to_string(), obj.into_bytes()));
    files.push((MTLX_FILE.to_string(), mtlx.into_bytes()));
    Ok(MaterialxExport { files, triangles, coat: coat.is_some() })
}

/// Where an OpenPBR input's value comes from.
enum Source {
    /// A literal, as MaterialX writes it ("0.5", "1, 0.5, 0.25").
    Value(String),
    /// A length in millimetres.
    Distance(String),
    /// A texture file, its colour space ("" for data), and a factor it is multiplied by.
    Image(&'static str, &'static str, Option<f32>),
    /// A tangent-space normal map.
    Normal(&'static str),
}

fn unit_u8(v: f32) -> u8 {
    (v.clamp(0.0, 1.0) * 255.0).round() as u8
}

fn num(v: f32) -> String {
    format!("{}", (f64::from(v) * 1e6).round() / 1e6)
}

fn color(c: [f64; 3]) -> String {
    let r = |v: f64| (v * 1e6).round() / 1e6;
    format!("{}, {}, {}", r(c[0]), r(c[1]), r(c[2]))
}

/// OpenPBR's `specular_weight` scales the dielectric F0 of `specular_ior`: per texel F0 over the
/// skin's, as an 8-bit texture × a factor (≥ 1) that brings its largest value to 1. `None` where
/// every texel has the skin's F0.
fn specular_weight(s: &SurfaceMaps, ior: f32) -> Option<(Vec<u8>, f32)> {
    let base = fresnel_f0(ior);
    if base <= 0.0 || s.f0.iter().all(|&f| (f - base).abs() <= 1e-6 * base) {
        return None;
    }
    let factor = (s.f0.iter().copied().fold(0.0, f32::max) / base).max(1.0);
    Some((s.f0.iter().map(|&f| unit_u8(f / (base * factor))).collect(), factor))
}

/// OpenPBR's subsurface radius (mm) and per-channel scale (largest 1) for `skin`: see the module
/// documentation.
pub fn subsurface_radius_mm(skin: &Skin) -> (f32, [f64; 3]) {
    let per_channel: [f64; 3] = match (&skin.medium, &skin.subsurface) {
        (Some(m), _) => m.sigma_t_per_mm().map(|t| if t > 0.0 { 1.0 / t } else { 0.0 }),
        (None, SubsurfaceModel::ScreenSpace { profile }) => profile_mean_radius_mm(profile),
        (None, _) => profile_mean_radius_mm(&DiffusionProfile::skin()),
    };
    let max = per_channel.iter().copied().fold(0.0, f64::max);
    if max <= 0.0 {
        return (0.0, [1.0; 3]);
    }
    (max as f32, per_channel.map(|r| r / max))
}

/// Σ w σ√(π/2) / Σ w per channel: the mean radius of a sum of 2-D Gaussians.
fn profile_mean_radius_mm(p: &DiffusionProfile) -> [f64; 3] {
    let half_pi_sqrt = std::f64::consts::FRAC_PI_2.sqrt();
    std::array::from_fn(|c| {
        let (sum, weight) = p
            .gaussians
            .iter()
            .fold((0.0, 0.0), |(s, w), g| (s + g.weight[c] * g.variance_mm2.sqrt() * half_pi_sqrt, w + g.weight[c]));
        if weight > 0.0 { sum / weight } else { 0.0 }
    })
}

/// The mean of the renderer's per-vertex colours of the eyes (OBJ has no colour per vertex);
/// zero without eyes.
fn mean_eye_color(mesh: &TriangleMesh, skin_albedo: [f32; 3]) -> [f32; 3] {
    let albedo = crate::gpu_mesh::vertex_albedo(mesh, skin_albedo, Default::default());
    let mut seen = vec![false; mesh.positions.len()];
    let (mut sum, mut n) = ([0.0f32; 3], 0usize);
    for g in mesh.groups.iter().filter(|g| g.is_eye()) {
        for &v in &mesh.indices[g.triangles.start * 3..g.triangles.end * 3] {
            let v = v as usize;
            if !std::mem::replace(&mut seen[v], true) {
                (0..3).for_each(|c| sum[c] += albedo[v][c]);
                n += 1;
            }
        }
    }
    if n == 0 { [0.0; 3] } else { sum.map(|s| s / n as f32) }
}

/// The mesh as OBJ text (mm, Rouge's UV convention: v up): the skin's triangles as group `skin`
/// with material `skin`, each eye group under its name with material `eyes`. Returns the text,
/// the triangle count and whether there are eyes.
fn obj_text(mesh: &TriangleMesh) -> (String, usize, bool) {
    let mut s = format!("# Written by `rouge export materialx` (Rouge {}). Units: mm.\n", env!("CARGO_PKG_VERSION"));
    let _ = writeln!(s, "# Materials: {MTLX_FILE} (MaterialX; `skin` and `eyes` are its material names)");
    for p in &mesh.positions {
        let _ = writeln!(s, "v {} {} {}", p.x, p.y, p.z);
    }
    for t in &mesh.uvs {
        let _ = writeln!(s, "vt {} {}", t.x, t.y);
    }
    for n in &mesh.normals {
        let n = n.try_normalize().unwrap_or(glam::Vec3::Z);
        let _ = writeln!(s, "vn {} {} {}", n.x, n.y, n.z);
    }
    let with_normals = mesh.normals.len() == mesh.positions.len();
    let mut eye = vec![false; mesh.triangle_count()];
    for g in mesh.groups.iter().filter(|g| g.is_eye()) {
        eye[g.triangles.clone()].iter_mut().for_each(|e| *e = true);
    }
    let face = |s: &mut String, t: usize| {
        let i = &mesh.indices[t * 3..t * 3 + 3];
        let v = |k: usize| {
            let j = i[k] + 1;
            if with_normals { format!("{j}/{j}/{j}") } else { format!("{j}/{j}") }
        };
        let _ = writeln!(s, "f {} {} {}", v(0), v(1), v(2));
    };
    s.push_str("g skin\nusemtl skin\n");
    (0..mesh.triangle_count()).filter(|&t| !eye[t]).for_each(|t| face(&mut s, t));
    let mut has_eyes = false;
    for g in mesh.groups.iter().filter(|g| g.is_eye() && !g.triangles.is_empty()) {
        has_eyes = true;
        let _ = writeln!(s, "g {}\nusemtl eyes", g.name.replace(char::is_whitespace, "_"));
        g.triangles.clone().for_each(|t| face(&mut s, t));
    }
    (s, mesh.triangle_count(), has_eyes)
}

fn xml_escape(s: &str) -> String {
    s.replace('&', "&amp;").replace('<', "&lt;").replace('>', "&gt;").replace('"', "&quot;").replace("--", "- -")
}

/// The MaterialX 1.39 document: for each material its image nodes, an `open_pbr_surface` and a
/// `surfacematerial`, then a look assigning them to the OBJ's groups.
fn mtlx_text(look: &str, skin: &[(&str, &str, Source)], eyes: Option<&[(&str, &str, Source)]>) -> String {
    let mut x = String::from("<?xml version=\"1.0\"?>\n<materialx version=\"1.39\" colorspace=\"lin_rec709\">\n");
    let _ = writeln!(
        x,
        "  <!-- Written by `rouge export materialx` (Rouge {}): look \"{}\" over the skin, baked; mesh {OBJ_FILE} (mm). -->",
        env!("CARGO_PKG_VERSION"),
        xml_escape(look)
    );
    let mut images: Vec<String> = Vec::new();
    let mut material = |name: &str, inputs: &[(&str, &str, Source)]| {
        let mut body = String::new();
        for (input, kind, source) in inputs {
            let node = format!("{name}_{input}");
            let from = match source {
                Source::Value(v) => {
                    let _ = writeln!(body, "    <input name=\"{input}\" type=\"{kind}\" value=\"{v}\" />");
                    continue;
                }
                Source::Distance(v) => {
                    let _ = writeln!(
                        body,
                        "    <input name=\"{input}\" type=\"{kind}\" value=\"{v}\" unittype=\"distance\" unit=\"millimeter\" />"
                    );
                    continue;
                }
                Source::Image(file, space, factor) => {
                    // One image node per file, named after it (the base and subsurface colours
                    // share theirs).
                    let image = file.trim_end_matches(".png").to_string();
                    if !images.contains(&image) {
                        let space = if space.is_empty() { String::new() } else { format!(" colorspace=\"{space}\"") };
                        let _ = writeln!(
                            x,
                            "  <image name=\"{image}\" type=\"{kind}\">\n    <input name=\"file\" type=\"filename\" value=\"{file}\"{space} />\n  </image>"
                        );
                        images.push(image.clone());
                    }
                    match factor {
                        None => image,
                        Some(f) => {
                            let _ = writeln!(
                                x,
                                "  <multiply name=\"{node}_scaled\" type=\"{kind}\">\n    <input name=\"in1\" type=\"{kind}\" nodename=\"{image}\" />\n    <input name=\"in2\" type=\"float\" value=\"{}\" />\n  </multiply>",
                                num(*f)
                            );
                            format!("{node}_scaled")
                        }
                    }
                }
                Source::Normal(file) => {
                    let _ = writeln!(
                        x,
                        "  <image name=\"{node}_image\" type=\"vector3\">\n    <input name=\"file\" type=\"filename\" value=\"{file}\" />\n  </image>\n  <normalmap name=\"{node}\" type=\"vector3\">\n    <input name=\"in\" type=\"vector3\" nodename=\"{node}_image\" />\n  </normalmap>"
                    );
                    node
                }
            };
            let _ = writeln!(body, "    <input name=\"{input}\" type=\"{kind}\" nodename=\"{from}\" />");
        }
        let _ = writeln!(
            x,
            "  <open_pbr_surface name=\"{name}_surface\" type=\"surfaceshader\">\n{body}  </open_pbr_surface>\n  <surfacematerial name=\"{name}\" type=\"material\">\n    <input name=\"surfaceshader\" type=\"surfaceshader\" nodename=\"{name}_surface\" />\n  </surfacematerial>"
        );
    };
    material("skin", skin);
    if let Some(eyes) = eyes {
        material("eyes", eyes);
    }
    x.push_str(
        "  <look name=\"rouge\">\n    <materialassign name=\"skin_assign\" material=\"skin\" geom=\"/skin\" />\n",
    );
    if eyes.is_some() {
        x.push_str("    <materialassign name=\"eyes_assign\" material=\"eyes\" geom=\"/eye*\" />\n");
    }
    x.push_str("  </look>\n</materialx>\n");
    x
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_profile_mean_radius_is_the_rayleigh_mean_of_each_gaussian() {
        use crate::sss::Gaussian;
        let one = DiffusionProfile { gaussians: vec![Gaussian { variance_mm2: 4.0, weight: [1.0, 1.0, 0.0] }] };
        let r = profile_mean_radius_mm(&one);
        assert!((r[0] - 2.0 * std::f64::consts::FRAC_PI_2.sqrt()).abs() < 1e-12);
        assert_eq!(r[2], 0.0);
        // d'Eon's skin profile: red scatters farthest, blue least.
        let skin = profile_mean_radius_mm(&DiffusionProfile::skin());
        assert!(skin[0] > skin[1] && skin[1] > skin[2], "{skin:?}");
    }

    #[test]
    fn names_and_text_are_escaped_for_xml() {
        assert_eq!(xml_escape("a<b & \"c\" -- d"), "a&lt;b &amp; &quot;c&quot; - - d");
    }
}
