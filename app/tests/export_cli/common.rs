//! What the export tests share: the repository root, the `rouge` binary run from it, its
//! stderr, and a folder's file names.

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

pub fn root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("..")
}

pub fn rouge(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_rouge")).args(args).current_dir(root()).output().expect("run rouge")
}

pub fn stderr(o: &Output) -> String {
    String::from_utf8_lossy(&o.stderr).into_owned()
}

/// The names in `dir`, sorted.
pub fn names(dir: &Path) -> Vec<String> {
    let mut n: Vec<String> =
        std::fs::read_dir(dir).expect("dir").map(|e| e.expect("entry").file_name().to_string_lossy().into()).collect();
    n.sort();
    n
}
