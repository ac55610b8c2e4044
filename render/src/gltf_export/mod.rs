//! `rouge export gltf`: the head as drawn (posed, shaped, subdivided) and its eyes as a glTF 2.0
//! asset, with the look baked into textures (docs/FORMATS.md, "Exported files").
//!
//! - [`bake`]: the look over the skin per texel of the UV space, as the lighting pass composes it
//!   under white light without subsurface scattering ([`bake_surface`] → [`SurfaceMaps`]).
//! - [`document`]: the glTF document and its containers (.glb, or .gltf with files beside it).
//! - Here: [`export_gltf`] turns the mesh (mm, OBJ UV convention) into glTF's conventions
//!   (metres, v down), the baked planes into PNG textures and the materials that use them.
//!
//! Materials: the skin's base colour is the baked diffuse reflectance; its metallic-roughness
//! texture holds the roughness of the one lobe standing for the renderer's stack of Kelemen
//! lobes (metallic 0) and, in its red channel, the head's ambient occlusion ([`occlusion`]); `KHR_materials_ior` carries the skin's IOR where it is not glTF's 1.5, and
//! `KHR_materials_specular` the F0 the layers add (a texture of F0 relative to the skin's), and
//! `KHR_materials_clearcoat` a gloss layer (finish `gloss`, [`coat`]): its coverage as the coat's
//! texture and its roughness, the lobe under it baked without it (glTF's coat has index 1.5). The
//! eyes keep the renderer's per-vertex sclera, iris and pupil as `COLOR_0`. Subsurface
//! scattering has no ratified extension: the baked albedo stands in for it.

pub mod bake;
pub mod coat;
pub mod document;
pub mod occlusion;

pub use bake::{SkinSurface, SurfaceMaps, TEXTURE_PX_RANGE, TexelSurface, bake_surface};
pub use document::Document;

use crate::error::{RenderError, Result};
use crate::job::{Loaded, RenderJob, SkinTextureImages};
use crate::renderer::LayerInput;
use crate::scene::fresnel_f0;
use document::{Image, Primitive, encode_png};
use rouge_measure::colorimetry::srgb_encode;
use rouge_model::mesh::TriangleMesh;
use serde_json::{Value, json};

/// glTF's default index of refraction (`KHR_materials_ior` absent).
const GLTF_DEFAULT_IOR: f32 = 1.5;

/// What `rouge export gltf` exports.
#[derive(Clone, Copy, Debug)]
pub struct GltfInput<'a> {
    /// The mesh as drawn, millimetres (posed, shaped, subdivided); each group named like an eye
    /// becomes a primitive of its own.
    pub mesh: &'a TriangleMesh,
    /// The skin under the look.
    pub skin: SkinSurface<'a>,
    /// The look's visible layers, bottom to top.
    pub layers: &'a [LayerInput<'a>],
    /// The skin's tangent-space normal map (RGBA8, OpenGL convention, +Y up, as glTF's), when
    /// the scene has one.
    pub normal_map: Option<&'a image::RgbaImage>,
    /// Side of the baked textures, texels.
    pub texture_px: u32,
    /// The look's name (kept in `asset.extras`).
    pub look_name: &'a str,
    /// The lashes' and brows' colour (a mascara's on the lashes).
    pub hair: crate::HairAlbedo,
    /// Bake the head's ambient occlusion into `occlusionTexture` ([`occlusion`]: 1-3 s on the
    /// subdivided head; viewers apply it to ambient light only).
    pub occlusion: bool,
}

/// An exported asset, ready to write.
#[derive(Clone, Debug)]
pub struct GltfExport {
    /// The document ([`Document::write`]).
    pub document: Document,
    /// The baked surface the textures were made from.
    pub surface: SurfaceMaps,
    /// Triangles exported (skin and eyes).
    pub triangles: usize,
}

/// `v` as JSON in its shortest decimal form (1.4, not 1.399999976158142).
fn num(v: f32) -> Value {
    v.to_string().parse::<f64>().map_or(json!(f64::from(v)), |x| json!(x))
}

/// glTF's perceptual roughness for a Beckmann lobe of RMS slope `m`: glTF's microfacet α is
/// roughness², and Beckmann's m and GGX's α describe surfaces of about the same roughness
/// (their distributions share the mean square slope), so roughness = √m.
pub fn gltf_roughness(beckmann_m: f32) -> f32 {
    beckmann_m.max(0.0).sqrt().min(1.0)
}

