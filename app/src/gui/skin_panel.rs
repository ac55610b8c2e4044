//! The "Skin" panel: the document's skin maps (docs/SKIN.md, "The app's Skin panel"). A tone
//! (the named tones, an ITA° between them, or a measured spectrum fitted on import), the
//! conditions, the seed and the map size make a [`SkinRecipe`]; a change generates the maps on a
//! worker and puts them in the document as one undo step (the skin edits carried over); "No
//! skin maps" goes back to the flat skin. The blood switch and the skin brushes (more or less
//! melanin or blood, a spot) are here too; the brushes take the Brush panel's radius, falloff
//! and mirror.

use super::*;
use rouge_measure::analysis::skin::read_sampled_skins;
use rouge_measure::skin::fit::{FitOptions, SkinFitter, lab_d65};
use rouge_measure::skin::{SkinParams, ita_deg, skin_at_ita, skin_tones};
use rouge_model::skin::{Condition, ProjectSkin, SkinBrush, SkinBrushKind, SkinConditions, SkinRecipe};

/// Where the skin's base parameters come from.
#[derive(Clone, Debug, PartialEq)]
enum ToneChoice {
    /// No skin maps: the flat skin.
    Flat,
    /// A built-in tone by name.
    Named(String),
    /// Between the tones at an ITA°.
    Ita,
    /// Fitted to a measured spectrum, or any other base a project brought.
    Custom(SkinParams),
}

/// The panel's own state.
#[derive(Debug)]
pub(super) struct SkinPanel {
    tone: ToneChoice,
    ita_deg: f64,
    conditions: SkinConditions,
    seed: u64,
    size_px: u32,
    /// The typed measured-spectrum file.
    spectrum_path: String,
    /// The document's recipe the panel last showed.
    synced: Option<SkinRecipe>,
    /// The skin brush's settings while it is off.
    brush: SkinBrush,
}

impl Default for SkinPanel {
    fn default() -> Self {
        SkinPanel {
            tone: ToneChoice::Flat,
            ita_deg: 28.0,
            conditions: SkinConditions::default(),
            seed: 1,
            size_px: DEFAULT_SKIN_PX,
            spectrum_path: String::new(),
            synced: None,
            brush: SkinBrush::default(),
        }
    }
}

/// The app's skin maps' default size, texels a side: as `rouge render --skin-map-px` (half a
/// millimetre a texel on the default head; the 2048² skin edits are read at it).
pub const DEFAULT_SKIN_PX: u32 = 1024;
/// The sizes offered.
const SIZES_PX: [u32; 3] = [512, 1024, 2048];

impl SkinPanel {
    /// The recipe the panel's settings make; `None` for the flat skin.
    fn recipe(&self) -> Result<Option<SkinRecipe>, String> {
        let (tone, base) = match &self.tone {
            ToneChoice::Flat => return Ok(None),
            ToneChoice::Named(name) => {
                return SkinRecipe::from_tone(name, self.conditions, self.seed, self.size_px)
                    .map(Some)
                    .map_err(|e| e.to_string());
            }
            ToneChoice::Ita => (None, skin_at_ita(self.ita_deg).map_err(|e| e.to_string())?),
            ToneChoice::Custom(p) => (None, *p),
        };
        Ok(Some(SkinRecipe { tone, base, conditions: self.conditions, seed: self.seed, size_px: self.size_px }))
    }

    /// Takes the document's recipe (a project opened, an undo) into the settings.
    fn adopt(&mut self, recipe: Option<&SkinRecipe>) {
        self.synced = recipe.cloned();
        let Some(r) = recipe else {
            self.tone = ToneChoice::Flat;
            return;
        };
        let ita_base = (self.tone == ToneChoice::Ita).then(|| skin_at_ita(self.ita_deg).ok()).flatten();
        self.tone = match &r.tone {
            Some(name) => ToneChoice::Named(name.clone()),
            None if ita_base == Some(r.base) => ToneChoice::Ita,
            None => ToneChoice::Custom(r.base),
        };
        self.conditions = r.conditions;
        self.seed = r.seed;
        self.size_px = r.size_px;
    }
}

