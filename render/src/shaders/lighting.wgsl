// Lighting pass ([Huang2013] figure 1, steps 2, 3 and 5). Per pixel:
// - the cosmetic stack's R (from above and from below) and T, from each layer's table of R0 and
//   T against thickness, composed bottom to top with the Kubelka-Munk layer formulas ([Huang2013]
//   eq. 3-4, with T1²R2 in the numerator) per channel of the compositing basis
//   (rouge_measure::compositing::CompositingBasis: a linear transform of linear sRGB whose
//   per-channel products are closer to spectral ones; the tables are uploaded in it), and over the skin in
//   the same basis; results go back to linear sRGB (BASIS_TO_SRGB) before they leave the pass;
// - the irradiance of every light (shadowed where the light casts shadows) and of the
//   environment's spherical harmonics;
// - the skin radiance before scattering: light that crossed the stack (× T), with the
//   inter-reflections between skin and the stack's underside (1 / (1 − R_below·albedo));
// - what leaves at the surface without scattering: the stack's diffuse reflectance and the
//   Kelemen/Szirmay-Kalos specular lobes of the skin (two: a sharp and a broad one) and of each
//   layer, bottom to top, each lower lobe attenuated by the layers above it (T² for the way in
//   and the way out, × the clarity of the layer's finish).

@group(1) @binding(0) var gb_normal: texture_2d<f32>;
@group(1) @binding(1) var gb_albedo: texture_2d<f32>;
// The depth buffer as an unfilterable float texture (WebGPU allows it for Depth32Float): GLSL,
// on wgpu's GL backend, can only texelFetch depth that way, not as a depth texture.
@group(1) @binding(2) var gb_depth: texture_2d<f32>;
@group(1) @binding(3) var gb_thickness_a: texture_2d<f32>;
@group(1) @binding(4) var gb_thickness_b: texture_2d<f32>;
// Per layer three rows of `frame.counts.z` entries: R0, then T (in the compositing basis), at
// thickness X = X0·u/(1 − u) for u = i/(n − 1) (the last entry is the opaque limit: R∞, T = 0);
// then the interference colour of the layer's shimmer platelets (linear sRGB, zeros without a
// shimmer) at cos(h, l) = i/(n − 1) (rouge_measure::finish::Shimmer::interference_table).
@group(1) @binding(5) var<storage, read> tables: array<vec4<f32>>;
@group(1) @binding(6) var shadow_maps: texture_depth_2d_array;
@group(1) @binding(7) var shadow_sampler: sampler_comparison;
// The half-space diffuse law's table (`half_space_nodes` below; 4 zeros under Lambert).
@group(1) @binding(12) var<storage, read> half_space_table: array<f32>;
//#insert diffusion
// The outputs (`LightingOut`): the pass is a compute pass, one invocation a pixel (on GPUs whose
// graphics pipeline runs on a few of their SMs, such as the H100/H200, a full-screen fragment pass
// took ten to thirty times as long: docs/BENCHMARKS.md, `rouge bench shading`).
@group(1) @binding(9) var out_diffuse: texture_storage_2d<rgba16float, write>;
@group(1) @binding(10) var out_surface: texture_storage_2d<rgba16float, write>;
//#if LAYERS_A
@group(1) @binding(11) var out_exit_t: texture_storage_2d<rgba16float, write>;
//#endif
//#if GLITTER
// The glitter's flake-field coordinates (gbuffer.wgsl `glitter`).
@group(1) @binding(8) var gb_glitter: texture_2d<u32>;
//#insert glitter
//#endif

// TABLE_X0_MM (mm), the X0 of the table parameterisation, is injected from its owner,
// rouge_measure::layer_table, and BASIS_FROM_SRGB / BASIS_TO_SRGB from
// rouge_measure::compositing, by shader::shader_source.

