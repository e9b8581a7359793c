"""ScanMapper's options in the vocabulary of the rest of mapping (session 15's audit).

* ``ScanMapper(occupied=0.9, free=0.4)`` took probabilities while
  ``integrate_scan(hit=, miss=)`` takes log-odds: ScanMapper now takes
  ``hit=``/``miss=`` in log-odds, defaults ``logit(0.9)``/``logit(0.4)`` (the
  same increments as before); ``occupied=``/``free=`` still work, converted,
  with a DeprecationWarning.
* ``min_rotation`` is now ``min_angle``, the ``*_angle`` of ScanMatcher's
  ``search_angle``/``max_step_angle`` (and the pair ``min_distance``/``min_angle``
  mirrors ``search_distance``/``search_angle``).
"""

from __future__ import annotations

import inspect
import math
import warnings
from typing import Any

import numpy as np
import pytest

from navkit.mapping import LaserScan, ScanMapper


def _logit(p: float) -> float:
    return math.log(p / (1.0 - p))


def _room_scan() -> LaserScan:
    angles = np.linspace(-math.pi, math.pi, 90, endpoint=False)
    with np.errstate(divide="ignore"):
        ranges = np.minimum(3.0 / np.abs(np.cos(angles)), 2.0 / np.abs(np.sin(angles)))
    return LaserScan(ranges, angle_min=-math.pi, angle_increment=2 * math.pi / 90,
                     range_min=0.1, range_max=10.0)  # fmt: skip


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
