//! `rouge export materialx` end to end: its OBJ re-imports through the repo's loader with the
//! triangles, bounds and eye groups of the mesh `rouge render` draws; bad options and unwritable
//! paths fail naming them and leave no temporary file. MaterialX's own validation of the .mtlx is
//! python/test_materialx_export.py (PyPI materialx).

use super::common::{names, rouge, stderr};
use rouge_model::mesh::{Bounds, load_mesh};
use rouge_render::job::{LookChoice, RenderJob};
use std::path::Path;
use std::process::Output;

fn export(out: &Path, textures: &str) -> Output {
    let out = out.to_str().expect("utf-8");
    rouge(&["export", "materialx", "--subdiv", "1", "--flat-skin", "--textures", textures, "--out", out])
}

#[test]
fn the_obj_reimports_as_the_drawn_mesh_beside_its_material_and_textures() {
    let dir = tempfile::tempdir().expect("temp dir");
    let o = export(dir.path(), "256");
    assert!(o.status.success(), "{}", stderr(&o));
    // The textures are named by their content (`skin_NAME.<16 hex>.png`), as the .mtlx names them.
    let plain: Vec<String> = names(dir.path())
        .iter()
        .map(|n| rouge_measure::file_set::content_tag_stem(n, "png").map_or_else(|| n.clone(), |s| format!("{s}.png")))
        .collect();
    assert_eq!(
        plain,
        ["face.mtlx", "face.obj", "skin_base_color.png", "skin_specular_roughness.png", "skin_specular_weight.png"]
    );
    for n in names(dir.path()) {
        if let Some(stem) = rouge_measure::file_set::content_tag_stem(&n, "png") {
            assert!(rouge_render::materialx_export::TEXTURE_STEMS.contains(&stem), "{n}: the writer knows it by name");
        }
    }
    let mtlx = std::fs::read_to_string(dir.path().join("face.mtlx")).expect("mtlx");
    assert!(names(dir.path()).iter().filter(|n| n.ends_with(".png")).all(|n| mtlx.contains(n.as_str())), "{mtlx}");
    let drawn =
        RenderJob { subdivision: 1, look: LookChoice::Default, ..RenderJob::default() }.load().expect("scene").mesh;
    let back = load_mesh(Some(&dir.path().join("face.obj")), 1.0, 0).expect("re-import");
    assert_eq!(back.triangle_count(), drawn.triangle_count());
    let (a, b) = (Bounds::of(&back.positions).expect("bounds"), Bounds::of(&drawn.positions).expect("bounds"));
    assert!(a.min.abs_diff_eq(b.min, 1e-3) && a.max.abs_diff_eq(b.max, 1e-3), "{a:?} vs {b:?}");
    let eyes = back.groups.iter().filter(|g| g.is_eye()).count();
    assert_eq!(eyes, drawn.groups.iter().filter(|g| g.is_eye()).count(), "{:?}", back.groups);
    assert!(eyes > 0);
    let base_file = names(dir.path()).into_iter().find(|n| n.starts_with("skin_base_color.")).expect("base colour");
    let base = image::open(dir.path().join(base_file)).expect("png");
    assert_eq!((base.width(), base.height()), (256, 256));
}

#[test]
fn bad_options_and_unwritable_paths_fail_naming_them() {
    let dir = tempfile::tempdir().expect("temp dir");
    let o = export(dir.path(), "300");
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
    assert!(stderr(&o).contains("--textures"), "{}", stderr(&o));

    let file = dir.path().join("taken");
    std::fs::write(&file, b"previous").expect("file");
    let o = export(&file, "256");
    assert!(!o.status.success());
    assert!(stderr(&o).contains("--out") && stderr(&o).contains("taken"), "{}", stderr(&o));
    assert_eq!(std::fs::read(&file).expect("kept"), b"previous");

    // The .mtlx's name is taken by a folder: the files before it are written whole, the .mtlx
    // fails naming it, and no temporary file is left.
    let out = dir.path().join("out");
    std::fs::create_dir_all(out.join("face.mtlx")).expect("folder");
    let o = export(&out, "256");
    assert!(!o.status.success());
    assert!(stderr(&o).contains("face.mtlx") && stderr(&o).contains("cannot write"), "{}", stderr(&o));
    assert!(names(&out).iter().all(|n| !n.starts_with('.')), "no temporary file: {:?}", names(&out));
}
