"""Validation helpers specific to estimation: covariance matrices, variances, index lists (private).

Documented ranges of :mod:`navkit.estimation`: every covariance entry and every
variance has a magnitude of at most :data:`MAX_COVARIANCE`; a measurement
variance given as a scalar is at least :data:`MIN_VARIANCE`.
"""

from __future__ import annotations

import math
import numbers
from collections.abc import Iterable
from typing import Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

from navkit._shared.types import FloatArray
from navkit._shared.validation import SMALLEST_POSITIVE, as_float_array, finite_float, unpack

__all__ = [
    "MAX_COVARIANCE",
    "MIN_VARIANCE",
    "check_magnitude",
    "covariance",
    "index_tuple",
    "ldl_positive_definite",
    "negative_eigenvalue_note",
    "variance",
]

# Relative tolerance for symmetry and semi-definiteness checks of user matrices.
_REL_TOL = 1e-9
# The same for a matrix given in float32 (every entry a float32 value): a product
# such as J S Jᵀ computed in float32 is asymmetric, and a rank-deficient G Q Gᵀ
# indefinite, by up to about 2 float32 epsilons of its largest entry (measured
# for n = 2 to 15); 64 of them (7.6e-6) leave room for larger sums and still
# refuse any matrix that is not symmetric by intent.
_FLOAT32_REL_TOL = 64.0 * float(np.finfo(np.float32).eps)

#: Largest magnitude of a covariance entry or a variance (units squared): a standard
#: deviation of 1e50 leaves 200 orders of magnitude of headroom for the products
#: of a filter step, far beyond any physical uncertainty.
MAX_COVARIANCE = 1e100
#: Smallest scalar measurement variance: keeps 1/variance far from overflow.
MIN_VARIANCE = 1e-100


def variance(value: Any, name: str) -> float:
    """Return ``value`` as a float in [MIN_VARIANCE, MAX_COVARIANCE] or raise naming ``name``."""
    out = finite_float(value, name)
    if not MIN_VARIANCE <= out <= MAX_COVARIANCE:
        raise ValueError(
            f"{name} must be in [{MIN_VARIANCE:g}, {MAX_COVARIANCE:g}], got {out}"
            + not_given_hint(np.array([out]), drop="skip that reading")
        )
    return out


def not_given_hint(values: FloatArray, drop: str = "drop those rows") -> str:
    """A hint for an out-of-range variance message where ``values`` hold -1 or 0 ("" if neither).

    ROS messages mark a covariance "not given" by -1 in its first entry (REP 145,
    ``sensor_msgs/Imu``) and "unknown" by all zeros (``sensor_msgs/Imu``), and the
    bag readers keep those rows as recorded: passed on as variances, they are out
    of range for that reason. A planar user reads the yaw variance from entry
    ``[2, 2]`` or ``[8]``, which is 0 in both kinds of row. ``drop``: what to
    leave out, the rows of a stream or, for one measurement's variance, that
    reading (a scalar update has no rows to drop).
    """
    if np.any(values == -1.0):
        return f" (-1 marks a covariance not given in ROS messages, REP 145: {drop})"
    if np.any(values == 0.0):
        return (
            " (0 may be a ROS message's covariance of all zeros, which marks it unknown"
            f" (sensor_msgs/Imu): assume a variance or {drop})"
        )
    return ""


def check_magnitude(arr: FloatArray, name: str) -> None:
    """Raise naming ``name`` if an entry of ``arr`` exceeds :data:`MAX_COVARIANCE` in magnitude."""
    if arr.size and float(np.max(np.abs(arr))) > MAX_COVARIANCE:
        # The value exactly (repr): ``:g`` rounds one just past the limit to "1e+100".
        raise ValueError(
            f"{name} entries must have magnitude <= {MAX_COVARIANCE:g}, "
            f"got {float(np.max(np.abs(arr)))!r}"
        )


