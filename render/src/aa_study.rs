//! `rouge bench aa`'s measuring side: a turning mesh rendered in each antialiasing mode and
//! compared with a supersampled reference (k×k box filter, the same frame code at k× the size)
//! on the pixels within two pixels of a discontinuity edge: RMSE and ΔE2000 per frame, and the
//! crawl between consecutive frames ([`crate::aa::crawl`]); cost per frame; and the edge counts
//! of \[Sander2001\] table 1.

use crate::Renderer;
use crate::aa::{self, AaMode, EdgeAa, EdgeCoverage};
use crate::error::Result;
use crate::scene::{Camera, Scene};
use crate::silhouettes::{EdgeClass, FrameEdgeStats, classify};
use crate::uniforms::FrameView;
use std::time::Instant;

/// What to measure.
#[derive(Clone, Debug)]
pub struct AaStudy {
    /// Image size.
    pub size: (u32, u32),
    /// Camera yaws of the turning sequence, degrees.
    pub yaws_deg: Vec<f32>,
    /// Camera pitch, degrees.
    pub pitch_deg: f32,
    /// Supersampling of the reference (k×k samples per pixel).
    pub reference_k: u32,
    /// The modes measured, each with the coverage of its edge overdraw.
    pub modes: Vec<(AaMode, EdgeCoverage)>,
    /// Frames timed per mode (the median is reported).
    pub timed_frames: u32,
    /// Also measure unsorted two-sided overdraw with every edge classified on the GPU
    /// ([`Renderer::set_edge_gpu_classify`]), the row `edges-gpu`.
    pub gpu_classify: bool,
    /// Which pixels are measured.
    pub mask: Mask,
}

/// The pixels an [`AaStudy`] measures.
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize)]
pub enum Mask {
    /// Within 2 pixels of a mesh edge drawn from that view ([`edge_mask`]).
    NearEdges,
    /// Where the reference differs from its 1-pixel blur by more than this many levels of 255
    /// ([`aa::detail_mask`]): issue 27's measure, every discontinuity a viewer sees.
    Detail(f32),
}

/// One mode's results over the sequence.
#[derive(Clone, Debug, serde::Serialize)]
pub struct AaRow {
    /// `--aa` name.
    pub mode: String,
    /// Coverage of the edge overdraw (none for the other modes).
    pub coverage: Option<EdgeCoverage>,
    /// Mean over the frames of the RMSE (linear sRGB) near discontinuities.
    pub rmse: f64,
    /// The same in levels of 255 of the sRGB-encoded images.
    pub rmse_srgb8: f64,
    /// Pixels measured a frame (mean).
    pub pixels: f64,
    /// Mean over the frames of the mean ΔE2000 near discontinuities.
    pub delta_e_mean: f64,
    /// Mean over consecutive frame pairs of the crawl ([`aa::crawl`]).
    pub crawl: f64,
    /// Median wall time of a frame (render and wait), ms; GPU work on the adapter named in the
    /// report (lavapipe: CPU cores, noisy).
    pub frame_ms: f64,
    /// Median GPU time of each pass over the timed frames (timestamp queries), ms, in frame
    /// order; empty where the adapter has no timestamps.
    pub pass_ms: Vec<(String, f64)>,
}

impl AaRow {
    /// The frame's GPU time: the sum of [`AaRow::pass_ms`].
    pub fn gpu_ms(&self) -> f64 {
        self.pass_ms.iter().map(|(_, ms)| ms).sum()
    }

    /// The GPU time the antialiasing adds to the aliased frame `none`: for a supersampled
    /// mode the whole difference; otherwise the passes `none` does not run (edge overdraw) and
    /// what the antialiased hair pass takes beyond the aliased one (the other passes do the same
    /// work, so their run-to-run noise is left out).
    pub fn aa_ms(&self, none: &AaRow) -> f64 {
        if self.mode.starts_with("ssaa") {
            return self.gpu_ms() - none.gpu_ms();
        }
        let of = |row: &AaRow, pass: &str| row.pass_ms.iter().find(|(p, _)| p == pass).map(|(_, ms)| *ms);
        self.pass_ms
            .iter()
            .map(|(pass, ms)| match of(none, pass) {
                None => *ms,
                Some(base) if pass.starts_with("hair") => (ms - base).max(0.0),
                Some(_) => 0.0,
            })
            .sum()
    }
}

