//! The surface map: every texel's position on the mesh, from rasterising it in UV space,
//! dilated across seams, with a 3D grid for radius queries.

use super::*;

// ------------------------------------------------------------------------------------------
// Surface map

/// Where each texel of a UV map lies on the surface: built once per mesh and map size.
///
/// A texel is *covered* when a triangle covers its centre in UV space or when it lies in the
/// two-texel dilation ring around such texels (it then takes the position of the nearest
/// covered texel). Only covered texels are ever painted.
#[derive(Clone)]
pub struct SurfaceMap {
    /// Map width in texels.
    pub width: u32,
    /// Map height in texels.
    pub height: u32,
    /// Per texel (row-major, row 0 at the top): its index into `points`, or [`UNCOVERED`].
    pub(super) slot: Vec<u32>,
    /// Positions of the covered texels, mm, grouped by grid cell (cells in x-fastest order).
    pub(super) points: Vec<Vec3>,
    /// Texel index (y · width + x) of each entry of `points`.
    pub(super) texels: Vec<u32>,
    /// Unit surface normal of each entry of `points` (interpolated from the mesh's vertex
    /// normals; NaN where the mesh has none, which every facing test passes).
    pub(super) normals: Vec<Vec3>,
    /// The mesh triangle under each entry of `points` (index into `graph.triangles`).
    pub(super) tri: Vec<u32>,
    /// The mesh's vertices welded and joined along its edges, for paths along the surface.
    pub(super) graph: super::reach::MeshGraph,
    /// The uniform grid over `points`.
    pub(super) grid: Grid,
    /// Centre of the mesh's bounds, mm: the fitted symmetry plane passes through it.
    pub(super) centre: Vec3,
}

impl fmt::Debug for SurfaceMap {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.debug_struct("SurfaceMap")
            .field("width", &self.width)
            .field("height", &self.height)
            .field("covered", &self.points.len())
            .field("graph_vertices", &self.graph.vertices())
            .field("grid", &self.grid)
            .field("centre", &self.centre)
            .finish()
    }
}

/// A uniform grid of cells; cell (i, j, k) holds `points[starts[c]..starts[c + 1]]` with
/// c = i + dims[0]·(j + dims[1]·k), so a run of cells along x is one contiguous slice.
#[derive(Clone)]
pub(super) struct Grid {
    origin: Vec3,
    cell_mm: f32,
    dims: [usize; 3],
    starts: Vec<u32>,
}

impl fmt::Debug for Grid {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.debug_struct("Grid")
            .field("origin", &self.origin)
            .field("cell_mm", &self.cell_mm)
            .field("dims", &self.dims)
            .finish()
    }
}

impl Grid {
    /// An empty grid: every query finds nothing.
    pub(super) fn empty() -> Grid {
        Grid { origin: Vec3::ZERO, cell_mm: GRID_CELL_MM, dims: [0; 3], starts: vec![0] }
    }

    /// A grid over the box `bounds`, cells of `GRID_CELL_MM` grown until there are at most
    /// `MAX_GRID_CELLS`.
    pub(super) fn over(bounds: Bounds) -> Grid {
        let size = bounds.size().max(Vec3::ZERO);
        let mut cell_mm = GRID_CELL_MM;
        loop {
            let dims = [0, 1, 2].map(|i| (size[i] / cell_mm).floor() as usize + 1);
            let cells = dims[0].saturating_mul(dims[1]).saturating_mul(dims[2]);
            if cells <= MAX_GRID_CELLS {
                return Grid { origin: bounds.min, cell_mm, dims, starts: Vec::new() };
            }
            cell_mm *= ((cells as f64 / MAX_GRID_CELLS as f64).cbrt() as f32).max(1.01);
        }
    }

