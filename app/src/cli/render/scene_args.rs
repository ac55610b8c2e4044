//! The scene options `rouge render` and `rouge export mitsuba` share, so that an export is
//! exactly the scene the renderer draws: mesh, look, lights, environment, camera, image size,
//! skin material (a physical medium or today's skin) and its subsurface model.

use anyhow::{Context, Result, bail};
use clap::Args;
use rouge_measure::Extrapolation;
use rouge_measure::analysis::skin::read_skins;
use rouge_model::look::{Look, ThicknessSource};
use rouge_model::medium::Medium;
use rouge_model::skin::SkinConditions;
use rouge_render::diffusion::ProfileModel;
use rouge_render::job::{FacePose, LookChoice, RenderJob, skin_of_tone};
use rouge_render::profile_fit::FittedProfile;
use rouge_render::{LightRig, Scene, Skin};
use std::path::PathBuf;

// clap prints these doc comments as `--help` verbatim: citations stay `[Key]` (`\[Key\]` would show).
#[allow(rustdoc::broken_intra_doc_links)]
#[derive(Debug, Clone, Args)]
pub struct SceneArgs {
    /// Mesh to render (.obj, .gltf, .glb), or builtin:head, builtin:sphere (25 mm radius),
    /// builtin:wedge (60×40 mm, 1 to 15 mm thick), both times --mesh-scale; the embedded default
    /// head (hm08, CC0) when absent.
    #[arg(long)]
    pub mesh: Option<PathBuf>,
    /// Millimetres per mesh unit (scans come in metres, centimetres or arbitrary units); for the
    /// built-in sphere and wedge, their scale.
    #[arg(long, default_value_t = 1.0, value_parser = parse_mesh_scale)]
    pub mesh_scale: f32,
    /// Catmull-Clark subdivision levels applied to the mesh (0-3).
    #[arg(long, default_value_t = 2, value_parser = clap::value_parser!(u32).range(0..=3))]
    pub subdiv: u32,
    /// Look document (JSON, `rouge-look` v1), `bare` for no cosmetics, or `default`
    /// (foundation + blush + lipstick).
    #[arg(long, default_value = "default")]
    pub look: String,
    /// Lights: the studio rig (key, fill, rim and a soft environment), or one white directional
    /// light of irradiance π with shadows and no environment, from the front left, from behind
    /// or from the camera, or nothing but the --env map.
    #[arg(long, value_enum, default_value_t = Lights::Studio)]
    pub lights: Lights,
    /// Equirectangular HDR environment map (.exr) lighting the scene through spherical harmonics;
    /// without it, the rig's (the studio's soft dome, or none).
    #[arg(long)]
    pub env: Option<PathBuf>,
    /// No environment light at all, whatever the rig.
    #[arg(long, conflicts_with = "env")]
    pub no_environment: bool,
    /// Skin albedo texture (PNG, sRGB) in the mesh's UV space; replaces the skin colour.
    #[arg(long)]
    pub albedo_map: Option<PathBuf>,
    /// Tangent-space normal map (PNG, OpenGL convention: green = +V); MikkTSpace tangents are
    /// generated for the mesh.
    #[arg(long)]
    pub normal_map: Option<PathBuf>,
    /// Image width, pixels.
    #[arg(long, default_value_t = 1280, allow_negative_numbers = true)]
    pub width: u32,
    /// Image height, pixels.
    #[arg(long, default_value_t = 720, allow_negative_numbers = true)]
    pub height: u32,
    /// Camera yaw around the head, degrees (positive: from the head's left).
    #[arg(long, default_value_t = 0.0, allow_hyphen_values = true, value_parser = parse_angle_deg)]
    pub yaw: f32,
    /// Camera pitch, degrees (positive: from above).
    #[arg(long, default_value_t = 0.0, allow_hyphen_values = true, value_parser = parse_angle_deg)]
    pub pitch: f32,
    /// A close-up of one region of the default head instead of the whole face, about 60 mm
    /// across the image's height (12 px/mm at 720 px): cheeks, lips, eyelids, nose, forehead,
    /// under_eye, chin, temples or ears (of paired regions the side toward --yaw).
    #[arg(long, value_parser = parse_region)]
    pub close_up: Option<rouge_model::skin::AnatomyRegion>,
    /// A mascara on the default head's lashes, over the look's: length=X (1-2, × the natural
    /// lash), volume=X (1-5, × its thickness), curl=DEG (0-60, extra curl at the tip),
    /// color=black|brown|blue|R/G/B (linear albedo); e.g.
    /// `--mascara length=1.4,volume=2.5,curl=20,color=black`.
    #[arg(long, value_parser = parse_mascara)]
    pub mascara: Option<rouge_model::mesh::lashes::Mascara>,
    /// A tinted brow gel on the default head's brows, over the look's: color=black|brown|R/G/B
    /// (linear albedo), strength=X (0-1, the part of the hairs coated; 1 if left out), fill=X
    /// (0-1, a fibre gel's extra hairs as a fraction of the brow's own; 0 if left out); e.g.
    /// `--brow-gel color=brown,strength=0.7,fill=0.5`. A brow pencil or powder is a layer on the
    /// `brows` region instead.
    #[arg(long, value_parser = parse_brow_gel)]
    pub brow_gel: Option<rouge_model::mesh::brow_gel::BrowGel>,
    /// Physical medium under the skin: a built-in measured medium of [Jensen2001] (apple,
    /// chicken1, chicken2, cream, ketchup, marble, potato, skimmilk, skin1, skin2, wholemilk) or
    /// a `rouge-medium` JSON file. The skin's albedo, IOR and scattering profile then come from
    /// the medium (see --profile).
    #[arg(long, conflicts_with_all = ["sigma_a", "sigma_s"])]
    pub medium: Option<String>,
    /// Absorption σa per linear RGB channel, mm⁻¹ (with --sigma-s and --eta: an explicit medium).
    #[arg(long, value_delimiter = ',', requires_all = ["sigma_s", "eta"])]
    pub sigma_a: Option<Vec<f64>>,
    /// Reduced scattering σs′ = σs(1 − g) per linear RGB channel, mm⁻¹ (g = 0 is assumed).
    #[arg(long, value_delimiter = ',', requires_all = ["sigma_a", "eta"])]
    pub sigma_s: Option<Vec<f64>>,
    /// Relative index of refraction of the medium's boundary (with --medium: replaces the
    /// medium's; 1 is an index-matched boundary, which the path tracer references use).
    #[arg(long)]
    pub eta: Option<f64>,
    /// Diffusion model the medium's screen-space profile comes from (fitted by Gaussians): the
    /// classic dipole of [Jensen2001], the better dipole of [dEon2012], or Burley's normalized
    /// diffusion [Christensen2015]. docs/BENCHMARKS.md says which matches the path tracer best.
    #[arg(long, value_enum, default_value_t = Profile::BetterDipole)]
    pub profile: Profile,
    /// How the skin's light depends on the light's and the viewer's directions: `lambert`
    /// (the albedo in every direction; with a medium, its half-space's exact albedo under its η
    /// by adding-doubling, which the profile's total approximates), or `half-space`, the
    /// exact transport of an isotropic half-space under the skin's boundary (η = the medium's,
    /// else the skin's IOR) by adding-doubling: every albedo, single scattering, refraction and
    /// the darker grazing exits a boundary makes. The albedo is the same under both laws, read as
    /// the reflectance at normal incidence; only its angular shape differs. Default: half-space
    /// with a medium (--medium, --sigma-a/--sigma-s/--eta: it is that medium's exact transport,
    /// closest to the path tracer on every scene, docs/BENCHMARKS.md), Lambert for a skin colour.
    #[arg(long, value_enum)]
    pub diffuse: Option<Diffuse>,
    /// Skin reflectance for the skin's colour: a CSV table (`wavelength_nm` or `wavelength` and
    /// one column per skin, or one skin per row) or a CGATS file, e.g. a measured skin of your
    /// own or one of python/skin_gamut.py's skins; the first skin unless --skin-sample names one.
    /// Spectra not covering 380-780 nm have their end values held.
    #[arg(long, conflicts_with_all = ["medium", "sigma_a"])]
    pub skin: Option<PathBuf>,
    /// Which skin of --skin.
    #[arg(long, requires = "skin")]
    pub skin_sample: Option<String>,
    /// A named tone of the spectral skin model (`rouge skin tones`: very-light ... very-deep) or
    /// an Individual Typology Angle in degrees (about 60 to -60: the skin of that ITA between the
    /// tones): the skin's colour from its reflectance spectrum (docs/SKIN.md).
    #[arg(long, allow_negative_numbers = true, conflicts_with_all = ["medium", "sigma_a", "skin"])]
    pub skin_tone: Option<String>,
    /// Paint the skin from skin maps: the tone (--skin-tone; light without one) over the default
    /// head's anatomy (more blood in the cheeks, nose, chin and ears, the lips' own colour,
    /// thinner and darker skin around the eyes) with any --skin-conditions. The maps' colour
    /// through the spectral skin model becomes the skin's albedo texture (docs/SKIN.md). `rouge
    /// render` does this on the default head by default (--flat-skin: one colour); this flag asks
    /// for it on another mesh, or in `export mitsuba` (which refuses it).
    #[arg(long, conflicts_with_all = ["medium", "sigma_a", "skin", "albedo_map"])]
    pub skin_maps: bool,
    /// One colour for the whole skin (the tone's; light without --skin-tone) instead of skin
    /// maps, which `rouge render` draws on the default head unless the skin comes from --skin,
    /// --medium, --sigma-a or --albedo-map.
    #[arg(long, conflicts_with_all = ["skin_maps", "skin_conditions"])]
    pub flat_skin: bool,
    /// Skin conditions of the skin maps, NAME=AMOUNT,... with amounts 0 to 1: freckles, moles,
    /// redness, acne, hyperpigmentation, under_eye, veins (implies --skin-maps).
    #[arg(long, conflicts_with_all = ["medium", "sigma_a", "skin", "albedo_map"])]
    pub skin_conditions: Option<SkinConditions>,
    /// Seed of the skin conditions' placement (the same seed, the same freckles).
    #[arg(long, default_value_t = 1)]
    pub skin_seed: u64,
    /// Leave out the skin's microgeometry (pores, fine lines, the T-zone's shine, and the default
    /// head's expression wrinkles and lip furrows), which comes with the skin maps
    /// (docs/FINISHES.md; foundations with a levelling finish fill it).
    #[arg(long)]
    pub no_skin_detail: bool,
    /// Keep the skin maps' blood still whatever the --expression (by default it follows it: a
    /// smile flushes the cheeks, pressed lips blanch; docs/SKIN.md).
    #[arg(long)]
    pub no_blood_flow: bool,
    /// Side of the skin maps, texels (16 to 4096; the painted maps' 2048 is 2 texels a mm on the
    /// default head).
    #[arg(long, default_value_t = 1024)]
    pub skin_map_px: u32,
    /// Morph the mesh toward its bounding sphere by this fraction (0 to 1): a deformation for
    /// testing what depends on the rest pose (the baked local thickness of --subsurface thickness).
    #[arg(long, default_value_t = 0.0)]
    pub morph: f32,
    /// Expression of the default head: NAME=WEIGHT,... (NAME alone: weight 1) with weights 0 to 1, each NAME a preset
    /// (neutral, smile, surprise, blink, talk) or a Face Units target (ARKit names: jawOpen,
    /// mouthSmileLeft, eyeBlinkRight, browInnerUp, ...; data/heads/hm08_targets.txt lists them).
    /// A unit's total over presets and itself is clamped to 1.
    #[arg(long)]
    pub expression: Option<String>,
    /// Face shape of the default head: NAME=WEIGHT,... from MakeHuman's targets (age, weight,
    /// gender, head-oval, nose-hump, chin-width, ...: -1 to 1, or 0 to 1 for one-sided shapes
    /// such as head-oval).
    #[arg(long)]
    pub shape: Option<String>,
}

