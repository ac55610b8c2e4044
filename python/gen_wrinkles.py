"""Expression wrinkles and lip furrows of the default head: data/heads/masks/wrinkles.png (and
wrinkles.json: where the map lies in the UVs).

Reads the committed default head (data/heads/hm08_head.obj, its `head` group: the skin) and the
region masks beside it, rasterises the skin's rest positions into its UV space at WRINKLE_PX², and
draws four families of furrows there as depths (0-1 of each family's depth in
rouge_model::skin::wrinkles), one per channel:

  R  forehead lines: four horizontal lines above the brows, 9 mm apart, bending down toward the
     temples, broken into segments; inside the forehead mask.
  G  crow's feet: six rays fanning out from each outer canthus, 3 to 15-19 mm from it, drawn in
     cylindrical coordinates about the head's vertical axis (so they follow the skin round
     toward the temple); lateral of the canthus only.
  B  nasolabial folds: a broad groove from above each ala of the nose to beside and below the
     mouth's corner (a quadratic curve in the front projection, bowed outward).
  A  lip furrows: near-vertical lines 1.1 mm apart across the vermilion, fanning toward the
     mouth's corners; inside the lips mask, shallower toward the lips' contact line.

Every furrow has the cross-section (1 - (d/w)²)² for a distance d < w from its centre line, w its
half-width. Shapes, sizes and counts are *choices* after the usual description of facial
wrinkles (frontal lines, lateral canthal lines, nasolabial fold, perioral lines), not fitted to a
measured face; the renderer scales each family by the Face Units that make it
(rouge_model::skin::wrinkles::WrinkleWeights). Deterministic (fixed seed); no arguments.

Run: .venv/bin/python python/gen_wrinkles.py
"""
from __future__ import annotations

import json
import struct
import zlib
from pathlib import Path

import numpy as np

from gen_head_raster import gutter, rasterise, uv_to_px
from gen_head_regions import smoothstep

ROOT = Path(__file__).resolve().parent.parent
OBJ = ROOT / "data/heads/hm08_head.obj"
MASKS = ROOT / "data/heads/masks"
OUT = MASKS / "wrinkles.png"
PREVIEW = Path("/tmp/wrinkles_preview.png")
WRINKLE_PX = 2048
# The map covers only this square of the head's UVs (u0, v0, side): the face from the forehead to
# the chin (hm08 lays the whole body out in its UVs; the face is a small part). 0.065 mm a texel.
UV_RECT = (0.775, 0.40, 0.17)
SEED = 20261125

# forehead lines (front projection, mm; y from the eyeballs' centres)
FORE_Y0_MM, FORE_STEP_MM, FORE_LINES = 24.0, 9.0, 4
FORE_BEND = 0.004  # mm of drop per mm² of |x|
FORE_HALF_W_MM = 0.55
# crow's feet (the tangent plane at the outer canthus)
CROW_ANGLES_DEG = (-38.0, -22.0, -8.0, 6.0, 20.0, 34.0)
CROW_R_MM = (3.0, 15.0)
CROW_HALF_W_MM = 0.35
# nasolabial fold
NASO_HALF_W_MM = 3.0
# lip furrows
LIP_SPACING_MM, LIP_HALF_W_MM = 1.1, 0.22


def read_grey_png(path: Path) -> np.ndarray:
    """An 8-bit greyscale PNG as written by gen_head_raster.write_png (filter 0 on every row), 0-1."""
    data = path.read_bytes()
    pos, idat, w, h = 8, b"", 0, 0
    while pos < len(data):
        n, tag = struct.unpack(">I4s", data[pos:pos + 8])
        body = data[pos + 8:pos + 8 + n]
        if tag == b"IHDR":
            w, h, depth, colour = struct.unpack(">IIBB", body[:10])
            assert depth == 8 and colour == 0, f"{path}: not 8-bit grey"
        elif tag == b"IDAT":
            idat += body
        pos += 12 + n
    raw = np.frombuffer(zlib.decompress(idat), dtype=np.uint8).reshape(h, w + 1)
    assert (raw[:, 0] == 0).all(), f"{path}: filtered rows"
    return raw[:, 1:] / 255.0


