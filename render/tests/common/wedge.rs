//! The backlit wedge of the slab law's GPU tests (slab_gpu.rs, slab_spread_gpu.rs) and its exact
//! geometry: a built-in mesh in view, the wedge's columns and planes, the lit extent and the light
//! scattered once along the view ray as the thickness pass should find them.

use glam::Vec3;
use rouge_model::look::Look;
use rouge_model::medium::Medium;
use rouge_model::mesh::load_mesh;
use rouge_render::slab_extent::{lateral_rates_per_mm, lit_extent};
use rouge_render::slab_march::{sampling_rate_per_mm, view_march};
use rouge_render::slab_transmittance::{kappa, single_unreflected, transmittance};
use rouge_render::{Camera, Gpu, LightRig, Renderer, Scene, Skin, SlabThrough, SubsurfaceModel};
use std::path::Path;

/// A built-in mesh with a bare look, framed by the default camera at 160²: the skin's diffuse
/// radiance at a point of it.
pub struct View {
    pub r: Renderer,
    pub camera: Camera,
}

impl View {
    /// The frame's side, pixels.
    pub const SIZE: u32 = 160;

    pub fn new(gpu: &Gpu, mesh: &str, albedo: [f32; 3]) -> View {
        let mesh = load_mesh(Some(Path::new(mesh)), 1.0, 0).expect("built-in mesh");
        let mut r = Renderer::new(&gpu.device, &gpu.queue);
        r.set_mesh(&mesh, albedo).expect("mesh");
        r.set_look(&Look::bare()).expect("look");
        let camera = Camera::framing(&r.mesh_bounds().expect("bounds"), 0.0, 0.0);
        View { r, camera }
    }

    pub fn diffuse_at(&mut self, scene: &Scene, at: Vec3) -> [f32; 4] {
        self.r.render(scene, &self.camera, Self::SIZE, Self::SIZE, false).expect("render");
        let cap = self.r.capture().expect("capture");
        let (px, py) = self.r.project(at).expect("in view");
        cap.diffuse[(py as u32 * Self::SIZE + px as u32) as usize]
    }
}

/// Whether the line through `p` along `l` meets the convex `mesh` (every face's plane holds the
/// mesh on its inner side): the light's map holds the mesh in that column.
pub fn line_meets_convex(mesh: &rouge_model::mesh::Mesh, p: Vec3, l: Vec3) -> bool {
    column_entry(mesh, p, l).is_some()
}

/// The lit extent at `at` under the light toward `l` (exactly, `slab_extent::lit_extent`) for a
/// slab `depth_mm` thick of `medium`, where `covered` says whether a column meets the mesh.
pub fn exact_lit_extent(medium: &Medium, depth_mm: f64, l: Vec3, at: Vec3, covered: impl Fn(Vec3) -> bool) -> [f64; 3] {
    let rates = lateral_rates_per_mm(medium.sigma_t_prime_per_mm(), medium.reduced_albedo().map(kappa), depth_mm);
    let right = l.any_orthonormal_vector();
    let up = l.cross(right);
    lit_extent(rates, |x, y| covered(at + right * x as f32 + up * y as f32))
}

/// The plane slab's transmittance without its light scattered once and not reflected, which the
/// pass marches through the mesh instead (`exact_march`): for albedo `alpha`, index `eta`,
/// optical thickness `tau` and the external cosines `mu_v`, `mu_l`.
pub fn unmarched_transmittance(alpha: f64, eta: f64, tau: f64, mu_v: f64, mu_l: f64) -> f64 {
    transmittance(alpha, eta, tau, mu_v, mu_l).expect("domain") - single_unreflected(alpha, eta, tau, mu_v, mu_l)
}

/// The built-in medium `name` of index `eta` in the built-in wedge lit from behind (above and
/// the right), under the slab model with `through` carrying the light that crossed it; no
/// specular.
pub fn backlit_wedge(gpu: &Gpu, name: &str, eta: f64, through: SlabThrough) -> BacklitWedge {
    let medium = Medium::builtin(name).expect("built-in medium").with_eta(eta).expect("η");
    let (skin, _) = Skin::from_medium(&medium, rouge_render::diffusion::ProfileModel::BetterDipole);
    let mut scene = Scene::rig(LightRig::Back);
    scene.skin = Skin { subsurface: SubsurfaceModel::Slab { kernel: None, through }, ..skin };
    scene.specular = false;
    let view = View::new(gpu, "builtin:wedge", scene.skin.albedo);
    // The back rig's light, toward it.
    let l = Vec3::new(0.55, 0.3, -0.78).normalize();
    BacklitWedge { medium, scene, view, wedge: rouge_model::mesh::shapes::wedge(), l }
}

