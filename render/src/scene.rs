//! What a frame shows besides the mesh and the look: camera, lights, environment, skin, SSS
//! settings, exposure. Units are millimetres; +Y up, the face looks toward +Z.

use crate::cube_atlas::AtlasSettings;
use crate::diffusion::ProfileModel;
use crate::directional_dipole::{DipoleKind, DipoleSettings};
use crate::env::ShIrradiance;
use crate::error::{RenderError, Result};
use crate::local_thickness::{ThicknessSource, TranslucencyParams};
use crate::profile_fit::FittedProfile;
use crate::sss::DiffusionProfile;
use glam::{Mat4, Vec3};
use rouge_measure::Spectrum;
use rouge_measure::colorimetry::{Colorimeter, Viewing};
use rouge_model::medium::Medium;
use rouge_model::mesh::{Bounds, TriangleMesh};
use rouge_model::skin::AnatomyRegion;

/// An orbit camera around the mesh.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Camera {
    /// Point looked at, mm.
    pub target: Vec3,
    /// Distance from the target, mm.
    pub distance: f32,
    /// Rotation about +Y, degrees; 0 looks at the face from +Z, positive turns the camera to the
    /// face's left (the viewer sees more of the right cheek).
    pub yaw_deg: f32,
    /// Elevation, degrees; positive looks from above.
    pub pitch_deg: f32,
    /// Vertical field of view, degrees.
    pub fov_y_deg: f32,
}

impl Camera {
    /// A portrait framing of `bounds`: a 25° lens at a distance where the bounding sphere's
    /// height fits the frame, looking at the upper part of the bounds (the face, not the neck).
    pub fn framing(bounds: &Bounds, yaw_deg: f32, pitch_deg: f32) -> Camera {
        let size = bounds.size();
        let centre = bounds.center();
        let fov_y_deg = 25.0f32;
        let half_height = 0.5 * size.y.max(size.x) * 0.95;
        let distance = half_height / (0.5 * fov_y_deg.to_radians()).tan() + 0.5 * size.z;
        Camera { target: centre + Vec3::new(0.0, 0.05 * size.y, 0.0), distance, yaw_deg, pitch_deg, fov_y_deg }
    }

    /// A close-up of `region` of the default head (its UV mask, `rouge_model::skin::AnatomyRegion`)
    /// from the direction `yaw_deg`, `pitch_deg`: the camera aims at the centroid of the mesh's
    /// skin vertices weighted by the mask (of cheeks, ears and eyelids only the side toward the camera)
    /// from a fifth of the framing distance, with the same field of view: about 60 mm of face
    /// across the image's height, so a 1280×720 frame has about 12 pixels per millimetre.
    /// `None` when the mesh has no vertex in the region (another mesh's UVs).
    pub fn close_up(mesh: &TriangleMesh, region: AnatomyRegion, yaw_deg: f32, pitch_deg: f32) -> Option<Camera> {
        let bounds = Bounds::of(&mesh.positions)?;
        let framing = Camera::framing(&bounds, yaw_deg, pitch_deg);
        let paired = matches!(region, AnatomyRegion::Cheeks | AnatomyRegion::Ears | AnatomyRegion::Eyelids);
        let side = if yaw_deg >= 0.0 { 1.0 } else { -1.0 };
        // The skin's vertices only: the brows' hairs carry the skin's UVs under them.
        let mut skin = vec![false; mesh.positions.len()];
        mesh.only(|g| g.is_skin()).indices.iter().for_each(|&v| skin[v as usize] = true);
        let (mut sum, mut weight) = (Vec3::ZERO, 0.0f64);
        for ((p, uv), _) in mesh.positions.iter().zip(&mesh.uvs).zip(&skin).filter(|(_, s)| **s) {
            let on_side = !paired || (p.x - bounds.center().x) * side > 0.0;
            let w = if on_side { region.weight_uv(uv.x, uv.y) } else { 0.0 };
            sum += *p * w as f32;
            weight += w;
        }
        (weight > 0.0).then(|| Camera { target: sum / weight as f32, distance: 0.2 * framing.distance, ..framing })
    }

    /// Camera position, mm.
    pub fn position(&self) -> Vec3 {
        let (yaw, pitch) = (self.yaw_deg.to_radians(), self.pitch_deg.to_radians());
        self.target + self.distance * Vec3::new(yaw.sin() * pitch.cos(), pitch.sin(), yaw.cos() * pitch.cos())
    }

