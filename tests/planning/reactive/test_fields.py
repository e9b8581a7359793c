"""Potential fields: analytic forces against finite differences, limits and bad input."""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import assume, given, settings
from hypothesis import strategies as st

from navkit.planning import (
    BlendedAttraction,
    CompositeField,
    ConicAttraction,
    KhatibRepulsion,
    ParaboloidAttraction,
    PiecewiseAttraction,
    PiecewiseRepulsion,
    PotentialField,
    field_grid,
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


@settings(max_examples=150)
@given(point, point, gain, gain, length, length, st.floats(0.0, 3.0), st.floats(0.05, 1.0),
       gain, gain)
def test_blended_force_is_minus_gradient(
    p: tuple[float, float], goal: tuple[float, float], k: float, c: float, a: float, b: float,
    rad_thr: float, width: float, m: float, u: float,
) -> None:
    field = BlendedAttraction(goal, k_att=k, c=c, a=a, b=b, rad_thr=rad_thr, width=width, m=m,
                              u_trans=u)
    q = np.array(p)
    assume(far_from(q, field.goal, [0.0], 1e-2))
    assert_force_is_gradient(field, q)


@settings(max_examples=100)
@given(point, point, gain, gain, length, length)
def test_paraboloid_force_is_minus_gradient(
    p: tuple[float, float], goal: tuple[float, float], k: float, c: float, a: float, b: float
) -> None:
    assert_force_is_gradient(ParaboloidAttraction(goal, k_att=k, c=c, a=a, b=b), np.array(p))


@settings(max_examples=100)
@given(point, point, gain, gain, st.floats(0.0, 2.0))
def test_conic_force_is_minus_gradient(
    p: tuple[float, float], goal: tuple[float, float], m: float, u: float, rad_thr: float
) -> None:
    field = ConicAttraction(goal, m=m, u_trans=u, rad_thr=rad_thr)
    q = np.array(p)
    assume(far_from(q, field.goal, [0.0], 1e-2))
    assert_force_is_gradient(field, q)
    assert np.linalg.norm(field.force(q)[0]) == pytest.approx(m * u, rel=1e-12)


@settings(max_examples=100)
@given(point, point, gain, st.floats(0.0, 2.0), length)
def test_piecewise_attraction_force_is_minus_gradient(
    p: tuple[float, float], goal: tuple[float, float], alpha: float, r: float, s: float
) -> None:
    field = PiecewiseAttraction(goal, alpha=alpha, r=r, s=s)
    q = np.array(p)
    assume(far_from(q, field.goal, [0.0, r, r + s], 1e-3))
    assert_force_is_gradient(field, q)


obstacle_sets = st.lists(point, min_size=1, max_size=6)


@settings(max_examples=100)
@given(point, obstacle_sets, gain, length)
def test_khatib_force_is_minus_gradient(
    p: tuple[float, float], obstacles: list[tuple[float, float]], k: float, d0: float
) -> None:
    field = KhatibRepulsion(obstacles, k_rep=k, d0=d0)
    q = np.array(p)
    # Singular at the obstacles; at d0 the force is continuous but U'' jumps.
    assume(all(far_from(q, np.array(o), [0.0], 0.05 * d0) for o in obstacles))
    assume(all(far_from(q, np.array(o), [d0], 1e-3) for o in obstacles))
    assert_force_is_gradient(field, q)


@settings(max_examples=100)
@given(point, obstacle_sets, gain, gain, st.floats(0.0, 1.0), length)
def test_piecewise_repulsion_force_is_minus_gradient(
    p: tuple[float, float], obstacles: list[tuple[float, float]], delta: float, beta: float,
    r: float, s: float,
) -> None:
    field = PiecewiseRepulsion(obstacles, delta=delta, beta=beta, r=r, s=s)
    q = np.array(p)
    assume(all(far_from(q, np.array(o), [0.0, r, r + s], 1e-3) for o in obstacles))
    assert_force_is_gradient(field, q)


@settings(max_examples=50)
@given(point, point, obstacle_sets)
def test_composite_force_is_minus_gradient_and_sum(
    p: tuple[float, float], goal: tuple[float, float], obstacles: list[tuple[float, float]]
) -> None:
    parts: list[PotentialField] = [
        BlendedAttraction(goal, rad_thr=1.0, width=0.3),
        KhatibRepulsion(obstacles, k_rep=0.5, d0=1.5),
        PiecewiseRepulsion(obstacles, delta=2.0, beta=1.0, r=0.0, s=1.0),
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
        "rad_thr": st.floats(1.0, 4.0), "width": st.floats(0.01, 0.1),
    }
)


