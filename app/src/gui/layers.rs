//! The layers panel (top of the left panel): visibility, lock, order, duplicate, remove, rename, clear,
//! thickness multiplier, finish and material of each layer, and adding a layer of the selected
//! material.

use super::*;

// The layer row's buttons are icons (egui's bundled emoji-icon font), so the name gets the room.
/// Lock toggle, unlocked.
pub const UNLOCKED: &str = "🔓";
/// Lock toggle, locked.
pub const LOCKED: &str = "🔒";
/// Move the layer up.
pub const UP: &str = "⏶";
/// Move the layer down.
pub const DOWN: &str = "⏷";
/// Duplicate the layer.
pub const DUPLICATE: &str = "🗐";
/// Remove the layer.
pub const REMOVE: &str = "🗑";

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
                let mut locked = l.locked;
                if ui
                    .toggle_value(&mut locked, if l.locked { LOCKED } else { UNLOCKED })
                    .on_hover_text("locked: paint, fill and clear are refused (one undo step)")
                    .changed()
                {
                    action = Some(Box::new(move |d: &mut Document| d.set_locked(i, locked)));
                }
                materials::swatch(ui, &l.preset, 14.0);
                // The buttons from the right edge, the name in what is left, cut short with "…"
                // (whole on hover): a long name once widened the panel over the viewport.
                ui.with_layout(egui::Layout::right_to_left(egui::Align::Center), |ui| {
                    if ui.small_button(REMOVE).on_hover_text("remove").clicked() {
                        action = Some(Box::new(move |d: &mut Document| d.remove_layer(i)));
                    }
                    if ui.small_button(DUPLICATE).on_hover_text("duplicate above (one undo step)").clicked() {
                        action = Some(Box::new(move |d: &mut Document| d.duplicate_layer(i)));
                    }
                    if ui.small_button(DOWN).on_hover_text("move down").clicked() && i > 0 {
                        action = Some(Box::new(move |d: &mut Document| d.move_layer(i, i - 1)));
                    }
                    if ui.small_button(UP).on_hover_text("move up").clicked() && i + 1 < n {
                        action = Some(Box::new(move |d: &mut Document| d.move_layer(i, i + 1)));
                    }
                    let name = egui::Button::selectable(active == i, l.name.as_str()).truncate();
                    if ui.add(name).on_hover_text(l.name.as_str()).clicked() {
                        select = Some(i);
                    }
                });
            });
        }
        if let Some(i) = select {
            self.set_active_layer(i);
            self.ui.rename_buffer = self.editor.document().layers[i].name.clone();
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
                ui.text_edit_singleline(&mut self.ui.rename_buffer);
                if ui.button("Rename").clicked() && !self.ui.rename_buffer.trim().is_empty() {
                    let name = self.ui.rename_buffer.trim().to_string();
                    self.rename_layer(i, &name);
                }
            });
            if ui.button("Clear layer").on_hover_text("set the whole map to 0 mm (one undo step)").clicked() {
                self.clear_layer(i);
            }
            let mut m = multiplier;
            let slider = egui::Slider::new(&mut m, 0.0..=4.0).text("thickness multiplier (×)");
            if ui
                .add(slider)
                .on_hover_text(
                    "scales the layer's painted thickness (mm) for rendering: not an opacity, the Kubelka-Munk \
                     layer simply gets thicker or thinner",
                )
                .drag_stopped()
            {
                let c = self.editor.edit(|d| d.set_multiplier(i, m));
                self.apply_change(c);
            }
            self.finish_choice(ui, i);
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
    }

    /// The active layer's finish (`rouge_measure::finish`): none (a clear film, as presets
    /// without a finish render) or a named one, as one undo step; the gloss a meter would read
    /// of its lobe on hover.
    fn finish_choice(&mut self, ui: &mut egui::Ui, i: usize) {
        use rouge_measure::finish::{FinishKind, GlossGeometry, gloss_units};
        let Some((preset_ref, preset)) =
            self.editor.document().layers.get(i).map(|l| (l.preset_ref.clone(), l.preset.clone()))
        else {
            return;
        };
        let current = preset.finish.map(|f| f.kind);
        let mut chosen = current;
        let gloss = GlossGeometry::ALL.map(|g| gloss_units(preset.specular, g));
        egui::ComboBox::from_label("finish")
            .selected_text(current.map_or("none", FinishKind::name))
            .show_ui(ui, |ui| {
                ui.selectable_value(&mut chosen, None, "none");
                for k in FinishKind::ALL {
                    ui.selectable_value(&mut chosen, Some(k), k.name());
                }
            })
            .response
            .on_hover_text(format!(
                "matte to gloss: the layer's specular lobe, how much of the shine below it passes, how much it \
                 fills the skin's pores (docs/FINISHES.md). Now {:.1} GU at 20°, {:.1} at 60°, {:.1} at 85°",
                gloss[0], gloss[1], gloss[2]
            ));
        if chosen != current {
            let mut finished = preset;
            finished.set_finish(chosen.map(FinishKind::defaults));
            let c = self.editor.edit(|d| d.set_preset(i, &preset_ref, finished));
            self.apply_change(c);
        }
    }
}
