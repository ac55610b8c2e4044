//! The session around the document: preparing meshes on a worker thread, the recovery offer,
//! autosave, and the window screenshot.

use super::*;

/// A mesh being prepared on a worker thread: triangles for the renderer, surface map for the brush.
type Prepared = Result<(TriangleMesh, Arc<SurfaceMap>), String>;

/// Work that finishes later: the mesh being prepared, the autosave timer, the window screenshot.
#[derive(Debug)]
pub(super) struct Jobs {
    /// The mesh being prepared: its label and the worker's answer.
    preparing: Option<(String, mpsc::Receiver<Prepared>)>,
    last_autosave: Instant,
    /// Frames shown with the face drawn, before the window screenshot is taken.
    frames_shown: u32,
    /// The window screenshot being written.
    screenshot: Option<mpsc::Receiver<Result<(), String>>>,
}

impl Default for Jobs {
    fn default() -> Self {
        Jobs { preparing: None, last_autosave: Instant::now(), frames_shown: 0, screenshot: None }
    }
}

impl Jobs {
    /// What is being prepared, while a mesh is.
    pub(super) fn preparing_label(&self) -> Option<&str> {
        self.preparing.as_ref().map(|(label, _)| label.as_str())
    }

    pub(super) fn preparing(&self) -> bool {
        self.preparing.is_some()
    }
}

impl RougeApp {
    pub(super) fn start_mesh(&mut self, path: Option<PathBuf>, scale: f32) {
        let (tx, rx) = mpsc::channel();
        let label = path.as_ref().map_or("default head".to_string(), |p| p.display().to_string());
        self.face.on_default_head = path.is_none();
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
        self.jobs.preparing = Some((label, rx));
    }

    pub(super) fn poll_mesh(&mut self) -> bool {
        let Some((label, rx)) = &self.jobs.preparing else { return false };
        let result = match rx.try_recv() {
            Ok(r) => r,
            Err(mpsc::TryRecvError::Empty) => return false,
            Err(mpsc::TryRecvError::Disconnected) => Err("the mesh thread stopped".into()),
        };
        let label = label.clone();
        self.jobs.preparing = None;
        match result {
            Ok((mesh, surface)) => {
                if let Err(e) = self.gpu.set_mesh(mesh, self.view.skin_albedo()) {
                    self.ui.message = Some((false, format!("{label}: {e}")));
                    return true;
                }
                self.editor.set_surface(Some(surface));
                // A morph preview was of the mesh before.
                self.view.morph = Default::default();
                self.view.reset_orbit();
                self.view.framing = None;
                self.sync_layers();
                self.ui.mesh_name = label;
                self.pose_from_document();
            }
            Err(e) => self.ui.message = Some((false, e)),
        }
        true
    }

    pub(super) fn recovery_ui(&mut self, ui: &mut egui::Ui) {
        if !self.ui.recovery_offer {
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
                            let c = self.editor.replace_document(doc);
                            self.apply_change(c);
                            self.apply_change(Change::Skin { rect: None });
                            self.pose_from_document();
                        }
                        Err(e) => self.ui.message = Some((false, e.to_string())),
                    }
                    self.ui.recovery_offer = false;
                }
                if ui.button("Discard").clicked() {
                    let _ = Document::clear_recovery(&dir);
                    self.ui.recovery_offer = false;
                }
            });
        });
    }

    /// With `Options::window_screenshot`: once the face has been shown for a few frames, asks
    /// the window for a screenshot, writes it, and closes the window.
    pub(super) fn window_screenshot(&mut self, ctx: &egui::Context) {
        let Some(path) = self.options.window_screenshot.clone() else { return };
        if self.ready() && self.gpu.has_frame() {
            self.jobs.frames_shown += 1;
        }
        ctx.request_repaint_after(Duration::from_millis(100));
        if let Some(rx) = &self.jobs.screenshot {
            if let Ok(result) = rx.try_recv() {
                if let Err(e) = result {
                    eprintln!("rouge: {e}");
                }
                ctx.send_viewport_cmd(egui::ViewportCommand::Close);
            }
            return;
        }
        if self.jobs.frames_shown >= 3 {
            let (tx, rx) = mpsc::channel();
            let repaint = ctx.clone();
            ctx.request_screenshot(move |image| {
                let [w, h] = image.size;
                let bytes: Vec<u8> = image.pixels.iter().flat_map(|c| c.to_array()).collect();
                let r = write_png(&path, w as u32, h as u32, &bytes).map_err(|e| e.to_string());
                let _ = tx.send(r);
                repaint.request_repaint();
            });
            self.jobs.screenshot = Some(rx);
        }
    }

    pub(super) fn autosave(&mut self) {
        if !self.options.autosave
            || self.jobs.last_autosave.elapsed() < AUTOSAVE_EVERY
            || !self.editor.document().is_modified()
        {
            return;
        }
        self.jobs.last_autosave = Instant::now();
        if let Err(e) = self.editor.document_mut().autosave(&self.options.recovery_dir()) {
            self.ui.message = Some((false, format!("autosave failed: {e}")));
        }
    }

    /// The typed project folder, for machines without a file dialog (left panel).
    pub(super) fn project_folder_panel(&mut self, ui: &mut egui::Ui) {
        egui::CollapsingHeader::new("Project folder").default_open(false).show(ui, |ui| {
            ui.label("Typed path, for machines without a file dialog");
            ui.text_edit_singleline(&mut self.ui.project_path);
            ui.horizontal(|ui| {
                let dir = PathBuf::from(self.ui.project_path.trim());
                let has = !self.ui.project_path.trim().is_empty();
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
    }
}
