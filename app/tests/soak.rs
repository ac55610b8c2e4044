//! The short soak (CI's version of `rouge bench soak`, docs/BENCHMARKS.md "Soak"): a few
//! thousand dabs of the scripted session on the editor core, with a small undo budget so that the
//! history reaches it: the undo history stays within its budget, the process's memory stops
//! growing with it, and the project saved at the end (and the last autosave) reopen equal to the
//! document in memory. Times are reported, not asserted.

use std::process::Command;

#[test]
fn a_short_soak_stays_within_the_undo_budget_and_reopens_identical() {
    let dir = tempfile::tempdir().expect("tempdir");
    let json = dir.path().join("soak.json");
    let budget_mib = 48.0;
    let o = Command::new(env!("CARGO_BIN_EXE_rouge"))
        .args(["bench", "soak", "--dabs", "3000", "--history-budget-mib", "48", "--seed", "3", "--dir"])
        .arg(dir.path().join("work"))
        .arg("--json")
        .arg(&json)
        .output()
        .expect("run rouge");
    let stdout = String::from_utf8_lossy(&o.stdout);
    assert!(o.status.success(), "{stdout}\n{}", String::from_utf8_lossy(&o.stderr));
    let r: serde_json::Value = serde_json::from_slice(&std::fs::read(&json).expect("the report")).expect("JSON");
    let n = |k: &str| r[k].as_f64().unwrap_or_else(|| panic!("{k} in {r}"));
    assert_eq!(r["reopened_identical"], true, "{stdout}");
    assert!(n("dabs") >= 3000.0, "{stdout}");
    // Everything the script does, done: undo bursts, layer edits, poses, saves and autosaves.
    for (k, at_least) in
        [("undos", 50.0), ("redos", 10.0), ("layer_edits", 5.0), ("pose_changes", 2.0), ("autosaves", 1.0)]
    {
        assert!(n(k) >= at_least, "{k}: {}\n{stdout}", n(k));
    }
    let slices = r["slices"].as_array().expect("slices");
    assert_eq!(slices.len(), 10, "{stdout}");
    let s = |i: usize, k: &str| slices[i][k].as_f64().unwrap_or_else(|| panic!("{k}"));
    for i in 0..10 {
        assert!(s(i, "history_mib") <= budget_mib, "slice {i}: the history is past its budget\n{stdout}");
        assert!(s(i, "dab_ms_mean") > 0.0 && s(i, "rss_mib") > 0.0, "slice {i}\n{stdout}");
    }
    // No growth beyond the undo budget: from the first tenth on, memory grows by less than the
    // history may hold plus a few maps (16 MiB each) of the layers added since.
    let growth = (1..10).map(|i| s(i, "rss_mib")).fold(f64::MIN, f64::max) - s(0, "rss_mib");
    assert!(growth < budget_mib + 6.0 * 16.0, "memory grew {growth:.0} MiB\n{stdout}");
}
