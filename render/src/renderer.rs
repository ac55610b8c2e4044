//! The renderer: what is uploaded (mesh, look, skin maps), the passes, the frame's targets, and
//! the frame itself, which plans ([`FramePlan`]) and then records the planned passes in order.
//! The frame of \[Huang2013\] figure 1 on wgpu: shadow maps → G-buffer → lighting (cosmetic stack,
//! irradiance through it, specular lobes) → the skin's subsurface model → composition.

use crate::error::{RenderError, Result};
use crate::frame::{FramePlan, FrameSettings, Uploaded};
use crate::gpu_look::{GpuLook, SkinTextures};
use crate::gpu_mesh::GpuMesh;
use crate::passes::cube_atlas::AtlasResources;
use crate::passes::depth_copy::DepthCopyPass;
use crate::passes::dipole::DipoleResources;
use crate::passes::edge_overdraw::GpuEdges;
use crate::passes::shadow::{ShadowKey, shadow_keys};
use crate::passes::{FrameEncoder, Passes, Recording, Shared};
use crate::profiler::{PassTiming, Profiler};
use crate::scene::{Camera, Scene};
use crate::shader::Variant;
use crate::targets::{Formats, Target, TargetPool};
use crate::uniforms::{FrameUniform, FrameView};
use crate::wgpu_util::validated;
use rouge_model::TexelRect;
use rouge_model::look::{Look, ThicknessMap};
use rouge_model::mesh::{Bounds, TriangleMesh};

mod antialiasing;
mod readback;

pub use crate::gpu_look::LayerInput;
pub use crate::targets::egui_view;
pub use readback::{FrameCapture, FrameDepth, ThicknessImage};

/// What the last frame was, for readback and picking.
#[derive(Debug)]
struct LastFrame {
    variant: Variant,
    sss_ran: bool,
    /// The bounce pass ran ([`crate::Target::Bounced`] holds the skin radiance composed).
    bounce_ran: bool,
    view: FrameView,
    /// The depth buffer, read once per frame on the first pick.
    depth: std::sync::Mutex<Option<std::sync::Arc<Vec<f32>>>>,
}

/// The renderer: owns the passes, the uploaded mesh and look, and the frame's targets.
#[derive(Debug)]
pub struct Renderer {
    shared: Shared,
    passes: Passes,
    targets: TargetPool,
    mesh: Option<GpuMesh>,
    textures: SkinTextures,
    look: GpuLook,
    /// Depth readback where depth cannot be copied (GL); locked by the `&self` readers.
    depth_copy: std::sync::Mutex<DepthCopyPass>,
    profiler: Option<Profiler>,
    profiling: bool,
    timings: Vec<PassTiming>,
    last: Option<LastFrame>,
    /// The mesh's discontinuity edges ([`crate::edges`]), and the edge antialiasing of frames.
    edges: Option<GpuEdges>,
    edge_aa: crate::aa::EdgeAa,
    edge_stats: crate::silhouettes::FrameEdgeStats,
    edge_gpu_classify: bool,
    /// The dipole models' maps and their accumulation.
    dipole: DipoleResources,
    /// The cube atlas (redrawn every frame that uses it).
    atlas: AtlasResources,
    /// Counts mesh uploads (the dipole maps depend on the mesh).
    mesh_generation: u64,
    /// How deep the wrinkle families are ([`Renderer::set_wrinkle_weights`]).
    wrinkle_weights: rouge_model::skin::WrinkleWeights,
    /// The hairs' albedo of the next mesh upload ([`Renderer::set_hair_albedo`]).
    hair_albedo: crate::HairAlbedo,
    /// Keep current shadow maps between frames ([`Renderer::set_keep_shadow_maps`]).
    keep_shadow_maps: bool,
    /// The mesh's hair strands at its current pose (the hair pass), empty without hair.
    hair: crate::passes::hair::HairStrands,
    /// The hairs drawn with their box-filter coverage ([`Renderer::set_hair_aa`]).
    hair_aa: bool,
}

