//! `rouge export gltf` end to end: the .glb and the .gltf re-import through the repo's own
//! glTF loader with the triangles and bounds of the mesh `rouge render` draws, carry the bake
//! in their base-colour image (rows in glTF's order), pass the Khronos glTF-Validator with no
//! error and no warning (skipped, saying so, without node or `npm ci --prefix tests/gltf`), and
//! bad options and unwritable paths fail with a message and leave no file behind.

use super::common::{root, rouge, stderr};
use rouge_model::mesh::{Bounds, load_mesh};
use rouge_render::gltf_export::export_job;
use rouge_render::job::{LookChoice, RenderJob};
use std::path::Path;
use std::process::Command;

/// The scene options of the exports here: the default head at one subdivision level with the
/// default look over the light tone's flat colour, textures of 256².
const SCENE: [&str; 6] = ["--subdiv", "1", "--flat-skin", "--textures", "256", "--out"];

/// The job `rouge render` runs with [`SCENE`]'s options (the studio's skin colour).
fn job() -> RenderJob {
    RenderJob { subdivision: 1, look: LookChoice::Default, ..RenderJob::default() }
}

/// The JSON and binary chunks of a .glb.
fn glb_chunks(bytes: &[u8]) -> (serde_json::Value, &[u8]) {
    let u32_at = |i: usize| u32::from_le_bytes(bytes[i..i + 4].try_into().expect("4 bytes")) as usize;
    assert_eq!(&bytes[0..4], b"glTF");
    assert_eq!(u32_at(8), bytes.len(), "header length");
    let json_len = u32_at(12);
    let json = serde_json::from_slice(&bytes[20..20 + json_len]).expect("JSON chunk");
    let bin_at = 20 + json_len;
    assert_eq!(&bytes[bin_at + 4..bin_at + 8], b"BIN\0");
    (json, &bytes[bin_at + 8..bin_at + 8 + u32_at(bin_at)])
}

/// Runs the Khronos glTF-Validator on `files` through tests/gltf/validate.mjs, or says why not.
fn validate(files: &[&Path]) {
    let dir = root().join("tests/gltf");
    if !dir.join("node_modules/gltf-validator").is_dir() {
        eprintln!("SKIPPED glTF-Validator: tests/gltf/node_modules is absent (run `npm ci --prefix tests/gltf`)");
        return;
    }
    let o = match Command::new("node").arg(dir.join("validate.mjs")).args(files).output() {
        Ok(o) => o,
        Err(e) => {
            eprintln!("SKIPPED glTF-Validator: cannot run node ({e})");
            return;
        }
    };
    let out = String::from_utf8_lossy(&o.stdout);
    assert!(o.status.success(), "glTF-Validator found errors or warnings:\n{out}\n{}", stderr(&o));
    for line in out.lines() {
        let report: serde_json::Value = serde_json::from_str(line).expect("a report per file");
        assert_eq!((report["numErrors"].as_u64(), report["numWarnings"].as_u64()), (Some(0), Some(0)), "{line}");
        eprintln!(
            "glTF-Validator {}: {} errors, {} warnings, {} infos, {} hints for {}",
            report["validatorVersion"],
            report["numErrors"],
            report["numWarnings"],
            report["numInfos"],
            report["numHints"],
            report["file"]
        );
    }
}

