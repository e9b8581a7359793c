"""Potential fields: analytic forces against finite differences, limits and bad input."""

from __future__ import annotations

import dataclasses
import math
from collections.abc import Callable

import numpy as np
import pytest
from hypothesis import assume, given, settings
from hypothesis import strategies as st

from hypothesis_twins import slow_twin
from navkit.planning import (
    BlendedAttraction,
    CompositeField,
    ConicAttraction,
    KhatibRepulsion,
    ParaboloidAttraction,
    PiecewiseAttraction,
    PiecewiseRepulsion,
    PotentialField,
)

coord = st.floats(-5.0, 5.0, allow_nan=False)
point = st.tuples(coord, coord)
gain = st.floats(0.1, 10.0)
length = st.floats(0.2, 3.0)


def fd_force(field: PotentialField, p: np.ndarray, h: float = 1e-6) -> np.ndarray:
    """-∇U by central differences at one point."""
    out = np.empty(2)
    for k in range(2):
        e = np.zeros(2)
        e[k] = h
        u = field.potential(np.stack((p + e, p - e)))
        out[k] = -(u[0] - u[1]) / (2.0 * h)
    return out


def assert_force_is_gradient(field: PotentialField, p: np.ndarray) -> None:
    analytic = field.force(p)[0]
    numeric = fd_force(field, p)
    scale = max(np.linalg.norm(analytic), 1e-3)
    assert np.linalg.norm(analytic - numeric) <= 1e-5 * scale, (analytic, numeric)


def far_from(p: np.ndarray, centre: np.ndarray, radii: list[float], margin: float) -> bool:
    d = float(np.hypot(*(p - centre)))
    return all(abs(d - r) > margin for r in radii)


# --- force = -∇U --------------------------------------------------------------------


@settings(max_examples=50)
@given(point, point, gain, gain, length, length, st.floats(0.0, 3.0), st.floats(0.05, 1.0),
       gain, gain)
def test_blended_force_is_minus_gradient(
    p: tuple[float, float], goal: tuple[float, float], k: float, c: float, a: float, b: float,
    threshold_radius: float, width: float, m: float, u: float,
) -> None:
    field = BlendedAttraction(goal, k_att=k, c=c, a=a, b=b, threshold_radius=threshold_radius,
                              width=width, m=m, u_trans=u)
    q = np.array(p)
    assume(far_from(q, field.goal_xy, [0.0], 1e-2))
    assert_force_is_gradient(field, q)


test_blended_force_is_minus_gradient_thoroughly = slow_twin(
    test_blended_force_is_minus_gradient, max_examples=150
)


@settings(max_examples=40)
@given(point, point, gain, gain, length, length)
def test_paraboloid_force_is_minus_gradient(
    p: tuple[float, float], goal: tuple[float, float], k: float, c: float, a: float, b: float
) -> None:
    assert_force_is_gradient(ParaboloidAttraction(goal, k_att=k, c=c, a=a, b=b), np.array(p))


test_paraboloid_force_is_minus_gradient_thoroughly = slow_twin(
    test_paraboloid_force_is_minus_gradient, max_examples=100
)


@settings(max_examples=40)
@given(point, point, gain, gain, st.floats(0.0, 2.0))
def test_conic_force_is_minus_gradient(
    p: tuple[float, float], goal: tuple[float, float], m: float, u: float,
    threshold_radius: float,
) -> None:
    field = ConicAttraction(goal, m=m, u_trans=u, threshold_radius=threshold_radius)
    q = np.array(p)
    assume(far_from(q, field.goal_xy, [0.0], 1e-2))
    assert_force_is_gradient(field, q)
    assert np.linalg.norm(field.force(q)[0]) == pytest.approx(m * u, rel=1e-12)


test_conic_force_is_minus_gradient_thoroughly = slow_twin(
    test_conic_force_is_minus_gradient, max_examples=100
)


@settings(max_examples=40)
@given(point, point, gain, st.floats(0.0, 2.0), length)
def test_piecewise_attraction_force_is_minus_gradient(
    p: tuple[float, float], goal: tuple[float, float], alpha: float, r: float, s: float
) -> None:
    field = PiecewiseAttraction(goal, alpha=alpha, goal_radius=r, spread=s)
    q = np.array(p)
    assume(far_from(q, field.goal_xy, [0.0, r, r + s], 1e-3))
    assert_force_is_gradient(field, q)


