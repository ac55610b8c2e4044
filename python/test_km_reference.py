"""Kubelka-Munk: the mpmath references and the ``rouge km`` CLI.

* data/reference/km_*.csv are exactly what gen_km_reference.py generates,
  and the mpmath identities behind them hold (invert(forward) round trip,
  sinh/coth forms, limits, inter-reflection series).
* ``rouge km invert|layer|stack`` agrees with mpmath to relative 1e-9 on
  seeded random valid inputs and on every reference row, and rejects invalid
  input with exit status 2 and a message on stderr.
"""

from __future__ import annotations

import math
import sys

import numpy as np
import pytest
from mpmath import mp, mpf

import gen_km_reference as gen

REL = 1e-9
F64_MIN_NORMAL = sys.float_info.min
REF_FILES = ("km_invert.csv", "km_forward.csv", "km_stack.csv")


def read_reference(repo_root, name: str) -> tuple[list[str], list[dict[str, str]]]:
    text = (repo_root / "data" / "reference" / name).read_text()
    rows = [ln for ln in text.splitlines() if ln and not ln.startswith("#")]
    header = rows[0].split(",")
    return header, [dict(zip(header, r.split(","), strict=True)) for r in rows[1:]]


def assert_close(got: float, ref, what: str, rel: float = REL) -> None:
    """Relative comparison where the reference is a normal f64; otherwise the
    result must be (numerically) zero."""
    ref_f = float(ref) if not isinstance(ref, float) else ref
    assert isinstance(got, (int, float)) and math.isfinite(got), f"{what}: got {got!r}"
    if abs(ref_f) >= F64_MIN_NORMAL:
        err = abs(got - ref_f) / abs(ref_f)
        assert err <= rel, f"{what}: got {got!r}, reference {ref}, relative error {err:.3g}"
    else:
        assert abs(got) <= 1e-300, f"{what}: got {got!r}, reference {ref} (below f64 normal range)"


def arg(name: str, value) -> str:
    """``--name=value`` (the = form keeps negative numbers from looking like flags)."""
    if isinstance(value, (list, tuple)):
        value = ",".join(repr(float(v)) for v in value)
    elif isinstance(value, float):
        value = repr(value)
    return f"--{name}={value}"


# --------------------------------------------------------------------------
# The reference files themselves (no binary needed).


@pytest.mark.parametrize("name", REF_FILES)
def test_reference_file_regenerates_exactly(repo_root, name):
    fresh = gen.render_all()[f"data/reference/{name}"]
    on_disk = (repo_root / "data" / "reference" / name).read_text()
    assert fresh == on_disk, (
        f"data/reference/{name} differs from gen_km_reference.py output; "
        "run .venv/bin/python python/gen_km_reference.py"
    )


@pytest.mark.parametrize(
    ("name", "columns", "n_inputs"),
    [
        ("km_invert.csv", "case,r_inf,r,rg,thickness_mm,s_per_mm,k_per_mm", 4),
        ("km_forward.csv", "case,s_per_mm,k_per_mm,thickness_mm,rg,r0,t,r_over_rg", 4),
        ("km_stack.csv", "case,r1,t1,r2,t2,r12,t12", 4),
    ],
)
def test_reference_file_format(repo_root, name, columns, n_inputs):
    header, rows = read_reference(repo_root, name)
    assert ",".join(header) == columns
    assert len(rows) >= 20
    cases = [r["case"] for r in rows]
    assert len(set(cases)) == len(cases), "case names must be unique"
    for r in rows:
        for col in header[1 : 1 + n_inputs]:
            # Inputs are repr() of f64: they round-trip exactly.
            assert repr(float(r[col])) == r[col], (r["case"], col)
        for col in header[1 + n_inputs :]:
            mpf(r[col])  # parses
            if r[col] != "0.0":
                digits = r[col].split("e")[0].replace("-", "").replace(".", "").lstrip("0")
                assert len(digits) <= gen.DIGITS, (r["case"], col)


def test_mpmath_identities_hold():
    worst = gen.self_check()
    assert worst["invert_roundtrip"] < 1e-40


