//! Meshes that move: everything about subdividing and triangulating a mesh that does not depend
//! on where its vertices are, computed once, so that a deformed frame (new base positions from
//! [`super::targets`]) re-runs only the position rules, the normals and a gather.

use glam::Vec3;

use super::gather::{NormalGather, StepGather, par_fill_pair, threads};
use super::subdivide::StepTopology;
use super::{Mesh, TriangleMesh};

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
    /// Positions of the finest level.
    fine_count: usize,
    /// The triangle mesh of the rest pose.
    rest: TriangleMesh,
    /// Finest-level position of each triangle-mesh vertex.
    sources: Vec<u32>,
    base_count: usize,
    /// Each level's positions and the finest faces' vector areas, kept between updates so a
    /// frame allocates nothing (fresh pages are most of the cost on a virtual machine).
    scratch: Scratch,
}

/// [`SubdivisionPlan`]'s buffers between updates; a clone starts empty.
#[derive(Debug, Default)]
struct Scratch(std::sync::Mutex<(Vec<Vec<Vec3>>, Vec<Vec3>)>);

impl Clone for Scratch {
    fn clone(&self) -> Scratch {
        Scratch::default()
    }
}

impl SubdivisionPlan {
    /// Plans `levels` Catmull-Clark steps of `base` and its triangulation at `base`'s positions.
    /// The rest mesh ([`SubdivisionPlan::rest`]) is exactly `base.catmull_clark(levels).triangulate()`, with the base's hairs as strands
    /// ([`super::strands::subdivided_with_strands`]).
    pub fn new(base: &Mesh, levels: u32) -> SubdivisionPlan {
        let strands = super::strands::HairStrands::of(base);
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
        let (mut rest, sources) = mesh.triangulate_with_sources();
        rest.strands = super::strands::attach(&strands, &sources);
        SubdivisionPlan {
            normals: NormalGather::new(mesh.positions.len(), &mesh.faces),
            steps,
            fine_count: mesh.positions.len(),
            rest,
            sources,
            base_count: base.positions.len(),
            scratch: Scratch::default(),
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
    /// gather form (`model/src/mesh/gather.rs`: the serial rules' result bit for bit). Tangents, if any,
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
        let mut guard = self.scratch.0.lock().unwrap_or_else(std::sync::PoisonError::into_inner);
        let (levels, areas) = &mut *guard;
        levels.resize_with(self.steps.len(), Vec::new);
        for (i, (step, gather)) in self.steps.iter().enumerate() {
            let (done, next) = levels.split_at_mut(i);
            let parent = done.last().map_or(base, |p| p.as_slice());
            gather.positions_into(step, parent, &mut next[0], threads);
        }
        let positions = levels.last().map_or(base, |p| p.as_slice());
        debug_assert_eq!(positions.len(), self.fine_count);
        self.normals.areas_into(positions, areas, threads);
        let (sources, areas) = (&self.sources, &*areas);
        par_fill_pair(&mut out.positions, &mut out.normals, threads, |i| {
            let s = sources[i] as usize;
            (positions[s], self.normals.normal(s, areas).try_normalize().unwrap_or(Vec3::Z))
        });
        out.tangents = None;
    }
}
