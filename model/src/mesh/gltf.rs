//! glTF 2.0 reader (.gltf with data-URI or external buffers, .glb with embedded buffer).
//! UVs are converted to the OBJ convention (v up): v = 1 − v_glTF.

use std::collections::HashMap;
use std::path::{Path, PathBuf};

use glam::{Mat3, Mat4, Vec2, Vec3};

use super::{Corner, Face, Group, Mesh, MeshError, check_scale};

fn gltf_err(path: &Path, message: impl Into<String>) -> MeshError {
    MeshError::Gltf { path: PathBuf::from(path), message: message.into() }
}

/// Deepest node hierarchy accepted (glTF forbids cycles; a cycle would otherwise never end).
pub const MAX_NODE_DEPTH: usize = 64;
/// Most node placements a scene may make (each reference of a node, and of its children, counts).
pub const MAX_NODE_INSTANCES: usize = 10_000;
/// Largest external buffer file read (bytes), checked before it is read (5,000,000 triangles
/// with positions, normals, UVs and indices take about 200 MB).
pub const MAX_BUFFER_BYTES: u64 = 1 << 30;
/// Most triangles a glTF mesh may place, before subdivision.
pub const MAX_TRIANGLES: usize = 5_000_000;

/// Every accessor a primitive names exists (gltf-json's validation assumes so and panics).
fn check_accessor_references(root: &gltf::json::Root) -> Result<(), String> {
    let count = root.accessors.len();
    for (m, mesh) in root.meshes.iter().enumerate() {
        for (p, prim) in mesh.primitives.iter().enumerate() {
            let named = prim.attributes.values().map(|i| i.value()).chain(prim.indices.as_ref().map(|i| i.value()));
            for index in named {
                if index >= count {
                    return Err(format!("mesh {m} primitive {p} names accessor {index}, but there are {count}"));
                }
            }
        }
    }
    Ok(())
}

/// The accessors the reader takes have the types it can read (the gltf crate's reader hits
/// `unreachable!` on float indices).
fn check_accessor_types(prim: &gltf::Primitive) -> Result<(), String> {
    use gltf::Semantic;
    use gltf::accessor::{DataType as T, Dimensions as D};
    let ok = |semantic: &str, a: Option<gltf::Accessor>, dims: D, types: &[T]| -> Result<(), String> {
        match a {
            Some(a) if a.dimensions() != dims || !types.contains(&a.data_type()) => Err(format!(
                "{semantic} accessor {} is {:?} {:?}, expected {dims:?} of {types:?}",
                a.index(),
                a.dimensions(),
                a.data_type()
            )),
            _ => Ok(()),
        }
    };
    ok("indices", prim.indices(), D::Scalar, &[T::U8, T::U16, T::U32])?;
    ok("POSITION", prim.get(&Semantic::Positions), D::Vec3, &[T::F32])?;
    ok("NORMAL", prim.get(&Semantic::Normals), D::Vec3, &[T::F32])?;
    ok("TEXCOORD_0", prim.get(&Semantic::TexCoords(0)), D::Vec2, &[T::F32, T::U8, T::U16])
}

/// Decodes standard or URL-safe base64 (padding optional, whitespace ignored).
fn decode_base64(s: &str) -> Option<Vec<u8>> {
    let mut out = Vec::with_capacity(s.len() * 3 / 4);
    let mut acc = 0u32;
    let mut bits = 0;
    for ch in s.bytes() {
        let v = match ch {
            b'A'..=b'Z' => ch - b'A',
            b'a'..=b'z' => ch - b'a' + 26,
            b'0'..=b'9' => ch - b'0' + 52,
            b'+' | b'-' => 62,
            b'/' | b'_' => 63,
            b'=' => break,
            b' ' | b'\n' | b'\r' | b'\t' => continue,
            _ => return None,
        };
        acc = (acc << 6) | u32::from(v);
        bits += 6;
        if bits >= 8 {
            bits -= 8;
            out.push((acc >> bits) as u8);
            acc &= (1 << bits) - 1;
        }
    }
    Some(out)
}