struct LightingOut {
    // rgb: skin radiance before scattering, a: 1 on skin
    diffuse: vec4<f32>,
    // rgb: radiance that leaves at the surface (stack reflectance, specular, non-skin diffuse)
    surface: vec4<f32>,
//#if LAYERS_A
    // rgb: T of the stack, for the scattered light on its way out
    exit_t: vec4<f32>,
//#endif
}

// Beckmann distribution of half vectors ([Beckmann1963]), normalised so that ∫ D (n·h) dω = 1.
fn beckmann(n_dot_h: f32, m: f32) -> f32 {
    let c2 = max(n_dot_h * n_dot_h, 1e-6);
    let m2 = m * m;
    return exp((c2 - 1.0) / (m2 * c2)) / (PI * m2 * c2 * c2);
}

// Kelemen/Szirmay-Kalos specular BRDF ([Huang2013] eq. 5, [Kelemen2001]): P_H(H) F(H·L) / (2 (1 + L·V)),
// Schlick's Fresnel from F0 ([Schlick1994]). CPU twin: render/src/specular.rs.
fn kelemen(n: vec3<f32>, l: vec3<f32>, v: vec3<f32>, m: f32, f0: f32) -> f32 {
    let h_un = l + v;
    let len2 = dot(h_un, h_un);
    if len2 < 1e-8 {
        return 0.0;
    }
    let h = h_un * inverseSqrt(len2);
    let n_dot_h = dot(n, h);
    if n_dot_h <= 0.0 {
        return 0.0;
    }
    let fresnel = f0 + (1.0 - f0) * pow(1.0 - max(dot(h, l), 0.0), 5.0);
    return beckmann(n_dot_h, m) * fresnel / (2.0 * (1.0 + dot(l, v)));
}

// The skin's two lobes: roughness × SKIN_LOBE_ROUGHNESS, mixed SKIN_LOBE_MIX : 1 − SKIN_LOBE_MIX
// (constants injected from their owner, render/src/specular.rs, whose `skin_lobes` is the CPU twin).
fn skin_lobes(n: vec3<f32>, l: vec3<f32>, v: vec3<f32>, m: f32, f0: f32) -> f32 {
    let sharp = kelemen(n, l, v, SKIN_LOBE_ROUGHNESS.x * m, f0);
    let broad = kelemen(n, l, v, SKIN_LOBE_ROUGHNESS.y * m, f0);
    return SKIN_LOBE_MIX * sharp + (1.0 - SKIN_LOBE_MIX) * broad;
}

//#if LAYERS_A
struct Rt {
    r: vec3<f32>,
    t: vec3<f32>,
}

fn layer_rt(layer: u32, x_mm: f32) -> Rt {
    let n = frame.counts.z;
    let u = x_mm / (x_mm + TABLE_X0_MM);
    let f = u * f32(n - 1u);
    let i = min(u32(f), n - 2u);
    let w = f - f32(i);
    let r_row = 3u * layer * n;
    let t_row = r_row + n;
    var out: Rt;
    out.r = mix(tables[r_row + i].rgb, tables[r_row + i + 1u].rgb, w);
    out.t = mix(tables[t_row + i].rgb, tables[t_row + i + 1u].rgb, w);
    return out;
}

// The interference colour of layer `layer`'s shimmer at cos(h, l) = `c` (linear interpolation).
fn interference(layer: u32, c: f32) -> vec3<f32> {
    let n = frame.counts.z;
    let row = (3u * layer + 2u) * n;
    let f = clamp(c, 0.0, 1.0) * f32(n - 1u);
    let i = min(u32(f), n - 2u);
    return mix(tables[row + i].rgb, tables[row + i + 1u].rgb, f - f32(i));
}
//#endif

//#if SHADOWS
//#insert shadow_factor
//#endif

//#if ENV
//#insert sh_eval
//#endif

