//! The material library (built-in presets, user presets, imports) and its panel: list, import
//! from a measurement file in the background, plots of the selected material.

use egui_plot::{Line, Plot};
use rouge_measure::import::{self, ImportOptions};
use rouge_measure::preset::{ImportReport, Preset, layer_spectra, table_thicknesses_mm};
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
                if tx.send(import_file(&path, thickness, extrapolate, &user_dir)).is_err() {
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
    let v = u32::from_str_radix(hex.trim_start_matches('#'), 16).unwrap_or(0x808080);
    egui::Color32::from_rgb((v >> 16) as u8, (v >> 8) as u8, v as u8)
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
    let wl = &p.wavelengths_nm;
    let series = |v: &[f64]| -> Vec<[f64; 2]> { wl.iter().zip(v).map(|(&x, &y)| [x, y]).collect() };
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
    let (s_spec, k_spec) = (p.s(), p.k());
    let r_inf: Vec<f64> =
        s_spec.values().iter().zip(k_spec.values()).map(|(&s, &k)| rouge_measure::km::r_inf_from_s_k(s, k)).collect();
    let mut reflectance = Vec::new();
    if let Some(meas) = &p.measurement {
        reflectance.push(Curve::new("R_inf measured", SERIES[0], series(&meas.r_inf)));
        reflectance.push(Curve::new("R measured", SERIES[1], series(&meas.r)));
        reflectance.push(Curve::new("Rg", SERIES[2], series(&meas.rg)));
    }
    reflectance.push(Curve::new("R_inf from S, K", SERIES[3], series(&r_inf)).dashed());
    labelled_plot(ui, ("refl", &p.name), "Reflectance", "nm", reflectance, Some((0.0, 1.0)));
    // S and K on axes of their own: K falls by orders of magnitude past 600 nm where S does not.
    labelled_plot(
        ui,
        ("s", &p.name),
        "S, scattering (1/mm)",
        "nm",
        vec![Curve::new("S", SERIES[4], series(&p.s_per_mm))],
        None,
    );
    labelled_plot(
        ui,
        ("k", &p.name),
        "K, absorption (1/mm)",
        "nm",
        vec![Curve::new("K", SERIES[5], series(&p.k_per_mm))],
        Some((0.0, 0.0)),
    );
    let xs = table_thicknesses_mm();
    let channels = [
        ("R", egui::Color32::from_rgb(220, 60, 50)),
        ("G", egui::Color32::from_rgb(60, 170, 70)),
        ("B", egui::Color32::from_rgb(70, 110, 230)),
    ];
    let mut rt = Vec::new();
    for (c, (name, color)) in channels.into_iter().enumerate() {
        let r0: Vec<[f64; 2]> = xs.iter().zip(&p.derived.r0_linear_srgb).map(|(&x, v)| [x, v[c]]).collect();
        let t: Vec<[f64; 2]> = xs.iter().zip(&p.derived.t_linear_srgb).map(|(&x, v)| [x, v[c]]).collect();
        rt.push(Curve::new(&format!("R0 {name}"), color, r0));
        rt.push(Curve::new(&format!("T {name}"), color, t).dashed());
    }
    labelled_plot(ui, ("rt", &p.name), "R0(X) solid, T(X) dashed, linear sRGB", "mm", rt, Some((0.0, 1.0)));
}

/// Grid steps for a short plot: the largest of 1, 2 or 5 × 10ⁿ that fits the visible range at
/// least twice (labelled), with a fifth and a tenth of it for the finer lines, so that a 110-point
/// plot shows two or more y labels whatever the magnitude (S, K and R differ by decades).
fn nice_steps(input: egui_plot::GridInput) -> [f64; 3] {
    let range = (input.bounds.1 - input.bounds.0).abs().max(1e-12);
    let decade = 10f64.powf((range / 2.0).log10().floor());
    let large = [5.0, 2.0, 1.0].iter().map(|m| m * decade).find(|&step| range / step >= 2.0).unwrap_or(decade);
    [large / 10.0, large / 5.0, large]
}

/// Colours of the plots' series (the R, G, B channels have their own).
const SERIES: [egui::Color32; 6] = [
    egui::Color32::from_rgb(31, 119, 180),
    egui::Color32::from_rgb(255, 127, 14),
    egui::Color32::from_rgb(120, 120, 120),
    egui::Color32::from_rgb(214, 39, 140),
    egui::Color32::from_rgb(44, 160, 44),
    egui::Color32::from_rgb(200, 60, 40),
];

/// One curve of a plot.
struct Curve {
    name: String,
    color: egui::Color32,
    dashed: bool,
    points: Vec<[f64; 2]>,
}

impl Curve {
    fn new(name: &str, color: egui::Color32, points: Vec<[f64; 2]>) -> Curve {
        Curve { name: name.to_string(), color, dashed: false, points }
    }

    fn dashed(self) -> Curve {
        Curve { dashed: true, ..self }
    }
}

/// A titled plot with ticks on both axes, `y_range` included (both ends equal: only that
/// value), and its legend as a row of labels under it, where it covers no curve.
fn labelled_plot(
    ui: &mut egui::Ui,
    id: impl std::hash::Hash + std::fmt::Debug,
    title: &str,
    x_label: &str,
    curves: Vec<Curve>,
    y_range: Option<(f64, f64)>,
) {
    ui.label(title);
    let mut plot = Plot::new(id)
        .height(110.0)
        .x_axis_label(x_label)
        .y_axis_min_width(40.0)
        .y_axis_formatter(|mark, _| {
            let text = format!("{:.3}", mark.value);
            text.trim_end_matches('0').trim_end_matches('.').to_string()
        })
        .grid_spacing(egui::Rangef::new(6.0, 48.0))
        .y_grid_spacer(egui_plot::uniform_grid_spacer(nice_steps))
        .allow_scroll(false);
    if let Some((lo, hi)) = y_range {
        plot = plot.include_y(lo).include_y(hi);
    }
    plot.show(ui, |pu| {
        for c in &curves {
            let style = if c.dashed { egui_plot::LineStyle::dashed_loose() } else { egui_plot::LineStyle::Solid };
            pu.line(Line::new(c.name.clone(), c.points.clone()).color(c.color).style(style).width(1.5));
        }
    });
    ui.horizontal_wrapped(|ui| {
        for c in &curves {
            let (rect, _) = ui.allocate_exact_size(egui::vec2(14.0, 10.0), egui::Sense::hover());
            let y = rect.center().y;
            ui.painter().line_segment(
                [egui::pos2(rect.left(), y), egui::pos2(rect.right(), y)],
                egui::Stroke::new(if c.dashed { 1.0 } else { 2.0 }, c.color),
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
