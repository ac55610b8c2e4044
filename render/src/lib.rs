//! Rouge renderer: real-time skin with layered cosmetics ([Huang2013] section 3, figure 1) on wgpu.
//!
//! It uploads what `rouge-model` gives it (meshes, looks, thickness maps) and knows no UI.
//! Headless first: [`gpu::Gpu`] opens a device without a window (Mesa lavapipe where there is no
//! GPU), and the painting app hands in its own device. Modules:
//! - [`env`]: HDR environment maps and their spherical-harmonics irradiance ([Benmounah2009] section 4.1.2).
//! - [`sss`]: the skin diffusion profile, the separable kernel and the brute-force reference.
//! - [`frame`]: the frame plan (which passes run, on which targets, what is skipped and why).
//! - [`passes`]: one module per pass, each with its pipelines, layouts and uniforms.
//! - [`renderer`]: uploads and the frame itself; [`targets`], [`shader`], [`uniforms`],
//!   [`profiler`] and [`wgpu_util`] serve it.

pub mod aa;
pub mod aa_study;
pub mod cube_atlas;
pub mod diffusion;
pub mod directional_dipole;
pub mod edges;
pub mod env;
pub mod error;
pub mod frame;
pub mod gpu;
pub mod gpu_look;
pub mod gpu_mesh;
pub mod job;
pub mod local_thickness;
pub mod mitsuba;
pub mod passes;
pub mod profile_fit;
pub mod profiler;
pub mod renderer;
pub mod scene;
pub mod shader;
pub mod silhouettes;
pub mod specular;
pub mod sss;
pub mod study;
pub mod targets;
pub mod translucency;
pub mod uniforms;
pub mod wgpu_util;

pub use error::{RenderError, Result};
pub use gpu::Gpu;
pub use renderer::Renderer;
pub use scene::{Camera, Light, LightKind, LightRig, Scene, Skin, SssSettings, SubsurfaceModel};
