// Discontinuity edge overdraw ([Sander2001]) after composition: each edge is a screen-space quad
// 2 × HALF_WIDTH_PX wide over its projected segment; the fragment shader computes the exact
// box-filter coverage of the drawn face's half-plane and blends the face's colour "over" the
// composited image. The face's colour is its lit, composited colour read from a copy of the image
// one pixel into the face's side of the edge, at the point of the edge nearest the fragment.
//
// Classification (section 3.5, signs corrected: see render/src/edges.rs) is `classify` below; its
// CPU twin is render/src/silhouettes.rs `classify`, which also orders the sorted mode's instances.

struct EdgePass {
    // x: bloat, pixels (0.5: the paper's width-1 line; 0: exact coverage), y: depth pull toward
    // the eye (fraction of the distance), z: τ of the asymmetric transfer, w: unused
    params: vec4<f32>,
    // x: 1 for two-sided coverage, y: 1 when the mesh is closed, z, w: unused
    flags: vec4<u32>,
}

@group(1) @binding(0) var<uniform> edge_pass: EdgePass;
@group(1) @binding(1) var composited: texture_2d<f32>;

const HALF_WIDTH_PX: f32 = 1.5;

struct EdgeIn {
    @location(0) p0: vec3<f32>,
    // 0 smooth (silhouette candidate), 1 sharp, 2 boundary
    @location(1) kind: u32,
    @location(2) p1: vec3<f32>,
    @location(3) n_left: vec3<f32>,
    @location(4) n_right: vec3<f32>,
}

struct EdgeOut {
    @builtin(position) pos: vec4<f32>,
    // The edge's first end, pixels.
    @location(0) @interpolate(flat) a: vec2<f32>,
    // Unit normal of the edge toward the drawn face's side, pixels (y down).
    @location(1) @interpolate(flat) side: vec2<f32>,
    // Opacity of this draw (1, β′ or 1 − β′).
    @location(2) @interpolate(flat) alpha: f32,
}

// One draw of an edge: which face's side (+1: the screen-left of p0 → p1, -1: the right) and
// its opacity; alpha 0 draws nothing.
struct Draw {
    side: f32,
    alpha: f32,
}

// Draws `k` (0 or 1) of an edge seen from the eye ([Sander2001] section 3.5). A face toward the
// eye lies on the screen-left of its own counter-clockwise edge, a face seen from behind on the
// right; the right face's winding runs p1 → p0.
fn classify(e: EdgeIn, k: u32) -> Draw {
    let v = frame.camera_pos.xyz - 0.5 * (e.p0 + e.p1);
    let dl = dot(e.n_left, v);
    let dr = dot(e.n_right, v);
    let left_side = select(-1.0, 1.0, dl > 0.0);
    let right_side = select(1.0, -1.0, dr > 0.0);
    let two_sided = edge_pass.flags.x == 1u;
    let none = Draw(0.0, 0.0);
    let silhouette = e.kind == 2u || (dl > 0.0) != (dr > 0.0);
    if e.kind == 0u && !silhouette {
        return none;
    }
    if silhouette {
        // Shaded from the front face (the only face of a boundary edge); two-sided coverage also
        // draws what lies beyond the silhouette over the face's pixels.
        let front = select(right_side, left_side, e.kind == 2u || dl > 0.0);
        if k == 0u {
            return Draw(front, 1.0);
        }
        if two_sided {
            return Draw(-front, 1.0);
        }
        return none;
    }
    // A sharp edge with both faces toward the eye (or both away on an open mesh).
    if dl <= 0.0 && edge_pass.flags.y == 1u {
        return none;
    }
    if two_sided {
        return Draw(select(right_side, left_side, k == 0u), 1.0);
    }
    let sum = dl + dr;
    let beta = select(clamp(dr / sum, 0.0, 1.0), 0.5, sum == 0.0);
    let tau = edge_pass.params.z;
    let beta_prime = clamp((beta - tau) / (1.0 - tau), 0.0, 1.0);
    // Double draw: the face with the larger weight first at alpha 1, the other over it.
    if beta_prime < 0.5 {
        return Draw(select(right_side, left_side, k == 0u), select(beta_prime, 1.0, k == 0u));
    }
    return Draw(select(left_side, right_side, k == 0u), select(1.0 - beta_prime, 1.0, k == 0u));
}

fn to_pixels(clip: vec4<f32>) -> vec2<f32> {
    let ndc = clip.xy / clip.w;
    return vec2<f32>((ndc.x * 0.5 + 0.5) * frame.viewport.x, (0.5 - 0.5 * ndc.y) * frame.viewport.y);
}

// Vertex `i` of an instance: 0-5 the first draw's quad, 6-11 the second's (one instance keeps its
// two draws in order, as the double draw needs).
@vertex
fn vs_edge(e: EdgeIn, @builtin(vertex_index) i: u32) -> EdgeOut {
    var out: EdgeOut;
    out.pos = vec4<f32>(-2.0, -2.0, 0.0, 1.0);
    out.a = vec2<f32>(0.0);
    out.side = vec2<f32>(0.0, 1.0);
    out.alpha = 0.0;
    let draw = classify(e, i / 6u);
    if draw.alpha <= 0.0 {
        return out;
    }
    // The quad's depth is pulled toward the eye along the view ray (same pixels), so that the
    // edge passes the depth test against its own faces: the paper's polygon offset.
    let eye = frame.camera_pos.xyz;
    let pull = edge_pass.params.y;
    let c0 = frame.view_proj * vec4<f32>(mix(e.p0, eye, pull), 1.0);
    let c1 = frame.view_proj * vec4<f32>(mix(e.p1, eye, pull), 1.0);
    if c0.w <= 1e-3 || c1.w <= 1e-3 {
        return out;
    }
    let a = to_pixels(c0);
    let b = to_pixels(c1);
    let d = b - a;
    if dot(d, d) < 1e-8 {
        return out;
    }
    // The screen-left of p0 → p1 (y up) is (d.y, −d.x) in pixel coordinates (y down).
    let side = draw.side * normalize(vec2<f32>(d.y, -d.x));
    let corner = array<u32, 6>(0u, 1u, 2u, 2u, 1u, 3u)[i % 6u];
    let end = select(c0, c1, (corner & 1u) == 1u);
    let px = select(a, b, (corner & 1u) == 1u) + side * select(-HALF_WIDTH_PX, HALF_WIDTH_PX, corner >= 2u);
    let ndc = vec2<f32>(px.x * frame.viewport.z * 2.0 - 1.0, 1.0 - px.y * frame.viewport.w * 2.0);
    out.pos = vec4<f32>(ndc * end.w, end.z, end.w);
    out.a = a;
    out.side = side;
    out.alpha = draw.alpha;
    return out;
}

//#insert coverage

@fragment
fn fs_edge(in: EdgeOut) -> @location(0) vec4<f32> {
    let p = in.pos.xy;
    // Signed distance of the pixel centre from the edge, positive on the drawn face's side.
    let s = dot(p - in.a, in.side);
    let two_sided = edge_pass.flags.x == 1u;
    if two_sided && s >= 0.0 {
        // Two-sided: each draw paints only the pixels of the other side.
        discard;
    }
    let coverage = box_coverage(s + edge_pass.params.x, in.side);
    let foot = p - s * in.side;
    let dims = vec2<i32>(textureDimensions(composited));
    let texel = clamp(vec2<i32>(floor(foot + in.side)), vec2<i32>(0), dims - 1);
    let colour = textureLoad(composited, texel, 0).rgb;
    return vec4<f32>(colour, in.alpha * coverage);
}
