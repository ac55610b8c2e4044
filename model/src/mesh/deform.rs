//! Meshes that move: everything about subdividing and triangulating a mesh that does not depend
//! on where its vertices are, computed once, so that a deformed frame (new base positions from
//! [`super::targets`]) re-runs only the position rules, the normals and a gather.

use glam::Vec3;

use super::gather::{NormalGather, StepGather, par_fill, threads};
use super::subdivide::StepTopology;
use super::{Face, Mesh, TriangleMesh};

/// A base mesh's subdivision and triangulation with the positions left open: build once with
/// [`SubdivisionPlan::new`], then [`SubdivisionPlan::mesh`] or [`SubdivisionPlan::update`] per
/// set of base positions.
///
/// Triangles and UVs are those of the rest pose (the quads' diagonals are chosen there), so a
/// deformed mesh keeps the index buffer and the UV layout of the rest mesh and only its
/// positions and normals change.
#[derive(Debug, Clone)]
pub struct SubdivisionPlan {
    steps: Vec<(StepTopology, StepGather)>,
    /// The finest faces' vertex lists (for the normals).
    normals: NormalGather,
    /// The finest level's faces (for the normals).
    faces: Vec<Face>,
    /// Positions of the finest level.
    fine_count: usize,
    /// The triangle mesh of the rest pose.
    rest: TriangleMesh,
    /// Finest-level position of each triangle-mesh vertex.
    sources: Vec<u32>,
    base_count: usize,
}

impl SubdivisionPlan {
    /// Plans `levels` Catmull-Clark steps of `base` and its triangulation at `base`'s positions.
    /// The rest mesh ([`SubdivisionPlan::rest`]) is exactly `base.catmull_clark(levels).triangulate()`.
    pub fn new(base: &Mesh, levels: u32) -> SubdivisionPlan {
        let mut steps = Vec::with_capacity(levels as usize);
        let mut mesh = base.clone();
        for _ in 0..levels {
            let step = StepTopology::new(&mesh);
            let positions = step.positions(&mesh.positions);
            mesh = Mesh { positions, ..step.children(&mesh) };
            let gather = StepGather::new(&step);
            steps.push((step, gather));
        }
        if levels > 0 {
            mesh.recompute_normals();
        }
        let (rest, sources) = mesh.triangulate_with_sources();
        SubdivisionPlan {
            normals: NormalGather::new(mesh.positions.len(), &mesh.faces),
            steps,
            fine_count: mesh.positions.len(),
            faces: mesh.faces,
            rest,
            sources,
            base_count: base.positions.len(),
        }
    }

    /// The triangle mesh at the base's rest positions.
    pub fn rest(&self) -> &TriangleMesh {
        &self.rest
    }

    /// Positions the base mesh has (what [`SubdivisionPlan::update`] takes).
    pub fn base_vertex_count(&self) -> usize {
        self.base_count
    }

    /// The triangle mesh for base positions `base` (as many as the planned mesh had).
    pub fn mesh(&self, base: &[Vec3]) -> TriangleMesh {
        let mut out = self.rest.clone();
        self.update(base, &mut out);
        out
    }

    /// Rewrites the positions and normals of `out` (a clone of [`SubdivisionPlan::rest`]) for
    /// base positions `base`: the subdivision's position rules level by level, area-weighted
    /// normals of the finest faces, then one gather, each step on every core (at most 16) in
    /// gather form ([`super::gather`]: the serial rules' result bit for bit). Tangents, if any,
    /// are dropped (they would be stale). At 0 levels the normals are recomputed too (the rest
    /// mesh keeps the file's).
    ///
    /// # Panics
    /// If `base` or `out` does not match the plan (a programming error, checked up front).
    pub fn update(&self, base: &[Vec3], out: &mut TriangleMesh) {
        self.update_on(base, out, threads());
    }

    /// The threads [`SubdivisionPlan::update`] uses: the machine's cores, at most 16.
    pub fn threads() -> usize {
        threads()
    }

    /// [`SubdivisionPlan::update`] on `threads` threads (1: the calling thread alone).
    ///
    /// # Panics
    /// As [`SubdivisionPlan::update`].
    pub fn update_on(&self, base: &[Vec3], out: &mut TriangleMesh, threads: usize) {
        assert_eq!(base.len(), self.base_count, "SubdivisionPlan::update: base positions of another mesh");
        assert_eq!(out.positions.len(), self.sources.len(), "SubdivisionPlan::update: not this plan's mesh");
        let mut positions = base.to_vec();
        for (step, gather) in &self.steps {
            positions = gather.positions(step, &positions, threads);
        }
        debug_assert_eq!(positions.len(), self.fine_count);
        let normals = self.normals.normals(&positions, &self.faces, threads);
        let sources = &self.sources;
        par_fill(&mut out.positions, threads, |i| positions[sources[i] as usize]);
        par_fill(&mut out.normals, threads, |i| normals[sources[i] as usize].try_normalize().unwrap_or(Vec3::Z));
        out.tangents = None;
    }
}
