//! How much of the slab law's lit plane is there: the lit extent that scales the slab law
//! ([`crate::slab_transmittance`]) where the part the light crosses is narrower than the light
//! spreads in it (issue 31 item 4; docs/BENCHMARKS.md "The slab's lit extent").
//!
//! The slab law lights a pixel as a plane slab would: lit over its whole far face, the light
//! that reaches the exit point entered within a few diffusion lengths of it on every side. A
//! finger 9 mm wide, lit from behind, is a slab only along its length: across it, the light that
//! would have entered beyond its sides is not there. The law over-lit the fingers' middles 1.5-2×
//! (issue 31, the backlit hand).
//!
//! The light reaching the exit point through a slab comes from entry points spread across the
//! plane at right angles to the light with a density p(ρ) about the point's own column. Diffusion
//! between the slab's two extrapolated boundaries, L = d + 2z_b apart (z_b = 2D = 2/(3σt′) at an
//! index-matched boundary), carries a lateral offset ρ with the slowest decay
//! e^{−qρ}, q = √(σ² + (π/L)²) (the slab's fundamental mode: \[Contini1997\] §2, the lateral
//! Fourier component k decays through the depth as √(σ² + k²) and the boundaries add (π/L)²), σ
//! the medium's decay rate with depth (Case's κ·σt′, [`crate::slab_transmittance::kappa`], as the
//! law's table takes out). Rouge takes the whole spread with that decay,
//!
//! ```text
//! p(ρ) dA = q²/(2π) · e^{−qρ} dA      (∫ p dA = 1, mean radius 2/q)
//! ```
//!
//! and counts the share of it where the light's shadow map sees the mesh: the lit extent
//! f = ∫ p(ρ) · [the map's column at ρ holds the mesh] dA, 1 on a plane and ½ on a half-plane
//! ([`lit_extent`]). The radiance is the slab law's × f per channel; σ differs per channel, so
//! red (which spreads furthest) loses most on a thin finger.
//!
//! Domain and limits: directional lights (a point light's perspective map has no constant texel
//! size, and its plane counts as whole, f = 1); the column's test is the shadow map's (anything
//! on the light's ray counts, whether the light enters there before or after the exit plane);
//! the kernel is the far field's (the near field, within ~L of the column, is more peaked: f is
//! then a lower bound at an edge).
//! Light entering a face beside the exit face (a wedge's top face near its front edge) is the
//! law's own limit, not this module's: there f still removes what lies beyond the silhouette.
//!
//!
//! The plane also has no sides. Where the exit face meets a side face beyond which the medium
//! ends (a wedge's front and bottom faces), the slab's light leaves through it: [`side_drain`]
//! takes the fundamental mode's image across that face's extrapolated boundary, 1 − e^{−q(a + z_b)}
//! at a distance a from the edge, for a side face the light does not reach (shaders/slab_edge.wgsl
//! finds the edge in the G-buffer).
//!
//! **Each column its own slab** ([`spread_light`]). A column of the map that holds the mesh is
//! not always the exit point's own plane: beside a lit side face (a wedge's top face, where the
//! light that reaches the front face 2 mm below it entered through the top), the columns a few
//! millimetres off enter through the face opposite the exit face (the wedge's back). The law's
//! plane slab for a side face is its weakest case (the exit face is at right angles to the entry,
//! not parallel: skim milk's red came out at 0.6-0.7 of the path tracer's over the wedge's top 3
//! mm, then jumped to 1.0 where the light's path from the exit point switched faces, the "seam"
//! in docs/images/slab_translucency.png), and the opposite face's is its own case. So a column
//! whose entry face is more nearly opposite the exit face than the exit point's own (n·n_e lower
//! by [`SPREAD_OPPOSITE_MARGIN`]), and nearer opposite than at right angles
//! ([`SPREAD_OPPOSITE_MAX_COS`]), sends what its own plane slab would: the slab law at the exit
//! point's distance from that face's plane, spread at that slab's own rates q_j,
//!
//! ```text
//! light = ∫ p(ρ; q)·centre dA (own face)  +  ∫ p(ρ; q_j)·μ_l,j T_j facing_j dA (opposite faces)
//! ```
//!
//! and a column of a face no more opposite than the exit point's own (a lit side face seen from
//! the interior, whose plane slab would put the exit point 20 mm under it) counts as the centre's
//! plane, as before. On a plane every column is the centre's and the law is unchanged. Measured
//! on the backlit wedges (docs/BENCHMARKS.md "Each column its own slab"): skim milk's red over
//! its top rows is 0.72-0.94 of the path tracer's (0.56-0.73 before), and the seam's jump fell
//! from 0.73 → 1.03 to 0.94 → 1.03. Giving every column its own face's slab made the interior
//! worse (a point 20 mm from the right face took that face's slab, 20 mm deep, in place of the
//! back face's 11 mm).
//!
//! The shader (`slab_spread` in shaders/slab_spread.wgsl) takes [`LIT_EXTENT_SAMPLES`] radii
//! stratified in p of the channel that spreads furthest ([`lit_extent_radii`]) on the
//! golden-angle spiral, and weights the other channels (and an opposite face's columns) by their
//! p over that one; this module is its converged twin, for the tests.