    /// View matrix (right-handed, looking down −Z in view space).
    pub fn view(&self) -> Mat4 {
        glam::camera::rh::view::look_at_mat4(self.position(), self.target, Vec3::Y)
    }

    /// Near and far planes that enclose a sphere of `radius` around the target.
    pub fn clip_planes(&self, radius: f32) -> (f32, f32) {
        let near = (self.distance - 1.5 * radius).max(self.distance * 0.05).max(1.0);
        (near, self.distance + 1.5 * radius)
    }

    /// [`Camera::clip_planes`] around a mesh with `bounds` (the renderer's, every export's).
    pub fn clip_planes_around(&self, bounds: &Bounds) -> (f32, f32) {
        let radius = 0.5 * bounds.size().length();
        self.clip_planes(radius.max(self.distance * 0.02))
    }

    /// Perspective projection for `aspect` (width / height), depth in [0, 1].
    pub fn projection(&self, aspect: f32, near: f32, far: f32) -> Mat4 {
        glam::camera::rh::proj::directx::perspective(self.fov_y_deg.to_radians(), aspect, near, far)
    }

    /// Focal length in pixels for an image `height` pixels tall.
    pub fn focal_px(&self, height: u32) -> f32 {
        0.5 * height as f32 / (0.5 * self.fov_y_deg.to_radians()).tan()
    }
}

/// Where a light is.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum LightKind {
    /// Infinitely far, along `toward` (unit vector from the scene toward the light).
    Directional {
        /// Unit vector toward the light.
        toward: Vec3,
    },
    /// At `position` (mm); irradiance falls off with the squared distance.
    Point {
        /// Position, mm.
        position: Vec3,
    },
}

/// A light. `irradiance` is linear RGB irradiance at normal incidence: everywhere for a
/// directional light, at the scene centre for a point light. A white Lambertian surface facing a
/// light of irradiance π has radiance 1.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Light {
    /// Directional or point.
    pub kind: LightKind,
    /// Irradiance at normal incidence, linear RGB.
    pub irradiance: [f32; 3],
    /// Whether the light casts shadows (one shadow map each).
    pub shadows: bool,
    /// This light's multiplier of the thickness translucency's back lobe (the talk's per-light
    /// `fLTScale`, \[BarreBrisebois2011\]; the material's fitted scale times this). 1 by default.
    pub translucency_scale: f32,
}

/// Skin: albedo, specular and scattering.
#[derive(Clone, Debug, PartialEq)]
pub struct Skin {
    /// Total diffuse reflectance, linear sRGB.
    pub albedo: [f32; 3],
    /// Beckmann roughness of the skin's specular lobe.
    pub roughness: f32,
    /// Index of refraction of the skin surface (Schlick F0 from it).
    pub ior: f32,
    /// How light scatters under the surface (the subsurface model of the skin material).
    pub subsurface: SubsurfaceModel,
    /// The physical medium under the surface, when the material names one (`--medium`): what
    /// `rouge export mitsuba` puts inside the mesh. `None`: a measured albedo and profile only.
    pub medium: Option<Medium>,
    /// How the light entering the skin depends on the light's and the viewer's directions.
    pub diffuse: DiffuseLaw,
}

/// The skin's diffuse law: the radiance the lighting pass hands to the subsurface model per unit
/// irradiance, as a function of the incidence and exit cosines.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum DiffuseLaw {
    /// Lambert: albedo/π in every direction, the albedo being a medium's exact half-space
    /// albedo ([`Skin::medium_albedo`], what the diffusion models' Rd approximates) or a
    /// measured colour.
    #[default]
    Lambert,
    /// The exact transport of an isotropic half-space under the skin's boundary (η = the skin's
    /// IOR, 1 to 3; adding-doubling's table, [`crate::dielectric_brdf`]; at η = 1
    /// \[Chandrasekhar1960\]'s, [`crate::half_space`]): radiance E·πf(μ, μ₀)/π per light and
    /// E·R(μ)/π from the environment, the albedo read per pixel as the normal-incidence
    /// reflectance R(1), which is what [`Skin::medium_albedo`] is, so the law changes a skin's
    /// angular shape and not its albedo. Matches a path tracer's half-space at every albedo,
    /// where the dipoles' totals fall 10-36% short at low albedo.
    HalfSpace,
}

impl DiffuseLaw {
    /// The name on the command line and in the frame plan.
    pub fn name(self) -> &'static str {
        match self {
            DiffuseLaw::Lambert => "lambert",
            DiffuseLaw::HalfSpace => "half-space",
        }
    }
}

