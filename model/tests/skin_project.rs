//! Skin maps in project folders: saved with the project and reopened bit for bit (save, autosave
//! and recovery alike), the recipe kept to regenerate them, stale files removed, bad files named,
//! and a project saved before skin maps (its `look.json` and `face.json` as the code before them
//! wrote them, `tests/data/project_before_skin_maps/`) opening as before.

use std::collections::BTreeSet;
use std::path::Path;

use crate::common::project;
use project::project_file;
use std::sync::Arc;

use rouge_model::document::{Document, MAP_SIZE};
use rouge_model::look::ThicknessMap;
use rouge_model::skin::{ProjectSkin, SKIN_FILE, SkinChannel, SkinConditions, SkinMaps, SkinRecipe};

fn files_in(dir: &Path) -> BTreeSet<String> {
    std::fs::read_dir(dir)
        .map(|d| d.flatten().map(|e| e.file_name().to_string_lossy().into_owned()).collect())
        .unwrap_or_default()
}

fn skin_files(dir: &Path) -> BTreeSet<String> {
    files_in(&dir.join("maps")).into_iter().filter(|f| f.starts_with("skin-")).collect()
}

/// A small generated skin (128² keeps the tests quick; the format has no size of its own).
fn skin(conditions: &str, seed: u64) -> Arc<ProjectSkin> {
    let c: SkinConditions = conditions.parse().expect("conditions");
    let recipe = SkinRecipe::from_tone("medium", c, seed, 128).expect("recipe");
    Arc::new(ProjectSkin::generate(recipe).expect("generate"))
}

fn assert_same_bits(a: &SkinMaps, b: &SkinMaps) {
    assert_eq!((a.width(), a.height(), a.base()), (b.width(), b.height(), b.base()));
    for c in SkinChannel::ALL {
        let bits = |m: &SkinMaps| m.plane(c).iter().map(|v| v.to_bits()).collect::<Vec<_>>();
        assert!(bits(a) == bits(b), "channel {} differs", c.name());
    }
}

#[test]
fn skin_maps_save_and_reopen_bit_for_bit_with_their_recipe() {
    let tmp = tempfile::tempdir().expect("temp dir");
    let dir = tmp.path().join("With skin");
    let mut doc = Document::default_project();
    assert!(doc.skin.is_none() && !doc.is_modified());
    doc.skin = Some(skin("freckles=0.7,redness=0.5,veins=1", 99));
    assert!(doc.is_modified(), "new skin maps modify the document");
    doc.save_project(&dir).expect("save");
    assert!(!doc.is_modified());
    assert!(project_file(&dir, "skin").is_file() && !dir.join(SKIN_FILE).exists());
    assert_eq!(skin_files(&dir).len(), 1);

    let opened = Document::open_project(&dir).expect("open");
    let (a, b) = (doc.skin.as_ref().unwrap(), opened.skin.as_ref().expect("the skin comes back"));
    assert_eq!(a.recipe, b.recipe);
    assert_eq!(b.recipe.tone.as_deref(), Some("medium"));
    assert_eq!(b.recipe.conditions.to_string(), "freckles=0.7,redness=0.5,veins=1");
    assert_same_bits(&a.maps, &b.maps);
    assert!(!opened.is_modified() && !opened.can_undo());
    // The recipe makes the same maps again.
    assert_same_bits(&b.recipe.generate().expect("regenerate"), &b.maps);

    // Saving again with the same maps writes nothing new; other maps replace the file.
    let before = skin_files(&dir);
    doc.save_project(&dir).expect("save again");
    assert_eq!(skin_files(&dir), before);
    doc.skin = Some(skin("moles=1", 1));
    doc.save_project(&dir).expect("save other skin");
    let after = skin_files(&dir);
    assert_eq!(after.len(), 1);
    assert_ne!(after, before, "the old skin maps are deleted");
    assert_same_bits(&Document::open_project(&dir).unwrap().skin.unwrap().maps, &doc.skin.as_ref().unwrap().maps);

    // Without skin maps the project loses them and opens without.
    doc.skin = None;
    assert!(doc.is_modified());
    doc.save_project(&dir).expect("save without skin");
    assert!(skin_files(&dir).is_empty() && !files_in(&dir).iter().any(|f| f.starts_with("skin")));
    assert!(Document::open_project(&dir).unwrap().skin.is_none());
    // The painted layers are untouched by all this.
    assert_eq!(files_in(&dir.join("maps")).len(), doc.layers.len());
}