/// The edge counts of one mesh averaged over viewpoints (\[Sander2001\] table 1).
#[derive(Clone, Copy, Debug, Default, serde::Serialize)]
pub struct EdgeTable {
    /// Preprocess counts.
    pub counts: crate::edges::EdgeCounts,
    /// Per-frame counts averaged over the viewpoints.
    pub extracted_silhouettes: f64,
    /// Edges drawn.
    pub rendered: f64,
    /// Edges sorted.
    pub sorted: f64,
    /// Sharp edges blended by β′ > 0 (the paper's line coverage).
    pub blended: f64,
    /// CPU µs per frame of the silhouette search: every candidate tested.
    pub search_brute_us: f64,
    /// CPU µs per frame of the search that skips clusters.
    pub search_skipping_us: f64,
    /// CPU µs per frame of the whole sorted list (search, classification, sort).
    pub sorted_list_us: f64,
}

/// The pixels within 2 pixels of an edge drawn from `camera` (visible or not: the mask does not
/// depend on the mode measured).
pub fn edge_mask(r: &Renderer, camera: &Camera, (w, h): (u32, u32)) -> Vec<bool> {
    let (Some(edges), Some(bounds)) = (r.edges(), r.mesh_bounds()) else {
        return vec![false; (w * h) as usize];
    };
    let view = FrameView::new(camera, &bounds, (w, h));
    let eye = camera.position();
    let project = |p: glam::Vec3| {
        let c = view.view_proj * p.extend(1.0);
        let n = c.truncate() / c.w.max(1e-6);
        [(n.x + 1.0) * 0.5 * w as f32, (1.0 - n.y) * 0.5 * h as f32]
    };
    let segments: Vec<_> = edges
        .set
        .edges
        .iter()
        .filter(|e| classify(e, eye, edges.set.closed) != EdgeClass::Hidden)
        .map(|e| (project(e.p0), project(e.p1)))
        .collect();
    aa::mask_near_segments(&segments, (w as usize, h as usize), 2.0)
}

/// Runs the study on the mesh uploaded to `r` (its edges are prepared here), the camera framing
/// it at each yaw of `study`.
///
/// # Errors
/// As [`Renderer::render`]; [`crate::RenderError::Invalid`] without a mesh or for `msaa4`.
pub fn run(
    r: &mut Renderer,
    scene: &Scene,
    mesh: &rouge_model::mesh::TriangleMesh,
    study: &AaStudy,
) -> Result<Vec<AaRow>> {
    r.prepare_edges(mesh);
    let bounds = r.mesh_bounds().ok_or_else(|| crate::RenderError::Invalid("no mesh".into()))?;
    let cameras: Vec<Camera> =
        study.yaws_deg.iter().map(|&yaw| Camera::framing(&bounds, yaw, study.pitch_deg)).collect();
    // The reference: no edge overdraw (supersampling resolves the edges), the hairs with their
    // coverage (thinner than a pixel even k× larger).
    r.set_edge_aa(EdgeAa::Off);
    r.set_hair_aa(true);
    let mut references = Vec::new();
    let mut masks = Vec::new();
    for camera in &cameras {
        let reference = r.render_linear_srgb(scene, camera, study.size, study.reference_k)?;
        masks.push(match study.mask {
            Mask::NearEdges => edge_mask(r, camera, study.size),
            Mask::Detail(threshold) => {
                aa::detail_mask(&reference, (study.size.0 as usize, study.size.1 as usize), threshold)
            }
        });
        references.push(reference);
    }
    let mut rows = Vec::new();
    let mut runs: Vec<(AaMode, EdgeCoverage, bool)> = study.modes.iter().map(|&(m, c)| (m, c, false)).collect();
    if study.gpu_classify {
        runs.push((AaMode::Edges, EdgeCoverage::TwoSided, true));
    }
    for (mode, coverage, gpu) in runs {
        let k = r.set_aa_mode(mode, coverage)?;
        r.set_edge_gpu_classify(gpu);
        let mut images = Vec::new();
        let (mut rmse, mut rmse8, mut de, mut pixels) = (0.0, 0.0, 0.0, 0.0);
        for (i, camera) in cameras.iter().enumerate() {
            let image = r.render_linear_srgb(scene, camera, study.size, k)?;
            let e = aa::edge_error(&image, &references[i], &masks[i]);
            rmse += e.rmse;
            rmse8 += e.rmse_srgb8;
            de += e.delta_e_mean;
            pixels += e.pixels as f64;
            images.push(image);
        }
        let mut crawl = 0.0;
        for i in 1..images.len() {
            let mask: Vec<bool> = masks[i - 1].iter().zip(&masks[i]).map(|(a, b)| *a || *b).collect();
            crawl += aa::crawl([&images[i - 1], &images[i]], [&references[i - 1], &references[i]], &mask);
        }
        let mut times = Vec::new();
        let camera = cameras[cameras.len() / 2];
        for _ in 0..study.timed_frames.max(1) + 1 {
            let start = Instant::now();
            r.render(scene, &camera, study.size.0 * k, study.size.1 * k, true)?;
            r.wait()?;
            times.push(start.elapsed().as_secs_f64() * 1e3);
        }
        times.remove(0); // the first frame builds pipelines
        times.sort_by(f64::total_cmp);
        // The passes' GPU times, profiled apart from the wall times (profiling waits per frame).
        r.set_profiling(true);
        let mut per_pass: Vec<(String, Vec<f64>)> = Vec::new();
        for _ in 0..study.timed_frames.max(1) {
            r.render(scene, &camera, study.size.0 * k, study.size.1 * k, true)?;
            r.wait()?;
            for t in r.timings() {
                match per_pass.iter_mut().find(|(name, _)| *name == t.pass) {
                    Some((_, v)) => v.push(t.ms),
                    None => per_pass.push((t.pass.clone(), vec![t.ms])),
                }
            }
        }
        r.set_profiling(false);
        let pass_ms = per_pass
            .into_iter()
            .map(|(name, mut v)| {
                v.sort_by(f64::total_cmp);
                (name, v[v.len() / 2])
            })
            .collect();
        let n = cameras.len().max(1) as f64;
        let edge_mode = matches!(mode, AaMode::Edges | AaMode::EdgesSorted);
        r.set_edge_gpu_classify(false);
        rows.push(AaRow {
            mode: if gpu { "edges-gpu".into() } else { mode.name() },
            coverage: edge_mode.then_some(coverage),
            rmse: rmse / n,
            rmse_srgb8: rmse8 / n,
            pixels: pixels / n,
            delta_e_mean: de / n,
            crawl: crawl / (images.len().saturating_sub(1).max(1)) as f64,
            frame_ms: times[times.len() / 2],
            pass_ms,
        });
    }
    r.set_edge_aa(EdgeAa::Off);
    r.set_hair_aa(false);
    Ok(rows)
}

