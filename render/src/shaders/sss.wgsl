// Separable screen-space subsurface scattering ([Huang2013] figure 1, step 4; [Jimenez2015]), one
// direction per pass, as a compute pass (one invocation a pixel, writing `dst`: on GPUs whose
// graphics pipeline runs on a few of their SMs, such as the H100/H200, a full-screen fragment
// pass took ten times as long; docs/BENCHMARKS.md, `rouge bench shading`). Kernel and rules: see
// the Rust module `sss` (its `separable_pass_cpu` is this shader on the CPU).

struct SssPass {
    // xy: direction in pixels (1, 0) or (0, 1); z: width (profile scale); w: depth follow (mm)
    dir: vec4<f32>,
    // x: sample count
    count: vec4<u32>,
    // x: offset (mm), yzw: weight per channel
    samples: array<vec4<f32>, 33>,
}

@group(1) @binding(0) var<uniform> sss_pass: SssPass;
@group(1) @binding(1) var src: texture_2d<f32>;
// The depth buffer as an unfilterable float texture (GLSL cannot read it as a depth texture).
@group(1) @binding(2) var src_depth: texture_2d<f32>;
@group(1) @binding(3) var linear_sampler: sampler;
@group(1) @binding(4) var dst: texture_storage_2d<rgba16float, write>;

@compute @workgroup_size(8, 8)
fn cs_sss(@builtin(global_invocation_id) id: vec3<u32>) {
    if any(id.xy >= textureDimensions(dst)) {
        return;
    }
    // The pixel's centre, as a fragment's position.
    textureStore(dst, vec2<i32>(id.xy), sss_at(vec2<f32>(id.xy) + 0.5));
}

fn sss_at(frag: vec2<f32>) -> vec4<f32> {
    let p = vec2<i32>(frag);
    let centre = textureLoad(src, p, 0);
    if centre.a < 0.5 {
        return centre;
    }
    let size = vec2<f32>(textureDimensions(src));
    let max_p = vec2<i32>(size) - 1;
    let z = max(linear_depth(textureLoad(src_depth, p, 0).r), 1e-3);
    let px_per_mm = frame.projection.x / z;
    let dir = sss_pass.dir.xy;
    let scale = sss_pass.dir.z * px_per_mm;
    let follow = sss_pass.dir.w;
    var sum = vec3<f32>(0.0);
    for (var j = 0u; j < sss_pass.count.x; j++) {
        let k = sss_pass.samples[j];
        let o = k.x * scale;
        if o == 0.0 {
            // The centre sample (and every sample at width 0): exact, no filtering.
            sum += centre.rgb * k.yzw;
            continue;
        }
        let pos = frag + dir * o;
        let c = textureSampleLevel(src, linear_sampler, pos / size, 0.0);
        var s = c.rgb + (1.0 - c.a) * centre.rgb;
        let q = clamp(vec2<i32>(floor(pos)), vec2<i32>(0), max_p);
        let dz = linear_depth(textureLoad(src_depth, q, 0).r) - z;
        var w = 1.0;
        if follow > 0.0 {
            w = clamp(abs(dz) / follow, 0.0, 1.0);
        }
        s = mix(s, centre.rgb, w);
        sum += s * k.yzw;
    }
    return vec4<f32>(sum, centre.a);
}
