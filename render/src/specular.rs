//! The CPU twin, in double precision, of the specular lobes of shaders/lighting.wgsl: the
//! skin's two lobes and one per cosmetic layer (\[Huang2013\] eq. 5, \[Kelemen2001\]), each a
//! Kelemen/Szirmay-Kalos lobe of `rouge_measure::specular` (re-exported here). Tests check the
//! layering (energy, Fresnel limits, the order in which layers attenuate the lobes below them),
//! and render/tests/specular_gpu.rs checks the shader against it.
//!
//! **Layers.** Bottom to top: lobes = lobes · c_i · T_i² + coverage_i · f_r(layer i), starting
//! from the skin's lobes. Light reaching a lower interface crosses layer i twice (in and out),
//! hence T² where \[Huang2013\] writes T; c_i is the part of that light the layer lets through
//! specularly (its finish's clarity, `rouge_measure::finish`: 1 for a clear film, less for a
//! powder whose fillers scatter it into the diffuse), reached as the layer forms
//! (c = 1 − coverage·(1 − clarity)). A layer's own lobe fades in over its first
//! `LAYER_FULL_COVERAGE_MM` (the renderer's look upload), so a layer of zero thickness adds nothing.
//! A layer with a shimmer ([`ShimmerLobe`]) adds its platelets' lobe, coloured by their
//! interference, to its own.

use glam::DVec3;
pub use rouge_measure::specular::{beckmann, fresnel_f0, kelemen, schlick};

/// The roughness of the skin's two lobes, as multiples of the skin's roughness: a sharper and a
/// broader lobe (\[UnrealSubsurfaceProfile\]'s defaults `Roughness0`, `Roughness1`).
pub const SKIN_LOBE_ROUGHNESS: [f64; 2] = [0.75, 1.30];
/// The weight of the sharper lobe; the broader has the rest (\[UnrealSubsurfaceProfile\]'s
/// `LobeMix`; which lobe its 0.85 weighs is our reading: the sharper, as in \[dEon2007\]'s
/// skin). Both lobes are normalised, so the pair reflects about what one lobe of the same F0
/// would (within 10 % at views up to 45°, 20 % beyond: the Kelemen lobe has no shadowing term).
pub const SKIN_LOBE_MIX: f64 = 0.85;

/// The skin's specular: two Kelemen lobes of roughness `m` × [`SKIN_LOBE_ROUGHNESS`], mixed
/// [`SKIN_LOBE_MIX`] : 1 − [`SKIN_LOBE_MIX`] (skin's sheen has a sharp highlight on a broad
/// glow: the dual-lobe skin specular of current engines and of \[dEon2007\]'s measured skin).
pub fn skin_lobes(n: DVec3, l: DVec3, v: DVec3, m: f64, f0: f64) -> f64 {
    let [m0, m1] = SKIN_LOBE_ROUGHNESS.map(|k| k * m);
    SKIN_LOBE_MIX * kelemen(n, l, v, m0, f0) + (1.0 - SKIN_LOBE_MIX) * kelemen(n, l, v, m1, f0)
}

/// The constants of the skin's lobes for WGSL (injected by `shader::shader_source`).
pub fn wgsl_constants() -> String {
    let [r0, r1] = SKIN_LOBE_ROUGHNESS;
    format!(
        "const SKIN_LOBE_ROUGHNESS: vec2<f32> = vec2<f32>({r0:?}, {r1:?});\nconst SKIN_LOBE_MIX: f32 = {SKIN_LOBE_MIX:?};\n"
    )
}

/// One cosmetic layer's specular parameters at a point, as the lighting pass sees them.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LayerLobe<'a> {
    /// Beckmann roughness of the layer's surface.
    pub roughness: f64,
    /// Schlick F0 of the layer's surface.
    pub f0: f64,
    /// Thickness of the layer here, mm.
    pub thickness_mm: f64,
    /// Thickness at which the layer's lobe is fully formed, mm.
    pub full_coverage_mm: f64,
    /// The layer's transmittance here, linear RGB.
    pub t: [f64; 3],
    /// The part of the lobes below that a fully formed layer passes specularly (its finish's
    /// clarity, in [0, 1]).
    pub clarity: f64,
    /// The layer's shimmer, if any.
    pub shimmer: Option<ShimmerLobe<'a>>,
}

