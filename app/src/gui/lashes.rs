//! The "Lashes and brows" panel: a mascara on the default head's lashes ([`Mascara`]: length,
//! volume, curl, colour), shown live while a slider is dragged and kept as one undo step when the
//! drag ends (or at once for a click or a key), and a tinted brow gel on its brows ([`BrowGel`]:
//! colour, strength; one undo step per change); both saved with the project's `look.json`.

use super::*;
use rouge_model::mesh::brow_gel::BrowGel;
use rouge_model::mesh::lashes::Mascara;

/// What the Mascara switch puts on natural lashes: a lengthening, volumising mascara with a
/// little curl, inside every range and visible at the default framing.
const DEFAULT_MASCARA: Mascara = Mascara { length: 1.3, volume: 2.5, curl_deg: 15.0, color: None };

/// What the Brow gel switch puts on natural brows: a brown tint over most of the hairs.
const DEFAULT_BROW_GEL: BrowGel = BrowGel { color: [0.045, 0.027, 0.016], strength: 0.8, fill: 0.0 };

impl RougeApp {
    /// The mascara panel (under the Face panel).
    pub(super) fn lashes_panel(&mut self, ui: &mut egui::Ui) {
        egui::CollapsingHeader::new("Lashes and brows").default_open(false).show(ui, |ui| {
            if !self.face.on_default_head {
                ui.label("Mascara and brow gel coat the default head's lashes and brows only.");
                return;
            }
            self.brow_gel_controls(ui);
            let saved = self.editor.document().mascara;
            let mut on = saved.is_some();
            if ui
                .checkbox(&mut on, "Mascara")
                .on_hover_text("natural lashes, or a mascara that lengthens, thickens and curls them")
                .changed()
            {
                self.face.mascara_preview = None;
                self.commit_mascara(on.then_some(DEFAULT_MASCARA));
            }
            let Some(mut m) = self.face.mascara_preview.or(saved) else { return };
            let sliders = [
                (&mut m.length, Mascara::LENGTH, "length (× natural)", "how much longer the lashes look"),
                (&mut m.volume, Mascara::VOLUME, "volume (× natural)", "how much thicker each lash is coated"),
                (&mut m.curl_deg, Mascara::CURL_DEG, "curl (°)", "extra turn of the tips away from the eye"),
            ];
            let mut commit = false;
            let mut preview = false;
            let shades = [
                (None, "natural"),
                (Mascara::named_color("black"), "black"),
                (Mascara::named_color("brown"), "brown"),
                (Mascara::named_color("blue"), "blue"),
            ];
            let current = shades.iter().find(|(c, _)| *c == m.color).map_or("custom", |(_, n)| n);
            egui::ComboBox::from_label("colour").selected_text(current).show_ui(ui, |ui| {
                for (c, name) in shades {
                    commit |= ui.selectable_value(&mut m.color, c, name).changed();
                }
            });
            for (value, (lo, hi), text, hover) in sliders {
                let r = ui.add(egui::Slider::new(value, lo..=hi).text(text)).on_hover_text(hover);
                preview |= r.dragged() && r.changed();
                commit |= r.drag_stopped() || (r.changed() && !r.dragged());
            }
            if commit {
                self.face.mascara_preview = None;
                self.commit_mascara(Some(m));
            } else if preview {
                self.face.mascara_preview = Some(m);
                let pose = self.face().clone();
                self.show_pose(&pose);
            }
        });
    }

    /// The brow gel's switch, shade, strength and fill (each change one undo step).
    fn brow_gel_controls(&mut self, ui: &mut egui::Ui) {
        let saved = self.editor.document().brow_gel;
        let mut on = saved.is_some();
        if ui
            .checkbox(&mut on, "Brow gel")
            .on_hover_text("natural brows, or a tinted gel that colours the hairs")
            .changed()
        {
            self.commit_brow_gel(on.then_some(DEFAULT_BROW_GEL));
        }
        let Some(mut g) = saved else { return };
        let mut commit = false;
        let shades = ["brown", "black"].map(|n| (Mascara::named_color(n).unwrap_or(DEFAULT_BROW_GEL.color), n));
        let current = shades.iter().find(|(c, _)| *c == g.color).map_or("custom", |(_, n)| n);
        egui::ComboBox::from_label("gel colour").selected_text(current).show_ui(ui, |ui| {
            for (c, name) in shades {
                commit |= ui.selectable_value(&mut g.color, c, name).changed();
            }
        });
        let r = ui
            .add(egui::Slider::new(&mut g.strength, 0.0..=1.0).text("gel strength"))
            .on_hover_text("the part of the brow hairs the gel coats");
        commit |= r.drag_stopped() || (r.changed() && !r.dragged());
        let r = ui
            .add(egui::Slider::new(&mut g.fill, 0.0..=1.0).text("brow fill"))
            .on_hover_text("a fibre gel's extra hairs, as a fraction of the brow's own: most where the brow is sparse");
        commit |= r.drag_stopped() || (r.changed() && !r.dragged());
        if commit {
            self.commit_brow_gel(Some(g));
        }
        ui.separator();
    }

    /// Puts `brow_gel` into the document (one undo step) and onto the viewport's brows.
    pub fn commit_brow_gel(&mut self, brow_gel: Option<BrowGel>) {
        match self.editor.document_mut().set_brow_gel(brow_gel) {
            Ok(c) => self.apply_change(c),
            Err(e) => self.ui.message = Some((false, e.to_string())),
        }
    }

    /// Puts `mascara` into the document (one undo step) and onto the viewport's lashes.
    pub fn commit_mascara(&mut self, mascara: Option<Mascara>) {
        match self.editor.document_mut().set_mascara(mascara) {
            Ok(c) => self.apply_change(c),
            Err(e) => self.ui.message = Some((false, e.to_string())),
        }
    }
}
