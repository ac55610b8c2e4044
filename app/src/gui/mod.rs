//! The painting app (`rouge` with no arguments): paint cosmetic thickness maps on a 3D face and
//! see them rendered live by rouge-render on the app's own wgpu device.
//!
//! Layout: menu bar; left panel = layers and brush; right panel = material library (import,
//! plots); centre = the viewport. Viewport controls: left drag paints (Alt+left or right drag
//! orbits), middle drag or Shift+right drag pans, wheel zooms; Ctrl+Z / Ctrl+Shift+Z undo and
//! redo; F resets the view.
//!
//! The renderer draws into its own texture, which egui shows as a native texture, so the app,
//! the CLI and the tests run the same frame code. Frames are drawn only when something changed
//! (view, light, layers, a dab), which matters on software Vulkan.

mod edit;
mod layers;
pub mod materials;
mod materials_panel;
mod menu;
mod session;
mod viewport;

use crate::editor::Editor;
use anyhow::{Context as _, Result};
use egui::{Color32, Key, Modifiers, Pos2, Rect, Sense, Vec2};
use glam::Vec3;
use materials::Library;
use rouge_model::document::{Change, Document};
use rouge_model::mesh::TriangleMesh;
use rouge_model::paint::{Brush, BrushMode, SurfaceMap};
use rouge_render::job::{load_mesh, write_png};
use rouge_render::renderer::LayerInput;
use rouge_render::{Camera, LightKind, Renderer, Scene};
use std::path::{Path, PathBuf};
use std::sync::{Arc, mpsc};
use std::time::{Duration, Instant};

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

/// A mesh being prepared on a worker thread: triangles for the renderer, surface map for the brush.
type Prepared = Result<(TriangleMesh, Arc<SurfaceMap>), String>;

/// Orbit camera state (the renderer's `Camera` is derived from it and the mesh bounds).
#[derive(Clone, Copy, Debug, PartialEq)]
struct View {
    yaw: f32,
    pitch: f32,
    zoom: f32,
    pan: Vec3,
}

impl Default for View {
    fn default() -> Self {
        View { yaw: 0.0, pitch: 0.0, zoom: 1.0, pan: Vec3::ZERO }
    }
}

/// A layer edit chosen in the layer list, applied after the list is drawn.
type LayerAction = Box<dyn FnOnce(&mut Document) -> Change>;

/// The painting app.
pub struct RougeApp {
    options: Options,
    renderer: Renderer,
    bare: Option<Renderer>,
    device: wgpu::Device,
    queue: wgpu::Queue,
    egui_renderer: Arc<egui::mutex::RwLock<egui_wgpu::Renderer>>,
    texture: Option<egui::TextureId>,
    bare_texture: Option<egui::TextureId>,
    mesh: Option<TriangleMesh>,
    mesh_name: String,
    preparing: Option<(String, mpsc::Receiver<Prepared>)>,
    /// Document, active layer, brush, stroke: the egui-free editor core.
    editor: Editor,
    library: Library,
    scene: Scene,
    view: View,
    light_yaw: f32,
    light_pitch: f32,
    light_intensity: f32,
    environment: bool,
    split: bool,
    split_at: f32,
    needs_render: bool,
    frame_size: (u32, u32),
    viewport: Rect,
    last_autosave: Instant,
    recovery_offer: bool,
    message: Option<(bool, String)>,
    rename_buffer: String,
    last_frame_ms: f64,
    frames_shown: u32,
    project_path: String,
    screenshot_state: Option<mpsc::Receiver<Result<(), String>>>,
}

impl std::fmt::Debug for RougeApp {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("RougeApp")
            .field("document", &self.editor.document().name)
            .field("mesh", &self.mesh_name)
            .finish()
    }
}

