"""``navkit plan``: gaps a mutation review of ``navkit.cli._plan`` found (review 45, MUTANT23).

Each test here failed on a mutant of ``plan_command``, ``_point_text`` or
``_warm_up`` that every earlier test passed: the table's rows, the JSON's
fields, the compile notice, and the warm-up that keeps compiling out of the
times printed.
"""

from __future__ import annotations

import json
import math
import os
import re
from pathlib import Path
from typing import Any

import numpy as np
import pytest

from navkit.cli import _kernels, _plan, main
from navkit.mapping import OccupancyGrid
from navkit.mapping.io import write_map
from navkit.sim import Scene
from subprocess_probe import probe_outcome


def _map(folder: Path, resolution: float, shape: tuple[int, int] = (10, 12)) -> Path:
    """A map of ``shape`` (rows, cols), not square, with a wall up from the bottom."""
    occupied = np.zeros(shape, dtype=bool)
    occupied[:6, 6] = True
    path = folder / "maps" / "m.yaml"
    path.parent.mkdir()
    write_map(OccupancyGrid.from_occupancy(occupied, resolution=resolution), path)
    return path


def _rows(out: str) -> dict[str, str]:
    """The table's rows: name -> value text (columns are two or more spaces apart)."""
    lines = out.splitlines()
    body = lines[lines.index(next(line for line in lines if line.startswith("---"))) + 1 :]
    pairs = (re.split(r"\s{2,}", line.strip(), maxsplit=1) for line in body if "  " in line)
    return {pair[0]: pair[1] for pair in pairs if len(pair) == 2}


