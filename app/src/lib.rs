//! The `rouge` application: the painting app (`gui`), shared by the binary and its tests.

pub mod editor;
pub mod gui;
