//! The on-disk cache of bakes: keyed by mesh and settings, versioned, checksummed, written
//! atomically.

use std::io::Write;
use std::path::{Path, PathBuf};

use super::trace::splitmix64;
use super::{BakeSettings, Falloff, LocalThickness, ThicknessError, bake_local_thickness, check_mesh};
use crate::mesh::TriangleMesh;

/// First bytes of a cache file.
const CACHE_MAGIC: &[u8; 8] = b"ROUGE-LT";
/// Version of the cache file layout and of the bake it stores: bump it whenever either changes,
/// so old files are rebaked rather than misread.
const CACHE_VERSION: u32 = 1;
/// Bytes of a cache file before the per-vertex data.
const CACHE_HEADER_BYTES: usize = 8 + 4 + 16 + 8 + 4 + 4 + 4 + 12 + 8 + 8;

/// Whether [`bake_local_thickness_cached`] used its cache.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum CacheUse {
    /// Read from a valid cache file; nothing was traced.
    Hit,
    /// Baked (no file, or a corrupt, stale or mismatched one) and written to the cache.
    Miss,
    /// No cache directory: baked and not stored.
    Off,
}

/// [`bake_local_thickness`] with an on-disk cache: `<dir>/<hex key>.bin`, the key a 128-bit hash
/// of the mesh's positions, normals and indices (the normals steer the rays, so they are part of
/// the key) and of the settings. The file has a versioned header that repeats the key, vertex
/// count and settings, and a checksum of its contents; it is written to a temporary file in the
/// same directory and renamed into place, so a reader never sees half a file. A missing,
/// corrupt, stale or mismatched file is ignored and rebaked (and replaced), never a panic.
/// `cache_dir = None` bakes without a cache ([`CacheUse::Off`]).
///
/// # Errors
/// As [`bake_local_thickness`]; [`ThicknessError::Cache`] when the directory cannot be created or
/// the file cannot be written (the bake is lost: call again with `None` to bake without a cache).
pub fn bake_local_thickness_cached(
    mesh: &TriangleMesh,
    settings: &BakeSettings,
    cache_dir: Option<&Path>,
) -> Result<(LocalThickness, CacheUse), ThicknessError> {
    let Some(dir) = cache_dir else {
        return Ok((bake_local_thickness(mesh, settings)?, CacheUse::Off));
    };
    settings.validate()?;
    check_mesh(mesh)?;
    let key = cache_key(mesh, settings);
    let path = dir.join(format!("{}.bin", hex(&key)));
    if let Ok(bytes) = std::fs::read(&path)
        && let Some(bake) = decode_cache(&bytes, &key, mesh.vertex_count(), settings)
    {
        return Ok((bake, CacheUse::Hit));
    }
    let bake = bake_local_thickness(mesh, settings)?;
    let cache_error = |path: &Path, source| ThicknessError::Cache { path: path.to_path_buf(), source };
    std::fs::create_dir_all(dir).map_err(|e| cache_error(dir, e))?;
    let temp = dir.join(format!(".{}.{}.tmp", hex(&key), std::process::id()));
    let written = std::fs::File::create(&temp).and_then(|mut f| {
        f.write_all(&encode_cache(&bake, &key))?;
        f.sync_all()
    });
    if let Err(e) = written.and_then(|()| std::fs::rename(&temp, &path)) {
        let _ = std::fs::remove_file(&temp);
        return Err(cache_error(&path, e));
    }
    Ok((bake, CacheUse::Miss))
}

/// The thickness cache directory: `$ROUGE_CACHE_DIR`, else `$XDG_CACHE_HOME/rouge/thickness`,
/// else `~/.cache/rouge/thickness` (`$HOME`); `None` when none of them is set (empty counts as
/// unset).
pub fn default_cache_dir() -> Option<PathBuf> {
    let var = |name: &str| std::env::var_os(name).filter(|v| !v.is_empty()).map(PathBuf::from);
    var("ROUGE_CACHE_DIR")
        .or_else(|| var("XDG_CACHE_HOME").map(|d| d.join("rouge").join("thickness")))
        .or_else(|| var("HOME").map(|d| d.join(".cache").join("rouge").join("thickness")))
}

/// A two-lane 64-bit multiply-xorshift hash over 32-bit words: stable across platforms and
/// Rust versions (unlike `std`'s `DefaultHasher`), for cache keys and file checksums. Not
/// cryptographic: the cache header re-checks vertex count and settings.
struct WordHasher([u64; 2]);

impl WordHasher {
    fn new() -> Self {
        WordHasher([0x6a09_e667_f3bc_c908, 0xbb67_ae85_84ca_a73b])
    }

    fn word(&mut self, w: u32) {
        let [a, b] = &mut self.0;
        *a = (*a ^ u64::from(w)).wrapping_mul(0x0000_0100_0000_01b3).rotate_left(23);
        *b = (*b ^ u64::from(w).rotate_left(17)).wrapping_mul(0x9e37_79b9_7f4a_7c15) ^ (*b >> 29);
    }