@compute @workgroup_size(8, 8)
fn cs_lighting(@builtin(global_invocation_id) id: vec3<u32>) {
    if any(id.xy >= textureDimensions(out_diffuse)) {
        return;
    }
    let p = vec2<i32>(id.xy);
    // The pixel's centre, as a fragment's position.
    let out = lighting_at(vec2<f32>(id.xy) + 0.5);
    textureStore(out_diffuse, p, out.diffuse);
    textureStore(out_surface, p, out.surface);
//#if LAYERS_A
    textureStore(out_exit_t, p, out.exit_t);
//#endif
}

// The half-space diffuse law (render/src/dielectric_brdf.rs, `GpuTable`, whose `pi_brdf` and
// `reflectance` are these functions' CPU twins; the curvature ratios are `gpu_ratios` of
// render/src/curved_half_space.rs, checked on a sphere by render/tests/curved_half_space.rs):
// adding-doubling's angular law of a half-space under the skin's boundary, the albedo read as its
// normal-incidence reflectance r_n. The table: a header of 8 (node count K, cosine count M, r_max, η, curvature
// node count J, the largest |H|), then per albedo node k (r_n = r_max·(k/(K − 1))²) the M×M shape
// πf(μ, μ₀)(μ + μ₀)/(r_n T(μ) T(μ₀)) and the M exit values R(μ)/(r_n T(μ)), T the boundary's
// Fresnel transmittance, cosines even in [0, 1]; then J ratios per channel of the environment
// term's curvature correction (render/src/curved_half_space.rs), H even in ±|H|max.
struct HalfSpaceNodes {
    // Offset of each channel's lower node, and the upper node's weight.
    lo: vec3<u32>,
    f: vec3<f32>,
    // The view's cosine and the boundary's transmittance there (the same for every light).
    mu: f32,
    t_mu: f32,
}

// A pixel's nodes: its albedo a per channel and the view's cosine mu.
fn half_space_nodes(a: vec3<f32>, mu: f32) -> HalfSpaceNodes {
    let last = half_space_table[0] - 1.0;
    let m = u32(half_space_table[1]);
    let at = sqrt(clamp(a / half_space_table[2], vec3<f32>(0.0), vec3<f32>(1.0))) * last;
    let k = min(floor(at), vec3<f32>(last - 1.0));
    return HalfSpaceNodes(8u + vec3<u32>(k) * (m * m + m), at - k, mu, half_space_t(mu));
}

// The boundary's Fresnel transmittance at external cosine mu (1 at η = 1: no boundary).
fn half_space_t(mu: f32) -> f32 {
    let eta = half_space_table[3];
    return select(1.0 - fresnel_in(mu, eta), 1.0, eta <= 1.0);
}

// The M×M values at `base`, bilinearly at (x, y) ∈ [0, 1]².
fn half_space_grid(base: u32, x: f32, y: f32) -> f32 {
    let m = u32(half_space_table[1]);
    let ax = x * f32(m - 1u);
    let ay = y * f32(m - 1u);
    let i = min(u32(ax), m - 2u);
    let j = min(u32(ay), m - 2u);
    let fx = ax - f32(i);
    let fy = ay - f32(j);
    let r0 = base + i * m + j;
    let low = mix(half_space_table[r0], half_space_table[r0 + 1u], fy);
    let high = mix(half_space_table[r0 + m], half_space_table[r0 + m + 1u], fy);
    return mix(low, high, fx);
}

// πf(μ, μ₀) per channel of albedo a: radiance towards the view's μ per unit irradiance from μ₀,
// times π.
fn half_space_pi_f(n: HalfSpaceNodes, a: vec3<f32>, mu0: f32) -> vec3<f32> {
    let m = u32(half_space_table[1]);
    let per = m * m + m;
    var shape = vec3<f32>(0.0);
    for (var c = 0u; c < 3u; c++) {
        shape[c] = mix(half_space_grid(n.lo[c], n.mu, mu0), half_space_grid(n.lo[c] + per, n.mu, mu0), n.f[c]);
    }
    return a * shape * (n.t_mu * half_space_t(mu0) / max(n.mu + mu0, 1e-6));
}

