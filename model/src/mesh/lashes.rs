//! Eyelashes as strands, and what a mascara does to them.
//!
//! The default head's lashes (`python/gen_head_parts.py`) are ribbons: per strand a strip of
//! quads from the root on the lid margin to the tip, written twice (front and back faces with
//! their own vertices). [`LashRig::of`] finds the strips in a mesh's `lash` groups and orders
//! each from root to tip; [`LashRig::apply`] reshapes them in place on the base positions
//! (before subdivision, after the face's targets), so a mascara follows every expression.
//!
//! What mascara does to lashes, in the terms cosmetic claims use ("lengthening", "volumising",
//! "curling"): fibres and film lengthen the lash beyond its tip (up to about +30-60 % in
//! consumer tests), the film thickens it (2-4× its diameter with volumising formulas), and the
//! film's shrinkage as it dries lifts the lash into a curl (about 10-30° more at the tip)
//! (\[Thibaut2010\] for the natural lash: 0.06-0.12 mm thick, 7-12 mm long, 80-160 per upper lid).

use glam::{Quat, Vec3};
use serde::{Deserialize, Serialize};

use super::{Mesh, Part};
use crate::error::{ModelError, Result};

/// What a mascara does to the lashes it coats. The default changes nothing.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Mascara {
    /// Length as a multiple of the natural lash's (1 = unchanged), [`Mascara::LENGTH`].
    #[serde(default = "one")]
    pub length: f32,
    /// Thickness as a multiple of the natural lash's (1 = unchanged), [`Mascara::VOLUME`].
    #[serde(default = "one")]
    pub volume: f32,
    /// Extra curl at the tip, degrees (the lash turns away from the eye's opening, up on the
    /// upper lid and down on the lower), [`Mascara::CURL_DEG`].
    #[serde(default)]
    pub curl_deg: f32,
    /// Linear albedo of the coated lashes, each channel in 0..=1 (`None`: the lashes keep their
    /// own colour); [`Mascara::named_color`] gives the usual shades.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub color: Option<[f32; 3]>,
}

fn one() -> f32 {
    1.0
}

impl Default for Mascara {
    fn default() -> Mascara {
        Mascara { length: 1.0, volume: 1.0, curl_deg: 0.0, color: None }
    }
}

impl Mascara {
    /// Allowed lengths (no mascara shortens a lash; 2× is far past any on the market).
    pub const LENGTH: (f32, f32) = (1.0, 2.0);
    /// Allowed thickness multiples.
    pub const VOLUME: (f32, f32) = (1.0, 5.0);
    /// Allowed extra curl, degrees.
    pub const CURL_DEG: (f32, f32) = (0.0, 60.0);

    /// The linear albedo of a named mascara shade: `black` (iron oxide or carbon black in a wax
    /// film: about 1 % diffuse reflectance), `brown` and `blue` (*choices* of the usual shades,
    /// not measured products).
    pub fn named_color(name: &str) -> Option<[f32; 3]> {
        match name {
            "black" => Some([0.010, 0.010, 0.011]),
            "brown" => Some([0.045, 0.027, 0.016]),
            "blue" => Some([0.012, 0.020, 0.060]),
            _ => None,
        }
    }

    /// Whether it changes nothing.
    pub fn is_none(&self) -> bool {
        *self == Mascara::default()
    }

    /// Checks every field against its range.
    ///
    /// # Errors
    /// [`ModelError::Invalid`] naming the field, its value and its range.
    pub fn validate(&self) -> Result<()> {
        for (name, v, (lo, hi)) in [
            ("length", self.length, Mascara::LENGTH),
            ("volume", self.volume, Mascara::VOLUME),
            ("curl_deg", self.curl_deg, Mascara::CURL_DEG),
        ] {
            if !(v.is_finite() && (lo..=hi).contains(&v)) {
                return Err(ModelError::Invalid(format!("mascara {name} {v}: must be within {lo}..={hi}")));
            }
        }
        if let Some(c) = self.color
            && !c.iter().all(|v| v.is_finite() && (0.0..=1.0).contains(v))
        {
            return Err(ModelError::Invalid(format!(
                "mascara color {c:?}: each channel must be within 0..=1 (linear albedo)"
            )));
        }
        Ok(())
    }

