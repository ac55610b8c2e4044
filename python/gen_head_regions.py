"""The region masks of the default head as per-vertex weights in [0, 1] (python/gen_head.py
rasterises them in UV space into data/heads/masks/): the regions a look names (lips, cheeks,
eyelids, tzone) and the anatomical regions of the skin maps (nose, forehead, under_eye, ears,
chin, temples; model/src/skin). Each is built from 3D geometry relative to landmarks of the
hm08 mesh; the shapes' parameters are the constants below (gen_head.py's module doc describes
each region).
"""

from __future__ import annotations

import numpy as np

# Rings of the mouth counted outwards from the lip-contact ring: rings 0..5 are lip
# (vermilion); ring 6 is skin. Found on the midline profile: the upper lip rolls out between
# rings 6 and 5 (hm08 362 -> 455) and the lower lip's border is the 4 mm step back under it
# between rings 5 and 6 (hm08 492 -> 5337). Ring -1 (inner lip, inside the slit) gets 0.
LIP_RINGS = (0, 5)

# mask shape parameters (mm, relative to the landmarks named in each weights_* function)
EYELID_FULL_MM = 5.0  # full weight up to this distance from the upper lash line
EYELID_ZERO_MM = 11.0  # zero from this distance on
EYELID_H_RAMP_MM = 2.5  # ramp above the line through the two eye corners
CHEEK_DX_MM = 8.0  # cheek centre: this far lateral of the eyeball centre ...
CHEEK_T = 0.45  # ... and this fraction of the way down from eye-centre height to mouth-corner height
CHEEK_TILT_DEG = 20.0  # ellipse tilted up towards the temple
CHEEK_RX_MM = 26.0
CHEEK_RY_MM = 18.0
CHEEK_FULL = 0.35  # full weight inside this fraction of the ellipse
TZ_FORE_Y = 45.0  # forehead ellipse: centre this high above eye-centre height, on the midline
TZ_FORE_R = (58.0, 27.0)  # its half-width and half-height
TZ_FORE_FULL = 0.5  # full weight inside this fraction of it
TZ_NOSE_HALF = (5.0, 10.0)  # nose strip: full-weight half-width at the top and at the tip
TZ_NOSE_SOFT = 6.0  # then fading to zero over this
TZ_NOSE_TOP = (30.0, 36.0)  # strip runs up to 30..36 mm above eye-centre height (into the forehead)
TZ_NOSE_BOTTOM = (-6.0, -2.0)  # and down to 6..2 mm below the nose tip
UNDER_EYE_FULL_MM = 4.0  # under_eye: full weight up to this distance from the lower lash line
UNDER_EYE_ZERO_MM = 14.0  # zero from this distance on
NOSE_TOP_MM = 8.0  # nose: the profile starts this far above eye-centre height (the nasion)
NOSE_BELOW_TIP_MM = -14.0  # and ends this far below the tip (the subnasale)
NOSE_DEPTH_MM = 40.0  # profile points lie at most this far behind the tip
NOSE_FULL_MM = (6.0, 14.0)  # full weight up to this distance from the profile, bridge .. alae
NOSE_SOFT_MM = 4.0  # then fading to zero over this
EAR_MIN_X_MM = 78.0  # ears: vertices this far from the midplane lie on the auricle
EAR_R_MM = (16.0, 34.0, 22.0)  # the ellipsoid's half-axes (x, y, z) around the auricle's centre
EAR_FULL = 0.7  # full weight inside this fraction of it
CHIN_UP_MM = 17.0  # chin: ellipse centre this far above the chin's lowest midline point
CHIN_R_MM = (25.0, 17.0)  # its half-width and half-height
CHIN_FULL = 0.45  # full weight inside this fraction of it
TEMPLE_DX_MM = 32.0  # temples: centre nearest the point this far lateral of the eyeball centre,
TEMPLE_DY_MM = 10.0  # this far above it
TEMPLE_DZ_MM = -30.0  # and this far behind it
TEMPLE_R_MM = 26.0  # a ball of this radius
TEMPLE_FULL = 0.2  # full weight inside this fraction of it


def smoothstep(e0: float, e1: float, x: np.ndarray) -> np.ndarray:
    t = np.clip((x - e0) / (e1 - e0), 0.0, 1.0)
    return t * t * (3.0 - 2.0 * t)


