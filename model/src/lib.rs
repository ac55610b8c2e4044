//! Rouge's model: everything a makeup session edits, with no GPU and no UI, so that the
//! renderer (`rouge-render`) only uploads what it is given and the editor logic is testable
//! without a window or a device.
//!
//! - [`mesh`]: OBJ/glTF loading with a unit scale, Catmull-Clark, triangulation, MikkTSpace, the
//!   embedded default head.
//! - [`look`]: the look document (cosmetic layers bottom to top, each a preset and a thickness).
//! - [`document`]: the painting document: layers with 2048² thickness maps, undo/redo, projects,
//!   exports, recovery.
//! - [`paint`]: the brush: the surface map, dabs, strokes.
//! - [`medium`]: physical participating media (σa, σs′, g, η), the built-in measured ones.
//! - [`rect`]: the one texel-rectangle type.
//! - [`skin`]: skin maps: the spectral skin model's parameters per texel, generated from a tone,
//!   the default head's anatomy and skin conditions, saved in projects.
//! - [`disk_cache`]: what the on-disk caches share (thickness bakes, skin colour tables).
//! - [`thickness`]: local thickness baked per vertex by inward rays (\[BarreBrisebois2011\]), its
//!   UV map and on-disk cache.

pub mod disk_cache;
pub mod document;
pub mod error;
pub mod hdr;
pub mod look;
pub mod medium;
pub mod mesh;
pub mod paint;
pub mod rect;
pub mod skin;
pub mod thickness;

pub use error::{ModelError, Result};
pub use mesh::{
    Bounds, Corner, Face, Group, Mesh, MeshError, TriangleGroup, TriangleMesh, load_gltf, load_mesh, load_obj,
};
pub use rect::TexelRect;