    /// Parses `length=1.3,volume=2,curl=20,color=black` (any subset; `curl_deg` may be written
    /// `curl`; `color` is a [`Mascara::named_color`] or `R/G/B` linear albedo).
    ///
    /// # Errors
    /// An unknown key, a number that does not parse, or a value out of range, named.
    pub fn parse(spec: &str) -> Result<Mascara> {
        let mut m = Mascara::default();
        for item in spec.split(',').map(str::trim).filter(|s| !s.is_empty()) {
            let (k, v) = item
                .split_once('=')
                .ok_or_else(|| ModelError::Invalid(format!("mascara `{item}`: expected KEY=VALUE")))?;
            if k.trim() == "color" {
                m.color = Some(parse_color("mascara", v.trim())?);
                continue;
            }
            let v: f32 =
                v.trim().parse().map_err(|_| ModelError::Invalid(format!("mascara {k}: `{v}` is not a number")))?;
            match k.trim() {
                "length" => m.length = v,
                "volume" => m.volume = v,
                "curl" | "curl_deg" => m.curl_deg = v,
                other => {
                    return Err(ModelError::Invalid(format!(
                        "mascara: unknown `{other}` (use length, volume, curl, color)"
                    )));
                }
            }
        }
        m.validate()?;
        Ok(m)
    }
}

/// A hair product's colour (`what`: `mascara`, `brow gel`): a named shade
/// ([`Mascara::named_color`]) or `R/G/B` linear albedo.
pub(crate) fn parse_color(what: &str, v: &str) -> Result<[f32; 3]> {
    if let Some(c) = Mascara::named_color(v) {
        return Ok(c);
    }
    let parts: Vec<&str> = v.split('/').collect();
    let bad =
        || ModelError::Invalid(format!("{what} color `{v}`: use black, brown, blue or R/G/B (linear albedo 0-1)"));
    if parts.len() != 3 {
        return Err(bad());
    }
    let mut c = [0.0f32; 3];
    for (o, p) in c.iter_mut().zip(parts) {
        *o = p.trim().parse().map_err(|_| bad())?;
    }
    Ok(c)
}

/// One lash strip: its rungs (the two vertices across the ribbon) from root to tip, and the
/// eye it grows by.
#[derive(Debug, Clone)]
struct Strand {
    rungs: Vec<[u32; 2]>,
    eye: usize,
}

/// The lash strips of a mesh, found once at rest ([`LashRig::of`]).
#[derive(Debug, Clone, Default)]
pub struct LashRig {
    strands: Vec<Strand>,
    /// Vertices of each eye group (their mean is the eye's centre in any pose).
    eyes: Vec<Vec<u32>>,
}

impl LashRig {
    /// Finds the strips of the mesh's lash groups ([`Part::Lash`]): quads chained by their
    /// shared rungs, each ordered from the end nearer an eyeball's centre (the root) to the
    /// other. A mesh without lashes or without eyes gives an empty rig.
    pub fn of(mesh: &Mesh) -> LashRig {
        let eyes = eye_vertices(mesh);
        if eyes.is_empty() {
            return LashRig::default();
        }
        let centres: Vec<Vec3> = eyes.iter().map(|v| centre(&mesh.positions, v)).collect();
        let mut strands = Vec::new();
        for strip in super::strands::strips(mesh, Part::Lash) {
            let mut rungs = strip.rungs;
            let eye = root_first(&mut rungs, &mesh.positions, &centres);
            strands.push(Strand { rungs, eye });
        }
        LashRig { strands, eyes }
    }

    /// Number of lash strips (each side of a ribbon counts once).
    pub fn strand_count(&self) -> usize {
        self.strands.len()
    }