    /// Linear cell index of a point inside the grid's box (clamped to the grid).
    pub(super) fn cell_of(&self, p: Vec3) -> usize {
        let c = ((p - self.origin) / self.cell_mm).floor();
        let [i, j, k] = [0, 1, 2].map(|a| (c[a].max(0.0) as usize).min(self.dims[a].saturating_sub(1)));
        i + self.dims[0] * (j + self.dims[1] * k)
    }

    /// Unclamped cell coordinates of a point (saturating for points far away).
    pub(super) fn coords(&self, p: Vec3) -> [i64; 3] {
        let c = ((p - self.origin) / self.cell_mm).floor();
        [0, 1, 2].map(|a| c[a].clamp(-1.0e9, 1.0e9) as i64)
    }

    /// Inclusive cell ranges covering the box [lo, hi], clipped to the grid; `None` when the
    /// box misses the grid (or holds NaN).
    pub(super) fn range(&self, lo: Vec3, hi: Vec3) -> Option<CellBox> {
        if !(lo.is_finite() && hi.is_finite()) || self.dims.contains(&0) {
            return None;
        }
        let (a, b) = (self.coords(lo), self.coords(hi));
        let mut out = CellBox { lo: [0; 3], hi: [0; 3] };
        for axis in 0..3 {
            let last = self.dims[axis] as i64 - 1;
            if b[axis] < 0 || a[axis] > last {
                return None;
            }
            out.lo[axis] = a[axis].max(0) as usize;
            out.hi[axis] = b[axis].min(last) as usize;
        }
        Some(out)
    }

    /// The index range into `points` of cells x0..=x1 in row (j, k).
    pub(super) fn run(&self, x0: usize, x1: usize, j: usize, k: usize) -> std::ops::Range<usize> {
        let base = self.dims[0] * (j + self.dims[1] * k);
        self.starts[base + x0] as usize..self.starts[base + x1 + 1] as usize
    }

    /// Calls `f` with the index range into `points` of every row of cells in `cells`.
    pub(super) fn for_each_run(&self, cells: CellBox, mut f: impl FnMut(std::ops::Range<usize>)) {
        for k in cells.lo[2]..=cells.hi[2] {
            for j in cells.lo[1]..=cells.hi[1] {
                f(self.run(cells.lo[0], cells.hi[0], j, k));
            }
        }
    }
}

/// An inclusive box of grid cells.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) struct CellBox {
    lo: [usize; 3],
    hi: [usize; 3],
}

/// A triangle prepared for rasterising: UVs in pixel space (y down), the attribute at its
/// corners, pixel bounds.
pub(super) struct RasterTriangle {
    uv: [Vec2; 3],
    attribute: [Vec3; 3],
    /// Half-open texel bounds (x0, y0, x1, y1) of the texel centres it may cover.
    bounds: [usize; 4],
}

