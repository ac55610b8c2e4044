// G-buffer pass ([Huang2013] figure 1, step 1): world normal, albedo, and the thickness of every cosmetic
// layer at each pixel, read from the look's thickness maps in the mesh's UV space. Depth comes
// from the depth attachment.

@group(1) @binding(0) var thickness_maps: texture_2d_array<f32>;
@group(1) @binding(1) var map_sampler: sampler;
// Skin albedo texture (sRGB, read linear) and tangent-space normal map, when the scene has them.
@group(1) @binding(2) var albedo_map: texture_2d<f32>;
@group(1) @binding(3) var normal_map: texture_2d<f32>;
// The baked local thickness ([BarreBrisebois2011]; rgb, white = thin) in the mesh's UV space.
@group(1) @binding(4) var local_thickness_map: texture_2d<f32>;
//#if SKIN_DETAIL
// The skin's microgeometry (model/src/skin/detail.rs): the tileable relief with its mips (rgb: the
// tangent-space normal, averaged over finer texels; a: cavity), the region map in the mesh's UVs
// (r: pore depth relative to PORE_DEPTH_MM, g: the skin's specular scale from its oiliness), and
// a repeating trilinear sampler.
@group(1) @binding(5) var detail_tile: texture_2d<f32>;
@group(1) @binding(6) var detail_regions: texture_2d<f32>;
@group(1) @binding(7) var detail_sampler: sampler;
// The default head's expression wrinkles and lip furrows (model/src/skin/wrinkles.rs): per
// channel a family's depth, 0-1 of its depth at full weight, over the square frame.wrinkles[0]
// of the UVs.
@group(1) @binding(8) var wrinkle_map: texture_2d<f32>;

// The wrinkles' depth at `st` (the wrinkle map's texture coordinates), mm.
fn wrinkle_depth_mm(st: vec2<f32>, depth_mm: vec4<f32>) -> f32 {
    return dot(textureSampleLevel(wrinkle_map, map_sampler, st, 0.0), depth_mm);
}
//#endif

struct VsIn {
    @location(0) position: vec3<f32>,
    @location(1) normal: vec3<f32>,
    @location(2) uv: vec2<f32>,
    // rgb: linear albedo, a: 1 for skin (scatters, takes cosmetics), 0 otherwise (eyes)
    @location(3) albedo: vec4<f32>,
    // xyz: MikkTSpace tangent, w: bitangent sign (zero when the mesh has no tangents)
    @location(4) tangent: vec4<f32>,
}

struct VsOut {
    @builtin(position) clip: vec4<f32>,
    @location(0) normal: vec3<f32>,
    @location(1) uv: vec2<f32>,
    @location(2) albedo: vec4<f32>,
    @location(3) tangent: vec4<f32>,
    // World position, mm (the skin detail's frame from its derivatives).
    @location(4) world: vec3<f32>,
}

@vertex
fn vs_gbuffer(v: VsIn) -> VsOut {
    var out: VsOut;
    out.clip = frame.view_proj * vec4<f32>(v.position, 1.0);
    out.normal = v.normal;
    out.uv = v.uv;
    out.albedo = v.albedo;
    out.tangent = v.tangent;
    out.world = v.position;
    return out;
}

struct GbufferOut {
    // xyz: world normal, w: 0 where no mesh covers the pixel, else the skin's specular scale in
    // (0, 1] (cavity × oiliness with skin detail; 1 without)
    @location(0) normal: vec4<f32>,
    // rgb: albedo (stored sRGB-encoded, read back linear), a: skin flag
    @location(1) albedo: vec4<f32>,
//#if LAYERS_A
    // thickness (mm) of layers 0-3
    @location(2) thickness_a: vec4<f32>,
//#endif
//#if LAYERS_B
    // thickness (mm) of layers 4-7
    @location(3) thickness_b: vec4<f32>,
//#endif
//#if THICKNESS
    // rgb: local thickness (white = thin; 1 with the shadow-map source, which reads it per
    // light later), a: translucency material id / 3 (0: none, 1: skin)
    @location(4) local_thickness: vec4<f32>,
//#endif
//#if GLITTER
    // The glitter's flake-field coordinates (targets::GLITTER_FORMAT): x, y the UV in mm as f32
    // bits; z the footprint's half extents in mm, log-coded as two snorm16 (`footprint_encode`),
    // the first signed by the UV frame's handedness; w the octahedral code of the unit UV
    // tangent (+u) as two snorm16.
    @location(5) glitter: vec4<u32>,
//#endif
}

//#if GLITTER
//#insert glitter
//#endif

// Thickness of layer `i` at `uv`. Maps are stored like textures: image row 0 is v = 1.
fn layer_thickness(uv: vec2<f32>, i: u32) -> f32 {
    return max(textureSampleLevel(thickness_maps, map_sampler, vec2<f32>(uv.x, 1.0 - uv.y), i32(i), 0.0).r, 0.0);
}

