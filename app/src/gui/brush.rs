//! The brush panel: mode (paint, erase, smooth), radius, thickness, flow, hardness, mirror.

use super::*;

impl RougeApp {
    pub(super) fn brush_panel(&mut self, ui: &mut egui::Ui) {
        let brush = &mut self.editor.brush;
        ui.heading("Brush");
        ui.horizontal(|ui| {
            ui.selectable_value(&mut brush.mode, BrushMode::Paint, "Paint");
            ui.selectable_value(&mut brush.mode, BrushMode::Erase, "Erase");
            ui.selectable_value(&mut brush.mode, BrushMode::Smooth, "Smooth");
        });
        ui.add(egui::Slider::new(&mut brush.radius_mm, 1.0..=40.0).text("radius (mm on the skin)"));
        let mut microns = brush.thickness_mm * 1000.0;
        if ui.add(egui::Slider::new(&mut microns, 0.0..=100.0).text("thickness (µm)")).changed() {
            brush.thickness_mm = microns / 1000.0;
        }
        ui.add(egui::Slider::new(&mut brush.flow, 0.01..=1.0).text("flow"));
        ui.add(egui::Slider::new(&mut brush.hardness, 0.0..=1.0).text("hardness"));
        ui.checkbox(&mut brush.mirror, "Mirror across the face's midplane");
    }
}
