//! Wavefront OBJ reader (positions, texture coordinates, normals, polygon faces, groups).

use std::path::Path;

use glam::{Vec2, Vec3};

use super::{Corner, Face, Group, Mesh, MeshError, check_scale};
use rouge_measure::LocatedError;

/// Loads a Wavefront OBJ file as a polygon [`Mesh`], multiplying positions by `scale_to_mm`.
///
/// Supports `v`, `vt`, `vn`, `f` (corners `v`, `v/vt`, `v//vn`, `v/vt/vn`, negative relative
/// indices, polygons of any size), `o`, `g` and `usemtl` (each change starts a new [`Group`]),
/// and `#` comments; other statements (`s`, `mtllib`, `l`, ...) are ignored. Missing normals
/// are computed (area-weighted); corners without a texture coordinate get UV (0, 0).
///
/// # Errors
/// [`MeshError::Io`] if the file cannot be read, [`MeshError::Parse`] (with line and column)
/// for malformed numbers, out-of-range indices or faces with fewer than three corners,
/// [`MeshError::InvalidScale`] and [`MeshError::Empty`].
pub fn load_obj(path: impl AsRef<Path>, scale_to_mm: f32) -> Result<Mesh, MeshError> {
    let path = path.as_ref();
    check_scale(scale_to_mm)?;
    let text = std::fs::read_to_string(path).map_err(|source| MeshError::Io { path: path.to_owned(), source })?;
    parse_obj(&text, path, scale_to_mm)
}

struct Parser<'a> {
    path: &'a Path,
    line: usize,
}

impl Parser<'_> {
    fn err(&self, column: usize, message: impl Into<String>) -> MeshError {
        MeshError::Parse(LocatedError::at(self.path, self.line, Some(column), message))
    }

    fn float(&self, tok: Option<(usize, &str)>, end_col: usize, what: &str) -> Result<f32, MeshError> {
        let (col, s) = tok.ok_or_else(|| self.err(end_col, format!("missing {what}")))?;
        match s.parse::<f32>() {
            Ok(v) if v.is_finite() => Ok(v),
            _ => Err(self.err(col, format!("invalid number `{s}` for {what}"))),
        }
    }

    /// Resolves a 1-based (or negative, relative) OBJ index against `count` elements.
    fn index(&self, s: &str, col: usize, count: usize, what: &str) -> Result<u32, MeshError> {
        let i: i64 = s.parse().map_err(|_| self.err(col, format!("invalid {what} index `{s}`")))?;
        let resolved = if i > 0 { i - 1 } else { count as i64 + i };
        if i == 0 || resolved < 0 || resolved >= count as i64 {
            return Err(self.err(col, format!("{what} index {i} out of range (have {count})")));
        }
        Ok(resolved as u32)
    }
}

/// Splits a line into whitespace-separated tokens with their 1-based character columns.
fn tokens(line: &str) -> Vec<(usize, &str)> {
    let mut out = Vec::new();
    let mut start: Option<(usize, usize)> = None; // (byte offset, column)
    let mut col = 0;
    for (byte, ch) in line.char_indices() {
        col += 1;
        if ch.is_whitespace() {
            if let Some((b, c)) = start.take() {
                out.push((c, &line[b..byte]));
            }
        } else if start.is_none() {
            start = Some((byte, col));
        }
    }
    if let Some((b, c)) = start {
        out.push((c, &line[b..]));
    }
    out
}

