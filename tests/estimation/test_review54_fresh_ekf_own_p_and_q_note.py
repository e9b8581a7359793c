"""Review 53's EKF promises attacked (review 54, FRESH): four found, two fixed by the lead.

* ef1b54e names a process noise ``Q`` "accepted as positive semi-definite to its
  rounding" with its negative eigenvalue when a prediction loses positive
  definiteness. The eigenvalue is ``numpy.linalg.eigvalsh``'s, and for a ``Q``
  that is exactly positive semi-definite and singular (``G Gᵀ`` of an integer
  ``G``, computed exactly) that is often a negative number of the size of its
  own rounding (-9.5e-16 for ``g gᵀ``, ``g = [4, -3, -1]``): the error then
  tells the user to "pass a positive semi-definite Q", which they did, where the
  step failed for another reason (here a Jacobian that forgets the state).
* 54bec22's docstring says an ``ExtendedKalmanFilter``'s :attr:`P` "is always a
  valid ``P0``"; a prediction may grow ``P`` beyond the 1e100 that ``P0``'s
  entries are held to (an unstable model without measurements, or a ``Q`` of
  1e100 added to a ``P`` of 1e99), and ``ExtendedKalmanFilter(ekf.x, ekf.P)``
  then raises ``ValueError``.
* The other way round: 54bec22 takes a ``P0`` that NumPy's Cholesky *or* the
  filter's own checks take, so a near-singular ``P0`` NumPy takes (``A Aᵀ`` of a
  tall ``A``, which the docstring names as one that passes) and the kernels'
  LDLᵀ refuses is a valid ``P0`` whose first prediction with nothing to add
  (``F = I``, ``Q = 0``: a step of ``dt = 0`` between two measurements of one
  stamp, ``P' = P0`` exactly) raises ``FilterError`` "predicted covariance is
  not positive definite": 2,202 of 6,996 such ``A Aᵀ`` (2 to 5 rows) NumPy
  takes with normal pivots. The filter's own :attr:`P` meets the same step
  too: an update far more precise than the estimate commits a ``P`` that the
  scaled Cholesky test of its exact path takes and the predict's LDLᵀ refuses
  (104 of 1,325 updates with ``R`` 1e-14 to 1e-40 of ``H P Hᵀ``), and the next
  predict with ``F = I``, ``Q = 0`` raises ``FilterError``.

Both files are another helper's this session (FOUND7: ``_covariance.py``,
``_ekf.py``), so the fixes are left to the lead; see the xfail reasons.
"""

from __future__ import annotations

from functools import partial

import numpy as np
import pytest

from navkit.errors import FilterError
from navkit.estimation import ExtendedKalmanFilter


def _exactly_semidefinite_with_negative_computed_eigenvalue() -> list[np.ndarray]:
    """``G Gᵀ`` of small integer ``G`` of lower rank whose eigvalsh's least value is < 0.

    The products are integers far below 2**53, so computed exactly: every one
    is positive semi-definite (and singular), whatever eigvalsh says.
    """
    rng = np.random.default_rng(5454)
    found = []
    for _ in range(400):
        n = int(rng.integers(2, 6))
        g = rng.integers(-5, 6, size=(n, int(rng.integers(1, n)))).astype(np.float64)
        q = g @ g.T
        if np.any(q) and float(np.linalg.eigvalsh(q)[0]) < 0.0:
            found.append(q)
    return found


def test_an_exactly_semidefinite_q_is_not_blamed_for_a_failed_prediction() -> None:
    products = _exactly_semidefinite_with_negative_computed_eigenvalue()
    if not products:
        pytest.skip("this LAPACK's eigvalsh gives no negative eigenvalue for these products")
    blamed = failed = 0
    for q in products:
        n = q.shape[0]
        ekf = ExtendedKalmanFilter(np.zeros(n), np.eye(n))
        # A model that forgets the state: F P Fᵀ = 0, so P' = Q, singular (which the
        # LDLᵀ check, in float64, may still take: those steps go through).
        try:
            ekf.predict(lambda x: 0.0 * x, np.zeros((n, n)), q)
        except FilterError as exc:
            assert str(exc).startswith("predicted covariance is not positive definite")
            assert ekf.P.tolist() == np.eye(n).tolist()
            failed += 1
            blamed += "pass a positive semi-definite Q" in str(exc)
    if not failed:
        pytest.skip("no prediction failed with these products on this machine")
    # Before (ef1b54e): every one of them (eigvalsh's -1e-16 ... -1e-15) named Q.
    assert blamed == 0, f"{blamed} of {failed} exactly semi-definite Q named"


def test_a_q_with_a_real_negative_eigenvalue_is_still_named() -> None:
    # The other side of the line the xfail above asks for: a float32 Q whose
    # negative eigenvalue is its own (-3.5 of 1e6, inside the float32 tolerance of
    # its largest entry, 9.1e5) is named, also when it is not diagonal (a rotation
    # of diag(-3.5, 1e6) computed in float32).
    c, s = np.float32(np.cos(0.3)), np.float32(np.sin(0.3))
    r = np.array([[c, -s], [s, c]], dtype=np.float32)
    q = r @ np.diag(np.array([-3.5, 1e6], dtype=np.float32)) @ r.T
    least = float(np.linalg.eigvalsh(q.astype(np.float64))[0])
    assert -4.0 < least < -3.0
    ekf = ExtendedKalmanFilter([0.0, 0.0], np.eye(2))
    with pytest.raises(FilterError, match=r"\(Q, .* negative eigenvalue, -3\.\d+"):
        ekf.predict(lambda x: x, np.eye(2), q)


