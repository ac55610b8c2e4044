//! The viewport: orbit camera, lights, picking on the GPU depth buffer, frames into egui
//! native textures (with the bare-skin half of the before/after split), input and overlays.

use super::*;

impl RougeApp {
    pub(super) fn camera(&self) -> Option<Camera> {
        let bounds = self.renderer.mesh_bounds()?;
        let mut c = Camera::framing(&bounds, self.view.yaw, self.view.pitch);
        c.distance /= self.view.zoom;
        c.target += self.view.pan;
        Some(c)
    }

    pub(super) fn update_lights(&mut self) {
        let (yaw, pitch) = (self.light_yaw.to_radians(), self.light_pitch.to_radians());
        let toward = Vec3::new(yaw.sin() * pitch.cos(), pitch.sin(), yaw.cos() * pitch.cos());
        let studio = Scene::studio();
        self.scene.lights = studio.lights.clone();
        if let Some(key) = self.scene.lights.first_mut() {
            key.kind = LightKind::Directional { toward };
            key.irradiance = studio.lights[0].irradiance.map(|v| v * self.light_intensity);
        }
        self.scene.environment = if self.environment { studio.environment } else { None };
    }

    pub(super) fn pick(&self, pos: Pos2) -> Option<Vec3> {
        let (w, h) = self.frame_size;
        let r = self.viewport;
        if w == 0 || !r.contains(pos) {
            return None;
        }
        let x = ((pos.x - r.min.x) / r.width() * w as f32) as u32;
        let y = ((pos.y - r.min.y) / r.height() * h as f32) as u32;
        match self.renderer.pick(x, y) {
            Ok(p) => p,
            Err(e) => {
                eprintln!("rouge: pick failed: {e}");
                None
            }
        }
    }

    pub(super) fn render(&mut self, size: (u32, u32)) {
        let Some(camera) = self.camera() else { return };
        if size.0 == 0 || size.1 == 0 {
            return;
        }
        let start = Instant::now();
        self.update_lights();
        match self.renderer.render(&self.scene, &camera, size.0, size.1, true) {
            Ok(texture) => {
                let view = rouge_render::renderer::egui_view(&texture);
                let mut r = self.egui_renderer.write();
                match self.texture {
                    Some(id) if self.frame_size == size => {
                        r.update_egui_texture_from_wgpu_texture(&self.device, &view, wgpu::FilterMode::Linear, id)
                    }
                    _ => {
                        if let Some(id) = self.texture.take() {
                            r.free_texture(&id);
                        }
                        self.texture = Some(r.register_native_texture(&self.device, &view, wgpu::FilterMode::Linear));
                    }
                }
            }
            Err(e) => self.message = Some((false, e.to_string())),
        }
        if self.split {
            self.render_bare(&camera, size);
        }
        self.frame_size = size;
        self.needs_render = false;
        self.last_frame_ms = start.elapsed().as_secs_f64() * 1e3;
    }

    pub(super) fn render_bare(&mut self, camera: &Camera, size: (u32, u32)) {
        if self.bare.is_none() {
            let mut bare = Renderer::new(&self.device, &self.queue);
            if let Some(mesh) = &self.mesh
                && bare.set_mesh(mesh, self.scene.skin.albedo).is_err()
            {
                return;
            }
            self.bare = Some(bare);
        }
        let Some(bare) = self.bare.as_mut() else { return };
        if let Ok(texture) = bare.render(&self.scene, camera, size.0, size.1, true) {
            let view = rouge_render::renderer::egui_view(&texture);
            let mut r = self.egui_renderer.write();
            if let Some(id) = self.bare_texture.take() {
                r.free_texture(&id);
            }
            self.bare_texture = Some(r.register_native_texture(&self.device, &view, wgpu::FilterMode::Linear));
        }
    }

    /// Renders the current view at `size` and writes it as a PNG (the screenshot export).
    ///
    /// # Errors
    /// Rendering or writing fails.
    pub fn screenshot(&mut self, path: &Path, size: (u32, u32)) -> Result<()> {
        let camera = self.camera().context("no mesh yet")?;
        self.update_lights();
        self.renderer.render(&self.scene, &camera, size.0, size.1, true)?;
        let pixels = self.renderer.read_display()?;
        write_png(path, size.0, size.1, &pixels)?;
        self.needs_render = true;
        Ok(())
    }

    pub(super) fn viewport_ui(&mut self, ui: &mut egui::Ui) {
        let avail = ui.available_size();
        let ppp = ui.ctx().pixels_per_point();
        let size = ((avail.x * ppp).round().max(1.0) as u32, (avail.y * ppp).round().max(1.0) as u32);
        let (rect, response) = ui.allocate_exact_size(avail, Sense::click_and_drag());
        self.viewport = rect;
        if let Some((label, _)) = &self.preparing {
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
        if orbit {
            let d = response.drag_delta();
            self.view.yaw -= d.x * 0.4;
            self.view.pitch = (self.view.pitch + d.y * 0.4).clamp(-80.0, 80.0);
            self.needs_render = true;
        } else if pan {
            if let Some(c) = self.camera() {
                let d = response.drag_delta();
                let mm_per_point = c.distance * (0.5 * c.fov_y_deg.to_radians()).tan() * 2.0 / rect.height().max(1.0);
                let view = c.view();
                let right = Vec3::new(view.x_axis.x, view.y_axis.x, view.z_axis.x);
                let up = Vec3::new(view.x_axis.y, view.y_axis.y, view.z_axis.y);
                self.view.pan += (-right * d.x + up * d.y) * mm_per_point;
                self.needs_render = true;
            }
        } else if self.ready() && !alt {
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
                self.view.zoom = (self.view.zoom * (1.0 + scroll * 0.002)).clamp(0.3, 8.0);
                self.needs_render = true;
            }
        }
        if self.needs_render || size != self.frame_size {
            self.render(size);
        }
        // Draw.
        let uv = Rect::from_min_max(Pos2::ZERO, Pos2::new(1.0, 1.0));
        if let Some(id) = self.texture {
            ui.painter().image(id, rect, uv, Color32::WHITE);
        }
        if self.split
            && let Some(id) = self.bare_texture
        {
            let x = rect.min.x + rect.width() * self.split_at;
            let left = Rect::from_min_max(rect.min, Pos2::new(x, rect.max.y));
            let left_uv = Rect::from_min_max(Pos2::ZERO, Pos2::new(self.split_at, 1.0));
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
        // Brush outline under the cursor (its screen radius at the surface's depth).
        if let Some(hover) = response.hover_pos()
            && !alt
            && self.ready()
            && let (Some(c), Some(w)) = (self.camera(), self.pick(hover))
        {
            let dist = (c.position() - w).length().max(1.0);
            let px = self.editor.brush.radius_mm * c.focal_px(self.frame_size.1) / dist / ppp;
            ui.painter().circle_stroke(hover, px, egui::Stroke::new(1.0, Color32::from_white_alpha(180)));
        }
        ui.painter().text(
            rect.left_bottom() + Vec2::new(8.0, -8.0),
            egui::Align2::LEFT_BOTTOM,
            format!("frame submitted in {:.0} ms · {}×{}", self.last_frame_ms, self.frame_size.0, self.frame_size.1),
            egui::FontId::monospace(11.0),
            Color32::from_white_alpha(150),
        );
    }
}
