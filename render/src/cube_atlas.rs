//! Translucency through an on-the-fly cube-map atlas (\[Benmounah2009\], paper 000): the geometry
//! of the atlas and the CPU twins of the choices its shaders make (shaders/atlas_irradiance.wgsl,
//! shaders/atlas_gather.wgsl), its settings, and the atlas read back ([`AtlasImage`]).
//!
//! Every frame the mesh is drawn orthographically onto the six faces of its bounding cube (an
//! array texture of six layers; seven on GL, [`crate::targets::array_layers`]), storing the irradiance E(x) that enters the medium (eq. 4: lights
//! with their shadows and the environment's SH, each through the Fresnel transmittance), n·p in
//! alpha (section 4.3.1), the normal and the depth. A full-screen pass then picks, per skin pixel,
//! the face that sees the point best and gathers E·R_d over a kernel of taps there (local
//! scattering, section 4.3), and adds light through thin parts from the opposite face (global
//! scattering, section 4.4). Nothing is precomputed, so the mesh may deform freely.
//!
//! # The formulas, derived (and where the paper's print differs)
//! - **Table 1** is \[Jensen2001\]'s dipole. Two slips: `z_v = z_r(1 + 4AD)` mixes a length with a
//!   number (D is in mm); Jensen's height of the virtual source is `z_v = z_r + 4AD = z_r(1 + 4A/3)`
//!   since D = z_r/3. And `x_v = x_i − z_v N_i` puts the virtual source on the real one's side; the
//!   boundary condition puts it above the surface, `x_v = x_i + z_v N_i` (on a plane both give the
//!   same distance, on a curved surface they do not). F_dr, A, D, σ_tr, α′ are as printed. Home:
//!   [`crate::diffusion::ChannelProfile::classic_between`] (derivation of the terms in
//!   `crate::diffusion`).
//! - **Eq. 8** (environment irradiance as a product of SH coefficients) is wrong; the zonal form
//!   is exact: [`crate::env::ShIrradiance::fresnel_transmitted`].
//! - **Eq. 9-10** (global term). Eq. 10 writes `B(x) = E(x) R_d(x_s; x)`: R_d where eq. 9 defines
//!   R_g, E at x rather than at the source x_s, and no area, so B would be in W/m² per mm². We
//!   read the section as the paper describes it, "no convolution": the lit surface behind a thin
//!   part, at x_s on the opposite face of the atlas, is a plane of real sources (eq. 9) at depth
//!   z_r under it, with irradiance E(x_s) locally uniform. Integrated over that plane eq. 9 gives
//!   (∫ z(1 + σS)e^{−σS}/S³ dA = 2π e^{−σz}, see `crate::diffusion`)
//!   `B_g(x) = E(x_s) · α′/2 · e^{−σ_tr S}` with S = |x_s − z_r n_s − x|:
//!   [`crate::diffusion::ChannelProfile::real_source_plane`], [`GlobalTerm::RealSource`]. It
//!   ignores both faces' boundary conditions and reads the backlit wedges twice as bright as the
//!   path tracer; the default, [`GlobalTerm::Slab`], takes instead the diffusion transmittance of
//!   a slab of the local thickness d = n·(x − x_s) with the same constants (extrapolated
//!   boundaries on both faces, [`crate::diffusion::ChannelProfile::slab_transmittance`]):
//!   `B_g = E(x_s)·T(d)`, still one sample, no convolution (docs/BENCHMARKS.md measures both).
//! - **Kernel** (section 4.3.2). The paper takes the mean free path l_d = 1/σ′_t as "the maximum
//!   distance a photon travels" and the kernel's radius, shrunk by the scalar product sp of the
//!   normal with the face: k = sp·l_d; it settles on a 5×5 kernel. We keep the radius physical,
//!   R = sp·R₁, and the kernel a grid of `kernel_max`² taps spread over the square [−R, R]², so
//!   that the reach does not change with the atlas's resolution. R₁ is [`Reach`]: the paper's
//!   l_d (`MeanFreePaths(1.0)`, the longest of the three channels), or by default the profile's
//!   support, three decay lengths 1/σ_tr (capped at 40 mean free paths,
//!   [`crate::diffusion::ChannelProfile::support_mm`]). Diffusion reaches much further than a
//!   mean free path: on marble the paper's reach holds a fifth of R_d (docs/BENCHMARKS.md).
//! - **Local gather.** B(x) = Σ_j E_j R_d(x_j → x) A_j over the taps j: cells of side Δ = 2R/k
//!   centred on x's place in the face, x_j the tap's point on the stored surface (its lateral
//!   position and the texel's depth), A_j = Δ²/(n_j·a) the surface a cell covers (n_j·a clamped at
//!   [`MIN_AREA_COSINE`]). The centre cell's R_d is singular-ish (≈ α′/4πz_r² at r = 0): it is
//!   integrated over the disk of the cell's area in closed form
//!   ([`crate::diffusion::ChannelProfile::classic_disk_total`]), so a flat, evenly lit surface
//!   gets the same radiosity from any kernel, and a coarse one never over-counts the centre.
//!   Each tap is weighted by max(0, n_j·n), 1 on flat skin: the dipole's plane breaks where the
//!   entry surface turns away from the exit (a closed mouth's slit, an eyelid's rim lit up
//!   without it, docs/BENCHMARKS.md).
//! - **Output**: L_o = F_t(η, ω_o)/π · (B_local + B_global) (eq. 2), added to the skin's diffuse
//!   radiance; the lighting pass leaves the skin's direct and environment light to the atlas.
//!
//! # Face selection and self-occlusion (section 4.2-4.3.1)
//! The chosen faces are those with a corner above the fragment's tangent plane, sorted by
//! sp = n·a, the greatest first (faces with sp ≤ 0 see the back of the point and are dropped).
//! The point is on a face when the texel it projects to holds it and not an occluder:
//! - [`OcclusionTest::PlaneOffset`], the paper's: the stored n′·p′ (p relative to the cube's
//!   centre) against the fragment's n·p. It is fragile: a texel's centre is up to half a texel
//!   from the fragment, and on a curved surface (curvature κ) n′ − n ≈ κδ, so n′·p′ − n·p ≈ κδ|p|,
//!   a millimetre at the scale of a head, the size of what it should tell apart.
//! - [`OcclusionTest::TangentPlane`] (the default): the stored point p′ (from the atlas depth)
//!   against the fragment's tangent plane, |n·(p′ − p)| < tolerance, and the stored normal within
//!   45° of the fragment's. On the same surface p′ − p is tangent, so the difference is second
//!   order (κδ²/2); an occluder is off the plane, or, where it meets the surface edge-on (a
//!   closed mouth's slit, an eyelid's rim), turned away from it.
//! - [`OcclusionTest::Off`]: the best face, always (the paper's ablation).
//!
//! Domain: a closed or open triangle mesh of any size (mm); media as [`crate::diffusion`].
//! Points on no face get no local term, as in the paper; they still get the global one.

