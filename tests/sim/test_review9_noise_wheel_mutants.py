"""Range-noise, wheel and segment rules of navkit.sim that no earlier test pinned down.

Found by mutation testing (session 13, second pass over navkit.sim): each test
here fails on a one-line change of the code that every other test let through.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from constant_controller import Constant, run_constant
from navkit.geometry import Pose2D, Twist2D
from navkit.kinematics import DiffDrive, OmniDrive
from navkit.sim import Imu, ImuReading, RangeNoise, Robot, Simulation, World


def test_equal_band_limits_are_refused() -> None:
    # The limits must be strictly increasing: two equal limits would make an
    # empty band.
    with pytest.raises(ValueError, match="strictly increasing"):
        RangeNoise(limits=(2.0, 2.0, math.inf), sigma=(0.01, 0.02, 0.03), bias=(0.0, 0.0, 0.0))
    RangeNoise(limits=(2.0, 2.5, math.inf), sigma=(0.01, 0.02, 0.03), bias=(0.0, 0.0, 0.0))


def _noisy(
    ranges: list[float],
    noise: RangeNoise,
    *,
    range_min: float = 0.1,
    range_max: float = 40.0,
    dropout: float = 0.0,
    uniforms: list[float] | None = None,
) -> np.ndarray:
    """The sensor's noise kernel on exact ``ranges`` with z = 0 (the mean reading)."""
    from navkit.sim._lidar_kernels import apply_range_noise

    out = np.array(ranges, dtype=np.float64)
    limits, bias, sigma = noise.arrays()
    apply_range_noise(out, np.zeros(out.size),
                      np.ones(out.size) if uniforms is None else np.array(uniforms),
                      limits, bias, sigma, np.array(noise.absolute), dropout, range_min,
                      range_max)  # fmt: skip
    return out


def test_a_range_exactly_at_a_band_limit_belongs_to_the_next_band() -> None:
    # Band b is the first with r < limits[b]: r = 3 is not < 3, so band 1.
    noise = RangeNoise(limits=(3.0, math.inf), sigma=(0.0, 0.0), bias=(0.0, 0.1))
    got = _noisy([2.5, 3.0, 5.0], noise)
    assert got.tolist() == pytest.approx([2.5, 3.0 * 1.1, 5.0 * 1.1])


def test_readings_exactly_at_range_min_and_range_max_follow_rep_117() -> None:
    # REP 117: a reading below range_min reads -inf, one at or beyond range_max
    # reads +inf; range_min itself is a valid reading.
    exact = RangeNoise(limits=(math.inf,), sigma=(0.0,), bias=(0.0,))
    got = _noisy(
        [0.1, 0.1 * (1 - 1e-12), 40.0, 40.0 * (1 - 1e-12)], exact, range_min=0.1, range_max=40.0
    )
    assert got[0] == 0.1
    assert got[1] == -math.inf
    assert got[2] == math.inf
    assert got[3] == 40.0 * (1 - 1e-12)


def test_a_uniform_draw_equal_to_the_dropout_rate_keeps_the_beam() -> None:
    # A beam is dropped when its uniform draw u < dropout: a probability of
    # exactly `dropout` for u uniform on [0, 1).
    exact = RangeNoise(limits=(math.inf,), sigma=(0.0,), bias=(0.0,))
    got = _noisy([2.0, 2.0, 2.0], exact, dropout=0.25, uniforms=[0.25, 0.2499, 0.9])
    assert got[0] == 2.0
    assert math.isnan(got[1])
    assert got[2] == 2.0


DIFF = DiffDrive(track=0.3, wheel_radius=0.05)