test_piecewise_attraction_force_is_minus_gradient_thoroughly = slow_twin(
    test_piecewise_attraction_force_is_minus_gradient, max_examples=100
)


obstacle_sets = st.lists(point, min_size=1, max_size=6)


@settings(max_examples=40)
@given(point, obstacle_sets, gain, length)
def test_khatib_force_is_minus_gradient(
    p: tuple[float, float], obstacles: list[tuple[float, float]], k: float, d0: float
) -> None:
    field = KhatibRepulsion(obstacles, k_rep=k, influence_radius=d0)
    q = np.array(p)
    # Singular at the obstacles; at d0 the force is continuous but U'' jumps.
    assume(all(far_from(q, np.array(o), [0.0], 0.05 * d0) for o in obstacles))
    assume(all(far_from(q, np.array(o), [d0], 1e-3) for o in obstacles))
    assert_force_is_gradient(field, q)


test_khatib_force_is_minus_gradient_thoroughly = slow_twin(
    test_khatib_force_is_minus_gradient, max_examples=100
)


@settings(max_examples=40)
@given(point, obstacle_sets, gain, gain, st.floats(0.0, 1.0), length)
def test_piecewise_repulsion_force_is_minus_gradient(
    p: tuple[float, float], obstacles: list[tuple[float, float]], delta: float, beta: float,
    r: float, s: float,
) -> None:
    field = PiecewiseRepulsion(obstacles, delta=delta, beta=beta, obstacle_radius=r, spread=s)
    q = np.array(p)
    assume(all(far_from(q, np.array(o), [0.0, r, r + s], 1e-3) for o in obstacles))
    assert_force_is_gradient(field, q)


test_piecewise_repulsion_force_is_minus_gradient_thoroughly = slow_twin(
    test_piecewise_repulsion_force_is_minus_gradient, max_examples=100
)


@settings(max_examples=50)
@given(point, point, obstacle_sets)
def test_composite_force_is_minus_gradient_and_sum(
    p: tuple[float, float], goal: tuple[float, float], obstacles: list[tuple[float, float]]
) -> None:
    parts: list[PotentialField] = [
        BlendedAttraction(goal, threshold_radius=1.0, width=0.3),
        KhatibRepulsion(obstacles, k_rep=0.5, influence_radius=1.5),
        PiecewiseRepulsion(obstacles, delta=2.0, beta=1.0, obstacle_radius=0.0, spread=1.0),
    ]
    total = parts[0] + parts[1] + parts[2]
    q = np.array(p)
    assume(far_from(q, np.array(goal), [0.0], 1e-2))
    assume(all(far_from(q, np.array(o), [0.0, 1.0, 1.5], 0.05) for o in obstacles))
    assert isinstance(total, CompositeField)
    assert len(total.fields) == 3
    np.testing.assert_allclose(
        total.force(q), sum(f.force(q) for f in parts), rtol=1e-12, atol=1e-12
    )
    np.testing.assert_allclose(total.potential(q), sum(parts).potential(q), rtol=1e-12)
    assert_force_is_gradient(total, q)


# --- limits of the blended attraction -----------------------------------------------


blend_params = st.fixed_dictionaries(
    {
        "k_att": gain, "c": gain, "a": length, "b": length, "m": gain, "u_trans": gain,
        "threshold_radius": st.floats(1.0, 4.0), "width": st.floats(0.01, 0.1),
    }
)


@settings(max_examples=40)
@given(blend_params, point, st.floats(0.0, 1.0), st.floats(-math.pi, math.pi))
def test_blended_tends_to_paraboloid_near_goal(
    params: dict[str, float], goal: tuple[float, float], frac: float, angle: float
) -> None:
    field = BlendedAttraction(goal, **params)
    # Inside threshold_radius - 20ω, σ <= e^-40: the blend must equal the paraboloid.
    d = frac * (params["threshold_radius"] - 20.0 * params["width"])
    assume(d > 0.0)
    q = np.array(goal) + d * np.array([math.cos(angle), math.sin(angle)])
    par = ParaboloidAttraction(goal, k_att=params["k_att"], c=params["c"], a=params["a"],
                               b=params["b"])
    assert field.sigma([d])[0] < 1e-17
    np.testing.assert_allclose(field.force(q), par.force(q), rtol=1e-9, atol=1e-9)
    np.testing.assert_allclose(field.potential(q), par.potential(q), rtol=1e-9, atol=1e-9)