/// Radii the shader samples per pixel and light (`LIT_EXTENT_RADII` in shaders/slab_spread.wgsl).
pub const LIT_EXTENT_SAMPLES: usize = 16;

/// The shader's radii in units of 1/q: p's quantiles at the midpoints of
/// [`LIT_EXTENT_SAMPLES`] equal strata (p's radius is Gamma(2)-distributed in qρ).
pub fn lit_extent_radii() -> [f64; LIT_EXTENT_SAMPLES] {
    std::array::from_fn(|j| gamma2_quantile((j as f64 + 0.5) / LIT_EXTENT_SAMPLES as f64))
}

/// The extrapolated boundary's distance beyond an index-matched face (mm), z_b = 2D = 2/(3σt′),
/// for extinction `sigma_t_per_mm` (σa + σs′): where diffusion's fluence vanishes outside a slab's
/// faces ([`lateral_rates_per_mm`]: L = d + 2z_b) and outside a side face ([`side_drain`]).
pub fn extrapolation_mm(sigma_t_per_mm: f64) -> f64 {
    2.0 / (3.0 * sigma_t_per_mm)
}

/// The lateral decay rate q (mm⁻¹) of the light crossing a slab `depth_mm` thick, per channel,
/// for a medium of extinction `sigma_t_per_mm` (σa + σs′) and Case's decay rate `kappa` (per unit
/// optical depth): √(σ² + (π/L)²), σ = κσt′, L = d + 4/(3σt′) (the module's doc). Finite and
/// positive for finite σt′ > 0 and d ≥ 0.
pub fn lateral_rates_per_mm(sigma_t_per_mm: [f64; 3], kappa: [f64; 3], depth_mm: f64) -> [f64; 3] {
    std::array::from_fn(|c| {
        let sigma = kappa[c] * sigma_t_per_mm[c];
        let span = depth_mm.max(0.0) + 2.0 * extrapolation_mm(sigma_t_per_mm[c]);
        (sigma * sigma + (std::f64::consts::PI / span).powi(2)).sqrt()
    })
}

/// The lit extent per channel: the share of p(ρ) (the module's doc) at `rates` (mm⁻¹) over the
/// offsets (x, y) (mm, in the plane at right angles to the light) where `covered` holds
/// ([`spread_light`] of a light of 1 wherever the map holds the mesh). 1 where `covered` always
/// holds.
pub fn lit_extent(rates: [f64; 3], covered: impl Fn(f64, f64) -> bool) -> [f64; 3] {
    spread_light(rates, [1.0; 3], |x, y| if covered(x, y) { Column::Centre } else { Column::Empty })
}