def write_rgba_png(path: Path, img: np.ndarray) -> None:
    img = np.ascontiguousarray(img, dtype=np.uint8)
    h, w = img.shape[:2]
    raw = b"".join(b"\x00" + img[y].tobytes() for y in range(h))

    def chunk(tag: bytes, data: bytes) -> bytes:
        return struct.pack(">I", len(data)) + tag + data + struct.pack(">I", zlib.crc32(tag + data) & 0xFFFFFFFF)

    ihdr = struct.pack(">IIBBBBB", w, h, 8, 6, 0, 0, 0)
    path.write_bytes(b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", ihdr) + chunk(b"IDAT", zlib.compress(raw, 9)) + chunk(b"IEND", b""))


def profile(d: np.ndarray, half_w: float) -> np.ndarray:
    """A furrow's depth (0-1) at distance d (mm) from its centre line."""
    t = np.clip(d / half_w, 0.0, 1.0)
    return (1.0 - t * t) ** 2


def read_obj() -> tuple[np.ndarray, np.ndarray, dict[str, list[list[tuple[int, int]]]]]:
    V, VT, groups, g = [], [], {}, None
    for line in OBJ.read_text().splitlines():
        if line.startswith("v "):
            V.append([float(x) for x in line.split()[1:4]])
        elif line.startswith("vt "):
            VT.append([float(x) for x in line.split()[1:3]])
        elif line.startswith("g "):
            g = line.split()[1]
        elif line.startswith("f "):
            groups.setdefault(g, []).append([tuple(int(a) - 1 for a in c.split("/")[:2]) for c in line.split()[1:]])
    return np.array(V), np.array(VT), groups


def sample(mask: np.ndarray, uv: np.ndarray) -> np.ndarray:
    """A mask (row 0 at v = 1) at UVs, nearest texel."""
    h, w = mask.shape
    c = np.clip((uv[:, 0] * w).astype(int), 0, w - 1)
    r = np.clip(((1.0 - uv[:, 1]) * h).astype(int), 0, h - 1)
    return mask[r, c]


def value_noise(x: np.ndarray, period: float, rng: np.random.Generator) -> np.ndarray:
    """Smooth 1D noise in 0-1 with features about `period` apart."""
    knots = rng.random(256)
    s = x / period + 128.0
    i = np.floor(s).astype(int) % 255
    f = s - np.floor(s)
    f = f * f * (3 - 2 * f)
    return knots[i] * (1 - f) + knots[i + 1] * f


def main() -> None:
    rng = np.random.default_rng(SEED)
    V, VT, groups = read_obj()
    skin = groups["head"]
    # --- landmarks ---------------------------------------------------------------------------
    eyes = {g: V[sorted({c[0] for f in groups[g] for c in f})].mean(axis=0) for g in ("eye_l", "eye_r")}
    assert eyes["eye_l"][0] > 0, "eye_l is the subject's left, at +x"
    skin_v = np.array(sorted({c[0] for f in skin for c in f}))
    mouth_v = np.array(sorted({c[0] for f in groups["mouth"] for c in f} & set(skin_v.tolist())))
    ring = V[mouth_v]  # the lip-contact ring: skin vertices shared with the mouth bag
    corner_l = ring[np.argmax(ring[:, 0])]
    mid = skin_v[np.abs(V[skin_v, 0]) < 0.5]
    tip = V[mid[np.argmax(V[mid, 2])]]
    eye_y = eyes["eye_l"][1]
    # the outer canthus: the skin nearest the lateral end of the left lashes
    lash = V[sorted({c[0] for f in groups["lashes_l"] for c in f})]
    lash_end = lash[np.argmax(lash[:, 0])]
    canthus_l = V[skin_v[np.argmin(np.linalg.norm(V[skin_v] - lash_end, axis=1))]]
    nose = read_grey_png(MASKS / "nose.png")
    # --- the skin's rest positions in UV space --------------------------------------------------
    tris_v, tris_t = [], []
    for f in skin:
        for k in range(1, len(f) - 1):
            tris_v.append([f[0][0], f[k][0], f[k + 1][0]])
            tris_t.append([f[0][1], f[k][1], f[k + 1][1]])
    tris_v, tris_t = np.array(tris_v), np.array(tris_t)
    u0, v0, side_uv = UV_RECT
    in_rect = (VT[tris_t] - np.array([u0, v0])) / side_uv
    pos, cov = rasterise(uv_to_px(in_rect, WRINKLE_PX), V[tris_v], WRINKLE_PX, WRINKLE_PX)
    rows, cols = np.nonzero(cov)
    q = pos[rows, cols]
    uv = np.stack([u0 + side_uv * (cols + 0.5) / WRINKLE_PX, v0 + side_uv * (1.0 - (rows + 0.5) / WRINKLE_PX)], axis=1)
    front = q[:, 2] > 0.0
    x, y = q[:, 0], q[:, 1]
    depth = np.zeros((len(q), 4))

    # R: forehead lines
    forehead = sample(read_grey_png(MASKS / "forehead.png"), uv)
    fore = np.zeros(len(q))
    for k in range(FORE_LINES):
        yk = eye_y + FORE_Y0_MM + k * FORE_STEP_MM - FORE_BEND * x * x + 1.5 * (value_noise(x, 25.0, rng) - 0.5)
        keep = smoothstep(0.2, 0.4, value_noise(x + 100.0 * k, 14.0, rng))
        fore = np.maximum(fore, profile(np.abs(y - yk), FORE_HALF_W_MM) * keep * (1.0 - 0.15 * k))
    depth[:, 0] = fore * forehead * front

    # G: crow's feet, both sides: in cylindrical coordinates about the head's vertical axis (arc
    # length around it from the canthus, and height), which follow the skin round to the temple
    crow = np.zeros(len(q))
    radius = np.hypot(canthus_l[0], canthus_l[2])
    for side in (1.0, -1.0):
        phi_c = np.arctan2(side * canthus_l[0], canthus_l[2])
        s = side * (np.arctan2(x, q[:, 2]) - phi_c) * radius
        t = y - canthus_l[1]
        r = np.hypot(s, t)
        ang = np.degrees(np.arctan2(t, s))
        for a in CROW_ANGLES_DEG:
            a = a + rng.uniform(-4.0, 4.0)
            length = CROW_R_MM[1] + rng.uniform(0.0, 4.0)
            dist = np.abs(r * np.sin(np.radians(ang - a)))
            along = smoothstep(CROW_R_MM[0], CROW_R_MM[0] + 3.0, r) * (1.0 - smoothstep(length - 5.0, length, r))
            on = (s > 0) & (np.abs(ang - a) < 60.0) & (x * side > 0)
            crow = np.maximum(crow, np.where(on, profile(dist, CROW_HALF_W_MM) * along, 0.0))
    depth[:, 1] = crow

    # B: nasolabial folds, from above the ala to beside and below the mouth's corner
    noses = skin_v[(sample(nose, uv_of_vertices(VT, skin)[skin_v]) > 0.5) & (V[skin_v, 1] < tip[1])]
    ala_l = V[noses[np.argmax(V[noses, 0])]]
    naso = np.zeros(len(q))
    for side in (1.0, -1.0):
        a = np.array([side * (abs(ala_l[0]) + 1.5), ala_l[1] + 4.0])
        b = np.array([side * (abs(corner_l[0]) + 7.0), corner_l[1] - 12.0])
        ctrl = (a + b) / 2 + np.array([side * 5.0, 0.0])
        ts = np.linspace(0.0, 1.0, 64)[:, None]
        curve = (1 - ts) ** 2 * a + 2 * (1 - ts) * ts * ctrl + ts ** 2 * b
        p = np.stack([x, y], axis=1)
        seg_a, seg_b = curve[:-1], curve[1:]
        ab = seg_b - seg_a
        best = np.full(len(q), np.inf)
        best_t = np.zeros(len(q))
        for i in range(len(ab)):
            tt = np.clip(((p - seg_a[i]) @ ab[i]) / (ab[i] @ ab[i]), 0.0, 1.0)
            dd = np.linalg.norm(p - (seg_a[i] + tt[:, None] * ab[i]), axis=1)
            closer = dd < best
            best[closer] = dd[closer]
            best_t[closer] = (i + tt[closer]) / len(ab)
        along = smoothstep(0.0, 0.15, best_t) * (1.0 - smoothstep(0.75, 1.0, best_t))
        naso = np.maximum(naso, np.where(front & (x * side > 0), profile(best, NASO_HALF_W_MM) * along, 0.0))
    depth[:, 2] = naso

    # A: lip furrows, fanning toward the corners
    lips = sample(read_grey_png(MASKS / "lips.png"), uv)
    y_mid = ring[:, 1].mean()
    fan = x * (1.0 + 0.35 * np.abs(y - y_mid) / 8.0)
    u = fan / LIP_SPACING_MM
    k = np.floor(u)
    jitter = (np.sin(k * 12.9898 + 78.233) * 43758.5453) % 1.0 - 0.5
    dist = np.abs(u - k - 0.5 - 0.3 * jitter) * LIP_SPACING_MM
    contact = smoothstep(0.5, 2.5, np.abs(y - y_mid))
    depth[:, 3] = profile(dist, LIP_HALF_W_MM) * lips * front * (0.4 + 0.6 * contact)

    img = np.zeros((WRINKLE_PX, WRINKLE_PX, 4))
    img[rows, cols] = np.clip(depth, 0.0, 1.0)
    img = gutter(img, cov, 2)
    # every furrow lies inside the rectangle: its border is clear
    assert img[[0, -1]].max() == 0.0 and img[:, [0, -1]].max() == 0.0, "a furrow reaches the map's edge"
    write_rgba_png(OUT, np.round(img * 255.0))
    # where the map lies in the head's UVs, read by rouge_model::skin::wrinkles
    OUT.with_suffix(".json").write_text(json.dumps(
        {"format": "rouge-wrinkles", "version": 1, "generator": "python/gen_wrinkles.py",
         "uv_rect": {"u0": UV_RECT[0], "v0": UV_RECT[1], "side": UV_RECT[2]},
         "channels": ["forehead", "crows_feet", "nasolabial", "lip_furrows"]}, indent=2) + "\n")
    if PREVIEW:
        write_rgba_png(PREVIEW, np.round(np.concatenate([img[..., :3], np.ones_like(img[..., :1])], -1)
                                          * 255.0 + (img[..., 3:] * 255.0) * np.array([1, 1, 0, 0])).clip(0, 255))
    # the skin's scale in the map: mm between horizontally neighbouring covered texels
    right = cov[rows, np.minimum(cols + 1, WRINKLE_PX - 1)]
    step = np.linalg.norm(pos[rows, np.minimum(cols + 1, WRINKLE_PX - 1)] - q, axis=1)[right]
    in_lips = (lips > 0.5)[right]
    print(f"mm per texel: median {np.median(step):.3f}, lips {np.median(step[in_lips]):.3f}")
    print(f"wrote {OUT} ({OUT.stat().st_size // 1024} KB); canthus {canthus_l.round(1)}, corner {corner_l.round(1)}, "
          f"ala {ala_l.round(1)}, tip {tip.round(1)}; texels with depth per family:",
          [(depth[:, c] > 0.1).sum() for c in range(4)])


def uv_of_vertices(VT: np.ndarray, faces: list) -> np.ndarray:
    """A UV for every vertex (the last corner that names it), for sampling masks per vertex."""
    n = max(c[0] for f in faces for c in f) + 1
    out = np.zeros((n, 2))
    for f in faces:
        for v, t in f:
            out[v] = VT[t]
    return out


if __name__ == "__main__":
    main()