/// `--lights` values.
#[derive(Clone, Copy, Debug, PartialEq, Eq, clap::ValueEnum)]
pub enum Lights {
    /// Key, fill and rim lights and a soft environment.
    Studio,
    /// One white light from the front left.
    FrontLeft,
    /// One white light from behind.
    Back,
    /// One white light from the camera.
    Front,
    /// No light: only the environment given with --env.
    None,
}

/// `--profile` values.
// clap prints these doc comments as `--help` verbatim: citations stay `[Key]` (`\[Key\]` would show).
#[allow(rustdoc::broken_intra_doc_links)]
#[derive(Clone, Copy, Debug, PartialEq, Eq, clap::ValueEnum)]
pub enum Profile {
    /// Classic dipole ([Jensen2001]).
    Dipole,
    /// Better dipole ([dEon2012]).
    BetterDipole,
    /// Burley's normalized diffusion ([Christensen2015]).
    Burley,
}

/// `--diffuse` values.
#[derive(Clone, Copy, Debug, PartialEq, Eq, clap::ValueEnum)]
pub enum Diffuse {
    /// Lambert: the albedo in every direction.
    Lambert,
    /// The exact transport of an isotropic half-space under the skin's boundary (adding-doubling).
    HalfSpace,
}

impl Profile {
    pub fn model(self) -> ProfileModel {
        match self {
            Profile::Dipole => ProfileModel::ClassicDipole,
            Profile::BetterDipole => ProfileModel::BetterDipole,
            Profile::Burley => ProfileModel::Burley,
        }
    }
}

