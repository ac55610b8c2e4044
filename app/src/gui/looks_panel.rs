//! The looks library (left panel, under the layers): a thumbnail of each complete look of
//! [`crate::looks::LIBRARY`]; a click replaces the layers with the look's, as one undo step.

use super::*;
use crate::looks::{LIBRARY, LibraryLook};

impl RougeApp {
    pub(super) fn looks_panel(&mut self, ui: &mut egui::Ui) {
        egui::CollapsingHeader::new("Looks library").default_open(false).show(ui, |ui| {
            if self.look_thumbnails.is_empty() {
                self.look_thumbnails = LIBRARY.iter().filter_map(|l| thumbnail(ui.ctx(), l)).collect();
            }
            ui.label("Click a look to replace the layers with it (one undo step)");
            let mut chosen = None;
            ui.horizontal_wrapped(|ui| {
                for (i, look) in LIBRARY.iter().enumerate() {
                    let name = look.id.replace('_', " ");
                    let clicked = match self.look_thumbnails.get(i) {
                        Some(t) => ui
                            .add(egui::Button::image_and_text(
                                egui::Image::new((t.id(), Vec2::splat(96.0))),
                                name.as_str(),
                            ))
                            .clicked(),
                        None => ui.button(name.as_str()).clicked(),
                    };
                    if clicked {
                        chosen = Some(look);
                    }
                }
            });
            if let Some(look) = chosen {
                self.apply_library_look(look.id);
            }
        });
    }

    /// Replaces the layers with the library look `id` ([`crate::looks::LIBRARY`]), as one undo
    /// step; an unknown id or a look that does not load is reported in the status line.
    pub fn apply_library_look(&mut self, id: &str) {
        let look = LIBRARY.iter().find(|l| l.id == id).map(LibraryLook::look);
        match look {
            Some(Ok(look)) => {
                let c = self.editor.apply_look(&look);
                self.ui.rename_buffer =
                    self.editor.document().layers.last().map(|l| l.name.clone()).unwrap_or_default();
                self.apply_change(c);
                self.ui.message = Some((true, format!("applied the look “{}” (Ctrl+Z undoes it)", look.name)));
            }
            Some(Err(e)) => self.ui.message = Some((false, format!("{e:#}"))),
            None => self.ui.message = Some((false, format!("no look `{id}` in the library"))),
        }
    }
}

/// The look's embedded thumbnail as an egui texture; `None` if the PNG does not decode.
fn thumbnail(ctx: &egui::Context, look: &LibraryLook) -> Option<egui::TextureHandle> {
    let img = image::load_from_memory(look.thumbnail_png).ok()?.to_rgba8();
    let size = [img.width() as usize, img.height() as usize];
    let image = egui::ColorImage::from_rgba_unmultiplied(size, img.as_raw());
    Some(ctx.load_texture(format!("look {}", look.id), image, egui::TextureOptions::LINEAR))
}
