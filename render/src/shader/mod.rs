//! WGSL sources specialised per [`Variant`]: the common declarations, constants injected from
//! their Rust owners, and a pass file with its `//#if FLAG … //#else … //#endif` blocks resolved.
//!
//! The preprocessor is strict, so that a typo cannot silently remove code: an unknown flag, an
//! `//#if` inside another (nesting is not supported), an `//#else` or `//#endif` without an
//! `//#if`, a second `//#else`, an unclosed block and an unknown `//#insert` are all errors that
//! name the file and line.

use crate::error::{RenderError, Result};

/// Most cosmetic layers a look may have (two RGBA16F thickness targets): the look model's limit.
pub const MAX_LAYERS: usize = rouge_model::look::MAX_LAYERS;

/// Which local thickness the thickness translucency reads ([`crate::local_thickness`]).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum ThicknessVariant {
    /// No material uses the thickness model: no target, no pass.
    Off,
    /// The baked map, sampled in the G-buffer pass.
    Baked,
    /// Each light's shadow map, read in the thickness pass.
    ShadowMap,
    /// Each light's shadow map, through the slab law ([`crate::slab_transmittance`]) in place of
    /// the talk's term.
    Slab,
}

/// What a scene and look need compiled.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct Variant {
    /// Number of cosmetic layers, 0..=[`MAX_LAYERS`].
    pub layers: u32,
    /// Some light casts shadows.
    pub shadows: bool,
    /// An environment lights the scene.
    pub env: bool,
    /// Tone-mapped sRGB output (else linear radiance).
    pub display: bool,
    /// The skin albedo comes from a texture.
    pub albedo_map: bool,
    /// A tangent-space normal map perturbs the normals.
    pub normal_map: bool,
    /// The skin's microgeometry perturbs the skin's normals and scales its specular.
    pub skin_detail: bool,
    /// The thickness translucency and its local-thickness source.
    pub thickness: ThicknessVariant,
    /// A dipole model takes over the skin's direct light (the lighting pass leaves it out).
    pub dipole: bool,
    /// The cube atlas takes over the skin's environment light too (only with `dipole`).
    pub atlas: bool,
    /// Some layer has glitter (only with layers): the G-buffer keeps the flake field's UVs and
    /// footprint, the lighting pass adds the flakes' sparkle.
    pub glitter: bool,
    /// The mesh's hairs are drawn as fibres (the hair pass) and composited over the frame.
    pub hair: bool,
}

impl Variant {
    /// The variant with every flag off and no layers.
    pub const BARE: Variant = Variant {
        layers: 0,
        shadows: false,
        env: false,
        display: false,
        albedo_map: false,
        normal_map: false,
        skin_detail: false,
        thickness: ThicknessVariant::Off,
        dipole: false,
        atlas: false,
        glitter: false,
        hair: false,
    };

    /// Every variant, for validating all shader sources: the diffusion models' flags are
    /// (dipole, atlas) ∈ {(off, off), (on, off), (on, on)}; glitter only with layers.
    pub fn all() -> impl Iterator<Item = Variant> {
        let thickness =
            [ThicknessVariant::Off, ThicknessVariant::Baked, ThicknessVariant::ShadowMap, ThicknessVariant::Slab];
        (0..=MAX_LAYERS as u32).flat_map(move |layers| {
            (0..384u32).flat_map(move |bits| {
                thickness.into_iter().map(move |thickness| Variant {
                    layers,
                    shadows: bits & 1 != 0,
                    env: bits & 2 != 0,
                    display: bits & 4 != 0,
                    albedo_map: bits & 8 != 0,
                    normal_map: bits & 16 != 0,
                    skin_detail: bits % 192 >= 96,
                    thickness,
                    dipole: bits % 96 >= 32,
                    atlas: bits % 96 >= 64,
                    glitter: bits >= 192 && layers > 0,
                    // Tied to the shadow bit: the passes that read it (hair, composite) meet
                    // it on and off with every other flag they depend on.
                    hair: bits & 1 != 0,
                })
            })
        })
    }

