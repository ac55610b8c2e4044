//! `rouge export web`: a share page, one self-contained HTML file that opens from disk in a
//! browser with no network: three.js (bundled into `app/web/page.bundle.js` from npm `three` by
//! `tests/web/bundle.mjs`) draws the look's .glb (`rouge export gltf`'s, inlined as base64) with
//! a before/after slider against the bare skin's baked base colour, and lists the look's products
//! (docs/FORMATS.md, "rouge export web").

use crate::cli::render::scene_args::SceneArgs;
use anyhow::{Context, Result, bail};
use clap::Args;
use rouge_model::look::Look;
use rouge_model::mesh::Bounds;
use rouge_render::gltf_export::{bare_skin_texture, export_loaded};
use rouge_render::job::Loaded;
use serde_json::{Value, json};
use std::path::{Path, PathBuf};

/// The page around the data (placeholders `{{NAME}}`).
const PAGE_HTML: &str = include_str!("../../web/page.html");
/// app/web/page.js with three.js, one classic script (a page opened from disk may not import
/// modules).
const PAGE_SCRIPT: &str = include_str!("../../web/page.bundle.js");
/// The page's file in `--out`.
pub const PAGE_FILE: &str = "index.html";

#[derive(Debug, Args)]
pub struct WebArgs {
    #[command(flatten)]
    pub scene: SceneArgs,
    /// Side of the baked textures, texels (the page carries the look's textures and the bare
    /// skin's base colour).
    #[arg(long, default_value = "1024", value_parser = clap::builder::PossibleValuesParser::new(crate::cli::export::TEXTURE_SIDES))]
    pub textures: String,
    /// Output folder (created): DIR/index.html, replaced atomically.
    #[arg(long)]
    pub out: PathBuf,
}

pub fn run(args: &WebArgs) -> Result<()> {
    args.scene.check()?;
    let texture_px = crate::cli::export::texture_px(&args.textures)?;
    let page_path = output_file(&args.out, PAGE_FILE)?;
    let (job, _) = args.scene.render_job()?;
    let start = std::time::Instant::now();
    rouge_render::gltf_export::bake::check_texture_px(texture_px)?;
    let loaded = job.load()?;
    let images = job.skin_textures()?;
    // No occlusion: the page lights the head with one directional light, which glTF's
    // occlusion does not darken.
    let export = export_loaded(&loaded, &images, texture_px, false)?;
    let (bare_png, bare_roughness) = bare_skin_texture(&loaded, &images, texture_px)?;
    let data = page_data(&loaded, (job.width, job.height), bare_roughness, texture_px)?;
    let html = share_page(&data, &export.document.glb_bytes(), &bare_png, job.width as f32 / job.height as f32);
    crate::write_output(&page_path, html.as_bytes())?;
    eprintln!(
        "rouge: wrote {} ({} triangles, {} products, textures of {texture_px}², {:.1} MB, {:.2} s)",
        page_path.display(),
        export.triangles,
        data["products"].as_array().map_or(0, Vec::len),
        html.len() as f64 / 1e6,
        start.elapsed().as_secs_f64()
    );
    Ok(())
}

/// `dir/name` after making `dir` (the `--out` folder), refused when `dir` is a file.
///
/// # Errors
/// `--out DIR` named when it is a file or cannot be made.
pub fn output_file(dir: &Path, name: &str) -> Result<PathBuf> {
    if dir.exists() && !dir.is_dir() {
        bail!("--out {}: is a file; give a folder", dir.display());
    }
    std::fs::create_dir_all(dir).with_context(|| format!("--out {}: cannot create the folder", dir.display()))?;
    Ok(dir.join(name))
}

/// What the page reads from `#rouge-data`: the look's name and products, Rouge's camera (metres,
/// the .glb's units) for an image of `size`, the background, and the bare skin's roughness.
///
/// # Errors
/// An empty mesh.
pub fn page_data(loaded: &Loaded, size: (u32, u32), bare_roughness: f32, texture_px: u32) -> Result<Value> {
    let bounds = Bounds::of(&loaded.mesh.positions).context("the mesh has no vertex")?;
    let camera = &loaded.camera;
    let (near, far) = camera.clip_planes_around(&bounds);
    let m = |v: glam::Vec3| (v * 1e-3).to_array();
    Ok(json!({
        "look": loaded.look.name,
        "generator": generator(),
        "texture_px": texture_px,
        "size": [size.0, size.1],
        "background": loaded.scene.background,
        "camera": {
            "fov_y_deg": camera.fov_y_deg,
            "position_m": m(camera.position()),
            "target_m": m(camera.target),
            "near_m": near * 1e-3,
            "far_m": far * 1e-3,
        },
        "bare": {"roughness": bare_roughness},
        "products": products(&loaded.look),
    }))
}