/// The edge counts of table 1 for the mesh uploaded to `r` (edges prepared), averaged over
/// `yaws` around it, with the CPU cost of the two silhouette searches and of the sorted list.
///
/// # Errors
/// [`crate::RenderError::Invalid`] without prepared edges or a mesh.
pub fn edge_table(r: &Renderer, yaws_deg: &[f32], pitch_deg: f32) -> Result<EdgeTable> {
    let edges = r.edges().ok_or_else(|| crate::RenderError::Invalid("no edges prepared".into()))?;
    let bounds = r.mesh_bounds().ok_or_else(|| crate::RenderError::Invalid("no mesh".into()))?;
    let mut table = EdgeTable { counts: edges.set.counts, ..Default::default() };
    let eyes: Vec<glam::Vec3> = yaws_deg.iter().map(|&y| Camera::framing(&bounds, y, pitch_deg).position()).collect();
    let n = eyes.len().max(1) as f64;
    let time = |f: &dyn Fn(glam::Vec3)| {
        let start = Instant::now();
        for &eye in &eyes {
            f(eye);
        }
        start.elapsed().as_secs_f64() * 1e6 / n
    };
    table.search_brute_us = time(&|eye| {
        std::hint::black_box(edges.silhouettes_brute_force(eye));
    });
    table.search_skipping_us = time(&|eye| {
        std::hint::black_box(edges.silhouettes_skipping(eye));
    });
    table.sorted_list_us = time(&|eye| {
        std::hint::black_box(edges.frame(eye, true));
    });
    let mut sum = FrameEdgeStats::default();
    for &eye in &eyes {
        let (_, s) = edges.frame(eye, true);
        sum.extracted_silhouettes += s.extracted_silhouettes;
        sum.rendered += s.rendered;
        sum.sorted += s.sorted;
        sum.blended += s.blended;
    }
    table.extracted_silhouettes = sum.extracted_silhouettes as f64 / n;
    table.rendered = sum.rendered as f64 / n;
    table.sorted = sum.sorted as f64 / n;
    table.blended = sum.blended as f64 / n;
    Ok(table)
}
