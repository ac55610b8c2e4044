//! CI's short fuzz run: every file of every fuzz corpus (`fuzz/corpus/TARGET/`, the seeds of
//! `fuzz/make_seeds.py` and what the libFuzzer runs kept) through its target's parser, on stable
//! Rust, in a few seconds. A panic fails the test and names the file; an error is the expected
//! answer to a malformed file. The long runs and their figures: docs/BENCHMARKS.md.

#[path = "../fuzz/src/lib.rs"]
mod harness;

use std::path::{Path, PathBuf};

fn corpus(target: &str) -> Vec<PathBuf> {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("../fuzz/corpus").join(target);
    let mut files: Vec<PathBuf> = std::fs::read_dir(&dir)
        .unwrap_or_else(|e| panic!("{}: {e}", dir.display()))
        .map(|e| e.expect("a directory entry").path())
        .collect();
    files.sort();
    files
}

#[test]
fn every_corpus_file_is_an_answer_not_a_panic() {
    let mut failures = Vec::new();
    let mut count = 0;
    for (target, run) in harness::TARGETS {
        let files = corpus(target);
        assert!(!files.is_empty(), "fuzz/corpus/{target} is empty");
        for file in files {
            let data = std::fs::read(&file).expect("a corpus file");
            count += 1;
            if std::panic::catch_unwind(|| run(&data)).is_err() {
                failures.push(format!("{target}: {}", file.display()));
            }
        }
    }
    harness::remove_scratch();
    assert!(failures.is_empty(), "{} of {count} corpus files panicked:\n{}", failures.len(), failures.join("\n"));
}

/// The seeds reach past the parsers' first checks: a replay of files that all fail at the
/// first byte would prove nothing.
#[test]
fn the_seeds_are_valid_files() {
    let seed = |target: &str, name: &str| -> Vec<u8> {
        std::fs::read(corpus(target).into_iter().find(|p| p.ends_with(name)).expect(name)).expect(name)
    };
    let dir = tempfile::tempdir().expect("temp dir");
    for (name, contents) in harness::split_project(&seed("project", "full")) {
        let path = dir.path().join(name);
        std::fs::create_dir_all(path.parent().expect("a parent")).expect("folder");
        std::fs::write(path, contents).expect("write");
    }
    let doc = rouge_model::document::Document::open_project(dir.path()).expect("the full project seed opens");
    assert_eq!(doc.layers.len(), 3);
    assert!(doc.skin.as_ref().is_some_and(|s| s.edits.is_some()), "skin maps and edits");
    assert!(!doc.face.expression.is_empty());

    for name in ["triangle.glb", "triangle.gltf"] {
        let path = dir.path().join(name);
        std::fs::write(&path, seed("gltf", name)).expect("write");
        let mesh = rouge_model::mesh::load_gltf(&path, 1.0).expect(name);
        assert_eq!(mesh.faces.len(), 1, "{name}");
    }
    let obj = rouge_model::mesh::parse_obj(&String::from_utf8_lossy(&seed("obj", "quad.obj")), Path::new("q"), 1.0);
    assert_eq!(obj.expect("quad.obj").faces.len(), 2);
    let (w, h, texels) = rouge_model::hdr::decode_rgb_exr(&seed("env", "studio.exr"), 4096).expect("studio.exr");
    assert_eq!((w, h, texels[1]), (8, 4, [0.6, 0.4, 0.3]), "the environment seed's second texel");
    let medium = dir.path().join("m.json");
    std::fs::write(&medium, seed("medium", "skin1.json")).expect("write");
    rouge_model::medium::Medium::load(&medium).expect("skin1.json");
}
