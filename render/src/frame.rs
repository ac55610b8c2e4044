//! The frame plan: from the scene, what the renderer has uploaded (the look's layers, the skin's
//! maps) and the frame settings, which passes run, in which order, reading and writing which
//! targets, and what is skipped and why. [`crate::Renderer::render`] walks it; `rouge render
//! --explain` prints it.
//!
//! Only what the scene uses runs or is allocated: no shadow pass for a light that casts no
//! shadow; no SSS passes (nor their targets) when the skin's subsurface model is `none` or the
//! width is 0; no thickness targets, table lookups or layer lobes for a bare look; no SH code
//! without an environment. Shaders are specialised per [`Variant`] accordingly.

use crate::aa::EdgeAa;
use crate::error::{RenderError, Result};
use crate::local_thickness::ThicknessSource;
use crate::passes::sss::Direction;
use crate::passes::{composite, gbuffer, lighting};
use crate::scene::{LightKind, Scene, SubsurfaceModel};
use crate::shader::{ThicknessVariant, Variant};
use crate::sss::SeparableKernel;
use crate::targets::Target;
use crate::uniforms::MAX_LIGHTS;
use std::fmt::Write as _;

/// What the renderer has uploaded that the plan depends on.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Uploaded {
    /// Layers of the look (0 = bare).
    pub layers: u32,
    /// A skin albedo texture is bound.
    pub albedo_map: bool,
    /// A normal map is bound.
    pub normal_map: bool,
    /// A baked local-thickness map is bound ([`crate::Renderer::set_local_thickness`]).
    pub local_thickness_map: bool,
}

/// The output of a frame.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct FrameSettings {
    /// Width, pixels.
    pub width: u32,
    /// Height, pixels.
    pub height: u32,
    /// Tone-mapped sRGB (true) or linear radiance (false).
    pub display: bool,
    /// The largest texture side the device takes.
    pub max_side: u32,
    /// Discontinuity edge overdraw ([Sander2001]).
    pub aa: EdgeAa,
}

/// One step of the frame.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Step {
    /// Depth of the mesh from scene light `light` into shadow map `layer`.
    Shadow {
        /// The light's index in the scene.
        light: usize,
        /// Its layer of the shadow-map array.
        layer: u32,
    },
    /// The G-buffer.
    Gbuffer,
    /// Lighting through the cosmetic stack.
    Lighting,
    /// Thickness translucency added to the skin's diffuse radiance.
    Thickness,
    /// The dipole models' light G-buffer, one view per directional light.
    DipoleLight {
        /// Light views.
        slots: u32,
    },
    /// The dipole models' K radiance maps.
    DipoleRadiance,
    /// The dipole models' combination, added to the skin's diffuse radiance.
    DipoleCombine,
    /// The cube atlas's six faces of irradiance, drawn from the current mesh.
    AtlasIrradiance,
    /// The cube atlas's gather, added to the skin's diffuse radiance.
    AtlasGather,
    /// One direction of the screen-space scattering blur.
    Sss(Direction),
    /// Composition of `skin` (diffuse or scattered) with the surface radiance.
    Composite {
        /// The skin radiance composed.
        skin: Target,
    },
    /// Discontinuity edges drawn over the display image ([Sander2001]).
    EdgeOverdraw {
        /// Silhouettes and near-silhouette sharp edges sorted back to front on the CPU.
        sorted: bool,
    },
}

/// A planned pass with what it reads and writes.
#[derive(Clone, Debug, PartialEq)]
pub struct PlannedPass {
    /// The step.
    pub step: Step,
    /// What it reads (targets and uploaded data), by name.
    pub reads: Vec<String>,
    /// The targets it writes.
    pub writes: Vec<String>,
}

/// A pass, target or piece of shader code left out, and why.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Skipped {
    /// What is left out.
    pub what: String,
    /// Why.
    pub why: String,
}

/// The plan of one frame.
#[derive(Clone, Debug)]
pub struct FramePlan {
    /// Width and height, pixels.
    pub size: (u32, u32),
    /// The shader variant.
    pub variant: Variant,
    /// The passes, in order.
    pub passes: Vec<PlannedPass>,
    /// What is left out, and why.
    pub skipped: Vec<Skipped>,
    /// Shadow maps needed.
    pub shadow_maps: u32,
    /// The separable kernel, when the SSS passes run.
    pub kernel: Option<SeparableKernel>,
    /// The render targets the passes use.
    pub targets: Vec<Target>,
    /// The skin material in words: its medium, albedo and subsurface model.
    pub material: String,
}

