//! The one error of a located input: a file, and the line and column in it where something is
//! wrong. Every spectral input (measurements, spectra tables, CGATS, the embedded ColorChecker)
//! and every preset JSON error is one; `Display` writes `file:line:column: message`, dropping
//! the parts the error has not (`file: message` for a whole-file error).

use std::fmt;
use std::path::{Path, PathBuf};

/// An error in an input file: where, and why.
///
/// # Examples
///
/// ```
/// use rouge_measure::LocatedError;
/// use std::path::Path;
///
/// let e = LocatedError::at(Path::new("skin.csv"), 3, Some(2), "`x` is not a number");
/// assert_eq!(e.to_string(), "skin.csv:3:2: `x` is not a number");
/// let e = LocatedError::file(Path::new("skin.csv"), "the file is empty");
/// assert_eq!(e.to_string(), "skin.csv: the file is empty");
/// ```
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub struct LocatedError {
    /// The file (`<embedded ...>` for data compiled into Rouge).
    pub path: PathBuf,
    /// 1-based line, when the error has one.
    pub line: Option<usize>,
    /// 1-based column (field number in tables, character in JSON), when the error has one.
    pub column: Option<usize>,
    /// What is wrong.
    pub message: String,
}

impl fmt::Display for LocatedError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}", self.path.display())?;
        if let Some(line) = self.line {
            write!(f, ":{line}")?;
            if let Some(column) = self.column {
                write!(f, ":{column}")?;
            }
        }
        write!(f, ": {}", self.message)
    }
}

impl LocatedError {
    /// An error about the whole file.
    pub fn file(path: &Path, message: impl Into<String>) -> Self {
        LocatedError { path: path.to_path_buf(), line: None, column: None, message: message.into() }
    }

    /// An error at a line (and optionally a column).
    pub fn at(path: &Path, line: usize, column: Option<usize>, message: impl Into<String>) -> Self {
        LocatedError { path: path.to_path_buf(), line: Some(line), column, message: message.into() }
    }
}
