// Thickness translucency ([BarreBrisebois2011], render/src/local_thickness.rs): for every light,
//   albedo/π · E · (s_light · s · saturate(V · −(L + N δ))^p + a) · T,
// added to the skin's diffuse radiance. T, the local thickness (white = thin), is the baked map
// the G-buffer sampled, or, per light, the falloff w(d) of the distance d the light travelled
// inside the mesh, read from the light's shadow map. The parameters come per material id.
// The slab law (THICKNESS_SLAB, render/src/slab_transmittance.rs) replaces the talk's term for
// the skin: the light through a plane slab of the thickness the light crossed, exactly,
//   E · μ_l · T(μ_v, μ_l; α′, σt′·d·μ_l) · clamp(1 − n·n_e, 0, 1) / π per light,
// μ_l the light's cosine on the face where it entered and n_e that face's normal (the slope of
// the shadow map there), d the distance it travelled inside, from the shadow map; taken over
// the plane's lateral spread as the light's map holds it (slab_spread.wgsl,
// render/src/slab_extent.rs: the share there, and a more nearly opposite face's own slab). Its light
// scattered once (T₁'s unreflected share) is marched along the view ray through the mesh to
// the back faces' depth instead (slab_march.wgsl), unscaled by the spread or the facing, where
// the back-face pass drew one.

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
    // x: 1 exponential falloff, 0 power falloff; y (slab law only): 1 where the light crosses
    // the mesh to a pixel facing away from a directional light, the hidden-entry gather alone
    // with the transmission kernel (through.wgsl) in place of the slab law
    kind: vec4<u32>,
    // The slab law's medium per channel: reduced albedo α′, Case's decay rate κ, and σt′ per mm;
    // the table's axes (slab.wgsl).
    slab_albedo: vec4<f32>,
    slab_kappa: vec4<f32>,
    slab_sigma_t: vec4<f32>,
    slab_axes: vec4<f32>,
    // The hidden-entry gather (slab law only): per channel the classic dipole's (α′, σ_tr, z_r,
    // z_v); x η, y reach (mm), z samples (0: off), w the radii's sampling rate (mm⁻¹).
    gather_medium: array<vec4<f32>, 3>,
    gather: vec4<f32>,
    // The screen-space kernel: x its reach on the surface (mm; 0: none runs), y the depth
    // difference (mm) over which it stops following a sample.
    screen_kernel: vec4<f32>,
}
@group(1) @binding(5) var<uniform> params: ThicknessPass;
//#if THICKNESS_SLAB
@group(1) @binding(6) var<storage, read> slab_table: array<f32>;
// The depth of the nearest back face at each pixel (passes/back_depth.rs): where the camera's ray
// leaves the mesh.
@group(1) @binding(7) var back_depth: texture_2d<f32>;
//#insert slab
//#insert diffusion
//#endif

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

// `world` in the light's shadow map: where it falls (uv in [0, 1)) and the texel there, its
// distance from the light and that of the first surface the light met there (mm); `inside` is
// false off the map.
struct MapPoint {
    uv: vec2<f32>,
    texel: vec2<i32>,
    depth_mm: f32,
    first_mm: f32,
    inside: bool,
}

fn map_point(light: Light, world: vec3<f32>) -> MapPoint {
    var m: MapPoint;
    let p = light.shadow_view_proj * vec4<f32>(world, 1.0);
    let ndc = p.xyz / p.w;
    m.uv = ndc.xy * vec2<f32>(0.5, -0.5) + 0.5;
    m.inside = all(m.uv >= vec2<f32>(0.0)) && all(m.uv < vec2<f32>(1.0)) && ndc.z <= 1.0;
    if !m.inside {
        return m;
    }
    m.texel = vec2<i32>(m.uv * vec2<f32>(textureDimensions(shadow_depths).xy));
    m.depth_mm = light_depth_mm(light, ndc.z);
    m.first_mm = light_depth_mm(light, textureLoad(shadow_depths, m.texel, i32(light.shadow.x), 0).r);
    return m;
}

// How far the light travelled inside the mesh before the point: its depth from the light minus
// the first surface's, mm; 0 off the map.
fn light_path_mm(m: MapPoint) -> f32 {
    return select(0.0, max(m.depth_mm - m.first_mm, 0.0), m.inside);
}
//#endif

//#if THICKNESS_SLAB
// The first surface's distance from the light (mm) at texel c of the light's map, c clamped.
fn first_mm(light: Light, c: vec2<i32>, size: vec2<i32>) -> f32 {
    let k = clamp(c, vec2<i32>(0), size - 1);
    return light_depth_mm(light, textureLoad(shadow_depths, k, i32(light.shadow.x), 0).r);
}