test_blended_tends_to_paraboloid_near_goal_thoroughly = slow_twin(
    test_blended_tends_to_paraboloid_near_goal, max_examples=100
)


@settings(max_examples=40)
@given(blend_params, point, st.floats(0.0, 50.0), st.floats(-math.pi, math.pi))
def test_blended_tends_to_constant_magnitude_cone_far_away(
    params: dict[str, float], goal: tuple[float, float], extra: float, angle: float
) -> None:
    field = BlendedAttraction(goal, **params)
    d = params["threshold_radius"] + 20.0 * params["width"] + extra
    direction = np.array([math.cos(angle), math.sin(angle)])
    force = field.force(np.array(goal) + d * direction)[0]
    cone = -params["m"] * params["u_trans"] * direction
    np.testing.assert_allclose(force, cone, rtol=1e-9, atol=1e-9 * params["m"] * params["u_trans"])


test_blended_tends_to_constant_magnitude_cone_far_away_thoroughly = slow_twin(
    test_blended_tends_to_constant_magnitude_cone_far_away, max_examples=100
)


def test_blending_width_moves_between_the_limits() -> None:
    # At threshold_radius the blend is half way; a wide blend mixes in the paraboloid further out.
    goal = (0.0, 0.0)
    q = np.array([[1.5, 0.0]])
    par = ParaboloidAttraction(goal).force(q)[0, 0]
    cone = ConicAttraction(goal).force(q)[0, 0]
    sharp = BlendedAttraction(goal, threshold_radius=1.0, width=0.01).force(q)[0, 0]
    wide = BlendedAttraction(goal, threshold_radius=1.0, width=1.0).force(q)[0, 0]
    assert sharp == pytest.approx(cone, rel=1e-12)
    assert abs(wide - cone) > 0.1
    assert par < cone < 0.0
    assert BlendedAttraction(goal, threshold_radius=1.0).sigma([1.0])[0] == 0.5


# --- repulsion ----------------------------------------------------------------------


@settings(max_examples=40)
@given(point, obstacle_sets, gain, length)
def test_khatib_is_exactly_zero_beyond_the_influence_radius(
    p: tuple[float, float], obstacles: list[tuple[float, float]], k: float, d0: float
) -> None:
    q = np.array(p)
    dists = np.hypot(*(np.array(obstacles) - q).T)
    assume(bool(np.all(dists > d0)))
    field = KhatibRepulsion(obstacles, k_rep=k, influence_radius=d0)
    assert field.potential(q)[0] == 0.0
    assert np.all(field.force(q) == 0.0)


test_khatib_is_exactly_zero_beyond_the_influence_radius_thoroughly = slow_twin(
    test_khatib_is_exactly_zero_beyond_the_influence_radius, max_examples=100
)


@settings(max_examples=40)
@given(point, obstacle_sets, gain, gain, st.floats(0.0, 1.0), length)
def test_piecewise_repulsion_is_exactly_zero_beyond_reach(
    p: tuple[float, float], obstacles: list[tuple[float, float]], delta: float, beta: float,
    r: float, s: float,
) -> None:
    q = np.array(p)
    dists = np.hypot(*(np.array(obstacles) - q).T)
    assume(bool(np.all(dists > r + s)))
    field = PiecewiseRepulsion(obstacles, delta=delta, beta=beta, obstacle_radius=r, spread=s)
    assert field.potential(q)[0] == 0.0
    assert np.all(field.force(q) == 0.0)


test_piecewise_repulsion_is_exactly_zero_beyond_reach_thoroughly = slow_twin(
    test_piecewise_repulsion_is_exactly_zero_beyond_reach, max_examples=100
)


@settings(max_examples=50)
@given(point, gain, length, st.floats(-math.pi, math.pi))
def test_khatib_grows_without_bound_toward_obstacle(
    obstacle: tuple[float, float], k: float, d0: float, angle: float
) -> None:
    field = KhatibRepulsion([obstacle], k_rep=k, influence_radius=d0)
    direction = np.array([math.cos(angle), math.sin(angle)])
    dists = d0 * np.logspace(-0.01, -6, 40)
    pts = np.array(obstacle) + dists[:, None] * direction
    force = field.force(pts)
    mag = np.linalg.norm(force, axis=1)
    assert np.all(np.diff(mag) > 0.0)
    assert np.all(np.diff(field.potential(pts)) > 0.0)
    assert mag[-1] > 1e15 * k / d0**2
    # Pushed straight away from the obstacle.
    np.testing.assert_allclose(force / mag[:, None], np.broadcast_to(direction, force.shape),
                               atol=1e-6)


