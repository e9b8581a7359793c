"""Issue 12 on reactive navigation: documented ranges, no NaN inside them, hostile input."""

from __future__ import annotations

import math
from typing import Any

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from hypothesis_twins import slow_twin
from navkit.mapping import LaserScan, LocalGrid
from navkit.planning import (
    BlendedAttraction,
    CompositeField,
    ConicAttraction,
    GreedyStep,
    KhatibRepulsion,
    ParaboloidAttraction,
    PiecewiseAttraction,
    PiecewiseRepulsion,
    PotentialField,
    SampledField,
    greedy_step,
    piecewise_repulsive_force_from_scan,
    repulsive_force_from_scan,
    sample_field,
)

TINY = 5e-324  # the smallest positive float (subnormal)
GOAL = (1.0, 2.0)

# Every field class with its parameters: (name, low, high, may be 0).
GAIN = (1e-12, 1e12, False)
LENGTH = (1e-6, 1e6, False)
OFFSET = (0.0, 1e6, True)
FIELDS: dict[type[PotentialField], tuple[Any, dict[str, tuple[float, float, bool]]]] = {
    ParaboloidAttraction: (GOAL, {"k_att": GAIN, "c": GAIN, "a": LENGTH, "b": LENGTH}),
    ConicAttraction: (GOAL, {"m": GAIN, "u_trans": GAIN, "threshold_radius": OFFSET}),
    BlendedAttraction: (GOAL, {"k_att": GAIN, "c": GAIN, "a": LENGTH, "b": LENGTH,
                               "threshold_radius": OFFSET, "width": LENGTH, "m": GAIN,
                               "u_trans": GAIN}),
    PiecewiseAttraction: (GOAL, {"alpha": GAIN, "goal_radius": OFFSET, "spread": LENGTH}),
    KhatibRepulsion: ([[1.0, 0.0]], {"k_rep": GAIN, "influence_radius": LENGTH}),
    PiecewiseRepulsion: ([[1.0, 0.0]], {"delta": GAIN, "beta": GAIN, "obstacle_radius": OFFSET,
                                        "spread": LENGTH}),
}
PARAMS = [(cls, name, rng) for cls, (_, params) in FIELDS.items() for name, rng in params.items()]


def build(cls: type[PotentialField], **kwargs: Any) -> PotentialField:
    return cls(FIELDS[cls][0], **kwargs)  # type: ignore[call-arg]


# --- the issue's reproductions -------------------------------------------------------


def test_issue_reproductions() -> None:
    assert np.array_equal(
        KhatibRepulsion([[1e-200, 0.0], [-1e-200, 0.0]]).force([[0.0, 0.0]]), [[0.0, 0.0]]
    )
    scan = LaserScan([1e-200, 1e-200], angle_min=0.0, angle_increment=math.pi, range_min=0.0,
                     range_max=10.0)
    force = repulsive_force_from_scan(scan, k_rep=1.0, influence_radius=1.0)
    assert np.all(np.isfinite(force)) and force[0] == 0.0
    for call in (
        lambda: KhatibRepulsion([[1.0, 1.0]], k_rep=TINY),
        lambda: KhatibRepulsion([[1.0, 1.0]], influence_radius=TINY),
        lambda: repulsive_force_from_scan(scan, k_rep=TINY),
        lambda: repulsive_force_from_scan(scan, influence_radius=TINY),
        lambda: ParaboloidAttraction((1.0, 1.0), a=TINY),
        lambda: BlendedAttraction((1.0, 1.0), a=TINY),
        lambda: BlendedAttraction((1.0, 1.0), b=TINY),
        lambda: BlendedAttraction((1.0, 1.0), width=TINY),
        lambda: BlendedAttraction((1.0, 1.0)).force([[1e308, -1e308]]),
        lambda: BlendedAttraction((1e308, 0.0)),
    ):
        with pytest.raises(ValueError):
            call()


@pytest.mark.parametrize("cls", list(FIELDS))
@pytest.mark.parametrize("empty", [[], np.empty((0, 2)), np.empty(0), [[]]])
def test_empty_point_sets_give_empty_results(cls: type[PotentialField], empty: Any) -> None:
    # Issue 12: KhatibRepulsion([[1, 1]]).force([]) raised "range() arg 3 must not be zero".
    field = build(cls)
    assert field.force(empty).shape == (0, 2)
    assert field.potential(empty).shape == (0,)
    total = field + ConicAttraction((0.0, 0.0))
    assert total.force(empty).shape == (0, 2)
    assert CompositeField([]).force(empty).shape == (0, 2)