@settings(max_examples=100)
@given(blend_params, point, st.floats(0.0, 1.0), st.floats(-math.pi, math.pi))
def test_blended_tends_to_paraboloid_near_goal(
    params: dict[str, float], goal: tuple[float, float], frac: float, angle: float
) -> None:
    field = BlendedAttraction(goal, **params)
    # Inside rad_thr - 20ω, σ <= e^-40: the blend must equal the paraboloid.
    d = frac * (params["rad_thr"] - 20.0 * params["width"])
    assume(d > 0.0)
    q = np.array(goal) + d * np.array([math.cos(angle), math.sin(angle)])
    par = ParaboloidAttraction(goal, k_att=params["k_att"], c=params["c"], a=params["a"],
                               b=params["b"])
    assert field.sigma([d])[0] < 1e-17
    np.testing.assert_allclose(field.force(q), par.force(q), rtol=1e-9, atol=1e-9)
    np.testing.assert_allclose(field.potential(q), par.potential(q), rtol=1e-9, atol=1e-9)


@settings(max_examples=100)
@given(blend_params, point, st.floats(0.0, 50.0), st.floats(-math.pi, math.pi))
def test_blended_tends_to_constant_magnitude_cone_far_away(
    params: dict[str, float], goal: tuple[float, float], extra: float, angle: float
) -> None:
    field = BlendedAttraction(goal, **params)
    d = params["rad_thr"] + 20.0 * params["width"] + extra
    direction = np.array([math.cos(angle), math.sin(angle)])
    force = field.force(np.array(goal) + d * direction)[0]
    cone = -params["m"] * params["u_trans"] * direction
    np.testing.assert_allclose(force, cone, rtol=1e-9, atol=1e-9 * params["m"] * params["u_trans"])


def test_blending_width_moves_between_the_limits() -> None:
    # At rad_thr the blend is half way; a wide blend mixes in the paraboloid further out.
    goal = (0.0, 0.0)
    q = np.array([[1.5, 0.0]])
    par = ParaboloidAttraction(goal).force(q)[0, 0]
    cone = ConicAttraction(goal).force(q)[0, 0]
    sharp = BlendedAttraction(goal, rad_thr=1.0, width=0.01).force(q)[0, 0]
    wide = BlendedAttraction(goal, rad_thr=1.0, width=1.0).force(q)[0, 0]
    assert sharp == pytest.approx(cone, rel=1e-12)
    assert abs(wide - cone) > 0.1
    assert par < cone < 0.0
    assert BlendedAttraction(goal, rad_thr=1.0).sigma([1.0])[0] == 0.5


# --- repulsion ----------------------------------------------------------------------


@settings(max_examples=100)
@given(point, obstacle_sets, gain, length)
def test_khatib_is_exactly_zero_beyond_d0(
    p: tuple[float, float], obstacles: list[tuple[float, float]], k: float, d0: float
) -> None:
    q = np.array(p)
    dists = np.hypot(*(np.array(obstacles) - q).T)
    assume(bool(np.all(dists > d0)))
    field = KhatibRepulsion(obstacles, k_rep=k, d0=d0)
    assert field.potential(q)[0] == 0.0
    assert np.all(field.force(q) == 0.0)


@settings(max_examples=100)
@given(point, obstacle_sets, gain, gain, st.floats(0.0, 1.0), length)
def test_piecewise_repulsion_is_exactly_zero_beyond_reach(
    p: tuple[float, float], obstacles: list[tuple[float, float]], delta: float, beta: float,
    r: float, s: float,
) -> None:
    q = np.array(p)
    dists = np.hypot(*(np.array(obstacles) - q).T)
    assume(bool(np.all(dists > r + s)))
    field = PiecewiseRepulsion(obstacles, delta=delta, beta=beta, r=r, s=s)
    assert field.potential(q)[0] == 0.0
    assert np.all(field.force(q) == 0.0)


