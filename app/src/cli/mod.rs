//! The subcommands of `rouge`, a module each: its options (clap), its run, its output.

pub mod analyze;
pub mod analyze_correct;
pub mod analyze_metamerism;
pub mod analyze_plot;
pub mod analyze_recipe;
pub mod color;
pub mod export;
pub mod export_web;
pub mod finish;
pub mod import;
pub mod km;
pub mod qc;
pub mod render;
pub mod skin;
pub mod skin_maps;
