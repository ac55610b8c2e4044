//! The plan in words (`rouge render --explain`): the passes with what they read and write, what
//! is skipped and why, and the skin material.

use super::{Access, FramePlan, Resource};
use crate::scene::{DiffuseLaw, Skin, SlabThrough, SubsurfaceModel};
use std::fmt::{self, Write as _};

impl Resource {
    /// As a pass reads it.
    fn read_text(&self) -> String {
        match *self {
            Resource::Target(t) => t.name().into(),
            Resource::Mesh => "mesh".into(),
            Resource::PosedMesh => "mesh (current positions)".into(),
            Resource::Light { index, kind } => format!("light {index} ({kind})"),
            Resource::DirectionalLights(n) => format!("{n} directional light(s)"),
            Resource::ShadowMap(layer) => format!("shadow map {layer}"),
            Resource::ShadowMaps => "shadow maps".into(),
            Resource::ThicknessMaps(n) => format!("{n} thickness map(s)"),
            Resource::LayerTables => "layer tables".into(),
            Resource::AlbedoMap => "albedo map".into(),
            Resource::NormalMap => "normal map".into(),
            Resource::LocalThicknessMap => "local-thickness map".into(),
            Resource::SkinDetail => "skin detail (relief tile, region map, wrinkle map)".into(),
            Resource::Glitter(mask) => {
                let layers: Vec<String> = (0..8).filter(|i| mask & (1 << i) != 0).map(|i| i.to_string()).collect();
                format!("glitter of layer(s) {} (flake fields)", layers.join(", "))
            }
            Resource::Environment => "SH environment".into(),
            Resource::LightGbuffer { .. } => "light G-buffer".into(),
            Resource::RadianceMaps { .. } => "radiance maps".into(),
            Resource::CubeAtlas(_) => "cube atlas".into(),
            Resource::MeshEdges { sorted: true } => "mesh edges (silhouettes sorted back to front)".into(),
            Resource::MeshEdges { sorted: false } => {
                "mesh edges (unsorted: the CPU's silhouette list, or every edge classified on the GPU)".into()
            }
            Resource::DisplayCopy => "display (a copy)".into(),
            Resource::Strands(n) => format!("{n} hair strands (sorted back to front)"),
        }
    }

    /// As a pass writes it: with its size where the pass makes it.
    fn write_text(&self) -> String {
        match *self {
            Resource::LightGbuffer { slots, px } => format!("light G-buffer ({slots}×{px}², normals + depth)"),
            Resource::RadianceMaps { directions, px, samples, kind, progressive } => format!(
                "{directions} radiance maps {px}² ({samples} {kind} samples a texel{})",
                if progressive { ", accumulated over frames" } else { "" }
            ),
            Resource::CubeAtlas(px) => format!("cube atlas 6×{px}² (irradiance, n·p, normal, depth)"),
            _ => self.read_text(),
        }
    }
}

impl fmt::Display for Access {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(match self {
            Access::Replace => "",
            Access::Add => " (added)",
            Access::Blend => " (blended), depth tested",
        })
    }
}

impl FramePlan {
    /// The plan for people: the passes in order with what they read and write, then what is
    /// skipped and why.
    pub fn explain(&self) -> String {
        self.to_string()
    }
}

impl fmt::Display for FramePlan {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let v = self.variant;
        writeln!(
            f,
            "frame {}×{}, {} output; variant: {} layer(s), shadows {}, environment {}, albedo map {}, normal map {}",
            self.size.0,
            self.size.1,
            if v.display { "tone-mapped sRGB" } else { "linear" },
            v.layers,
            on_off(v.shadows),
            on_off(v.env),
            on_off(v.albedo_map),
            on_off(v.normal_map),
        )?;
        writeln!(f, "{}", self.material)?;
        writeln!(f, "passes:")?;
        for (i, p) in self.passes.iter().enumerate() {
            let reads: Vec<String> = p.reads.iter().map(Resource::read_text).collect();
            let writes: Vec<String> = p.writes.iter().map(|(r, a)| format!("{}{a}", r.write_text())).collect();
            writeln!(f, "  {}. {:<16} {} -> {}", i + 1, p.step.name(), reads.join(", "), writes.join(", "))?;
        }
        if !self.skipped.is_empty() {
            writeln!(f, "skipped:")?;
            for s in &self.skipped {
                writeln!(f, "  - {}: {}", s.what, s.why)?;
            }
        }
        Ok(())
    }
}