def test_imu_reads_the_centripetal_term_of_a_sideways_motion() -> None:
    # Body acceleration a = dv/dt + omega x v. Holding vy = 0.3 m/s and omega =
    # 0.5 rad/s (vx = 0), the body-frame acceleration is (-omega*vy, 0).
    omni = OmniDrive.three_wheel(wheel_radius=0.05, base_radius=0.2)
    robot = Robot(drive=omni, footprint=0.25, imu=Imu())
    _, ctrl = run_constant(robot, Twist2D(0.0, 0.3, 0.5), 1.0)
    late = [r for obs in ctrl.seen for r in obs.new if isinstance(r, ImuReading) and r.stamp > 0.2]
    assert late
    assert all(r.acceleration_x == pytest.approx(-0.5 * 0.3, abs=1e-9) for r in late)
    assert all(r.acceleration_y == pytest.approx(0.0, abs=1e-9) for r in late)


@pytest.mark.parametrize("speed", [0.5123, 0.3377])
def test_a_wheel_ramp_ending_inside_a_physics_step_moves_the_exact_distance(speed: float) -> None:
    # Wheels ramp at 10 rad/s² (0.5 m/s² on 5 cm wheels) to speed / 0.05 rad/s and
    # hold: the ramp lasts t1 = speed / 0.5 s, generally ending inside a physics
    # step, and the robot covers speed * (T - t1 / 2) in T seconds.
    robot = Robot(drive=DIFF, footprint=0.2, max_wheel_acceleration=10.0)
    trace, _ = run_constant(robot, Twist2D(speed), 2.0)
    t1 = speed / 0.5
    assert trace.poses[-1, 0] == pytest.approx(speed * (2.0 - t1 / 2.0), abs=1e-9)


def test_full_slip_stops_a_wheel_instead_of_giving_it_full_grip() -> None:
    # Each wheel keeps 1 - min(|s|, 1) of its speed, s ~ N(0, wheel_slip²). With
    # wheel_slip = 1 the kept fraction has the mean E[1 - min(|z|, 1)] =
    # P(|z| < 1) - 2 (phi(0) - phi(1)) for z standard normal.
    phi0, phi1 = 1.0 / math.sqrt(2.0 * math.pi), math.exp(-0.5) / math.sqrt(2.0 * math.pi)
    kept = math.erf(1.0 / math.sqrt(2.0)) - 2.0 * (phi0 - phi1)  # 0.3687
    robot = Robot(drive=DIFF, footprint=0.2, wheel_slip=1.0)
    trace, _ = run_constant(robot, Twist2D(0.2), 20.0, seed=5)
    # The forward speed is the mean of both wheels' ground speeds: the path length
    # is 0.2 m/s * 20 s times the mean kept fraction (chords of short arcs).
    assert trace.metrics.distance / (0.2 * 20.0) == pytest.approx(kept, rel=0.05)


def test_goal_yaw_exactly_at_the_yaw_tolerance_is_reached() -> None:
    # Driving straight along +x (heading exactly 0) into a goal whose heading is
    # 0.5 rad: the error is exactly yaw_tolerance = 0.5 rad (pi - 0.5 and its
    # difference from pi are exact in float64), which counts as reached.
    robot = Robot(drive=DIFF, footprint=0.2)
    for tol, reached in ((0.5, True), (0.4999, False)):
        sim = Simulation(
            World(),
            robot,
            Constant(Twist2D(0.2)),
            start=(0.0, 0.0, 0.0),
            goal=(0.5, 0.0, 0.5),
            goal_tolerance=0.1,
            yaw_tolerance=tol,
            duration=5.0,
        )
        assert sim.run().metrics.reached is reached


def test_a_robot_exactly_goal_tolerance_away_has_reached_the_goal() -> None:
    # "The goal is reached within this distance": the first step at exactly
    # goal_tolerance from the goal is the time to goal. The radius is taken as the
    # float distance from a recorded pose (x only: the robot drives along +x).
    robot = Robot(drive=DIFF, footprint=0.2)
    free = Simulation(
        World(), robot, Constant(Twist2D(0.2)), start=(0.0, 0.0, 0.0), duration=3.0
    ).run()
    k = int(np.searchsorted(free.poses[:, 0], 0.3))
    assert np.all(free.poses[:, 1:] == 0.0) and free.poses[k - 1, 0] < free.poses[k, 0]
    goal_x = 0.55
    radius = goal_x - float(free.poses[k, 0])
    trace = Simulation(
        World(),
        robot,
        Constant(Twist2D(0.2)),
        start=(0.0, 0.0, 0.0),
        goal=(goal_x, 0.0),
        goal_tolerance=radius,
        duration=3.0,
    ).run()
    assert trace.metrics.reached
    assert trace.metrics.time_to_goal == pytest.approx(float(free.times[k]), abs=1e-12)


