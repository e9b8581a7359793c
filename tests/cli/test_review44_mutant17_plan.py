"""``navkit plan``: gaps a mutation review found (review 44, MUTANT17).

Each test here failed on a mutant of ``navkit.cli._plan`` that every earlier
test passed.
"""

from __future__ import annotations

import io
import os
from pathlib import Path

import numpy as np
import pytest

from navkit.cli import _kernels, main
from navkit.cli._parser import build_parser
from navkit.cli._plan import plan_command
from navkit.errors import NoPathError
from navkit.mapping import OccupancyGrid
from navkit.mapping.io import write_map
from navkit.planning import MapPlanner


def _map(folder: Path) -> str:
    occupied = np.zeros((10, 12), dtype=bool)
    occupied[:6, 6] = True
    write_map(OccupancyGrid.from_occupancy(occupied, resolution=0.1), folder / "m.yaml")
    return str(folder / "m.yaml")


def _plan(folder: Path, *options: str) -> list[str]:
    return ["plan", _map(folder), "--start", "0.15,0.15", "--goal", "1.05,0.15", *options]


@pytest.mark.parametrize("name", ["route.jpg", "route.PNG.txt", "route"])
def test_a_plot_that_is_no_png_is_refused_before_the_plan(
    tmp_path: Path, name: str, capsys: pytest.CaptureFixture[str]
) -> None:
    pytest.importorskip("matplotlib")
    code = main(_plan(tmp_path, "--plot", str(tmp_path / name)))
    captured = capsys.readouterr()
    assert code == 1
    assert captured.err.startswith("navkit: error: --plot: ") and ".png" in captured.err
    assert captured.out == ""  # no table printed before the refusal
    assert not (tmp_path / name).exists()


def test_quiet_silences_the_compilation_notice(
    tmp_path: Path, capsys: pytest.CaptureFixture[str], monkeypatch: pytest.MonkeyPatch
) -> None:
    # A cold cache, as on a first run (without compiling anything anew).
    monkeypatch.setattr(_kernels, "kernels_cached", lambda kind: False)
    monkeypatch.setattr(_kernels, "jit_disabled", lambda: False)
    assert main(_plan(tmp_path)) == 0
    assert "compiling navkit's kernels" in capsys.readouterr().err
    assert main(_plan(tmp_path, "--quiet")) == 0
    assert capsys.readouterr().err == ""


def test_no_path_keeps_the_searchs_expansion_count(tmp_path: Path) -> None:
    # The command re-raises the planner's NoPathError in its options' words; the
    # count of expanded cells goes with it (for an embedder calling the command).
    occupied = np.zeros((10, 12), dtype=bool)
    occupied[:, 6] = True  # a wall across the map
    grid = OccupancyGrid.from_occupancy(occupied, resolution=0.1)
    write_map(grid, tmp_path / "m.yaml")
    argv = ["plan", str(tmp_path / "m.yaml"), "--start", "0.15,0.15", "--goal", "1.05,0.15"]
    with pytest.raises(NoPathError) as library:
        MapPlanner(grid, robot_radius=0.0).plan((0.15, 0.15), (1.05, 0.15))
    with pytest.raises(NoPathError, match=r"--start .* --goal") as command:
        plan_command(build_parser().parse_args(argv), io.StringIO(), io.StringIO())
    assert command.value.expanded == library.value.expanded > 0


def test_an_output_that_is_the_maps_yaml_by_another_name_is_refused(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    # The same file, not the same spelling: a hard link to the YAML would be replaced.
    argv = _plan(tmp_path)
    alias = tmp_path / "alias.json"
    os.link(tmp_path / "m.yaml", alias)
    before = (tmp_path / "m.yaml").read_bytes()
    assert main([*argv, "--json", str(alias)]) == 1
    assert "is the map's YAML" in capsys.readouterr().err
    assert (tmp_path / "m.yaml").read_bytes() == before
