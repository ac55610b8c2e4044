//! The painting app (`rouge` with no arguments): paint cosmetic thickness maps on a 3D face and
//! see them rendered live by rouge-render on the app's own wgpu device.
//!
//! Layout: menu bar; left panel = layers, brush, project folder and key light; right panel =
//! material library (import, plots); centre = the viewport. Viewport controls: left drag paints (Alt+left or right drag
//! orbits), middle drag or Shift+right drag pans, wheel zooms; Ctrl+Z / Ctrl+Shift+Z undo and
//! redo; F sets the brush radius by moving the mouse; Home resets the view.
//!
//! The renderer draws into its own texture, which egui shows as a native texture, so the app,
//! the CLI and the tests run the same frame code. Frames are drawn only when something changed
//! (view, light, layers, a dab), which matters on software Vulkan.
//!
//! Code: edits go through the egui-free [`crate::editor::Editor`]; `edit.rs` uploads what each
//! edit changed. One file per panel (`layers.rs`, `brush.rs`, `materials_panel.rs`, `menu.rs`,
//! `viewport.rs`, `translucency.rs` for the subsurface model, `skin_panel.rs` for the skin maps,
//! whose bakes and blood flow live in `skin_view.rs`); `viewport.rs` also holds the view and GPU state, `session.rs` the background
//! jobs (mesh preparation, autosave, recovery, the window screenshot).

mod brush;
mod device_lost;
pub use device_lost::{DeviceLoss, LOSE_DEVICE_ENV, RECOVER_FLAG};
mod edit;
mod expression;
mod face;
mod frame_stats;
pub use frame_stats::with_timestamp_queries;
mod lashes;
pub mod layers;
mod looks_panel;
pub mod materials;
mod materials_panel;
mod menu;
mod session;
mod skin_panel;
pub use skin_panel::DEFAULT_SKIN_PX;
mod skin_view;
pub use skin_view::{FullBake, SkinBakeTimes};
mod translucency;
pub use translucency::{DiffuseChoice, SubsurfaceChoice};
mod viewport;
mod views;
pub use views::HeatMapFrame;

use crate::editor::Editor;
use anyhow::{Context as _, Result};
use egui::{Color32, Key, Modifiers, Pos2, Rect, Sense, Vec2};
use glam::Vec3;
use materials::Library;
use rouge_model::TexelRect;
use rouge_model::document::{Change, Document};
use rouge_model::mesh::{Bounds, TriangleMesh};
use rouge_model::paint::{Brush, BrushMode, SurfaceMap};
use rouge_model::skin::AnatomyRegion;
use rouge_render::job::{load_mesh, write_png};
use rouge_render::renderer::LayerInput;
use rouge_render::{Camera, LightKind, Renderer, Scene};
use session::Jobs;
use std::path::{Path, PathBuf};
use std::sync::{Arc, mpsc};
use std::time::{Duration, Instant};
use viewport::{GpuState, ViewState};

/// The status bar's height (points): one line, always.
const STATUS_HEIGHT: f32 = 24.0;

/// How often unsaved work is written to the recovery folder.
pub const AUTOSAVE_EVERY: Duration = Duration::from_secs(60);

/// Where the app keeps per-user files.
#[derive(Clone, Debug)]
pub struct Options {
    /// Folder for user presets and the crash-recovery autosave.
    pub data_dir: PathBuf,
    /// A project folder to open at start.
    pub project: Option<PathBuf>,
    /// Write autosaves (off in tests that do not want them).
    pub autosave: bool,
    /// A mesh to paint instead of the default head, with its millimetres per unit.
    pub mesh: Option<(PathBuf, f32)>,
    /// Take a screenshot of the whole window once the face is drawn, write it here as a PNG,
    /// and close (for checking the real window under Xvfb, and for the README's picture).
    pub window_screenshot: Option<PathBuf>,
    /// Adopt the autosave without asking: the restart after a lost GPU ([`RECOVER_FLAG`]).
    pub recover: bool,
}

impl Options {
    /// `$XDG_DATA_HOME/rouge` or `~/.local/share/rouge`.
    pub fn default_data_dir() -> PathBuf {
        std::env::var_os("XDG_DATA_HOME")
            .map(PathBuf::from)
            .or_else(|| std::env::var_os("HOME").map(|h| PathBuf::from(h).join(".local/share")))
            .unwrap_or_else(std::env::temp_dir)
            .join("rouge")
    }