/// The ITA° of the skin `p` (D65, CIE 1931); NaN-free: 0 when the model cannot say.
fn ita_of(p: &SkinParams) -> f64 {
    p.reflectance().map_or(0.0, |r| ita_deg(&lab_d65(&r)))
}

impl RougeApp {
    /// Makes the document's skin maps from `recipe` on a worker (one undo step when they are
    /// ready; [`RougeApp::wait_skin`] waits), or with `None` goes back to the flat skin now.
    pub fn set_skin_recipe(&mut self, recipe: Option<SkinRecipe>) {
        let Some(recipe) = recipe else {
            let c = self.editor.set_skin(None);
            self.apply_change(c);
            self.skin_panel.adopt(None);
            return;
        };
        let what = match &recipe.tone {
            Some(t) => format!("{t}, {}², seed {}", recipe.size_px, recipe.seed),
            None => format!("ITA {:.1}°, {}², seed {}", ita_of(&recipe.base), recipe.size_px, recipe.seed),
        };
        self.skin_panel.adopt(Some(&recipe));
        self.start_skin_job(what, move || ProjectSkin::generate(recipe).map_err(|e| e.to_string()));
    }

    /// Fits the first spectrum of the measurement file `path` (CSV, CGATS, .sp: what `rouge skin
    /// fit` reads) with the skin model and makes skin maps of that skin (with the panel's
    /// conditions, seed and size) on a worker. Errors, shown in the status line, name the file.
    pub fn load_skin_spectrum(&mut self, path: &Path) {
        let (conditions, seed, size_px) = (self.skin_panel.conditions, self.skin_panel.seed, self.skin_panel.size_px);
        let file = path.to_owned();
        let what = format!("fitted to {}", file.display());
        self.start_skin_job(what, move || {
            let named = |e: &dyn std::fmt::Display| format!("{}: {e}", file.display());
            let skins = read_sampled_skins(&file).map_err(|e| e.to_string())?;
            let (name, spectrum) = skins.first().ok_or_else(|| named(&"no spectra"))?;
            let fitter = SkinFitter::new(FitOptions::default()).map_err(|e| named(&e))?;
            let fit = fitter
                .fit(spectrum.wavelengths_nm(), spectrum.values())
                .map_err(|e| named(&format!("spectrum `{name}`: {e}")))?;
            let recipe = SkinRecipe { tone: None, base: fit.params, conditions, seed, size_px };
            ProjectSkin::generate(recipe).map_err(|e| e.to_string())
        });
    }

    /// Paints the skin with `brush` (`Some`) or the active layer (`None`).
    pub fn set_skin_brush(&mut self, brush: Option<SkinBrush>) {
        if let Some(b) = brush {
            self.skin_panel.brush = b;
        }
        self.editor.skin_brush = brush;
    }

    fn start_skin_job(&mut self, what: String, job: impl FnOnce() -> Result<ProjectSkin, String> + Send + 'static) {
        let rx = super::session::spawn_job(format!("making the skin maps ({what})"), job);
        // A newer wish replaces one still running (its answer is dropped).
        self.skin.generating = Some((what, rx));
    }

