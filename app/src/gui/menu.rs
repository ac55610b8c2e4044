//! The menu bar (File, Edit, View) and keyboard shortcuts.

use super::*;

impl RougeApp {
    pub(super) fn shortcuts(&mut self, ctx: &egui::Context) {
        let typing = ctx.egui_wants_keyboard_input();
        let (redo, undo, reset, radius) = ctx.input_mut(|i| {
            (
                i.consume_key(Modifiers::COMMAND | Modifiers::SHIFT, Key::Z),
                i.consume_key(Modifiers::COMMAND, Key::Z),
                i.consume_key(Modifiers::NONE, Key::Home),
                !typing && i.consume_key(Modifiers::NONE, Key::F),
            )
        });
        if redo {
            self.redo();
        } else if undo {
            self.undo();
        }
        if reset {
            self.view.reset_orbit();
        }
        if radius {
            self.start_radius_drag(ctx);
        }
    }

    pub(super) fn menu(&mut self, ui: &mut egui::Ui) {
        egui::MenuBar::new().ui(ui, |ui| {
            ui.menu_button("File", |ui| {
                if ui.button("New project (default look)").clicked() {
                    self.adopt_document(Document::default_project(), None);
                }
                if ui.button("Open project…").clicked()
                    && let Some(dir) = self.pick_folder_or_explain("Open project")
                {
                    self.open_project_or_say(&dir);
                }
                if ui.button("Save project").clicked()
                    && let Some(dir) =
                        self.options.project.clone().or_else(|| self.pick_folder_or_explain("Save project"))
                {
                    let r = self.save_project_to(&dir).map(|()| format!("saved {}", dir.display()));
                    self.report(r);
                }
                if ui.button("Save project as…").clicked()
                    && let Some(dir) = self.pick_folder_or_explain("Save project as")
                {
                    let r = self.save_project_to(&dir).map(|()| format!("saved {}", dir.display()));
                    self.report(r);
                }
                ui.separator();
                if ui.button("Open mesh… (.obj, .gltf, .glb)").clicked()
                    && let Some(p) = rfd::FileDialog::new().add_filter("mesh", &["obj", "gltf", "glb"]).pick_file()
                {
                    let scale = if p.extension().is_some_and(|e| e == "glb" || e == "gltf") { 25.0 } else { 1.0 };
                    self.start_mesh(Some(p), scale);
                }
                if ui.button("Default head").clicked() {
                    self.start_mesh(None, 1.0);
                }
                ui.separator();
                if ui.button("Export maps (EXR + 16-bit PNG)…").clicked()
                    && let Some(dir) = rfd::FileDialog::new().pick_folder()
                {
                    let r = self
                        .editor
                        .document()
                        .export_maps(&dir)
                        .map(|files| format!("exported {} files to {}", files.len(), dir.display()));
                    self.report(r.map_err(anyhow::Error::from));
                }
                if ui.button("Export active layer's preset…").clicked()
                    && let Some(p) = rfd::FileDialog::new().add_filter("preset", &["json"]).save_file()
                {
                    let r = self
                        .editor
                        .document()
                        .export_preset(self.editor.active(), &p)
                        .map(|()| format!("wrote {}", p.display()));
                    self.report(r.map_err(anyhow::Error::from));
                }
                if ui.button("Screenshot (PNG)…").clicked()
                    && let Some(p) = rfd::FileDialog::new().add_filter("PNG", &["png"]).save_file()
                {
                    let size = if self.gpu.frame_size.0 > 0 { self.gpu.frame_size } else { (1280, 720) };
                    let r = self.screenshot(&p, size).map(|()| format!("wrote {}", p.display()));
                    self.report(r);
                }
            });
            ui.menu_button("Edit", |ui| {
                if ui.add_enabled(self.editor.document().can_undo(), egui::Button::new("Undo (Ctrl+Z)")).clicked() {
                    self.undo();
                }
                if ui.add_enabled(self.editor.document().can_redo(), egui::Button::new("Redo (Ctrl+Shift+Z)")).clicked()
                {
                    self.redo();
                }
            });
            ui.menu_button("View", |ui| {
                if ui.button("Reset view (Home)").clicked() {
                    self.view.reset_orbit();
                }
                ui.menu_button("Close-up", |ui| {
                    for region in AnatomyRegion::ALL {
                        if ui.button(region.name().replace('_', " ")).clicked() {
                            self.view_close_up(region);
                        }
                    }
                });
                self.views_menu(ui);
                if ui.checkbox(&mut self.view.split, "Before / after split").changed() {
                    self.view.needs_render = true;
                }
                if ui.checkbox(&mut self.view.environment, "Environment light").changed() {
                    self.view.needs_render = true;
                }
                use rouge_render::aa::{EdgeAa, EdgeCoverage};
                ui.label("Antialiasing");
                let current = self.gpu.renderer.edge_aa();
                for (aa, name) in [
                    (EdgeAa::Off, "None"),
                    (EdgeAa::Unsorted(EdgeCoverage::TwoSided), "Edges"),
                    (EdgeAa::Sorted(EdgeCoverage::TwoSided), "Edges, sorted"),
                ] {
                    if ui.radio(current == aa, name).clicked() {
                        self.gpu.set_edge_aa(aa);
                        self.view.needs_render = true;
                    }
                }
                ui.separator();
                self.frame_stats_menu(ui);
            });
            ui.separator();
            let modified = if self.editor.document().is_modified() { " •" } else { "" };
            ui.label(format!("{}{modified} — {}", self.editor.document().name, self.ui.mesh_name));
        });
    }

    pub(super) fn report(&mut self, r: Result<String>) {
        self.ui.message = Some(match r {
            Ok(m) => (true, m),
            Err(e) => (false, format!("{e:#}")),
        });
    }
}