/// How much more nearly opposite the exit face (in n·n_e, outward normals) a column's entry face
/// must be than the exit point's own to take its own slab in [`spread_light`]
/// (`SPREAD_OPPOSITE_MARGIN` in shaders/slab_spread.wgsl): the shader reads the faces' normals
/// from the light map's one-sided slopes, which a curved surface turns a little from texel to
/// texel; faces at a wedge's edge differ by 0.8-1.
pub const SPREAD_OPPOSITE_MARGIN: f64 = 0.1;

/// The largest n·n_e (outward normals) at which a column's entry face takes its own slab in
/// [`spread_light`] (`SPREAD_OPPOSITE_MAX_COS` in shaders/slab_spread.wgsl): nearer opposite the
/// exit face than at right angles to it, −√½. Beside a sphere's terminator the columns' faces
/// turn only part of the way from the exit point's grazing entry, and the plane slab between
/// such a face and the exit point is the law's weak case again: without this bound the spheres'
/// crescents past the terminator came out brighter (ketchup ΔE 0.755 → 0.805, skim milk 1.96 →
/// 2.02, under the kernel); at −½ as at −√½ the spheres are unchanged.
pub const SPREAD_OPPOSITE_MAX_COS: f64 = -std::f64::consts::FRAC_1_SQRT_2;

/// What one column of the light's map beside the exit point holds, for [`spread_light`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Column {
    /// No mesh, or an entry face whose plane lies beyond the exit point: no light.
    Empty,
    /// The mesh, entered through a face no more nearly opposite the exit face than the exit
    /// point's own (within [`SPREAD_OPPOSITE_MARGIN`]) or not nearer opposite than at right
    /// angles ([`SPREAD_OPPOSITE_MAX_COS`]): the exit point's own plane slab.
    Centre,
    /// A face more nearly opposite the exit face, and nearer opposite than at right angles to it:
    /// the light its own plane slab sends to the exit point (over the irradiance, per channel:
    /// μ_l·T·facing at the exit point's distance from that face's plane) and that slab's lateral
    /// rates (mm⁻¹, [`lateral_rates_per_mm`]).
    Own {
        /// μ_l·T·facing per channel.
        light: [f64; 3],
        /// The lateral decay rates per channel, mm⁻¹.
        rates: [f64; 3],
    },
}

/// The slab law's light at an exit point over its lateral spread, per channel (the module's doc,
/// "Each column its own slab"; `slab_spread` in shaders/slab_spread.wgsl is the 16-sample
/// estimate):
///
/// ```text
/// ∫ p(ρ; q) · centre dA over the columns of the exit point's own slab
///   + ∫ p(ρ; q_j) · light_j dA over the columns of a more nearly opposite face j
/// ```
///
/// `rates` q and `centre` the exit point's own slab's lateral rates and light (μ_l·T·facing per
/// channel), `column` what the map holds at an offset (x, y) (mm, in the plane at right angles
/// to the light). A midpoint rule in u = 1 − (1 + qρ)e^{−qρ} of each channel's own q (2048
/// radii) × 512 angles: converged to about 10⁻³ for the shapes of the tests. `centre` where every
/// column is the centre's.
pub fn spread_light(rates: [f64; 3], centre: [f64; 3], column: impl Fn(f64, f64) -> Column) -> [f64; 3] {
    const RADII: usize = 2048;
    const ANGLES: usize = 512;
    // The radii in units of 1/q, the same for every channel.
    let radii: Vec<f64> = (0..RADII).map(|i| gamma2_quantile((i as f64 + 0.5) / RADII as f64)).collect();
    std::array::from_fn(|c| {
        let q = rates[c];
        let mut sum = 0.0;
        for t in &radii {
            let rho = t / q;
            for k in 0..ANGLES {
                let phi = std::f64::consts::TAU * (k as f64 + 0.5) / ANGLES as f64;
                sum += match column(rho * phi.cos(), rho * phi.sin()) {
                    Column::Empty => 0.0,
                    Column::Centre => centre[c],
                    // p(ρ; q_j) over the p(ρ; q) the radii sample.
                    Column::Own { light, rates } => {
                        let r = rates[c] / q;
                        light[c] * r * r * (-(rates[c] - q) * rho).exp()
                    }
                };
            }
        }
        sum / (RADII * ANGLES) as f64
    })
}

