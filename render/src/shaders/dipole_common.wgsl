// Shared by the dipole passes (dipole_light, dipole_radiance, dipole_combine): their uniform and
// the BSSRDFs; needs `//#insert diffusion` before it. CPU twins: render/src/directional_dipole.rs (derivation and tests there).
// Keep `DipolePass` in sync with passes/dipole/mod.rs (tests/shaders.rs checks it with naga).

struct DipolePass {
    // per channel c: x D (mm), y σ_tr (mm⁻¹), z d_e (mm), w A
    channel: array<vec4<f32>, 3>,
    // per channel c: x (3σ′_t)⁻² (mm²: the back-lit offset; 9μ₀² times it is the mean-free-path
    // source's front-lit depth²), y α′, z classic z_r (mm), w classic z_v (mm)
    extra: array<vec4<f32>, 3>,
    // x C_φ(η), y C_E(η), z 1/(4C_φ(1/η)), w η
    boundary: vec4<f32>,
    // classic dipole σ_tr per channel (rgb), w: 0 the standard dipole, 1 the directional as
    // published, 2 the directional with the mean-free-path source (power α′, depth μ₀/σ′_t)
    classic: vec4<f32>,
    // x σ used for the exponential radial sampling (mm⁻¹), y samples N, z frame index (seed),
    // w largest sampling radius (mm)
    sampling: vec4<f32>,
    // x ε_g G-buffer shrink (mm), y ε_c intrusion (mm), z ε_b depth bias (mm), w fixes bit set
    // (1 shrink, 2 intrusion, 4 world-space depth bias)
    fixes: vec4<f32>,
    // x directions K, y lights with a light G-buffer, z light G-buffer side (texels), w radiance map side
    counts: vec4<u32>,
    // per light slot: world → light clip (orthographic), and its inverse
    light_view_proj: array<mat4x4<f32>, 4>,
    light_inv_view_proj: array<mat4x4<f32>, 4>,
    // per light slot: which scene light (x), its near/far plane (y, z, mm), mm per texel (w)
    light_info: array<vec4<f32>, 4>,
    // per direction: world → clip (orthographic), and the direction toward the viewer in xyz
    dir_view_proj: array<mat4x4<f32>, 32>,
    dir_axis: array<vec4<f32>, 32>,
    // per direction: near/far plane (mm) in x, y
    dir_planes: array<vec4<f32>, 32>,
}
@group(1) @binding(0) var<uniform> dipole: DipolePass;

// S∞ of a ray source (CPU: DipoleChannel::s_infinite) for channel c.
fn s_infinite(c: u32, x: vec3<f32>, w: vec3<f32>, r_in: f32, no: vec3<f32>) -> f32 {
    let ch = dipole.channel[c];
    let d = ch.x;
    let r = max(r_in, 1e-6);
    let r2 = r * r;
    let s = ch.y * r;
    let s1 = 1.0 + s;
    let x_dot_w = dot(x, w);
    let fluence = r2 / d + 3.0 * s1 * x_dot_w;
    let flux = 3.0 * d * s1 * dot(w, no) - (s1 + 3.0 * d * (3.0 * s1 + s * s) / r2 * x_dot_w) * dot(x, no);
    return exp(-s) / (4.0 * PI * PI * r2 * r) * (dipole.boundary.x * fluence - dipole.boundary.y * flux);
}

// n_i* (CPU: directional_dipole::modified_normal).
fn modified_normal(x: vec3<f32>, ni: vec3<f32>) -> vec3<f32> {
    let c = cross(ni, x);
    let x2 = dot(x, x);
    if x2 < 1e-12 || dot(c, c) < 1e-12 * x2 {
        return ni;
    }
    return cross(x * inverseSqrt(x2), normalize(c));
}

// The directional dipole's S_d/(4C_φ(1/η)) for channel c, w12 the refracted direction, times
// the source's power (CPU: DipoleChannel::s_d times exit_norm).
fn directional_sd(c: u32, xi: vec3<f32>, ni: vec3<f32>, w12: vec3<f32>, xo: vec3<f32>, no: vec3<f32>) -> f32 {
    let ch = dipole.channel[c];
    let d = ch.x;
    let de = ch.z;
    let x = xo - xi;
    let r2 = dot(x, x);
    let ni_star = modified_normal(x, ni);
    let x_dot_w = dot(x, w12);
    let mu0 = -dot(no, w12);
    let published = dipole.classic.w < 1.5;
    var dr2 = r2 + dipole.extra[c].x;
    if mu0 > 0.0 {
        let cos_beta = -sqrt(max(r2 - x_dot_w * x_dot_w, 0.0) / (r2 + de * de));
        let dmu = d * mu0;
        // The real source's depth: D·μ₀ as published, μ₀/σ′t = 3μ₀·(3σ′t)⁻¹ with the
        // mean-free-path source.
        let depth_sq = select(9.0 * mu0 * mu0 * dipole.extra[c].x, dmu * dmu, published);
        dr2 = r2 + depth_sq - 2.0 * dmu * de * cos_beta;
    }
    let wv = w12 - 2.0 * dot(w12, ni_star) * ni_star;
    let xv = x - 2.0 * ch.w * de * ni_star;
    let sd = s_infinite(c, x, w12, sqrt(dr2), no) - s_infinite(c, xv, wv, length(xv), no);
    let power = select(dipole.extra[c].y, 1.0, published);
    return power * max(sd, 0.0) * dipole.boundary.z;
}

// The classic dipole's R(r) for channel c (CPU: ChannelProfile::radial, ClassicDipole).
fn classic_radial(c: u32, r: f32) -> f32 {
    let e = dipole.extra[c];
    return dipole_radial(vec4<f32>(e.y, dipole.classic[c], e.z, e.w), r);
}

// The BSSRDF without the exit Fresnel term, per channel: light entering at xi (normal ni) from
// the direction `toward_light`, leaving at xo (normal no). 0 when the light is below xi's plane.
fn bssrdf_in(xi: vec3<f32>, ni: vec3<f32>, toward_light: vec3<f32>, xo: vec3<f32>, no: vec3<f32>) -> vec3<f32> {
    let cos_i = dot(toward_light, ni);
    if cos_i <= 0.0 {
        return vec3<f32>(0.0);
    }
    let eta = dipole.boundary.w;
    let t12 = 1.0 - fresnel_in(cos_i, eta);
    var out: vec3<f32>;
    if dipole.classic.w > 0.5 {
        let k = 1.0 / eta;
        let cos_t = sqrt(max(1.0 - k * k * (1.0 - cos_i * cos_i), 0.0));
        let w12 = normalize(-k * toward_light + ni * (k * cos_i - cos_t));
        for (var c = 0u; c < 3u; c++) {
            out[c] = directional_sd(c, xi, ni, w12, xo, no);
        }
    } else {
        let r = length(xo - xi);
        for (var c = 0u; c < 3u; c++) {
            out[c] = classic_radial(c, r) / PI;
        }
    }
    return out * t12;
}

// Distance along an orthographic projection's axis (mm) of a [0, 1] depth with planes (near, far).
fn ortho_depth_mm(planes: vec2<f32>, d: f32) -> f32 {
    return planes.x + d * (planes.y - planes.x);
}
