//! `rouge bench export`: what `rouge export gltf` costs per texture size: the scene loaded once
//! (mesh, look, skin maps), then per `--textures` the bake and the document
//! ([`rouge_render::gltf_export::export_gltf`]), the .glb encoded and written, and its size; and
//! once per size `rouge export materialx` (bake, PNGs, OBJ, .mtlx, written) and `rouge export
//! web`'s page (the .glb, the bare skin's bake, the page put together), their time and size.

use crate::bench::report::{emit_with_json, markdown_table};
use crate::cli::export_web::{page_data, share_page};
use crate::cli::render::scene_args::SceneArgs;
use anyhow::{Result, bail};
use clap::Args;
use rouge_render::gltf_export::{TEXTURE_PX_RANGE, bare_skin_texture, export_loaded};
use rouge_render::materialx_export::export_materialx;
use serde::Serialize;
use std::path::PathBuf;
use std::time::Instant;

#[derive(Debug, Args)]
pub struct ExportBenchArgs {
    #[command(flatten)]
    pub scene: SceneArgs,
    /// Texture sides to time, texels.
    #[arg(long, value_delimiter = ',', default_values_t = [1024u32, 2048, 4096])]
    pub textures: Vec<u32>,
    /// Exports timed per size (the median is reported).
    #[arg(long, default_value_t = 3)]
    pub repeats: usize,
    /// Also write the rows as JSON here.
    #[arg(long)]
    pub json: Option<PathBuf>,
}

/// One texture size.
#[derive(Debug, Serialize)]
struct Row {
    texture_px: u32,
    triangles: usize,
    /// Loading the scene (mesh, look, skin maps), once for every size.
    load_s: f64,
    /// The bake (the ambient occlusion's included), the PNG encoding and the document (median).
    export_s: f64,
    /// The same without the ambient occlusion, once.
    without_occlusion_s: f64,
    /// The .glb's bytes put together and written (median).
    write_s: f64,
    glb_bytes: u64,
    /// PNG bytes of each image, by name.
    images: Vec<(String, usize)>,
    /// `rouge export materialx` (bake, textures, OBJ, .mtlx, written), once.
    materialx_s: f64,
    /// Every file of the MaterialX export.
    materialx_bytes: u64,
    /// `rouge export web`'s page (export, bare bake, page), once, not written: the export is
    /// the one timed in `without_occlusion_s`.
    web_s: f64,
    web_bytes: usize,
    threads: usize,
}

fn median(mut v: Vec<f64>) -> f64 {
    v.sort_by(f64::total_cmp);
    v[v.len() / 2]
}

pub fn run(args: &ExportBenchArgs) -> Result<()> {
    args.scene.check()?;
    if args.repeats == 0 {
        bail!("--repeats 0: time at least one export");
    }
    if let Some(px) = args.textures.iter().find(|px| !TEXTURE_PX_RANGE.contains(px)) {
        bail!("--textures {px}: use {} to {} texels", TEXTURE_PX_RANGE.start(), TEXTURE_PX_RANGE.end());
    }
    let (job, _) = args.scene.render_job()?;
    let t = Instant::now();
    let loaded = job.load()?;
    let images = job.skin_textures()?;
    let load_s = t.elapsed().as_secs_f64();
    let path = std::env::temp_dir().join(format!("rouge-bench-export-{}.glb", std::process::id()));
    let mtlx_dir = std::env::temp_dir().join(format!("rouge-bench-materialx-{}", std::process::id()));
    std::fs::create_dir_all(&mtlx_dir)?;
    let mut rows = Vec::new();
    for &texture_px in &args.textures {
        let (mut export_s, mut write_s) = (Vec::new(), Vec::new());
        let mut last = None;
        for _ in 0..args.repeats {
            let t = Instant::now();
            let export = export_loaded(&loaded, &images, texture_px, true)?;
            export_s.push(t.elapsed().as_secs_f64());
            let t = Instant::now();
            export.document.write(&path)?;
            write_s.push(t.elapsed().as_secs_f64());
            last = Some(export);
        }
        let Some(export) = last else { bail!("no export ran") };
        // The export without occlusion is the web page's too: timed once, counted in both.
        let t = Instant::now();
        let plain = export_loaded(&loaded, &images, texture_px, false)?;
        let without_occlusion_s = t.elapsed().as_secs_f64();
        let t = Instant::now();
        let written = export_materialx(&loaded, &images, texture_px)?.write(&mtlx_dir)?;
        let materialx_s = t.elapsed().as_secs_f64();
        let materialx_bytes = written.iter().filter_map(|p| std::fs::metadata(p).ok()).map(|m| m.len()).sum();
        let t = Instant::now();
        let glb = plain.document.glb_bytes();
        let (bare, roughness) = bare_skin_texture(&loaded, &images, texture_px)?;
        let data = page_data(&loaded, (job.width, job.height), roughness, texture_px)?;
        let web_bytes = share_page(&data, &glb, &bare, job.width as f32 / job.height as f32).len();
        let web_s = without_occlusion_s + t.elapsed().as_secs_f64();
        rows.push(Row {
            texture_px,
            triangles: export.triangles,
            load_s,
            export_s: median(export_s),
            write_s: median(write_s),
            without_occlusion_s,
            glb_bytes: std::fs::metadata(&path)?.len(),
            images: export.document.images.iter().map(|i| (i.name.to_string(), i.png.len())).collect(),
            materialx_s,
            materialx_bytes,
            web_s,
            web_bytes,
            threads: std::thread::available_parallelism().map_or(1, |n| n.get()),
        });
    }
    std::fs::remove_file(&path).ok();
    std::fs::remove_dir_all(&mtlx_dir).ok();
    let table = markdown_table(
        &format!(
            "`rouge export gltf` per texture size ({} triangles; scene loaded once in {load_s:.2} s; median of {})",
            rows.first().map_or(0, |r| r.triangles),
            args.repeats
        ),
        &[
            "textures",
            "bake + PNG + document (s)",
            "the same without occlusion (s)",
            "write .glb (s)",
            ".glb (MB)",
            "images (MB)",
            "materialx (s)",
            "materialx (MB)",
            "web page (s)",
            "web page (MB)",
        ],
        1,
        rows.iter().map(|r| {
            let images = r.images.iter().map(|(n, b)| format!("{n} {:.2}", *b as f64 / 1e6)).collect::<Vec<_>>();
            vec![
                format!("{0}²", r.texture_px),
                format!("{:.2}", r.export_s),
                format!("{:.2}", r.without_occlusion_s),
                format!("{:.3}", r.write_s),
                format!("{:.1}", r.glb_bytes as f64 / 1e6),
                images.join(", "),
                format!("{:.2}", r.materialx_s),
                format!("{:.1}", r.materialx_bytes as f64 / 1e6),
                format!("{:.2}", r.web_s),
                format!("{:.1}", r.web_bytes as f64 / 1e6),
            ]
        }),
    );
    emit_with_json(&table, &rows, args.json.as_deref())
}