/// A material's subsurface scattering model: which technique the frame plan runs for it, with
/// its parameters. Each model adds only the passes and G-buffer channels it needs; `None` adds
/// nothing. The translucency models of the later issues (local thickness, cube-map atlas dipole,
/// directional and standard dipole) join here as variants with their physical medium.
#[derive(Clone, Debug, PartialEq)]
pub enum SubsurfaceModel {
    /// No scattering: the skin's diffuse radiance is used where it enters.
    None,
    /// The separable screen-space kernel (\[Jimenez2015\]) of a diffusion profile (two passes).
    ScreenSpace {
        /// The diffusion profile the kernel is built from.
        profile: DiffusionProfile,
    },
    /// Fast thickness translucency (\[BarreBrisebois2011\], [`crate::local_thickness`]): light
    /// through thin parts from behind, one full-screen pass and a local-thickness G-buffer target.
    Thickness {
        /// Distortion, power, scale, ambient.
        params: TranslucencyParams,
        /// Where the local thickness comes from.
        source: ThicknessSource,
        /// With a profile, the screen-space kernel of it blurs the skin's diffuse radiance, the
        /// light through thin parts with it (`screen-space+thickness`: the kernel's scattering
        /// near where light entered, the thickness term's light from behind, issue 31 item 4);
        /// without, the diffuse light stays where it entered.
        kernel: Option<DiffusionProfile>,
    },
    /// The slab law ([`crate::slab_transmittance`]): each light that crossed the mesh before a
    /// skin pixel lights it as a plane slab of the skin's medium, of the thickness the light
    /// crossed (its shadow map) and tilted as the face it entered (the map's slope), would: exact
    /// transport, every order of scattering, no fitted parameter, over the share of the slab's
    /// lit plane the light's map holds, drained toward an edge where the exit face meets a side
    /// face the light does not reach ([`crate::slab_extent`]). It fades out where the exit
    /// face turns the same way as the entry face (past a convex terminator, the kernel's part)
    /// and is off where the surface faces the light. The thickness pass draws it,
    /// with the local-thickness target for the material id. Needs `Skin::medium`, and lights
    /// that cast shadows; the plane slab is exact under the medium's boundary for 1 ≤ η ≤ 1.6
    /// ([`crate::slab_transmittance`]).
    Slab {
        /// With a profile, its screen-space kernel blurs the skin's diffuse radiance, the slab's
        /// light with it (`screen-space+slab`), as in [`SubsurfaceModel::Thickness`].
        kernel: Option<DiffusionProfile>,
        /// What carries the light that crossed the mesh to a pixel facing away from a
        /// directional light: the slab law, or the transmission gather.
        through: SlabThrough,
    },
    /// The directional dipole (\[Frisvad2014\]) or the standard dipole (\[Jensen2001\]) of the
    /// skin's medium, gathered from light G-buffers into K radiance maps and combined per pixel
    /// (\[DirDipoleThesis\], the dipole passes). Takes over the skin's direct light; needs
    /// `Skin::medium`.
    Dipole {
        /// Which BSSRDF.
        kind: DipoleKind,
        /// Samples, directions, map sizes, the artifact fixes, progressive accumulation.
        settings: DipoleSettings,
    },
    /// Jensen's dipole gathered in an on-the-fly cube-map atlas (\[Benmounah2009\],
    /// [`crate::cube_atlas`]): the mesh drawn onto the six faces of its bounding cube every
    /// frame, so it may deform. Takes over the skin's direct and environment light; needs
    /// `Skin::medium`.
    CubeAtlas {
        /// Atlas size, kernel, self-occlusion test, global term.
        settings: AtlasSettings,
    },
}

/// What carries, under [`SubsurfaceModel::Slab`], the light that crossed the mesh to a pixel
/// facing away from a directional light (issue 31 item 4; docs/BENCHMARKS.md "The transmission
/// gather"). Point lights and pixels facing the light take the slab law's path either way.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum SlabThrough {
    /// The slab law: a plane slab of the thickness the light crossed, exact, over the share of
    /// its lit plane the light's map holds, and the hidden-entry gather for the rest. Best where
    /// the body is wider than the light spreads in it (a wedge, a head).
    #[default]
    Law,
    /// The transmission gather (the hidden-entry gather alone, with the kernel of
    /// `shaders/through.wgsl`, [`crate::through_gather`]): every entry the
    /// light's map holds, carried to the pixel by the classic dipole's sources seen through the
    /// exit face with its boundary image, at the medium's exact decay rate. No plane assumed:
    /// best across a body narrower than the light spreads (a finger: the backlit hand 3.44 →
    /// 2.17 ΔE2000); diffusion, so it misses a low albedo's thin slab (the ketchup wedge). Its
    /// gather takes [`crate::slab_transmittance::TRANSMISSION_GATHER_SAMPLES`] samples.
    Gather,
}