use crate::diffusion::ChannelProfile;
use crate::error::{RenderError, Result};
use glam::{Mat4, Vec2, Vec3, Vec4};
use rouge_model::mesh::Bounds;

/// Below this n·a a texel's surface area is taken as texel²/[`MIN_AREA_COSINE`] (a face that
/// sees the surface edge-on would otherwise give it an unbounded area).
pub const MIN_AREA_COSINE: f32 = 0.2;

/// The tangent-plane test wants the stored normal within 45° of the point's.
pub const MAX_NORMAL_ANGLE_COS: f32 = std::f32::consts::FRAC_1_SQRT_2;

/// How a point is found on a face (module doc).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum OcclusionTest {
    /// No test: the face most aligned with the normal.
    Off,
    /// \[Benmounah2009\] section 4.3.1: the stored n·p against the fragment's.
    PlaneOffset,
    /// The stored point against the fragment's tangent plane.
    TangentPlane,
}

impl OcclusionTest {
    /// Every test, in the order of the benchmark's ablation.
    pub const ALL: [OcclusionTest; 3] = [OcclusionTest::Off, OcclusionTest::PlaneOffset, OcclusionTest::TangentPlane];

    /// The command-line name.
    pub fn name(self) -> &'static str {
        match self {
            OcclusionTest::Off => "off",
            OcclusionTest::PlaneOffset => "plane-offset",
            OcclusionTest::TangentPlane => "tangent-plane",
        }
    }

    /// The test named `name`.
    ///
    /// # Errors
    /// [`RenderError::Invalid`] listing the names.
    pub fn parse(name: &str) -> Result<OcclusionTest> {
        Self::ALL.into_iter().find(|t| t.name() == name).ok_or_else(|| {
            RenderError::Invalid(format!(
                "unknown self-occlusion test {name:?} (known: {})",
                Self::ALL.map(Self::name).join(", ")
            ))
        })
    }

    /// The shader's code for the test.
    pub fn code(self) -> u32 {
        self as u32
    }
}

