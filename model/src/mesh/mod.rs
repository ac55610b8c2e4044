//! Polygon and triangle meshes: types, loading, subdivision, triangulation, tangents.
//!
//! Units: positions are millimetres. Loaders take a declared `scale_to_mm` factor because
//! scans come in arbitrary units (metres, centimetres, millimetres).

pub mod brow_gel;
mod cap;
pub mod deform;
mod gather;
mod gltf;
pub mod lashes;
mod load;
mod obj;
mod pool;
pub mod shapes;
pub mod strands;
mod subdivide;
mod tangents;
pub mod targets;

use std::collections::HashMap;
use std::ops::Range;
use std::path::PathBuf;

use glam::{Vec2, Vec3, Vec4};

pub use self::cap::close_boundary_loops;
pub use self::gltf::load_gltf;
pub use self::load::load_mesh;
pub use self::obj::{load_obj, parse_obj};

/// The default head (MakeHuman hm08 head and neck, CC0; see data/SOURCES.md), embedded so the
/// renderer works from any directory on a fresh machine. Millimetres, +Y up, facing +Z.
pub const DEFAULT_HEAD_OBJ: &str = include_str!("../../../data/heads/hm08_head.obj");

/// Loads the embedded default head (not yet subdivided).
///
/// # Errors
/// Only if the embedded file were corrupt (a build error in practice).
pub fn default_head() -> Result<Mesh, MeshError> {
    parse_obj(DEFAULT_HEAD_OBJ, std::path::Path::new("<embedded data/heads/hm08_head.obj>"), 1.0)
}

/// Errors from loading or preparing a mesh.
#[derive(Debug, thiserror::Error)]
pub enum MeshError {
    /// The file could not be read.
    #[error("{path}: {source}")]
    Io {
        /// File that failed.
        path: PathBuf,
        /// Underlying I/O error.
        source: std::io::Error,
    },
    /// A syntax or index error in an OBJ file, with its 1-based line and column.
    #[error(transparent)]
    Parse(#[from] rouge_measure::LocatedError),
    /// A glTF file that could not be read or interpreted.
    #[error("{path}: glTF: {message}")]
    Gltf {
        /// File being loaded.
        path: PathBuf,
        /// What is wrong.
        message: String,
    },
    /// The mesh has no texture coordinates (TEXCOORD_0 for glTF), which the renderer needs.
    #[error("{path}: mesh has no texture coordinates")]
    MissingUvs {
        /// File being loaded.
        path: PathBuf,
    },
    /// The declared unit scale is not a finite positive number.
    #[error("invalid scale_to_mm {0}: must be finite and > 0")]
    InvalidScale(f32),
    /// The mesh contains no faces.
    #[error("mesh has no faces")]
    Empty,
    /// MikkTSpace could not generate tangents.
    #[error("tangent generation failed: {0}")]
    Tangents(String),
}

/// One corner of a polygon: indices into [`Mesh::positions`], [`Mesh::uvs`] and [`Mesh::normals`].
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct Corner {
    /// Index into [`Mesh::positions`].
    pub position: u32,
    /// Index into [`Mesh::uvs`].
    pub uv: u32,
    /// Index into [`Mesh::normals`].
    pub normal: u32,
}

/// A polygon face (at least three corners, counter-clockwise seen from outside).
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Face {
    /// Corners in winding order.
    pub corners: Vec<Corner>,
}

/// A named range of consecutive faces sharing a group name and material (OBJ `g` / `usemtl`,
/// glTF mesh / material).
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Group {
    /// Group name (OBJ `g`, or glTF mesh name).
    pub name: String,
    /// Material name (OBJ `usemtl`, or glTF material name), if any.
    pub material: Option<String>,
    /// Range of indices into [`Mesh::faces`].
    pub faces: Range<usize>,
}

impl Group {
    /// What the group is ([`Part::of`] its name and material), as [`TriangleGroup::part`].
    pub fn part(&self) -> Part {
        Part::of(&self.name, self.material.as_deref())
    }
}

/// Axis-aligned bounding box in millimetres.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Bounds {
    /// Minimum corner.
    pub min: Vec3,
    /// Maximum corner.
    pub max: Vec3,
}

