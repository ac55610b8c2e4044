//! The shaders' tests: every WGSL shader variant validates with naga, and the Rust uniform structs have exactly the
//! layout naga computes for their WGSL twins.

use super::{PassShader, ThicknessVariant, Variant, shader_source};
use crate::passes::FramePass;
use crate::passes::composite::CompositePass;
use crate::passes::cube_atlas::AtlasUniform;
use crate::passes::cube_atlas::gather::AtlasGatherPass;
use crate::passes::dipole::DipoleUniform;
use crate::passes::dipole::radiance::DipoleRadiancePass;
use crate::passes::edge_overdraw::EdgeOverdrawPass;
use crate::passes::edge_overdraw::EdgeUniform;
use crate::passes::gbuffer::GbufferPass;
use crate::passes::lighting::LightingPass;
use crate::passes::sss::SssPass;
use crate::passes::sss::SssUniform;
use crate::passes::thickness::{ThicknessPass, ThicknessUniform};
use crate::uniforms::{FrameUniform, LayerUniform, LightUniform};

const LIGHTING: &PassShader = &LightingPass::SHADER;
const GBUFFER: &PassShader = &GbufferPass::SHADER;
const COMPOSITE: &PassShader = &CompositePass::SHADER;
const THICKNESS: &PassShader = &ThicknessPass::SHADER;

fn source(pass: &PassShader, variant: Variant) -> String {
    shader_source(pass, variant, false).unwrap_or_else(|e| panic!("{} {variant:?}: {e}", pass.owner))
}

fn parse_source(pass: &PassShader, variant: Variant, src: &str) -> naga::Module {
    naga::front::wgsl::parse_str(src)
        .unwrap_or_else(|e| panic!("{} {variant:?}:\n{}", pass.owner, e.emit_to_string(src)))
}

fn parse(pass: &PassShader, variant: Variant) -> naga::Module {
    parse_source(pass, variant, &source(pass, variant))
}

#[test]
fn every_shader_variant_validates() {
    // Each pass depends on part of the variant only (PassShader::reduce): validate every distinct
    // source once, for both display encodings (the hardware's on Vulkan, Metal, DX12, the
    // shader's on GL).
    let mut seen = std::collections::HashSet::new();
    for half_linear in [false, true] {
        for variant in Variant::all() {
            for pass in crate::passes::SHADERS {
                let key = (pass.owner, (pass.reduce)(variant), half_linear);
                if !seen.insert(key) {
                    continue;
                }
                let src = shader_source(pass, key.1, half_linear).unwrap_or_else(|e| panic!("{}: {e}", pass.owner));
                let module = parse_source(pass, key.1, &src);
                let mut validator = naga::valid::Validator::new(
                    naga::valid::ValidationFlags::all(),
                    naga::valid::Capabilities::default(),
                );
                if let Err(e) = validator.validate(&module) {
                    panic!("{} {:?} half_linear {half_linear}: {}", pass.owner, key.1, e.emit_to_string(&src));
                }
            }
        }
    }
    assert_eq!(Variant::all().count(), 9 * 384 * 4);
    // G-buffer: 9 layer counts × albedo × normal map × skin detail × 3 thickness variants (the
    // slab law's is the shadow map's), and the 8 with layers again with glitter; thickness: 4; lighting: 9 × shadows × env × 3
    // (dipole, atlas), and the 8 with layers again with glitter; composite: 2 × display × hair;
    // shadow, back-face depth, SSS, depth copy, edge overdraw, the three dipole passes, the atlas
    // gather and the bounce: 1 each; the atlas irradiance and the hair: shadows × env.
    let per_encoding = 9 * 8 * 3 + 8 * 8 * 3 + 4 + 9 * 12 + 8 * 12 + 2 * 2 * 2 + 5 + 3 + 1 + 1 + 4 + 4;
    assert_eq!(seen.len(), 2 * per_encoding);
}

