//! The right panel: the material library, measurement import with progress, and plots.

use super::*;

impl RougeApp {
    pub(super) fn materials_panel(&mut self, ui: &mut egui::Ui) {
        ui.heading("Materials");
        egui::ScrollArea::vertical().id_salt("library").max_height(180.0).show(ui, |ui| {
            for (i, m) in self.library.materials.iter().enumerate() {
                ui.horizontal(|ui| {
                    materials::swatch(ui, &m.preset, 14.0);
                    if ui.selectable_label(self.library.selected == i, &m.preset.name).clicked() {
                        self.library.selected = i;
                    }
                });
            }
        });
        ui.separator();
        ui.label("Import a measurement (R_inf, R, Rg)");
        ui.horizontal(|ui| {
            ui.text_edit_singleline(&mut self.library.import_path);
            if ui.button("Browse…").clicked()
                && let Some(files) = rfd::FileDialog::new().pick_files()
            {
                let paths: Vec<String> = files.iter().map(|p| p.display().to_string()).collect();
                self.library.import_path = paths.join("; ");
            }
        });
        ui.add(
            egui::Slider::new(&mut self.library.import_thickness_mm, 0.001..=0.5)
                .text("thin layer (mm), if the file has none"),
        );
        ui.checkbox(&mut self.library.import_extrapolate, "extrapolate to 380-780 nm");
        ui.horizontal(|ui| {
            let can = !self.library.busy() && !self.library.import_path.trim().is_empty();
            if ui.add_enabled(can, egui::Button::new("Import")).clicked() {
                let paths: Vec<PathBuf> = self
                    .library
                    .import_path
                    .split(';')
                    .map(str::trim)
                    .filter(|p| !p.is_empty())
                    .map(PathBuf::from)
                    .collect();
                self.library.start_import(paths);
            }
            if self.library.busy() {
                let (done, total) = self.library.progress();
                ui.spinner();
                ui.add(
                    egui::ProgressBar::new(done as f32 / total.max(1) as f32).text(format!("importing {done}/{total}")),
                );
            }
        });
        if let Some((ok, msg)) = &self.library.last_message {
            ui.colored_label(if *ok { Color32::LIGHT_GREEN } else { Color32::LIGHT_RED }, msg);
        }
        ui.separator();
        if let Some(m) = self.library.materials.get(self.library.selected) {
            egui::ScrollArea::vertical().id_salt("plots").show(ui, |ui| materials::plots(ui, m));
        }
    }
}
