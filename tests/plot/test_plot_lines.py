"""plot_path, plot_trace and plot_scan: what is drawn where."""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest
from plot_pixels import grey_at, render

from navkit.mapping import LaserScan, OccupancyGrid
from navkit.planning import Path2D
from navkit.plot import plot_grid, plot_path, plot_scan, plot_trace
from navkit.sim import Event, Metrics, ScanReading, Trace

pytest.importorskip("matplotlib")


def _trace(*, estimates: bool = True, collision_at: float | None = None) -> Trace:
    """A hand-made run along y = 1 from x = 0 to 2 in 2 s, its estimate 0.1 m off."""
    times = np.linspace(0.0, 2.0, 21)
    poses = np.column_stack((times, np.ones_like(times), np.zeros_like(times)))
    est = poses + np.array([0.0, 0.1, 0.0]) if estimates else np.full_like(poses, np.nan)
    events = () if collision_at is None else (Event(collision_at, "collision", "bump"),)
    metrics = Metrics(False, "timeout", 2.0, math.nan, math.nan, math.nan, math.nan,
                      math.nan, math.nan, 0.1, len(events), 2.0)  # fmt: skip
    return Trace(times, poses, est, np.zeros_like(poses), (), events, metrics)


# ------------------------------------------------------------------ plot_path
def test_world_points_and_paths_are_drawn_as_given() -> None:
    pts = np.array([[0.0, 0.0], [1.0, 0.5], [2.0, 0.5]])
    ax = plot_path(pts, label="plan", color="red")
    line = ax.lines[0]
    assert line.get_xydata().tolist() == pts.tolist()
    assert line.get_label() == "plan" and line.get_color() == "red"
    path = Path2D(pts, "world", cost=2.1, length=2.1, expanded=3)
    assert plot_path(path).lines[0].get_xydata().tolist() == pts.tolist()


def test_a_grid_path_is_converted_to_world_coordinates() -> None:
    grid = OccupancyGrid.empty(width=2.0, height=1.0, resolution=0.5)
    grid_path = Path2D([[0, 0], [1, 2], [1, 3]], "grid", cost=3.0, length=3.0, expanded=3)
    ax = plot_path(grid_path, grid=grid)
    np.testing.assert_allclose(ax.lines[0].get_xydata(), grid.cell_to_world(grid_path.points))
    with pytest.raises(ValueError, match="grid="):
        plot_path(grid_path)


def test_a_path_over_a_map_lands_on_its_cells(tmp_path: Path) -> None:
    grid = OccupancyGrid.from_occupancy(np.zeros((20, 20), dtype=bool), resolution=0.1)
    ax = plot_grid(grid)
    plot_path(np.array([[0.2, 1.0], [1.8, 1.0]]), ax=ax, color="black")
    image, pixel = render(ax, tmp_path)
    assert grey_at(image, pixel([1.0, 1.0]), radius=0) < 0.3  # on the line
    assert grey_at(image, pixel([1.0, 1.5])) > 0.95  # beside it


@pytest.mark.parametrize(
    ("path", "kwargs", "error", "match"),
    [
        (np.empty((0, 2)), {}, ValueError, "at least one"),
        (np.array([[0.0, math.nan]]), {}, ValueError, "finite"),
        (np.array([[0.0, 2e9]]), {}, ValueError, "1e\\+09"),
        (np.zeros((3, 3)), {}, ValueError, "path"),
        ("0,0", {}, TypeError, "path"),
        (np.zeros((2, 2)), {"label": 3}, TypeError, "label"),
        (np.zeros((2, 2)), {"color": "no-such-colour"}, ValueError, "color"),
        (np.zeros((2, 2)), {"grid": "map"}, TypeError, "grid"),
    ],
)
def test_bad_paths_are_refused(path: object, kwargs: dict, error: type, match: str) -> None:
    with pytest.raises(error, match=match):
        plot_path(path, **kwargs)  # type: ignore[arg-type]


# ------------------------------------------------------------------ plot_trace
def test_a_trace_is_drawn_true_solid_estimate_dashed_with_ends_marked() -> None:
    ax = plot_trace(_trace(), label="run")
    styles = {line.get_label(): line.get_linestyle() for line in ax.lines}
    assert styles["run"] == "-" and styles["run (estimate)"] == "--"
    true_line = next(line for line in ax.lines if line.get_label() == "run")
    assert true_line.get_xydata()[[0, -1]].tolist() == [[0.0, 1.0], [2.0, 1.0]]
    markers = [line.get_marker() for line in ax.lines]
    assert "o" in markers and "s" in markers
    colours = {line.get_color() for line in ax.lines}
    assert len(colours) == 1  # one run, one colour


