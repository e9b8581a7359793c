"""Attractive potential fields: a pull toward one goal point ``goal_xy``.

The soccer robot's paraboloid, cone and their sigmoid blend, and the
omnidirectional LiDAR robot's piecewise-linear attraction (Goodrich's form).
Parameter names follow navkit's vocabulary; each class states the paper's
symbol of every parameter (e.g. the papers' ``rad_thr`` is ``threshold_radius``,
the piecewise ``r`` is ``goal_radius`` and ``s`` is ``spread``).
"""

from __future__ import annotations

import dataclasses
import functools
import weakref
from collections.abc import Callable, Sequence
from dataclasses import dataclass
from types import MappingProxyType
from typing import TYPE_CHECKING, Any, TypeVar

import numpy as np
from numpy.typing import ArrayLike

from navkit._shared.frozen import extra_state, frozen_setattr
from navkit._shared.types import FloatArray
from navkit._shared.validation import as_float_array
from navkit.planning.reactive._limits import gain, length
from navkit.planning.reactive._potential_field import (
    PotentialField,
    _frozen,
    _goal,
    _offsets,
    _restore,
    _unit,
)

__all__ = [
    "AttractiveField",
    "BlendedAttraction",
    "ConicAttraction",
    "ParaboloidAttraction",
    "PiecewiseAttraction",
]

_A = TypeVar("_A", bound="AttractiveField")


def _check(
    field: object,
    gains: tuple[str, ...],
    lengths: tuple[str, ...] = (),
    zero_lengths: tuple[str, ...] = (),
) -> None:
    """Validate float parameters in place: gains in [1e-12, 1e12], lengths in [1e-6, 1e6] m.

    ``zero_lengths`` are lengths that may also be 0.
    """
    for name in gains:
        object.__setattr__(field, name, gain(getattr(field, name), name))
    for name in lengths:
        object.__setattr__(field, name, length(getattr(field, name), name))
    for name in zero_lengths:
        object.__setattr__(field, name, length(getattr(field, name), name, allow_zero=True))


def _moved(field: _A, goal: FloatArray) -> _A:
    """A copy of ``field`` (as :func:`copy.copy` makes) with ``goal``, read-only, as its goal.

    What a subclass adds beyond the dataclass fields (its ``__dict__``, its own
    slots: a parameter set in its ``__init__``) is kept too: the controller
    calls :meth:`AttractiveField.with_goal` every step, and a field rebuilt
    from its dataclass fields alone lost it (``AttributeError`` in its ``_force``).
    """
    kind = type(field)
    out = object.__new__(kind)
    fields = dataclasses.fields(field)
    # navkit's own fields hold their dataclass fields alone: not looked for there
    # (3 µs a controller step, 5 % of it).
    if kind not in _OWN_FIELDS:
        extra = extra_state(field, skip=[f.name for f in fields])
        if extra is not None:
            instance, slots = extra
            if instance:
                # A cached_property's value was computed for the old goal: dropped,
                # it is computed again for the new one when read.
                cached = _cached_names(kind)
                out.__dict__.update(
                    {k: v for k, v in instance.items() if k not in cached} if cached else instance
                )
            for name, value in slots.items():
                object.__setattr__(out, name, value)
    # The fields last: a dataclass subclass without slots keeps its own in __dict__ too.
    for f in fields:
        object.__setattr__(out, f.name, getattr(field, f.name))
    object.__setattr__(out, "goal_xy", goal)
    return out


def _cached_names(kind: type) -> frozenset[str]:
    """The names of ``kind``'s :func:`functools.cached_property` attributes (found once)."""
    names = _CACHED.get(kind)
    if names is None:
        # The first class of the MRO defining a name decides what it is.
        found: dict[str, bool] = {}
        for klass in kind.__mro__:
            for name, value in vars(klass).items():
                found.setdefault(name, isinstance(value, functools.cached_property))
        names = frozenset(name for name, cached in found.items() if cached)
        _CACHED[kind] = names
    return names


#: Per class, its cached_property names: looked up at every controller step.
_CACHED: weakref.WeakKeyDictionary[type, frozenset[str]] = weakref.WeakKeyDictionary()