/// The settings of the cube-atlas model.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct AtlasSettings {
    /// Side of each of the six faces, texels.
    pub atlas_px: u32,
    /// Taps per side of the kernel (odd, 1 to 63; the paper settles on 5).
    pub kernel_max: u32,
    /// The kernel's radius at sp = 1.
    pub reach: Reach,
    /// Shrink the kernel by the scalar product of the normal with the face (section 4.3.2).
    pub adaptive: bool,
    /// How a point is found on a face.
    pub occlusion: OcclusionTest,
    /// The global term (section 4.4): light through thin parts from the surface behind.
    pub global: GlobalTerm,
}

impl Default for AtlasSettings {
    fn default() -> Self {
        AtlasSettings {
            atlas_px: 512,
            kernel_max: 5,
            reach: Reach::Support,
            adaptive: true,
            occlusion: OcclusionTest::TangentPlane,
            global: GlobalTerm::Slab,
        }
    }
}

impl AtlasSettings {
    /// Checks the ranges.
    ///
    /// # Errors
    /// [`RenderError::Invalid`] naming the setting.
    pub fn check(&self) -> Result<()> {
        if !(16..=4096).contains(&self.atlas_px) {
            return Err(RenderError::Invalid(format!("cube atlas size {}: 16 to 4096 texels", self.atlas_px)));
        }
        if self.kernel_max.is_multiple_of(2) || !(1..=63).contains(&self.kernel_max) {
            return Err(RenderError::Invalid(format!(
                "cube atlas kernel {}: an odd number of taps a side from 1 to 63",
                self.kernel_max
            )));
        }
        if let Reach::MeanFreePaths(m) = self.reach
            && !(m.is_finite() && m > 0.0 && m <= 1000.0)
        {
            return Err(RenderError::Invalid(format!("cube atlas reach {m} mean free paths: must be in (0, 1000]")));
        }
        Ok(())
    }

    /// The kernel's radius R in mm for a face at scalar product `sp` with the normal, for the
    /// channels' `profiles` (classic dipole).
    pub fn kernel_radius_mm(&self, sp: f32, profiles: &[ChannelProfile]) -> f32 {
        let longest = |f: fn(&ChannelProfile) -> f64| profiles.iter().map(f).fold(0.0, f64::max) as f32;
        let full = match self.reach {
            Reach::Support => longest(ChannelProfile::support_mm),
            Reach::MeanFreePaths(m) => m * longest(ChannelProfile::mean_free_path_mm),
        };
        if self.adaptive { sp.clamp(0.0, 1.0) * full } else { full }
    }
}

/// The global term's transmission through a thin part (module doc).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum GlobalTerm {
    /// No global term.
    Off,
    /// \[Benmounah2009\] eq. 9: the real source alone, integrated over the lit surface behind.
    RealSource,
    /// The diffusion transmittance of a slab of the local thickness, both faces' boundary
    /// conditions ([`crate::diffusion::ChannelProfile::slab_transmittance`]).
    Slab,
}

impl GlobalTerm {
    /// Every choice, in the order of the benchmark's ablation.
    pub const ALL: [GlobalTerm; 3] = [GlobalTerm::Off, GlobalTerm::RealSource, GlobalTerm::Slab];

    /// The command-line name.
    pub fn name(self) -> &'static str {
        match self {
            GlobalTerm::Off => "off",
            GlobalTerm::RealSource => "real-source",
            GlobalTerm::Slab => "slab",
        }
    }

    /// The choice named `name`.
    ///
    /// # Errors
    /// [`RenderError::Invalid`] listing the names.
    pub fn parse(name: &str) -> Result<GlobalTerm> {
        Self::ALL.into_iter().find(|t| t.name() == name).ok_or_else(|| {
            RenderError::Invalid(format!(
                "unknown global term {name:?} (known: {})",
                Self::ALL.map(Self::name).join(", ")
            ))
        })
    }
}