/// The head of `input` as a glTF document with its look baked at `input.texture_px`.
///
/// # Errors
/// [`RenderError::Invalid`] for a mesh without triangles or UVs, tangents that cannot be made,
/// or what [`bake_surface`] refuses.
pub fn export_gltf(input: &GltfInput<'_>) -> Result<GltfExport> {
    let surface = bake_surface(&input.skin, input.layers, input.texture_px)?;
    // A gloss is the clear coat; the lobe under it is baked from the other layers.
    let (under, coat) = coat::split_coat(input.layers, input.texture_px);
    let below = if coat.is_some() { Some(bake_surface(&input.skin, &under, input.texture_px)?) } else { None };
    let lobe = below.as_ref().unwrap_or(&surface);
    // Tangents only where a normal texture uses them.
    let mesh = if input.normal_map.is_some() { with_tangents(input.mesh)? } else { checked(input.mesh)? };
    let skin = input.skin;
    let occlusion =
        if input.occlusion { Some(occlusion::occlusion_plane(input.mesh, input.texture_px)?) } else { None };

    let mut images = vec![
        Image { name: "base_color", png: encode_png(side(&surface), &base_color_texels(&surface), 3)? },
        Image {
            name: if input.occlusion { "occlusion_roughness_metallic" } else { "metallic_roughness" },
            png: encode_png(side(&surface), &orm_texels(lobe, occlusion.as_deref()), 3)?,
        },
    ];
    let texture = |i: usize| json!({"index": i});
    let mut skin_material = json!({
        "name": "skin",
        "pbrMetallicRoughness": {
            "baseColorTexture": texture(0),
            "metallicFactor": 0.0,
            "roughnessFactor": 1.0,
            "metallicRoughnessTexture": texture(1),
        },
    });
    if occlusion.is_some() {
        skin_material["occlusionTexture"] = texture(1);
    }
    let mut extensions_used = Vec::new();
    let mut skin_ext = serde_json::Map::new();
    let ior = ior_extension(skin.ior);
    if let Some(ior) = &ior {
        skin_ext.insert("KHR_materials_ior".into(), ior.clone());
        extensions_used.push("KHR_materials_ior");
    }
    if let Some((texels, color_factor)) = specular_texels(lobe, skin.ior) {
        images.push(Image { name: "specular", png: encode_png(side(&surface), &texels, 4)? });
        skin_ext.insert(
            "KHR_materials_specular".into(),
            json!({"specularTexture": texture(images.len() - 1), "specularColorFactor": [num(color_factor), num(color_factor), num(color_factor)]}),
        );
        extensions_used.push("KHR_materials_specular");
    }
    if let Some(coat) = &coat {
        images.push(Image { name: "clearcoat", png: encode_png(side(&surface), &coat.texels(), 1)? });
        skin_ext.insert(
            "KHR_materials_clearcoat".into(),
            json!({
                "clearcoatFactor": 1.0,
                "clearcoatTexture": texture(images.len() - 1),
                "clearcoatRoughnessFactor": num(gltf_roughness(coat.beckmann_roughness)),
            }),
        );
        extensions_used.push("KHR_materials_clearcoat");
    }
    if let Some(n) = input.normal_map {
        images.push(Image { name: "normal", png: encode_png(n.dimensions(), n.as_raw(), 4)? });
        skin_material["normalTexture"] = texture(images.len() - 1);
    }
    if !skin_ext.is_empty() {
        skin_material["extensions"] = Value::Object(skin_ext);
    }
    let mut eye_material = json!({
        "name": "eyes",
        "pbrMetallicRoughness": {
            "baseColorFactor": [1.0, 1.0, 1.0, 1.0],
            "metallicFactor": 0.0,
            "roughnessFactor": num(gltf_roughness(skin.beckmann_roughness)),
        },
    });
    if let Some(ior) = ior {
        eye_material["extensions"] = json!({"KHR_materials_ior": ior});
    }

    let primitives = primitives(&mesh, skin.albedo, input.hair, input.normal_map.is_some());
    let triangles = primitives.iter().map(|p| p.indices.len() / 3).sum();
    // The eyes' material only with eyes (the skin's is material 0, the eyes' 1).
    let mut materials = vec![skin_material];
    if primitives.iter().any(|p| p.material == 1) {
        materials.push(eye_material);
    }
    let document = Document {
        primitives,
        materials,
        images,
        extensions_used,
        extras: json!({"rouge": {
            "look": input.look_name,
            "texture_px": input.texture_px,
            "base_color": "diffuse reflectance of the look over the skin under white light, subsurface scattering excluded",
        }}),
    };
    Ok(GltfExport { document, surface, triangles })
}