fn on_off(b: bool) -> &'static str {
    if b { "on" } else { "off" }
}

/// The skin material in words: its medium, albedo, diffuse law (`curved`: with the curvature of
/// its environment term), subsurface model and the model's settings.
pub(super) fn material(skin: &Skin, curved: bool) -> String {
    let medium = skin.medium.as_ref().map_or("no medium".to_string(), |m| {
        format!("medium {} (σa {:?}, σs′ {:?} mm⁻¹, η {})", m.name, m.sigma_a_per_mm, m.sigma_s_prime_per_mm, m.eta)
    });
    let profile = skin.subsurface.profile().map_or(String::new(), |p| {
        format!(", a profile of {} Gaussians up to σ = {:.2} mm", p.gaussians.len(), p.max_sigma_mm())
    });
    let how = match skin.diffuse {
        DiffuseLaw::Lambert => "",
        DiffuseLaw::HalfSpace if curved => {
            " (adding-doubling's angular law under the boundary of η = the skin's IOR, a table in the lighting pass; \
             the environment's term corrected per pixel for the surface's mean curvature)"
        }
        DiffuseLaw::HalfSpace => {
            " (adding-doubling's angular law under the boundary of η = the skin's IOR, a table in the lighting pass)"
        }
    };
    let law = format!("diffuse law {}{how}", skin.diffuse.name());
    let mut out = format!(
        "skin: {medium}, albedo {:.3}, {:.3}, {:.3}, {law}; subsurface {}{profile}",
        skin.albedo[0],
        skin.albedo[1],
        skin.albedo[2],
        skin.subsurface.name()
    );
    match &skin.subsurface {
        SubsurfaceModel::Thickness { params, source, .. } => {
            let (falloff, cutoff) = source.falloff();
            let _ = write!(
                out,
                " (distortion {}, power {}, scale {}, ambient {}; {} local thickness, falloff {falloff:?} to {cutoff} mm)",
                params.distortion,
                params.power,
                params.scale,
                params.ambient,
                source.name()
            );
        }
        SubsurfaceModel::Slab { through, .. } => {
            if *through == SlabThrough::Gather {
                let _ = write!(
                    out,
                    " (the light that crossed the mesh to a pixel facing away from a directional light: every entry in \
                     its shadow map within the medium's reach, carried by the classic dipole seen through the exit \
                     face with its boundary image, at the medium's exact decay rate, {} samples; elsewhere",
                    through.gather_samples()
                );
            }
            let _ = write!(
                out,
                " (each shadowed light through a plane slab of the medium, exactly: adding-doubling's table of \
                 all but single scattering, which is marched along the view ray to the back faces' depth, each \
                 point lit through its path in the shadow map (16 points; in closed form where no back face is \
                 drawn, and its paths reflected once inside), under the medium's boundary (η {}: the faces' Fresnel \
                 transmittance and the light they hold inside); the thickness the light crossed from its shadow map, \
                 the face it entered from the map's slope; over the share of the slab's plane the map holds and, for \
                 directional lights, drained toward the edges where the face meets a side face the light does \
                 not reach (found in the G-buffer, 8 directions; the strongest drain); beside it, for directional lights, the light \
                 entering within the medium's reach that neither the lighting nor the kernel carries (faces the \
                 camera does not see, and seen ones beyond the kernel's reach or depth), from the map, carried by \
                 the classic dipole ({} samples))",
                skin.medium.as_ref().map_or(1.0, |m| m.eta),
                through.gather_samples()
            );
            if *through == SlabThrough::Gather {
                out.push(')');
            }
        }
        SubsurfaceModel::CubeAtlas { settings: a } => {
            let _ = write!(
                out,
                " (atlas 6×{}², kernel {k}×{k} taps, reach {}{}, self-occlusion test {}, global term {})",
                a.atlas_px,
                a.reach.name(),
                if a.adaptive { " × n·a" } else { "" },
                a.occlusion.name(),
                a.global.name(),
                k = a.kernel_max,
            );
        }
        _ => {}
    }
    out
}
