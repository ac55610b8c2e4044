//! `rouge export mitsuba`: the scene `rouge render` draws, as a Mitsuba 3 scene (\[Mitsuba3\]),
//! the ground truth the subsurface models are measured against (docs/TRANSLUCENCY.md).
//!
//! What is written (`DIR/scene.xml`, loadable by `mi.load_file`, with its files beside it):
//! - **Camera**: `perspective` with the same position, target, up (+Y) and vertical field of
//!   view, `fov_axis = y`; an `hdrfilm` of the same size with a box filter (Rouge samples pixel
//!   centres; the box filter averages the pixel, which differs only on silhouettes).
//! - **Lights**: a directional light becomes `directional` with the same irradiance (W/m² for
//!   W/(m² sr); a white Lambertian facing irradiance π has radiance 1 in both); a point light
//!   becomes `point` with intensity E·d², d its distance to the mesh's bounds centre, where Rouge
//!   defines its irradiance. The path tracer shadows every light; Rouge shadows only lights with
//!   `shadows` (the reference rigs shadow theirs).
//! - **Environment**: `envmap` of the same radiance: Rouge's EXR rolled by half a turn (Mitsuba's
//!   u is Rouge's u − ½: `u_m = atan2(x, −z)/2π`, `u_r = (atan2(x, −z) + π)/2π`; rows agree, top =
//!   +Y), or the studio dome tabulated at 256×128. Rouge lights with its 9-term SH irradiance,
//!   unoccluded; the path tracer integrates the map with occlusion.
//! - **Skin** (`skin.ply`, binary, mm, smooth normals) with the boundary and interior of
//!   [`Interior`], its open boundary loops (the default head's neck) closed with flat caps so the
//!   medium has a closed boundary (Rouge draws the open mesh; the caps face away from the camera);
//!   the mouth bag is part of it (it closes the head's surface); **eyes and the other parts**
//!   (`eyes.ply`: eyes, teeth, tongue, lashes) opaque diffuse with Rouge's albedo of each part as
//!   vertex colours.
//! - **Integrator**: `volpathmis` (spectral MIS, so chromatic media do not blow up one channel's
//!   weights) with `max_depth = -1` and Russian roulette only past depth 100000: unbiased;
//!   emitters hidden from the camera, so the film's alpha is the object's coverage.

use crate::env::{EnvMap, studio_radiance};
use crate::error::{RenderError, Result};
use crate::gpu_mesh::vertex_albedo;
use crate::scene::{Camera, LightKind, Scene};
use rouge_model::mesh::{Bounds, TriangleMesh, close_boundary_loops};
use std::fmt::Write as _;
use std::path::Path;

/// What is below the skin's surface in the export.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Interior {
    /// The skin's medium (σa, σs from σs′ and g, η) behind a dielectric boundary, rough
    /// (Beckmann, [`ExportInput::boundary_alpha`]) by default: a smooth boundary would stop the
    /// path tracer from connecting delta lights to the interior.
    Medium,
    /// The same boundary over a black absorber (σa = 10⁴ mm⁻¹, no scattering): only what the
    /// surface reflects. Medium − Absorber is the light that went below the surface, what a
    /// subsurface model has to reproduce.
    Absorber,
    /// An opaque Lambertian of the skin's albedo, no boundary: the camera, light and unit check.
    Lambert,
}

impl Interior {
    /// The name on the command line.
    pub fn name(self) -> &'static str {
        match self {
            Interior::Medium => "medium",
            Interior::Absorber => "absorber",
            Interior::Lambert => "lambert",
        }
    }
}

/// A scene ready to write: the XML and the files it names.
#[derive(Clone, Debug)]
pub struct MitsubaScene {
    /// `scene.xml`.
    pub xml: String,
    /// `(file name, bytes)` written beside it.
    pub files: Vec<(String, Vec<u8>)>,
}

