// Composition ([Huang2013] figure 1, step 6): the scattered skin radiance leaving through the stack (× T),
// plus what left at the surface, over the background; then either linear radiance (for EXR) or
// exposure and Khronos PBR Neutral tone mapping into an sRGB target (for PNG and the app).

@group(1) @binding(0) var diffuse: texture_2d<f32>;
@group(1) @binding(1) var surface: texture_2d<f32>;
@group(1) @binding(2) var exit_t: texture_2d<f32>;
@group(1) @binding(3) var coverage: texture_2d<f32>;
// The hair pass's premultiplied radiance and transmittance (render/src/passes/hair.rs).
@group(1) @binding(5) var hair_image: texture_2d<f32>;

// Khronos PBR Neutral ([KhronosNeutral]): hue-preserving, linear below ~0.76, so product colours stay true.
fn pbr_neutral(color_in: vec3<f32>) -> vec3<f32> {
    let start = 0.76;
    let desat = 0.15;
    var color = color_in;
    let x = min(color.r, min(color.g, color.b));
    var offset = 0.04;
    if x < 0.08 {
        offset = x - 6.25 * x * x;
    }
    color -= offset;
    let peak = max(color.r, max(color.g, color.b));
    if peak < start {
        return color;
    }
    let d = 1.0 - start;
    let new_peak = 1.0 - d * d / (peak + d - start);
    color *= new_peak / peak;
    let g = 1.0 - 1.0 / (desat * (peak - new_peak) + 1.0);
    return mix(color, vec3<f32>(new_peak), g);
}

// The display target is a plain RGBA8 storage texture (sRGB formats cannot be storage
// textures), so the shader applies the sRGB transfer function ([IEC61966]) itself; the linear
// output is Rgba32Float, or Rgba16Float on wgpu's GL backend.
//#if HALF_LINEAR
alias LinearImage = texture_storage_2d<rgba16float, write>;
//#else
alias LinearImage = texture_storage_2d<rgba32float, write>;
//#endif
//#if DISPLAY
@group(1) @binding(4) var out_image: texture_storage_2d<rgba8unorm, write>;
//#else
@group(1) @binding(4) var out_image: LinearImage;
//#endif

fn display_encode(c: vec3<f32>) -> vec3<f32> {
    let lo = c * 12.92;
    let hi = 1.055 * pow(c, vec3<f32>(1.0 / 2.4)) - 0.055;
    return select(hi, lo, c <= vec3<f32>(0.0031308));
}

@compute @workgroup_size(8, 8)
fn cs_composite(@builtin(global_invocation_id) id: vec3<u32>) {
    let size = textureDimensions(out_image);
    if id.x >= size.x || id.y >= size.y {
        return;
    }
    let p = vec2<i32>(id.xy);
    var c: vec3<f32>;
    if textureLoad(coverage, p, 0).w == 0.0 {
        // The pixel centre's height, 0 at the top and 1 at the bottom.
        let y = (f32(id.y) + 0.5) * frame.viewport.w;
        c = frame.background.rgb * (1.0 - 0.6 * y);
    } else {
        var t = vec3<f32>(1.0);
//#if LAYERS_A
        t = textureLoad(exit_t, p, 0).rgb;
//#endif
        c = textureLoad(diffuse, p, 0).rgb * t + textureLoad(surface, p, 0).rgb;
    }
//#if HAIR
    // The hairs over everything behind them, in linear radiance.
    let hair = textureLoad(hair_image, p, 0);
    c = c * hair.a + hair.rgb;
//#endif
//#if DISPLAY
    textureStore(out_image, p, vec4<f32>(display_encode(pbr_neutral(max(c * frame.projection.w, vec3<f32>(0.0)))), 1.0));
//#else
    // Radiance is never negative; the hidden-entry gather's signed sum (thickness.wgsl) could
    // take a noisy pixel below 0, and the display's branch clamps the same way.
    textureStore(out_image, p, vec4<f32>(max(c, vec3<f32>(0.0)), 1.0));
//#endif
}