    fn recovery_dir(&self) -> PathBuf {
        self.data_dir.join("recovery")
    }
}

/// A layer edit chosen in the layer list, applied after the list is drawn.
type LayerAction = Box<dyn FnOnce(&mut Document) -> Change>;

/// The painting app: the editor core and the material library (what the user works on), and
/// apart from them the view, the GPU objects, the background jobs and the panels' own state.
pub struct RougeApp {
    options: Options,
    /// Document, active layer, brush, stroke: the egui-free editor core.
    editor: Editor,
    library: Library,
    /// Camera, lights and split: how the document is looked at ([`viewport`]).
    view: ViewState,
    /// Device, renderers and the egui textures their frames are shown through ([`viewport`]).
    gpu: GpuState,
    /// Mesh preparation, autosave timing and the window screenshot ([`session`]).
    jobs: Jobs,
    /// The posed default head: expression, shape, animation ([`face`]).
    face: face::FaceState,
    /// Status message, edit buffers and the recovery offer.
    ui: UiState,
    /// The solo and heat-map views and the F radius drag ([`views`]).
    views: views::LayerViews,
    /// The looks library's thumbnails, once loaded ([`looks_panel`]).
    look_thumbnails: Vec<egui::TextureHandle>,
    /// The skin maps on screen: bakes, blood flow ([`skin_view`]).
    skin: skin_view::SkinView,
    /// The Skin panel's settings ([`skin_panel`]).
    skin_panel: skin_panel::SkinPanel,
    /// The frame-rate and GPU-time readout ([`frame_stats`]).
    frames: frame_stats::FrameStats,
    /// Whether eframe's device is lost, and what the app did then ([`device_lost`]).
    device_watch: device_lost::DeviceWatch,
    device_loss: Option<DeviceLoss>,
}

/// What the panels keep between frames that is neither document nor view.
#[derive(Debug)]
struct UiState {
    /// The status line: (ok, text).
    message: Option<(bool, String)>,
    /// The active layer's name being edited.
    rename_buffer: String,
    /// The typed project folder.
    project_path: String,
    /// Whether to ask about the autosave found at start.
    recovery_offer: bool,
    /// The mesh being painted, as the menu bar names it.
    mesh_name: String,
    /// Where the brush panel's Fill button fills.
    fill: brush::FillTarget,
    /// An error to show in a dialog until dismissed (a project that cannot be opened).
    error_dialog: Option<String>,
    /// Open the Project folder section on the next frame (no file dialog came up).
    show_project_folder: bool,
}

impl std::fmt::Debug for RougeApp {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("RougeApp")
            .field("document", &self.editor.document().name)
            .field("mesh", &self.ui.mesh_name)
            .field("view", &self.view)
            .finish_non_exhaustive()
    }
}

impl RougeApp {
    /// Opens the app on eframe's wgpu device with the default project (or `options.project`).
    ///
    /// # Errors
    /// Without eframe's wgpu renderer, or when the project cannot be opened.
    pub fn new(cc: &eframe::CreationContext<'_>, options: Options) -> Result<RougeApp> {
        let rs = cc.wgpu_render_state.as_ref().context("the app needs eframe's wgpu renderer")?;
        // A project that cannot be opened is said in a dialog over the default project.
        let (doc, error_dialog, project) = match &options.project {
            Some(dir) => match Document::open_project(dir) {
                Ok(doc) => (doc, None, Some(dir.clone())),
                Err(e) => (Document::default_project(), Some(cannot_open(dir, &e.into())), None),
            },
            None => (Document::default_project(), None, None),
        };
        let mut options = options;
        options.project = project;
        let ui = UiState {
            message: None,
            rename_buffer: doc.layers.last().map(|l| l.name.clone()).unwrap_or_default(),
            project_path: options.project.as_ref().map(|p| p.display().to_string()).unwrap_or_default(),
            recovery_offer: (options.autosave || options.recover)
                && Document::recovery_available(&options.recovery_dir()),
            mesh_name: "default head (hm08, CC0)".into(),
            fill: brush::FillTarget::Whole,
            error_dialog,
            show_project_folder: false,
        };
        let mut app = RougeApp {
            editor: Editor::new(doc),
            library: Library::load(options.data_dir.join("presets")),
            view: ViewState::default(),
            gpu: GpuState::new(rs),
            jobs: Jobs::default(),
            face: face::FaceState::default(),
            ui,
            views: views::LayerViews::default(),
            look_thumbnails: Vec::new(),
            skin: Default::default(),
            skin_panel: Default::default(),
            frames: Default::default(),
            device_watch: device_lost::DeviceWatch::new(&rs.device, cc.egui_ctx.clone()),
            device_loss: None,
            options,
        };
        match app.options.mesh.clone() {
            Some((path, scale)) => app.start_mesh(Some(path), scale),
            None => app.start_mesh(None, 1.0),
        }
        // Started again after a lost device: the autosave is the work, adopted without asking.
        if app.options.recover && app.ui.recovery_offer {
            app.recover("after the graphics device was lost, Rouge restarted and recovered the unsaved work");
            eprintln!(
                "rouge: restarted after the lost graphics device; the unsaved work is recovered from the autosave"
            );
        }
        // A project opened at start shows its skin maps.
        app.request_skin_bake();
        Ok(app)
    }