impl SurfaceMap {
    /// Rasterises every skin triangle of `mesh` ([`crate::mesh::TriangleGroup::is_skin`]) into a `width` × `height` UV map (barycentric
    /// interpolation of the 3D positions and normals at texel centres), dilates the covered area
    /// by two texels, buckets the covered texels in a 3D grid, notes the triangle under each
    /// texel, and welds the mesh's vertices into a graph for paths along the surface. Triangles
    /// with indices out of range, non-finite data or no area in UV space are skipped; where UV
    /// islands overlap, the later triangle wins. An empty mesh or a zero size gives a map that
    /// covers nothing.
    ///
    /// Any [`TriangleMesh`] works: a deformed head (an expression, a face shape) with the same
    /// UVs gives the deformed surface; build again whenever the positions change.
    ///
    /// Uses all available cores (`std::thread::scope`) for rasterising and dilating.
    pub fn build(mesh: &TriangleMesh, width: u32, height: u32) -> SurfaceMap {
        // Paint and the skin's maps live on the skin: the eyes, mouth, teeth, tongue and lashes
        // are left out (their UV islands stay uncovered).
        let skin = mesh.only(|g| g.is_skin());
        let mesh = &skin;
        let (w, h) = (width as usize, height as usize);
        let centre = Bounds::of(&mesh.positions).map_or(Vec3::ZERO, |b| b.center());
        let centre = if centre.is_finite() { centre } else { Vec3::ZERO };
        let empty = || SurfaceMap {
            width,
            height,
            slot: vec![UNCOVERED; w * h],
            points: Vec::new(),
            texels: Vec::new(),
            normals: Vec::new(),
            tri: Vec::new(),
            graph: super::reach::MeshGraph::default(),
            grid: Grid::empty(),
            centre,
        };
        if w == 0 || h == 0 || w.checked_mul(h).is_none_or(|n| n >= UNCOVERED as usize) {
            return SurfaceMap { slot: Vec::new(), ..empty() };
        }
        let (covered, mut grid) = {
            let texel_pos = rasterise(mesh, &mesh.positions, w, h);
            let covered = dilate_and_collect(&texel_pos, w, h);
            let bounds = covered.iter().fold(None, |b: Option<Bounds>, &(_, p)| {
                Some(b.map_or(Bounds { min: p, max: p }, |b| Bounds { min: b.min.min(p), max: b.max.max(p) }))
            });
            let Some(bounds) = bounds else { return empty() };
            (covered, Grid::over(bounds))
        };
        // Counting sort of the covered texels by grid cell (stable: texel order within a cell).
        let cell: Vec<u32> = covered.iter().map(|&(_, p)| grid.cell_of(p) as u32).collect();
        let cells = grid.dims[0] * grid.dims[1] * grid.dims[2];
        let mut starts = vec![0u32; cells + 1];
        for &c in &cell {
            starts[c as usize + 1] += 1;
        }
        for c in 0..cells {
            starts[c + 1] += starts[c];
        }
        let mut cursor = starts.clone();
        let (mut points, mut texels) = (vec![Vec3::ZERO; covered.len()], vec![0u32; covered.len()]);
        let mut slot = vec![UNCOVERED; w * h];
        for (&(i, p), &c) in covered.iter().zip(&cell) {
            let s = cursor[c as usize];
            cursor[c as usize] += 1;
            points[s as usize] = p;
            texels[s as usize] = i;
            slot[i as usize] = s;
        }
        grid.starts = starts;
        let normals = texel_normals(mesh, &texels, w, h);
        let tri = texel_triangles(mesh, &texels, w, h);
        let graph = super::reach::MeshGraph::of(mesh);
        SurfaceMap { width, height, slot, points, texels, normals, tri, graph, grid, centre }
    }

    /// Number of covered texels (rasterised or in the dilation ring).
    pub fn covered(&self) -> usize {
        self.points.len()
    }

    /// The surface position of texel (x, y), mm; `None` outside the map or where the texel is
    /// not covered (no triangle covers its centre and it lies outside the dilation ring).
    pub fn position(&self, x: u32, y: u32) -> Option<Vec3> {
        if x >= self.width || y >= self.height {
            return None;
        }
        let s = *self.slot.get(y as usize * self.width as usize + x as usize)?;
        self.points.get(s as usize).copied()
    }

    /// x of the fitted symmetry plane (the mesh bounds' centre x), mm: 0 for the default head.
    pub fn mirror_x(&self) -> f32 {
        self.centre.x
    }

    /// The centre of the mesh's bounds, mm (where [`MirrorPlane::fitted`] planes pass).
    pub fn centre(&self) -> Vec3 {
        self.centre
    }

    /// The mirror image of `p` across the fitted plane x = [`SurfaceMap::mirror_x`].
    pub fn mirror(&self, p: Vec3) -> Vec3 {
        MirrorPlane::fitted(Axis::X, self).reflect(p)
    }

