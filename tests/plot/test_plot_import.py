"""navkit.plot without matplotlib: importable, and each function names the plot extra."""

from __future__ import annotations

import math
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

import navkit.plot as nkplot
from navkit.mapping import LaserScan, OccupancyGrid
from navkit.sim import Metrics, Scene, Trace


def test_importing_navkit_plot_does_not_import_matplotlib() -> None:
    code = "import sys, navkit.plot; print('matplotlib' in sys.modules)"
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    assert out.stdout.strip() == "False"


def _sampled():  # type: ignore[no-untyped-def]
    from navkit.planning import ConicAttraction, sample_field

    return sample_field(ConicAttraction((0, 0)), xlim=(-1, 1), ylim=(-1, 1), resolution=0.5)


def _trace() -> Trace:
    poses = np.zeros((2, 3))
    metrics = Metrics(False, "timeout", 1.0, *[math.nan] * 6, 1.0, 0, 0.0)
    return Trace(np.array([0.0, 1.0]), poses, poses, poses, (), (), metrics)


_GRID = OccupancyGrid.empty(width=1.0, height=1.0, resolution=0.5)
_SCAN = LaserScan([1.0], angle_min=0.0, angle_increment=0.1, range_min=0.1, range_max=2.0)
CALLS = {
    "plot_grid": lambda: nkplot.plot_grid(_GRID),
    "plot_path": lambda: nkplot.plot_path(np.zeros((2, 2))),
    "plot_trace": lambda: nkplot.plot_trace(_trace()),
    "plot_scan": lambda: nkplot.plot_scan(_SCAN, (0.0, 0.0, 0.0)),
    "plot_field": lambda: nkplot.plot_field(_sampled()),
    "plot_scene": lambda: nkplot.plot_scene(Scene("x")),
    "save_figure": lambda: nkplot.save_figure(object(), "x.png"),  # type: ignore[arg-type]
    "animate_trace": lambda: nkplot.animate_trace(_trace(), "x.gif"),
}


@pytest.mark.parametrize("name", sorted(CALLS))
def test_without_matplotlib_an_import_error_names_the_extra(
    name: str, monkeypatch: pytest.MonkeyPatch, tmp_path: Path
) -> None:
    monkeypatch.chdir(tmp_path)
    monkeypatch.setitem(sys.modules, "matplotlib", None)
    with pytest.raises(ImportError, match=r"pip install 'navkit\[plot\]'"):
        CALLS[name]()
    assert list(tmp_path.iterdir()) == []


def test_every_public_function_is_listed() -> None:
    assert sorted(nkplot.__all__) == [
        "animate_trace", "plot_field", "plot_grid", "plot_path", "plot_scan", "plot_scene",
        "plot_trace", "save_figure",
    ]  # fmt: skip
