"""Second-wave review of navkit.plot: scene windows at large coordinates, exact range messages."""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from hypothesis_twins import slow_twin
from navkit.geometry import Twist2D
from navkit.kinematics import DiffDrive
from navkit.mapping import OccupancyGrid
from navkit.planning import ConicAttraction, sample_field
from navkit.plot import animate_trace, plot_field, plot_grid, plot_scene, save_figure
from navkit.sim import Robot, Scene, Simulation, World

_COORD = st.floats(-1e9, 1e9, allow_nan=False)


def _drawn_limits(scene: Scene) -> tuple[tuple[float, float], tuple[float, float]]:
    ax = plot_scene(scene)
    ax.figure.canvas.draw()  # matplotlib settles (and may widen) the limits here
    return ax.get_xlim(), ax.get_ylim()


@pytest.mark.parametrize(("x", "dx"), [(1e6, math.ulp(1e6)), (1e9, -1e-7), (0.0, 1e-300)])
def test_a_tiny_scene_far_out_is_not_drawn_kilometres_wide(x: float, dx: float) -> None:
    # Two points one rounding step apart at x = 1e6 m used to be drawn in a
    # window 100 km wide (matplotlib widens a window narrower than 1e-15 of
    # its coordinates to ±5 % of them), and two at the origin in a ±0.05 m one.
    points = np.array([[x, 0.0], [x + dx, 0.0]])
    (x0, x1), (y0, y1) = _drawn_limits(Scene("two points", points=(("p", points),)))
    assert x0 < min(x, x + dx) and max(x, x + dx) < x1
    assert y0 < 0.0 < y1
    assert x1 - x0 <= 1e-9 * max(1.0, abs(x))
    assert y1 - y0 <= 1e-9 * max(1.0, abs(x))


@settings(max_examples=15, deadline=None)
@given(_COORD, _COORD, st.floats(0.0, 1e3), st.floats(0.0, 1e3))
def test_the_drawn_window_is_the_scene_and_its_margin(
    x: float, y: float, width: float, height: float
) -> None:
    # The documented window: the points' box grown by max(5 %, min(0.25 m, the
    # larger side)) -- or by 0.25 m around a single point -- unless that is
    # below 1e-12 of the coordinates, which matplotlib could not draw at scale.
    corner = np.array([[x, y], [x + width, y + height]])
    corner = np.clip(corner, -1e9, 1e9)
    lo, hi = corner.min(axis=0), corner.max(axis=0)
    span = float(np.max(hi - lo))
    floor = 1e-12 * max(1.0, float(np.abs(corner).max()))
    margin = max(0.05 * span, min(0.25, max(span, floor))) if span > 0.0 else 0.25
    (x0, x1), (y0, y1) = _drawn_limits(Scene("box", points=(("p", corner),)))
    tol = 1e-9 * (margin + span)
    assert x0 == pytest.approx(lo[0] - margin, abs=tol)
    assert x1 == pytest.approx(hi[0] + margin, abs=tol)
    assert y0 == pytest.approx(lo[1] - margin, abs=tol)
    assert y1 == pytest.approx(hi[1] + margin, abs=tol)


test_the_drawn_window_is_the_scene_and_its_margin_thoroughly = slow_twin(
    test_the_drawn_window_is_the_scene_and_its_margin, max_examples=40
)


@pytest.mark.parametrize("bad", [1.0000001, math.nextafter(1.0, 2.0), -1e-9])
def test_alpha_errors_print_the_value_given(bad: float) -> None:
    grid = OccupancyGrid.from_occupancy(np.eye(4, dtype=bool), resolution=0.1)
    with pytest.raises(ValueError, match="alpha") as info:
        plot_grid(grid, alpha=bad)
    # ":g" printed 1.0000001 as "1", a value inside the range it refused.
    assert f"got {bad!r}" in str(info.value)


def test_dpi_errors_print_the_value_given(tmp_path: object) -> None:
    grid = OccupancyGrid.from_occupancy(np.eye(4, dtype=bool), resolution=0.1)
    ax = plot_grid(grid)
    for bad in (600.0000001, math.nextafter(10.0, 0.0)):
        with pytest.raises(ValueError, match="dpi") as info:
            save_figure(ax, f"{tmp_path}/a.png", dpi=bad)
        assert f"got {bad!r}" in str(info.value)
    # Exactly at the limits is accepted.
    for dpi in (10.0, 600.0):
        assert save_figure(ax, f"{tmp_path}/a.png", dpi=dpi).exists()


def test_footprint_errors_print_the_value_given(tmp_path: object) -> None:
    robot = Robot(drive=DiffDrive(track=0.3, wheel_radius=0.05), footprint=0.15)
    trace = Simulation(World(), robot, lambda obs: Twist2D(0.5, 0.0, 0.0),
                       start=(0.0, 0.0, 0.0), duration=0.2).run()  # fmt: skip
    bad = 1e6 * (1 + 1e-9)
    with pytest.raises(ValueError, match="footprint") as info:
        animate_trace(trace, f"{tmp_path}/a.gif", footprint=bad)
    assert f"got {bad!r}" in str(info.value)


def test_a_field_of_exactly_1024_by_1024_samples_is_drawn() -> None:
    # sample_field gives this window 1024 × 1024 samples, the documented most; the
    # float estimate (hi - lo) / resolution rounds up to 1025 per axis and was refused.
    lo, hi, res = 521.9248898251512, 532.1648898251512, 0.01
    field = ConicAttraction(np.zeros(2))
    assert sample_field(field, xlim=(lo, hi), ylim=(lo, hi), resolution=res).shape == (1024, 1024)
    ax = plot_field(field, kind="quiver", xlim=(lo, hi), ylim=(lo, hi), resolution=res)
    assert ax.collections


@settings(max_examples=12, deadline=None)
@given(
    st.floats(-1e4, 1e4, allow_nan=False),
    st.sampled_from([0.001, 0.01, 0.05, 0.1, 0.3]),
    st.integers(1020, 1028),
)
def test_plot_field_refuses_exactly_what_exceeds_its_documented_samples(
    lo: float, res: float, cells: int
) -> None:
    field = ConicAttraction(np.zeros(2))
    window = (lo, lo + cells * res)
    rows, cols = sample_field(field, xlim=window, ylim=(0.0, 1024 * res), resolution=res).shape
    if rows * cols <= 1 << 20:
        plot_field(field, kind="quiver", xlim=window, ylim=(0.0, 1024 * res), resolution=res)
    else:
        with pytest.raises(ValueError, match=f"{rows} × {cols}"):
            plot_field(field, kind="quiver", xlim=window, ylim=(0.0, 1024 * res), resolution=res)
