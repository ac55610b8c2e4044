//! Every WGSL shader variant validates with naga, and the Rust uniform structs have exactly the
//! layout naga computes for their WGSL twins.

use rouge_render::passes::Pass;
use rouge_render::shader::{Variant, shader_source};
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
    let mut count = 0;
    // Both display encodings: the hardware's (Vulkan, Metal, DX12) and the shader's (GL).
    for encode_srgb in [false, true] {
        for variant in Variant::all() {
            for pass in Pass::ALL {
                let src = shader_source(pass, variant, encode_srgb).unwrap_or_else(|e| panic!("{pass:?}: {e}"));
                let module = parse_source(pass, variant, &src);
                let mut validator = naga::valid::Validator::new(
                    naga::valid::ValidationFlags::all(),
                    naga::valid::Capabilities::default(),
                );
                if let Err(e) = validator.validate(&module) {
                    panic!("{pass:?} {variant:?} encode_srgb {encode_srgb}: {}", e.emit_to_string(&src));
                }
                count += 1;
            }
        }
    }
    assert_eq!(count, 2 * 9 * 32 * Pass::ALL.len());
}

#[test]
fn variants_compile_only_what_the_scene_uses() {
    let bare = Variant { layers: 0, shadows: false, env: false, display: true, albedo_map: false, normal_map: false };
    let src = source(Pass::Lighting, bare);
    assert!(!src.contains("layer_rt"), "a bare look must not carry the layer tables");
    assert!(!src.contains("shadow_factor"), "no shadow code without a shadowing light");
    assert!(!src.contains("fn sh_irradiance"), "no SH code without an environment");
    let full = Variant { layers: 5, shadows: true, env: true, display: true, albedo_map: true, normal_map: true };
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
    // The table constant comes from its owner, rouge-measure, not a copy in the WGSL file.
    assert!(!Pass::Lighting.source().contains("const TABLE_X0_MM"));
    assert!(source(Pass::Lighting, full).contains("const TABLE_X0_MM"));
}

#[test]
fn rust_and_wgsl_uniform_layouts_match() {
    let variant = Variant { layers: 8, shadows: true, env: true, display: true, albedo_map: true, normal_map: true };
    // Frame, Light and Layer are in every pass; SssPass in the SSS pass.
    let lighting = parse(Pass::Lighting, variant);
    let sss = parse(Pass::Sss, variant);
    for (name, size, fields) in uniform_layouts() {
        let module = if name == "SssPass" { &sss } else { &lighting };
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
