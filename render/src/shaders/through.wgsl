// Inserted into thickness.wgsl (the slab variant): the transmission gather, read from the
// lights' shadow maps (SlabThrough::Gather).

// The flux through the exit face (outward normal `no`) at `xo` of a unit point source of the
// diffusion equation at `s`, with its image across the exit face's extrapolated boundary z_b
// outside it (of opposite sign, so the fluence vanishes there): h the source's depth below the
// exit's tangent plane, ρ its offset along it,
//   h·f(√(ρ² + h²)) + (h + 2z_b)·f(√(ρ² + (h + 2z_b)²)),  f(d) = (1 + σd)e^{−σd}/d³,
// a unit source's term of [Donner2005]'s multipole for a slab's transmission, its i = 0 pair,
// for a face of any orientation. Over the whole exit plane it totals 2π(e^{−σh} + e^{−σ(h+2z_b)}).
fn exit_flux(s: vec3<f32>, xo: vec3<f32>, no: vec3<f32>, z_b: f32, sigma: f32) -> f32 {
    let d = xo - s;
    let h = dot(d, no);
    let rho2 = max(dot(d, d) - h * h, 0.0);
    let h_image = h + 2.0 * z_b;
    return h * point_source_flux(1.0, sqrt(rho2 + h * h), sigma)
        + h_image * point_source_flux(1.0, sqrt(rho2 + h_image * h_image), sigma);
}

// The light entering at `xi` (outward normal `ni`) that leaves through the exit face at `xo`
// (outward normal `no`) per mm² of entry, one channel: the classic dipole's sources
// ([Jensen2001]: the real one z_r inside the entry face, the virtual one z_v outside it; `m` is
// (α′, σ_tr, z_r, z_v)), each seen through the exit face with its image there (`exit_flux`), at
// the medium's exact asymptotic decay `sigma` = κσt′ (Case's eigenvalue, the slab law's
// [`slab_transmittance::kappa`]) in place of diffusion's σ_tr, which decays too fast as the
// albedo falls (14% in green, 30% in blue for skin1). The projections on the exit's own normal
// make it a transmission kernel: across a finger the exit face turns away from the entry face,
// and the flux through it is not the entry plane's. Over a plane slab of thickness d at right
// angles it totals α′/2 (e^{−σ(d−z_r)} + e^{−σ(d−z_r+2z_b)} − e^{−σ(d+z_v)} − e^{−σ(d+z_v+2z_b)}),
// within 3-11% of the exact slab's diffuse transmittance in skin1's red from 7 to 15 mm
// (adding-doubling, iadpython; docs/BENCHMARKS.md).
fn through_entry(m: vec4<f32>, sigma: f32, xi: vec3<f32>, ni: vec3<f32>, xo: vec3<f32>, no: vec3<f32>) -> f32 {
    let z_b = 0.5 * (m.w - m.z);
    let real = exit_flux(xi - m.z * ni, xo, no, z_b, sigma);
    let virtual_source = exit_flux(xi + m.w * ni, xo, no, z_b, sigma);
    return max(m.x / (4.0 * PI) * (real - virtual_source), 0.0);
}

// `through_entry` per channel, at the medium's exact decay rates κσt′.
fn through_entry3(xi: vec3<f32>, ni: vec3<f32>, xo: vec3<f32>, no: vec3<f32>) -> vec3<f32> {
    let decay = params.slab_kappa.xyz * params.slab_sigma_t.xyz;
    return vec3<f32>(
        through_entry(params.gather_medium[0], decay.x, xi, ni, xo, no),
        through_entry(params.gather_medium[1], decay.y, xi, ni, xo, no),
        through_entry(params.gather_medium[2], decay.z, xi, ni, xo, no),
    );
}

// The transmission gather of one directional light at `world`, a pixel facing away from it
// (`kind.y` = 1, the slab law's alternative): [Dachsbacher2003]'s translucent shadow map, every
// entry the light's map holds within `params.gather.y` mm, each carried to the pixel by
// `through_entry`,
//   L = T(μ_v)/π · ∫ K(x_i → x) · T(μ_i) · E dA⊥,
// with the hidden-entry gather's samples (radii stratified by e^{−σρ}, the golden-angle spiral)
// and its rule for entries the camera sees (the kernel spreads their light; the gather takes
// what it misses). No plane is assumed: a finger's lit side, curved and narrower than the light
// spreads, counts as the map holds it.
fn through_gather(light: Light, axes: MapAxes, m: MapPoint, world: vec3<f32>, n: vec3<f32>, v: vec3<f32>) -> vec3<f32> {
    let texel_mm = max(axes.texel_mm.x, axes.texel_mm.y);
    let arrival = light_arrival(light, world);
    let l = arrival.l;
    let eta = params.gather.x;
    let reach = params.gather.y;
    let count = u32(params.gather.z);
    let sigma = params.gather.w;
    let kept = 1.0 - exp(-sigma * reach);
    var sum = vec3<f32>(0.0);
    for (var j = 0u; j < count; j++) {
        let u = (f32(j) + 0.5) / f32(count);
        let rho = -log(1.0 - u * kept) / sigma;
        let area = 2.0 * PI * rho * kept / (sigma * exp(-sigma * rho));
        let phi = f32(j) * 2.39996323;
        let o = rho * vec2<f32>(cos(phi), sin(phi));
        var e: MapPoint;
        e.uv = m.uv + vec2<f32>(o.x, -o.y) * axes.uv_per_mm;
        if any(e.uv < vec2<f32>(0.0)) || any(e.uv >= vec2<f32>(1.0)) {
            continue;
        }
        e.texel = vec2<i32>(e.uv * vec2<f32>(axes.size));
        let stored = textureLoad(shadow_depths, e.texel, i32(light.shadow.x), 0).r;
        if stored >= 1.0 {
            continue;
        }
        e.first_mm = light_depth_mm(light, stored);
        e.inside = true;
        let xi = world + o.x * axes.right + o.y * axes.up - l * (e.first_mm - m.depth_mm);
        let ni = entry_normal(light, axes, e, n, l);
        var unseen = 1.0;
        if seen_by_camera(xi, ni, 2.0 * texel_mm) {
            let mu_v = clamp(dot(ni, normalize(frame.camera_pos.xyz - xi)), 0.0, 1.0);
            unseen = 1.0 - kernel_share(xi - world, v) * mu_v;
        }
        let t_in = 1.0 - fresnel_in(dot(ni, l), eta);
        sum += through_entry3(xi, ni, world, n) * (t_in * area * unseen);
    }
    let t_out = 1.0 - fresnel_in(dot(n, v), eta);
    return arrival.e * sum * (t_out / (PI * f32(count))) * light.translucency.x;
}
