//! The material library (built-in presets, user presets, imports) and its panel: list, import
//! from a measurement file in the background, plots of the selected material.

use crate::material_plots::Panel;
use egui_plot::{Line, Plot};
use rouge_measure::import::{self, ImportOptions};
use rouge_measure::layer_table::layer_spectra;
use rouge_measure::preset::{ImportReport, Preset};
use rouge_measure::{Extrapolation, Kind};
use std::path::{Path, PathBuf};
use std::sync::mpsc;

/// Where a material came from.
#[derive(Clone, Debug, PartialEq)]
pub enum Source {
    /// Embedded in the binary (data/presets).
    Builtin,
    /// A JSON file in the user's preset folder.
    User(PathBuf),
}

/// One material of the library.
#[derive(Clone, Debug)]
pub struct Material {
    /// How a look refers to it: `builtin:NAME` or a path.
    pub preset_ref: String,
    /// The preset.
    pub preset: Preset,
    /// Origin.
    pub source: Source,
    /// The import report, for materials imported in this session.
    pub report: Option<ImportReport>,
}

/// A finished import: the new material, or why it failed.
pub type ImportResult = Result<Material, String>;

/// The library and the state of its panel.
#[derive(Debug)]
pub struct Library {
    /// Every material, built-in first.
    pub materials: Vec<Material>,
    /// Index of the material shown in the plots.
    pub selected: usize,
    /// Folder of user presets (imports are saved there).
    pub user_dir: PathBuf,
    /// Thickness (mm) of the thin layer, for files that do not give it.
    pub import_thickness_mm: f64,
    /// Hold the ends constant for measurements that stop short of 380-780 nm.
    pub import_extrapolate: bool,
    /// Paths typed into the panel, separated by `;` (for machines without a file dialog).
    pub import_path: String,
    /// The running import, if any.
    pending: Option<mpsc::Receiver<ImportResult>>,
    /// Files done and files in the running import.
    progress: (usize, usize),
    /// Whether every file of the current import so far succeeded.
    last_message_ok: bool,
    /// Message of the last import (report or error).
    pub last_message: Option<(bool, String)>,
}

impl Library {
    /// The built-in presets plus every readable preset in `user_dir`.
    pub fn load(user_dir: PathBuf) -> Library {
        let mut materials: Vec<Material> = rouge_model::look::builtin_preset_names()
            .iter()
            .filter_map(|n| {
                rouge_model::look::builtin_preset(n).map(|preset| Material {
                    preset_ref: format!("builtin:{n}"),
                    preset,
                    source: Source::Builtin,
                    report: None,
                })
            })
            .collect();
        if let Ok(entries) = std::fs::read_dir(&user_dir) {
            let mut paths: Vec<PathBuf> = entries
                .filter_map(|e| e.ok().map(|e| e.path()))
                .filter(|p| p.extension().is_some_and(|x| x == "json"))
                .collect();
            paths.sort();
            for path in paths {
                if let Ok(preset) = Preset::load(&path) {
                    materials.push(Material {
                        preset_ref: path.display().to_string(),
                        preset,
                        source: Source::User(path),
                        report: None,
                    });
                }
            }
        }
        Library {
            materials,
            selected: 0,
            user_dir,
            import_thickness_mm: 0.02,
            import_extrapolate: false,
            import_path: String::new(),
            pending: None,
            progress: (0, 0),
            last_message_ok: true,
            last_message: None,
        }
    }

    /// Whether an import is running.
    pub fn busy(&self) -> bool {
        self.pending.is_some()
    }

    /// Files imported so far and files in the running import.
    pub fn progress(&self) -> (usize, usize) {
        self.progress
    }

    /// Starts importing `paths` one after the other on a background thread.
    pub fn start_import(&mut self, paths: Vec<PathBuf>) {
        let (tx, rx) = mpsc::channel();
        let user_dir = self.user_dir.clone();
        let thickness = self.import_thickness_mm;
        let extrapolate = self.import_extrapolate;
        self.progress = (0, paths.len());
        std::thread::spawn(move || {
            for path in paths {
                let what = format!("importing {}", path.display());
                let result =
                    crate::gui::session::caught(&what, || import_file(&path, thickness, extrapolate, &user_dir));
                if tx.send(result).is_err() {
                    return;
                }
            }
        });
        self.pending = Some(rx);
        self.last_message = None;
        self.last_message_ok = true;
    }