impl SceneArgs {
    /// The medium the options name, if any.
    pub fn medium(&self) -> Result<Option<Medium>> {
        if let Some(name) = &self.medium {
            // A file's errors name the file already; a built-in name gets the option's name.
            let resolved = Medium::resolve(name);
            let mut m = if name.to_ascii_lowercase().ends_with(".json") {
                resolved?
            } else {
                resolved.with_context(|| format!("--medium {name}"))?
            };
            if let Some(eta) = self.eta {
                m = m.with_eta(eta).with_context(|| format!("--medium {name} --eta {eta}"))?;
            }
            return Ok(Some(m));
        }
        if self.eta.is_some() && (self.sigma_a.is_none() || self.sigma_s.is_none()) {
            bail!("--eta needs --medium, or --sigma-a and --sigma-s");
        }
        match (&self.sigma_a, &self.sigma_s, self.eta) {
            (Some(a), Some(s), Some(eta)) => {
                let three = |v: &[f64], flag: &str| -> Result<[f64; 3]> {
                    v.try_into().map_err(|_| anyhow::anyhow!("{flag}: give three values R,G,B"))
                };
                let m = Medium::from_coefficients("explicit", three(a, "--sigma-a")?, three(s, "--sigma-s")?, eta)
                    .context("--sigma-a/--sigma-s/--eta")?;
                Ok(Some(m))
            }
            _ => Ok(None),
        }
    }

