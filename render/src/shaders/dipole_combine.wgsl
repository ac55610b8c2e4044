// Dipole combination ([DirDipoleThesis] section 4.2, step 3): for each skin pixel, the average of
// the radiance maps over the directions from which the point was visible (its depth in that
// direction's depth map, within a bias), times the exit Fresnel transmittance T₂₁(ω_o), added to
// the skin's diffuse radiance. A point seen from no direction gets nothing.
//#insert diffusion
//#insert dipole_common

//#insert skin_pixel
@group(1) @binding(4) var maps: texture_2d_array<f32>;
@group(1) @binding(5) var map_depths: texture_2d_array<f32>;

@fragment
fn fs_dipole_combine(@builtin(position) frag: vec4<f32>) -> @location(0) vec4<f32> {
    let px = skin_pixel(frag);
    if !px.ok {
        return vec4<f32>(0.0);
    }
    let n = px.n;
    let x = px.x;
    let v = px.v;
    // Fix 2 (section 4.4.2): look the point up slightly inside along its normal.
    var xq = x;
    if (u32(dipole.fixes.w) & 2u) != 0u {
        xq = x - dipole.fixes.y * n;
    }
    let side = i32(dipole.counts.w);
    var sum = vec3<f32>(0.0);
    var seen = 0.0;
    for (var k = 0u; k < dipole.counts.x; k++) {
        let c = dipole.dir_view_proj[k] * vec4<f32>(xq, 1.0);
        let uv = vec2<f32>(c.x * 0.5 + 0.5, 0.5 - c.y * 0.5);
        if any(uv < vec2<f32>(0.0)) || any(uv >= vec2<f32>(1.0)) {
            continue;
        }
        // A direction that sees the back of the surface cannot see the point.
        let facing = dot(n, dipole.dir_axis[k].xyz);
        if facing <= 0.05 {
            continue;
        }
        let texel = vec2<i32>(uv * f32(side));
        let stored = textureLoad(map_depths, texel, i32(k), 0).r;
        // The map's depth is its texel centre's: on a slanted surface it differs from the point's
        // by up to a texel times the slope, so the bias grows with tan θ.
        let slope = sqrt(max(1.0 - facing * facing, 0.0)) / facing;
        // Fix 3 (section 4.4.3): compare in world units (mm along the direction) with a bias,
        // else in [0, 1] depth with a fixed one.
        var visible: bool;
        if (u32(dipole.fixes.w) & 4u) != 0u {
            let planes = dipole.dir_planes[k].xy;
            visible = ortho_depth_mm(planes, c.z) - dipole.fixes.z * (1.0 + slope) < ortho_depth_mm(planes, stored);
        } else {
            visible = c.z <= stored + 1e-4;
        }
        if visible {
            sum += textureLoad(maps, texel, i32(k), 0).rgb;
            seen += 1.0;
        }
    }
    if seen == 0.0 {
        return vec4<f32>(0.0);
    }
    let t21 = 1.0 - fresnel_in(dot(v, n), dipole.boundary.w);
    // The cosmetic stack's T on the way in (the exit pixel's, passes/skin_gather.rs).
    return vec4<f32>(sum / seen * t21 * px.t, 0.0);
}
