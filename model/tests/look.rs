//! Integration tests of the look document (`rouge-look` v1): the default look, JSON round trips,
//! the example looks in data/looks, path resolution, region masks on the default head, PNG and
//! EXR thickness maps, and the error messages.

use std::path::{Path, PathBuf};

use exr::prelude::{AnyChannel, AnyChannels, FlatSamples, Image, SmallVec, WritableImage, f16};
use glam::Vec3;
use rouge_model::load_obj;
use rouge_model::look::{
    Look, LookLayer, Region, SCHEMA, ThicknessMap, ThicknessSource, VERSION, builtin_preset, builtin_preset_names,
};

fn repo() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("..")
}

/// Writes `json` as `look.json` in `dir` and returns the load error's message.
fn load_err(dir: &Path, json: &str) -> String {
    let path = dir.join("look.json");
    std::fs::write(&path, json).expect("write the look");
    let e = Look::load(&path).expect_err("the look must be refused").to_string();
    assert!(e.starts_with(&path.display().to_string()), "the message must name the look file: {e}");
    e
}

/// A look document with one layer per entry of `layers` (JSON objects).
fn look_json(layers: &[&str]) -> String {
    format!(r#"{{ "schema": "rouge-look", "version": 1, "name": "t", "layers": [{}] }}"#, layers.join(", "))
}

fn write_png_u16(path: &Path, w: u32, h: u32, v: Vec<u16>) {
    image::ImageBuffer::<image::Luma<u16>, Vec<u16>>::from_raw(w, h, v)
        .expect("w * h values")
        .save(path)
        .expect("write the PNG");
}

fn close(a: f32, b: f32, tol: f32) -> bool {
    (a - b).abs() <= tol
}

#[test]
fn default_look_has_foundation_blush_lipstick_in_order() {
    let look = Look::default_look();
    assert_eq!(look.name, "Default");
    let refs: Vec<&str> = look.layers.iter().map(|l| l.preset_ref.as_str()).collect();
    assert_eq!(refs, ["builtin:foundation_02_ivory", "builtin:blush_01_petal", "builtin:lipstick_02_red"]);
    assert_eq!(look.layers[0].thickness, ThicknessSource::Uniform { mm: 0.015 });
    assert_eq!(look.layers[1].thickness, ThicknessSource::Region { region: Region::Cheeks, mm: 0.008 });
    assert_eq!(look.layers[2].thickness, ThicknessSource::Region { region: Region::Lips, mm: 0.02 });
    assert_eq!(look.layers[0].map, ThicknessMap::uniform(0.015));
    assert_eq!((look.layers[1].map.width, look.layers[1].map.height), (1024, 1024));
    assert!(close(look.layers[1].map.max_mm(), 0.008, 1e-6));
    assert!(close(look.layers[2].map.max_mm(), 0.02, 1e-6));
    for l in &look.layers {
        assert!(l.visible);
        assert_eq!(l.name, l.preset.name, "default layer names are the presets' names");
    }
    assert_eq!(look.visible_layers().count(), 3);
    assert!(Look::bare().layers.is_empty());
}

#[test]
fn builtin_presets_are_the_thirteen_of_data_presets() {
    let names = builtin_preset_names();
    assert_eq!(names.len(), 13);
    for name in names {
        let p = builtin_preset(name).unwrap_or_else(|| panic!("built-in {name} does not load"));
        let file = rouge_measure::preset::Preset::load(&repo().join(format!("data/presets/{name}.json"))).unwrap();
        assert_eq!(p, file, "{name}");
    }
    let mut on_disk: Vec<String> = std::fs::read_dir(repo().join("data/presets"))
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|e| e == "json"))
        .map(|p| p.file_stem().unwrap().to_string_lossy().into_owned())
        .collect();
    on_disk.sort();
    assert_eq!(on_disk, names);
    assert!(builtin_preset("foundation_02").is_none());
}

#[test]
fn json_round_trip_of_the_default_look() {
    let look = Look::default_look();
    let text = look.to_json();
    assert!(text.contains(&format!("\"schema\": \"{SCHEMA}\"")) && text.contains(&format!("\"version\": {VERSION}")));
    let back = Look::from_json(&text, Path::new("anywhere/default.json")).unwrap();
    assert_eq!(back, look);
    assert_eq!(back.to_json(), text);
}

