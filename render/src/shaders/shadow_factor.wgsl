// A light's visibility at `world` (normal `n`) from its shadow map: 3×3 comparison samples with
// the light's depth bias and normal offset. Needs `shadow_maps: texture_depth_2d_array` and
// `shadow_sampler: sampler_comparison` declared by the pass (the lighting and cube-atlas passes).
fn shadow_factor(light: Light, world: vec3<f32>, n: vec3<f32>) -> f32 {
    if light.shadow.x < 0.0 {
        return 1.0;
    }
    let p = light.shadow_view_proj * vec4<f32>(world + n * light.shadow.z, 1.0);
    let ndc = p.xyz / p.w;
    let uv = ndc.xy * vec2<f32>(0.5, -0.5) + 0.5;
    let depth = ndc.z - light.shadow.y;
    if any(uv < vec2<f32>(0.0)) || any(uv > vec2<f32>(1.0)) || depth > 1.0 {
        return 1.0;
    }
    let layer = i32(light.shadow.x);
    var sum = 0.0;
    for (var dy = -1; dy <= 1; dy++) {
        for (var dx = -1; dx <= 1; dx++) {
            let o = vec2<f32>(f32(dx), f32(dy)) * light.shadow.w;
            sum += textureSampleCompareLevel(shadow_maps, shadow_sampler, uv + o, layer, depth);
        }
    }
    return sum / 9.0;
}
