//! What the app's window tests share: the app in an egui_kittest harness on lavapipe, and points
//! of the default face found from the mesh's surface map.

#![allow(dead_code)] // each test file uses its own part

use egui_kittest::Harness;
use glam::Vec3;
use rouge_app::gui::{Options, RougeApp};
use std::path::{Path, PathBuf};

/// The app at 1200×760 with its data in `data_dir` (no autosave), the face loaded.
pub fn harness(data_dir: &Path) -> Harness<'static, RougeApp> {
    harness_with_mesh(data_dir, None)
}

/// [`harness`] on another mesh (path and scale to mm).
pub fn harness_with_mesh(data_dir: &Path, mesh: Option<(PathBuf, f32)>) -> Harness<'static, RougeApp> {
    let dir = data_dir.to_owned();
    let mut h = Harness::builder().with_size(egui::vec2(1200.0, 760.0)).wgpu().build_eframe(move |cc| {
        RougeApp::new(
            cc,
            Options { data_dir: dir, project: None, autosave: false, mesh, window_screenshot: None, recover: false },
        )
        .expect("the app opens")
    });
    h.state_mut().wait_ready();
    h.run_steps(4);
    h
}

/// The surface point `(dx, dy)` mm beside and above the nose tip: the nose tip is the frontmost
/// surface point near the midplane, and the point the frontmost one within 4 mm of the offset.
pub fn beside_nose_tip(app: &RougeApp, dx: f32, dy: f32) -> Vec3 {
    let surface = app.surface().expect("surface map");
    let mid = surface.mirror_x();
    let frontmost = |keep: &dyn Fn(Vec3) -> bool| {
        let mut best: Option<Vec3> = None;
        for y in (0..surface.height).step_by(4) {
            for x in (0..surface.width).step_by(4) {
                if let Some(p) = surface.position(x, y)
                    && keep(p)
                    && best.is_none_or(|b| p.z > b.z)
                {
                    best = Some(p);
                }
            }
        }
        best.expect("a surface point")
    };
    let tip = frontmost(&|p| (p.x - mid).abs() < 10.0);
    let (tx, ty) = (tip.x + dx, tip.y + dy);
    frontmost(&move |p: Vec3| (p.x - tx).abs() < 4.0 && (p.y - ty).abs() < 4.0)
}