@frozen_setattr
@dataclass(frozen=True, slots=True, eq=False, repr=False)
class AttractiveField(PotentialField):
    """Base of the attractive fields: a field pulling toward one goal point.

    Subclasses add their parameters as keyword-only fields; :meth:`with_goal`
    moves any of them to a new goal (the controller does so every step).

    Parameters
    ----------
    goal_xy : array_like, shape (2,)
        Goal ``(x, y)`` in metres (world frame), ``|x|, |y| <= 1e9``; stored
        as a read-only copy.

    Examples
    --------
    >>> fields = [ParaboloidAttraction((0.0, 0.0)), ConicAttraction((0.0, 0.0))]
    >>> [isinstance(field, AttractiveField) for field in fields]
    [True, True]
    >>> [float(field.with_goal((1.0, 0.0)).force([0.0, 0.0])[0, 0]) for field in fields]
    [2.0, 1.0]
    """

    goal_xy: FloatArray

    __setstate__ = _restore

    if TYPE_CHECKING:
        # The generated ``__init__`` takes the goal as array_like (``__post_init__``
        # converts it), also in a subclass that inherits it; this tells type checkers
        # so, at no runtime cost.
        def __init__(self, goal_xy: ArrayLike) -> None: ...

    def __post_init__(self) -> None:
        object.__setattr__(self, "goal_xy", _goal(self.goal_xy))

    def with_goal(self: _A, goal_xy: ArrayLike) -> _A:
        """Return the same field (all parameters kept) centred on a new goal ``(x, y)``.

        Only the goal is validated: the parameters were checked when ``self``
        was built. What a subclass adds beyond its dataclass fields (its
        ``__dict__``, its own slots) is kept as :func:`copy.copy` keeps it, but
        for the values of its :func:`functools.cached_property` attributes,
        which the new field computes again when they are read. Any other value
        of its own that depends on the goal must be computed from ``goal_xy``
        where it is used, not stored.

        Parameters
        ----------
        goal_xy : array_like, shape (2,)
            New goal ``(x, y)`` in metres (world frame), ``|x|, |y| <= 1e9``.

        Returns
        -------
        AttractiveField
            A new field of the same class as ``self``, with the same parameters.

        Raises
        ------
        TypeError, ValueError
            ``goal_xy`` not two finite real numbers within ±1e9 m.

        Examples
        --------
        >>> ConicAttraction((0.0, 0.0), m=2.0).with_goal((1.0, 1.0)).goal_xy
        array([1., 1.])
        """
        return _moved(self, _goal(goal_xy))

    def _with_checked_goal(self: _A, goal_xy: FloatArray) -> _A:
        """:meth:`with_goal` for a goal its caller has checked, without checking it again.

        The controller's constructor path (it moves the goal every step, having
        checked it already): ``goal_xy`` must be a float64 array of shape (2,)
        holding finite values within ±1e9 m. It is stored as a read-only copy.
        """
        return _moved(self, _frozen(goal_xy))


@frozen_setattr
@dataclass(frozen=True, slots=True, eq=False, repr=False, kw_only=True)
class ParaboloidAttraction(AttractiveField):
    """Elliptic paraboloid attraction ``U = K_att·c·((x - xd)²/a² + (y - yd)²/b²)``.

    The near-goal limit (σ → 0) of :class:`BlendedAttraction`. The parameters
    keep the paper's symbols.

    Parameters
    ----------
    goal_xy : array_like, shape (2,)
        Goal ``q_d = (xd, yd)`` in metres.
    k_att : float, default 1.0
        Attraction gain ``K_att``, in ``[1e-12, 1e12]``.
    c : float, default 1.0
        Curvature, in ``[1e-12, 1e12]``.
    a, b : float, default 1.0
        Ellipse semi-axes along x and y (m), in ``[1e-6, 1e6]``.

    Raises
    ------
    ValueError
        A parameter out of its range, a goal beyond ±1e9 m or not finite.
    TypeError
        A parameter that is not a real number (or is a bool).

    Examples
    --------
    >>> field = ParaboloidAttraction((1.0, 0.0), k_att=2.0, a=1.0, b=2.0)
    >>> field.potential([[0.0, 2.0]])
    array([4.])
    >>> field.force([[0.0, 2.0]])
    array([[ 4., -2.]])
    """

    k_att: float = 1.0
    c: float = 1.0
    a: float = 1.0
    b: float = 1.0

    # Slot names before 0123de4 (see _restore).
    _renamed_fields = MappingProxyType({"goal": "goal_xy"})
    __setstate__ = _restore

    if TYPE_CHECKING:
        # The generated ``__init__`` takes the arrays as array_like (``__post_init__``
        # converts them); this signature tells type checkers so, at no runtime cost.
        def __init__(
            self,
            goal_xy: ArrayLike,
            *,
            k_att: float = ...,
            c: float = ...,
            a: float = ...,
            b: float = ...,
        ) -> None: ...

    def __post_init__(self) -> None:
        AttractiveField.__post_init__(self)
        _check(self, ("k_att", "c"), ("a", "b"))

    def _scales(self) -> tuple[float, float]:
        kc = self.k_att * self.c
        return kc / (self.a * self.a), kc / (self.b * self.b)

    def _potential(self, pts: FloatArray) -> FloatArray:
        sx, sy = self._scales()
        diff = pts - self.goal_xy
        out: FloatArray = sx * diff[:, 0] ** 2 + sy * diff[:, 1] ** 2
        return out

    def _force(self, pts: FloatArray) -> FloatArray:
        sx, sy = self._scales()
        diff = pts - self.goal_xy
        return np.stack((0.0 - 2.0 * sx * diff[:, 0], 0.0 - 2.0 * sy * diff[:, 1]), axis=1)