#[test]
fn autosave_and_recovery_carry_the_skin_maps() {
    let tmp = tempfile::tempdir().expect("temp dir");
    let recovery = tmp.path().join("recovery");
    let mut doc = Document::default_project();
    doc.skin = Some(skin("acne=0.6,under_eye=0.8", 5));
    // The app autosaves a modified document: new skin maps are a modification.
    assert!(doc.is_modified());
    doc.autosave(&recovery).expect("autosave");
    assert!(doc.is_modified(), "an autosave does not mark the document saved");
    let recovered = Document::open_project(&recovery).expect("recover");
    assert_same_bits(&recovered.skin.unwrap().maps, &doc.skin.as_ref().unwrap().maps);
    Document::clear_recovery(&recovery).expect("clear");
    assert!(files_in(&recovery).is_empty(), "{:?}", files_in(&recovery));
}

/// Writes the project that `Document::save_project` wrote before skin maps existed:
/// `look.json` and `face.json` as it wrote them (committed), and the one map they name, whose
/// writer (`ThicknessMap::save_exr`) is unchanged.
fn old_project(dir: &Path) {
    let fixture = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data/project_before_skin_maps");
    std::fs::create_dir_all(dir.join("maps")).expect("folders");
    for f in ["look.json", "face.json"] {
        std::fs::copy(fixture.join(f), dir.join(f)).expect("copy the fixture");
    }
    let mut map = ThicknessMap { width: MAP_SIZE, height: MAP_SIZE, mm: vec![0.0; (MAP_SIZE * MAP_SIZE) as usize] };
    for y in 1000..1016u32 {
        for x in 800..816u32 {
            map.mm[(y * MAP_SIZE + x) as usize] = 0.001 * (1 + (x + y) % 7) as f32;
        }
    }
    map.save_exr(&dir.join("maps/00-blush-01-petal-pink-9bff78d485696875.exr")).expect("the map");
}

#[test]
fn a_project_saved_before_skin_maps_opens_as_before_and_takes_them() {
    let tmp = tempfile::tempdir().expect("temp dir");
    let dir = tmp.path().join("old");
    old_project(&dir);
    let doc = Document::open_project(&dir).expect("an old project opens");
    assert_eq!(doc.name, "Saved before skin maps");
    assert!(doc.skin.is_none() && !doc.is_modified());
    assert_eq!(doc.layers.len(), 1);
    assert_eq!(doc.layers[0].multiplier, 1.5);
    assert_eq!(doc.layers[0].map.mm[1000 * MAP_SIZE as usize + 801], 0.001 * 3.0);
    assert_eq!(doc.face.expression.get("smile"), Some(&0.5));

    // Saved again without skin maps it is the same project (no skin file, the same map).
    let mut doc = doc;
    doc.save_project(&dir).expect("save");
    assert!(!files_in(&dir).iter().any(|f| f.starts_with("skin")), "{:?}", files_in(&dir));
    assert_eq!(files_in(&dir.join("maps")).len(), 1);
    // And it takes skin maps like any project.
    doc.skin = Some(skin("freckles=0.3", 2));
    doc.save_project(&dir).expect("save with skin");
    assert!(Document::open_project(&dir).unwrap().skin.is_some());
}