impl Renderer {
    /// A renderer on `device` (the app's, or [`crate::gpu::Gpu::headless`]'s). Formats follow
    /// the device's backend ([`Formats::for_device`]).
    pub fn new(device: &wgpu::Device, queue: &wgpu::Queue) -> Renderer {
        let formats = Formats::for_device(device);
        let shared = Shared::new(device, queue, formats);
        let passes = Passes::new(&shared);
        Renderer {
            passes,
            targets: TargetPool::new(formats),
            mesh: None,
            textures: SkinTextures::default(),
            look: GpuLook::empty(device, formats.min_array_layers),
            depth_copy: std::sync::Mutex::new(DepthCopyPass::new(&shared)),
            profiler: Profiler::new(device, queue),
            profiling: false,
            timings: Vec::new(),
            last: None,
            edges: None,
            edge_aa: crate::aa::EdgeAa::Off,
            edge_stats: Default::default(),
            edge_gpu_classify: false,
            dipole: DipoleResources::new(device, formats.min_array_layers),
            atlas: AtlasResources::new(device, formats.min_array_layers),
            mesh_generation: 0,
            wrinkle_weights: Default::default(),
            hair_albedo: Default::default(),
            keep_shadow_maps: true,
            hair: Default::default(),
            hair_aa: false,
            shared,
        }
    }

    /// The formats chosen for this device.
    pub fn formats(&self) -> Formats {
        self.shared.formats
    }

    /// The lashes' and brows' albedo the uploaded mesh was given ([`Renderer::set_hair_albedo`]).
    pub fn hair_albedo(&self) -> crate::HairAlbedo {
        self.hair_albedo
    }

    /// The lashes' and brows' albedo of the meshes uploaded from now on ([`Renderer::set_mesh`]):
    /// a mascara's colour on the lashes, a brow gel's on the brows ([`crate::HairAlbedo::with_products`]).
    pub fn set_hair_albedo(&mut self, hair: crate::HairAlbedo) {
        self.hair_albedo = hair;
    }

    /// Uploads a triangle mesh (mm) with the skin albedo per vertex (and the hairs' of
    /// [`Renderer::set_hair_albedo`]).
    ///
    /// # Errors
    /// [`RenderError::Invalid`] for an empty mesh.
    pub fn set_mesh(&mut self, mesh: &TriangleMesh, skin_albedo: [f32; 3]) -> Result<()> {
        let device = &self.shared.device;
        let hair = self.hair_albedo;
        self.mesh = Some(validated(device, "mesh upload", || GpuMesh::upload(device, mesh, skin_albedo, hair))?);
        self.mesh_changed(mesh);
        Ok(())
    }

    /// What follows a new or moved mesh: the dipole maps' key, and the edges (a posed copy of
    /// the mesh moves the edges found on it; another mesh drops them, and they are found again
    /// when edge antialiasing is on).
    fn mesh_changed(&mut self, mesh: &TriangleMesh) {
        self.mesh_generation += 1;
        self.hair = crate::passes::hair::HairStrands::of(mesh, self.hair_albedo.brow_fill);
        if !self.edges.as_mut().is_some_and(|e| e.reposition(mesh)) {
            self.edges = None;
            if self.edge_aa != crate::aa::EdgeAa::Off {
                self.prepare_edges(mesh);
            }
        }
    }

    /// Poses the uploaded mesh: `mesh` is it with new positions and normals (the app's
    /// expressions, `rouge bench deform`: a [`rouge_model::mesh::deform::SubdivisionPlan`]
    /// keeps the vertices, triangles and UVs), written into the existing vertex buffer
    /// (`GpuMesh::move_to`: 24 of the 64 bytes a vertex through kept staging memory, no
    /// allocation, no index upload).
    /// Any other mesh, or other albedos, is uploaded afresh as [`Renderer::set_mesh`] does.
    ///
    /// # Errors
    /// As [`Renderer::set_mesh`].
    pub fn move_mesh(&mut self, mesh: &TriangleMesh, skin_albedo: [f32; 3]) -> Result<()> {
        let hair = self.hair_albedo;
        let gpu = (&self.shared.device, &self.shared.queue);
        let moved = self.mesh.as_mut().is_some_and(|m| m.move_to(gpu, mesh, skin_albedo, hair));
        if !moved {
            return self.set_mesh(mesh, skin_albedo);
        }
        self.mesh_changed(mesh);
        Ok(())
    }