#[test]
fn json_round_trip_keeps_names_hidden_layers_and_map_references() {
    let dir = tempfile::tempdir().unwrap();
    std::fs::create_dir(dir.path().join("maps")).unwrap();
    write_png_u16(&dir.path().join("maps/m.png"), 2, 1, vec![0, 65535]);
    ThicknessMap { width: 2, height: 2, mm: vec![0.0, 0.01, 0.02, 0.03] }.save_exr(&dir.path().join("t.exr")).unwrap();
    let json = look_json(&[
        r#"{ "name": "Base", "preset": "builtin:foundation_01_porcelain", "thickness": { "uniform_mm": 0.0125 } }"#,
        r#"{ "preset": "builtin:blush_02_coral", "visible": false, "thickness": { "mask": "maps/m.png", "thickness_mm": 0.01 } }"#,
        r#"{ "preset": "builtin:lipstick_01_nude", "thickness": { "map": "t.exr" } }"#,
        r#"{ "preset": "builtin:eyeshadow_02_sapphire", "thickness": { "map": "maps/m.png", "scale_mm": 0.004 } }"#,
    ]);
    let path = dir.path().join("look.json");
    let look = Look::from_json(&json, &path).unwrap();
    assert_eq!(look.layers[0].name, "Base");
    assert!(!look.layers[1].visible);
    assert_eq!(look.visible_layers().map(|l| l.preset_ref.as_str()).collect::<Vec<_>>().len(), 3);
    assert!(look.visible_layers().all(|l| l.preset_ref != "builtin:blush_02_coral"));
    look.save(&path).unwrap();
    let text = std::fs::read_to_string(&path).unwrap();
    assert!(text.contains("\"maps/m.png\"") && text.contains("\"t.exr\""), "maps stay references:\n{text}");
    assert!(text.contains("\"visible\": false") && text.contains("\"name\": \"Base\""), "{text}");
    let back = Look::load(&path).unwrap();
    assert_eq!(back, look);
}

#[test]
fn example_looks_in_data_load() {
    let mut n = 0;
    for entry in std::fs::read_dir(repo().join("data/looks")).unwrap() {
        let path = entry.unwrap().path();
        if path.extension().is_some_and(|e| e == "json") {
            let look = Look::load(&path).unwrap_or_else(|e| panic!("{e}"));
            assert!(!look.layers.is_empty(), "{}", path.display());
            n += 1;
        }
    }
    assert!(n >= 5, "default and the four looks of the library");
    assert_eq!(Look::load(&repo().join("data/looks/default.json")).unwrap(), Look::default_look());
    let evening = Look::load(&repo().join("data/looks/evening.json")).unwrap();
    let refs: Vec<&str> = evening.layers.iter().map(|l| l.preset_ref.as_str()).collect();
    assert_eq!(
        refs,
        [
            "builtin:foundation_02_ivory",
            "builtin:eyeshadow_01_smoky",
            "builtin:blush_01_petal",
            "builtin:lipstick_03_berry"
        ]
    );
    assert_eq!(evening.layers[0].preset, builtin_preset("foundation_02_ivory").unwrap());
    assert_eq!(evening.layers[1].name, "Smoky lids");
}

#[test]
fn relative_paths_resolve_against_the_look_file() {
    let dir = tempfile::tempdir().unwrap();
    let root = dir.path();
    std::fs::create_dir_all(root.join("presets")).unwrap();
    std::fs::create_dir_all(root.join("looks/masks")).unwrap();
    std::fs::copy(repo().join("data/presets/blush_02_coral.json"), root.join("presets/coral.json")).unwrap();
    // RGB 8-bit mask 2x2: only the first channel counts.
    let rgb = vec![255, 0, 0, 0, 255, 255, 51, 7, 7, 102, 200, 200];
    image::RgbImage::from_raw(2, 2, rgb).unwrap().save(root.join("looks/masks/m.png")).unwrap();
    let json = look_json(&[
        r#"{ "preset": "../presets/coral.json", "thickness": { "mask": "masks/m.png", "thickness_mm": 0.02 } }"#,
    ]);
    std::fs::write(root.join("looks/l.json"), json).unwrap();
    let look = Look::load(&root.join("looks/l.json")).unwrap();
    let layer: &LookLayer = &look.layers[0];
    assert_eq!(layer.preset, builtin_preset("blush_02_coral").unwrap());
    assert_eq!(layer.name, "Blush 02 Coral");
    assert_eq!((layer.map.width, layer.map.height), (2, 2));
    let want = [0.02, 0.0, 0.02 * 51.0 / 255.0, 0.02 * 102.0 / 255.0];
    for (got, want) in layer.map.mm.iter().zip(want) {
        assert!(close(*got, want, 1e-7), "{:?}", layer.map.mm);
    }
}

