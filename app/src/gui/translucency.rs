//! The Subsurface panel: which subsurface model the skin uses in the viewport: the screen-space
//! kernel (the default), the fast thickness translucency (\[BarreBrisebois2011\]) with a baked
//! local thickness or one read per light from its shadow map, the kernel with the slab law's
//! light through thin parts ([`rouge_render::slab_transmittance`]), the directional dipole, the
//! cube-map atlas dipole (\[Benmounah2009\], with the paper's deformation test: the head morphed
//! toward its bounding sphere, by hand or animated), or none. The bake runs on a
//! background thread (cached on disk by mesh: instant the second time); until it lands the
//! viewport keeps the screen-space kernel and says so. Under the model, a checkbox chooses how
//! the skin returns light by angle: Lambert, or the exact half-space under its surface
//! ([`rouge_render::dielectric_brdf`]); both are saved with the project. A second checkbox adds
//! the light between surfaces ([`rouge_render::bounce`]), a view setting like the environment.
//!
//! The app's skin is not a measured medium, so the translucency takes skin1's coefficients
//! (\[Jensen2001\]: its σ_tr falloff) and the parameters fitted to the path tracer for skin1.

use super::*;
use rouge_model::medium::Medium;
use rouge_model::thickness::UvMap;
use rouge_render::job::bake_thickness_map;
use rouge_render::local_thickness::{ThicknessSource, TranslucencyParams};
use rouge_render::{SlabThrough, SubsurfaceModel};

/// The subsurface models the viewport offers: the document's choice, saved with the project.
pub use rouge_model::document::{DiffuseChoice, SubsurfaceChoice};

/// The paper's deformation test in the viewport: the mesh morphed toward its bounding sphere.
#[derive(Debug, Default)]
pub(super) struct MorphPreview {
    /// 0 (the mesh) to 1 (the sphere).
    pub(super) t: f32,
    /// Sweeping t back and forth.
    pub(super) animate: bool,
    clock_s: f64,
    last_tick: Option<Instant>,
    /// The mesh before the morph, while t > 0.
    base: Option<TriangleMesh>,
}

/// What the Subsurface panel calls `choice`.
fn label(choice: SubsurfaceChoice) -> &'static str {
    match choice {
        SubsurfaceChoice::ScreenSpace => "Screen-space scattering",
        SubsurfaceChoice::ThicknessBaked => "Translucency (baked thickness)",
        SubsurfaceChoice::ThicknessPerLight => "Translucency (per light)",
        SubsurfaceChoice::ScreenSpaceThickness => "Scattering + translucency (per light)",
        SubsurfaceChoice::ScreenSpaceSlab => "Scattering + slab translucency (skin1)",
        SubsurfaceChoice::ScreenSpaceSlabGather => "Scattering + gathered translucency (skin1)",
        SubsurfaceChoice::DirectionalDipole => "Directional dipole (skin1)",
        SubsurfaceChoice::CubeAtlas => "Cube-map atlas dipole (skin1)",
        SubsurfaceChoice::None => "None",
    }
}

/// Where the viewport's local-thickness map is.
#[derive(Debug, Default)]
pub(super) enum LocalThicknessState {
    /// Not baked for this mesh.
    #[default]
    Missing,
    /// Baking on a thread.
    Baking(mpsc::Receiver<std::result::Result<UvMap, String>>),
    /// Uploaded to the renderer.
    Ready,
    /// The bake failed (the message).
    Failed(String),
}

/// skin1's medium, parsed once (the panel applies its choice every frame).
fn skin1() -> Option<&'static Medium> {
    static SKIN1: std::sync::OnceLock<Option<Medium>> = std::sync::OnceLock::new();
    SKIN1.get_or_init(|| Medium::builtin("skin1").ok()).as_ref()
}

/// The translucency of the app's skin: skin1's medium, its parameters fitted to the path
/// tracer, `baked` or per light, alone or under the skin's screen-space kernel (with the
/// parameters fitted under a kernel).
fn thickness_model(baked: bool, with_kernel: bool) -> SubsurfaceModel {
    let skin1 = skin1();
    let source = ThicknessSource::for_medium(baked, skin1, 64, 30.0);
    let (params, _) = TranslucencyParams::fitted(skin1, source.name(), with_kernel);
    let kernel = match SubsurfaceModel::skin_screen_space() {
        SubsurfaceModel::ScreenSpace { profile } => Some(profile).filter(|_| with_kernel),
        _ => None,
    };
    SubsurfaceModel::Thickness { params, source, kernel }
}

