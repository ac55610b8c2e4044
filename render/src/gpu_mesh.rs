//! The mesh on the GPU: two vertex streams, the moving one (position and normal: what a pose
//! changes, rewritten in place by [`GpuMesh::move_to`]) and the fixed one (UV, albedo with the
//! skin flag, tangent), and a 32-bit index buffer, with the vertex layouts the passes draw it with.

use crate::error::{RenderError, Result};
use crate::wgpu_util::buffer_init;
use bytemuck::{Pod, Zeroable};
use glam::Vec3;
use rouge_model::mesh::{Bounds, TriangleMesh};

/// What a pose changes of a vertex (stream 0: the G-buffer and shadow passes read it).
#[repr(C)]
#[derive(Clone, Copy, Pod, Zeroable)]
struct MovingVertex {
    position: [f32; 3],
    normal: [f32; 3],
}

/// What a pose leaves alone (stream 1: the G-buffer pass reads it).
#[repr(C)]
#[derive(Clone, Copy, Pod, Zeroable)]
struct FixedVertex {
    uv: [f32; 2],
    albedo: [f32; 4],
    tangent: [f32; 4],
}

/// Position and normal (locations 0 and 1).
const MOVING_ATTRIBUTES: [wgpu::VertexAttribute; 2] = wgpu::vertex_attr_array![0 => Float32x3, 1 => Float32x3];
/// UV, albedo, tangent (locations 2-4).
const FIXED_ATTRIBUTES: [wgpu::VertexAttribute; 3] =
    wgpu::vertex_attr_array![2 => Float32x2, 3 => Float32x4, 4 => Float32x4];
/// The position only (shadow pass), the moving stream's stride.
const POSITION_ATTRIBUTES: [wgpu::VertexAttribute; 1] = wgpu::vertex_attr_array![0 => Float32x3];

/// The vertex buffer layouts with every attribute: the moving stream (slot 0), the fixed (slot 1).
pub fn full_layouts() -> [wgpu::VertexBufferLayout<'static>; 2] {
    [
        wgpu::VertexBufferLayout {
            array_stride: std::mem::size_of::<MovingVertex>() as u64,
            step_mode: wgpu::VertexStepMode::Vertex,
            attributes: &MOVING_ATTRIBUTES,
        },
        wgpu::VertexBufferLayout {
            array_stride: std::mem::size_of::<FixedVertex>() as u64,
            step_mode: wgpu::VertexStepMode::Vertex,
            attributes: &FIXED_ATTRIBUTES,
        },
    ]
}

/// The vertex buffer layout with positions only (the moving stream, slot 0).
pub fn position_layout() -> wgpu::VertexBufferLayout<'static> {
    wgpu::VertexBufferLayout {
        array_stride: std::mem::size_of::<MovingVertex>() as u64,
        step_mode: wgpu::VertexStepMode::Vertex,
        attributes: &POSITION_ATTRIBUTES,
    }
}

/// An uploaded triangle mesh.
#[derive(Debug)]
pub struct GpuMesh {
    moving: wgpu::Buffer,
    /// Mapped memory kept for [`GpuMesh::move_to`]'s writes: a new staging buffer each frame
    /// (`Queue::write_buffer`'s) cost the H200's frame 12 ms at 3 MB, the mapping of fresh
    /// host memory in its virtual machine.
    belt: wgpu::util::StagingBelt,
    fixed: wgpu::Buffer,
    indices: wgpu::Buffer,
    index_count: u32,
    /// The triangles that are not hair drawn as fibres (the G-buffer's when the hair pass runs),
    /// when the mesh has strands.
    without_hair: Option<(wgpu::Buffer, u32)>,
    vertex_count: usize,
    /// The albedos the fixed stream was written with (a pose under other albedos is uploaded
    /// afresh).
    albedos: ([f32; 3], HairAlbedo),
    /// Bounds of the positions, mm.
    pub bounds: Bounds,
    /// Whether the vertices carry tangents (a normal map needs them).
    pub has_tangents: bool,
    /// The mesh's mean scale, mm per UV unit (the skin detail's,
    /// [`rouge_model::skin::detail::tiles_per_uv`] × its tile): the glitter's flake fields lie
    /// in UV × this. 0 for a mesh without UV area.
    pub mm_per_uv: f32,
}

