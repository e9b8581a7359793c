"""OmniDrive kinematics."""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import assume, given, settings
from hypothesis import strategies as st

from hypothesis_twins import slow_twin
from navkit.geometry import Twist2D
from navkit.kinematics import OmniDrive

speeds = st.floats(-3, 3, allow_nan=False)
twists = st.builds(Twist2D, speeds, speeds, speeds)


@st.composite
def layouts(draw: st.DrawFn) -> OmniDrive:
    n = draw(st.integers(3, 6))
    angles = draw(st.lists(st.floats(0, 2 * math.pi), min_size=n, max_size=n))
    r = draw(st.floats(0.01, 0.2))
    big_l = draw(st.floats(0.05, 1.0))
    jac = np.column_stack((-np.sin(angles), np.cos(angles), np.full(n, big_l))) / r
    assume(np.linalg.cond(jac) < 1e6)
    return OmniDrive(angles, wheel_radius=r, base_radius=big_l)


@settings(max_examples=40)
@given(layouts(), twists)
def test_forward_inverse_identity(drive: OmniDrive, t: Twist2D) -> None:
    back = drive.forward(drive.inverse(t))
    np.testing.assert_allclose(back.as_array(), t.as_array(), atol=1e-7)


test_forward_inverse_identity_thoroughly = slow_twin(
    test_forward_inverse_identity, max_examples=100
)


@settings(max_examples=40)
@given(layouts(), st.lists(st.tuples(speeds, speeds, speeds), min_size=1, max_size=6))
def test_batch_matches_single(drive: OmniDrive, rows: list[tuple[float, float, float]]) -> None:
    tw = np.array(rows)
    wheels = drive.inverse_batch(tw)
    assert wheels.shape == (len(rows), drive.n_wheels)
    for row, w in zip(rows, wheels, strict=True):
        np.testing.assert_allclose(w, drive.inverse(Twist2D(*row)), atol=1e-12)
    np.testing.assert_allclose(drive.forward_batch(wheels), tw, atol=1e-7)


test_batch_matches_single_thoroughly = slow_twin(test_batch_matches_single, max_examples=100)


def test_three_wheel_known_values() -> None:
    r, big_l = 0.05, 0.2
    drive = OmniDrive.three_wheel(wheel_radius=r, base_radius=big_l)
    # Wrapped to (-π, π]: the wheel mounted at 270° reads -90°.
    np.testing.assert_allclose(drive.wheel_angles, np.radians([30, 150, -90]))
    s3 = math.sqrt(3) / 2
    np.testing.assert_allclose(drive.inverse(Twist2D(1.0, 0, 0)), [-0.5 / r, -0.5 / r, 1 / r])
    np.testing.assert_allclose(
        drive.inverse(Twist2D(0, 1.0, 0)), [s3 / r, -s3 / r, 0.0], atol=1e-12
    )
    np.testing.assert_allclose(drive.inverse(Twist2D(0, 0, 1.0)), [big_l / r] * 3)


def test_papers_forward_matrix_is_not_the_inverse() -> None:
    """The paper's forward rows r*[cos(θi+π/2), sin(θi+π/2), 1/(3L)] give 1.5× vx, vy."""
    r, big_l = 0.05, 0.2
    drive = OmniDrive.three_wheel(wheel_radius=r, base_radius=big_l)
    th = drive.wheel_angles
    paper = r * np.vstack(
        (np.cos(th + math.pi / 2), np.sin(th + math.pi / 2), np.full(3, 1 / (3 * big_l)))
    )
    t = Twist2D(0.4, -0.3, 0.0)
    np.testing.assert_allclose(paper @ drive.inverse(t), [0.6, -0.45, 0.0], atol=1e-12)
    np.testing.assert_allclose(drive.forward(drive.inverse(t)).as_array(), t.as_array(), atol=1e-12)


