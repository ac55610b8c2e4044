//! The session around the document: preparing meshes on a worker thread, the recovery offer,
//! autosave, and the window screenshot.

use super::*;

/// `work`'s answer, or, when it panics, an error naming `what` and the panic's message: a panic
/// in a worker thread is a message in the window, never a thread that silently stops (which
/// left an empty viewport, and `--window-screenshot` waiting for ever).
pub(crate) fn caught<T>(what: &str, work: impl FnOnce() -> Result<T, String>) -> Result<T, String> {
    std::panic::catch_unwind(std::panic::AssertUnwindSafe(work)).unwrap_or_else(|payload| {
        let why = payload
            .downcast_ref::<&str>()
            .map(|s| (*s).to_string())
            .or_else(|| payload.downcast_ref::<String>().cloned())
            .unwrap_or_else(|| "no message".into());
        Err(format!("{what} failed with an internal error (a bug in Rouge, please report it): {why}"))
    })
}

/// Runs `work` on a new thread; its answer (or its panic, through [`caught`]) arrives on the
/// receiver.
pub(super) fn spawn_job<T: Send + 'static>(
    what: String,
    work: impl FnOnce() -> Result<T, String> + Send + 'static,
) -> mpsc::Receiver<Result<T, String>> {
    let (tx, rx) = mpsc::channel();
    std::thread::spawn(move || {
        let _ = tx.send(caught(&what, work));
    });
    rx
}

/// The file in the recovery folder naming the project folder the autosaved work belongs to.
const RECOVERED_FROM_FILE: &str = "project-folder.txt";

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
    /// The last mesh could not be prepared (nothing to draw until another one is).
    mesh_failed: bool,
}