def covariance(value: ArrayLike, name: str, n: int, *, semidefinite: bool = False) -> FloatArray:
    """Return ``value`` as a symmetric (n, n) float64 covariance or raise naming ``name``.

    Positive definiteness is required unless ``semidefinite`` (process noise may
    be zero on some states), with LDLᵀ pivots of at least the smallest normal
    float (as the filters' kernels need). Tiny asymmetry from rounding is averaged out:
    up to 1e-9 of the largest entry, or 64 float32 epsilons (7.6e-6) of it for a
    matrix whose entries are all float32 values (a float32 array, or one computed
    in float32 and stored as float64, as a driver may fill a ROS covariance),
    whose own rounding is that coarse, unless none of them looks rounded: each
    an integer of at most 2²⁴ (which float32 arithmetic does not round) or a
    decimal of at most 6 significant digits (the float32 of one, or the float64:
    a matrix typed by hand, ``[[1e6, 2.5], [3.5, 1e6]]`` or ``np.float32([[1e6,
    0.1], [0.2, 1e6]])``, whose asymmetry is intent; see :func:`_float32_rounded`);
    the same tolerance bounds a negative
    eigenvalue when ``semidefinite``, a negative diagonal entry included (a float32
    ``T Q Tᵀ`` of a noise of lower rank has one, whose exact value is 0, about half
    the time; :func:`negative_eigenvalue_note` names the matrix when a step it was
    added to fails). Entries must have magnitude <= :data:`MAX_COVARIANCE`.

    Examples
    --------
    >>> import numpy as np
    >>> P = np.float32([[0.5, 0.1], [0.1000001, 0.2]])  # symmetric to float32 rounding
    >>> covariance(P, "P0", 2)
    array([[0.5       , 0.10000005],
           [0.10000005, 0.2       ]])
    >>> covariance(P.astype(np.float64) + 1e-12, "P0", 2)  # float64: 1e-9 of 0.5
    Traceback (most recent call last):
    ...
    ValueError: P0 must be symmetric
    """
    arr = as_float_array(value, name, shape=(n, n))
    check_magnitude(arr, name)
    scale = max(float(np.max(np.abs(arr))), 1e-300)
    # The float32 tolerance is looked for only where the strict one refuses (the
    # answer is the same, and an exactly symmetric matrix pays no test of its values).
    tol = _REL_TOL * scale
    loose: bool | None = None
    if np.max(np.abs(arr - arr.T)) > tol:
        loose = _float32_rounded(arr)
        if not loose or np.max(np.abs(arr - arr.T)) > _FLOAT32_REL_TOL * scale:
            raise ValueError(f"{name} must be symmetric")
    original = arr
    # 0.5*a + 0.5*b equals 0.5*(a + b) bit for bit and never overflows.
    arr = np.asarray(0.5 * arr + 0.5 * arr.T, dtype=np.float64)
    if semidefinite and n:
        least = float(np.linalg.eigvalsh(arr)[0])
        if least < -tol:
            if loose is None:
                loose = _float32_rounded(original)
            if not loose or least < -_FLOAT32_REL_TOL * scale:
                raise ValueError(f"{name} must be positive semi-definite")
    else:
        try:
            lower = np.linalg.cholesky(arr)
        except np.linalg.LinAlgError:
            lower = None
        # The kernels take a matrix as positive definite only if the pivots of its
        # LDLᵀ factorisation (the squared Cholesky diagonal) are normal floats, whose
        # reciprocals are finite: NumPy accepts a variance of 1e-320, which would pass
        # here and fail the filter's first step.
        if lower is None:
            pivot = math.nan
        else:
            pivot = float(np.min(np.diag(lower))) ** 2 if n else SMALLEST_POSITIVE
        # Near singular, NumPy's Cholesky (another order of operations) may refuse a
        # matrix the filter's own checks accept, and an ExtendedKalmanFilter refused its
        # own P as P0 (its second pivot 2.2e-16, LAPACK's 0.0; 80 of 1,197 updates with
        # R 1e-16 to 1e-40 of P; review 53, REUSE's finding): such a matrix is taken if
        # one of those checks takes it.
        if not pivot >= SMALLEST_POSITIVE and not _filter_takes(arr):
            if lower is None:
                raise ValueError(f"{name} must be positive definite")
            raise ValueError(
                f"{name} must be positive definite with LDLᵀ pivots of at least "
                f"{SMALLEST_POSITIVE!r} (a normal float), got a pivot of {pivot!r}"
            )
    return arr


#: Largest matrix :func:`_filter_takes` factorises in Python (about 0.05 s at 200);
#: beyond, the kernel itself (compiled on first need, O(n³) in Python took seconds).
_LDL_MAX_N = 200


def _filter_takes(a: FloatArray) -> bool:
    """Whether an ExtendedKalmanFilter's checks of a covariance it commits take ``a``.

    Its kernels' LDLᵀ factorisation (:func:`ldl_positive_definite` up to
    :data:`_LDL_MAX_N` rows, the kernel itself beyond), or the scaled Cholesky
    test of its exact updates.
    """
    # numba's, when first needed
    from navkit.estimation._ekf_kernels import _is_covariance, is_positive_definite

    n = a.shape[0]
    if n <= _LDL_MAX_N:
        taken = ldl_positive_definite(a)
    else:
        # Beyond the replay's rows too: an EKF of 201 states refused its own P as P0
        # (12 of 88 after an update with R 1e-20 of P; review 53, FRESH3).
        work = np.empty((n, n), dtype=np.float64)
        inv_d = np.empty(n, dtype=np.float64)
        taken = is_positive_definite(np.array(a, dtype=np.float64, order="C"), work, inv_d)
    return taken or _is_covariance(a)


