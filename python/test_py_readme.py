"""The README's Python example runs (python/example_sk_plot.py, the code the README shows) and
draws a PNG; the README quotes the script's code lines verbatim."""

from __future__ import annotations

import subprocess
import sys


def test_readme_example_runs(repo_root, tmp_path):
    out = tmp_path / "sk.png"
    p = subprocess.run(
        [sys.executable, str(repo_root / "python" / "example_sk_plot.py"), str(out)],
        cwd=repo_root, capture_output=True, text=True, timeout=120, check=False,
    )
    assert p.returncode == 0, p.stderr
    assert out.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n" and out.stat().st_size > 10_000


def test_readme_quotes_the_example(repo_root):
    readme = (repo_root / "README.md").read_text()
    script = (repo_root / "python" / "example_sk_plot.py").read_text()
    for line in ("import rouge", "rouge.read_measurement(", "rouge.R_to_SK_KubelkaMunk("):
        quoted = next(ln for ln in script.splitlines() if line in ln)
        assert quoted in readme, f"README must show: {quoted}"
