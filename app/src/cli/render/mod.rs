//! `rouge render`: one frame of the renderer to a PNG (tone-mapped) or an EXR (linear radiance).

pub mod atlas_args;
pub mod dipole_args;
pub mod scene_args;
pub mod thickness_args;

use crate::cli::render::atlas_args::AtlasArgs;
use crate::cli::render::dipole_args::DipoleArgs;
use crate::cli::render::scene_args::SceneArgs;
use crate::cli::render::thickness_args::{BakePose, ThicknessArgs};
use anyhow::{Result, bail};
use clap::Args;
use rouge_model::thickness::CacheUse;
use rouge_render::DipoleKind;
use rouge_render::bounce::BounceSettings;
use rouge_render::job::render_to_file;
use rouge_render::{SlabThrough, SubsurfaceModel};
use std::path::PathBuf;
use std::time::Instant;

// clap prints these doc comments as `--help` verbatim: citations stay `[Key]` (`\[Key\]` would show).
#[allow(rustdoc::broken_intra_doc_links)]
#[derive(Debug, Args)]
pub struct RenderArgs {
    #[command(flatten)]
    pub scene: SceneArgs,
    /// Subsurface scattering width (1 = measured skin profile, 0 = none).
    #[arg(long, default_value_t = 1.0)]
    pub sss_width: f32,
    /// SSS kernel samples per direction (odd, 3-33); 11 is where the error against the
    /// brute-force reference stops falling (docs/BENCHMARKS.md).
    #[arg(long, default_value_t = 11)]
    pub sss_samples: u32,
    /// Exposure multiplier before tone mapping (PNG only).
    #[arg(long, default_value_t = 1.0)]
    pub exposure: f32,
    /// Turn off every specular lobe.
    #[arg(long)]
    pub no_specular: bool,
    /// Subsurface model of the skin: the screen-space separable kernel of d'Eon's skin profile
    /// (or of the --medium's profile), fast thickness translucency (light through thin parts
    /// from behind: ears, nostrils; [BarreBrisebois2011]), the dipoles of the --medium through
    /// radiance maps or through a cube-map atlas drawn every frame (the mesh may deform:
    /// --morph, --expression; [Benmounah2009]), or none (the diffuse light stays where it entered).
    #[arg(long, value_enum, default_value_t = Subsurface::ScreenSpace)]
    pub subsurface: Subsurface,
    /// Light between surfaces: one bounce of the skin's glow from each part the camera sees to
    /// every skin part facing it (a finger's far side lit by the next finger, the nose by the
    /// cheek), which no subsurface model carries; screen space, no occlusion (render/src/bounce.rs).
    /// Off: the frame plan runs no bounce pass.
    #[arg(long)]
    pub bounce: bool,
    /// Screen samples per pixel of --bounce (1-256).
    #[arg(long, default_value_t = BounceSettings::default().samples, requires = "bounce")]
    pub bounce_samples: u32,
    /// How far --bounce looks for light, mm.
    #[arg(long, default_value_t = BounceSettings::default().reach_mm, requires = "bounce")]
    pub bounce_reach: f32,
    #[command(flatten)]
    pub thickness: ThicknessArgs,
    #[command(flatten)]
    pub dipole: DipoleArgs,
    #[command(flatten)]
    pub atlas: AtlasArgs,
    /// Antialiasing: none, edges (the default, AaMode::DEFAULT: discontinuity edge overdraw [Sander2001],
    /// unsorted, and the hairs drawn with their coverage; about 3 % of a 1280×720 frame),
    /// edges-sorted (silhouettes sorted back to front), ssaa2 or ssaa4 (supersampling k×k, PNG
    /// only; the hairs with their coverage too); msaa4 is refused (no multisampled G-buffer).
    /// docs/BENCHMARKS.md compares them.
    #[arg(long, default_value = "edges")]
    pub aa: String,
    /// Coverage of the edge overdraw: two-sided (exact box coverage on both sides of an edge,
    /// the default: closest to supersampling) or line (the paper's width-1 line, one side).
    #[arg(long, value_enum, default_value_t = AaCoverage::TwoSided)]
    pub aa_coverage: AaCoverage,
    /// Print the frame plan (the passes that run, in order, with what each reads and writes, and
    /// what is skipped and why) on stdout; renders too when --out is given.
    #[arg(long)]
    pub explain: bool,
    /// Output image: .png (tone-mapped sRGB) or .exr (linear radiance, for analysis).
    #[arg(long, required_unless_present = "explain")]
    pub out: Option<PathBuf>,
}