@pytest.mark.parametrize(
    "kwargs",
    [{"xlim": (-1e308, 1e308), "ylim": (0.0, 1.0), "resolution": 0.1},
     {"xlim": (0.0, 1.0), "ylim": (0.0, 1.0), "resolution": 1e-12},
     {"xlim": (-1e9, 1e9), "ylim": (-1e9, 1e9), "resolution": 1e-6}],
)
def test_sample_field_says_how_big_the_window_would_be(kwargs: dict[str, Any]) -> None:
    # Issue 12: OverflowError and MemoryError before.
    with pytest.raises(ValueError, match=r"would need .* cells \(.*B\).*2\*\*26"):
        sample_field(ConicAttraction((0.0, 0.0)), **kwargs)


# --- ranges --------------------------------------------------------------------------


@pytest.mark.parametrize(("cls", "name", "rng"), PARAMS)
def test_parameter_ranges(cls: type[PotentialField], name: str,
                          rng: tuple[float, float, bool]) -> None:
    low, high, zero = rng
    for bad in (low * (1 - 2**-52) if low else -TINY, high * (1 + 2**-52), -1.0, 1e308):
        with pytest.raises(ValueError, match=name):
            build(cls, **{name: bad})
    if not zero:
        with pytest.raises(ValueError, match=name):
            build(cls, **{name: TINY})
    for bad_type in (True, "1.0", 1 + 0j, None, np.array([1.0])):
        with pytest.raises(TypeError, match=name):
            build(cls, **{name: bad_type})
    for good in (low, high, np.float32(1.0), 1):
        field = build(cls, **{name: good})
        assert type(getattr(field, name)) is float


@pytest.mark.parametrize("cls", list(FIELDS))
def test_points_must_lie_within_a_billion_metres(cls: type[PotentialField]) -> None:
    field = build(cls)
    for far in ([1e9 * (1 + 2**-52), 0.0], [[0.0, -1e308]], [0.0, math.inf], [math.nan, 0.0]):
        with pytest.raises(ValueError, match="points_xy"):
            field.force(far)
        with pytest.raises(ValueError, match="points_xy"):
            field.potential(far)
    for bad in ([1 + 1j, 0.0], ["1", "2"], [True, False]):
        with pytest.raises(TypeError, match="points_xy"):
            field.force(bad)
    edge = [[1e9, -1e9], [-1e9, 1e9]]
    assert np.all(np.isfinite(field.force(edge)))
    assert np.all(np.isfinite(field.potential(edge)))
    place = "goal_xy" if FIELDS[cls][0] is GOAL else "obstacles_xy"
    with pytest.raises(ValueError, match=place):
        cls([[2e9, 0.0]] if place == "obstacles_xy" else (2e9, 0.0))  # type: ignore[call-arg]


def log_uniform(low: float, high: float) -> st.SearchStrategy[float]:
    return st.floats(math.log(low), math.log(high)).map(math.exp).map(lambda v: min(high, v))


def parameters(cls: type[PotentialField]) -> st.SearchStrategy[dict[str, float]]:
    entries = {}
    for name, (low, high, zero) in FIELDS[cls][1].items():
        value = log_uniform(max(low, 1e-6), high)
        entries[name] = st.one_of(st.just(0.0), value) if zero else value
    return st.fixed_dictionaries(entries)


coordinate = st.one_of(
    st.floats(-1e9, 1e9), st.floats(-1e-6, 1e-6), st.sampled_from([0.0, 1e-200, -5e-324, 1e9])
)
points = st.lists(st.tuples(coordinate, coordinate), min_size=1, max_size=6)


@pytest.mark.parametrize("cls", list(FIELDS))
@settings(max_examples=50, deadline=None)
@given(data=st.data())
def test_no_nan_and_no_inf_inside_the_ranges(
    cls: type[PotentialField], data: st.DataObject
) -> None:
    kwargs = data.draw(parameters(cls))
    centre = data.draw(points)
    where = data.draw(points)
    first = centre[0] if FIELDS[cls][0] is GOAL else centre
    field = cls(first, **kwargs)  # type: ignore[call-arg]
    pts = np.array(where + centre[:2])  # also exactly on the goal / obstacles
    force = field.force(pts)
    potential = field.potential(pts)
    assert np.all(np.isfinite(force)), (kwargs, force)
    assert not np.any(np.isnan(potential))
    if cls is KhatibRepulsion:
        # +inf exactly on an obstacle (documented), finite everywhere else.
        on = (pts[:, None, :] == field.obstacles_xy[None, :, :]).all(axis=2).any(axis=1)
        assert np.array_equal(np.isinf(potential), on)
    else:
        assert np.all(np.isfinite(potential))


