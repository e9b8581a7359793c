"""Planar poses (SE(2)) and body twists."""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass, fields
from typing import Any, Never

import numpy as np
from numpy.typing import ArrayLike

from navkit._shared.angles import wrap_float
from navkit._shared.frozen import frozen_setattr, reduce_record, restore_read_only
from navkit._shared.types import FloatArray
from navkit._shared.validation import (
    as_float_array,
    as_points,
    finite_float,
    has_array_protocol,
    is_ndarray,
)

__all__ = ["Pose2D", "Twist2D", "as_pose", "as_twist"]


@frozen_setattr
@dataclass(frozen=True, slots=True)
class Pose2D:
    """A planar pose: position (m) and heading (rad) of a frame in the world.

    The heading is wrapped to (-π, π] on construction. A pose maps points from its
    own (robot) frame to the world frame: ``p_world = R(theta) @ p_robot + (x, y)``.

    Parameters
    ----------
    x, y : float
        Position in metres: any finite real numbers.
    theta : float, default 0.0
        Heading in radians, counter-clockwise from the world x axis: any finite
        real number.

    Raises
    ------
    TypeError
        A field that is not a real number (complex, strings and booleans are
        refused).
    ValueError
        A field that is NaN or infinite. The operations below raise a
        ``ValueError`` naming their argument when a result would overflow
        float64 (coordinates beyond ±1.8e308), never return one that is not
        finite; a finite result is returned even when a partial sum of it
        (``x + cos(theta) * other.x``, say) would overflow.

    Examples
    --------
    >>> import math
    >>> robot = Pose2D(1.0, 2.0, math.pi / 2)
    >>> robot.transform_points([1.0, 0.0]).round(12)
    array([[1., 3.]])
    >>> robot.compose(Pose2D(1.0, 0.0, 0.0))
    Pose2D(x=1.0, y=3.0, theta=1.5707963267948966)
    >>> f"{robot:.2f}"  # a format spec applies to each field
    'Pose2D(x=1.00, y=2.00, theta=1.57)'
    """

    x: float
    y: float
    theta: float = 0.0

    # NumPy defers binary operators to the pose: ``row @ pose`` reaches __rmatmul__
    # (it raised NumPy's "matmul: Input operand 1 does not have enough dimensions")
    # and ``row == pose`` is False (it compared each element with the pose). Not a
    # field (no annotation); np.asarray(pose) is still a 0-d object array. An object
    # array (of poses) is still compared element by element: see __eq__.
    __array_ufunc__ = None

    def __post_init__(self) -> None:
        object.__setattr__(self, "x", finite_float(self.x, "x"))
        object.__setattr__(self, "y", finite_float(self.y, "y"))
        # Plain Python (bit for bit the kernel's wrap): constructing a pose, as module
        # constants and defaults do at import, must not start numba.
        object.__setattr__(self, "theta", wrap_float(finite_float(self.theta, "theta")))

    def __reduce__(self) -> tuple[Any, ...]:
        # Copies and pickles keep what a subclass adds (its __dict__ or slots),
        # which the slotted dataclass's own state drops. A plain pose rebuilds
        # from its fields (theta is already wrapped: unchanged): copies as quick
        # and pickles as small as before, which older navkit versions load too.
        if type(self) is Pose2D:
            return Pose2D, (self.x, self.y, self.theta)
        return reduce_record(self, ())

    def __setstate__(self, state: Any) -> None:
        # A subclass's own attributes, restored after the rebuild (reduce_record);
        # the field values of a pickle older than __reduce__.
        restore_read_only(self, state, ())

    def __format__(self, format_spec: str) -> str:
        return _formatted(self, format_spec)

    def __eq__(self, other: object) -> Any:
        # The dataclass's comparison (fields, same class), and an object array's
        # elements compared with the pose (``pose in np.array([p, q])``): with
        # __array_ufunc__ = None NumPy leaves that to the pose (review 35).
        if other.__class__ is self.__class__:
            return self.x == other.x and self.y == other.y and self.theta == other.theta
        return _elementwise(np.equal, other, self)

    def __ne__(self, other: object) -> Any:
        if other.__class__ is self.__class__:
            return not (self.x == other.x and self.y == other.y and self.theta == other.theta)
        return _elementwise(np.not_equal, other, self)

    def compose(self, other: Pose2D | ArrayLike) -> Pose2D:
        """Return ``self ⊕ other``: ``other`` (given in this pose's frame) in the world frame.

        Parameters
        ----------
        other : Pose2D or array_like, shape (3,)
            A pose, or ``[x, y, theta]``, expressed in this pose's frame.

        Returns
        -------
        Pose2D
            ``other`` in the world frame.

        Raises
        ------
        TypeError
            If ``other`` is neither a Pose2D nor a sequence of three numbers.
        ValueError
            If ``other`` has non-finite values, or the result would overflow.

        Examples
        --------
        >>> import math
        >>> Pose2D(1.0, 0.0, math.pi / 2).compose([1.0, 0.0, 0.0]).y
        1.0
        """
        o = other if type(other) is Pose2D else as_pose(other, "other")
        # Plain Python, the same operations as the kernels' compose_scalar: composing
        # poses must not start numba (and a call into a kernel costs more here).
        c = math.cos(self.theta)
        s = math.sin(self.theta)
        x = self.x + c * o.x - s * o.y
        y = self.y + s * o.x + c * o.y
        if not (x - x == 0.0 and y - y == 0.0):
            # A partial sum (x + c*dx) can overflow where the result does not: the
            # same operations an eighth of the size cannot (see _SHRINK).
            dx = o.x * _SHRINK
            dy = o.y * _SHRINK
            x, y = _grow(
                self.x * _SHRINK + c * dx - s * dy,
                self.y * _SHRINK + s * dx + c * dy,
                "other",
                "composing the poses",
            )
        return Pose2D(x, y, wrap_float(self.theta + o.theta))

    def __matmul__(self, other: Pose2D | ArrayLike) -> Pose2D:
        """``a @ b`` is ``a.compose(b)``; ``b`` may be a sequence ``[x, y, theta]``.

        Raises
        ------
        TypeError, ValueError
            As :meth:`compose`.
        """
        return self.compose(other)

    def __rmatmul__(self, left: Pose2D | ArrayLike) -> Pose2D:
        """``left @ pose`` for ``left`` a sequence or array row ``[x, y, theta]``.

        ``as_pose(left) ⊕ pose``: an odometry pose kept as an array row (a row
        of ``BagOdometry.poses``) composes with a pose as a ``Pose2D`` does,
        ``odometry_row @ mount``.

        Raises
        ------
        TypeError, ValueError
            ``left`` not three finite real numbers (as :func:`as_pose`, naming
            the left operand).

        Examples
        --------
        >>> import numpy as np
        >>> np.array([1.0, 0.0, np.pi / 2]) @ Pose2D(1.0, 0.0, 0.0)
        Pose2D(x=1.0, y=1.0, theta=1.5707963267948966)
        """
        return as_pose(left, "left operand of @").compose(self)

    def __add__(self, other: Never) -> Any:
        """No sum: ``pose + row`` raises a ``TypeError`` that says what to write.

        A pose is a transform, not a vector of three numbers. With an array, a
        list, a tuple or a record the ``TypeError`` names the ways to move a
        pose; with anything else Python's own (``NotImplemented``).

        Raises
        ------
        TypeError
            Always, as Python's ``+`` does for unsupported operands.

        Examples
        --------
        >>> Pose2D(1.0, 2.0, 0.0) + [0.5, 0.0, 0.0]
        Traceback (most recent call last):
        ...
        TypeError: unsupported operand type(s) for +: 'Pose2D' and 'list' (a Pose2D is ...
        """
        return _no_sum(self, other, reflected=False)

    def __radd__(self, other: Never) -> Any:
        """``row + pose``: a ``TypeError`` as :meth:`__add__`'s.

        NumPy left ``row + pose`` to the pose (``__array_ufunc__ = None``) and,
        with no ``__radd__``, Python fell back to the array's sequence
        concatenation: "Concatenation operation is not implemented for NumPy
        arrays, use np.concatenate() instead".

        Raises
        ------
        TypeError
            Always, as Python's ``+`` does for unsupported operands.

        Examples
        --------
        >>> import numpy as np
        >>> np.array([0.5, 0.0, 0.0]) + Pose2D(1.0, 2.0, 0.0)
        Traceback (most recent call last):
        ...
        TypeError: unsupported operand type(s) for +: 'numpy.ndarray' and 'Pose2D' (a Pose2D is ...
        """
        return _no_sum(self, other, reflected=True)

    def inverse(self) -> Pose2D:
        """Return the inverse transform, so that ``p.compose(p.inverse())`` is the identity.

        Returns
        -------
        Pose2D
            The world frame expressed in this pose's frame: heading ``-theta``
            (wrapped), position ``-R(theta)ᵀ (x, y)`` in metres.

        Raises
        ------
        ValueError
            If the result would overflow (coordinates near ±1.8e308).

        Examples
        --------
        >>> Pose2D(1.0, 0.0, 0.0).inverse()
        Pose2D(x=-1.0, y=-0.0, theta=-0.0)
        """
        c = math.cos(self.theta)
        s = math.sin(self.theta)
        x = -c * self.x - s * self.y
        y = s * self.x - c * self.y
        if not (x - x == 0.0 and y - y == 0.0):
            raise _overflow("pose", "inverting the pose")
        return Pose2D(x, y, -self.theta)

    def relative_to(self, frame: Pose2D | ArrayLike) -> Pose2D:
        """Express this pose in the frame of ``frame``: ``frame.inverse() ⊕ self``.

        Computed directly as ``R(frame.theta)ᵀ (self.xy - frame.xy)`` and heading
        ``wrap(self.theta - frame.theta)``, so the result is accurate to the
        rounding of the distance between the poses, not of their coordinates
        (at UTM coordinates, 1e6 m, composing with ``frame.inverse()`` would be
        about 1e-9 m off).

        Parameters
        ----------
        frame : Pose2D or array_like, shape (3,)
            The reference pose (world frame), or ``[x, y, theta]``.

        Returns
        -------
        Pose2D
            This pose in ``frame``'s frame (m, m, rad).

        Raises
        ------
        TypeError
            If ``frame`` is neither a Pose2D nor a sequence of three numbers.
        ValueError
            If ``frame`` has non-finite values, or the result would overflow.

        Examples
        --------
        >>> Pose2D(2.0, 1.0, 0.0).relative_to(Pose2D(1.0, 1.0, 0.0))
        Pose2D(x=1.0, y=0.0, theta=0.0)
        >>> Pose2D(2.0, 1.0, 0.0).relative_to((1.0, 1.0, 0.0))
        Pose2D(x=1.0, y=0.0, theta=0.0)
        """
        ref = as_pose(frame, "frame")
        c = math.cos(ref.theta)
        s = math.sin(ref.theta)
        # Rotate the difference of the positions, not frame.inverse() ⊕ self: the
        # inverse's translation is as large as the coordinates and cancels against
        # self's, which at UTM sizes (1e6 m) costs about 1e-9 m.
        dx = self.x - ref.x
        dy = self.y - ref.y
        x = c * dx + s * dy
        y = c * dy - s * dx
        if not (x - x == 0.0 and y - y == 0.0):
            # The difference can overflow where the rotated result does not.
            dx = self.x * _SHRINK - ref.x * _SHRINK
            dy = self.y * _SHRINK - ref.y * _SHRINK
            x, y = _grow(c * dx + s * dy, c * dy - s * dx, "frame", "expressing the pose in frame")
        return Pose2D(x, y, wrap_float(self.theta - ref.theta))

    def transform_points(self, points_xy: ArrayLike) -> FloatArray:
        """Map points from this pose's frame to the world frame.

        Parameters
        ----------
        points_xy : array_like, shape (N, 2) or (2,)
            ``(x, y)`` points in metres in the pose's frame.

        Returns
        -------
        ndarray, shape (N, 2)
            New array of world points.

        Raises
        ------
        TypeError, ValueError
            ``points_xy`` not finite real points, or world points that would
            overflow float64.

        Examples
        --------
        >>> import math
        >>> robot = Pose2D(1.0, 2.0, math.pi / 2)
        >>> robot.transform_points([[1.0, 0.0], [0.0, 1.0]]).round(12)
        array([[1., 3.],
               [0., 2.]])
        >>> robot.transform_points([1.0, 0.0]).shape
        (1, 2)
        """
        pts = as_points(points_xy, "points_xy")
        c = math.cos(self.theta)
        s = math.sin(self.theta)
        # Underflow too: a product of normal values may be subnormal (yaw 1e-307, a
        # point 1 cm off), NumPy's default answer under any caller's np.seterr.
        with np.errstate(over="ignore", invalid="ignore", under="ignore"):
            out = _rotate_shift(pts, c, s, self.x, self.y)
            if not np.isfinite(out).all():
                # As in compose: a partial sum may overflow where the point does not.
                # Only there: the other points stay those of a call of their own.
                small = _rotate_shift(pts * _SHRINK, c, s, self.x * _SHRINK, self.y * _SHRINK)
                out = np.where(np.isfinite(out), out, small / _SHRINK)
        if not np.isfinite(out).all():
            raise _overflow("points_xy", "transforming the points")
        return out

    def as_array(self) -> FloatArray:
        """Return ``[x, y, theta]`` as a new float64 array.

        Returns
        -------
        ndarray, shape (3,)
            ``[x, y, theta]`` in m, m, rad.

        Examples
        --------
        >>> Pose2D(1.0, 2.0, 0.5).as_array()
        array([1. , 2. , 0.5])
        """
        return np.array([self.x, self.y, self.theta], dtype=np.float64)

    @classmethod
    def from_array(cls, values: ArrayLike) -> Pose2D:
        """Build a pose from ``[x, y, theta]``.

        Parameters
        ----------
        values : array_like, shape (3,)
            ``[x, y, theta]`` in m, m, rad: finite real numbers (theta is wrapped
            to (-π, π]).

        Returns
        -------
        Pose2D
            The pose.

        Raises
        ------
        TypeError, ValueError
            ``values`` not three finite real numbers.

        Examples
        --------
        >>> Pose2D.from_array([1.0, 2.0, 0.5])
        Pose2D(x=1.0, y=2.0, theta=0.5)
        >>> Pose2D.from_array([0.0, 0.0, 4.0]).theta  # wrapped: 4 - 2π
        -2.2831853071795862
        """
        arr = as_float_array(values, "values", shape=(3,))
        return cls(float(arr[0]), float(arr[1]), float(arr[2]))


