"""The CARMEN evaluation harness's metrics (benchmarks/carmen_eval.py) on known trajectories."""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

import carmen_eval as ce
from navkit.mapping import LaserScan
from test_bench_astar import shared_data


def trajectory(n: int = 40, seed: int = 1) -> np.ndarray:
    """A wandering path: steps of 0.6-1.0 m, turns up to ±25°."""
    rng = np.random.default_rng(seed)
    steps = np.column_stack(
        (
            rng.uniform(0.6, 1.0, n - 1),
            rng.normal(0.0, 0.05, n - 1),
            rng.uniform(-0.45, 0.45, n - 1),
        )
    )
    return ce.chain(steps, start=(2.0, -1.0, 0.3))


def rigidly_moved(poses: np.ndarray, x: float, y: float, theta: float) -> np.ndarray:
    return ce.compose(np.broadcast_to([x, y, theta], poses.shape), poses)


def test_chain_inverts_relative_motions() -> None:
    poses = trajectory()
    np.testing.assert_allclose(
        ce.chain(ce.relative_motions(poses), start=poses[0]), poses, atol=1e-9
    )


@settings(max_examples=25, deadline=None)
@given(st.floats(-50, 50), st.floats(-50, 50), st.floats(-math.pi, math.pi))
def test_ate_of_rigidly_moved_trajectory_is_zero(x: float, y: float, theta: float) -> None:
    truth = trajectory()
    moved = rigidly_moved(truth, x, y, theta)
    assert np.max(ce.absolute_trajectory_error(moved, truth)) < 1e-9
    m = ce.compute_metrics(moved, truth)
    assert m.ate_rms_m < 1e-9 and m.pair.mean_m < 1e-9 and m.pair.mean_deg < 1e-7
    assert m.over_5m.mean_m < 1e-9 and m.gross_failures == 0


def test_rpe_of_identical_trajectories_is_zero() -> None:
    truth = trajectory()
    for distance in (None, 1.0, 5.0):
        t, r = ce.relative_pose_errors(truth, truth, distance=distance)
        assert t.size > 0 and np.all(t == 0.0) and np.all(r == 0.0)


def test_known_pair_offset() -> None:
    """One pair's motion off by 0.3 m along x and 4°: that pair's error, nothing else."""
    truth = trajectory()
    motions = ce.relative_motions(truth)
    motions[10] += [0.3, 0.0, math.radians(4.0)]
    est = ce.chain(motions)
    t, r = ce.relative_pose_errors(est, truth)
    # E = M_true⁻¹ (M_true + δ): translation error = |R(-θ) δxy| = 0.3, rotation 4°.
    assert t[10] == pytest.approx(0.3, abs=1e-9)
    assert math.degrees(r[10]) == pytest.approx(4.0, abs=1e-9)
    others = np.delete(np.arange(t.size), 10)
    assert np.max(t[others]) < 1e-9 and np.max(np.abs(r[others])) < 1e-12
    m = ce.compute_metrics(est, truth)
    assert m.pair.mean_m == pytest.approx(0.3 / t.size)
    assert m.pair.rms_m == pytest.approx(0.3 / math.sqrt(t.size))
    assert m.pair.mean_deg == pytest.approx(4.0 / t.size)
    assert m.gross_failures == 0  # 0.3 m and 4° are below 0.5 m / 10°


def test_gross_failures_count_pairs_over_the_bounds() -> None:
    truth = trajectory()
    motions = ce.relative_motions(truth)
    motions[3, 0] += 0.6  # > 0.5 m
    motions[7, 2] += math.radians(11.0)  # > 10°
    motions[9, 1] += 0.4  # below both
    m = ce.compute_metrics(ce.chain(motions), truth)
    assert m.gross_failures == 2 and m.pairs == truth.shape[0] - 1


