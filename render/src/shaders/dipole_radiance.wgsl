// Dipole radiance maps ([DirDipoleThesis] section 4.2, step 2): the mesh seen from direction k
// (orthographic, layer k of the maps). Each fragment x_o gathers, for every light with a light
// G-buffer, the BSSRDF over N samples on a disk around x_o's place in that light's G-buffer:
//   L(x_o) = Σ_l E_l Σ_j S(x_j, ω_l; x_o) w_j,
// with x_j read back from the light's depth and normal. The disk lies in the light's image plane,
// where the irradiance times the surface area is E_l times the projected area (the n·ω_l of the
// thesis's formula cancels the projection's 1/(n·ω_l)). Radii are exponential in σ
// (pdf σe^{−σr}, stratified, the angle by the golden ratio), so w_j = 2πr e^{σr}/(Nσ) is the inverse
// area density. Frame f rotates and shifts the pattern, and the texel keeps the running mean of
// its frames: mix(previous, this frame, 1/(f + 1)), the previous frame's maps read from the
// other half of a ping-pong pair (fixed-function constant blending was unreliable on lavapipe).
//#insert diffusion
//#insert dipole_common

@group(1) @binding(1) var light_normals: texture_2d_array<f32>;
@group(1) @binding(2) var light_depths: texture_2d_array<f32>;
@group(1) @binding(3) var previous_maps: texture_2d_array<f32>;

fn layer_view_proj(layer: u32) -> mat4x4<f32> {
    return dipole.dir_view_proj[layer];
}

//#insert layered_mesh

// A light G-buffer texel: world position and normal, or w = 0 where no skin is.
struct Entry {
    x: vec3<f32>,
    n: vec3<f32>,
    ok: bool,
}

// The light G-buffer at `t` (texels, continuous): the texel's normal and depth, the position at
// `t` itself, so that the entry point lies where the disk sample does.
fn light_entry(slot: u32, t: vec2<f32>) -> Entry {
    var e: Entry;
    let side = i32(dipole.counts.z);
    let texel = vec2<i32>(floor(t));
    e.ok = false;
    if any(texel < vec2<i32>(0)) || any(texel >= vec2<i32>(side)) {
        return e;
    }
    let nd = textureLoad(light_normals, texel, i32(slot), 0);
    let depth = textureLoad(light_depths, texel, i32(slot), 0).r;
    if nd.w < 0.5 || depth >= 1.0 {
        return e;
    }
    let uv = t / f32(side);
    let ndc = vec2<f32>(uv.x * 2.0 - 1.0, 1.0 - uv.y * 2.0);
    let h = dipole.light_inv_view_proj[slot] * vec4<f32>(ndc, depth, 1.0);
    e.x = h.xyz / h.w;
    e.n = normalize(nd.xyz);
    e.ok = true;
    return e;
}

const GOLDEN_ANGLE: f32 = 2.39996323;

// PCG's output permutation of one step (Jarzynski and Olano 2020, "Hash functions for GPU
// rendering"), nested over the texel's coordinates and the frame so that no line of texels
// shares a pattern; to [0, 1).
fn pcg(v: u32) -> u32 {
    let state = v * 747796405u + 2891336453u;
    let word = ((state >> ((state >> 28u) + 4u)) ^ state) * 277803737u;
    return (word >> 22u) ^ word;
}

fn hash01(p: vec2<u32>, f: u32) -> f32 {
    return f32(pcg(pcg(pcg(p.x) + p.y) + f)) / 4294967296.0;
}

@fragment
fn fs_dipole_radiance(in: LayerVsOut, @builtin(front_facing) front: bool) -> @location(0) vec4<f32> {
    let texel = vec2<u32>(in.clip.xy);
    if in.skin < 0.5 {
        return vec4<f32>(0.0, 0.0, 0.0, 1.0);
    }
    var no = normalize(in.normal);
    if !front {
        no = -no;
    }
    let xo = in.world;
    let sigma = dipole.sampling.x;
    let n = max(u32(dipole.sampling.y), 1u);
    let frame_index = dipole.sampling.z;
    let r_max = dipole.sampling.w;
    let side = f32(dipole.counts.z);
    var total = vec3<f32>(0.0);
    for (var slot = 0u; slot < dipole.counts.y; slot++) {
        let light = frame.lights[u32(dipole.light_info[slot].x)];
        let toward = normalize(light.position.xyz);
        // Fix 1 (section 4.4.1): look the exit point up a little inside, across the light.
        var xq = xo;
        if (u32(dipole.fixes.w) & 1u) != 0u {
            xq = xo - dipole.fixes.x * (no - toward * dot(toward, no));
        }
        let p = dipole.light_view_proj[slot] * vec4<f32>(xq, 1.0);
        let centre = vec2<f32>(p.x * 0.5 + 0.5, 0.5 - p.y * 0.5) * side;
        let texel_mm = dipole.light_info[slot].w;
        var sum = vec3<f32>(0.0);
        for (var j = 0u; j < n; j++) {
            // Stratified exponential radius, truncated at r_max (pdf renormalised).
            let jitter = hash01(texel, u32(frame_index) * 2u);
            let spin = 6.2831853 * hash01(texel, u32(frame_index) * 2u + 1u);
            let u = (f32(j) + jitter) / f32(n);
            let tail = 1.0 - exp(-sigma * r_max);
            let r = -log(1.0 - u * tail) / sigma;
            let theta = GOLDEN_ANGLE * f32(j) + spin;
            let offset_mm = r * vec2<f32>(cos(theta), sin(theta));
            // Texels: x along the clip x axis, y down.
            let t = centre + vec2<f32>(offset_mm.x, -offset_mm.y) / texel_mm;
            let e = light_entry(slot, t);
            if !e.ok {
                continue;
            }
            let pdf_area = sigma * exp(-sigma * r) / (2.0 * PI * max(r, 1e-4) * tail);
            let weight = 1.0 / (f32(n) * pdf_area);
            sum += bssrdf_in(e.x, e.n, toward, xo, no) * weight;
        }
        total += light.color.rgb * sum;
    }
    if frame_index > 0.5 {
        let previous = textureLoad(previous_maps, vec2<i32>(texel), i32(in.layer), 0).rgb;
        total = mix(previous, total, 1.0 / (frame_index + 1.0));
    }
    return vec4<f32>(total, 1.0);
}