impl SlabThrough {
    /// The uniform's `kind.y`: 1 for the transmission gather.
    pub fn gpu_flag(self) -> u32 {
        match self {
            SlabThrough::Law => 0,
            SlabThrough::Gather => 1,
        }
    }

    /// The gather's samples per pixel and light under this choice.
    pub fn gather_samples(self) -> u32 {
        match self {
            SlabThrough::Law => crate::slab_transmittance::HIDDEN_ENTRY_SAMPLES,
            SlabThrough::Gather => crate::slab_transmittance::TRANSMISSION_GATHER_SAMPLES,
        }
    }
}

impl SubsurfaceModel {
    /// The screen-space kernel of d'Eon's six-Gaussian skin profile (\[dEon2007\]), today's default.
    pub fn skin_screen_space() -> SubsurfaceModel {
        SubsurfaceModel::ScreenSpace { profile: DiffusionProfile::skin() }
    }

    /// The name used on the command line and in `--explain`.
    pub fn name(&self) -> &'static str {
        match self {
            SubsurfaceModel::None => "none",
            SubsurfaceModel::ScreenSpace { .. } => "screen-space",
            SubsurfaceModel::Thickness { kernel: Some(_), .. } => "screen-space+thickness",
            SubsurfaceModel::Thickness { kernel: None, .. } => "thickness",
            SubsurfaceModel::Slab { kernel: Some(_), through: SlabThrough::Law } => "screen-space+slab",
            SubsurfaceModel::Slab { kernel: None, through: SlabThrough::Law } => "slab",
            SubsurfaceModel::Slab { kernel: Some(_), through: SlabThrough::Gather } => "screen-space+slab-gather",
            SubsurfaceModel::Slab { kernel: None, through: SlabThrough::Gather } => "slab-gather",
            SubsurfaceModel::Dipole { kind, .. } => kind.name(),
            SubsurfaceModel::CubeAtlas { .. } => "cube-atlas",
        }
    }

    /// The diffusion profile of the screen-space kernel, where the model has one (the
    /// screen-space model, or the thickness model with a kernel).
    pub fn profile(&self) -> Option<&DiffusionProfile> {
        match self {
            SubsurfaceModel::ScreenSpace { profile }
            | SubsurfaceModel::Thickness { kernel: Some(profile), .. }
            | SubsurfaceModel::Slab { kernel: Some(profile), .. } => Some(profile),
            SubsurfaceModel::None
            | SubsurfaceModel::Thickness { kernel: None, .. }
            | SubsurfaceModel::Slab { kernel: None, .. }
            | SubsurfaceModel::Dipole { .. }
            | SubsurfaceModel::CubeAtlas { .. } => None,
        }
    }
}

impl Skin {
    /// Skin whose albedo is the linear sRGB (D65, CIE 1931) of a reflectance spectrum; d'Eon's
    /// skin profile; roughness 0.35 and IOR 1.4 (F0 ≈ 0.028), the values of d'Eon and Luebke (\[dEon2007\]).
    pub fn from_spectrum(reflectance: &Spectrum) -> Skin {
        let c = Colorimeter::get(Viewing::D65_1931);
        let rgb = c.srgb_linear(&c.xyz(reflectance));
        Skin {
            albedo: rgb.map(|v| v.clamp(0.0, 1.0) as f32),
            roughness: 0.35,
            ior: 1.4,
            subsurface: SubsurfaceModel::skin_screen_space(),
            medium: None,
            diffuse: DiffuseLaw::Lambert,
        }
    }