@frozen_setattr
@dataclass(frozen=True, slots=True, eq=False, repr=False, kw_only=True)
class ConicAttraction(AttractiveField):
    """Linear cone attraction ``U = m·(d - rad_thr)·U_trans``, ``d = ‖q - q_d‖``.

    The far-from-goal limit (σ → 1) of :class:`BlendedAttraction`: the force has
    the constant magnitude ``m·U_trans`` everywhere except at the goal itself,
    where the cone's tip has no gradient and the force is defined as zero. The
    paper's ``rad_thr`` is ``threshold_radius`` here.

    Parameters
    ----------
    goal_xy : array_like, shape (2,)
        Goal ``q_d = (xd, yd)`` in metres.
    m : float, default 1.0
        Gradient (speed), in ``[1e-12, 1e12]``.
    u_trans : float, default 1.0
        Translation constant ``U_trans``, in ``[1e-12, 1e12]``.
    threshold_radius : float, default 0.0
        Offset ``rad_thr`` of the cone (m), in ``[0, 1e6]``; shifts the
        potential only.

    Raises
    ------
    ValueError
        A parameter out of its range, a goal beyond ±1e9 m or not finite.
    TypeError
        A parameter that is not a real number (or is a bool).

    Examples
    --------
    >>> ConicAttraction((0.0, 0.0), m=0.5).force([[3.0, 4.0]])
    array([[-0.3, -0.4]])
    """

    m: float = 1.0
    u_trans: float = 1.0
    threshold_radius: float = 0.0

    # Slot names before 0123de4 (see _restore).
    _renamed_fields = MappingProxyType({"goal": "goal_xy", "rad_thr": "threshold_radius"})
    __setstate__ = _restore

    if TYPE_CHECKING:
        # The generated ``__init__`` takes the arrays as array_like (``__post_init__``
        # converts them); this signature tells type checkers so, at no runtime cost.
        def __init__(
            self,
            goal_xy: ArrayLike,
            *,
            m: float = ...,
            u_trans: float = ...,
            threshold_radius: float = ...,
        ) -> None: ...

    def __post_init__(self) -> None:
        AttractiveField.__post_init__(self)
        _check(self, ("m", "u_trans"), zero_lengths=("threshold_radius",))

    def _potential(self, pts: FloatArray) -> FloatArray:
        _, d = _offsets(pts, self.goal_xy)
        out: FloatArray = self.m * self.u_trans * (d - self.threshold_radius)
        return out

    def _force(self, pts: FloatArray) -> FloatArray:
        diff, d = _offsets(pts, self.goal_xy)
        # ``0.0 - x`` rather than ``-x`` so zero components print as 0, not -0.
        out: FloatArray = 0.0 - self.m * self.u_trans * _unit(diff, d)
        return out


def _with_scipy_special(rebuild: Callable[..., Any], args: tuple[Any, ...]) -> Any:
    """``rebuild(*args)`` after importing scipy.special (see ``BlendedAttraction.__reduce__``)."""
    import scipy.special  # noqa: F401

    return rebuild(*args)