// R(μ) per channel of albedo a at the view's μ: the light returned from μ (and, by reciprocity,
// the radiance towards μ under a uniform sky of radiance 1).
fn half_space_r(n: HalfSpaceNodes, a: vec3<f32>) -> vec3<f32> {
    let m = u32(half_space_table[1]);
    let per = m * m + m;
    let at = n.mu * f32(m - 1u);
    let i = min(u32(at), m - 2u);
    let fi = at - f32(i);
    var exit = vec3<f32>(0.0);
    for (var c = 0u; c < 3u; c++) {
        let lo = n.lo[c] + m * m + i;
        let below = mix(half_space_table[lo], half_space_table[lo + 1u], fi);
        let above = mix(half_space_table[lo + per], half_space_table[lo + per + 1u], fi);
        exit[c] = mix(below, above, n.f[c]);
    }
    return a * exit * n.t_mu;
}

// The curvature correction of the environment term at mean curvature h (mm⁻¹), per channel.
fn half_space_curvature(h: f32) -> vec3<f32> {
    let j = u32(half_space_table[4]);
    let h_max = half_space_table[5];
    let m = u32(half_space_table[1]);
    let start = 8u + u32(half_space_table[0]) * (m * m + m);
    let at = (clamp(h, -h_max, h_max) / h_max * 0.5 + 0.5) * f32(j - 1u);
    let i = min(u32(at), j - 2u);
    let f = at - f32(i);
    var out = vec3<f32>(1.0);
    for (var c = 0u; c < 3u; c++) {
        let o = start + c * j + i;
        out[c] = mix(half_space_table[o], half_space_table[o + 1u], f);
    }
    return out;
}

// The surface's change toward the neighbouring pixel at offset d: position and normal, or none
// off the skin's geometry.
struct SurfaceStep {
    dp: vec3<f32>,
    dn: vec3<f32>,
    ok: bool,
}

fn surface_step(p: vec2<i32>, d: vec2<i32>, world: vec3<f32>, n: vec3<f32>) -> SurfaceStep {
    let q = p + d;
    let size = vec2<i32>(textureDimensions(gb_normal));
    var step = SurfaceStep(vec3<f32>(0.0), vec3<f32>(0.0), false);
    if any(q < vec2<i32>(0)) || any(q >= size) {
        return step;
    }
    let nd = textureLoad(gb_normal, q, 0);
    if nd.w == 0.0 {
        return step;
    }
    step.dp = world_at(vec2<f32>(q) + 0.5, textureLoad(gb_depth, q, 0).r) - world;
    step.dn = normalize(nd.xyz) - n;
    step.ok = true;
    return step;
}

// The change across the pixel from the steps toward a and b on opposite sides: the central
// difference a − b where both are on the surface at similar distances (it averages the
// triangles on both sides), else the step to the nearer point (a silhouette or a depth jump is on
// the far side); dn = S dp holds for either sign.
fn across(a: SurfaceStep, b: SurfaceStep) -> SurfaceStep {
    if a.ok && b.ok {
        let la = dot(a.dp, a.dp);
        let lb = dot(b.dp, b.dp);
        if max(la, lb) < 9.0 * min(la, lb) {
            return SurfaceStep(a.dp - b.dp, a.dn - b.dn, true);
        }
    }
    if !b.ok || (a.ok && dot(a.dp, a.dp) <= dot(b.dp, b.dp)) {
        return a;
    }
    return b;
}

// How far (pixels) the curvature's differences reach on each side: two, so that a central
// difference spans four pixels and the triangles' facets of interpolated normals average out.
const CURVATURE_REACH: i32 = 2;

