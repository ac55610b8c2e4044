//! The `rouge` application: the painting app (`gui`), shared by the binary and its tests.

pub mod editor;
pub mod gui;
pub mod heatmap;
pub mod looks;
pub mod material_plots;
pub mod radius_drag;
pub mod ticks;
