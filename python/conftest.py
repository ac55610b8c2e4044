"""Shared pytest fixtures for the Python cross-checks of the Rust CLI.

Run from the repository root:  .venv/bin/python -m pytest python

The CLI tests need the ``rouge`` binary: $ROUGE_BIN if set, else
<repo>/target/debug/rouge.  A missing binary is a failure, not a skip.
"""

from __future__ import annotations

import json
import os
import subprocess
import sys
import warnings
from pathlib import Path

import pytest

HERE = Path(__file__).resolve().parent
REPO = HERE.parent

if str(HERE) not in sys.path:
    sys.path.insert(0, str(HERE))

# colour-science warns at import about the missing matplotlib and on every
# spectral alignment; neither matters here.
warnings.filterwarnings("ignore", module=r"colour(\..*)?")
warnings.filterwarnings("ignore", message=r".*Matplotlib.*")


@pytest.fixture(scope="session")
def repo_root() -> Path:
    return REPO


@pytest.fixture(scope="session")
def rouge_bin() -> str:
    env = os.environ.get("ROUGE_BIN")
    if env:
        path = Path(env)
    else:
        path = REPO / "target" / "debug" / ("rouge.exe" if os.name == "nt" else "rouge")
    if not path.is_file():
        pytest.fail(
            f"rouge binary not found at {path}. Build it first with "
            "`cargo build -p rouge-app` (from the repository root), or point "
            "ROUGE_BIN at an existing rouge executable.",
            pytrace=False,
        )
    return str(path)


class RougeRun:
    """Call the CLI; ``json`` runs it expecting success and one JSON value."""

    def __init__(self, exe: str):
        self.exe = exe

    def __call__(self, *args: str, timeout: float = 120) -> subprocess.CompletedProcess:
        return subprocess.run(
            [self.exe, *args], capture_output=True, text=True, timeout=timeout, check=False
        )

    def json(self, *args: str):
        p = self(*args)
        assert p.returncode == 0, (
            f"rouge {' '.join(args)} exited with {p.returncode}\nstderr:\n{p.stderr}"
        )
        try:
            return json.loads(p.stdout)
        except json.JSONDecodeError as e:  # pragma: no cover - message only
            raise AssertionError(
                f"rouge {' '.join(args)} did not print one JSON value: {e}\nstdout:\n{p.stdout!r}"
            ) from None


@pytest.fixture(scope="session")
def rouge(rouge_bin) -> RougeRun:
    return RougeRun(rouge_bin)
