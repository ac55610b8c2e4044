//! The renderer's error type. Every error that comes from a file names that file.

use rouge_model::mesh::MeshError;
use std::fmt::Display;
use std::path::Path;

/// Why loading a scene or rendering a frame failed.
#[derive(Debug, thiserror::Error)]
pub enum RenderError {
    /// A file (look, preset, thickness map, environment map, output) could not be read, parsed
    /// or written. `path` is the file as given; `message` says what is wrong with it, with the
    /// field, line or pixel where one applies.
    #[error("{path}: {message}")]
    File {
        /// The file at fault.
        path: String,
        /// What is wrong with it.
        message: String,
    },
    /// A model error (look, project, map, mesh): it names its file.
    #[error(transparent)]
    Model(#[from] rouge_model::ModelError),
    /// The mesh could not be loaded or prepared.
    #[error(transparent)]
    Mesh(#[from] MeshError),
    /// The GPU could not be set up or a GPU operation failed.
    #[error("GPU: {0}")]
    Gpu(String),
    /// A shader source breaks a rule of the `//#if` preprocessor (file and line named).
    #[error("shader: {0}")]
    Shader(String),
    /// A parameter is out of its domain (the message says which and why).
    #[error("{0}")]
    Invalid(String),
}

impl RenderError {
    /// An error about the file at `path`.
    pub fn file(path: &Path, message: impl Display) -> Self {
        RenderError::File { path: path.display().to_string(), message: message.to_string() }
    }
}

/// Result with [`RenderError`].
pub type Result<T> = std::result::Result<T, RenderError>;