/// What [`backlit_wedge`] sets up: the medium, the scene, its view, the wedge's mesh and the
/// unit vector toward the light.
pub struct BacklitWedge {
    pub medium: Medium,
    pub scene: Scene,
    pub view: View,
    pub wedge: rouge_model::mesh::Mesh,
    pub l: Vec3,
}

/// Whether `p` is inside the convex `mesh` (within 10⁻⁴ mm of it).
fn inside_convex(mesh: &rouge_model::mesh::Mesh, p: Vec3) -> bool {
    mesh.faces.iter().all(|face| {
        let n = mesh.normals[face.corners[0].normal as usize];
        n.dot(p - mesh.positions[face.corners[0].position as usize]) <= 1e-4
    })
}

/// How far the ray from `p` (inside the convex `mesh`) along `d` goes before it leaves it.
fn exit_distance(mesh: &rouge_model::mesh::Mesh, p: Vec3, d: Vec3) -> f32 {
    let mut t = f32::INFINITY;
    for face in &mesh.faces {
        let n = mesh.normals[face.corners[0].normal as usize];
        let (a, b) = (n.dot(d), n.dot(p - mesh.positions[face.corners[0].position as usize]));
        if a > 1e-9 {
            t = t.min((-b / a).max(0.0));
        }
    }
    t
}

/// The light scattered once toward the camera at `camera` from `at` on the front face (z = 7.5,
/// normal +z) of the convex `mesh` of `medium`, per unit E/π, as the pass marches it
/// (`slab_march::view_march`): along the camera's refracted ray to where it leaves the mesh, each
/// point's path to the light (toward `l`) from the mesh's planes, the faces' transmittances as
/// the slab law's; `entry` is the outward normal of the face the light enters above `at`.
pub fn exact_march(
    mesh: &rouge_model::mesh::Mesh,
    medium: &Medium,
    camera: Vec3,
    at: Vec3,
    l: Vec3,
    entry: Vec3,
) -> [f64; 3] {
    let (alpha, sigma_t, eta) = (medium.reduced_albedo(), medium.sigma_t_prime_per_mm(), medium.eta);
    let n = Vec3::Z;
    let d = (at - camera).normalize();
    let (mu_v, mu_l) = (f64::from(-d.z), f64::from(l.dot(entry)));
    let nu = |mu: f64| (1.0 - (1.0 - mu * mu) / (eta * eta)).max(0.0).sqrt();
    let (nu_v, nu_l) = (nu(mu_v), nu(mu_l));
    let dir = if eta == 1.0 {
        d
    } else {
        // Snell's law in vector form, into the medium of index η.
        let r = (1.0 / eta) as f32;
        (r * d + (r * mu_v as f32 - nu_v as f32) * n).normalize()
    };
    let chord = f64::from(exit_distance(mesh, at, d)) * mu_v / nu_v;
    let k = sampling_rate_per_mm(sigma_t, f64::from(dir.dot(entry)), nu_l, chord);
    let integral = view_march(sigma_t, k, chord, |s| {
        let p = at + dir * s as f32;
        let (into, _) = column_entry(mesh, p, l)?;
        inside_convex(mesh, p).then(|| f64::from((into - p).length()) * mu_l / nu_l)
    });
    let f = |mu: f64| rouge_render::diffusion::fresnel_dielectric(mu, eta);
    let boundary = if eta == 1.0 { 1.0 } else { (1.0 - f(mu_v)) * (1.0 - f(mu_l)) / (eta * eta) };
    std::array::from_fn(|c| boundary * alpha[c] * sigma_t[c] / 4.0 * integral[c])
}

/// Where the line through `p` along `l` (toward the light) enters the convex `mesh`: the point
/// furthest toward the light on it, and that face's outward normal; None if it misses.
pub fn column_entry(mesh: &rouge_model::mesh::Mesh, p: Vec3, l: Vec3) -> Option<(Vec3, Vec3)> {
    let (mut lo, mut hi, mut entry_normal) = (f32::NEG_INFINITY, f32::INFINITY, Vec3::ZERO);
    for face in &mesh.faces {
        let n = mesh.normals[face.corners[0].normal as usize];
        let q = mesh.positions[face.corners[0].position as usize];
        // n·(p + t·l − q) ≤ 0 inside.
        let (a, b) = (n.dot(l), n.dot(p - q));
        if a.abs() < 1e-9 {
            if b > 0.0 {
                return None;
            }
        } else if a > 0.0 {
            if -b / a < hi {
                (hi, entry_normal) = (-b / a, n);
            }
        } else {
            lo = lo.max(-b / a);
        }
    }
    (lo <= hi).then_some((p + hi * l, entry_normal))
}