#[test]
fn glb_and_gltf_reimport_with_the_drawn_mesh_carry_the_bake_and_validate() {
    let dir = tempfile::tempdir().expect("temp dir");
    let glb = dir.path().join("face.glb");
    let gltf = dir.path().join("face.gltf");
    for out in [&glb, &gltf] {
        let mut args = vec!["export", "gltf"];
        args.extend(SCENE);
        args.push(out.to_str().expect("utf-8"));
        let o = rouge(&args);
        assert!(o.status.success(), "{}", stderr(&o));
        assert!(stderr(&o).contains("triangles"), "{}", stderr(&o));
    }
    // Beside the .gltf, its companions named by their content (`STEM_NAME.<16 hex>.png`).
    let names: Vec<String> = std::fs::read_dir(dir.path())
        .expect("dir")
        .map(|e| e.expect("entry").file_name().to_string_lossy().into())
        .collect();
    let mut kinds: Vec<String> = names
        .iter()
        .map(|n| {
            ["bin", "png"]
                .iter()
                .find_map(|ext| rouge_measure::file_set::content_tag_stem(n, ext).map(|s| format!("{s}.{ext}")))
                .unwrap_or_else(|| n.clone())
        })
        .collect();
    kinds.sort();
    assert_eq!(
        kinds,
        [
            "face.bin",
            "face.glb",
            "face.gltf",
            "face_base_color.png",
            "face_occlusion_roughness_metallic.png",
            "face_specular.png"
        ],
        "no temporary file is left: {names:?}"
    );

    // The repo's loader reads both back (metres → mm): the triangles and bounds of the drawn mesh.
    let drawn = job().load().expect("the scene").mesh;
    let drawn_bounds = Bounds::of(&drawn.positions).expect("bounds");
    for file in [&glb, &gltf] {
        let back = load_mesh(Some(file), 1000.0, 0).expect("re-import");
        assert_eq!(back.triangle_count(), drawn.triangle_count(), "{}", file.display());
        let b = Bounds::of(&back.positions).expect("bounds");
        assert!(
            b.min.abs_diff_eq(drawn_bounds.min, 1e-3) && b.max.abs_diff_eq(drawn_bounds.max, 1e-3),
            "{b:?} vs {drawn_bounds:?}"
        );
        assert!(back.groups.iter().any(|g| g.is_eye()), "the eyes stay eyes: {:?}", back.groups);
    }

    // The .glb's base colour is the bake, row 0 at glTF's v = 0 (the mesh's v = 1).
    let bytes = std::fs::read(&glb).expect("glb");
    let (json, bin) = glb_chunks(&bytes);
    let image =
        json["images"].as_array().expect("images").iter().find(|i| i["name"] == "base_color").expect("base colour");
    let view = &json["bufferViews"][image["bufferView"].as_u64().expect("view") as usize];
    let (at, len) =
        (view["byteOffset"].as_u64().unwrap_or(0) as usize, view["byteLength"].as_u64().expect("length") as usize);
    let png = image::load_from_memory(&bin[at..at + len]).expect("PNG").to_rgb8();
    assert_eq!(png.dimensions(), (256, 256));
    let baked = export_job(&job(), 256, false).expect("in-process export").surface;
    let lips = rouge_model::look::Region::Lips.mask();
    let (u, v) = (0..lips.mm.len())
        .max_by(|&a, &b| lips.mm[a].total_cmp(&lips.mm[b]))
        .map(|i| ((i as u32 % lips.width) as f32 + 0.5, (i as u32 / lips.width) as f32 + 0.5))
        .map(|(x, y)| (x / lips.width as f32, 1.0 - y / lips.height as f32))
        .expect("lips");
    let expect = baked
        .texel_at_uv(u, v)
        .base_color
        .map(|c| (rouge_measure::colorimetry::srgb_encode(f64::from(c)) * 255.0).round() as i32);
    let (x, y) = ((u * 256.0) as u32, ((1.0 - v) * 256.0) as u32);
    let got = png.get_pixel(x, y).0.map(i32::from);
    assert!(got.iter().zip(expect).all(|(a, b)| (a - b).abs() <= 1), "lips texel {got:?} vs the bake {expect:?}");
    assert!(got[0] > got[1] + 40, "the lips are red in the file: {got:?}");
    assert!(json["extensionsUsed"].as_array().is_some_and(|e| e.iter().any(|x| x == "KHR_materials_specular")));

    // Every image is named as the writer knows its images (it removes an earlier export's by
    // these names).
    for image in json["images"].as_array().expect("images") {
        let name = image["name"].as_str().expect("a name");
        assert!(rouge_render::gltf_export::document::IMAGE_NAMES.contains(&name), "{name}");
    }

    // Occlusion in the roughness texture's red channel: the eyelids, under the brow ridge and
    // over the eyeball, see less sky than the cheeks, which see nearly all of it.
    let skin = &json["materials"][0];
    assert_eq!(skin["occlusionTexture"]["index"], skin["pbrMetallicRoughness"]["metallicRoughnessTexture"]["index"]);
    let orm = json["images"]
        .as_array()
        .expect("images")
        .iter()
        .find(|i| i["name"] == "occlusion_roughness_metallic")
        .expect("occlusion-roughness-metallic");
    let view = &json["bufferViews"][orm["bufferView"].as_u64().expect("view") as usize];
    let (at, len) =
        (view["byteOffset"].as_u64().unwrap_or(0) as usize, view["byteLength"].as_u64().expect("length") as usize);
    let orm = image::load_from_memory(&bin[at..at + len]).expect("PNG").to_rgb8();
    let mean_occlusion = |region: rouge_model::look::Region| {
        let mask = region.mask().resized(256, 256);
        let inside: Vec<f32> = orm
            .enumerate_pixels()
            .filter(|(x, y, _)| mask.mm[(y * 256 + x) as usize] > 0.0)
            .map(|p| f32::from(p.2.0[0]) / 255.0)
            .collect();
        inside.iter().sum::<f32>() / inside.len().max(1) as f32
    };
    let (lids, cheeks) =
        (mean_occlusion(rouge_model::look::Region::Eyelids), mean_occlusion(rouge_model::look::Region::Cheeks));
    assert!(cheeks > 0.8 && lids < cheeks - 0.05, "occlusion: eyelids {lids}, cheeks {cheeks}");

    validate(&[&glb, &gltf]);
}

