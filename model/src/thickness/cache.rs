//! The on-disk cache of bakes: keyed by mesh and settings, versioned, checksummed, written
//! atomically ([`crate::disk_cache`]).

use std::path::{Path, PathBuf};

use super::{BakeSettings, Falloff, LocalThickness, ThicknessError, bake_local_thickness, check_mesh};
pub use crate::disk_cache::CacheUse;
use crate::disk_cache::{WordHasher, hex, seal, unseal, write_atomically};
use crate::mesh::TriangleMesh;

/// First bytes of a cache file.
const CACHE_MAGIC: &[u8; 8] = b"ROUGE-LT";
/// Version of the cache file layout and of the bake it stores: bump it whenever either changes,
/// so old files are rebaked rather than misread.
const CACHE_VERSION: u32 = 1;
/// Bytes of a cache file before the per-vertex data.
const CACHE_HEADER_BYTES: usize = 8 + 4 + 16 + 8 + 4 + 4 + 4 + 12 + 8 + 8;

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
    write_atomically(dir, &format!("{}.bin", hex(&key)), &encode_cache(&bake, &key))
        .map_err(|(path, source)| ThicknessError::Cache { path, source })?;
    Ok((bake, CacheUse::Miss))
}

/// The thickness cache directory: `$ROUGE_CACHE_DIR/thickness`, else
/// `$XDG_CACHE_HOME/rouge/thickness`, else `~/.cache/rouge/thickness` (`$HOME`); `None` when none
/// of them is set (empty counts as unset).
pub fn default_cache_dir() -> Option<PathBuf> {
    crate::disk_cache::cache_dir("thickness")
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
    seal(out)
}

/// The bake a cache file holds, when it is intact and for this key, vertex count and settings.
fn decode_cache(bytes: &[u8], key: &[u8; 16], n: usize, settings: &BakeSettings) -> Option<LocalThickness> {
    let expected = n.checked_mul(16)?.checked_add(CACHE_HEADER_BYTES + 16)?;
    if bytes.len() != expected {
        return None;
    }
    let body = unseal(bytes)?;
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