def test_reference_rows_round_trip(repo_root):
    """Recompute from the files: invert -> forward gives back R, to 1e-25."""
    _, rows = read_reference(repo_root, "km_invert.csv")
    with mp.workdps(gen.DPS):
        for r in rows:
            s, k = mpf(r["s_per_mm"]), mpf(r["k_per_mm"])
            # Inputs are f64 values: mpf(float(..)), not the decimal string.
            r0, t = gen.km_layer_mp(s, k, float(r["thickness_mm"]))
            back = gen.over_background_mp(r0, t, float(r["rg"]))
            # 30 printed digits for S and K: R comes back to ~1e-28.
            assert abs(back - mpf(float(r["r"]))) <= mpf(10) ** -25, r["case"]


def test_stack_formula_is_not_the_misprint():
    """R12 = R1 + T1^2 R2/(1 - R1 R2); the printed T1 R1 T1 numerator is wrong."""
    with mp.workdps(gen.DPS):
        r1, t1, r2, t2 = mpf("0.3"), mpf("0.5"), mpf("0.6"), mpf("0.2")
        good = gen.stack2_mp(r1, t1, r2, t2)
        series = gen.stack_series_mp(r1, t1, r2, t2)
        assert abs(good[0] - series[0]) < mpf(10) ** -50
        misprint = r1 + t1 * r1 * t1 / (1 - r1 * r2)
        assert abs(misprint - series[0]) > mpf("0.01")


# --------------------------------------------------------------------------
# CLI: random valid cases.

RNG_SEED = 20240611
N_RANDOM = 50


def _random_invert_cases():
    rng = np.random.default_rng(RNG_SEED)
    out = []
    while len(out) < N_RANDOM:
        r_inf = float(rng.uniform(0.02, 0.98))
        rg = float(rng.uniform(0.0, 0.98))
        if abs(rg - r_inf) < 0.02:
            continue
        r = float(rg + rng.uniform(0.02, 0.98) * (r_inf - rg))
        d = float(10 ** rng.uniform(-3, 0))
        out.append((r_inf, r, rg, d))
    return out


def _random_layer_cases():
    rng = np.random.default_rng(RNG_SEED + 1)
    return [
        (float(10 ** rng.uniform(-1, 3)), float(10 ** rng.uniform(-2, 2)), float(10 ** rng.uniform(-3, 0)))
        for _ in range(N_RANDOM)
    ]


def _random_stack_cases():
    rng = np.random.default_rng(RNG_SEED + 2)
    out = []
    for _ in range(N_RANDOM):
        n = int(rng.integers(1, 5))
        rs = [float(rng.uniform(0.0, 0.9)) for _ in range(n)]
        ts = [float(rng.uniform(0.0, 1.0 - r)) for r in rs]
        out.append((rs, ts))
    return out


def test_cli_invert_random(rouge):
    for r_inf, r, rg, d in _random_invert_cases():
        out = rouge.json(
            "km", "invert", arg("r-inf", r_inf), arg("r", r), arg("rg", rg), arg("thickness-mm", d)
        )
        assert isinstance(out, dict) and set(out) == {"s_per_mm", "k_per_mm"}, out
        with mp.workdps(gen.DPS):
            s, k = gen.km_invert_mp(r_inf, r, rg, d)
        what = f"invert r_inf={r_inf!r} r={r!r} rg={rg!r} d={d!r}"
        assert_close(out["s_per_mm"], s, what + " S")
        assert_close(out["k_per_mm"], k, what + " K")


def test_cli_layer_random(rouge):
    for s, k, x in _random_layer_cases():
        out = rouge.json("km", "layer", arg("s", s), arg("k", k), arg("thickness-mm", x))
        assert isinstance(out, dict) and set(out) == {"r0", "t"}, out
        with mp.workdps(gen.DPS):
            r0, t = gen.km_layer_mp(s, k, x)
        what = f"layer s={s!r} k={k!r} x={x!r}"
        assert_close(out["r0"], r0, what + " r0")
        assert_close(out["t"], t, what + " t")


def test_cli_stack_random(rouge):
    for rs, ts in _random_stack_cases():
        out = rouge.json("km", "stack", arg("r", rs), arg("t", ts))
        assert isinstance(out, dict) and set(out) == {"r", "t"}, out
        with mp.workdps(gen.DPS):
            r, t = gen.stack_mp(rs, ts)
        what = f"stack r={rs} t={ts} (top first)"
        assert_close(out["r"], r, what + " r")
        assert_close(out["t"], t, what + " t")