/// A shimmer's lobe as the lighting pass draws it: the platelets' Kelemen lobe of roughness
/// `spread` with Fresnel 1, times their interference colour at cos(h, l) (linear interpolation
/// in `table`, entries at c = i/(n − 1): `rouge_measure::finish::Shimmer::interference_table`),
/// times `strength`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ShimmerLobe<'a> {
    /// Strength (platelet coverage), in [0, 1].
    pub strength: f64,
    /// The platelets' RMS tilt.
    pub spread: f64,
    /// Interference colour by cos(h, l), linear sRGB.
    pub table: &'a [[f64; 3]],
}

impl ShimmerLobe<'_> {
    /// The lobe per channel for light from `l` seen from `v` at normal `n`.
    pub fn eval(&self, n: DVec3, l: DVec3, v: DVec3) -> [f64; 3] {
        let h = l + v;
        let c = if h.length_squared() > 1e-8 { h.normalize().dot(l).clamp(0.0, 1.0) } else { 0.0 };
        let last = self.table.len().saturating_sub(1);
        let f = c * last as f64;
        let i = (f as usize).min(last.saturating_sub(1));
        let w = f - i as f64;
        let lobe = self.strength * kelemen(n, l, v, self.spread, 1.0);
        std::array::from_fn(|k| {
            let (a, b) = (self.table.get(i).map_or(0.0, |t| t[k]), self.table.get(i + 1).map_or(0.0, |t| t[k]));
            lobe * (a + (b - a) * w)
        })
    }
}

