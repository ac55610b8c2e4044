// The fibre model's scattering (render/src/fibre.rs `scattering` is its CPU twin, with the
// citations, conventions and domain; render/tests/fibre_gpu.rs checks the two agree). Inserted
// into shaders/hair.wgsl; FIBRE_ETA and CUTICLE_TILT_RAD come from `fibre::wgsl_constants`.

fn fresnel_keratin(cos: f32) -> f32 {
    let k = (1.0 - FIBRE_ETA) / (1.0 + FIBRE_ETA);
    let f0 = k * k;
    return f0 + (1.0 - f0) * pow(1.0 - clamp(cos, 0.0, 1.0), 5.0);
}

fn unit_gaussian(b: f32, x: f32) -> f32 {
    return exp(-0.5 * x * x / (b * b)) / (2.5066283 * b);
}

// Outgoing radiance per unit irradiance of a directional light of a fibre with tangent `t`
// (root to tip), lit from `l`, seen from `v` (render/src/fibre.rs `scattering`, its twin: the
// citations, conventions and domain are there).
fn fibre_scattering(t: vec3<f32>, l: vec3<f32>, v: vec3<f32>, sigma_a: vec3<f32>, roughness: f32) -> vec3<f32> {
    let theta_i = asin(clamp(dot(t, l), -1.0, 1.0));
    let theta_o = asin(clamp(dot(t, v), -1.0, 1.0));
    let cos_d = max(cos(0.5 * (theta_o - theta_i)), 1e-3);
    let lp = l - t * dot(t, l);
    let vp = v - t * dot(t, v);
    let cos_phi = dot(lp, vp) / sqrt(dot(lp, lp) * dot(vp, vp) + 1e-4);
    let cos_half_phi = sqrt(clamp(0.5 + 0.5 * cos_phi, 0.0, 1.0));
    let b = max(roughness, 1e-3);
    let sum = theta_i + theta_o;
    let m_r = unit_gaussian(b, sum + 2.0 * CUTICLE_TILT_RAD) / cos_d;
    let r = m_r * 0.25 * cos_half_phi * fresnel_keratin(sqrt(clamp(0.5 + 0.5 * dot(l, v), 0.0, 1.0)));
    let eta_p = 1.19 / cos_d + 0.36 * cos_d;
    let a = 1.0 / eta_p;
    let h = cos_half_phi * (1.0 + a * (0.6 - 0.8 * cos_phi));
    let f_tt = fresnel_keratin(cos_d * sqrt(clamp(1.0 - h * h, 0.0, 1.0)));
    let m_tt = unit_gaussian(0.5 * b, sum - CUTICLE_TILT_RAD) / cos_d;
    let n_tt = exp(-3.65 * cos_phi - 3.98);
    let path_tt = 2.0 * sqrt(clamp(1.0 - (h * a) * (h * a), 0.0, 1.0)) / cos_d;
    let f_trt = fresnel_keratin(cos_d * 0.5);
    let m_trt = unit_gaussian(2.0 * b, sum - 4.0 * CUTICLE_TILT_RAD) / cos_d;
    let n_trt = exp(17.0 * cos_phi - 16.78);
    let path_trt = 3.2 / cos_d;
    let tt = m_tt * n_tt * (1.0 - f_tt) * (1.0 - f_tt) * exp(-sigma_a * path_tt);
    let trt = m_trt * n_trt * (1.0 - f_trt) * (1.0 - f_trt) * f_trt * exp(-sigma_a * path_trt);
    return vec3<f32>(r) + tt + trt;
}