def ldl_positive_definite(a: FloatArray) -> bool:
    """Whether the filters' LDLᵀ check takes the symmetric ``a`` as positive definite.

    The operations of ``_ekf_kernels._positive_definite`` in their order (the
    lower triangle read; every pivot a normal float), in Python: for the matrices
    NumPy's Cholesky refuses or finds a subnormal pivot in, so that whatever
    :class:`~navkit.estimation.ExtendedKalmanFilter` commits as its covariance
    (checked so) is a valid ``P0``. O(n³) Python operations: a 200 x 200 matrix
    takes about 0.05 s.

    Examples
    --------
    >>> import numpy as np
    >>> p = np.array([[1.2295186115074588, 1.1701889166820183],
    ...               [1.1701889166820183, 1.113722141258639]])
    >>> ldl_positive_definite(p)  # second pivot 2.2e-16 (LAPACK's Cholesky: 0.0)
    True
    >>> ldl_positive_definite(np.array([[1.0, 1.0], [1.0, 1.0]]))
    False
    """
    rows = a.tolist()
    n = len(rows)
    work = [[0.0] * n for _ in range(n)]
    inv_d = [0.0] * n
    for i in range(n):
        wi = work[i]
        for j in range(i):
            t = rows[i][j]
            wj = work[j]
            for k in range(j):
                t -= wi[k] * wj[k]
            wi[j] = t  # L[i, j] d[j], made L[i, j] below
        d = rows[i][i]
        for k in range(i):
            w = wi[k]
            lk = w * inv_d[k]
            d -= w * lk
            wi[k] = lk
        if not SMALLEST_POSITIVE <= d < math.inf:
            return False
        inv_d[i] = 1.0 / d
    return True


def negative_eigenvalue_note(matrix: FloatArray, name: str) -> str:
    """Why a filter step that added the semi-definite ``matrix`` may have failed ("" if not).

    :func:`covariance` with ``semidefinite`` accepts a matrix whose least
    eigenvalue is negative within its rounding tolerance (a float32 ``G Q Gᵀ``
    of a noise of lower rank is indefinite so, by up to tens of float32
    epsilons of its largest entry: a diagonal entry whose exact value is 0
    comes out as low as -62 of them). Added to a covariance smaller than that
    eigenvalue it leaves one that is not positive definite: the filter's error
    then names ``name`` and its least eigenvalue here. A least eigenvalue within
    ``4 n`` float64 epsilons of the largest is ``eigvalsh``'s own rounding of an
    exactly semi-definite matrix (an integer ``G Gᵀ``), not named.

    Examples
    --------
    >>> import numpy as np
    >>> negative_eigenvalue_note(np.diag([-7.5, 1e6]), "Q")
    ' (Q, accepted as positive semi-definite to its rounding, has a negative eigenvalue, -7.5, ...'
    >>> negative_eigenvalue_note(np.eye(2), "Q")
    ''
    """
    if not matrix.size:
        return ""
    eigenvalues = np.linalg.eigvalsh(matrix)
    least = float(eigenvalues[0])
    # eigvalsh's own error: the zero eigenvalue of an exactly semi-definite
    # singular matrix (an integer G Gᵀ) comes out as -1e-16 of its largest, at most
    # 0.64 n eps of it for n from 2 to 12 (review 54, FRESH): not the matrix's own.
    largest = float(np.max(np.abs(eigenvalues)))
    own_error = 4.0 * matrix.shape[0] * float(np.finfo(np.float64).eps) * largest
    if not least < -own_error:
        return ""
    return (
        f" ({name}, accepted as positive semi-definite to its rounding, has a negative"
        f" eigenvalue, {least:.6g}, which the step added: pass a positive semi-definite"
        f" {name}, e.g. with that eigenvalue set to 0)"
    )


