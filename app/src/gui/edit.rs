//! Document → renderer: what each edit changed is uploaded (every layer, or one rectangle of
//! one map); strokes go through the editor core ([`crate::editor::Editor`]).

use super::*;

impl RougeApp {
    /// Uploads the layers the editor renders (every visible layer, or the active one in the
    /// solo view) after a layer edit, a new document or a new mesh.
    pub(super) fn sync_layers(&mut self) {
        let layers = &self.editor.document().layers;
        let inputs: Vec<LayerInput<'_>> = self
            .editor
            .render_layers()
            .into_iter()
            .map(|i| &layers[i])
            .map(|l| LayerInput { preset: &l.preset, map: &l.map, multiplier: l.multiplier })
            .collect();
        if let Err(e) = self.gpu.renderer.set_layers(&inputs) {
            self.ui.message = Some((false, e.to_string()));
        }
        self.view.needs_render = true;
    }

    /// Uploads what an edit changed: every layer, or one rectangle of one map.
    pub(super) fn apply_change(&mut self, change: Change) {
        match change {
            Change::Nothing => {}
            Change::Layers => self.sync_layers(),
            Change::Map { layer, rect } => {
                if let (Some(ri), Some(l)) = (self.editor.render_index(layer), self.editor.document().layers.get(layer))
                    && let Err(e) = self.gpu.renderer.update_thickness(ri, &l.map, l.multiplier, rect)
                {
                    self.ui.message = Some((false, e.to_string()));
                }
                self.view.needs_render = true;
            }
            Change::Skin { rect: None } => self.request_skin_bake(),
            Change::Skin { rect: Some(rect) } => self.skin_edits_changed(rect),
            Change::Hair => {
                let pose = self.face().clone();
                self.show_pose(&pose);
            }
        }
    }

    pub(super) fn apply_changes(&mut self, changes: Vec<Change>) {
        for change in changes {
            self.apply_change(change);
        }
    }

    /// Moves the brush of the open stroke to the surface point `world`.
    pub(super) fn paint_at(&mut self, world: Vec3) {
        match self.editor.stroke_to(world) {
            Ok(changes) => self.apply_changes(changes),
            Err(e) => self.ui.message = Some((false, e.to_string())),
        }
    }

    pub(super) fn begin_stroke(&mut self) {
        self.refresh_surface();
        self.editor.begin_stroke();
    }

    pub(super) fn end_stroke(&mut self) {
        let changes = self.editor.end_stroke();
        self.apply_changes(changes);
    }
}
