//! Exports of several files killed at any moment (issue 30's kill harness, for exports): `rouge
//! export gltf --out face.gltf` and `rouge export materialx` run over the same output again and
//! again, two looks in turn, each SIGKILLed after a random delay within one export's time. After
//! every kill the .gltf (or the .mtlx) on disk must be whole and every file it names there and
//! its own: the .bin as long as its buffer says and every image a PNG. Without the content-named
//! companions (`rouge_measure::file_set`) a kill between the .bin and the .gltf left a .gltf
//! whose accessors ran past its new .bin. `ROUGE_KILL_ROUNDS` (default 6 per format) sets the
//! kills.

use super::common::{root, rouge};
use std::path::Path;
use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

/// The options of every export here: quick (no subdivision, flat skin, 256² textures).
const QUICK: [&str; 6] = ["--subdiv", "0", "--flat-skin", "--textures", "256", "--look"];

/// The two looks the exports alternate between, so that consecutive exports differ.
const LOOKS: [&str; 2] = ["default", "bare"];

fn rounds() -> u32 {
    std::env::var("ROUGE_KILL_ROUNDS").ok().and_then(|v| v.parse().ok()).unwrap_or(8)
}

/// The arguments of export `i` (`kind` gltf or materialx) into `out`.
fn args<'a>(kind: &'a str, i: usize, out: &'a str) -> Vec<&'a str> {
    let mut a = vec!["export", kind];
    a.extend(QUICK);
    a.push(LOOKS[i % 2]);
    if kind == "gltf" {
        a.push("--no-occlusion");
    }
    a.extend(["--out", out]);
    a
}

/// Runs export `i` to completion and returns how long it took.
fn complete(kind: &str, i: usize, out: &str) -> Duration {
    let t = Instant::now();
    let o = rouge(&args(kind, i, out));
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    t.elapsed()
}

/// Runs export `i` and kills it after `delay`.
fn killed(kind: &str, i: usize, out: &str, delay: Duration) {
    let mut child = Command::new(env!("CARGO_BIN_EXE_rouge"))
        .args(args(kind, i, out))
        .current_dir(root())
        .stdout(Stdio::null())
        .stderr(Stdio::null())
        .spawn()
        .expect("spawn rouge");
    std::thread::sleep(delay);
    let _ = child.kill();
    let _ = child.wait();
}

/// The file names a .gltf names (its buffer's and images' URIs), after checking that each is
/// there and whole.
fn check_gltf(path: &Path) -> Vec<String> {
    let doc: serde_json::Value =
        serde_json::from_slice(&std::fs::read(path).expect("the .gltf is there")).expect("the .gltf is whole JSON");
    let dir = path.parent().expect("folder");
    let buffer = &doc["buffers"][0];
    let bin = buffer["uri"].as_str().expect("the buffer's file");
    let length = std::fs::metadata(dir.join(bin)).unwrap_or_else(|e| panic!("{bin}: {e}")).len();
    assert_eq!(Some(length), buffer["byteLength"].as_u64(), "{bin} is not the .gltf's buffer");
    let mut named = vec![bin.to_string()];
    for image in doc["images"].as_array().expect("images") {
        let file = image["uri"].as_str().expect("an image's file");
        image::open(dir.join(file)).unwrap_or_else(|e| panic!("{file}: {e}"));
        named.push(file.to_string());
    }
    named
}

/// The texture files a .mtlx names, after checking that each is there and a PNG.
fn check_mtlx(dir: &Path) -> Vec<String> {
    let text = std::fs::read_to_string(dir.join("face.mtlx")).expect("the .mtlx is there");
    assert!(text.trim_end().ends_with("</materialx>"), "the .mtlx is whole");
    let named: Vec<String> = text
        .split("type=\"filename\" value=\"")
        .skip(1)
        .filter_map(|rest| rest.split('"').next())
        .map(str::to_string)
        .collect();
    assert!(!named.is_empty(), "the .mtlx names its textures");
    for file in &named {
        image::open(dir.join(file)).unwrap_or_else(|e| panic!("{file}: {e}"));
    }
    named
}

/// The files of `dir` a finished export leaves, without the temporary files of killed writes.
fn left(dir: &Path) -> Vec<String> {
    let mut n: Vec<String> = std::fs::read_dir(dir)
        .expect("dir")
        .map(|e| e.expect("entry").file_name().to_string_lossy().into_owned())
        .filter(|n| !(n.starts_with('.') && n.contains(".tmp-")))
        .collect();
    n.sort();
    n
}

