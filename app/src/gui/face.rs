//! The posed default head (expression and face shape through its morph targets) and the "Face"
//! panel (shape sliders). Posing re-runs only what depends on the positions (a
//! [`SubdivisionPlan`] made on first use): targets, subdivision rules, normals, upload. The
//! UV-space maps (layers, masks, baked local thickness) stay, so the makeup follows the skin;
//! the brush's surface map is rebuilt from the posed mesh before the next stroke, so picking
//! and dabs use the deformed positions and strokes land in the same UV maps.

use super::*;
use rouge_model::mesh::default_head;
use rouge_model::mesh::deform::SubdivisionPlan;
use rouge_model::mesh::lashes::{LashRig, Mascara};
use rouge_model::mesh::targets::{FacePose, TargetSet};

/// Subdivision of the painted default head (what `start_mesh` loads).
const HEAD_LEVELS: u32 = 2;

/// The posing state: the plan, the base positions, the animation clock.
#[derive(Debug, Default)]
pub(super) struct FaceState {
    /// The default head's base positions, its subdivision plan and its lash strips, made on the
    /// first pose.
    plan: Option<(Vec<Vec3>, SubdivisionPlan, LashRig)>,
    /// The mascara shown while a Lashes slider is dragged (the document's takes over when the
    /// drag ends and becomes one undo step).
    pub(super) mascara_preview: Option<Mascara>,
    /// The viewport's mesh has been posed since it was loaded (it is posed in place, in
    /// [`GpuState::pose_mesh`]).
    posed: bool,
    /// The surface map predates the last pose.
    surface_stale: bool,
    /// The mesh being painted is the default head (the targets' mesh).
    pub(super) on_default_head: bool,
    /// Playing the expression cycle; its clock in seconds and the last tick.
    pub(super) animate: bool,
    clock_s: f64,
    last_tick: Option<Instant>,
}

impl RougeApp {
    /// The face (expression and shape) of the document.
    pub fn face(&self) -> &FacePose {
        &self.editor.document().face
    }

    /// Sets the document's face and poses the viewport's head.
    ///
    /// # Errors
    /// Unknown target names or weights out of range; a mesh other than the default head.
    pub fn set_face(&mut self, pose: FacePose) -> Result<()> {
        TargetSet::default_head()?.resolve(&pose)?;
        self.editor.document_mut().face = pose.clone();
        self.pose_head(&pose).map_err(anyhow::Error::msg)
    }

    /// The viewport's posed default head (subdivided), `None` while it shows the head at rest
    /// (nothing posed since the mesh was loaded).
    pub fn posed_mesh(&self) -> Option<&TriangleMesh> {
        self.gpu.mesh().filter(|_| self.face.posed)
    }

    /// The hairs' albedo the viewport's head was uploaded with (a mascara's and a brow gel's).
    pub fn hair_albedo(&self) -> rouge_render::HairAlbedo {
        self.gpu.renderer.hair_albedo()
    }

    /// Plays or stops the expression cycle (neutral, smile, blink, talk, surprise).
    pub fn set_animation(&mut self, on: bool) {
        self.face.animate = on;
        self.face.last_tick = None;
        if !on {
            let pose = self.face().clone();
            self.show_pose(&pose);
        }
    }

    /// Rebuilds the brush's surface map from the posed mesh if a pose changed it (the app does
    /// this when a stroke begins).
    pub fn refresh_surface(&mut self) {
        if !self.face.surface_stale {
            return;
        }
        if let Some(mesh) = self.posed_mesh() {
            let size = rouge_model::document::MAP_SIZE;
            self.editor.set_surface(Some(Arc::new(SurfaceMap::build(mesh, size, size))));
        }
        self.face.surface_stale = false;
    }

    /// Poses the head, showing an error in the status line.
    pub(super) fn show_pose(&mut self, pose: &FacePose) {
        if let Err(e) = self.pose_head(pose) {
            self.ui.message = Some((false, e));
        }
    }

    /// The viewport shows a newly loaded mesh, at rest.
    pub(super) fn mesh_loaded(&mut self) {
        self.face.posed = false;
    }

    /// After a new mesh or document: pose the default head as the document says (a posed head
    /// goes back to rest for a neutral document).
    pub(super) fn pose_from_document(&mut self) {
        self.face.mascara_preview = None;
        let pose = self.face().clone();
        if !self.face.posed && pose.is_neutral() && !self.hair_products_shown() {
            self.skin_pose(Default::default());
        } else {
            self.show_pose(&pose);
        }
    }