/// Parses OBJ text already in memory (an embedded mesh); `path` names it in error messages.
///
/// # Errors
/// As [`load_obj`], except I/O.
pub fn parse_obj(text: &str, path: &Path, scale: f32) -> Result<Mesh, MeshError> {
    check_scale(scale)?;
    let mut mesh = Mesh::default();
    let mut p = Parser { path, line: 0 };
    let mut missing_normal = false;
    let mut missing_uv = false;
    let mut group_name = String::from("default");
    let mut material: Option<String> = None;
    let mut group_start = 0usize;

    let flush = |mesh: &mut Mesh, name: &str, material: &Option<String>, start: &mut usize| {
        if mesh.faces.len() > *start {
            mesh.groups.push(Group {
                name: name.to_owned(),
                material: material.clone(),
                faces: *start..mesh.faces.len(),
            });
            *start = mesh.faces.len();
        }
    };

    for (n, raw) in text.lines().enumerate() {
        p.line = n + 1;
        let line = raw.split('#').next().unwrap_or("");
        let toks = tokens(line);
        let Some(&(_, keyword)) = toks.first() else { continue };
        let end_col = line.chars().count() + 1;
        let mut args = toks[1..].iter().copied();
        match keyword {
            "v" => {
                let x = p.float(args.next(), end_col, "x")?;
                let y = p.float(args.next(), end_col, "y")?;
                let z = p.float(args.next(), end_col, "z")?;
                mesh.positions.push(Vec3::new(x, y, z) * scale);
            }
            "vt" => {
                let u = p.float(args.next(), end_col, "u")?;
                let v = match args.next() {
                    Some(t) => p.float(Some(t), end_col, "v")?,
                    None => 0.0,
                };
                mesh.uvs.push(Vec2::new(u, v));
            }
            "vn" => {
                let x = p.float(args.next(), end_col, "normal x")?;
                let y = p.float(args.next(), end_col, "normal y")?;
                let z = p.float(args.next(), end_col, "normal z")?;
                mesh.normals.push(Vec3::new(x, y, z));
            }
            "f" => {
                let mut corners = Vec::with_capacity(toks.len() - 1);
                for (col, tok) in args {
                    let mut parts = tok.split('/');
                    let v = parts.next().unwrap_or("");
                    let position = p.index(v, col, mesh.positions.len(), "vertex")?;
                    let vt = parts.next().filter(|s| !s.is_empty());
                    let vn = parts.next().filter(|s| !s.is_empty());
                    if parts.next().is_some() {
                        return Err(p.err(col, format!("malformed face corner `{tok}`")));
                    }
                    let uv_col = col + v.len() + 1;
                    let uv = match vt {
                        Some(s) => p.index(s, uv_col, mesh.uvs.len(), "texture coordinate")?,
                        None => {
                            missing_uv = true;
                            u32::MAX
                        }
                    };
                    let normal = match vn {
                        Some(s) => {
                            let vn_col = uv_col + vt.map_or(0, str::len) + 1;
                            p.index(s, vn_col, mesh.normals.len(), "normal")?
                        }
                        None => {
                            missing_normal = true;
                            0
                        }
                    };
                    corners.push(Corner { position, uv, normal });
                }
                if corners.len() < 3 {
                    return Err(p.err(1, format!("face has {} corners, needs at least 3", corners.len())));
                }
                mesh.faces.push(Face { corners });
            }
            "g" | "o" => {
                let name = toks[1..].iter().map(|t| t.1).collect::<Vec<_>>().join(" ");
                flush(&mut mesh, &group_name, &material, &mut group_start);
                group_name = if name.is_empty() { "default".to_owned() } else { name };
            }
            "usemtl" => {
                flush(&mut mesh, &group_name, &material, &mut group_start);
                material = toks.get(1).map(|t| t.1.to_owned());
            }
            _ => {}
        }
    }
    flush(&mut mesh, &group_name, &material, &mut group_start);
    if mesh.faces.is_empty() {
        return Err(MeshError::Empty);
    }
    // Corners without a texture coordinate share one (0, 0) UV appended after the file's
    // (appending earlier would shift negative `vt` indices).
    if missing_uv {
        let zero = mesh.uvs.len() as u32;
        mesh.uvs.push(Vec2::ZERO);
        for c in mesh.faces.iter_mut().flat_map(|f| f.corners.iter_mut()).filter(|c| c.uv == u32::MAX) {
            c.uv = zero;
        }
    }
    // Normals: use the file's unless some corner lacks one or some is unusable.
    if missing_normal || mesh.normals.iter().any(|n| n.try_normalize().is_none()) {
        mesh.recompute_normals();
    } else {
        for n in &mut mesh.normals {
            *n = n.normalize_or(Vec3::Z);
        }
    }
    Ok(mesh)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn tokens_have_columns() {
        assert_eq!(tokens("f  1/2 3\t4"), vec![(1, "f"), (4, "1/2"), (8, "3"), (10, "4")]);
    }

    #[test]
    fn forms_and_negative_indices() {
        let src = "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvt 1 1\nvn 0 0 1\n\
                   f 1 2 3\nf 1/1 2/2 3/3\nf 1//1 3//1 4//1\nf -4/-3/-1 -3/-2/-1 -2/-1/-1 -1/1/1\n";
        let m = parse_obj(src, Path::new("t.obj"), 10.0).unwrap();
        assert_eq!(m.faces.len(), 4);
        assert_eq!(m.faces[3].corners[0], Corner { position: 0, uv: 0, normal: 0 });
        assert_eq!(m.positions[2], Vec3::new(10.0, 10.0, 0.0));
        // Some corners lacked normals, so all were recomputed per position.
        assert!(m.normals.iter().all(|n| (*n - Vec3::Z).length() < 1e-6));
    }
}
