//! Files that change together: an export of several files (a .gltf with its .bin and images, a
//! MaterialX document with its textures) or a project folder, written so that a kill or a full
//! disk at any point leaves a set that opens whole, the previous one or the new one, never a mix.
//!
//! The recipe ([`write_file_set`]): the companions are named by their content
//! ([`content_tagged`]: `STEM.<16 hex digits>.EXT`), so a new companion never replaces an old one
//! that the previous commit file still names; each is written atomically ([`write_atomic`]);
//! then the one file that names them (the commit file) is replaced atomically; then the previous
//! generation's companions, which nothing names any more, are removed. Until the commit file's
//! rename, the old set is whole on disk; after it, the new one is.
//!
//! [`read_bounded`] is the reading side: a file another file names is read whole only when it is a
//! regular file under a size limit.
//!
//! The names' hash ([`bytes_hash`]) is a multiply-rotate mix with SplitMix64's finaliser
//! ([`mix64`], \[Steele2014\]): not cryptographic, only to tell contents apart.

use std::path::{Path, PathBuf};

/// Hex digits of a content tag.
pub const HASH_DIGITS: usize = 16;

/// SplitMix64's output finaliser (\[Steele2014\]: Steele, Lea & Flood, "Fast splittable
/// pseudorandom number generators", OOPSLA 2014; the "mix64" of its listing, without the
/// generator's increment).
pub fn mix64(mut z: u64) -> u64 {
    z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
    z ^ (z >> 31)
}

/// 64-bit hash of `bytes`: what names a file by its content.
pub fn bytes_hash(bytes: &[u8]) -> u64 {
    let mut h = 0x9E37_79B9_7F4A_7C15u64;
    for &b in bytes {
        h = (h.rotate_left(23) ^ u64::from(b)).wrapping_mul(0xD6E8_FEB8_6659_FD93);
    }
    mix64(h ^ bytes.len() as u64)
}

/// `STEM.<hash of bytes, 16 hex digits>.EXT`.
pub fn content_tagged(stem: &str, ext: &str, bytes: &[u8]) -> String {
    format!("{stem}.{:016x}.{ext}", bytes_hash(bytes))
}

/// The stem of `file` when it is named as [`content_tagged`] names files with extension `ext`.
pub fn content_tag_stem<'a>(file: &'a str, ext: &str) -> Option<&'a str> {
    let rest = file.strip_suffix(ext)?.strip_suffix('.')?;
    let (stem, hash) = rest.rsplit_once('.')?;
    (hash.len() == HASH_DIGITS && hash.bytes().all(|b| b.is_ascii_digit() || (b'a'..=b'f').contains(&b)))
        .then_some(stem)
}

/// Writes `companions` (file names in `dir` and their bytes, named by their content) and then
/// `commit` (the file that names them) atomically, then removes the earlier generations'
/// companions (a removal that fails is left): every other file of `dir` whose stem and extension
/// `ours` recognises as this writer's, named by its content (`STEM.<hash>.EXT`), or named plainly
/// (`STEM.EXT`, as before content names) where the previous commit file named it. `dir` empty
/// means the working folder. Returns the files written, the commit file last.
///
/// # Errors
/// The file that could not be written and why; the files written before it stay (they are new
/// names: the previous commit file and the companions it names are untouched).
pub fn write_file_set(
    dir: &Path,
    companions: &[(String, Vec<u8>)],
    commit: &Path,
    commit_bytes: &[u8],
    ours: &dyn Fn(&str, &str) -> bool,
) -> Result<Vec<PathBuf>, (PathBuf, std::io::Error)> {
    let previous = std::fs::read_to_string(commit).unwrap_or_default();
    let mut written = Vec::new();
    for (name, bytes) in companions {
        let path = dir.join(name);
        write_atomic(&path, bytes).map_err(|e| (path.clone(), e))?;
        written.push(path);
    }
    write_atomic(commit, commit_bytes).map_err(|e| (commit.to_path_buf(), e))?;
    written.push(commit.to_path_buf());
    let stale = |name: &str| {
        let Some((plain_stem, ext)) = name.rsplit_once('.') else { return false };
        match content_tag_stem(name, ext) {
            Some(stem) => ours(stem, ext),
            None => ours(plain_stem, ext) && previous.contains(&format!("\"{name}\"")),
        }
    };
    let listing = if dir.as_os_str().is_empty() { Path::new(".") } else { dir };
    if let Ok(entries) = std::fs::read_dir(listing) {
        for entry in entries.flatten() {
            let name = entry.file_name();
            let Some(name) = name.to_str() else { continue };
            let current = companions.iter().any(|(c, _)| c == name) || commit.file_name().is_some_and(|c| c == name);
            if !current && stale(name) {
                let _ = std::fs::remove_file(entry.path());
            }
        }
    }
    Ok(written)
}