// The one-sided difference of smaller magnitude of the first surface's distance beside texel c
// (where it is z) along `step`, so that a silhouette's jump beside a face is not read as its
// slope.
fn first_slope(light: Light, c: vec2<i32>, z: f32, step: vec2<i32>, size: vec2<i32>) -> f32 {
    let ahead = first_mm(light, c + step, size) - z;
    let behind = z - first_mm(light, c - step, size);
    return select(behind, ahead, abs(ahead) < abs(behind));
}

// A light's orthographic map in the world: its unit axes along the NDC's x (right) and y (up;
// the texels run down), the uv per mm along them, a texel's side (mm) and the map's size. Made
// once per light and pixel: the gather reads it per sample.
struct MapAxes {
    right: vec3<f32>,
    up: vec3<f32>,
    uv_per_mm: vec2<f32>,
    texel_mm: vec2<f32>,
    size: vec2<i32>,
}

fn map_axes(light: Light) -> MapAxes {
    var a: MapAxes;
    a.size = vec2<i32>(textureDimensions(shadow_depths).xy);
    let v = light.shadow_view_proj;
    // The gradients of the map's NDC x and y over the world; the NDC spans 2 over the map.
    let gx = vec3<f32>(v[0].x, v[1].x, v[2].x);
    let gy = vec3<f32>(v[0].y, v[1].y, v[2].y);
    a.right = normalize(gx);
    a.up = normalize(gy);
    a.uv_per_mm = 0.5 * vec2<f32>(length(gx), length(gy));
    a.texel_mm = 1.0 / (vec2<f32>(a.size) * a.uv_per_mm);
    return a;
}

// The outward normal of the face where the light entered the mesh above the point `m`, from the
// slope of the first surface in the light's orthographic map: with s the slopes (mm of depth per
// mm) along the map's right and down axes, n_e ∝ l + s_x·right + s_y·down. A point light's
// perspective map has no constant texel size; it takes the exit face's −n, exact for a slab
// with parallel faces.
fn entry_normal(light: Light, axes: MapAxes, m: MapPoint, n: vec3<f32>, l: vec3<f32>) -> vec3<f32> {
    if light.translucency.w > 0.5 {
        return -n;
    }
    let sx = first_slope(light, m.texel, m.first_mm, vec2<i32>(1, 0), axes.size) / axes.texel_mm.x;
    let sy = first_slope(light, m.texel, m.first_mm, vec2<i32>(0, 1), axes.size) / axes.texel_mm.y;
    return normalize(l + sx * axes.right - sy * axes.up);
}

// The extrapolated boundary's distance beyond a face per channel (mm), z_b = 2/(3σt′)
// (slab_extent::extrapolation_mm): of the slab's faces (`lateral_rates`) and of a side face
// (`side_drain`, slab_edge.wgsl).
fn slab_extrapolation_mm() -> vec3<f32> {
    return vec3<f32>(2.0 / 3.0) / params.slab_sigma_t.xyz;
}

// The lateral decay rates q (mm⁻¹) per channel of the light crossing a slab `depth_mm` thick:
// √(σ² + (π/L)²), σ = κσt′, L = d + 2z_b (slab_extent::lateral_rates_per_mm, its twin).
fn lateral_rates(depth_mm: f32) -> vec3<f32> {
    let sigma = params.slab_kappa.xyz * params.slab_sigma_t.xyz;
    let span = depth_mm + 2.0 * slab_extrapolation_mm();
    return sqrt(sigma * sigma + (PI / span) * (PI / span));
}

// One light's slab radiance, how far the exit face turns from the entry face (`facing`), and
// the share of the light leaving the point that the slab stands for (`share`: `facing` times
// the lit extent, over the channels); the hidden-entry gather takes the rest.
struct SlabLight {
    radiance: vec3<f32>,
    facing: f32,
    share: f32,
}

// How one light reaches the exit point `world` (normal n, seen from v) through the mesh: its
// arrival, the distance d (mm) it travelled inside, the outward normal n_e of the face it
// entered (from the map's slope), the external cosines there (mu_l) and at the exit (mu_v), and
// the faces as it meets them; `through` is false where the light met no mesh before `world` or
// the surface faces the light. The slab law's and the march's inputs alike.
struct SlabEntry {
    arrival: Arrival,
    d: f32,
    n_e: vec3<f32>,
    mu_l: f32,
    mu_v: f32,
    faces: SlabFaces,
    through: bool,
}