#[test]
fn bad_textures_and_unwritable_paths_fail_naming_them_and_leave_no_file() {
    let dir = tempfile::tempdir().expect("temp dir");
    let out = dir.path().join("face.glb");
    let o = rouge(&["export", "gltf", "--textures", "300", "--out", out.to_str().expect("utf-8")]);
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
    assert!(stderr(&o).contains("--textures"), "{}", stderr(&o));
    let o = rouge(&[
        "export",
        "gltf",
        "--subdiv",
        "0",
        "--flat-skin",
        "--out",
        dir.path().join("face.obj").to_str().expect("utf-8"),
    ]);
    assert_eq!(o.status.code(), Some(2));
    assert!(stderr(&o).contains("--out") && stderr(&o).contains(".glb"), "{}", stderr(&o));

    // The output's name is taken by a folder with a file in it: the rename fails, the folder
    // and its file stay as they were, and no temporary file is left.
    std::fs::create_dir(&out).expect("folder");
    std::fs::write(out.join("keep.txt"), b"previous").expect("file");
    let mut args = vec!["export", "gltf", "--subdiv", "0", "--flat-skin", "--textures", "256", "--out"];
    args.push(out.to_str().expect("utf-8"));
    let o = rouge(&args);
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
    assert!(stderr(&o).contains("face.glb") && stderr(&o).contains("cannot write"), "{}", stderr(&o));
    assert_eq!(std::fs::read(out.join("keep.txt")).expect("kept"), b"previous");
    let left: Vec<_> = std::fs::read_dir(dir.path()).expect("dir").map(|e| e.expect("entry").file_name()).collect();
    assert_eq!(left, [std::ffi::OsString::from("face.glb")], "only the folder is there");

    // A folder that does not exist: nothing is written anywhere.
    let missing = dir.path().join("no/such/face.gltf");
    args.pop();
    args.push(missing.to_str().expect("utf-8"));
    let o = rouge(&args);
    assert_eq!(o.status.code(), Some(2));
    assert!(stderr(&o).contains("no/such/face"), "{}", stderr(&o));
}