def _float32_rounded(arr: FloatArray) -> bool:
    """Whether ``arr`` holds float32 values as float32 arithmetic rounds them.

    Every entry a float32 value, and at least one of them neither an integer of
    at most 2²⁴ (exact in float32 arithmetic, which rounds none of their
    products and sums) nor a short decimal (see :func:`_short_decimals`): a
    matrix whose every entry is one of those was typed, and its asymmetry is
    intent (a float64 ``P0 [[1e6, 2.5], [3.5, 1e6]]`` was averaged to 3.0, where
    its integer twin was refused; review 53, FRESH). Products computed in
    float32 keep the tolerance: of 50,436 asymmetric ones (``J S Jᵀ`` and ``J (S
    Jᵀ)``, 2 to 4 rows, random, rounded and rotation ``J``, variances from 1e-4
    to 1.2e7), 55 look typed and are refused, 41 of them, refused before too,
    all integers (every float32 value from 2²³ to 2²⁴ is one), 1 all short
    decimals (review 54, FOUND7).

    Told by the values, not the dtype: the filters convert a float32 matrix to
    float64 before checking it, and a float32 result stored in a float64 array
    (a ROS message's covariance) is as coarse.

    Examples
    --------
    >>> import numpy as np
    >>> _float32_rounded(np.array([[0.5, 0.1], [0.1, 0.5]]))  # 0.1: no float32 value
    False
    >>> _float32_rounded(np.float32([[0.5, 0.1], [0.1000001, 0.2]]))  # 7 digits
    True
    >>> _float32_rounded(np.float32([[1e6, 3.0], [4.0, 1e6]]))  # integers: exact in float32
    False
    >>> _float32_rounded(np.array([[1e6, 2.5], [3.5, 1e6]]))  # typed: short decimals
    False
    """
    # Entries beyond float32's range become inf, not equal: not float32 values.
    with np.errstate(over="ignore"):
        if not np.array_equal(arr.astype(np.float32), arr):
            return False
    # Integers as large as a float32 is exact for: their products and sums in float32
    # are exact too, so their asymmetry is not rounding (a float64 P0 [[1e6, 3], [4,
    # 1e6]] was averaged to 3.5; review 52, FRESH).
    if arr.size and not _typed(float(arr.flat[arr.size - 1])):
        return True  # one entry that looks rounded is enough (a float32 product's do)
    exact = (arr == np.round(arr)) & (np.abs(arr) <= 2.0**24)
    return not bool(np.all(exact | _short_decimals(arr)))


def _typed(value: float) -> bool:
    """Whether the float32 value ``value`` is an integer of at most 2²⁴ or a short decimal.

    One entry of :func:`_float32_rounded`'s test, as its arrays compute it (a
    first look that spares them for a float32 product, whose entries are not).

    Examples
    --------
    >>> _typed(2.5), _typed(16777216.0), _typed(float(np.float32(0.1))), _typed(1e6 + 0.0625)
    (True, True, True, False)
    """
    if value == round(value) and abs(value) <= 2.0**24:
        return True
    size = abs(value)  # not 0 (an integer)
    step = 10.0 ** (math.floor(math.log10(size)) - (_SHORT_DIGITS - 1))
    return float(np.float32(round(size / step) * step)) == size


#: Significant digits of a decimal taken as typed: C's FLT_DIG, the most that any
#: decimal keeps through float32 (as ``navkit._shared.float32`` reads a resolution).
_SHORT_DIGITS = 6


def _short_decimals(arr: FloatArray) -> NDArray[np.bool_]:
    """Which float32 values of ``arr`` stand for a decimal of at most 6 significant digits.

    Those whose shortest float32 decimal (``np.format_float_scientific(np.float32(v),
    unique=True)``) has at most :data:`_SHORT_DIGITS` digits: the float32 of such a
    decimal, typed in float32 (``np.float32(0.1)``) or in float64 (2.5, 0.0078125,
    exact in both), and 0. A value that float32 arithmetic rounded rarely is one:
    its 24 significant bits make a decimal of 7 to 9 digits. Computed with
    arrays: each value rounded to 6 significant digits (in float64, exact enough:
    a value that stands for such a decimal lies within 6e-8 of it in units of its
    sixth digit) and compared after rounding that to float32.

    Examples
    --------
    >>> import numpy as np
    >>> _short_decimals(np.float32([0.1, 2.5, 0.1000001, 1e-5, 0.0, -123456.0, 1234567.0]))
    array([ True,  True, False,  True,  True,  True, False])
    """
    values = np.abs(np.asarray(arr, dtype=np.float64)).ravel()
    out = values == 0.0
    some = values[~out]
    with np.errstate(over="ignore", under="ignore"):
        step = 10.0 ** (np.floor(np.log10(some)) - (_SHORT_DIGITS - 1))
        nearest = np.rint(some / step) * step
        out[~out] = nearest.astype(np.float32).astype(np.float64) == some
    shaped: NDArray[np.bool_] = out.reshape(np.shape(arr))
    return shaped


def index_tuple(indices: Iterable[Any], name: str, n: int) -> tuple[int, ...]:
    """Validate distinct integer indices into a length-``n`` vector."""
    try:
        items = unpack(indices, name)
    except TypeError:
        raise TypeError(f"{name} must be a sequence of integer indices") from None
    out: list[int] = []
    for item in items:
        if isinstance(item, bool) or not isinstance(item, numbers.Integral):
            raise TypeError(f"{name} must hold integers, got {item!r}")
        if not 0 <= int(item) < n:
            raise ValueError(f"{name} index {int(item)} is out of range for length {n}")
        out.append(int(item))
    if len(set(out)) != len(out):
        raise ValueError(f"{name} holds duplicate indices: {out}")
    return tuple(out)