/// `--subsurface` values (more join with the translucency models).
// clap prints these doc comments as `--help` verbatim: citations stay `[Key]` (`\[Key\]` would show).
#[allow(rustdoc::broken_intra_doc_links)]
#[derive(Clone, Copy, Debug, PartialEq, Eq, clap::ValueEnum)]
pub enum Subsurface {
    /// No subsurface scattering.
    None,
    /// Separable screen-space kernel ([Jimenez2015]).
    ScreenSpace,
    /// Fast thickness translucency ([BarreBrisebois2011]).
    Thickness,
    /// The screen-space kernel with the thickness translucency's light from behind added before
    /// the blur: the kernel near where light entered, the thickness term through thin parts; its
    /// parameters fitted under the kernel where the --medium's file has them.
    ScreenSpaceThickness,
    /// Light through thin parts as through a plane slab of the --medium, exactly (adding-doubling;
    /// the thickness each light crossed from its shadow map, over the slab's lateral spread, where
    /// a face opposite the exit face sends its own slab's light beside a lit side face; the light
    /// scattered once marched along the view ray through the mesh), and the light entering nearby
    /// that the diffuse law and the kernel do not carry, mostly on faces the camera does not see
    /// (from the shadow map, by the dipole): no fitted parameter.
    Slab,
    /// The screen-space kernel with the slab's light from behind added before the blur.
    ScreenSpaceSlab,
    /// As slab, but the light that crossed the mesh to a pixel facing away from a directional
    /// light is gathered from every entry in the light's shadow map and carried by the classic
    /// dipole seen through the exit face (a transmission kernel), with no plane assumed: better
    /// across bodies narrower than the light spreads (fingers), worse through thin slabs of a
    /// low albedo (docs/BENCHMARKS.md "The transmission gather").
    SlabGather,
    /// The screen-space kernel with the transmission gather's light added before the blur.
    ScreenSpaceSlabGather,
    /// The directional dipole ([Frisvad2014]) of the --medium, through light G-buffers and
    /// radiance maps ([DirDipoleThesis]); --dipole-frames accumulates samples.
    DirectionalDipole,
    /// The directional dipole with Rouge's correction of its source: the ray's scattered power α′
    /// and the real source at the depth of its mean free path (a flat half-space's energy
    /// 0.7-1.0× the exact one's at every incidence, where the published model's is 1.3-2.2×).
    DirectionalDipoleMfp,
    /// Jensen's standard dipole ([Jensen2001]) in the same passes, for comparison.
    StandardDipole,
    /// Jensen's dipole gathered in a cube-map atlas of the --medium redrawn every frame
    /// ([Benmounah2009]); --atlas-* options.
    CubeAtlas,
}

/// `--aa-coverage` values.
#[derive(Clone, Copy, Debug, PartialEq, Eq, clap::ValueEnum)]
pub enum AaCoverage {
    /// Exact box-filter coverage on both sides of each edge.
    TwoSided,
    /// The paper's antialiased line of width 1, one side, sharp edges blended by β′.
    Line,
}