@fragment
fn fs_gbuffer(in: VsOut, @builtin(front_facing) front: bool) -> GbufferOut {
    var n = normalize(in.normal);
    let tex_uv = vec2<f32>(in.uv.x, 1.0 - in.uv.y);
//#if SKIN_DETAIL
    // Derivatives in uniform control flow, before any branch: the detail's footprint and the UVs'
    // cotangent frame. The tile's image rows run down its v, hence −v.
    let detail_uv = vec2<f32>(in.uv.x, -in.uv.y) * frame.skin.w;
    let detail_dx = dpdx(detail_uv);
    let detail_dy = dpdy(detail_uv);
    let dp_dx = dpdx(in.world);
    let dp_dy = dpdy(in.world);
    let duv_dx = dpdx(in.uv);
    let duv_dy = dpdy(in.uv);
//#endif
//#if GLITTER
    // The flake field lies in UV × the mesh's mm per UV unit (render/src/glitter.rs); its
    // footprint and frame come from derivatives, taken here in uniform control flow.
    let glitter_uv = in.uv * frame.surface.x;
    let glitter_dx = dpdx(glitter_uv);
    let glitter_dy = dpdy(glitter_uv);
    let glitter_dp_dx = dpdx(in.world);
    let glitter_dp_dy = dpdy(in.world);
//#endif
//#if NORMAL_MAP
    if dot(in.tangent.xyz, in.tangent.xyz) > 0.0 {
        let t = normalize(in.tangent.xyz - n * dot(n, in.tangent.xyz));
        let b = cross(n, t) * select(1.0, -1.0, in.tangent.w < 0.0);
        let m = textureSampleLevel(normal_map, map_sampler, tex_uv, 0.0).xyz * 2.0 - 1.0;
        n = normalize(t * m.x + b * m.y + n * m.z);
    }
//#endif
    if !front {
        n = -n;
    }
    var out: GbufferOut;
    out.normal = vec4<f32>(n, 1.0);
    out.albedo = in.albedo;
//#if ALBEDO_MAP
    if in.albedo.a > 0.5 {
        out.albedo = vec4<f32>(textureSampleLevel(albedo_map, map_sampler, tex_uv, 0.0).rgb, 1.0);
    }
//#endif
    // Σ levelling·thickness over the layers here, mm (what fills the skin's relief; unused, and
    // left out by the compiler, without SKIN_DETAIL).
    var levelled_mm = 0.0;
//#if LAYERS_A
    var a = vec4<f32>(0.0);
    for (var i = 0u; i < min(LAYERS, 4u); i++) {
        a[i] = layer_thickness(in.uv, i) * in.albedo.a;
        levelled_mm += frame.layers[i].film.x * a[i];
    }
    out.thickness_a = a;
//#endif
//#if LAYERS_B
    var b = vec4<f32>(0.0);
    for (var i = 4u; i < LAYERS; i++) {
        b[i - 4u] = layer_thickness(in.uv, i) * in.albedo.a;
        levelled_mm += frame.layers[i].film.x * b[i - 4u];
    }
    out.thickness_b = b;
//#endif
//#if SKIN_DETAIL
    // Skin relief: the tile's slopes scaled by the region's pore depth and by what the layers
    // leave of the relief, exp(−Σ levelling·t / d) (rouge_measure::finish::pore_relief, whose
    // product over layers this is), applied in the UVs' cotangent frame ([Schuler2013]: T along
    // +u, B along +v, the longer of the two made unit); cavity and oiliness scale the skin's lobes.
    if in.albedo.a > 0.5 && frame.skin.w > 0.0 {
        let region = textureSampleLevel(detail_regions, map_sampler, tex_uv, 0.0);
        let depth_mm = max(region.r * PORE_DEPTH_MM, 1e-6);
        let amplitude = region.r * exp(-levelled_mm / depth_mm);
        let d = textureSampleGrad(detail_tile, detail_sampler, detail_uv, detail_dx, detail_dy);
        let m = d.xyz * 2.0 - 1.0;
        let slope = m.xy / max(m.z, 0.2) * amplitude;
        let n0 = out.normal.xyz;
        let dp2perp = cross(dp_dy, n0);
        let dp1perp = cross(n0, dp_dx);
        let t = dp2perp * duv_dx.x + dp1perp * duv_dy.x;
        let b = dp2perp * duv_dx.y + dp1perp * duv_dy.y;
        let unit = inverseSqrt(max(max(dot(t, t), dot(b, b)), 1e-20));
        let specular = mix(1.0, d.a, clamp(amplitude, 0.0, 1.0)) * region.g;
        out.normal = vec4<f32>(normalize(n0 + (t * slope.x + b * slope.y) * unit), max(specular, 1.0 / 64.0));
        // Wrinkles: the surface −Σ depth lowered by the furrows, its UV gradient by central
        // differences over the pixel's footprint (at least a texel: a box-filtered slope, so
        // furrows finer than a pixel fade instead of aliasing), as a surface gradient from the
        // UVs' derivatives ([Schuler2013]'s cotangent frame with its determinant), n − ∇h. Each
        // family is left by the layers above as the pores are, exp(−Σ levelling·t / depth), and
        // its depth blends from the right side's to the left's across the midline (±10 mm).
        let rect = frame.wrinkles[0];
        let st = vec2<f32>((in.uv.x - rect.x) / rect.z, 1.0 - (in.uv.y - rect.y) / rect.z);
        if rect.z > 0.0 && all(st > vec2<f32>(0.0)) && all(st < vec2<f32>(1.0)) {
            let weighted = mix(frame.wrinkles[2], frame.wrinkles[1], smoothstep(-10.0, 10.0, in.world.x));
            let depth_mm = weighted * exp(-levelled_mm / max(weighted, vec4<f32>(1e-6)));
            let e = max(rect.w, 0.5 * max(length(duv_dx), length(duv_dy)) / rect.z);
            let ds = wrinkle_depth_mm(st + vec2<f32>(e, 0.0), depth_mm) - wrinkle_depth_mm(st - vec2<f32>(e, 0.0), depth_mm);
            let dt = wrinkle_depth_mm(st + vec2<f32>(0.0, e), depth_mm) - wrinkle_depth_mm(st - vec2<f32>(0.0, e), depth_mm);
            // height h = −depth; st.x grows with u, st.y falls with v
            let dh_du = -ds / (2.0 * e * rect.z);
            let dh_dv = dt / (2.0 * e * rect.z);
            let n1 = out.normal.xyz;
            let r1 = cross(dp_dy, n1);
            let r2 = cross(n1, dp_dx);
            let det = dot(dp_dx, r1);
            if abs(det) > 1e-12 {
                let grad_h = ((r1 * duv_dx.x + r2 * duv_dy.x) * dh_du + (r1 * duv_dx.y + r2 * duv_dy.y) * dh_dv) / det;
                out.normal = vec4<f32>(normalize(n1 - grad_h), out.normal.w);
            }
        }
    }
//#endif
//#if GLITTER
    // The UV tangent: the surface gradient of u in the UVs' cotangent frame ([Schuler2013]),
    // made unit in the final normal's plane; the handedness is the sign of (n × t)·∇v. The
    // cotangent formula assumes (∂p/∂x × ∂p/∂y)·n > 0, as with GL's upward window y; WebGPU's
    // framebuffer y runs down, which turns both gradients around: `glitter_orient` turns them
    // back (checked on a plane against the CPU twin, render/tests/specular_gpu.rs).
    let glitter_n = out.normal.xyz;
    let glitter_perp_y = cross(glitter_dp_dy, glitter_n);
    let glitter_perp_x = cross(glitter_n, glitter_dp_dx);
    let glitter_orient = select(-1.0, 1.0, dot(cross(glitter_dp_dx, glitter_dp_dy), glitter_n) >= 0.0);
    let glitter_gu = (glitter_perp_y * glitter_dx.x + glitter_perp_x * glitter_dy.x) * glitter_orient;
    let glitter_gv = (glitter_perp_y * glitter_dx.y + glitter_perp_x * glitter_dy.y) * glitter_orient;
    let glitter_tu = glitter_gu - glitter_n * dot(glitter_n, glitter_gu);
    let glitter_t = glitter_tu * inverseSqrt(max(dot(glitter_tu, glitter_tu), 1e-30));
    let glitter_hand = select(-1.0, 1.0, dot(cross(glitter_n, glitter_t), glitter_gv) >= 0.0);
    let glitter_half = max(0.5 * (abs(glitter_dx) + abs(glitter_dy)), vec2<f32>(1e-4));
    out.glitter = vec4<u32>(
        bitcast<u32>(glitter_uv.x),
        bitcast<u32>(glitter_uv.y),
        pack2x16snorm(footprint_encode(glitter_half, glitter_hand)),
        pack2x16snorm(oct_encode(glitter_t)),
    );
//#endif
//#if THICKNESS
    let skin = select(0.0, 1.0, in.albedo.a > 0.5);
    var local = vec3<f32>(1.0);
//#endif
//#if THICKNESS_MAP
    local = clamp(textureSampleLevel(local_thickness_map, map_sampler, tex_uv, 0.0).rgb, vec3<f32>(0.0), vec3<f32>(1.0));
//#endif
//#if THICKNESS
    out.local_thickness = vec4<f32>(local * skin, skin / 3.0);
//#endif
    return out;
}