def test_saturate_keeps_direction() -> None:
    drive = OmniDrive.three_wheel(wheel_radius=0.05, base_radius=0.2)
    w = drive.inverse(Twist2D(2.0, 1.0, 3.0))
    out = drive.saturate(w, max_wheel_speed=10.0)
    assert np.max(np.abs(out)) == pytest.approx(10.0)
    t_in, t_out = drive.forward(w).as_array(), drive.forward(out).as_array()
    np.testing.assert_allclose(t_out / np.linalg.norm(t_out), t_in / np.linalg.norm(t_in))
    small = np.array([1.0, -2.0, 0.5])
    np.testing.assert_array_equal(drive.saturate(small, max_wheel_speed=10.0), small)
    batch = drive.saturate(np.array([w, small]), max_wheel_speed=10.0)
    np.testing.assert_allclose(batch[1], small)
    assert np.max(np.abs(batch[0])) == pytest.approx(10.0)
    np.testing.assert_array_equal(drive.saturate(np.zeros(3), max_wheel_speed=1.0), np.zeros(3))


def test_bad_input() -> None:
    with pytest.raises(ValueError, match="wheel_angles"):
        OmniDrive([0.0, 1.0], wheel_radius=0.05, base_radius=0.2)
    with pytest.raises(ValueError, match="wheel_angles"):
        OmniDrive([0.0, 0.0, 0.0], wheel_radius=0.05, base_radius=0.2)
    with pytest.raises(ValueError, match="wheel_angles"):
        OmniDrive([0.0, math.pi, 2 * math.pi], wheel_radius=0.05, base_radius=0.2)
    with pytest.raises(ValueError, match="wheel_angles"):
        OmniDrive([0.0, 1.0, math.nan], wheel_radius=0.05, base_radius=0.2)
    with pytest.raises(ValueError, match="wheel_radius"):
        OmniDrive.three_wheel(wheel_radius=0.0, base_radius=0.2)
    with pytest.raises(ValueError, match="base_radius"):
        OmniDrive.three_wheel(wheel_radius=0.05, base_radius=-1.0)
    drive = OmniDrive.three_wheel(wheel_radius=0.05, base_radius=0.2)
    with pytest.raises(ValueError, match="wheel_speeds"):
        drive.forward([1.0, 2.0])
    with pytest.raises(ValueError, match="wheel_speeds"):
        drive.forward([1.0, 2.0, math.nan])
    with pytest.raises(ValueError, match="max_wheel_speed"):
        drive.saturate([1.0, 2.0, 3.0], max_wheel_speed=0.0)
    with pytest.raises(ValueError, match="twists"):
        drive.inverse_batch(np.zeros((2, 2)))
    with pytest.raises(TypeError, match="twist must be a Twist2D"):
        drive.inverse(1.0)
    with pytest.raises(ValueError, match="twist"):
        drive.inverse([1.0, 0.0])


def test_inverse_accepts_sequences() -> None:
    drive = OmniDrive.three_wheel(wheel_radius=0.05, base_radius=0.2)
    ref = drive.inverse(Twist2D(0.3, -0.2, 0.5))
    assert ref.shape == (3,)
    np.testing.assert_array_equal(drive.inverse([0.3, -0.2, 0.5]), ref)
    np.testing.assert_array_equal(drive.inverse((0.3, -0.2, 0.5)), ref)
    np.testing.assert_array_equal(drive.inverse(np.array([0.3, -0.2, 0.5])), ref)


def test_options_are_keyword_only() -> None:
    with pytest.raises(TypeError, match="positional"):
        OmniDrive([0.0, 2.0, 4.0], 0.05, 0.2)  # type: ignore[call-arg]
    with pytest.raises(TypeError, match="positional"):
        OmniDrive.three_wheel(0.05, 0.2)  # type: ignore[call-arg]
    drive = OmniDrive.three_wheel(wheel_radius=0.05, base_radius=0.2)
    with pytest.raises(TypeError, match="positional"):
        drive.saturate([1.0, 2.0, 3.0], 10.0)  # type: ignore[call-arg]
    assert drive.wheel_radius == 0.05 and drive.base_radius == 0.2