@settings(max_examples=50)
@given(point, gain, length, st.floats(-math.pi, math.pi))
def test_khatib_grows_without_bound_toward_obstacle(
    obstacle: tuple[float, float], k: float, d0: float, angle: float
) -> None:
    field = KhatibRepulsion([obstacle], k_rep=k, d0=d0)
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
    field = KhatibRepulsion([[1.0, 1.0], [3.0, 1.0]], k_rep=1.0, d0=5.0)
    assert field.potential([1.0, 1.0])[0] == math.inf
    # Only the other obstacle pushes: (1/2 - 1/5)/4 toward -x.
    np.testing.assert_allclose(field.force([1.0, 1.0]), [[-0.075, 0.0]], rtol=1e-12)


def test_piecewise_repulsion_pieces() -> None:
    field = PiecewiseRepulsion([[0.0, 0.0]], delta=3.0, beta=2.0, r=1.0, s=0.5)
    pts = np.array([[0.0, 0.5], [0.0, 1.25], [0.0, 1.5], [0.0, 2.0]])
    np.testing.assert_allclose(field.force(pts)[:, 1], [3.0, 0.5, 0.0, 0.0])
    np.testing.assert_allclose(field.potential(pts), [0.25 + 1.5, 0.0625, 0.0, 0.0])


def test_piecewise_attraction_is_continuous_at_the_outer_radius() -> None:
    # The paper's "α beyond s + r" would jump from α·s to α here; α·s is continuous.
    field = PiecewiseAttraction((0.0, 0.0), alpha=2.0, r=0.5, s=3.0)
    inner, outer = field.force([[3.5 - 1e-9, 0.0], [3.5 + 1e-9, 0.0]])[:, 0]
    assert inner == pytest.approx(-6.0) and outer == pytest.approx(-6.0)


# --- composition, immutability, bad input --------------------------------------------


def test_fields_are_immutable_and_copy_their_input() -> None:
    obstacles = np.array([[1.0, 0.0]])
    field = KhatibRepulsion(obstacles, d0=2.0)
    before = field.force([0.0, 0.0]).copy()
    obstacles[0, 0] = 100.0
    np.testing.assert_array_equal(field.force([0.0, 0.0]), before)
    with pytest.raises(AttributeError, match="immutable"):
        field.d0 = 3.0  # type: ignore[misc]
    with pytest.raises(ValueError, match="read-only"):
        field.obstacles[0, 0] = 5.0
    points = np.array([[0.5, 0.5]])
    field.force(points)
    np.testing.assert_array_equal(points, [[0.5, 0.5]])


def test_with_goal_keeps_parameters() -> None:
    field = BlendedAttraction((0.0, 0.0), k_att=2.0, width=0.5, m=3.0)
    moved = field.with_goal((1.0, 2.0))
    assert isinstance(moved, BlendedAttraction)
    assert (moved.k_att, moved.width, moved.m) == (2.0, 0.5, 3.0)
    np.testing.assert_array_equal(moved.goal, [1.0, 2.0])
    np.testing.assert_array_equal(field.goal, [0.0, 0.0])
    np.testing.assert_allclose(moved.force([[2.0, 3.0]]), field.force([[1.0, 1.0]]))
    assert "BlendedAttraction(goal=(1.0, 2.0)" in repr(moved)


@pytest.mark.parametrize("cls", [KhatibRepulsion, PiecewiseRepulsion])
def test_empty_obstacles_give_zero_field(cls: type[PotentialField]) -> None:
    field = cls(np.empty((0, 2)))
    pts = np.array([[0.0, 0.0], [1.0, 2.0]])
    np.testing.assert_array_equal(field.force(pts), np.zeros((2, 2)))
    np.testing.assert_array_equal(field.potential(pts), np.zeros(2))
    assert cls([]).obstacles.shape == (0, 2)


