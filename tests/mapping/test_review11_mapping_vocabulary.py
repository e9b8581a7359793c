"""Renamed mapping keywords: the old names still work for a release, with a warning.

``max_range`` is now ``range_max`` (the name ``LaserScan``, ``sim.Lidar`` and
``World.raycast`` use) in ``integrate_scan``, ``OccupancyGrid.integrate_scan``,
``ScanMapper`` and ``ScanMatcher`` (and its property);
``grid_to_msg_fields(trinary=)`` is now ``mode="scale" | "trinary"`` (as
``write_map`` and ``OccupancyGrid.save``); ``BagImu.to_base(mounting=)`` is now
``mount=`` (as ``sim.Lidar(mount=)``).
"""

from __future__ import annotations

import inspect
import math
import warnings
from typing import Any

import numpy as np
import pytest

from navkit.geometry import rpy_to_quaternion
from navkit.mapping import LaserScan, OccupancyGrid, ScanMapper, ScanMatcher, integrate_scan
from navkit.mapping.io import BagImu, grid_to_msg_fields

POSE = (0.05, 0.55, 0.0)


def _scan() -> LaserScan:
    return LaserScan([7.0, 2.0], angle_min=0.0, angle_increment=0.05, range_min=0.1, range_max=8.0)


def _grid() -> OccupancyGrid:
    return OccupancyGrid.empty(width=10.0, height=1.0, resolution=0.1)


def _room_scan() -> LaserScan:
    angles = np.linspace(-math.pi, math.pi, 90, endpoint=False)
    with np.errstate(divide="ignore"):
        ranges = np.minimum(3.0 / np.abs(np.cos(angles)), 2.0 / np.abs(np.sin(angles)))
    return LaserScan(ranges, angle_min=-math.pi, angle_increment=2 * math.pi / 90,
                     range_min=0.1, range_max=10.0)  # fmt: skip


def test_integrate_scan_range_max_caps_without_warning() -> None:
    capped, full = _grid(), _grid()
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        integrate_scan(capped, _scan(), POSE, range_max=4.0)
        integrate_scan(full, _scan(), POSE)
    # The 7 m return is cut at 4 m: no hit where the full scan marks one.
    assert full.occupied().any() and not np.array_equal(capped.logodds, full.logodds)


@pytest.mark.parametrize("as_method", [False, True])
def test_integrate_scan_old_name_warns_and_gives_the_same_cells(as_method: bool) -> None:
    new, old = _grid(), _grid()
    n_new = integrate_scan(new, _scan(), POSE, range_max=4.0)
    with pytest.warns(DeprecationWarning, match="max_range is deprecated.*range_max") as rec:
        if as_method:
            n_old = old.integrate_scan(_scan(), POSE, max_range=4.0)
        else:
            n_old = integrate_scan(old, _scan(), POSE, max_range=4.0)
    assert n_old == n_new
    np.testing.assert_array_equal(old.logodds, new.logodds)
    assert rec[0].filename == __file__
    with pytest.raises(TypeError, match="both range_max and its old name max_range"):
        if as_method:
            _grid().integrate_scan(_scan(), POSE, range_max=4.0, max_range=4.0)
        else:
            integrate_scan(_grid(), _scan(), POSE, range_max=4.0, max_range=4.0)


def test_scan_matcher_range_max_and_deprecated_aliases() -> None:
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        matcher = ScanMatcher(range_max=4.0)
        assert matcher.range_max == 4.0 and ScanMatcher().range_max is None
        assert "range_max=4.0" in repr(matcher)
    with pytest.warns(DeprecationWarning, match="max_range is deprecated") as rec:
        old = ScanMatcher(max_range=4.0)
    assert rec[0].filename == __file__
    assert old.range_max == 4.0
    with pytest.warns(DeprecationWarning, match=r"ScanMatcher\.max_range is deprecated") as rec:
        assert old.max_range == 4.0
    assert rec[0].filename == __file__
    with pytest.raises(TypeError, match="both range_max"):
        ScanMatcher(range_max=4.0, max_range=3.0)
    with pytest.raises(ValueError, match="range_max"):
        ScanMatcher(range_max=0.0)