    /// The render job these options describe; the fitted profile when a medium is named.
    pub fn job(&self) -> Result<(RenderJob, Option<FittedProfile>)> {
        self.job_with(false)
    }

    /// [`SceneArgs::job`] as `rouge render` takes it: skin maps on the default head by default
    /// (unless --flat-skin, or the skin's colour comes from --skin, --medium, --sigma-a or
    /// --albedo-map, or the mesh is not the default head).
    ///
    /// # Errors
    /// As [`SceneArgs::job`].
    pub fn render_job(&self) -> Result<(RenderJob, Option<FittedProfile>)> {
        self.job_with(true)
    }

    /// Whether the skin gets maps without --skin-maps: `rouge render` on the default head with no
    /// other source for the skin's colour.
    fn maps_by_default(&self) -> bool {
        let default_head = self.mesh.as_ref().is_none_or(|m| m.to_str() == Some("builtin:head"));
        default_head
            && !self.flat_skin
            && self.skin.is_none()
            && self.medium.is_none()
            && self.sigma_a.is_none()
            && self.albedo_map.is_none()
    }

    fn job_with(&self, maps_by_default: bool) -> Result<(RenderJob, Option<FittedProfile>)> {
        let look = match self.look.as_str() {
            "default" => LookChoice::Default,
            "bare" => LookChoice::Bare,
            path => LookChoice::File(PathBuf::from(path)),
        };
        let rig = match self.lights {
            Lights::Studio => LightRig::Studio,
            Lights::FrontLeft => LightRig::FrontLeft,
            Lights::Back => LightRig::Back,
            Lights::Front => LightRig::Front,
            Lights::None => LightRig::None,
        };
        let mut scene = Scene::rig(rig);
        if self.no_environment {
            scene.environment = None;
        }
        if let Some(path) = &self.skin {
            let skins = read_skins(path, Extrapolation::Constant)?;
            let names = || skins.iter().map(|(n, _)| n.as_str()).collect::<Vec<_>>().join(", ");
            let (_, spectrum) = match &self.skin_sample {
                Some(name) => skins
                    .iter()
                    .find(|(n, _)| n == name)
                    .with_context(|| format!("{}: no skin `{name}` (it has {})", path.display(), names()))?,
                None => skins.first().with_context(|| format!("{}: no skin spectra", path.display()))?,
            };
            scene.skin = Skin { subsurface: scene.skin.subsurface.clone(), ..Skin::from_spectrum(spectrum) };
        }
        let wants_maps =
            self.skin_maps || self.skin_conditions.is_some() || (maps_by_default && self.maps_by_default());
        let maps = wants_maps.then(|| (self.skin_conditions.unwrap_or_default(), self.skin_seed, self.skin_map_px));
        let skin_maps = skin_of_tone(&mut scene, self.skin_tone.as_deref(), maps)
            .with_context(|| format!("--skin-tone {}", self.skin_tone.as_deref().unwrap_or("light")))?;
        let mut fit = None;
        if let Some(medium) = self.medium()? {
            let (skin, fitted) = Skin::from_medium(&medium, self.profile.model());
            scene.skin = skin;
            fit = Some(fitted);
        }
        // Without --diffuse the skin keeps its own law (a medium's is the half-space).
        match self.diffuse {
            Some(Diffuse::HalfSpace) => scene.skin = scene.skin.clone().half_space(),
            Some(Diffuse::Lambert) => scene.skin = scene.skin.clone().lambert(),
            None => {}
        }
        let job = RenderJob {
            mesh: self.mesh.clone(),
            mesh_scale_mm: self.mesh_scale,
            subdivision: self.subdiv,
            look,
            env: self.env.clone(),
            albedo_map: self.albedo_map.clone(),
            skin_detail: skin_maps.is_some() && !self.no_skin_detail,
            skin_maps,
            blood_flow: !self.no_blood_flow,
            normal_map: self.normal_map.clone(),
            width: self.width,
            height: self.height,
            yaw_deg: self.yaw,
            pitch_deg: self.pitch,
            close_up: self.close_up,
            scene,
            morph: self.morph,
            thickness_bake_rest_pose: false,
            face: self.face()?,
            mascara: self.mascara,
            brow_gel: self.brow_gel,
        };
        self.note_regions(&job);
        Ok((job, fit))
    }

