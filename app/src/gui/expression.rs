//! The "Expression" panel: the presets (smile, surprise, blink, talk) and the 51 Face Units as
//! sliders, "Neutral", and the animation toggle that plays the expression cycle.

use super::face::set_weight;
use super::*;
use rouge_model::mesh::targets::{EXPRESSION_PRESETS, FacePose, TargetSet};

impl RougeApp {
    pub(super) fn expression_panel(&mut self, ui: &mut egui::Ui) {
        let Ok(targets) = TargetSet::default_head() else { return };
        egui::CollapsingHeader::new("Expression").default_open(false).show(ui, |ui| {
            if self.options.mesh.is_some() {
                ui.label("Expressions move the default head only.");
                return;
            }
            let mut animate = self.face.animate;
            if ui.checkbox(&mut animate, "Animate (neutral, smile, blink, talk, surprise)").changed() {
                self.set_animation(animate);
            }
            let mut expression = self.face().expression.clone();
            let mut changed = ui.button("Neutral").clicked() && !expression.is_empty();
            if changed {
                expression.clear();
            }
            for p in EXPRESSION_PRESETS.iter().filter(|p| !p.units.is_empty()) {
                let mut w = expression.get(p.name).copied().unwrap_or(0.0);
                if ui.add(egui::Slider::new(&mut w, 0.0..=1.0).text(p.name)).changed() {
                    set_weight(&mut expression, p.name, w);
                    changed = true;
                }
            }
            egui::CollapsingHeader::new("Face Units").default_open(false).show(ui, |ui| {
                for (name, _) in &targets.expressions {
                    let mut w = expression.get(name).copied().unwrap_or(0.0);
                    if ui.add(egui::Slider::new(&mut w, 0.0..=1.0).text(name)).changed() {
                        set_weight(&mut expression, name, w);
                        changed = true;
                    }
                }
            });
            if changed {
                let pose = FacePose { expression, ..self.face().clone() };
                self.editor.document_mut().face = pose.clone();
                if !self.face.animate {
                    self.show_pose(&pose);
                }
            }
        });
    }
}