impl Bounds {
    /// Extent along each axis (`max - min`).
    pub fn size(&self) -> Vec3 {
        self.max - self.min
    }

    /// Centre of the box.
    pub fn center(&self) -> Vec3 {
        (self.min + self.max) * 0.5
    }

    /// Bounds of a point set; `None` when it is empty.
    pub fn of(points: &[Vec3]) -> Option<Bounds> {
        let first = *points.first()?;
        Some(
            points
                .iter()
                .fold(Bounds { min: first, max: first }, |b, &p| Bounds { min: b.min.min(p), max: b.max.max(p) }),
        )
    }
}

/// A polygon mesh with face-varying UVs and normals, in millimetres.
///
/// Faces stay polygons (the default head is all quads) until [`Mesh::triangulate`].
/// Positions, UVs and normals are indexed separately per corner, so UV seams are explicit.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Mesh {
    /// Vertex positions in millimetres.
    pub positions: Vec<Vec3>,
    /// Unit normals, referenced by [`Corner::normal`].
    pub normals: Vec<Vec3>,
    /// Texture coordinates, referenced by [`Corner::uv`].
    pub uvs: Vec<Vec2>,
    /// Polygon faces.
    pub faces: Vec<Face>,
    /// Named face ranges, in face order, covering every face.
    pub groups: Vec<Group>,
}

impl Mesh {
    /// Axis-aligned bounds of the positions used by faces, or `None` if there are no faces.
    pub fn bounds(&self) -> Option<Bounds> {
        let mut it = self.faces.iter().flat_map(|f| f.corners.iter()).map(|c| self.positions[c.position as usize]);
        let first = it.next()?;
        let (min, max) = it.fold((first, first), |(lo, hi), p| (lo.min(p), hi.max(p)));
        Some(Bounds { min, max })
    }

    /// The first group with this name, if any.
    pub fn group(&self, name: &str) -> Option<&Group> {
        self.groups.iter().find(|g| g.name == name)
    }

    /// Number of corners over all faces.
    pub fn corner_count(&self) -> usize {
        self.faces.iter().map(|f| f.corners.len()).sum()
    }

    /// Replaces the normals by area-weighted smooth vertex normals, one per position
    /// (`Corner::normal == Corner::position`). Vertices with no area get +Z instead of NaN.
    pub fn recompute_normals(&mut self) {
        self.normals = vertex_normals(&self.positions, &self.faces);
        for face in &mut self.faces {
            for c in &mut face.corners {
                c.normal = c.position;
            }
        }
    }

    /// Triangulates every polygon (fan from its first corner; quads split along the shorter
    /// diagonal) into an indexed triangle mesh with one vertex per unique
    /// (position, uv, normal) triple. Faces whose corners are all the same point are dropped.
    pub fn triangulate(&self) -> TriangleMesh {
        self.triangulate_with_sources().0
    }

