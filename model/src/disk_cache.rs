//! What Rouge's on-disk caches share (the thickness bakes, [`crate::thickness`]; the skin colour
//! tables, [`crate::skin::table_cache`]): where they live, a hash stable across platforms and
//! Rust versions for their keys and checksums, and files sealed with a checksum and written
//! atomically (to a temporary file in the same directory, renamed into place, so that a reader
//! never sees half a file).

use std::io::Write;
use std::path::{Path, PathBuf};

use crate::thickness::splitmix64;

/// Whether a cached computation used its cache.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum CacheUse {
    /// Read from a valid cache file; nothing was computed.
    Hit,
    /// Computed (no file, or a corrupt, stale or mismatched one) and written to the cache.
    Miss,
    /// No cache directory: computed and not stored.
    Off,
}

/// The cache directory `name`: `$ROUGE_CACHE_DIR/<name>`, else `$XDG_CACHE_HOME/rouge/<name>`,
/// else `~/.cache/rouge/<name>` (`$HOME`); `None` when none of them is set (empty counts as unset).
pub(crate) fn cache_dir(name: &str) -> Option<PathBuf> {
    let var = |key: &str| std::env::var_os(key).filter(|v| !v.is_empty()).map(PathBuf::from);
    var("ROUGE_CACHE_DIR")
        .or_else(|| var("XDG_CACHE_HOME").map(|d| d.join("rouge")))
        .or_else(|| var("HOME").map(|d| d.join(".cache").join("rouge")))
        .map(|root| root.join(name))
}

/// A two-lane 64-bit multiply-xorshift hash over 32-bit words: stable across platforms and
/// Rust versions (unlike `std`'s `DefaultHasher`), for cache keys and file checksums. Not
/// cryptographic: each cache's header re-checks what its key stands for.
pub(crate) struct WordHasher([u64; 2]);

impl WordHasher {
    pub(crate) fn new() -> Self {
        WordHasher([0x6a09_e667_f3bc_c908, 0xbb67_ae85_84ca_a73b])
    }

    pub(crate) fn word(&mut self, w: u32) {
        let [a, b] = &mut self.0;
        *a = (*a ^ u64::from(w)).wrapping_mul(0x0000_0100_0000_01b3).rotate_left(23);
        *b = (*b ^ u64::from(w).rotate_left(17)).wrapping_mul(0x9e37_79b9_7f4a_7c15) ^ (*b >> 29);
    }

    pub(crate) fn finish(&self) -> [u8; 16] {
        let [a, b] = self.0;
        let (a, b) = (splitmix64(a ^ b.rotate_left(32)), splitmix64(b ^ a));
        let mut out = [0u8; 16];
        out[..8].copy_from_slice(&a.to_le_bytes());
        out[8..].copy_from_slice(&b.to_le_bytes());
        out
    }
}

/// `bytes` in lower-case hexadecimal (a key as a file name).
pub(crate) fn hex(bytes: &[u8]) -> String {
    bytes.iter().map(|b| format!("{b:02x}")).collect()
}

/// The checksum of `bytes`.
fn checksum(bytes: &[u8]) -> [u8; 16] {
    let mut h = WordHasher::new();
    h.word(bytes.len() as u32);
    for chunk in bytes.chunks(4) {
        let mut w = [0u8; 4];
        w[..chunk.len()].copy_from_slice(chunk);
        h.word(u32::from_le_bytes(w));
    }
    h.finish()
}

/// `body` followed by its checksum (16 bytes).
pub(crate) fn seal(mut body: Vec<u8>) -> Vec<u8> {
    let sum = checksum(&body);
    body.extend_from_slice(&sum);
    body
}

/// The body of a file [`seal`] wrote, when its checksum holds.
pub(crate) fn unseal(bytes: &[u8]) -> Option<&[u8]> {
    let (body, sum) = bytes.split_at(bytes.len().checked_sub(16)?);
    (checksum(body) == sum).then_some(body)
}

/// Writes `bytes` to `dir/name` atomically, creating `dir`: a temporary file in `dir` (named
/// after `name`, this process and this write), synced, then renamed into place. On an error the temporary
/// file is removed and the error says which path failed.
pub(crate) fn write_atomically(dir: &Path, name: &str, bytes: &[u8]) -> Result<PathBuf, (PathBuf, std::io::Error)> {
    std::fs::create_dir_all(dir).map_err(|e| (dir.to_path_buf(), e))?;
    let path = dir.join(name);
    // This process and a counter: two threads writing the same name never share a temporary.
    static WRITES: std::sync::atomic::AtomicU64 = std::sync::atomic::AtomicU64::new(0);
    let n = WRITES.fetch_add(1, std::sync::atomic::Ordering::Relaxed);
    let temp = dir.join(format!(".{name}.{}.{n}.tmp", std::process::id()));
    let written = std::fs::File::create(&temp).and_then(|mut f| {
        f.write_all(bytes)?;
        f.sync_all()
    });
    if let Err(e) = written.and_then(|()| std::fs::rename(&temp, &path)) {
        let _ = std::fs::remove_file(&temp);
        return Err((path, e));
    }
    Ok(path)
}
