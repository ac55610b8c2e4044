// The slab law over the columns of a directional light's map around the exit point
// (render/src/slab_extent.rs, whose `spread_light` is the converged twin): the light reaching the
// exit point through a plane slab entered at every offset within its lateral spread, each column
// counted as the map holds it. No mesh in a column: no light (the lit extent, `lit`). The exit
// point's own entry face: the centre's slab. A face more nearly opposite the exit face than that
// one, and nearer opposite than at right angles (a wedge's back face beside the top face the
// centre's light entered): that face's own plane slab, at the distance from the exit point to
// its plane and its own lateral spread. A lit side face's plane slab is the law's weakest (the
// exit face is at right angles to it); the opposite face's is the law's own case, so it serves
// wherever it is there (docs/BENCHMARKS.md "Each column its own slab").

// The lit extent's radii in units of 1/q: the Gamma(2) distribution's quantiles at the 16
// strata's midpoints, (j + ½)/16 (slab_extent::lit_extent_radii, whose test checks these).
const LIT_EXTENT_RADII = array<f32, 16>(
    0.273582, 0.511626, 0.701280, 0.876004, 1.046251, 1.217671, 1.394451, 1.580509,
    1.780213, 1.999098, 2.244936, 2.529734, 2.874153, 3.319419, 3.970680, 5.307471,
);

// How much more nearly opposite the exit face (in n·n_e) a column's face must be than the exit
// point's entry face to take its own slab: the faces' normals come from the map's one-sided
// slopes, which a curved surface turns a little from texel to texel
// (slab_extent::SPREAD_OPPOSITE_MARGIN).
const SPREAD_OPPOSITE_MARGIN: f32 = 0.1;
// And nearer opposite the exit face than at right angles to it (n·n_e below −√½): on a curved
// body the faces of the columns beside a terminator turn only part of the way, and the plane
// slab between such a face and the exit point is the law's weak case again (the spheres'
// crescents past the terminator too bright without it; slab_extent::SPREAD_OPPOSITE_MAX_COS).
const SPREAD_OPPOSITE_MAX_COS: f32 = -0.70710678;

// The light per channel, over E, that a plane slab `depth_mm` thick entered at the cosine mu_l
// (faces met as `faces`) sends to the exit point seen at mu_v: μ_l·T. `once` as in
// `slab_single`.
fn plane_slab_light(depth_mm: f32, mu_v: f32, mu_l: f32, faces: SlabFaces, once: f32) -> vec3<f32> {
    var t = vec3<f32>(0.0);
    for (var c = 0; c < 3; c++) {
        let tau = params.slab_sigma_t[c] * depth_mm;
        t[c] = mu_l * slab_transmittance(u32(c), params.slab_albedo[c], params.slab_kappa[c], tau, mu_v, mu_l, faces, params.slab_axes, once);
    }
    return t;
}

// A column's weight per channel at the radius rho (mm), drawn from p of the channel that spreads
// furthest (q_min): p(ρ; q) over p(ρ; q_min), (q/q_min)² e^{−(q − q_min)ρ}, for a slab spreading
// at the rates q.
fn spread_weight(q: vec3<f32>, q_min: f32, rho: f32) -> vec3<f32> {
    return (q / q_min) * (q / q_min) * exp(-(q - q_min) * rho);
}

// The spread law's light over E per channel (`light`) and the lit extent (`lit`: the share of
// the centre's spread p(ρ) = q²/(2π) e^{−qρ} where the map holds the mesh).
struct SlabSpread {
    light: vec3<f32>,
    lit: vec3<f32>,
}

// At the exit point `m` in the light's map (normal n), whose own entry `e` gives the plane slab
// `centre` (its light over E, μ_l·T·facing) spreading at the lateral rates q: the radii stratified
// in p of the channel that spreads furthest (q_min), each channel weighted by its own p over that
// one, (q/q_min)² e^{−(q − q_min)ρ}; angles on the golden-angle spiral. A column of another face
// weighs in at its own slab's rates. A point light's perspective map has no constant texel size
// (as in `entry_normal`): its plane counts as whole, the centre's.
fn slab_spread(light: Light, axes: MapAxes, m: MapPoint, e: SlabEntry, n: vec3<f32>, centre: vec3<f32>, q: vec3<f32>, once: f32) -> SlabSpread {
    var out: SlabSpread;
    if light.translucency.w > 0.5 {
        out.light = centre;
        out.lit = vec3<f32>(1.0);
        return out;
    }
    let q_min = min(q.x, min(q.y, q.z));
    let own_face = min(dot(n, e.n_e) - SPREAD_OPPOSITE_MARGIN, SPREAD_OPPOSITE_MAX_COS);
    // Where the exit point's own face is within the margin of opposite (a slab's interior), no
    // column's face can be nearer: every column the map holds is the centre's, and its face's
    // slope is not read.
    let any_own = own_face > -1.0;
    var sum = vec3<f32>(0.0);
    var lit = vec3<f32>(0.0);
    var total = vec3<f32>(0.0);
    for (var j = 0u; j < 16u; j++) {
        let rho = LIT_EXTENT_RADII[j] / q_min;
        let w = spread_weight(q, q_min, rho);
        total += w;
        let phi = f32(j) * 2.39996323;
        let uv = m.uv + rho * vec2<f32>(cos(phi), -sin(phi)) * axes.uv_per_mm;
        if any(uv < vec2<f32>(0.0)) || any(uv >= vec2<f32>(1.0)) {
            continue;
        }
        var s = m;
        s.uv = uv;
        s.texel = vec2<i32>(uv * vec2<f32>(axes.size));
        let stored = textureLoad(shadow_depths, s.texel, i32(light.shadow.x), 0).r;
        if stored >= 1.0 {
            continue;
        }
        lit += w;
        if !any_own {
            sum += w * centre;
            continue;
        }
        s.first_mm = light_depth_mm(light, stored);
        let n_e = entry_normal(light, axes, s, n, e.arrival.l);
        if dot(n, n_e) > own_face {
            sum += w * centre;
            continue;
        }
        // The column's entry, offset across the light from the exit point and ℓ toward it; the
        // slab is the exit point's distance from that face's plane (none if it lies beyond).
        let offset = rho * (cos(phi) * axes.right + sin(phi) * axes.up);
        let depth_mm = dot(offset + (m.depth_mm - s.first_mm) * e.arrival.l, n_e);
        if depth_mm <= 0.0 {
            continue;
        }
        let mu_l = max(dot(n_e, e.arrival.l), 1e-3);
        let facing = clamp(1.0 - dot(n, n_e), 0.0, 1.0);
        sum += spread_weight(lateral_rates(depth_mm), q_min, rho) * facing * plane_slab_light(depth_mm, e.mu_v, mu_l, slab_faces(params.slab_axes.x, e.mu_v, mu_l), once);
    }
    let norm = max(total, vec3<f32>(1e-12));
    out.light = sum / norm;
    out.lit = lit / norm;
    return out;
}
