//! The stages of [`super::FramePlan::new`], in the frame's order: each adds its passes (with
//! what they read and write) or says why it adds none.

use super::{Access, PlannedPass, Resource, Skipped, Step};
use crate::aa::EdgeAa;
use crate::cube_atlas::GlobalTerm;
use crate::dielectric_brdf::GpuLaw;
use crate::error::{RenderError, Result};
use crate::local_thickness::ThicknessSource;
use crate::passes::cube_atlas::AtlasStep;
use crate::passes::dipole::DipoleStep;
use crate::passes::edge_overdraw::EdgeStep;
use crate::passes::lighting::LightingStep;
use crate::passes::shadow::ShadowStep;
use crate::passes::sss::{Direction, SssStep};
use crate::passes::thickness::ThicknessUniform;
use crate::passes::{bounce, composite, gbuffer, lighting, skin_gather, thickness};
use crate::scene::{DiffuseLaw, LightKind, Scene, SlabThrough, SubsurfaceModel};
use crate::shader::{ThicknessVariant, Variant};
use crate::sss::SeparableKernel;
use crate::targets::Target;

/// What goes when no thickness pass runs: the pass, the slab law's back-face depth pass and the
/// G-buffer's local-thickness target.
const THICKNESS_PASSES: &str = "thickness pass, back-face depth pass and local-thickness target";

/// The plan as it is built.
#[derive(Debug, Default)]
pub(super) struct Planner {
    pub passes: Vec<PlannedPass>,
    pub skipped: Vec<Skipped>,
}

/// The skin's subsurface model as the frame runs it: at most one of these is set.
#[derive(Debug, Default)]
pub(super) struct Models {
    /// The thickness translucency: its source and uniform.
    pub thickness: Option<(ThicknessVariant, ThicknessUniform)>,
    /// The dipole passes.
    pub dipole: Option<DipoleStep>,
    /// The cube atlas.
    pub atlas: Option<AtlasStep>,
}

impl Models {
    /// The variant's thickness flag.
    pub fn thickness_variant(&self) -> ThicknessVariant {
        self.thickness.map_or(ThicknessVariant::Off, |(v, _)| v)
    }
}

fn targets(t: &[Target]) -> Vec<Resource> {
    t.iter().map(|&t| Resource::Target(t)).collect()
}

impl Planner {
    fn push(&mut self, step: Step, reads: Vec<Resource>, writes: Vec<(Resource, Access)>) {
        self.passes.push(PlannedPass { step, reads, writes });
    }

    pub fn skip(&mut self, what: impl Into<String>, why: impl Into<String>) {
        self.skipped.push(Skipped { what: what.into(), why: why.into() });
    }

    /// One shadow map per shadowing light, in scene order; returns how many. The pass of a map
    /// in `kept` (bit i: layer i) does not run: the map is current.
    pub fn shadows(&mut self, scene: &Scene, kept: u8) -> u32 {
        let mut layer = 0;
        for (light, l) in scene.lights.iter().enumerate() {
            let kind = light_kind(l.kind);
            if l.shadows && kept & (1 << layer) != 0 {
                self.skip(
                    format!("shadow pass for light {light} ({kind})"),
                    format!(
                        "shadow map {layer} is kept from an earlier frame: neither the mesh nor the light has moved"
                    ),
                );
                layer += 1;
            } else if l.shadows {
                self.push(
                    Step::Shadow(ShadowStep { light, layer }),
                    vec![Resource::Mesh, Resource::Light { index: light, kind }],
                    vec![(Resource::ShadowMap(layer), Access::Replace)],
                );
                layer += 1;
            } else {
                self.skip(format!("shadow pass for light {light} ({kind})"), "the light casts no shadow");
            }
        }
        layer
    }

    /// The subsurface model's settings, checked, and what it needs that the scene lacks.
    pub fn subsurface_models(&mut self, scene: &Scene, uploaded: super::Uploaded, shadow_maps: u32) -> Result<Models> {
        Ok(Models {
            thickness: self.thickness_model(scene, uploaded.local_thickness_map, shadow_maps)?,
            dipole: self.dipole_model(scene)?,
            atlas: self.atlas_model(scene)?,
        })
    }

