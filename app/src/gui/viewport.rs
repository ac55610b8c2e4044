//! The viewport: orbit camera, lights, picking on the GPU depth buffer, frames into egui
//! native textures (with the bare-skin half of the before/after split), input and overlays.

use super::translucency::LocalThicknessState;
use super::*;
use rouge_model::paint::PaintView;

/// Orbit camera state (the renderer's `Camera` is derived from it and the mesh bounds).
#[derive(Clone, Copy, Debug, PartialEq)]
pub(super) struct Orbit {
    yaw_deg: f32,
    pitch_deg: f32,
    zoom: f32,
    pan_mm: Vec3,
}

impl Default for Orbit {
    fn default() -> Self {
        Orbit { yaw_deg: 0.0, pitch_deg: 0.0, zoom: 1.0, pan_mm: Vec3::ZERO }
    }
}

/// How the document is looked at: camera, key light, environment, the before/after split, and
/// where on screen the frame is shown. None of it is saved with the document.
#[derive(Debug)]
pub(super) struct ViewState {
    pub(super) orbit: Orbit,
    /// The studio scene with the key light below applied ([`ViewState::update_lights`]) and
    /// the subsurface model ([`RougeApp::apply_subsurface`]).
    pub(super) scene: Scene,
    /// The cube atlas's deformation test (the mesh morphed toward its bounding sphere).
    pub(super) morph: super::translucency::MorphPreview,
    pub(super) light_yaw_deg: f32,
    pub(super) light_pitch_deg: f32,
    pub(super) light_intensity: f32,
    pub(super) environment: bool,
    pub(super) split: bool,
    /// Where the split line is, 0-1 across the viewport.
    pub(super) split_at: f32,
    /// The viewport on screen (egui points).
    pub(super) rect: Rect,
    /// Something shown changed since the last frame: draw a new one.
    pub(super) needs_render: bool,
    /// Bounds the camera frames instead of the drawn mesh's (the posed head frames its rest
    /// pose, so the view holds still while the face moves).
    pub(super) framing: Option<rouge_model::mesh::Bounds>,
    /// Draw the brush's symmetry plane on the skin.
    pub(super) show_plane: bool,
    /// Where the plane cuts the surface, for that plane (cached).
    pub(super) plane_trace: Option<(rouge_model::paint::MirrorPlane, Vec<(Vec3, Vec3)>)>,
    /// The surface point under the cursor, and the active layer's thickness there (mm).
    pub(super) hover_world: Option<Vec3>,
    pub(super) hover_mm: Option<f32>,
}

impl Default for ViewState {
    fn default() -> Self {
        ViewState {
            orbit: Orbit::default(),
            scene: Scene::studio(),
            morph: Default::default(),
            light_yaw_deg: -34.0,
            light_pitch_deg: 27.0,
            light_intensity: 1.0,
            environment: true,
            split: false,
            split_at: 0.5,
            rect: Rect::NOTHING,
            needs_render: true,
            framing: None,
            // Drawn on request only: on by default it was a thick cyan line down the face.
            show_plane: false,
            plane_trace: None,
            hover_world: None,
            hover_mm: None,
        }
    }
}

impl ViewState {
    /// The camera framing `renderer`'s mesh from the orbit; `None` before a mesh is set.
    fn camera(&self, renderer: &Renderer) -> Option<Camera> {
        let bounds = self.framing.or_else(|| renderer.mesh_bounds())?;
        let mut c = Camera::framing(&bounds, self.orbit.yaw_deg, self.orbit.pitch_deg);
        c.distance /= self.orbit.zoom;
        c.target += self.orbit.pan_mm;
        Some(c)
    }

    /// Puts the key light and the environment switch into the scene.
    fn update_lights(&mut self) {
        let (yaw, pitch) = (self.light_yaw_deg.to_radians(), self.light_pitch_deg.to_radians());
        let toward = Vec3::new(yaw.sin() * pitch.cos(), pitch.sin(), yaw.cos() * pitch.cos());
        let studio = Scene::studio();
        self.scene.lights = studio.lights.clone();
        if let Some(key) = self.scene.lights.first_mut() {
            key.kind = LightKind::Directional { toward };
            key.irradiance = studio.lights[0].irradiance.map(|v| v * self.light_intensity);
        }
        self.scene.environment = if self.environment { studio.environment } else { None };
    }