@pytest.mark.parametrize(
    ("build", "match"),
    [
        (lambda: BlendedAttraction((math.nan, 0.0)), "goal"),
        (lambda: ConicAttraction((0.0, math.inf)), "goal"),
        (lambda: ParaboloidAttraction((0.0, 0.0, 0.0)), "goal"),
        (lambda: BlendedAttraction((0.0, 0.0), width=0.0), "width"),
        (lambda: BlendedAttraction((0.0, 0.0), width=-1.0), "width"),
        (lambda: BlendedAttraction((0.0, 0.0), rad_thr=-1.0), "rad_thr"),
        (lambda: BlendedAttraction((0.0, 0.0), a=0.0), "a must"),
        (lambda: KhatibRepulsion([[0.0, 0.0]], d0=0.0), "d0"),
        (lambda: KhatibRepulsion([[0.0, 0.0]], d0=-2.0), "d0"),
        (lambda: KhatibRepulsion([[0.0, 0.0]], k_rep=math.nan), "k_rep"),
        (lambda: KhatibRepulsion([[0.0, 0.0, 0.0]]), "obstacles"),
        (lambda: KhatibRepulsion([[0.0, math.nan]]), "obstacles"),
        (lambda: PiecewiseRepulsion([[0.0, 0.0]], s=0.0), "s must"),
        (lambda: PiecewiseAttraction((0.0, 0.0), r=-0.1), "r must"),
        (lambda: ConicAttraction((0.0, 0.0)).force([[math.nan, 0.0]]), "points"),
        (lambda: ConicAttraction((0.0, 0.0)).potential(np.zeros((3, 3))), "points"),
        (lambda: field_grid(ConicAttraction((0.0, 0.0)), (1.0, 0.0), (0.0, 1.0), 0.1), "xlim"),
        (lambda: field_grid(ConicAttraction((0.0, 0.0)), (0.0, 1.0), (0.0, 1.0), 0.0),
         "resolution"),
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
    with pytest.raises(TypeError, match="field"):
        field_grid("not a field", (0.0, 1.0), (0.0, 1.0), 0.1)  # type: ignore[arg-type]
    with pytest.raises(TypeError, match=r"fields\[1\]"):
        CompositeField(ConicAttraction((0.0, 0.0)), "x")  # type: ignore[arg-type]


# --- field_grid ---------------------------------------------------------------------


def test_field_grid_paper_sized_map() -> None:
    grid = field_grid(ParaboloidAttraction((6.0, 6.0)), (0.0, 12.0), (0.0, 12.0), 0.01)
    assert grid.potential.shape == (1200, 1200)
    assert grid.force.shape == (1200, 1200, 2)
    assert grid.x[0] == pytest.approx(0.005) and grid.x[-1] == pytest.approx(11.995)
    row, col = 123, 987
    expected = ParaboloidAttraction((6.0, 6.0)).potential([grid.x[col], grid.y[row]])[0]
    assert grid.potential[row, col] == pytest.approx(expected, rel=1e-12)


def test_field_grid_matches_pointwise_evaluation_in_blocks() -> None:
    rng = np.random.default_rng(7)
    obstacles = rng.uniform(-3.0, 3.0, size=(3000, 2))
    field = BlendedAttraction((2.0, -1.0)) + KhatibRepulsion(obstacles, d0=0.4)
    grid = field_grid(field, (-3.0, 3.0), (-2.0, 2.5), 0.05)  # 90 x 120 = 10800 points
    assert grid.potential.shape == (90, 120)
    rows = rng.integers(0, 90, 30)
    cols = rng.integers(0, 120, 30)
    pts = np.stack((grid.x[cols], grid.y[rows]), axis=1)
    np.testing.assert_allclose(grid.potential[rows, cols], field.potential(pts), rtol=1e-12)
    np.testing.assert_allclose(grid.force[rows, cols], field.force(pts), rtol=1e-12, atol=1e-12)


def test_khatib_overflow_is_infinite_not_nan() -> None:
    field = KhatibRepulsion([[0.0, 0.0]], d0=1.0)
    force = field.force([[0.0, 1e-200], [-1e-200, 0.0]])
    np.testing.assert_array_equal(force, [[0.0, math.inf], [-math.inf, 0.0]])
    assert field.potential([[0.0, 1e-200]])[0] == math.inf


def test_default_blend_pulls_toward_the_goal_beyond_its_displaced_minimum() -> None:
    field = BlendedAttraction((1.0, -2.0))
    d = np.concatenate((np.linspace(0.004, 2.0, 5000), np.linspace(2.0, 50.0, 500)))
    for angle in np.linspace(-math.pi, math.pi, 9):
        u = np.array([math.cos(angle), math.sin(angle)])
        radial = field.force(field.goal + d[:, None] * u) @ u
        assert np.all(radial < 0.0)
    # ... and slightly outward inside it: the minimum is 3.75 mm from the goal.
    assert field.force([[1.003, -2.0]])[0, 0] > 0.0


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