def seg_dist(p: np.ndarray, a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """Distance from points p (N,3) to the polyline segments a[i]-b[i] (M,3): (N,) minimum."""
    ab = b - a
    t = np.einsum("nmk,mk->nm", p[:, None, :] - a[None], ab) / np.einsum("mk,mk->m", ab, ab)
    t = np.clip(t, 0.0, 1.0)
    q = a[None] + t[..., None] * ab[None]
    return np.linalg.norm(p[:, None, :] - q, axis=-1).min(axis=1)


def region_weights(n_vertices: int, Pm: np.ndarray, head_verts, outer: np.ndarray, mouth: dict[int, list[int]],
                   eyes: dict, eye_info: dict, origin, nose_tip: int, chin: int) -> dict[str, np.ndarray]:
    """Per-vertex weights of every region over the `n_vertices` source vertices: `Pm` their
    positions in output mm, `head_verts` the head's, `outer` those not in the mouth bag or the
    eye sockets, `mouth` the mouth's rings and `eyes` each eye's lash-line ring and inside
    (gen_head.rings), `eye_info` the eyeballs' centres, `origin` the output origin (hundredths of
    a mm), `nose_tip` and `chin` landmark vertices."""
    def weights_lips() -> np.ndarray:
        w = np.zeros(n_vertices)
        for k in range(LIP_RINGS[0], LIP_RINGS[1] + 1):
            w[mouth[k]] = 1.0
        return w

    def lid(name: str, upper: bool) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
        """The candidate vertices near eye `name` and, for each, the distance to the upper (or
        lower) half of its lash-line ring and the signed height above the line through the two
        canthi (front projection)."""
        loop0 = eyes[name][0]
        ring = Pm[loop0]
        i_in, i_out = np.argmin(np.abs(ring[:, 0])), np.argmax(np.abs(ring[:, 0]))
        a, b = sorted((int(i_in), int(i_out)))
        arc1 = loop0[a:b + 1]
        arc2 = loop0[b:] + loop0[:a + 1]
        pick = max if upper else min
        arc = pick(arc1, arc2, key=lambda arc: float(np.mean(Pm[arc, 1])))
        A, B = Pm[arc[:-1]], Pm[arc[1:]]
        c_in, c_out = Pm[loop0[i_in]], Pm[loop0[i_out]]
        mid = (c_in + c_out) / 2
        cand = np.array([v for v in head_verts if outer[v] and np.linalg.norm(Pm[v] - mid) < 30.0])
        q = Pm[cand]
        d = seg_dist(q, A, B)
        t = (q[:, 0] - c_in[0]) / (c_out[0] - c_in[0])
        h = q[:, 1] - (c_in[1] + t * (c_out[1] - c_in[1]))
        return cand, q, d, h

    def weights_eyelids() -> np.ndarray:
        w = np.zeros(n_vertices)
        for name in ("eye_l", "eye_r"):
            cand, _, d, h = lid(name, upper=True)
            wk = (1.0 - smoothstep(EYELID_FULL_MM, EYELID_ZERO_MM, d)) * smoothstep(0.0, EYELID_H_RAMP_MM, h)
            w[cand] = np.maximum(w[cand], wk)
        return w

    def weights_under_eye() -> np.ndarray:
        # the lower lid and the infraorbital skin: distance from the lower half of the lash line,
        # below the line through the canthi
        w = np.zeros(n_vertices)
        for name in ("eye_l", "eye_r"):
            cand, _, d, h = lid(name, upper=False)
            wk = (1.0 - smoothstep(UNDER_EYE_FULL_MM, UNDER_EYE_ZERO_MM, d)) * smoothstep(0.0, EYELID_H_RAMP_MM, -h)
            w[cand] = np.maximum(w[cand], wk)
        return w

    # landmarks in output mm
    e_l = eye_info["eye_l"][0] * 100 - np.array(origin) / 100
    m_corner = Pm[mouth[0]][np.argmax(Pm[mouth[0], 0])]
    tip = Pm[nose_tip]

    def weights_cheeks() -> np.ndarray:
        w = np.zeros(n_vertices)
        hv = np.array([v for v in head_verts if outer[v]])
        q = Pm[hv]
        for side in (1.0, -1.0):
            cx = side * (e_l[0] + CHEEK_DX_MM)
            cy = e_l[1] + CHEEK_T * (m_corner[1] - e_l[1])
            # centre: the frontmost outer vertex within 5 mm of (cx, cy) in the front projection
            close = np.hypot(q[:, 0] - cx, q[:, 1] - cy) < 5.0
            c = q[close][np.argmax(q[close][:, 2])]
            d = q - c
            ang = np.radians(CHEEK_TILT_DEG) * side
            du = d[:, 0] * np.cos(ang) + d[:, 1] * np.sin(ang)
            dv = -d[:, 0] * np.sin(ang) + d[:, 1] * np.cos(ang)
            rho = np.sqrt((du / CHEEK_RX_MM) ** 2 + (dv / CHEEK_RY_MM) ** 2 + (d[:, 2] / CHEEK_RX_MM) ** 2)
            w[hv] = np.maximum(w[hv], 1.0 - smoothstep(CHEEK_FULL, 1.0, rho))
        return w

    def front_outer() -> tuple[np.ndarray, np.ndarray]:
        hv = np.array([v for v in head_verts if outer[v]])
        return hv, Pm[hv]

    def forehead_part(q: np.ndarray) -> np.ndarray:
        # an ellipse in the front projection
        fx, fy = (q[:, 0]) / TZ_FORE_R[0], (q[:, 1] - TZ_FORE_Y) / TZ_FORE_R[1]
        return 1.0 - smoothstep(TZ_FORE_FULL, 1.0, np.hypot(fx, fy))

    def weights_tzone() -> np.ndarray:
        # forehead: an ellipse in the front projection; nose: a strip along the midline from
        # the glabella to just below the tip, widening towards the tip. Front half only.
        w = np.zeros(n_vertices)
        hv, q = front_outer()
        ax = np.abs(q[:, 0])
        fore = forehead_part(q)
        t = np.clip((TZ_NOSE_TOP[0] - q[:, 1]) / (TZ_NOSE_TOP[0] - tip[1]), 0.0, 1.0)
        half = TZ_NOSE_HALF[0] + t * (TZ_NOSE_HALF[1] - TZ_NOSE_HALF[0])
        nose = ((1.0 - smoothstep(half, half + TZ_NOSE_SOFT, ax))
                * smoothstep(tip[1] + TZ_NOSE_BOTTOM[0], tip[1] + TZ_NOSE_BOTTOM[1], q[:, 1])
                * (1.0 - smoothstep(*TZ_NOSE_TOP, q[:, 1])))
        w[hv] = np.where(q[:, 2] > 0.0, np.maximum(fore, nose), 0.0)
        return w

    def weights_forehead() -> np.ndarray:
        # the forehead ellipse of the T-zone alone
        w = np.zeros(n_vertices)
        hv, q = front_outer()
        w[hv] = np.where(q[:, 2] > 0.0, forehead_part(q), 0.0)
        return w

    def weights_nose() -> np.ndarray:
        # the external nose: 3D distance from its midline profile (nasion to tip to subnasale),
        # the full-weight distance growing from the bridge to the alae
        w = np.zeros(n_vertices)
        hv, q = front_outer()
        mid = np.array([v for v in head_verts if outer[v] and Pm[v, 0] == 0.0 and Pm[v, 2] > tip[2] - NOSE_DEPTH_MM
                        and tip[1] + NOSE_BELOW_TIP_MM <= Pm[v, 1] <= e_l[1] + NOSE_TOP_MM])
        prof = Pm[mid[np.argsort(-Pm[mid, 1])]]
        d = seg_dist(q, prof[:-1], prof[1:])
        t = np.clip((e_l[1] + NOSE_TOP_MM - q[:, 1]) / (e_l[1] + NOSE_TOP_MM - tip[1]), 0.0, 1.0)
        full = NOSE_FULL_MM[0] + t * (NOSE_FULL_MM[1] - NOSE_FULL_MM[0])
        w[hv] = np.where(q[:, 2] > 0.0, 1.0 - smoothstep(full, full + NOSE_SOFT_MM, d), 0.0)
        return w

    def ellipsoid(q: np.ndarray, centre: np.ndarray, radii: tuple[float, float, float], full: float) -> np.ndarray:
        rho = np.sqrt((((q - centre) / np.array(radii)) ** 2).sum(axis=1))
        return 1.0 - smoothstep(full, 1.0, rho)

    def nearest_outer(q: np.ndarray, p: np.ndarray) -> np.ndarray:
        return q[np.argmin(np.linalg.norm(q - p, axis=1))]

    def weights_ears() -> np.ndarray:
        # an ellipsoid around each auricle, centred on the middle of the outer ear's extent
        w = np.zeros(n_vertices)
        hv, q = front_outer()
        far = q[np.abs(q[:, 0]) > EAR_MIN_X_MM]
        for side in (1.0, -1.0):
            s = far[far[:, 0] * side > 0]
            c = (s.min(axis=0) + s.max(axis=0)) / 2
            w[hv] = np.maximum(w[hv], ellipsoid(q, c, EAR_R_MM, EAR_FULL))
        return w

    def weights_chin() -> np.ndarray:
        # the mental prominence: an ellipse in the front projection above the chin's lowest
        # midline point, front half only
        w = np.zeros(n_vertices)
        hv, q = front_outer()
        cy = Pm[chin][1] + CHIN_UP_MM
        rho = np.hypot(q[:, 0] / CHIN_R_MM[0], (q[:, 1] - cy) / CHIN_R_MM[1])
        w[hv] = np.where(q[:, 2] > 0.0, 1.0 - smoothstep(CHIN_FULL, 1.0, rho), 0.0)
        return w

    def weights_temples() -> np.ndarray:
        # a ball on each temple, centred on the skin nearest a point lateral of and above the
        # outer canthus
        w = np.zeros(n_vertices)
        hv, q = front_outer()
        for side in (1.0, -1.0):
            guess = np.array([side * (e_l[0] + TEMPLE_DX_MM), e_l[1] + TEMPLE_DY_MM, e_l[2] + TEMPLE_DZ_MM])
            c = nearest_outer(q, guess)
            w[hv] = np.maximum(w[hv], ellipsoid(q, c, (TEMPLE_R_MM,) * 3, TEMPLE_FULL))
        return w

    return {
        "lips": weights_lips(),
        "cheeks": weights_cheeks(),
        "eyelids": weights_eyelids(),
        "tzone": weights_tzone(),
        # the anatomical regions of the skin maps (model/src/skin)
        "nose": weights_nose(),
        "forehead": weights_forehead(),
        "under_eye": weights_under_eye(),
        "ears": weights_ears(),
        "chin": weights_chin(),
        "temples": weights_temples(),
    }