def test_no_dashed_line_without_an_estimator_or_when_asked() -> None:
    assert all(line.get_linestyle() != "--" for line in plot_trace(_trace(estimates=False)).lines)
    assert all(line.get_linestyle() != "--" for line in plot_trace(_trace(), estimate=False).lines)


def test_collisions_are_marked_where_they_happened() -> None:
    ax = plot_trace(_trace(collision_at=1.25))
    crosses = [line for line in ax.lines if line.get_marker() == "x"]
    assert len(crosses) == 1
    assert crosses[0].get_xydata().tolist() == [[1.25, 1.0]]
    assert crosses[0].get_color() == "red"


def test_bad_traces_are_refused() -> None:
    with pytest.raises(TypeError, match="Trace"):
        plot_trace(np.zeros((3, 3)))  # type: ignore[arg-type]
    with pytest.raises(TypeError, match="estimate"):
        plot_trace(_trace(), estimate=1)  # type: ignore[arg-type]


def test_a_trace_without_rows_is_a_value_error_in_every_drawing(tmp_path: Path) -> None:
    # It used to be an IndexError (marking the start of a run that has none).
    from navkit.plot import animate_trace, plot_scene
    from navkit.sim import Scene

    empty = Trace(np.zeros(0), np.zeros((0, 3)), np.zeros((0, 3)), np.zeros((0, 3)), (), (),
                  _trace().metrics)  # fmt: skip
    with pytest.raises(ValueError, match=r"^trace has no poses"):
        plot_trace(empty)
    with pytest.raises(ValueError, match=r"scene\.traces\[1\] has no poses"):
        plot_scene(Scene("s", traces=(("full", _trace()), ("empty", empty))))
    with pytest.raises(ValueError, match="source has no poses"):
        animate_trace(empty, tmp_path / "run.gif")
    assert list(tmp_path.iterdir()) == []
    # One row is a run too: start and end marked at the same place.
    one = Trace(np.zeros(1), np.ones((1, 3)), np.full((1, 3), np.nan), np.zeros((1, 3)), (),
                (), _trace().metrics)  # fmt: skip
    markers = [line.get_xydata().tolist() for line in plot_trace(one).lines[1:]]
    assert markers == [[[1.0, 1.0]], [[1.0, 1.0]]]


# ------------------------------------------------------------------ plot_scan
def _scan() -> LaserScan:
    return LaserScan([1.0, 2.0, math.inf, 0.01], angle_min=0.0, angle_increment=math.pi / 2,
                     range_min=0.1, range_max=5.0)  # fmt: skip


def test_scan_end_points_are_the_valid_returns_in_the_world() -> None:
    pose = (1.0, 1.0, math.pi / 2)
    ax = plot_scan(_scan(), pose, rays=True, label="scan")
    dots = ax.collections[0]
    np.testing.assert_allclose(dots.get_offsets(), _scan().to_points(pose), atol=1e-12)
    np.testing.assert_allclose(dots.get_offsets(), [[1.0, 2.0], [-1.0, 1.0]], atol=1e-12)
    rays = ax.collections[1].get_segments()
    assert len(rays) == 2 and all(np.allclose(ray[0], [1.0, 1.0]) for ray in rays)
    assert dots.get_label() == "scan"


def test_a_scan_reading_from_a_simulated_trace_draws_too() -> None:
    reading = ScanReading(0.5, _scan())
    ax = plot_scan(reading.scan, (0.0, 0.0, 0.0))
    assert len(ax.collections) == 1  # no rays unless asked


@pytest.mark.parametrize(
    ("scan", "pose", "kwargs", "error"),
    [
        ([1.0], (0.0, 0.0, 0.0), {}, TypeError),
        (None, (0.0, 0.0), {}, ValueError),
        (None, (0.0, 0.0, math.nan), {}, ValueError),
        (None, (2e9, 0.0, 0.0), {}, ValueError),
        (None, (0.0, 0.0, 0.0), {"rays": "yes"}, TypeError),
    ],
)
def test_bad_scans_are_refused(scan: object, pose: object, kwargs: dict, error: type) -> None:
    with pytest.raises(error):
        plot_scan(_scan() if scan is None else scan, pose, **kwargs)  # type: ignore[arg-type]