/// The default head's corner UVs at the vertex nearest to `p` (mm).
fn head_uvs_near(mesh: &rouge_model::Mesh, p: Vec3) -> Vec<glam::Vec2> {
    let (best, d) = mesh
        .positions
        .iter()
        .enumerate()
        .map(|(i, q)| (i as u32, q.distance(p)))
        .min_by(|a, b| a.1.total_cmp(&b.1))
        .expect("the head has vertices");
    assert!(d < 1.0, "no vertex of the head within 1 mm of {p}");
    let uvs: Vec<glam::Vec2> = mesh
        .faces
        .iter()
        .flat_map(|f| f.corners.iter())
        .filter(|c| c.position == best)
        .map(|c| mesh.uvs[c.uv as usize])
        .collect();
    assert!(!uvs.is_empty());
    uvs
}

#[test]
fn region_masks_line_up_with_the_default_head() {
    for r in Region::all() {
        let m = r.mask();
        assert_eq!((m.width, m.height, m.mm.len()), (1024, 1024, 1024 * 1024), "{r}");
        assert!(close(m.max_mm(), 1.0, 1e-6), "{r}");
        assert_eq!(Region::parse(r.name()), Some(r));
    }
    assert_eq!(Region::parse("nose"), None);
    // UVs read off data/heads/hm08_head.obj (vertices on the lips' and forehead's midline).
    let lips = Region::Lips.mask();
    assert!(lips.sample_uv(0.897749, 0.483167) > 0.9, "upper lip");
    assert!(lips.sample_uv(0.919265, 0.483154) > 0.9, "lower lip");
    assert_eq!(lips.sample_uv(0.784338, 0.483168), 0.0, "forehead");
    assert!(Region::Tzone.mask().sample_uv(0.784338, 0.483168) > 0.9, "forehead");
    // Through the mesh loader: points on the face (mm, from python/gen_head.py's landmarks).
    let mesh = load_obj(repo().join("data/heads/hm08_head.obj"), 1.0).unwrap();
    let at = |r: Region, p: Vec3| {
        let uvs = head_uvs_near(&mesh, p);
        uvs.iter().map(|uv| r.mask().sample_uv(uv.x, uv.y)).fold(f32::NAN, f32::max)
    };
    let lip = Vec3::new(0.0, -61.3, 115.1);
    let forehead = Vec3::new(0.0, 56.6, 102.3);
    let left_cheek = Vec3::new(34.9, -33.2, 97.5);
    let right_cheek = Vec3::new(-34.9, -33.2, 97.5);
    let left_lid = Vec3::new(31.0, 5.3, 96.3);
    assert!(at(Region::Lips, lip) > 0.9);
    assert_eq!(at(Region::Lips, forehead), 0.0);
    assert_eq!(at(Region::Lips, left_cheek), 0.0);
    assert!(at(Region::Cheeks, left_cheek) > 0.9);
    assert!(at(Region::Cheeks, right_cheek) > 0.9);
    assert_eq!(at(Region::Cheeks, lip), 0.0);
    assert!(at(Region::Eyelids, left_lid) > 0.9);
    assert!(at(Region::Tzone, forehead) > 0.9);
    // The brows' region lies under the brow hairs (whose UVs are the skin's under them), and
    // nowhere near the lips or the cheeks.
    let brow_uvs: Vec<glam::Vec2> = mesh
        .groups
        .iter()
        .filter(|g| g.part() == rouge_model::mesh::Part::Brow)
        .flat_map(|g| mesh.faces[g.faces.clone()].iter())
        .flat_map(|f| f.corners.iter())
        .map(|c| mesh.uvs[c.uv as usize])
        .collect();
    assert!(brow_uvs.len() > 1000, "{} brow corners", brow_uvs.len());
    let on_brow = brow_uvs.iter().filter(|uv| Region::Brows.mask().sample_uv(uv.x, uv.y) > 0.5).count();
    assert!(on_brow as f64 > 0.9 * brow_uvs.len() as f64, "{on_brow} of {} hair corners in the mask", brow_uvs.len());
    for p in [lip, left_cheek, forehead, left_lid] {
        assert_eq!(at(Region::Brows, p), 0.0, "{p}");
    }
    // The v convention matters: with v read downwards the cheek would miss.
    let uv = head_uvs_near(&mesh, left_cheek)[0];
    assert!(Region::Cheeks.mask().sample_uv(uv.x, 1.0 - uv.y) < 0.5);
}