def test_khatib_on_the_obstacle_is_infinite_potential_and_zero_force() -> None:
    field = KhatibRepulsion([[1.0, 1.0], [3.0, 1.0]], k_rep=1.0, influence_radius=5.0)
    assert field.potential([1.0, 1.0])[0] == math.inf
    # Only the other obstacle pushes: (1/2 - 1/5)/4 toward -x.
    np.testing.assert_allclose(field.force([1.0, 1.0]), [[-0.075, 0.0]], rtol=1e-12)


def test_piecewise_repulsion_pieces() -> None:
    field = PiecewiseRepulsion([[0.0, 0.0]], delta=3.0, beta=2.0, obstacle_radius=1.0, spread=0.5)
    pts = np.array([[0.0, 0.5], [0.0, 1.25], [0.0, 1.5], [0.0, 2.0]])
    np.testing.assert_allclose(field.force(pts)[:, 1], [3.0, 0.5, 0.0, 0.0])
    np.testing.assert_allclose(field.potential(pts), [0.25 + 1.5, 0.0625, 0.0, 0.0])


def test_piecewise_attraction_is_continuous_at_the_outer_radius() -> None:
    # The paper's "α beyond s + r" would jump from α·s to α here; α·s is continuous.
    field = PiecewiseAttraction((0.0, 0.0), alpha=2.0, goal_radius=0.5, spread=3.0)
    inner, outer = field.force([[3.5 - 1e-9, 0.0], [3.5 + 1e-9, 0.0]])[:, 0]
    assert inner == pytest.approx(-6.0) and outer == pytest.approx(-6.0)


# --- composition, immutability, bad input --------------------------------------------


ALL_FIELDS = [
    lambda: ParaboloidAttraction((1.0, 2.0), k_att=2.0),
    lambda: ConicAttraction((1.0, 2.0), threshold_radius=0.5),
    lambda: BlendedAttraction((1.0, 2.0), width=0.3),
    lambda: PiecewiseAttraction((1.0, 2.0), goal_radius=0.2, spread=2.0),
    lambda: KhatibRepulsion([[1.0, 0.0], [0.0, 1.0]], influence_radius=2.0),
    lambda: PiecewiseRepulsion([[1.0, 0.0]], obstacle_radius=0.1, spread=2.0),
    lambda: ConicAttraction((3.0, 0.0)) + KhatibRepulsion([[1.0, 0.0]]),
]


@pytest.mark.parametrize("build", ALL_FIELDS)
def test_fields_are_frozen(build: object) -> None:
    field = build()  # type: ignore[operator]
    for f in dataclasses.fields(field):
        with pytest.raises(dataclasses.FrozenInstanceError):
            setattr(field, f.name, getattr(field, f.name))
    assert not hasattr(field, "__dict__")  # slotted


def test_fields_are_immutable_and_copy_their_input() -> None:
    obstacles = np.array([[1.0, 0.0]])
    field = KhatibRepulsion(obstacles, influence_radius=2.0)
    before = field.force([0.0, 0.0]).copy()
    obstacles[0, 0] = 100.0
    np.testing.assert_array_equal(field.force([0.0, 0.0]), before)
    assert obstacles.flags.writeable  # the caller's array is not frozen
    with pytest.raises(dataclasses.FrozenInstanceError):
        field.influence_radius = 3.0  # type: ignore[misc]
    with pytest.raises(ValueError, match="read-only"):
        field.obstacles_xy[0, 0] = 5.0
    goal = np.array([1.0, 2.0])
    attraction = ConicAttraction(goal)
    goal[0] = 7.0
    np.testing.assert_array_equal(attraction.goal_xy, [1.0, 2.0])
    assert goal.flags.writeable
    with pytest.raises(ValueError, match="read-only"):
        attraction.goal_xy[0] = 5.0
    points = np.array([[0.5, 0.5]])
    field.force(points)
    attraction.potential(points)
    attraction.with_goal(points[0])
    np.testing.assert_array_equal(points, [[0.5, 0.5]])
    assert points.flags.writeable


