//! Every integration test of rouge-render, one test executable: each file of tests/ is a module here
//! (one compile and link of the crate and its dependencies for all of them; see tests/run.sh).
//! Run one file's tests with `cargo test -p rouge-render --test render <file>::`.

mod bounce_gpu;
mod common;
mod cube_atlas_gpu;
mod curved_half_space;
mod dielectric_brdf;
mod dielectric_half_space;
mod diffusion;
mod dipole_gpu;
mod directional_dipole;
mod edges;
mod env;
mod face_parts;
mod face_pose;
mod fibre_gpu;
mod finish_gpu;
mod frame;
mod gltf_bake;
mod half_space;
mod mitsuba;
mod skin_maps;
mod slab_gpu;
mod slab_spread_gpu;
mod slab_transmittance;
mod specular_gpu;
mod thickness;
