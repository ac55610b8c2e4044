//! The workspace's integration tests, one test executable (one compile and link for all):
//! Kubelka-Munk against mpmath references (km_reference.rs), its properties (km_properties.rs),
//! measurement import (import_formats.rs) and the fuzzers' corpora replayed (fuzz_replay.rs).

mod fuzz_replay;
mod import_formats;
mod km_properties;
mod km_reference;