    /// The unit normal of texel (x, y) (interpolated from the mesh's vertex normals); `None`
    /// where the texel is not covered or the mesh has no usable normal there.
    pub fn normal(&self, x: u32, y: u32) -> Option<Vec3> {
        if x >= self.width || y >= self.height {
            return None;
        }
        let s = *self.slot.get(y as usize * self.width as usize + x as usize)?;
        self.normals.get(s as usize).copied().filter(|n| n.is_finite())
    }

    /// Number of the mesh's vertices once welded by position (UV seams joined): the vertices of
    /// the graph brush paths run on.
    pub fn welded_vertices(&self) -> usize {
        self.graph.vertices()
    }

    /// The position of the covered texel closest to `p` within `max_mm` (3D distance), for
    /// projecting interpolated stroke points back onto the surface; `None` when there is none
    /// or `p` is not finite.
    ///
    /// Searches grid cells in growing shells around `p` and stops once no closer point can
    /// remain, so the cost depends on the distance to the answer, not on `max_mm`.
    pub fn nearest_on_surface(&self, p: Vec3, max_mm: f32) -> Option<Vec3> {
        self.nearest_slot(p, max_mm).map(|s| self.points[s])
    }

    /// The texel (x, y) whose surface position is closest to `p` within `max_mm`, as
    /// [`SurfaceMap::nearest_on_surface`]: what lies under a picked point.
    pub fn nearest_texel(&self, p: Vec3, max_mm: f32) -> Option<(u32, u32)> {
        let i = self.texels[self.nearest_slot(p, max_mm)?];
        Some((i % self.width, i / self.width))
    }

    /// Index into `points` of the covered texel closest to `p` within `max_mm`.
    pub(super) fn nearest_slot(&self, p: Vec3, max_mm: f32) -> Option<usize> {
        if !p.is_finite() || max_mm.is_nan() || max_mm < 0.0 || self.points.is_empty() {
            return None;
        }
        let max_mm = max_mm.min(1.0e6);
        let grid = &self.grid;
        let c = grid.coords(p);
        let dims = grid.dims.map(|d| d as i64);
        let mut best: Option<usize> = None;
        let mut best_d2 = max_mm * max_mm;
        let shells = (max_mm / grid.cell_mm).ceil() as i64 + 1;
        for k in 0..=shells {
            // Every point in shell k is at least (k − 1) cells from p (p lies in cell c).
            let reach = (k - 1).max(0) as f32 * grid.cell_mm;
            if reach * reach > best_d2 {
                break;
            }
            let (z0, z1) = ((c[2] - k).max(0), (c[2] + k).min(dims[2] - 1));
            let (y0, y1) = ((c[1] - k).max(0), (c[1] + k).min(dims[1] - 1));
            let (x0, x1) = ((c[0] - k).max(0), (c[0] + k).min(dims[0] - 1));
            if z0 > z1 || y0 > y1 || x0 > x1 {
                continue;
            }
            let mut visit = |xa: i64, xb: i64, y: i64, z: i64| {
                for i in grid.run(xa as usize, xb as usize, y as usize, z as usize) {
                    let d2 = self.points[i].distance_squared(p);
                    if d2 <= best_d2 {
                        best_d2 = d2;
                        best = Some(i);
                    }
                }
            };
            for z in z0..=z1 {
                for y in y0..=y1 {
                    if (z - c[2]).abs() == k || (y - c[1]).abs() == k {
                        visit(x0, x1, y, z);
                    } else {
                        // Only the two end cells of this row lie on the shell.
                        if c[0] - k >= 0 && c[0] - k < dims[0] {
                            visit(c[0] - k, c[0] - k, y, z);
                        }
                        if k > 0 && c[0] + k >= 0 && c[0] + k < dims[0] {
                            visit(c[0] + k, c[0] + k, y, z);
                        }
                    }
                }
            }
        }
        best
    }
}