fn load_buffers(doc: &gltf::Document, blob: Option<Vec<u8>>, path: &Path) -> Result<Vec<Vec<u8>>, MeshError> {
    let mut blob = blob;
    let mut out = Vec::new();
    for buffer in doc.buffers() {
        let data = match buffer.source() {
            gltf::buffer::Source::Bin => blob.take().ok_or_else(|| gltf_err(path, "missing GLB binary chunk"))?,
            gltf::buffer::Source::Uri(uri) => {
                if let Some(rest) = uri.strip_prefix("data:") {
                    let (_, payload) =
                        rest.split_once(";base64,").ok_or_else(|| gltf_err(path, "unsupported data URI"))?;
                    decode_base64(payload).ok_or_else(|| gltf_err(path, "invalid base64 in data URI"))?
                } else {
                    let file = path.parent().unwrap_or(Path::new(".")).join(uri);
                    rouge_measure::file_set::read_bounded(&file, MAX_BUFFER_BYTES)
                        .map_err(|source| MeshError::Io { path: file, source })?
                }
            }
        };
        if data.len() < buffer.length() {
            return Err(gltf_err(path, format!("buffer {} shorter than declared", buffer.index())));
        }
        out.push(data);
    }
    Ok(out)
}

/// Loads every triangle primitive of the default scene (or the first scene) of a glTF 2.0
/// file (.gltf or .glb) as one [`Mesh`], applying node transforms, then `scale_to_mm`.
///
/// Reads POSITION, NORMAL and TEXCOORD_0; positions that are bit-identical after transforming
/// are welded so the mesh has connectivity, while UVs and normals stay per corner. Each
/// primitive becomes a [`Group`] named after its mesh (or `mesh<N>`) with its material name.
/// Missing normals are computed (area-weighted). Non-triangle primitives are skipped.
///
/// # Errors
/// [`MeshError::Io`], [`MeshError::Gltf`] for unreadable or invalid files,
/// [`MeshError::MissingUvs`] if a primitive has no TEXCOORD_0, [`MeshError::Empty`] if no
/// triangles were found, [`MeshError::InvalidScale`].
pub fn load_gltf(path: impl AsRef<Path>, scale_to_mm: f32) -> Result<Mesh, MeshError> {
    let path = path.as_ref();
    check_scale(scale_to_mm)?;
    let bytes = std::fs::read(path).map_err(|source| MeshError::Io { path: path.to_owned(), source })?;
    // gltf-json's own validation indexes a primitive's accessors without checking them (it
    // panicked on a POSITION naming a missing accessor): the references are checked here first.
    let gltf = gltf::Gltf::from_slice_without_validation(&bytes).map_err(|e| gltf_err(path, e.to_string()))?;
    let gltf::Gltf { document, blob } = gltf;
    check_accessor_references(document.as_json()).map_err(|m| gltf_err(path, m))?;
    let document = gltf::Document::from_json(document.into_json()).map_err(|e| gltf_err(path, e.to_string()))?;
    let buffers = load_buffers(&document, blob, path)?;
    let scene =
        document.default_scene().or_else(|| document.scenes().next()).ok_or_else(|| gltf_err(path, "no scene"))?;

    let mut mesh = Mesh::default();
    let mut weld: HashMap<[u32; 3], u32> = HashMap::new();
    let mut missing_normals = false;
    let mut stack: Vec<(gltf::Node, Mat4, usize)> = scene.nodes().map(|n| (n, Mat4::IDENTITY, 0)).collect();
    let mut instances = 0usize;
    while let Some((node, parent, depth)) = stack.pop() {
        // A node that is its own ancestor looped for ever; one node referenced 100,000 times
        // rendered for half a minute. Both are refused (docs/FORMATS.md).
        if depth > MAX_NODE_DEPTH {
            return Err(gltf_err(path, format!("the node hierarchy is deeper than {MAX_NODE_DEPTH} (a cycle?)")));
        }
        instances += 1;
        if instances > MAX_NODE_INSTANCES {
            return Err(gltf_err(path, format!("the scene places more than {MAX_NODE_INSTANCES} nodes")));
        }
        let world = parent * Mat4::from_cols_array_2d(&node.transform().matrix());
        for child in node.children() {
            stack.push((child, world, depth + 1));
        }
        let Some(gmesh) = node.mesh() else { continue };
        let to_mm = Mat4::from_scale(Vec3::splat(scale_to_mm)) * world;
        let normal_matrix = Mat3::from_mat4(world).inverse().transpose();
        let flip = Mat3::from_mat4(world).determinant() < 0.0;
        for prim in gmesh.primitives() {
            if prim.mode() != gltf::mesh::Mode::Triangles {
                continue;
            }
            check_accessor_types(&prim).map_err(|m| gltf_err(path, m))?;
            let reader = prim.reader(|b| buffers.get(b.index()).map(Vec::as_slice));
            let positions: Vec<Vec3> = reader
                .read_positions()
                .ok_or_else(|| match prim.get(&gltf::Semantic::Positions) {
                    Some(a) => gltf_err(
                        path,
                        format!("POSITION accessor {} cannot be read (it runs past its buffer view)", a.index()),
                    ),
                    None => gltf_err(path, "primitive without POSITION"),
                })?
                .map(|p| to_mm.transform_point3(Vec3::from_array(p)))
                .collect();
            let uvs: Vec<Vec2> = reader
                .read_tex_coords(0)
                .ok_or_else(|| MeshError::MissingUvs { path: path.to_owned() })?
                .into_f32()
                // glTF puts the UV origin at the top left (v down); Rouge uses the OBJ
                // convention (v up) everywhere, so maps and masks line up on both.
                .map(|[u, v]| Vec2::new(u, 1.0 - v))
                .collect();
            let normals: Option<Vec<Vec3>> = reader
                .read_normals()
                .map(|it| it.map(|n| (normal_matrix * Vec3::from_array(n)).normalize_or(Vec3::Z)).collect());
            let indices: Vec<u32> = match reader.read_indices() {
                Some(ix) => ix.into_u32().collect(),
                None => (0..positions.len() as u32).collect(),
            };
            if uvs.len() < positions.len() {
                return Err(MeshError::MissingUvs { path: path.to_owned() });
            }
            missing_normals |= normals.as_ref().is_none_or(|n| n.len() < positions.len());

            let pos_ids: Vec<u32> = positions
                .iter()
                .map(|p| {
                    *weld.entry(p.to_array().map(f32::to_bits)).or_insert_with(|| {
                        mesh.positions.push(*p);
                        (mesh.positions.len() - 1) as u32
                    })
                })
                .collect();
            let uv_base = mesh.uvs.len() as u32;
            mesh.uvs.extend_from_slice(&uvs[..positions.len()]);
            let n_base = mesh.normals.len() as u32;
            match &normals {
                Some(n) if n.len() >= positions.len() => mesh.normals.extend_from_slice(&n[..positions.len()]),
                _ => mesh.normals.extend(std::iter::repeat_n(Vec3::Z, positions.len())),
            }
            let start = mesh.faces.len();
            if start + indices.len() / 3 > MAX_TRIANGLES {
                return Err(gltf_err(path, format!("more than {MAX_TRIANGLES} triangles")));
            }
            for tri in indices.chunks_exact(3) {
                if tri.iter().any(|&i| i as usize >= positions.len()) {
                    return Err(gltf_err(path, "index out of range"));
                }
                let mut corners: Vec<Corner> = tri
                    .iter()
                    .map(|&i| Corner { position: pos_ids[i as usize], uv: uv_base + i, normal: n_base + i })
                    .collect();
                if flip {
                    corners.reverse();
                }
                mesh.faces.push(Face { corners });
            }
            let name = gmesh.name().map_or_else(|| format!("mesh{}", gmesh.index()), str::to_owned);
            let material = prim.material().name().map(str::to_owned);
            mesh.groups.push(Group { name, material, faces: start..mesh.faces.len() });
        }
    }
    if mesh.faces.is_empty() {
        return Err(MeshError::Empty);
    }
    if missing_normals {
        mesh.recompute_normals();
    }
    Ok(mesh)
}

#[cfg(test)]
mod tests {
    use super::decode_base64;

    #[test]
    fn base64_roundtrip() {
        assert_eq!(decode_base64("aGVsbG8=").unwrap(), b"hello");
        assert_eq!(decode_base64("aGVsbG8gd29ybGQ").unwrap(), b"hello world");
        assert!(decode_base64("a*b").is_none());
    }
}
