//! Skin under a cosmetic layer as the renderer draws it, against the spectral computation: the
//! renderer's side of `rouge bench skin` and of its tests.
//!
//! A flat patch lit from the front by white light of irradiance π (so a reflectance R shows as
//! radiance R), no specular, no environment, subsurface off, linear output: what is left is the
//! diffuse colour of skin under the layer, which the lighting pass composes per channel of the
//! compositing basis ([`rouge_measure::compositing::CompositingBasis`]). The reference is the
//! layer composed over the skin's reflectance at every wavelength
//! ([`rouge_measure::analysis::Layer::reflectance_over`], \[Huang2013\] eq. 3-4), as CIELAB of its
//! linear sRGB (D65).
//!
//! - [`SkinPatch`]: renders the patch's centre for a skin and a layer.
//! - [`spot_coverage`]: coverage on screen against coverage on paper: the ΔE2000 between a spot
//!   (a condition at full strength) and the skin around it, rendered under a layer of thickness
//!   d, against what `rouge analyze coverage` predicts for the same spectra.

use crate::error::{RenderError, Result};
use crate::renderer::LayerInput;
use crate::{Camera, Gpu, Renderer, Scene, Skin, SubsurfaceModel};
use glam::Vec3;
use rouge_measure::analysis::Layer;
use rouge_measure::analysis::coverage::{ContrastChart, coverage_table};
use rouge_measure::colorimetry::{Colorimeter, Viewing, delta_e_2000_raw, linear_srgb_to_lab};
use rouge_measure::preset::Preset;
use rouge_measure::skin::{SkinColorTable, SkinParams};
use rouge_measure::spectrum::Spectrum;
use rouge_model::look::ThicknessMap;
use rouge_model::mesh::TriangleMesh;
use rouge_model::skin::generate::at_full_strength;
use rouge_model::skin::{Condition, SkinChannel, SkinMaps};

/// Where the skin's colour comes from.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum SkinColour {
    /// The skin's colour as one uniform albedo (`rouge render --skin-tone`).
    Albedo,
    /// Uniform skin maps of the skin through its colour table and the 8-bit albedo texture (what
    /// `rouge render --skin-maps` draws).
    Maps,
}

impl SkinColour {
    /// Its name in tables.
    pub const fn name(self) -> &'static str {
        match self {
            SkinColour::Albedo => "tone albedo",
            SkinColour::Maps => "skin maps",
        }
    }
}

/// A flat patch of skin on the GPU, ready to be rendered under one layer at a time.
pub struct SkinPatch {
    renderer: Renderer,
    mesh: TriangleMesh,
    scene: Scene,
    camera: Camera,
    /// The colour table of the last tone, kept: building one takes seconds.
    table: Option<(SkinParams, SkinColorTable)>,
}

impl std::fmt::Debug for SkinPatch {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("SkinPatch").field("camera", &self.camera).finish_non_exhaustive()
    }
}

/// Pixels per side of the rendered patch (its centre pixel is read).
const PATCH_PX: u32 = 8;

impl SkinPatch {
    /// A patch on `gpu`, skin not yet set.
    ///
    /// # Errors
    /// The mesh upload failing.
    pub fn new(gpu: &Gpu) -> Result<SkinPatch> {
        let mut renderer = Renderer::new(&gpu.device, &gpu.queue);
        let mesh = TriangleMesh::flat_square(100.0);
        let mut scene = Scene::white_light(Vec3::Z);
        scene.specular = false;
        scene.environment = None;
        scene.skin.subsurface = SubsurfaceModel::None;
        renderer.set_mesh(&mesh, scene.skin.albedo)?;
        let bounds = renderer.mesh_bounds().ok_or_else(|| RenderError::Invalid("the patch has no bounds".into()))?;
        let camera = Camera::framing(&bounds, 0.0, 0.0);
        Ok(SkinPatch { renderer, mesh, scene, camera, table: None })
    }

    /// Sets the skin to `params`, coloured as `colour` says; returns its reflectance spectrum.
    ///
    /// # Errors
    /// Parameters outside the skin model's domain, named.
    pub fn set_skin(&mut self, params: &SkinParams, colour: SkinColour) -> Result<Spectrum> {
        self.set_skin_of_tone(params, params, colour)
    }