@pytest.mark.parametrize("build", ALL_FIELDS)
def test_copied_and_unpickled_fields_stay_read_only(
    build: object, duplicate: Callable[[PotentialField], PotentialField]
) -> None:
    # pickle and deepcopy rebuild a frozen record without __post_init__: its arrays
    # came back writable, and a Khatib field's cached k-d tree then went stale.
    field = build()  # type: ignore[operator]
    copy = duplicate(field)
    assert type(copy) is type(field)
    points = np.array([[0.3, 0.4], [1.5, 1.0], [-2.0, 0.5]])
    np.testing.assert_array_equal(copy.force(points), field.force(points))
    np.testing.assert_array_equal(copy.potential(points), field.potential(points))
    for part in copy._parts():
        for f in dataclasses.fields(part):  # type: ignore[arg-type]
            value = getattr(part, f.name)
            if isinstance(value, np.ndarray):
                assert not value.flags.writeable, f.name


def test_kdtree_cache_is_not_an_argument_nor_in_the_repr() -> None:
    field = KhatibRepulsion(np.zeros((800, 2)), influence_radius=0.5)
    names = {f.name: f for f in dataclasses.fields(field)}
    assert not names["_kdtree"].init and not names["_kdtree"].repr
    with pytest.raises(TypeError):
        KhatibRepulsion([[0.0, 0.0]], _kdtree=None)  # type: ignore[call-arg]
    field.force(np.ones((400, 2)))  # 320,000 pairs: the k-d tree path builds the cache
    assert field._kdtree is not None
    assert repr(field) == (
        "KhatibRepulsion(obstacles_xy=<array shape=(800, 2)>, k_rep=1.0, influence_radius=0.5)"
    )


@pytest.mark.parametrize(
    "build",
    [
        lambda: ParaboloidAttraction((0.0, 0.0), 2.0),
        lambda: ConicAttraction((0.0, 0.0), 1.0, 1.0),
        lambda: BlendedAttraction((0.0, 0.0), 1.0),
        lambda: PiecewiseAttraction((0.0, 0.0), 1.0, 0.0, 1.0),
        lambda: KhatibRepulsion([[0.0, 0.0]], 1.0, 1.0),
        lambda: PiecewiseRepulsion([[0.0, 0.0]], 1.0, 1.0, 0.0, 1.0),
    ],
)
def test_parameters_are_keyword_only(build: object) -> None:
    with pytest.raises(TypeError, match="positional"):
        build()  # type: ignore[operator]


def test_fields_take_goal_and_obstacles_by_keyword_too() -> None:
    assert ConicAttraction(goal_xy=(1.0, 2.0)).goal_xy.tolist() == [1.0, 2.0]
    assert KhatibRepulsion(obstacles_xy=[[1.0, 2.0]]).obstacles_xy.shape == (1, 2)


def test_with_goal_keeps_parameters() -> None:
    field = BlendedAttraction((0.0, 0.0), k_att=2.0, width=0.5, m=3.0)
    moved = field.with_goal((1.0, 2.0))
    assert isinstance(moved, BlendedAttraction)
    assert (moved.k_att, moved.width, moved.m) == (2.0, 0.5, 3.0)
    np.testing.assert_array_equal(moved.goal_xy, [1.0, 2.0])
    np.testing.assert_array_equal(field.goal_xy, [0.0, 0.0])
    np.testing.assert_allclose(moved.force([[2.0, 3.0]]), field.force([[1.0, 1.0]]))
    assert "BlendedAttraction(goal_xy=(1.0, 2.0), k_att=2.0" in repr(moved)
    assert not moved.goal_xy.flags.writeable
    with pytest.raises(ValueError, match="goal_xy"):
        field.with_goal((math.nan, 0.0))


def test_sum_and_composition() -> None:
    a = ConicAttraction((1.0, 0.0))
    b = KhatibRepulsion([[0.5, 0.5]], influence_radius=1.0)
    c = PiecewiseRepulsion([[0.0, -0.5]])
    nested = (a + b) + (c + a)
    assert isinstance(nested, CompositeField)
    assert nested.fields == (a, b, c, a)  # flattened
    assert sum([a]) is a
    total = sum([a, b, c])
    assert isinstance(total, CompositeField) and total.fields == (a, b, c)
    assert CompositeField(f for f in (a, b)).fields == (a, b)  # any iterable
    q = np.array([[0.2, 0.1], [-1.0, 2.0]])
    np.testing.assert_allclose(
        total.force(q), a.force(q) + b.force(q) + c.force(q), rtol=1e-12, atol=1e-12
    )
    np.testing.assert_array_equal(CompositeField(()).force(q), np.zeros((2, 2)))