/// The scene of `job` as `rouge render` draws it (mesh posed, shaped and subdivided; the look's
/// visible layers; the skin's colour, albedo texture or skin maps, and its normal map) exported
/// with textures of `texture_px`² texels, and its ambient occlusion when `occlusion`. Lights,
/// camera and environment are not exported.
///
/// # Errors
/// What [`RenderJob::load`], [`RenderJob::skin_textures`] and [`export_gltf`] refuse.
pub fn export_job(job: &RenderJob, texture_px: u32, occlusion: bool) -> Result<GltfExport> {
    // Refused before anything is loaded: skin maps take seconds.
    bake::check_texture_px(texture_px)?;
    let loaded = job.load()?;
    let images = job.skin_textures()?;
    export_loaded(&loaded, &images, texture_px, occlusion)
}

/// [`export_job`] from a scene already loaded and its skin textures read (what a benchmark
/// times apart).
///
/// # Errors
/// What [`export_gltf`] refuses.
pub fn export_loaded(
    loaded: &Loaded,
    images: &SkinTextureImages,
    texture_px: u32,
    occlusion: bool,
) -> Result<GltfExport> {
    let layers: Vec<LayerInput<'_>> = loaded.look.visible_layers().map(layer_input).collect();
    export_gltf(&GltfInput {
        mesh: &loaded.mesh,
        skin: skin_surface(loaded, images),
        layers: &layers,
        normal_map: images.normal.as_ref(),
        texture_px,
        look_name: &loaded.look.name,
        hair: crate::gpu_mesh::HairAlbedo::with_products(loaded.look.mascara.as_ref(), loaded.look.brow_gel.as_ref()),
        occlusion,
    })
}

/// The bare skin of a scene (no layer) baked at `texture_px`: its base colour as the PNG texture
/// [`export_gltf`] writes (sRGB RGB8, rows in glTF's order) and glTF's roughness of its one lobe
/// (the same everywhere). `rouge export web` shows it beside the look.
///
/// # Errors
/// What [`bake_surface`] and the PNG encoder refuse.
pub fn bare_skin_texture(loaded: &Loaded, images: &SkinTextureImages, texture_px: u32) -> Result<(Vec<u8>, f32)> {
    let surface = bake_surface(&skin_surface(loaded, images), &[], texture_px)?;
    let png = encode_png(side(&surface), &base_color_texels(&surface), 3)?;
    Ok((png, gltf_roughness(loaded.scene.skin.roughness)))
}

/// A look's layer as the bake takes it (its thickness as painted).
pub(crate) fn layer_input(l: &rouge_model::look::LookLayer) -> LayerInput<'_> {
    LayerInput { preset: &l.preset, map: &l.map, multiplier: 1.0 }
}

/// The skin of a loaded scene as the bake reads it.
pub(crate) fn skin_surface<'a>(loaded: &Loaded, images: &'a SkinTextureImages) -> SkinSurface<'a> {
    let skin = &loaded.scene.skin;
    SkinSurface {
        albedo: skin.albedo,
        albedo_map: images.albedo.as_ref(),
        beckmann_roughness: skin.roughness,
        ior: skin.ior,
    }
}

fn side(s: &SurfaceMaps) -> (u32, u32) {
    (s.side_px, s.side_px)
}

/// The mesh, refused without triangles or without a UV per vertex.
pub(crate) fn checked(mesh: &TriangleMesh) -> Result<std::borrow::Cow<'_, TriangleMesh>> {
    if mesh.triangle_count() == 0 || mesh.uvs.len() != mesh.positions.len() {
        return Err(RenderError::Invalid(format!(
            "glTF export: the mesh has {} triangles and {} UVs for {} vertices (needs triangles and a UV per vertex)",
            mesh.triangle_count(),
            mesh.uvs.len(),
            mesh.positions.len()
        )));
    }
    Ok(std::borrow::Cow::Borrowed(mesh))
}

/// The mesh with MikkTSpace tangents (generated on a copy when it has none).
fn with_tangents(mesh: &TriangleMesh) -> Result<std::borrow::Cow<'_, TriangleMesh>> {
    checked(mesh)?;
    if mesh.tangents.is_some() {
        return Ok(std::borrow::Cow::Borrowed(mesh));
    }
    let mut m = mesh.clone();
    m.generate_tangents()?;
    Ok(std::borrow::Cow::Owned(m))
}