impl RougeApp {
    /// Opens the app on eframe's wgpu device with the default project (or `options.project`).
    ///
    /// # Errors
    /// Without eframe's wgpu renderer, or when the project cannot be opened.
    pub fn new(cc: &eframe::CreationContext<'_>, options: Options) -> Result<RougeApp> {
        let rs = cc.wgpu_render_state.as_ref().context("the app needs eframe's wgpu renderer")?;
        let renderer = Renderer::new(&rs.device, &rs.queue);
        let doc = match &options.project {
            Some(dir) => Document::open_project(dir)?,
            None => Document::default_project(),
        };
        let library = Library::load(options.data_dir.join("presets"));
        let recovery_offer = options.autosave && Document::recovery_available(&options.recovery_dir());
        let mut app = RougeApp {
            renderer,
            bare: None,
            device: rs.device.clone(),
            queue: rs.queue.clone(),
            egui_renderer: rs.renderer.clone(),
            texture: None,
            bare_texture: None,
            mesh: None,
            mesh_name: "default head (hm08, CC0)".into(),
            preparing: None,
            editor: Editor::new(doc),
            library,
            scene: Scene::studio(),
            view: View::default(),
            light_yaw: -34.0,
            light_pitch: 27.0,
            light_intensity: 1.0,
            environment: true,
            split: false,
            split_at: 0.5,
            needs_render: true,
            frame_size: (0, 0),
            viewport: Rect::NOTHING,
            last_autosave: Instant::now(),
            recovery_offer,
            message: None,
            rename_buffer: String::new(),
            last_frame_ms: 0.0,
            frames_shown: 0,
            project_path: String::new(),
            screenshot_state: None,
            options,
        };
        app.rename_buffer = app.editor.document().layers.last().map(|l| l.name.clone()).unwrap_or_default();
        app.project_path = app.options.project.as_ref().map(|p| p.display().to_string()).unwrap_or_default();
        let mesh = app.options.mesh.clone();
        match mesh {
            Some((path, scale)) => app.start_mesh(Some(path), scale),
            None => app.start_mesh(None, 1.0),
        }
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

    /// Selects the layer strokes go to.
    pub fn set_active_layer(&mut self, i: usize) {
        self.editor.set_active_layer(i);
    }

    /// Surface points of the dabs of the last stroke.
    pub fn last_stroke_dabs(&self) -> &[Vec3] {
        self.editor.last_stroke_dabs()
    }

    /// Turns the before/after split on or off, with the line at `at` (0-1) of the viewport.
    pub fn set_split(&mut self, on: bool, at: f32) {
        self.split = on;
        self.split_at = at.clamp(0.0, 1.0);
        self.needs_render = true;
    }

    /// A point on the lips of the default head (the centre of the lipstick layer's texels).
    pub fn lip_point(&self) -> Option<Vec3> {
        let surface = self.editor.surface().map(|s| &**s)?;
        let lips = self.editor.document().layers.iter().find(|l| l.preset.kind == rouge_measure::Kind::Lipstick)?;
        let (mut sum, mut n) = (Vec3::ZERO, 0.0f32);
        for y in (0..lips.map.height).step_by(4) {
            for x in (0..lips.map.width).step_by(4) {
                if lips.map.mm[(y * lips.map.width + x) as usize] > 0.0
                    && let Some(p) = surface.position(x, y)
                {
                    sum += p;
                    n += 1.0;
                }
            }
        }
        (n > 0.0).then(|| sum / n)
    }

    /// The material library.
    pub fn library_mut(&mut self) -> &mut Library {
        &mut self.library
    }

    /// The last message shown (ok, text).
    pub fn message(&self) -> Option<&(bool, String)> {
        self.message.as_ref()
    }

    /// Whether the mesh and brush are ready.
    pub fn ready(&self) -> bool {
        self.preparing.is_none() && self.mesh.is_some() && self.editor.surface().is_some()
    }

    /// Blocks until the mesh is prepared (tests).
    pub fn wait_ready(&mut self) {
        while self.preparing.is_some() {
            if !self.poll_mesh() {
                std::thread::sleep(Duration::from_millis(10));
            }
        }
    }

    /// Screen position (egui points) of a world point in the current viewport.
    pub fn screen_pos_of(&self, world: Vec3) -> Option<Pos2> {
        let (px, py) = self.renderer.project(world)?;
        let (w, h) = self.frame_size;
        if w == 0 || h == 0 {
            return None;
        }
        let r = self.viewport;
        Some(Pos2::new(r.min.x + px / w as f32 * r.width(), r.min.y + py / h as f32 * r.height()))
    }

    /// Saves the project into `dir`.
    ///
    /// # Errors
    /// As [`Document::save_project`].
    pub fn save_project_to(&mut self, dir: &Path) -> Result<()> {
        self.editor.document_mut().save_project(dir)?;
        self.options.project = Some(dir.to_owned());
        self.project_path = dir.display().to_string();
        if self.options.autosave {
            let _ = Document::clear_recovery(&self.options.recovery_dir());
        }
        Ok(())
    }

    /// Opens the project in `dir`, replacing the document.
    ///
    /// # Errors
    /// As [`Document::open_project`]; the current document is kept on error.
    pub fn open_project_from(&mut self, dir: &Path) -> Result<()> {
        let doc = Document::open_project(dir)?;
        let change = self.editor.replace_document(doc);
        self.options.project = Some(dir.to_owned());
        self.project_path = dir.display().to_string();
        self.apply_change(change);
        Ok(())
    }

    /// Sets layer `i`'s whole map to zero thickness, as one undo step (e.g. to repaint the
    /// default look's region-based layers on another mesh).
    pub fn clear_layer(&mut self, i: usize) {
        let c = self.editor.clear_layer(i);
        self.apply_change(c);
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
        if self.poll_mesh() || self.library.poll() {
            ui.ctx().request_repaint();
        }
        if self.preparing.is_some() || self.library.busy() {
            ui.ctx().request_repaint_after(Duration::from_millis(50));
        }
        self.shortcuts(ui.ctx());
        self.autosave();
        egui::Panel::top("menu").show(ui, |ui| self.menu(ui));
        egui::Panel::bottom("status").show(ui, |ui| {
            ui.horizontal(|ui| match &self.message {
                Some((true, m)) => {
                    ui.colored_label(Color32::LIGHT_GREEN, m);
                }
                Some((false, m)) => {
                    ui.colored_label(Color32::LIGHT_RED, m);
                }
                None => {
                    ui.label("Left drag: paint · Alt+drag / right drag: orbit · Shift+right / middle drag: pan · wheel: zoom · F: reset");
                }
            });
        });
        egui::Panel::left("layers").default_size(270.0).show(ui, |ui| {
            egui::ScrollArea::vertical().show(ui, |ui| self.layers_panel(ui));
        });
        egui::Panel::right("materials").default_size(320.0).show(ui, |ui| self.materials_panel(ui));
        egui::CentralPanel::default().show(ui, |ui| self.viewport_ui(ui));
        self.recovery_ui(ui);
        self.window_screenshot(ui.ctx());
    }

    fn on_exit(&mut self) {
        if !self.options.autosave {
            return;
        }
        // Unsaved work survives a close as an autosave (offered at the next start); a saved
        // document leaves nothing to recover.
        let dir = self.options.recovery_dir();
        if self.editor.document().is_modified() {
            let _ = self.editor.document_mut().autosave(&dir);
        } else {
            let _ = Document::clear_recovery(&dir);
        }
    }
}

/// Opens the app in a window.
///
/// # Errors
/// When no window or GPU can be opened.
pub fn run(options: Options) -> Result<()> {
    let native = eframe::NativeOptions {
        viewport: egui::ViewportBuilder::default().with_inner_size([1440.0, 900.0]).with_title("Rouge"),
        renderer: eframe::Renderer::Wgpu,
        ..Default::default()
    };
    eframe::run_native("Rouge", native, Box::new(move |cc| Ok(Box::new(RougeApp::new(cc, options)?))))
        .map_err(|e| anyhow::anyhow!("cannot open the app window: {e}"))
}