# FRESH's finding: the docstring (54bec22) said the filter's P "is always a valid P0";
# it says now "while its entries stay within 1e100" (the lead, review 54): a filter
# rebuilt from a P past that is refused by name, not taken.
@pytest.mark.parametrize("case", ["unstable model", "largest Q"])
def test_a_filter_rebuilt_from_its_own_p_beyond_1e100(case: str) -> None:
    if case == "unstable model":
        # x' = 1.5 x, never observed: P grows by 2.25 a step, past 1e100 after 284.
        ekf = ExtendedKalmanFilter([1.0], [[1.0]])
        for _ in range(300):
            ekf.predict(lambda x: 1.5 * x, [[1.5]], [[1e-6]])
    else:
        ekf = ExtendedKalmanFilter([0.0, 0.0], np.eye(2) * 1e99)
        ekf.predict(lambda x: x, np.eye(2), np.eye(2) * 1e100)  # Q at its largest
    assert np.isfinite(ekf.P).all() and float(np.max(ekf.P)) > 1e100
    with pytest.raises(ValueError, match=r"P0 entries must have magnitude <= 1e\+100"):
        ExtendedKalmanFilter(ekf.x, ekf.P)
    doc = " ".join((ExtendedKalmanFilter.__doc__ or "").split())
    assert "is a valid ``P0`` while its entries stay within 1e100" in doc


def _taken_by_numpy_not_by_the_kernels() -> list[np.ndarray]:
    """Exactly singular ``A Aᵀ`` (tall ``A``) that NumPy's Cholesky takes and the LDLᵀ does not."""
    from navkit.estimation._covariance import ldl_positive_definite

    rng = np.random.default_rng(54)
    found = []
    for _ in range(300):
        n = int(rng.integers(2, 6))
        a = rng.normal(size=(n, n - 1))
        p = a @ a.T
        p = 0.5 * p + 0.5 * p.T
        try:
            lower = np.linalg.cholesky(p)
        except np.linalg.LinAlgError:
            continue
        if float(np.min(np.diag(lower))) ** 2 >= 2.2250738585072014e-308 and not (
            ldl_positive_definite(p)
        ):
            found.append(p)
    return found


@pytest.mark.xfail(
    strict=True,
    reason=(
        "FRESH (review 54), handed over: a P0 that NumPy's Cholesky takes and the kernels' "
        "LDLᵀ refuses (54bec22 takes either) is accepted, and the first predict with F = I, "
        "Q = 0 (P' = P0 exactly) raises FilterError; refuse such a P0 in the constructor "
        "(the filter's own check decides) or let the step keep it"
    ),
)
def test_a_p0_the_constructor_takes_survives_a_step_that_adds_nothing() -> None:
    matrices = _taken_by_numpy_not_by_the_kernels()
    if not matrices:
        pytest.skip("this LAPACK's Cholesky and the LDLᵀ agree on these matrices")
    refused = 0
    for p0 in matrices:
        n = p0.shape[0]
        try:
            ekf = ExtendedKalmanFilter(np.zeros(n), p0)
        except ValueError:
            continue  # refused as P0: consistent
        try:
            ekf.predict(lambda x: x, np.eye(n), np.zeros((n, n)))
        except FilterError:
            refused += 1
            continue
        assert ekf.P.tolist() == p0.tolist()
    assert refused == 0, (
        f"{refused} of {len(matrices)} accepted P0 refused by a step adding nothing"
    )


@pytest.mark.xfail(
    strict=True,
    reason=(
        "FRESH (review 54), handed over: after an update far more precise than the "
        "estimate (the exact path, checked by the scaled Cholesky test _is_covariance), "
        "P may fail the predict's LDLᵀ, and a predict with F = I, Q = 0 then raises "
        "FilterError: the filter's two checks of a committed P disagree (the class notes "
        "warn that a near-singular P may make a later step fail, but this step copies P)"
    ),
)
def test_the_filters_own_p_survives_a_step_that_adds_nothing() -> None:
    from navkit.estimation._covariance import ldl_positive_definite

    rng = np.random.default_rng(2)
    met = refused = 0
    for _ in range(600):
        n = int(rng.integers(2, 5))
        a = rng.normal(size=(n, n))
        p0 = a @ a.T + 0.1 * np.eye(n)
        ekf = ExtendedKalmanFilter(np.zeros(n), p0)
        m = int(rng.integers(1, n))
        h = rng.normal(size=(m, n))
        r = np.diag(np.diag(h @ p0 @ h.T) * 10.0 ** rng.uniform(-40, -14, size=m))
        try:
            ekf.update(np.zeros(m), partial(np.matmul, h), h, r)
        except FilterError:
            continue
        if ldl_positive_definite(ekf.P):
            continue
        met += 1
        p = ekf.P.copy()
        try:
            ekf.predict(lambda x: x, np.eye(n), np.zeros((n, n)))
        except FilterError:
            refused += 1
            continue
        assert ekf.P.tolist() == p.tolist()
    if not met:
        pytest.skip("no update committed a P the LDLᵀ refuses on this machine")
    assert refused == 0, (
        f"{refused} of {met} of the filter's own P refused by a step adding nothing"
    )