@frozen_setattr
@dataclass(frozen=True, slots=True, eq=False, repr=False, kw_only=True)
class BlendedAttraction(AttractiveField):
    """Paraboloid near the goal blended into a cone far away by a sigmoid.

    In the paper's symbols, with ``d = ‖q - q_d‖`` and
    ``σ(d) = ½[tanh((d - rad_thr)/ω) + 1]``::

        U_par  = K_att·c·((x - xd)²/a² + (y - yd)²/b²)
        U_cone = m·(d - rad_thr)·U_trans
        U      = [1 - σ(d)]·U_par + σ(d)·U_cone

    and the force is the full gradient, blending terms included::

        -∇U = -[1 - σ]·∇U_par - σ·m·U_trans·∇d - σ'(d)·(U_cone - U_par)·∇d,
        σ'(d) = (2/ω)·σ·(1 - σ),  ∇d = (q - q_d)/d.

    σ and 1 - σ are evaluated as ``expit(±2(d - rad_thr)/ω)`` (the same function
    as the tanh form) so neither loses precision where it is tiny. At the goal
    itself ``∇d`` is undefined (the cone's tip); its terms are taken as zero there.

    Names: ``goal_xy`` is ``q_d``, ``k_att`` is ``K_att``, ``threshold_radius`` is
    ``rad_thr``, ``width`` is ``ω`` and ``u_trans`` is ``U_trans``; ``c``, ``a``,
    ``b`` and ``m`` keep the paper's symbols.

    Parameters
    ----------
    goal_xy : array_like, shape (2,)
        Goal ``(xd, yd)`` in metres.
    k_att, c : float, default 1.0
        Paraboloid gain and curvature, in ``[1e-12, 1e12]``.
    a, b : float, default 1.0
        Ellipse semi-axes (m), in ``[1e-6, 1e6]``.
    threshold_radius : float, default 0.5
        Distance ``rad_thr`` (m) at which σ = ½, in ``[0, 1e6]``.
    width : float, default 0.15
        Blending width ω (m), in ``[1e-6, 1e6]``: σ goes from 0.12 to 0.88 over
        ``threshold_radius ± ω``.
    m : float, default 1.0
        Cone gradient (speed), in ``[1e-12, 1e12]``.
    u_trans : float, default 1.0
        Translation constant, in ``[1e-12, 1e12]``.

    Notes
    -----
    The blend is not automatically free of spurious minima. At ``d = rad_thr``
    the cone term is 0 while the paraboloid is ``K_att·c·rad_thr²/a²`` (circular
    case, ``a = b``), so the ``σ'(U_cone - U_par)`` term pulls the robot outward
    with ``K_att·c·rad_thr²/(2ω·a²)``; when that exceeds the inward
    ``K_att·c·rad_thr/a² + m·U_trans/2`` the field has a ring of local minima just
    outside ``rad_thr`` (narrow widths, large ``rad_thr``). Inside, σ(0) > 0 and the
    cone's negative offset displace the minimum from the goal, to first order by
    ``σ(0)·m·U_trans·(2·rad_thr/ω - 1)·a²/(2·K_att·c)``. The defaults
    (``K_att = c = a = b = m = U_trans = 1``, ``rad_thr = 0.5``, ``ω = 0.15``)
    pull toward the goal everywhere beyond 4 mm, where the minimum lies (3.75 mm);
    with ``rad_thr = 0.5`` a width of 0.1 has the ring at 0.55 m, and widths of 0.3
    and 0.5 a minimum 4.6 cm from the goal (widths between them up to 5.5 cm, near
    0.38). Check a chosen parameter set with
    :func:`sample_field` or a radial profile (``tests/control/test_blending_widths.py``
    compares widths in closed loop).

    Raises
    ------
    ValueError
        A parameter out of its range, a goal beyond ±1e9 m or not finite.
    TypeError
        A parameter that is not a real number (or is a bool).

    Examples
    --------
    >>> field = BlendedAttraction((0.0, 0.0), threshold_radius=1.0, width=0.1)
    >>> far = field.force([[30.0, 40.0]])          # the cone: magnitude m·U_trans
    >>> bool(np.allclose(far, [[-0.6, -0.8]]))
    True
    >>> near = field.force([[0.1, 0.0]])           # the paraboloid: -2·K_att·c·x/a²
    >>> bool(np.allclose(near, [[-0.2, 0.0]]))
    True
    """

    k_att: float = 1.0
    c: float = 1.0
    a: float = 1.0
    b: float = 1.0
    threshold_radius: float = 0.5
    width: float = 0.15
    m: float = 1.0
    u_trans: float = 1.0

    def __reduce__(self) -> tuple[Any, ...]:
        # As __post_init__ does, which a copy unpickled in a fresh process (a sweep's
        # worker) never runs: its first force paid the scipy.special import (0.3 s).
        # Not in __setstate__: the rebuild that copies go through does not call it.
        rebuild, args, *rest = AttractiveField.__reduce__(self)
        return (_with_scipy_special, (rebuild, args), *rest)

    # Slot names before 0123de4 (see _restore).
    _renamed_fields = MappingProxyType({"goal": "goal_xy", "rad_thr": "threshold_radius"})

    def __setstate__(self, state: Sequence[Any]) -> None:
        _restore(self, state)
        import scipy.special  # noqa: F401  # older pickles: see __reduce__

    if TYPE_CHECKING:
        # The generated ``__init__`` takes the arrays as array_like (``__post_init__``
        # converts them); this signature tells type checkers so, at no runtime cost.
        def __init__(
            self,
            goal_xy: ArrayLike,
            *,
            k_att: float = ...,
            c: float = ...,
            a: float = ...,
            b: float = ...,
            threshold_radius: float = ...,
            width: float = ...,
            m: float = ...,
            u_trans: float = ...,
        ) -> None: ...

    def __post_init__(self) -> None:
        AttractiveField.__post_init__(self)
        _check(self, ("k_att", "c", "m", "u_trans"), ("a", "b", "width"), ("threshold_radius",))
        # scipy.special (0.1-0.3 s to import) here, not in the first force of a control loop.
        import scipy.special  # noqa: F401

    def sigma(self, d: ArrayLike) -> FloatArray:
        """Blending function σ(d) = ½[tanh((d - rad_thr)/ω) + 1] for distances ``d`` (m).

        Parameters
        ----------
        d : array_like
            Distances from the goal, m, finite; any shape.

        Returns
        -------
        ndarray
            New array of σ values in [0, 1], the shape of ``d`` (0-d for a
            scalar: an array always, as :meth:`potential` and :meth:`force`
            return): 0 near the goal (the paraboloid), 1 far from it (the cone),
            ½ at ``threshold_radius``.

        Raises
        ------
        TypeError
            ``d`` not real numbers.
        ValueError
            ``d`` holding NaN or an infinity.

        Examples
        --------
        >>> field = BlendedAttraction((0.0, 0.0), threshold_radius=1.0)
        >>> field.sigma([1.0])
        array([0.5])
        >>> field.sigma(1.0)
        array(0.5)
        """
        from scipy.special import expit

        dist = as_float_array(d, "d")
        # Into an array of its own: for a 0-d d, expit (a ufunc) returns a NumPy scalar.
        out: FloatArray = np.empty_like(dist)
        # Far beyond the blend the argument may overflow to ±inf: σ is then 1 or 0.
        with np.errstate(over="ignore"):
            expit(2.0 * (dist - self.threshold_radius) / self.width, out=out)
        return out

    def _terms(
        self, pts: FloatArray
    ) -> tuple[FloatArray, FloatArray, FloatArray, FloatArray, FloatArray, FloatArray]:
        from scipy.special import expit

        diff, d = _offsets(pts, self.goal_xy)
        z = 2.0 * (d - self.threshold_radius) / self.width
        sig = expit(z)
        one_minus = expit(-z)
        kc = self.k_att * self.c
        u_par = kc * (diff[:, 0] ** 2 / self.a**2 + diff[:, 1] ** 2 / self.b**2)
        u_cone = self.m * self.u_trans * (d - self.threshold_radius)
        return diff, d, sig, one_minus, u_par, u_cone

    def _potential(self, pts: FloatArray) -> FloatArray:
        _, _, sig, one_minus, u_par, u_cone = self._terms(pts)
        out: FloatArray = one_minus * u_par + sig * u_cone
        return out

    def _force(self, pts: FloatArray) -> FloatArray:
        diff, d, sig, one_minus, u_par, u_cone = self._terms(pts)
        kc2 = 2.0 * self.k_att * self.c
        grad_par = np.stack((kc2 * diff[:, 0] / self.a**2, kc2 * diff[:, 1] / self.b**2), axis=1)
        dsigma = (2.0 / self.width) * sig * one_minus
        radial = sig * self.m * self.u_trans + dsigma * (u_cone - u_par)
        grad = one_minus[:, None] * grad_par + radial[:, None] * _unit(diff, d)
        out: FloatArray = 0.0 - grad
        return out


