// The slab law's transmission T(μ_v, μ_l; α′, τ) (render/src/slab_transmittance.rs, the CPU
// twin, with the same taps): single scattering in closed form plus adding-doubling's higher
// orders, G = T_m·e^{κτ}, read trilinearly from `slab_table`, the medium's channels' grids
// (slab_transmittance::medium_values, already interpolated at each channel's albedo), laid out
// [channel][thickness][μ_v][μ_l]. `axes`: y the thickness nodes (even in ln(1 + τ)), z the
// cosine nodes (even in [0, 1]), w ln(1 + τ_max).

// The node below x ∈ [0, 1] on n even nodes, and the weight of the one above.
fn slab_cell(x: f32, n: f32) -> vec2<f32> {
    let s = clamp(x, 0.0, 1.0) * (n - 1.0);
    let i = min(floor(s), n - 2.0);
    return vec2<f32>(i, s - i);
}

// T₁: α′/4 (e^{−τ/μ_l} − e^{−τ/μ_v})/(μ_l − μ_v), its limit where the cosines meet.
fn slab_single(a: f32, tau: f32, mu_v: f32, mu_l: f32) -> f32 {
    if mu_v <= 0.0 || mu_l <= 0.0 {
        return 0.0;
    }
    let d = mu_l - mu_v;
    if abs(d) < 1e-3 * max(mu_v, mu_l) {
        let mu = 0.5 * (mu_v + mu_l);
        return 0.25 * a * tau * exp(-tau / mu) / (mu * mu);
    }
    return 0.25 * a * (exp(-tau / mu_l) - exp(-tau / mu_v)) / d;
}

fn slab_weight(c: vec2<f32>, upper: u32) -> f32 {
    return select(1.0 - c.y, c.y, upper == 1u);
}

// T of `channel`, whose albedo is a and Case decay rate kappa, at optical thickness tau.
fn slab_transmittance(channel: u32, a: f32, kappa: f32, tau: f32, mu_v: f32, mu_l: f32, axes: vec4<f32>) -> f32 {
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
    return slab_single(a, tau, mu_v, mu_l) + g * exp(-kappa * tau);
}