@frozen_setattr
@dataclass(frozen=True, slots=True)
class Twist2D:
    """A planar velocity in the robot (body) frame.

    Parameters
    ----------
    vx : float
        Forward velocity, m/s.
    vy : float, default 0.0
        Lateral velocity (to the robot's left), m/s.
    omega : float, default 0.0
        Yaw rate, rad/s, counter-clockwise positive.

    Raises
    ------
    TypeError
        A field that is not a real number (complex, strings and booleans are
        refused).
    ValueError
        A field that is NaN or infinite.

    Examples
    --------
    >>> Twist2D(0.5, 0.0, 0.1).as_array()
    array([0.5, 0. , 0.1])
    """

    vx: float
    vy: float = 0.0
    omega: float = 0.0

    # As Pose2D's: ``array == twist`` is False, not a comparison of each element
    # (but an object array's elements are compared with the twist: see __eq__).
    __array_ufunc__ = None

    def __post_init__(self) -> None:
        object.__setattr__(self, "vx", finite_float(self.vx, "vx"))
        object.__setattr__(self, "vy", finite_float(self.vy, "vy"))
        object.__setattr__(self, "omega", finite_float(self.omega, "omega"))

    def __reduce__(self) -> tuple[Any, ...]:
        # As Pose2D's: a subclass's own attributes survive copies and pickles.
        if type(self) is Twist2D:
            return Twist2D, (self.vx, self.vy, self.omega)
        return reduce_record(self, ())

    def __setstate__(self, state: Any) -> None:
        # As Pose2D's.
        restore_read_only(self, state, ())

    def __format__(self, format_spec: str) -> str:
        return _formatted(self, format_spec)

    def __eq__(self, other: object) -> Any:
        # As Pose2D's.
        if other.__class__ is self.__class__:
            return self.vx == other.vx and self.vy == other.vy and self.omega == other.omega
        return _elementwise(np.equal, other, self)

    def __ne__(self, other: object) -> Any:
        if other.__class__ is self.__class__:
            return not (self.vx == other.vx and self.vy == other.vy and self.omega == other.omega)
        return _elementwise(np.not_equal, other, self)

    def __add__(self, other: Never) -> Any:
        """No sum: ``twist + row`` raises a ``TypeError`` that says what to write.

        As :meth:`Pose2D.__add__`: with an array, a list, a tuple or a record
        the ``TypeError`` says how to add to the fields.

        Raises
        ------
        TypeError
            Always, as Python's ``+`` does for unsupported operands.

        Examples
        --------
        >>> Twist2D(0.5) + Twist2D(0.1)
        Traceback (most recent call last):
        ...
        TypeError: unsupported operand type(s) for +: 'Twist2D' and 'Twist2D' (a Twist2D has ...
        """
        return _no_sum(self, other, reflected=False)

    def __radd__(self, other: Never) -> Any:
        """``row + twist``: a ``TypeError`` as :meth:`__add__`'s (not NumPy's "Concatenation").

        Raises
        ------
        TypeError
            Always, as Python's ``+`` does for unsupported operands.

        Examples
        --------
        >>> [0.1, 0.0, 0.0] + Twist2D(0.5)
        Traceback (most recent call last):
        ...
        TypeError: unsupported operand type(s) for +: 'list' and 'Twist2D' (a Twist2D has ...
        """
        return _no_sum(self, other, reflected=True)

    def as_array(self) -> FloatArray:
        """Return ``[vx, vy, omega]`` as a new float64 array.

        Returns
        -------
        ndarray, shape (3,)
            ``[vx, vy, omega]`` in m/s, m/s, rad/s.

        Examples
        --------
        >>> Twist2D(0.5, 0.0, 0.1).as_array()
        array([0.5, 0. , 0.1])
        """
        return np.array([self.vx, self.vy, self.omega], dtype=np.float64)

    @classmethod
    def from_array(cls, values: ArrayLike) -> Twist2D:
        """Build a twist from ``[vx, vy, omega]``.

        Parameters
        ----------
        values : array_like, shape (3,)
            ``[vx, vy, omega]`` in m/s, m/s, rad/s: finite real numbers.

        Returns
        -------
        Twist2D
            The twist.

        Raises
        ------
        TypeError, ValueError
            ``values`` not three finite real numbers.

        Examples
        --------
        >>> Twist2D.from_array([0.5, 0.0, 0.1])
        Twist2D(vx=0.5, vy=0.0, omega=0.1)
        """
        arr = as_float_array(values, "values", shape=(3,))
        return cls(float(arr[0]), float(arr[1]), float(arr[2]))