/// Reads the regular file `path` whole, refusing anything else (a folder, a device such as
/// `/dev/zero`, a pipe) and any file over `max_bytes` before reading it: files that other files
/// name (a look's maps and presets, a project's skin maps, a glTF's buffers) come from wherever
/// that file points, and a device never ends.
///
/// # Errors
/// The I/O error, or [`std::io::ErrorKind::InvalidData`] naming the size or the kind of file.
pub fn read_bounded(path: &Path, max_bytes: u64) -> std::io::Result<Vec<u8>> {
    use std::io::Read;
    let invalid = |m: String| std::io::Error::new(std::io::ErrorKind::InvalidData, m);
    // Asked before opening: opening a pipe blocks until something writes into it.
    let meta = std::fs::metadata(path)?;
    if !meta.is_file() {
        return Err(invalid("not a regular file".into()));
    }
    if meta.len() > max_bytes {
        return Err(invalid(format!("{} bytes: more than the {max_bytes} allowed", meta.len())));
    }
    let file = std::fs::File::open(path)?;
    let mut bytes = Vec::with_capacity(meta.len() as usize);
    // A file that grows while it is read stops at the limit all the same.
    file.take(max_bytes + 1).read_to_end(&mut bytes)?;
    if bytes.len() as u64 > max_bytes {
        return Err(invalid(format!("more than the {max_bytes} bytes allowed")));
    }
    Ok(bytes)
}

/// Writes `bytes` to `path` through a temporary sibling file and a rename.
pub fn write_atomic(path: &Path, bytes: &[u8]) -> std::io::Result<()> {
    use std::io::Write;
    let dir = path.parent().filter(|d| !d.as_os_str().is_empty()).unwrap_or(Path::new("."));
    let name = path.file_name().map_or_else(|| "out".into(), |n| n.to_string_lossy().into_owned());
    let tmp = dir.join(format!(".{name}.tmp-{}", std::process::id()));
    let result = (|| {
        let mut f = std::fs::File::create(&tmp)?;
        f.write_all(bytes)?;
        f.sync_all()?;
        std::fs::rename(&tmp, path)
    })();
    if result.is_err() {
        let _ = std::fs::remove_file(&tmp);
    }
    result
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn names_carry_their_content_and_are_recognised() {
        let a = content_tagged("face_base_color", "png", b"one");
        assert_ne!(a, content_tagged("face_base_color", "png", b"two"));
        assert_eq!(a, content_tagged("face_base_color", "png", b"one"));
        assert_eq!(content_tag_stem(&a, "png"), Some("face_base_color"));
        assert_eq!(content_tag_stem(&a, "bin"), None);
        assert_eq!(content_tag_stem("face_base_color.png", "png"), None);
        assert_eq!(content_tag_stem("face.0123456789abcdeg.png", "png"), None);
        assert_eq!(content_tag_stem("face.0123456789abcdef.png", "png"), Some("face"));
    }

    #[test]
    fn a_new_set_replaces_the_old_and_removes_only_what_is_stale() {
        let dir = tempfile::tempdir().expect("temp dir");
        let d = dir.path();
        let commit = d.join("face.gltf");
        let set = |content: &[u8]| vec![(content_tagged("face", "bin", content), content.to_vec())];
        let ours = |stem: &str, ext: &str| stem == "face" && ext == "bin";
        let first = set(b"first");
        write_file_set(d, &first, &commit, first[0].0.as_bytes(), &ours).expect("first");
        std::fs::write(d.join("notes.txt"), b"mine").expect("a file of the user's");
        let second = set(b"second");
        let written = write_file_set(d, &second, &commit, second[0].0.as_bytes(), &ours).expect("second");
        assert_eq!(written, [d.join(&second[0].0), commit.clone()]);
        let mut left: Vec<String> = std::fs::read_dir(d)
            .expect("dir")
            .map(|e| e.expect("entry").file_name().into_string().expect("utf-8"))
            .collect();
        left.sort();
        let mut want = vec![second[0].0.clone(), "face.gltf".into(), "notes.txt".into()];
        want.sort();
        assert_eq!(left, want, "the first generation's companion is gone, the user's file stays");
        assert_eq!(std::fs::read(&commit).expect("commit"), second[0].0.as_bytes());
    }
}