    /// The `//#if` flags of this variant, with their values.
    fn flags(self, half_linear: bool) -> [(&'static str, bool); 17] {
        [
            ("DIPOLE", self.dipole),
            ("ATLAS", self.atlas),
            ("THICKNESS", self.thickness != ThicknessVariant::Off),
            ("THICKNESS_MAP", self.thickness == ThicknessVariant::Baked),
            ("THICKNESS_LIGHT", matches!(self.thickness, ThicknessVariant::ShadowMap | ThicknessVariant::Slab)),
            ("THICKNESS_SLAB", self.thickness == ThicknessVariant::Slab),
            ("LAYERS_A", self.layers > 0),
            ("LAYERS_B", self.layers > 4),
            ("SHADOWS", self.shadows),
            ("ENV", self.env),
            ("DISPLAY", self.display),
            ("ALBEDO_MAP", self.albedo_map),
            ("NORMAL_MAP", self.normal_map),
            ("SKIN_DETAIL", self.skin_detail),
            ("GLITTER", self.glitter),
            ("HAIR", self.hair),
            ("HALF_LINEAR", half_linear),
        ]
    }
}

/// A pass's shader, declared once in the pass's module: its owner (pipeline and bind-group
/// labels), its WGSL file, and the part of the frame's [`Variant`] its pipelines depend on
/// (passes share pipelines across the rest).
#[derive(Debug)]
pub struct PassShader {
    /// The owner in labels, as `"LightingPass"` (validation errors then name the file).
    pub owner: &'static str,
    /// The WGSL file, relative to render/ (for errors).
    pub file: &'static str,
    /// Its source before preprocessing.
    pub source: &'static str,
    /// The reduction of the frame's variant to what the pass depends on.
    pub reduce: fn(Variant) -> Variant,
}

/// A pass's [`PassShader`]: `pass_shader!(GbufferPass, "gbuffer.wgsl", reduce)` for the file
/// render/src/shaders/gbuffer.wgsl, compiled in.
macro_rules! pass_shader {
    ($owner:ident, $file:literal, $reduce:expr) => {
        $crate::shader::PassShader {
            owner: stringify!($owner),
            file: concat!("shaders/", $file),
            source: include_str!(concat!(env!("CARGO_MANIFEST_DIR"), "/src/shaders/", $file)),
            reduce: $reduce,
        }
    };
}
pub(crate) use pass_shader;

/// The reduction of passes that depend on no flag of the variant.
pub fn bare(_: Variant) -> Variant {
    Variant::BARE
}

/// The WGSL source of `pass` specialised for `variant`, on a device whose linear output is
/// Rgba32Float (`half_linear` false) or Rgba16Float (`half_linear` true: wgpu's GL backend, see
/// [`crate::targets::Formats::linear`]).
///
/// # Errors
/// [`RenderError::Shader`] when the pass file breaks a preprocessor rule.
pub fn shader_source(pass: &PassShader, variant: Variant, half_linear: bool) -> Result<String> {
    let mut out = format!("const LAYERS: u32 = {}u;\n", variant.layers);
    out.push_str(&rouge_measure::layer_table::wgsl_constants());
    out.push_str(&rouge_measure::compositing::CompositingBasis::get().wgsl_constants());
    out.push_str(&crate::specular::wgsl_constants());
    out.push_str(&crate::glitter::wgsl_constants());
    out.push_str(&crate::fibre::wgsl_constants());
    out.push_str(&format!("const PORE_DEPTH_MM: f32 = {:?};\n", rouge_model::skin::detail::PORE_DEPTH_MM));
    out.push_str(include_str!("../shaders/common.wgsl"));
    out.push_str(&preprocess(pass.file, pass.source, &variant.flags(half_linear))?);
    Ok(out)
}

/// Text that `//#insert NAME` puts in place of the line.
fn insertion(name: &str) -> Option<&'static str> {
    match name {
        "sh_eval" => Some(crate::env::WGSL_SH_EVAL),
        "dipole_common" => Some(include_str!("../shaders/dipole_common.wgsl")),
        "diffusion" => Some(include_str!("../shaders/diffusion.wgsl")),
        "shadow_factor" => Some(include_str!("../shaders/shadow_factor.wgsl")),
        "atlas_common" => Some(include_str!("../shaders/atlas_common.wgsl")),
        "skin_pixel" => Some(include_str!("../shaders/skin_pixel.wgsl")),
        "layered_mesh" => Some(include_str!("../shaders/layered_mesh.wgsl")),
        "glitter" => Some(include_str!("../shaders/glitter.wgsl")),
        "coverage" => Some(include_str!("../shaders/coverage.wgsl")),
        "fibre" => Some(crate::fibre::WGSL_SCATTERING),
        "slab" => Some(crate::slab_transmittance::WGSL),
        "through" => Some(include_str!("../shaders/through.wgsl")),
        "slab_edge" => Some(include_str!("../shaders/slab_edge.wgsl")),
        "slab_march" => Some(include_str!("../shaders/slab_march.wgsl")),
        "slab_spread" => Some(include_str!("../shaders/slab_spread.wgsl")),
        _ => None,
    }
}