    /// The document being painted.
    pub fn document(&self) -> &Document {
        self.editor.document()
    }

    /// The surface map of the mesh, once prepared.
    pub fn surface(&self) -> Option<&SurfaceMap> {
        self.editor.surface().map(|s| &**s)
    }

    /// The brush.
    pub fn brush_mut(&mut self) -> &mut Brush {
        &mut self.editor.brush
    }

    /// Selects the layer strokes go to (the solo and heat-map views follow it).
    pub fn set_active_layer(&mut self, i: usize) {
        let c = self.editor.set_active_layer(i);
        self.apply_change(c);
        self.view.needs_render = true;
    }

    /// Surface points of the dabs of the last stroke.
    pub fn last_stroke_dabs(&self) -> &[Vec3] {
        self.editor.last_stroke_dabs()
    }

    /// Turns the before/after split on or off, with the line at `at` (0-1) of the viewport.
    pub fn set_split(&mut self, on: bool, at: f32) {
        self.view.split = on;
        self.view.split_at = at.clamp(0.0, 1.0);
        self.view.needs_render = true;
    }

    /// Chooses the skin's subsurface model in the viewport (the Subsurface panel's choice), the
    /// document's: saved with the project, and unsaved work until then.
    pub fn set_subsurface(&mut self, choice: SubsurfaceChoice) {
        self.editor.document_mut().subsurface = choice;
        self.view.needs_render = true;
    }

    /// Chooses the skin's diffuse law in the viewport (the Subsurface panel's checkbox), the
    /// document's: saved with the project, and unsaved work until then.
    pub fn set_diffuse(&mut self, choice: DiffuseChoice) {
        self.editor.document_mut().diffuse = choice;
        self.view.needs_render = true;
    }

