//! `rouge analyze coverage|match|mix|metamerism|correct|recipe`, `rouge qc` and `rouge import
//! --repeatability` through the binary: tables, JSON, PNG plots, and errors that name the file,
//! line and column.

use std::path::Path;
use std::process::{Command, Output};

fn rouge(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_rouge"))
        .args(args)
        .current_dir(Path::new(env!("CARGO_MANIFEST_DIR")).join(".."))
        .output()
        .expect("run rouge")
}

fn stdout(o: &Output) -> String {
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    String::from_utf8_lossy(&o.stdout).into_owned()
}

const FOUNDATIONS: [&str; 5] = [
    "foundation_01_porcelain",
    "foundation_02_ivory",
    "foundation_03_sand",
    "foundation_04_caramel",
    "data/presets/foundation_05_espresso.json",
];

#[test]
fn coverage_prints_the_table_writes_json_and_a_png() {
    let dir = tempfile::tempdir().unwrap();
    let (json, png) = (dir.path().join("c.json"), dir.path().join("c.png"));
    let args = ["analyze", "coverage", "builtin:foundation_02_ivory", "--json", json.to_str().unwrap(), "--plot"];
    let out = stdout(&rouge(&[&args[..], &[png.to_str().unwrap()]].concat()));
    assert!(out.contains("hiding thickness (contrast ratio 0.98): 77.96 µm"), "{out}");
    let v: serde_json::Value = serde_json::from_str(&std::fs::read_to_string(&json).unwrap()).unwrap();
    let rows = v["rows"].as_array().unwrap();
    assert!((rows[0]["contrast_ratio"].as_f64().unwrap() - 0.01 / 0.80).abs() < 1e-12);
    assert_eq!(v["skins"].as_array().unwrap().len(), 2);
    let img = image::open(&png).unwrap();
    assert!(img.width() >= 800 && img.height() >= 300);
}

#[test]
fn match_finds_the_shade_a_synthetic_skin_was_made_from() {
    // A skin the colour of 60 µm of Caramel over the ColorChecker's light skin, as a table.
    let dir = tempfile::tempdir().unwrap();
    let skin = dir.path().join("skin.csv");
    let preset = rouge_measure::Preset::load(Path::new("../data/presets/foundation_04_caramel.json")).unwrap();
    let layer = rouge_measure::analysis::Layer::from_preset(&preset).unwrap();
    let rows: String = rouge_measure::spectrum::working_wavelengths_nm()
        .iter()
        .zip(layer.reflectance_over(f64::INFINITY, &rouge_measure::Spectrum::constant(0.3)).0)
        .map(|(nm, r)| format!("{nm},{r}\n"))
        .collect();
    std::fs::write(&skin, format!("wavelength_nm,caramel_skin\n{rows}")).unwrap();
    let json = dir.path().join("m.json");
    let mut args = vec!["analyze", "match"];
    args.extend(FOUNDATIONS);
    args.extend(["--skin", skin.to_str().unwrap(), "--json", json.to_str().unwrap()]);
    let out = stdout(&rouge(&args));
    assert!(out.contains("Foundation 04 Caramel") && out.contains("0 of 1 skins in gaps"), "{out}");
    let v: serde_json::Value = serde_json::from_str(&std::fs::read_to_string(&json).unwrap()).unwrap();
    assert_eq!(v["skins"][0]["best_shade"], "Foundation 04 Caramel");
    assert!(v["skins"][0]["delta_e"].as_f64().unwrap() < 1e-9);
}

#[test]
fn mix_reaches_a_mixture_of_its_bases() {
    let out = stdout(&rouge(&[
        "analyze",
        "mix",
        "foundation_01_porcelain",
        "foundation_04_caramel",
        "--target-preset",
        "foundation_04_caramel",
    ]));
    let line = out.lines().find(|l| l.trim_start().starts_with("Foundation 04 Caramel")).unwrap();
    assert!(line.ends_with(" 1.0000") && out.contains("ΔE2000 0.000"), "{out}");
}