    /// Collects finished imports; returns true when something changed.
    pub fn poll(&mut self) -> bool {
        let Some(rx) = &self.pending else { return false };
        let mut changed = false;
        let mut messages: Vec<(bool, String)> = Vec::new();
        loop {
            match rx.try_recv() {
                Ok(result) => {
                    changed = true;
                    self.progress.0 += 1;
                    match result {
                        Ok(m) => {
                            messages.push((true, import_summary(&m)));
                            self.materials.push(m);
                            self.selected = self.materials.len() - 1;
                        }
                        Err(e) => messages.push((false, e)),
                    }
                }
                Err(mpsc::TryRecvError::Empty) => break,
                Err(mpsc::TryRecvError::Disconnected) => {
                    if self.progress.0 < self.progress.1 {
                        messages.push((false, "the import thread stopped unexpectedly".into()));
                    }
                    self.pending = None;
                    changed = true;
                    break;
                }
            }
        }
        if !messages.is_empty() {
            let mut all = self.last_message.take().map(|(_, m)| vec![m]).unwrap_or_default();
            let ok = messages.iter().all(|(ok, _)| *ok) && self.last_message_ok;
            all.extend(messages.into_iter().map(|(_, m)| m));
            self.last_message_ok = ok;
            self.last_message = Some((ok, all.join("\n")));
        }
        changed
    }

    /// Waits for a running import (tests).
    pub fn wait(&mut self) {
        while self.busy() {
            if !self.poll() {
                std::thread::sleep(std::time::Duration::from_millis(5));
            }
        }
    }
}

fn import_summary(m: &Material) -> String {
    let mut s = format!("Imported {} ({:?})", m.preset.name, m.preset.kind);
    if let Some(r) = &m.report {
        s.push_str(&format!(
            "\nR_inf {}; reconstruction ΔE2000: R {:.3}, R_inf {:.3}\nmax |R - R(S,K)| {:.2e} at {} nm",
            r.r_inf_srgb_hex, r.delta_e_2000_r, r.delta_e_2000_r_inf, r.max_abs_r_error.1, r.max_abs_r_error.0
        ));
    }
    if let Source::User(p) = &m.source {
        s.push_str(&format!("\nsaved as {}", p.display()));
    }
    s
}

/// Imports one measurement file into a preset saved in `user_dir`.
pub fn import_file(path: &Path, thickness_mm: f64, extrapolate: bool, user_dir: &Path) -> ImportResult {
    let m = import::read_measurement(path, &ImportOptions::default()).map_err(|e| e.to_string())?;
    let working = m
        .to_working_grid(if extrapolate { Extrapolation::Constant } else { Extrapolation::Refuse })
        .map_err(|e| format!("{}: {e}", path.display()))?;
    let thickness = m.thickness_mm.unwrap_or(thickness_mm);
    let kind = m.kind.unwrap_or(Kind::Other);
    let (preset, report) =
        Preset::from_measurement(&m, &working, &m.name, kind, thickness, None).map_err(|e| e.to_string())?;
    std::fs::create_dir_all(user_dir).map_err(|e| format!("{}: cannot create: {e}", user_dir.display()))?;
    let stem: String =
        preset.name.chars().map(|c| if c.is_ascii_alphanumeric() { c.to_ascii_lowercase() } else { '_' }).collect();
    let out = user_dir.join(format!("{stem}.json"));
    preset.save(&out).map_err(|e| e.to_string())?;
    Ok(Material { preset_ref: out.display().to_string(), preset, source: Source::User(out), report: Some(report) })
}

fn srgb_hex_to_color(hex: &str) -> egui::Color32 {
    color(crate::material_plots::hex_rgb(hex).unwrap_or([128; 3]))
}

/// Colour swatch of a preset's R∞.
pub fn swatch(ui: &mut egui::Ui, preset: &Preset, size: f32) -> egui::Response {
    let (rect, response) = ui.allocate_exact_size(egui::vec2(size, size), egui::Sense::hover());
    ui.painter().rect_filled(rect, 3.0, srgb_hex_to_color(&preset.derived.r_inf_srgb_hex));
    response
}

/// Plots of the selected material: measured R∞, R, Rg (when the preset has its measurement),
/// S and K per wavelength, and R0(X), T(X) against thickness.
pub fn plots(ui: &mut egui::Ui, m: &Material) {
    let p = &m.preset;
    ui.horizontal(|ui| {
        swatch(ui, p, 28.0);
        ui.vertical(|ui| {
            ui.strong(&p.name);
            ui.label(format!("{:?} · measured at {} mm · R_inf {}", p.kind, p.thickness_mm, p.derived.r_inf_srgb_hex));
        });
    });
    if let Some(r) = &m.report {
        ui.label(format!(
            "Reconstruction from S, K: ΔE2000 R {:.3}, R_inf {:.3} (max |ΔR| {:.1e})",
            r.delta_e_2000_r, r.delta_e_2000_r_inf, r.max_abs_r_error.1
        ));
    } else if let Some(meas) = &p.measurement
        && let Some(de) = reconstruction_delta_e(p, &meas.r, &meas.rg)
    {
        ui.label(format!("Reconstruction from S, K: ΔE2000 R {de:.3}"));
    }
    for (i, panel) in crate::material_plots::material_panels(p, None).iter().enumerate() {
        labelled_plot(ui, (i, &p.name), panel);
    }
}

