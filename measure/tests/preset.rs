//! Checks of presets (`rouge_measure::preset`): the JSON round trip is exact, the derived
//! tables start clear, bad presets are refused naming the field, and a failed save keeps the
//! old file.

use rouge_measure::Spectrum;
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
    v["version"] = 2.into();
    let e = Preset::from_json(&v.to_string(), "p.json").unwrap_err().to_string();
    assert!(e.contains("version 2 is not supported"), "{e}");
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