    /// [`SkinPatch::set_skin`] for skin of `params` on a face of tone `base`: with skin maps, one
    /// texel of `params` in maps whose base is `base`, through `base`'s colour table, as the
    /// generated maps draw a spot (`params` within the maps' ranges around `base`).
    ///
    /// # Errors
    /// Parameters outside the skin model's domain or the maps' ranges, named.
    pub fn set_skin_of_tone(&mut self, base: &SkinParams, params: &SkinParams, colour: SkinColour) -> Result<Spectrum> {
        let invalid = |e: String| RenderError::Invalid(format!("skin: {e}"));
        let reflectance = params.reflectance().map_err(|e| invalid(e.to_string()))?;
        self.scene.skin = Skin { subsurface: SubsurfaceModel::None, ..Skin::from_spectrum(&reflectance) };
        self.renderer.set_mesh(&self.mesh, self.scene.skin.albedo)?;
        let albedo = match colour {
            SkinColour::Albedo => None,
            SkinColour::Maps => {
                let planes = SkinChannel::ALL.map(|c| vec![c.of(params) as f32]);
                let maps = SkinMaps::from_planes(1, 1, base, planes).map_err(invalid)?;
                if self.table.as_ref().is_none_or(|(b, _)| b != maps.base()) {
                    self.table = Some((*maps.base(), crate::job::skin_color_table(maps.base())?));
                }
                self.table.as_ref().map(|(_, table)| crate::job::bake_skin_albedo(&maps, table))
            }
        };
        self.renderer.set_textures(albedo.as_ref(), None)?;
        Ok(reflectance)
    }

    /// Linear sRGB of the patch's centre under `preset` at `thickness_um` (µm, ≥ 0).
    ///
    /// # Errors
    /// A thickness that is negative or not finite, or a GPU failure.
    pub fn render(&mut self, preset: &Preset, thickness_um: f64) -> Result<[f64; 3]> {
        if !(thickness_um >= 0.0 && thickness_um.is_finite()) {
            return Err(RenderError::Invalid(format!("thickness {thickness_um} µm must be finite and ≥ 0")));
        }
        let map = ThicknessMap::uniform((thickness_um * 1e-3) as f32);
        self.renderer.set_layers(&[LayerInput { preset, map: &map, multiplier: 1.0 }])?;
        self.renderer.render(&self.scene, &self.camera, PATCH_PX, PATCH_PX, false)?;
        let pixels = self.renderer.read_linear()?;
        let centre = pixels[(PATCH_PX * PATCH_PX / 2 + PATCH_PX / 2) as usize];
        Ok([0, 1, 2].map(|c| f64::from(centre[c])))
    }
}

/// CIELAB of `preset` at `thickness_um` over a skin of reflectance `skin`, composed at every
/// wavelength (the reference), in the renderer's CIELAB (linear sRGB, D65 white).
pub fn reference_lab(preset: &Preset, thickness_um: f64, skin: &Spectrum) -> [f64; 3] {
    let c = Colorimeter::get(Viewing::D65_1931);
    let layer = Layer { name: preset.name.clone(), s: preset.s(), k: preset.k() };
    linear_srgb_to_lab(c.srgb_linear(&c.xyz(&layer.reflectance_over(thickness_um * 1e-3, skin))))
}

/// One thickness of [`spot_coverage`].
#[derive(Clone, Debug, PartialEq, serde::Serialize)]
pub struct SpotRow {
    /// Layer thickness, µm.
    pub thickness_um: f64,
    /// ΔE2000 between spot and skin under the layer, as `rouge analyze coverage` predicts it
    /// (its CIELAB of each skin under the film).
    pub paper_delta_e: f64,
    /// The same, rendered.
    pub screen_delta_e: f64,
}

/// Coverage on screen against coverage on paper: a spot of `condition` at full strength on a
/// skin of `base` ([`at_full_strength`]), under `preset` at each of `thickness_um`.
///
/// # Errors
/// A skin outside the model's domain, a bad thickness or a GPU failure.
pub fn spot_coverage(
    patch: &mut SkinPatch,
    base: &SkinParams,
    condition: Condition,
    preset: &Preset,
    thickness_um: &[f64],
    colour: SkinColour,
) -> Result<Vec<SpotRow>> {
    let spot = at_full_strength(base, condition);
    let c = Colorimeter::get(Viewing::D65_1931);
    let skins = [
        ("skin".to_string(), patch.set_skin(base, colour)?),
        ("spot".to_string(), spot.reflectance().map_err(|e| RenderError::Invalid(format!("spot: {e}")))?),
    ];
    let layer = Layer { name: preset.name.clone(), s: preset.s(), k: preset.k() };
    let xs: Vec<f64> = thickness_um.iter().map(|um| um * 1e-3).collect();
    let paper = coverage_table(&layer, &xs, ContrastChart::default(), &skins, c)
        .map_err(|e| RenderError::Invalid(format!("coverage: {e}")))?;
    let mut around = Vec::with_capacity(thickness_um.len());
    for &um in thickness_um {
        around.push(linear_srgb_to_lab(patch.render(preset, um)?));
    }
    patch.set_skin_of_tone(base, &spot, colour)?;
    let mut rows = Vec::with_capacity(thickness_um.len());
    for ((&um, row), around) in thickness_um.iter().zip(&paper).zip(around) {
        let on_spot = linear_srgb_to_lab(patch.render(preset, um)?);
        rows.push(SpotRow {
            thickness_um: um,
            paper_delta_e: delta_e_2000_raw(row.lab_on_skin[0], row.lab_on_skin[1]),
            screen_delta_e: delta_e_2000_raw(around, on_spot),
        });
    }
    Ok(rows)
}