@frozen_setattr
@dataclass(frozen=True, slots=True, eq=False, repr=False, kw_only=True)
class PiecewiseAttraction(AttractiveField):
    """Piecewise-linear attraction of the omnidirectional LiDAR robot (Goodrich's form).

    In the paper's symbols, with ``d`` the distance to the goal, the force points
    at the goal with magnitude ``0`` for ``d < r``, ``α(d - r)`` for
    ``r <= d <= s + r`` and ``α·s`` beyond. The paper writes ``α`` for the last
    piece, which is dimensionally inconsistent and makes the force jump at
    ``d = s + r``; ``α·s`` (Goodrich's potential-field tutorial) is the continuous
    form used here. The potential is its integral, ``0``, ``½α(d - r)²`` and
    ``½α·s² + α·s(d - s - r)``.

    Names: ``alpha`` is ``α``, ``goal_radius`` is ``r`` and ``spread`` is ``s``
    (Goodrich's name for the width of the linear zone).

    Parameters
    ----------
    goal_xy : array_like, shape (2,)
        Goal ``(xd, yd)`` in metres.
    alpha : float, default 1.0
        Gain ``α`` (1/s for a velocity field), in ``[1e-12, 1e12]``.
    goal_radius : float, default 0.0
        Goal radius ``r`` (m) inside which there is no force, in ``[0, 1e6]``.
    spread : float, default 1.0
        Width ``s`` of the linear zone (m), in ``[1e-6, 1e6]``.

    Raises
    ------
    ValueError
        A parameter out of its range, a goal beyond ±1e9 m or not finite.
    TypeError
        A parameter that is not a real number (or is a bool).

    Examples
    --------
    >>> field = PiecewiseAttraction((0.0, 0.0), alpha=2.0, goal_radius=0.5, spread=1.0)
    >>> field.force([[0.25, 0.0], [1.0, 0.0], [10.0, 0.0]])
    array([[ 0.,  0.],
           [-1.,  0.],
           [-2.,  0.]])
    """

    alpha: float = 1.0
    goal_radius: float = 0.0
    spread: float = 1.0

    # Slot names before 0123de4 (see _restore).
    _renamed_fields = MappingProxyType({"goal": "goal_xy", "r": "goal_radius", "s": "spread"})
    __setstate__ = _restore

    if TYPE_CHECKING:
        # The generated ``__init__`` takes the arrays as array_like (``__post_init__``
        # converts them); this signature tells type checkers so, at no runtime cost.
        def __init__(
            self,
            goal_xy: ArrayLike,
            *,
            alpha: float = ...,
            goal_radius: float = ...,
            spread: float = ...,
        ) -> None: ...

    def __post_init__(self) -> None:
        AttractiveField.__post_init__(self)
        _check(self, ("alpha",), ("spread",), ("goal_radius",))

    def _potential(self, pts: FloatArray) -> FloatArray:
        _, d = _offsets(pts, self.goal_xy)
        a, r, s = self.alpha, self.goal_radius, self.spread
        lin = np.clip(d - r, 0.0, s)
        out: FloatArray = 0.5 * a * lin**2 + a * s * np.maximum(d - s - r, 0.0)
        return out

    def _force(self, pts: FloatArray) -> FloatArray:
        diff, d = _offsets(pts, self.goal_xy)
        mag = self.alpha * np.clip(d - self.goal_radius, 0.0, self.spread)
        out: FloatArray = 0.0 - mag[:, None] * _unit(diff, d)
        return out


#: navkit's own fields, whose state is their dataclass fields alone (not a module
#: name test: a user's subclass may live in a package named ``navkit...``).
_OWN_FIELDS = frozenset(
    {AttractiveField, ParaboloidAttraction, ConicAttraction, BlendedAttraction, PiecewiseAttraction}
)
