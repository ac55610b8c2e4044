//! The skin colour tables' cache on disk (rouge_model::skin::table_cache): a miss computes and
//! writes, a hit reads the same table, a damaged or stale file is recomputed and replaced, a
//! directory that cannot be written still gives the table, and old tables are evicted.

use rouge_measure::skin::{SkinColorTable, skin_tone};
use rouge_model::disk_cache::CacheUse;
use rouge_model::skin::table_cache::{MAX_TABLES, color_table_cached};

fn tables_in(dir: &std::path::Path) -> Vec<std::path::PathBuf> {
    let mut v: Vec<_> = std::fs::read_dir(dir).expect("dir").map(|e| e.expect("entry").path()).collect();
    v.sort();
    v
}

#[test]
fn a_tone_s_table_is_computed_once_then_read_and_bad_files_are_recomputed() {
    let dir = tempfile::tempdir().expect("tempdir");
    let base = skin_tone("deep").expect("tone").params;
    let (first, use1) = color_table_cached(&base, Some(dir.path())).expect("table");
    assert_eq!(use1, CacheUse::Miss);
    let files = tables_in(dir.path());
    assert_eq!(files.len(), 1, "one file, no temporary left: {files:?}");
    let (second, use2) = color_table_cached(&base, Some(dir.path())).expect("table");
    assert_eq!(use2, CacheUse::Hit);
    assert_eq!(second.to_bytes(), first.to_bytes());
    assert_eq!(second.to_bytes(), SkinColorTable::new(&base).expect("table").to_bytes(), "what new() computes");
    // A flipped byte: the checksum refuses it; recomputed and the file replaced.
    let mut bytes = std::fs::read(&files[0]).expect("read");
    bytes[1000] ^= 0x10;
    std::fs::write(&files[0], &bytes).expect("write");
    let (third, use3) = color_table_cached(&base, Some(dir.path())).expect("table");
    assert_eq!((use3, third.to_bytes() == first.to_bytes()), (CacheUse::Miss, true));
    assert_eq!(color_table_cached(&base, Some(dir.path())).expect("table").1, CacheUse::Hit, "replaced");
    // Another tone is another file.
    let light = skin_tone("light").expect("tone").params;
    assert_eq!(color_table_cached(&light, Some(dir.path())).expect("table").1, CacheUse::Miss);
    assert_eq!(tables_in(dir.path()).len(), 2);
    // No directory: computed, not stored; a directory that is a file: computed all the same.
    assert_eq!(color_table_cached(&base, None).expect("table").1, CacheUse::Off);
    let blocked = dir.path().join("a-file");
    std::fs::write(&blocked, b"not a directory").expect("write");
    let (table, used) = color_table_cached(&base, Some(&blocked)).expect("the table without its cache");
    assert_eq!((used, table.to_bytes() == first.to_bytes()), (CacheUse::Miss, true));
    // Out of the model's domain: the model's error, not a cache file.
    let bad = rouge_measure::skin::SkinParams { blood_fraction: f64::NAN, ..base };
    assert!(color_table_cached(&bad, Some(dir.path())).is_err());
}

#[test]
fn the_oldest_tables_go_beyond_the_limit() {
    let dir = tempfile::tempdir().expect("tempdir");
    for k in 0..MAX_TABLES {
        std::fs::write(dir.path().join(format!("old{k:02}.bin")), b"an older table").expect("write");
    }
    // Older by their modification time.
    std::thread::sleep(std::time::Duration::from_millis(20));
    let base = skin_tone("light").expect("tone").params;
    assert_eq!(color_table_cached(&base, Some(dir.path())).expect("table").1, CacheUse::Miss);
    let files = tables_in(dir.path());
    assert_eq!(files.len(), MAX_TABLES, "{files:?}");
    assert!(!files.iter().any(|f| f.ends_with("old00.bin")), "the oldest went");
    assert_eq!(color_table_cached(&base, Some(dir.path())).expect("table").1, CacheUse::Hit, "the newest stayed");
}