    /// Region masks are drawn for the default head's UVs: say so when they land on another mesh.
    fn note_regions(&self, job: &RenderJob) {
        let Some(mesh) = &self.mesh else { return };
        if mesh.to_str() == Some("builtin:head") {
            return;
        }
        let regions = |l: &Look| l.layers.iter().any(|l| matches!(l.thickness, ThicknessSource::Region { .. }));
        let uses_regions = match &job.look {
            LookChoice::Default => true,
            LookChoice::Bare => false,
            LookChoice::File(p) => Look::load(p).is_ok_and(|l| regions(&l)),
            LookChoice::Loaded(l) => regions(l),
        };
        if job.skin_maps.is_some() {
            eprintln!(
                "rouge: note: skin maps follow the default head's anatomy in its UVs; on {} they land wherever \
                 its UVs put them",
                mesh.display()
            );
        }
        if uses_regions {
            eprintln!(
                "rouge: note: the look uses region masks drawn for the default head's UVs; on {} they land \
                 wherever its UVs put them (use thickness maps painted for this mesh, or --look bare)",
                mesh.display()
            );
        }
    }

    /// The expression and face shape the options give (names checked when the job loads).
    pub fn face(&self) -> Result<FacePose> {
        let parse = |spec: &Option<String>, option: &str| match spec {
            Some(s) => FacePose::parse_weights(s, option),
            None => Ok(Default::default()),
        };
        Ok(FacePose { expression: parse(&self.expression, "--expression")?, shape: parse(&self.shape, "--shape")? })
    }