def test_scan_mapper_old_name_warns_and_maps_the_same() -> None:
    scan = _room_scan()
    new = ScanMapper(resolution=0.1, range_max=2.5)
    with pytest.warns(DeprecationWarning, match="max_range is deprecated"):
        old = ScanMapper(resolution=0.1, max_range=2.5)
    full = ScanMapper(resolution=0.1)
    for mapper in (new, old, full):
        mapper.update(scan)
    np.testing.assert_array_equal(old.map.logodds, new.map.logodds)
    assert not np.array_equal(full.map.logodds, new.map.logodds)  # the cap matters here
    with pytest.raises(TypeError, match="both range_max"):
        ScanMapper(range_max=2.5, max_range=2.5)
    # The default follows the matcher's range_max (new name on both).
    capped = ScanMapper(resolution=0.1, matcher=ScanMatcher(range_max=2.5))
    capped.update(scan)
    np.testing.assert_array_equal(capped.map.logodds, new.map.logodds)


def _two_cell_grid() -> OccupancyGrid:
    return OccupancyGrid.from_probabilities(np.array([[0.8, 0.1, 0.5]]), resolution=0.1)


def test_grid_to_msg_fields_mode_default_is_scale() -> None:
    grid = _two_cell_grid()
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        default = grid_to_msg_fields(grid).data.tolist()
        assert grid_to_msg_fields(grid, mode="scale").data.tolist() == default == [80, 10, -1]
        assert grid_to_msg_fields(grid, mode="trinary").data.tolist() == [100, 0, -1]


@pytest.mark.parametrize(("trinary", "mode"), [(True, "trinary"), (False, "scale")])
def test_grid_to_msg_fields_trinary_bool_still_works(trinary: bool, mode: str) -> None:
    grid = _two_cell_grid()
    with pytest.warns(DeprecationWarning, match="trinary is deprecated.*use mode") as rec:
        old = grid_to_msg_fields(grid, trinary=trinary)
    assert rec[0].filename == __file__
    np.testing.assert_array_equal(old.data, grid_to_msg_fields(grid, mode=mode).data)
    with pytest.raises(TypeError, match="both mode and its old name trinary"):
        grid_to_msg_fields(grid, mode="trinary", trinary=trinary)


def test_grid_to_msg_fields_trinary_must_still_be_a_bool() -> None:
    for value in ("no", 1):
        with pytest.raises(TypeError, match="trinary must be a bool"):
            grid_to_msg_fields(_two_cell_grid(), trinary=value)  # type: ignore[arg-type]


def _imu() -> BagImu:
    return BagImu("/imu", "imu_link", [0.0], [0.0], [[0.0, 0.0, 0.0, 1.0]],
                  [[0.0, 0.1, 0.2]], [[0.0, 0.0, 9.8]], *[np.eye(3)[None]] * 3)  # fmt: skip


def test_bag_imu_to_base_mount_positional_and_keyword_agree() -> None:
    mount = rpy_to_quaternion(0.0, 0.0, math.pi / 2)
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        positional = _imu().to_base(mount, frame_id="base")
        keyword = _imu().to_base(mount=mount, frame_id="base")
    with pytest.warns(DeprecationWarning, match="mounting is deprecated.*use mount") as rec:
        old = _imu().to_base(mounting=mount, frame_id="base")
    assert rec[0].filename == __file__
    for other in (keyword, old):
        np.testing.assert_array_equal(other.angular_velocities, positional.angular_velocities)
        np.testing.assert_array_equal(
            other.angular_velocity_covariances, positional.angular_velocity_covariances
        )
    np.testing.assert_allclose(positional.angular_velocities, [[-0.1, 0.0, 0.2]], atol=1e-15)
    with pytest.raises(TypeError, match="both mount and its old name mounting"):
        _imu().to_base(mount, mounting=mount)
    with pytest.raises(TypeError, match="mount"):
        _imu().to_base()


# ScanMapper in the vocabulary of the rest of mapping:
# ScanMapper's options in the vocabulary of the rest of mapping (session 15's audit).
#
# * ``ScanMapper(occupied=0.9, free=0.4)`` took probabilities while
# ``integrate_scan(hit=, miss=)`` takes log-odds: ScanMapper now takes
# ``hit=``/``miss=`` in log-odds, defaults ``logit(0.9)``/``logit(0.4)`` (the
# same increments as before); ``occupied=``/``free=`` still work, converted,
# with a DeprecationWarning.
# * ``min_rotation`` is now ``min_angle``, the ``*_angle`` of ScanMatcher's
# ``search_angle``/``max_step_angle`` (and the pair ``min_distance``/``min_angle``
# mirrors ``search_distance``/``search_angle``).
def _logit(p: float) -> float:
    return math.log(p / (1.0 - p))




def _named(name: str, value: Any) -> dict[str, Any]:
    return {name: value}


def _map(**options: Any) -> np.ndarray:
    mapper = ScanMapper(resolution=0.1, **options)
    mapper.update(_room_scan())
    return mapper.map.logodds