def _formatted(record: Pose2D | Twist2D, format_spec: str) -> str:
    """``format(record, spec)``: the record's repr, each field formatted with ``spec``.

    Without it ``f"{pose:.2f}"`` raised ``TypeError`` (object's ``__format__``
    takes no spec); an empty spec gives ``str(record)``, as before.
    """
    if not format_spec:
        return str(record)
    try:
        parts = ", ".join(
            f"{field.name}={format(getattr(record, field.name), format_spec)}"
            for field in fields(record)
        )
    except ValueError as exc:
        raise ValueError(
            f"format spec {format_spec!r} of a {type(record).__name__} must format its "
            f"float fields: {exc}"
        ) from None
    return f"{type(record).__qualname__}({parts})"


# Positions are linear in the coordinates (for fixed headings), so a result can be
# computed an eighth of the size and scaled back, both exactly (powers of two; only
# subnormal parts, far below the rounding of coordinates near 1e308, are rounded).
# At that size no partial sum of x + c*dx - s*dy (|c|, |s| <= 1) overflows unless
# the result itself is beyond ±1.8e308 when scaled back.
_SHRINK = 0.125


def _rotate_shift(pts: FloatArray, c: float, s: float, x: float, y: float) -> FloatArray:
    """``pts @ [[c, s], [-s, c]] + (x, y)``, computed element by element.

    Not with ``@``: BLAS rounds a matrix product differently by its size and by
    CPU (fused multiply-adds in some kernels), so a point would not map to the same
    bits alone as among others (1.7e308 rotated by 45° came out 2.09e292 in a call
    of two points and 2.00e292 alone, on an AMD EPYC's OpenBLAS).
    """
    px = pts[:, 0]
    py = pts[:, 1]
    out: FloatArray = np.empty(pts.shape)
    out[:, 0] = px * c - py * s + x
    out[:, 1] = px * s + py * c + y
    return out


