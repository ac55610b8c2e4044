//! `rouge render`: one frame of the renderer to a PNG (tone-mapped) or an EXR (linear radiance).

use anyhow::{Result, bail};
use clap::Args;
use rouge_model::look::{Look, ThicknessSource};
use rouge_render::SubsurfaceModel;
use rouge_render::job::{LookChoice, RenderJob, render_to_file};
use std::path::PathBuf;
use std::time::Instant;

#[derive(Debug, Args)]
pub struct RenderArgs {
    /// Mesh to render (.obj, .gltf, .glb); the embedded default head (hm08, CC0) when absent.
    #[arg(long)]
    pub mesh: Option<PathBuf>,
    /// Millimetres per mesh unit (scans come in metres, centimetres or arbitrary units).
    #[arg(long, default_value_t = 1.0)]
    pub mesh_scale: f32,
    /// Catmull-Clark subdivision levels applied to the mesh (0-3).
    #[arg(long, default_value_t = 2, value_parser = clap::value_parser!(u32).range(0..=3))]
    pub subdiv: u32,
    /// Look document (JSON, `rouge-look` v1), `bare` for no cosmetics, or `default`
    /// (foundation + blush + lipstick).
    #[arg(long, default_value = "default")]
    pub look: String,
    /// Equirectangular HDR environment map (.exr) lighting the scene through spherical harmonics;
    /// without it, a built-in soft studio dome.
    #[arg(long)]
    pub env: Option<PathBuf>,
    /// Skin albedo texture (PNG, sRGB) in the mesh's UV space; replaces the skin colour.
    #[arg(long)]
    pub albedo_map: Option<PathBuf>,
    /// Tangent-space normal map (PNG, OpenGL convention: green = +V); MikkTSpace tangents are
    /// generated for the mesh.
    #[arg(long)]
    pub normal_map: Option<PathBuf>,
    /// Image width, pixels.
    #[arg(long, default_value_t = 1280)]
    pub width: u32,
    /// Image height, pixels.
    #[arg(long, default_value_t = 720)]
    pub height: u32,
    /// Camera yaw around the head, degrees (positive: from the head's left).
    #[arg(long, default_value_t = 0.0, allow_hyphen_values = true)]
    pub yaw: f32,
    /// Camera pitch, degrees (positive: from above).
    #[arg(long, default_value_t = 0.0, allow_hyphen_values = true)]
    pub pitch: f32,
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
    /// Subsurface model of the skin: the screen-space separable kernel of d'Eon's skin profile,
    /// or none (the diffuse light stays where it entered).
    #[arg(long, value_enum, default_value_t = Subsurface::ScreenSpace)]
    pub subsurface: Subsurface,
    /// Print the frame plan (the passes that run, in order, with what each reads and writes, and
    /// what is skipped and why) on stdout; renders too when --out is given.
    #[arg(long)]
    pub explain: bool,
    /// Output image: .png (tone-mapped sRGB) or .exr (linear radiance, for analysis).
    #[arg(long, required_unless_present = "explain")]
    pub out: Option<PathBuf>,
}

/// `--subsurface` values (more join with the translucency models).
#[derive(Clone, Copy, Debug, PartialEq, Eq, clap::ValueEnum)]
pub enum Subsurface {
    /// No subsurface scattering.
    None,
    /// Separable screen-space kernel ([Jimenez2015]).
    ScreenSpace,
}

pub fn run(args: &RenderArgs) -> Result<()> {
    let look = match args.look.as_str() {
        "default" => LookChoice::Default,
        "bare" => LookChoice::Bare,
        path => LookChoice::File(PathBuf::from(path)),
    };
    if !(args.exposure.is_finite() && args.exposure > 0.0) {
        bail!("--exposure {}: must be positive", args.exposure);
    }
    let mut job = RenderJob {
        mesh: args.mesh.clone(),
        mesh_scale_mm: args.mesh_scale,
        subdivision: args.subdiv,
        look,
        env: args.env.clone(),
        albedo_map: args.albedo_map.clone(),
        normal_map: args.normal_map.clone(),
        width: args.width,
        height: args.height,
        yaw_deg: args.yaw,
        pitch_deg: args.pitch,
        ..RenderJob::default()
    };
    job.scene.sss.width = args.sss_width;
    job.scene.sss.samples = args.sss_samples;
    job.scene.exposure = args.exposure;
    job.scene.specular = !args.no_specular;
    job.scene.skin.subsurface = match args.subsurface {
        Subsurface::None => SubsurfaceModel::None,
        Subsurface::ScreenSpace => SubsurfaceModel::skin_screen_space(),
    };
    if let Some(mesh) = &args.mesh {
        let regions = |l: &Look| l.layers.iter().any(|l| matches!(l.thickness, ThicknessSource::Region { .. }));
        let uses_regions = match &job.look {
            LookChoice::Default => true,
            LookChoice::Bare => false,
            LookChoice::File(p) => Look::load(p).is_ok_and(|l| regions(&l)),
        };
        if uses_regions {
            eprintln!(
                "rouge: note: the look uses region masks drawn for the default head's UVs; on {} they land \
                 wherever its UVs put them (use thickness maps painted for this mesh, or --look bare)",
                mesh.display()
            );
        }
    }
    let start = Instant::now();
    let mut prepared = job.prepare()?;
    let loaded = start.elapsed();
    let display = args.out.as_ref().is_none_or(|out| !out.extension().is_some_and(|e| e.eq_ignore_ascii_case("exr")));
    if args.explain {
        let plan = prepared.renderer.plan(&prepared.scene, args.width, args.height, display)?;
        crate::emit(plan.explain().trim_end())?;
    }
    let Some(out) = &args.out else {
        return Ok(());
    };
    render_to_file(&mut prepared, out)?;
    eprintln!(
        "rouge: wrote {} ({}×{}, {} triangles, {} layers) on {} in {:.2} s (loading {:.2} s)",
        out.display(),
        args.width,
        args.height,
        prepared.triangles,
        prepared.renderer.layer_count(),
        prepared.gpu.describe(),
        start.elapsed().as_secs_f64(),
        loaded.as_secs_f64()
    );
    Ok(())
}