impl RougeApp {
    /// Puts the chosen subsurface model into the scene; starts the bake when the baked
    /// translucency is chosen and the mesh has no map yet, and uploads it when it lands.
    pub(super) fn apply_subsurface(&mut self) {
        if let LocalThicknessState::Baking(rx) = &self.gpu.local_thickness
            && let Ok(result) = rx.try_recv()
        {
            self.gpu.local_thickness = match result.and_then(|map| {
                let texels = map.texels.as_slice();
                self.gpu.renderer.set_local_thickness(Some((map.width, map.height, texels))).map_err(|e| e.to_string())
            }) {
                Ok(()) => LocalThicknessState::Ready,
                Err(e) => LocalThicknessState::Failed(e),
            };
            self.view.needs_render = true;
        }
        let choice = self.editor.document().subsurface;
        if choice == SubsurfaceChoice::ThicknessBaked
            && matches!(self.gpu.local_thickness, LocalThicknessState::Missing)
            && let Some(mesh) = self.gpu.mesh_for_bake()
        {
            let settings = match thickness_model(true, false) {
                SubsurfaceModel::Thickness { source: ThicknessSource::Baked(s), .. } => s,
                _ => rouge_model::thickness::BakeSettings::default(),
            };
            let rx = super::session::spawn_job("baking the local thickness".into(), move || {
                bake_thickness_map(&mesh, &settings).map(|(map, _)| map).map_err(|e| e.to_string())
            });
            self.gpu.local_thickness = LocalThicknessState::Baking(rx);
        }
        // The dipoles and the slab law need a physical medium: the app's skin takes skin1's.
        let physical = matches!(
            choice,
            SubsurfaceChoice::DirectionalDipole
                | SubsurfaceChoice::CubeAtlas
                | SubsurfaceChoice::ScreenSpaceSlab
                | SubsurfaceChoice::ScreenSpaceSlabGather
        );
        self.view.scene.skin.medium = physical.then(|| skin1().cloned()).flatten();
        self.view.scene.skin.diffuse = match self.editor.document().diffuse {
            DiffuseChoice::Lambert => rouge_render::DiffuseLaw::Lambert,
            DiffuseChoice::HalfSpace => rouge_render::DiffuseLaw::HalfSpace,
        };
        self.view.scene.skin.subsurface = match choice {
            SubsurfaceChoice::DirectionalDipole => SubsurfaceModel::Dipole {
                kind: rouge_render::DipoleKind::Directional,
                settings: rouge_render::DipoleSettings::default(),
            },
            SubsurfaceChoice::CubeAtlas => {
                SubsurfaceModel::CubeAtlas { settings: rouge_render::cube_atlas::AtlasSettings::default() }
            }
            SubsurfaceChoice::ScreenSpace => SubsurfaceModel::skin_screen_space(),
            SubsurfaceChoice::None => SubsurfaceModel::None,
            SubsurfaceChoice::ThicknessPerLight => thickness_model(false, false),
            SubsurfaceChoice::ScreenSpaceThickness => thickness_model(false, true),
            SubsurfaceChoice::ScreenSpaceSlab | SubsurfaceChoice::ScreenSpaceSlabGather => SubsurfaceModel::Slab {
                kernel: SubsurfaceModel::skin_screen_space().profile().cloned(),
                through: if choice == SubsurfaceChoice::ScreenSpaceSlabGather {
                    SlabThrough::Gather
                } else {
                    SlabThrough::Law
                },
            },
            SubsurfaceChoice::ThicknessBaked => match self.gpu.local_thickness {
                LocalThicknessState::Ready => thickness_model(true, false),
                _ => SubsurfaceModel::skin_screen_space(),
            },
        };
    }

    /// Whether a bake is running, or the dipole's maps are still accumulating (the viewport keeps
    /// repainting: 32 frames of samples, then it rests).
    pub(super) fn baking(&self) -> bool {
        matches!(self.gpu.local_thickness, LocalThicknessState::Baking(_))
            || (self.editor.document().subsurface == SubsurfaceChoice::DirectionalDipole
                && self.gpu.renderer.dipole_frames() < 32)
    }

