//! What the skin project tests share (skin_edits.rs and skin_project.rs).

use std::path::Path;

/// The file a project's `look.json` names in its `project` part: `face` or `skin`.
pub fn project_file(dir: &Path, which: &str) -> std::path::PathBuf {
    let path = dir.join("look.json");
    let text = std::fs::read_to_string(&path).expect("look.json");
    let (_, part) = rouge_model::look::Look::from_project_json(&text, &path).expect("look.json loads");
    let part = part.expect("a project part");
    dir.join(match which {
        "face" => part.face,
        _ => part.skin.expect("a skin file"),
    })
}