test_no_nan_and_no_inf_inside_the_ranges_thoroughly = slow_twin(
    test_no_nan_and_no_inf_inside_the_ranges, max_examples=150
)


@settings(max_examples=40, deadline=None)
@given(
    st.lists(st.one_of(st.floats(0.0, 1e9), st.sampled_from([1e-300, 5e-324, 1e-9])),
             min_size=1, max_size=50),
    log_uniform(1e-12, 1e12), log_uniform(1e-6, 1e6), log_uniform(1e-12, 1e12),
)
def test_scan_repulsion_is_finite_inside_the_ranges(
    ranges: list[float], k: float, d0: float, beta: float
) -> None:
    scan = LaserScan(ranges, angle_min=-1.0, angle_increment=2.0 / len(ranges), range_min=0.0,
                     range_max=1e9)
    assert np.all(np.isfinite(repulsive_force_from_scan(scan, k_rep=k, influence_radius=d0)))
    force = piecewise_repulsive_force_from_scan(scan, delta=k, beta=beta, spread=d0,
                                                obstacle_radius=d0)
    assert np.all(np.isfinite(force))


test_scan_repulsion_is_finite_inside_the_ranges_thoroughly = slow_twin(
    test_scan_repulsion_is_finite_inside_the_ranges, max_examples=100
)


@pytest.mark.parametrize(
    ("kwargs", "error"),
    [({"k_rep": 1e13}, ValueError), ({"influence_radius": 1e-7}, ValueError),
     ({"k_rep": True}, TypeError), ({"influence_radius": "1"}, TypeError),
     ({"k_rep": np.nan}, ValueError), ({"influence_radius": math.inf}, ValueError)],
)
def test_scan_repulsion_parameter_ranges(kwargs: dict[str, Any], error: type) -> None:
    scan = LaserScan([0.5, 1.0], angle_min=0.0, angle_increment=0.1, range_min=0.1,
                     range_max=5.0)
    with pytest.raises(error, match=next(iter(kwargs))):
        repulsive_force_from_scan(scan, **kwargs)
    translated = {"k_rep": "delta", "influence_radius": "spread"}
    piecewise = {translated[k]: v for k, v in kwargs.items()}
    with pytest.raises(error, match=next(iter(piecewise))):
        piecewise_repulsive_force_from_scan(scan, **piecewise)


# --- greedy step and its record ------------------------------------------------------


@pytest.mark.parametrize("flag", ["yes", None, 1, 0.0, np.array([True])])
def test_greedy_require_progress_must_be_a_bool(flag: Any) -> None:
    # Issue 12: require_progress="yes" was taken as True.
    with pytest.raises(TypeError, match="require_progress"):
        greedy_step(LocalGrid.from_points([]), (2.0, 0.0), require_progress=flag)


@pytest.mark.parametrize(
    ("goal", "error"),
    [((1e308, 0.0), ValueError), ((0.0, -1e10), ValueError), ((math.nan, 0.0), ValueError),
     ((1 + 1j, 0.0), TypeError), (("1", "2"), TypeError), ((True, False), TypeError)],
)
def test_greedy_goal_range(goal: Any, error: type) -> None:
    with pytest.raises(error, match="goal_robot_xy"):
        greedy_step(LocalGrid.from_points([]), goal)


def test_greedy_far_goal_inside_the_range() -> None:
    step = greedy_step(LocalGrid.from_points([]), (1e9, -1e9))
    assert math.isfinite(step.cost) and step.waypoint_robot_xy[0] > 0 > step.waypoint_robot_xy[1]


