//! The viewport's layer views and the F radius drag: the solo view (only the active layer
//! rendered), the active layer's thickness as a heat map with a legend in µm, and Blender's F
//! (press F, move, click or Enter to keep, Esc or right click to cancel).
//!
//! The heat map is the renderer's own: with the heat map on, only the active layer is uploaded
//! (the solo view), so the G-buffer's first thickness channel holds that layer's thickness ×
//! its multiplier at every pixel, exactly what the lighting pass used. `Renderer::thickness_image` reads
//! it back and [`HeatScale::image`] colours it; painted pixels cover the rendered frame,
//! unpainted ones leave it visible.

use super::*;
use crate::heatmap::HeatScale;
use crate::radius_drag::RadiusDrag;

/// The heat map of the last frame: its pixels (RGBA, the frame's size) and scale.
#[derive(Clone, Debug)]
pub struct HeatMapFrame {
    /// Width and height, pixels (the viewport's frame).
    pub size: (u32, u32),
    /// RGBA bytes: a colour of the scale where painted, clear elsewhere.
    pub rgba: Vec<u8>,
    /// The scale of the legend.
    pub scale: HeatScale,
    /// The layer shown.
    pub layer: usize,
}

/// The solo and heat-map switches, the heat map shown, and a radius drag in progress.
#[derive(Default)]
pub(super) struct LayerViews {
    solo: bool,
    heat: bool,
    frame: Option<HeatMapFrame>,
    texture: Option<egui::TextureHandle>,
    /// The heat map changed since it was last given to egui.
    stale: bool,
    radius_drag: Option<RadiusDrag>,
    /// A click that ended a radius drag: the button is ignored until it is released.
    swallow_primary: bool,
}

impl RougeApp {
    /// Shows only the active layer (`true`) or every visible layer.
    pub fn set_solo(&mut self, on: bool) {
        self.views.solo = on;
        self.sync_view_layers();
    }

    /// Shows the active layer's thickness as a heat map (with the solo view while it is on).
    pub fn set_heat_map(&mut self, on: bool) {
        self.views.heat = on;
        if !on {
            self.views.frame = None;
            self.views.texture = None;
        }
        self.sync_view_layers();
    }

    /// The heat map of the last frame, while the heat map is on.
    pub fn heat_map(&self) -> Option<&HeatMapFrame> {
        self.views.frame.as_ref()
    }

    /// Where the viewport is on screen (egui points).
    pub fn viewport_rect(&self) -> Rect {
        self.view.rect
    }

    /// The brush radius drag in progress (F), if any.
    pub fn radius_drag(&self) -> Option<&RadiusDrag> {
        self.views.radius_drag.as_ref()
    }

    fn sync_view_layers(&mut self) {
        let c = self.editor.set_solo(self.views.solo || self.views.heat);
        self.apply_change(c);
        self.view.needs_render = true;
    }

    /// The View menu's layer views.
    pub(super) fn views_menu(&mut self, ui: &mut egui::Ui) {
        let (mut solo, mut heat) = (self.views.solo, self.views.heat);
        if ui.checkbox(&mut solo, "Solo active layer").on_hover_text("render only the active layer").changed() {
            self.set_solo(solo);
        }
        if ui
            .checkbox(&mut heat, "Thickness heat map")
            .on_hover_text("the active layer's rendered thickness (map × multiplier) in µm")
            .changed()
        {
            self.set_heat_map(heat);
        }
    }

    /// After a frame: with the heat map on, reads the active layer's thickness back from the
    /// G-buffer and colours it on the scale of the layer's thickest texel.
    pub(super) fn update_heat_map(&mut self) {
        if !self.views.heat {
            return;
        }
        let layer = self.editor.active();
        let Some(l) = self.editor.document().layers.get(layer) else { return };
        let scale = HeatScale::for_max_mm(l.map.max_mm() * l.multiplier);
        let shown = self.editor.render_index(layer).is_some();
        match self.gpu.renderer.thickness_image() {
            Ok(image) => {
                let rgba = scale.image(image.texels.iter().map(|t| if shown { t[0] } else { 0.0 }));
                self.views.frame = Some(HeatMapFrame { size: image.size, rgba, scale, layer });
                self.views.stale = true;
            }
            Err(e) => self.ui.message = Some((false, format!("heat map: {e}"))),
        }
    }

    /// Draws the heat map over the frame in `rect` and its legend at the right edge.
    pub(super) fn draw_heat_map(&mut self, ui: &egui::Ui, rect: Rect) {
        let Some(frame) = &self.views.frame else { return };
        if self.views.stale || self.views.texture.is_none() {
            let image =
                egui::ColorImage::from_rgba_unmultiplied([frame.size.0 as usize, frame.size.1 as usize], &frame.rgba);
            match &mut self.views.texture {
                Some(t) => t.set(image, egui::TextureOptions::LINEAR),
                None => {
                    self.views.texture = Some(ui.ctx().load_texture("heat map", image, egui::TextureOptions::LINEAR))
                }
            }
            self.views.stale = false;
        }
        if let Some(t) = &self.views.texture {
            ui.painter().image(t.id(), rect, Rect::from_min_max(Pos2::ZERO, Pos2::new(1.0, 1.0)), Color32::WHITE);
        }
        let name = self.editor.document().layers.get(frame.layer).map_or("", |l| l.name.as_str());
        legend(ui.painter(), rect, &frame.scale, name);
    }