#[test]
fn bad_inputs_are_named() {
    let dir = tempfile::tempdir().unwrap();
    let skin = dir.path().join("skin.csv");
    std::fs::write(&skin, "wavelength_nm,a\n380,0.3\n390,oops\n").unwrap();
    let o = rouge(&["analyze", "coverage", "foundation_02_ivory", "--skin", skin.to_str().unwrap()]);
    let err = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(2));
    assert!(err.contains("skin.csv:3:2"), "{err}");
    let o = rouge(&["analyze", "coverage", "no_such_preset"]);
    assert!(String::from_utf8_lossy(&o.stderr).contains("built-in: blush_01_petal"));
    let o = rouge(&["analyze", "mix", "foundation_01_porcelain", "foundation_04_caramel", "--target", "50,0"]);
    assert!(String::from_utf8_lossy(&o.stderr).contains("expected three finite numbers"));
    let o = rouge(&["analyze", "match", "foundation_01_porcelain", "--thickness-um", "20:10"]);
    assert!(String::from_utf8_lossy(&o.stderr).contains("the maximum is below the minimum"));
}

#[test]
fn metamerism_and_correct_write_json_and_refuse_bad_input() {
    let dir = tempfile::tempdir().unwrap();
    let json = dir.path().join("m.json");
    let args = ["analyze", "metamerism", "foundation_03_sand", "foundation_02_ivory", "--test", "A,F11"];
    let out = stdout(&rouge(&[&args[..], &["--json", json.to_str().unwrap()]].concat()));
    assert!(out.contains("FL11 / CIE 1931") && out.contains("D65 / CIE 1964"), "{out}");
    let v: serde_json::Value = serde_json::from_str(&std::fs::read_to_string(&json).unwrap()).unwrap();
    // Two test illuminants × three corrections, and the observer index with three corrections.
    assert_eq!(v["illuminant"].as_array().unwrap().len(), 6);
    assert_eq!(v["observer"].as_array().unwrap().len(), 3);
    // A spectrum file as the batch (one of several, by name) against the recipe's prediction.
    let out = stdout(&rouge(&[
        "analyze",
        "correct",
        "--colorant",
        "foundation_01_porcelain,foundation_04_caramel",
        "--recipe",
        "0.4,0.6",
        "--batch",
        "data/skin/colorchecker_skin.csv#light_skin",
    ]));
    assert!(out.contains("predicted after correction"), "{out}");
    let o =
        rouge(&["analyze", "correct", "--colorant", "foundation_01_porcelain", "--recipe", "0.4,0.6", "--batch", "x"]);
    assert_eq!(o.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&o.stderr).contains("2 amounts for 1 colorants"));
    let o = rouge(&["analyze", "metamerism", "foundation_03_sand", "data/skin/colorchecker_skin.csv"]);
    assert_eq!(o.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&o.stderr).contains("pick one"), "{}", String::from_utf8_lossy(&o.stderr));
}

