//! `rouge export web` end to end: the share page is one file that names nothing outside it; opened
//! from disk in headless Chromium (tests/web/check.mjs, playwright-core driving Debian's
//! chromium; skipped, saying so, without them) it draws the head with no console error and no
//! request, lists the look's products, and its slider shows two different faces (the bare skin,
//! the look); bad options and unwritable paths fail naming them and leave no file behind.

use super::common::{names, root, rouge, stderr};
use std::path::Path;
use std::process::{Command, Output};

/// The default head at one subdivision with the default look over the flat light skin, 256².
fn export(out: &Path) -> Output {
    rouge(&[
        "export",
        "web",
        "--subdiv",
        "1",
        "--flat-skin",
        "--textures",
        "256",
        "--out",
        out.to_str().expect("utf-8"),
    ])
}

/// Runs tests/web/check.mjs on `page`, or says why not.
fn check_in_chromium(page: &Path, shots: &Path) -> Option<serde_json::Value> {
    let chromium = std::env::var("CHROMIUM").unwrap_or_else(|_| "/usr/bin/chromium".into());
    if !Path::new(&chromium).exists() {
        eprintln!("SKIPPED the page in Chromium: {chromium} is absent (apt-get install chromium, or set CHROMIUM)");
        return None;
    }
    if !root().join("tests/web/node_modules/playwright-core").is_dir() {
        eprintln!(
            "SKIPPED the page in Chromium: tests/web/node_modules is absent (run `npm ci --omit=dev --prefix tests/web`)"
        );
        return None;
    }
    let o = match Command::new("node").arg(root().join("tests/web/check.mjs")).arg(page).arg(shots).output() {
        Ok(o) => o,
        Err(e) => {
            eprintln!("SKIPPED the page in Chromium: cannot run node ({e})");
            return None;
        }
    };
    assert!(o.status.success(), "check.mjs failed:\n{}\n{}", String::from_utf8_lossy(&o.stdout), stderr(&o));
    Some(serde_json::from_slice(&o.stdout).expect("check.mjs prints one JSON report"))
}

#[test]
fn the_page_opens_from_disk_draws_the_head_and_compares_bare_skin_with_the_look() {
    let dir = tempfile::tempdir().expect("temp dir");
    let out = dir.path().join("share");
    let o = export(&out);
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(stderr(&o).contains("3 products"), "{}", stderr(&o));
    assert_eq!(names(&out), ["index.html"], "one file, no temporary file left");
    let html = std::fs::read_to_string(out.join("index.html")).expect("page");
    assert!(html.contains(r#"<script type="application/octet-stream" id="rouge-glb">Z2xURg"#), "the .glb inline");
    assert!(html.contains("Lipstick 02 Classic Red"), "the product list");

    let shots = dir.path().join("shots");
    std::fs::create_dir(&shots).expect("shots");
    let Some(report) = check_in_chromium(&out.join("index.html"), &shots) else { return };
    eprintln!("{report}");
    assert_eq!(report["errors"], serde_json::json!([]), "no console error, no exception");
    assert_eq!(report["requests"], serde_json::json!([]), "nothing loaded from outside the page");
    assert_eq!(report["title"], "Default - Rouge");
    let products = report["products"].as_array().expect("products");
    assert_eq!(products.len(), 3, "{products:?}");
    assert!(products[2].as_str().is_some_and(|p| p.starts_with("Lipstick 02 Classic Red lipstick")), "{products:?}");
    // The head covers a fifth of the view (about 0.2 on this framing; 0 if nothing drew).
    let covered = report["shots"]["look"]["covered"].as_f64().expect("covered");
    assert!((0.1..0.5).contains(&covered), "share of the canvas drawn: {covered}");

    // The slider: at 0 the look, at 100 the bare skin; the foundation changes the whole face.
    let look = image::open(shots.join("page_look.png")).expect("look").to_rgb8();
    let bare = image::open(shots.join("page_bare.png")).expect("bare").to_rgb8();
    assert_eq!(look.dimensions(), bare.dimensions());
    let differ = look
        .pixels()
        .zip(bare.pixels())
        .filter(|(a, b)| a.0.iter().zip(b.0).map(|(&x, y)| (i32::from(x) - i32::from(y)).abs()).sum::<i32>() > 12)
        .count() as f64
        / f64::from(look.width() * look.height());
    assert!(differ > 0.3 * covered, "the bare skin and the look differ on {differ:.3} of the view");
}

#[test]
fn bad_options_and_unwritable_paths_fail_naming_them_and_leave_no_file() {
    let dir = tempfile::tempdir().expect("temp dir");
    let o = rouge(&["export", "web", "--textures", "300", "--out", dir.path().to_str().expect("utf-8")]);
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
    assert!(stderr(&o).contains("--textures"), "{}", stderr(&o));

    // --out names a file.
    let file = dir.path().join("taken");
    std::fs::write(&file, b"previous").expect("file");
    let o = export(&file);
    assert!(!o.status.success());
    assert!(stderr(&o).contains("--out") && stderr(&o).contains("taken"), "{}", stderr(&o));
    assert_eq!(std::fs::read(&file).expect("kept"), b"previous");

    // The page's name is taken by a folder: the rename fails, and no temporary file is left.
    let out = dir.path().join("share");
    std::fs::create_dir_all(out.join("index.html")).expect("folder");
    let o = export(&out);
    assert!(!o.status.success());
    assert!(stderr(&o).contains("index.html") && stderr(&o).contains("cannot write"), "{}", stderr(&o));
    assert_eq!(names(&out), ["index.html"], "no temporary file is left");
}