/// What an export needs from a render job.
#[derive(Debug)]
pub struct ExportInput<'a> {
    /// The triangle mesh as rendered (mm, after subdivision).
    pub mesh: &'a TriangleMesh,
    /// Lights, environment and skin.
    pub scene: &'a Scene,
    /// An environment loaded from a file (replaces the scene's SH when given).
    pub env: Option<&'a EnvMap>,
    /// Camera (as [`Camera::framing`] makes it from the same bounds).
    pub camera: &'a Camera,
    /// Image size.
    pub width: u32,
    /// Image size.
    pub height: u32,
    /// Boundary and interior.
    pub interior: Interior,
    /// Samples per pixel written as the default of `$spp`.
    pub spp: u32,
    /// Angular radius of the lights, degrees: 0 writes delta lights (`directional`, `point`);
    /// above 0 a directional light becomes a distant disk and a point light a sphere of that
    /// angular radius with the same irradiance, so that the path tracer can weigh light and BSDF
    /// samples (MIS) at the medium's boundary instead of connecting to a delta light alone.
    pub light_radius_deg: f64,
    /// Beckmann roughness α of the boundary of a medium or absorber; 0 for a smooth dielectric
    /// (which delta lights cannot reach through: use it with an environment only).
    pub boundary_alpha: f64,
}

fn v3(v: glam::Vec3) -> String {
    format!("{}, {}, {}", v.x, v.y, v.z)
}

fn rgb(c: [f64; 3]) -> String {
    format!("{}, {}, {}", c[0], c[1], c[2])
}

/// Binary little-endian PLY of `triangles` of `mesh` (positions, normals, optional colours).
fn ply(mesh: &TriangleMesh, triangles: &[usize], colours: Option<&[[f32; 4]]>) -> Vec<u8> {
    let mut remap = vec![u32::MAX; mesh.positions.len()];
    let mut verts = Vec::new();
    let mut faces = Vec::with_capacity(triangles.len());
    for &t in triangles {
        let f: [u32; 3] = std::array::from_fn(|k| {
            let v = mesh.indices[3 * t + k] as usize;
            if remap[v] == u32::MAX {
                remap[v] = verts.len() as u32;
                verts.push(v);
            }
            remap[v]
        });
        faces.push(f);
    }
    let mut header = String::from("ply\nformat binary_little_endian 1.0\n");
    let _ = writeln!(header, "element vertex {}", verts.len());
    header.push_str("property float x\nproperty float y\nproperty float z\n");
    header.push_str("property float nx\nproperty float ny\nproperty float nz\n");
    if colours.is_some() {
        header.push_str("property float r\nproperty float g\nproperty float b\n");
    }
    let _ = writeln!(header, "element face {}", faces.len());
    header.push_str("property list uchar uint vertex_indices\nend_header\n");
    let mut out = header.into_bytes();
    for &v in &verts {
        let (p, n) = (mesh.positions[v], mesh.normals[v]);
        for x in [p.x, p.y, p.z, n.x, n.y, n.z] {
            out.extend_from_slice(&x.to_le_bytes());
        }
        if let Some(c) = colours {
            for x in &c[v][..3] {
                out.extend_from_slice(&x.to_le_bytes());
            }
        }
    }
    for f in faces {
        out.push(3);
        for i in f {
            out.extend_from_slice(&i.to_le_bytes());
        }
    }
    out
}

/// The environment as Mitsuba's equirectangular bitmap (columns rolled by half a turn).
fn mitsuba_env(env: &EnvMap) -> Vec<[f32; 4]> {
    let (w, h) = (env.width, env.height);
    let mut out = vec![[0.0; 4]; w * h];
    for j in 0..h {
        for i in 0..w {
            let c = env.texels[j * w + (i + w / 2) % w];
            out[j * w + i] = [c[0], c[1], c[2], 1.0];
        }
    }
    out
}