/// Vertex `i` of the moving stream of `mesh` (+Z where a normal is missing).
fn moving_vertex(mesh: &TriangleMesh, i: usize) -> MovingVertex {
    MovingVertex {
        position: mesh.positions[i].to_array(),
        normal: mesh.normals.get(i).copied().unwrap_or(Vec3::Z).to_array(),
    }
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
        let fixed: Vec<FixedVertex> = (0..mesh.positions.len())
            .map(|i| FixedVertex {
                uv: mesh.uvs.get(i).map_or([0.0; 2], |uv| uv.to_array()),
                albedo: albedo[i],
                tangent: mesh.tangents.as_ref().and_then(|t| t.get(i)).map_or([0.0; 4], |t| t.to_array()),
            })
            .collect();
        let mm_per_uv =
            rouge_model::skin::detail::tiles_per_uv(mesh).map_or(0.0, |t| t * rouge_model::skin::detail::TILE_MM);
        let vertex = wgpu::BufferUsages::VERTEX;
        let moving: Vec<MovingVertex> = (0..mesh.positions.len()).map(|i| moving_vertex(mesh, i)).collect();
        let moving_bytes: &[u8] = bytemuck::cast_slice(&moving);
        Ok(GpuMesh {
            mm_per_uv,
            moving: buffer_init(device, "GpuMesh::moving", moving_bytes, vertex | wgpu::BufferUsages::COPY_DST),
            belt: wgpu::util::StagingBelt::new(device.clone(), moving_bytes.len() as u64),
            fixed: buffer_init(device, "GpuMesh::fixed", bytemuck::cast_slice(&fixed), vertex),
            indices: buffer_init(
                device,
                "GpuMesh::indices",
                bytemuck::cast_slice(&mesh.indices),
                wgpu::BufferUsages::INDEX,
            ),
            index_count: mesh.indices.len() as u32,
            without_hair: without_hair(mesh).map(|indices| {
                let bytes: &[u8] = bytemuck::cast_slice(&indices);
                (buffer_init(device, "GpuMesh::without_hair", bytes, wgpu::BufferUsages::INDEX), indices.len() as u32)
            }),
            vertex_count: mesh.positions.len(),
            albedos: (skin_albedo, hair),
            bounds,
            has_tangents: mesh.tangents.is_some(),
        })
    }

    /// Moves the uploaded vertices to `mesh`'s positions and normals in place (the moving
    /// stream rewritten through kept staging memory, submitted at once; nothing allocated),
    /// when `mesh` is this mesh posed: as many vertices and triangle corners, under the same
    /// albedos, and tangents only if the upload had them. The triangles, UVs and albedos stay
    /// those of the upload (a posed mesh from [`rouge_model::mesh::deform::SubdivisionPlan`]
    /// keeps them). Returns `false`, changing nothing, for any other mesh (upload it afresh).
    pub fn move_to(
        &mut self,
        (device, queue): (&wgpu::Device, &wgpu::Queue),
        mesh: &TriangleMesh,
        skin_albedo: [f32; 3],
        hair: HairAlbedo,
    ) -> bool {
        let same = mesh.positions.len() == self.vertex_count
            && mesh.indices.len() == self.index_count as usize
            && self.albedos == (skin_albedo, hair)
            && (mesh.tangents.is_none() || self.has_tangents);
        let Some(bounds) = Bounds::of(&mesh.positions).filter(|_| same) else { return false };
        let stride = std::mem::size_of::<MovingVertex>();
        let Some(size) = wgpu::BufferSize::new((self.vertex_count * stride) as u64) else { return false };
        let mut encoder =
            device.create_command_encoder(&wgpu::CommandEncoderDescriptor { label: Some("GpuMesh::move_to") });
        {
            let mut view = self.belt.write_buffer(&mut encoder, &self.moving, 0, size);
            // In batches: the mapping is write-only (and write-combined on a discrete GPU).
            const BATCH: usize = 4096;
            let mut batch = Vec::with_capacity(BATCH.min(self.vertex_count));
            for first in (0..self.vertex_count).step_by(BATCH) {
                let end = (first + BATCH).min(self.vertex_count);
                batch.clear();
                batch.extend((first..end).map(|i| moving_vertex(mesh, i)));
                view.slice(first * stride..end * stride).copy_from_slice(bytemuck::cast_slice(&batch));
            }
        }
        self.belt.finish();
        queue.submit([encoder.finish()]);
        self.belt.recall();
        self.bounds = bounds;
        true
    }

    /// Binds the buffers and draws every triangle.
    pub fn draw(&self, pass: &mut wgpu::RenderPass<'_>) {
        self.draw_instance(pass, 0);
    }

    /// Draws every triangle but the hairs' that the hair pass draws as fibres (all of them for a
    /// mesh without strands).
    pub fn draw_without_hair(&self, pass: &mut wgpu::RenderPass<'_>) {
        let (indices, count) = self.triangles(true);
        pass.set_vertex_buffer(0, self.moving.slice(..));
        pass.set_vertex_buffer(1, self.fixed.slice(..));
        pass.set_index_buffer(indices.slice(..), wgpu::IndexFormat::Uint32);
        pass.draw_indexed(0..count, 0, 0..1);
    }

    /// Binds the moving stream alone (a pipeline of [`position_layout`]) and draws every
    /// triangle.
    pub fn draw_positions(&self, pass: &mut wgpu::RenderPass<'_>) {
        self.draw_positions_of(pass, false);
    }

    /// [`GpuMesh::draw_positions`], leaving out the hairs the hair pass draws as fibres where
    /// `without_hair` (as the G-buffer does).
    pub fn draw_positions_of(&self, pass: &mut wgpu::RenderPass<'_>, without_hair: bool) {
        let (indices, count) = self.triangles(without_hair);
        pass.set_vertex_buffer(0, self.moving.slice(..));
        pass.set_index_buffer(indices.slice(..), wgpu::IndexFormat::Uint32);
        pass.draw_indexed(0..count, 0, 0..1);
    }

    /// The index buffer and count of every triangle, or of every one but the fibre-drawn hairs'.
    fn triangles(&self, without_hair: bool) -> (&wgpu::Buffer, u32) {
        match &self.without_hair {
            Some((indices, count)) if without_hair => (indices, *count),
            _ => (&self.indices, self.index_count),
        }
    }

    /// Draws every triangle as instance `instance` (a shader's `instance_index` then selects a
    /// view, as the dipole passes' directions and lights do).
    pub fn draw_instance(&self, pass: &mut wgpu::RenderPass<'_>, instance: u32) {
        pass.set_vertex_buffer(0, self.moving.slice(..));
        pass.set_vertex_buffer(1, self.fixed.slice(..));
        pass.set_index_buffer(self.indices.slice(..), wgpu::IndexFormat::Uint32);
        pass.draw_indexed(0..self.index_count, 0, instance..instance + 1);
    }
}