/// How far the gather kernel reaches (at sp = 1).
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Reach {
    /// The diffusion profile's support: three decay lengths 1/σ_tr, at most 40 mean free paths.
    Support,
    /// This many mean free paths 1/σ′_t (\[Benmounah2009\] section 4.3.2 uses 1).
    MeanFreePaths(f32),
}

impl Reach {
    /// `support` or the number of mean free paths (the command line's and the tables' name).
    pub fn name(self) -> String {
        match self {
            Reach::Support => "support".into(),
            Reach::MeanFreePaths(m) => format!("{m} mfp"),
        }
    }

    /// `support` or a number of mean free paths.
    ///
    /// # Errors
    /// [`RenderError::Invalid`] saying what is accepted.
    pub fn parse(text: &str) -> Result<Reach> {
        if text == "support" {
            return Ok(Reach::Support);
        }
        let m: f32 = text.trim_end_matches("mfp").trim().parse().map_err(|_| {
            RenderError::Invalid(format!("cube atlas reach {text:?}: 'support' or a number of mean free paths"))
        })?;
        Ok(Reach::MeanFreePaths(m))
    }
}

/// The bounding cube of a mesh and its six orthographic faces.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct AtlasFrame {
    /// Centre of the cube, mm.
    pub centre: Vec3,
    /// Half its side, mm.
    pub half_mm: f32,
    /// Face side, texels.
    pub px: u32,
}

/// Face `f`'s outward axis a, and the image's right (U) and up (V) directions, U × V = a:
/// +X, −X, +Y, −Y, +Z, −Z.
pub fn face_axes(f: usize) -> (Vec3, Vec3, Vec3) {
    match f {
        0 => (Vec3::X, Vec3::NEG_Z, Vec3::Y),
        1 => (Vec3::NEG_X, Vec3::Z, Vec3::Y),
        2 => (Vec3::Y, Vec3::X, Vec3::NEG_Z),
        3 => (Vec3::NEG_Y, Vec3::X, Vec3::Z),
        4 => (Vec3::Z, Vec3::X, Vec3::Y),
        _ => (Vec3::NEG_Z, Vec3::NEG_X, Vec3::Y),
    }
}

/// The face opposite face `f`.
pub fn opposite(f: usize) -> usize {
    f ^ 1
}

impl AtlasFrame {
    /// The cube around `bounds` (its largest extent, 2% and two texels of margin so that no
    /// surface touches a face), `px` texels a side.
    pub fn new(bounds: &Bounds, px: u32) -> AtlasFrame {
        let extent = bounds.size().max_element().max(1e-3);
        let half = 0.5 * extent * 1.02;
        let half_mm = half * (1.0 + 4.0 / px.max(4) as f32);
        AtlasFrame { centre: bounds.center(), half_mm, px }
    }

    /// Side of a texel, mm.
    pub fn texel_mm(&self) -> f32 {
        2.0 * self.half_mm / self.px as f32
    }

    /// World → clip of face `f`: x = U·(p − c)/h, y = V·(p − c)/h, depth (h − a·(p − c))/2h, so
    /// the face's own side is near (0) and the far side of the cube far (1).
    pub fn view_proj(&self, f: usize) -> Mat4 {
        let (a, u, v) = face_axes(f);
        let (c, h) = (self.centre, self.half_mm);
        Mat4::from_cols(
            Vec4::new(u.x / h, v.x / h, -a.x / (2.0 * h), 0.0),
            Vec4::new(u.y / h, v.y / h, -a.y / (2.0 * h), 0.0),
            Vec4::new(u.z / h, v.z / h, -a.z / (2.0 * h), 0.0),
            Vec4::new(-u.dot(c) / h, -v.dot(c) / h, (h + a.dot(c)) / (2.0 * h), 1.0),
        )
    }