    /// The diffuse law the viewport's last frame used (`lambert`, `half-space`).
    pub fn diffuse_in_use(&self) -> &'static str {
        self.view.scene.skin.diffuse.name()
    }

    /// Whether the viewport draws the light between surfaces (the Subsurface panel's checkbox).
    pub fn bounce_in_use(&self) -> bool {
        self.view.scene.bounce.is_some()
    }

    /// The subsurface model the viewport's last frame used (`screen-space`, `thickness`, `none`),
    /// and whether a local-thickness bake is still running.
    pub fn subsurface_in_use(&self) -> (&'static str, bool) {
        (self.view.scene.skin.subsurface.name(), self.baking())
    }

    /// A point on the lips of the default head (the centre of the lipstick layer's texels).
    pub fn lip_point(&self) -> Option<Vec3> {
        self.editor.lip_point()
    }

    /// The material library.
    pub fn library_mut(&mut self) -> &mut Library {
        &mut self.library
    }

    /// What the layers panel's Rename field holds.
    pub fn rename_field(&self) -> &str {
        &self.ui.rename_buffer
    }

    /// The project folder File ▸ Save project writes into (none: it asks).
    pub fn project_folder(&self) -> Option<&Path> {
        self.options.project.as_deref()
    }

    /// The status line's thickness readout (mm), while the cursor is over the face.
    pub fn thickness_under_cursor(&self) -> Option<f32> {
        self.view.hover_mm
    }

    /// The error dialog's text, while one is shown.
    pub fn error_dialog(&self) -> Option<&str> {
        self.ui.error_dialog.as_deref()
    }

    /// The last message shown (ok, text).
    pub fn message(&self) -> Option<&(bool, String)> {
        self.ui.message.as_ref()
    }

    /// Whether the mesh and brush are ready.
    pub fn ready(&self) -> bool {
        !self.jobs.preparing() && self.gpu.has_mesh() && self.editor.surface().is_some()
    }

    /// Blocks until the mesh is prepared (tests).
    pub fn wait_ready(&mut self) {
        while self.jobs.preparing() {
            if !self.poll_mesh() {
                std::thread::sleep(Duration::from_millis(10));
            }
        }
    }

    /// Screen position (egui points) of a world point in the current viewport.
    pub fn screen_pos_of(&self, world: Vec3) -> Option<Pos2> {
        self.gpu.screen_pos_of(self.view.rect, world)
    }

    /// Saves the project into `dir`.
    ///
    /// # Errors
    /// As [`Document::save_project`].
    pub fn save_project_to(&mut self, dir: &Path) -> Result<()> {
        // A new (or unnamed) project takes its folder's name (the title said "Untitled" for ever).
        let doc = self.editor.document_mut();
        if (doc.name == rouge_model::document::UNTITLED || doc.name.trim().is_empty())
            && let Some(folder) = dir.file_name().map(|n| n.to_string_lossy().trim().to_string())
            && !folder.is_empty()
        {
            doc.name = folder;
        }
        self.editor.document_mut().save_project(dir)?;
        self.options.project = Some(dir.to_owned());
        self.ui.project_path = dir.display().to_string();
        if self.options.autosave {
            self.clear_autosave();
        }
        Ok(())
    }

    /// Makes `doc` the document (opened, recovered or new), belonging to the project folder
    /// `project`: the layer list, the Rename field, the project folder field, the face and the
    /// skin maps all follow it.
    fn adopt_document(&mut self, doc: Document, project: Option<PathBuf>) {
        let change = self.editor.replace_document(doc);
        self.ui.project_path = project.as_ref().map(|p| p.display().to_string()).unwrap_or_default();
        self.options.project = project;
        self.ui.rename_buffer =
            self.editor.document().layers.get(self.editor.active()).map(|l| l.name.clone()).unwrap_or_default();
        self.apply_change(change);
        self.apply_change(Change::Skin { rect: None });
        self.pose_from_document();
    }

    /// Opens the project in `dir`, replacing the document.
    ///
    /// # Errors
    /// As [`Document::open_project`]; the current document is kept on error.
    pub fn open_project_from(&mut self, dir: &Path) -> Result<()> {
        let doc = Document::open_project(dir)?;
        self.adopt_document(doc, Some(dir.to_owned()));
        Ok(())
    }

    /// The viewport's size on screen (points), as the last frame laid it out.
    pub fn viewport_size(&self) -> Vec2 {
        self.view.rect.size()
    }

    /// Renames layer `i` (one undo step), as the Rename button does.
    pub fn rename_layer(&mut self, i: usize, name: &str) {
        let c = self.editor.edit(|d| d.rename_layer(i, name));
        self.apply_change(c);
    }

    /// The status line's message, on one line (cut short with "…"; the whole text on hover).
    fn status_message(&self, ui: &mut egui::Ui) {
        let (colour, text) = match &self.ui.message {
            Some((true, m)) => (Color32::LIGHT_GREEN, m.as_str()),
            Some((false, m)) => (Color32::LIGHT_RED, m.as_str()),
            None => (
                ui.visuals().text_color(),
                "Left drag: paint · Shift+click: straight line · [ ] or F: size · Alt+drag / right drag: orbit · \
                 Shift+right / middle drag: pan · wheel: zoom · Home: reset view",
            ),
        };
        ui.with_layout(egui::Layout::left_to_right(egui::Align::Center), |ui| {
            ui.add(egui::Label::new(egui::RichText::new(text).color(colour)).truncate()).on_hover_text(text);
        });
    }

    /// Sets layer `i`'s whole map to zero thickness, as one undo step (e.g. to repaint the
    /// default look's region-based layers on another mesh).
    pub fn clear_layer(&mut self, i: usize) {
        match self.editor.clear_layer(i) {
            Ok(c) => self.apply_change(c),
            Err(e) => self.ui.message = Some((false, e.to_string())),
        }
    }

    /// Undoes the last stroke or layer edit.
    pub fn undo(&mut self) {
        let c = self.editor.undo();
        self.apply_change(c);
    }

    /// Redoes the last undone step.
    pub fn redo(&mut self) {
        let c = self.editor.redo();
        self.apply_change(c);
    }

    /// Paints a stroke through screen points (what a drag does), as one undo step.
    pub fn paint_stroke_screen(&mut self, points: &[Pos2]) {
        self.begin_stroke();
        for p in points {
            if let Some(w) = self.pick(*p) {
                self.paint_at(w);
            }
        }
        self.end_stroke();
    }
}