def test_cli_stack_order_matters(rouge):
    """Top layer first: a dark absorbing top over a white base differs from
    the reverse, and the CLI must follow the top-first order."""
    rs, ts = [0.05, 0.8], [0.3, 0.1]
    top_first = rouge.json("km", "stack", arg("r", rs), arg("t", ts))
    with mp.workdps(gen.DPS):
        r, t = gen.stack_mp(rs, ts)
        r_rev, _ = gen.stack_mp(rs[::-1], ts[::-1])
    assert abs(float(r) - float(r_rev)) > 0.1
    assert_close(top_first["r"], r, "stack top-first r")
    assert_close(top_first["t"], t, "stack top-first t")


# --------------------------------------------------------------------------
# CLI: every reference row.


def test_cli_matches_km_invert_reference(rouge, repo_root):
    _, rows = read_reference(repo_root, "km_invert.csv")
    for row in rows:
        out = rouge.json(
            "km",
            "invert",
            f"--r-inf={row['r_inf']}",
            f"--r={row['r']}",
            f"--rg={row['rg']}",
            f"--thickness-mm={row['thickness_mm']}",
        )
        assert_close(out["s_per_mm"], row["s_per_mm"], f"km_invert.csv {row['case']} S")
        assert_close(out["k_per_mm"], row["k_per_mm"], f"km_invert.csv {row['case']} K")


def test_cli_matches_km_forward_reference(rouge, repo_root):
    _, rows = read_reference(repo_root, "km_forward.csv")
    for row in rows:
        out = rouge.json(
            "km",
            "layer",
            f"--s={row['s_per_mm']}",
            f"--k={row['k_per_mm']}",
            f"--thickness-mm={row['thickness_mm']}",
        )
        assert_close(out["r0"], row["r0"], f"km_forward.csv {row['case']} r0")
        assert_close(out["t"], row["t"], f"km_forward.csv {row['case']} t")


def test_cli_matches_km_stack_reference(rouge, repo_root):
    _, rows = read_reference(repo_root, "km_stack.csv")
    for row in rows:
        out = rouge.json(
            "km", "stack", f"--r={row['r1']},{row['r2']}", f"--t={row['t1']},{row['t2']}"
        )
        assert_close(out["r"], row["r12"], f"km_stack.csv {row['case']} r")
        assert_close(out["t"], row["t12"], f"km_stack.csv {row['case']} t")


# --------------------------------------------------------------------------
# CLI: invalid input.

INVALID = [
    ("r_inf_above_one", ["km", "invert", "--r-inf=1.2", "--r=0.5", "--rg=0.04", "--thickness-mm=0.05"]),
    ("r_inf_zero", ["km", "invert", "--r-inf=0.0", "--r=0.5", "--rg=0.04", "--thickness-mm=0.05"]),
    ("r_rg_opposite_sides", ["km", "invert", "--r-inf=0.5", "--r=0.6", "--rg=0.3", "--thickness-mm=0.05"]),
    ("r_rg_opposite_sides_2", ["km", "invert", "--r-inf=0.5", "--r=0.3", "--rg=0.8", "--thickness-mm=0.05"]),
    ("r_beyond_rg", ["km", "invert", "--r-inf=0.5", "--r=0.2", "--rg=0.3", "--thickness-mm=0.05"]),
    ("thickness_zero", ["km", "invert", "--r-inf=0.5", "--r=0.3", "--rg=0.04", "--thickness-mm=0"]),
    ("thickness_negative", ["km", "invert", "--r-inf=0.5", "--r=0.3", "--rg=0.04", "--thickness-mm=-1"]),
    ("layer_negative_s", ["km", "layer", "--s=-1", "--k=1", "--thickness-mm=0.05"]),
    ("stack_length_mismatch", ["km", "stack", "--r=0.1,0.2", "--t=0.5"]),
]


@pytest.mark.parametrize(("label", "argv"), INVALID, ids=[i[0] for i in INVALID])
def test_cli_invalid_input_exits_2(rouge, label, argv):
    p = rouge(*argv)
    assert p.returncode == 2, f"{label}: exit status {p.returncode}, stdout {p.stdout!r}"
    assert p.stderr.strip(), f"{label}: no message on stderr"