#[test]
fn bad_skin_files_are_errors_naming_the_file_and_the_fault() {
    let tmp = tempfile::tempdir().expect("temp dir");
    let dir = tmp.path().join("p");
    let mut doc = Document::default_project();
    doc.skin = Some(skin("redness=0.2", 3));
    doc.save_project(&dir).expect("save");
    let json_path = project_file(&dir, "skin");
    let json_name = json_path.file_name().expect("a name").to_string_lossy().into_owned();
    let good = std::fs::read_to_string(&json_path).expect("the skin file");
    let open_err = |text: &str| {
        std::fs::write(&json_path, text).expect("write");
        Document::open_project(&dir).expect_err("a bad skin.json").to_string()
    };
    let e = open_err(&good.replace("\"redness\": 0.2", "\"redness\": 2.0"));
    assert!(e.contains(&json_name) && e.contains("`redness` = 2"), "{e}");
    let e = open_err(&good.replace("\"redness\"", "\"blush\""));
    assert!(e.contains(&json_name) && e.contains("`blush`") && e.contains("freckles"), "{e}");
    let e = open_err(&good.replace("\"blood_fraction\": ", "\"blood_fraction\": 9"));
    assert!(e.contains(&json_name) && e.contains("blood_fraction"), "{e}");
    let e = open_err(&good.replace("\"version\": 1", "\"version\": 2"));
    assert!(e.contains("rouge-skin") && e.contains("version 2"), "{e}");
    let e = open_err(&good.replace("\"seed\"", "\"sed\""));
    assert!(e.contains("line") && e.contains("sed"), "{e}");
    // The EXR: missing, or not an EXR.
    std::fs::write(&json_path, &good).expect("restore");
    let exr = dir.join("maps").join(skin_files(&dir).into_iter().next().expect("the skin EXR"));
    std::fs::write(&exr, b"not an exr").expect("spoil the EXR");
    let e = Document::open_project(&dir).expect_err("a bad EXR").to_string();
    assert!(e.contains(&exr.file_name().unwrap().to_string_lossy().into_owned()) && e.contains("OpenEXR"), "{e}");
}

#[test]
fn an_exr_missing_a_channel_or_out_of_range_is_named() {
    use rouge_measure::skin::SkinParams;
    let maps = skin("", 0).maps.clone();
    let bytes = maps.to_exr_bytes().expect("encode");
    assert_same_bits(&SkinMaps::from_exr_bytes(&bytes, maps.base()).expect("decode"), &maps);
    // A thick epidermis under weak scattering is valid; read with strong scattering it is not.
    let weak = SkinParams { scattering_500nm_per_mm: 1.0, scattering_power: 1.0, ..SkinParams::LIGHT };
    let planes = SkinChannel::ALL.map(|c| vec![if c == SkinChannel::Epidermis { 0.25 } else { c.of(&weak) as f32 }; 4]);
    let thick = SkinMaps::from_planes(2, 2, &weak, planes).expect("valid under weak scattering");
    let strong = SkinParams { scattering_500nm_per_mm: 10.0, scattering_power: 4.0, ..weak };
    let Err(e) = SkinMaps::from_exr_bytes(&thick.to_exr_bytes().expect("encode"), &strong) else {
        panic!("an epidermis past the table's reach was accepted")
    };
    assert!(e.contains("epidermis_thickness_mm") && e.contains("texel (0, 0)"), "{e}");
    // A one-channel EXR (a thickness map) is not skin maps.
    let dir = tempfile::tempdir().expect("temp dir");
    let file = dir.path().join("y.exr");
    ThicknessMap::uniform(0.5).save_exr(&file).expect("a one-channel EXR");
    let Err(e) = SkinMaps::from_exr_bytes(&std::fs::read(&file).expect("read"), maps.base()) else {
        panic!("a thickness map was read as skin maps")
    };
    assert!(e.contains("no channel \"melanin_fraction\"") && e.contains("\"Y\""), "{e}");
}