    /// Aims the orbit at a close-up of `region` ([`Camera::close_up`]: about 60 mm of face
    /// across the viewport's height) from the current direction, on `mesh` (the drawn one).
    ///
    /// # Errors
    /// No mesh yet, or the mesh has no skin in the region (UVs other than the default head's).
    fn close_up(
        &mut self,
        renderer: &Renderer,
        mesh: Option<&TriangleMesh>,
        region: AnatomyRegion,
    ) -> std::result::Result<(), String> {
        let (Some(mesh), Some(bounds)) = (mesh, self.framing.or_else(|| renderer.mesh_bounds())) else {
            return Err("no mesh to look at yet".into());
        };
        let (yaw, pitch) = (self.orbit.yaw_deg, self.orbit.pitch_deg);
        let close = Camera::close_up(mesh, region, yaw, pitch).ok_or_else(|| {
            format!("this mesh has no skin in the {} region (its UVs are not the default head's)", region.name())
        })?;
        let whole = Camera::framing(&bounds, yaw, pitch);
        self.orbit.zoom = whole.distance / close.distance;
        self.orbit.pan_mm = close.target - whole.target;
        self.needs_render = true;
        Ok(())
    }

    /// Back to the default orbit (F, View → Reset view, a new mesh).
    pub(super) fn reset_orbit(&mut self) {
        self.orbit = Orbit::default();
        self.needs_render = true;
    }

    /// The skin albedo meshes are uploaded with.
    pub(super) fn skin_albedo(&self) -> [f32; 3] {
        self.scene.skin.albedo
    }
}

/// The app's edge antialiasing until the View menu changes it: sorted two-sided edges, which
/// the measurements support (on the turning head a third less error and crawl near
/// discontinuities for under 1 ms of a 35 ms lavapipe frame; docs/BENCHMARKS.md).
pub(super) const DEFAULT_EDGE_AA: rouge_render::aa::EdgeAa =
    rouge_render::aa::EdgeAa::Sorted(rouge_render::aa::EdgeCoverage::TwoSided);

/// The GPU side of the app: eframe's device, the renderer painting the document, the one
/// showing bare skin for the split, and the egui textures their frames are shown through.
pub(super) struct GpuState {
    pub(super) device: wgpu::Device,
    queue: wgpu::Queue,
    egui_renderer: Arc<egui::mutex::RwLock<egui_wgpu::Renderer>>,
    pub(super) renderer: Renderer,
    /// Renders the bare-skin half of the split; made on first use, dropped with a new mesh.
    bare: Option<Renderer>,
    /// The mesh being painted (kept for the bare renderer).
    mesh: Option<TriangleMesh>,
    texture: Option<egui::TextureId>,
    bare_texture: Option<egui::TextureId>,
    /// The size of the last frame, in pixels.
    pub(super) frame_size: (u32, u32),
    last_frame_ms: f64,
    /// The baked local thickness of the mesh, for the translucency.
    pub(super) local_thickness: LocalThicknessState,
    /// The skin's albedo texture baked from the document's skin maps (`None`: the flat skin),
    /// uploaded to both renderers ([`GpuState::set_skin_albedo`]).
    skin_albedo: Option<Arc<image::RgbaImage>>,
}

impl std::fmt::Debug for GpuState {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("GpuState")
            .field("has_mesh", &self.mesh.is_some())
            .field("frame_size", &self.frame_size)
            .finish_non_exhaustive()
    }
}

impl GpuState {
    pub(super) fn new(rs: &egui_wgpu::RenderState) -> GpuState {
        let mut renderer = Renderer::new(&rs.device, &rs.queue);
        renderer.set_edge_aa(DEFAULT_EDGE_AA);
        GpuState {
            renderer,
            device: rs.device.clone(),
            queue: rs.queue.clone(),
            egui_renderer: rs.renderer.clone(),
            bare: None,
            mesh: None,
            texture: None,
            bare_texture: None,
            frame_size: (0, 0),
            last_frame_ms: 0.0,
            local_thickness: LocalThicknessState::Missing,
            skin_albedo: None,
        }
    }

    /// Uploads a newly prepared mesh; the bare renderer is made again on its next use.
    ///
    /// # Errors
    /// As [`Renderer::set_mesh`]; the previous mesh stays.
    pub(super) fn set_mesh(&mut self, mesh: TriangleMesh, skin_albedo: [f32; 3]) -> rouge_render::Result<()> {
        self.renderer.set_mesh(&mesh, skin_albedo)?;
        self.renderer.set_local_thickness(None)?;
        self.local_thickness = LocalThicknessState::Missing;
        self.bare = None;
        self.mesh = Some(mesh);
        Ok(())
    }