pub fn run(args: &RenderArgs) -> Result<()> {
    if !(args.exposure.is_finite() && args.exposure > 0.0) {
        bail!("--exposure {}: must be positive", args.exposure);
    }
    args.scene.check()?;
    let (mut job, fit) = args.scene.render_job()?;
    if let (Some(fit), Some(medium)) = (&fit, &job.scene.skin.medium) {
        let albedo = rouge_render::Skin::medium_albedo(medium, fit);
        eprintln!(
            "rouge: {} profile of {}: albedo {:.4}, {:.4}, {:.4} (the profile's total {:.4}, {:.4}, {:.4}); {} Gaussians, fit error {:.2}%, {:.2}%, {:.2}%",
            fit.model.name(),
            medium.name,
            albedo[0],
            albedo[1],
            albedo[2],
            fit.total[0],
            fit.total[1],
            fit.total[2],
            fit.profile.gaussians.len(),
            100.0 * fit.fit_error[0],
            100.0 * fit.fit_error[1],
            100.0 * fit.fit_error[2]
        );
    }
    job.scene.sss.width = args.sss_width;
    job.scene.sss.samples = args.sss_samples;
    if args.bounce {
        let settings =
            BounceSettings { samples: args.bounce_samples, reach_mm: args.bounce_reach, ..BounceSettings::default() };
        settings.check().map_err(|e| anyhow::anyhow!("--bounce-*: {e}"))?;
        job.scene.bounce = Some(settings);
    }
    job.scene.exposure = args.exposure;
    job.scene.specular = !args.no_specular;
    // The material's own kernel (d'Eon's skin profile, or the medium's fitted profile), or none.
    match args.subsurface {
        Subsurface::None => job.scene.skin.subsurface = SubsurfaceModel::None,
        Subsurface::ScreenSpace => {}
        Subsurface::Thickness | Subsurface::ScreenSpaceThickness => {
            // The material's kernel, kept under the thickness term in the combination.
            let combined = args.subsurface == Subsurface::ScreenSpaceThickness;
            let kernel = job.scene.skin.subsurface.profile().filter(|_| combined).cloned();
            job.scene.skin.subsurface = args.thickness.model(job.scene.skin.medium.as_ref(), kernel)?;
            job.thickness_bake_rest_pose = args.thickness.thickness_bake == BakePose::Rest;
        }
        Subsurface::Slab | Subsurface::ScreenSpaceSlab | Subsurface::SlabGather | Subsurface::ScreenSpaceSlabGather => {
            let combined = matches!(args.subsurface, Subsurface::ScreenSpaceSlab | Subsurface::ScreenSpaceSlabGather);
            let through = match args.subsurface {
                Subsurface::SlabGather | Subsurface::ScreenSpaceSlabGather => SlabThrough::Gather,
                _ => SlabThrough::Law,
            };
            let kernel = job.scene.skin.subsurface.profile().filter(|_| combined).cloned();
            job.scene.skin.subsurface = SubsurfaceModel::Slab { kernel, through };
        }
        Subsurface::DirectionalDipole => job.scene.skin.subsurface = args.dipole.model(DipoleKind::Directional)?,
        Subsurface::DirectionalDipoleMfp => {
            job.scene.skin.subsurface = args.dipole.model(DipoleKind::DirectionalMeanFreePath)?
        }
        Subsurface::StandardDipole => job.scene.skin.subsurface = args.dipole.model(DipoleKind::Standard)?,
        Subsurface::CubeAtlas => job.scene.skin.subsurface = args.atlas.model()?,
    }
    let aa = rouge_render::aa::AaMode::parse(&args.aa)?;
    let coverage = match args.aa_coverage {
        AaCoverage::TwoSided => rouge_render::aa::EdgeCoverage::TwoSided,
        AaCoverage::Line => rouge_render::aa::EdgeCoverage::Line,
    };
    let start = Instant::now();
    let loaded_scene = job.load()?;
    let mut prepared = job.prepare_loaded(&loaded_scene)?;
    let supersample = prepared.set_antialiasing(aa, coverage, &loaded_scene.mesh)?;
    let loaded = start.elapsed();
    if let Some(bake) = &prepared.thickness_bake {
        eprintln!(
            "rouge: local thickness of {} vertices: {} ({:.2} s to bake)",
            bake.vertices,
            match bake.cache {
                CacheUse::Hit => "from the cache",
                CacheUse::Miss => "baked and cached",
                CacheUse::Off => "baked (no cache directory)",
            },
            bake.seconds
        );
    }
    let display = args.out.as_ref().is_none_or(|out| !out.extension().is_some_and(|e| e.eq_ignore_ascii_case("exr")));
    if args.explain {
        let plan = prepared.renderer.plan(&prepared.scene, args.scene.width, args.scene.height, display)?;
        crate::emit(plan.explain().trim_end())?;
        if let Some(r) = &job.skin_maps {
            let blood = if job.blood_flow { "blood follows the expression" } else { "blood still" };
            crate::emit(&format!(
                "skin maps: tone {}, conditions {}, seed {}, {}² texels -> the albedo map (skin colour table); {blood}",
                r.tone.as_deref().unwrap_or("from an ITA"),
                r.conditions,
                r.seed,
                r.size_px
            ))?;
        }
        crate::emit(&mesh_parts_line(&loaded_scene.mesh, &loaded_scene.look))?;
        if let Some(w) = job.wrinkle_weights()? {
            crate::emit(&format!("wrinkles (left / right, of each family's depth): {w}"))?;
        }
    }
    let Some(out) = &args.out else {
        return Ok(());
    };
    // Progressive convergence of the dipole maps: accumulate the frames before the written one.
    if matches!(prepared.scene.skin.subsurface, SubsurfaceModel::Dipole { .. }) {
        for _ in 1..args.dipole.dipole_frames {
            let (w, h) = prepared.size;
            prepared.renderer.render(&prepared.scene, &prepared.camera, w, h, false)?;
        }
    }
    if supersample > 1 {
        if !out.extension().is_some_and(|e| e.eq_ignore_ascii_case("png")) {
            bail!("--aa {}: supersampling writes PNG only", args.aa);
        }
        let (w, h) = prepared.size;
        let linear = prepared.renderer.render_linear_srgb(&prepared.scene, &prepared.camera, (w, h), supersample)?;
        rouge_render::job::write_png(out, w, h, &rouge_render::aa::encode_srgb8(&linear))?;
    } else {
        render_to_file(&mut prepared, out)?;
    }
    eprintln!(
        "rouge: wrote {} ({}×{}, {} triangles, {} layers) on {} in {:.2} s (loading {:.2} s)",
        out.display(),
        args.scene.width,
        args.scene.height,
        prepared.triangles,
        prepared.renderer.layer_count(),
        prepared.gpu.describe(),
        start.elapsed().as_secs_f64(),
        loaded.as_secs_f64()
    );
    Ok(())
}