#[test]
fn variants_compile_only_what_the_scene_uses() {
    let bare = Variant { display: true, ..Variant::BARE };
    let src = source(LIGHTING, bare);
    assert!(!src.contains("layer_rt"), "a bare look must not carry the layer tables");
    assert!(!src.contains("shadow_factor"), "no shadow code without a shadowing light");
    assert!(!src.contains("fn sh_irradiance"), "no SH code without an environment");
    let full = Variant {
        layers: 5,
        shadows: true,
        env: true,
        display: true,
        albedo_map: true,
        normal_map: true,
        skin_detail: true,
        thickness: ThicknessVariant::Baked,
        dipole: false,
        atlas: false,
        glitter: true,
        hair: true,
    };
    let src = source(LIGHTING, full);
    assert!(src.contains("layer_rt") && src.contains("shadow_factor") && src.contains("fn sh_irradiance"));
    assert!(source(GBUFFER, full).contains("thickness_b"));
    assert!(!source(GBUFFER, Variant { layers: 4, ..full }).contains("thickness_b"));
    assert!(source(GBUFFER, full).contains("textureSampleLevel(normal_map"));
    assert!(!source(GBUFFER, bare).contains("textureSampleLevel(normal_map"));
    assert!(source(GBUFFER, full).contains("detail_tile") && !source(GBUFFER, bare).contains("detail_tile"));
    assert!(!source(GBUFFER, bare).contains("textureSampleLevel(albedo_map"));
    // Glitter: its code and its G-buffer target only in a look with glitter.
    let plain = Variant { glitter: false, ..full };
    assert!(
        source(LIGHTING, full).contains("fn pixel_sparkle") && !source(LIGHTING, plain).contains("fn pixel_sparkle")
    );
    assert!(
        source(GBUFFER, full).contains("@location(5) glitter")
            && !source(GBUFFER, plain).contains("@location(5) glitter")
    );
    // The output image: RGBA8 for display, else the backend's linear format (half floats on GL).
    let linear = Variant { display: false, ..bare };
    assert!(source(COMPOSITE, bare).contains("var out_image: texture_storage_2d<rgba8unorm, write>"));
    assert!(source(COMPOSITE, linear).contains("var out_image: LinearImage"));
    let half = shader_source(COMPOSITE, linear, true).expect("source");
    assert!(half.contains("<rgba16float, write>") && !half.contains("<rgba32float, write>"));
    assert!(source(COMPOSITE, linear).contains("<rgba32float, write>"));
    // The thickness translucency: a G-buffer target and a pass only when a material uses it; the
    // shadow-map source's code only with that source.
    assert!(!source(GBUFFER, bare).contains("local_thickness:"));
    assert!(source(GBUFFER, full).contains("textureSampleLevel(local_thickness_map"));
    let light = Variant { thickness: ThicknessVariant::ShadowMap, ..full };
    assert!(!source(GBUFFER, light).contains("textureSampleLevel(local_thickness_map"));
    assert!(source(THICKNESS, light).contains("fn light_path_mm"));
    assert!(!source(THICKNESS, full).contains("fn light_path_mm"));
    // The table constant comes from its owner, rouge-measure, not a copy in the WGSL file.
    assert!(!LIGHTING.source.contains("const TABLE_X0_MM"));
    assert!(source(LIGHTING, full).contains("const TABLE_X0_MM"));
}