impl Default for Jobs {
    fn default() -> Self {
        Jobs { preparing: None, last_autosave: Instant::now(), frames_shown: 0, screenshot: None, mesh_failed: false }
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
        let label = path.as_ref().map_or("default head".to_string(), |p| p.display().to_string());
        self.face.on_default_head = path.is_none();
        let rx = spawn_job(format!("preparing the mesh {label}"), move || {
            let mesh =
                load_mesh(path.as_deref(), scale, if path.is_some() { 0 } else { 2 }).map_err(|e| e.to_string())?;
            let size = rouge_model::document::MAP_SIZE;
            let surface = SurfaceMap::build(&mesh, size, size);
            Ok((mesh, Arc::new(surface)))
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
                self.mesh_loaded();
                self.editor.set_surface(Some(surface));
                // A morph preview was of the mesh before.
                self.view.morph = Default::default();
                self.view.reset_orbit();
                self.view.framing = None;
                self.sync_layers();
                self.ui.mesh_name = label;
                self.pose_from_document();
            }
            Err(e) => {
                self.jobs.mesh_failed = true;
                self.ui.message = Some((false, e));
            }
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
                    self.recover("recovered the unsaved work");
                }
                if ui.button("Discard").clicked() {
                    let _ = Document::clear_recovery(&dir);
                    self.ui.recovery_offer = false;
                }
            });
        });
    }

    /// Adopts the autosave (in the project it came from, when it had one) and says `what` in the
    /// status line; the recovery offer is answered.
    pub(super) fn recover(&mut self, what: &str) {
        let dir = self.options.recovery_dir();
        match Document::open_recovery(&dir) {
            Ok(doc) => {
                let project = std::fs::read_to_string(dir.join(RECOVERED_FROM_FILE))
                    .ok()
                    .map(|p| PathBuf::from(p.trim()))
                    .filter(|p| !p.as_os_str().is_empty());
                self.adopt_document(doc, project);
                self.ui.message = Some((true, format!("{what} (not saved yet)")));
            }
            Err(e) => self.ui.message = Some((false, format!("cannot recover the autosave: {e}"))),
        }
        self.ui.recovery_offer = false;
    }

    /// The error dialog ([`UiState::error_dialog`]), until OK.
    pub(super) fn error_dialog_ui(&mut self, ui: &mut egui::Ui) {
        let Some(text) = self.ui.error_dialog.clone() else { return };
        egui::Modal::new(egui::Id::unique("rouge error dialog")).show(ui.ctx(), |ui| {
            ui.set_max_width(520.0);
            ui.heading("Cannot open the project");
            ui.label(text);
            if ui.button("OK").clicked() {
                self.ui.error_dialog = None;
            }
        });
    }

    /// Opens the project in `dir`; an error goes to the error dialog (the document is kept).
    pub(super) fn open_project_or_say(&mut self, dir: &Path) {
        match self.open_project_from(dir) {
            Ok(()) => self.ui.message = Some((true, format!("opened {}", dir.display()))),
            Err(e) => {
                self.ui.error_dialog =
                    Some(cannot_open(dir, &e).replace("The default project is open instead.", "Nothing was changed."))
            }
        }
    }

    /// A folder from the file dialog; when none comes back (cancelled, or no dialog could be
    /// shown: without a desktop portal rfd only logs), the status line says where to type one
    /// and the Project folder section opens.
    pub(super) fn pick_folder_or_explain(&mut self, purpose: &str) -> Option<PathBuf> {
        let dir = rfd::FileDialog::new().set_title(purpose).pick_folder();
        if dir.is_none() {
            self.ui.message = Some((
                false,
                format!(
                    "{purpose}: no folder was chosen. If no dialog appeared (this system has no file dialog), \
                     type the folder under Project folder in the left panel and use its buttons."
                ),
            ));
            self.ui.show_project_folder = true;
        }
        dir
    }

    /// With `Options::window_screenshot`: once the face has been shown for a few frames, asks
    /// the window for a screenshot, writes it, and closes the window.
    pub(super) fn window_screenshot(&mut self, ctx: &egui::Context) {
        let Some(path) = self.options.window_screenshot.clone() else { return };
        if self.jobs.mesh_failed && !self.jobs.preparing() {
            // No face will be drawn: say why and fail, rather than wait for ever.
            let why = self.ui.message.as_ref().map_or("the mesh could not be prepared", |(_, m)| m.as_str());
            eprintln!("rouge: --window-screenshot: nothing to show: {why}");
            std::process::exit(2);
        }
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
        if let Err(e) = self.write_autosave() {
            self.ui.message = Some((false, format!("autosave failed: {e}")));
        }
    }

    /// Writes the autosave, and beside it the project folder the work belongs to.
    pub(super) fn write_autosave(&mut self) -> Result<()> {
        let dir = self.options.recovery_dir();
        self.editor.document_mut().autosave(&dir)?;
        let from = dir.join(RECOVERED_FROM_FILE);
        match &self.options.project {
            Some(p) => rouge_measure::file_set::write_atomic(&from, p.display().to_string().as_bytes())
                .with_context(|| format!("{}", from.display()))?,
            None => {
                let _ = std::fs::remove_file(&from);
            }
        }
        Ok(())
    }

    /// Clears the autosave (after a save, or a close with nothing unsaved).
    pub(super) fn clear_autosave(&self) {
        let dir = self.options.recovery_dir();
        let _ = Document::clear_recovery(&dir);
        let _ = std::fs::remove_file(dir.join(RECOVERED_FROM_FILE));
    }

    /// The typed project folder, for machines without a file dialog (left panel).
    pub(super) fn project_folder_panel(&mut self, ui: &mut egui::Ui) {
        let open = std::mem::take(&mut self.ui.show_project_folder).then_some(true);
        egui::CollapsingHeader::new("Project folder").default_open(false).open(open).show(ui, |ui| {
            ui.horizontal(|ui| {
                ui.label("Name");
                // The document's name, saved with the project (a new one takes its folder's).
                ui.text_edit_singleline(&mut self.editor.document_mut().name);
            });
            ui.label("Typed path, for machines without a file dialog");
            ui.text_edit_singleline(&mut self.ui.project_path);
            ui.horizontal(|ui| {
                let dir = PathBuf::from(self.ui.project_path.trim());
                let has = !self.ui.project_path.trim().is_empty();
                if ui.add_enabled(has, egui::Button::new("Open")).clicked() {
                    self.open_project_or_say(&dir);
                }
                if ui.add_enabled(has, egui::Button::new("Save")).clicked() {
                    let r = self.save_project_to(&dir).map(|()| format!("saved {}", dir.display()));
                    self.report(r);
                }
            });
        });
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_panicking_job_answers_with_an_error_naming_the_job_and_the_panic() {
        let rx = spawn_job("preparing the mesh x.glb".into(), || -> Result<(), String> {
            let empty: Vec<u32> = Vec::new();
            Err(format!("{}", empty[3])) // index out of bounds, as gltf-json did
        });
        let answer = rx.recv_timeout(Duration::from_secs(10)).expect("an answer, not a stopped thread");
        let e = answer.expect_err("an error");
        assert!(e.contains("preparing the mesh x.glb") && e.contains("index out of bounds"), "{e}");
        assert_eq!(caught("x", || Ok::<_, String>(7)), Ok(7));
    }
}