fn names(targets: &[Target]) -> Vec<String> {
    targets.iter().map(|t| t.name().to_string()).collect()
}

fn skip(what: impl Into<String>, why: impl Into<String>) -> Skipped {
    Skipped { what: what.into(), why: why.into() }
}

impl FramePlan {
    /// Plans a frame of `scene` with the `uploaded` look and maps at `settings`.
    ///
    /// # Errors
    /// [`RenderError::Invalid`] for a zero or oversized image, too many lights, a negative or
    /// non-finite SSS width, or an SSS sample count or range the kernel refuses.
    pub fn new(scene: &Scene, uploaded: Uploaded, settings: FrameSettings) -> Result<FramePlan> {
        let (width, height, max) = (settings.width, settings.height, settings.max_side);
        if width == 0 || height == 0 || width > max || height > max {
            return Err(RenderError::Invalid(format!("image size {width}×{height}: each side must be 1 to {max}")));
        }
        if scene.lights.len() > MAX_LIGHTS {
            return Err(RenderError::Invalid(format!(
                "{} lights: the renderer takes at most {MAX_LIGHTS}",
                scene.lights.len()
            )));
        }
        if !(scene.sss.width.is_finite() && scene.sss.width >= 0.0) {
            return Err(RenderError::Invalid(format!("SSS width {}: must be ≥ 0", scene.sss.width)));
        }
        let mut passes = Vec::new();
        let mut skipped = Vec::new();

        // Shadows: one map per shadowing light, in scene order.
        let mut shadow_maps = 0;
        for (light, l) in scene.lights.iter().enumerate() {
            let kind = match l.kind {
                LightKind::Directional { .. } => "directional",
                LightKind::Point { .. } => "point",
            };
            if l.shadows {
                passes.push(PlannedPass {
                    step: Step::Shadow { light, layer: shadow_maps },
                    reads: vec![format!("mesh, light {light} ({kind})")],
                    writes: vec![format!("shadow map {shadow_maps}")],
                });
                shadow_maps += 1;
            } else {
                skipped.push(skip(format!("shadow pass for light {light} ({kind})"), "the light casts no shadow"));
            }
        }
        let thickness = thickness_variant(scene, uploaded, shadow_maps, &mut skipped)?;
        let dipole_slots = dipole_slots(scene, &mut skipped)?;
        let atlas = atlas_settings(scene, &mut skipped)?;
        let variant = Variant {
            layers: uploaded.layers,
            shadows: shadow_maps > 0,
            env: scene.environment.is_some(),
            display: settings.display,
            albedo_map: uploaded.albedo_map,
            normal_map: uploaded.normal_map,
            thickness,
            dipole: dipole_slots.is_some() || atlas.is_some(),
            atlas: atlas.is_some(),
        };

        // G-buffer.
        let mut gbuffer_reads = vec!["mesh".to_string()];
        if variant.layers > 0 {
            gbuffer_reads.push(format!("{} thickness map(s)", variant.layers));
        }
        if variant.albedo_map {
            gbuffer_reads.push("albedo map".into());
        }
        if variant.normal_map {
            gbuffer_reads.push("normal map".into());
        }
        if variant.thickness == ThicknessVariant::Baked {
            gbuffer_reads.push("local-thickness map".into());
        }
        let mut gbuffer_writes = gbuffer::outputs(variant);
        gbuffer_writes.push(Target::Depth);
        passes.push(PlannedPass { step: Step::Gbuffer, reads: gbuffer_reads, writes: names(&gbuffer_writes) });
        if variant.layers == 0 {
            skipped.push(skip("thickness targets, layer tables and layer lobes", "the look is bare"));
        } else if variant.layers <= 4 {
            skipped.push(skip("thickness 4-7 target", format!("the look has {} layers", variant.layers)));
        }

        // Lighting.
        let mut lighting_reads = names(&lighting::inputs(variant));
        if variant.layers > 0 {
            lighting_reads.push("layer tables".into());
        }
        if variant.shadows {
            lighting_reads.push("shadow maps".into());
        }
        if variant.env {
            lighting_reads.push("SH environment".into());
        } else {
            skipped.push(skip("environment (SH) term", "the scene has no environment"));
        }
        passes.push(PlannedPass {
            step: Step::Lighting,
            reads: lighting_reads,
            writes: names(&lighting::outputs(variant)),
        });

        if variant.thickness != ThicknessVariant::Off {
            let mut reads = names(&crate::passes::thickness::inputs());
            if variant.thickness == ThicknessVariant::ShadowMap {
                reads.push("shadow maps".into());
            }
            passes.push(PlannedPass {
                step: Step::Thickness,
                reads,
                writes: vec![format!("{} (added)", Target::Diffuse.name())],
            });
        }

        if let (Some(slots), SubsurfaceModel::Dipole { kind, settings }) = (dipole_slots, &scene.skin.subsurface) {
            passes.push(PlannedPass {
                step: Step::DipoleLight { slots },
                reads: vec![format!("mesh, {slots} directional light(s)")],
                writes: vec![format!("light G-buffer ({slots}×{}², normals + depth)", settings.light_map_px)],
            });
            passes.push(PlannedPass {
                step: Step::DipoleRadiance,
                reads: vec!["mesh".into(), "light G-buffer".into()],
                writes: vec![format!(
                    "{} radiance maps {}² ({} {} samples a texel{})",
                    settings.directions,
                    settings.map_px,
                    settings.samples,
                    kind.name(),
                    if settings.progressive { ", accumulated over frames" } else { "" }
                )],
            });
            let mut reads = names(&crate::passes::skin_gather::inputs());
            if variant.layers > 0 {
                reads.push(Target::ExitT.name().into());
            }
            reads.push("radiance maps".into());
            passes.push(PlannedPass {
                step: Step::DipoleCombine,
                reads,
                writes: vec![format!("{} (added)", Target::Diffuse.name())],
            });
        }

        if let Some(a) = atlas {
            let mut reads = vec!["mesh (current positions)".to_string()];
            if variant.shadows {
                reads.push("shadow maps".into());
            }
            if variant.env {
                reads.push("SH environment".into());
            }
            passes.push(PlannedPass {
                step: Step::AtlasIrradiance,
                reads,
                writes: vec![format!("cube atlas 6×{}² (irradiance, n·p, normal, depth)", a.atlas_px)],
            });
            let mut reads = names(&crate::passes::skin_gather::inputs());
            if variant.layers > 0 {
                reads.push(Target::ExitT.name().into());
            }
            reads.push("cube atlas".into());
            passes.push(PlannedPass {
                step: Step::AtlasGather,
                reads,
                writes: vec![format!("{} (added)", Target::Diffuse.name())],
            });
        }

        // The skin's subsurface model.
        let kernel = match &scene.skin.subsurface {
            SubsurfaceModel::CubeAtlas { .. } => {
                skipped.push(skip("SSS passes", "the skin's subsurface model is cube-atlas"));
                None
            }
            SubsurfaceModel::Dipole { kind, .. } => {
                skipped.push(skip("SSS passes", format!("the skin's subsurface model is {}", kind.name())));
                None
            }
            SubsurfaceModel::None => {
                skipped.push(skip("SSS passes", "the skin's subsurface model is none"));
                None
            }
            SubsurfaceModel::Thickness { .. } => {
                skipped.push(skip("SSS passes", "the skin's subsurface model is thickness"));
                None
            }
            SubsurfaceModel::ScreenSpace { profile } => {
                let kernel = SeparableKernel::new(profile, scene.sss.samples, scene.sss.range_sigmas as f64)?;
                if scene.sss.width > 0.0 || scene.sss.run_at_zero_width {
                    for direction in [Direction::Horizontal, Direction::Vertical] {
                        let (src, dst) = direction.targets();
                        passes.push(PlannedPass {
                            step: Step::Sss(direction),
                            reads: names(&[src, Target::Depth]),
                            writes: names(&[dst]),
                        });
                    }
                    Some(kernel)
                } else {
                    skipped.push(skip("SSS passes", "the SSS width is 0"));
                    None
                }
            }
        };

        // Composite.
        let skin = if kernel.is_some() { Target::Scattered } else { Target::Diffuse };
        let mut composite_reads = vec![skin, Target::Surface, Target::Normal];
        if variant.layers > 0 {
            composite_reads.push(Target::ExitT);
        }
        let out = composite::output(variant);
        passes.push(PlannedPass {
            step: Step::Composite { skin },
            reads: names(&composite_reads),
            writes: names(&[out]),
        });

        edge_overdraw_step(settings.aa, variant.display, &mut passes, &mut skipped);

        let mut targets: Vec<Target> = gbuffer_writes;
        targets.extend(lighting::outputs(variant));
        if kernel.is_some() {
            targets.extend([Target::SssScratch, Target::Scattered]);
        }
        targets.push(out);
        targets.sort();
        targets.dedup();
        let skin = &scene.skin;
        let medium = skin.medium.as_ref().map_or("no medium".to_string(), |m| {
            format!("medium {} (σa {:?}, σs′ {:?} mm⁻¹, η {})", m.name, m.sigma_a_per_mm, m.sigma_s_prime_per_mm, m.eta)
        });
        let profile = skin.subsurface.profile().map_or(String::new(), |p| {
            format!(", a profile of {} Gaussians up to σ = {:.2} mm", p.gaussians.len(), p.max_sigma_mm())
        });
        let thickness_text = match &skin.subsurface {
            SubsurfaceModel::Thickness { params, source } => {
                let (falloff, cutoff) = source.falloff();
                format!(
                    " (distortion {}, power {}, scale {}, ambient {}; {} local thickness, falloff {falloff:?} to {cutoff} mm)",
                    params.distortion,
                    params.power,
                    params.scale,
                    params.ambient,
                    source.name()
                )
            }
            SubsurfaceModel::CubeAtlas { settings: a } => format!(
                " (atlas 6×{}², kernel {k}×{k} taps, reach {}{}, self-occlusion test {}, global term {})",
                a.atlas_px,
                a.reach.name(),
                if a.adaptive { " × n·a" } else { "" },
                a.occlusion.name(),
                a.global.name(),
                k = a.kernel_max,
            ),
            _ => String::new(),
        };
        let material = format!(
            "skin: {medium}, albedo {:.3}, {:.3}, {:.3}; subsurface {}{profile}{thickness_text}",
            skin.albedo[0],
            skin.albedo[1],
            skin.albedo[2],
            skin.subsurface.name()
        );
        Ok(FramePlan { size: (width, height), variant, passes, skipped, shadow_maps, kernel, targets, material })
    }