    /// The Subsurface panel (left panel, under the light).
    pub(super) fn subsurface_panel(&mut self, ui: &mut egui::Ui) {
        ui.heading("Subsurface");
        let before = self.editor.document().subsurface;
        let mut chosen = before;
        egui::ComboBox::from_id_salt("subsurface")
            .selected_text(label(before))
            .show_ui(ui, |ui| {
                for c in SubsurfaceChoice::ALL {
                    ui.selectable_value(&mut chosen, c, label(c));
                }
            })
            .response
            .on_hover_text(
                "Translucency: light from behind through thin parts (ears, nostrils, lips), \
                 [Barré-Brisebois 2011], with skin1's parameters fitted to a path tracer. Baked: \
                 the thickness of the mesh at rest; per light: from the light's shadow map. \
                 Scattering + translucency: both, the closest to the path tracer on a front-lit head.",
            );
        if chosen != before {
            self.set_subsurface(chosen);
        }
        let mut exact = self.editor.document().diffuse == DiffuseChoice::HalfSpace;
        let toggled = ui
            .checkbox(&mut exact, "Exact skin surface (half-space)")
            .on_hover_text(
                "How the skin returns light by angle: the exact transport of a half-space of skin under \
                 its surface (η 1.4, adding-doubling), darker towards grazing views and light, where the \
                 surface reflects more, instead of the same in every direction (Lambert). The colour at \
                 normal incidence stays. Closer to a path tracer on every scene measured \
                 (docs/BENCHMARKS.md).",
            )
            .changed();
        if toggled {
            self.set_diffuse(if exact { DiffuseChoice::HalfSpace } else { DiffuseChoice::Lambert });
        }
        let mut bounce = self.view.scene.bounce.is_some();
        let toggled = ui
            .checkbox(&mut bounce, "Light between surfaces")
            .on_hover_text(
                "One bounce of the skin's glow onto the skin facing it: the nose lit by the cheek, the \
                 sides of the fingers by each other. Screen space: only what the viewport shows glows. \
                 A view setting, not saved.",
            )
            .changed();
        if toggled {
            self.view.scene.bounce = bounce.then(rouge_render::bounce::BounceSettings::default);
            self.view.needs_render = true;
        }
        if chosen == SubsurfaceChoice::CubeAtlas {
            self.morph_controls(ui);
        } else if self.view.morph.t != 0.0 {
            self.set_morph(0.0);
        }
        match (&self.gpu.local_thickness, chosen) {
            (LocalThicknessState::Baking(_), SubsurfaceChoice::ThicknessBaked) => {
                ui.horizontal(|ui| {
                    ui.spinner();
                    ui.label("Baking the local thickness…");
                });
            }
            (LocalThicknessState::Failed(e), SubsurfaceChoice::ThicknessBaked) => {
                ui.colored_label(Color32::from_rgb(220, 80, 80), format!("Bake failed: {e}"));
            }
            _ => {}
        }
    }

    /// The morph slider and its animation (the cube atlas's deformation test).
    fn morph_controls(&mut self, ui: &mut egui::Ui) {
        let mut t = self.view.morph.t;
        let slider = ui
            .add_enabled(!self.view.morph.animate, egui::Slider::new(&mut t, 0.0..=1.0).text("morph to sphere"))
            .on_hover_text(
                "The paper's deformation test: the mesh moved toward its bounding sphere. The atlas is \
                 drawn from the current positions every frame, so the translucency follows. A preview: \
                 the brush paints on the unmorphed head; set it back to 0 to paint.",
            );
        if slider.changed() {
            self.set_morph(t);
        }
        ui.checkbox(&mut self.view.morph.animate, "Animate the morph");
    }

    /// Morphs the viewport's mesh `t` of the way toward its bounding sphere (0 restores it).
    pub fn set_morph(&mut self, t: f32) {
        let t = t.clamp(0.0, 1.0);
        let base = match self.view.morph.base.take() {
            Some(base) => base,
            None => match self.gpu.mesh_for_bake() {
                Some(mesh) => mesh,
                None => return,
            },
        };
        let albedo = self.view.skin_albedo();
        let shown = if t == 0.0 {
            Ok(base.clone())
        } else {
            rouge_model::thickness::morph_to_bounding_sphere(&base, t).map_err(|e| e.to_string())
        };
        match shown.and_then(|mesh| self.gpu.set_moved_mesh(mesh, albedo).map_err(|e| e.to_string())) {
            Ok(()) => self.view.morph.t = t,
            Err(e) => self.ui.message = Some((false, format!("morph: {e}"))),
        }
        if self.view.morph.t != 0.0 {
            self.view.morph.base = Some(base);
        }
        self.view.needs_render = true;
    }

    /// After the viewport's mesh changed under a morph preview (a new pose): morph the new
    /// mesh by the same t, so the preview and the pose both show.
    pub(super) fn remorph(&mut self) {
        let t = self.view.morph.t;
        if t != 0.0 {
            self.view.morph.base = None;
            self.set_morph(t);
        }
    }

    /// The bounds of the mesh the viewport draws (posed and morphed as shown).
    pub fn shown_mesh_bounds(&self) -> Option<rouge_model::mesh::Bounds> {
        self.gpu.renderer.mesh_bounds()
    }

    /// How far the viewport's mesh is morphed toward its bounding sphere.
    pub fn morph(&self) -> f32 {
        self.view.morph.t
    }

    /// Advances the morph's animation: t = (1 − cos)/2 over four seconds.
    pub(super) fn animate_morph(&mut self, ctx: &egui::Context) {
        let m = &mut self.view.morph;
        if !m.animate || self.editor.document().subsurface != SubsurfaceChoice::CubeAtlas {
            m.last_tick = None;
            return;
        }
        let now = Instant::now();
        m.clock_s += m.last_tick.map_or(0.0, |t| (now - t).as_secs_f64());
        m.last_tick = Some(now);
        let t = (0.5 * (1.0 - (m.clock_s * std::f64::consts::PI / 2.0).cos())) as f32;
        self.set_morph(t);
        ctx.request_repaint();
    }
}