/// Resolves `//#if FLAG`, `//#else`, `//#endif` and `//#insert NAME` lines of `source` (named
/// `file` in errors) with the values in `flags`.
///
/// # Errors
/// [`RenderError::Shader`] naming `file` and the line for an unknown flag or insertion, a
/// nested `//#if`, an `//#else`/`//#endif` without `//#if`, a second `//#else`, an unclosed
/// block, or any other `//#` directive.
pub fn preprocess(file: &str, source: &str, flags: &[(&str, bool)]) -> Result<String> {
    let fail = |line: usize, message: String| RenderError::Shader(format!("{file}:{line}: {message}"));
    // The open block: (line of its //#if, whether its current branch is kept, seen //#else).
    let mut open: Option<(usize, bool, bool)> = None;
    let mut out = String::with_capacity(source.len());
    for (i, line) in source.lines().enumerate() {
        let number = i + 1;
        let t = line.trim();
        if let Some(directive) = t.strip_prefix("//#") {
            let (word, arg) = directive.split_once(' ').map_or((directive, ""), |(w, a)| (w, a.trim()));
            match word {
                "if" => {
                    if let Some((at, _, _)) = open {
                        return Err(fail(
                            number,
                            format!("nested //#if (the block opened at line {at} is still open)"),
                        ));
                    }
                    let value = flags.iter().find(|(name, _)| *name == arg).map(|(_, on)| *on).ok_or_else(|| {
                        let known: Vec<&str> = flags.iter().map(|(n, _)| *n).collect();
                        fail(number, format!("unknown flag {arg:?} (known: {})", known.join(", ")))
                    })?;
                    open = Some((number, value, false));
                }
                "else" => match open {
                    Some((_, _, true)) => return Err(fail(number, "a second //#else in one block".into())),
                    Some((at, keep, false)) => open = Some((at, !keep, true)),
                    None => return Err(fail(number, "//#else without //#if".into())),
                },
                "endif" => {
                    if open.take().is_none() {
                        return Err(fail(number, "//#endif without //#if".into()));
                    }
                }
                "insert" => {
                    if open.is_none_or(|(_, keep, _)| keep) {
                        let text = insertion(arg).ok_or_else(|| fail(number, format!("unknown insertion {arg:?}")))?;
                        out.push_str(text);
                        out.push('\n');
                    }
                }
                _ => return Err(fail(number, format!("unknown directive //#{word}"))),
            }
            continue;
        }
        if open.is_none_or(|(_, keep, _)| keep) {
            out.push_str(line);
            out.push('\n');
        }
    }
    if let Some((at, _, _)) = open {
        return Err(fail(at, "//#if is never closed with //#endif".into()));
    }
    Ok(out)
}

#[cfg(test)]
mod preprocessor_tests {
    use super::*;

    const FLAGS: [(&str, bool); 2] = [("ON", true), ("OFF", false)];

    fn run(src: &str) -> Result<String> {
        preprocess("test.wgsl", src, &FLAGS)
    }

    #[test]
    fn blocks_keep_the_branch_of_their_flag() {
        let out = run("a\n//#if ON\nb\n//#else\nc\n//#endif\n//#if OFF\nd\n//#else\ne\n//#endif\nf\n").expect("valid");
        assert_eq!(out, "a\nb\ne\nf\n");
    }

    #[test]
    fn an_unknown_flag_is_an_error_naming_the_line() {
        let e = run("a\n//#if LAYRES_A\nb\n//#endif\n").expect_err("typo").to_string();
        assert!(e.contains("test.wgsl:2") && e.contains("LAYRES_A") && e.contains("ON, OFF"), "{e}");
    }

    #[test]
    fn nesting_is_refused() {
        let e = run("//#if ON\n//#if OFF\nx\n//#endif\n//#endif\n").expect_err("nested").to_string();
        assert!(e.contains("test.wgsl:2") && e.contains("nested") && e.contains("line 1"), "{e}");
    }

    #[test]
    fn unbalanced_blocks_are_refused() {
        let stray = run("a\n//#endif\n").expect_err("stray endif").to_string();
        assert!(stray.contains("test.wgsl:2") && stray.contains("without //#if"), "{stray}");
        let stray_else = run("//#else\n").expect_err("stray else").to_string();
        assert!(stray_else.contains("test.wgsl:1"), "{stray_else}");
        let unclosed = run("a\n//#if ON\nb\n").expect_err("unclosed").to_string();
        assert!(unclosed.contains("test.wgsl:2") && unclosed.contains("never closed"), "{unclosed}");
        let twice = run("//#if ON\n//#else\n//#else\n//#endif\n").expect_err("two elses").to_string();
        assert!(twice.contains("test.wgsl:3"), "{twice}");
    }

    #[test]
    fn unknown_directives_and_insertions_are_refused() {
        assert!(run("//#ifdef ON\n").is_err());
        assert!(run("//#insert nothing\n").expect_err("unknown insertion").to_string().contains("nothing"));
        assert!(run("//#insert sh_eval\n").expect("known").contains("fn sh_irradiance"));
        assert!(!run("//#if OFF\n//#insert sh_eval\n//#endif\n").expect("skipped").contains("sh_irradiance"));
    }
}

#[cfg(test)]
mod tests;
