//! `rouge export mitsuba`: the scene `rouge render` draws, as a Mitsuba 3 scene (the ground truth
//! of docs/TRANSLUCENCY.md); `rouge export gltf`: the head and its look as a glTF 2.0 asset for
//! DCC tools, engines and browsers; `rouge export web` (`export_web`): a share page;
//! `rouge export materialx`: the mesh as OBJ with an OpenPBR Surface material
//! (docs/FORMATS.md, "Exported files").

use crate::cli::render::scene_args::SceneArgs;
use anyhow::{Context, Result, bail};
use clap::{Args, Subcommand};
use rouge_render::mitsuba::{ExportInput, Interior, export};
use std::path::PathBuf;

#[derive(Debug, Subcommand)]
pub enum ExportCommand {
    /// A Mitsuba 3 scene (DIR/scene.xml with skin.ply, eyes.ply and env.exr beside it) of exactly
    /// what `rouge render` draws with the same options: mesh in mm, camera, lights, environment,
    /// and the skin's boundary and interior medium. Render it with
    /// `python/render_reference.py` or `mi.load_file("DIR/scene.xml", spp=N)`.
    Mitsuba(MitsubaArgs),
    /// The head as `rouge render` draws it with the same options (posed, shaped, subdivided) and
    /// its eyes as glTF 2.0, with the look baked into textures: base colour (the skin and its
    /// cosmetics under white light, subsurface scattering excluded), metallic-roughness with the
    /// head's ambient occlusion, the
    /// normal map when the scene has one, KHR_materials_ior and KHR_materials_specular.
    /// Positions in metres (`rouge render --mesh FILE --mesh-scale 1000 --subdiv 0` reads it
    /// back). docs/FORMATS.md says what each file holds and what is lost.
    Gltf(GltfArgs),
    /// A share page: DIR/index.html, one self-contained file that opens from disk in a browser
    /// with no network: three.js draws the head as `export gltf` writes it, with a before/after
    /// slider (the bare skin | the look) and the look's products.
    Web(crate::cli::export_web::WebArgs),
    /// The head as `rouge render` draws it with the same options as DIR/face.obj (mm) with an
    /// OpenPBR Surface material in DIR/face.mtlx (MaterialX 1.39) over the look baked into
    /// textures: base and subsurface colour, subsurface radius from the skin's medium or
    /// profile, specular roughness and weight, a coat where a layer is a gloss.
    Materialx(MaterialxArgs),
}

#[derive(Debug, Args)]
pub struct MaterialxArgs {
    #[command(flatten)]
    pub scene: SceneArgs,
    #[command(flatten)]
    pub textures: Textures,
    /// Output folder (created): face.obj, face.mtlx and skin_*.png, each replaced atomically.
    #[arg(long)]
    pub out: PathBuf,
}

/// The sides `--textures` takes, texels.
pub const TEXTURE_SIDES: [&str; 5] = ["256", "512", "1024", "2048", "4096"];

/// `--textures` of the exports that bake at 2048² by default.
#[derive(Debug, Args)]
pub struct Textures {
    /// Side of the baked textures, texels.
    #[arg(long, default_value = "2048", value_parser = clap::builder::PossibleValuesParser::new(TEXTURE_SIDES))]
    pub textures: String,
}

/// `--textures SIDE` as texels (one of [`TEXTURE_SIDES`]).
pub fn texture_px(side: &str) -> Result<u32> {
    side.parse().with_context(|| format!("--textures {side}"))
}

#[derive(Debug, Args)]
pub struct GltfArgs {
    #[command(flatten)]
    pub scene: SceneArgs,
    #[command(flatten)]
    pub textures: Textures,
    /// Output: FILE.glb (one file, textures inside) or FILE.gltf (with FILE.bin and
    /// FILE_*.png beside it). Every file is replaced atomically.
    #[arg(long)]
    pub out: PathBuf,
    /// Leave the ambient occlusion out (its bake takes 1-3 s on the subdivided head; glTF
    /// viewers darken only their ambient light with it, so a scene lit by lights alone draws
    /// the same without it).
    #[arg(long)]
    pub no_occlusion: bool,
}

#[derive(Debug, Args)]
pub struct MitsubaArgs {
    #[command(flatten)]
    pub scene: SceneArgs,
    /// Below the surface: the material's medium behind a rough dielectric, the same boundary
    /// over a black absorber (the surface reflection alone; medium − absorber is the light that
    /// went below the surface), or an opaque Lambertian of the skin's albedo (the check that
    /// camera, lights and units match).
    #[arg(long, value_enum, default_value_t = InteriorArg::Medium)]
    pub interior: InteriorArg,
    /// Samples per pixel written as the scene's default (`$spp`).
    #[arg(long, default_value_t = 256)]
    pub spp: u32,
    /// Beckmann roughness α of the medium's boundary; 0 for a smooth dielectric. The path
    /// tracer connects delta lights (directional, point) to the interior only through a rough
    /// boundary, and a rough one loses a little energy at every internal reflection (Mitsuba's
    /// microfacet model is single-scattering): docs/TRANSLUCENCY.md gives the loss per α.
    #[arg(long, default_value_t = 0.1)]
    pub boundary_alpha: f64,
    /// Angular radius of the lights in degrees: 0 keeps delta lights; above 0 each directional
    /// light becomes a distant disk and each point light a sphere of that angular radius with
    /// the same irradiance. Delta lights reach a medium only by light sampling through a rough
    /// boundary, whose estimates have rare huge weights (fireflies); area lights let the path
    /// tracer combine light and BSDF samples (MIS). docs/TRANSLUCENCY.md measures both.
    #[arg(long, default_value_t = 0.0)]
    pub light_radius_deg: f64,
    /// Leave out the mesh's lashes, brows, teeth and tongue (its tissue and eyes alone): the
    /// default head as the committed translucency references were rendered, before it had those
    /// parts (python/translucency_pixel_bins.py compares with them).
    #[arg(long)]
    pub without_parts: bool,
    /// Output folder (created; scene.xml and its files are replaced atomically).
    #[arg(long)]
    pub out: PathBuf,
}