    /// Where `p` falls on face `f`: continuous texel coordinates (x right, y down; texel (i, j)
    /// covers [i, i+1] × [j, j+1]) and the [0, 1] depth.
    pub fn project(&self, f: usize, p: Vec3) -> (Vec2, f32) {
        let (a, u, v) = face_axes(f);
        let d = p - self.centre;
        let n = self.px as f32;
        let s = Vec2::new((u.dot(d) / self.half_mm * 0.5 + 0.5) * n, (0.5 - v.dot(d) / self.half_mm * 0.5) * n);
        (s, (self.half_mm - a.dot(d)) / (2.0 * self.half_mm))
    }

    /// The world point at continuous texel coordinates `t` and depth `z` of face `f`.
    pub fn unproject(&self, f: usize, t: Vec2, z: f32) -> Vec3 {
        let (a, u, v) = face_axes(f);
        let n = self.px as f32;
        let s = 2.0 * t.x / n - 1.0;
        let q = 1.0 - 2.0 * t.y / n;
        let h = self.half_mm;
        self.centre + u * (h * s) + v * (h * q) + a * (h - 2.0 * h * z)
    }

    /// The faces that may hold point `x` with normal `n`: a corner of the face above the tangent
    /// plane and sp = n·a > 0, greatest sp first (\[Benmounah2009\] section 4.2, figure 3).
    pub fn chosen_faces(&self, x: Vec3, n: Vec3) -> Vec<(usize, f32)> {
        let mut out: Vec<(usize, f32)> = (0..6)
            .filter_map(|f| {
                let (a, u, v) = face_axes(f);
                let sp = n.dot(a);
                let h = self.half_mm;
                let above = [(-1.0, -1.0), (-1.0, 1.0), (1.0, -1.0), (1.0, 1.0)]
                    .iter()
                    .any(|&(i, j)| n.dot(self.centre + (a + u * i + v * j) * h - x) > 0.0);
                (sp > 0.0 && above).then_some((f, sp))
            })
            .collect();
        out.sort_by(|a, b| b.1.total_cmp(&a.1));
        out
    }

    /// Whether the texel of face `f` that `x` (normal `n`) projects to holds `x` itself, given
    /// what the atlas stored there: the point `stored`, its normal `stored_normal` and its
    /// n′·(p′ − c) `stored_plane_mm`. Tolerances: half a texel for the tangent plane, two texels
    /// for the paper's n·p. The tangent-plane test also wants the normals within
    /// [`MAX_NORMAL_ANGLE_COS`]: where a fold meets the surface edge-on (the inner lip at a closed
    /// mouth's slit, an eyelid's rim) the occluder's point can lie in the tangent plane too.
    pub fn holds(
        &self,
        test: OcclusionTest,
        x: Vec3,
        n: Vec3,
        stored: Vec3,
        stored_normal: Vec3,
        stored_plane_mm: f32,
    ) -> bool {
        let texel = self.texel_mm();
        match test {
            OcclusionTest::Off => true,
            OcclusionTest::PlaneOffset => (stored_plane_mm - n.dot(x - self.centre)).abs() < 2.0 * texel,
            OcclusionTest::TangentPlane => {
                n.dot(stored - x).abs() < 0.5 * texel + 0.01 && n.dot(stored_normal) > MAX_NORMAL_ANGLE_COS
            }
        }
    }
}

/// The atlas read back to the CPU (tests, inspection): per face, row-major texels.
#[derive(Clone, Debug)]
pub struct AtlasImage {
    /// The cube.
    pub frame: AtlasFrame,
    /// Per face: irradiance (rgb) and n·(p − c) (a).
    pub irradiance: Vec<Vec<[f32; 4]>>,
    /// Per face: normal (xyz) and medium flag (w).
    pub normals: Vec<Vec<[f32; 4]>>,
    /// Per face: [0, 1] depth (1 where nothing was drawn).
    pub depths: Vec<Vec<f32>>,
}

impl AtlasImage {
    /// The point stored at texel (`x`, `y`) of face `f` and its n·p, or `None` where nothing is.
    pub fn stored(&self, f: usize, x: u32, y: u32) -> Option<(glam::Vec3, f32)> {
        let i = (y * self.frame.px + x) as usize;
        let z = *self.depths[f].get(i)?;
        (z < 1.0).then(|| {
            let t = glam::Vec2::new(x as f32 + 0.5, y as f32 + 0.5);
            (self.frame.unproject(f, t, z), self.irradiance[f][i][3])
        })
    }