    /// Poses the uploaded head in place: `pose` writes new positions and normals into the
    /// viewport's mesh, first made again from `rest` when given (the first pose after a load:
    /// the same vertices, triangles and UVs), and they go into the existing vertex buffers
    /// ([`Renderer::move_mesh`]); no copy of the mesh per pose. The local thickness, which lies
    /// in UV space and so follows the skin, stays; the split's bare renderer moves with it.
    ///
    /// # Errors
    /// No mesh to pose; as [`Renderer::set_mesh`], when the GPU keeps the previous positions
    /// (the next pose writes them again).
    pub(super) fn pose_mesh(
        &mut self,
        rest: Option<&TriangleMesh>,
        skin_albedo: [f32; 3],
        pose: impl FnOnce(&mut TriangleMesh),
    ) -> rouge_render::Result<()> {
        if let Some(rest) = rest {
            self.mesh = Some(rest.clone());
        }
        let Some(mesh) = self.mesh.as_mut() else {
            return Err(rouge_render::RenderError::Invalid("no mesh is loaded to pose".into()));
        };
        pose(mesh);
        self.upload_moved(skin_albedo)
    }

    /// Shows `mesh`, the viewport's mesh moved (the morph preview: the same vertices, triangles
    /// and UVs), written into the existing vertex buffers as [`GpuState::pose_mesh`] does.
    ///
    /// # Errors
    /// As [`GpuState::pose_mesh`].
    pub(super) fn set_moved_mesh(&mut self, mesh: TriangleMesh, skin_albedo: [f32; 3]) -> rouge_render::Result<()> {
        self.mesh = Some(mesh);
        self.upload_moved(skin_albedo)
    }

    /// Writes the moved mesh's positions and normals to the GPU, the split's bare renderer's too.
    fn upload_moved(&mut self, skin_albedo: [f32; 3]) -> rouge_render::Result<()> {
        let Some(mesh) = self.mesh.as_ref() else { return Ok(()) };
        self.renderer.move_mesh(mesh, skin_albedo)?;
        if self.bare.as_mut().is_some_and(|bare| bare.move_mesh(mesh, skin_albedo).is_err()) {
            self.bare = None;
        }
        Ok(())
    }

    /// The mesh the viewport shows (posed in place by [`GpuState::pose_mesh`]).
    pub(super) fn mesh(&self) -> Option<&TriangleMesh> {
        self.mesh.as_ref()
    }

    /// Uploads the skin's albedo texture (the skin maps' colour) to the document's renderer and
    /// the split's bare one, or with `None` goes back to the flat skin colour.
    ///
    /// # Errors
    /// As [`Renderer::set_textures`].
    pub(super) fn set_skin_albedo(&mut self, albedo: Option<Arc<image::RgbaImage>>) -> rouge_render::Result<()> {
        self.renderer.set_textures(albedo.as_deref(), None)?;
        if let Some(bare) = self.bare.as_mut() {
            bare.set_textures(albedo.as_deref(), None)?;
        }
        self.skin_albedo = albedo;
        Ok(())
    }

    /// Sets the edge antialiasing of the painted frames ([`rouge_render::aa`]), preparing the
    /// mesh's discontinuity edges when it is turned on.
    pub(super) fn set_edge_aa(&mut self, aa: rouge_render::aa::EdgeAa) {
        self.renderer.set_edge_aa(aa);
        self.bare = None;
        if aa != rouge_render::aa::EdgeAa::Off
            && self.renderer.edges().is_none()
            && let Some(mesh) = &self.mesh
        {
            self.renderer.prepare_edges(mesh);
        }
    }

    /// A copy of the mesh for a bake on another thread.
    pub(super) fn mesh_for_bake(&self) -> Option<TriangleMesh> {
        self.mesh.clone()
    }

    pub(super) fn has_mesh(&self) -> bool {
        self.mesh.is_some()
    }

    /// Whether a frame has been shown.
    pub(super) fn has_frame(&self) -> bool {
        self.texture.is_some()
    }