#[test]
fn rust_and_wgsl_uniform_layouts_match() {
    let variant = Variant {
        layers: 8,
        shadows: true,
        env: true,
        display: true,
        albedo_map: true,
        normal_map: true,
        skin_detail: true,
        thickness: ThicknessVariant::ShadowMap,
        dipole: true,
        atlas: true,
        glitter: true,
        hair: true,
    };
    // Frame, Light and Layer are in every pass; SssPass in the SSS pass.
    let lighting = parse(LIGHTING, variant);
    let sss = parse(&SssPass::SHADER, variant);
    let thickness = parse(THICKNESS, variant);
    let edges = parse(&EdgeOverdrawPass::SHADER, variant);
    let hair = parse(&crate::passes::hair::HairPass::SHADER, variant);
    let dipole = parse(&DipoleRadiancePass::SHADER, variant);
    let atlas = parse(&AtlasGatherPass::SHADER, variant);
    let bounce = parse(&crate::passes::bounce::BouncePass::SHADER, variant);
    for (name, size, fields) in uniform_layouts() {
        let module = match name {
            "SssPass" => &sss,
            "ThicknessPass" => &thickness,
            "EdgePass" => &edges,
            "HairPass" => &hair,
            "DipolePass" => &dipole,
            "AtlasPass" => &atlas,
            "BouncePass" => &bounce,
            _ => &lighting,
        };
        let mut layouter = naga::proc::Layouter::default();
        layouter.update(module.to_ctx()).expect("layout");
        let (handle, ty) = module
            .types
            .iter()
            .find(|(_, t)| t.name.as_deref() == Some(name))
            .unwrap_or_else(|| panic!("no WGSL struct {name}"));
        let naga::TypeInner::Struct { members, span } = &ty.inner else { panic!("{name} is not a struct") };
        assert_eq!(*span as usize, size, "{name}: WGSL size {span} vs Rust {size}");
        assert_eq!(layouter[handle].size as usize, size);
        let wgsl: Vec<(String, usize)> =
            members.iter().map(|m| (m.name.clone().unwrap_or_default(), m.offset as usize)).collect();
        let rust: Vec<(String, usize)> = fields.iter().map(|(n, o)| (n.to_string(), *o)).collect();
        assert_eq!(wgsl, rust, "{name}: member names and offsets");
    }
}

/// A uniform struct's WGSL name, size in bytes, and (field, offset) pairs.
type UniformLayout = (&'static str, usize, Vec<(&'static str, usize)>);