#[test]
fn recipe_ranks_recipes_writes_json_and_names_bad_constraints() {
    let dir = tempfile::tempdir().unwrap();
    let json = dir.path().join("r.json");
    // A lipstick as the target from a library of one folder and a file: the lipstick itself is
    // excluded, the foundations are limited, two colorants are tied and one has a price.
    let out = stdout(&rouge(&[
        "analyze",
        "recipe",
        "lipstick_01_nude",
        "--library",
        "data/presets",
        "--k",
        "2",
        "--illuminants",
        "D65,A",
        "--weights",
        "1,0.5",
        "--max",
        "lipstick_01_nude=0,foundation_01_porcelain=0.3",
        "--fixed",
        "blush_01_petal:blush_02_coral=1",
        "--cost",
        "lipstick_02_red=12.5",
        "--top",
        "5",
        "--json",
        json.to_str().unwrap(),
        "--png",
        dir.path().join("r.png").to_str().unwrap(),
    ]));
    assert!(out.contains("ΔE00 A") && out.contains("13 colorants, k = 2"), "{out}");
    assert_eq!(&std::fs::read(dir.path().join("r.png")).unwrap()[1..4], b"PNG");
    let v: serde_json::Value = serde_json::from_str(&std::fs::read_to_string(&json).unwrap()).unwrap();
    let recipes = v["recipes"].as_array().unwrap();
    assert_eq!(recipes.len(), 5);
    for r in recipes {
        let amount = |name: &str| {
            r["colorants"].as_array().unwrap().iter().find(|c| c["name"] == name).map(|c| c["amount"].as_f64().unwrap())
        };
        assert!(amount("lipstick_01_nude").is_none(), "{r}");
        assert!(amount("foundation_01_porcelain").unwrap_or(0.0) <= 0.3 + 1e-12, "{r}");
        if let Some(petal) = amount("blush_01_petal") {
            assert!((petal - amount("blush_02_coral").unwrap()).abs() < 1e-9, "{r}");
        }
        assert!((r["cost"].as_f64().unwrap() - 12.5 * amount("lipstick_02_red").unwrap_or(0.0)).abs() < 1e-9);
        assert_eq!(r["delta_e_2000"].as_array().unwrap().len(), 2);
    }
    let objectives: Vec<f64> = recipes.iter().map(|r| r["objective"].as_f64().unwrap()).collect();
    assert!(objectives.windows(2).all(|w| w[0] <= w[1]), "{objectives:?}");
    // Impossible constraints and a colorant on another grid say what and where.
    let err = |args: &[&str]| {
        let o = rouge(&[&["analyze", "recipe", "lipstick_01_nude", "--library", "data/presets"], args].concat());
        assert!(!o.status.success());
        String::from_utf8_lossy(&o.stderr).into_owned()
    };
    let e = err(&["--min", "foundation_02_ivory=0.7,foundation_03_sand=0.6"]);
    assert!(e.contains("sum to 1.2") && e.contains("foundation_03_sand ≥ 0.6"), "{e}");
    let e = err(&["--min", "foundation_02_ivory=0.6", "--max", "foundation_02_ivory=0.4"]);
    assert!(e.contains("colorant `foundation_02_ivory`: min 0.6 > max 0.4"), "{e}");
    let e = err(&["--fixed", "blush_01_petal:nothing=2"]);
    assert!(e.contains("no colorant `nothing`"), "{e}");
    let e = err(&[
        "--fixed",
        "blush_01_petal:blush_02_coral=2",
        "--max",
        "blush_01_petal=0.1",
        "--min",
        "blush_02_coral=0.2",
    ]);
    assert!(e.contains("fixed ratios of blush_01_petal, blush_02_coral contradict"), "{e}");
    let preset: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string("../data/presets/blush_01_petal.json").unwrap()).unwrap();
    let mut short = preset.clone();
    for field in ["wavelengths_nm", "s_per_mm", "k_per_mm"] {
        let cut: Vec<serde_json::Value> = short[field].as_array().unwrap()[4..].to_vec();
        short[field] = serde_json::Value::Array(cut);
    }
    let bad = dir.path().join("short_blush.json");
    std::fs::write(&bad, short.to_string()).unwrap();
    let o =
        rouge(&["analyze", "recipe", "lipstick_01_nude", "--library", "foundation_02_ivory", bad.to_str().unwrap()]);
    let e = String::from_utf8_lossy(&o.stderr);
    assert!(!o.status.success() && e.contains("short_blush.json") && e.contains("wavelengths_nm"), "{e}");
}

#[test]
fn qc_draws_the_batch_report_with_its_tolerance_contours() {
    let dir = tempfile::tempdir().unwrap();
    let png = dir.path().join("qc.png");
    let json = dir.path().join("qc.json");
    let out = stdout(&rouge(&[
        "qc",
        "foundation_03_sand",
        "foundation_02_ivory",
        "foundation_04_caramel",
        "data/skin/colorchecker_skin.csv#light_skin",
        "--metric",
        "cmc",
        "--tolerance",
        "6",
        "--png",
        png.to_str().unwrap(),
        "--json",
        json.to_str().unwrap(),
    ]));
    assert!(out.contains("pass") && out.contains("FAIL"), "{out}");
    let bytes = std::fs::read(&png).unwrap();
    assert_eq!(&bytes[1..4], b"PNG");
    let image = image::load_from_memory(&bytes).unwrap().to_rgb8();
    // Two panels side by side; the pass dots (green) and the tolerance contour (red) are drawn.
    assert_eq!(image.width(), 840);
    let has = |rgb: [u8; 3]| image.pixels().any(|p| p.0 == rgb);
    assert!(has([44, 160, 44]) && has([214, 39, 40]), "no pass marker or CMC contour");
    let o =
        rouge(&["qc", "foundation_03_sand", "foundation_02_ivory", "--tolerance=-1", "--png", png.to_str().unwrap()]);
    assert!(!o.status.success() && String::from_utf8_lossy(&o.stderr).contains("tolerance -1"));
}