/// Delays spread over [0.5, 1.1) × span, where an export writes its files (a fixed sequence, so
/// a failure can be run again).
fn delays(span: Duration, n: u32) -> impl Iterator<Item = Duration> {
    let mut state = 0x2545_f491_4f6c_dd1du64;
    (0..n).map(move |_| {
        state ^= state << 13;
        state ^= state >> 7;
        state ^= state << 17;
        span.mul_f64(0.5 + 0.6 * (state >> 11) as f64 / (1u64 << 53) as f64)
    })
}

/// The complete export of each look into a folder of its own: the commit file's bytes and the
/// bytes of every file it names, by name.
type Reference = Vec<(Vec<u8>, Vec<(String, Vec<u8>)>)>;

fn references(kind: &str, commit: &str, named: fn(&Path) -> Vec<String>) -> (Reference, Duration) {
    let mut span = Duration::ZERO;
    let reference = (0..LOOKS.len())
        .map(|i| {
            let dir = tempfile::tempdir().expect("temp dir");
            let out = if kind == "gltf" { dir.path().join(commit) } else { dir.path().to_path_buf() };
            span = span.max(complete(kind, i, out.to_str().expect("utf-8")));
            let files = named(&dir.path().join(commit))
                .into_iter()
                .map(|n| {
                    let bytes = std::fs::read(dir.path().join(&n)).expect("named file");
                    (n, bytes)
                })
                .collect();
            (std::fs::read(dir.path().join(commit)).expect("commit file"), files)
        })
        .collect();
    (reference, span)
}

/// The folder `dir` holds one look's export, whole: its commit file and every file it names.
fn assert_one_look(dir: &Path, commit: &str, reference: &Reference, after: &str) {
    let bytes = std::fs::read(dir.join(commit)).expect("the commit file is there");
    let (_, files) = reference
        .iter()
        .find(|(c, _)| *c == bytes)
        .unwrap_or_else(|| panic!("{after}: {commit} is neither look's complete export"));
    for (name, want) in files {
        let got = std::fs::read(dir.join(name)).unwrap_or_else(|e| panic!("{after}: {name}: {e}"));
        assert!(got == *want, "{after}: {name} is not the {commit}'s look's");
    }
}

#[test]
fn a_gltf_killed_at_any_moment_leaves_one_looks_whole_export_and_a_finished_one_no_stale_file() {
    let (reference, span) = references("gltf", "face.gltf", check_gltf);
    let dir = tempfile::tempdir().expect("temp dir");
    let out = dir.path().join("face.gltf");
    let out_s = out.to_str().expect("utf-8");
    complete("gltf", 0, out_s);
    for (k, delay) in delays(span, rounds()).enumerate() {
        killed("gltf", k + 1, out_s, delay);
        check_gltf(&out);
        assert_one_look(dir.path(), "face.gltf", &reference, &format!("kill {k} after {delay:?}"));
    }
    complete("gltf", 1, out_s);
    let mut expected = check_gltf(&out);
    expected.push("face.gltf".into());
    expected.sort();
    assert_eq!(left(dir.path()), expected, "a finished export leaves its own files only");
}

#[test]
fn a_materialx_export_killed_at_any_moment_leaves_one_looks_whole_material_and_a_finished_one_no_stale_file() {
    let (reference, span) = references("materialx", "face.mtlx", |p| check_mtlx(p.parent().expect("folder")));
    let dir = tempfile::tempdir().expect("temp dir");
    let out_s = dir.path().to_str().expect("utf-8");
    complete("materialx", 0, out_s);
    for (k, delay) in delays(span, rounds()).enumerate() {
        killed("materialx", k + 1, out_s, delay);
        check_mtlx(dir.path());
        assert_one_look(dir.path(), "face.mtlx", &reference, &format!("kill {k} after {delay:?}"));
    }
    complete("materialx", 1, out_s);
    let mut expected = check_mtlx(dir.path());
    expected.extend(["face.mtlx".into(), "face.obj".into()]);
    expected.sort();
    expected.dedup();
    assert_eq!(left(dir.path()), expected, "a finished export leaves its own files only");
}

#[test]
fn a_gltf_export_leaves_another_exports_files_beside_it_alone() {
    // `face_closeup.gltf` shares `face_`'s prefix: exporting `face.gltf` again, with another
    // look, must not take its images for an earlier `face.gltf`'s.
    let dir = tempfile::tempdir().expect("temp dir");
    let (face, closeup) = (dir.path().join("face.gltf"), dir.path().join("face_closeup.gltf"));
    complete("gltf", 0, face.to_str().expect("utf-8"));
    complete("gltf", 0, closeup.to_str().expect("utf-8"));
    complete("gltf", 1, face.to_str().expect("utf-8"));
    let mut expected = check_gltf(&face);
    expected.extend(check_gltf(&closeup));
    expected.extend(["face.gltf".into(), "face_closeup.gltf".into()]);
    expected.sort();
    expected.dedup();
    assert_eq!(left(dir.path()), expected, "each export keeps its own files");
}