    /// The panel.
    pub(super) fn skin_panel_ui(&mut self, ui: &mut egui::Ui) {
        let doc_recipe = self.editor.document().skin.as_ref().map(|s| s.recipe.clone());
        if self.skin.generating.is_none() && doc_recipe != self.skin_panel.synced {
            self.skin_panel.adopt(doc_recipe.as_ref());
        }
        egui::CollapsingHeader::new("Skin").default_open(true).show(ui, |ui| {
            let mut apply = false;
            let mut load: Option<PathBuf> = None;
            let p = &mut self.skin_panel;
            let label = match &p.tone {
                ToneChoice::Flat => "No skin maps (flat skin)".to_string(),
                ToneChoice::Named(n) => n.clone(),
                ToneChoice::Ita => format!("ITA {:.0}°", p.ita_deg),
                ToneChoice::Custom(b) => format!("measured (ITA {:.1}°)", ita_of(b)),
            };
            egui::ComboBox::from_label("Tone").selected_text(label).show_ui(ui, |ui| {
                apply |= ui.selectable_value(&mut p.tone, ToneChoice::Flat, "No skin maps (flat skin)").clicked();
                for t in skin_tones() {
                    let text = format!("{} (Fitzpatrick {})", t.name, t.fitzpatrick);
                    apply |= ui.selectable_value(&mut p.tone, ToneChoice::Named(t.name.clone()), text).clicked();
                }
                apply |= ui.selectable_value(&mut p.tone, ToneChoice::Ita, "ITA° slider").clicked();
            });
            if p.tone == ToneChoice::Ita {
                let r = ui.add(egui::Slider::new(&mut p.ita_deg, -60.0..=60.0).text("ITA°"));
                apply |= r.drag_stopped() || (r.changed() && !r.dragged());
            }
            ui.horizontal(|ui| {
                ui.add(egui::TextEdit::singleline(&mut p.spectrum_path).hint_text("measured spectrum file").desired_width(150.0));
                if ui.button("Load measured spectrum…").on_hover_text("Fit the skin model to a measured reflectance (CSV, CGATS, .sp); empty field: choose a file").clicked() {
                    let chosen = if p.spectrum_path.trim().is_empty() {
                        rfd::FileDialog::new().pick_file().map(|f| f.display().to_string())
                    } else {
                        Some(p.spectrum_path.trim().to_string())
                    };
                    if let Some(f) = chosen {
                        load = Some(PathBuf::from(&f));
                        p.spectrum_path = f;
                    }
                }
            });
            ui.label("Conditions");
            for c in Condition::ALL {
                let mut a = p.conditions.get(c);
                let r = ui.add(egui::Slider::new(&mut a, 0.0..=1.0).text(c.key()));
                if r.changed() && p.conditions.set(c, a).is_ok() {
                    apply |= !r.dragged();
                }
                apply |= r.drag_stopped();
            }
            ui.horizontal(|ui| {
                ui.label("Seed");
                let r = ui.add(egui::DragValue::new(&mut p.seed));
                apply |= r.drag_stopped() || (r.changed() && !r.dragged());
                egui::ComboBox::from_label("texels").selected_text(format!("{}²", p.size_px)).show_ui(ui, |ui| {
                    for s in SIZES_PX {
                        apply |= ui.selectable_value(&mut p.size_px, s, format!("{s}²")).clicked();
                    }
                });
            });
            if let Some((what, _)) = &self.skin.generating {
                ui.horizontal(|ui| {
                    ui.spinner();
                    ui.label(format!("generating: {what}"));
                });
            } else if self.skin.bake_running() {
                ui.horizontal(|ui| {
                    ui.spinner();
                    ui.label("baking the skin's colour");
                });
            } else if let Some((px, bake_ms, table_ms)) = self.skin.last_bake {
                ui.weak(format!("colour of {px}² baked in {bake_ms:.0} ms (+ table {table_ms:.0} ms)"));
            }
            let mut follows = self.skin.blood_follows;
            if ui
                .checkbox(&mut follows, "Blood follows expression")
                .on_hover_text("A smile flushes the cheeks, pressed lips blanch (Animate plays it)")
                .changed()
            {
                self.set_blood_follows(follows);
            }
            ui.separator();
            let mut on = self.editor.skin_brush.is_some();
            let mut brush = self.skin_panel.brush;
            let mut changed = ui.checkbox(&mut on, "Paint the skin").on_hover_text("Strokes change the skin itself, apart from the makeup layers (radius, falloff, mirror: the Brush panel)").changed();
            ui.horizontal_wrapped(|ui| {
                for k in SkinBrushKind::ALL {
                    changed |= ui.selectable_value(&mut brush.kind, k, k.label()).clicked();
                }
            });
            changed |= ui.add(egui::Slider::new(&mut brush.factor, 1.05..=4.0).text("× factor")).changed();
            if changed {
                self.set_skin_brush(on.then_some(brush));
                self.skin_panel.brush = brush;
            }
            if let Some(path) = load {
                self.load_skin_spectrum(&path);
            }
            if apply {
                match self.skin_panel.recipe() {
                    Ok(r) if r != doc_recipe => self.set_skin_recipe(r),
                    Ok(_) => {}
                    Err(e) => self.ui.message = Some((false, format!("skin maps: {e}"))),
                }
            }
        });
    }
}