    /// The G-buffer: normals, albedo, the layers' thickness, the local thickness, depth.
    pub fn gbuffer(&mut self, variant: Variant) {
        let mut reads = vec![Resource::Mesh];
        if variant.layers > 0 {
            reads.push(Resource::ThicknessMaps(variant.layers));
        }
        if variant.albedo_map {
            reads.push(Resource::AlbedoMap);
        }
        if variant.normal_map {
            reads.push(Resource::NormalMap);
        }
        if variant.thickness == ThicknessVariant::Baked {
            reads.push(Resource::LocalThicknessMap);
        }
        if variant.skin_detail {
            reads.push(Resource::SkinDetail);
        } else {
            self.skip("skin detail (pores, fine lines, oiliness, wrinkles)", "no skin detail is bound");
        }
        let mut writes = targets(&gbuffer::outputs(variant));
        writes.push(Resource::Target(Target::Depth));
        self.push(Step::Gbuffer(()), reads, writes.into_iter().map(|r| (r, Access::Replace)).collect());
        if variant.layers == 0 {
            self.skip("thickness targets, layer tables and layer lobes", "the look is bare");
        } else if variant.layers <= 4 {
            self.skip("thickness 4-7 target", format!("the look has {} layers", variant.layers));
        }
    }

    /// Says why no glitter is drawn, where none is (the lighting pass names the layers that
    /// have it otherwise).
    pub fn glitter(&mut self, layers: u8, specular: bool) {
        if layers == 0 {
            self.skip("glitter", "none in the look");
        } else if !specular {
            self.skip("glitter", "specular is off");
        }
    }

    /// The half-space law's table when the skin's diffuse law is `half-space`
    /// ([`crate::dielectric_brdf`]), with the curvature of its environment term when the skin has
    /// a medium and the scene an environment ([`crate::curved_half_space`]) and the G-buffer's
    /// normals are the mesh's (`detail_normals`: a normal map or skin detail would put pores into
    /// the curvature); none under Lambert. The plan says what goes.
    ///
    /// # Errors
    /// [`RenderError::Invalid`] for an η outside the law's table (1 ≤ η ≤ 3).
    pub fn half_space_law(&mut self, scene: &Scene, detail_normals: bool) -> Result<Option<GpuLaw>> {
        if scene.skin.diffuse != DiffuseLaw::HalfSpace {
            self.skip("half-space law table", "the skin's diffuse law is Lambert");
            return Ok(None);
        }
        let eta = f64::from(scene.skin.ior);
        if !crate::dielectric_half_space::ETA_RANGE.contains(&eta) {
            return Err(RenderError::Invalid(format!(
                "the half-space diffuse law is tabulated for 1 ≤ η ≤ 3; the skin's η is {eta}"
            )));
        }
        const TERM: &str = "curvature of the half-space law's environment term";
        let curvature = match (&scene.skin.medium, scene.environment.is_some()) {
            (Some(_), true) if detail_normals => {
                self.skip(TERM, "the G-buffer's normals carry a normal map or skin detail, not the mesh's curvature");
                None
            }
            (Some(m), true) => {
                let (alpha, sigma_t) = (m.reduced_albedo(), m.sigma_t_prime_per_mm());
                Some(std::array::from_fn(|c| [alpha[c], sigma_t[c]]))
            }
            (None, _) => {
                self.skip(TERM, "the skin has no medium");
                None
            }
            (_, false) => {
                self.skip(TERM, "the scene has no environment");
                None
            }
        };
        Ok(Some(GpuLaw { eta, curvature }))
    }

    /// Lighting through the cosmetic stack.
    pub fn lighting(&mut self, variant: Variant, glitter: u8, half_space: Option<GpuLaw>) {
        let mut reads = targets(&lighting::inputs(variant));
        if variant.layers > 0 {
            reads.push(Resource::LayerTables);
        }
        if variant.glitter {
            reads.push(Resource::Glitter(glitter));
        }
        if variant.shadows {
            reads.push(Resource::ShadowMaps);
        }
        if variant.env {
            reads.push(Resource::Environment);
        } else {
            self.skip("environment (SH) term", "the scene has no environment");
        }
        let writes = lighting::outputs(variant).into_iter().map(|t| (Resource::Target(t), Access::Replace)).collect();
        self.push(Step::Lighting(LightingStep { half_space }), reads, writes);
    }

