// Cube-atlas gather ([Benmounah2009] sections 4.2-4.4), per skin pixel x with normal n:
// 1. the faces with a corner above x's tangent plane and sp = n·a > 0, greatest sp first;
// 2. the first that holds x (the self-occlusion test) is selected; none: no local term;
// 3. local: B = Σ_j E_j R_d(x_j → x) A_j over k×k taps on [−R, R]² around x's place there
//    (R = sp·reach·l_d when adaptive), the centre cell integrated over a disk of its area;
// 4. global: the opposite face's surface behind x lights a slab of the local thickness d:
//    B_g = E_s · T(d) (or, the paper's, a plane of real sources: E_s · α′/2 · e^{−σ_tr S});
// 5. L = T(η, n·v)/π · (B + B_g), times the cosmetic stack's T on the way in (the exit pixel's,
//    passes/skin_gather.rs), added to the skin's diffuse radiance.
// Derivations and the CPU twins: render/src/cube_atlas.rs, render/src/diffusion.rs.
//#insert diffusion
//#insert atlas_common

//#insert skin_pixel
@group(1) @binding(4) var atlas_irradiance: texture_2d_array<f32>;
@group(1) @binding(5) var atlas_normals: texture_2d_array<f32>;
@group(1) @binding(6) var atlas_depths: texture_2d_array<f32>;

// What the atlas holds at a texel: the point at its centre and the depth, its normal, the
// irradiance, n·p; ok when the texel is on the medium.
struct Stored {
    x: vec3<f32>,
    depth: f32,
    n: vec3<f32>,
    e: vec3<f32>,
    plane: f32,
    ok: bool,
}

fn stored_at(f: u32, texel: vec2<i32>) -> Stored {
    var s: Stored;
    s.ok = false;
    let side = i32(atlas.params.z);
    if any(texel < vec2<i32>(0)) || any(texel >= vec2<i32>(side)) {
        return s;
    }
    let depth = textureLoad(atlas_depths, texel, i32(f), 0).r;
    let nm = textureLoad(atlas_normals, texel, i32(f), 0);
    if depth >= 1.0 || nm.w < 0.5 {
        return s;
    }
    let ir = textureLoad(atlas_irradiance, texel, i32(f), 0);
    s.x = atlas_point(f, vec2<f32>(texel) + 0.5, depth);
    s.depth = depth;
    s.n = normalize(nm.xyz);
    s.e = ir.rgb;
    s.plane = ir.a;
    s.ok = true;
    return s;
}

// The self-occlusion test (cube_atlas::AtlasFrame::holds): does the texel x projects to on face
// f hold x itself?
fn holds(f: u32, x: vec3<f32>, n: vec3<f32>) -> bool {
    let test = atlas.settings.z;
    if test == 0u {
        return true;
    }
    let depth_texel = vec2<i32>(floor(atlas_texel(f, x)));
    let side = i32(atlas.params.z);
    if any(depth_texel < vec2<i32>(0)) || any(depth_texel >= vec2<i32>(side)) {
        return false;
    }
    let depth = textureLoad(atlas_depths, depth_texel, i32(f), 0).r;
    if depth >= 1.0 {
        return false;
    }
    let texel = atlas.params.y;
    if test == 1u {
        let plane = textureLoad(atlas_irradiance, depth_texel, i32(f), 0).a;
        return abs(plane - dot(n, x - atlas.cube.xyz)) < 2.0 * texel;
    }
    let p = atlas_point(f, vec2<f32>(depth_texel) + 0.5, depth);
    let stored_n = normalize(textureLoad(atlas_normals, depth_texel, i32(f), 0).xyz);
    return abs(dot(n, p - x)) < 0.5 * texel + 0.01 && dot(n, stored_n) > 0.70710678;
}

// [Benmounah2009] Table 1 corrected (diffusion.wgsl classic_between), channel c.
fn rd_between(c: u32, xi: vec3<f32>, ni: vec3<f32>, xo: vec3<f32>) -> f32 {
    return classic_between(atlas.medium[c], xi, ni, xo);
}

// ∫ R_d over a disk of radius a (diffusion::ChannelProfile::classic_disk_total), channel c.
fn rd_disk(c: u32, a: f32) -> f32 {
    let m = atlas.medium[c];
    let dr = sqrt(a * a + m.z * m.z);
    let dv = sqrt(a * a + m.w * m.w);
    return 0.5 * m.x * (exp(-m.y * m.z) - m.z * exp(-m.y * dr) / dr + exp(-m.y * m.w) - m.w * exp(-m.y * dv) / dv);
}

