"""``navkit plan`` on a map in UTM coordinates: the table's points are the points.

The start, goal and escape rows were printed with ``:g`` (6 significant digits): on
a map at a UTM origin (x ~ 5e5 m, y ~ 4.5e6 m) a start at (500130.87, 4500681.73)
read ``(500131, 4.50068e+06)``, 1.73 m off in y, and the escape cell's centre was
just as vague. They are now printed to the nanometre, or to the float's own
spacing where that is coarser (9.3e-10 m at 4.5e6 m).
"""

from __future__ import annotations

import math
import re
from decimal import Decimal
from pathlib import Path

import numpy as np
import pytest
from hypothesis import example, given, settings
from hypothesis import strategies as st

from hypothesis_twins import slow_twin
from navkit._shared.metres import metres_text as _metres_text
from navkit.cli import main
from navkit.mapping import OccupancyGrid
from navkit.mapping.io import read_map, write_map
from navkit.planning import MapPlanner

ORIGIN = (500123.45, 4500678.9)
RADIUS = 0.3


def _room(origin: tuple[float, float]) -> OccupancyGrid:
    """A 3 x 2 m map at ``origin``: a wall at x = 1.4 to 1.6 m up to y = 1 m."""
    occupied = np.zeros((20, 30), dtype=bool)
    occupied[:10, 14:16] = True
    return OccupancyGrid.from_occupancy(
        occupied, resolution=0.1, origin=(origin[0], origin[1], 0.0)
    )


def _row(out: str, name: str) -> tuple[float, float]:
    match = re.search(rf"^{re.escape(name)}\s+\((\S+), (\S+)\)\s*$", out, flags=re.MULTILINE)
    assert match is not None, out
    return float(match.group(1)), float(match.group(2))


def _plan(map_yaml: Path, start: tuple[float, float], goal: tuple[float, float]) -> list[str]:
    return ["plan", str(map_yaml), f"--start={start[0]!r},{start[1]!r}",
            f"--goal={goal[0]!r},{goal[1]!r}", "--radius", str(RADIUS),
            "--start-tolerance", "0.5", "--quiet"]  # fmt: skip


def test_start_goal_and_escape_rows_are_the_points_at_utm_coordinates(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    write_map(_room(ORIGIN), tmp_path / "utm.yaml")
    # As typed; the start (1.87, 0.43) m from the origin, within --radius of the
    # wall's right side, escapes to a cell centre.
    start = (500125.32, 4500679.33)
    goal = (500126.06, 4500680.47)
    assert main(_plan(tmp_path / "utm.yaml", start, goal)) == 0
    out = capsys.readouterr().out
    assert _row(out, "start (m)") == start
    assert _row(out, "goal (m)") == goal
    library = MapPlanner(read_map(tmp_path / "utm.yaml"), robot_radius=RADIUS)
    expected = library.plan(start, goal, start_tolerance=0.5)
    assert not np.array_equal(expected.points[0], expected.points[1])  # it did escape
    escaped = _row(out, "escaped to (m)")
    # To a float step of 4.5e6 m (9.3e-10 m): :g was off by up to 50 m here.
    for got, want in zip(escaped, expected.points[1].tolist(), strict=True):
        assert abs(got - want) <= math.ulp(want)
    # The same escape as on the map at the origin, translated.
    near = MapPlanner(_room((0.0, 0.0)), robot_radius=RADIUS).plan(
        (start[0] - ORIGIN[0], start[1] - ORIGIN[1]),
        (goal[0] - ORIGIN[0], goal[1] - ORIGIN[1]),
        start_tolerance=0.5,
    )
    shifted = np.asarray(escaped) - np.asarray(ORIGIN)
    np.testing.assert_allclose(shifted, near.points[1], rtol=0.0, atol=2e-9)


@settings(max_examples=200, deadline=None)
@given(st.floats(-1e15, 1e15, allow_nan=False, allow_infinity=False, exclude_max=True,
                 exclude_min=True))  # fmt: skip
# CI's slow twin (session 37): nine decimals whose nearest float lies 5.02e-10 away
# raised StopIteration. The text itself, read exactly, is within the nanometre.
@example(32768.6277635715)
def test_metres_text_is_within_a_nanometre_or_a_float_step(value: float) -> None:
    text = _metres_text(value)
    assert "e" not in text and text != "-0"
    # Read back within a float step, or the text itself (read exactly) within 5e-10.
    assert abs(float(text) - value) <= max(5e-10, math.ulp(value)) or abs(
        Decimal(text) - Decimal(value)
    ) <= Decimal("5e-10")
    # No more decimals than a nanometre.
    assert len(text.partition(".")[2]) <= 9


test_metres_text_is_within_a_nanometre_or_a_float_step_thoroughly = slow_twin(
    test_metres_text_is_within_a_nanometre_or_a_float_step, max_examples=2000
)


@pytest.mark.parametrize(
    ("value", "text"),
    [(1.25, "1.25"), (0.35000000000000003, "0.35"), (-0.0, "0"), (3.0, "3"),
     (500130.87, "500130.87"), (4500681.725000001, "4500681.725"),
     (1e15, "1000000000000000.0"), (-1e300, "-1e+300")],
)  # fmt: skip
def test_metres_text_known_values(value: float, text: str) -> None:
    # Small maps read as before (:g was exact there); UTM points in full.
    assert _metres_text(value) == text