    /// Moves the default head to `pose` and uploads it (the local thickness stays).
    fn pose_head(&mut self, pose: &FacePose) -> std::result::Result<(), String> {
        if !self.face.on_default_head {
            return Err("expressions and face shapes move the default head's vertices; this mesh has no targets".into());
        }
        let mascara = self.shown_mascara();
        if !self.face.posed && pose.is_neutral() && !self.hair_products_shown() {
            return Ok(());
        }
        let targets = TargetSet::default_head().map_err(|e| e.to_string())?;
        if self.face.plan.is_none() {
            let head = default_head().map_err(|e| e.to_string())?;
            let plan = SubdivisionPlan::new(&head, HEAD_LEVELS);
            let rig = LashRig::of(&head);
            self.face.plan = Some((head.positions, plan, rig));
        }
        let Some((base, plan, rig)) = &self.face.plan else { return Ok(()) };
        let mut positions = base.clone();
        targets.apply(pose, &mut positions).map_err(|e| e.to_string())?;
        if let Some(m) = &mascara {
            rig.apply(m, &mut positions);
        }
        self.view.framing = Bounds::of(&plan.rest().positions);
        let brow_gel = self.editor.document().brow_gel;
        self.gpu.renderer.set_hair_albedo(rouge_render::HairAlbedo::with_products(mascara.as_ref(), brow_gel.as_ref()));
        let rest = (!self.face.posed).then(|| plan.rest());
        let skin_albedo = self.view.skin_albedo();
        self.gpu.pose_mesh(rest, skin_albedo, |mesh| plan.update(&positions, mesh)).map_err(|e| e.to_string())?;
        self.face.posed = true;
        self.face.surface_stale = true;
        self.view.needs_render = true;
        self.remorph();
        // The skin's blood follows the expression (the Skin panel's switch).
        let (units, _) = targets.resolve(pose).map_err(|e| e.to_string())?;
        self.skin_pose(units);
        Ok(())
    }

    /// The mascara on the viewport's lashes: the one being dragged, else the document's.
    pub(super) fn shown_mascara(&self) -> Option<Mascara> {
        self.face.mascara_preview.or(self.editor.document().mascara)
    }

    /// Whether a mascara or a brow gel is shown (the head is then posed and its hairs coloured
    /// even at rest).
    pub(super) fn hair_products_shown(&self) -> bool {
        self.shown_mascara().is_some() || self.editor.document().brow_gel.is_some()
    }

    /// A panel's edit of the face: into the document, and onto the head unless the animation
    /// is posing it.
    pub(super) fn edit_face(&mut self, pose: FacePose) {
        self.editor.document_mut().face = pose.clone();
        if !self.face.animate {
            self.show_pose(&pose);
        }
    }

    /// Advances the expression cycle (not during a stroke, which paints on the pose it began on).
    pub(super) fn animate_face(&mut self, ctx: &egui::Context) {
        if !self.face.animate || !self.ready() {
            return;
        }
        let now = Instant::now();
        if !self.editor.stroking() {
            self.face.clock_s += self.face.last_tick.map_or(0.0, |t| (now - t).as_secs_f64());
            let pose = FacePose {
                expression: rouge_model::mesh::targets::expression_cycle(self.face.clock_s),
                shape: self.face().shape.clone(),
            };
            self.show_pose(&pose);
        }
        self.face.last_tick = Some(now);
        ctx.request_repaint();
    }

    /// The "Face" panel: MakeHuman shape sliders (two-sided -1 to 1, one-sided 0 to 1).
    pub(super) fn face_panel(&mut self, ui: &mut egui::Ui) {
        let Ok(targets) = TargetSet::default_head() else { return };
        egui::CollapsingHeader::new("Face").default_open(false).show(ui, |ui| {
            if !self.face.on_default_head {
                ui.label("Face shapes move the default head only.");
                return;
            }
            let mut shape = self.face().shape.clone();
            let mut changed = ui.button("Reset shape").clicked() && !shape.is_empty();
            if changed {
                shape.clear();
            }
            for s in &targets.shapes {
                changed |= weight_slider(ui, &mut shape, &s.name, s.range());
            }
            if changed {
                self.edit_face(FacePose { shape, ..self.face().clone() });
            }
        });
    }
}

/// A slider for weight `name` of `map` over `lo..=hi`; a zero weight is dropped from the map so
/// a saved face lists only what moves. Returns whether it changed.
pub(super) fn weight_slider(
    ui: &mut egui::Ui,
    map: &mut std::collections::BTreeMap<String, f32>,
    name: &str,
    (lo, hi): (f32, f32),
) -> bool {
    let mut w = map.get(name).copied().unwrap_or(0.0);
    let changed = ui.add(egui::Slider::new(&mut w, lo..=hi).text(name)).changed();
    if changed && w == 0.0 {
        map.remove(name);
    } else if changed {
        map.insert(name.to_string(), w);
    }
    changed
}
