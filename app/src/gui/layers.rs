//! The left panel: layers (visibility, order, rename, clear, multiplier, material), the
//! brush, the typed project folder and the key light.

use super::*;

impl RougeApp {
    pub(super) fn layers_panel(&mut self, ui: &mut egui::Ui) {
        ui.heading("Layers");
        ui.label("Top of the list = top of the stack");
        let n = self.editor.document().layers.len();
        let mut action: Option<LayerAction> = None;
        let mut select: Option<usize> = None;
        let active = self.editor.active();
        for i in (0..n).rev() {
            let l = &self.editor.document().layers[i];
            ui.horizontal(|ui| {
                let mut visible = l.visible;
                if ui.checkbox(&mut visible, "").on_hover_text("visible").changed() {
                    action = Some(Box::new(move |d: &mut Document| d.set_visible(i, visible)));
                }
                materials::swatch(ui, &l.preset, 14.0);
                if ui.selectable_label(active == i, &l.name).clicked() {
                    select = Some(i);
                }
                if ui.small_button("Up").on_hover_text("move up").clicked() && i + 1 < n {
                    action = Some(Box::new(move |d: &mut Document| d.move_layer(i, i + 1)));
                }
                if ui.small_button("Down").on_hover_text("move down").clicked() && i > 0 {
                    action = Some(Box::new(move |d: &mut Document| d.move_layer(i, i - 1)));
                }
                if ui.small_button("Del").on_hover_text("remove").clicked() {
                    action = Some(Box::new(move |d: &mut Document| d.remove_layer(i)));
                }
            });
        }
        if let Some(i) = select {
            self.editor.set_active_layer(i);
            self.rename_buffer = self.editor.document().layers[i].name.clone();
        }
        if let Some(a) = action.take() {
            let c = self.editor.edit(a);
            self.apply_change(c);
        }
        let active = self
            .editor
            .document()
            .layers
            .get(self.editor.active())
            .map(|l| (l.name.clone(), l.preset.name.clone(), l.multiplier));
        if let Some((name, preset_name, multiplier)) = active {
            ui.separator();
            ui.label(format!("Active: {name} ({preset_name})"));
            let i = self.editor.active();
            ui.horizontal(|ui| {
                ui.text_edit_singleline(&mut self.rename_buffer);
                if ui.button("Rename").clicked() && !self.rename_buffer.trim().is_empty() {
                    let name = self.rename_buffer.trim().to_string();
                    let c = self.editor.edit(|d| d.rename_layer(i, &name));
                    self.apply_change(c);
                }
            });
            if ui.button("Clear layer").on_hover_text("set the whole map to 0 mm (one undo step)").clicked() {
                self.clear_layer(i);
            }
            let mut m = multiplier;
            if ui.add(egui::Slider::new(&mut m, 0.0..=4.0).text("thickness ×")).drag_stopped() {
                let c = self.editor.edit(|d| d.set_multiplier(i, m));
                self.apply_change(c);
            }
            let selected = self.library.materials.get(self.library.selected).cloned();
            if let Some(mat) = selected
                && ui.button(format!("Use material “{}”", mat.preset.name)).clicked()
            {
                let c = self.editor.edit(|d| d.set_preset(i, &mat.preset_ref, mat.preset.clone()));
                self.apply_change(c);
            }
        }
        let selected = self.library.materials.get(self.library.selected).cloned();
        if let Some(mat) = selected
            && ui.button(format!("Add layer of “{}”", mat.preset.name)).clicked()
        {
            let c = self.editor.add_layer(&mat.preset_ref, mat.preset.clone());
            self.apply_change(c);
        }

        ui.separator();
        ui.heading("Brush");
        ui.horizontal(|ui| {
            ui.selectable_value(&mut self.editor.brush.mode, BrushMode::Paint, "Paint");
            ui.selectable_value(&mut self.editor.brush.mode, BrushMode::Erase, "Erase");
            ui.selectable_value(&mut self.editor.brush.mode, BrushMode::Smooth, "Smooth");
        });
        ui.add(egui::Slider::new(&mut self.editor.brush.radius_mm, 1.0..=40.0).text("radius (mm on the skin)"));
        let mut microns = self.editor.brush.thickness_mm * 1000.0;
        if ui.add(egui::Slider::new(&mut microns, 0.0..=100.0).text("thickness (µm)")).changed() {
            self.editor.brush.thickness_mm = microns / 1000.0;
        }
        ui.add(egui::Slider::new(&mut self.editor.brush.flow, 0.01..=1.0).text("flow"));
        ui.add(egui::Slider::new(&mut self.editor.brush.hardness, 0.0..=1.0).text("hardness"));
        ui.checkbox(&mut self.editor.brush.mirror, "Mirror across the face's midplane");

        ui.separator();
        egui::CollapsingHeader::new("Project folder").default_open(false).show(ui, |ui| {
            ui.label("Typed path, for machines without a file dialog");
            ui.text_edit_singleline(&mut self.project_path);
            ui.horizontal(|ui| {
                let dir = PathBuf::from(self.project_path.trim());
                let has = !self.project_path.trim().is_empty();
                if ui.add_enabled(has, egui::Button::new("Open")).clicked() {
                    let r = self.open_project_from(&dir).map(|()| format!("opened {}", dir.display()));
                    self.report(r);
                }
                if ui.add_enabled(has, egui::Button::new("Save")).clicked() {
                    let r = self.save_project_to(&dir).map(|()| format!("saved {}", dir.display()));
                    self.report(r);
                }
            });
        });

        ui.separator();
        ui.heading("Light");
        let mut changed = ui.add(egui::Slider::new(&mut self.light_yaw, -180.0..=180.0).text("key yaw °")).changed();
        changed |= ui.add(egui::Slider::new(&mut self.light_pitch, -60.0..=85.0).text("key pitch °")).changed();
        changed |= ui.add(egui::Slider::new(&mut self.light_intensity, 0.0..=3.0).text("key intensity")).changed();
        changed |= ui.checkbox(&mut self.environment, "Environment").changed();
        if changed {
            self.needs_render = true;
        }
        if self.split {
            changed = ui.add(egui::Slider::new(&mut self.split_at, 0.0..=1.0).text("before | after")).changed();
            self.needs_render |= changed;
        }
    }
}
