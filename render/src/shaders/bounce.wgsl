// Light between surfaces: one bounce of the skin's glow from the pixels the camera sees to every
// skin pixel facing them (render/src/bounce.rs has the estimate, its sampling and its domain;
// passes/bounce.rs runs it). Two compute passes: `cs_bounce_gather` writes each skin pixel's
// irradiance from the glow of the skin around it into `out` (the bounce-light target);
// `cs_bounce_add` averages it over the pixel's neighbours on the same surface (the irradiance
// varies over millimetres, the samples' noise per pixel) and writes `skin` (the skin's diffuse
// radiance, before the blur) plus the light it sends back into `out` (the bounced target).

struct BouncePass {
    // x: samples, y: reach (mm), z: near (mm), w: the least cosine toward the camera of a source
    params: vec4<f32>,
}

@group(1) @binding(0) var<uniform> bounce: BouncePass;
@group(1) @binding(1) var skin: texture_2d<f32>;
@group(1) @binding(2) var gb_normal: texture_2d<f32>;
@group(1) @binding(3) var gb_albedo: texture_2d<f32>;
// The depth buffer as an unfilterable float texture (as sss.wgsl reads it).
@group(1) @binding(4) var gb_depth: texture_2d<f32>;
// The cosmetic stack's transmittance; bound to a stand-in and not read when the look has no
// layers.
@group(1) @binding(5) var gb_exit_t: texture_2d<f32>;
@group(1) @binding(6) var out: texture_storage_2d<rgba16float, write>;
// The gathered irradiance (the add pass's input; a stand-in in the gather).
@group(1) @binding(7) var gathered: texture_2d<f32>;

// A skin pixel as a source or receiver: world position (mm), unit normal, view depth (mm); ok
// is false where there is no skin.
struct Glow {
    x: vec3<f32>,
    n: vec3<f32>,
    z: f32,
    ok: bool,
}

// The cosmetic stack's transmittance at pixel p (1 without layers): read for the sources' light
// out and the receiver's light in, not for the add pass's neighbours.
fn stack_t(p: vec2<i32>) -> vec3<f32> {
    if frame.counts.y > 0u {
        return textureLoad(gb_exit_t, p, 0).rgb;
    }
    return vec3<f32>(1.0);
}

fn glow_at(p: vec2<i32>) -> Glow {
    var g: Glow;
    let nd = textureLoad(gb_normal, p, 0);
    g.ok = nd.w != 0.0 && textureLoad(gb_albedo, p, 0).a >= 0.5;
    if !g.ok {
        return g;
    }
    let d = textureLoad(gb_depth, p, 0).r;
    g.n = normalize(nd.xyz);
    g.x = world_at(vec2<f32>(p) + 0.5, d);
    g.z = max(linear_depth(d), 1e-3);
    return g;
}

// The irradiance at `r` (pixel p) from the glow of the skin pixels around it.
fn irradiance(p: vec2<i32>, r: Glow) -> vec3<f32> {
    let size = vec2<i32>(textureDimensions(skin));
    let f = frame.projection.x;
    let px_per_mm = f / r.z;
    // From half a pixel: `near` applies in the world (bounce.rs).
    let r0 = 0.5;
    let r1 = min(bounce.params.y * px_per_mm, length(vec2<f32>(size)));
    if r1 <= r0 {
        return vec3<f32>(0.0);
    }
    let span = log(r1 / r0);
    let count = u32(bounce.params.x);
    // A per-pixel turn and shift of the samples: neighbouring pixels' errors are independent.
    let h = fract(sin(vec2<f32>(dot(vec2<f32>(p), vec2<f32>(12.9898, 78.233)), dot(vec2<f32>(p), vec2<f32>(39.3468, 11.135)))) * 43758.5453);
    let turn = 2.0 * PI * h.x;
    var sum = vec3<f32>(0.0);
    for (var j = 0u; j < count; j++) {
        let u = (f32(j) + h.y) / f32(count);
        let rs = r0 * exp(u * span);
        let phi = f32(j) * 2.39996323 + turn;
        let q = vec2<i32>(floor(vec2<f32>(p) + 0.5 + rs * vec2<f32>(cos(phi), sin(phi))));
        if any(q < vec2<i32>(0)) || any(q >= size) {
            continue;
        }
        let s = glow_at(q);
        if !s.ok {
            continue;
        }
        let d = s.x - r.x;
        let dist = length(d);
        if dist <= bounce.params.z {
            continue;
        }
        let w = d / dist;
        let cos_r = dot(r.n, w);
        let cos_s = -dot(s.n, w);
        if cos_r <= 0.0 || cos_s <= 0.0 {
            continue;
        }
        let to_eye = frame.camera_pos.xyz - s.x;
        let ell = length(to_eye);
        let mu = max(dot(s.n, to_eye) / ell, bounce.params.w);
        // The pixel's area on the surface, mm²: solid angle (z/ℓ)³/f² times ℓ², over μ.
        let area = s.z * s.z * s.z / (ell * f * f * mu);
        let l = textureLoad(skin, q, 0).rgb * stack_t(q);
        // Times rs², the inverse of the sample's density up to the constant below.
        sum += l * (cos_r * cos_s * area / (dist * dist) * rs * rs);
    }
    return sum * (2.0 * PI * span / f32(count));
}

@compute @workgroup_size(8, 8)
fn cs_bounce_gather(@builtin(global_invocation_id) id: vec3<u32>) {
    if any(id.xy >= textureDimensions(out)) {
        return;
    }
    let p = vec2<i32>(id.xy);
    let r = glow_at(p);
    var e = vec3<f32>(0.0);
    if r.ok {
        e = irradiance(p, r);
    }
    textureStore(out, p, vec4<f32>(e, 0.0));
}

// Half the side of the add pass's square of neighbours, pixels.
const FILTER_RADIUS: i32 = 2;

@compute @workgroup_size(8, 8)
fn cs_bounce_add(@builtin(global_invocation_id) id: vec3<u32>) {
    if any(id.xy >= textureDimensions(out)) {
        return;
    }
    let p = vec2<i32>(id.xy);
    let own = textureLoad(skin, p, 0);
    let r = glow_at(p);
    if !r.ok {
        textureStore(out, p, own);
        return;
    }
    // The neighbours on the same surface: within a millimetre and a pixel's depth of the
    // pixel's plane, their normals within 60°.
    let size = vec2<i32>(textureDimensions(out));
    let tolerance = bounce.params.z + 2.0 * r.z / frame.projection.x;
    var sum = vec3<f32>(0.0);
    var weight = 0.0;
    for (var dy = -FILTER_RADIUS; dy <= FILTER_RADIUS; dy++) {
        for (var dx = -FILTER_RADIUS; dx <= FILTER_RADIUS; dx++) {
            let q = p + vec2<i32>(dx, dy);
            if any(q < vec2<i32>(0)) || any(q >= size) {
                continue;
            }
            let s = glow_at(q);
            if !s.ok || abs(dot(s.x - r.x, r.n)) > tolerance || dot(s.n, r.n) < 0.5 {
                continue;
            }
            sum += textureLoad(gathered, q, 0).rgb;
            weight += 1.0;
        }
    }
    // The pixel itself always counts: weight ≥ 1.
    let e = sum / max(weight, 1.0);
    let albedo = textureLoad(gb_albedo, p, 0).rgb;
    textureStore(out, p, vec4<f32>(own.rgb + e * albedo * stack_t(p) / PI, own.a));
}