    /// Shows `texture` through the egui texture in `slot`: updated in place while the frame
    /// size stays, registered anew (freeing the old one) when it changes.
    fn show(&self, slot: &mut Option<egui::TextureId>, same_size: bool, texture: &wgpu::Texture) {
        let view = rouge_render::renderer::egui_view(texture);
        let mut r = self.egui_renderer.write();
        match *slot {
            Some(id) if same_size => {
                r.update_egui_texture_from_wgpu_texture(&self.device, &view, wgpu::FilterMode::Linear, id)
            }
            _ => {
                if let Some(id) = slot.take() {
                    r.free_texture(&id);
                }
                *slot = Some(r.register_native_texture(&self.device, &view, wgpu::FilterMode::Linear));
            }
        }
    }

    /// Renders the document's frame at `size` into the shown texture.
    fn render(&mut self, scene: &Scene, camera: &Camera, size: (u32, u32)) -> rouge_render::Result<()> {
        let texture = self.renderer.render(scene, camera, size.0, size.1, true)?;
        let mut slot = self.texture.take();
        self.show(&mut slot, self.frame_size == size, &texture);
        self.texture = slot;
        Ok(())
    }

    /// Renders bare skin (no layers) at `size` into the split's texture.
    fn render_bare(&mut self, scene: &Scene, camera: &Camera, size: (u32, u32)) {
        if self.bare.is_none() {
            let mut bare = Renderer::new(&self.device, &self.queue);
            // The split's two halves antialiased alike.
            bare.set_edge_aa(self.renderer.edge_aa());
            if let Some(mesh) = &self.mesh
                && bare.set_mesh(mesh, scene.skin.albedo).is_err()
            {
                return;
            }
            // The "before" half shows the bare skin with its maps.
            if bare.set_textures(self.skin_albedo.as_deref(), None).is_err() {
                return;
            }
            self.bare = Some(bare);
        }
        let Some(bare) = self.bare.as_mut() else { return };
        if let Ok(texture) = bare.render(scene, camera, size.0, size.1, true) {
            let mut slot = self.bare_texture.take();
            self.show(&mut slot, self.frame_size == size, &texture);
            self.bare_texture = slot;
        }
    }

    /// The frame pixel under the screen point `pos` of the viewport `rect`.
    fn pixel_at(&self, rect: Rect, pos: Pos2) -> Option<(u32, u32)> {
        let (w, h) = self.frame_size;
        if w == 0 || h == 0 || !rect.contains(pos) {
            return None;
        }
        let x = ((pos.x - rect.min.x) / rect.width() * w as f32) as u32;
        let y = ((pos.y - rect.min.y) / rect.height() * h as f32) as u32;
        Some((x, y))
    }

    /// The screen point of the viewport `rect` showing the world point `world`.
    pub(super) fn screen_pos_of(&self, rect: Rect, world: Vec3) -> Option<Pos2> {
        let (px, py) = self.renderer.project(world)?;
        let (w, h) = self.frame_size;
        if w == 0 || h == 0 {
            return None;
        }
        Some(Pos2::new(rect.min.x + px / w as f32 * rect.width(), rect.min.y + py / h as f32 * rect.height()))
    }
}

impl RougeApp {
    pub(super) fn camera(&self) -> Option<Camera> {
        self.view.camera(&self.gpu.renderer)
    }

    /// View ▸ Close-up: the viewport aimed at `region` of the face (from the current direction;
    /// Home goes back to the whole face). A failure is shown in the status line.
    pub fn view_close_up(&mut self, region: AnatomyRegion) {
        if let Err(e) = self.view.close_up(&self.gpu.renderer, self.gpu.mesh.as_ref(), region) {
            self.ui.message = Some((false, e));
        }
    }

    /// The surface point under the screen point `pos`, read from the last frame's depth.
    pub(super) fn pick(&self, pos: Pos2) -> Option<Vec3> {
        let (x, y) = self.gpu.pixel_at(self.view.rect, pos)?;
        match self.gpu.renderer.pick(x, y) {
            Ok(p) => p,
            Err(e) => {
                eprintln!("rouge: pick failed: {e}");
                None
            }
        }
    }

    fn render(&mut self, size: (u32, u32)) {
        let Some(camera) = self.camera() else { return };
        if size.0 == 0 || size.1 == 0 {
            return;
        }
        let start = Instant::now();
        self.view.update_lights();
        self.apply_subsurface();
        // Per-pass GPU times for the frame readout, one frame in frame_stats::PROFILE_EVERY
        // (nothing without timestamp queries).
        let profiled = self.frames.profile_next();
        self.gpu.renderer.set_profiling(profiled);
        match self.gpu.render(&self.view.scene, &camera, size) {
            Ok(()) => self.note_frame(profiled),
            Err(e) => self.ui.message = Some((false, e.to_string())),
        }
        if self.view.split {
            self.gpu.render_bare(&self.view.scene, &camera, size);
        }
        self.gpu.frame_size = size;
        self.update_heat_map();
        self.view.needs_render = false;
        self.gpu.last_frame_ms = start.elapsed().as_secs_f64() * 1e3;
    }

