//! The skin colour tables on disk. [`SkinColorTable::new`] computes 109,375 spectra (about a
//! second on two cores in a release build) and every `rouge render`, `rouge skin-maps` and app
//! start that bakes skin maps needs the table of its tone: [`color_table_cached`] keeps each
//! tone's table (1.3 MB) in a cache directory ([`default_table_dir`]) and reads it back in
//! milliseconds. A file is trusted only when it is whole (checksummed, [`crate::disk_cache`]),
//! of this tone bit for bit, and its probe nodes equal the model's values computed now
//! ([`SkinColorTable::from_bytes`]): a table of another version of the skin model is recomputed,
//! never read.

use std::path::{Path, PathBuf};

use rouge_measure::skin::{SkinColorTable, SkinError, SkinParams};

use crate::disk_cache::{CacheUse, WordHasher, cache_dir, hex, seal, unseal, write_atomically};

/// Tables kept in the directory; beyond it the least recently written go (a tone's table is
/// 1.3 MB; the ten named tones and a few ITAs fit).
pub const MAX_TABLES: usize = 32;

/// The directory of the skin colour tables: `$ROUGE_CACHE_DIR/skin-tables`, else
/// `$XDG_CACHE_HOME/rouge/skin-tables`, else `~/.cache/rouge/skin-tables`; `None` when none of
/// those variables is set.
pub fn default_table_dir() -> Option<PathBuf> {
    cache_dir("skin-tables")
}

/// [`SkinColorTable::new`] for `base`, read from `dir` when a valid table of it is there, else
/// computed and written there (atomically; a directory that cannot be written costs the next
/// call the computation again, nothing else). `dir = None` computes without a cache.
///
/// # Errors
/// [`SkinError`] when `base` is outside the model's domain, as [`SkinColorTable::new`].
pub fn color_table_cached(base: &SkinParams, dir: Option<&Path>) -> Result<(SkinColorTable, CacheUse), SkinError> {
    let Some(dir) = dir else {
        return Ok((SkinColorTable::new(base)?, CacheUse::Off));
    };
    base.validate()?;
    let mut key = WordHasher::new();
    for v in base.to_array() {
        let bits = v.to_bits();
        key.word(bits as u32);
        key.word((bits >> 32) as u32);
    }
    let name = format!("{}.bin", hex(&key.finish()));
    if let Ok(bytes) = std::fs::read(dir.join(&name))
        && let Some(table) = unseal(&bytes).and_then(|body| SkinColorTable::from_bytes(base, body))
    {
        return Ok((table, CacheUse::Hit));
    }
    let table = SkinColorTable::new(base)?;
    if write_atomically(dir, &name, &seal(table.to_bytes())).is_ok() {
        evict_oldest(dir);
    }
    Ok((table, CacheUse::Miss))
}

/// Removes the least recently modified tables of `dir` beyond [`MAX_TABLES`].
fn evict_oldest(dir: &Path) {
    let Ok(entries) = std::fs::read_dir(dir) else { return };
    let mut tables: Vec<(std::time::SystemTime, PathBuf)> = entries
        .filter_map(|e| e.ok())
        .filter(|e| e.file_name().to_str().is_some_and(|n| n.ends_with(".bin") && !n.starts_with('.')))
        .filter_map(|e| Some((e.metadata().ok()?.modified().ok()?, e.path())))
        .collect();
    if tables.len() > MAX_TABLES {
        tables.sort();
        for (_, path) in &tables[..tables.len() - MAX_TABLES] {
            let _ = std::fs::remove_file(path);
        }
    }
}
