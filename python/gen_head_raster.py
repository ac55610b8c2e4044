"""PNG writing, triangle rasterisation in pixel space and the UV masks' edge extension, shared by
the head's generators (python/gen_head.py, gen_wrinkles.py, gen_brow_mask.py), and the check
renders `gen_head.py --preview` writes (not part of the data; for looking at).
"""

from __future__ import annotations

import struct
import zlib
from pathlib import Path

import numpy as np


def write_png(path: Path, img: np.ndarray) -> None:
    """8-bit greyscale (H, W) or RGB (H, W, 3), filter 0 on every row, zlib level 9."""
    img = np.ascontiguousarray(img, dtype=np.uint8)
    h, w = img.shape[:2]
    colour_type = 0 if img.ndim == 2 else 2
    raw = b"".join(b"\x00" + img[y].tobytes() for y in range(h))

    def chunk(tag: bytes, data: bytes) -> bytes:
        return struct.pack(">I", len(data)) + tag + data + struct.pack(">I", zlib.crc32(tag + data) & 0xFFFFFFFF)

    ihdr = struct.pack(">IIBBBBB", w, h, 8, colour_type, 0, 0, 0)
    path.write_bytes(b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", ihdr) + chunk(b"IDAT", zlib.compress(raw, 9)) + chunk(b"IEND", b""))


def rasterise(tri_xy: np.ndarray, tri_attr: np.ndarray, width: int, height: int,
              tri_depth: np.ndarray | None = None) -> tuple[np.ndarray, np.ndarray]:
    """Fills triangles given in pixel coordinates (pixel (c, r) has its centre at (c+0.5, r+0.5)),
    interpolating per-corner attributes barycentrically at pixel centres. With tri_depth, a
    z-buffer keeps the smallest depth; without, later triangles overwrite earlier ones.
    Returns (image (H, W, C), coverage (H, W) bool)."""
    n_attr = tri_attr.shape[2]
    img = np.zeros((height, width, n_attr))
    cov = np.zeros((height, width), dtype=bool)
    zbuf = np.full((height, width), np.inf)
    for t in range(len(tri_xy)):
        p = tri_xy[t]
        c0 = max(int(np.floor(p[:, 0].min() - 0.5)), 0)
        c1 = min(int(np.ceil(p[:, 0].max() - 0.5)), width - 1)
        r0 = max(int(np.floor(p[:, 1].min() - 0.5)), 0)
        r1 = min(int(np.ceil(p[:, 1].max() - 0.5)), height - 1)
        if c1 < c0 or r1 < r0:
            continue
        (ax, ay), (bx, by), (cx, cy) = p
        den = (by - cy) * (ax - cx) + (cx - bx) * (ay - cy)
        if abs(den) < 1e-14:
            continue
        xs = np.arange(c0, c1 + 1) + 0.5
        ys = np.arange(r0, r1 + 1)[:, None] + 0.5
        l0 = ((by - cy) * (xs - cx) + (cx - bx) * (ys - cy)) / den
        l1 = ((cy - ay) * (xs - cx) + (ax - cx) * (ys - cy)) / den
        l2 = 1.0 - l0 - l1
        eps = -1e-9
        inside = (l0 >= eps) & (l1 >= eps) & (l2 >= eps)
        if not inside.any():
            continue
        lam = np.stack([l0, l1, l2], axis=-1)
        sub_img = img[r0:r1 + 1, c0:c1 + 1]
        if tri_depth is not None:
            z = lam @ tri_depth[t]
            sub_z = zbuf[r0:r1 + 1, c0:c1 + 1]
            inside &= z < sub_z
            sub_z[inside] = z[inside]
        sub_img[inside] = (lam @ tri_attr[t])[inside]
        cov[r0:r1 + 1, c0:c1 + 1] |= inside
    return img, cov


def gutter(img: np.ndarray, cov: np.ndarray, px: int) -> np.ndarray:
    """Edge extension: `px` times, every uncovered pixel next to (8-neighbourhood) covered
    ones takes the mean of those neighbours and becomes covered."""
    img = img.copy()
    cov = cov.copy()
    h, w = cov.shape
    for _ in range(px):
        acc = np.zeros_like(img)
        cnt = np.zeros((h, w))
        pi = np.pad(img, ((1, 1), (1, 1), (0, 0)))
        pc = np.pad(cov, 1)
        for dy in (-1, 0, 1):
            for dx in (-1, 0, 1):
                if dx == 0 and dy == 0:
                    continue
                c = pc[1 + dy:1 + dy + h, 1 + dx:1 + dx + w]
                acc += pi[1 + dy:1 + dy + h, 1 + dx:1 + dx + w] * c[..., None]
                cnt += c
        grow = (~cov) & (cnt > 0)
        img[grow] = acc[grow] / cnt[grow][:, None]
        cov = cov | grow
    return img



def uv_to_px(uv: np.ndarray, size: int) -> np.ndarray:
    """OBJ uv (v up) -> pixel coordinates of a size x size image whose row 0 is the top (v = 1)."""
    return np.stack([uv[..., 0] * size, (1.0 - uv[..., 1]) * size], axis=-1)


def render_previews(out: Path, obj, head_ids, eye_ids, Pm, UV, masks) -> None:
    """Check renders of the head (`obj`, a gen_head.Obj) and its region `masks` into `out`."""
    out.mkdir(parents=True, exist_ok=True)
    colours = {"lips": (0.85, 0.1, 0.2), "cheeks": (0.95, 0.45, 0.3), "eyelids": (0.3, 0.35, 0.9), "tzone": (0.1, 0.7, 0.3),
               "nose": (0.9, 0.8, 0.1), "forehead": (0.2, 0.8, 0.8), "under_eye": (0.5, 0.2, 0.7),
               "ears": (0.9, 0.3, 0.8), "chin": (0.3, 0.5, 0.2), "temples": (0.2, 0.4, 0.9)}
    tv, tt, te = [], [], []
    for gi, ids in enumerate([head_ids] + [eye_ids[n] for n in sorted(eye_ids)]):
        for i in ids:
            f = obj.faces[i]
            for k in range(1, len(f) - 1):
                tv.append([f[0][0], f[k][0], f[k + 1][0]])
                tt.append([f[0][1], f[k][1], f[k + 1][1]])
                te.append(gi > 0)
    tv, tt, te = np.array(tv), np.array(tt), np.array(te)
    fn = np.cross(Pm[tv[:, 1]] - Pm[tv[:, 0]], Pm[tv[:, 2]] - Pm[tv[:, 0]])
    Nv = np.zeros_like(Pm)
    for k in range(3):
        np.add.at(Nv, tv[:, k], fn)
    Nv /= np.linalg.norm(Nv, axis=1, keepdims=True) + 1e-30

    def ry(a: float) -> np.ndarray:  # turn the head by a about +Y
        return np.array([[np.cos(a), 0, -np.sin(a)], [0, 1, 0], [np.sin(a), 0, np.cos(a)]])

    # name: (rotation, centre (x, y) in mm on screen, px per mm, width, height)
    views = {
        "front": (np.eye(3), (0.0, 20.0), 3.0, 900, 900),
        "left": (ry(np.pi / 2), (0.0, 20.0), 3.0, 900, 900),
        "oblique": (ry(0.6), (0.0, 20.0), 3.0, 900, 900),
        "mouth": (np.eye(3), (0.0, -68.0), 12.0, 900, 540),
        "eyes": (np.eye(3), (0.0, 2.0), 9.0, 900, 400),
    }
    light = np.array([0.3, 0.5, 0.8])
    light /= np.linalg.norm(light)
    for vname, (R, (cx, cy), scale, sw, sh) in views.items():
        Q = Pm @ R.T
        xy = np.stack([(Q[:, 0] - cx) * scale + sw / 2, (cy - Q[:, 1]) * scale + sh / 2], axis=1)
        lam = np.clip((Nv @ R.T) @ light, 0.0, 1.0) * 0.75 + 0.2
        attr = np.concatenate([lam[tv][..., None], UV[tt], np.repeat(te[:, None, None], 3, 1).astype(float)], axis=2)
        img, cov = rasterise(xy[tv], attr, sw, sh, tri_depth=-Q[tv][..., 2])
        shade, uvp, is_eye = img[..., 0], img[..., 1:3], img[..., 3] > 0.5
        px = np.clip(uv_to_px(uvp, 1024).astype(int), 0, 1023)
        base = np.repeat(shade[..., None], 3, axis=2) * np.array([1.0, 0.93, 0.88])
        base[is_eye] = shade[is_eye][:, None] * np.array([0.8, 0.85, 1.0])
        allimg = base.copy()
        for n, m in masks.items():
            w = (m[px[..., 1], px[..., 0]] / 255.0) * cov * (~is_eye)
            col = np.array(colours[n])
            one = base * (1 - w[..., None]) + (shade[..., None] * col) * w[..., None]
            allimg = allimg * (1 - w[..., None]) + (shade[..., None] * col) * w[..., None]
            if vname == "front":
                write_png(out / f"{vname}_{n}.png", np.clip(one * cov[..., None] * 255, 0, 255).astype(np.uint8))
        write_png(out / f"{vname}_all.png", np.clip(allimg * cov[..., None] * 255, 0, 255).astype(np.uint8))
    # UV view: the masks in colour over the head's UV wireframe
    uvimg = np.zeros((1024, 1024, 3))
    for n, m in masks.items():
        uvimg += (m[..., None] / 255.0) * np.array(colours[n])
    for i in head_ids:
        f = obj.faces[i]
        for (a, b) in zip(f, f[1:] + f[:1]):
            pa, pb = uv_to_px(UV[a[1]], 1024), uv_to_px(UV[b[1]], 1024)
            for t in np.linspace(0, 1, 24):
                c, r = (pa * (1 - t) + pb * t).astype(int)
                if 0 <= c < 1024 and 0 <= r < 1024:
                    uvimg[r, c] = np.maximum(uvimg[r, c], 0.35)
    write_png(out / "uv_all.png", np.clip(uvimg * 255, 0, 255).astype(np.uint8))
    # the face part of the UV view, 4x (nearest), with the UV edges drawn at that scale
    r0, r1, c0, c1, z = 420, 640, 760, 980, 4
    crop = np.zeros(((r1 - r0) * z, (c1 - c0) * z, 3))
    for n, m in masks.items():
        crop += np.kron(m[r0:r1, c0:c1] / 255.0, np.ones((z, z)))[..., None] * np.array(colours[n])
    for i in head_ids:
        f = obj.faces[i]
        for (a, b) in zip(f, f[1:] + f[:1]):
            pa, pb = uv_to_px(UV[a[1]], 1024), uv_to_px(UV[b[1]], 1024)
            for t in np.linspace(0, 1, 60):
                c, r = ((pa * (1 - t) + pb * t - (c0, r0)) * z).astype(int)
                if 0 <= c < crop.shape[1] and 0 <= r < crop.shape[0]:
                    crop[r, c] = np.maximum(crop[r, c], 0.45)
    write_png(out / "uv_face_x4.png", np.clip(crop * 255, 0, 255).astype(np.uint8))
    print(f"previews in {out}")
