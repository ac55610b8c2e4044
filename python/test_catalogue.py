"""python/catalogue.py on a small grid (two shades, one tone, one expression), here and on a Dask
LocalCluster of two worker processes: the same PNGs and the same colour figures either way, the
images rendered off this process on the cluster, and the figures tell the shades apart (the red
lipstick's lips are redder and further from the bare lips than the nude's). Skipped, saying so,
where the `rouge` wheel has no renderer (CI) or dask.distributed is absent."""

import csv
import os

import pytest

rouge = pytest.importorskip("rouge")
if not rouge.HAS_RENDER:
    pytest.skip("SKIPPED: the installed `rouge` wheel was built without the renderer "
                "(maturin develop -m py/Cargo.toml --features render)", allow_module_level=True)
pytest.importorskip("distributed", reason="SKIPPED: dask.distributed is not installed (pip install dask distributed)")

import catalogue  # noqa: E402

JOBS = [(shade, "medium", "neutral", 96, 72, 0) for shade in ("builtin:lipstick_01_nude", "builtin:lipstick_02_red")]


def rows(out):
    with open(out / "catalogue.csv") as f:
        return list(csv.DictReader(f))


def test_here_and_on_a_local_cluster_give_the_same_catalogue(tmp_path):
    here = catalogue.run(JOBS, tmp_path / "here")
    cluster = catalogue.run(JOBS, tmp_path / "cluster", workers=2)
    assert here["images"] == cluster["images"] == 2
    a, b = rows(tmp_path / "here"), rows(tmp_path / "cluster")
    figures = ["file", "lips_pixels", "lips_L", "lips_a", "lips_b", "delta_E00_vs_bare_lips"]
    assert [[r[k] for k in figures] for r in a] == [[r[k] for k in figures] for r in b]
    for r in a:
        assert (tmp_path / "here" / r["file"]).read_bytes() == (tmp_path / "cluster" / r["file"]).read_bytes()
    workers = {r["worker"].split(":")[-1] for r in b}
    assert str(os.getpid()) not in workers and 1 <= len(workers) <= 2, workers
    nude, red = a
    assert int(nude["lips_pixels"]) > 20, "the lips are found"
    assert float(red["lips_a"]) > float(nude["lips_a"]) + 5
    assert float(red["delta_E00_vs_bare_lips"]) > float(nude["delta_E00_vs_bare_lips"])