    /// The passes of the thickness, dipole or cube-atlas model, added to the diffuse radiance.
    pub fn subsurface_passes(&mut self, variant: Variant, models: Models) {
        let added = vec![(Resource::Target(Target::Diffuse), Access::Add)];
        if let Some((source, uniform)) = models.thickness {
            let mut reads = targets(&thickness::inputs());
            if matches!(source, ThicknessVariant::ShadowMap | ThicknessVariant::Slab) {
                reads.push(Resource::ShadowMaps);
            }
            if source == ThicknessVariant::Slab {
                let back = Resource::Target(Target::BackDepth);
                self.push(Step::BackDepth(()), vec![Resource::Mesh], vec![(back, Access::Replace)]);
                reads.push(back);
            } else {
                self.skip("back-face depth pass", "only the slab law marches the view ray through the mesh");
            }
            self.push(Step::Thickness(uniform), reads, added.clone());
        }
        // What a gather into the skin's pixels reads of the frame.
        let mut gather = targets(&skin_gather::inputs());
        if variant.layers > 0 {
            gather.push(Resource::Target(Target::ExitT));
        }
        if let Some(step) = models.dipole {
            let s = step.settings;
            let (slots, directions) = (step.slots(), s.directions);
            let light_gbuffer = Resource::LightGbuffer { slots, px: s.light_map_px };
            let maps = Resource::RadianceMaps {
                directions,
                px: s.map_px,
                samples: s.samples,
                kind: step.kind.name(),
                progressive: s.progressive,
            };
            let reads = vec![Resource::Mesh, Resource::DirectionalLights(slots)];
            self.push(Step::DipoleLight(step), reads, vec![(light_gbuffer, Access::Replace)]);
            let reads = vec![Resource::Mesh, light_gbuffer];
            self.push(Step::DipoleRadiance(directions), reads, vec![(maps, Access::Replace)]);
            let reads = [gather.as_slice(), &[maps]].concat();
            self.push(Step::DipoleCombine(()), reads, added.clone());
        }
        if let Some(step) = models.atlas {
            let atlas = Resource::CubeAtlas(step.settings.atlas_px);
            let mut reads = vec![Resource::PosedMesh];
            if variant.shadows {
                reads.push(Resource::ShadowMaps);
            }
            if variant.env {
                reads.push(Resource::Environment);
            }
            self.push(Step::AtlasIrradiance(step), reads, vec![(atlas, Access::Replace)]);
            let reads = [gather.as_slice(), &[atlas]].concat();
            self.push(Step::AtlasGather(()), reads, added);
        }
    }

    /// The screen-space blur of `skin` (the diffuse or bounced radiance) when the skin's model is
    /// screen-space and the width is not 0; its kernel, or why it does not run.
    pub fn screen_space(&mut self, scene: &Scene, skin: Target) -> Result<Option<SeparableKernel>> {
        let Some(profile) = scene.skin.subsurface.profile() else {
            self.skip("SSS passes", format!("the skin's subsurface model is {}", scene.skin.subsurface.name()));
            return Ok(None);
        };
        let sss = &scene.sss;
        let kernel = SeparableKernel::new(profile, sss.samples, sss.range_sigmas as f64)?;
        if !sss.runs() {
            self.skip("SSS passes", "the SSS width is 0");
            return Ok(None);
        }
        for direction in [Direction::Horizontal, Direction::Vertical] {
            let (src, dst) = direction.targets(skin);
            let step = SssStep::new((direction, skin), &kernel, sss.width, sss.follow_mm, sss.samples);
            self.push(Step::Sss(step), targets(&[src, Target::Depth]), vec![(Resource::Target(dst), Access::Replace)]);
        }
        Ok(Some(kernel))
    }

    /// The hair pass: the strands as fibres into the hair target, or why not.
    pub fn hair(&mut self, variant: Variant, strands: u32, antialiased: bool) {
        if !variant.hair {
            return self.skip("hair pass", "the mesh has no hair strands (lashes, brows)");
        }
        let mut reads = vec![Resource::Strands(strands), Resource::Target(Target::Depth)];
        if variant.shadows {
            reads.push(Resource::ShadowMaps);
        }
        if variant.env {
            reads.push(Resource::Environment);
        }
        self.push(
            Step::Hair(crate::passes::hair::HairStep { antialiased }),
            reads,
            vec![(Resource::Target(Target::Hair), Access::Blend)],
        );
    }

