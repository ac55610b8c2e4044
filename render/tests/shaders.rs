//! Every WGSL shader variant validates with naga, and the Rust uniform structs have exactly the
//! layout naga computes for their WGSL twins.

use rouge_render::passes::Pass;
use rouge_render::shader::{ThicknessVariant, Variant, shader_source};
use rouge_render::uniforms::uniform_layouts;

fn source(pass: Pass, variant: Variant) -> String {
    shader_source(pass, variant, false).unwrap_or_else(|e| panic!("{pass:?} {variant:?}: {e}"))
}

fn parse_source(pass: Pass, variant: Variant, src: &str) -> naga::Module {
    naga::front::wgsl::parse_str(src).unwrap_or_else(|e| panic!("{pass:?} {variant:?}:\n{}", e.emit_to_string(src)))
}

fn parse(pass: Pass, variant: Variant) -> naga::Module {
    let src = source(pass, variant);
    naga::front::wgsl::parse_str(&src).unwrap_or_else(|e| panic!("{pass:?} {variant:?}:\n{}", e.emit_to_string(&src)))
}

#[test]
fn every_shader_variant_validates() {
    // Each pass depends on part of the variant only (Variant::for_pass): validate every distinct
    // source once, for both display encodings (the hardware's on Vulkan, Metal, DX12, the
    // shader's on GL).
    let mut seen = std::collections::HashSet::new();
    for encode_srgb in [false, true] {
        for variant in Variant::all() {
            for pass in Pass::ALL {
                let key = (pass, variant.for_pass(pass), encode_srgb);
                if !seen.insert(key) {
                    continue;
                }
                let src = shader_source(pass, key.1, encode_srgb).unwrap_or_else(|e| panic!("{pass:?}: {e}"));
                let module = parse_source(pass, key.1, &src);
                let mut validator = naga::valid::Validator::new(
                    naga::valid::ValidationFlags::all(),
                    naga::valid::Capabilities::default(),
                );
                if let Err(e) = validator.validate(&module) {
                    panic!("{pass:?} {:?} encode_srgb {encode_srgb}: {}", key.1, e.emit_to_string(&src));
                }
            }
        }
    }
    assert_eq!(Variant::all().count(), 9 * 96 * 3);
    // G-buffer: 9 layer counts × albedo × normal map × 3 thickness variants; thickness: 3;
    // lighting: 9 × shadows × env × 3 (dipole, atlas); composite: 2 × display; shadow, SSS,
    // depth copy, edge overdraw, the three dipole passes and the atlas gather: 1 each; the atlas
    // irradiance: shadows × env.
    let per_encoding = 9 * 4 * 3 + 3 + 9 * 12 + 2 * 2 + 4 + 3 + 1 + 4;
    assert_eq!(seen.len(), 2 * per_encoding);
}

#[test]
fn variants_compile_only_what_the_scene_uses() {
    let bare = Variant { display: true, ..Variant::BARE };
    let src = source(Pass::Lighting, bare);
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
        thickness: ThicknessVariant::Baked,
        dipole: false,
        atlas: false,
    };
    let src = source(Pass::Lighting, full);
    assert!(src.contains("layer_rt") && src.contains("shadow_factor") && src.contains("fn sh_irradiance"));
    assert!(source(Pass::Gbuffer, full).contains("thickness_b"));
    assert!(!source(Pass::Gbuffer, Variant { layers: 4, ..full }).contains("thickness_b"));
    assert!(source(Pass::Gbuffer, full).contains("textureSampleLevel(normal_map"));
    assert!(!source(Pass::Gbuffer, bare).contains("textureSampleLevel(normal_map"));
    assert!(!source(Pass::Gbuffer, bare).contains("textureSampleLevel(albedo_map"));
    // The display encoding: only the GL variant applies the sRGB curve in the shader.
    let encoded = shader_source(Pass::Composite, bare, true).expect("source");
    assert!(encoded.contains("0.0031308") && !source(Pass::Composite, bare).contains("0.0031308"));
    // The thickness translucency: a G-buffer target and a pass only when a material uses it; the
    // shadow-map source's code only with that source.
    assert!(!source(Pass::Gbuffer, bare).contains("local_thickness:"));
    assert!(source(Pass::Gbuffer, full).contains("textureSampleLevel(local_thickness_map"));
    let light = Variant { thickness: ThicknessVariant::ShadowMap, ..full };
    assert!(!source(Pass::Gbuffer, light).contains("textureSampleLevel(local_thickness_map"));
    assert!(source(Pass::Thickness, light).contains("fn light_path_mm"));
    assert!(!source(Pass::Thickness, full).contains("fn light_path_mm"));
    // The table constant comes from its owner, rouge-measure, not a copy in the WGSL file.
    assert!(!Pass::Lighting.source().contains("const TABLE_X0_MM"));
    assert!(source(Pass::Lighting, full).contains("const TABLE_X0_MM"));
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
        thickness: ThicknessVariant::ShadowMap,
        dipole: true,
        atlas: true,
    };
    // Frame, Light and Layer are in every pass; SssPass in the SSS pass.
    let lighting = parse(Pass::Lighting, variant);
    let sss = parse(Pass::Sss, variant);
    let thickness = parse(Pass::Thickness, variant);
    let edges = parse(Pass::EdgeOverdraw, variant);
    let dipole = parse(Pass::DipoleRadiance, variant);
    let atlas = parse(Pass::AtlasGather, variant);
    for (name, size, fields) in uniform_layouts() {
        let module = match name {
            "SssPass" => &sss,
            "ThicknessPass" => &thickness,
            "EdgePass" => &edges,
            "DipolePass" => &dipole,
            "AtlasPass" => &atlas,
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
