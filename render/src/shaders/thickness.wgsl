// Thickness translucency ([BarreBrisebois2011], render/src/local_thickness.rs): for every light,
//   albedo/π · E · (s_light · s · saturate(V · −(L + N δ))^p + a) · T,
// added to the skin's diffuse radiance. T, the local thickness (white = thin), is the baked map
// the G-buffer sampled, or, per light, the falloff w(d) of the distance d the light travelled
// inside the mesh, read from the light's shadow map. The parameters come per material id.

@group(1) @binding(0) var gb_normal: texture_2d<f32>;
@group(1) @binding(1) var gb_albedo: texture_2d<f32>;
@group(1) @binding(2) var gb_depth: texture_2d<f32>;
@group(1) @binding(3) var gb_local: texture_2d<f32>;
// The lights' shadow maps as plain depths (textureLoad), for the shadow-map source.
@group(1) @binding(4) var shadow_depths: texture_2d_array<f32>;

struct ThicknessPass {
    // per material id (0: none): x distortion δ, y power p, z scale s, w ambient a
    materials: array<vec4<f32>, 4>,
    // shadow-map source: rgb the exponential rates per mm (or x the power exponent), w cutoff mm
    falloff: vec4<f32>,
    // x: 1 exponential falloff, 0 power falloff
    kind: vec4<u32>,
}
@group(1) @binding(5) var<uniform> params: ThicknessPass;

// The talk's term over albedo × irradiance; CPU twin: local_thickness::translucency_term.
fn translucency(l: vec3<f32>, n: vec3<f32>, v: vec3<f32>, m: vec4<f32>, light_scale: f32) -> f32 {
    let bent = l + n * m.x;
    let lobe = clamp(dot(v, -bent), 0.0, 1.0);
    var back = 0.0;
    if lobe > 0.0 {
        back = pow(lobe, m.y);
    }
    return (light_scale * m.z * back + m.w) / PI;
}

//#if THICKNESS_LIGHT
// w(d) of the bake's falloff (rouge_model::thickness::Falloff): exp(−k·d) per channel or
// (1 − d/cutoff)^exponent, 0 from the cutoff on.
fn falloff_weight(d_mm: f32) -> vec3<f32> {
    let cutoff = params.falloff.w;
    if d_mm >= cutoff {
        return vec3<f32>(0.0);
    }
    if params.kind.x == 1u {
        return exp(-params.falloff.rgb * d_mm);
    }
    return vec3<f32>(pow(1.0 - d_mm / cutoff, params.falloff.x));
}

// Distance along the light's projection axis (mm) of a [0, 1] shadow-map depth.
fn light_depth_mm(light: Light, d: f32) -> f32 {
    let near = light.translucency.y;
    let far = light.translucency.z;
    if light.translucency.w > 0.5 {
        return near * far / (far - d * (far - near));
    }
    return near + d * (far - near);
}

// How far the light travelled inside the mesh before `world`: its depth from the light minus
// the first surface the light met there (the shadow map), mm; 0 outside the map.
fn light_path_mm(light: Light, world: vec3<f32>) -> f32 {
    let p = light.shadow_view_proj * vec4<f32>(world, 1.0);
    let ndc = p.xyz / p.w;
    let uv = ndc.xy * vec2<f32>(0.5, -0.5) + 0.5;
    if any(uv < vec2<f32>(0.0)) || any(uv >= vec2<f32>(1.0)) || ndc.z > 1.0 {
        return 0.0;
    }
    let size = vec2<f32>(textureDimensions(shadow_depths).xy);
    let first = textureLoad(shadow_depths, vec2<i32>(uv * size), i32(light.shadow.x), 0).r;
    return max(light_depth_mm(light, ndc.z) - light_depth_mm(light, first), 0.0);
}
//#endif

@fragment
fn fs_thickness(@builtin(position) frag: vec4<f32>) -> @location(0) vec4<f32> {
    let p = vec2<i32>(frag.xy);
    let local = textureLoad(gb_local, p, 0);
    let id = u32(round(local.a * 3.0));
    if id == 0u {
        return vec4<f32>(0.0);
    }
    let m = params.materials[id];
    let n = normalize(textureLoad(gb_normal, p, 0).xyz);
    let albedo = textureLoad(gb_albedo, p, 0).rgb;
    let world = world_at(frag.xy, textureLoad(gb_depth, p, 0).r);
    let v = normalize(frame.camera_pos.xyz - world);
    var sum = vec3<f32>(0.0);
    for (var li = 0u; li < frame.counts.x; li++) {
        let light = frame.lights[li];
        var t = local.rgb;
//#if THICKNESS_LIGHT
        if light.shadow.x < 0.0 {
            continue;
        }
        t = falloff_weight(light_path_mm(light, world));
//#endif
        let arrival = light_arrival(light, world);
        sum += arrival.e * t * translucency(arrival.l, n, v, m, light.translucency.x);
    }
    return vec4<f32>(albedo * sum, 0.0);
}