    /// Renders the current view at `size` and writes it as a PNG (the screenshot export).
    ///
    /// # Errors
    /// Rendering or writing fails.
    pub fn screenshot(&mut self, path: &Path, size: (u32, u32)) -> Result<()> {
        let camera = self.camera().context("no mesh yet")?;
        self.view.update_lights();
        self.apply_subsurface();
        self.gpu.renderer.render(&self.view.scene, &camera, size.0, size.1, true)?;
        let pixels = self.gpu.renderer.read_display()?;
        write_png(path, size.0, size.1, &pixels)?;
        self.view.needs_render = true;
        Ok(())
    }

    /// The key light and the split line (left panel).
    pub(super) fn light_panel(&mut self, ui: &mut egui::Ui) {
        let v = &mut self.view;
        ui.heading("Light");
        let mut changed = ui.add(egui::Slider::new(&mut v.light_yaw_deg, -180.0..=180.0).text("key yaw °")).changed();
        changed |= ui.add(egui::Slider::new(&mut v.light_pitch_deg, -60.0..=85.0).text("key pitch °")).changed();
        changed |= ui.add(egui::Slider::new(&mut v.light_intensity, 0.0..=3.0).text("key intensity")).changed();
        changed |= ui.checkbox(&mut v.environment, "Environment").changed();
        if v.split {
            changed |= ui.add(egui::Slider::new(&mut v.split_at, 0.0..=1.0).text("before | after")).changed();
        }
        v.needs_render |= changed;
    }