/// What the slab law keeps beside a side face, per channel (`side_drain` in
/// shaders/slab_edge.wgsl, which finds the edge in the G-buffer): `edge_mm` from the exit point
/// to the edge where its face meets a side face and the medium ends, for lateral decay rates
/// `rates` (mm⁻¹, [`lateral_rates_per_mm`]) in a medium of extinction `sigma_t_per_mm`.
///
/// The slab's fundamental mode, which carries its light sideways as e^{−qρ}, meets the side
/// face's extrapolated boundary z_b = 2/(3σt′) beyond the edge, where diffusion's fluence
/// vanishes; its image there (\[Contini1997\]'s image sources, turned to the lateral boundary)
/// leaves 1 − e^{−q(a + z_b)} of the plane's light at a distance a from the face. A side face
/// the light reaches carries its own light in (the hidden-entry gather's entries, whose dipole
/// images that face), so the drain takes only the share of the side face the light does not
/// reach directly: w = 1 − e^{−σt′·path}, `edge_path_mm` the distance the light crossed inside
/// before the edge. The result is 1 − w·e^{−q(a + z_b)}, in (0, 1]; 1 where the light reaches
/// the edge directly (path 0) or the edge is far (a → ∞).
///
/// Domain: σt′ > 0 and q > 0 finite; a and the path are clamped at 0 (and may be infinite).
/// Measured against the path tracer on the backlit wedges (docs/BENCHMARKS.md "The slab's side
/// faces"); at a straight edge of a thick slab diffusion is its own limit (the near field within
/// a mean free path of the edge).
pub fn side_drain(rates: [f64; 3], sigma_t_per_mm: [f64; 3], edge_mm: f64, edge_path_mm: f64) -> [f64; 3] {
    std::array::from_fn(|c| {
        let z_b = extrapolation_mm(sigma_t_per_mm[c]);
        let unlit = -(-sigma_t_per_mm[c] * edge_path_mm.max(0.0)).exp_m1();
        1.0 - unlit * (-rates[c] * (edge_mm.max(0.0) + z_b)).exp()
    })
}