fn slab_entry(light: Light, axes: MapAxes, m: MapPoint, world: vec3<f32>, n: vec3<f32>, v: vec3<f32>) -> SlabEntry {
    var e: SlabEntry;
    e.d = light_path_mm(m);
    e.arrival = light_arrival(light, world);
    // The ray toward the light must start inside the mesh: where the surface faces the light,
    // whatever the map saw first is another part in front of this one (a nose's shadow on the
    // cheek), and the light it let through crossed air before arriving here.
    e.through = e.d > 0.0 && dot(n, e.arrival.l) < 0.0;
    if !e.through {
        return e;
    }
    e.n_e = entry_normal(light, axes, m, n, e.arrival.l);
    e.mu_l = max(dot(e.n_e, e.arrival.l), 1e-3);
    e.mu_v = clamp(dot(n, v), 0.0, 1.0);
    e.faces = slab_faces(params.slab_axes.x, e.mu_v, e.mu_l);
    return e;
}

// The slab law's radiance of one light (see the top of the file) at `world`, which falls at `m`
// in its map; 0 (facing 0) where the light met no mesh before `world` or the surface faces the
// light.
fn slab_radiance(light: Light, axes: MapAxes, m: MapPoint, frag: vec2<f32>, world: vec3<f32>, n: vec3<f32>, v: vec3<f32>) -> SlabLight {
    var out: SlabLight;
    let e = slab_entry(light, axes, m, world, n, v);
    if !e.through {
        return out;
    }
    // The slab's thickness: the distance from `world` to the plane the light entered. (Measured
    // along the exit face's normal instead, d·μ_l/(−n·n_e), the wedges' faces 13° apart come
    // 2-3% closer to the path tracer, but light entering a face at right angles to the exit face
    // is lost: ΔE 4.6 → 6.5 on the marble wedge, 1.6 → 6.1 on the ketchup wedge.)
    let depth_mm = e.d * e.mu_l;
    // A slab leaves through the face opposite the one it entered (outward normals at n·n_e = −1);
    // the law holds to a right angle (n·n_e = 0, a wedge's top face feeding its front) and fades
    // to nothing as the two faces turn the same way (n·n_e → 1: the thin cap beyond a convex
    // terminator, lit at grazing over a strip narrower than the light spreads, which the kernel
    // carries from the lit side).
    out.facing = clamp(1.0 - dot(n, e.n_e), 0.0, 1.0);
    // The light scattered once is marched through the mesh along the view ray (slab_march.wgsl)
    // where the back-face pass found the ray's exit; the plane's closed form serves elsewhere.
    let chord = view_chord_mm(frag, world);
    let once = select(1.0, 0.0, chord >= 0.0);
    let centre = out.facing * plane_slab_light(depth_mm, e.mu_v, e.mu_l, e.faces, once);
    // Over the plane's lateral spread, as the light's map holds it (slab_spread.wgsl): a finger
    // is narrower than the light spreads in it, and beside a lit side face the opposite face's
    // slab carries its own light.
    let q = lateral_rates(depth_mm);
    let spread = slab_spread(light, axes, m, e, n, centre, q, once);
    // What is left of it beside a side face the light does not reach (slab_edge.wgsl); a point
    // light's plane counts as whole, as in `slab_spread`.
    var t = spread.light;
    if light.translucency.w < 0.5 {
        t *= side_drain(light, frag, world, q);
    }
    let marched = once_scattered(light, axes, world, n, v, e, chord);
    // The slab stands for the light of the plane it assumes where that plane is there.
    out.share = out.facing * dot(spread.lit, vec3<f32>(1.0 / 3.0));
    // The march is the once-scattered light through the mesh as it is: no plane assumed, so
    // neither the spread, the drain nor the facing scale it.
    out.radiance = e.arrival.e * (t + marched) * (light.translucency.x / PI);
    return out;
}

// The share of the light entering at an offset `d` from the exit point, where the camera sees
// it, that the screen-space kernel carries there (seen from the direction `v`): the kernel
// reaches `params.screen_kernel.x` mm across the view and follows a sample in proportion to
// 1 − |Δz| / `params.screen_kernel.y` of its depth difference ([Jimenez2015]'s rule, sss.wgsl);
// none where no kernel runs.
fn kernel_share(d: vec3<f32>, v: vec3<f32>) -> f32 {
    let reach = params.screen_kernel.x;
    if reach <= 0.0 {
        return 0.0;
    }
    let dz = dot(d, v);
    if length(d - dz * v) > reach {
        return 0.0;
    }
    return 1.0 - clamp(abs(dz) / max(params.screen_kernel.y, 1e-6), 0.0, 1.0);
}

