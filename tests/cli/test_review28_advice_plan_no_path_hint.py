"""``navkit plan``'s no-path hint names the command's options, and following it works.

The planner's hint "a smaller robot_radius or a finite unknown_cost may open
one" reached the command line as written: ``--radius`` is the command's word
for ``robot_radius``, and it takes no ``unknown_cost`` (unknown space is
always impassable there).
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

from navkit.cli import main
from navkit.mapping import OccupancyGrid


def _error_line(capsys: pytest.CaptureFixture[str]) -> str:
    lines = capsys.readouterr().err.strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith("navkit: error: "), lines
    return lines[0]


def _plan(path: Path, radius: str) -> int:
    return main(["plan", str(path), "--start", "0.55,0.95", "--goal", "2.45,0.95",
                 "--radius", radius, "--quiet"])  # fmt: skip


@pytest.fixture
def gap(tmp_path: Path) -> Path:
    """A 3 x 2 m map with a wall at x = 1.4 to 1.6 m, open 0.4 m at y = 0.8 to 1.2 m."""
    occupied = np.zeros((20, 30), dtype=bool)
    occupied[:, 14:16] = True
    occupied[8:12, 14:16] = False
    unknown = np.zeros_like(occupied)
    unknown[0, 0] = True  # unknown cells on the map: the planner's hint names them too
    OccupancyGrid.from_occupancy(occupied, resolution=0.1, unknown=unknown).save(
        tmp_path / "gap.yaml"
    )
    return tmp_path / "gap.yaml"


def test_no_path_hint_says_radius_and_a_smaller_one_plans(
    gap: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    assert _plan(gap, "0.3") == 1
    line = _error_line(capsys)
    assert "obstacles grown by --radius 0.3 m" in line, line
    assert line.endswith("; a smaller --radius may open one"), line
    for internal in ("robot_radius", "unknown_cost"):
        assert internal not in line, line
    # Following it: the 0.4 m gap takes a robot of radius below 0.2 m.
    assert _plan(gap, "0.1") == 0
    assert "length (m)" in capsys.readouterr().out


def test_no_path_through_unknown_space_does_not_offer_unknown_cost(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    occupied = np.zeros((20, 30), dtype=bool)
    unknown = np.zeros_like(occupied)
    unknown[:, 14:16] = True  # unknown space across the map
    OccupancyGrid.from_occupancy(occupied, resolution=0.1, unknown=unknown).save(
        tmp_path / "fog.yaml"
    )
    assert _plan(tmp_path / "fog.yaml", "0") == 1
    line = _error_line(capsys)
    assert "unknown cells impassable may close every way" in line, line
    for internal in ("robot_radius", "unknown_cost", "a smaller --radius"):
        assert internal not in line, line
