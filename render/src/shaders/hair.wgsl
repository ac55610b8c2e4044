// The hair pass (render/src/passes/hair.rs): each segment of a lash or brow strand is a fibre
// (a centre line and a radius), drawn as a screen-space quad around its projected centre line
// and shaded by the fibre model (render/src/fibre.rs `scattering`, twin of `fibre_scattering`
// below), at the segment's ends in the vertex stage. Antialiased, the quad is widened by a pixel and each fragment carries the exact box
// coverage of the fibre's strip (coverage.wgsl); aliased, the quad is the fibre's own width and
// every covered pixel centre is opaque, as the G-buffer would draw it. The pass accumulates
// premultiplied radiance and transmittance ("over", back to front as the CPU sorted them) into
// the hair target, which the composite lays over the frame in linear radiance.

struct HairPass {
    // x: 1 when antialiased, y: widening in pixels, z, w: unused
    params: vec4<f32>,
    // σa per unit radius of the lashes (rgb) and their albedo under the environment (w: unused)
    lash_sigma_a: vec4<f32>,
    lash_albedo: vec4<f32>,
    brow_sigma_a: vec4<f32>,
    brow_albedo: vec4<f32>,
    // x: longitudinal roughness (radians), yzw: unused
    fibre: vec4<f32>,
}

@group(1) @binding(0) var<uniform> hair_pass: HairPass;
@group(1) @binding(1) var shadow_maps: texture_depth_2d_array;
@group(1) @binding(2) var shadow_sampler: sampler_comparison;

//#insert shadow_factor
//#insert sh_eval
//#insert coverage

struct SegmentIn {
    // The centre line before the segment, its two ends and after it (mm); the ends' radii (mm).
    @location(0) prev: vec3<f32>,
    @location(1) p0: vec3<f32>,
    @location(2) p1: vec3<f32>,
    @location(3) next: vec3<f32>,
    @location(4) radii: vec2<f32>,
    // 0 lash, 1 brow
    @location(5) part: u32,
}

struct SegmentOut {
    @builtin(position) pos: vec4<f32>,
    // The segment's ends in pixels; its unit direction and normal on screen.
    @location(0) @interpolate(flat) a: vec2<f32>,
    @location(1) @interpolate(flat) b: vec2<f32>,
    // The joints' cutting directions (bisectors of the neighbouring segments' directions).
    @location(2) @interpolate(flat) cut_a: vec2<f32>,
    @location(3) @interpolate(flat) cut_b: vec2<f32>,
    // The ends' radii in pixels.
    @location(4) @interpolate(flat) radii_px: vec2<f32>,
    // The fibre's radiance, shaded at the segment's ends (the vertex stage) and interpolated.
    @location(5) radiance: vec3<f32>,
}

fn to_pixels(clip: vec4<f32>) -> vec2<f32> {
    let ndc = clip.xy / clip.w;
    return vec2<f32>((ndc.x * 0.5 + 0.5) * frame.viewport.x, (0.5 - 0.5 * ndc.y) * frame.viewport.y);
}

// The unit vector of `d`, or `fallback` for a (near) zero one.
fn unit_or(d: vec2<f32>, fallback: vec2<f32>) -> vec2<f32> {
    let l2 = dot(d, d);
    return select(fallback, d * inverseSqrt(l2), l2 > 1e-10);
}

