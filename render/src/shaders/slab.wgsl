// The slab law's transmission T(μ_v, μ_l; α′, τ, η) (render/src/slab_transmittance.rs, the CPU
// twin, with the same taps): single scattering under the boundary in closed form plus
// adding-doubling's higher orders, G = T_m·e^{κτ}/(T_F(μ_v)·T_F(μ_l)), read trilinearly from
// `slab_table`, the medium's channels' grids (slab_transmittance::medium_values, already
// interpolated at the skin's η and each channel's albedo), laid out
// [channel][thickness][μ_v][μ_l]. `axes`: x η, y the thickness nodes (even in ln(1 + τ)),
// z the cosine nodes (even in [0, 1]), w ln(1 + τ_max). Needs fresnel_in (diffusion.wgsl).

// The node below x ∈ [0, 1] on n even nodes, and the weight of the one above.
fn slab_cell(x: f32, n: f32) -> vec2<f32> {
    let s = clamp(x, 0.0, 1.0) * (n - 1.0);
    let i = min(floor(s), n - 2.0);
    return vec2<f32>(i, s - i);
}

// Single scattering between internal cosines: α′/4 (e^{−τ/ν_l} − e^{−τ/ν_v})/(ν_l − ν_v), its
// limit where the cosines meet.
fn slab_single_inside(a: f32, tau: f32, nu_v: f32, nu_l: f32) -> f32 {
    let d = nu_l - nu_v;
    if abs(d) < 1e-3 * max(nu_v, nu_l) {
        let nu = 0.5 * (nu_v + nu_l);
        return 0.25 * a * tau * exp(-tau / nu) / (nu * nu);
    }
    return 0.25 * a * (exp(-tau / nu_l) - exp(-tau / nu_v)) / d;
}

// The slab's faces as the light meets them (the CPU twin's `Faces`): the internal cosines ν and
// the Fresnel reflectances F of the exit (v) and the entry (l). Channel-independent: made once
// per pixel and light (`slab_faces`) for T₁ and the table's T_F(μ_v)·T_F(μ_l). At η = 1 ν = μ
// and F = 0, grazing included.
struct SlabFaces {
    nu_v: f32,
    nu_l: f32,
    f_v: f32,
    f_l: f32,
}

// The internal cosine of light refracted into index η at external cosine μ, held at 10⁻⁴ and
// above (just above η = 1, f32 loses it to cancellation at grazing; the faces pass nothing there).
fn slab_refracted(mu: f32, eta: f32) -> f32 {
    return max(sqrt(max(1.0 - (1.0 - mu * mu) / (eta * eta), 0.0)), 1e-4);
}

fn slab_faces(eta: f32, mu_v: f32, mu_l: f32) -> SlabFaces {
    if eta == 1.0 {
        return SlabFaces(mu_v, mu_l, 0.0, 0.0);
    }
    return SlabFaces(slab_refracted(mu_v, eta), slab_refracted(mu_l, eta), fresnel_in(mu_v, eta), fresnel_in(mu_l, eta));
}

// T₁ under the boundary: T_F(μ_v)·T_F(μ_l)·(once·T₁(ν_v, ν_l) + the two once-scattered paths
// with one internal reflection)/η² (the CPU twin's doc), 0 at a cosine of 0. `once` is 1, or 0
// where the light scattered once without reflection is marched through the mesh instead
// (slab_march.wgsl).
fn slab_single(a: f32, eta: f32, tau: f32, faces: SlabFaces, once: f32) -> f32 {
    // A cosine of 0 (ν = μ at η = 1; at η > 1 ν ≥ 10⁻⁴ and F = 1 there, so the faces pass nothing).
    if faces.nu_v <= 0.0 || faces.nu_l <= 0.0 {
        return 0.0;
    }
    if eta == 1.0 {
        return once * slab_single_inside(a, tau, faces.nu_v, faces.nu_l);
    }
    let nu_v = faces.nu_v;
    let nu_l = faces.nu_l;
    // The two paths with one internal reflection.
    let back = 0.25 * a * (1.0 - exp(-tau * (1.0 / nu_v + 1.0 / nu_l))) / (nu_v + nu_l);
    let reflected = back * (faces.f_l * exp(-tau / nu_l) + faces.f_v * exp(-tau / nu_v));
    return (1.0 - faces.f_v) * (1.0 - faces.f_l) * (once * slab_single_inside(a, tau, nu_v, nu_l) + reflected) / (eta * eta);
}

fn slab_weight(c: vec2<f32>, upper: u32) -> f32 {
    return select(1.0 - c.y, c.y, upper == 1u);
}

// T of `channel`, whose albedo is a and Case decay rate kappa, at optical thickness tau, the
// faces met at the external cosines mu_v and mu_l (`slab_faces(axes.x, mu_v, mu_l)`); `once` as
// in `slab_single`.
fn slab_transmittance(channel: u32, a: f32, kappa: f32, tau: f32, mu_v: f32, mu_l: f32, faces: SlabFaces, axes: vec4<f32>, once: f32) -> f32 {
    let ck = slab_cell(log(1.0 + tau) / axes.w, axes.y);
    let cv = slab_cell(mu_v, axes.z);
    let cl = slab_cell(mu_l, axes.z);
    let n_tau = u32(axes.y);
    let n_mu = u32(axes.z);
    var g = 0.0;
    for (var dk = 0u; dk < 2u; dk++) {
        for (var dv = 0u; dv < 2u; dv++) {
            for (var dl = 0u; dl < 2u; dl++) {
                let w = slab_weight(ck, dk) * slab_weight(cv, dv) * slab_weight(cl, dl);
                let row = channel * n_tau + u32(ck.x) + dk;
                let i = (row * n_mu + u32(cv.x) + dv) * n_mu + u32(cl.x) + dl;
                g += w * slab_table[i];
            }
        }
    }
    let boundary = (1.0 - faces.f_v) * (1.0 - faces.f_l);
    return slab_single(a, axes.x, tau, faces, once) + g * exp(-kappa * tau) * boundary;
}