/// `--interior` values.
#[derive(Clone, Copy, Debug, PartialEq, Eq, clap::ValueEnum)]
pub enum InteriorArg {
    /// The medium behind a rough dielectric boundary.
    Medium,
    /// A black absorber behind the same boundary.
    Absorber,
    /// An opaque Lambertian surface of the skin's albedo.
    Lambert,
}

pub fn run(cmd: &ExportCommand) -> Result<()> {
    match cmd {
        ExportCommand::Mitsuba(args) => run_mitsuba(args),
        ExportCommand::Gltf(args) => run_gltf(args),
        ExportCommand::Web(args) => crate::cli::export_web::run(args),
        ExportCommand::Materialx(args) => run_materialx(args),
    }
}

fn run_gltf(args: &GltfArgs) -> Result<()> {
    args.scene.check()?;
    let texture_px = texture_px(&args.textures.textures)?;
    match args.out.extension().and_then(|e| e.to_str()).map(str::to_ascii_lowercase).as_deref() {
        Some("glb" | "gltf") => {}
        _ => bail!("--out {}: use FILE.glb (one file) or FILE.gltf (files beside it)", args.out.display()),
    }
    let (job, _) = args.scene.render_job()?;
    let start = std::time::Instant::now();
    let export = rouge_render::gltf_export::export_job(&job, texture_px, !args.no_occlusion)?;
    let written = export.document.write(&args.out)?;
    let bytes: u64 = written.iter().filter_map(|p| std::fs::metadata(p).ok()).map(|m| m.len()).sum();
    eprintln!(
        "rouge: wrote {} ({} triangles, {} textures of {texture_px}², {:.1} MB, {:.2} s)",
        written.iter().map(|p| p.display().to_string()).collect::<Vec<_>>().join(", "),
        export.triangles,
        export.document.images.len(),
        bytes as f64 / 1e6,
        start.elapsed().as_secs_f64()
    );
    Ok(())
}

fn run_materialx(args: &MaterialxArgs) -> Result<()> {
    args.scene.check()?;
    let texture_px = texture_px(&args.textures.textures)?;
    let mtlx = crate::cli::export_web::output_file(&args.out, rouge_render::materialx_export::MTLX_FILE)?;
    let (job, _) = args.scene.render_job()?;
    let start = std::time::Instant::now();
    rouge_render::gltf_export::bake::check_texture_px(texture_px)?;
    let loaded = job.load()?;
    let images = job.skin_textures()?;
    let export = rouge_render::materialx_export::export_materialx(&loaded, &images, texture_px)?;
    let written = export.write(&args.out)?;
    let bytes: u64 = written.iter().filter_map(|p| std::fs::metadata(p).ok()).map(|m| m.len()).sum();
    eprintln!(
        "rouge: wrote {} and {} other files ({} triangles, textures of {texture_px}², coat {}, {:.1} MB, {:.2} s)",
        mtlx.display(),
        written.len() - 1,
        export.triangles,
        if export.coat { "from a gloss layer" } else { "none" },
        bytes as f64 / 1e6,
        start.elapsed().as_secs_f64()
    );
    Ok(())
}

fn run_mitsuba(args: &MitsubaArgs) -> Result<()> {
    args.scene.check()?;
    if !(args.boundary_alpha.is_finite() && (0.0..=1.0).contains(&args.boundary_alpha)) {
        anyhow::bail!("--boundary-alpha {}: must lie in [0, 1]", args.boundary_alpha);
    }
    if !(args.light_radius_deg.is_finite() && (0.0..45.0).contains(&args.light_radius_deg)) {
        anyhow::bail!("--light-radius-deg {}: must lie in [0, 45)", args.light_radius_deg);
    }
    let (job, _) = args.scene.job()?;
    if job.skin_maps.is_some() {
        bail!(
            "--skin-maps/--skin-conditions: export mitsuba does not carry skin maps yet (export without them: \
             the skin then has the tone's uniform colour)"
        );
    }
    if args.scene.render_job()?.0.skin_maps.is_some() {
        eprintln!(
            "rouge: note: `rouge render` draws skin maps here; the exported skin has the tone's uniform colour \
             (render with --flat-skin to compare with the export)"
        );
    }
    let loaded = job.load()?;
    let interior = match args.interior {
        InteriorArg::Medium => Interior::Medium,
        InteriorArg::Absorber => Interior::Absorber,
        InteriorArg::Lambert => Interior::Lambert,
    };
    let stripped = args.without_parts.then(|| loaded.mesh.without_parts());
    let mesh = stripped.as_ref().unwrap_or(&loaded.mesh);
    let scene = export(&ExportInput {
        mesh,
        scene: &loaded.scene,
        env: loaded.env.as_ref(),
        camera: &loaded.camera,
        width: job.width,
        height: job.height,
        interior,
        spp: args.spp,
        boundary_alpha: args.boundary_alpha,
        light_radius_deg: args.light_radius_deg,
    })?;
    scene.write(&args.out)?;
    eprintln!(
        "rouge: wrote {} ({} triangles, interior {}, {}×{})",
        args.out.join("scene.xml").display(),
        mesh.triangle_count(),
        interior.name(),
        job.width,
        job.height
    );
    Ok(())
}
