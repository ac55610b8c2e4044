//! Shared helpers of the workspace integration tests (`rouge-tests`): where the repository is,
//! reading the CSV tables under `data/` (reference values, truth files), and error measures.
//! Only `std`: the test targets bring `rouge-measure`, `proptest` and the rest.

use std::path::{Path, PathBuf};

/// The repository root (the directory holding the workspace `Cargo.toml`).
pub fn repo_root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).parent().map_or_else(|| PathBuf::from(".."), Path::to_path_buf)
}

/// A path under `data/`.
pub fn data_path(relative: &str) -> PathBuf {
    repo_root().join("data").join(relative)
}

/// One data row of a [`Table`].
#[derive(Clone, Debug, PartialEq)]
pub struct Row {
    /// 1-based line in the file.
    pub line: usize,
    /// The cells, trimmed, in header order.
    pub cells: Vec<String>,
}

/// A comma-separated table: `#` comment lines and blank lines skipped, the first other line is
/// the header, every following line a row with exactly as many cells as the header.
#[derive(Clone, Debug, PartialEq)]
pub struct Table {
    /// The file.
    pub path: PathBuf,
    /// Column names.
    pub header: Vec<String>,
    /// Data rows.
    pub rows: Vec<Row>,
}

impl Table {
    /// Reads a table; panics with the file and line on any malformation (test data is fixed).
    pub fn read(path: &Path) -> Table {
        let text = std::fs::read_to_string(path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
        let mut lines = text
            .lines()
            .enumerate()
            .map(|(i, l)| (i + 1, l.trim()))
            .filter(|(_, l)| !l.is_empty() && !l.starts_with('#'));
        let (_, header) = lines.next().unwrap_or_else(|| panic!("{}: no header", path.display()));
        let header: Vec<String> = header.split(',').map(|c| c.trim().to_string()).collect();
        let rows = lines
            .map(|(line, l)| {
                let cells: Vec<String> = l.split(',').map(|c| c.trim().to_string()).collect();
                assert_eq!(cells.len(), header.len(), "{}:{line}: wrong number of cells", path.display());
                Row { line, cells }
            })
            .collect();
        Table { path: path.to_path_buf(), header, rows }
    }

    /// Index of a column; panics if the table has no such column.
    pub fn column(&self, name: &str) -> usize {
        self.header
            .iter()
            .position(|h| h == name)
            .unwrap_or_else(|| panic!("{}: no column `{name}` in {:?}", self.path.display(), self.header))
    }

    /// The text of a cell.
    pub fn text<'a>(&self, row: &'a Row, name: &str) -> &'a str {
        &row.cells[self.column(name)]
    }

    /// A cell as the nearest binary64 (`str::parse` rounds correctly; magnitudes beyond the
    /// binary64 range give 0 or ∞).
    pub fn num(&self, row: &Row, name: &str) -> f64 {
        let t = self.text(row, name);
        t.parse::<f64>().unwrap_or_else(|e| panic!("{}:{}: `{name}` = `{t}`: {e}", self.path.display(), row.line))
    }

    /// A cell as a reference value (see [`RefValue`]).
    pub fn reference(&self, row: &Row, name: &str) -> RefValue {
        RefValue::parse(self.text(row, name))
            .unwrap_or_else(|| panic!("{}:{}: `{name}` is not a number", self.path.display(), row.line))
    }

    /// A whole column as numbers.
    pub fn nums(&self, name: &str) -> Vec<f64> {
        self.rows.iter().map(|r| self.num(r, name)).collect()
    }
}

/// A high-precision decimal reference classified by how a binary64 result can be compared to it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum RefValue {
    /// Exactly zero (every digit of the decimal is 0): the result must be exactly 0.
    Zero,
    /// Nonzero but below `f64::MIN_POSITIVE` (subnormal or far beyond the binary64 range): the
    /// result must be at most 1e-300 in magnitude.
    Tiny,
    /// A normal binary64 (the decimal correctly rounded): compare relatively.
    Normal(f64),
}

impl RefValue {
    /// Classifies a decimal string; `None` if it is not a number.
    pub fn parse(text: &str) -> Option<RefValue> {
        let v = text.trim().parse::<f64>().ok()?;
        let mantissa = text.trim().split(['e', 'E']).next().unwrap_or("");
        let all_zero = mantissa.chars().filter(char::is_ascii_digit).all(|c| c == '0');
        Some(if all_zero {
            RefValue::Zero
        } else if v.abs() < f64::MIN_POSITIVE {
            RefValue::Tiny
        } else {
            RefValue::Normal(v)
        })
    }

    /// Checks `value` against the reference: `Ok(relative error)` (0 for Zero/Tiny references
    /// that are met) or `Err(description)`.
    pub fn check(self, value: f64, rel_tol: f64) -> Result<f64, String> {
        match self {
            RefValue::Zero if value == 0.0 => Ok(0.0),
            RefValue::Zero => Err(format!("{value:e} should be exactly 0")),
            RefValue::Tiny if value.abs() <= 1e-300 => Ok(0.0),
            RefValue::Tiny => Err(format!("{value:e} should be ≤ 1e-300 (the reference is below f64::MIN_POSITIVE)")),
            RefValue::Normal(r) => {
                let e = rel_err(value, r);
                if e <= rel_tol {
                    Ok(e)
                } else {
                    Err(format!("{value:e} vs reference {r:e}: relative error {e:.3e} > {rel_tol:e}"))
                }
            }
        }
    }
}

/// `|value − reference| / |reference|` (∞ for NaN).
pub fn rel_err(value: f64, reference: f64) -> f64 {
    let e = ((value - reference) / reference).abs();
    if e.is_nan() { f64::INFINITY } else { e }
}

/// Whether `a` and `b` agree to `rel_tol` relative to the larger magnitude; two values both below
/// `f64::MIN_POSITIVE` (subnormal: relative precision is lost there) always agree.
pub fn close_rel(a: f64, b: f64, rel_tol: f64) -> bool {
    let m = a.abs().max(b.abs());
    a == b || (a - b).abs() <= rel_tol * m || m < f64::MIN_POSITIVE
}

/// Median of finite values (the upper median for an even count); NaN for an empty slice.
pub fn median(values: &[f64]) -> f64 {
    let mut v = values.to_vec();
    v.sort_by(f64::total_cmp);
    if v.is_empty() { f64::NAN } else { v[v.len() / 2] }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn classifies_references() {
        assert_eq!(RefValue::parse("0.0"), Some(RefValue::Zero));
        assert_eq!(RefValue::parse("0"), Some(RefValue::Zero));
        assert_eq!(RefValue::parse("5.07e-435"), Some(RefValue::Tiny));
        assert_eq!(RefValue::parse("1e-310"), Some(RefValue::Tiny));
        assert_eq!(RefValue::parse("2.5e-1990187337223280832993117860957271489"), Some(RefValue::Tiny));
        assert_eq!(RefValue::parse("0.5"), Some(RefValue::Normal(0.5)));
        assert_eq!(RefValue::parse("x"), None);
        assert!(RefValue::Tiny.check(1e-301, 1e-9).is_ok());
        assert!(RefValue::Zero.check(1e-320, 1e-9).is_err());
        assert!(RefValue::Normal(1.0).check(f64::NAN, 1e-9).is_err());
    }

    #[test]
    fn repo_root_holds_the_data() {
        assert!(data_path("reference/km_invert.csv").is_file());
    }
}