    /// Preprocesses the discontinuity edges of `mesh` ([`crate::edges::EdgeSet::new`]) and
    /// uploads them; [`Renderer::set_mesh`] does it when edge antialiasing is on, and
    /// [`Renderer::set_edge_aa`] needs it done before a frame with edges.
    pub fn prepare_edges(&mut self, mesh: &TriangleMesh) {
        let set = crate::edges::EdgeSet::new(mesh, crate::edges::EdgeOptions::default());
        let frames = crate::silhouettes::EdgeFrames::new(set);
        self.edges = Some(GpuEdges::new(frames));
    }

    /// Sets the edge antialiasing of the following frames, and the hairs' coverage with it (on
    /// with any edge overdraw; [`Renderer::set_hair_aa`] afterwards sets it apart). A frame with
    /// edges needs the mesh's edges ([`Renderer::prepare_edges`], done by
    /// [`Renderer::set_mesh`] once this is on).
    pub fn set_edge_aa(&mut self, aa: crate::aa::EdgeAa) {
        self.edge_aa = aa;
        self.hair_aa = aa != crate::aa::EdgeAa::Off;
    }

    /// Whether the hairs' fibres are drawn with their box-filter coverage (the antialiased hair
    /// pass) or as opaque pixel centres; [`Renderer::set_aa_mode`] turns it on for every mode
    /// but `none`.
    pub fn set_hair_aa(&mut self, on: bool) {
        self.hair_aa = on;
    }

    /// Whether unsorted edge overdraw feeds every edge to the GPU, whose vertex stage classifies
    /// each (brute force, no CPU work per frame), instead of the CPU's list (the default).
    pub fn set_edge_gpu_classify(&mut self, on: bool) {
        self.edge_gpu_classify = on;
    }

    /// The edge antialiasing of the following frames.
    pub fn edge_aa(&self) -> crate::aa::EdgeAa {
        self.edge_aa
    }

    /// The preprocessed edges of the mesh, when prepared.
    pub fn edges(&self) -> Option<&crate::silhouettes::EdgeFrames> {
        self.edges.as_ref().map(|e| &e.frames)
    }

    /// Edge counts of the last frame drawn with sorted edges (zero otherwise).
    pub fn edge_stats(&self) -> crate::silhouettes::FrameEdgeStats {
        self.edge_stats
    }

    /// Sets or clears the skin albedo texture (sRGB-encoded RGBA8, in the mesh's UV space, row 0
    /// at v = 1) and the tangent-space normal map (RGBA8, +Y up, OpenGL convention). A normal map
    /// needs a mesh uploaded with tangents ([`TriangleMesh::generate_tangents`]).
    ///
    /// # Errors
    /// [`RenderError::Invalid`] for a normal map on a mesh without tangents, or an empty image.
    pub fn set_textures(&mut self, albedo: Option<&image::RgbaImage>, normal: Option<&image::RgbaImage>) -> Result<()> {
        if normal.is_some() && !self.mesh.as_ref().is_some_and(|m| m.has_tangents) {
            return Err(RenderError::Invalid("a normal map needs a mesh with tangents (generate them first)".into()));
        }
        let (device, queue) = (&self.shared.device, &self.shared.queue);
        let local_thickness = self.textures.local_thickness.take();
        let detail = self.textures.detail.take();
        let wrinkles = self.textures.wrinkles.take();
        let uploaded = validated(device, "texture upload", || SkinTextures::upload(device, queue, albedo, normal));
        self.textures = SkinTextures { local_thickness, detail, wrinkles, ..uploaded? };
        Ok(())
    }