// Whether the camera sees the surface point `x` (outward normal `nx`): it faces the camera and
// lies no deeper than the G-buffer's surface at its pixel, within `tol_mm` plus two pixels'
// width there. Light entering where the camera sees is the lighting pass's (and the kernel's).
fn seen_by_camera(x: vec3<f32>, nx: vec3<f32>, tol_mm: f32) -> bool {
    if dot(nx, frame.camera_pos.xyz - x) <= 0.0 {
        return false;
    }
    let clip = frame.view_proj * vec4<f32>(x, 1.0);
    let ndc = clip.xyz / clip.w;
    let frag = vec2<f32>(ndc.x * 0.5 + 0.5, 0.5 - ndc.y * 0.5) * frame.viewport.xy;
    if any(frag < vec2<f32>(0.0)) || any(frag >= frame.viewport.xy) {
        return false;
    }
    let stored = textureLoad(gb_depth, vec2<i32>(frag), 0).r;
    if stored >= 1.0 {
        return false;
    }
    let z = linear_depth(stored);
    let pixel_mm = z / frame.projection.x;
    return linear_depth(ndc.z) <= z + tol_mm + 2.0 * pixel_mm;
}

// The hidden-entry gather ([Dachsbacher2003]'s translucent shadow map, restricted to what the
// G-buffer cannot see): the light of one directional light entering the mesh within
// `params.gather.y` mm of `world` on faces the camera does not see, carried to `world` by the
// classic dipole at their distance (diffusion.wgsl dipole_radial), leaving through a
// Lambertian exit under the boundary:
//   L = T(μ_v)/π · ∫ R(x_i → x) · T(μ_i) · E dA⊥,
// dA⊥ the light map's area (a texel passes E·dA⊥ whatever the slope of the face it lights). The
// radii are stratified by e^{−σρ} over [0, reach], the angles on the golden-angle spiral.
fn hidden_entry(light: Light, axes: MapAxes, m: MapPoint, world: vec3<f32>, n: vec3<f32>, v: vec3<f32>) -> vec3<f32> {
    if light.translucency.w > 0.5 || !m.inside {
        return vec3<f32>(0.0);
    }
    let texel_mm = max(axes.texel_mm.x, axes.texel_mm.y);
    let arrival = light_arrival(light, world);
    let l = arrival.l;
    let eta = params.gather.x;
    let reach = params.gather.y;
    let count = u32(params.gather.z);
    let sigma = params.gather.w;
    let kept = 1.0 - exp(-sigma * reach);
    // The lighting pass's law lit the exit point's whole neighbourhood as the point itself (μ_o
    // where the map's first surface is the point, else 0): the gather adds what the hidden
    // entries received beyond that.
    let mu_o = select(0.0, max(dot(n, l), 0.0), light_path_mm(m) < 2.0 * texel_mm);
    // Under the transmission gather, whose kernel is steeper, the spiral turns by a per-point
    // angle: the same spiral at every pixel steps through the map's texels alike in neighbouring
    // pixels and leaves a structured error (single bright pixels that the screen-space kernel
    // spreads into its taps' lattice); turned, it is noise the kernel averages.
    let turn = select(0.0, 2.0 * PI * fract(sin(dot(world, vec3<f32>(12.9898, 78.233, 37.719))) * 43758.5453), params.kind.y == 1u);
    var sum = vec3<f32>(0.0);
    for (var j = 0u; j < count; j++) {
        let u = (f32(j) + 0.5) / f32(count);
        let rho = -log(1.0 - u * kept) / sigma;
        // 2πρ/p(ρ), p(ρ) = σe^{−σρ}/kept: the map area each sample stands for, times N.
        let area = 2.0 * PI * rho * kept / (sigma * exp(-sigma * rho));
        let phi = f32(j) * 2.39996323 + turn;
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
        let mu_i = max(dot(ni, l), 0.25);
        let d = xi - world;
        var unseen = 1.0 - mu_o / mu_i;
        if seen_by_camera(xi, ni, 2.0 * texel_mm) {
            // The kernel spreads a seen entry's light by its pixels' area, dA·μ_v: it misses
            // 1 − μ_v of what it reaches and all of what it does not.
            let mu_v = clamp(dot(ni, normalize(frame.camera_pos.xyz - xi)), 0.0, 1.0);
            unseen *= 1.0 - kernel_share(d, v) * mu_v;
        }
        let t_in = 1.0 - fresnel_in(dot(ni, l), eta);
        let r = length(d);
        var rd = vec3<f32>(
            dipole_radial(params.gather_medium[0], r),
            dipole_radial(params.gather_medium[1], r),
            dipole_radial(params.gather_medium[2], r),
        );
        if params.kind.y == 1u {
            // The transmission gather's kernel (through.wgsl), where chosen: an entry on a face
            // turned from the pixel's (a finger's far side feeding its lit rim or its front) is
            // seen through the pixel's own face.
            rd = through_entry3(xi, ni, world, n);
        }
        sum += rd * (t_in * area * unseen);
    }
    let t_out = 1.0 - fresnel_in(dot(n, v), eta);
    // Signed: an entry lit less than the pixel (μ_i < μ_o) takes back what the lighting pass's
    // law gave the pixel from it, so a lit cap whose neighbourhood turns from the light comes out
    // darker than a plane's. The sum is the entries' light (each at least 0) minus what the law
    // assumed of them, so it takes back at most the gather's own estimate of the law's light.
    // (Clamped at 0, as it was before 2026-11-28, it kept that excess: the skim-milk sphere's
    // lit cap 5% too red, ΔE 2.31 against 1.95; docs/BENCHMARKS.md "The gather, signed".)
    return arrival.e * sum * (t_out / (PI * f32(count))) * light.translucency.x;
}
//#insert slab_edge
//#insert slab_march
//#insert slab_spread
//#insert through
//#endif