@pytest.mark.parametrize("cls", [KhatibRepulsion, PiecewiseRepulsion])
def test_empty_obstacles_give_zero_field(cls: type[PotentialField]) -> None:
    field = cls(np.empty((0, 2)))  # type: ignore[call-arg]
    pts = np.array([[0.0, 0.0], [1.0, 2.0]])
    np.testing.assert_array_equal(field.force(pts), np.zeros((2, 2)))
    np.testing.assert_array_equal(field.potential(pts), np.zeros(2))
    assert cls([]).obstacles_xy.shape == (0, 2)  # type: ignore[call-arg, attr-defined]


@pytest.mark.parametrize(
    ("build", "match"),
    [
        (lambda: BlendedAttraction((math.nan, 0.0)), "goal_xy"),
        (lambda: ConicAttraction((0.0, math.inf)), "goal_xy"),
        (lambda: ParaboloidAttraction((0.0, 0.0, 0.0)), "goal_xy"),
        (lambda: BlendedAttraction((0.0, 0.0), width=0.0), "width"),
        (lambda: BlendedAttraction((0.0, 0.0), width=-1.0), "width"),
        (lambda: BlendedAttraction((0.0, 0.0), threshold_radius=-1.0), "threshold_radius"),
        (lambda: ConicAttraction((0.0, 0.0), threshold_radius=-1.0), "threshold_radius"),
        (lambda: BlendedAttraction((0.0, 0.0), a=0.0), "a must"),
        (lambda: KhatibRepulsion([[0.0, 0.0]], influence_radius=0.0), "influence_radius"),
        (lambda: KhatibRepulsion([[0.0, 0.0]], influence_radius=-2.0), "influence_radius"),
        (lambda: KhatibRepulsion([[0.0, 0.0]], k_rep=math.nan), "k_rep"),
        (lambda: KhatibRepulsion([[0.0, 0.0, 0.0]]), "obstacles_xy"),
        (lambda: KhatibRepulsion([[0.0, math.nan]]), "obstacles_xy"),
        (lambda: PiecewiseRepulsion([[0.0, 0.0]], spread=0.0), "spread"),
        (lambda: PiecewiseRepulsion([[0.0, 0.0]], obstacle_radius=-0.1), "obstacle_radius"),
        (lambda: PiecewiseAttraction((0.0, 0.0), goal_radius=-0.1), "goal_radius"),
        (lambda: PiecewiseAttraction((0.0, 0.0), spread=0.0), "spread"),
        (lambda: ConicAttraction((0.0, 0.0)).force([[math.nan, 0.0]]), "points_xy"),
        (lambda: ConicAttraction((0.0, 0.0)).potential(np.zeros((3, 3))), "points_xy"),
    ],
)
def test_bad_input_raises_naming_the_argument(build: object, match: str) -> None:
    with pytest.raises(ValueError, match=match):
        build()  # type: ignore[operator]


def test_type_errors() -> None:
    with pytest.raises(TypeError, match="k_att"):
        BlendedAttraction((0.0, 0.0), k_att="1")  # type: ignore[arg-type]
    with pytest.raises(TypeError):
        ConicAttraction((0.0, 0.0)) + 1.0  # type: ignore[operator]
    with pytest.raises(TypeError, match=r"fields\[1\]"):
        CompositeField([ConicAttraction((0.0, 0.0)), "x"])  # type: ignore[list-item]
    with pytest.raises(TypeError, match="fields must be an iterable"):
        CompositeField(ConicAttraction((0.0, 0.0)))  # type: ignore[arg-type]
    with pytest.raises(TypeError, match="abstract"):
        PotentialField()  # type: ignore[abstract]