    /// A material of `medium` whose screen-space profile comes from `model` fitted by Gaussians
    /// ([`FittedProfile`]): the albedo is what the profile's total diffuse reflectance stands
    /// for, computed exactly ([`Skin::medium_albedo`]), the IOR the medium's η, the roughness
    /// that of skin, and the diffuse law the medium's exact half-space ([`DiffuseLaw::HalfSpace`]:
    /// closer to the path tracer than Lambert on every reference scene, docs/BENCHMARKS.md;
    /// [`Skin::lambert`] for the other). Returns the fit too (its error is reported).
    pub fn from_medium(medium: &Medium, model: ProfileModel) -> (Skin, FittedProfile) {
        let fit = FittedProfile::of_medium(medium, model);
        let skin = Skin {
            albedo: Skin::medium_albedo(medium, &fit),
            roughness: 0.35,
            ior: medium.eta as f32,
            subsurface: SubsurfaceModel::ScreenSpace { profile: fit.profile.clone() },
            medium: Some(medium.clone()),
            diffuse: DiffuseLaw::HalfSpace,
        };
        (skin, fit)
    }

    /// The albedo of `medium` per channel: the subsurface reflectance at normal incidence of its
    /// half-space under its boundary ([`crate::dielectric_half_space`], adding-doubling: every
    /// order of scattering and the boundary's internal reflections), which the diffusion
    /// profiles' totals approximate, 2-37% off for skin at η = 1.3 (docs/BENCHMARKS.md, "The
    /// dielectric half-space"). `fit`'s totals stand in only for a medium outside the table's
    /// domain, which [`Medium`]'s checks keep out.
    pub fn medium_albedo(medium: &Medium, fit: &FittedProfile) -> [f32; 3] {
        let exact = crate::dielectric_half_space::medium_normal_reflectance(medium);
        std::array::from_fn(|c| exact[c].unwrap_or(fit.total[c]).clamp(0.0, 1.0) as f32)
    }

    /// This skin under [`DiffuseLaw::HalfSpace`]. The albedo stays: the law reads it as the
    /// half-space's normal-incidence reflectance under a boundary of the skin's IOR, which a
    /// medium's albedo is ([`Skin::medium_albedo`]) and a measured colour stands for.
    pub fn half_space(self) -> Skin {
        Skin { diffuse: DiffuseLaw::HalfSpace, ..self }
    }

    /// This skin under [`DiffuseLaw::Lambert`], its albedo unchanged.
    pub fn lambert(self) -> Skin {
        Skin { diffuse: DiffuseLaw::Lambert, ..self }
    }

    /// The ColorChecker's "light skin" or "dark skin" patch.
    ///
    /// # Errors
    /// [`RenderError::Invalid`] for another patch name.
    pub fn colorchecker(patch: &str) -> Result<Skin> {
        let patches = rouge_measure::import::colorchecker_skin().map_err(|e| RenderError::Invalid(e.to_string()))?;
        let (_, spectrum) = patches
            .iter()
            .find(|(name, _)| name == patch)
            .ok_or_else(|| RenderError::Invalid(format!("no skin patch {patch:?}: use light_skin or dark_skin")))?;
        Ok(Skin::from_spectrum(spectrum))
    }

    /// Schlick's F0 for the skin's IOR.
    pub fn f0(&self) -> f32 {
        fresnel_f0(self.ior)
    }
}

impl Default for Skin {
    fn default() -> Self {
        // The embedded table always has the patch; fall back to its known colour regardless.
        Skin::colorchecker("light_skin").unwrap_or(Skin {
            albedo: [0.40, 0.26, 0.20],
            roughness: 0.35,
            ior: 1.4,
            subsurface: SubsurfaceModel::skin_screen_space(),
            medium: None,
            diffuse: DiffuseLaw::Lambert,
        })
    }
}

/// Schlick's normal-incidence reflectance for a dielectric of index `ior` in air.
pub fn fresnel_f0(ior: f32) -> f32 {
    rouge_measure::specular::fresnel_f0(f64::from(ior)) as f32
}

/// Screen-space scattering settings.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SssSettings {
    /// Scale of the diffusion profile's distances: 1 is the measured profile, 0 no scattering
    /// (the pass is then skipped unless `run_at_zero_width`).
    pub width: f32,
    /// Kernel samples per direction: odd, 3 to 33.
    pub samples: u32,
    /// Depth difference (mm) over which a sample is replaced by the centre value.
    pub follow_mm: f32,
    /// Kernel range in σ of the widest Gaussian.
    pub range_sigmas: f32,
    /// Run the passes even at width 0 (for testing that they are then the identity).
    pub run_at_zero_width: bool,
}

impl SssSettings {
    /// Whether the blur runs when the skin's model has a kernel: the width is not 0 (or the
    /// test asks for it at 0).
    pub fn runs(&self) -> bool {
        self.width != 0.0 || self.run_at_zero_width
    }

