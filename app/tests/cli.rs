//! The `rouge` binary end to end: outputs, exit statuses, error messages, files written.

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

fn root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("..")
}

fn rouge(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_rouge")).args(args).current_dir(root()).output().expect("run rouge")
}

/// `rouge render` of a small frame to `out` with the Vulkan loader pointed at no driver, and
/// `backend` as WGPU_BACKEND (or wgpu's own choice).
fn render_without_vulkan_driver(out: &Path, (w, h): (u32, u32), backend: Option<&str>) -> Output {
    let mut cmd = Command::new(env!("CARGO_BIN_EXE_rouge"));
    cmd.args(["render", "--width", &w.to_string(), "--height", &h.to_string(), "--out"])
        .arg(out)
        .env("VK_ICD_FILENAMES", "/nonexistent/rouge-test-icd.json")
        .env("VK_DRIVER_FILES", "/nonexistent/rouge-test-icd.json")
        .current_dir(root());
    match backend {
        Some(b) => cmd.env("WGPU_BACKEND", b),
        None => cmd.env_remove("WGPU_BACKEND"),
    };
    cmd.output().expect("run rouge")
}

fn stdout(o: &Output) -> String {
    String::from_utf8_lossy(&o.stdout).into_owned()
}

fn stderr(o: &Output) -> String {
    String::from_utf8_lossy(&o.stderr).into_owned()
}

#[test]
fn demo_prints_a_report() {
    let o = rouge(&["demo"]);
    assert!(o.status.success(), "{}", stderr(&o));
    let s = stdout(&o);
    assert!(s.contains("Foundation 02 Ivory"), "{s}");
    assert!(s.contains("check R     max |measured − from S,K|"), "{s}");
}

#[test]
fn km_invert_prints_numbers_that_read_back_bit_for_bit() {
    let o = rouge(&["km", "invert", "--r-inf", "0.5", "--r", "0.3", "--rg", "0.05", "--thickness-mm", "0.02"]);
    assert!(o.status.success(), "{}", stderr(&o));
    let v: serde_json::Value = serde_json::from_str(&stdout(&o)).expect("json");
    let c = rouge_measure::km::invert_s_k(0.5, 0.3, 0.05, 0.02).expect("valid");
    assert_eq!(v["s_per_mm"].as_f64().map(f64::to_bits), Some(c.s_per_mm.to_bits()));
    assert_eq!(v["k_per_mm"].as_f64().map(f64::to_bits), Some(c.k_per_mm.to_bits()));
}

#[test]
fn errors_exit_2_with_a_message() {
    for args in [
        &["km", "invert", "--r-inf", "1.2", "--r", "0.3", "--rg", "0.05", "--thickness-mm", "0.02"][..],
        &["km", "layer", "--s", "-1", "--k", "1", "--thickness-mm", "1"],
        &["km", "stack", "--r", "0.1,0.2", "--t", "0.5"],
        &["km", "stack", "--r", "0.7", "--t", "0.5"],
        &["color", "does/not/exist.csv"],
        &["color", "data/skin/colorchecker_skin.csv", "--illuminant", "F3"],
    ] {
        let o = rouge(args);
        assert_eq!(o.status.code(), Some(2), "{args:?}: {}", stdout(&o));
        assert!(!stderr(&o).trim().is_empty(), "{args:?}: no message");
    }
}

#[test]
fn import_writes_a_loadable_preset_and_a_failed_import_keeps_the_old_one() {
    let dir = tempfile::tempdir().expect("tempdir");
    let out = dir.path().join("p.json");
    let out_s = out.to_str().expect("utf-8 path");
    let o = rouge(&["import", "data/measurements/lipstick_02_red.csv", "--out", out_s]);
    assert!(o.status.success(), "{}", stderr(&o));
    let preset = rouge_measure::Preset::load(&out).expect("loads");
    assert_eq!(preset.kind, rouge_measure::Kind::Lipstick);
    let before = std::fs::read(&out).expect("read");

    let o = rouge(&["import", "data/measurements/bad/non_numeric.csv", "--out", out_s]);
    assert_eq!(o.status.code(), Some(2));
    let e = stderr(&o);
    assert!(e.contains("non_numeric.csv:27:3"), "{e}");
    assert_eq!(std::fs::read(&out).expect("read"), before, "a failed import must not touch the old preset");

    let o = rouge(&["import", "data/measurements/bad/r_outside_bounds.csv", "--out", out_s]);
    assert_eq!(o.status.code(), Some(2));
    assert!(stderr(&o).contains("at 550 nm"), "{}", stderr(&o));
    assert_eq!(std::fs::read(&out).expect("read"), before);
}