/// Grid steps for a short plot: the [`crate::ticks::nice_step`] that splits the visible range in
/// at most four (labelled), with a fifth and a tenth of it for the finer lines, so that a 110-point
/// plot shows two or more y labels whatever the magnitude (S, K and R differ by decades).
fn nice_steps(input: egui_plot::GridInput) -> [f64; 3] {
    let large = crate::ticks::nice_step(input.bounds.1 - input.bounds.0, 4);
    [large / 10.0, large / 5.0, large]
}

/// The x axis's label of the tick at `value`: none within 3 % of the axis's right end, where a
/// label centred on its tick runs past the plot and was cut at the panel's edge ("800" of the
/// wavelength axis, whose data end at 780 nm).
fn x_tick_label(value: f64, step: f64, range: &std::ops::RangeInclusive<f64>) -> String {
    let (min, max) = (*range.start(), *range.end());
    if value > max - 0.03 * (max - min) {
        return String::new();
    }
    crate::ticks::label(value, step)
}

fn color(rgb: [u8; 3]) -> egui::Color32 {
    egui::Color32::from_rgb(rgb[0], rgb[1], rgb[2])
}

/// A panel of [`crate::material_plots`]: its title, ticks and labels on both axes, and its
/// legend as a row of labels under it, where it covers no curve.
fn labelled_plot(ui: &mut egui::Ui, id: impl std::hash::Hash + std::fmt::Debug, panel: &Panel) {
    ui.label(panel.title);
    let plot = Plot::new(id)
        .height(120.0)
        .x_axis_label(panel.x_label)
        .y_axis_label(panel.y_label)
        .y_axis_min_width(56.0)
        .x_axis_formatter(|mark, range| x_tick_label(mark.value, mark.step_size, range))
        .y_axis_formatter(|mark, _| crate::ticks::label(mark.value, mark.step_size))
        .grid_spacing(egui::Rangef::new(6.0, 48.0))
        .y_grid_spacer(egui_plot::uniform_grid_spacer(nice_steps))
        .allow_scroll(false)
        .include_y(panel.y_include[0])
        .include_y(panel.y_include[1]);
    plot.show(ui, |pu| {
        for c in &panel.curves {
            let style = if c.dashed { egui_plot::LineStyle::dashed_loose() } else { egui_plot::LineStyle::Solid };
            pu.line(Line::new(c.name.clone(), c.points.clone()).color(color(c.rgb)).style(style).width(1.5));
        }
    });
    ui.horizontal_wrapped(|ui| {
        for c in &panel.curves {
            let (rect, _) = ui.allocate_exact_size(egui::vec2(14.0, 10.0), egui::Sense::hover());
            let y = rect.center().y;
            ui.painter().line_segment(
                [egui::pos2(rect.left(), y), egui::pos2(rect.right(), y)],
                egui::Stroke::new(if c.dashed { 1.0 } else { 2.0 }, color(c.rgb)),
            );
            ui.small(&c.name);
        }
    });
}

/// ΔE2000 between the measured R and R re-computed from S and K over the measured background.
fn reconstruction_delta_e(p: &Preset, r: &[f64], rg: &[f64]) -> Option<f64> {
    use rouge_measure::colorimetry::{Colorimeter, Viewing, delta_e_2000_raw};
    use rouge_measure::spectrum::Spectrum;
    let (s, k) = (p.s(), p.k());
    let (r0, t) = layer_spectra(&s, &k, p.thickness_mm);
    let recomputed = Spectrum::from_fn({
        let mut i = 0;
        move |_| {
            let (r0i, ti, g) = (r0.values()[i], t.values()[i], rg.get(i).copied().unwrap_or(0.0));
            i += 1;
            r0i + ti * ti * g / (1.0 - r0i * g)
        }
    });
    let measured = Spectrum::from_slice(r).ok()?;
    let c = Colorimeter::get(Viewing::D65_1931);
    let lab = |s: &Spectrum| c.lab(&c.xyz(s)).lab;
    Some(delta_e_2000_raw(lab(&measured), lab(&recomputed)))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_last_tick_label_is_left_out_where_it_would_run_past_the_plot() {
        // The wavelength axis as the plot frames 380-780 nm with its 5 % margins.
        let range = 360.0..=800.0;
        assert_eq!(x_tick_label(800.0, 100.0, &range), "");
        assert_eq!(x_tick_label(700.0, 100.0, &range), "700");
        assert_eq!(x_tick_label(400.0, 100.0, &range), "400");
        // The thickness axis 0-0.2 mm: its last tick is inside by 4.5 %, and stays.
        assert_eq!(x_tick_label(0.2, 0.1, &(-0.01..=0.21)), "0.2");
    }
}
