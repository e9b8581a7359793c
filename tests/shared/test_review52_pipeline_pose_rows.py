"""Rows of poses handed where points are wanted get the hint that fits (review 52, PIPELINE).

Every trajectory navkit returns is rows of poses ``[x, y, theta]``
(``ScanMapper.trajectory``, ``Trace.poses``, ``BagOdometry.poses``), and the next
package along a pipeline often wants points ``(N, 2)``: a tracker's path, a
moving obstacle's waypoints, the cells of world points. For two poses, shape
``(2, 3)``, the error used to say only "it looks transposed ... pass its .T,
shape (3, 2)": following it gives three points made of mixed coordinates
(``(x0, x1), (y0, y1), (theta0, theta1)``), which every call then takes without a
word. The hint now names the poses and ``[:, :2]`` first.
"""

from __future__ import annotations

import re

import numpy as np
import pytest

from navkit.control import FollowTheCarrot, OnOffTracker, RegulatedPurePursuit
from navkit.mapping import OccupancyGrid
from navkit.planning import Path2D
from navkit.sim import MovingObstacle

# Two poses of a robot driving along +x then turning: what ScanMapper.trajectory or
# Trace.poses hold after two steps.
TWO_POSES = np.array([[1.0, 2.0, 0.0], [3.0, 2.0, 0.5]])
FIVE_POSES = np.column_stack([np.linspace(0.5, 3.5, 5), np.full(5, 2.0), np.zeros(5)])


def _message(call: object) -> str:
    with pytest.raises(ValueError) as info:
        call()  # type: ignore[operator]
    return str(info.value)


@pytest.mark.parametrize("tracker_type", [RegulatedPurePursuit, FollowTheCarrot, OnOffTracker])
def test_a_trajectory_of_two_poses_given_as_a_path_names_the_poses(tracker_type: type) -> None:
    tracker = tracker_type()
    message = _message(lambda: tracker.set_path(TWO_POSES))
    assert "rows of poses [x, y, theta]? pass its [:, :2], shape (2, 2)" in message
    # The transpose is still offered, but second and as the other reading.
    assert message.index("[:, :2]") < message.index(".T")
    # The advice given first works and keeps the poses' positions.
    tracker.set_path(TWO_POSES[:, :2])
    cmd = tracker.step(TWO_POSES[0], 0.05)
    assert cmd.vx > 0.0  # it drives along the path (+x), which starts at the robot


def test_following_the_old_advice_would_have_been_silently_wrong() -> None:
    """Why the transpose must not be the only advice: it is accepted, and wrong."""
    wrong = Path2D(TWO_POSES.T, "world", cost=0.0, length=0.0, expanded=0)
    assert wrong.points.tolist() == [[1.0, 3.0], [2.0, 2.0], [0.0, 0.5]]
    assert not np.array_equal(wrong.points[[0, -1]], TWO_POSES[:, :2])


@pytest.mark.parametrize("poses", [TWO_POSES, FIVE_POSES], ids=["2 poses", "5 poses"])
def test_poses_where_world_points_are_wanted(poses: np.ndarray) -> None:
    rows = len(poses)
    hint = f"rows of poses [x, y, theta]? pass its [:, :2], shape ({rows}, 2)"
    grid = OccupancyGrid.empty(width=4.0, height=4.0, resolution=0.1)
    calls = {
        "points_xy": lambda: grid.world_to_cell(poses),
        "path_xy": lambda: MovingObstacle.scripted(0.2, poses, speed=0.5),
        "path": lambda: RegulatedPurePursuit().set_path(poses),
    }
    for name, call in calls.items():
        message = _message(call)
        assert message.startswith(name), message
        assert hint in message, message
    # And the advice is taken as the points the poses stand at.
    cells = grid.world_to_cell(poses[:, :2])
    assert np.array_equal(cells, grid.world_to_cell(np.array([[p[0], p[1]] for p in poses])))


@pytest.mark.parametrize("shape", [(2, 5), (2, 1), (4, 3)])
def test_other_shapes_keep_their_hints(shape: tuple[int, int]) -> None:
    grid = OccupancyGrid.empty(width=4.0, height=4.0, resolution=0.1)
    message = _message(lambda: grid.world_to_cell(np.zeros(shape)))
    if shape[0] == 2:
        assert message.endswith(
            f" (it looks transposed, one column per item: pass its .T, shape {shape[::-1]})"
        )
        assert "poses" not in message
    else:
        assert re.search(r"rows of poses .*shape \(4, 2\)\)$", message)
        assert "transposed" not in message


def test_poses_where_poses_are_wanted_are_not_told_to_drop_theta() -> None:
    """The poses hint is for (N, 2) points only: a (N, 3) pose array is fine where it is wanted."""
    from navkit._shared.validation import transposed_hint

    assert transposed_hint((5, 3), (None, 3)) == ""
    assert "[:, :2]" not in transposed_hint((3, 4), (None, 3))


def test_the_getting_started_table_quotes_the_message() -> None:
    from pathlib import Path

    page = (Path(__file__).resolve().parents[2] / "docs" / "getting-started.md").read_text(
        encoding="utf-8"
    )
    quoted = "rows of poses [x, y, theta]? pass its [:, :2]"
    assert f'error "{quoted}"' in page
    assert quoted in _message(lambda: FollowTheCarrot().set_path(FIVE_POSES))