def test_greedy_step_records_copy_and_never_freeze() -> None:
    # Issue 12: records built from lists crashed, and froze the caller's array.
    waypoint = np.array([0.2, 0.0])
    step = GreedyStep([10, 12], waypoint, g=np.float32(0.25), h=1, candidates=np.int64(440))
    assert waypoint.flags.writeable and not np.shares_memory(waypoint, step.waypoint_robot_xy)
    waypoint[0] = 9.0
    assert step.waypoint_robot_xy.tolist() == [0.2, 0.0]
    assert step.cell == (10, 12) and type(step.cell[0]) is int
    assert (step.g, step.h, step.candidates) == (0.25, 1.0, 440)
    assert GreedyStep((1, 2), [0.1, 0.2], 0.0, 0.0, 0).waypoint_robot_xy.tolist() == [0.1, 0.2]
    with pytest.raises(ValueError):
        step.waypoint_robot_xy[0] = 1.0
    real = greedy_step(LocalGrid.from_points([]), (2.0, 0.0))
    assert not real.waypoint_robot_xy.flags.writeable


@pytest.mark.parametrize(
    ("kwargs", "error", "match"),
    [
        ({"cell": (True, 1)}, TypeError, "cell"),
        ({"cell": {0: 1, 1: 2}}, TypeError, "cell"),
        ({"cell": "ab"}, TypeError, "cell"),
        ({"cell": (1.5, 2)}, TypeError, "cell"),
        ({"cell": (1, 2, 3)}, TypeError, "cell"),
        ({"cell": (-1, 2)}, ValueError, "cell"),
        ({"waypoint_xy": [1 + 1j, 0.0]}, TypeError, "waypoint_xy"),
        ({"waypoint_xy": ["1", "2"]}, TypeError, "waypoint_xy"),
        ({"waypoint_xy": [0.0, math.inf]}, ValueError, "waypoint_xy"),
        ({"waypoint_xy": [0.0, 1.0, 2.0]}, ValueError, "waypoint_xy"),
        ({"g": "1"}, TypeError, "g"),
        ({"g": -1.0}, ValueError, "g"),
        ({"h": math.nan}, ValueError, "h"),
        ({"candidates": True}, TypeError, "candidates"),
        ({"candidates": -1}, ValueError, "candidates"),
        ({"candidates": 2.5}, TypeError, "candidates"),
    ],
)
def test_greedy_step_record_types(kwargs: dict[str, Any], error: type, match: str) -> None:
    fields: dict[str, Any] = {"cell": (1, 2), "waypoint_xy": (0.0, 0.0), "g": 0.0, "h": 0.0,
                              "candidates": 0}
    fields.update(kwargs)
    with pytest.raises(error, match=match):
        GreedyStep(**fields)


# --- sampled fields ------------------------------------------------------------------


def test_sampled_field_ranges() -> None:
    sampled = sample_field(ConicAttraction((0.0, 0.0)), xlim=(-1.0, 1.0), ylim=(0.0, 1.0),
                           resolution=0.5)
    with pytest.raises(ValueError, match="points_xy"):
        sampled.world_to_cell([1e308, 0.0])
    with pytest.raises(ValueError, match="points_xy"):
        sampled.contains([[0.0, -1e10]])
    with pytest.raises(TypeError, match="continuous"):
        sampled.world_to_cell([0.0, 0.0], continuous="no")  # type: ignore[call-overload]
    with pytest.raises(ValueError, match="cells"):
        sampled.cell_to_world([1e300, 0.0])
    assert sampled.world_to_cell([1e9, -1e9]).tolist() == [-2000000000, 2000000002]
    base = {"x": [0.5, 1.5], "y": [0.5], "potential": [[1.0, 2.0]],
            "force": np.zeros((1, 2, 2)), "resolution": 1.0}
    for change, match in [
        ({"potential": [[np.nan, 1.0]]}, "potential"),
        ({"force": np.full((1, 2, 2), np.inf)}, "force"),
        ({"x": [2e9, 2e9 + 1]}, "x"),
        ({"resolution": 1e-7, "x": [0.0, 1e-7], "y": [0.0]}, "resolution"),
        ({"resolution": 1e7, "x": [0.0, 1e7], "y": [0.0]}, "resolution"),
    ]:
        with pytest.raises(ValueError, match=match):
            SampledField(**{**base, **change})
    # +inf potential (a Khatib obstacle) stays allowed.
    SampledField(**{**base, "potential": [[np.inf, 1.0]]})
    with pytest.raises(ValueError, match="resolution"):
        sample_field(ConicAttraction((0.0, 0.0)), xlim=(0.0, 1.0), ylim=(0.0, 1.0),
                     resolution=1e300)
    with pytest.raises(ValueError, match="xlim"):
        sample_field(ConicAttraction((0.0, 0.0)), xlim=(0.0, 1e10), ylim=(0.0, 1.0),
                     resolution=1e6)
