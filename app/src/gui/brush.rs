//! The brush panel: presets of a makeup kit, mode, size, thickness, flow, hardness, falloff,
//! spacing, the stabiliser, how the brush keeps to the surface, symmetry (axis, offset, fit,
//! shown in the viewport), and fills; `[` / `]` resize the brush.

use super::*;
use crate::radius_drag::RADIUS_RANGE_MM;
use rouge_model::look::Region;
use rouge_model::paint::{Axis, BRUSH_PRESETS, Falloff, FillRegion, MirrorPlane, Reach};

/// Brush-size step of `[` and `]` (a factor).
const SIZE_STEP: f32 = 1.15;

/// Where a fill goes.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) enum FillTarget {
    /// One of the default head's region masks.
    Region(Region),
    /// The UV island under the cursor's last surface point.
    Island,
    /// Every texel of the head.
    Whole,
}

impl FillTarget {
    fn label(self) -> String {
        match self {
            FillTarget::Region(r) => format!("{r} mask"),
            FillTarget::Island => "UV island under the cursor".into(),
            FillTarget::Whole => "whole head".into(),
        }
    }
}

impl RougeApp {
    pub(super) fn brush_panel(&mut self, ui: &mut egui::Ui) {
        ui.heading("Brush");
        ui.horizontal_wrapped(|ui| {
            for p in BRUSH_PRESETS {
                let on = p.matches(&self.editor.brush);
                if ui.selectable_label(on, p.name).on_hover_text(p.purpose).clicked() {
                    self.editor.brush = p.apply(&self.editor.brush);
                }
            }
        });
        let brush = &mut self.editor.brush;
        ui.horizontal(|ui| {
            ui.selectable_value(&mut brush.mode, BrushMode::Paint, "Paint");
            ui.selectable_value(&mut brush.mode, BrushMode::Erase, "Erase");
            ui.selectable_value(&mut brush.mode, BrushMode::Smooth, "Smooth");
        });
        ui.add(egui::Slider::new(&mut brush.radius_mm, RADIUS_RANGE_MM).logarithmic(true).text("radius (mm) [ ] F"));
        let mut microns = brush.thickness_mm * 1000.0;
        if ui.add(egui::Slider::new(&mut microns, 0.0..=100.0).text("thickness (µm)")).changed() {
            brush.thickness_mm = microns / 1000.0;
        }
        ui.add(egui::Slider::new(&mut brush.flow, 0.01..=1.0).text("flow"));
        ui.add(egui::Slider::new(&mut brush.hardness, 0.0..=1.0).text("hardness"));
        ui.add(egui::Slider::new(&mut brush.spacing, 0.05..=2.0).text("spacing (× radius)"));
        egui::ComboBox::from_label("falloff").selected_text(brush.falloff.name()).show_ui(ui, |ui| {
            for f in Falloff::ALL {
                ui.selectable_value(&mut brush.falloff, f, f.name());
            }
        });
        ui.add(egui::Slider::new(&mut self.editor.stabiliser_mm, 0.0..=15.0).text("stabiliser (mm of string)"))
            .on_hover_text(
                "Lazy mouse: the brush trails the pointer by this much, so a shaky hand draws a steady line",
            );
        let brush = &mut self.editor.brush;
        let mut on_surface = brush.reach == Reach::Surface;
        if ui
            .checkbox(&mut on_surface, "Stay on the surface")
            .on_hover_text(
                "Paint reaches along the skin, not through the air: closed lips, lids and nostrils stay apart",
            )
            .changed()
        {
            brush.reach = if on_surface { Reach::Surface } else { Reach::Ball };
        }
        ui.checkbox(&mut brush.front_faces_only, "Front faces only")
            .on_hover_text("Only skin facing the camera takes paint");
        self.symmetry_ui(ui);
        self.fill_ui(ui);
    }

