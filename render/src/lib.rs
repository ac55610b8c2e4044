//! Rouge renderer, CPU side: loading and preparing head meshes for rendering.
//!
//! This first piece holds no GPU code. It loads polygon meshes from OBJ and glTF
//! ([`mesh::load_obj`], [`mesh::load_gltf`]), subdivides them with Catmull-Clark
//! ([`mesh::Mesh::catmull_clark`]), triangulates them into indexed vertex buffers
//! ([`mesh::Mesh::triangulate`]) and generates MikkTSpace tangents
//! ([`mesh::TriangleMesh::generate_tangents`]).

pub mod mesh;

pub use mesh::{Bounds, Corner, Face, Group, Mesh, MeshError, TriangleGroup, TriangleMesh, load_gltf, load_obj};
