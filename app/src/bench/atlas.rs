//! `rouge bench cube-atlas`: \[Benmounah2009\]'s Table 2 for Rouge's cube-atlas model: frame time
//! with and without deformation against triangle count (the hm08 hand and head at several
//! subdivision levels, the built-in sphere). Deformation is the paper's: the mesh morphed toward
//! its bounding sphere, a new t each frame, re-uploaded, the atlas redrawn from it.

use anyhow::{Context, Result, bail};
use clap::Args;
use rouge_model::medium::Medium;
use rouge_model::thickness::morph_to_bounding_sphere;
use rouge_render::cube_atlas::AtlasSettings;
use rouge_render::job::{LookChoice, RenderJob};
use rouge_render::{LightRig, Scene, Skin, SubsurfaceModel};
use serde::Serialize;
use std::path::PathBuf;
use std::time::Instant;

#[derive(Debug, Args)]
pub struct AtlasBenchArgs {
    /// Frame width.
    #[arg(long, default_value_t = 800)]
    pub width: u32,
    /// Frame height.
    #[arg(long, default_value_t = 600)]
    pub height: u32,
    /// Frames timed per mesh and mode (after two warm-up frames).
    #[arg(long, default_value_t = 10)]
    pub frames: u32,
    /// Subdivision levels of the hand and the head.
    #[arg(long, value_delimiter = ',', default_values_t = [0u32, 1, 2, 3])]
    pub levels: Vec<u32>,
    /// Leave out meshes above this many triangles.
    #[arg(long, default_value_t = 600_000)]
    pub max_triangles: usize,
    /// Side of the atlas's faces, texels.
    #[arg(long, default_value_t = 512)]
    pub atlas_px: u32,
    /// Also write the rows as JSON here.
    #[arg(long)]
    pub json: Option<PathBuf>,
}

/// One mesh of the table: milliseconds per frame.
#[derive(Debug, Serialize)]
struct Row {
    mesh: String,
    level: u32,
    triangles: usize,
    /// Render and wait, the mesh still.
    still_ms: f64,
    /// Morph (CPU), upload, render and wait.
    deforming_ms: f64,
    /// The CPU morph alone.
    morph_ms: f64,
    /// GPU time of the atlas passes (irradiance + gather) and of the whole frame, when the
    /// adapter has timestamps.
    atlas_gpu_ms: Option<f64>,
    frame_gpu_ms: Option<f64>,
    device: String,
}

fn ms(t: Instant) -> f64 {
    t.elapsed().as_secs_f64() * 1e3
}

pub fn run(args: &AtlasBenchArgs) -> Result<()> {
    if args.frames == 0 {
        bail!("--frames 0: time at least one frame");
    }
    let settings = AtlasSettings { atlas_px: args.atlas_px, ..AtlasSettings::default() };
    settings.check()?;
    let hand = PathBuf::from("data/hands/hm08_hand.obj");
    let mut meshes: Vec<(String, Option<PathBuf>, u32, &str)> =
        vec![("sphere".into(), Some("builtin:sphere".into()), 0, "marble")];
    for &level in &args.levels {
        if level > 3 {
            bail!("--levels {level}: use 0 to 3");
        }
        meshes.push(("hand".into(), Some(hand.clone()), level, "skin1"));
        meshes.push(("head".into(), None, level, "skin1"));
    }
    let mut rows = Vec::new();
    for (name, path, level, medium) in meshes {
        let medium = Medium::builtin(medium)?.with_eta(1.0)?;
        let mut scene = Scene::rig(LightRig::Back);
        let skin = Skin::from_medium(&medium, rouge_render::diffusion::ProfileModel::ClassicDipole).0.lambert();
        scene.skin = Skin { subsurface: SubsurfaceModel::CubeAtlas { settings }, ..skin };
        let job = RenderJob {
            mesh: path,
            subdivision: level,
            look: LookChoice::Bare,
            width: args.width,
            height: args.height,
            scene,
            ..RenderJob::default()
        };
        let loaded = job.load().with_context(|| format!("{name} level {level}"))?;
        let triangles = loaded.mesh.triangle_count();
        if triangles > args.max_triangles {
            eprintln!("rouge: {name} level {level}: {triangles} triangles, over --max-triangles");
            continue;
        }
        let mut p = job.prepare_loaded(&loaded)?;
        let albedo = p.scene.skin.albedo;
        p.renderer.set_profiling(true);
        let (w, h) = (args.width, args.height);
        for _ in 0..2 {
            p.renderer.render(&p.scene, &p.camera, w, h, true)?;
        }
        p.renderer.wait()?;
        let (mut still, mut atlas_gpu, mut frame_gpu) = (0.0, 0.0, 0.0);
        for _ in 0..args.frames {
            let t = Instant::now();
            p.renderer.render(&p.scene, &p.camera, w, h, true)?;
            p.renderer.wait()?;
            still += ms(t);
            let timings = p.renderer.timings();
            frame_gpu += timings.iter().map(|t| t.ms).sum::<f64>();
            atlas_gpu += timings.iter().filter(|t| t.pass.starts_with("atlas")).map(|t| t.ms).sum::<f64>();
        }
        let timed = !p.renderer.timings().is_empty();
        let (mut deforming, mut morph) = (0.0, 0.0);
        for i in 0..args.frames {
            let t = Instant::now();
            let morph_t = 0.5 * (1.0 - (i as f32 * 0.7).cos()) * 0.6;
            let m = morph_to_bounding_sphere(&loaded.mesh, morph_t)?;
            morph += ms(t);
            p.renderer.set_mesh(&m, albedo)?;
            p.renderer.render(&p.scene, &p.camera, w, h, true)?;
            p.renderer.wait()?;
            deforming += ms(t);
        }
        let n = f64::from(args.frames);
        let row = Row {
            mesh: name.clone(),
            level,
            triangles,
            still_ms: still / n,
            deforming_ms: deforming / n,
            morph_ms: morph / n,
            atlas_gpu_ms: timed.then_some(atlas_gpu / n),
            frame_gpu_ms: timed.then_some(frame_gpu / n),
            device: p.gpu.describe(),
        };
        eprintln!(
            "rouge: {name} level {level}: {triangles} triangles, {:.1} ms still, {:.1} ms deforming",
            row.still_ms, row.deforming_ms
        );
        rows.push(row);
    }
    let gpu = |v: Option<f64>| v.map_or("-".to_string(), |v| format!("{v:.2}"));
    let caption = format!(
        "Cube-atlas translucency, {}×{}, atlas 6×{}², back light; {} frames each; {}",
        args.width,
        args.height,
        args.atlas_px,
        args.frames,
        rows.first().map_or(String::new(), |r| r.device.clone())
    );
    let header = [
        "mesh",
        "level",
        "triangles",
        "fps still",
        "fps deforming",
        "ms still",
        "ms deforming (morph on the CPU)",
        "atlas GPU ms",
        "frame GPU ms",
    ];
    let cells = rows.iter().map(|r| {
        vec![
            r.mesh.clone(),
            r.level.to_string(),
            r.triangles.to_string(),
            format!("{:.1}", 1e3 / r.still_ms),
            format!("{:.1}", 1e3 / r.deforming_ms),
            format!("{:.1}", r.still_ms),
            format!("{:.1} ({:.1})", r.deforming_ms, r.morph_ms),
            gpu(r.atlas_gpu_ms),
            gpu(r.frame_gpu_ms),
        ]
    });
    let table = crate::bench::report::markdown_table(&caption, &header, 1, cells);
    crate::bench::report::emit_with_json(&table, &rows, args.json.as_deref())?;
    Ok(())
}