/// The homogeneous medium `interior` of single-scattering albedo `albedo` and extinction
/// `sigma_t_per_mm`, Henyey-Greenstein `g` (isotropic at 0).
fn medium_xml(albedo: [f64; 3], sigma_t_per_mm: [f64; 3], g: f64) -> String {
    let phase = if g == 0.0 {
        "<phase type=\"isotropic\"/>".to_string()
    } else {
        format!("<phase type=\"hg\"><float name=\"g\" value=\"{g}\"/></phase>")
    };
    // Mitsuba reads an RGB sigma_t as a reflectance (each channel ≤ 1): write it relative to its
    // largest channel and put that in `scale`.
    let scale = sigma_t_per_mm.iter().copied().fold(0.0, f64::max);
    format!(
        "    <medium type=\"homogeneous\" id=\"interior\">\n        <rgb name=\"albedo\" value=\"{}\"/>\n        \
         <rgb name=\"sigma_t\" value=\"{}\"/>\n        <float name=\"scale\" value=\"{scale}\"/>\n        {phase}\n    </medium>\n",
        rgb(albedo),
        rgb(sigma_t_per_mm.map(|v| v / scale))
    )
}

/// Builds the Mitsuba scene of `input`.
///
/// # Errors
/// [`RenderError::Invalid`] when the interior is a medium and the skin has none, or the mesh is
/// empty.
pub fn export(input: &ExportInput) -> Result<MitsubaScene> {
    let ExportInput { mesh, scene, camera, width, height, interior, spp, .. } = *input;
    let bounds = Bounds::of(&mesh.positions).ok_or_else(|| RenderError::Invalid("empty mesh".into()))?;
    let radius = 0.5 * bounds.size().length();
    let (near, far) = camera.clip_planes_around(&bounds);
    let mut x = String::new();
    let _ = writeln!(x, "<!-- Written by `rouge export mitsuba` (Rouge {}). Units: mm. -->", env!("CARGO_PKG_VERSION"));
    x.push_str("<scene version=\"3.0.0\">\n");
    let _ = writeln!(x, "    <default name=\"spp\" value=\"{spp}\"/>\n    <default name=\"seed\" value=\"0\"/>");
    // Russian roulette only past a depth no diffusion path reaches by default: Mitsuba's roulette
    // survives with probability ≤ 0.95 per bounce whatever the albedo, so in a deep, bright medium
    // (thousands of scattering events) it turns the long paths into rare, huge weights.
    x.push_str("    <default name=\"rr_depth\" value=\"100000\"/>\n");
    x.push_str("    <integrator type=\"volpathmis\">\n        <integer name=\"max_depth\" value=\"-1\"/>\n");
    // Emitters are hidden from the camera: the background is black and the film's alpha is the
    // object's coverage (with a visible environment Mitsuba sets alpha 1 everywhere).
    x.push_str("        <integer name=\"rr_depth\" value=\"$rr_depth\"/>\n        <boolean name=\"hide_emitters\" value=\"true\"/>\n");
    x.push_str("    </integrator>\n");
    let _ = writeln!(
        x,
        "    <sensor type=\"perspective\">\n        <string name=\"fov_axis\" value=\"y\"/>\n        \
         <float name=\"fov\" value=\"{}\"/>\n        <float name=\"near_clip\" value=\"{near}\"/>\n        \
         <float name=\"far_clip\" value=\"{far}\"/>\n        <transform name=\"to_world\">\n            \
         <lookat origin=\"{}\" target=\"{}\" up=\"0, 1, 0\"/>\n        </transform>\n        \
         <sampler type=\"independent\">\n            <integer name=\"sample_count\" value=\"$spp\"/>\n            \
         <integer name=\"seed\" value=\"$seed\"/>\n        </sampler>\n        <film type=\"hdrfilm\">\n            \
         <integer name=\"width\" value=\"{width}\"/>\n            <integer name=\"height\" value=\"{height}\"/>\n            \
         <string name=\"pixel_format\" value=\"rgba\"/>\n            <rfilter type=\"box\"/>\n        </film>\n    </sensor>",
        camera.fov_y_deg,
        v3(camera.position()),
        v3(camera.target)
    );
    let tan = input.light_radius_deg.to_radians().tan();
    for l in &scene.lights {
        let e = l.irradiance.map(f64::from);
        match (l.kind, tan > 0.0) {
            (LightKind::Directional { toward }, false) => {
                let _ = writeln!(
                    x,
                    "    <emitter type=\"directional\">\n        <vector name=\"direction\" value=\"{}\"/>\n        \
                     <rgb name=\"irradiance\" value=\"{}\"/>\n    </emitter>",
                    v3(-toward.normalize()),
                    rgb(e)
                );
            }
            (LightKind::Directional { toward }, true) => {
                // A Lambertian disk of half-angle θ seen on its axis gives E = π L sin²θ.
                let distance = 20.0 * radius;
                let (r, sin2) = (distance * tan as f32, (input.light_radius_deg.to_radians().sin()).powi(2));
                let origin = bounds.center() + toward.normalize() * distance;
                let up = if toward.normalize().y.abs() > 0.95 { "0, 0, 1" } else { "0, 1, 0" };
                let _ = writeln!(
                    x,
                    "    <shape type=\"disk\">\n        <transform name=\"to_world\">\n            <scale value=\"{r}\"/>\n            \
                     <lookat origin=\"{}\" target=\"{}\" up=\"{up}\"/>\n        </transform>\n        \
                     <emitter type=\"area\">\n            <rgb name=\"radiance\" value=\"{}\"/>\n        </emitter>\n    </shape>",
                    v3(origin),
                    v3(bounds.center()),
                    rgb(e.map(|v| v / (std::f64::consts::PI * sin2)))
                );
            }
            (LightKind::Point { position }, area) => {
                let d2 = f64::from((position - bounds.center()).length_squared().max(1e-6));
                let intensity = e.map(|v| v * d2);
                if area {
                    // A Lambertian sphere of radius r and radiance L has intensity π r² L.
                    let r = d2.sqrt() * tan;
                    let _ = writeln!(
                        x,
                        "    <shape type=\"sphere\">\n        <point name=\"center\" value=\"{}\"/>\n        \
                         <float name=\"radius\" value=\"{r}\"/>\n        <emitter type=\"area\">\n            \
                         <rgb name=\"radiance\" value=\"{}\"/>\n        </emitter>\n    </shape>",
                        v3(position),
                        rgb(intensity.map(|v| v / (std::f64::consts::PI * r * r)))
                    );
                } else {
                    let _ = writeln!(
                        x,
                        "    <emitter type=\"point\">\n        <point name=\"position\" value=\"{}\"/>\n        \
                         <rgb name=\"intensity\" value=\"{}\"/>\n    </emitter>",
                        v3(position),
                        rgb(intensity)
                    );
                }
            }
        }
    }
    let mut files = Vec::new();
    let env = match (input.env, &scene.environment) {
        (Some(env), _) => Some(env.clone()),
        (None, Some(_)) => Some(EnvMap::from_fn(256, 128, studio_radiance)),
        (None, None) => None,
    };
    if let Some(env) = env {
        let bitmap = mitsuba_env(&env);
        files.push(("env.exr".to_string(), crate::job::encode_exr(env.width as u32, env.height as u32, &bitmap)?));
        x.push_str(
            "    <emitter type=\"envmap\">\n        <string name=\"filename\" value=\"env.exr\"/>\n    </emitter>\n",
        );
    }
    let skin = &scene.skin;
    let eta = skin.medium.as_ref().map_or(f64::from(skin.ior), |m| m.eta);
    let boundary = if (eta - 1.0).abs() < 1e-9 {
        // Index-matched: no boundary at all, so light samples reach every medium vertex through
        // the surface (shadow rays pass null surfaces, with the medium's transmittance).
        "        <bsdf type=\"null\"/>\n".to_string()
    } else if input.boundary_alpha > 0.0 {
        format!(
            "        <bsdf type=\"roughdielectric\">\n            <string name=\"distribution\" value=\"beckmann\"/>\n            \
             <float name=\"alpha\" value=\"{}\"/>\n            <float name=\"int_ior\" value=\"{eta}\"/>\n            \
             <float name=\"ext_ior\" value=\"1.0\"/>\n        </bsdf>\n",
            input.boundary_alpha
        )
    } else {
        format!(
            "        <bsdf type=\"dielectric\">\n            <float name=\"int_ior\" value=\"{eta}\"/>\n            \
             <float name=\"ext_ior\" value=\"1.0\"/>\n        </bsdf>\n"
        )
    };
    let body = match interior {
        Interior::Lambert => format!(
            "        <bsdf type=\"diffuse\">\n            <rgb name=\"reflectance\" value=\"{}\"/>\n        </bsdf>\n",
            rgb(skin.albedo.map(f64::from))
        ),
        Interior::Medium => {
            let m = skin.medium.as_ref().ok_or_else(|| {
                RenderError::Invalid("the interior is a medium but the material names none (give --medium)".into())
            })?;
            x.push_str(&medium_xml(m.albedo(), m.sigma_t_per_mm(), m.g));
            format!("{boundary}        <ref name=\"interior\" id=\"interior\"/>\n")
        }
        // A black absorber: light that enters is gone within a micrometre.
        Interior::Absorber => {
            x.push_str(&medium_xml([0.0; 3], [1e4; 3], 0.0));
            format!("{boundary}        <ref name=\"interior\" id=\"interior\"/>\n")
        }
    };
    let mut is_part = vec![false; mesh.triangle_count()];
    for g in mesh.groups.iter().filter(|g| !g.is_tissue()) {
        is_part[g.triangles.clone()].fill(true);
    }
    let (eyes, skin_tris): (Vec<usize>, Vec<usize>) = (0..mesh.triangle_count()).partition(|&t| is_part[t]);
    // The medium needs a closed boundary: open loops (the head's neck) get flat caps.
    let (closed, caps) = close_boundary_loops(mesh, &skin_tris);
    let all: Vec<usize> = (0..closed.triangle_count()).collect();
    files.push(("skin.ply".to_string(), ply(&closed, &all, None)));
    if caps > 0 {
        let _ = writeln!(x, "    <!-- skin.ply: {caps} open boundary loop(s) closed with flat caps -->");
    }
    let _ = write!(
        x,
        "    <shape type=\"ply\" id=\"skin\">\n        <string name=\"filename\" value=\"skin.ply\"/>\n{body}    </shape>\n"
    );
    if !eyes.is_empty() {
        let colours = vertex_albedo(mesh, skin.albedo, Default::default());
        files.push(("eyes.ply".to_string(), ply(mesh, &eyes, Some(&colours))));
        x.push_str(
            "    <shape type=\"ply\" id=\"eyes\">\n        <string name=\"filename\" value=\"eyes.ply\"/>\n        \
             <bsdf type=\"diffuse\">\n            <texture type=\"mesh_attribute\" name=\"reflectance\">\n                \
             <string name=\"name\" value=\"vertex_color\"/>\n            </texture>\n        </bsdf>\n    </shape>\n",
        );
    }
    x.push_str("</scene>\n");
    Ok(MitsubaScene { xml: x, files })
}

impl MitsubaScene {
    /// Writes `scene.xml` and its files into `dir` (created if missing), each atomically.
    ///
    /// # Errors
    /// [`RenderError::File`] naming the file that could not be written.
    pub fn write(&self, dir: &Path) -> Result<()> {
        std::fs::create_dir_all(dir).map_err(|e| RenderError::file(dir, format!("cannot create the folder: {e}")))?;
        for (name, bytes) in
            self.files.iter().map(|(n, b)| (n.as_str(), b.as_slice())).chain([("scene.xml", self.xml.as_bytes())])
        {
            let path = dir.join(name);
            rouge_measure::file_set::write_atomic(&path, bytes)
                .map_err(|e| RenderError::file(&path, format!("cannot write: {e}")))?;
        }
        Ok(())
    }
}