    /// The bounce between facing parts when the scene asks for it (settings checked), adding to
    /// the skin's diffuse radiance before the blur, which spreads the bounced light as it does
    /// the light that entered from the lights and averages the bounce's per-pixel noise; returns
    /// the skin radiance the blur or the composite reads.
    ///
    /// # Errors
    /// [`RenderError::Invalid`] for settings out of range.
    pub fn bounce(&mut self, scene: &Scene, variant: Variant) -> Result<Target> {
        let Some(settings) = scene.bounce else {
            self.skip("bounce pass and its targets", "light between surfaces is off");
            return Ok(Target::Diffuse);
        };
        settings.check()?;
        let mut reads = bounce::inputs().to_vec();
        if variant.layers > 0 {
            reads.push(Target::ExitT);
        }
        let writes = [Target::BounceLight, Target::Bounced].map(|t| (Resource::Target(t), Access::Replace)).to_vec();
        self.push(Step::Bounce(settings), targets(&reads), writes);
        Ok(Target::Bounced)
    }

    /// Composition of the skin radiance `skin` (diffuse, scattered or bounced) with the surface
    /// radiance.
    pub fn composite(&mut self, variant: Variant, skin: Target) {
        let mut reads = vec![skin, Target::Surface, Target::Normal];
        if variant.layers > 0 {
            reads.push(Target::ExitT);
        }
        if variant.hair {
            reads.push(Target::Hair);
        }
        let out = Resource::Target(composite::output(variant));
        self.push(Step::Composite(skin), targets(&reads), vec![(out, Access::Replace)]);
    }

    /// The edge overdraw after composition, when the frame asks for it and has a display image
    /// to blend into (the linear output is Rgba32Float, which cannot be blended without an
    /// extension).
    pub fn edge_overdraw(&mut self, aa: EdgeAa, display: bool) {
        let (sorted, coverage) = match aa {
            EdgeAa::Off => return self.skip("edge overdraw", "edge antialiasing is off"),
            EdgeAa::Unsorted(c) => (false, c),
            EdgeAa::Sorted(c) => (true, c),
        };
        if !display {
            return self.skip("edge overdraw", "a linear frame has no display image to blend the edges into");
        }
        let reads = vec![Resource::MeshEdges { sorted }, Resource::DisplayCopy];
        self.push(
            Step::EdgeOverdraw(EdgeStep { sorted, coverage }),
            reads,
            vec![(Resource::Target(Target::Display), Access::Blend)],
        );
    }

    /// The render targets the passes read or write, sorted.
    pub fn targets(&self) -> Vec<Target> {
        let mut out: Vec<Target> = self
            .passes
            .iter()
            .flat_map(|p| p.reads.iter().chain(p.writes.iter().map(|(r, _)| r)))
            .filter_map(|r| match r {
                Resource::Target(t) => Some(*t),
                _ => None,
            })
            .collect();
        out.sort();
        out.dedup();
        out
    }

    /// The thickness translucency when the skin's model is `thickness`: off unless the scene has
    /// a light; the baked source needs its map uploaded; the shadow-map source needs a light with
    /// a shadow map (lights without one get no term, and the pass is skipped when none has one).
    fn thickness_model(
        &mut self,
        scene: &Scene,
        local_thickness_map: bool,
        shadow_maps: u32,
    ) -> Result<Option<(ThicknessVariant, ThicknessUniform)>> {
        let (params, source) = match &scene.skin.subsurface {
            SubsurfaceModel::Thickness { params, source, .. } => (params, source),
            SubsurfaceModel::Slab { through, .. } => return self.slab_model(scene, shadow_maps, *through),
            _ => {
                self.skip(THICKNESS_PASSES, "no material uses the thickness model");
                return Ok(None);
            }
        };
        params.check()?;
        if scene.lights.is_empty() {
            self.skip(THICKNESS_PASSES, "the scene has no light");
            return Ok(None);
        }
        let variant = match source {
            ThicknessSource::Baked(_) if !local_thickness_map => {
                return Err(RenderError::Invalid(
                    "the thickness model's baked source needs a local-thickness map: bake one and upload it with \
                     Renderer::set_local_thickness (rouge render does both)"
                        .into(),
                ));
            }
            ThicknessSource::Baked(_) => ThicknessVariant::Baked,
            ThicknessSource::ShadowMap { .. } => {
                let readers = ShadowMapReaders {
                    term: "thickness translucency",
                    why: "the shadow-map source reads the light's shadow map, and the light casts no shadow",
                    none: "no light has a shadow map",
                };
                if !self.shadow_map_readers(scene, shadow_maps, readers) {
                    return Ok(None);
                }
                ThicknessVariant::ShadowMap
            }
        };
        let (falloff, cutoff_mm) = source.falloff();
        Ok(Some((variant, ThicknessUniform::new(*params, falloff, cutoff_mm))))
    }