def test_hit_and_miss_defaults_are_the_old_probabilities_as_log_odds() -> None:
    params = inspect.signature(ScanMapper).parameters
    assert params["hit"].default == _logit(0.9)
    assert params["miss"].default == _logit(0.4)
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        default = _map()
        explicit = _map(hit=_logit(0.9), miss=_logit(0.4))
    np.testing.assert_array_equal(default, explicit)
    # The increments are written as given: one scan leaves exactly hit or miss.
    assert set(np.unique(default).tolist()) == {
        0.0, float(np.float32(_logit(0.9))), float(np.float32(_logit(0.4)))
    }


def test_hit_and_miss_are_used() -> None:
    base = _map(hit=1.5, miss=-0.25)
    assert float(base.max()) == pytest.approx(1.5) and float(base.min()) == pytest.approx(-0.25)
    assert not np.array_equal(_map(hit=2.5, miss=-0.25), base)
    assert not np.array_equal(_map(hit=1.5, miss=-0.5), base)


@pytest.mark.parametrize(("old", "new", "p"), [("occupied", "hit", 0.7), ("free", "miss", 0.2)])
def test_old_probabilities_warn_and_give_the_same_map(old: str, new: str, p: float) -> None:
    given: dict[str, Any] = {old: p}
    with pytest.warns(DeprecationWarning, match=f"{old} is deprecated.*use {new}") as rec:
        mapper = ScanMapper(resolution=0.1, **given)
    assert rec[0].filename == __file__
    mapper.update(_room_scan())
    np.testing.assert_array_equal(mapper.map.logodds, _map(**{new: _logit(p)}))
    assert not np.array_equal(mapper.map.logodds, _map())  # p is not the default
    with pytest.raises(TypeError, match=f"both {new} and its old name {old}"):
        ScanMapper(**given, **_named(new, 1.0 if new == "hit" else -1.0))


@pytest.mark.parametrize(
    ("options", "error", "match"),
    [
        ({"occupied": 0.5}, ValueError, "occupied must be > 0.5"),
        ({"occupied": 1.0}, ValueError, "occupied must be < 1"),
        ({"free": 0.0}, ValueError, "free must be > 0"),
        ({"free": 0.5}, ValueError, "free must be < 0.5"),
        ({"occupied": "0.9"}, TypeError, "occupied"),
        ({"hit": -0.1}, ValueError, "hit must be >= 0"),
        ({"hit": 2e6}, ValueError, "hit"),
        ({"miss": 0.1}, ValueError, "miss must be <= 0"),
        ({"miss": -math.inf}, ValueError, "miss"),
        ({"hit": math.nan}, ValueError, "hit"),
        ({"miss": "x"}, TypeError, "miss"),
        ({"min_angle": 4.0}, ValueError, "min_angle must be >= 0 and <= 3.14159"),
        ({"min_rotation": -1.0}, ValueError, "min_rotation must be >= 0"),
    ],
)
def test_bad_values_name_what_the_caller_wrote(
    options: dict[str, Any], error: type[Exception], match: str
) -> None:
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", DeprecationWarning)
        with pytest.raises(error, match=match):
            ScanMapper(**options)


def _rotation_writes(**options: Any) -> bool:
    """Whether a scan 0.75 rad turned from the first is written (no translation)."""
    beams = LaserScan([1.0, 1.5], angle_min=-0.3, angle_increment=0.6, range_min=0.1,
                      range_max=8.0)  # fmt: skip
    mapper = ScanMapper(resolution=0.1, min_distance=5.0, **options)
    mapper.update(beams, odometry=(0.0, 0.0, 0.0))
    before = mapper.map.logodds.copy()
    mapper.update(beams, odometry=(0.0, 0.0, 0.75))
    return not np.array_equal(mapper.map.logodds, before)


def test_min_angle_and_its_old_name() -> None:
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        assert _rotation_writes(min_angle=0.5)
        assert not _rotation_writes(min_angle=1.0)
        assert not _rotation_writes()  # default 0.9 rad
    assert inspect.signature(ScanMapper).parameters["min_angle"].default == 0.9
    for angle, writes in ((0.5, True), (1.0, False)):
        with pytest.warns(DeprecationWarning, match="min_rotation is deprecated.*min_angle"):
            assert _rotation_writes(min_rotation=angle) is writes
    with pytest.raises(TypeError, match="both min_angle and its old name min_rotation"):
        ScanMapper(min_angle=0.5, min_rotation=0.5)
