//! The Subsurface panel: which subsurface model the skin uses in the viewport: the screen-space
//! kernel (the default), the fast thickness translucency ([BarreBrisebois2011]) with a baked
//! local thickness or one read per light from its shadow map, or none. The bake runs on a
//! background thread (cached on disk by mesh: instant the second time); until it lands the
//! viewport keeps the screen-space kernel and says so.
//!
//! The app's skin is not a measured medium, so the translucency takes skin1's coefficients
//! ([Jensen2001]: its σ_tr falloff) and the parameters fitted to the path tracer for skin1.

use super::*;
use rouge_model::medium::Medium;
use rouge_model::thickness::UvMap;
use rouge_render::SubsurfaceModel;
use rouge_render::job::bake_thickness_map;
use rouge_render::local_thickness::{ThicknessSource, TranslucencyParams};

/// The subsurface models the viewport offers.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum SubsurfaceChoice {
    /// d'Eon's skin profile through the separable kernel.
    ScreenSpace,
    /// Thickness translucency with the baked local thickness.
    ThicknessBaked,
    /// Thickness translucency with the per-light shadow-map thickness (follows deformation).
    ThicknessPerLight,
    /// The directional dipole of skin1 ([Frisvad2014]), accumulated over frames while still.
    DirectionalDipole,
    /// No subsurface scattering.
    None,
}

impl SubsurfaceChoice {
    const ALL: [SubsurfaceChoice; 5] = [
        SubsurfaceChoice::ScreenSpace,
        SubsurfaceChoice::ThicknessBaked,
        SubsurfaceChoice::ThicknessPerLight,
        SubsurfaceChoice::DirectionalDipole,
        SubsurfaceChoice::None,
    ];

    fn label(self) -> &'static str {
        match self {
            SubsurfaceChoice::ScreenSpace => "Screen-space scattering",
            SubsurfaceChoice::ThicknessBaked => "Translucency (baked thickness)",
            SubsurfaceChoice::ThicknessPerLight => "Translucency (per light)",
            SubsurfaceChoice::DirectionalDipole => "Directional dipole (skin1)",
            SubsurfaceChoice::None => "None",
        }
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

/// The translucency of the app's skin: skin1's medium, fitted parameters, `baked` or per light.
fn thickness_model(baked: bool) -> SubsurfaceModel {
    let skin1 = skin1();
    let source = ThicknessSource::for_medium(baked, skin1, 64, 30.0);
    let (params, _) = TranslucencyParams::for_medium(skin1, source.name());
    SubsurfaceModel::Thickness { params, source }
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
        let choice = self.view.subsurface;
        if choice == SubsurfaceChoice::ThicknessBaked
            && matches!(self.gpu.local_thickness, LocalThicknessState::Missing)
            && let Some(mesh) = self.gpu.mesh_for_bake()
        {
            let (tx, rx) = mpsc::channel();
            let settings = match thickness_model(true) {
                SubsurfaceModel::Thickness { source: ThicknessSource::Baked(s), .. } => s,
                _ => rouge_model::thickness::BakeSettings::default(),
            };
            std::thread::spawn(move || {
                let _ = tx.send(bake_thickness_map(&mesh, &settings).map(|(map, _)| map).map_err(|e| e.to_string()));
            });
            self.gpu.local_thickness = LocalThicknessState::Baking(rx);
        }
        // The dipole needs a physical medium: the app's skin takes skin1's for it.
        self.view.scene.skin.medium =
            (choice == SubsurfaceChoice::DirectionalDipole).then(|| skin1().cloned()).flatten();
        self.view.scene.skin.subsurface = match choice {
            SubsurfaceChoice::DirectionalDipole => SubsurfaceModel::Dipole {
                kind: rouge_render::passes::dipole::DipoleKind::Directional,
                settings: rouge_render::passes::dipole::DipoleSettings::default(),
            },
            SubsurfaceChoice::ScreenSpace => SubsurfaceModel::skin_screen_space(),
            SubsurfaceChoice::None => SubsurfaceModel::None,
            SubsurfaceChoice::ThicknessPerLight => thickness_model(false),
            SubsurfaceChoice::ThicknessBaked => match self.gpu.local_thickness {
                LocalThicknessState::Ready => thickness_model(true),
                _ => SubsurfaceModel::skin_screen_space(),
            },
        };
    }

    /// Whether a bake is running, or the dipole's maps are still accumulating (the viewport keeps
    /// repainting: 32 frames of samples, then it rests).
    pub(super) fn baking(&self) -> bool {
        matches!(self.gpu.local_thickness, LocalThicknessState::Baking(_))
            || (self.view.subsurface == SubsurfaceChoice::DirectionalDipole && self.gpu.renderer.dipole_frames() < 32)
    }

    /// The Subsurface panel (left panel, under the light).
    pub(super) fn subsurface_panel(&mut self, ui: &mut egui::Ui) {
        ui.heading("Subsurface");
        let before = self.view.subsurface;
        egui::ComboBox::from_id_salt("subsurface")
            .selected_text(before.label())
            .show_ui(ui, |ui| {
                for c in SubsurfaceChoice::ALL {
                    ui.selectable_value(&mut self.view.subsurface, c, c.label());
                }
            })
            .response
            .on_hover_text(
                "Translucency: light from behind through thin parts (ears, nostrils, lips), \
                 [Barré-Brisebois 2011], with skin1's parameters fitted to a path tracer. Baked: \
                 the thickness of the mesh at rest; per light: from the light's shadow map.",
            );
        if self.view.subsurface != before {
            self.view.needs_render = true;
        }
        match (&self.gpu.local_thickness, self.view.subsurface) {
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
}
