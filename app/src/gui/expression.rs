//! The "Expression" panel: the presets (smile, surprise, blink, talk) and the 52 Face Units as
//! sliders, "Neutral", and the animation toggle that plays the expression cycle.

use super::face::weight_slider;
use super::*;
use rouge_model::mesh::targets::{EXPRESSION_PRESETS, FacePose, TargetSet};

impl RougeApp {
    pub(super) fn expression_panel(&mut self, ui: &mut egui::Ui) {
        let Ok(targets) = TargetSet::default_head() else { return };
        egui::CollapsingHeader::new("Expression").default_open(false).show(ui, |ui| {
            if !self.face.on_default_head {
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
                changed |= weight_slider(ui, &mut expression, p.name, (0.0, 1.0));
            }
            egui::CollapsingHeader::new("Face Units").default_open(false).show(ui, |ui| {
                for (name, _) in &targets.expressions {
                    changed |= weight_slider(ui, &mut expression, name, (0.0, 1.0));
                }
            });
            if changed {
                self.edit_face(FacePose { expression, ..self.face().clone() });
            }
        });
    }
}