/// The look's visible layers, bottom to top, as the page lists them.
pub fn products(look: &Look) -> Vec<Value> {
    look.visible_layers()
        .map(|l| {
            json!({
                "layer": l.name,
                "product": l.preset.name,
                "kind": l.preset.kind,
                "finish": l.preset.finish.map(|f| f.kind),
                "swatch": l.preset.derived.r_inf_srgb_hex,
            })
        })
        .collect()
}

fn generator() -> String {
    format!("Rouge {} (rouge export web)", env!("CARGO_PKG_VERSION"))
}

/// The page: [`PAGE_HTML`] with the data, the .glb and the bare skin's PNG (base64) and the
/// script inlined; `aspect` (width / height) sizes the view.
pub fn share_page(data: &Value, glb: &[u8], bare_png: &[u8], aspect: f32) -> String {
    // Inside <script>, "</" could close the element: JSON allows "<\/".
    let data = data.to_string().replace("</", "<\\/");
    let mut out = String::with_capacity(PAGE_HTML.len() + PAGE_SCRIPT.len() + data.len() + 4 * glb.len() / 3 + 8);
    let mut rest = PAGE_HTML;
    while let Some(at) = rest.find("{{") {
        out.push_str(&rest[..at]);
        let end = rest[at..].find("}}").map_or(rest.len(), |e| at + e + 2);
        match &rest[at..end] {
            "{{GENERATOR}}" => out.push_str(&generator()),
            "{{ASPECT}}" => out.push_str(&format!("{aspect:.4}")),
            "{{DATA}}" => out.push_str(&data),
            "{{GLB}}" => base64_into(glb, &mut out),
            "{{BARE}}" => base64_into(bare_png, &mut out),
            "{{SCRIPT}}" => out.push_str(PAGE_SCRIPT),
            other => out.push_str(other),
        }
        rest = &rest[end..];
    }
    out.push_str(rest);
    out
}

/// `bytes` in base64 (RFC 4648, with padding) appended to `out`.
pub fn base64_into(bytes: &[u8], out: &mut String) {
    const ALPHABET: &[u8; 64] = b"ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    for chunk in bytes.chunks(3) {
        let b = [chunk[0], chunk.get(1).copied().unwrap_or(0), chunk.get(2).copied().unwrap_or(0)];
        let n = (u32::from(b[0]) << 16) | (u32::from(b[1]) << 8) | u32::from(b[2]);
        for i in 0..4 {
            if i <= chunk.len() {
                out.push(ALPHABET[(n >> (18 - 6 * i) & 63) as usize] as char);
            } else {
                out.push('=');
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn base64_matches_rfc_4648_test_vectors() {
        for (input, expect) in [
            ("", ""),
            ("f", "Zg=="),
            ("fo", "Zm8="),
            ("foo", "Zm9v"),
            ("foob", "Zm9vYg=="),
            ("fooba", "Zm9vYmE="),
            ("foobar", "Zm9vYmFy"),
        ] {
            let mut out = String::new();
            base64_into(input.as_bytes(), &mut out);
            assert_eq!(out, expect, "{input:?}");
        }
    }

    #[test]
    fn the_page_inlines_everything_and_escapes_the_data() {
        let data = json!({"look": "</script><b>x"});
        let page = share_page(&data, b"glTF", b"PNG", 1.5);
        assert!(!page.replace(PAGE_SCRIPT, "").contains("{{"), "every placeholder is filled");
        assert!(page.contains(r#"{"look":"<\/script><b>x"}"#), "the data cannot close its element");
        assert!(page.contains("Z2xURg=="), "the .glb is inlined");
        assert_eq!(page.matches("</script>").count(), 4, "data, .glb, bare skin, script");
        assert!(!PAGE_HTML.contains("src=") && !PAGE_HTML.contains("http"), "nothing is loaded from elsewhere");
    }
}