def test_arrays_read_only() -> None:
    drive = OmniDrive.three_wheel(wheel_radius=0.05, base_radius=0.2)
    with pytest.raises(ValueError):
        drive.jacobian[0, 0] = 1.0


def test_saturate_never_rounds_above_the_limit() -> None:
    """w * (limit / peak) could land one ulp above the limit (3.7 rad/s: 1 in 10 commands)."""
    drive = OmniDrive.three_wheel(wheel_radius=0.05, base_radius=0.2)
    rng = np.random.default_rng(0)
    wheels = rng.normal(size=(2000, 3)) * rng.uniform(1.0, 100.0, size=(2000, 1))
    for limit in (0.3, 3.7, 10.0):
        out = drive.saturate(wheels, max_wheel_speed=limit)
        peaks = np.abs(out).max(axis=1)
        assert (peaks <= limit).all()
        np.testing.assert_array_equal(peaks[np.abs(wheels).max(axis=1) > limit], limit)
    # A tiny limit on huge speeds keeps the direction instead of underflowing to zero.
    out = drive.saturate([1e308, -1e308, 1e307], max_wheel_speed=1e-300)
    np.testing.assert_allclose(out, [1e-300, -1e-300, 1e-301])


def accepted(angles: list[float], *, wheel_radius: float, base_radius: float) -> bool:
    """Whether OmniDrive takes the layout (a refusal must be the singular-layout error)."""
    try:
        OmniDrive(angles, wheel_radius=wheel_radius, base_radius=base_radius)
    except ValueError as err:
        assert "singular layout" in str(err)
        return False
    return True


# Factors that keep a 5 cm wheel and a 20 cm base radius within [1e-6, 1e6] m.
ROBOT_SCALES = [1e-4, 1e-2, 1.0, 1e2, 1e4]
BASE_RADII = [1e-6, 1e-3, 0.2, 1.0, 1e3, 1e6]


@st.composite
def doubtful_layouts(draw: st.DrawFn) -> list[float]:
    """Layouts close to singular: wheels nearly parallel, at nearly two places, bunched."""
    n = draw(st.integers(3, 5))
    base = draw(st.floats(-math.pi, math.pi))
    spread = draw(st.floats(0.1, 3.0))
    kind = draw(st.sampled_from([(0.0, math.pi), (spread, -spread), (0.0, 0.0)]))
    angles = []
    for i in range(n):
        exponent = draw(st.integers(-12, -1))
        sign = draw(st.sampled_from([-1.0, 1.0]))
        jitter = sign * 10.0**exponent * draw(st.floats(1.0, 9.0)) * (i + 1)
        angles.append(base + kind[i % 2] + jitter)
    return angles


@settings(max_examples=40)
@given(doubtful_layouts())
def test_the_singular_layout_verdict_does_not_depend_on_the_robots_size(
    angles: list[float],
) -> None:
    # It used to be the condition number of the Jacobian, whose rotation column is in
    # metres: a layout passed at one base radius and was refused at another.
    verdict = accepted(angles, wheel_radius=0.05, base_radius=0.2)
    for k in ROBOT_SCALES:
        assert accepted(angles, wheel_radius=0.05 * k, base_radius=0.2 * k) == verdict
    for base_radius in BASE_RADII:
        assert accepted(angles, wheel_radius=0.05, base_radius=base_radius) == verdict


test_the_singular_layout_verdict_does_not_depend_on_the_robots_size_thoroughly = slow_twin(
    test_the_singular_layout_verdict_does_not_depend_on_the_robots_size, max_examples=100
)


