//! Every integration test of rouge-app, one test executable: each file of tests/ is a module here
//! (one compile and link of the crate and its dependencies for all of them; see tests/run.sh).
//! Run one file's tests with `cargo test -p rouge-app --test app <file>::`.

mod analyze_cli;
mod cli;
mod common;
mod editor;
mod editor_paint;
mod editor_views;
mod export_cli;
mod face_cli;
mod gui;
mod gui_session;
mod gui_skin;
mod gui_views;
mod soak;