/// The skin's triangles, and each other part's group (eyes, teeth, tongue, lashes), as
/// primitives of their own vertices, in glTF's conventions: positions in metres, v = 1 − v_OBJ
/// (the repo's loader flips it back). Each part keeps its group's name (the loader makes each
/// glTF mesh a group, and the renderer places an eye's iris and pupil about its group's centre)
/// and carries the renderer's colours per vertex (`gpu_mesh::vertex_albedo`); the skin its
/// tangents when `with_tangents` (a normal texture uses them).
fn primitives(
    mesh: &TriangleMesh,
    skin_albedo: [f32; 3],
    hair: crate::gpu_mesh::HairAlbedo,
    with_tangents: bool,
) -> Vec<Primitive> {
    let albedo = crate::gpu_mesh::vertex_albedo(mesh, skin_albedo, hair);
    // Which primitive each triangle goes to: 0 the skin, i + 1 the i-th group of another part.
    let parts: Vec<_> = mesh.groups.iter().filter(|g| !g.is_skin()).collect();
    let mut part = vec![0usize; mesh.triangle_count()];
    for (i, g) in parts.iter().enumerate() {
        part[g.triangles.clone()].iter_mut().for_each(|p| *p = i + 1);
    }
    let tangents = mesh.tangents.as_deref().filter(|_| with_tangents);
    let names = std::iter::once("skin").chain(parts.iter().map(|g| g.name.as_str()));
    let mut out = Vec::new();
    for (which, name) in names.enumerate() {
        let (is_part, material) = (which > 0, usize::from(which > 0));
        let mut remap = vec![u32::MAX; mesh.positions.len()];
        let mut p = Primitive { name: name.into(), material, ..Primitive::default() };
        let mut colors = Vec::new();
        let mut tangent = Vec::new();
        for (t, tri) in mesh.indices.chunks_exact(3).enumerate() {
            if part[t] != which {
                continue;
            }
            for &v in tri {
                let v = v as usize;
                if remap[v] == u32::MAX {
                    remap[v] = p.positions_m.len() as u32;
                    p.positions_m.push((mesh.positions[v] * 1e-3).to_array());
                    p.normals.push(
                        mesh.normals
                            .get(v)
                            .map_or([0.0, 0.0, 1.0], |n| n.try_normalize().unwrap_or(glam::Vec3::Z).to_array()),
                    );
                    if let Some(t) = tangents {
                        tangent.push(t.get(v).map_or([1.0, 0.0, 0.0, 1.0], |t| t.to_array()));
                    }
                    let uv = mesh.uvs[v];
                    p.uvs.push([uv.x, 1.0 - uv.y]);
                    colors.push([albedo[v][0], albedo[v][1], albedo[v][2]]);
                }
                p.indices.push(remap[v]);
            }
        }
        if is_part {
            p.colors = Some(colors);
        } else if tangents.is_some() {
            p.tangents = Some(tangent);
        }
        if !p.indices.is_empty() {
            out.push(p);
        }
    }
    out
}

/// The base colour plane as sRGB-encoded RGB8.
pub(crate) fn base_color_texels(s: &SurfaceMaps) -> Vec<u8> {
    let lut: Vec<u8> = (0..4096).map(|i| (srgb_encode(i as f64 / 4095.0) * 255.0).round() as u8).collect();
    s.base_color.iter().flat_map(|c| c.map(|v| lut[(v.clamp(0.0, 1.0) * 4095.0).round() as usize])).collect()
}

/// glTF's occlusion and metallic-roughness textures in one (the "ORM" packing glTF's channels
/// allow): R = occlusion (255 without it), G = roughness, B = metallic (0).
fn orm_texels(s: &SurfaceMaps, occlusion: Option<&[f32]>) -> Vec<u8> {
    let byte = |v: f32| (v.clamp(0.0, 1.0) * 255.0).round() as u8;
    let ao = |i: usize| occlusion.and_then(|o| o.get(i)).copied().unwrap_or(1.0);
    s.beckmann_roughness.iter().enumerate().flat_map(|(i, &m)| [byte(ao(i)), byte(gltf_roughness(m)), 0]).collect()
}

/// `KHR_materials_ior` for a surface of index `ior`, unless it is glTF's default.
fn ior_extension(ior: f32) -> Option<Value> {
    ((ior - GLTF_DEFAULT_IOR).abs() > 1e-4).then(|| json!({"ior": num(ior)}))
}

/// `KHR_materials_specular`'s texture (RGBA8, F0 in alpha, linear) and colour factor such that
/// F0(ior) × factor × alpha is each texel's F0 (the extension's `dielectric_f0`): `None` where
/// every texel has the skin's own F0 (nothing to carry).
fn specular_texels(s: &SurfaceMaps, ior: f32) -> Option<(Vec<u8>, f32)> {
    let base = fresnel_f0(ior);
    if base <= 0.0 || s.f0.iter().all(|&f| (f - base).abs() <= 1e-6 * base) {
        return None;
    }
    let max = s.f0.iter().copied().fold(0.0, f32::max);
    let factor = (max / base).max(1.0);
    let texels =
        s.f0.iter().flat_map(|&f| [255, 255, 255, ((f / (base * factor)).clamp(0.0, 1.0) * 255.0).round() as u8]);
    Some((texels.collect(), factor))
}