/// The plan's line on the mesh: its triangles per part, where the hairs are drawn, the mascara
/// and the brow gel drawn (`look`'s: the job's over the file's).
fn mesh_parts_line(mesh: &rouge_model::mesh::TriangleMesh, look: &rouge_model::look::Look) -> String {
    use rouge_model::mesh::Part;
    let parts = mesh.part_triangles();
    let counts: Vec<String> = parts.iter().map(|(p, n)| format!("{} {n}", p.name())).collect();
    let mut line = format!("mesh: {} triangles ({})", mesh.triangle_count(), counts.join(", "));
    if parts.iter().any(|(p, _)| matches!(p, Part::Lash | Part::Brow)) {
        line.push_str("; the lashes and brows are triangles of the shadow and G-buffer passes, no pass of their own");
        match look.mascara.filter(|m| !m.is_none()) {
            Some(m) => line.push_str(&format!(
                "; mascara length {:.2}×, volume {:.2}×, curl {:.0}°",
                m.length, m.volume, m.curl_deg
            )),
            None => line.push_str("; natural lashes (no mascara)"),
        }
        match look.brow_gel {
            Some(g) => line.push_str(&format!(
                "; brow gel {:.3}, {:.3}, {:.3} (linear) at strength {:.2}",
                g.color[0], g.color[1], g.color[2], g.strength
            )),
            None => line.push_str("; natural brows (no brow gel)"),
        }
    }
    line
}