/// The unit normal of each covered texel `texels[i]` (texel indices of a `w` × `h` map): the
/// mesh's vertex normals rasterised like the positions; a texel of the dilation ring takes the
/// nearest rasterised normal within [`DILATE_TEXELS`]; NaN where there is none (a mesh without
/// normals).
fn texel_normals(mesh: &TriangleMesh, texels: &[u32], w: usize, h: usize) -> Vec<Vec3> {
    let nan = Vec3::splat(f32::NAN);
    if mesh.normals.len() != mesh.positions.len() || texels.is_empty() {
        return vec![nan; texels.len()];
    }
    let raster = rasterise(mesh, &mesh.normals, w, h);
    let r = DILATE_TEXELS as i64;
    texels
        .iter()
        .map(|&i| {
            if raster[i as usize].is_finite() {
                return raster[i as usize].normalize_or(nan);
            }
            let (x, y) = ((i as usize % w) as i64, (i as usize / w) as i64);
            let mut best = (i64::MAX, nan);
            for dy in -r..=r {
                for dx in -r..=r {
                    let (nx, ny) = (x + dx, y + dy);
                    if nx < 0 || ny < 0 || nx >= w as i64 || ny >= h as i64 {
                        continue;
                    }
                    let n = raster[ny as usize * w + nx as usize];
                    if n.is_finite() && dx * dx + dy * dy < best.0 {
                        best = (dx * dx + dy * dy, n);
                    }
                }
            }
            best.1.normalize_or(nan)
        })
        .collect()
}

/// The index of the triangle under each covered texel `texels[i]` of a `w` × `h` map (the
/// dilation ring takes its nearest covered texel's, as for the positions); `u32::MAX` where
/// none. The rasteriser interpolates per-vertex attributes, so each triangle gets three vertices
/// of its own carrying its index (exact in f32 up to 2²⁴ triangles).
fn texel_triangles(mesh: &TriangleMesh, texels: &[u32], w: usize, h: usize) -> Vec<u32> {
    let n = mesh.indices.len() / 3;
    let corner_uv = |i: u32| mesh.uvs.get(i as usize).copied().unwrap_or(Vec2::NAN);
    let unshared = TriangleMesh {
        uvs: mesh.indices.iter().map(|&i| corner_uv(i)).collect(),
        indices: (0..(3 * n) as u32).collect(),
        ..TriangleMesh::default()
    };
    let ids: Vec<Vec3> = (0..3 * n).map(|c| Vec3::splat((c / 3) as f32)).collect();
    let mut id_of = vec![f32::NAN; w * h];
    for (i, v) in dilate_and_collect(&rasterise(&unshared, &ids, w, h), w, h) {
        id_of[i as usize] = v.x;
    }
    texels
        .iter()
        .map(|&i| {
            let id = id_of[i as usize].round();
            if id >= 0.0 && (id as usize) < n { id as u32 } else { u32::MAX }
        })
        .collect()
}

/// A per-vertex attribute of `mesh` (`attribute[i]` belongs to vertex i: the positions for the
/// surface map, baked values for [`crate::thickness::thickness_uv_map`]) interpolated
/// barycentrically at every texel centre of a `w` × `h` UV map (row 0 at the top, v = 1); NaN
/// where no triangle covers the texel centre. Triangles with an index out of range of the
/// attribute or the UVs, non-finite data or no area in UV space are skipped; where UV islands
/// overlap, the later triangle wins. Rasterised in bands of rows on all cores.
pub(crate) fn rasterise(mesh: &TriangleMesh, attribute: &[Vec3], w: usize, h: usize) -> Vec<Vec3> {
    let nan = Vec3::splat(f32::NAN);
    let triangles: Vec<RasterTriangle> = mesh
        .indices
        .chunks_exact(3)
        .filter_map(|t| raster_triangle(mesh, attribute, [t[0], t[1], t[2]], w, h))
        .collect();
    // Bin the triangles by the bands of rows they touch.
    let bands = h.div_ceil(RASTER_BAND_ROWS);
    let mut binned: Vec<Vec<u32>> = vec![Vec::new(); bands];
    for (i, t) in triangles.iter().enumerate() {
        for bin in &mut binned[t.bounds[1] / RASTER_BAND_ROWS..=(t.bounds[3] - 1) / RASTER_BAND_ROWS] {
            bin.push(i as u32);
        }
    }
    let mut out = vec![nan; w * h];
    let work: Mutex<Vec<(usize, &mut [Vec3])>> =
        Mutex::new(out.chunks_mut(RASTER_BAND_ROWS * w).enumerate().rev().collect());
    let threads = std::thread::available_parallelism().map_or(1, |n| n.get()).min(bands);
    let job = || {
        loop {
            let next = match work.lock() {
                Ok(mut queue) => queue.pop(),
                Err(_) => None,
            };
            let Some((band, rows)) = next else { break };
            let y_band = band * RASTER_BAND_ROWS;
            for &t in &binned[band] {
                raster_into(&triangles[t as usize], rows, w, y_band);
            }
        }
    };
    if threads <= 1 {
        job();
    } else {
        std::thread::scope(|s| {
            for _ in 0..threads {
                s.spawn(job);
            }
        });
    }
    out
}