    /// [`Mesh::triangulate`], and the position index each triangle-mesh vertex came from.
    pub(crate) fn triangulate_with_sources(&self) -> (TriangleMesh, Vec<u32>) {
        let mut out = TriangleMesh::default();
        let mut sources = Vec::new();
        let mut map: HashMap<Corner, u32> = HashMap::new();
        let mut vertex = |c: Corner, out: &mut TriangleMesh| -> u32 {
            *map.entry(c).or_insert_with(|| {
                sources.push(c.position);
                out.positions.push(self.positions[c.position as usize]);
                out.uvs.push(self.uvs[c.uv as usize]);
                out.normals.push(self.normals[c.normal as usize].try_normalize().unwrap_or(Vec3::Z));
                (out.positions.len() - 1) as u32
            })
        };
        for group in &self.groups {
            let start = out.indices.len() / 3;
            for face in &self.faces[group.faces.clone()] {
                let cs = &face.corners;
                if cs.len() < 3 {
                    continue;
                }
                let mut tris: Vec<[Corner; 3]> = Vec::with_capacity(cs.len() - 2);
                if cs.len() == 4 {
                    let p = |i: usize| self.positions[cs[i].position as usize];
                    if p(0).distance_squared(p(2)) <= p(1).distance_squared(p(3)) {
                        tris.push([cs[0], cs[1], cs[2]]);
                        tris.push([cs[0], cs[2], cs[3]]);
                    } else {
                        tris.push([cs[0], cs[1], cs[3]]);
                        tris.push([cs[1], cs[2], cs[3]]);
                    }
                } else {
                    for i in 1..cs.len() - 1 {
                        tris.push([cs[0], cs[i], cs[i + 1]]);
                    }
                }
                for t in tris {
                    if t[0].position == t[1].position && t[1].position == t[2].position {
                        continue;
                    }
                    for c in t {
                        let v = vertex(c, &mut out);
                        out.indices.push(v);
                    }
                }
            }
            out.groups.push(TriangleGroup {
                name: group.name.clone(),
                material: group.material.clone(),
                triangles: start..out.indices.len() / 3,
            });
        }
        (out, sources)
    }
}

/// A named range of triangles of a [`TriangleMesh`].
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct TriangleGroup {
    /// Group name.
    pub name: String,
    /// Material name, if any.
    pub material: Option<String>,
    /// Range of triangle indices (triangle `t` uses `indices[3t..3t+3]`).
    pub triangles: Range<usize>,
}

/// What a group of a face mesh is: the skin (the medium that scatters and takes cosmetics) or
/// one of the parts that are not skin. The default head (`python/gen_head.py`) names its parts
/// by material: `eye`, `oral`, `teeth`, `tongue`, `lash`, `brow`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Part {
    /// Skin: scatters, carries the skin's maps and the cosmetics.
    Skin,
    /// An eyeball.
    Eye,
    /// The inside of the mouth (the oral cavity behind the lips).
    Mouth,
    /// Teeth.
    Teeth,
    /// The tongue.
    Tongue,
    /// Eyelashes (ribbons).
    Lash,
    /// Eyebrow hairs (ribbons lying on the brow's skin).
    Brow,
}

impl Part {
    /// Whether the part is hair (lashes, brows): strands the renderer draws as fibres.
    pub fn is_hair(self) -> bool {
        matches!(self, Part::Lash | Part::Brow)
    }

    /// Every part, skin first.
    pub const ALL: [Part; 7] = [Part::Skin, Part::Eye, Part::Mouth, Part::Teeth, Part::Tongue, Part::Lash, Part::Brow];

    /// Its name in words (plural where the head has several).
    pub const fn name(self) -> &'static str {
        match self {
            Part::Skin => "skin",
            Part::Eye => "eyes",
            Part::Mouth => "mouth",
            Part::Teeth => "teeth",
            Part::Tongue => "tongue",
            Part::Lash => "lashes",
            Part::Brow => "brows",
        }
    }

    /// The part a group with this name and material is: the material names it when it is
    /// `eye`, `oral`, `teeth`, `tongue`, `lash` or `brow` (any case); otherwise a group whose name contains
    /// "eye" is an eye (meshes from other tools name their eyes so), and anything else skin.
    pub fn of(name: &str, material: Option<&str>) -> Part {
        match material.map(str::to_ascii_lowercase).as_deref() {
            Some("eye") => Part::Eye,
            Some("oral") => Part::Mouth,
            Some("teeth") => Part::Teeth,
            Some("tongue") => Part::Tongue,
            Some("lash") => Part::Lash,
            Some("brow") => Part::Brow,
            _ if name.to_ascii_lowercase().contains("eye") => Part::Eye,
            _ => Part::Skin,
        }
    }
}