// The talk's term of every light at `world` for material parameters m, over albedo.
fn lobe_sum(local: vec3<f32>, m: vec4<f32>, world: vec3<f32>, n: vec3<f32>, v: vec3<f32>) -> vec3<f32> {
    var sum = vec3<f32>(0.0);
    for (var li = 0u; li < frame.counts.x; li++) {
        let light = frame.lights[li];
        var t = local;
//#if THICKNESS_LIGHT
        if light.shadow.x < 0.0 {
            continue;
        }
        t = falloff_weight(light_path_mm(map_point(light, world)));
//#endif
        let arrival = light_arrival(light, world);
        sum += arrival.e * t * translucency(arrival.l, n, v, m, light.translucency.x);
    }
    return sum;
}

@fragment
fn fs_thickness(@builtin(position) frag: vec4<f32>) -> @location(0) vec4<f32> {
    let p = vec2<i32>(frag.xy);
    let local = textureLoad(gb_local, p, 0);
    let id = u32(round(local.a * 3.0));
    if id == 0u {
        return vec4<f32>(0.0);
    }
    let n = normalize(textureLoad(gb_normal, p, 0).xyz);
    let world = world_at(frag.xy, textureLoad(gb_depth, p, 0).r);
    let v = normalize(frame.camera_pos.xyz - world);
//#if THICKNESS_SLAB
    var sum = vec3<f32>(0.0);
    for (var li = 0u; li < frame.counts.x; li++) {
        let light = frame.lights[li];
        if light.shadow.x >= 0.0 {
            // Where `world` falls in the light's map, and the map's axes: for the slab and the
            // gather alike.
            let m = map_point(light, world);
            let axes = map_axes(light);
            // The transmission gather, where chosen, takes the light that crossed the mesh to a
            // pixel facing away from a directional light; the slab law takes the rest.
            if params.kind.y == 1u && params.gather.z > 0.0 && light.translucency.w < 0.5 && m.inside
                && dot(n, light_arrival(light, world).l) < 0.0 {
                // The gather alone, with the transmission kernel (`through_entry3`): every
                // entry the map holds, no plane assumed. (A point light's perspective map has
                // no constant texel size for the gather: the slab law serves it.) The light
                // scattered once, which diffusion does not carry, is marched as under the law.
                sum += hidden_entry(light, axes, m, world, n, v) + marched_light(light, axes, m, frag.xy, world, n, v);
                continue;
            }
            let slab = slab_radiance(light, axes, m, frag.xy, world, n, v);
            sum += slab.radiance;
            // The gather takes the share the slab leaves: nothing where the light left
            // through the face opposite the one it entered, over a plane lit all around.
            if params.gather.z > 0.0 && slab.share < 1.0 {
                sum += (1.0 - slab.share) * hidden_entry(light, axes, m, world, n, v);
            }
        }
    }
    return vec4<f32>(sum, 0.0);
//#else
    let albedo = textureLoad(gb_albedo, p, 0).rgb;
    return vec4<f32>(albedo * lobe_sum(local.rgb, params.materials[id], world, n, v), 0.0);
//#endif
}
