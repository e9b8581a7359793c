"""Prose claims of the docs pages, recomputed (a review of whether the docs are true today).

``tests/test_review10_docs_claims.py`` pins defaults and numbers quoted from
computations; this file adds the claims a docs review found unpinned: the words
the getting-started page's "Common mistakes" table quotes from navkit's
messages, the first-use CPU time quoted on two pages, the float spacings and
drift the geometry and estimation guides quote for UTM coordinates, and the
kinds of failure the estimation guide's conventions promise.
"""

from __future__ import annotations

import math
import re
import warnings
from collections.abc import Callable
from pathlib import Path
from typing import Any

import numpy as np
import pytest

from navkit.control import FollowTheCarrot
from navkit.errors import FilterError
from navkit.estimation import DiffOdometry, ExtendedKalmanFilter, FusionStatus, PlanarFusion
from navkit.geometry import Pose2D, as_pose, rollout
from navkit.kinematics import DiffDrive, OmniDrive
from navkit.mapping import LaserScan, OccupancyGrid
from navkit.planning import astar, plan_path

ROOT = Path(__file__).resolve().parents[1]


def _page(relative: str) -> str:
    """A page's text with every run of whitespace collapsed to one space."""
    return " ".join((ROOT / relative).read_text(encoding="utf-8").split())


# ---------------------------------------------------------------------------
# getting-started.md, "Common mistakes": the quoted words are navkit's own.


def _map() -> OccupancyGrid:
    occupied = np.zeros((40, 60), dtype=bool)
    occupied[:30, 28:32] = True
    return OccupancyGrid.from_occupancy(occupied, resolution=0.1)


def _yaml_in_percent(folder: Path) -> None:
    _map().save(folder / "map.yaml")
    text = (folder / "map.yaml").read_text(encoding="utf-8")
    assert "occupied_thresh: 0.65" in text
    (folder / "map.yaml").write_text(text.replace("occupied_thresh: 0.65", "occupied_thresh: 65"))
    OccupancyGrid.load(folder / "map.yaml")


def _grid_path_to_tracker() -> None:
    FollowTheCarrot().set_path(astar(np.ones((10, 10)), (0, 0), (9, 9)))


# (the words the table quotes, the mistake, the exception it raises)
MISTAKES: list[tuple[tuple[str, ...], Callable[[Path], Any], type[Exception]]] = [
    (
        ("look like degrees",),
        lambda _: LaserScan(
            np.ones(360), angle_min=-180.0, angle_increment=1.0, range_min=0.1, range_max=10.0
        ),
        ValueError,
    ),
    (
        ("a cell is an integer (row, col) index", "world_to_cell"),
        lambda _: astar(np.ones((20, 20)), (1.5, 2.0), (10, 10)),
        TypeError,
    ),
    (("was it given as (x, y)?",), lambda _: astar(np.ones((10, 30)), (25, 3), (1, 1)), ValueError),
    (("a Pose2D is [x, y, theta]",), lambda _: as_pose([1.0, 2.0]), ValueError),
    (
        ("it looks transposed, one column per item: pass its .T",),
        lambda _: _map().world_to_cell(np.zeros((2, 5))),
        ValueError,
    ),
    (("[value]",), lambda _: ExtendedKalmanFilter(5.0, np.eye(1)), ValueError),
    (("np.ravel",), lambda _: ExtendedKalmanFilter(np.zeros((3, 1)), np.eye(3)), ValueError),
    (
        ("its origin is the lower-left corner of cell (0, 0)",),
        lambda _: plan_path(_map(), (-2.0, -1.0), (1.0, 1.0)),
        ValueError,
    ),
    (("they are probabilities, not percent",), _yaml_in_percent, ValueError),
    (
        ("grid_from_msg", "np.where(data < 0, 0.5, data / 100)"),
        lambda _: OccupancyGrid.from_probabilities(np.array([[0, 100, -1]]), resolution=0.1),
        ValueError,
    ),
    (
        ("np.where(occupied, np.inf, 1.0)",),
        lambda _: astar(np.zeros((10, 10), dtype=bool), (0, 0), (9, 9)),
        ValueError,
    ),
    (
        ("traversal_costs(grid)", "np.where(occupied, np.inf, 1.0)"),
        lambda _: astar(np.zeros((10, 10), dtype=np.uint8), (0, 0), (9, 9)),  # a Nav2 costmap
        ValueError,
    ),
    (("traversal_costs(grid)",), lambda _: astar(_map(), (0, 0), (9, 9)), ValueError),
    (
        ("call set_path(path) first",),
        lambda _: FollowTheCarrot().step(Pose2D(0.0, 0.0, 0.0), 0.1),
        RuntimeError,
    ),
    (("path.to_world(grid)", "MapPlanner"), lambda _: _grid_path_to_tracker(), ValueError),
]