impl TriangleGroup {
    /// What the group is ([`Part::of`] its name and material).
    pub fn part(&self) -> Part {
        Part::of(&self.name, self.material.as_deref())
    }

    /// Whether the group is an eye: the renderer gives its vertices an eye's albedo.
    pub fn is_eye(&self) -> bool {
        self.part() == Part::Eye
    }

    /// Whether the group bounds the head's tissue: the skin and the mouth bag, which together
    /// close the head's surface (the medium a path tracer fills, what a thickness ray crosses).
    pub fn is_tissue(&self) -> bool {
        matches!(self.part(), Part::Skin | Part::Mouth)
    }

    /// Whether the group is skin. Every other part gets its own albedo and no scattering, takes
    /// no cosmetics, and exports keep it out of the skin's medium (the oral cavity included: it
    /// closes the skin's surface at the lips, but its tissue is not the skin's).
    pub fn is_skin(&self) -> bool {
        self.part() == Part::Skin
    }
}

/// An indexed triangle mesh ready for a vertex buffer: every attribute is per vertex.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct TriangleMesh {
    /// Positions in millimetres.
    pub positions: Vec<Vec3>,
    /// Unit normals.
    pub normals: Vec<Vec3>,
    /// Texture coordinates.
    pub uvs: Vec<Vec2>,
    /// Tangents (`xyz` unit, orthogonal to the normal; `w` = ±1 bitangent sign), once
    /// [`TriangleMesh::generate_tangents`] has run.
    pub tangents: Option<Vec<Vec4>>,
    /// Triangle list, three vertex indices per triangle, counter-clockwise.
    pub indices: Vec<u32>,
    /// Named triangle ranges.
    pub groups: Vec<TriangleGroup>,
    /// The hairs (lashes, brows) as strands over these vertices, when the mesh was made from a
    /// polygon mesh with hair ribbons ([`strands::subdivided_with_strands`]); the renderer draws
    /// them as fibres ([`strands::HairStrands`]).
    pub strands: Option<std::sync::Arc<strands::HairStrands>>,
}

impl TriangleMesh {
    /// The triangles of each part the mesh has, in [`Part::ALL`]'s order (a mesh without groups
    /// is all skin); parts without triangles are left out.
    pub fn part_triangles(&self) -> Vec<(Part, usize)> {
        let total = self.indices.len() / 3;
        if self.groups.is_empty() {
            return vec![(Part::Skin, total)];
        }
        Part::ALL
            .into_iter()
            .map(|part| {
                let n = self
                    .groups
                    .iter()
                    .filter(|g| g.part() == part)
                    .map(|g| g.triangles.end.min(total).saturating_sub(g.triangles.start))
                    .sum();
                (part, n)
            })
            .filter(|(_, n)| *n > 0)
            .collect()
    }

    /// The tissue and the eyes alone: no lashes, brows, teeth or tongue ([`TriangleMesh::only`]).
    /// The default head's Mitsuba references of issue 31 (`data/reference/translucency`) were
    /// rendered before it had those parts; `rouge bench translucency` and `rouge export mitsuba
    /// --without-parts` draw it this way to compare with them.
    pub fn without_parts(&self) -> TriangleMesh {
        self.only(|g| g.is_tissue() || g.is_eye())
    }

