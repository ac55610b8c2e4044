//! `rouge render` / `rouge export mitsuba` with --expression and --shape, `rouge bench deform`,
//! close-ups (`--close-up`) and finishes (`rouge finish`): the face's options end to end.

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

fn rouge(args: &[&str]) -> Output {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("..");
    Command::new(env!("CARGO_BIN_EXE_rouge")).args(args).current_dir(root).output().expect("run rouge")
}

fn stderr(o: &Output) -> String {
    String::from_utf8_lossy(&o.stderr).into_owned()
}

fn path(dir: &Path, name: &str) -> PathBuf {
    dir.join(name)
}

#[test]
fn bad_face_options_are_named() {
    let dir = tempfile::tempdir().expect("tempdir");
    let out = path(dir.path(), "x.png");
    let out = out.to_str().expect("utf-8");
    let cases: [(&[&str], &[&str]); 5] = [
        (&["--expression", "smle=1"], &["--expression", "`smle`", "smile"]),
        (&["--expression", "mouthSmileLef=1"], &["mouthSmileLeft"]),
        (&["--shape", "age=2"], &["--shape", "age=2", "-1 to 1"]),
        (&["--expression", "smile=much"], &["--expression", "`much`"]),
        (&["--mesh", "builtin:sphere", "--expression", "smile"], &["default head", "builtin:sphere"]),
    ];
    for (args, needles) in cases {
        let mut all = vec!["render", "--width", "32", "--height", "32", "--out", out];
        all.extend_from_slice(args);
        let o = rouge(&all);
        assert_eq!(o.status.code(), Some(2), "{args:?}");
        let err = stderr(&o);
        for n in needles {
            assert!(err.contains(n), "{args:?}: {err}");
        }
    }
    assert!(!Path::new(out).exists());
}

#[test]
fn an_expression_changes_the_render_and_the_export() {
    let dir = tempfile::tempdir().expect("tempdir");
    let frame = |name: &str, extra: &[&str]| {
        let out = path(dir.path(), name);
        let mut args = vec!["render", "--width", "96", "--height", "96", "--subdiv", "1", "--out"];
        args.push(out.to_str().expect("utf-8"));
        args.extend_from_slice(extra);
        let o = rouge(&args);
        assert!(o.status.success(), "{}", stderr(&o));
        image::open(&out).expect("png").to_rgba8()
    };
    let neutral = frame("neutral.png", &[]);
    let named_neutral = frame("named.png", &["--expression", "neutral", "--shape", "age=0"]);
    assert_eq!(neutral, named_neutral, "neutral weights draw the neutral head");
    let smile = frame("smile.png", &["--expression", "smile=0.8,jawOpen=0.3", "--shape", "age=0.3"]);
    let differ = neutral.pixels().zip(smile.pixels()).filter(|(a, b)| a != b).count();
    assert!(differ > 200, "{differ} pixels differ");

    let export = |name: &str, extra: &[&str]| {
        let out = path(dir.path(), name);
        let mut args =
            vec!["export", "mitsuba", "--medium", "skin1", "--subdiv", "0", "--out", out.to_str().expect("utf-8")];
        args.extend_from_slice(extra);
        let o = rouge(&args);
        assert!(o.status.success(), "{}", stderr(&o));
        let read = |file: &str| std::fs::read(out.join(file)).expect(file);
        (read("skin.ply"), read("eyes.ply"))
    };
    let (skin, parts) = export("a", &[]);
    assert_ne!(skin, export("b", &["--expression", "blink"]).0, "the export carries the pose");
    // Without the lashes, brows, teeth and tongue (as the head's translucency references were
    // rendered): the same tissue, and only the eyes beside it.
    let (bare_skin, eyes) = export("c", &["--without-parts"]);
    assert_eq!(bare_skin, skin, "the tissue is the same");
    assert!(eyes.len() * 2 < parts.len(), "eyes alone: {} bytes against {} with the parts", eyes.len(), parts.len());
}