def test_ate_of_a_known_offset() -> None:
    """A square estimated 10 % too large: no rigid motion helps, each corner is 0.1·√2 off."""
    corners = np.array([[1.0, 1.0], [-1.0, 1.0], [-1.0, -1.0], [1.0, -1.0]])
    truth = np.column_stack((corners + np.array([5.0, 3.0]), np.zeros(4)))
    est = rigidly_moved(np.column_stack((1.1 * corners, np.zeros(4))), 2.0, 1.0, 0.7)
    err = ce.absolute_trajectory_error(est, truth)
    np.testing.assert_allclose(err, 0.1 * math.sqrt(2.0), atol=1e-12)
    m = ce.compute_metrics(est, truth)
    assert m.ate_rms_m == pytest.approx(0.1 * math.sqrt(2.0))
    assert m.ate_mean_m == pytest.approx(0.1 * math.sqrt(2.0))


def test_distance_pairs_reach_the_distance() -> None:
    truth = trajectory(60)
    steps = np.hypot(*np.diff(truth[:, :2], axis=0).T)
    travelled = np.concatenate(([0.0], np.cumsum(steps)))
    for distance in (1.0, 5.0):
        i, j = ce.pair_indices(truth, distance)
        assert i.size > 0
        assert np.all(travelled[j] - travelled[i] >= distance)
        assert np.all(travelled[j - 1] - travelled[i] < distance)


def test_motion_prior_is_seeded_with_the_right_spread() -> None:
    truth = trajectory(2001)
    a = ce.motion_prior(truth, seed=3)
    np.testing.assert_array_equal(a, ce.motion_prior(truth, seed=3))
    assert not np.array_equal(a, ce.motion_prior(truth, seed=4))
    noise = a - ce.relative_motions(truth)
    noise[:, 2] = np.angle(np.exp(1j * noise[:, 2]))
    np.testing.assert_allclose(noise.std(axis=0), [0.05, 0.05, math.radians(2.0)], rtol=0.1)


def test_dead_reckoning_with_exact_prior_is_perfect() -> None:
    truth = trajectory()
    data = ce.CarmenData("synthetic", (), truth)
    result = ce.evaluate(ce.dead_reckoning, data, ce.relative_motions(truth), name="prior")
    assert result.metrics.ate_rms_m < 1e-9 and result.metrics.pair.mean_m < 1e-9
    assert result.metrics.seconds_per_scan >= 0.0


def room_scan(pose: np.ndarray) -> LaserScan:
    """Ranges from ``pose`` inside the 8 m × 5 m box [0, 8] × [0, 5] with a pillar-free wall set."""
    angles = np.linspace(-math.pi, math.pi, 360, endpoint=False)
    x, y, th = pose
    d = np.stack((np.cos(angles + th), np.sin(angles + th)), axis=1)
    with np.errstate(divide="ignore"):
        tx = np.where(d[:, 0] > 0, (8.0 - x) / d[:, 0], -x / d[:, 0])
        ty = np.where(d[:, 1] > 0, (5.0 - y) / d[:, 1], -y / d[:, 1])
    ranges = np.minimum(np.abs(tx), np.abs(ty))
    return LaserScan(
        ranges, angle_min=-math.pi, angle_increment=2 * math.pi / 360, range_min=0.0, range_max=20.0
    )


def test_icp_recovers_a_small_offset_in_a_room() -> None:
    a, b = np.array([3.0, 2.0, 0.1]), np.array([3.4, 2.2, 0.25])
    true_motion = ce.between(a, b)
    guess = true_motion + np.array([0.05, -0.05, math.radians(2.0)])
    got = ce.icp_align(room_scan(b).to_points(), room_scan(a).to_points(), guess)
    np.testing.assert_allclose(got, true_motion, atol=0.02)


def test_baselines_on_the_first_intel_scans() -> None:
    data = ce.load_log("intel", max_scans=40, data_dir=shared_data("carmen-logs").parent)
    prior = ce.motion_prior(data.poses)
    results = {
        name: ce.evaluate(method, data, prior, name=name)
        for name, method in (("prior", ce.dead_reckoning), ("icp", ce.icp_method))
    }
    assert results["icp"].metrics.pair.mean_deg < results["prior"].metrics.pair.mean_deg
    assert "| intel | icp |" in ce.format_table(list(results.values()))