def test_khatib_saturates_below_a_nanometre_instead_of_overflowing() -> None:
    # Issue 12: the push used to overflow to inf below ~1e-103 m, and two obstacles
    # at ±1e-200 gave inf - inf = NaN. Below 1e-9 m it now takes its value at 1e-9 m.
    field = KhatibRepulsion([[0.0, 0.0]], influence_radius=1.0)
    force = field.force([[0.0, 1e-200], [-1e-200, 0.0], [0.0, 1e-9], [5e-324, 0.0]])
    top = (1.0 / 1e-9 - 1.0) / (1e-9 * 1e-9)  # Khatib's law at 1e-9 m, k_rep = d0 = 1
    np.testing.assert_array_equal(force, [[0.0, top], [-top, 0.0], [0.0, top], [top, 0.0]])
    u = field.potential([[0.0, 1e-200], [0.0, 1e-9], [0.0, 0.0]])
    assert u[0] == u[1] == 0.5 * (1.0 / 1e-9 - 1.0) ** 2
    assert u[2] == math.inf  # on the obstacle itself, as documented
    # Monotone up to the saturation: nearer never pushes less.
    d = np.logspace(-12, 0, 200)
    mag = np.abs(field.force(np.column_stack((d, np.zeros_like(d))))[:, 0])
    assert np.all(np.diff(mag) <= 0.0) and np.all(np.isfinite(mag))


@pytest.mark.parametrize(
    "obstacles", [[[1e-200, 0.0], [-1e-200, 0.0]], [[0.0, 5e-324], [0.0, -5e-324]]]
)
def test_opposite_obstacles_next_to_the_point_cancel(obstacles: list[list[float]]) -> None:
    # Issue 12 reproduction: KhatibRepulsion([[1e-200, 0], [-1e-200, 0]]).force([[0, 0]]) was NaN.
    field = KhatibRepulsion(obstacles)
    np.testing.assert_array_equal(field.force([[0.0, 0.0]]), [[0.0, 0.0]])
    assert math.isfinite(field.potential([[0.0, 0.0]])[0])


def test_default_blend_pulls_toward_the_goal_beyond_its_displaced_minimum() -> None:
    field = BlendedAttraction((1.0, -2.0))
    d = np.concatenate((np.linspace(0.004, 2.0, 5000), np.linspace(2.0, 50.0, 500)))
    for angle in np.linspace(-math.pi, math.pi, 9):
        u = np.array([math.cos(angle), math.sin(angle)])
        radial = field.force(field.goal_xy + d[:, None] * u) @ u
        assert np.all(radial < 0.0)
    # ... and slightly outward inside it: the minimum is 3.75 mm from the goal.
    assert field.force([[1.003, -2.0]])[0, 0] > 0.0


@pytest.mark.parametrize(("width", "minimum"), [(0.3, 0.046), (0.38, 0.055), (0.5, 0.046)])
def test_wide_blends_displace_the_minimum_as_documented(width: float, minimum: float) -> None:
    # BlendedAttraction's Notes: with rad_thr = 0.5, widths of 0.3 and 0.5 put the minimum
    # 4.6 cm from the goal and widths between them up to 5.5 cm.
    field = BlendedAttraction((0.0, 0.0), threshold_radius=0.5, width=width)
    d = np.linspace(1e-5, 0.2, 20000)
    radial = field.force(np.stack((d, np.zeros_like(d)), axis=1))[:, 0]
    outward = d[radial > 0.0]
    assert np.all(np.diff(outward) < 2e-5)  # one interval from the goal to the minimum
    assert outward.max() == pytest.approx(minimum, abs=5e-4)


@pytest.mark.parametrize("cls", [KhatibRepulsion, PiecewiseRepulsion])
def test_large_problems_match_small_ones(cls: type[PotentialField]) -> None:
    # More than 2**18 pairs go through k-d trees; one point at a time never does.
    rng = np.random.default_rng(3)
    obstacles = rng.uniform(-2.0, 2.0, (700, 2))
    pts = np.concatenate((rng.uniform(-2.0, 2.0, (600, 2)), obstacles[:5]))
    field = cls(obstacles)
    big_u, big_f = field.potential(pts), field.force(pts)
    for k in range(0, pts.shape[0], 50):
        np.testing.assert_allclose(big_u[k], field.potential(pts[k])[0], rtol=1e-12)
        np.testing.assert_allclose(big_f[k], field.force(pts[k])[0], rtol=1e-12, atol=1e-12)
    if cls is KhatibRepulsion:
        assert np.all(np.isinf(big_u[-5:]))
        assert np.all(np.isfinite(big_f))