/// t with 1 − (1 + t)e^{−t} = u (the Gamma(2) distribution's quantile), by bisection: the
/// distribution rises monotonically from 0 at t = 0, and (1 + t)e^{−t} ≤ e^{−t/2}·2 puts the
/// root below 2 − 2 ln(1 − u).
fn gamma2_quantile(u: f64) -> f64 {
    let (mut lo, mut hi) = (0.0, 2.0 - 2.0 * (1.0 - u).ln());
    for _ in 0..200 {
        let mid = 0.5 * (lo + hi);
        if 1.0 - (1.0 + mid) * (-mid).exp() < u {
            lo = mid;
        } else {
            hi = mid;
        }
        if hi - lo < 1e-14 * hi.max(1e-300) {
            break;
        }
    }
    0.5 * (lo + hi)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_gamma_quantile_inverts_its_distribution() {
        for u in [1e-6, 0.01, 0.5, 0.9, 0.999, 1.0 - 1e-9] {
            let t = gamma2_quantile(u);
            let back = 1.0 - (1.0 + t) * (-t).exp();
            assert!((back - u).abs() < 1e-10, "u {u}: t {t} gives {back}");
        }
    }

    #[test]
    fn a_plane_is_all_there_a_half_plane_half_and_a_strip_by_its_width() {
        let q = [0.2, 0.5, 1.0];
        assert_eq!(lit_extent(q, |_, _| true), [1.0; 3]);
        for f in lit_extent(q, |x, _| x > 0.0) {
            assert!((f - 0.5).abs() < 1e-3, "{f}");
        }
        // A strip 9 mm wide (a finger) holds the disk of radius 4.5 mm, whose share is
        // 1 − (1 + 4.5q)e^{−4.5q}, and not the plane: its share lies between, and grows with q.
        let strip = lit_extent(q, |x, _| x.abs() < 4.5);
        for c in 0..3 {
            let t = q[c] * 4.5;
            let disk = 1.0 - (1.0 + t) * (-t).exp();
            assert!(disk < strip[c] && strip[c] < 1.0, "channel {c}: {} against the disk's {disk}", strip[c]);
        }
        assert!(strip[0] < strip[1] && strip[1] < strip[2], "{strip:?}");
    }

    #[test]
    fn a_column_of_the_centre_s_own_slab_or_its_like_is_the_centre_and_the_spread_weighs_the_rest_by_its_rates() {
        let q = [0.2, 0.5, 1.0];
        let centre = [0.3, 0.2, 0.1];
        // A plane: the centre's light.
        let plane = spread_light(q, centre, |_, _| Column::Centre);
        for c in 0..3 {
            assert!((plane[c] - centre[c]).abs() < 1e-9, "{plane:?}");
        }
        // Half the plane another face whose slab sends the same light at the same rates: the same.
        let same =
            spread_light(
                q,
                centre,
                |x, _| if x > 0.0 { Column::Centre } else { Column::Own { light: centre, rates: q } },
            );
        for c in 0..3 {
            assert!((same[c] - centre[c]).abs() < 1e-9, "{same:?}");
        }
        // A whole plane of another face spreading twice as fast: its own light (its p integrates
        // to 1 over the radii of the centre's), and half of it over a half-plane.
        let light = [0.5, 0.4, 0.05];
        let own = Column::Own { light, rates: q.map(|q| 2.0 * q) };
        let whole = spread_light(q, centre, |_, _| own);
        let half = spread_light(q, centre, |x, _| if x > 0.0 { own } else { Column::Empty });
        for c in 0..3 {
            assert!((whole[c] - light[c]).abs() < 1e-3 * light[c], "{whole:?}");
            assert!((half[c] - 0.5 * light[c]).abs() < 1e-3 * light[c], "{half:?}");
        }
        // The opposite face beyond 3 mm of a side face's centre: the nearer columns weigh in as
        // the centre's share of them, the farther ones as the other slab's share of them.
        let mixed = spread_light(q, centre, |x, _| if x < 3.0 { Column::Centre } else { own });
        let (near, far) = (lit_extent(q, |x, _| x < 3.0), lit_extent(q.map(|q| 2.0 * q), |x, _| x >= 3.0));
        for c in 0..3 {
            let want = centre[c] * near[c] + light[c] * far[c];
            assert!((mixed[c] - want).abs() < 1e-3 * want, "channel {c}: {mixed:?} against {want}");
        }
    }

    #[test]
    fn the_rate_is_the_medium_s_decay_in_a_thick_slab_and_the_boundaries_in_a_thin_one() {
        // σt′ 2 mm⁻¹, κ 0.1: σ = 0.2 mm⁻¹.
        let thick = lateral_rates_per_mm([2.0; 3], [0.1; 3], 1e6);
        assert!((thick[0] - 0.2).abs() < 1e-6, "{thick:?}");
        let thin = lateral_rates_per_mm([2.0; 3], [0.0; 3], 0.0);
        assert!((thin[0] - std::f64::consts::PI * 1.5).abs() < 1e-12, "{thin:?}");
        // A negative depth is a slab of none.
        let none = lateral_rates_per_mm([2.0; 3], [0.1; 3], -1.0);
        assert!((none[0] - (thin[0] * thin[0] + 0.04).sqrt()).abs() < 1e-12, "{none:?}");
    }

    #[test]
    fn the_side_drain_takes_the_unlit_edge_s_image_and_nothing_where_the_light_arrives() {
        let (q, sigma_t) = ([0.2, 0.5, 1.0], [0.7, 1.2, 1.9]);
        // At the edge of a side face in the dark: the image at z_b beyond leaves 1 − e^{−q·z_b}.
        let at_edge = side_drain(q, sigma_t, 0.0, f64::INFINITY);
        for c in 0..3 {
            let want = 1.0 - (-q[c] * 2.0 / (3.0 * sigma_t[c])).exp();
            assert!((at_edge[c] - want).abs() < 1e-12, "channel {c}: {} against {want}", at_edge[c]);
        }
        // It grows back toward the plane's light with the distance, monotonically.
        let mut last = at_edge;
        for a in [0.5, 1.0, 2.0, 5.0, 10.0, 40.0] {
            let f = side_drain(q, sigma_t, a, 8.0);
            for c in 0..3 {
                assert!(f[c] > last[c] && f[c] <= 1.0, "a {a}, channel {c}: {f:?} after {last:?}");
            }
            last = f;
        }
        assert!(last.iter().all(|f| *f > 0.999), "{last:?}");
        // A side face the light reaches directly drains nothing; one behind 1 mm of the medium
        // by the share the light does not reach.
        assert_eq!(side_drain(q, sigma_t, 0.0, 0.0), [1.0; 3]);
        let thin = side_drain(q, sigma_t, 0.0, 1.0);
        for c in 0..3 {
            let w = 1.0 - (-sigma_t[c]).exp();
            assert!((1.0 - thin[c] - w * (1.0 - at_edge[c])).abs() < 1e-12, "channel {c}: {thin:?}");
        }
        // The domain's edges: a negative distance or path is none, an infinite distance the plane.
        assert_eq!(side_drain(q, sigma_t, -3.0, -1.0), [1.0; 3]);
        assert_eq!(side_drain(q, sigma_t, f64::INFINITY, 5.0), [1.0; 3]);
        assert_eq!(side_drain(q, sigma_t, -3.0, 5.0), side_drain(q, sigma_t, 0.0, 5.0));
        for f in side_drain([1e-9; 3], [1e3; 3], 0.0, 1e9).into_iter().chain(side_drain([1e3; 3], [1e-6; 3], 0.0, 1e9))
        {
            assert!(f.is_finite() && f > 0.0 && f <= 1.0, "{f}");
        }
    }

    #[test]
    fn the_shader_samples_this_module_s_radii() {
        let shader = include_str!("shaders/slab_spread.wgsl");
        let start = shader.find("const LIT_EXTENT_RADII = array<f32, 16>(").expect("the shader's radii");
        let body = &shader[start..];
        let list = &body[body.find('(').expect("(") + 1..body.find(')').expect(")")];
        let radii: Vec<f64> =
            list.split(',').map(str::trim).filter(|v| !v.is_empty()).map(|v| v.parse().expect("a number")).collect();
        let want = lit_extent_radii();
        assert_eq!(radii.len(), want.len(), "{radii:?}");
        for (got, want) in radii.iter().zip(want) {
            assert!((got - want).abs() < 1e-6, "{got} against {want}");
        }
        let margin = shader.find("const SPREAD_OPPOSITE_MARGIN: f32 = ").expect("the shader's margin");
        let value = &shader[margin..];
        let value: f64 =
            value[value.find('=').expect("=") + 1..value.find(';').expect(";")].trim().parse().expect("a number");
        assert_eq!(value, SPREAD_OPPOSITE_MARGIN);
        let bound = shader.find("const SPREAD_OPPOSITE_MAX_COS: f32 = ").expect("the shader's bound");
        let value = &shader[bound..];
        let value: f64 =
            value[value.find('=').expect("=") + 1..value.find(';').expect(";")].trim().parse().expect("a number");
        assert!((value - SPREAD_OPPOSITE_MAX_COS).abs() < 1e-8, "{value}");
    }
}