def test_distance_is_the_path_length_not_the_displacement() -> None:
    # On an arc of radius v / omega the path length is v * T while the start and
    # end are only a chord 2 R sin(omega T / 2) apart.
    v, omega, duration = 0.2, 0.5, 10.0
    trace, _ = run_constant(Robot(drive=DIFF, footprint=0.2), Twist2D(v, 0.0, omega), duration)
    assert trace.metrics.distance == pytest.approx(v * duration, rel=1e-3)
    chord = 2.0 * (v / omega) * math.sin(omega * duration / 2.0)
    assert math.hypot(*trace.poses[-1, :2]) == pytest.approx(chord, rel=1e-3)


class _FixedEstimate:
    """An estimator that always reports the same pose."""

    def observe(self, t: float, reading: object) -> None:
        pass

    @property
    def pose(self) -> Pose2D:
        return Pose2D(1.0, 2.0, 0.0)


def test_estimate_metrics_use_the_estimate() -> None:
    # The robot stays at the origin while its estimator says (1, 2): the final
    # error is measured from the true pose, the estimated one from the estimate.
    sim = Simulation(
        World(),
        Robot(drive=DIFF, footprint=0.2),
        Constant(Twist2D(0.0)),
        start=(0.0, 0.0, 0.0),
        goal=(3.0, 2.0),
        duration=0.5,
        estimator=_FixedEstimate(),
    )
    m = sim.run().metrics
    assert m.final_error == pytest.approx(math.hypot(3.0, 2.0))
    assert m.final_error_estimated == pytest.approx(2.0)
    assert m.estimate_error == pytest.approx(math.hypot(1.0, 2.0))


def test_metrics_refuse_a_negative_min_clearance() -> None:
    # min_clearance is a distance: >= 0 (or inf); any negative value is refused.
    import dataclasses

    trace, _ = run_constant(Robot(drive=DIFF, footprint=0.2), Twist2D(0.1), 0.2)
    for bad in (-0.5, -2.0):
        with pytest.raises(ValueError, match="min_clearance"):
            dataclasses.replace(trace.metrics, min_clearance=bad)
    assert dataclasses.replace(trace.metrics, min_clearance=0.0).min_clearance == 0.0


def test_reverse_wheel_speeds_saturate_too() -> None:
    # max_wheel_speed bounds |wheel speed|: 5 rad/s on 5 cm wheels is 0.25 m/s,
    # backward as forward.
    robot = Robot(drive=DIFF, footprint=0.2, max_wheel_speed=5.0)
    trace, _ = run_constant(robot, Twist2D(-1.0), 2.0)
    assert trace.poses[-1, 0] == pytest.approx(-0.25 * 2.0, abs=1e-9)


def test_point_polyline_distances_match_shapely_past_the_ends_and_for_one_vertex() -> None:
    # K >= 1 vertices: past either end of the path the nearest point is the end
    # vertex; a one-vertex path is that point.
    from shapely.geometry import LineString, Point

    from navkit.sim._polyline_distance_kernels import point_polyline_distances

    pts = np.array([[2.0, 1.0], [-1.5, -0.5], [0.5, 0.3], [3.0, 4.0]])
    for path in (np.array([[0.0, 0.0], [1.0, 0.0]]),
                 np.array([[0.0, 0.0], [1.0, 0.0], [1.0, 1.0]]),
                 np.array([[0.25, -0.5]])):  # fmt: skip
        out = np.empty(pts.shape[0])
        point_polyline_distances(pts, path, out)
        ref = LineString(path) if path.shape[0] > 1 else Point(path[0])
        expected = [ref.distance(Point(p)) for p in pts]
        assert out.tolist() == pytest.approx(expected, abs=1e-12)
