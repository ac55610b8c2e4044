//! What the model's tests share: the head they paint on (here), and the skin projects (project.rs).

pub mod project;

use rouge_model::mesh::{TriangleMesh, load_mesh};
use rouge_model::paint::SurfaceMap;
use std::sync::OnceLock;

/// Side of the test maps, texels.
pub const SIZE: u32 = 1024;

/// The lighter default head's skin (one Catmull-Clark level; the eyes, mouth, teeth, tongue
/// and lashes left out, as the surface map leaves them) and its surface map at 1024², built
/// once per test binary.
pub fn head() -> &'static (TriangleMesh, SurfaceMap) {
    static HEAD: OnceLock<(TriangleMesh, SurfaceMap)> = OnceLock::new();
    HEAD.get_or_init(|| {
        let mesh = load_mesh(None, 1.0, 1).expect("default head").only(|g| g.is_skin());
        let surface = SurfaceMap::build(&mesh, SIZE, SIZE);
        (mesh, surface)
    })
}
