//! Every integration test of rouge-model, one test executable: each file of tests/ is a module here
//! (one compile and link of the crate and its dependencies for all of them; see tests/run.sh).
//! Run one file's tests with `cargo test -p rouge-model --test model <file>::`.

mod common;
mod document;
mod look;
mod mesh;
mod paint;
mod paint_surface;
mod parts;
mod project_commit;
mod shapes;
mod skin_edits;
mod skin_maps;
mod skin_project;
mod skin_table_cache;
mod targets;
mod thickness;