    /// F: starts a radius drag with the pointer on the edge of the brush circle (the pointer
    /// must be over the viewport).
    pub(super) fn start_radius_drag(&mut self, ctx: &egui::Context) {
        let Some(pointer) = ctx.pointer_hover_pos().filter(|p| self.view.rect.contains(*p)) else { return };
        let Some(c) = self.camera() else { return };
        let dist = self.pick(pointer).map_or(c.distance, |w| (c.position() - w).length()).max(1.0);
        let points_per_mm = c.focal_px(self.gpu.frame_size.1) / dist / ctx.pixels_per_point();
        self.views.radius_drag = RadiusDrag::start([pointer.x, pointer.y], self.editor.brush.radius_mm, points_per_mm);
    }

    /// While a radius drag runs: the pointer sets the radius, a click or Enter keeps it, Esc or
    /// a right click restores the old one. Returns whether the viewport's
    /// other input (painting, orbiting) must wait: during the drag, and until the button that
    /// ended it is released.
    pub(super) fn radius_drag_input(&mut self, ui: &egui::Ui) -> bool {
        let (pointer, primary, secondary, enter, escape, primary_down) = ui.input(|i| {
            (
                i.pointer.hover_pos(),
                i.pointer.primary_pressed(),
                i.pointer.secondary_pressed(),
                i.key_pressed(Key::Enter),
                i.key_pressed(Key::Escape),
                i.pointer.primary_down(),
            )
        });
        if self.views.swallow_primary {
            self.views.swallow_primary = primary_down;
            return true;
        }
        let Some(drag) = self.views.radius_drag.as_mut() else { return false };
        if let Some(p) = pointer {
            self.editor.brush.radius_mm = drag.pointer_at([p.x, p.y]);
        }
        let drag = *drag;
        if secondary || escape {
            self.editor.brush.radius_mm = drag.start_mm();
            self.views.radius_drag = None;
            self.views.swallow_primary = primary_down;
        } else if primary || enter {
            self.editor.brush.radius_mm = drag.radius_mm();
            self.views.radius_drag = None;
            self.views.swallow_primary = primary_down || primary;
            self.ui.message = Some((true, format!("brush radius {:.1} mm", drag.radius_mm())));
        }
        true
    }
}

impl RougeApp {
    /// The radius drag's circle, centre and radius (over the frame).
    pub(super) fn draw_radius_drag(&self, ui: &egui::Ui) {
        let Some(drag) = &self.views.radius_drag else { return };
        let centre = Pos2::new(drag.centre()[0], drag.centre()[1]);
        let p = ui.painter();
        p.circle_stroke(centre, drag.radius_points(), egui::Stroke::new(2.0, Color32::WHITE));
        p.circle_filled(centre, 2.0, Color32::WHITE);
        p.text(
            centre + Vec2::new(0.0, -drag.radius_points() - 6.0),
            egui::Align2::CENTER_BOTTOM,
            format!("radius {:.1} mm · click/Enter: keep · Esc/right click: cancel", drag.radius_mm()),
            egui::FontId::proportional(13.0),
            Color32::WHITE,
        );
    }
}

/// The heat map's legend in the top right corner of `rect`: the layer's name, the unit, a
/// vertical colour bar with 0 at the bottom and a tick and label every step of the scale.
fn legend(painter: &egui::Painter, rect: Rect, scale: &HeatScale, layer: &str) {
    let white = Color32::WHITE;
    let name = painter.layout_no_wrap(layer.to_string(), egui::FontId::proportional(11.0), white);
    let width = name.size().x.max(92.0) + 16.0;
    let back = Rect::from_min_size(Pos2::new(rect.max.x - 8.0 - width, rect.min.y + 8.0), Vec2::new(width, 300.0));
    painter.rect_filled(back, 4.0, Color32::from_black_alpha(170));
    painter.galley(back.min + Vec2::new(8.0, 6.0), name, white);
    let font = egui::FontId::proportional(12.0);
    painter.text(back.min + Vec2::new(8.0, 24.0), egui::Align2::LEFT_TOP, "µm", font.clone(), white);
    let bar = Rect::from_min_size(back.min + Vec2::new(8.0, 46.0), Vec2::new(16.0, 220.0));
    let mut mesh = egui::Mesh::default();
    const STEPS: u32 = 32;
    for k in 0..=STEPS {
        let t = k as f32 / STEPS as f32;
        let [r, g, b] = crate::heatmap::colour_map(t);
        let y = bar.max.y - t * bar.height();
        mesh.colored_vertex(Pos2::new(bar.min.x, y), Color32::from_rgb(r, g, b));
        mesh.colored_vertex(Pos2::new(bar.max.x, y), Color32::from_rgb(r, g, b));
        if k > 0 {
            let i = 2 * k;
            mesh.add_triangle(i - 2, i - 1, i);
            mesh.add_triangle(i - 1, i + 1, i);
        }
    }
    painter.add(egui::Shape::mesh(mesh));
    painter.rect_stroke(bar, 0.0, egui::Stroke::new(1.0, white), egui::StrokeKind::Outside);
    for um in scale.ticks_um() {
        let y = bar.max.y - (um / scale.top_um) as f32 * bar.height();
        painter.line_segment([Pos2::new(bar.max.x, y), Pos2::new(bar.max.x + 5.0, y)], egui::Stroke::new(1.0, white));
        painter.text(Pos2::new(bar.max.x + 8.0, y), egui::Align2::LEFT_CENTER, scale.label(um), font.clone(), white);
    }
    painter.text(
        Pos2::new(bar.min.x, bar.max.y + 10.0),
        egui::Align2::LEFT_TOP,
        "clear: unpainted",
        egui::FontId::proportional(11.0),
        Color32::from_white_alpha(200),
    );
}