#[test]
fn bench_deform_writes_rows_per_level() {
    let dir = tempfile::tempdir().expect("tempdir");
    let json = path(dir.path(), "deform.json");
    let o = rouge(&[
        "bench",
        "deform",
        "--frames",
        "2",
        "--levels",
        "0,1",
        "--width",
        "64",
        "--height",
        "64",
        "--json",
        json.to_str().expect("utf-8"),
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let rows: serde_json::Value = serde_json::from_slice(&std::fs::read(&json).expect("json")).expect("parse");
    let rows = rows.as_array().expect("rows");
    assert_eq!(rows.iter().map(|r| r["level"].as_u64()).collect::<Vec<_>>(), [Some(0), Some(1)]);
    for r in rows {
        for k in ["targets_ms", "subdivide_planned_ms", "subdivide_fresh_ms", "upload_ms", "render_ms", "frame_ms"] {
            assert!(r[k].as_f64().is_some_and(|v| v.is_finite() && v >= 0.0), "{k}: {r}");
        }
    }
    assert!(rows[1]["triangles"].as_u64() > rows[0]["triangles"].as_u64());
}

#[test]
fn bench_skin_measures_every_tone_against_the_spectral_composition() {
    let dir = tempfile::tempdir().expect("tempdir");
    let json = path(dir.path(), "skin.json");
    // Two tones and two thicknesses keep it short; render/tests/skin_maps.rs holds the target on a
    // larger grid.
    let args = ["bench", "skin", "--tones", "light,deep", "--thickness-um", "0,20"];
    let o = rouge(&[&args[..], &["--json", json.to_str().expect("utf-8")]].concat());
    assert!(o.status.success(), "{}", stderr(&o));
    let doc: serde_json::Value = serde_json::from_slice(&std::fs::read(&json).expect("json")).expect("parse");
    let rows = doc["accuracy"].as_array().expect("accuracy rows");
    assert_eq!(rows.len(), 6, "two tones and all, from the tone's albedo and from skin maps");
    for all in [&rows[2], &rows[5]] {
        assert_eq!(all["tone"], "all");
        assert_eq!(all["samples"], 2 * 5 * 2);
        // Near the skin issue's target (0.5 mean, 1.0 at the 95th percentile over all ten tones;
        // these two, with the espresso foundation at 20 µm on light skin, are harder).
        assert!(all["delta_e_mean"].as_f64().is_some_and(|v| v < 0.7), "{all}");
        assert!(all["delta_e_p95"].as_f64().is_some_and(|v| v < 1.2), "{all}");
    }
    for r in rows {
        let (mean, p95, max) = (r["delta_e_mean"].as_f64(), r["delta_e_p95"].as_f64(), r["delta_e_max"].as_f64());
        let (Some(mean), Some(p95), Some(max)) = (mean, p95, max) else { panic!("{r}") };
        assert!(mean <= max && p95 <= max && max < 1.6, "{r}");
    }
    let coverage = doc["coverage"].as_array().expect("coverage rows");
    assert_eq!(coverage.len(), 6, "two tones × three spots");
    for c in coverage {
        assert!(c["worst_difference"].as_f64().is_some_and(|v| v < 1.0), "{c}");
        assert_eq!(c["rows"].as_array().map(Vec::len), Some(2), "{c}");
    }
    let bad = rouge(&["bench", "skin", "--thickness-um=-5"]);
    assert!(!bad.status.success() && stderr(&bad).contains("--thickness-um"), "{}", stderr(&bad));
    let bad = rouge(&["bench", "skin", "--tones", "mauve"]);
    assert!(!bad.status.success() && stderr(&bad).contains("--tones mauve"), "{}", stderr(&bad));
}

/// `rouge skin maps`: the maps as the project's OpenEXR (read back to the same maps), their albedo
/// and the conditions' mask (white where the spots are, black elsewhere); bad options are named
/// and a failed write keeps the previous file.
#[test]
fn skin_maps_are_written_as_files() {
    let dir = tempfile::tempdir().expect("tempdir");
    let [exr, albedo, mask] = ["m.exr", "a.png", "mask.png"].map(|n| path(dir.path(), n));
    let s = |p: &PathBuf| p.to_str().expect("utf-8").to_string();
    let args = ["skin", "maps", "--tone", "tan", "--conditions", "moles=1", "--seed", "3", "--size-px", "64"];
    let outs = ["--out", &s(&exr), "--albedo", &s(&albedo), "--conditions-mask", &s(&mask)];
    let o = rouge(&[&args[..], &outs[..]].concat());
    assert!(o.status.success(), "{}", stderr(&o));
    let base = rouge_measure::skin::skin_tone("tan").expect("tone").params;
    let maps = rouge_model::skin::SkinMaps::from_exr_bytes(&std::fs::read(&exr).expect("exr"), &base).expect("maps");
    let conditions = "moles=1".parse().expect("conditions");
    let expected = rouge_model::skin::SkinMaps::generate(&base, &conditions, 3, 64).expect("maps");
    assert!(maps == expected, "the file holds the maps render --skin-maps draws");
    let a = image::open(&albedo).expect("albedo").to_rgba8();
    assert_eq!(a.dimensions(), (64, 64));
    let m = image::open(&mask).expect("mask").to_luma16();
    let lit = m.pixels().filter(|p| p.0[0] > 0).count();
    assert!(lit > 0 && lit < 64 * 64 / 10, "{lit} texels in the moles' mask");
    // Nothing to write, a bad tone, an unwritable file.
    let o = rouge(&["skin", "maps"]);
    assert!(o.status.code() == Some(2) && stderr(&o).contains("--out"), "{}", stderr(&o));
    let o = rouge(&["skin", "maps", "--tone", "mauve", "--out", &s(&exr)]);
    assert!(o.status.code() == Some(2) && stderr(&o).contains("--tone mauve"), "{}", stderr(&o));
    let before = std::fs::read(&exr).expect("exr");
    let missing = dir.path().join("no/such/dir/m.exr");
    let o = rouge(&["skin", "maps", "--out", missing.to_str().expect("utf-8")]);
    assert!(o.status.code() == Some(2) && stderr(&o).contains("cannot write"), "{}", stderr(&o));
    assert_eq!(std::fs::read(&exr).expect("exr"), before);
}

#[test]
fn close_ups_and_finishes_from_the_command_line() {
    let dir = tempfile::tempdir().expect("tempdir");
    let png = path(dir.path(), "lips.png");
    let o = rouge(&["render", "--close-up", "lips", "--width", "64", "--height", "48", "--out", png.to_str().unwrap()]);
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(png.exists());
    let o = rouge(&["render", "--close-up", "elbow", "--out", png.to_str().unwrap()]);
    assert!(!o.status.success() && stderr(&o).contains("cheeks"), "{}", stderr(&o));

    // A named finish is written as preset schema version 2 and read back; gloss readings fit the
    // lobe; bad input is named and leaves the file as it was.
    let preset = path(dir.path(), "red.json");
    let p = preset.to_str().unwrap();
    let o = rouge(&["finish", "builtin:lipstick_02_red", "--kind", "gloss", "--out", p]);
    assert!(o.status.success(), "{}", stderr(&o));
    let text = std::fs::read_to_string(&preset).unwrap();
    assert!(text.contains("\"version\": 2") && text.contains("\"kind\": \"gloss\""), "{text}");
    let o = rouge(&["finish", p]);
    let shown = String::from_utf8_lossy(&o.stdout).into_owned();
    assert!(o.status.success() && shown.contains("finish gloss") && shown.contains("at 60°"), "{shown}");
    let o = rouge(&["finish", p, "--gloss", "60=12"]);
    assert!(o.status.success() && stderr(&o).contains("60°: read 12.0 GU"), "{}", stderr(&o));
    let before = std::fs::read(&preset).unwrap();
    for (args, says) in [
        (&["--gloss", "45=3"][..], "20, 60 or 85"),
        (&["--gloss", "60=lots"][..], "gloss units"),
        (&["--clarity", "2"][..], "finish.clarity"),
        (&["--kind", "velvet"][..], "matte, satin, dewy or gloss"),
    ] {
        let o = rouge(&[&["finish", p][..], args].concat());
        assert!(!o.status.success() && stderr(&o).contains(says), "{args:?}: {}", stderr(&o));
    }
    assert_eq!(std::fs::read(&preset).unwrap(), before, "a refused change writes nothing");
    // Glitter: added, shown, refused naming the field, taken out.
    let o = rouge(&["finish", p, "--glitter-size-um", "150", "--glitter-color", "0.9,0.8,0.4"]);
    assert!(o.status.success(), "{}", stderr(&o));
    let text = std::fs::read_to_string(&preset).unwrap();
    assert!(text.contains("\"glitter\"") && text.contains("\"size_um\": 150.0"), "{text}");
    let shown = String::from_utf8_lossy(&rouge(&["finish", p]).stdout).into_owned();
    assert!(shown.contains("glitter 150 µm flakes"), "{shown}");
    let o = rouge(&["finish", p, "--glitter-density", "30"]);
    assert!(!o.status.success() && stderr(&o).contains("glitter.density_per_mm2"), "{}", stderr(&o));
    let o = rouge(&["finish", p, "--glitter-color", "1,2"]);
    assert!(!o.status.success() && stderr(&o).contains("R,G,B"), "{}", stderr(&o));
    let o = rouge(&["finish", p, "--no-glitter"]);
    assert!(o.status.success() && !std::fs::read_to_string(&preset).unwrap().contains("glitter"));
    let o = rouge(&["finish", "builtin:lipstick_02_red", "--kind", "matte"]);
    assert!(!o.status.success() && stderr(&o).contains("--out"), "{}", stderr(&o));
    let o = rouge(&["finish", p, "--clear"]);
    assert!(o.status.success());
    assert!(std::fs::read_to_string(&preset).unwrap().contains("\"version\": 1"));
}
