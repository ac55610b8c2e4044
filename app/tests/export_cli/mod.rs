//! The exports end to end (a module of the app's one test executable, tests/all.rs):
//! `rouge export gltf` (gltf.rs), `rouge export web` (web.rs), `rouge export materialx`
//! (materialx.rs), both killed at any moment (kill.rs), with what they share in common.rs.

mod common;
mod gltf;
mod kill;
mod materialx;
mod web;