/// Field offsets of the uniforms, for the layout test against naga's view of the WGSL.
fn uniform_layouts() -> Vec<UniformLayout> {
    use crate::passes::bounce::BounceUniform;
    use crate::passes::hair::HairUniform;
    use std::mem::{offset_of, size_of};
    vec![
        ("BouncePass", size_of::<BounceUniform>(), vec![("params", offset_of!(BounceUniform, params))]),
        (
            "HairPass",
            size_of::<HairUniform>(),
            vec![
                ("params", offset_of!(HairUniform, params)),
                ("lash_sigma_a", offset_of!(HairUniform, lash_sigma_a)),
                ("lash_albedo", offset_of!(HairUniform, lash_albedo)),
                ("brow_sigma_a", offset_of!(HairUniform, brow_sigma_a)),
                ("brow_albedo", offset_of!(HairUniform, brow_albedo)),
                ("fibre", offset_of!(HairUniform, fibre)),
            ],
        ),
        (
            "Frame",
            size_of::<FrameUniform>(),
            vec![
                ("view_proj", offset_of!(FrameUniform, view_proj)),
                ("inv_view_proj", offset_of!(FrameUniform, inv_view_proj)),
                ("view", offset_of!(FrameUniform, view)),
                ("camera_pos", offset_of!(FrameUniform, camera_pos)),
                ("viewport", offset_of!(FrameUniform, viewport)),
                ("projection", offset_of!(FrameUniform, projection)),
                ("skin", offset_of!(FrameUniform, skin)),
                ("sss", offset_of!(FrameUniform, sss)),
                ("background", offset_of!(FrameUniform, background)),
                ("counts", offset_of!(FrameUniform, counts)),
                ("wrinkles", offset_of!(FrameUniform, wrinkles)),
                ("sh", offset_of!(FrameUniform, sh)),
                ("lights", offset_of!(FrameUniform, lights)),
                ("layers", offset_of!(FrameUniform, layers)),
                ("surface", offset_of!(FrameUniform, surface)),
            ],
        ),
        (
            "Light",
            size_of::<LightUniform>(),
            vec![
                ("position", offset_of!(LightUniform, position)),
                ("color", offset_of!(LightUniform, color)),
                ("shadow", offset_of!(LightUniform, shadow)),
                ("translucency", offset_of!(LightUniform, translucency)),
                ("shadow_view_proj", offset_of!(LightUniform, shadow_view_proj)),
            ],
        ),
        (
            "Layer",
            size_of::<LayerUniform>(),
            vec![
                ("params", offset_of!(LayerUniform, params)),
                ("film", offset_of!(LayerUniform, film)),
                ("glitter", offset_of!(LayerUniform, glitter)),
                ("glitter_color", offset_of!(LayerUniform, glitter_color)),
            ],
        ),
        (
            "DipolePass",
            size_of::<DipoleUniform>(),
            vec![
                ("channel", offset_of!(DipoleUniform, channel)),
                ("extra", offset_of!(DipoleUniform, extra)),
                ("boundary", offset_of!(DipoleUniform, boundary)),
                ("classic", offset_of!(DipoleUniform, classic)),
                ("sampling", offset_of!(DipoleUniform, sampling)),
                ("fixes", offset_of!(DipoleUniform, fixes)),
                ("counts", offset_of!(DipoleUniform, counts)),
                ("light_view_proj", offset_of!(DipoleUniform, light_view_proj)),
                ("light_inv_view_proj", offset_of!(DipoleUniform, light_inv_view_proj)),
                ("light_info", offset_of!(DipoleUniform, light_info)),
                ("dir_view_proj", offset_of!(DipoleUniform, dir_view_proj)),
                ("dir_axis", offset_of!(DipoleUniform, dir_axis)),
                ("dir_planes", offset_of!(DipoleUniform, dir_planes)),
            ],
        ),
        (
            "AtlasPass",
            size_of::<AtlasUniform>(),
            vec![
                ("view_proj", offset_of!(AtlasUniform, view_proj)),
                ("axis", offset_of!(AtlasUniform, axis)),
                ("right", offset_of!(AtlasUniform, right)),
                ("up", offset_of!(AtlasUniform, up)),
                ("cube", offset_of!(AtlasUniform, cube)),
                ("medium", offset_of!(AtlasUniform, medium)),
                ("params", offset_of!(AtlasUniform, params)),
                ("settings", offset_of!(AtlasUniform, settings)),
                ("kernel", offset_of!(AtlasUniform, kernel)),
                ("sh_fresnel", offset_of!(AtlasUniform, sh_fresnel)),
            ],
        ),
        (
            "ThicknessPass",
            size_of::<ThicknessUniform>(),
            vec![
                ("materials", offset_of!(ThicknessUniform, materials)),
                ("falloff", offset_of!(ThicknessUniform, falloff)),
                ("kind", offset_of!(ThicknessUniform, kind)),
                ("slab_albedo", offset_of!(ThicknessUniform, slab_albedo)),
                ("slab_kappa", offset_of!(ThicknessUniform, slab_kappa)),
                ("slab_sigma_t", offset_of!(ThicknessUniform, slab_sigma_t)),
                ("slab_axes", offset_of!(ThicknessUniform, slab_axes)),
                ("gather_medium", offset_of!(ThicknessUniform, gather_medium)),
                ("gather", offset_of!(ThicknessUniform, gather)),
                ("screen_kernel", offset_of!(ThicknessUniform, screen_kernel)),
            ],
        ),
        (
            "EdgePass",
            size_of::<EdgeUniform>(),
            vec![("params", offset_of!(EdgeUniform, params)), ("flags", offset_of!(EdgeUniform, flags))],
        ),
        (
            "SssPass",
            size_of::<SssUniform>(),
            vec![
                ("dir", offset_of!(SssUniform, dir)),
                ("count", offset_of!(SssUniform, count)),
                ("samples", offset_of!(SssUniform, samples)),
            ],
        ),
    ]
}