    fn symmetry_ui(&mut self, ui: &mut egui::Ui) {
        let surface = self.editor.surface().cloned();
        let brush = &mut self.editor.brush;
        ui.horizontal(|ui| {
            ui.checkbox(&mut brush.mirror, "Mirror");
            ui.checkbox(&mut self.view.show_plane, "show plane");
        });
        let Some(surface) = surface else { return };
        let mut plane = brush.plane(&surface);
        let before = plane;
        ui.horizontal(|ui| {
            ui.label("axis");
            for a in Axis::ALL {
                if ui.selectable_label(plane.axis == a, a.name()).clicked() && plane.axis != a {
                    plane = MirrorPlane::fitted(a, &surface);
                }
            }
            if ui.button("Fit").on_hover_text("The offset about which the mesh is most nearly symmetric").clicked() {
                plane = MirrorPlane::fit(plane.axis, &surface);
            }
        });
        let c = surface.centre()[plane.axis.index()];
        ui.add(egui::Slider::new(&mut plane.offset_mm, c - 60.0..=c + 60.0).text("plane offset (mm)"));
        if plane != before {
            brush.mirror_plane = Some(plane);
        }
    }

    fn fill_ui(&mut self, ui: &mut egui::Ui) {
        ui.horizontal(|ui| {
            egui::ComboBox::from_id_salt("fill target").selected_text(self.ui.fill.label()).show_ui(ui, |ui| {
                for t in
                    Region::all().map(FillTarget::Region).into_iter().chain([FillTarget::Island, FillTarget::Whole])
                {
                    ui.selectable_value(&mut self.ui.fill, t, t.label());
                }
            });
            if ui
                .button("Fill")
                .on_hover_text("Fill the active layer at the brush's thickness (one undo step)")
                .clicked()
            {
                self.fill_active();
            }
        });
    }

    /// Fills the active layer at the brush's thickness inside the chosen target.
    pub(super) fn fill_active(&mut self) {
        let result = match self.ui.fill {
            FillTarget::Region(r) => self.editor.fill(FillRegion::Mask(r.mask())),
            FillTarget::Whole => self.editor.fill(FillRegion::Whole),
            FillTarget::Island => {
                match self.view.hover_world.and_then(|w| self.editor.surface()?.nearest_texel(w, 2.0)) {
                    Some((x, y)) => self.editor.fill(FillRegion::Island { x, y }),
                    None => Err("fill: point at the head first (the island under the cursor)".into()),
                }
            }
        };
        match result {
            Ok(change) => {
                self.ui.message = Some((true, format!("filled the {}", self.ui.fill.label())));
                self.apply_change(change);
            }
            Err(e) => self.ui.message = Some((false, e)),
        }
    }

    /// `[` and `]`: the brush a step smaller or larger.
    pub(super) fn brush_keys(&mut self, ctx: &egui::Context) {
        if ctx.egui_wants_keyboard_input() {
            return;
        }
        let (smaller, larger) = ctx.input(|i| (i.key_pressed(Key::OpenBracket), i.key_pressed(Key::CloseBracket)));
        let b = &mut self.editor.brush;
        if smaller {
            b.radius_mm = (b.radius_mm / SIZE_STEP).max(*RADIUS_RANGE_MM.start());
        }
        if larger {
            b.radius_mm = (b.radius_mm * SIZE_STEP).min(*RADIUS_RANGE_MM.end());
        }
    }

    /// The symmetry plane where it cuts the skin facing the camera, as dots in the viewport.
    pub(super) fn draw_symmetry(&mut self, ui: &egui::Ui) {
        if !(self.view.show_plane && self.editor.brush.mirror) {
            return;
        }
        let (Some(surface), Some(c)) = (self.editor.surface().cloned(), self.camera()) else { return };
        let plane = self.editor.brush.plane(&surface);
        if self.view.plane_trace.as_ref().is_none_or(|(p, _)| *p != plane) {
            self.view.plane_trace = Some((plane, plane.trace(&surface, 1.0)));
        }
        let Some((_, trace)) = &self.view.plane_trace else { return };
        let eye = c.position();
        let colour = Color32::from_rgba_unmultiplied(120, 220, 255, 200);
        for &(p, n) in trace {
            if n.dot(eye - p) > 0.0
                && let Some(s) = self.screen_pos_of(p)
            {
                ui.painter().circle_filled(s, 0.8, colour);
            }
        }
    }
}