@vertex
fn vs_hair(s: SegmentIn, @builtin(vertex_index) i: u32) -> SegmentOut {
    var out: SegmentOut;
    out.pos = vec4<f32>(-2.0, -2.0, 0.0, 1.0);
    let c0 = frame.view_proj * vec4<f32>(s.p0, 1.0);
    let c1 = frame.view_proj * vec4<f32>(s.p1, 1.0);
    if c0.w <= 1e-3 || c1.w <= 1e-3 {
        return out;
    }
    let a = to_pixels(c0);
    let b = to_pixels(c1);
    let dir = unit_or(b - a, vec2<f32>(1.0, 0.0));
    let cp = frame.view_proj * vec4<f32>(s.prev, 1.0);
    let cn = frame.view_proj * vec4<f32>(s.next, 1.0);
    let dir_prev = select(dir, unit_or(a - to_pixels(cp), dir), cp.w > 1e-3);
    let dir_next = select(dir, unit_or(to_pixels(cn) - b, dir), cn.w > 1e-3);
    let nrm = vec2<f32>(-dir.y, dir.x);
    // Radius in pixels: mm × focal length (pixels) / view depth (clip w).
    let r0 = s.radii.x * frame.projection.x / c0.w;
    let r1 = s.radii.y * frame.projection.x / c1.w;
    let widen = hair_pass.params.y;
    let half_width = max(r0, r1) + widen;
    let corner = array<u32, 6>(0u, 1u, 2u, 2u, 1u, 3u)[i % 6u];
    let at_b = (corner & 1u) == 1u;
    let end = select(c0, c1, at_b);
    // Along the segment, past each end by the half width so that the cut at the joint (the
    // bisector) lies inside the quad.
    let along = select(-half_width, half_width, at_b);
    let px = select(a, b, at_b) + dir * along + nrm * select(-half_width, half_width, corner >= 2u);
    let ndc = vec2<f32>(px.x * frame.viewport.z * 2.0 - 1.0, 1.0 - px.y * frame.viewport.w * 2.0);
    out.pos = vec4<f32>(ndc * end.w, end.z, end.w);
    out.a = a;
    out.b = b;
    out.cut_a = unit_or(dir_prev + dir, dir);
    out.cut_b = unit_or(dir + dir_next, dir);
    out.radii_px = vec2<f32>(r0, r1);
    let tangent = normalize(s.p1 - s.p0 + vec3<f32>(0.0, 0.0, 1e-9));
    out.radiance = fibre_radiance(select(s.p0, s.p1, at_b), tangent, s.part);
    return out;
}

//#insert fibre

// The fibre's radiance at `world` with tangent `tangent` (the lights with their shadows, and the
// environment through the fibre's albedo), for the part's absorption.
fn fibre_radiance(world: vec3<f32>, tangent: vec3<f32>, part: u32) -> vec3<f32> {
    let v = normalize(frame.camera_pos.xyz - world);
    // The fibre's normal toward the eye: where shadows are looked up and ambient light arrives.
    let facing = normalize(v - tangent * dot(v, tangent) + vec3<f32>(0.0, 1e-6, 0.0));
    var sigma_a = hair_pass.lash_sigma_a.rgb;
    var albedo = hair_pass.lash_albedo.rgb;
    if part == 1u {
        sigma_a = hair_pass.brow_sigma_a.rgb;
        albedo = hair_pass.brow_albedo.rgb;
    }
    var radiance = vec3<f32>(0.0);
    for (var i = 0u; i < frame.counts.x; i++) {
        let light = frame.lights[i];
        let arrival = light_arrival(light, world);
        var visible = 1.0;
//#if SHADOWS
        visible = shadow_factor(light, world, facing);
//#endif
        radiance += arrival.e * visible * fibre_scattering(tangent, arrival.l, v, sigma_a, hair_pass.fibre.x);
    }
//#if ENV
    radiance += albedo * sh_irradiance(frame.sh, facing) / PI;
//#endif
    return radiance;
}

@fragment
fn fs_hair(in: SegmentOut) -> @location(0) vec4<f32> {
    let p = in.pos.xy;
    // Each fragment belongs to one segment of its strand: between the cuts at its joints.
    if dot(p - in.a, in.cut_a) < 0.0 || dot(p - in.b, in.cut_b) >= 0.0 {
        discard;
    }
    let d = in.b - in.a;
    let len2 = max(dot(d, d), 1e-8);
    let t = clamp(dot(p - in.a, d) / len2, 0.0, 1.0);
    let dir = d * inverseSqrt(len2);
    let nrm = vec2<f32>(-dir.y, dir.x);
    let x = dot(p - in.a, nrm);
    let r = mix(in.radii_px.x, in.radii_px.y, t);
    var coverage = 1.0;
    if hair_pass.params.x > 0.5 {
        coverage = strip_coverage(x, r, nrm);
    } else if abs(x) > r {
        discard;
    }
    if coverage <= 0.0 {
        discard;
    }
    return vec4<f32>(in.radiance * coverage, coverage);
}