def _grow(x: float, y: float, name: str, what: str) -> tuple[float, float]:
    """``(x, y)`` computed at :data:`_SHRINK` scale back at full size, or the overflow error."""
    x /= _SHRINK
    y /= _SHRINK
    if not (x - x == 0.0 and y - y == 0.0):
        raise _overflow(name, what)
    return x, y


def _overflow(name: str, what: str) -> ValueError:
    return ValueError(f"{name}: {what} overflows float64 (coordinates beyond ±1.8e308)")


def _three(value: Any, name: str, what: str, fields: str) -> tuple[float, float, float]:
    if isinstance(value, (str, bytes)) or not (
        isinstance(value, Sequence)
        or issubclass(type(value), np.ndarray)
        or has_array_protocol(value)
    ):
        kind = type(value).__name__
        raise TypeError(f"{name} must be a {what} or a sequence {fields}, got {kind}")
    try:
        arr = as_float_array(value, name, shape=(3,))
    except ValueError as exc:
        if not _two_numbers(value):
            raise
        # Two numbers: usually a position where a whole pose (or twist) is wanted.
        raise ValueError(f"{exc}: a {what} is {fields}, so give all three") from None
    return float(arr[0]), float(arr[1]), float(arr[2])


def _two_numbers(value: Any) -> bool:
    """Whether ``value`` reads as two numbers (not two poses, not a ragged nesting)."""
    try:
        return bool(np.shape(value) == (2,))
    except ValueError:  # NumPy refuses ragged nested sequences
        return False


