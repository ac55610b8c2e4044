//! The makeup follows the face: a lipstick painted by the lips' region on the neutral head lies
//! on the lips of the smiling head in a render (GPU, lavapipe on CI).

use std::collections::HashSet;

use glam::Vec3;
use rouge_model::look::Region;
use rouge_model::mesh::TriangleMesh;
use rouge_render::job::{FacePose, LookChoice, RenderJob, posed_default_head};

const SIZE: u32 = 320;

/// The lips' triangles (all three corners with the lips mask above one half at their UV).
fn lip_triangles(mesh: &TriangleMesh) -> Vec<[Vec3; 3]> {
    let mask = Region::Lips.mask();
    let lip = |i: u32| {
        let uv = mesh.uvs[i as usize];
        mask.sample_uv(uv.x, uv.y) > 0.5
    };
    mesh.indices
        .chunks_exact(3)
        .filter(|t| t.iter().all(|&i| lip(i)))
        .map(|t| [0, 1, 2].map(|k| mesh.positions[t[k] as usize]))
        .collect()
}

#[test]
fn lipstick_stays_on_the_lips_of_a_smile() {
    let dir = tempfile::tempdir().expect("tempdir");
    let look = dir.path().join("lipstick.json");
    let text = r#"{"schema": "rouge-look", "version": 1, "name": "Lipstick", "layers": [
        {"preset": "builtin:lipstick_02_red", "thickness": {"region": "lips", "thickness_mm": 0.02}}]}"#;
    std::fs::write(&look, text).expect("write look");
    let smile = FacePose {
        expression: [("smile".to_string(), 1.0), ("jawOpen".to_string(), 0.5)].into_iter().collect(),
        ..FacePose::default()
    };
    let job = |look: LookChoice| RenderJob {
        look,
        width: SIZE,
        height: SIZE,
        subdivision: 1,
        face: smile.clone(),
        ..RenderJob::default()
    };
    let mut made_up = job(LookChoice::File(look)).prepare().expect("prepare");
    let with = made_up.render_display().expect("render");
    let without = job(LookChoice::Bare).prepare().expect("prepare").render_display().expect("render");
    // The lipstick's pixels: where the lipstick changes the frame.
    let lipstick: Vec<(i32, i32)> = (0..(SIZE * SIZE) as usize)
        .filter(|&i| (0..3).map(|c| with[4 * i + c].abs_diff(without[4 * i + c]) as u32).sum::<u32>() > 30)
        .map(|i| ((i as u32 % SIZE) as i32, (i as u32 / SIZE) as i32))
        .collect();
    assert!(lipstick.len() > 100, "{} lipstick pixels", lipstick.len());
    // The lips' silhouette in the same frame, posed and neutral: their projected triangles.
    let (rest, posed) = posed_default_head(None, &smile, None, 1).expect("pose");
    let silhouette = |triangles: Vec<[Vec3; 3]>| -> HashSet<(i32, i32)> {
        let mut out = HashSet::new();
        for t in triangles {
            let Some(q) = t.iter().map(|&p| made_up.renderer.project(p)).collect::<Option<Vec<(f32, f32)>>>() else {
                continue;
            };
            let area = (q[1].0 - q[0].0) * (q[2].1 - q[0].1) - (q[2].0 - q[0].0) * (q[1].1 - q[0].1);
            if area.abs() < 1e-6 {
                continue;
            }
            let (x0, x1) =
                (q.iter().map(|p| p.0).fold(f32::MAX, f32::min), q.iter().map(|p| p.0).fold(f32::MIN, f32::max));
            let (y0, y1) =
                (q.iter().map(|p| p.1).fold(f32::MAX, f32::min), q.iter().map(|p| p.1).fold(f32::MIN, f32::max));
            for y in (y0.floor() as i32)..=(y1.ceil() as i32) {
                for x in (x0.floor() as i32)..=(x1.ceil() as i32) {
                    let (px, py) = (x as f32 + 0.5, y as f32 + 0.5);
                    let edge =
                        |a: (f32, f32), b: (f32, f32)| ((b.0 - a.0) * (py - a.1) - (px - a.0) * (b.1 - a.1)) / area;
                    let (w0, w1, w2) = (edge(q[1], q[2]), edge(q[2], q[0]), edge(q[0], q[1]));
                    if w0 >= 0.0 && w1 >= 0.0 && w2 >= 0.0 {
                        // The pixel and its neighbours: one pixel of slack for the edges.
                        for (dx, dy) in [(0, 0), (1, 0), (-1, 0), (0, 1), (0, -1)] {
                            out.insert((x + dx, y + dy));
                        }
                    }
                }
            }
        }
        out
    };
    let on = |s: &HashSet<(i32, i32)>| lipstick.iter().filter(|p| s.contains(p)).count() as f64 / lipstick.len() as f64;
    let (smiling, neutral) = (on(&silhouette(lip_triangles(&posed))), on(&silhouette(lip_triangles(&rest))));
    assert!(smiling > 0.9, "{:.0}% of the lipstick lies on the smiling lips", smiling * 100.0);
    assert!(neutral < smiling - 0.1, "the neutral lips hold {:.0}% of it: the pose did not move them", neutral * 100.0);
}
