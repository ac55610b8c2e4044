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

pub mod materials;

use anyhow::{Context as _, Result};
use egui::{Color32, Key, Modifiers, Pos2, Rect, Sense, Vec2};
use glam::Vec3;
use materials::Library;
use rouge_model::TexelRect;
use rouge_model::document::{Change, Document};
use rouge_model::mesh::TriangleMesh;
use rouge_model::paint::{Brush, BrushMode, StrokeSpacer, SurfaceMap, apply_dab_split};
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
    surface: Option<Arc<SurfaceMap>>,
    preparing: Option<(String, mpsc::Receiver<Prepared>)>,
    doc: Document,
    library: Library,
    scene: Scene,
    view: View,
    light_yaw: f32,
    light_pitch: f32,
    light_intensity: f32,
    environment: bool,
    split: bool,
    split_at: f32,
    brush: Brush,
    active: usize,
    spacer: Option<StrokeSpacer>,
    stroke_dabs: Vec<Vec3>,
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
        f.debug_struct("RougeApp").field("document", &self.doc.name).field("mesh", &self.mesh_name).finish()
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
            surface: None,
            preparing: None,
            doc,
            library,
            scene: Scene::studio(),
            view: View::default(),
            light_yaw: -34.0,
            light_pitch: 27.0,
            light_intensity: 1.0,
            environment: true,
            split: false,
            split_at: 0.5,
            brush: Brush::default(),
            active: 0,
            spacer: None,
            stroke_dabs: Vec::new(),
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
        app.active = app.doc.layers.len().saturating_sub(1);
        app.rename_buffer = app.doc.layers.last().map(|l| l.name.clone()).unwrap_or_default();
        app.project_path = app.options.project.as_ref().map(|p| p.display().to_string()).unwrap_or_default();
        let mesh = app.options.mesh.clone();
        match mesh {
            Some((path, scale)) => app.start_mesh(Some(path), scale),
            None => app.start_mesh(None, 1.0),
        }
        Ok(app)
    }

    // ---- state access for tests and tools ----

    /// The document being painted.
    pub fn document(&self) -> &Document {
        &self.doc
    }

    /// The surface map of the mesh, once prepared.
    pub fn surface(&self) -> Option<&SurfaceMap> {
        self.surface.as_deref()
    }

    /// The brush.
    pub fn brush_mut(&mut self) -> &mut Brush {
        &mut self.brush
    }

    /// Selects the layer strokes go to.
    pub fn set_active_layer(&mut self, i: usize) {
        self.active = i.min(self.doc.layers.len().saturating_sub(1));
    }

    /// Surface points of the dabs of the last stroke.
    pub fn last_stroke_dabs(&self) -> &[Vec3] {
        &self.stroke_dabs
    }

    /// Turns the before/after split on or off, with the line at `at` (0-1) of the viewport.
    pub fn set_split(&mut self, on: bool, at: f32) {
        self.split = on;
        self.split_at = at.clamp(0.0, 1.0);
        self.needs_render = true;
    }

    /// A point on the lips of the default head (the centre of the lipstick layer's texels).
    pub fn lip_point(&self) -> Option<Vec3> {
        let surface = self.surface.as_deref()?;
        let lips = self.doc.layers.iter().find(|l| l.preset.kind == rouge_measure::Kind::Lipstick)?;
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
        self.preparing.is_none() && self.mesh.is_some() && self.surface.is_some()
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
        self.doc.save_project(dir)?;
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
        self.doc = Document::open_project(dir)?;
        self.options.project = Some(dir.to_owned());
        self.project_path = dir.display().to_string();
        self.active = self.doc.layers.len().saturating_sub(1);
        self.sync_layers();
        Ok(())
    }

    // ---- mesh ----

    fn start_mesh(&mut self, path: Option<PathBuf>, scale: f32) {
        let (tx, rx) = mpsc::channel();
        let label = path.as_ref().map_or("default head".to_string(), |p| p.display().to_string());
        std::thread::spawn(move || {
            let result = (|| -> Result<(TriangleMesh, Arc<SurfaceMap>), String> {
                let mesh =
                    load_mesh(path.as_deref(), scale, if path.is_some() { 0 } else { 2 }).map_err(|e| e.to_string())?;
                let size = rouge_model::document::MAP_SIZE;
                let surface = SurfaceMap::build(&mesh, size, size);
                Ok((mesh, Arc::new(surface)))
            })();
            let _ = tx.send(result);
        });
        self.preparing = Some((label, rx));
    }

    fn poll_mesh(&mut self) -> bool {
        let Some((label, rx)) = &self.preparing else { return false };
        let result = match rx.try_recv() {
            Ok(r) => r,
            Err(mpsc::TryRecvError::Empty) => return false,
            Err(mpsc::TryRecvError::Disconnected) => Err("the mesh thread stopped".into()),
        };
        let label = label.clone();
        self.preparing = None;
        match result {
            Ok((mesh, surface)) => {
                if let Err(e) = self.renderer.set_mesh(&mesh, self.scene.skin.albedo) {
                    self.message = Some((false, format!("{label}: {e}")));
                    return true;
                }
                self.bare = None;
                self.mesh = Some(mesh);
                self.surface = Some(surface);
                self.view = View::default();
                self.sync_layers();
                self.mesh_name = label;
            }
            Err(e) => self.message = Some((false, e)),
        }
        true
    }

    // ---- document → renderer ----

    fn render_index(&self, layer: usize) -> Option<usize> {
        let l = self.doc.layers.get(layer)?;
        l.visible.then(|| self.doc.layers[..layer].iter().filter(|l| l.visible).count())
    }

    fn sync_layers(&mut self) {
        let inputs: Vec<LayerInput<'_>> = self
            .doc
            .layers
            .iter()
            .filter(|l| l.visible)
            .map(|l| LayerInput { preset: &l.preset, map: &l.map, multiplier: l.multiplier })
            .collect();
        if let Err(e) = self.renderer.set_layers(&inputs) {
            self.message = Some((false, e.to_string()));
        }
        self.active = self.active.min(self.doc.layers.len().saturating_sub(1));
        self.needs_render = true;
    }

    fn apply_change(&mut self, change: Change) {
        match change {
            Change::Nothing => {}
            Change::Layers => self.sync_layers(),
            Change::Map { layer, rect } => {
                if let (Some(ri), Some(l)) = (self.render_index(layer), self.doc.layers.get(layer))
                    && let Err(e) = self.renderer.update_thickness(ri, &l.map, l.multiplier, rect)
                {
                    self.message = Some((false, e.to_string()));
                }
                self.needs_render = true;
            }
        }
    }

    /// Sets layer `i`'s whole map to zero thickness, as one undo step (e.g. to repaint the
    /// default look's region-based layers on another mesh).
    pub fn clear_layer(&mut self, i: usize) {
        if let Some(map) = self.doc.begin_stroke(i) {
            map.mm.fill(0.0);
            let rect = TexelRect::whole(map.width, map.height);
            self.doc.note_dirty(rect);
        }
        let c = self.doc.end_stroke();
        self.apply_change(c);
    }

    /// Undoes the last stroke or layer edit.
    pub fn undo(&mut self) {
        let c = self.doc.undo();
        self.apply_change(c);
    }

    /// Redoes the last undone step.
    pub fn redo(&mut self) {
        let c = self.doc.redo();
        self.apply_change(c);
    }

    // ---- camera and lights ----

    fn camera(&self) -> Option<Camera> {
        let bounds = self.renderer.mesh_bounds()?;
        let mut c = Camera::framing(&bounds, self.view.yaw, self.view.pitch);
        c.distance /= self.view.zoom;
        c.target += self.view.pan;
        Some(c)
    }

    fn update_lights(&mut self) {
        let (yaw, pitch) = (self.light_yaw.to_radians(), self.light_pitch.to_radians());
        let toward = Vec3::new(yaw.sin() * pitch.cos(), pitch.sin(), yaw.cos() * pitch.cos());
        let studio = Scene::studio();
        self.scene.lights = studio.lights.clone();
        if let Some(key) = self.scene.lights.first_mut() {
            key.kind = LightKind::Directional { toward };
            key.irradiance = studio.lights[0].irradiance.map(|v| v * self.light_intensity);
        }
        self.scene.environment = if self.environment { studio.environment } else { None };
    }

    // ---- painting ----

    fn paint_at(&mut self, world: Vec3, first: bool) {
        let Some(surface) = self.surface.clone() else { return };
        if self.brush.validate().is_err() {
            return;
        }
        let dabs = match (&mut self.spacer, first) {
            (Some(s), false) => s.move_to(world, &surface),
            _ => {
                let mut s = StrokeSpacer::new(&self.brush);
                let d = s.start(world);
                self.spacer = Some(s);
                d
            }
        };
        self.apply_dabs(&dabs, &surface);
    }

    /// Applies dabs to the active layer and uploads what changed: one rectangle per side of the
    /// face (the two sides of a mirrored dab are far apart in UV, their union mostly unchanged).
    fn apply_dabs(&mut self, dabs: &[Vec3], surface: &SurfaceMap) {
        if dabs.is_empty() {
            return;
        }
        let layer = self.active;
        let multiplier = self.doc.layers.get(layer).map_or(1.0, |l| l.multiplier);
        let Some(ri) = self.render_index(layer) else {
            self.message = Some((false, "the active layer is hidden: show it to paint".into()));
            return;
        };
        let brush = self.brush;
        let mut sides = [TexelRect::EMPTY; 2];
        if let Some(map) = self.doc.stroke_map(layer) {
            for &c in dabs {
                let [a, b] = apply_dab_split(map, surface, &brush, c);
                sides = [sides[0].union(a), sides[1].union(b)];
            }
        }
        self.stroke_dabs.extend_from_slice(dabs);
        for side in sides.into_iter().filter(|r| !r.is_empty()) {
            let rect = side;
            self.doc.note_dirty(rect);
            if let Some(l) = self.doc.layers.get(layer)
                && let Err(e) = self.renderer.update_thickness(ri, &l.map, multiplier, rect)
            {
                self.message = Some((false, e.to_string()));
            }
            self.needs_render = true;
        }
    }

    /// Paints a stroke through screen points (what a drag does), as one undo step.
    pub fn paint_stroke_screen(&mut self, points: &[Pos2]) {
        self.begin_stroke();
        for (i, p) in points.iter().enumerate() {
            if let Some(w) = self.pick(*p) {
                self.paint_at(w, i == 0 || self.spacer.is_none());
            }
        }
        self.end_stroke();
    }

    fn begin_stroke(&mut self) {
        self.spacer = None;
        self.stroke_dabs.clear();
        let _ = self.doc.begin_stroke(self.active);
    }

    fn end_stroke(&mut self) {
        if let (Some(mut spacer), Some(surface)) = (self.spacer.take(), self.surface.clone()) {
            let last = spacer.finish(&surface);
            self.apply_dabs(&last, &surface);
        }
        let c = self.doc.end_stroke();
        self.apply_change(c);
    }

    fn pick(&self, pos: Pos2) -> Option<Vec3> {
        let (w, h) = self.frame_size;
        let r = self.viewport;
        if w == 0 || !r.contains(pos) {
            return None;
        }
        let x = ((pos.x - r.min.x) / r.width() * w as f32) as u32;
        let y = ((pos.y - r.min.y) / r.height() * h as f32) as u32;
        match self.renderer.pick(x, y) {
            Ok(p) => p,
            Err(e) => {
                eprintln!("rouge: pick failed: {e}");
                None
            }
        }
    }

    // ---- frames ----

    fn render(&mut self, size: (u32, u32)) {
        let Some(camera) = self.camera() else { return };
        if size.0 == 0 || size.1 == 0 {
            return;
        }
        let start = Instant::now();
        self.update_lights();
        match self.renderer.render(&self.scene, &camera, size.0, size.1, true) {
            Ok(texture) => {
                let view = rouge_render::renderer::egui_view(&texture);
                let mut r = self.egui_renderer.write();
                match self.texture {
                    Some(id) if self.frame_size == size => {
                        r.update_egui_texture_from_wgpu_texture(&self.device, &view, wgpu::FilterMode::Linear, id)
                    }
                    _ => {
                        if let Some(id) = self.texture.take() {
                            r.free_texture(&id);
                        }
                        self.texture = Some(r.register_native_texture(&self.device, &view, wgpu::FilterMode::Linear));
                    }
                }
            }
            Err(e) => self.message = Some((false, e.to_string())),
        }
        if self.split {
            self.render_bare(&camera, size);
        }
        self.frame_size = size;
        self.needs_render = false;
        self.last_frame_ms = start.elapsed().as_secs_f64() * 1e3;
    }

    fn render_bare(&mut self, camera: &Camera, size: (u32, u32)) {
        if self.bare.is_none() {
            let mut bare = Renderer::new(&self.device, &self.queue);
            if let Some(mesh) = &self.mesh
                && bare.set_mesh(mesh, self.scene.skin.albedo).is_err()
            {
                return;
            }
            self.bare = Some(bare);
        }
        let Some(bare) = self.bare.as_mut() else { return };
        if let Ok(texture) = bare.render(&self.scene, camera, size.0, size.1, true) {
            let view = rouge_render::renderer::egui_view(&texture);
            let mut r = self.egui_renderer.write();
            if let Some(id) = self.bare_texture.take() {
                r.free_texture(&id);
            }
            self.bare_texture = Some(r.register_native_texture(&self.device, &view, wgpu::FilterMode::Linear));
        }
    }

    /// Renders the current view at `size` and writes it as a PNG (the screenshot export).
    ///
    /// # Errors
    /// Rendering or writing fails.
    pub fn screenshot(&mut self, path: &Path, size: (u32, u32)) -> Result<()> {
        let camera = self.camera().context("no mesh yet")?;
        self.update_lights();
        self.renderer.render(&self.scene, &camera, size.0, size.1, true)?;
        let pixels = self.renderer.read_display()?;
        write_png(path, size.0, size.1, &pixels)?;
        self.needs_render = true;
        Ok(())
    }

    // ---- UI ----

    fn shortcuts(&mut self, ctx: &egui::Context) {
        let (redo, undo, reset) = ctx.input_mut(|i| {
            (
                i.consume_key(Modifiers::COMMAND | Modifiers::SHIFT, Key::Z),
                i.consume_key(Modifiers::COMMAND, Key::Z),
                i.consume_key(Modifiers::NONE, Key::F),
            )
        });
        if redo {
            self.redo();
        } else if undo {
            self.undo();
        }
        if reset {
            self.view = View::default();
            self.needs_render = true;
        }
    }

    fn menu(&mut self, ui: &mut egui::Ui) {
        egui::MenuBar::new().ui(ui, |ui| {
            ui.menu_button("File", |ui| {
                if ui.button("New project (default look)").clicked() {
                    self.doc = Document::default_project();
                    self.sync_layers();
                }
                if ui.button("Open project…").clicked()
                    && let Some(dir) = rfd::FileDialog::new().pick_folder()
                    && let Err(e) = self.open_project_from(&dir)
                {
                    self.message = Some((false, format!("{e:#}")));
                }
                if ui.button("Save project").clicked()
                    && let Some(dir) = self.options.project.clone().or_else(|| rfd::FileDialog::new().pick_folder())
                {
                    let r = self.save_project_to(&dir).map(|()| format!("saved {}", dir.display()));
                    self.report(r);
                }
                if ui.button("Save project as…").clicked()
                    && let Some(dir) = rfd::FileDialog::new().pick_folder()
                {
                    let r = self.save_project_to(&dir).map(|()| format!("saved {}", dir.display()));
                    self.report(r);
                }
                ui.separator();
                if ui.button("Open mesh… (.obj, .gltf, .glb)").clicked()
                    && let Some(p) = rfd::FileDialog::new().add_filter("mesh", &["obj", "gltf", "glb"]).pick_file()
                {
                    let scale = if p.extension().is_some_and(|e| e == "glb" || e == "gltf") { 25.0 } else { 1.0 };
                    self.start_mesh(Some(p), scale);
                }
                if ui.button("Default head").clicked() {
                    self.start_mesh(None, 1.0);
                }
                ui.separator();
                if ui.button("Export maps (EXR + 16-bit PNG)…").clicked()
                    && let Some(dir) = rfd::FileDialog::new().pick_folder()
                {
                    let r = self
                        .doc
                        .export_maps(&dir)
                        .map(|files| format!("exported {} files to {}", files.len(), dir.display()));
                    self.report(r.map_err(anyhow::Error::from));
                }
                if ui.button("Export active layer's preset…").clicked()
                    && let Some(p) = rfd::FileDialog::new().add_filter("preset", &["json"]).save_file()
                {
                    let r = self.doc.export_preset(self.active, &p).map(|()| format!("wrote {}", p.display()));
                    self.report(r.map_err(anyhow::Error::from));
                }
                if ui.button("Screenshot (PNG)…").clicked()
                    && let Some(p) = rfd::FileDialog::new().add_filter("PNG", &["png"]).save_file()
                {
                    let size = if self.frame_size.0 > 0 { self.frame_size } else { (1280, 720) };
                    let r = self.screenshot(&p, size).map(|()| format!("wrote {}", p.display()));
                    self.report(r);
                }
            });
            ui.menu_button("Edit", |ui| {
                if ui.add_enabled(self.doc.can_undo(), egui::Button::new("Undo (Ctrl+Z)")).clicked() {
                    self.undo();
                }
                if ui.add_enabled(self.doc.can_redo(), egui::Button::new("Redo (Ctrl+Shift+Z)")).clicked() {
                    self.redo();
                }
            });
            ui.menu_button("View", |ui| {
                if ui.button("Reset view (F)").clicked() {
                    self.view = View::default();
                    self.needs_render = true;
                }
                if ui.checkbox(&mut self.split, "Before / after split").changed() {
                    self.needs_render = true;
                }
                if ui.checkbox(&mut self.environment, "Environment light").changed() {
                    self.needs_render = true;
                }
            });
            ui.separator();
            let modified = if self.doc.is_modified() { " •" } else { "" };
            ui.label(format!("{}{modified} — {}", self.doc.name, self.mesh_name));
        });
    }

    fn report(&mut self, r: Result<String>) {
        self.message = Some(match r {
            Ok(m) => (true, m),
            Err(e) => (false, format!("{e:#}")),
        });
    }

    fn layers_panel(&mut self, ui: &mut egui::Ui) {
        ui.heading("Layers");
        ui.label("Top of the list = top of the stack");
        let n = self.doc.layers.len();
        let mut action: Option<LayerAction> = None;
        for i in (0..n).rev() {
            let l = &self.doc.layers[i];
            ui.horizontal(|ui| {
                let mut visible = l.visible;
                if ui.checkbox(&mut visible, "").on_hover_text("visible").changed() {
                    action = Some(Box::new(move |d: &mut Document| d.set_visible(i, visible)));
                }
                materials::swatch(ui, &l.preset, 14.0);
                if ui.selectable_label(self.active == i, &l.name).clicked() {
                    self.active = i;
                    self.rename_buffer = l.name.clone();
                }
                if ui.small_button("Up").on_hover_text("move up").clicked() && i + 1 < n {
                    action = Some(Box::new(move |d: &mut Document| d.move_layer(i, i + 1)));
                }
                if ui.small_button("Down").on_hover_text("move down").clicked() && i > 0 {
                    action = Some(Box::new(move |d: &mut Document| d.move_layer(i, i - 1)));
                }
                if ui.small_button("Del").on_hover_text("remove").clicked() {
                    action = Some(Box::new(move |d: &mut Document| d.remove_layer(i)));
                }
            });
        }
        if let Some(a) = action.take() {
            let c = a(&mut self.doc);
            self.apply_change(c);
        }
        let active = self.doc.layers.get(self.active).map(|l| (l.name.clone(), l.preset.name.clone(), l.multiplier));
        if let Some((name, preset_name, multiplier)) = active {
            ui.separator();
            ui.label(format!("Active: {name} ({preset_name})"));
            let i = self.active;
            ui.horizontal(|ui| {
                ui.text_edit_singleline(&mut self.rename_buffer);
                if ui.button("Rename").clicked() && !self.rename_buffer.trim().is_empty() {
                    let name = self.rename_buffer.trim().to_string();
                    let c = self.doc.rename_layer(i, &name);
                    self.apply_change(c);
                }
            });
            if ui.button("Clear layer").on_hover_text("set the whole map to 0 mm (one undo step)").clicked() {
                self.clear_layer(i);
            }
            let mut m = multiplier;
            if ui.add(egui::Slider::new(&mut m, 0.0..=4.0).text("thickness ×")).drag_stopped() {
                let c = self.doc.set_multiplier(i, m);
                self.apply_change(c);
            }
            let selected = self.library.materials.get(self.library.selected).cloned();
            if let Some(mat) = selected
                && ui.button(format!("Use material “{}”", mat.preset.name)).clicked()
            {
                let c = self.doc.set_preset(i, &mat.preset_ref, mat.preset.clone());
                self.apply_change(c);
            }
        }
        let selected = self.library.materials.get(self.library.selected).cloned();
        if let Some(mat) = selected
            && ui.button(format!("Add layer of “{}”", mat.preset.name)).clicked()
        {
            let c = self.doc.add_layer(&mat.preset_ref, mat.preset.clone());
            self.active = self.doc.layers.len().saturating_sub(1);
            self.apply_change(c);
        }

        ui.separator();
        ui.heading("Brush");
        ui.horizontal(|ui| {
            ui.selectable_value(&mut self.brush.mode, BrushMode::Paint, "Paint");
            ui.selectable_value(&mut self.brush.mode, BrushMode::Erase, "Erase");
            ui.selectable_value(&mut self.brush.mode, BrushMode::Smooth, "Smooth");
        });
        ui.add(egui::Slider::new(&mut self.brush.radius_mm, 1.0..=40.0).text("radius (mm on the skin)"));
        let mut microns = self.brush.thickness_mm * 1000.0;
        if ui.add(egui::Slider::new(&mut microns, 0.0..=100.0).text("thickness (µm)")).changed() {
            self.brush.thickness_mm = microns / 1000.0;
        }
        ui.add(egui::Slider::new(&mut self.brush.flow, 0.01..=1.0).text("flow"));
        ui.add(egui::Slider::new(&mut self.brush.hardness, 0.0..=1.0).text("hardness"));
        ui.checkbox(&mut self.brush.mirror, "Mirror across the face's midplane");

        ui.separator();
        egui::CollapsingHeader::new("Project folder").default_open(false).show(ui, |ui| {
            ui.label("Typed path, for machines without a file dialog");
            ui.text_edit_singleline(&mut self.project_path);
            ui.horizontal(|ui| {
                let dir = PathBuf::from(self.project_path.trim());
                let has = !self.project_path.trim().is_empty();
                if ui.add_enabled(has, egui::Button::new("Open")).clicked() {
                    let r = self.open_project_from(&dir).map(|()| format!("opened {}", dir.display()));
                    self.report(r);
                }
                if ui.add_enabled(has, egui::Button::new("Save")).clicked() {
                    let r = self.save_project_to(&dir).map(|()| format!("saved {}", dir.display()));
                    self.report(r);
                }
            });
        });

        ui.separator();
        ui.heading("Light");
        let mut changed = ui.add(egui::Slider::new(&mut self.light_yaw, -180.0..=180.0).text("key yaw °")).changed();
        changed |= ui.add(egui::Slider::new(&mut self.light_pitch, -60.0..=85.0).text("key pitch °")).changed();
        changed |= ui.add(egui::Slider::new(&mut self.light_intensity, 0.0..=3.0).text("key intensity")).changed();
        changed |= ui.checkbox(&mut self.environment, "Environment").changed();
        if changed {
            self.needs_render = true;
        }
        if self.split {
            changed = ui.add(egui::Slider::new(&mut self.split_at, 0.0..=1.0).text("before | after")).changed();
            self.needs_render |= changed;
        }
    }

    fn materials_panel(&mut self, ui: &mut egui::Ui) {
        ui.heading("Materials");
        egui::ScrollArea::vertical().id_salt("library").max_height(180.0).show(ui, |ui| {
            for (i, m) in self.library.materials.iter().enumerate() {
                ui.horizontal(|ui| {
                    materials::swatch(ui, &m.preset, 14.0);
                    if ui.selectable_label(self.library.selected == i, &m.preset.name).clicked() {
                        self.library.selected = i;
                    }
                });
            }
        });
        ui.separator();
        ui.label("Import a measurement (R_inf, R, Rg)");
        ui.horizontal(|ui| {
            ui.text_edit_singleline(&mut self.library.import_path);
            if ui.button("Browse…").clicked()
                && let Some(files) = rfd::FileDialog::new().pick_files()
            {
                let paths: Vec<String> = files.iter().map(|p| p.display().to_string()).collect();
                self.library.import_path = paths.join("; ");
            }
        });
        ui.add(
            egui::Slider::new(&mut self.library.import_thickness_mm, 0.001..=0.5)
                .text("thin layer (mm), if the file has none"),
        );
        ui.checkbox(&mut self.library.import_extrapolate, "extrapolate to 380-780 nm");
        ui.horizontal(|ui| {
            let can = !self.library.busy() && !self.library.import_path.trim().is_empty();
            if ui.add_enabled(can, egui::Button::new("Import")).clicked() {
                let paths: Vec<PathBuf> = self
                    .library
                    .import_path
                    .split(';')
                    .map(str::trim)
                    .filter(|p| !p.is_empty())
                    .map(PathBuf::from)
                    .collect();
                self.library.start_import(paths);
            }
            if self.library.busy() {
                let (done, total) = self.library.progress();
                ui.spinner();
                ui.add(
                    egui::ProgressBar::new(done as f32 / total.max(1) as f32).text(format!("importing {done}/{total}")),
                );
            }
        });
        if let Some((ok, msg)) = &self.library.last_message {
            ui.colored_label(if *ok { Color32::LIGHT_GREEN } else { Color32::LIGHT_RED }, msg);
        }
        ui.separator();
        if let Some(m) = self.library.materials.get(self.library.selected) {
            egui::ScrollArea::vertical().id_salt("plots").show(ui, |ui| materials::plots(ui, m));
        }
    }

    fn viewport_ui(&mut self, ui: &mut egui::Ui) {
        let avail = ui.available_size();
        let ppp = ui.ctx().pixels_per_point();
        let size = ((avail.x * ppp).round().max(1.0) as u32, (avail.y * ppp).round().max(1.0) as u32);
        let (rect, response) = ui.allocate_exact_size(avail, Sense::click_and_drag());
        self.viewport = rect;
        if let Some((label, _)) = &self.preparing {
            ui.put(rect, egui::Spinner::new().size(32.0));
            ui.painter().text(
                rect.center() + Vec2::new(0.0, 30.0),
                egui::Align2::CENTER_TOP,
                format!("Preparing {label}…"),
                egui::FontId::proportional(14.0),
                Color32::GRAY,
            );
            return;
        }
        // Input.
        let (alt, shift) = ui.input(|i| (i.modifiers.alt, i.modifiers.shift));
        let primary = response.dragged_by(egui::PointerButton::Primary);
        let orbit = (primary && alt) || (response.dragged_by(egui::PointerButton::Secondary) && !shift);
        let pan = response.dragged_by(egui::PointerButton::Middle)
            || (response.dragged_by(egui::PointerButton::Secondary) && shift);
        if orbit {
            let d = response.drag_delta();
            self.view.yaw -= d.x * 0.4;
            self.view.pitch = (self.view.pitch + d.y * 0.4).clamp(-80.0, 80.0);
            self.needs_render = true;
        } else if pan {
            if let Some(c) = self.camera() {
                let d = response.drag_delta();
                let mm_per_point = c.distance * (0.5 * c.fov_y_deg.to_radians()).tan() * 2.0 / rect.height().max(1.0);
                let view = c.view();
                let right = Vec3::new(view.x_axis.x, view.y_axis.x, view.z_axis.x);
                let up = Vec3::new(view.x_axis.y, view.y_axis.y, view.z_axis.y);
                self.view.pan += (-right * d.x + up * d.y) * mm_per_point;
                self.needs_render = true;
            }
        } else if self.ready() && !alt {
            if response.drag_started_by(egui::PointerButton::Primary) {
                self.begin_stroke();
            }
            if primary
                && let Some(pos) = response.interact_pointer_pos()
                && let Some(w) = self.pick(pos)
            {
                let first = self.spacer.is_none();
                self.paint_at(w, first);
            }
            if response.drag_stopped_by(egui::PointerButton::Primary) {
                self.end_stroke();
            }
        }
        if response.hovered() {
            let scroll = ui.input(|i| i.smooth_scroll_delta.y);
            if scroll != 0.0 {
                self.view.zoom = (self.view.zoom * (1.0 + scroll * 0.002)).clamp(0.3, 8.0);
                self.needs_render = true;
            }
        }
        if self.needs_render || size != self.frame_size {
            self.render(size);
        }
        // Draw.
        let uv = Rect::from_min_max(Pos2::ZERO, Pos2::new(1.0, 1.0));
        if let Some(id) = self.texture {
            ui.painter().image(id, rect, uv, Color32::WHITE);
        }
        if self.split
            && let Some(id) = self.bare_texture
        {
            let x = rect.min.x + rect.width() * self.split_at;
            let left = Rect::from_min_max(rect.min, Pos2::new(x, rect.max.y));
            let left_uv = Rect::from_min_max(Pos2::ZERO, Pos2::new(self.split_at, 1.0));
            ui.painter().image(id, left, left_uv, Color32::WHITE);
            ui.painter().vline(x, rect.y_range(), egui::Stroke::new(2.0, Color32::WHITE));
            ui.painter().text(
                left.left_top() + Vec2::new(8.0, 8.0),
                egui::Align2::LEFT_TOP,
                "bare skin",
                egui::FontId::proportional(14.0),
                Color32::WHITE,
            );
            ui.painter().text(
                Pos2::new(x + 8.0, rect.min.y + 8.0),
                egui::Align2::LEFT_TOP,
                "makeup",
                egui::FontId::proportional(14.0),
                Color32::WHITE,
            );
        }
        // Brush outline under the cursor (its screen radius at the surface's depth).
        if let Some(hover) = response.hover_pos()
            && !alt
            && self.ready()
            && let (Some(c), Some(w)) = (self.camera(), self.pick(hover))
        {
            let dist = (c.position() - w).length().max(1.0);
            let px = self.brush.radius_mm * c.focal_px(self.frame_size.1) / dist / ppp;
            ui.painter().circle_stroke(hover, px, egui::Stroke::new(1.0, Color32::from_white_alpha(180)));
        }
        ui.painter().text(
            rect.left_bottom() + Vec2::new(8.0, -8.0),
            egui::Align2::LEFT_BOTTOM,
            format!("frame submitted in {:.0} ms · {}×{}", self.last_frame_ms, self.frame_size.0, self.frame_size.1),
            egui::FontId::monospace(11.0),
            Color32::from_white_alpha(150),
        );
    }

    fn recovery_ui(&mut self, ui: &mut egui::Ui) {
        if !self.recovery_offer {
            return;
        }
        let dir = self.options.recovery_dir();
        egui::Modal::new(egui::Id::unique("rouge recovery offer")).show(ui.ctx(), |ui| {
            ui.heading("Recover unsaved work?");
            ui.label(format!("Rouge did not close cleanly last time. An autosave is in {}.", dir.display()));
            ui.horizontal(|ui| {
                if ui.button("Recover").clicked() {
                    match Document::open_project(&dir) {
                        Ok(doc) => {
                            self.doc = doc;
                            self.sync_layers();
                        }
                        Err(e) => self.message = Some((false, e.to_string())),
                    }
                    self.recovery_offer = false;
                }
                if ui.button("Discard").clicked() {
                    let _ = Document::clear_recovery(&dir);
                    self.recovery_offer = false;
                }
            });
        });
    }

    /// With `Options::window_screenshot`: once the face has been shown for a few frames, asks
    /// the window for a screenshot, writes it, and closes the window.
    fn window_screenshot(&mut self, ctx: &egui::Context) {
        let Some(path) = self.options.window_screenshot.clone() else { return };
        if self.ready() && self.texture.is_some() {
            self.frames_shown += 1;
        }
        ctx.request_repaint_after(Duration::from_millis(100));
        if let Some(rx) = &self.screenshot_state {
            if let Ok(result) = rx.try_recv() {
                if let Err(e) = result {
                    eprintln!("rouge: {e}");
                }
                ctx.send_viewport_cmd(egui::ViewportCommand::Close);
            }
            return;
        }
        if self.frames_shown >= 3 {
            let (tx, rx) = mpsc::channel();
            let repaint = ctx.clone();
            ctx.request_screenshot(move |image| {
                let [w, h] = image.size;
                let bytes: Vec<u8> = image.pixels.iter().flat_map(|c| c.to_array()).collect();
                let r = write_png(&path, w as u32, h as u32, &bytes).map_err(|e| e.to_string());
                let _ = tx.send(r);
                repaint.request_repaint();
            });
            self.screenshot_state = Some(rx);
        }
    }

    fn autosave(&mut self) {
        if !self.options.autosave || self.last_autosave.elapsed() < AUTOSAVE_EVERY || !self.doc.is_modified() {
            return;
        }
        self.last_autosave = Instant::now();
        if let Err(e) = self.doc.autosave(&self.options.recovery_dir()) {
            self.message = Some((false, format!("autosave failed: {e}")));
        }
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
        if self.doc.is_modified() {
            let _ = self.doc.autosave(&dir);
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