#[test]
fn import_json_report_and_color_output() {
    let o = rouge(&[
        "import",
        "data/measurements/formats/foundation_02_ivory.ti3",
        "--thickness-mm",
        "0.02",
        "--json",
        "--out",
    ]);
    assert_eq!(o.status.code(), Some(2), "--out needs a value");
    let dir = tempfile::tempdir().expect("tempdir");
    let out = dir.path().join("t.json");
    let o = rouge(&[
        "import",
        "data/measurements/formats/foundation_02_ivory.ti3",
        "--thickness-mm",
        "0.02",
        "--json",
        "--out",
        out.to_str().expect("utf-8"),
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let v: serde_json::Value = serde_json::from_str(&stdout(&o)).expect("json");
    assert!(v["report"]["delta_e_2000_r"].as_f64().is_some_and(|d| d < 1e-6), "{v}");
    assert_eq!(v["scale"], "percent (detected: median value above 1.5)");

    let o = rouge(&["color", "data/skin/colorchecker_skin.csv"]);
    assert!(o.status.success(), "{}", stderr(&o));
    let v: serde_json::Value = serde_json::from_str(&stdout(&o)).expect("json");
    let names: Vec<&str> = v.as_array().expect("array").iter().filter_map(|x| x["name"].as_str()).collect();
    assert_eq!(names, ["dark_skin", "light_skin"]);
    let lab = &v[1]["lab"];
    // Light skin is a light, warm colour: L* about 66, a* and b* positive.
    assert!(lab[0].as_f64().is_some_and(|l| (60.0..72.0).contains(&l)), "{lab}");
    assert!(lab[1].as_f64().is_some_and(|a| a > 5.0) && lab[2].as_f64().is_some_and(|b| b > 5.0), "{lab}");
}

#[test]
fn color_reads_cgats_as_import_does() {
    // The X-Rite export (10 nm) and the Rouge CSV (5 nm) of one product: the same samples by
    // name, the same colours up to the resampling of the coarser grid.
    let colours = |file: &str| {
        let o = rouge(&["color", file]);
        assert!(o.status.success(), "{file}: {}", stderr(&o));
        let v: serde_json::Value = serde_json::from_str(&stdout(&o)).expect("json");
        v.as_array()
            .expect("array")
            .iter()
            .map(|c| {
                let lab: Vec<f64> = c["lab"].as_array().expect("lab").iter().filter_map(|x| x.as_f64()).collect();
                (c["name"].as_str().expect("name").to_ascii_lowercase(), lab)
            })
            .collect::<Vec<_>>()
    };
    let cgats = colours("data/measurements/formats/foundation_02_ivory_xrite.txt");
    let csv = colours("data/measurements/foundation_02_ivory.csv");
    assert_eq!(cgats.iter().map(|c| c.0.as_str()).collect::<Vec<_>>(), ["r_inf", "r", "rg"]);
    for ((name, a), (_, b)) in cgats.iter().zip(&csv) {
        assert!(a.iter().zip(b).all(|(x, y)| (x - y).abs() < 0.1), "{name}: {a:?} vs {b:?}");
    }
}

#[test]
fn help_names_every_subcommand() {
    let o = rouge(&["--help"]);
    assert!(o.status.success());
    let s = stdout(&o);
    for sub in ["import", "demo", "km", "color", "render", "export", "bench"] {
        assert!(s.contains(sub), "--help lacks {sub}: {s}");
    }
}

#[test]
fn radiance_white_standard_and_saunderson_options_change_the_result() {
    let dir = tempfile::tempdir().expect("tempdir");
    let out = dir.path().join("c.json");
    let out_s = out.to_str().expect("utf-8");
    let cs = "data/measurements/formats/foundation_02_ivory_cs2000.csv";
    let s_max = |extra: &[&str]| {
        let mut args = vec!["import", cs, "--thickness-mm", "0.02", "--json", "--out", out_s];
        args.extend_from_slice(extra);
        let o = rouge(&args);
        assert!(o.status.success(), "{extra:?}: {}", stderr(&o));
        let v: serde_json::Value = serde_json::from_str(&stdout(&o)).expect("json");
        v["report"]["s_range_per_mm"][1][0].as_f64().expect("S max")
    };
    let default = s_max(&[]);
    let flat = s_max(&["--white-reflectance", "0.97"]);
    let white = dir.path().join("white.csv");
    std::fs::write(&white, "wavelength_nm,baso4\n380,0.97\n780,0.97\n").expect("write");
    let spectrum = s_max(&["--white-spectrum", white.to_str().expect("utf-8")]);
    assert_ne!(default, flat, "the white standard's reflectance must matter");
    assert!((flat - spectrum).abs() <= 1e-9 * flat, "flat 0.97 and a flat 0.97 spectrum agree: {flat} {spectrum}");
    let saunderson = s_max(&["--saunderson-ior", "1.5"]);
    assert_ne!(default, saunderson);

    std::fs::write(&white, "wavelength_nm,baso4\n380,0.97\n780,1.2\n").expect("write");
    let o = rouge(&[
        "import",
        cs,
        "--thickness-mm",
        "0.02",
        "--out",
        out_s,
        "--white-spectrum",
        white.to_str().expect("utf-8"),
    ]);
    assert_eq!(o.status.code(), Some(2));
    assert!(stderr(&o).contains("at 780 nm"), "{}", stderr(&o));
}

#[test]
fn samples_are_chosen_by_name() {
    let dir = tempfile::tempdir().expect("tempdir");
    let text = std::fs::read_to_string(root().join("data/measurements/formats/foundation_02_ivory_xrite.txt"))
        .expect("read")
        .replace("\tR_INF\t", "\tOPAQUE\t")
        .replace("\tRG\t", "\tCARD\t");
    let file = dir.path().join("renamed.txt");
    std::fs::write(&file, text).expect("write");
    let (file, out) = (file.to_str().expect("utf-8"), dir.path().join("p.json"));
    let out = out.to_str().expect("utf-8");
    let o = rouge(&["import", file, "--out", out]);
    assert_eq!(o.status.code(), Some(2));
    assert!(stderr(&o).contains("no sample named `R_INF` (samples: OPAQUE, R, CARD)"), "{}", stderr(&o));
    let o = rouge(&["import", file, "--samples", "OPAQUE,R,CARD", "--out", out]);
    assert!(o.status.success(), "{}", stderr(&o));
    let o = rouge(&["import", file, "--samples", "OPAQUE,R", "--out", out]);
    assert_eq!(o.status.code(), Some(2));
    assert!(stderr(&o).contains("three names"), "{}", stderr(&o));
}

#[test]
fn plot_writes_the_material_panels_as_png_and_refuses_other_names() {
    let dir = tempfile::tempdir().expect("tempdir");
    let (out, png) = (dir.path().join("p.json"), dir.path().join("p.png"));
    let args = ["import", "data/measurements/blush_01_petal.csv", "--out", out.to_str().expect("utf-8"), "--plot"];
    let o = rouge(&[&args[..], &[png.to_str().expect("utf-8")]].concat());
    assert!(o.status.success(), "{}", stderr(&o));
    let img = image::open(&png).expect("a PNG").to_rgb8();
    // Four panels, two to a row, each with its legend under it.
    assert_eq!((img.width(), img.height()), (840, 764));
    // Each series colour is drawn: the six of the reflectance, S and K panels (app/src/material_plots.rs)
    // and the three channels of R0 and T.
    let has = |rgb: [u8; 3]| img.pixels().any(|p| p.0.iter().zip(rgb).all(|(&a, b)| a.abs_diff(b) <= 2));
    for rgb in [
        [31, 119, 180],
        [255, 127, 14],
        [214, 39, 140],
        [44, 160, 44],
        [200, 60, 40],
        [220, 60, 50],
        [60, 170, 70],
        [70, 110, 230],
    ] {
        assert!(has(rgb), "no curve in {rgb:?}");
    }
    let svg = dir.path().join("p.svg");
    let o = rouge(&[&args[..], &[svg.to_str().expect("utf-8")]].concat());
    assert_eq!(o.status.code(), Some(2));
    assert!(stderr(&o).contains("p.svg`: the plot is written as PNG"), "{}", stderr(&o));
    assert!(!svg.exists());
}

#[test]
fn render_writes_png_and_exr_and_bad_inputs_name_their_file() {
    let dir = tempfile::tempdir().expect("tempdir");
    let png = dir.path().join("face.png");
    let png_s = png.to_str().expect("utf-8 path");
    let o = rouge(&["render", "--width", "96", "--height", "64", "--subdiv", "1", "--out", png_s]);
    assert!(o.status.success(), "{}", stderr(&o));
    let img = image::open(&png).expect("a PNG").to_rgba8();
    assert_eq!((img.width(), img.height()), (96, 64));
    // The face is in the middle and is not background grey.
    let p = img.get_pixel(48, 28).0;
    assert!(p[0] > p[2] + 20, "skin at the centre: {p:?}");
    let before = std::fs::read(&png).expect("read");

    let exr = dir.path().join("face.exr");
    let o = rouge(&[
        "render",
        "--width",
        "32",
        "--height",
        "24",
        "--subdiv",
        "0",
        "--look",
        "bare",
        "--out",
        exr.to_str().expect("utf-8"),
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(std::fs::metadata(&exr).expect("exr written").len() > 1000);

    let text = dir.path().join("not-an-exr.exr");
    std::fs::write(&text, "hello").expect("write");
    let bad_look = dir.path().join("look.json");
    std::fs::write(&bad_look, r#"{"schema": "rouge-look", "version": 1, "layers": [{"preset": "nowhere.json", "thickness": {"uniform_mm": 0.01}}]}"#)
        .expect("write");
    for (args, names) in [
        (vec!["--mesh", "does/not/exist.obj"], "does/not/exist.obj"),
        (vec!["--mesh", "data/skin/colorchecker_skin.csv"], "colorchecker_skin.csv"),
        (vec!["--look", "does/not/exist.json"], "does/not/exist.json"),
        (vec!["--look", bad_look.to_str().expect("utf-8")], "nowhere.json"),
        (vec!["--env", text.to_str().expect("utf-8")], "not-an-exr.exr"),
        (vec!["--sss-samples", "16"], "odd"),
    ] {
        let mut all = vec!["render", "--width", "16", "--height", "16", "--subdiv", "0"];
        all.extend(args.iter().copied());
        all.extend(["--out", png_s]);
        let o = rouge(&all);
        assert_eq!(o.status.code(), Some(2), "{args:?}");
        assert!(stderr(&o).contains(names), "{args:?}: {}", stderr(&o));
        assert_eq!(std::fs::read(&png).expect("read"), before, "{args:?}: a failed render must keep the old image");
    }
    let o = rouge(&["render", "--width", "16", "--height", "16", "--subdiv", "0", "--out", "face.bmp"]);
    assert_eq!(o.status.code(), Some(2));
    assert!(stderr(&o).contains("face.bmp"), "{}", stderr(&o));
}

/// The app in a real window under Xvfb with `args`, its data in `data_dir`, ended after
/// `timeout_s`; `None` (and a line saying so) without xvfb-run.
fn app_under_xvfb(timeout_s: u32, data_dir: &Path, args: &[&std::ffi::OsStr]) -> Option<Output> {
    app_under_xvfb_with(timeout_s, data_dir, args, &[])
}

/// [`app_under_xvfb`] with `env` set.
fn app_under_xvfb_with(
    timeout_s: u32,
    data_dir: &Path,
    args: &[&std::ffi::OsStr],
    env: &[(&str, &str)],
) -> Option<Output> {
    if Command::new("xvfb-run").arg("--help").output().is_err() {
        eprintln!("skipped: xvfb-run is not installed (tests/run.sh installs xvfb)");
        return None;
    }
    let o = Command::new("timeout")
        .args([&timeout_s.to_string(), "xvfb-run", "-a", "-s", "-screen 0 1280x800x24"])
        .arg(env!("CARGO_BIN_EXE_rouge"))
        .args(args)
        .env("XDG_DATA_HOME", data_dir)
        .env("WINIT_UNIX_BACKEND", "x11")
        .envs(env.iter().copied())
        .env_remove("WAYLAND_DISPLAY")
        .current_dir(root())
        .output()
        .expect("run xvfb-run");
    Some(o)
}

#[test]
fn the_app_opens_a_real_window_under_xvfb_and_draws_the_face() {
    let dir = tempfile::tempdir().expect("tempdir");
    let shot = dir.path().join("window.png");
    let Some(o) = app_under_xvfb(180, dir.path(), &["--window-screenshot".as_ref(), shot.as_ref()]) else { return };
    assert!(o.status.success(), "status {:?}\n{}", o.status, stderr(&o));
    let img = image::open(&shot).expect("the window screenshot").to_rgba8();
    assert!(img.width() >= 800 && img.height() >= 500, "{}×{}", img.width(), img.height());
    // Skin-coloured pixels in the middle of the window: the face was drawn.
    let (w, h) = (img.width(), img.height());
    let skin = (h / 4..3 * h / 4)
        .flat_map(|y| (w / 3..2 * w / 3).map(move |x| (x, y)))
        .filter(|&(x, y)| {
            let p = img.get_pixel(x, y).0.map(i32::from);
            p[0] > 120 && p[0] > p[2] + 30 && p[1] > 60
        })
        .count();
    assert!(skin > 20_000, "{skin} skin-coloured pixels in the window's centre");
}

#[test]
fn a_lost_device_restarts_the_app_in_the_same_process_with_the_work_recovered() {
    // The device is destroyed once the face is shown: the app writes the autosave, closes, and
    // becomes Rouge again with --recover (exec: xvfb-run, waiting for this process, keeps its
    // display), which adopts the autosave and takes the screenshot.
    let dir = tempfile::tempdir().expect("tempdir");
    let shot = dir.path().join("window.png");
    let env = [(rouge_app::gui::LOSE_DEVICE_ENV, "1")];
    let Some(o) = app_under_xvfb_with(240, dir.path(), &["--window-screenshot".as_ref(), shot.as_ref()], &env) else {
        return;
    };
    let err = stderr(&o);
    assert!(o.status.success(), "status {:?}\n{err}", o.status);
    assert!(err.contains("the graphics device was lost") && err.contains("restarting"), "{err}");
    assert!(err.contains("the unsaved work is recovered from the autosave"), "{err}");
    assert!(dir.path().join("rouge/recovery").is_dir(), "the autosave is kept until the work is saved");
    let img = image::open(&shot).expect("the restarted app's screenshot").to_rgba8();
    assert!(img.width() >= 800 && img.height() >= 500, "{}×{}", img.width(), img.height());
}

#[test]
fn a_mesh_that_cannot_be_read_ends_the_window_screenshot_with_its_error() {
    let dir = tempfile::tempdir().expect("tempdir");
    let mesh = dir.path().join("broken.obj");
    std::fs::write(&mesh, "v 0 0 0\nv 1 0\n").expect("write");
    let shot = dir.path().join("window.png");
    // It waited for a face for ever: the timeout's 124 was the answer.
    let args = ["--mesh".as_ref(), mesh.as_ref(), "--window-screenshot".as_ref(), shot.as_ref()];
    let Some(o) = app_under_xvfb(120, dir.path(), &args) else { return };
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
    assert!(stderr(&o).contains("broken.obj:2:"), "{}", stderr(&o));
    assert!(!shot.exists(), "no screenshot of an empty viewport");
}

#[test]
fn without_a_gpu_driver_render_exits_2_with_the_package_to_install() {
    // Only Vulkan, and a Vulkan loader that finds no driver: no adapter at all.
    let out = std::env::temp_dir().join(format!("rouge-no-driver-{}.png", std::process::id()));
    let o = render_without_vulkan_driver(&out, (64, 48), Some("vulkan"));
    let err = stderr(&o);
    assert_eq!(o.status.code(), Some(2), "{err}");
    assert!(err.contains("apt-get install mesa-vulkan-drivers"), "{err}");
    assert!(!err.contains("panicked") && !err.contains("stack backtrace"), "{err}");
    assert_eq!(err.trim_end().lines().count(), 1, "one line, not a trace: {err}");
    assert!(!out.exists());
}

#[test]
fn without_a_vulkan_driver_render_writes_the_face_through_gl() {
    // The fresh machine of the renderer-architecture issue: Mesa's OpenGL (llvmpipe through EGL)
    // but no Vulkan driver. wgpu then picks its GL backend, which must render the face.
    let out = std::env::temp_dir().join(format!("rouge-gl-only-{}.png", std::process::id()));
    let o = render_without_vulkan_driver(&out, (160, 120), None);
    let err = stderr(&o);
    assert!(o.status.success(), "{err}");
    assert!(err.contains("(Gl,"), "expected the GL backend: {err}");
    let img = image::open(&out).expect("a PNG").to_rgba8();
    let skin = img.pixels().filter(|p| p[0] > p[2].saturating_add(30)).count();
    assert!(skin > 2000, "only {skin} skin-coloured pixels");
    let _ = std::fs::remove_file(&out);
}

#[test]
fn explain_prints_the_frame_plan_and_what_is_skipped() {
    let o =
        rouge(&["render", "--explain", "--look", "bare", "--subsurface", "none", "--width", "64", "--height", "48"]);
    assert!(o.status.success(), "{}", stderr(&o));
    let s = stdout(&o);
    for line in ["1. shadow 0", "gbuffer", "lighting", "composite", "the look is bare", "subsurface model is none"] {
        assert!(s.contains(line), "{line:?} missing:\n{s}");
    }
    assert!(!s.contains("sss horizontal ") && !s.contains(". sss"), "{s}");
    let o = rouge(&["render", "--explain", "--width", "64", "--height", "48"]);
    let s = stdout(&o);
    assert!(s.contains("sss horizontal") && s.contains("3 layer(s)"), "{s}");
    // The mesh's parts, where the hairs are drawn, and the wrinkles of the pose.
    assert!(s.contains("lashes 41536") && s.contains("no pass of their own") && s.contains("natural lashes"), "{s}");
    assert!(s.contains("forehead 0.00 / 0.00") && s.contains("lip furrows 0.50 / 0.50"), "{s}");
    let o = rouge(&["render", "--explain", "--width", "64", "--height", "48", "--expression", "browInnerUp=1"]);
    let s = stdout(&o);
    assert!(s.contains("forehead 1.00 / 1.00"), "{s}");
    // Without skin detail there are no wrinkles to plan.
    let o = rouge(&["render", "--explain", "--width", "64", "--height", "48", "--no-skin-detail"]);
    let s = stdout(&o);
    assert!(!s.contains("wrinkles (left") && s.contains("no skin detail is bound"), "{s}");
}

#[test]
fn the_cube_atlas_plans_its_passes_and_refuses_bad_options() {
    let base =
        ["render", "--subsurface", "cube-atlas", "--medium", "marble", "--mesh", "builtin:wedge", "--look", "bare"];
    let explain = [&base[..], &["--width", "64", "--height", "48", "--explain"]].concat();
    let o = rouge(&explain);
    assert!(o.status.success(), "{}", stderr(&o));
    let s = stdout(&o);
    for line in ["atlas irradiance", "atlas gather", "atlas 6×512²", "reach support", "global term slab"] {
        assert!(s.contains(line), "{line:?} missing:\n{s}");
    }
    for (option, value, says) in [
        ("--atlas-global", "sometimes", "--atlas-global"),
        ("--atlas-kernel", "4", "odd"),
        ("--atlas-reach", "far", "mean free paths"),
        ("--atlas-occlusion", "maybe", "tangent-plane"),
    ] {
        let o = rouge(&[&base[..], &[option, value, "--out", "never.png"]].concat());
        assert_eq!(o.status.code(), Some(2), "{option} {value}");
        assert!(stderr(&o).contains(says), "{option} {value}: {}", stderr(&o));
    }
    let o = rouge(&["render", "--subsurface", "cube-atlas", "--explain"]);
    assert_eq!(o.status.code(), Some(2));
    assert!(stderr(&o).contains("--medium"), "{}", stderr(&o));
}

#[test]
fn media_and_mitsuba_export_say_what_is_wrong_and_write_a_scene() {
    let o = rouge(&["render", "--medium", "jelly", "--out", "never.png"]);
    assert_eq!(o.status.code(), Some(2));
    assert!(stderr(&o).contains("skin1") && stderr(&o).contains("jelly"), "{}", stderr(&o));
    let o = rouge(&["render", "--eta", "1.2", "--out", "never.png"]);
    assert_eq!(o.status.code(), Some(2));
    assert!(stderr(&o).contains("--eta needs --medium"), "{}", stderr(&o));
    let o = rouge(&["render", "--sigma-a", "0.1,0.1", "--sigma-s", "1,1,1", "--eta", "1.3", "--out", "never.png"]);
    assert!(stderr(&o).contains("three values"), "{}", stderr(&o));
    let dir = tempfile::tempdir().expect("tempdir");
    let out = dir.path().join("scene");
    let args = ["export", "mitsuba", "--mesh", "builtin:wedge", "--medium", "ketchup", "--lights", "back"];
    let o = rouge(&[&args[..], &["--width", "32", "--height", "24", "--out", out.to_str().expect("utf-8")]].concat());
    assert!(o.status.success(), "{}", stderr(&o));
    let xml = std::fs::read_to_string(out.join("scene.xml")).expect("scene.xml");
    assert!(xml.contains("<integrator type=\"volpathmis\">") && xml.contains("skin.ply"));
    let ply = std::fs::read(out.join("skin.ply")).expect("skin.ply");
    assert!(ply.starts_with(b"ply\nformat binary_little_endian 1.0\n"));
    let o = rouge(&["export", "mitsuba", "--light-radius-deg", "50", "--out", out.to_str().expect("utf-8")]);
    assert_eq!(o.status.code(), Some(2));
    assert!(stderr(&o).contains("--light-radius-deg 50"), "{}", stderr(&o));
}

#[test]
fn thickness_translucency_renders_a_glowing_wedge_and_refuses_bad_parameters() {
    let dir = tempfile::tempdir().expect("tempdir");
    let out = dir.path().join("wedge.png");
    let args = ["render", "--mesh", "builtin:wedge", "--subsurface", "thickness", "--medium", "skin1", "--lights"];
    let o = rouge(&[&args[..], &["back", "--look", "bare", "--width", "48", "--height", "32", "--explain"]].concat());
    assert!(o.status.success(), "{}", stderr(&o));
    let s = stdout(&o);
    // skin1's parameters fitted to the path tracer (data/media/skin1.json).
    for line in
        ["thickness        normal, albedo, depth, local thickness", "local-thickness map", "distortion 0.75, power 1"]
    {
        assert!(s.contains(line), "{line:?} missing:\n{s}");
    }
    // Per light, from the shadow map: no bake, and the light's shadow map is read.
    let o = Command::new(env!("CARGO_BIN_EXE_rouge"))
        .args(args)
        .args([
            "back",
            "--thickness-source",
            "shadow-map",
            "--look",
            "bare",
            "--width",
            "48",
            "--height",
            "32",
            "--out",
        ])
        .arg(&out)
        .current_dir(root())
        .output()
        .expect("run rouge");
    assert!(o.status.success() && out.exists(), "{}", stderr(&o));
    assert!(!stderr(&o).contains("local thickness of"), "the shadow-map source bakes nothing: {}", stderr(&o));
    for (bad, says) in [
        (&["--translucency", "0.1,2,10"][..], "DISTORTION,POWER,SCALE,AMBIENT"),
        (&["--translucency", "0.1,-2,10,0"][..], "power -2"),
        (&["--thickness-cutoff-mm", "0"][..], "--thickness-cutoff-mm 0"),
        (&["--morph", "1.5"][..], "--morph 1.5"),
    ] {
        let o = rouge(&[&args[..], &["back", "--out", "never.png"], bad].concat());
        assert_eq!(o.status.code(), Some(2), "{bad:?}");
        assert!(stderr(&o).contains(says), "{bad:?}: {}", stderr(&o));
    }
}

/// The red albedo on the `skin:` line of `rouge render --explain`'s plan.
fn plan_skin_albedo_red(plan: &str) -> f64 {
    let line = plan.lines().find(|l| l.starts_with("skin: ")).expect("the skin line of the plan");
    let at = line.find("albedo ").expect("albedo") + 7;
    line[at..].split(',').next().and_then(|v| v.trim().parse().ok()).expect("a number")
}

#[test]
fn a_skin_reflectance_file_sets_the_skin_colour_and_a_missing_sample_is_named() {
    let args = ["render", "--skin", "data/skin/colorchecker_skin.csv", "--look", "bare", "--explain"];
    let o = rouge(&[&args[..], &["--skin-sample", "dark_skin", "--width", "32", "--height", "24"]].concat());
    assert!(o.status.success(), "{}", stderr(&o));
    let dark = stdout(&o);
    let o = rouge(&[&args[..], &["--skin-sample", "light_skin", "--width", "32", "--height", "24"]].concat());
    let light = stdout(&o);
    let (dark, light) = (plan_skin_albedo_red(&dark), plan_skin_albedo_red(&light));
    assert!(dark < 0.6 * light, "dark {dark} light {light}");
    let o = rouge(&[&args[..], &["--skin-sample", "olive", "--out", "never.png"]].concat());
    assert_eq!(o.status.code(), Some(2));
    assert!(stderr(&o).contains("no skin `olive`") && stderr(&o).contains("dark_skin, light_skin"), "{}", stderr(&o));
    let o = rouge(&["render", "--skin", "data/skin/colorchecker_skin.csv", "--medium", "skin1", "--out", "never.png"]);
    assert_eq!(o.status.code(), Some(2), "--skin and --medium both set the skin");
}

#[test]
fn a_named_skin_tone_sets_the_skin_colour() {
    let albedo = |tone: &str| -> f64 {
        let args = ["render", "--skin-tone", tone, "--look", "bare", "--explain", "--width", "32", "--height", "24"];
        let o = rouge(&args);
        assert!(o.status.success(), "{}", stderr(&o));
        plan_skin_albedo_red(&stdout(&o))
    };
    let (light, deep) = (albedo("very-light"), albedo("very-deep"));
    assert!(deep < 0.3 * light, "very-deep {deep} very-light {light}");
    let o = rouge(&["render", "--skin-tone", "mauve", "--out", "never.png"]);
    assert_eq!(o.status.code(), Some(2));
    assert!(stderr(&o).contains("--skin-tone") && stderr(&o).contains("very-deep"), "{}", stderr(&o));
    let o = rouge(&["render", "--skin-tone", "deep", "--medium", "skin1", "--out", "never.png"]);
    assert_eq!(o.status.code(), Some(2), "--skin-tone and --medium both set the skin");
    // An ITA between the tones: lighter than a deeper angle, and outside the span an error.
    let (ita_30, ita_minus_30) = (albedo("30"), albedo("-30"));
    assert!(ita_minus_30 < ita_30 && ita_30 < light, "{ita_minus_30} {ita_30} {light}");
    let o = rouge(&["render", "--skin-tone", "75", "--out", "never.png"]);
    assert!(o.status.code() == Some(2) && stderr(&o).contains("ITA 75"), "{}", stderr(&o));
    // Skin maps: the plan reads an albedo map and says where it comes from.
    let args = ["render", "--skin-conditions", "freckles=0.5", "--skin-map-px", "64", "--explain", "--width", "32"];
    let o = rouge(&[&args[..], &["--height", "24", "--no-blood-flow"]].concat());
    assert!(o.status.success(), "{}", stderr(&o));
    let text = stdout(&o);
    assert!(
        text.contains("albedo map on") && text.contains("skin maps: tone light, conditions freckles=0.5"),
        "{text}"
    );
    assert!(text.contains("blood still"), "{text}");
    let o = rouge(&["render", "--skin-conditions", "spots=1", "--out", "never.png"]);
    assert!(o.status.code() == Some(2) && stderr(&o).contains("spots"), "{}", stderr(&o));
}

/// Issue 30: non-finite camera angles and mesh scales rendered an empty frame with exit 0 over the
/// previous image; a negative size got clap's "unexpected argument". Each is now an error that
/// names the option and quotes the value as typed (`--yaw 1e308` was reported as `inf`), and the
/// previous output is left as it was.
#[test]
fn bad_camera_and_scale_values_are_named_and_keep_the_old_image() {
    let dir = tempfile::tempdir().expect("tempdir");
    let out = dir.path().join("keep.png");
    std::fs::write(&out, b"the previous image").expect("write");
    let out_s = out.to_str().expect("utf-8");
    for (bad, says) in [
        (&["--yaw", "nan"][..], "--yaw"),
        (&["--yaw", "inf"][..], "--yaw"),
        (&["--yaw", "1e308"][..], "--yaw"),
        (&["--yaw", "-1e30"][..], "--yaw"),
        (&["--pitch", "nan"][..], "--pitch"),
        (&["--pitch", "3600.5"][..], "--pitch"),
        (&["--mesh-scale", "nan"][..], "--mesh-scale"),
        (&["--mesh-scale", "0"][..], "--mesh-scale"),
        (&["--mesh-scale", "1e39"][..], "--mesh-scale"),
        (&["--width", "-5"][..], "--width"),
    ] {
        let o = rouge(&[&["render", "--out", out_s][..], bad].concat());
        assert_eq!(o.status.code(), Some(2), "{bad:?}: {}", stderr(&o));
        assert!(stderr(&o).contains(says), "{bad:?}: {}", stderr(&o));
        assert!(stderr(&o).contains(bad[1]), "{bad:?}: the value as typed: {}", stderr(&o));
        assert_eq!(std::fs::read(&out).expect("read"), b"the previous image", "{bad:?}");
    }
}
