//! How the benches report: a Markdown table for docs/BENCHMARKS.md on stdout and, when asked, the
//! rows as JSON.

use anyhow::Result;
use std::path::Path;

/// A Markdown table: `caption` on its own line, the header, the alignment row (the first `left`
/// columns left-aligned, the others right), then `rows`.
pub fn markdown_table(
    caption: &str,
    header: &[&str],
    left: usize,
    rows: impl IntoIterator<Item = Vec<String>>,
) -> String {
    let align: Vec<&str> = (0..header.len()).map(|i| if i < left { "---" } else { "---:" }).collect();
    let mut out = format!("{caption}\n| {} |\n|{}|\n", header.join(" | "), align.join("|"));
    for row in rows {
        out += &format!("| {} |\n", row.join(" | "));
    }
    out
}

/// Prints `table` and, with `json`, writes `rows` there as pretty JSON (atomically).
///
/// # Errors
/// A closed output or an unwritable file, named.
pub fn emit_with_json<T: serde::Serialize>(table: &str, rows: &T, json: Option<&Path>) -> Result<()> {
    crate::emit(table.trim_end())?;
    if let Some(path) = json {
        let text = serde_json::to_string_pretty(rows)?;
        crate::write_output(path, text.as_bytes())?;
    }
    Ok(())
}
