//! The mesh on the GPU: one interleaved vertex buffer (position, normal, UV, albedo with the
//! skin flag, tangent) and a 32-bit index buffer, with the vertex layouts the passes draw it with.

use crate::error::{RenderError, Result};
use crate::wgpu_util::buffer_init;
use bytemuck::{Pod, Zeroable};
use glam::Vec3;
use rouge_model::mesh::{Bounds, TriangleMesh};

/// One vertex, as the G-buffer and shadow passes read it.
#[repr(C)]
#[derive(Clone, Copy, Pod, Zeroable)]
struct Vertex {
    position: [f32; 3],
    normal: [f32; 3],
    uv: [f32; 2],
    albedo: [f32; 4],
    tangent: [f32; 4],
}

/// Every attribute of [`Vertex`] (G-buffer pass).
const FULL_ATTRIBUTES: [wgpu::VertexAttribute; 5] =
    wgpu::vertex_attr_array![0 => Float32x3, 1 => Float32x3, 2 => Float32x2, 3 => Float32x4, 4 => Float32x4];
/// The position only (shadow pass), same stride.
const POSITION_ATTRIBUTES: [wgpu::VertexAttribute; 1] = wgpu::vertex_attr_array![0 => Float32x3];

/// The vertex buffer layout with every attribute.
pub fn full_layout() -> wgpu::VertexBufferLayout<'static> {
    wgpu::VertexBufferLayout {
        array_stride: std::mem::size_of::<Vertex>() as u64,
        step_mode: wgpu::VertexStepMode::Vertex,
        attributes: &FULL_ATTRIBUTES,
    }
}

/// The vertex buffer layout with positions only.
pub fn position_layout() -> wgpu::VertexBufferLayout<'static> {
    wgpu::VertexBufferLayout {
        array_stride: std::mem::size_of::<Vertex>() as u64,
        step_mode: wgpu::VertexStepMode::Vertex,
        attributes: &POSITION_ATTRIBUTES,
    }
}

/// An uploaded triangle mesh.
#[derive(Debug)]
pub struct GpuMesh {
    vertices: wgpu::Buffer,
    indices: wgpu::Buffer,
    index_count: u32,
    /// Bounds of the positions, mm.
    pub bounds: Bounds,
    /// Whether the vertices carry tangents (a normal map needs them).
    pub has_tangents: bool,
    /// The mesh's mean scale, mm per UV unit (the skin detail's,
    /// [`rouge_model::skin::detail::tiles_per_uv`] × its tile): the glitter's flake fields lie
    /// in UV × this. 0 for a mesh without UV area.
    pub mm_per_uv: f32,
}

impl GpuMesh {
    /// Uploads `mesh` (mm) with `skin_albedo` (linear sRGB) on skin vertices and `hair` on the
    /// lashes and brows.
    ///
    /// # Errors
    /// [`RenderError::Invalid`] for a mesh without vertices or triangles.
    pub fn upload(
        device: &wgpu::Device,
        mesh: &TriangleMesh,
        skin_albedo: [f32; 3],
        hair: HairAlbedo,
    ) -> Result<GpuMesh> {
        let bounds =
            Bounds::of(&mesh.positions).ok_or_else(|| RenderError::Invalid("the mesh has no vertices".into()))?;
        if mesh.indices.is_empty() {
            return Err(RenderError::Invalid("the mesh has no triangles".into()));
        }
        let albedo = vertex_albedo(mesh, skin_albedo, hair);
        let vertices: Vec<Vertex> = (0..mesh.positions.len())
            .map(|i| Vertex {
                position: mesh.positions[i].to_array(),
                normal: mesh.normals.get(i).copied().unwrap_or(Vec3::Z).to_array(),
                uv: mesh.uvs.get(i).map_or([0.0; 2], |uv| uv.to_array()),
                albedo: albedo[i],
                tangent: mesh.tangents.as_ref().and_then(|t| t.get(i)).map_or([0.0; 4], |t| t.to_array()),
            })
            .collect();
        let mm_per_uv =
            rouge_model::skin::detail::tiles_per_uv(mesh).map_or(0.0, |t| t * rouge_model::skin::detail::TILE_MM);
        Ok(GpuMesh {
            mm_per_uv,
            vertices: buffer_init(
                device,
                "GpuMesh::vertices",
                bytemuck::cast_slice(&vertices),
                wgpu::BufferUsages::VERTEX,
            ),
            indices: buffer_init(
                device,
                "GpuMesh::indices",
                bytemuck::cast_slice(&mesh.indices),
                wgpu::BufferUsages::INDEX,
            ),
            index_count: mesh.indices.len() as u32,
            bounds,
            has_tangents: mesh.tangents.is_some(),
        })
    }

    /// Binds the buffers and draws every triangle.
    pub fn draw(&self, pass: &mut wgpu::RenderPass<'_>) {
        self.draw_instance(pass, 0);
    }