fn local_term(f: u32, sp: f32, x: vec3<f32>, n: vec3<f32>) -> vec3<f32> {
    let half = i32(atlas.settings.x);
    var radius_mm = atlas.kernel.x;
    if atlas.settings.y != 0u {
        radius_mm = clamp(sp, 0.0, 1.0) * radius_mm;
    }
    // Cells of side Δ (mm) tile [−R, R]²; in texels Δ / texel.
    let cell_mm = 2.0 * radius_mm / f32(2 * half + 1);
    let cell_texels = cell_mm / atlas.params.y;
    let centre = atlas_texel(f, x);
    let a = atlas.axis[f].xyz;
    var b = vec3<f32>(0.0);
    for (var dy = -half; dy <= half; dy++) {
        for (var dx = -half; dx <= half; dx++) {
            let t = centre + vec2<f32>(f32(dx), f32(dy)) * cell_texels;
            let s = stored_at(f, vec2<i32>(floor(t)));
            if !s.ok {
                continue;
            }
            // The surface a cell covers, times the agreement of the normals (1 on flat skin; the
            // dipole's plane breaks where the entry surface turns away from the exit, in folds).
            let area = cell_mm * cell_mm / max(dot(s.n, a), atlas.params.w) * max(dot(s.n, n), 0.0);
            if dx == 0 && dy == 0 {
                let r = sqrt(area / PI);
                b += s.e * vec3<f32>(rd_disk(0u, r), rd_disk(1u, r), rd_disk(2u, r));
            } else {
                // The tap's own point: its place in the face at the texel's depth.
                let xj = atlas_point(f, t, s.depth);
                let rd = vec3<f32>(rd_between(0u, xj, s.n, x), rd_between(1u, xj, s.n, x), rd_between(2u, xj, s.n, x));
                b += s.e * rd * area;
            }
        }
    }
    return b;
}

// A slab's diffuse transmittance (diffusion::ChannelProfile::slab_transmittance), channel c:
// α′ sinh(σ(z₀ + z_b)) cosh(σz_b) / sinh(σ(d + 2z_b)), in exponentials of non-positive arguments.
fn slab_transmittance(c: u32, d: f32) -> f32 {
    let m = atlas.medium[c];
    let zb = 0.5 * (m.w - m.z);
    let z0 = min(m.z, d);
    let s = m.y;
    if s * (d + 2.0 * zb) < 1e-4 {
        return m.x * (z0 + zb) / (d + 2.0 * zb);
    }
    let a = s * (z0 + zb);
    let bb = s * zb;
    let cc = s * (d + 2.0 * zb);
    return m.x * exp(a + bb - cc) * (1.0 - exp(-2.0 * a)) * (1.0 + exp(-2.0 * bb)) / (2.0 * (1.0 - exp(-2.0 * cc)));
}

fn global_term(f: u32, x: vec3<f32>, n_x: vec3<f32>) -> vec3<f32> {
    let back = f ^ 1u;
    let s = stored_at(back, vec2<i32>(floor(atlas_texel(back, x))));
    let a = atlas.axis[f].xyz;
    // The surface behind x: facing away from the selected face, and behind x along it.
    if !s.ok || dot(s.n, a) >= 0.0 || dot(x - s.x, a) <= 0.0 {
        return vec3<f32>(0.0);
    }
    var b = vec3<f32>(0.0);
    // The local thickness across the normal (a slab's, exactly).
    let d = max(dot(x - s.x, n_x), 0.0);
    for (var c = 0u; c < 3u; c++) {
        let m = atlas.medium[c];
        if atlas.settings.w == 1u {
            // [Benmounah2009] eq. 9 over the lit plane (diffusion::ChannelProfile::real_source_plane).
            b[c] = s.e[c] * 0.5 * m.x * exp(-m.y * length(s.x - m.z * s.n - x));
        } else {
            b[c] = s.e[c] * slab_transmittance(c, d);
        }
    }
    return b;
}

@fragment
fn fs_atlas_gather(@builtin(position) frag: vec4<f32>) -> @location(0) vec4<f32> {
    let px = skin_pixel(frag);
    if !px.ok {
        return vec4<f32>(0.0);
    }

    // 1. Chosen faces, sorted by sp (insertion sort of at most six).
    var order: array<u32, 6>;
    var sps: array<f32, 6>;
    var count = 0u;
    let h = atlas.cube.w;
    for (var f = 0u; f < 6u; f++) {
        let a = atlas.axis[f].xyz;
        let sp = dot(px.n, a);
        if sp <= 0.0 {
            continue;
        }
        var above = false;
        for (var k = 0u; k < 4u; k++) {
            let i = select(-1.0, 1.0, (k & 1u) != 0u);
            let j = select(-1.0, 1.0, (k & 2u) != 0u);
            let corner = atlas.cube.xyz + (a + atlas.right[f].xyz * i + atlas.up[f].xyz * j) * h;
            above = above || dot(px.n, corner - px.x) > 0.0;
        }
        if !above {
            continue;
        }
        var at = count;
        while at > 0u && sps[at - 1u] < sp {
            order[at] = order[at - 1u];
            sps[at] = sps[at - 1u];
            at -= 1u;
        }
        order[at] = f;
        sps[at] = sp;
        count += 1u;
    }
    if count == 0u {
        return vec4<f32>(0.0);
    }

    // 2-3. The first face that holds the point, and the local term there.
    var b = vec3<f32>(0.0);
    var selected = order[0];
    for (var i = 0u; i < count; i++) {
        if holds(order[i], px.x, px.n) {
            selected = order[i];
            b = local_term(order[i], sps[i], px.x, px.n);
            break;
        }
    }
    // 4. The global term through the thin part behind (also for points on no face).
    if atlas.settings.w != 0u {
        b += global_term(selected, px.x, px.n);
    }
    let t21 = 1.0 - fresnel_in(dot(px.v, px.n), atlas.params.x);
    return vec4<f32>(b * t21 * px.t / PI, 0.0);
}