    fn finish(&self) -> [u8; 16] {
        let [a, b] = self.0;
        let (a, b) = (splitmix64(a ^ b.rotate_left(32)), splitmix64(b ^ a));
        let mut out = [0u8; 16];
        out[..8].copy_from_slice(&a.to_le_bytes());
        out[8..].copy_from_slice(&b.to_le_bytes());
        out
    }
}

/// The settings as the 32-bit words the key and the header store.
fn settings_words(s: &BakeSettings) -> [u32; 9] {
    let (tag, params) = match s.falloff {
        Falloff::Power { exponent } => (0, [exponent, 0.0, 0.0]),
        Falloff::Exponential { per_mm } => (1, per_mm),
    };
    [
        s.rays,
        s.cutoff_mm.to_bits(),
        tag,
        params[0].to_bits(),
        params[1].to_bits(),
        params[2].to_bits(),
        s.seed as u32,
        (s.seed >> 32) as u32,
        0,
    ]
}

fn cache_key(mesh: &TriangleMesh, settings: &BakeSettings) -> [u8; 16] {
    let mut h = WordHasher::new();
    h.word(CACHE_VERSION);
    for list in [&mesh.positions, &mesh.normals] {
        h.word(list.len() as u32);
        for c in list.iter().flat_map(|p| p.to_array()) {
            h.word(c.to_bits());
        }
    }
    h.word(mesh.indices.len() as u32);
    mesh.indices.iter().for_each(|&i| h.word(i));
    for w in settings_words(settings) {
        h.word(w);
    }
    h.finish()
}

fn hex(bytes: &[u8]) -> String {
    bytes.iter().map(|b| format!("{b:02x}")).collect()
}

/// The checksum of a cache file's contents before the checksum itself.
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

/// Layout (little-endian): magic, version u32, key [16], vertex count u64, the settings words
/// (rays, cutoff, falloff tag, 3 parameters; seed u64), bake seconds f64, mean chords f32 × n,
/// values f32 × 3n, checksum [16].
fn encode_cache(bake: &LocalThickness, key: &[u8; 16]) -> Vec<u8> {
    let n = bake.mean_chord_mm.len();
    let mut out = Vec::with_capacity(CACHE_HEADER_BYTES + 16 * n + 16);
    out.extend_from_slice(CACHE_MAGIC);
    out.extend_from_slice(&CACHE_VERSION.to_le_bytes());
    out.extend_from_slice(key);
    out.extend_from_slice(&(n as u64).to_le_bytes());
    for w in &settings_words(&bake.settings)[..8] {
        out.extend_from_slice(&w.to_le_bytes());
    }
    out.extend_from_slice(&bake.bake_seconds.to_le_bytes());
    debug_assert_eq!(out.len(), CACHE_HEADER_BYTES);
    for c in &bake.mean_chord_mm {
        out.extend_from_slice(&c.to_le_bytes());
    }
    for v in bake.value.iter().flatten() {
        out.extend_from_slice(&v.to_le_bytes());
    }
    let sum = checksum(&out);
    out.extend_from_slice(&sum);
    out
}

/// The bake a cache file holds, when it is intact and for this key, vertex count and settings.
fn decode_cache(bytes: &[u8], key: &[u8; 16], n: usize, settings: &BakeSettings) -> Option<LocalThickness> {
    let expected = n.checked_mul(16)?.checked_add(CACHE_HEADER_BYTES + 16)?;
    if bytes.len() != expected {
        return None;
    }
    let (body, sum) = bytes.split_at(bytes.len() - 16);
    if checksum(body) != sum {
        return None;
    }
    let mut at = 0;
    let mut take = |len: usize| {
        let s = &body[at..at + len];
        at += len;
        s
    };
    let word = |s: &[u8]| u32::from_le_bytes([s[0], s[1], s[2], s[3]]);
    if take(8) != CACHE_MAGIC || word(take(4)) != CACHE_VERSION || take(16) != key {
        return None;
    }
    if u64::from_le_bytes(take(8).try_into().ok()?) != n as u64 {
        return None;
    }
    let stored: Vec<u32> = (0..8).map(|_| word(take(4))).collect();
    if stored[..] != settings_words(settings)[..8] {
        return None;
    }
    let bake_seconds = f64::from_le_bytes(take(8).try_into().ok()?);
    let mut float = || f32::from_le_bytes(take(4).try_into().unwrap_or([0xff; 4]));
    let mean_chord_mm: Vec<f32> = (0..n).map(|_| float()).collect();
    let value: Vec<[f32; 3]> = (0..n).map(|_| [float(), float(), float()]).collect();
    let sane = mean_chord_mm.iter().all(|c| c.is_finite()) && value.iter().flatten().all(|v| (0.0..=1.0).contains(v));
    sane.then_some(LocalThickness { settings: *settings, mean_chord_mm, value, bake_seconds })
}
