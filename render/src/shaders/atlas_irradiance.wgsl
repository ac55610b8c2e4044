// Cube-atlas irradiance ([Benmounah2009] sections 4.1-4.2): the mesh drawn orthographically onto
// face `instance_index` of its bounding cube. Each texel stores the irradiance that enters the
// medium there (eq. 4): every light, shadowed where it casts shadows, and the environment's SH,
// each through the Fresnel transmittance; n·p in alpha (p from the cube's centre, section
// 4.3.1); the normal, with w = 1 where the surface is the medium (eyes are not), in a second
// target; the depth in the attachment.
//#insert diffusion
//#insert atlas_common

@group(1) @binding(1) var shadow_maps: texture_depth_2d_array;
@group(1) @binding(2) var shadow_sampler: sampler_comparison;

//#if SHADOWS
//#insert shadow_factor
//#endif

//#if ENV
//#insert sh_eval
//#endif

fn layer_view_proj(layer: u32) -> mat4x4<f32> {
    return atlas.view_proj[layer];
}

//#insert layered_mesh

struct AtlasOut {
    // rgb: irradiance entering the medium; a: n·(p − centre), mm
    @location(0) irradiance: vec4<f32>,
    // xyz: normal; w: 1 on the medium
    @location(1) normal: vec4<f32>,
}

@fragment
fn fs_atlas_irradiance(in: LayerVsOut) -> AtlasOut {
    var out: AtlasOut;
    let n = normalize(in.normal);
    let plane = dot(n, in.world - atlas.cube.xyz);
    out.normal = vec4<f32>(n, 0.0);
    out.irradiance = vec4<f32>(0.0, 0.0, 0.0, plane);
    if in.skin < 0.5 {
        return out;
    }
    let eta = atlas.params.x;
    var e = vec3<f32>(0.0);
    for (var li = 0u; li < frame.counts.x; li++) {
        let light = frame.lights[li];
        let arrival = light_arrival(light, in.world);
        let cos_i = dot(n, arrival.l);
        if cos_i <= 0.0 {
            continue;
        }
        var visible = 1.0;
//#if SHADOWS
        visible = shadow_factor(light, in.world, n);
//#endif
        e += arrival.e * (cos_i * (1.0 - fresnel_in(cos_i, eta)) * visible);
    }
//#if ENV
    var sh = frame.sh;
    sh[0] = sh[0] * atlas.sh_fresnel.x;
    for (var i = 1u; i < 4u; i++) {
        sh[i] = sh[i] * atlas.sh_fresnel.y;
    }
    for (var i = 4u; i < 9u; i++) {
        sh[i] = sh[i] * atlas.sh_fresnel.z;
    }
    e += max(sh_irradiance(sh, n), vec3<f32>(0.0));
//#endif
    out.irradiance = vec4<f32>(e, plane);
    out.normal = vec4<f32>(n, 1.0);
    return out;
}
