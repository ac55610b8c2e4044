//! The exports end to end, one test executable (one link of the renderer for all of them):
//! `rouge export gltf` (gltf.rs), `rouge export web` (web.rs), `rouge export materialx`
//! (materialx.rs), both killed at any moment (kill.rs), with what they share in common.rs.

mod common;
mod gltf;
mod kill;
mod materialx;
mod web;