#[test]
fn sampling_follows_the_texture_convention() {
    // 2x2, row 0 = top: a b / c d.
    let m = ThicknessMap { width: 2, height: 2, mm: vec![1.0, 2.0, 3.0, 4.0] };
    assert_eq!(m.sample_uv(0.25, 0.75), 1.0, "top-left pixel centre");
    assert_eq!(m.sample_uv(0.75, 0.75), 2.0);
    assert_eq!(m.sample_uv(0.25, 0.25), 3.0, "bottom-left pixel centre");
    assert_eq!(m.sample_uv(0.5, 0.5), 2.5);
    assert_eq!(m.sample_uv(0.5, 0.75), 1.5);
    assert_eq!(m.sample_uv(0.0, 1.0), 1.0, "clamp to edge");
    assert_eq!(m.sample_uv(-3.0, 7.0), 1.0);
    assert_eq!(m.sample_uv(1.0, 0.0), 4.0);
    assert_eq!(m.max_mm(), 4.0);
    assert_eq!(m.resized(2, 2), m);
    assert_eq!(m.resized(1, 1).mm, [2.5]);
    let up = m.resized(4, 4);
    assert_eq!(up.mm[0], 1.0);
    assert_eq!(up.mm[1], 1.25);
    assert_eq!(up.mm[15], 4.0);
    let u = ThicknessMap::uniform(0.015).resized(8, 3);
    assert_eq!((u.width, u.height), (8, 3));
    assert!(u.mm.iter().all(|&v| v == 0.015));
    assert_eq!(ThicknessMap::uniform(0.015).sample_uv(0.3, 0.9), 0.015);
}