/// Prepares triangle `t` for rasterising `attribute`; `None` when it is unusable or covers no
/// texel centre.
pub(super) fn raster_triangle(
    mesh: &TriangleMesh,
    attribute: &[Vec3],
    t: [u32; 3],
    w: usize,
    h: usize,
) -> Option<RasterTriangle> {
    let mut uv = [Vec2::ZERO; 3];
    let mut value = [Vec3::ZERO; 3];
    for k in 0..3 {
        let i = t[k] as usize;
        let (p, q) = (*attribute.get(i)?, *mesh.uvs.get(i)?);
        if !(p.is_finite() && q.is_finite()) {
            return None;
        }
        value[k] = p;
        uv[k] = Vec2::new(q.x * w as f32, (1.0 - q.y) * h as f32);
    }
    let area = (uv[1] - uv[0]).perp_dot(uv[2] - uv[0]);
    if area.is_nan() || area.abs() <= 1.0e-9 {
        return None;
    }
    let lo = uv[0].min(uv[1]).min(uv[2]);
    let hi = uv[0].max(uv[1]).max(uv[2]);
    // Texel centres x + 0.5 within [lo, hi] (a hair wider so shared edges leave no cracks).
    let first = |v: f32, n: usize| ((v - 0.5 - 1.0e-3).ceil().max(0.0) as usize).min(n);
    let end = |v: f32, n: usize| (((v - 0.5 + 1.0e-3).floor() + 1.0).max(0.0) as usize).min(n);
    let bounds = [first(lo.x, w), first(lo.y, h), end(hi.x, w), end(hi.y, h)];
    (bounds[0] < bounds[2] && bounds[1] < bounds[3]).then_some(RasterTriangle { uv, attribute: value, bounds })
}

/// Writes the interpolated attribute of the texels of `rows` (texel rows from `y_band`) that
/// triangle `t` covers. Edges are inclusive (a tiny tolerance), so neighbours leave no cracks;
/// a texel on a shared edge gets the same value from either triangle.
pub(super) fn raster_into(t: &RasterTriangle, rows: &mut [Vec3], w: usize, y_band: usize) {
    let [a, b, c] = t.uv;
    let area = (b - a).perp_dot(c - a);
    let (sign, tolerance) = (area.signum(), -1.0e-5 * area.abs());
    let band_rows = rows.len() / w;
    let (y0, y1) = (t.bounds[1].max(y_band), t.bounds[3].min(y_band + band_rows));
    for y in y0..y1 {
        let row = &mut rows[(y - y_band) * w..(y - y_band + 1) * w];
        let py = y as f32 + 0.5;
        for (x, texel) in row.iter_mut().enumerate().take(t.bounds[2]).skip(t.bounds[0]) {
            let p = Vec2::new(x as f32 + 0.5, py);
            let la = (c - b).perp_dot(p - b) * sign;
            let lb = (a - c).perp_dot(p - c) * sign;
            let lc = (b - a).perp_dot(p - a) * sign;
            if la >= tolerance && lb >= tolerance && lc >= tolerance {
                let sum = la + lb + lc;
                *texel = (t.attribute[0] * la + t.attribute[1] * lb + t.attribute[2] * lc) / sum;
            }
        }
    }
}