    /// The plan for people: the passes in order with what they read and write, then what is
    /// skipped and why.
    pub fn explain(&self) -> String {
        let mut out = String::new();
        let v = self.variant;
        let _ = writeln!(
            out,
            "frame {}×{}, {} output; variant: {} layer(s), shadows {}, environment {}, albedo map {}, normal map {}",
            self.size.0,
            self.size.1,
            if v.display { "tone-mapped sRGB" } else { "linear" },
            v.layers,
            on_off(v.shadows),
            on_off(v.env),
            on_off(v.albedo_map),
            on_off(v.normal_map),
        );
        let _ = writeln!(out, "{}", self.material);
        let _ = writeln!(out, "passes:");
        for (i, p) in self.passes.iter().enumerate() {
            let _ = writeln!(
                out,
                "  {}. {:<16} {} -> {}",
                i + 1,
                step_name(p.step),
                p.reads.join(", "),
                p.writes.join(", ")
            );
        }
        if !self.skipped.is_empty() {
            let _ = writeln!(out, "skipped:");
            for s in &self.skipped {
                let _ = writeln!(out, "  - {}: {}", s.what, s.why);
            }
        }
        out
    }
}

/// The light views of the dipole passes when the skin's model is a dipole: one per directional
/// light (point lights get no subsurface light from it, and the plan says so); `None` otherwise.
fn dipole_slots(scene: &Scene, skipped: &mut Vec<Skipped>) -> Result<Option<u32>> {
    let SubsurfaceModel::Dipole { kind, settings } = &scene.skin.subsurface else {
        skipped.push(skip("dipole passes", "no material uses a dipole model"));
        return Ok(None);
    };
    settings.check()?;
    if scene.skin.medium.is_none() {
        return Err(RenderError::Invalid(format!(
            "the {} model needs the skin's physical medium (--medium, or --sigma-a/--sigma-s/--eta)",
            kind.name()
        )));
    }
    for (i, l) in scene.lights.iter().enumerate() {
        if matches!(l.kind, LightKind::Point { .. }) {
            skipped.push(skip(
                format!("dipole light G-buffer of light {i} (point)"),
                "the dipole passes take directional lights",
            ));
        }
    }
    let slots = crate::passes::dipole::dipole_lights(scene).len().min(MAX_LIGHTS) as u32;
    if slots == 0 {
        skipped.push(skip("dipole passes", "the scene has no directional light"));
        return Ok(None);
    }
    Ok(Some(slots))
}