@pytest.mark.parametrize(
    ("quoted", "mistake", "kind"), MISTAKES, ids=[" / ".join(m[0]) for m in MISTAKES]
)
def test_common_mistakes_quote_the_messages(
    quoted: tuple[str, ...],
    mistake: Callable[[Path], Any],
    kind: type[Exception],
    tmp_path: Path,
) -> None:
    table = re.search(r"## Common mistakes(.*)", _page("docs/getting-started.md"))
    assert table is not None
    with pytest.raises(kind) as raised:
        mistake(tmp_path)
    for words in quoted:
        assert words in table[1], f"the table no longer quotes {words!r}"
        assert words in str(raised.value), f"the message no longer says {words!r}"


def test_common_mistakes_degrees_warning_names_np_radians() -> None:
    row = re.search(r"\| omni `wheel_angles` in degrees .*? \| (.*?) \|", _page(
        "docs/getting-started.md"
    ))
    assert row is not None and "a warning naming `np.radians`" in row[1]
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        OmniDrive([30.0, 150.0, 270.0], wheel_radius=0.05, base_radius=0.2)
    assert any("np.radians" in str(w.message) for w in caught)


def test_common_mistakes_float_distances_to_diff_odometry_are_an_error() -> None:
    assert "float distances given to `DiffOdometry.update` are an error" in _page(
        "docs/getting-started.md"
    )
    odometry = DiffOdometry(DiffDrive(track=0.3, wheel_radius=0.05), ticks_per_rev=1000)
    odometry.update(0, 0)
    with pytest.raises(TypeError, match="left_ticks"):
        odometry.update(1.5, 2.5)


# ---------------------------------------------------------------------------
# First-use compilation: the two pages quote one figure, below the whole library's.


def test_first_script_compile_time_is_quoted_alike_and_below_the_whole_library() -> None:
    started = re.search(
        r"fuses its sensors spends about (\d+) s of CPU time compiling",
        _page("docs/getting-started.md"),
    )
    readme = re.search(
        r"\(about (\d+) s of CPU for a script that plans, simulates and fuses\)",
        _page("README.md"),
    )
    everything = re.search(
        r"\| everything \(`navkit\.sim\.warmup\(workers=1\)`\) \| ([\d.]+) s \|",
        _page("docs/compilation.md"),
    )
    assert started is not None and readme is not None and everything is not None
    assert started[1] == readme[1]
    # A script that uses some of the kernels cannot compile more than all of them.
    assert float(started[1]) <= float(everything[1])
    assert f"every kernel of navkit, about {float(everything[1]):g} s" in _page(
        "docs/getting-started.md"
    )


# ---------------------------------------------------------------------------
# Far from the origin: the spacings and the drift the guides quote.


def _sci(x: float) -> str:
    """``x`` as the prose writes it: ``1.9e-9``."""
    mantissa, exponent = f"{x:.1e}".split("e")
    return f"{mantissa}e{int(exponent)}"