/// The summed lobes of the skin (`skin` = roughness, F0: its two lobes, [`skin_lobes`]) under
/// `layers` (bottom to top), per RGB channel, for light from `l` seen from `v` at normal `n`:
/// what lighting.wgsl multiplies by the irradiance E·(n·l).
pub fn layered_lobes(n: DVec3, l: DVec3, v: DVec3, skin: (f64, f64), layers: &[LayerLobe]) -> [f64; 3] {
    let mut lobes = [skin_lobes(n, l, v, skin.0, skin.1); 3];
    for layer in layers {
        let coverage = (layer.thickness_mm / layer.full_coverage_mm).clamp(0.0, 1.0);
        let own = coverage * kelemen(n, l, v, layer.roughness, layer.f0);
        let shimmer = layer.shimmer.map_or([0.0; 3], |s| s.eval(n, l, v));
        let through = 1.0 - coverage * (1.0 - layer.clarity);
        for (c, lobe) in lobes.iter_mut().enumerate() {
            *lobe = *lobe * through * layer.t[c] * layer.t[c] + own + coverage * shimmer[c];
        }
    }
    lobes
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::f64::consts::PI;

    fn dir(theta: f64, phi: f64) -> DVec3 {
        DVec3::new(theta.sin() * phi.cos(), theta.sin() * phi.sin(), theta.cos())
    }

    #[test]
    fn layers_attenuate_the_lobes_below_them_twice() {
        let (n, l, v) = (DVec3::Z, dir(0.4, 0.0), dir(0.3, PI));
        let skin = skin_lobes(n, l, v, 0.35, 0.028);
        let layer = |thickness_mm, t| LayerLobe {
            roughness: 0.15,
            f0: 0.04,
            thickness_mm,
            full_coverage_mm: 0.002,
            t,
            clarity: 1.0,
            shimmer: None,
        };
        // A zero-thickness layer with T = 1 changes nothing.
        assert_eq!(layered_lobes(n, l, v, (0.35, 0.028), &[layer(0.0, [1.0; 3])]), [skin; 3]);
        // T = 0.5 scales the skin's lobe by 0.25 (in and out) and adds the layer's own lobe.
        let top = kelemen(n, l, v, 0.15, 0.04);
        let got = layered_lobes(n, l, v, (0.35, 0.028), &[layer(0.01, [0.5, 0.5, 0.5])]);
        assert!((got[0] - (0.25 * skin + top)).abs() < 1e-12);
        // Order: the top layer's lobe is not attenuated; the lower one is, by the top's T².
        let lower = LayerLobe { roughness: 0.5, ..layer(0.01, [1.0; 3]) };
        let upper = layer(0.01, [0.5, 1.0, 0.0]);
        let got = layered_lobes(n, l, v, (0.35, 0.028), &[lower, upper]);
        let below = skin + kelemen(n, l, v, 0.5, 0.04);
        for (c, t) in [0.5, 1.0, 0.0].into_iter().enumerate() {
            assert!((got[c] - (below * t * t + top)).abs() < 1e-12, "channel {c}");
        }
        // Half coverage: a 1 µm film has half its lobe.
        let half = layered_lobes(n, l, v, (0.35, 0.028), &[layer(0.001, [1.0; 3])]);
        assert!((half[0] - (skin + 0.5 * top)).abs() < 1e-12);
        // A powder of clarity 0.2 passes a fifth of the light below specularly once formed, and
        // all of it at zero thickness; halfway formed, 1 − 0.5 · 0.8 = 0.6.
        let powder = |thickness_mm| LayerLobe { clarity: 0.2, ..layer(thickness_mm, [1.0; 3]) };
        let own = |c: f64| c * top;
        for (thickness_mm, through, coverage) in [(0.0, 1.0, 0.0), (0.001, 0.6, 0.5), (0.01, 0.2, 1.0)] {
            let got = layered_lobes(n, l, v, (0.35, 0.028), &[powder(thickness_mm)]);
            assert!((got[0] - (skin * through + own(coverage))).abs() < 1e-12, "{thickness_mm} mm");
        }
    }

    fn albedo_of(f: impl Fn(DVec3) -> f64) -> f64 {
        rouge_measure::specular::hemisphere_integral(f, 400)
    }

    #[test]
    fn the_skins_two_lobes_keep_energy_and_fresnel_limits() {
        let n = DVec3::Z;
        for m in [0.2, 0.35, 0.5] {
            for view_deg in [0.0, 45.0, 75.0] {
                let v = dir(f64::to_radians(view_deg), 0.0);
                // With F = 1 no more leaves than arrives, and the pair is the mix of the two lobes.
                let pair = albedo_of(|l| skin_lobes(n, l, v, m, 1.0));
                let [a0, a1] = SKIN_LOBE_ROUGHNESS.map(|k| albedo_of(|l| kelemen(n, l, v, k * m, 1.0)));
                assert!(pair <= 1.0 + 1e-3, "m {m}, view {view_deg}°: {pair}");
                assert!((pair - (SKIN_LOBE_MIX * a0 + (1.0 - SKIN_LOBE_MIX) * a1)).abs() < 1e-9);
                // Skin's F0 reflects a few per cent, about as one lobe does (the Kelemen lobe has no
                // shadowing term, so broader lobes reflect a little more at grazing views).
                let skin = albedo_of(|l| skin_lobes(n, l, v, m, 0.028));
                let one = albedo_of(|l| kelemen(n, l, v, m, 0.028));
                let tolerance = if view_deg <= 45.0 { 0.1 } else { 0.2 };
                assert!(skin > 0.0 && (skin / one - 1.0).abs() < tolerance, "m {m}, {view_deg}°: {skin} vs {one}");
            }
        }
        // The sharper lobe raises the peak above one lobe's and the broader widens the tail.
        let (l, v) = (dir(0.3, 0.0), dir(0.3, PI));
        assert!(skin_lobes(n, l, v, 0.35, 0.028) > kelemen(n, l, v, 0.35, 0.028));
        let (l, v) = (dir(0.9, 0.0), dir(0.2, PI));
        assert!(skin_lobes(n, l, v, 0.35, 0.028) > 0.0);
        // Mirror direction at grazing incidence: Fresnel tends to 1 in both lobes.
        let theta = f64::to_radians(89.9);
        let (l, v) = (dir(theta, 0.0), dir(theta, PI));
        let f = skin_lobes(n, l, v, 0.35, 0.028) * 2.0 * (1.0 + l.dot(v));
        let d = SKIN_LOBE_MIX * beckmann(1.0, 0.75 * 0.35) + (1.0 - SKIN_LOBE_MIX) * beckmann(1.0, 1.3 * 0.35);
        assert!((f / d - schlick(0.028, theta.cos())).abs() < 1e-9);
    }
}