    /// Reshapes the lashes in `positions` (the rig's mesh's base positions, posed): each strip
    /// scaled from its root by `length` along itself, widened by `volume` about its centre
    /// line, and turned by up to `curl_deg` at the tip (in proportion to the distance from the
    /// root) away from its eye's opening (across the gaze axis, +Z for the default head). A [`Mascara::is_none`] leaves them as they are.
    pub fn apply(&self, mascara: &Mascara, positions: &mut [Vec3]) {
        if mascara.is_none() {
            return;
        }
        let centres: Vec<Vec3> = self.eyes.iter().map(|v| centre(positions, v)).collect();
        for s in &self.strands {
            let at = |r: [u32; 2]| [positions[r[0] as usize], positions[r[1] as usize]];
            let rungs: Vec<[Vec3; 2]> = s.rungs.iter().map(|&r| at(r)).collect();
            let mids: Vec<Vec3> = rungs.iter().map(|r| (r[0] + r[1]) * 0.5).collect();
            let (root, tip) = (mids[0], *mids.last().expect("a rung"));
            let along = (tip - root).normalize_or_zero();
            // Away from the eye's opening: the root's direction from the eye's centre across the
            // gaze axis (+Z, the default head's), up on the upper lid, down on the lower.
            let radial = (root - centres[s.eye]).reject_from(Vec3::Z);
            let outward = radial.reject_from(along).normalize_or_zero();
            let axis = along.cross(outward).normalize_or_zero();
            let mut arc = vec![0.0f32];
            for w in mids.windows(2) {
                arc.push(arc.last().expect("arc") + w[0].distance(w[1]));
            }
            let total = arc.last().copied().unwrap_or(0.0).max(1e-6);
            for (i, (&r, m)) in s.rungs.iter().zip(&mids).enumerate() {
                let t = arc[i] / total;
                let turn = Quat::from_axis_angle(axis, mascara.curl_deg.to_radians() * t);
                let centre = root + turn * ((*m - root) * mascara.length);
                for (k, &v) in r.iter().enumerate() {
                    positions[v as usize] = centre + turn * ((rungs[i][k] - *m) * mascara.volume);
                }
            }
        }
    }
}

/// The vertices of each eye group of `mesh` ([`Part::Eye`]), each once; their mean is the eye's
/// centre in any pose ([`centre`]). Groups without faces are left out.
pub(crate) fn eye_vertices(mesh: &Mesh) -> Vec<Vec<u32>> {
    mesh.groups
        .iter()
        .filter(|g| g.part() == Part::Eye)
        .map(|g| {
            let mut v: Vec<u32> =
                mesh.faces[g.faces.clone()].iter().flat_map(|f| f.corners.iter().map(|c| c.position)).collect();
            v.sort_unstable();
            v.dedup();
            v
        })
        .filter(|v| !v.is_empty())
        .collect()
}

/// Orders a lash strip's `rungs` root first: the root is the end nearer the eye whose centre
/// (`centres`, not empty) is nearest the strip's first end. Returns that eye.
pub(crate) fn root_first(rungs: &mut [[u32; 2]], positions: &[Vec3], centres: &[Vec3]) -> usize {
    let mid = |r: [u32; 2]| (positions[r[0] as usize] + positions[r[1] as usize]) * 0.5;
    let (root, tip) = (mid(rungs[0]), mid(rungs[rungs.len() - 1]));
    let eye = (0..centres.len())
        .min_by(|&a, &b| root.distance(centres[a]).total_cmp(&root.distance(centres[b])))
        .unwrap_or(0);
    if tip.distance(centres[eye]) < root.distance(centres[eye]) {
        rungs.reverse();
    }
    eye
}

/// The mean of `vertices`' positions.
pub(crate) fn centre(positions: &[Vec3], vertices: &[u32]) -> Vec3 {
    vertices.iter().map(|&v| positions[v as usize]).sum::<Vec3>() / vertices.len().max(1) as f32
}