def test_utm_spacings_and_rollout_drift() -> None:
    geometry = _page("docs/guides/geometry.md")
    estimation = _page("docs/guides/estimation.md")
    assert f"float64 values lie up to {_sci(np.spacing(1e7))} m apart" in geometry
    assert f"a northing of 5e6 m, where float64 values lie {_sci(np.spacing(5e6))} m apart" in (
        estimation
    )
    # 10^6 steps of 1 mm northward from a northing of 5e6 m.
    start = (5e5, 5e6, math.pi / 2)
    end = rollout(list(start), np.tile([1.0, 0.0, 0.0], (1_000_000, 1)), 0.001)[-1]
    drift_mm = 1e3 * abs(end[1] - start[1] - 1000.0)
    assert f"10^6 steps of 1 mm at a northing of 5e6 m end {drift_mm:.2f} mm off" in geometry
    # The same drift per 100 km (10^6 steps of 1 mm are 1 km), as the estimation guide quotes it.
    assert f"1 mm steps drifted {100 * drift_mm / 10:.1f} cm per 100 km" in estimation
    assert drift_mm < 1e6 * np.spacing(5e6) * 1e3  # "up to one spacing per step"


# ---------------------------------------------------------------------------
# The estimation guide's conventions: which failures raise and which refuse.


def test_estimation_conventions_failure_kinds() -> None:
    page = _page("docs/guides/estimation.md")
    conventions = re.search(r"## Conventions(.*?)## Compass heading", page)
    assert conventions is not None
    for name in ("OVERFLOW", "TIME_GAP", "OUT_OF_ORDER"):
        assert f"`{name}`" in conventions[1], name
        assert name in FusionStatus.__members__
    fusion = PlanarFusion(t0=0.0)
    # An update that would overflow is not applied; the prediction to its time is kept.
    result = fusion.update_odometry(1.0, 1e300, 0.0, v_variance=1e-100, omega_variance=1e-3)
    assert not result.accepted and FusionStatus(result.status) is FusionStatus.OVERFLOW
    assert fusion.t == 1.0 and np.isfinite(fusion.x).all() and np.isfinite(fusion.P).all()
    # A time gap whose prediction would overflow raises, the filter unchanged.
    x, p = fusion.x.copy(), fusion.P.copy()
    with pytest.raises(FilterError):
        fusion.predict(1e300)
    assert fusion.t == 1.0 and np.array_equal(fusion.x, x) and np.array_equal(fusion.P, p)
    # Older than the clock: refused without history, taken with it.
    late = fusion.update_yaw_rate(0.5, 0.1, variance=1e-3)
    assert FusionStatus(late.status) is FusionStatus.OUT_OF_ORDER
    kept = PlanarFusion(t0=0.0, history=1.0)
    kept.update_yaw_rate(1.0, 0.1, variance=1e-3)
    assert kept.update_yaw_rate(0.5, 0.1, variance=1e-3).accepted
    assert "unless `PlanarFusion(history=)`" in conventions[1]


# ---------------------------------------------------------------------------
# The sim guide: how much a scenario result holds.

WILLOW = ROOT.parent / "shared" / "data" / "ros-map-server-maps" / "willow_garage_2010"


@pytest.mark.skipif(not WILLOW.is_dir(), reason="the Willow Garage map is absent")
def test_sim_guide_demo_trial_sizes() -> None:
    import pickle

    from navkit.sim.scenarios import get_scenario

    result = get_scenario("demo")(map="willow").run(1, seed=0)
    sizes = [len(pickle.dumps(trial)) / 1e6 for trial in result.trials]
    quoted = (
        f"`demo` with one trial per leg holds {['no', 'one', 'two', 'three'][len(sizes)]}, of "
        f"{min(sizes):.1f}–{max(sizes):.1f} MB each with their scans, {sum(sizes):.0f} MB in all"
    )
    assert quoted in _page("docs/guides/sim.md")


def test_kinematics_guide_tick_delta_bits_has_no_default() -> None:
    import inspect

    from navkit.kinematics import tick_delta

    bits = inspect.signature(tick_delta).parameters["bits"]
    assert bits.kind is inspect.Parameter.KEYWORD_ONLY and bits.default is inspect.Parameter.empty
    assert "(`bits`, its width, has no default)" in _page("docs/guides/kinematics.md")