    /// Whether face `f` holds point `x` (normal `n`) under `test` ([`AtlasFrame::holds`] on what
    /// the atlas stored at the texel `x` projects to).
    pub fn holds(&self, f: usize, test: OcclusionTest, x: glam::Vec3, n: glam::Vec3) -> bool {
        let (t, _) = self.frame.project(f, x);
        let px = self.frame.px as f32;
        if t.x < 0.0 || t.y < 0.0 || t.x >= px || t.y >= px {
            return false;
        }
        let i = (t.y as u32 * self.frame.px + t.x as u32) as usize;
        let normal = glam::Vec4::from_array(self.normals[f][i]).truncate();
        match self.stored(f, t.x as u32, t.y as u32) {
            Some((p, plane)) => self.frame.holds(test, x, n, p, normal, plane),
            None => false,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn frame() -> AtlasFrame {
        let b = Bounds { min: Vec3::new(-40.0, -10.0, 5.0), max: Vec3::new(60.0, 30.0, 25.0) };
        AtlasFrame::new(&b, 256)
    }

    #[test]
    fn faces_are_right_handed_and_project_back() {
        let fr = frame();
        for f in 0..6 {
            let (a, u, v) = face_axes(f);
            assert!((u.cross(v) - a).length() < 1e-6, "face {f}");
            assert_eq!(face_axes(opposite(f)).0, -a);
            for p in [Vec3::new(1.0, 2.0, 3.0), Vec3::new(-35.0, 25.0, 20.0), Vec3::new(55.0, -5.0, 6.0)] {
                let (t, z) = fr.project(f, p);
                assert!((0.0..=1.0).contains(&z));
                assert!((fr.unproject(f, t, z) - p).length() < 1e-3, "face {f} {p}");
                let clip = fr.view_proj(f) * p.extend(1.0);
                let n = fr.px as f32;
                let from_clip = Vec2::new((clip.x * 0.5 + 0.5) * n, (0.5 - clip.y * 0.5) * n);
                assert!((from_clip - t).length() < 1e-3 && (clip.z - z).abs() < 1e-6, "face {f}");
            }
        }
    }

    #[test]
    fn the_near_side_is_near() {
        let fr = frame();
        let (_, near) = fr.project(0, Vec3::new(50.0, 0.0, 10.0));
        let (_, far) = fr.project(0, Vec3::new(-30.0, 0.0, 10.0));
        assert!(near < far);
    }

    #[test]
    fn kernels_shrink_with_the_scalar_product() {
        let p = [ChannelProfile::new(crate::diffusion::ProfileModel::ClassicDipole, 0.5, 1.5, 1.3); 3];
        let s = AtlasSettings { kernel_max: 9, reach: Reach::MeanFreePaths(2.0), ..Default::default() };
        assert!((s.kernel_radius_mm(1.0, &p) - 1.0).abs() < 1e-6);
        assert!((s.kernel_radius_mm(0.5, &p) - 0.5).abs() < 1e-6);
        assert!((AtlasSettings { adaptive: false, ..s }.kernel_radius_mm(0.1, &p) - 1.0).abs() < 1e-6);
        let support = AtlasSettings { reach: Reach::Support, ..s }.kernel_radius_mm(1.0, &p);
        assert!((f64::from(support) - p[0].support_mm()).abs() < 1e-5);
        assert!(AtlasSettings { kernel_max: 4, ..s }.check().is_err());
        assert!(AtlasSettings { atlas_px: 8, ..s }.check().is_err());
        for m in [0.0, -1.0, f32::NAN, f32::INFINITY] {
            assert!(AtlasSettings { reach: Reach::MeanFreePaths(m), ..s }.check().is_err(), "reach {m}");
        }
        assert_eq!(Reach::parse("support").expect("support"), Reach::Support);
        assert_eq!(Reach::parse("4").expect("4"), Reach::MeanFreePaths(4.0));
        assert!(Reach::parse("far").expect_err("words").to_string().contains("mean free paths"));
        assert!(OcclusionTest::parse("tangent").is_err());
        assert_eq!(OcclusionTest::parse("plane-offset").expect("known"), OcclusionTest::PlaneOffset);
    }
}