// The mean curvature H (mm⁻¹, positive where convex) at the pixel: half the trace of the shape
// operator dn = S dp, solved from one change in x and one in y (S = (PᵀP)⁻¹PᵀN in their basis);
// 0 where the pixel has no neighbour on the surface in either direction. Checked on a sphere's
// 1/R by render/tests/curved_half_space.rs.
fn mean_curvature(p: vec2<i32>, world: vec3<f32>, n: vec3<f32>) -> f32 {
    let r = CURVATURE_REACH;
    let x = across(surface_step(p, vec2<i32>(r, 0), world, n), surface_step(p, vec2<i32>(-r, 0), world, n));
    let y = across(surface_step(p, vec2<i32>(0, r), world, n), surface_step(p, vec2<i32>(0, -r), world, n));
    if !(x.ok && y.ok) {
        return 0.0;
    }
    let g00 = dot(x.dp, x.dp);
    let g01 = dot(x.dp, y.dp);
    let g11 = dot(y.dp, y.dp);
    let det = g00 * g11 - g01 * g01;
    if det <= 1e-12 * g00 * g11 {
        return 0.0;
    }
    let trace = g11 * dot(x.dp, x.dn) - g01 * (dot(y.dp, x.dn) + dot(x.dp, y.dn)) + g00 * dot(y.dp, y.dn);
    return 0.5 * trace / det;
}