impl eframe::App for RougeApp {
    fn ui(&mut self, ui: &mut egui::Ui, _frame: &mut eframe::Frame) {
        self.lose_device_if_asked();
        if self.device_lost_frame(ui.ctx()) {
            return;
        }
        if self.poll_mesh() | self.library.poll() | self.poll_skin() {
            ui.ctx().request_repaint();
        }
        if self.jobs.preparing() || self.library.busy() || self.skin.busy() {
            ui.ctx().request_repaint_after(Duration::from_millis(50));
        }
        self.shortcuts(ui.ctx());
        self.animate_face(ui.ctx());
        self.animate_morph(ui.ctx());
        self.autosave();
        egui::Panel::top("menu").show(ui, |ui| self.menu(ui));
        // One row, whatever it shows: a second row for the thickness readout, or a wrapped
        // message, made the viewport jump by a line as the cursor crossed the face.
        egui::Panel::bottom("status").exact_size(STATUS_HEIGHT).show(ui, |ui| {
            ui.horizontal_centered(|ui| {
                if let Some(mm) = self.view.hover_mm {
                    ui.with_layout(egui::Layout::right_to_left(egui::Align::Center), |ui| {
                        ui.monospace(format!("active layer under the cursor: {:.1} µm", mm * 1000.0));
                        self.status_message(ui);
                    });
                } else {
                    self.status_message(ui);
                }
            });
        });
        egui::Panel::left("layers").default_size(270.0).show(ui, |ui| {
            egui::ScrollArea::vertical().show(ui, |ui| {
                self.layers_panel(ui);
                self.looks_panel(ui);
                ui.separator();
                self.brush_panel(ui);
                ui.separator();
                self.project_folder_panel(ui);
                ui.separator();
                self.light_panel(ui);
                ui.separator();
                self.subsurface_panel(ui);
                ui.separator();
                self.skin_panel_ui(ui);
                ui.separator();
                self.expression_panel(ui);
                self.face_panel(ui);
                self.lashes_panel(ui);
            });
        });
        egui::Panel::right("materials").default_size(320.0).show(ui, |ui| self.materials_panel(ui));
        egui::CentralPanel::default().show(ui, |ui| self.viewport_ui(ui));
        self.recovery_ui(ui);
        self.error_dialog_ui(ui);
        self.window_screenshot(ui.ctx());
    }

    fn on_exit(&mut self) {
        // After a lost device the autosave written for the restart stays, whatever it holds.
        if !self.options.autosave || self.device_loss.is_some() {
            return;
        }
        // Unsaved work survives a close as an autosave (offered at the next start); a saved
        // document leaves nothing to recover.
        if self.editor.document().is_modified() {
            let _ = self.write_autosave();
        } else {
            self.clear_autosave();
        }
    }
}

/// "Cannot open the project DIR", and why, in the app's words.
fn cannot_open(dir: &Path, e: &anyhow::Error) -> String {
    format!("Rouge cannot open the project folder {}.\n\n{e:#}\n\nThe default project is open instead.", dir.display())
}

/// Opens the app in a window.
///
/// # Errors
/// When no window or GPU can be opened.
pub fn run(options: Options) -> Result<()> {
    let native = eframe::NativeOptions {
        viewport: egui::ViewportBuilder::default().with_inner_size([1440.0, 900.0]).with_title("Rouge"),
        renderer: eframe::Renderer::Wgpu,
        wgpu_options: egui_wgpu::WgpuConfiguration {
            wgpu_setup: with_timestamp_queries(egui_wgpu::WgpuSetup::without_display_handle()),
            ..Default::default()
        },
        ..Default::default()
    };
    eframe::run_native("Rouge", native, Box::new(move |cc| Ok(Box::new(RougeApp::new(cc, options)?))))
        .map_err(|e| anyhow::anyhow!("cannot open the app window: {e}"))?;
    if device_lost::RESTART_AFTER_DEVICE_LOSS.load(std::sync::atomic::Ordering::SeqCst) {
        device_lost::restart().context("cannot start Rouge again after the lost graphics device")?;
    }
    Ok(())
}