    /// Sets or clears the skin's microgeometry ([`rouge_model::skin::detail`]): the relief tile,
    /// the region map in the mesh's UVs, and the tiles per UV unit
    /// ([`rouge_model::skin::detail::tiles_per_uv`] of the mesh).
    ///
    /// # Errors
    /// [`RenderError::Invalid`] for a malformed tile or scale.
    pub fn set_skin_detail(
        &mut self,
        detail: Option<(&rouge_model::skin::DetailTile, &rouge_model::skin::RegionDetail, f32)>,
    ) -> Result<()> {
        let (device, queue) = (&self.shared.device, &self.shared.queue);
        self.textures.detail = detail
            .map(|(tile, regions, scale)| {
                validated(device, "skin detail upload", || {
                    crate::gpu_look::SkinDetailTextures::upload(device, queue, tile, regions, scale)
                })
            })
            .transpose()?;
        Ok(())
    }

    /// Sets or clears the default head's expression wrinkles and lip furrows
    /// ([`rouge_model::skin::wrinkles`]): drawn by the G-buffer pass with the skin detail
    /// ([`Renderer::set_skin_detail`]; without it the map costs nothing), each family as deep
    /// as [`Renderer::set_wrinkle_weights`] says.
    ///
    /// # Errors
    /// [`RenderError::Invalid`] for an empty or non-square map.
    pub fn set_wrinkle_map(&mut self, map: Option<&rouge_model::skin::WrinkleMap>) -> Result<()> {
        let (device, queue) = (&self.shared.device, &self.shared.queue);
        self.textures.wrinkles = map
            .map(|m| {
                validated(device, "wrinkle map upload", || crate::gpu_look::WrinkleTexture::upload(device, queue, m))
            })
            .transpose()?;
        Ok(())
    }

    /// How deep each wrinkle family is on each side (a pose's
    /// [`rouge_model::skin::WrinkleWeights`]; a neutral face's until set).
    pub fn set_wrinkle_weights(&mut self, weights: rouge_model::skin::WrinkleWeights) {
        self.wrinkle_weights = weights;
    }

    /// Sets or clears the baked local thickness of the thickness translucency
    /// ([`crate::local_thickness`]): RGBA texels in the mesh's UV space, row 0 at v = 1, rgb in
    /// [0, 1] with white = thin (what [`rouge_model::thickness::thickness_uv_map`] makes).
    ///
    /// # Errors
    /// [`RenderError::Invalid`] for an empty map or one whose texel count is not width × height.
    pub fn set_local_thickness(&mut self, map: Option<(u32, u32, &[[f32; 4]])>) -> Result<()> {
        let (device, queue) = (&self.shared.device, &self.shared.queue);
        self.textures.local_thickness = map
            .map(|(w, h, texels)| {
                validated(device, "local thickness upload", || {
                    crate::gpu_look::upload_local_thickness(device, queue, w, h, texels)
                })
            })
            .transpose()?;
        Ok(())
    }

    /// Bounds of the uploaded mesh.
    pub fn mesh_bounds(&self) -> Option<Bounds> {
        self.mesh.as_ref().map(|m| m.bounds)
    }

    /// Uploads a look: its visible layers' tables and thickness maps.
    ///
    /// # Errors
    /// [`RenderError::Invalid`] for more than [`crate::shader::MAX_LAYERS`] visible layers.
    pub fn set_look(&mut self, look: &Look) -> Result<()> {
        let layers: Vec<_> =
            look.visible_layers().map(|l| LayerInput { preset: &l.preset, map: &l.map, multiplier: 1.0 }).collect();
        self.set_layers(&layers)
    }