#[test]
fn sixteen_bit_png_map_with_scale() {
    let dir = tempfile::tempdir().unwrap();
    write_png_u16(&dir.path().join("lips.png"), 3, 1, vec![0, 32768, 65535]);
    let json = look_json(&[
        r#"{ "preset": "builtin:lipstick_02_red", "thickness": { "map": "lips.png", "scale_mm": 0.03 } }"#,
    ]);
    let look = Look::from_json(&json, &dir.path().join("l.json")).unwrap();
    let m = &look.layers[0].map;
    assert_eq!((m.width, m.height), (3, 1));
    assert_eq!(m.mm[0], 0.0);
    assert!(close(m.mm[1], 0.03 * 32768.0 / 65535.0, 1e-8));
    assert!(close(m.mm[2], 0.03, 1e-8));
    assert_eq!(look.layers[0].thickness, ThicknessSource::Map { path: "lips.png".into(), scale_mm: Some(0.03) });
    // Without a scale a PNG is no thickness.
    let json = look_json(&[r#"{ "preset": "builtin:lipstick_02_red", "thickness": { "map": "lips.png" } }"#]);
    let e = load_err(dir.path(), &json);
    assert!(e.contains("layer 0 (\"builtin:lipstick_02_red\")") && e.contains("needs `scale_mm`"), "{e}");
}

#[test]
fn exr_map_in_millimetres() {
    let dir = tempfile::tempdir().unwrap();
    let map = ThicknessMap { width: 3, height: 2, mm: vec![0.0, 0.005, 0.01, 0.02, 0.04, 0.08] };
    map.save_exr(&dir.path().join("lips_mm.exr")).unwrap();
    // An RGB EXR (channels stored B, G, R): R is the thickness.
    let ch = |name: &str, v: Vec<f32>| AnyChannel::new(name, FlatSamples::F32(v));
    let channels = AnyChannels::sort(SmallVec::from_vec(vec![
        ch("B", vec![9.0, 9.0]),
        ch("G", vec![8.0, 8.0]),
        AnyChannel::new("R", FlatSamples::F16(vec![f16::from_f32(0.5), f16::from_f32(0.25)])),
    ]));
    Image::from_channels((2, 1), channels).write().to_file(dir.path().join("rgb.exr")).unwrap();
    let json = look_json(&[
        r#"{ "preset": "builtin:lipstick_02_red", "thickness": { "map": "lips_mm.exr" } }"#,
        r#"{ "preset": "builtin:lipstick_02_red", "thickness": { "map": "rgb.exr", "scale_mm": 0.1 } }"#,
    ]);
    let look = Look::from_json(&json, &dir.path().join("l.json")).unwrap();
    assert_eq!(look.layers[0].map, map, "EXR thickness round-trips exactly");
    assert_eq!(look.layers[1].map.mm, [0.05, 0.025]);
}

#[test]
fn errors_name_the_file_the_layer_and_the_fault() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let ok = r#"{ "preset": "builtin:foundation_02_ivory", "thickness": { "uniform_mm": 0.01 } }"#;
    let check = |json: String, needles: &[&str]| {
        let e = load_err(d, &json);
        for n in needles {
            assert!(e.contains(n), "expected {n:?} in: {e}");
        }
    };
    // Unknown fields: in a layer, in its thickness, at the top.
    check(
        look_json(&[
            ok,
            r#"{ "name": "blush", "preset": "builtin:blush_01_petal", "opacity": 0.5, "thickness": { "uniform_mm": 0.01 } }"#,
        ]),
        &["layer 1 (\"blush\")", "unknown field `opacity`", "line 1"],
    );
    check(
        look_json(&[r#"{ "preset": "builtin:blush_01_petal", "thickness": { "uniform_mm": 0.01, "scale": 2 } }"#]),
        &["layer 0 (\"builtin:blush_01_petal\")", "unknown field `scale`"],
    );
    check(
        r#"{ "schema": "rouge-look", "version": 1, "name": "t", "author": "me", "layers": [] }"#.into(),
        &["unknown field `author`"],
    );
    // Schema and version.
    check(
        r#"{ "schema": "rouge-preset", "version": 1, "layers": [] }"#.into(),
        &["`schema` is `rouge-preset`", "rouge-look"],
    );
    check(r#"{ "schema": "rouge-look", "version": 2, "layers": [{"x": 1}] }"#.into(), &["version 2 is not supported"]);
    check("{ not json".into(), &["line 1"]);
    // Presets.
    check(
        look_json(&[ok, r#"{ "preset": "presets/nope.json", "thickness": { "uniform_mm": 0.01 } }"#]),
        &["layer 1 (\"presets/nope.json\")", "preset \"presets/nope.json\"", "nope.json"],
    );
    check(
        look_json(&[r#"{ "name": "X", "preset": "builtin:nope", "thickness": { "uniform_mm": 0.01 } }"#]),
        &["layer 0 (\"X\")", "no such built-in preset", "foundation_02_ivory"],
    );
    std::fs::write(d.join("bad_preset.json"), r#"{ "schema": "rouge-preset", "version": 1 }"#).unwrap();
    check(
        look_json(&[r#"{ "preset": "bad_preset.json", "thickness": { "uniform_mm": 0.01 } }"#]),
        &["layer 0", "preset \"bad_preset.json\"", &format!("{}:", d.join("bad_preset.json").display())],
    );
    // Maps and masks.
    check(
        look_json(&[ok, r#"{ "preset": "builtin:lipstick_02_red", "thickness": { "map": "missing.exr" } }"#]),
        &["layer 1", "thickness map \"missing.exr\"", "cannot read"],
    );
    std::fs::write(d.join("m.png"), "GIF89a, not a png at all").unwrap();
    check(
        look_json(&[
            r#"{ "name": "blush", "preset": "builtin:blush_01_petal", "thickness": { "mask": "m.png", "thickness_mm": 0.01 } }"#,
        ]),
        &["layer 0 (\"blush\")", "thickness mask \"m.png\"", "not a PNG file", "47 49 46 38"],
    );
    check(
        look_json(&[r#"{ "preset": "builtin:blush_01_petal", "thickness": { "map": "m.png", "scale_mm": 0.01 } }"#]),
        &["layer 0", "thickness map \"m.png\"", "neither an OpenEXR nor a PNG"],
    );
    let mut nan = vec![0.01_f32; 6];
    nan[4] = f32::NAN; // pixel (1, 1) of a 3x2 map
    ThicknessMap { width: 3, height: 2, mm: nan }.save_exr(&d.join("nan.exr")).unwrap();
    check(
        look_json(&[ok, ok, r#"{ "preset": "builtin:lipstick_02_red", "thickness": { "map": "nan.exr" } }"#]),
        &["layer 2", "thickness map \"nan.exr\"", "pixel (1, 1)", "NaN"],
    );
    check(
        look_json(&[
            r#"{ "preset": "builtin:lipstick_02_red", "thickness": { "mask": "nan.exr", "thickness_mm": 0.01 } }"#,
        ]),
        &["layer 0", "not a PNG file", "OpenEXR", "use `map`"],
    );
    let mut neg = vec![0.01_f32; 4];
    neg[2] = -0.001; // pixel (0, 1)
    ThicknessMap { width: 2, height: 2, mm: neg }.save_exr(&d.join("neg.exr")).unwrap();
    check(
        look_json(&[r#"{ "preset": "builtin:lipstick_02_red", "thickness": { "map": "neg.exr" } }"#]),
        &["layer 0", "pixel (0, 1)", "-0.001"],
    );
    // Thickness values.
    check(
        look_json(&[r#"{ "preset": "builtin:foundation_02_ivory", "thickness": { "uniform_mm": -0.01 } }"#]),
        &["layer 0 (\"builtin:foundation_02_ivory\")", "`uniform_mm` = -0.01", "≥ 0"],
    );
    check(
        look_json(&[
            ok,
            r#"{ "preset": "builtin:blush_01_petal", "thickness": { "region": "cheeks", "thickness_mm": 15 } }"#,
        ]),
        &["layer 1", "`thickness_mm` = 15", "≤ 10 mm"],
    );
    check(
        look_json(&[
            r#"{ "preset": "builtin:blush_01_petal", "thickness": { "region": "nose", "thickness_mm": 0.01 } }"#,
        ]),
        &["layer 0", "unknown region \"nose\""],
    );
    check(
        look_json(&[r#"{ "preset": "builtin:blush_01_petal", "thickness": { "region": "cheeks" } }"#]),
        &["layer 0", "`region` needs `thickness_mm`"],
    );
    check(
        look_json(&[
            r#"{ "preset": "builtin:blush_01_petal", "thickness": { "uniform_mm": 0.01, "region": "cheeks" } }"#,
        ]),
        &["layer 0", "both `uniform_mm` and `region`"],
    );
    check(look_json(&[r#"{ "preset": "builtin:blush_01_petal" }"#]), &["layer 0", "missing field `thickness`"]);
}

#[test]
fn save_into_a_missing_folder_names_the_file() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("no/such/dir/look.json");
    let e = Look::default_look().save(&path).unwrap_err().to_string();
    assert!(e.starts_with(&path.display().to_string()), "{e}");
}

/// Issue 30: a look with 100,000 layers (or 3,000 map layers) was loaded whole, maps and all,
/// before the 8-layer limit was checked (2.6 GB, then an allocation abort). The count is checked
/// first: 100,000 layers naming a map that does not exist fail on the count, not on the map.
#[test]
fn too_many_layers_are_refused_before_any_is_loaded() {
    let dir = tempfile::tempdir().unwrap();
    let layer = r#"{ "preset": "builtin:foundation_02_ivory", "thickness": { "map": "missing.exr" } }"#;
    let json = look_json(&vec![layer; 100_000]);
    let e = load_err(dir.path(), &json);
    assert!(e.contains("100000 layers") && e.contains("at most 8"), "{e}");
    let ok = r#"{ "preset": "builtin:foundation_02_ivory", "thickness": { "uniform_mm": 0.01 } }"#;
    assert!(Look::from_json(&look_json(&[ok; 8]), &dir.path().join("l.json")).is_ok());
    assert!(load_err(dir.path(), &look_json(&[ok; 9])).contains("9 layers"));
}

#[test]
fn a_look_carries_its_mascara_and_checks_it() {
    use rouge_model::mesh::lashes::Mascara;
    let path = std::path::Path::new("lashes.json");
    let text = r#"{"schema": "rouge-look", "version": 1, "name": "Lashes", "layers": [],
        "mascara": {"length": 1.4, "volume": 2.5, "curl_deg": 20}}"#;
    let look = Look::from_json(text, path).expect("a look with a mascara");
    assert_eq!(look.mascara, Some(Mascara { length: 1.4, volume: 2.5, curl_deg: 20.0, color: None }));
    let back = Look::from_json(&look.to_json(), path).expect("round trip");
    assert_eq!(back, look);
    // No mascara: none written.
    assert!(!Look::bare().to_json().contains("mascara"));
    let bad = text.replace("1.4", "3.0");
    let e = Look::from_json(&bad, path).expect_err("too long").to_string();
    assert!(e.contains("lashes.json") && e.contains("mascara length 3"), "{e}");
    let unknown = text.replace("\"volume\"", "\"colour\"");
    let e = Look::from_json(&unknown, path).expect_err("unknown field").to_string();
    assert!(e.contains("colour"), "{e}");
}

#[test]
fn a_look_carries_its_brow_gel_and_checks_it() {
    use rouge_model::mesh::brow_gel::BrowGel;
    let path = std::path::Path::new("brows.json");
    let text = r#"{"schema": "rouge-look", "version": 1, "name": "Brows", "layers": [],
        "brow_gel": {"color": [0.045, 0.027, 0.016], "strength": 0.7}}"#;
    let look = Look::from_json(text, path).expect("a look with a brow gel");
    assert_eq!(look.brow_gel, Some(BrowGel { color: [0.045, 0.027, 0.016], strength: 0.7, fill: 0.0 }));
    assert_eq!(Look::from_json(&look.to_json(), path).expect("round trip"), look);
    assert!(!Look::bare().to_json().contains("brow_gel"));
    let e = Look::from_json(&text.replace("0.7", "1.7"), path).expect_err("too strong").to_string();
    assert!(e.contains("brows.json") && e.contains("brow gel strength 1.7"), "{e}");
    let e = Look::from_json(&text.replace("\"strength\"", "\"hold\""), path).expect_err("unknown").to_string();
    assert!(e.contains("hold"), "{e}");
}

/// A look names its maps by path, so they can be anything: a pipe blocked the open for ever and
/// `/dev/zero` was read until memory ran out. Both are refused before a byte is read, and so
/// is a map wider than the limit (its header read, its pixels never decoded).
#[test]
fn a_map_that_is_a_pipe_a_device_or_too_wide_is_refused_before_reading() {
    let dir = tempfile::tempdir().unwrap();
    let pipe = dir.path().join("pipe.exr");
    let made = std::process::Command::new("mkfifo").arg(&pipe).status().is_ok_and(|s| s.success());
    assert!(made, "mkfifo");
    for map in ["pipe.exr", "/dev/zero"] {
        let e = load_err(
            dir.path(),
            &look_json(&[&format!(
                r#"{{ "preset": "builtin:blush_01_petal", "thickness": {{ "map": "{map}", "scale_mm": 0.01 }} }}"#
            )]),
        );
        assert!(e.contains(map) && e.contains("not a regular file"), "{e}");
    }
    // A PNG header claiming 100,000 × 1 pixels (no pixel data follows).
    let crc = |kind_data: &[u8]| {
        let mut c = 0xffff_ffffu32;
        for &b in kind_data {
            c ^= u32::from(b);
            for _ in 0..8 {
                c = if c & 1 == 1 { (c >> 1) ^ 0xedb8_8320 } else { c >> 1 };
            }
        }
        !c
    };
    let mut png = b"\x89PNG\r\n\x1a\n".to_vec();
    let mut chunk = |kind: &[u8], data: &[u8]| {
        let kind_data = [kind, data].concat();
        png.extend_from_slice(&(data.len() as u32).to_be_bytes());
        png.extend_from_slice(&kind_data);
        png.extend_from_slice(&crc(&kind_data).to_be_bytes());
    };
    chunk(b"IHDR", &[&100_000u32.to_be_bytes()[..], &1u32.to_be_bytes(), &[16, 0, 0, 0, 0]].concat());
    chunk(b"IDAT", &[]);
    chunk(b"IEND", &[]);
    std::fs::write(dir.path().join("wide.png"), &png).unwrap();
    let e = load_err(
        dir.path(),
        &look_json(&[
            r#"{ "preset": "builtin:blush_01_petal", "thickness": { "map": "wide.png", "scale_mm": 0.01 } }"#,
        ]),
    );
    assert!(e.contains("100000×1 pixels") && e.contains("8192"), "{e}");
}