#[test]
fn import_reads_the_repeatability_per_wavelength_from_a_file() {
    let dir = tempfile::tempdir().unwrap();
    let table = |from: usize| {
        let mut t = String::from("wavelength_nm,u\n");
        for nm in (from..=780).step_by(5) {
            // A spectrophotometer noisier in the blue: 0.004 at 380 nm falling to 0.001.
            t += &format!("{nm},{}\n", 0.001 + 0.003 * ((780 - nm) as f64 / 400.0).powi(3));
        }
        t
    };
    let u_file = dir.path().join("u.csv");
    std::fs::write(&u_file, table(380)).unwrap();
    let out = dir.path().join("p.json");
    let run = |u: &Path| {
        rouge(&[
            "import",
            "data/measurements/lipstick_02_red.csv",
            "--out",
            out.to_str().unwrap(),
            "--json",
            "--repeatability",
            u.to_str().unwrap(),
        ])
    };
    let v: serde_json::Value = serde_json::from_str(&stdout(&run(&u_file))).unwrap();
    assert!(v["uncertainty"]["source"].as_str().unwrap().contains("per wavelength from"), "{v}");
    let preset: serde_json::Value = serde_json::from_str(&std::fs::read_to_string(&out).unwrap()).unwrap();
    let u = preset["uncertainty"]["u_reflectance"].as_array().unwrap();
    assert!((u[0].as_f64().unwrap() - 0.004).abs() < 1e-12 && (u[80].as_f64().unwrap() - 0.001).abs() < 1e-12);
    // A file that stops short of 380 nm is refused, naming the file.
    let short = dir.path().join("short.csv");
    std::fs::write(&short, table(400)).unwrap();
    let o = run(&short);
    let e = String::from_utf8_lossy(&o.stderr);
    assert!(!o.status.success() && e.contains("short.csv"), "{e}");
}

#[path = "../../model/tests/support/tmpfs.rs"]
mod tmpfs;

#[test]
fn an_output_that_does_not_fit_on_the_disk_fails_naming_it_and_keeps_the_previous_file() {
    let dir = tempfile::tempdir().unwrap();
    let mount = dir.path().join("small disk");
    let _disk = match tmpfs::Tmpfs::mount(&mount, "1m") {
        Ok(d) => d,
        Err(e) => {
            eprintln!("SKIPPED: the full-disk test needs to mount a tmpfs (root): {e}");
            return;
        }
    };
    let (png, json) = (mount.join("coverage.png"), mount.join("coverage.json"));
    std::fs::write(&png, b"the previous plot").unwrap();
    std::fs::write(&json, b"{\"previous\": true}").unwrap();
    // Fill the disk.
    {
        use std::io::Write;
        let mut filler = std::fs::File::create(mount.join("filler")).unwrap();
        while filler.write_all(&[0u8; 4096]).is_ok() {}
    }
    for (flag, path) in [("--plot", &png), ("--json", &json)] {
        let before = std::fs::read(path).unwrap();
        let o = rouge(&["analyze", "coverage", "builtin:foundation_02_ivory", flag, path.to_str().unwrap()]);
        let err = String::from_utf8_lossy(&o.stderr);
        assert!(!o.status.success(), "{flag} onto a full disk succeeded");
        assert!(err.contains(&path.display().to_string()) && err.contains("No space left"), "{err}");
        let after = std::fs::read(path).unwrap();
        assert!(after == before, "{flag}: the previous file is not kept whole ({} bytes now)", after.len());
    }
    let mut names: Vec<String> =
        std::fs::read_dir(&mount).unwrap().map(|e| e.unwrap().file_name().to_string_lossy().into_owned()).collect();
    names.sort();
    assert_eq!(names, ["coverage.json", "coverage.png", "filler"], "no temporary file is left");
}