fn lighting_at(frag: vec2<f32>) -> LightingOut {
    let p = vec2<i32>(frag);
    var out: LightingOut;
    let nd = textureLoad(gb_normal, p, 0);
    if nd.w == 0.0 {
        out.diffuse = vec4<f32>(0.0);
        out.surface = vec4<f32>(0.0);
//#if LAYERS_A
        out.exit_t = vec4<f32>(1.0);
//#endif
        return out;
    }
    let n = normalize(nd.xyz);
    let albedo_skin = textureLoad(gb_albedo, p, 0);
    let albedo = albedo_skin.rgb;
    let is_skin = albedo_skin.a > 0.5;
    let depth = textureLoad(gb_depth, p, 0).r;
    let world = world_at(frag, depth);
    let v = normalize(frame.camera_pos.xyz - world);
//#if GLITTER
    // The pixel's footprint on the flake fields and the UV frame about this normal.
    let glitter_texel = textureLoad(gb_glitter, p, 0);
    let glitter_uv = vec2<f32>(bitcast<f32>(glitter_texel.x), bitcast<f32>(glitter_texel.y));
    let glitter_code = unpack2x16snorm(glitter_texel.z);
    let glitter_half = footprint_decode(glitter_code);
    let glitter_t0 = oct_decode(unpack2x16snorm(glitter_texel.w));
    let glitter_tu = glitter_t0 - n * dot(n, glitter_t0);
    let glitter_t = glitter_tu * inverseSqrt(max(dot(glitter_tu, glitter_tu), 1e-30));
    let glitter_b = cross(n, glitter_t) * select(-1.0, 1.0, glitter_code.x >= 0.0);
//#endif

    // Cosmetic stack, bottom to top: R seen from above, R seen from below (from the skin), T; in
    // the compositing basis.
    var r_top = vec3<f32>(0.0);
    var r_below = vec3<f32>(0.0);
    var t = vec3<f32>(1.0);
//#if LAYERS_A
    var layer_t: array<vec3<f32>, 8>;
    var thickness: array<f32, 8>;
    let ta = textureLoad(gb_thickness_a, p, 0);
    for (var i = 0u; i < min(LAYERS, 4u); i++) {
        thickness[i] = ta[i];
    }
//#endif
//#if LAYERS_B
    let tb = textureLoad(gb_thickness_b, p, 0);
    for (var i = 4u; i < LAYERS; i++) {
        thickness[i] = tb[i - 4u];
    }
//#endif
//#if LAYERS_A
    // Whether any layer covers the pixel: where none does, the skin keeps its albedo exactly.
    var covered = false;
    for (var i = 0u; i < LAYERS; i++) {
        covered = covered || thickness[i] > 0.0;
        let l = layer_rt(i, thickness[i]);
        let inter = 1.0 / (1.0 - l.r * r_top);
        r_below = r_below + t * t * l.r * inter;
        r_top = l.r + l.t * l.t * r_top * inter;
        t = l.t * t * inter;
        // The lobes below are attenuated in linear sRGB (exactly 1 where the layer is absent).
        layer_t[i] = select(BASIS_TO_SRGB * l.t, vec3<f32>(1.0), thickness[i] <= 0.0);
    }
//#endif

    // The half-space law reads the albedo as the normal-incidence reflectance r_n; it weighs each
    // light's irradiance by πf(μ, μ₀) and the environment's by R(μ) (μ: the view's cosine, μ₀:
    // the light's).
    let half_space = frame.sss.w > 0.5 && is_skin;
    let hs_a = clamp(albedo, vec3<f32>(0.0), vec3<f32>(1.0));
    let hs_mu = clamp(dot(n, v), 0.0, 1.0);
    var hs_nodes = HalfSpaceNodes(vec3<u32>(0u), vec3<f32>(0.0), 0.0, 0.0);
    if half_space {
        hs_nodes = half_space_nodes(hs_a, hs_mu);
    }
    // Σ over lights of irradiance × πf (used only by the half-space law).
    var weighted = vec3<f32>(0.0);

    // Irradiance and specular of every light.
    var irradiance = vec3<f32>(0.0);
    var specular = vec3<f32>(0.0);
    for (var li = 0u; li < frame.counts.x; li++) {
        let light = frame.lights[li];
        let arrival = light_arrival(light, world);
        let l = arrival.l;
        let e = arrival.e;
        let n_dot_l = dot(n, l);
        if n_dot_l <= 0.0 {
            continue;
        }
        var visible = 1.0;
//#if SHADOWS
        visible = shadow_factor(light, world, n);
//#endif
        let e_n = e * (n_dot_l * visible);
        irradiance += e_n;
        if half_space {
            let mu0 = min(n_dot_l, 1.0);
            weighted += e_n * half_space_pi_f(hs_nodes, hs_a, mu0);
        }
        if frame.skin.z > 0.0 {
            // The skin's lobes × its specular scale (the G-buffer normal's w: cavity × oiliness).
            var lobes = vec3<f32>(skin_lobes(n, l, v, frame.skin.x, frame.skin.y) * nd.w);
//#if LAYERS_A
            for (var i = 0u; i < LAYERS; i++) {
                // x: roughness, y: F0, z: full-coverage thickness, w: the finish's clarity.
                let q = frame.layers[i].params;
                let coverage = clamp(thickness[i] / q.z, 0.0, 1.0);
                let through = 1.0 - coverage * (1.0 - q.w);
                var own = vec3<f32>(coverage * kelemen(n, l, v, q.x, q.y));
                // Shimmer: the platelets' lobe (spread film.z, Fresnel 1) × their interference
                // colour at the half vector, × strength film.y.
                let film = frame.layers[i].film;
                if film.y > 0.0 {
                    let h_un = l + v;
                    let c = select(0.0, dot(h_un, l) * inverseSqrt(max(dot(h_un, h_un), 1e-12)), dot(h_un, h_un) > 1e-8);
                    own += coverage * film.y * kelemen(n, l, v, film.z, 1.0) * interference(i, c);
                }
//#endif
//#if GLITTER
                // Glitter: the part of the footprint the layer's lit flakes cover × the light's
                // radiance × the flakes' colour (render/src/glitter.rs `sparkle_lobe`).
                let flakes = frame.layers[i].glitter;
                if flakes.x > 0.0 && thickness[i] > 0.0 {
                    let hg = (l + v) * inverseSqrt(max(dot(l + v, l + v), 1e-12));
                    let h_t = vec3<f32>(dot(hg, glitter_t), dot(hg, glitter_b), dot(hg, n));
                    // A film thinner than the preset's holds proportionally fewer flakes.
                    let nominal_mm = max(frame.layers[i].glitter_color.w, 1e-6);
                    let p_flake = flakes.z * clamp(thickness[i] / nominal_mm, 0.0, 1.0);
                    let field = FlakeField(flakes.x, flakes.y, p_flake, flakes.w, i);
                    let sparkle = pixel_sparkle(field, glitter_uv, glitter_half, h_t);
                    own += coverage * sparkle_lobe(sparkle, frame.layers[i].glitter_color.rgb, n_dot_l);
                }
//#endif
//#if LAYERS_A
                lobes = lobes * (through * layer_t[i] * layer_t[i]) + own;
            }
//#endif
            specular += e_n * lobes;
        }
    }
    // The skin's diffuse light: a dipole model (render/src/passes/dipole) takes over the lights'.
    var skin_irradiance = irradiance;
    var skin_weighted = weighted;
//#if DIPOLE
    skin_irradiance = vec3<f32>(0.0);
    skin_weighted = vec3<f32>(0.0);
//#endif
    // The cube atlas takes the environment's light into the skin too (through its Fresnel).
    var skin_env = 1.0;
//#if ATLAS
    skin_env = 0.0;
//#endif
//#if ENV
    let env_e = max(sh_irradiance(frame.sh, n), vec3<f32>(0.0));
    irradiance += env_e;
    skin_irradiance += env_e * skin_env;
    if half_space {
        var env_r = half_space_r(hs_nodes, hs_a);
        // With the skin's medium: a convex surface under light from every side returns more.
        if half_space_table[4] > 1.0 {
            env_r *= half_space_curvature(mean_curvature(p, world, n));
        }
        skin_weighted += env_e * skin_env * env_r;
    }
//#endif
    // The albedo the skin's light enters with: under the half-space law, the irradiance-weighted
    // mean of πf over the lights and R(μ) for the environment, so that the stack below composes
    // it exactly as it composes a Lambertian albedo.
    var skin_albedo = albedo;
    if half_space {
        skin_albedo = select(vec3<f32>(0.0), skin_weighted / max(skin_irradiance, vec3<f32>(1e-30)), skin_irradiance > vec3<f32>(0.0));
    }

    // Light into the skin per unit irradiance, albedo·T / (1 − R_below·albedo), and what crosses the
    // stack again on its way out, × T; without layers simply the albedo and T = 1.
    var skin_in = skin_albedo;
    var exit_t = vec3<f32>(1.0);
//#if LAYERS_A
    // Composed in the basis, then back in linear sRGB. The way out is applied after scattering
    // (the composite, or a diffusion model's gather) as a factor: the ratio of the two products
    // rebuilds the basis's albedo·T² / (1 − R_below·albedo) exactly where nothing scatters.
    if covered {
        let a = BASIS_FROM_SRGB * skin_albedo;
        let once = a * t / (1.0 - r_below * a);
        skin_in = max(BASIS_TO_SRGB * once, vec3<f32>(0.0));
        let twice = max(BASIS_TO_SRGB * (once * t), vec3<f32>(0.0));
        let t_srgb = clamp(BASIS_TO_SRGB * t, vec3<f32>(0.0), vec3<f32>(1.0));
        let ratio = clamp(twice / max(skin_in, vec3<f32>(1e-6)), vec3<f32>(0.0), vec3<f32>(1.0));
        exit_t = select(t_srgb, ratio, skin_in > vec3<f32>(1e-5));
        r_top = BASIS_TO_SRGB * r_top;
    }
//#endif
    if is_skin {
        out.diffuse = vec4<f32>(skin_in * skin_irradiance / PI, 1.0);
        out.surface = vec4<f32>(r_top * irradiance / PI + specular, 1.0);
    } else {
        out.diffuse = vec4<f32>(0.0);
        out.surface = vec4<f32>(albedo * irradiance / PI + specular, 1.0);
    }
//#if LAYERS_A
    out.exit_t = vec4<f32>(exit_t, 1.0);
//#endif
    return out;
}