/// The indices of `mesh`'s triangles that are not hair, when it has strands (whose hairs the
/// hair pass draws as fibres).
fn without_hair(mesh: &TriangleMesh) -> Option<Vec<u32>> {
    mesh.strands.as_ref()?;
    let kept = mesh.only(|g| !g.part().is_hair()).indices;
    (!kept.is_empty()).then_some(kept)
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
/// Eumelanin concentration of the natural lashes: black hair (PBRT-v4's scale, \[dEon2011\]'s
/// spectra; [`crate::fibre::sigma_a_from_melanin`]). Lash hair is among the most pigmented.
pub const LASH_EUMELANIN: f32 = 8.0;
/// Eumelanin concentration of the natural brows: dark brown (between PBRT-v4's brown, 1.3, and
/// black, 8; brow hair carries less eumelanin than lash hair in most people).
pub const BROW_EUMELANIN: f32 = 2.5;
/// The hairs' colours, the lashes' (a mascara's colour, or the natural lash's) and the brows'
/// (the natural brows' tinted by a brow gel), and a fibre gel's fill of the brows. Each is a fibre's colour in the sense of
/// [`crate::fibre::sigma_a_from_color`] (what it passes across its diameter), which the hair pass
/// makes absorption; a mesh without strands draws the hairs in the G-buffer with it as albedo.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct HairAlbedo {
    /// The lashes'.
    pub lash: [f32; 3],
    /// The brows'.
    pub brow: [f32; 3],
    /// A fibre brow gel's extra hairs, a fraction of the brow's own (0..=1; the hair pass draws
    /// them, [`rouge_model::mesh::brow_gel::BrowGel::fill`]).
    pub brow_fill: f32,
}

impl Default for HairAlbedo {
    fn default() -> HairAlbedo {
        HairAlbedo {
            lash: crate::fibre::color_from_melanin(LASH_EUMELANIN, 0.0),
            brow: crate::fibre::color_from_melanin(BROW_EUMELANIN, 0.0),
            brow_fill: 0.0,
        }
    }
}

impl HairAlbedo {
    /// The natural hairs with `mascara`'s colour on the lashes, if it has one, and `brow_gel`'s
    /// tint on the brows ([`rouge_model::mesh::brow_gel::BrowGel::tint`]).
    pub fn with_products(
        mascara: Option<&rouge_model::mesh::lashes::Mascara>,
        brow_gel: Option<&rouge_model::mesh::brow_gel::BrowGel>,
    ) -> HairAlbedo {
        let natural = HairAlbedo::default();
        HairAlbedo {
            lash: mascara.and_then(|m| m.color).unwrap_or(natural.lash),
            brow: brow_gel.map_or(natural.brow, |g| g.tint(natural.brow)),
            brow_fill: brow_gel.map_or(0.0, |g| g.fill.clamp(0.0, 1.0)),
        }
    }
}

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
