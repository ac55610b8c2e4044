//! Rouge renderer: real-time skin with layered cosmetics (\[Huang2013\] section 3, figure 1) on wgpu.
//!
//! It uploads what `rouge-model` gives it (meshes, looks, thickness maps) and knows no UI.
//! Headless first: [`Gpu`] opens a device without a window (Mesa lavapipe where there is no
//! GPU), and the painting app hands in its own device. The public surface:
//! - [`Renderer`]: uploads (mesh, look, skin maps) and the frame; [`Scene`], [`Camera`] and the
//!   skin's [`SubsurfaceModel`] describe what it draws.
//! - [`frame`]: the frame plan (which passes run, on which targets, what is skipped and why).
//! - [`job`]: headless renders to PNG/EXR, the `rouge render` path; [`gltf_export`]: the scene as
//!   glTF 2.0 with the look baked into textures (`rouge export gltf`).
//! - The CPU models the passes run: [`sss`] (the diffusion profile and separable kernel),
//!   [`diffusion`], [`half_space`] (the exact half-space under the diffusion profiles, η = 1) and
//!   [`dielectric_half_space`] (its albedo under a dielectric boundary, the media's albedo) with
//!   [`dielectric_brdf`] (its angular law there, the `half-space` diffuse law's) and
//!   [`curved_half_space`] (a curved surface of it under light from every side),
//!   [`directional_dipole`], [`cube_atlas`], [`local_thickness`], [`env`](mod@env)
//!   (environment maps and their spherical-harmonics irradiance, \[Benmounah2009\] section 4.1.2),
//!   [`specular`], [`edges`] and [`silhouettes`] with [`aa`] (antialiasing).
//! - Studies and references: [`study`], [`translucency`], [`aa_study`], [`mitsuba`],
//!   [`profile_fit`], [`skin_study`] (skin under makeup against the spectral composition).
//!
//! Inside, one module per pass (`passes`, each declared once in its registry), the shader
//! preprocessor (`shader`), the uniforms, targets and wgpu helpers serve the renderer only.

pub mod aa;
pub mod aa_study;
pub mod bounce;
pub mod cube_atlas;
pub mod curved_half_space;
pub mod dielectric_brdf;
pub mod dielectric_half_space;
pub mod diffusion;
pub mod directional_dipole;
pub mod edges;
pub mod env;
pub mod error;
pub mod fibre;
pub mod frame;
pub mod glitter;
pub mod glitter_study;
pub mod gltf_export;
pub mod gpu;
pub(crate) mod gpu_look;
pub(crate) mod gpu_mesh;
pub mod half_space;
pub mod job;
pub mod local_thickness;
pub mod materialx_export;
pub mod mitsuba;
pub(crate) mod passes;
pub mod profile_fit;
pub(crate) mod profiler;
pub mod renderer;
pub mod scene;
pub(crate) mod shader;
pub mod silhouettes;
pub mod skin_study;
pub mod slab_extent;
pub mod slab_march;
pub mod slab_transmittance;
pub mod specular;
pub mod sss;
pub mod study;
pub mod targets;
pub mod through_gather;
pub mod translucency;
pub(crate) mod uniforms;
pub(crate) mod wgpu_util;

pub use directional_dipole::{DipoleKind, DipoleSettings};
pub use error::{RenderError, Result};
pub use gpu::Gpu;
pub use gpu_mesh::HairAlbedo;
pub use profiler::PassTiming;
pub use renderer::Renderer;
pub use scene::{
    Camera, DiffuseLaw, Light, LightKind, LightRig, Scene, Skin, SlabThrough, SssSettings, SubsurfaceModel,
};
pub use shader::{MAX_LAYERS, ThicknessVariant, Variant};
pub use uniforms::{MAX_LIGHTS, SceneConstants};
