// The slab law's side faces (render/src/slab_extent.rs `side_drain`, its CPU twin): where the
// exit face ends in an edge beyond which the medium stops (a wedge's front face meeting its
// bottom face), diffusion loses the light that crosses the slab through that side face. The
// drain scales the slab's light by 1 − w·e^{−q(a + z_b)}, a the distance (mm) from the exit
// point to the edge, q the slab's lateral decay rate, z_b = 2/(3σt′), w the share of the side
// face the light does not reach directly (1 − e^{−σt′·path}, path the distance the light crossed
// inside before the edge). A side face the light reaches is the hidden-entry gather's.
//
// The edges are found in the G-buffer: from the pixel, in 8 directions, at 1, 2, 4, ... pixels
// until the surface is 3/q_min away, then halved 4 times. The face ends where the medium's
// pixels end while its last one still faces the camera, flat (a silhouette turns away first),
// or where the normal turns by more than 60° between two samples the surface joins, at every
// scale (a crease). A jump in depth (another part in front, or behind) ends the search there:
// the face goes on out of sight. The drain is the least over the edges found.

const EDGE_DIRECTIONS: u32 = 8u;
const EDGE_DOUBLINGS: u32 = 7u;
const EDGE_HALVINGS: u32 = 4u;
// Where the medium's pixels end: the least n·v of the face's last pixel, so that a side face
// must turn by 60° or more to hide (a mesh's silhouette is a crease between polygons too, but
// one that turns just past the view: the hm08 hand's last polygons face the camera at 0.2-0.8),
// and the least cosine between its normal and the face's two pixels further in (flat: 8°); and
// the cosine of the turn that makes a crease.
const EDGE_FACING: f32 = 0.87;
const EDGE_FLAT: f32 = 0.99;
const EDGE_CREASE: f32 = 0.5;

// A G-buffer sample of the medium: where it is, its view depth (mm), its normal, and whether
// there is one.
struct EdgeSample {
    world: vec3<f32>,
    z_mm: f32,
    n: vec3<f32>,
    medium: bool,
}

fn edge_sample(frag: vec2<f32>) -> EdgeSample {
    var s: EdgeSample;
    let p = vec2<i32>(floor(frag));
    let depth = textureLoad(gb_depth, p, 0).r;
    let id = u32(round(textureLoad(gb_local, p, 0).a * 3.0));
    s.medium = depth < 1.0 && id != 0u;
    if s.medium {
        s.world = world_at(floor(frag) + 0.5, depth);
        s.z_mm = linear_depth(depth);
        s.n = normalize(textureLoad(gb_normal, p, 0).xyz);
    }
    return s;
}

// Whether `next` continues the face of `prev`, one `step_px` apart on screen: it is the medium,
// no further than a foreshortened step (else a part in front or behind: `joined` false), and
// turned by less than the crease.
struct EdgeStep {
    same_face: bool,
    joined: bool,
}

fn edge_step(prev: EdgeSample, next: EdgeSample, step_px: f32) -> EdgeStep {
    var s: EdgeStep;
    if !next.medium {
        s.joined = true;
        return s;
    }
    let v = normalize(frame.camera_pos.xyz - prev.world);
    let expected = step_px * (prev.z_mm / frame.projection.x) / max(dot(prev.n, v), 0.25);
    s.joined = length(next.world - prev.world) <= 4.0 * expected + 0.05;
    s.same_face = s.joined && dot(prev.n, next.n) >= EDGE_CREASE;
    return s;
}

// The slab's light kept beside a side face the light `light` does not reach (the top of the
// file), per channel, at `world` (pixel `frag`) for lateral decay rates `q` (mm⁻¹): the least
// over the edges found within 3/q_min, each drained by its distance and the light's path inside
// before it (so a lit edge nearer than an unlit one does not hide it); 1 where none is near.
fn side_drain(light: Light, frag: vec2<f32>, world: vec3<f32>, q: vec3<f32>) -> vec3<f32> {
    var drain = vec3<f32>(1.0);
    let centre = edge_sample(frag);
    if !centre.medium {
        return drain;
    }
    let reach_mm = 3.0 / min(q.x, min(q.y, q.z));
    let sigma_t = params.slab_sigma_t.xyz;
    let z_b = slab_extrapolation_mm();
    for (var k = 0u; k < EDGE_DIRECTIONS; k++) {
        let phi = f32(k) * (2.0 * PI / f32(EDGE_DIRECTIONS));
        let dir = vec2<f32>(cos(phi), sin(phi));
        var inside = centre;
        var inside_px = 0.0;
        var outside_px = -1.0;
        for (var i = 0u; i < EDGE_DOUBLINGS; i++) {
            let px = f32(1u << i);
            let at = frag + dir * px;
            if any(at < vec2<f32>(0.0)) || any(at >= frame.viewport.xy) {
                break;
            }
            let next = edge_sample(at);
            let step = edge_step(inside, next, px - inside_px);
            if !step.joined {
                break;
            }
            if !step.same_face {
                // Where the medium's pixels end behind a face already turning from the camera,
                // a silhouette: no need to halve toward it (most of a hand's directions).
                let v = normalize(frame.camera_pos.xyz - inside.world);
                if next.medium || dot(inside.n, v) >= EDGE_FACING {
                    outside_px = px;
                }
                break;
            }
            inside = next;
            inside_px = px;
            if length(next.world - world) > reach_mm {
                break;
            }
        }
        if outside_px < 0.0 {
            continue;
        }
        // Halve the bracket: the last sample of the face, and the first beyond it.
        for (var h = 0u; h < EDGE_HALVINGS; h++) {
            let mid = 0.5 * (inside_px + outside_px);
            let next = edge_sample(frag + dir * mid);
            let step = edge_step(inside, next, mid - inside_px);
            if step.joined && step.same_face {
                inside = next;
                inside_px = mid;
            } else {
                outside_px = mid;
            }
        }
        // Where the medium's pixels end, the face's last pixel must still face the camera, flat
        // as the face two pixels further in: not the turn of a silhouette. Where they go
        // on, beyond must join the face and still turn from it (a crease), not lie in front or behind.
        let beyond = edge_sample(frag + dir * outside_px);
        if beyond.medium {
            // A crease turns at every scale; a smooth bend, halved, no longer does.
            let step = edge_step(inside, beyond, outside_px - inside_px);
            if !step.joined || step.same_face {
                continue;
            }
        } else {
            let v = normalize(frame.camera_pos.xyz - inside.world);
            let in_px = frag + dir * (inside_px - 2.0);
            if dot(inside.n, v) < EDGE_FACING || any(in_px < vec2<f32>(0.0)) || any(in_px >= frame.viewport.xy) {
                continue;
            }
            let further_in = edge_sample(in_px);
            if !further_in.medium || dot(inside.n, further_in.n) < EDGE_FLAT {
                continue;
            }
        }
        let a = length(inside.world - world);
        let unlit = 1.0 - exp(-sigma_t * light_path_mm(map_point(light, inside.world)));
        drain = min(drain, 1.0 - unlit * exp(-q * (a + z_b)));
    }
    return drain;
}
