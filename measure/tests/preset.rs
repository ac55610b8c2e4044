//! Checks of presets (`rouge_measure::preset`): the JSON round trip is exact, the derived
//! tables start clear, bad presets are refused naming the field, a failed save keeps the old
//! file, and finishes (schema version 2) load beside version 1 presets.

use rouge_measure::Spectrum;
use rouge_measure::finish::FinishKind;
use rouge_measure::import::Kind;
use rouge_measure::preset::Preset;

fn sample() -> Preset {
    let s = Spectrum::from_fn(|nm| 30.0 - nm / 100.0);
    let k = Spectrum::from_fn(|nm| if nm < 550.0 { 8.0 } else { 0.5 });
    Preset::from_s_k("Test red", Kind::Lipstick, 0.02, &s, &k)
}

#[test]
fn json_round_trip_is_exact() {
    let p = sample();
    let back = Preset::from_json(&p.to_json(), "t.json").unwrap();
    assert_eq!(p, back);
}

#[test]
fn zero_thickness_row_is_clear() {
    let p = sample();
    assert_eq!(p.derived.r0_linear_srgb[0], [0.0; 3]);
    for v in p.derived.t_linear_srgb[0] {
        assert!((v - 1.0).abs() < 2e-3);
    }
}

#[test]
fn bad_presets_are_refused_with_the_field() {
    let p = sample();
    let mut v: serde_json::Value = serde_json::from_str(&p.to_json()).unwrap();
    v["version"] = 3.into();
    let e = Preset::from_json(&v.to_string(), "p.json").unwrap_err().to_string();
    assert!(e.contains("version 3 is not supported"), "{e}");
    let mut v: serde_json::Value = serde_json::from_str(&p.to_json()).unwrap();
    v["k_per_mm"][4] = (-1.0).into();
    let e = Preset::from_json(&v.to_string(), "p.json").unwrap_err().to_string();
    assert!(e.contains("`k_per_mm` at 400 nm"), "{e}");
    let mut v: serde_json::Value = serde_json::from_str(&p.to_json()).unwrap();
    v["kind"] = "mascara".into();
    let e = Preset::from_json(&v.to_string(), "p.json").unwrap_err().to_string();
    assert!(e.starts_with("p.json:"), "{e}");
    let mut v: serde_json::Value = serde_json::from_str(&p.to_json()).unwrap();
    v["specular"]["ior"] = 7.0.into();
    assert!(Preset::from_json(&v.to_string(), "p.json").unwrap_err().to_string().contains("specular.ior"));
}

#[test]
fn failed_save_keeps_the_old_file() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("p.json");
    sample().save(&path).unwrap();
    let before = std::fs::read(&path).unwrap();
    // A directory in the way of the temporary file makes the save fail.
    let blocker = dir.path().join(format!(".p.json.tmp-{}", std::process::id()));
    std::fs::create_dir(&blocker).unwrap();
    let mut other = sample();
    other.name = "changed".into();
    assert!(other.save(&path).is_err());
    assert_eq!(std::fs::read(&path).unwrap(), before);
}

#[test]
fn version_1_presets_still_load_and_a_finish_makes_version_2() {
    // Every preset in data/ was written as version 1 and loads as it was.
    let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../data/presets");
    let mut loaded = 0;
    for entry in std::fs::read_dir(&dir).unwrap() {
        let path = entry.unwrap().path();
        if path.extension().is_some_and(|e| e == "json") {
            let p = Preset::load(&path).unwrap_or_else(|e| panic!("{e}"));
            if p.finish.is_none() {
                assert_eq!(p.version, 1, "{}", path.display());
                assert_eq!(p.clarity_levelling(), (1.0, 0.0), "a clear film that follows the relief");
            }
            loaded += 1;
        }
    }
    assert!(loaded >= 4, "{loaded} presets in {}", dir.display());
    // The finished variants (`rouge finish`, data/SOURCES.md) are version 2 and load.
    for entry in std::fs::read_dir(dir.join("../finishes")).unwrap() {
        let p = Preset::load(&entry.unwrap().path()).unwrap_or_else(|e| panic!("{e}"));
        assert!(p.version == 2 && p.finish.is_some(), "{}", p.name);
    }
    // A finish is written as version 2, round-trips, and taking it away goes back to version 1.
    let mut p = sample();
    assert_eq!(p.version, 1);
    p.set_finish(Some(FinishKind::Matte.defaults()));
    assert_eq!((p.version, p.specular), (2, FinishKind::Matte.defaults().0));
    let back = Preset::from_json(&p.to_json(), "matte.json").unwrap();
    assert_eq!(back, p);
    assert!(p.to_json().contains("\"kind\": \"matte\""));
    p.set_finish(None);
    assert_eq!(p.version, 1);
    assert!(!p.to_json().contains("finish"));
    // A finish in a version 1 file, or out of range, is refused naming the field.
    let mut q = sample();
    q.set_finish(Some(FinishKind::Gloss.defaults()));
    let mut v: serde_json::Value = serde_json::from_str(&q.to_json()).unwrap();
    v["version"] = 1.into();
    let e = Preset::from_json(&v.to_string(), "g.json").unwrap_err().to_string();
    assert!(e.contains("`finish` needs preset schema version 2"), "{e}");
    let mut v: serde_json::Value = serde_json::from_str(&q.to_json()).unwrap();
    v["finish"]["clarity"] = 2.0.into();
    let e = Preset::from_json(&v.to_string(), "g.json").unwrap_err().to_string();
    assert!(e.contains("finish.clarity"), "{e}");
    let mut v: serde_json::Value = serde_json::from_str(&q.to_json()).unwrap();
    v["finish"]["kind"] = "velvet".into();
    let e = Preset::from_json(&v.to_string(), "g.json").unwrap_err().to_string();
    assert!(e.starts_with("g.json:"), "{e}");
}
