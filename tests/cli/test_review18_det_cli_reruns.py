"""The command line reruns alike: the same seed gives the same figures and the same files.

Two runs in fresh interpreters, with different ``PYTHONHASHSEED`` (set and dict
order) and worker counts (this process vs a pool), in different working folders:
the JSON is equal up to wall-clock measurements, the picture and the animation
byte for byte (no timestamps, no paths), and stdout differs only in its timing
lines. ``--seed`` promises "the same seed, the same figures".
"""

from __future__ import annotations

import json
import os
import subprocess
import sys
from pathlib import Path
from typing import Any

import pytest

from scenario_results import comparable_dict


def _comparable(data: dict[str, Any]) -> object:
    """The JSON without wall-clock figures."""
    return comparable_dict(json.loads(json.dumps(data)))


def _run(folder: Path, hash_seed: str, workers: str) -> str:
    folder.mkdir()
    env = {**os.environ, "PYTHONHASHSEED": hash_seed}
    argv = [sys.executable, "-m", "navkit", "run", "omni-apf", "--trials", "1", "--seed", "5",
            "--workers", workers, "--quiet", "--json", "r.json", "--plot", "r.png",
            "--animate", "r.gif"]  # fmt: skip
    done = subprocess.run(
        argv, cwd=folder, env=env, capture_output=True, text=True, timeout=600, check=True
    )
    return done.stdout


@pytest.mark.slow
def test_two_runs_with_one_seed_write_the_same_figures_and_files(tmp_path: Path) -> None:
    out_a = _run(tmp_path / "a", "1", "1")
    out_b = _run(tmp_path / "b", "2024", "2")
    a, b = tmp_path / "a", tmp_path / "b"
    json_a = json.loads((a / "r.json").read_text())
    json_b = json.loads((b / "r.json").read_text())
    assert _comparable(json_b) == _comparable(json_a)
    assert len(json_a["trials"]) > 1  # several trials: the order of their results counts
    for name in ("r.png", "r.gif"):
        assert (b / name).read_bytes() == (a / name).read_bytes(), name
    assert str(tmp_path) not in (a / "r.json").read_text()

    def untimed(out: str) -> list[str]:
        return [line for line in out.splitlines() if " trials in " not in line]

    assert untimed(out_b) == untimed(out_a)