def as_pose(value: Pose2D | ArrayLike, name: str = "pose") -> Pose2D:
    """Return ``value`` as a :class:`Pose2D`; a sequence ``[x, y, theta]`` is accepted.

    Every navkit function that takes a pose accepts either form through this
    function (as NumPy functions accept array-likes through ``np.asarray``).

    Parameters
    ----------
    value : Pose2D or array_like, shape (3,)
        A pose, or ``[x, y, theta]`` in m, m, rad.
    name : str, default "pose"
        Argument name used in error messages.

    Returns
    -------
    Pose2D
        ``value`` itself when it already is one.

    Raises
    ------
    TypeError
        Neither a Pose2D nor a numeric sequence.
    ValueError
        Not three finite numbers.

    Examples
    --------
    >>> as_pose([1.0, 2.0, 0.5])
    Pose2D(x=1.0, y=2.0, theta=0.5)
    >>> as_pose("1 2 3")
    Traceback (most recent call last):
    ...
    TypeError: pose must be a Pose2D or a sequence [x, y, theta], got str
    """
    if isinstance(value, Pose2D):
        return value
    return Pose2D(*_three(value, name, "Pose2D", "[x, y, theta]"))


def as_twist(value: Twist2D | ArrayLike, name: str = "twist") -> Twist2D:
    """Return ``value`` as a :class:`Twist2D`; a sequence ``[vx, vy, omega]`` is accepted.

    Parameters
    ----------
    value : Twist2D or array_like, shape (3,)
        A body twist, or ``[vx, vy, omega]`` in m/s, m/s, rad/s.
    name : str, default "twist"
        Argument name used in error messages.

    Returns
    -------
    Twist2D
        ``value`` itself when it already is one.

    Raises
    ------
    TypeError
        Neither a Twist2D nor a numeric sequence.
    ValueError
        Not three finite numbers.

    Examples
    --------
    >>> as_twist((0.5, 0.0, 0.1))
    Twist2D(vx=0.5, vy=0.0, omega=0.1)
    """
    if isinstance(value, Twist2D):
        return value
    return Twist2D(*_three(value, name, "Twist2D", "[vx, vy, omega]"))