#[test]
fn a_gloss_layer_becomes_a_clearcoat_over_the_lobe_of_the_layers_under_it() {
    let dir = tempfile::tempdir().expect("temp dir");
    let gloss = root().join("data/finishes/lipstick_02_red_gloss.json");
    let look = dir.path().join("gloss.json");
    let text = format!(
        r#"{{"schema": "rouge-look", "version": 1, "name": "gloss", "layers": [
            {{"preset": "builtin:foundation_02_ivory", "thickness": {{"uniform_mm": 0.015}}}},
            {{"preset": {:?}, "thickness": {{"region": "lips", "thickness_mm": 0.01}}}}]}}"#,
        gloss.to_str().expect("utf-8")
    );
    std::fs::write(&look, text).expect("look");
    let glb = dir.path().join("gloss.glb");
    // Without the occlusion (`--no-occlusion`): no occlusionTexture, and the texture is the
    // plain metallic-roughness one.
    let mut args = vec!["export", "gltf", "--no-occlusion", "--look", look.to_str().expect("utf-8")];
    args.extend(SCENE);
    args.push(glb.to_str().expect("utf-8"));
    let o = rouge(&args);
    assert!(o.status.success(), "{}", stderr(&o));
    let bytes = std::fs::read(&glb).expect("glb");
    let (json, bin) = glb_chunks(&bytes);
    assert!(json["materials"][0].get("occlusionTexture").is_none(), "{}", json["materials"][0]);
    assert!(json["extensionsUsed"].as_array().is_some_and(|e| e.iter().any(|x| x == "KHR_materials_clearcoat")));
    let coat = &json["materials"][0]["extensions"]["KHR_materials_clearcoat"];
    let preset = rouge_measure::preset::Preset::load(&gloss).expect("the gloss preset");
    let want = (preset.specular.roughness as f32).sqrt();
    assert!((coat["clearcoatRoughnessFactor"].as_f64().expect("roughness") as f32 - want).abs() < 1e-6, "{coat}");
    let image = |name: &str| {
        let images = json["images"].as_array().expect("images");
        let i = images.iter().find(|i| i["name"] == name).unwrap_or_else(|| panic!("no {name} image"));
        let view = &json["bufferViews"][i["bufferView"].as_u64().expect("view") as usize];
        let at = view["byteOffset"].as_u64().unwrap_or(0) as usize;
        let len = view["byteLength"].as_u64().expect("length") as usize;
        image::load_from_memory(&bin[at..at + len]).expect("PNG").to_rgb8()
    };
    let index = coat["clearcoatTexture"]["index"].as_u64().expect("texture") as usize;
    assert_eq!(json["images"][index]["name"], "clearcoat");
    // Full where the gloss covers, none outside the lips; the lobe under it is the foundation's,
    // not the gloss's.
    let (weight, rough) = (image("clearcoat"), image("metallic_roughness"));
    let lips = rouge_model::look::Region::Lips.mask().resized(256, 256);
    let coated: Vec<(u32, u32, u8)> =
        weight.enumerate_pixels().map(|(x, y, p)| (x, y, p.0[0])).filter(|c| c.2 > 0).collect();
    assert!(coated.iter().filter(|c| c.2 == 255).count() > 20, "the coat covers the lips: {} texels", coated.len());
    assert!(coated.iter().all(|&(x, y, _)| lips.mm[(y * 256 + x) as usize] > 0.0), "a coat outside the lips");
    let foundation = rouge_model::look::builtin_preset("foundation_02_ivory").expect("foundation");
    let under = (foundation.specular.roughness as f32).sqrt();
    for &(x, y, _) in coated.iter().filter(|c| c.2 == 255) {
        let got = f32::from(rough.get_pixel(x, y).0[1]) / 255.0;
        assert!(
            (got - under).abs() < 0.01,
            "base roughness {got} at ({x}, {y}): the foundation's is {under}, the gloss's {want}"
        );
    }
    validate(&[&glb]);
}