/// The covered texels of a [`rasterise`]d map after dilating by [`DILATE_TEXELS`], in texel
/// order: (index, value). A texel no triangle covers (NaN) within the (2·DILATE_TEXELS + 1)²
/// window around a covered one takes the value of the nearest covered texel in that window
/// (Euclidean distance in texels, ties in a fixed order). Bands of rows on all cores.
pub(crate) fn dilate_and_collect(src: &[Vec3], w: usize, h: usize) -> Vec<(u32, Vec3)> {
    const R: i64 = DILATE_TEXELS as i64;
    let mut offsets: Vec<(i64, i64)> = (-R..=R).flat_map(|dy| (-R..=R).map(move |dx| (dx, dy))).collect();
    offsets.retain(|&o| o != (0, 0));
    offsets.sort_by_key(|&(dx, dy)| dx * dx + dy * dy);
    let covered: Vec<bool> = par_rows(h, |rows| {
        rows.flat_map(|y| src[y * w..(y + 1) * w].iter().map(|p| !p.x.is_nan())).collect::<Vec<bool>>()
    })
    .concat();
    // Whether any texel within DILATE_TEXELS columns in the same row is covered.
    let near_in_row: Vec<bool> = par_rows(h, |rows| {
        rows.flat_map(|y| {
            let row = &covered[y * w..(y + 1) * w];
            (0..w).map(move |x| row[x.saturating_sub(DILATE_TEXELS)..(x + DILATE_TEXELS + 1).min(w)].contains(&true))
        })
        .collect::<Vec<bool>>()
    })
    .concat();
    par_rows(h, |rows| {
        let mut out = Vec::new();
        for y in rows {
            let (ya, yb) = (y.saturating_sub(DILATE_TEXELS), (y + DILATE_TEXELS + 1).min(h));
            for x in 0..w {
                let i = y * w + x;
                if covered[i] {
                    out.push((i as u32, src[i]));
                    continue;
                }
                if !(ya..yb).any(|yy| near_in_row[yy * w + x]) {
                    continue;
                }
                let nearest = offsets.iter().find_map(|&(dx, dy)| {
                    let (nx, ny) = (x as i64 + dx, y as i64 + dy);
                    let inside = nx >= 0 && ny >= 0 && nx < w as i64 && ny < h as i64;
                    let j = ny * w as i64 + nx;
                    (inside && covered[j as usize]).then(|| src[j as usize])
                });
                if let Some(p) = nearest {
                    out.push((i as u32, p));
                }
            }
        }
        out
    })
    .concat()
}

/// Runs `f` on contiguous bands of the rows 0..h, one band per core, and returns the results in
/// row order.
pub(crate) fn par_rows<T: Send>(h: usize, f: impl Fn(std::ops::Range<usize>) -> T + Sync) -> Vec<T> {
    let threads = std::thread::available_parallelism().map_or(1, |n| n.get()).clamp(1, h.max(1));
    let band = h.div_ceil(threads);
    if threads == 1 {
        return vec![f(0..h)];
    }
    std::thread::scope(|s| {
        let handles: Vec<_> = (0..threads)
            .map(|t| {
                let f = &f;
                s.spawn(move || f((t * band).min(h)..((t + 1) * band).min(h)))
            })
            .collect();
        // A worker can only panic on a bug here; pass it on rather than lose its rows.
        handles.into_iter().map(|handle| handle.join().unwrap_or_else(|e| std::panic::resume_unwind(e))).collect()
    })
}
