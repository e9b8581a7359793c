"""The command line without optional packages: a clear error before the work, or none."""

from __future__ import annotations

import io
import os
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

from navkit.cli import _progress
from navkit.cli._progress import ProgressBar
from navkit.mapping import OccupancyGrid
from navkit.mapping.io import write_map

_WITHOUT = """
import sys
for name in {names!r}:
    sys.modules[name] = None
from navkit.cli import main
sys.exit(main(sys.argv[1:]))
"""


def _navkit_without(names: list[str], *args: str) -> subprocess.CompletedProcess[str]:
    env = {k: v for k, v in os.environ.items() if k != "NUMBA_DISABLE_JIT"}
    return subprocess.run(
        [sys.executable, "-c", _WITHOUT.format(names=names), *args],
        env=env, capture_output=True, text=True, timeout=300,
    )  # fmt: skip


@pytest.fixture
def small_map(tmp_path: Path) -> Path:
    occupied = np.zeros((10, 12), dtype=bool)
    occupied[:6, 6] = True
    return write_map(OccupancyGrid.from_occupancy(occupied, resolution=0.1), tmp_path / "m.yaml")


@pytest.mark.parametrize(("option", "suffix"), [("--plot", ".png"), ("--animate", ".gif")])
def test_a_picture_without_matplotlib_fails_before_the_run(
    tmp_path: Path, option: str, suffix: str
) -> None:
    # The run went to its end (minutes for `navkit run`), printed its tables and
    # only then failed to draw.
    done = _navkit_without(
        ["matplotlib"], "demo", "--trials", "1", "--quiet", option, str(tmp_path / f"o{suffix}")
    )
    assert done.returncode == 1
    assert done.stdout == ""
    assert "Traceback" not in done.stderr
    assert done.stderr.startswith(f"navkit: error: {option} needs matplotlib")
    assert "pip install 'navkit[plot]'" in done.stderr


def test_plan_plot_without_matplotlib_fails_before_planning(
    tmp_path: Path, small_map: Path
) -> None:
    done = _navkit_without(
        ["matplotlib"], "plan", str(small_map), "--start", "0.15,0.15", "--goal", "1.05,0.15",
        "--plot", str(tmp_path / "p.png"), "--quiet",
    )  # fmt: skip
    assert done.returncode == 1
    assert done.stdout == ""
    assert "navkit[plot]" in done.stderr and "Traceback" not in done.stderr


class _Terminal(io.StringIO):
    def isatty(self) -> bool:
        return True


def test_no_bar_rather_than_a_failed_run_without_tqdm(monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setattr(_progress, "DELAY", 0.0)
    monkeypatch.setitem(sys.modules, "tqdm", None)
    stream = _Terminal()
    with ProgressBar(stream, enabled=True, description="demo") as bar:
        bar.start(2)
        bar(1, 2)
        bar(2, 2)
        assert not bar.shown
    assert stream.getvalue() == ""