/// The cube atlas's settings when the skin's model is `cube-atlas` (checked), `None` otherwise.
fn atlas_settings(scene: &Scene, skipped: &mut Vec<Skipped>) -> Result<Option<crate::cube_atlas::AtlasSettings>> {
    let SubsurfaceModel::CubeAtlas { settings } = &scene.skin.subsurface else {
        skipped.push(skip("cube-atlas passes and atlas", "no material uses the cube-atlas model"));
        return Ok(None);
    };
    settings.check()?;
    if scene.skin.medium.is_none() {
        return Err(RenderError::Invalid(
            "the cube-atlas model needs the skin's physical medium (--medium, or --sigma-a/--sigma-s/--eta)".into(),
        ));
    }
    if settings.global == crate::cube_atlas::GlobalTerm::Off {
        skipped.push(skip("cube-atlas global term", "switched off"));
    }
    Ok(Some(*settings))
}

/// Which thickness translucency the frame runs: off unless the skin's model is `thickness`; the
/// baked source needs its map uploaded; the shadow-map source needs a light with a shadow map
/// (lights without one get no term, and the pass is skipped when none has one).
fn thickness_variant(
    scene: &Scene,
    uploaded: Uploaded,
    shadow_maps: u32,
    skipped: &mut Vec<Skipped>,
) -> Result<ThicknessVariant> {
    let SubsurfaceModel::Thickness { params, source } = &scene.skin.subsurface else {
        skipped.push(skip("thickness pass and local-thickness target", "no material uses the thickness model"));
        return Ok(ThicknessVariant::Off);
    };
    params.check()?;
    if scene.lights.is_empty() {
        skipped.push(skip("thickness pass and local-thickness target", "the scene has no light"));
        return Ok(ThicknessVariant::Off);
    }
    match source {
        ThicknessSource::Baked(_) if !uploaded.local_thickness_map => Err(RenderError::Invalid(
            "the thickness model's baked source needs a local-thickness map: bake one and upload it with \
             Renderer::set_local_thickness (rouge render does both)"
                .into(),
        )),
        ThicknessSource::Baked(_) => Ok(ThicknessVariant::Baked),
        ThicknessSource::ShadowMap { .. } => {
            for (i, l) in scene.lights.iter().enumerate() {
                if !l.shadows {
                    skipped.push(skip(
                        format!("thickness translucency of light {i}"),
                        "the shadow-map source reads the light's shadow map, and the light casts no shadow",
                    ));
                }
            }
            if shadow_maps == 0 {
                skipped.push(skip("thickness pass and local-thickness target", "no light has a shadow map"));
                return Ok(ThicknessVariant::Off);
            }
            Ok(ThicknessVariant::ShadowMap)
        }
    }
}