_SUM_HINTS = {
    "Pose2D": (
        "a Pose2D is a transform, not a vector: pose @ Pose2D(dx, dy, dtheta) moves it by"
        " (dx, dy) in its own frame and turns it by dtheta;"
        " Pose2D.from_array(pose.as_array() + [dx, dy, dtheta]) adds in the world frame"
    ),
    "Twist2D": (
        "a Twist2D has no arithmetic:"
        " Twist2D.from_array(twist.as_array() + [dvx, dvy, domega]) adds to its fields"
    ),
}


def _no_sum(record: Pose2D | Twist2D, other: object, *, reflected: bool) -> Any:
    """``record + other`` (``other + record`` if ``reflected``): NotImplemented or a TypeError.

    An array, a list, a tuple or a navkit record (what a user adds a pose or a
    twist to, meaning an offset) gets Python's message with a hint; anything
    else is NotImplemented (the other operand may know the sum; if not, Python
    raises its own message). Without this, ``row + pose`` ended in NumPy's
    "Concatenation operation is not implemented for NumPy arrays" and
    ``pose + row`` in "operand 'Pose2D' does not support ufuncs".
    """
    if not (isinstance(other, (list, tuple, Pose2D, Twist2D)) or is_ndarray(other)):
        return NotImplemented
    left, right = (other, record) if reflected else (record, other)
    base = next(k.__name__ for k in type(record).__mro__ if k in (Pose2D, Twist2D))
    raise TypeError(
        f"unsupported operand type(s) for +: {_type_name(left)!r} and"
        f" {_type_name(right)!r} ({_SUM_HINTS[base]})"
    )


def _type_name(value: object) -> str:
    """The operand's type as Python's own operator messages name it ('numpy.ndarray')."""
    kind = type(value)
    return f"numpy.{kind.__name__}" if kind.__module__ == "numpy" else kind.__name__


def _elementwise(compare: np.ufunc, other: object, record: Pose2D | Twist2D) -> Any:
    """``compare`` of each element of an object array with ``record``, else NotImplemented.

    What NumPy computed before ``__array_ufunc__ = None`` (review 34) made it leave
    ``array == pose`` to the pose: a bool array, each element compared with the
    record by its own ``==``. The record goes in a 0-d object array, as NumPy
    held it then (a ufunc refuses the record itself). Anything else (a numeric
    row, a list, a number) is NotImplemented: then not equal.
    """
    if is_ndarray(other) and other.dtype == object:
        held = np.empty((), dtype=object)
        held[()] = record
        return compare(other, held)
    return NotImplemented
