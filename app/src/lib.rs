//! The `rouge` application: the painting app (`gui`), shared by the binary and its tests.

pub mod gui;