    pub(super) fn viewport_ui(&mut self, ui: &mut egui::Ui) {
        let avail = ui.available_size();
        let ppp = ui.ctx().pixels_per_point();
        let size = ((avail.x * ppp).round().max(1.0) as u32, (avail.y * ppp).round().max(1.0) as u32);
        let (rect, response) = ui.allocate_exact_size(avail, Sense::click_and_drag());
        self.view.rect = rect;
        if let Some(label) = self.jobs.preparing_label() {
            ui.put(rect, egui::Spinner::new().size(32.0));
            ui.painter().text(
                rect.center() + Vec2::new(0.0, 30.0),
                egui::Align2::CENTER_TOP,
                format!("Preparing {label}…"),
                egui::FontId::proportional(14.0),
                Color32::GRAY,
            );
            return;
        }
        // Input.
        let (alt, shift) = ui.input(|i| (i.modifiers.alt, i.modifiers.shift));
        let primary = response.dragged_by(egui::PointerButton::Primary);
        let orbit = (primary && alt) || (response.dragged_by(egui::PointerButton::Secondary) && !shift);
        let pan = response.dragged_by(egui::PointerButton::Middle)
            || (response.dragged_by(egui::PointerButton::Secondary) && shift);
        if self.radius_drag_input(ui) {
            // F: the pointer sets the brush radius; nothing else until it is kept or cancelled.
        } else if orbit {
            let d = response.drag_delta();
            self.view.orbit.yaw_deg -= d.x * 0.4;
            self.view.orbit.pitch_deg = (self.view.orbit.pitch_deg + d.y * 0.4).clamp(-80.0, 80.0);
            self.view.needs_render = true;
        } else if pan {
            if let Some(c) = self.camera() {
                let d = response.drag_delta();
                let mm_per_point = c.distance * (0.5 * c.fov_y_deg.to_radians()).tan() * 2.0 / rect.height().max(1.0);
                let view = c.view();
                let right = Vec3::new(view.x_axis.x, view.y_axis.x, view.z_axis.x);
                let up = Vec3::new(view.x_axis.y, view.y_axis.y, view.z_axis.y);
                self.view.orbit.pan_mm += (-right * d.x + up * d.y) * mm_per_point;
                self.view.needs_render = true;
            }
        } else if self.ready() && !alt {
            // Occlusion: while painting, the last frame's depth hides what the viewer cannot see.
            let painting = primary || response.drag_started_by(egui::PointerButton::Primary);
            let depth = if painting {
                self.gpu.renderer.depth_image().ok().and_then(|f| {
                    rouge_model::paint::DepthImage::new(f.view_proj, f.size.0, f.size.1, f.depth)
                        .map(std::sync::Arc::new)
                })
            } else {
                None
            };
            self.editor.view = self.camera().map(|c| PaintView { eye: c.position(), depth });
            self.editor.pressure = ui.input(|i| {
                i.events.iter().rev().find_map(|e| match e {
                    egui::Event::Touch { force, .. } => *force,
                    _ => None,
                })
            });
            if shift
                && response.clicked_by(egui::PointerButton::Primary)
                && let Some(pos) = response.interact_pointer_pos()
                && let Some(w) = self.pick(pos)
            {
                match self.editor.straight_stroke(w) {
                    Ok(changes) => self.apply_changes(changes),
                    Err(e) => self.ui.message = Some((false, e.to_string())),
                }
            }
            if response.drag_started_by(egui::PointerButton::Primary) {
                self.begin_stroke();
            }
            if primary
                && let Some(pos) = response.interact_pointer_pos()
                && let Some(w) = self.pick(pos)
            {
                self.paint_at(w);
            }
            if response.drag_stopped_by(egui::PointerButton::Primary) {
                self.end_stroke();
            }
        }
        if response.hovered() {
            let scroll = ui.input(|i| i.smooth_scroll_delta.y);
            if scroll != 0.0 {
                self.view.orbit.zoom = (self.view.orbit.zoom * (1.0 + scroll * 0.002)).clamp(0.3, 8.0);
                self.view.needs_render = true;
            }
        }
        if self.baking() {
            // Pick up the bake when it lands.
            self.view.needs_render = true;
            ui.ctx().request_repaint_after(Duration::from_millis(100));
        }
        if self.view.needs_render || size != self.gpu.frame_size {
            self.render(size);
        }
        // Draw.
        let uv = Rect::from_min_max(Pos2::ZERO, Pos2::new(1.0, 1.0));
        if let Some(id) = self.gpu.texture {
            ui.painter().image(id, rect, uv, Color32::WHITE);
        }
        if self.view.split
            && let Some(id) = self.gpu.bare_texture
        {
            let x = rect.min.x + rect.width() * self.view.split_at;
            let left = Rect::from_min_max(rect.min, Pos2::new(x, rect.max.y));
            let left_uv = Rect::from_min_max(Pos2::ZERO, Pos2::new(self.view.split_at, 1.0));
            ui.painter().image(id, left, left_uv, Color32::WHITE);
            ui.painter().vline(x, rect.y_range(), egui::Stroke::new(2.0, Color32::WHITE));
            ui.painter().text(
                left.left_top() + Vec2::new(8.0, 8.0),
                egui::Align2::LEFT_TOP,
                "bare skin",
                egui::FontId::proportional(14.0),
                Color32::WHITE,
            );
            ui.painter().text(
                Pos2::new(x + 8.0, rect.min.y + 8.0),
                egui::Align2::LEFT_TOP,
                "makeup",
                egui::FontId::proportional(14.0),
                Color32::WHITE,
            );
        }
        self.draw_heat_map(ui, rect);
        self.brush_keys(ui.ctx());
        self.draw_symmetry(ui);
        self.draw_radius_drag(ui);
        self.view.hover_world = response.hover_pos().and_then(|h| self.pick(h));
        self.view.hover_mm = self.view.hover_world.and_then(|w| self.editor.thickness_at(w));
        // Brush outline under the cursor (its screen radius at the surface's depth).
        if let Some(hover) = response.hover_pos()
            && !alt
            && self.radius_drag().is_none()
            && self.ready()
            && let (Some(c), Some(w)) = (self.camera(), self.pick(hover))
        {
            let dist = (c.position() - w).length().max(1.0);
            let px = self.editor.brush.radius_mm * c.focal_px(self.gpu.frame_size.1) / dist / ppp;
            ui.painter().circle_stroke(hover, px, egui::Stroke::new(1.0, Color32::from_white_alpha(180)));
        }
        let timing = match self.frames.in_viewport {
            true => self.frame_readout(),
            false => format!("frame submitted in {:.0} ms", self.gpu.last_frame_ms),
        };
        ui.painter().text(
            rect.left_bottom() + Vec2::new(8.0, -8.0),
            egui::Align2::LEFT_BOTTOM,
            format!("{timing} · {}×{}", self.gpu.frame_size.0, self.gpu.frame_size.1),
            egui::FontId::monospace(11.0),
            Color32::from_white_alpha(150),
        );
    }
}
