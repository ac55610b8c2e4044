//! Every integration test of rouge-measure, one test executable: each file of tests/ is a module here
//! (one compile and link of the crate and its dependencies for all of them; see tests/run.sh).
//! Run one file's tests with `cargo test -p rouge-measure --test measure <file>::`.

mod analysis;
mod colorimetry;
mod correction;
mod km;
mod preset;
mod recipe;
mod skin;
mod skin_properties;
mod skin_table;
mod skin_transport;
mod uncertainty;
