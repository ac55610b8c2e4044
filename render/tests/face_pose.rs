//! The makeup follows the face: a lipstick painted by the lips' region on the neutral head lies
//! on the lips of the smiling head in a render (GPU, lavapipe on CI).

use std::collections::HashSet;

use glam::Vec3;
use rouge_model::look::Region;
use rouge_model::mesh::TriangleMesh;
use rouge_render::job::{FacePose, LookChoice, RenderJob, posed_default_head};

const SIZE: u32 = 160;

/// The lips' vertices (lips mask above one half at their UV).
fn lip_points(mesh: &TriangleMesh) -> Vec<Vec3> {
    let mask = Region::Lips.mask();
    mesh.positions.iter().zip(&mesh.uvs).filter(|(_, uv)| mask.sample_uv(uv.x, uv.y) > 0.5).map(|(p, _)| *p).collect()
}

#[test]
fn lipstick_stays_on_the_lips_of_a_smile() {
    let dir = tempfile::tempdir().expect("tempdir");
    let look = dir.path().join("lipstick.json");
    let text = r#"{"schema": "rouge-look", "version": 1, "name": "Lipstick", "layers": [
        {"preset": "builtin:lipstick_02_red", "thickness": {"region": "lips", "thickness_mm": 0.02}}]}"#;
    std::fs::write(&look, text).expect("write look");
    let smile = FacePose {
        expression: [("smile".to_string(), 1.0), ("jawOpen".to_string(), 0.3)].into_iter().collect(),
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
    // The lips' silhouette in the same frame, posed and neutral: projected lip vertices, 2 px wide.
    let (rest, posed) = posed_default_head(None, &smile, 1).expect("pose");
    let silhouette = |points: Vec<Vec3>| -> HashSet<(i32, i32)> {
        let mut out = HashSet::new();
        for p in points {
            let Some((x, y)) = made_up.renderer.project(p) else { continue };
            for dy in -2..=2 {
                for dx in -2..=2 {
                    out.insert((x as i32 + dx, y as i32 + dy));
                }
            }
        }
        out
    };
    let on = |s: &HashSet<(i32, i32)>| lipstick.iter().filter(|p| s.contains(p)).count() as f64 / lipstick.len() as f64;
    let (smiling, neutral) = (on(&silhouette(lip_points(&posed))), on(&silhouette(lip_points(&rest))));
    assert!(smiling > 0.9, "{:.0}% of the lipstick lies on the smiling lips", smiling * 100.0);
    assert!(neutral < smiling - 0.1, "the neutral lips hold {:.0}% of it: the pose did not move them", neutral * 100.0);
}