    /// Draws every triangle as instance `instance` (a shader's `instance_index` then selects a
    /// view, as the dipole passes' directions and lights do).
    pub fn draw_instance(&self, pass: &mut wgpu::RenderPass<'_>, instance: u32) {
        pass.set_vertex_buffer(0, self.vertices.slice(..));
        pass.set_index_buffer(self.indices.slice(..), wgpu::IndexFormat::Uint32);
        pass.draw_indexed(0..self.index_count, 0, instance..instance + 1);
    }
}

/// Linear albedo of the teeth: a natural tooth's shade about CIELAB (78, 1, 18) (the middle of
/// the VITA classical shade guide's A range as spectrophotometers read it, \[Chu2010\]).
pub const TEETH_ALBEDO: [f32; 3] = [0.60, 0.52, 0.38];
/// Linear albedo of the tongue: a healthy tongue body, about CIELAB (48, 27, 11) (tongue colour
/// in calibrated images, \[Wang2013\]).
pub const TONGUE_ALBEDO: [f32; 3] = [0.30, 0.11, 0.09];
/// Linear albedo of the oral cavity seen between parted lips: the mucosa (about the tongue's
/// colour) times about 1/3 for the occlusion of the mouth, which the renderer does not compute
/// (a path-traced open mouth is this dark a few millimetres behind the lips).
pub const MOUTH_ALBEDO: [f32; 3] = [0.10, 0.035, 0.03];
/// Linear albedo of a dark eyelash: eumelanin-rich hair absorbs nearly all the light that
/// enters it, so a black lash reflects a few percent, mostly at its surface. A stand-in for a
/// fibre model (issue 27's hair shading), not a measurement.
pub const LASH_ALBEDO: [f32; 3] = [0.030, 0.025, 0.021];
/// The hairs' linear albedo: the lashes' (a mascara's colour, or the natural lash's) and the
/// brows' (constants in `render/src/gpu_mesh.rs`, cited there).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct HairAlbedo {
    /// The lashes'.
    pub lash: [f32; 3],
    /// The brows'.
    pub brow: [f32; 3],
}

impl Default for HairAlbedo {
    fn default() -> HairAlbedo {
        HairAlbedo { lash: LASH_ALBEDO, brow: BROW_ALBEDO }
    }
}

impl HairAlbedo {
    /// The natural hairs with `mascara`'s colour on the lashes, if it has one.
    pub fn with_mascara(mascara: Option<&rouge_model::mesh::lashes::Mascara>) -> HairAlbedo {
        let natural = HairAlbedo::default();
        HairAlbedo { lash: mascara.and_then(|m| m.color).unwrap_or(natural.lash), ..natural }
    }
}

/// Linear albedo of the eyebrow hairs: dark brown (the same stand-in as the lashes', a little
/// lighter: brow hair carries less eumelanin than lash hair in most people).
pub const BROW_ALBEDO: [f32; 3] = [0.055, 0.038, 0.027];

/// Albedo and material per vertex: the skin's albedo (a = 1: scatters, takes cosmetics) on skin
/// groups; every other part ([`rouge_model::mesh::Part`]) does not scatter (a = 0): eyes get a
/// sclera, iris and pupil by angle from the eye's forward axis (+Z), the mouth, teeth, tongue,
/// lashes and brows their constant albedo.
pub(crate) fn vertex_albedo(mesh: &TriangleMesh, skin: [f32; 3], hair: HairAlbedo) -> Vec<[f32; 4]> {
    use rouge_model::mesh::Part;
    let mut albedo = vec![[skin[0], skin[1], skin[2], 1.0]; mesh.positions.len()];
    for g in &mesh.groups {
        let constant = match g.part() {
            Part::Skin => continue,
            Part::Eye => None,
            Part::Mouth => Some(MOUTH_ALBEDO),
            Part::Teeth => Some(TEETH_ALBEDO),
            Part::Tongue => Some(TONGUE_ALBEDO),
            Part::Lash => Some(hair.lash),
            Part::Brow => Some(hair.brow),
        };
        let mut verts: Vec<u32> = mesh.indices[g.triangles.start * 3..g.triangles.end * 3].to_vec();
        verts.sort_unstable();
        verts.dedup();
        if let Some([r, gr, b]) = constant {
            verts.iter().for_each(|&v| albedo[v as usize] = [r, gr, b, 0.0]);
            continue;
        }
        if verts.is_empty() {
            continue;
        }
        let centre = verts.iter().map(|&v| mesh.positions[v as usize]).sum::<Vec3>() / verts.len() as f32;
        for &v in &verts {
            let d = (mesh.positions[v as usize] - centre).normalize_or_zero();
            let cos = d.z;
            albedo[v as usize] = if cos > 0.985 {
                [0.01, 0.01, 0.01, 0.0]
            } else if cos > 0.93 {
                [0.10, 0.05, 0.025, 0.0]
            } else {
                [0.62, 0.58, 0.55, 0.0]
            };
        }
    }
    albedo
}