    /// Checks the image size, the camera angles, the mesh scale and the morph.
    pub fn check(&self) -> Result<()> {
        if !(0.0..=1.0).contains(&self.morph) {
            bail!("--morph {}: must be 0 to 1", self.morph);
        }
        // A non-finite or astronomically large angle rendered an empty frame with exit 0.
        for (flag, deg) in [("--yaw", self.yaw), ("--pitch", self.pitch)] {
            if !(deg.is_finite() && deg.abs() <= 3600.0) {
                bail!("{flag} {deg}: must be a finite angle in degrees, -3600 to 3600");
            }
        }
        if !(self.mesh_scale.is_finite() && self.mesh_scale > 0.0) {
            bail!("--mesh-scale {}: must be a finite number of millimetres per unit above 0", self.mesh_scale);
        }
        if self.width == 0 || self.height == 0 || self.width > 16384 || self.height > 16384 {
            bail!("--width {} --height {}: each must be 1-16384 pixels", self.width, self.height);
        }
        Ok(())
    }
}

/// Largest camera angle, degrees either way (ten turns: anything past it is a typo).
const MAX_ANGLE_DEG: f64 = 3600.0;

/// A camera angle in degrees, -3600 to 3600. Read as f64 and checked before it becomes an f32,
/// so the message quotes what was typed (`1e308` was reported as `inf`).
fn parse_angle_deg(s: &str) -> Result<f32, String> {
    let deg: f64 = s.trim().parse().map_err(|e| format!("{s:?} is not a number: {e}"))?;
    if !(deg.is_finite() && deg.abs() <= MAX_ANGLE_DEG) {
        return Err(format!("{s:?} is not a finite angle in degrees, -{MAX_ANGLE_DEG} to {MAX_ANGLE_DEG}"));
    }
    Ok(deg as f32)
}

/// Millimetres per mesh unit: finite, above 0, within f32 (checked as typed, like the angles).
fn parse_mesh_scale(s: &str) -> Result<f32, String> {
    let mm: f64 = s.trim().parse().map_err(|e| format!("{s:?} is not a number: {e}"))?;
    let scale = mm as f32;
    if !(mm.is_finite() && scale.is_finite() && scale > 0.0) {
        return Err(format!("{s:?} is not a finite number of millimetres per unit above 0"));
    }
    Ok(scale)
}

fn parse_region(s: &str) -> Result<rouge_model::skin::AnatomyRegion, String> {
    use rouge_model::skin::AnatomyRegion;
    AnatomyRegion::ALL.into_iter().find(|r| r.name() == s).ok_or_else(|| {
        let names: Vec<_> = AnatomyRegion::ALL.iter().map(|r| r.name()).collect();
        format!("unknown region {s:?}: use one of {}", names.join(", "))
    })
}

fn parse_brow_gel(s: &str) -> Result<rouge_model::mesh::brow_gel::BrowGel, String> {
    rouge_model::mesh::brow_gel::BrowGel::parse(s).map_err(|e| e.to_string())
}

fn parse_mascara(s: &str) -> Result<rouge_model::mesh::lashes::Mascara, String> {
    rouge_model::mesh::lashes::Mascara::parse(s).map_err(|e| e.to_string())
}