def test_the_table_names_the_map_its_size_and_the_points_as_given(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    # A 12-column, 10-row map of 1 m cells in a folder: the title and the map row
    # name the file (not its folder), width x height, the resolution as typed
    # ("1 m", not "1.0 m"), the radius given, and the points in metres_text
    # ("10", not "10.0").
    path = _map(tmp_path, 1.0)
    argv = ["plan", str(path), "--start", "1.5,1.5", "--goal", "10,1.5", "--radius", "0.25"]
    assert main([*argv, "--quiet"]) == 0
    out = capsys.readouterr().out
    assert out.splitlines()[0] == "navkit plan on m.yaml"
    rows = _rows(out)
    assert rows["map"] == "m.yaml (12 x 10 cells of 1 m)"
    assert rows["robot radius (m)"] == "0.25"
    assert rows["start (m)"] == "(1.5, 1.5)"
    assert rows["goal (m)"] == "(10, 1.5)"


def test_the_json_holds_the_options_given_and_the_times_the_table_prints(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    # A radius other than the resolution and a tolerance other than 0: each JSON
    # field is the option's own. A large map and a short plan keep the costmap's
    # time far from the search's: each time is the table's row of the same name.
    path = _map(tmp_path, 0.1, shape=(400, 500))
    target = tmp_path / "plan.json"
    argv = ["plan", str(path), "--start", "0.15,0.15", "--goal", "0.45,0.15", "--radius", "0.05",
            "--start-tolerance", "0.07", "--json", str(target), "--quiet"]  # fmt: skip
    assert main(argv) == 0
    rows = _rows(capsys.readouterr().out)
    data = json.loads(target.read_text(encoding="utf-8"))
    assert data["robot_radius"] == 0.05 and data["start_tolerance"] == 0.07
    assert rows["start tolerance (m)"] == "0.07"
    for row, key in [("plan time (ms)", "plan_time_ms"), ("costmap time (ms)", "costmap_time_ms")]:
        assert math.isclose(float(rows[row]), data[key], rel_tol=1e-3), (row, rows[row], data)


def test_a_json_naming_the_maps_yaml_is_refused_under_its_own_option(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    path = _map(tmp_path, 0.1)
    before = path.read_bytes()
    argv = ["plan", str(path), "--start", "0.15,0.15", "--goal", "1.05,0.15", "--json", str(path)]
    assert main(argv) == 1
    err = capsys.readouterr().err
    assert err.startswith(f"navkit: error: --json: {path} is the map's YAML"), err
    assert path.read_bytes() == before


def test_a_plot_and_a_json_together_are_both_written(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    pytest.importorskip("matplotlib")
    picture, target = tmp_path / "route.png", tmp_path / "plan.json"
    argv = ["plan", str(_map(tmp_path, 0.1)), "--start", "0.15,0.15", "--goal", "1.05,0.15",
            "--plot", str(picture), "--json", str(target), "--quiet"]  # fmt: skip
    assert main(argv) == 0
    out = capsys.readouterr().out
    assert f"wrote {picture}" in out and f"wrote {target}" in out
    assert picture.read_bytes().startswith(b"\x89PNG\r\n\x1a\n")
    assert len(json.loads(target.read_text(encoding="utf-8"))["points"]) >= 2


def test_the_picture_draws_the_plan_and_its_two_ends(
    tmp_path: Path, capsys: pytest.CaptureFixture[str], monkeypatch: pytest.MonkeyPatch
) -> None:
    # What the picture holds, read from the scene it is drawn from (a PNG's pixels
    # would pin matplotlib's rendering): the path the JSON holds, under the
    # planner's name, and a marker at the start and one at the goal given.
    pytest.importorskip("matplotlib")
    scenes: list[Scene] = []

    def scene(*args: Any, **kwargs: Any) -> Scene:
        scenes.append(Scene(*args, **kwargs))
        return scenes[-1]

    monkeypatch.setattr(_plan, "Scene", scene)
    picture, target = tmp_path / "route.png", tmp_path / "plan.json"
    argv = ["plan", str(_map(tmp_path, 0.1)), "--start", "0.15,0.15", "--goal", "1.05,0.25",
            "--plot", str(picture), "--json", str(target), "--quiet"]  # fmt: skip
    assert main(argv) == 0
    assert picture.is_file()
    (drawn,) = scenes
    points = json.loads(target.read_text(encoding="utf-8"))["points"]
    ((name, path),) = drawn.paths
    assert name == "astar" and np.array_equal(path, points)
    ends = {label: np.asarray(xy).tolist() for label, xy in drawn.points}
    assert ends == {"start": [[0.15, 0.15]], "goal": [[1.05, 0.25]]}


@pytest.fixture
def cold_cache(monkeypatch: pytest.MonkeyPatch) -> list[str]:
    """Kernels uncached, as on a first run (nothing compiled anew): the kinds asked about."""
    asked: list[str] = []

    def kernels_cached(kind: str) -> bool:
        asked.append(kind)
        return False

    monkeypatch.setattr(_kernels, "kernels_cached", kernels_cached)
    monkeypatch.setattr(_kernels, "jit_disabled", lambda: False)
    return asked


def test_the_notice_is_the_planners_own(
    tmp_path: Path, capsys: pytest.CaptureFixture[str], cold_cache: list[str]
) -> None:
    # Field D*'s kernels, not A*'s: their cache is checked and their time said.
    argv = ["plan", str(_map(tmp_path, 0.1)), "--start", "0.15,0.15", "--goal", "1.05,0.15"]
    assert main([*argv, "--planner", "field_dstar"]) == 0
    err = capsys.readouterr().err
    # (And the distance transform's, which every kind of work runs: review 46.)
    assert cold_cache == ["field_dstar", "distance_transform"]
    seconds = _kernels.KERNELS["field_dstar"][1]
    assert f"compiling navkit's kernels once (about {seconds:.0f} s)" in err
    # And how to pay for it ahead, once, rather than in a timed run.
    assert "cached afterwards (`navkit warmup` compiles them all ahead)" in err


def test_an_unusable_cache_is_said_even_when_the_kernels_are_cached(
    tmp_path: Path, capsys: pytest.CaptureFixture[str], monkeypatch: pytest.MonkeyPatch
) -> None:
    # numba cannot write its cache here: the kernels are compiled in every run,
    # whatever the folders hold, and the notice says so rather than staying quiet.
    monkeypatch.setattr(_kernels, "kernels_cached", lambda kind: True)
    monkeypatch.setattr(_kernels, "jit_disabled", lambda: False)
    monkeypatch.setattr(_plan, "check_cache", lambda stream: "a read-only cache folder")
    argv = ["plan", str(_map(tmp_path, 0.1)), "--start", "0.15,0.15", "--goal", "1.05,0.15"]
    assert main(argv) == 0
    err = capsys.readouterr().err
    assert "again in every run: numba cannot cache them here" in err


def test_a_cache_dir_too_long_to_look_into_is_passed_over(
    tmp_path: Path, capsys: pytest.CaptureFixture[str], monkeypatch: pytest.MonkeyPatch
) -> None:
    # numba passes over a NUMBA_CACHE_DIR the system cannot look into (a name over
    # NAME_MAX: ENAMETOOLONG) and caches in __pycache__: the command looks there
    # too, and its plan runs rather than failing on "File name too long".
    monkeypatch.setattr(_kernels, "_numba_cache_dir", lambda: str(tmp_path / ("x" * 300)))
    assert _kernels.cache_folders("navkit.sim")[0].name == "__pycache__"
    argv = ["plan", str(_map(tmp_path, 0.1)), "--start", "0.15,0.15", "--goal", "1.05,0.15"]
    assert main(argv) == 0
    assert "navkit: error" not in capsys.readouterr().err


def test_a_cache_dir_numba_may_not_write_to_is_passed_over(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    # A folder on a read-only mount: os.access refuses writing even to root (whose
    # permission bits are no test; the mount is simulated here for that reason).
    custom = tmp_path / "cache"
    custom.mkdir()
    access = os.access
    monkeypatch.setattr(
        os, "access", lambda path, mode: False if Path(path) == custom else access(path, mode)
    )
    monkeypatch.setattr(_kernels, "_numba_cache_dir", lambda: str(custom))
    folders = _kernels.cache_folders("navkit.sim")
    assert folders and not any(custom in folder.parents for folder in folders)


#: In a fresh process: ``navkit plan`` on a real map (obstacles and unknown space, read
#: back by read_map), and the kernels loaded or compiled between the command's first
#: and last clock readings, whose differences the table prints as its times.
_KERNELS_IN_THE_TIMES = """
import json, sys, time
from pathlib import Path
import numpy as np
from numba.core.dispatcher import Dispatcher
from navkit._shared.jit import LazyKernel
from navkit.cli import main
from navkit.mapping import OccupancyGrid
from navkit.mapping.io import write_map

def overloads():
    counts = {}
    for name, module in list(sys.modules.items()):
        if name.startswith("navkit"):
            for value in list(vars(module).values()):
                if isinstance(value, LazyKernel):
                    value = value.dispatcher
                if isinstance(value, Dispatcher):
                    code = value.py_func
                    counts[f"{code.__module__}.{code.__qualname__}"] = len(value.overloads)
    return counts

snapshots = []
clock = time.perf_counter

def perf_counter():
    if sys._getframe(1).f_code.co_name == "plan_command":  # the command's own readings
        snapshots.append(overloads())
    return clock()

time.perf_counter = perf_counter
folder, planner = Path(sys.argv[1]), sys.argv[2]
logodds = np.full((30, 50), -5.0)
logodds[10:20, 25] = 5.0
logodds[25:, 40:] = 0.0
write_map(OccupancyGrid(logodds, resolution=0.05), folder / "m.yaml")
argv = ["plan", str(folder / "m.yaml"), "--start", "0.3,0.75", "--goal", "2.2,0.75",
        "--radius", "0.12", "--planner", planner, "--quiet"]
code = main(argv)
first, last = snapshots[0], snapshots[-1]
loaded = sorted(k for k, n in last.items() if n != first.get(k, 0))
print(json.dumps([code, len(snapshots), loaded]))
"""


@pytest.mark.parametrize("planner", ["astar", "field_dstar"])
def test_the_times_printed_hold_no_kernel_loading(tmp_path: Path, planner: str) -> None:
    # The warm-up is to load (or compile) every kernel before the first clock
    # reading. Its grid was empty, so no obstacle-distance kernel ran: the first
    # map's costmap loaded them, and on a cold cache compiled them (0.9 s printed
    # as the "costmap time" of a 12 x 10 map, 0.2 ms once compiled).
    code, readings, loaded = probe_outcome(_KERNELS_IN_THE_TIMES, str(tmp_path), planner)
    assert (code, readings, loaded) == (0, 3, [])