def test_bunched_wheels_are_judged_alike_at_every_size() -> None:
    # Three wheels within 0.1°: condition 8.5e6 with omega as L * omega, a usable if
    # poor layout. The old test refused it at base radius 1e-6 m and 1e6 m, not 0.2 m.
    angles = [0.0, 0.001, 0.002]
    for base_radius in BASE_RADII:
        drive = OmniDrive(angles, wheel_radius=0.05, base_radius=base_radius)
        t = Twist2D(0.3, -0.2, 0.5)
        back = drive.forward(drive.inverse(t))
        # Resolved to the condition number times the rounding, with omega as L * omega
        # (m/s) like vx and vy.
        want = t.as_array() * np.array([1.0, 1.0, base_radius])
        got = back.as_array() * np.array([1.0, 1.0, base_radius])
        np.testing.assert_allclose(got, want, rtol=0.0, atol=1e-8 * np.linalg.norm(want))


@pytest.mark.parametrize(
    "angles",
    [
        [0.0, 0.0, 0.0],
        [0.0, math.pi, 2 * math.pi],
        [0.3, 0.3 + math.pi, 0.3, 0.3 - math.pi],
        [-1.2, -1.2 + math.pi, -1.2 + 2 * math.pi, -1.2 - math.pi, -1.2],
        [0.5, -0.5, 0.5],  # only two wheel positions: rank 2
    ],
)
@pytest.mark.parametrize("wheel_radius", [1e-6, 0.05, 1e6])
@pytest.mark.parametrize("base_radius", BASE_RADII)
def test_a_singular_layout_is_refused_at_any_radius(
    angles: list[float], wheel_radius: float, base_radius: float
) -> None:
    with pytest.raises(ValueError, match="wheel_angles give a singular layout"):
        OmniDrive(angles, wheel_radius=wheel_radius, base_radius=base_radius)


@pytest.mark.parametrize("base_radius", [1e-6, 1.0, 1e6])
@pytest.mark.parametrize("wheel_radius", [1e-6, 0.05, 1e6])
def test_forward_inverts_inverse_for_a_nearly_singular_layout_at_every_size(
    wheel_radius: float, base_radius: float
) -> None:
    # Accepted (condition number of the layout about 5e9 < 1e10). The pseudo-inverse
    # used to be taken of the Jacobian, whose columns differ in scale by base_radius:
    # at 1e6 m NumPy's pinv cut off a singular value, and forward(inverse(1 m/s ahead))
    # gave vy = 0.05 m/s.
    angles = np.array([0.0, 2e-8, 0.1])
    layout = np.column_stack((-np.sin(angles), np.cos(angles), np.ones(3)))
    cond = float(np.linalg.cond(layout))
    assert cond < 1e10
    drive = OmniDrive(angles, wheel_radius=wheel_radius, base_radius=base_radius)
    for twist in ([1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0 / base_radius]):
        back = drive.forward(drive.inverse(twist)).as_array()
        # Errors measured as speeds (omega * base_radius for the rotation), relative to
        # the layout's condition number: what rounding allows, at any size.
        error = (back - twist) * np.array([1.0, 1.0, base_radius])
        assert np.abs(error).max() <= 1e-14 * cond


def test_copies_and_pickles_keep_the_arrays_read_only() -> None:
    import copy
    import pickle

    drive = OmniDrive(np.radians([45.0, 135.0, 225.0, 315.0]), wheel_radius=0.05, base_radius=0.2)
    speeds = [1.0, -2.0, 3.0, 0.5]
    for twin in (copy.copy(drive), copy.deepcopy(drive), pickle.loads(pickle.dumps(drive))):
        for arr in (twin.wheel_angles, twin.jacobian, twin.forward_matrix):
            assert not arr.flags.writeable
        assert repr(twin) == repr(drive)
        np.testing.assert_array_equal(twin.forward_matrix, drive.forward_matrix)
        assert twin.forward(speeds) == drive.forward(speeds)
    assert drive.jacobian.flags.writeable is False
