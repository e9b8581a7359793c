"""The scan matcher's kernels against outside references (review 38, mutation).

``_solve3`` declares the Gauss-Newton system singular where a Cholesky pivot falls
to 1e-12 of its diagonal entry: "truly singular directions still fail", every
other positive definite system is solved. A mutant refusing pivots below 1e-3 of
their entry (systems of condition above about 1e3: a corridor's scan, whose
along-corridor direction is weak) survived the suite, whose systems were all well
conditioned: the matcher then stopped with ``STATUS_SINGULAR`` where it had a step.
Oracle: ``numpy.linalg.solve`` of H plus the documented ridge (1e-9 of the largest
diagonal entry). And ``match_level``'s pull towards a prior pose: the public matcher's
prior is its guess, where the pull starts at zero, so the rotation pull's gradient
with the wrong sign, or its Hessian term taking the translation weight, survived the
suite; on a flat map the prior alone is the minimum (closed form), and its first step
is clamped to the documented largest steps (mutants of both clamps survived too).
"""

from __future__ import annotations

import numpy as np
import pytest

from navkit.mapping._scan_matcher_kernels import STATUS_CONVERGED, _solve3, match_level


def test_solve3_solves_ill_conditioned_positive_definite_systems() -> None:
    rng = np.random.default_rng(38)
    for trial in range(40):
        q, _ = np.linalg.qr(rng.normal(size=(3, 3)))
        log_kappa = 9.0 * trial / 39  # condition 1 to 1e9
        h = (q * 10.0 ** np.array([0.0, 0.5 * log_kappa, log_kappa])) @ q.T
        h = 0.5 * (h + h.T) * 10.0 ** rng.uniform(-4.0, 4.0)
        g = rng.normal(size=3)
        step = np.zeros(3)
        assert _solve3(h.copy(), g.copy(), step), trial
        ridged = h + 1e-9 * np.max(np.diag(h)) * np.eye(3)
        expected = np.linalg.solve(ridged, g)
        # Backward stable: the residual, not the step, is small whatever the condition.
        residual = np.abs(ridged @ step - g)
        assert (residual <= 1e-12 * (np.abs(ridged) @ np.abs(step) + np.abs(g))).all(), trial
        scale = np.linalg.cond(ridged) * 1e-15
        np.testing.assert_allclose(step, expected, rtol=max(1e-9, scale), atol=0.0)


def test_solve3_refuses_a_singular_system() -> None:
    # Rank 1 plus a ridge of 1e-9: the second pivot is 1e-9 of its entry, solved; a
    # zero matrix has no positive pivot at all.
    step = np.zeros(3)
    assert not _solve3(np.zeros((3, 3)), np.ones(3), step)
    v = np.array([1.0, 2.0, 3.0])
    assert _solve3(np.outer(v, v), v.copy(), step)
    assert np.allclose(np.outer(v, v) @ step, v, rtol=1e-6)


def _match(
    logodds: np.ndarray,
    points: np.ndarray,
    pose: np.ndarray,
    prior: np.ndarray,
    weights: tuple[float, float],
) -> tuple[int, int]:
    scratch = (np.empty((3, 3)), np.empty(3), np.empty(3), np.empty((0, 0)))
    return match_level(
        logodds, 0.0, 0.0, 0.0, 0.1, points, pose, 50, 10.0, 10.0, 1e-9, 1e-9,
        prior, weights[0], weights[1], 0.0, *scratch,
    )  # fmt: skip


def test_on_an_empty_map_the_prior_alone_is_the_minimum() -> None:
    # "translation_weight² |t - t₀|² + rotation_weight² (θ - θ₀)²" is added to the
    # mean cost: where the map is flat (every cell free, M = 0, no gradient), that
    # pull alone moves the pose, onto the prior. A mutant adding the rotation pull's
    # gradient with the wrong sign survived the suite (the public matcher's prior is
    # its guess, where the pull starts at zero): θ moved away from θ₀.
    logodds = np.full((40, 40), -40.0, dtype=np.float32)
    points = np.array([[0.3, 0.0], [0.0, 0.4], [-0.2, -0.1]])
    for weights in [(1.0, 1.0), (0.5, 3.0), (4.0, 0.25)]:
        pose = np.array([2.0, 1.5, 0.4])
        prior = np.array([1.7, 1.9, -0.3])
        _, status = _match(logodds, points, pose, prior, weights)
        assert status == STATUS_CONVERGED
        np.testing.assert_allclose(pose, prior, atol=1e-6)


@pytest.mark.parametrize("sign", [1.0, -1.0])
@pytest.mark.parametrize("reach", [10.0, 0.08])  # steps of 5 m and 1.2 rad, 0.4 m and 0.15 rad
def test_a_step_is_clamped_to_the_largest_steps_keeping_its_direction(
    sign: float, reach: float
) -> None:
    # "clamps the translation of Δξ to max_step_xy (m, keeping its direction) and the
    # rotation to max_step_theta (rad)": on a flat map the first step is the whole way
    # to the prior; one iteration with limits 0.25 m and 0.1 rad takes that much, along
    # that direction (the cost falls, so no halving). Mutants doubling
    # the translation's limit, or dropping the rotation's upper clamp, survived the suite.
    logodds = np.full((40, 40), -40.0, dtype=np.float32)
    points = np.array([[0.3, 0.0], [0.0, 0.4]])
    start = np.array([2.0, 1.5, 0.0])
    prior = start + sign * np.array([3.0 * reach, 4.0 * reach, 0.15 if reach < 1.0 else 1.2])
    pose = start.copy()
    scratch = (np.empty((3, 3)), np.empty(3), np.empty(3), np.empty((0, 0)))
    done, _ = match_level(
        logodds, 0.0, 0.0, 0.0, 0.1, points, pose, 1, 0.25, 0.1, 1e-9, 1e-9,
        prior, 1.0, 1.0, 0.0, *scratch,
    )  # fmt: skip
    assert done == 1
    moved = pose - start
    np.testing.assert_allclose(moved[:2], sign * 0.25 * np.array([0.6, 0.8]), rtol=1e-9)
    assert moved[2] == pytest.approx(sign * 0.1, rel=1e-12)
