// Single scattering along the view ray through the mesh (render/src/slab_march.rs, its CPU twin
// and the formula's home): the slab law's once-scattered light, marched from the exit point
// along the refracted view ray to where the camera's ray leaves the mesh (the back-face depth
// pass, `back_depth`), each point lit through the light's path read from its shadow map,
//   σs′/4 · ∫₀^{c′} e^{−σt′(s + ℓ′(s))} ds   per unit E/π (× T_F(μ_v)·T_F(μ_l)/η² by the caller),
// c′ = c·μ_v/ν_v, ℓ′ = ℓ·μ_l/ν_l; s sampled at VIEW_MARCH_SAMPLES strata as e^{−ks},
// k = σt′_min·(1 − a/ν_l), a the ray's cosine toward the entry face, held to |k·c′| ≤ 60.
// A point the light reaches without crossing the mesh (its path shorter than −2 texels, the
// shadow map's bias allowed) is outside it.

const VIEW_MARCH_SAMPLES: u32 = 16u;
const VIEW_MARCH_MAX_DECAYS: f32 = 60.0;

// The camera's ray through the mesh from the exit point `world` at pixel `frag`: the distance
// (mm) to the nearest back face behind it; −1 where the back-face pass drew none there.
fn view_chord_mm(frag: vec2<f32>, world: vec3<f32>) -> f32 {
    let d = textureLoad(back_depth, vec2<i32>(frag), 0).r;
    if d >= 1.0 {
        return -1.0;
    }
    let behind = world_at(frag, d) - world;
    return select(-1.0, length(behind), dot(behind, frame.camera_pos.xyz - world) <= 0.0);
}

// σs′/4 · ∫ e^{−σt′(s + ℓ′(s))} ds per channel for `light`, from `world` along the refracted
// view ray `dir` (into the mesh) over the chord `chord` (already c′), the light's paths scaled
// by `path_scale` (μ_l/ν_l); the ray's cosine `approach` toward the face the light entered and
// the light's refracted cosine `nu_l` there steer the sampling.
fn view_march(light: Light, world: vec3<f32>, dir: vec3<f32>, chord: f32, path_scale: f32, approach: f32, nu_l: f32, texel_mm: f32) -> vec3<f32> {
    let sigma_t = params.slab_sigma_t.xyz;
    let limit = VIEW_MARCH_MAX_DECAYS / max(chord, 1e-6);
    let k = clamp(min(sigma_t.x, min(sigma_t.y, sigma_t.z)) * (1.0 - approach / max(nu_l, 1e-4)), -limit, limit);
    var sum = vec3<f32>(0.0);
    for (var j = 0u; j < VIEW_MARCH_SAMPLES; j++) {
        let u = (f32(j) + 0.5) / f32(VIEW_MARCH_SAMPLES);
        var s = u * chord;
        var inv_p = chord;
        if abs(k * chord) >= 1e-3 {
            let span = 1.0 - exp(-k * chord);
            s = -log(1.0 - u * span) / k;
            inv_p = span / (k * exp(-k * s));
        }
        let m = map_point(light, world + dir * s);
        if !m.inside {
            continue;
        }
        let l = m.depth_mm - m.first_mm;
        if l < -2.0 * texel_mm {
            continue;
        }
        sum += exp(-sigma_t * (s + max(l, 0.0) * path_scale)) * inv_p;
    }
    return 0.25 * params.slab_albedo.xyz * sigma_t * sum / f32(VIEW_MARCH_SAMPLES);
}

// The marched light scattered once toward the camera per unit E/π (the faces' transmittances
// T_F(μ_v)·T_F(μ_l)/η² included) at `world`, of normal n, seen from v, for the light's entry `e`
// (`slab_entry`, through the mesh), over the camera ray's chord `chord` (`view_chord_mm`; none
// where negative): into the mesh along the refracted view ray as deep below the exit face as the
// camera's ray goes, the light's straight path from the map taken to its refracted one.
fn once_scattered(light: Light, axes: MapAxes, world: vec3<f32>, n: vec3<f32>, v: vec3<f32>, e: SlabEntry, chord: f32) -> vec3<f32> {
    let faces = e.faces;
    if chord < 0.0 || faces.nu_v <= 0.0 || faces.nu_l <= 0.0 {
        return vec3<f32>(0.0);
    }
    let eta = params.slab_axes.x;
    let dir = select(refract(-v, n, 1.0 / eta), -v, eta == 1.0);
    let depth_scale = select(e.mu_v / faces.nu_v, 1.0, eta == 1.0);
    let path_scale = select(e.mu_l / faces.nu_l, 1.0, eta == 1.0);
    let boundary = (1.0 - faces.f_v) * (1.0 - faces.f_l) / (eta * eta);
    let texel = max(axes.texel_mm.x, axes.texel_mm.y);
    return boundary * view_march(light, world, dir, chord * depth_scale, path_scale, dot(dir, e.n_e), faces.nu_l, texel);
}

// The radiance of `light` scattered once toward the camera at `world` (pixel `frag`, in the
// light's map at `m`), marched through the mesh, where the transmission gather takes the rest
// of the light that crossed it: the entry face from the map's slope, as the slab law's.
fn marched_light(light: Light, axes: MapAxes, m: MapPoint, frag: vec2<f32>, world: vec3<f32>, n: vec3<f32>, v: vec3<f32>) -> vec3<f32> {
    let e = slab_entry(light, axes, m, world, n, v);
    if !e.through {
        return vec3<f32>(0.0);
    }
    let marched = once_scattered(light, axes, world, n, v, e, view_chord_mm(frag, world));
    return e.arrival.e * marched * (light.translucency.x / PI);
}
