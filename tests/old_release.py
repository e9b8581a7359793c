"""Old releases' pickles in tests: scripts run on an earlier commit's source, their classes.

:func:`made_at` extracts ``src`` of a commit from the project's git checkout
into a temporary folder and runs a Python script there in a child process (its
own numba cache), returning the JSON the script prints: how the review 50
pickle tests make again the bytes an older release wrote. Skips the test when
no git checkout holds the commit (an sdist, a shallow clone).
"""

from __future__ import annotations

import json
import os
import subprocess
import sys
import types
from pathlib import Path
from typing import Any

import pytest

ROOT = Path(__file__).resolve().parents[1]


def made_at(commit: str, script: str, tmp_path: Path) -> Any:
    """The JSON printed by ``script`` run with the source of ``commit`` on its path."""
    try:
        archive = subprocess.run(
            ["git", "-C", str(ROOT), "archive", commit, "src"],
            capture_output=True, check=True, timeout=120,
        )  # fmt: skip
    except (OSError, subprocess.SubprocessError):
        pytest.skip(f"no git checkout holding {commit}")
    subprocess.run(["tar", "-x", "-C", str(tmp_path)], input=archive.stdout, check=True)
    env = {**os.environ, "PYTHONPATH": str(tmp_path / "src"),
           "NUMBA_CACHE_DIR": str(tmp_path / "numba")}  # fmt: skip
    made = subprocess.run(
        [sys.executable, "-c", script], capture_output=True, check=True, text=True, env=env,
        timeout=300,
    )  # fmt: skip
    return json.loads(made.stdout)


def install_module(monkeypatch: pytest.MonkeyPatch, name: str, source: str) -> types.ModuleType:
    """Module ``name`` made from ``source``, in ``sys.modules`` for the test (pickles look)."""
    module = types.ModuleType(name)
    monkeypatch.setitem(sys.modules, name, module)
    exec(source, module.__dict__)
    return module