    /// Uploads cosmetic layers bottom to top (the painting app's path: its maps carry a
    /// multiplier).
    ///
    /// # Errors
    /// [`RenderError::Invalid`] for more than [`crate::shader::MAX_LAYERS`] layers.
    pub fn set_layers(&mut self, layers: &[LayerInput<'_>]) -> Result<()> {
        let (device, queue) = (&self.shared.device, &self.shared.queue);
        let min_layers = self.shared.formats.min_array_layers;
        self.look = validated(device, "look upload", || GpuLook::upload(device, queue, layers, min_layers))?;
        Ok(())
    }

    /// Re-uploads the texels `rect` of layer `layer`'s thickness map after painting; `map` must
    /// have the size the layers were uploaded at.
    ///
    /// # Errors
    /// [`RenderError::Invalid`] for a layer or size that does not match the uploaded look.
    pub fn update_thickness(
        &mut self,
        layer: usize,
        map: &ThicknessMap,
        multiplier: f32,
        rect: TexelRect,
    ) -> Result<()> {
        self.look.update(&self.shared.queue, layer, map, multiplier, rect)
    }

    /// Number of layers of the uploaded look.
    pub fn layer_count(&self) -> u32 {
        self.look.layers
    }

    /// Collect per-pass GPU times of the following frames (when the adapter has timestamps).
    pub fn set_profiling(&mut self, on: bool) {
        self.profiling = on && self.profiler.is_some();
    }

    /// Per-pass GPU times of the last frame rendered with profiling on.
    pub fn timings(&self) -> &[PassTiming] {
        &self.timings
    }

    /// The variant of the last frame.
    pub fn last_variant(&self) -> Option<Variant> {
        self.last.as_ref().map(|l| l.variant)
    }

    /// The key of each shadow map a frame of `scene` draws, by layer.
    fn shadow_keys(&self, scene: &Scene) -> [Option<ShadowKey>; crate::uniforms::MAX_LIGHTS] {
        match &self.mesh {
            Some(m) => {
                let lights = crate::uniforms::light_uniforms(&scene.lights, &m.bounds);
                shadow_keys(&lights[..scene.lights.len().min(lights.len())], self.mesh_generation)
            }
            None => [None; crate::uniforms::MAX_LIGHTS],
        }
    }

    /// Whether frames keep a shadow map that is current (the default) or draw every shadow map
    /// every frame (to price the shadow pass of a moving light, `rouge bench render`).
    pub fn set_keep_shadow_maps(&mut self, keep: bool) {
        self.keep_shadow_maps = keep;
    }

    /// The plan of a frame of `scene` at `width` × `height` with what is uploaded now.
    ///
    /// # Errors
    /// As [`FramePlan::new`].
    pub fn plan(&self, scene: &Scene, width: u32, height: u32, display: bool) -> Result<FramePlan> {
        let uploaded = Uploaded {
            layers: self.look.layers,
            albedo_map: self.textures.albedo.is_some(),
            normal_map: self.textures.normal.is_some(),
            local_thickness_map: self.textures.local_thickness.is_some(),
            skin_detail: self.textures.detail.is_some(),
            glitter: self.look.glitter,
            shadow_maps_kept: if self.keep_shadow_maps {
                self.passes.shadow.current_layers(&self.shadow_keys(scene))
            } else {
                0
            },
            hair_strands: if self.mesh.is_some() { self.hair.strand_count() as u32 } else { 0 },
        };
        let max_side = self.shared.device.limits().max_texture_dimension_2d;
        let max_color_bytes = self.shared.device.limits().max_color_attachment_bytes_per_sample;
        FramePlan::new(
            scene,
            uploaded,
            FrameSettings {
                width,
                height,
                display,
                max_side,
                max_color_bytes,
                aa: self.edge_aa,
                hair_aa: self.hair_aa,
            },
        )
    }

    /// Renders one frame of `scene` seen by `camera` at `width` × `height`: the tone-mapped
    /// output when `display`, else linear radiance. Returns the output texture (sRGB-encoded
    /// RGBA8 or Rgba32Float), valid until the next frame at another size.
    ///
    /// # Errors
    /// [`RenderError::Invalid`] without a mesh, and as [`FramePlan::new`]; [`RenderError::Gpu`]
    /// when wgpu refuses the frame (the validation message, never a panic).
    pub fn render(
        &mut self,
        scene: &Scene,
        camera: &Camera,
        width: u32,
        height: u32,
        display: bool,
    ) -> Result<wgpu::Texture> {
        let plan = self.plan(scene, width, height, display)?;
        let device = self.shared.device.clone();
        let frame = validated(&device, "frame", || self.record_and_submit(&plan, camera));
        if frame.is_ok() {
            let keys = self.shadow_keys(scene);
            for planned in &plan.passes {
                if let crate::passes::Step::Shadow(s) = planned.step {
                    self.passes.shadow.set_drawn(s.layer, keys[s.layer as usize]);
                }
            }
        } else {
            self.passes.shadow.forget();
        }
        frame
    }

    /// Records the passes of `plan` in order and submits them: the plan carries what the frame
    /// takes from the scene; the camera places it.
    fn record_and_submit(&mut self, plan: &FramePlan, camera: &Camera) -> Result<wgpu::Texture> {
        let Renderer {
            shared,
            passes,
            targets,
            mesh,
            textures,
            look,
            profiler,
            profiling,
            timings,
            last,
            edges,
            edge_gpu_classify,
            edge_stats,
            dipole,
            atlas,
            mesh_generation,
            wrinkle_weights,
            hair,
            hair_albedo,
            ..
        } = self;
        let mesh =
            mesh.as_ref().ok_or_else(|| RenderError::Invalid("no mesh to render: call set_mesh first".into()))?;
        let device = &shared.device;
        targets.resize(plan.size);
        targets.ensure(device, plan.targets.iter().copied());
        passes.shadow.ensure_maps(shared, plan.shadow_maps);
        let view = FrameView::new(camera, &mesh.bounds, plan.size);
        let mut frame =
            FrameUniform::new(&plan.constants, camera, &view, &mesh.bounds, plan.size, (look.layers, look.params));
        frame.skin[3] = textures.detail.as_ref().map_or(0.0, |d| d.tiles_per_uv);
        if let (Some(_), Some(w)) = (&textures.detail, &textures.wrinkles) {
            let [left, right] = wrinkle_weights.depths_mm();
            let r = w.uv_rect;
            frame.wrinkles = [[r.u0, r.v0, r.side, 1.0 / w.side_px as f32], left, right];
        }
        frame.surface[0] = if plan.variant.glitter { mesh.mm_per_uv } else { 0.0 };
        shared.write_frame(&frame);

        let profiler = if *profiling { profiler.as_mut() } else { None };
        let encoder = device.create_command_encoder(&wgpu::CommandEncoderDescriptor { label: Some("Renderer::frame") });
        let mut rec = Recording {
            shared,
            targets,
            variant: plan.variant,
            enc: FrameEncoder { encoder, profiler },
            mesh,
            mesh_generation: *mesh_generation,
            look,
            textures,
            shadow_maps: passes.shadow.maps_view(),
            dipole,
            atlas,
            edges: edges.as_mut(),
            edge_gpu_classify: *edge_gpu_classify,
            eye: camera.position(),
            edge_stats: None,
            hair: plan.variant.hair.then_some(hair),
            hair_albedo: *hair_albedo,
        };
        if let Some(p) = rec.enc.profiler.as_mut() {
            p.begin_frame();
        }
        for planned in &plan.passes {
            passes.record(&mut rec, &planned.step)?;
        }
        let FrameEncoder { mut encoder, profiler } = rec.enc;
        if let Some(stats) = rec.edge_stats {
            *edge_stats = stats;
        }
        if let Some(p) = &profiler {
            p.resolve(&mut encoder);
        }
        shared.queue.submit([encoder.finish()]);
        *timings = match profiler {
            Some(p) => p.read(device)?,
            None => Vec::new(),
        };
        let variant = plan.variant;
        let bounce_ran = plan.targets.contains(&crate::targets::Target::Bounced);
        *last = Some(LastFrame {
            variant,
            sss_ran: plan.kernel.is_some(),
            bounce_ran,
            view,
            depth: std::sync::Mutex::new(None),
        });
        let out = if variant.display { Target::Display } else { Target::Linear };
        targets.get(out).cloned().ok_or_else(|| RenderError::Gpu("the output target was not created".into()))
    }

    /// Frames of samples the dipole models' radiance maps hold (progressive accumulation).
    pub fn dipole_frames(&self) -> u32 {
        self.dipole.frames_accumulated()
    }

    /// Waits for the GPU to finish the submitted work.
    ///
    /// # Errors
    /// [`RenderError::Gpu`] if the device is lost.
    pub fn wait(&self) -> Result<()> {
        self.shared
            .device
            .poll(wgpu::PollType::wait_indefinitely())
            .map(|_| ())
            .map_err(|e| RenderError::Gpu(e.to_string()))
    }
}
