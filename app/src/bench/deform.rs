//! `rouge bench deform`: what a deforming frame costs on the default head (the app's animation
//! and expression sliders): apply the targets, subdivide, re-upload the mesh, render. Per
//! subdivision level, the planned path ([`SubdivisionPlan`]: topology once, positions per frame)
//! against subdividing and triangulating afresh each frame, and the upload in place
//! ([`rouge_render::Renderer::move_mesh`]: positions and normals into the existing buffer) against
//! a new mesh upload.

use anyhow::Result;
use clap::Args;
use rouge_model::mesh::default_head;
use rouge_model::mesh::deform::SubdivisionPlan;
use rouge_model::mesh::targets::{FacePose, TargetSet, expression_cycle};
use rouge_render::job::{LookChoice, RenderJob};
use serde::Serialize;
use std::hint::black_box;
use std::path::PathBuf;
use std::time::Instant;

#[derive(Debug, Args)]
pub struct DeformBenchArgs {
    /// Frame width.
    #[arg(long, default_value_t = 1280)]
    pub width: u32,
    /// Frame height.
    #[arg(long, default_value_t = 720)]
    pub height: u32,
    /// Frames timed per level (poses along the app's expression cycle).
    #[arg(long, default_value_t = 20)]
    pub frames: usize,
    /// Subdivision levels to time.
    #[arg(long, value_delimiter = ',', default_values_t = [0u32, 1, 2])]
    pub levels: Vec<u32>,
    /// Also write the rows as JSON here.
    #[arg(long)]
    pub json: Option<PathBuf>,
}

/// Mean milliseconds per frame of each step, at one subdivision level.
#[derive(Debug, Serialize)]
struct Row {
    level: u32,
    triangles: usize,
    vertices: usize,
    plan_build_ms: f64,
    targets_ms: f64,
    subdivide_planned_ms: f64,
    subdivide_one_thread_ms: f64,
    threads: usize,
    subdivide_fresh_ms: f64,
    upload_ms: f64,
    upload_render_fresh_ms: f64,
    render_ms: f64,
    frame_ms: f64,
    device: String,
}

fn ms(t: Instant) -> f64 {
    t.elapsed().as_secs_f64() * 1e3
}

pub fn run(args: &DeformBenchArgs) -> Result<()> {
    if args.frames == 0 {
        anyhow::bail!("--frames 0: time at least one frame");
    }
    let targets = TargetSet::default_head()?;
    let base = default_head()?;
    let mut rows = Vec::new();
    for &level in &args.levels {
        if level > 3 {
            anyhow::bail!("--levels {level}: use 0 to 3");
        }
        let job = RenderJob {
            look: LookChoice::Default,
            width: args.width,
            height: args.height,
            subdivision: level,
            ..RenderJob::default()
        };
        let mut p = job.prepare()?;
        let t = Instant::now();
        let plan = SubdivisionPlan::new(&base, level);
        let plan_build_ms = ms(t);
        let mut mesh = plan.rest().clone();
        let albedo = p.scene.skin.albedo;
        let (mut tg, mut sp, mut s1, mut sf, mut up, mut uf, mut rd) = (0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0);
        let pose_of = |i: usize| -> Result<Vec<glam::Vec3>> {
            let pose = FacePose { expression: expression_cycle(i as f64 * 0.25), ..FacePose::default() };
            let mut positions = base.positions.clone();
            targets.apply(&pose, &mut positions)?;
            Ok(positions)
        };
        // The app's frame, frames back to back (a GPU left idle between frames by the
        // comparisons below clocks down, and the frame after is slow for that alone).
        // Three frames first, untimed, bring the GPU up to speed.
        for i in 0..3 {
            plan.update(&pose_of(i)?, &mut mesh);
            p.renderer.move_mesh(&mesh, albedo)?;
            p.renderer.render(&p.scene, &p.camera, args.width, args.height, true)?;
            p.renderer.wait()?;
        }
        for i in 0..args.frames {
            let t = Instant::now();
            let positions = pose_of(i)?;
            tg += ms(t);
            let t = Instant::now();
            plan.update(&positions, &mut mesh);
            sp += ms(t);
            let t = Instant::now();
            p.renderer.move_mesh(&mesh, albedo)?;
            up += ms(t);
            let t = Instant::now();
            p.renderer.render(&p.scene, &p.camera, args.width, args.height, true)?;
            p.renderer.wait()?;
            rd += ms(t);
        }
        // The same on one thread, and subdividing afresh (the CPU alone).
        for i in 0..args.frames {
            let positions = pose_of(i)?;
            let t = Instant::now();
            plan.update_on(&positions, &mut mesh, 1);
            s1 += ms(t);
            let t = Instant::now();
            let mut fresh = base.clone();
            fresh.positions = positions;
            black_box(fresh.catmull_clark(level).triangulate());
            sf += ms(t);
        }
        // What the frame cost before the in-place upload: the same posed mesh uploaded afresh
        // (new buffers; their copy to the GPU is done at the frame's submission, so this holds
        // the frame too).
        for _ in 0..args.frames {
            let t = Instant::now();
            p.renderer.set_mesh(&mesh, albedo)?;
            p.renderer.render(&p.scene, &p.camera, args.width, args.height, true)?;
            p.renderer.wait()?;
            uf += ms(t);
        }
        let n = args.frames as f64;
        rows.push(Row {
            level,
            triangles: mesh.triangle_count(),
            vertices: mesh.vertex_count(),
            plan_build_ms,
            targets_ms: tg / n,
            subdivide_planned_ms: sp / n,
            subdivide_one_thread_ms: s1 / n,
            threads: SubdivisionPlan::threads(),
            subdivide_fresh_ms: sf / n,
            upload_ms: up / n,
            upload_render_fresh_ms: uf / n,
            render_ms: rd / n,
            frame_ms: (tg + sp + up + rd) / n,
            device: p.gpu.describe(),
        });
    }
    let caption = format!(
        "Deforming frame on the default head, {}×{}, default look, {} poses of the expression cycle per level; {}",
        args.width,
        args.height,
        args.frames,
        rows.first().map_or(String::new(), |r| r.device.clone())
    );
    let header = [
        "level",
        "triangles",
        "plan (once)",
        "targets",
        "subdivide: planned, threads",
        "subdivide: planned, 1 thread",
        "subdivide: afresh",
        "upload: in place",
        "render + wait",
        "upload afresh + render + wait",
        "frame (planned)",
    ];
    let cells = rows.iter().map(|r| {
        vec![
            r.level.to_string(),
            r.triangles.to_string(),
            format!("{:.1} ms", r.plan_build_ms),
            format!("{:.2} ms", r.targets_ms),
            format!("{:.2} ms ({})", r.subdivide_planned_ms, r.threads),
            format!("{:.2} ms", r.subdivide_one_thread_ms),
            format!("{:.1} ms", r.subdivide_fresh_ms),
            format!("{:.2} ms", r.upload_ms),
            format!("{:.1} ms", r.render_ms),
            format!("{:.1} ms", r.upload_render_fresh_ms),
            format!("{:.1} ms", r.frame_ms),
        ]
    });
    let table = crate::bench::report::markdown_table(&caption, &header, 0, cells);
    crate::bench::report::emit_with_json(&table, &rows, args.json.as_deref())?;
    Ok(())
}