/// The edge overdraw after composition, when the frame asks for it and has a display image to
/// blend into (the linear output is Rgba32Float, which cannot be blended without an extension).
fn edge_overdraw_step(aa: EdgeAa, display: bool, passes: &mut Vec<PlannedPass>, skipped: &mut Vec<Skipped>) {
    let sorted = match aa {
        EdgeAa::Off => {
            skipped.push(skip("edge overdraw", "edge antialiasing is off"));
            return;
        }
        EdgeAa::Unsorted(_) => false,
        EdgeAa::Sorted(_) => true,
    };
    if !display {
        skipped.push(skip("edge overdraw", "a linear frame has no display image to blend the edges into"));
        return;
    }
    let order = if sorted { "silhouettes sorted back to front" } else { "classified on the GPU, unsorted" };
    passes.push(PlannedPass {
        step: Step::EdgeOverdraw { sorted },
        reads: vec![format!("mesh edges ({order})"), "display (a copy)".into()],
        writes: vec![format!("{} (blended), depth tested", Target::Display.name())],
    });
}

fn on_off(b: bool) -> &'static str {
    if b { "on" } else { "off" }
}

/// The name of a step, as in timings and `--explain`.
pub fn step_name(step: Step) -> String {
    match step {
        Step::Shadow { layer, .. } => format!("shadow {layer}"),
        Step::Gbuffer => "gbuffer".into(),
        Step::Lighting => "lighting".into(),
        Step::Thickness => "thickness".into(),
        Step::DipoleLight { .. } => "dipole light".into(),
        Step::DipoleRadiance => "dipole radiance".into(),
        Step::DipoleCombine => "dipole combine".into(),
        Step::AtlasIrradiance => "atlas irradiance".into(),
        Step::AtlasGather => "atlas gather".into(),
        Step::Sss(d) => d.label().into(),
        Step::Composite { .. } => "composite".into(),
        Step::EdgeOverdraw { .. } => "edge overdraw".into(),
    }
}

#[cfg(test)]
mod tests;