    /// The mesh with only the triangles of the groups `keep` accepts, and those groups (their
    /// ranges renumbered); all vertices are kept, so values stay per vertex. A group's range
    /// past the indices counts as empty. A mesh without groups is returned whole; the
    /// strands of hair parts left out are dropped.
    pub fn only(&self, keep: impl Fn(&TriangleGroup) -> bool) -> TriangleMesh {
        let mut out = self.clone();
        if self.groups.iter().any(|g| !keep(g)) {
            out.indices = Vec::new();
            out.groups = Vec::new();
            for g in self.groups.iter().filter(|g| keep(g)) {
                let start = out.indices.len() / 3;
                out.indices.extend_from_slice(
                    self.indices.get(3 * g.triangles.start..3 * g.triangles.end).unwrap_or_default(),
                );
                out.groups.push(TriangleGroup { triangles: start..out.indices.len() / 3, ..g.clone() });
            }
            // The strands of the hair parts left out go with them.
            if let Some(hairs) = &self.strands {
                let kept = |p: Part| out.groups.iter().any(|g| g.part() == p);
                let strands: Vec<_> = hairs.strands.iter().filter(|h| kept(h.part)).cloned().collect();
                out.strands = (!strands.is_empty()).then(|| std::sync::Arc::new(strands::HairStrands { strands }));
            }
        }
        out
    }

    /// A flat square of side `side_mm` in the z = 0 plane, centred on the origin and facing +Z,
    /// with UVs 0..1 (u along +X, v along +Y): a calibration target for renders of a swatch, a
    /// specular lobe or a brush stroke on a known surface.
    pub fn flat_square(side_mm: f32) -> TriangleMesh {
        let h = 0.5 * side_mm;
        let corners = [(-1.0, -1.0), (1.0, -1.0), (1.0, 1.0), (-1.0, 1.0)];
        TriangleMesh {
            positions: corners.iter().map(|&(x, y)| Vec3::new(x * h, y * h, 0.0)).collect(),
            normals: vec![Vec3::Z; 4],
            uvs: corners.iter().map(|&(x, y)| Vec2::new(0.5 * x + 0.5, 0.5 * y + 0.5)).collect(),
            tangents: None,
            indices: vec![0, 1, 2, 0, 2, 3],
            groups: vec![],
            strands: None,
        }
    }

    /// Number of vertices.
    pub fn vertex_count(&self) -> usize {
        self.positions.len()
    }

    /// Number of triangles.
    pub fn triangle_count(&self) -> usize {
        self.indices.len() / 3
    }
}

/// Area-weighted smooth normals of `faces` over `positions`, one per position (+Z where a
/// vertex has no area): the sum of the vector areas of the faces around each vertex, normalised.
pub(crate) fn vertex_normals(positions: &[Vec3], faces: &[Face]) -> Vec<Vec3> {
    let mut acc = vec![Vec3::ZERO; positions.len()];
    for face in faces {
        // Newell's method: the vector area (twice the area times the unit normal).
        let n = polygon_vector_area(positions, &face.corners);
        if !n.is_finite() {
            continue;
        }
        for c in &face.corners {
            acc[c.position as usize] += n;
        }
    }
    acc.into_iter().map(|n| n.try_normalize().unwrap_or(Vec3::Z)).collect()
}

/// Newell's vector area of a polygon: its direction is the normal, its length twice the area.
pub(crate) fn polygon_vector_area(positions: &[Vec3], corners: &[Corner]) -> Vec3 {
    newell_area(positions, corners.len(), |i| corners[i].position)
}

/// Newell's vector area of the polygon of `n` corners whose `i`-th is at `positions[corner(i)]`.
pub(crate) fn newell_area(positions: &[Vec3], n: usize, corner: impl Fn(usize) -> u32) -> Vec3 {
    let mut acc = Vec3::ZERO;
    for i in 0..n {
        let a = positions[corner(i) as usize];
        let b = positions[corner((i + 1) % n) as usize];
        acc += a.cross(b);
    }
    acc
}

/// Rejects a scale that is not finite and positive.
pub(crate) fn check_scale(scale_to_mm: f32) -> Result<(), MeshError> {
    if scale_to_mm.is_finite() && scale_to_mm > 0.0 { Ok(()) } else { Err(MeshError::InvalidScale(scale_to_mm)) }
}