    /// The slab law's thickness pass: the skin's medium, and a light with a shadow map.
    fn slab_model(
        &mut self,
        scene: &Scene,
        shadow_maps: u32,
        through: SlabThrough,
    ) -> Result<Option<(ThicknessVariant, ThicknessUniform)>> {
        let medium = scene.skin.medium.as_ref().ok_or_else(|| {
            RenderError::Invalid(
                "the slab model needs the skin's physical medium (--medium, or --sigma-a/--sigma-s/--eta)".into(),
            )
        })?;
        let readers = ShadowMapReaders {
            term: "slab translucency",
            why: "the slab law reads the thickness the light crossed from its shadow map, and the light casts none",
            none: "no light has a shadow map for the slab law",
        };
        if !self.shadow_map_readers(scene, shadow_maps, readers) {
            return Ok(None);
        }
        // The gather leaves to the screen-space kernel, where one runs, the light of the entries
        // it reaches and follows in depth.
        let sss = &scene.sss;
        let kernel = scene.skin.subsurface.profile().filter(|_| sss.runs()).map(|p| (sss.reach_mm(p), sss.follow_mm));
        Ok(Some((ThicknessVariant::Slab, ThicknessUniform::slab(medium, kernel, through)?)))
    }

    /// For a thickness pass that reads the lights' shadow maps: each light without one gets no
    /// `term` (the plan says `why`), and with none at all the pass and its target go (saying
    /// `none`). Whether the pass runs.
    fn shadow_map_readers(&mut self, scene: &Scene, shadow_maps: u32, readers: ShadowMapReaders) -> bool {
        for (i, l) in scene.lights.iter().enumerate() {
            if !l.shadows {
                self.skip(format!("{} of light {i}", readers.term), readers.why);
            }
        }
        if shadow_maps == 0 {
            self.skip(THICKNESS_PASSES, readers.none);
        }
        shadow_maps > 0
    }

    /// The dipole passes when the skin's model is a dipole: one light view per directional light
    /// (point lights get no subsurface light from them, and the plan says so).
    fn dipole_model(&mut self, scene: &Scene) -> Result<Option<DipoleStep>> {
        let SubsurfaceModel::Dipole { kind, settings } = &scene.skin.subsurface else {
            self.skip("dipole passes", "no material uses a dipole model");
            return Ok(None);
        };
        settings.check()?;
        let medium = scene.skin.medium.as_ref().ok_or_else(|| {
            RenderError::Invalid(format!(
                "the {} model needs the skin's physical medium (--medium, or --sigma-a/--sigma-s/--eta)",
                kind.name()
            ))
        })?;
        for (i, l) in scene.lights.iter().enumerate() {
            if matches!(l.kind, LightKind::Point { .. }) {
                self.skip(
                    format!("dipole light G-buffer of light {i} (point)"),
                    "the dipole passes take directional lights",
                );
            }
        }
        let step = DipoleStep::new(*kind, medium, *settings, scene);
        if step.lights.is_empty() {
            self.skip("dipole passes", "the scene has no directional light");
            return Ok(None);
        }
        Ok(Some(step))
    }

    /// The cube atlas when the skin's model is `cube-atlas` (settings checked).
    fn atlas_model(&mut self, scene: &Scene) -> Result<Option<AtlasStep>> {
        let SubsurfaceModel::CubeAtlas { settings } = &scene.skin.subsurface else {
            self.skip("cube-atlas passes and atlas", "no material uses the cube-atlas model");
            return Ok(None);
        };
        settings.check()?;
        let medium = scene.skin.medium.as_ref().ok_or_else(|| {
            RenderError::Invalid(
                "the cube-atlas model needs the skin's physical medium (--medium, or --sigma-a/--sigma-s/--eta)".into(),
            )
        })?;
        if settings.global == GlobalTerm::Off {
            self.skip("cube-atlas global term", "switched off");
        }
        Ok(Some(AtlasStep { settings: *settings, medium: medium.clone() }))
    }
}

/// A light's kind in words.
fn light_kind(kind: LightKind) -> &'static str {
    match kind {
        LightKind::Directional { .. } => "directional",
        LightKind::Point { .. } => "point",
    }
}

/// What the plan says of the lights a shadow-map thickness pass cannot read
/// ([`Planner::shadow_map_readers`]).
struct ShadowMapReaders {
    /// The term a light without a shadow map does not get.
    term: &'static str,
    /// Why.
    why: &'static str,
    /// Why the pass goes when no light has a shadow map.
    none: &'static str,
}