    /// How far the kernel of `profile` reaches on the surface, mm: `range_sigmas` × the widest
    /// Gaussian's σ × `width` ([`crate::sss::SeparableKernel::new`] puts its last samples there).
    pub fn reach_mm(&self, profile: &DiffusionProfile) -> f32 {
        self.range_sigmas * profile.max_sigma_mm() as f32 * self.width
    }
}

impl Default for SssSettings {
    fn default() -> Self {
        SssSettings { width: 1.0, samples: 11, follow_mm: 3.0, range_sigmas: 3.0, run_at_zero_width: false }
    }
}

/// Named light setups (`--lights`).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum LightRig {
    /// The default studio: key, fill and rim lights and a soft environment.
    Studio,
    /// One white key light from the front left, with shadows.
    FrontLeft,
    /// One white light from behind, with shadows (backlit translucency).
    Back,
    /// One white light from the camera's side (+Z), with shadows.
    Front,
    /// No light and no environment (add one with `--env`).
    None,
}

/// Everything about a frame but the mesh and the look.
#[derive(Clone, Debug, PartialEq)]
pub struct Scene {
    /// Up to [`crate::MAX_LIGHTS`] lights.
    pub lights: Vec<Light>,
    /// Environment irradiance, if any (no environment term without one).
    pub environment: Option<ShIrradiance>,
    /// Skin material.
    pub skin: Skin,
    /// Scattering.
    pub sss: SssSettings,
    /// One bounce of the skin's glow between parts that face each other ([`crate::bounce`]);
    /// `None`: no bounce pass.
    pub bounce: Option<crate::bounce::BounceSettings>,
    /// Specular lobes on (skin and layers).
    pub specular: bool,
    /// Exposure applied before tone mapping (display output only).
    pub exposure: f32,
    /// Background colour at the top of the frame, linear RGB (darkens toward the bottom).
    pub background: [f32; 3],
}

impl Scene {
    /// The default studio: a warm key light from the upper left with shadows, a cool fill point
    /// light from the right, a rim light from behind, and a soft studio environment.
    pub fn studio() -> Scene {
        Scene {
            lights: vec![
                Light {
                    kind: LightKind::Directional { toward: Vec3::new(-0.5, 0.45, 0.75).normalize() },
                    irradiance: [2.9, 2.75, 2.55],
                    shadows: true,
                    translucency_scale: 1.0,
                },
                Light {
                    kind: LightKind::Point { position: Vec3::new(450.0, -20.0, 500.0) },
                    irradiance: [0.55, 0.6, 0.68],
                    shadows: false,
                    translucency_scale: 1.0,
                },
                Light {
                    kind: LightKind::Directional { toward: Vec3::new(0.35, 0.55, -0.75).normalize() },
                    irradiance: [1.3, 1.3, 1.35],
                    shadows: false,
                    translucency_scale: 1.0,
                },
            ],
            environment: Some(ShIrradiance::studio()),
            skin: Skin::default(),
            sss: SssSettings::default(),
            bounce: None,
            specular: true,
            exposure: 1.0,
            background: [0.16, 0.17, 0.19],
        }
    }

    /// The scene of a light rig: `Studio` is [`Scene::studio`]; the others are one white
    /// directional light of irradiance π that casts shadows and no environment, the setups of
    /// the translucency references (a white Lambertian facing the light has radiance 1).
    pub fn rig(rig: LightRig) -> Scene {
        let toward = match rig {
            LightRig::Studio => return Scene::studio(),
            LightRig::FrontLeft => Vec3::new(-0.6, 0.35, 0.72),
            // From behind, above and to the right: the ear, the nostrils' rims and the silhouette
            // glow.
            LightRig::Back => Vec3::new(0.55, 0.3, -0.78),
            LightRig::Front => Vec3::Z,
            LightRig::None => return Scene { lights: Vec::new(), ..Scene::white_light(Vec3::Z) },
        };
        let mut scene = Scene::white_light(toward);
        scene.lights[0].shadows = true;
        scene
    }

    /// One white directional light of irradiance π along `toward`, nothing else: a white
    /// Lambertian surface facing it has radiance 1, so linear output reads as reflectance.
    pub fn white_light(toward: Vec3) -> Scene {
        Scene {
            lights: vec![Light {
                kind: LightKind::Directional { toward: toward.normalize() },
                irradiance: [std::f32::consts::PI; 3],
                shadows: false,
                translucency_scale: 1.0,
            }],
            environment: None,
            background: [0.0; 3],
            ..Scene::studio()
        }
    }
}
