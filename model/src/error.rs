//! The model's error type. Every error that comes from a file names that file.

use crate::mesh::MeshError;
use std::fmt::Display;
use std::path::Path;

/// Why loading or saving a mesh, look, project or map failed, or an edit was refused.
#[derive(Debug, thiserror::Error)]
pub enum ModelError {
    /// A file (look, preset, thickness map, project, export) could not be read, parsed or
    /// written. `path` is the file as given; `message` says what is wrong with it, with the
    /// field, line or pixel where one applies.
    #[error("{path}: {message}")]
    File {
        /// The file at fault.
        path: String,
        /// What is wrong with it.
        message: String,
    },
    /// The mesh could not be loaded or prepared.
    #[error(transparent)]
    Mesh(#[from] MeshError),
    /// A parameter is out of its domain (the message says which and why).
    #[error("{0}")]
    Invalid(String),
}

impl ModelError {
    /// An error about the file at `path`.
    pub fn file(path: &Path, message: impl Display) -> Self {
        ModelError::File { path: path.display().to_string(), message: message.to_string() }
    }
}

/// Result with [`ModelError`].
pub type Result<T> = std::result::Result<T, ModelError>;
