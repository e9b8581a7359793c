"""numba kernels: repulsive forces summed over the beams of a laser scan (private).

Beam ``k`` with range ``r`` and direction ``(cos_t[k], sin_t[k])`` puts an obstacle
at ``r·(cos, sin)`` in the sensor frame; the robot sits at the origin, so the
unit vector from the obstacle to the robot is ``-(cos, sin)`` and the distance is
``r`` itself. That polar form needs no square root or trigonometry in the loop:
the public layer passes tables of the beam cosines and sines.

A beam counts when ``range_min <= r < range_max`` (which also rejects NaN and
±inf), the definition of :meth:`navkit.mapping.LaserScan.valid_mask`.

The loops are branch-free (a beam that does not count is replaced by one whose
contribution is exactly zero) and compiled with the ``reassoc`` and ``contract``
fast-math flags only, so LLVM can split the two sums over SIMD lanes. That is
about 3x faster than a branching loop on 3,600 beams, whose mispredictions
dominate; the reordered sum differs from a sequential one by a few ulps of the
largest term. The NaN/inf flags are deliberately not set: NaN ranges must keep
comparing false.

The kernels allocate nothing and are compiled without numba's reference
counting (``NO_REFCOUNT``): with it, every call wrapped each array argument
(then four) in a MemInfo (a malloc, atomic reference counts, a free), about
0.4 µs of a 1.1 µs call on 360 beams. For the same reason the public call
passes the beam directions as one (2, N) table (:func:`khatib_beam_force_into`).
"""

from __future__ import annotations

import math
from collections.abc import Callable
from typing import Any, cast

import numpy as np

from navkit._shared.jit import NO_REFCOUNT, typed_njit

__all__ = [
    "khatib_beam_force",
    "khatib_beam_force_into",
    "khatib_entry",
    "mounted_khatib_force",
    "mounted_piecewise_force",
    "piecewise_beam_force",
]

_FASTMATH = {"reassoc", "contract"}


@typed_njit(**NO_REFCOUNT, fastmath=_FASTMATH)
def khatib_beam_force(
    ranges: np.ndarray,
    cos_t: np.ndarray,
    sin_t: np.ndarray,
    range_min: float,
    range_max: float,
    k_rep: float,
    influence_radius: float,
    min_distance: float,
) -> tuple[float, float]:
    """Sum of Khatib forces ``k_rep(1/r - 1/d0)/r²·(-cos, -sin)`` over beams with ``r <= d0``.

    ``d0`` is Khatib's symbol for ``influence_radius``. Ranges below
    ``min_distance`` (< d0) count as ``min_distance``, so every term is finite.
    """
    d0 = influence_radius
    inv_d0 = 1.0 / d0
    inv_min = 1.0 / min_distance
    fx = 0.0
    fy = 0.0
    for k in range(ranges.shape[0]):
        r = ranges[k]
        # r > 0: a zero range (range_min == 0) has no direction and contributes nothing.
        use = (r >= range_min) & (r < range_max) & (r <= d0) & (r > 0.0)
        # A beam that does not count is moved to d0, where its force is exactly 0.
        inv = 1.0 / (r if use else d0)
        # 1/max(r, min_distance), written as a select on the inverse (which
        # vectorises, where max with its NaN rule does not).
        inv = inv if inv < inv_min else inv_min
        w = k_rep * (inv - inv_d0) * inv * inv
        fx -= w * cos_t[k]
        fy -= w * sin_t[k]
    return fx, fy


@typed_njit(**NO_REFCOUNT, fastmath=_FASTMATH)
def khatib_beam_force_into(
    ranges: np.ndarray,
    directions: np.ndarray,
    range_min: float,
    range_max: float,
    k_rep: float,
    influence_radius: float,
    min_distance: float,
    out: np.ndarray,
) -> None:
    """:func:`khatib_beam_force` with the beam table ``directions`` (2, N), written into ``out``.

    ``directions`` holds the cosines in row 0 and the sines in row 1: one
    array argument instead of two is one fewer to unbox (the public call,
    through :func:`khatib_entry`, about 15-25 ns faster on 360 beams) and to
    type (through the dispatcher, 40-50 ns). Its rows are the arrays
    :func:`khatib_beam_force` reads, so the sum is the same loop and gives
    the same bits. The public call
    returns a new array: filling one here costs less than boxing a tuple
    and converting it.
    """
    fx, fy = khatib_beam_force(
        ranges, directions[0], directions[1], range_min, range_max, k_rep, influence_radius,
        min_distance,
    )  # fmt: skip
    out[0] = fx
    out[1] = fy


def khatib_entry() -> Callable[..., None]:
    """Compiled entry of :func:`khatib_beam_force_into` for a scan's arrays, skipping dispatch.

    Calling a numba dispatcher first types every argument to pick the compiled
    version (about 0.15 µs for three arrays, a third of the kernel's time on
    360 beams); the entry returned here is that version itself, compiled (or loaded
    from the cache) now. It checks nothing: the caller guarantees C-contiguous,
    aligned float64 ranges (N,) and directions (2, N) (writable or not: they
    are only read), five floats and a writable C-contiguous float64 ``out`` of
    length 2; anything else reads or writes the wrong memory.

    Examples
    --------
    >>> beams = np.array([0.5])
    >>> out = np.empty(2)
    >>> khatib_entry()(beams, np.array([[1.0], [0.0]]), 0.1, 10.0, 1.0, 1.0, 1e-9, out)
    >>> out
    array([-4., -0.])
    """
    # The dispatcher first: it loads numba (holding a Ctrl-C back until numba is
    # fully imported), which the import below would do unguarded.
    dispatcher: Any = khatib_beam_force_into
    if not hasattr(dispatcher, "compile"):  # NUMBA_DISABLE_JIT=1: a plain function
        return cast(Callable[..., None], dispatcher)
    from numba import types  # here: importing this module must not import numba

    # Read-only C-contiguous float64 arrays: a LaserScan's ranges and the cached table.
    signature = (
        types.Array(types.float64, 1, "C", readonly=True),
        types.Array(types.float64, 2, "C", readonly=True),
        *(types.float64,) * 5,
        types.Array(types.float64, 1, "C"),
    )
    return cast(Callable[..., None], dispatcher.compile(signature))


@typed_njit(**NO_REFCOUNT, fastmath=_FASTMATH)
def piecewise_beam_force(
    ranges: np.ndarray,
    cos_t: np.ndarray,
    sin_t: np.ndarray,
    range_min: float,
    range_max: float,
    delta: float,
    beta: float,
    obstacle_radius: float,
    spread: float,
) -> tuple[float, float]:
    """Sum of piecewise repulsions over the beams.

    A beam at range ``r`` pushes with ``δ`` inside ``obstacle_radius`` and with
    ``β(spread + obstacle_radius - r)`` out to ``spread + obstacle_radius``.
    """
    r_obs = obstacle_radius
    reach = spread + r_obs
    fx = 0.0
    fy = 0.0
    for k in range(ranges.shape[0]):
        r = ranges[k]
        use = (r >= range_min) & (r < range_max) & (r <= reach) & (r > 0.0)
        w = (delta if r < r_obs else beta * (reach - r)) if use else 0.0
        fx -= w * cos_t[k]
        fy -= w * sin_t[k]
    return fx, fy


# A scan from a sensor mounted at (mount_x, mount_y), turned by an angle whose cosine
# and sine are mount_cos and mount_sin: beam k ends at the point
# p = mount + r·(cos(θ_k + θ_m), sin(θ_k + θ_m)) of the robot frame, the angle sum
# expanded on the beam tables. The robot sits at the origin: the distance is |p|,
# no longer the range, and the push is along -p/|p|. A beam that does not count
# (invalid, a zero range, |p| = 0 or beyond the reach) gets a zero weight and a
# finite divisor instead of a branch, as above.


@typed_njit(**NO_REFCOUNT, no_cpython_wrapper=True, fastmath=_FASTMATH)
def _beam_end(
    r: float,
    cos_t: float,
    sin_t: float,
    range_min: float,
    range_max: float,
    mount_x: float,
    mount_y: float,
    mount_cos: float,
    mount_sin: float,
) -> tuple[float, float, float, bool]:
    """A beam's end point ``(px, py)`` in the robot frame, its distance ``|p|`` and validity.

    An invalid beam (out of range, or a zero range) ends at the mount.
    """
    valid = (r >= range_min) & (r < range_max) & (r > 0.0)
    rr = r if valid else 0.0
    px = mount_x + rr * (cos_t * mount_cos - sin_t * mount_sin)
    py = mount_y + rr * (sin_t * mount_cos + cos_t * mount_sin)
    return px, py, math.hypot(px, py), valid


@typed_njit(**NO_REFCOUNT, fastmath=_FASTMATH)
def mounted_khatib_force(
    ranges: np.ndarray,
    cos_t: np.ndarray,
    sin_t: np.ndarray,
    range_min: float,
    range_max: float,
    k_rep: float,
    influence_radius: float,
    min_distance: float,
    mount_x: float,
    mount_y: float,
    mount_cos: float,
    mount_sin: float,
) -> tuple[float, float]:
    """Khatib's ``k_rep(1/d - 1/d0)/d²·(-p/d)`` summed over the end points ``p``, ``d = |p| <= d0``.

    ``d`` below ``min_distance`` pushes as ``min_distance`` (along ``-p/d``).
    """
    d0 = influence_radius
    inv_d0 = 1.0 / d0
    inv_min = 1.0 / min_distance
    fx = 0.0
    fy = 0.0
    for k in range(ranges.shape[0]):
        px, py, d, valid = _beam_end(
            ranges[k], cos_t[k], sin_t[k], range_min, range_max,
            mount_x, mount_y, mount_cos, mount_sin,
        )  # fmt: skip
        use = valid & (d <= d0) & (d > 0.0)
        dd = d if use else d0
        inv = 1.0 / dd
        near = inv if inv < inv_min else inv_min
        w = k_rep * (near - inv_d0) * near * near if use else 0.0
        fx -= w * (px * inv)
        fy -= w * (py * inv)
    return fx, fy


@typed_njit(**NO_REFCOUNT, fastmath=_FASTMATH)
def mounted_piecewise_force(
    ranges: np.ndarray,
    cos_t: np.ndarray,
    sin_t: np.ndarray,
    range_min: float,
    range_max: float,
    delta: float,
    beta: float,
    obstacle_radius: float,
    spread: float,
    mount_x: float,
    mount_y: float,
    mount_cos: float,
    mount_sin: float,
) -> tuple[float, float]:
    """The piecewise push (``δ`` inside ``obstacle_radius``, then linear) from end points ``p``."""
    r_obs = obstacle_radius
    reach = spread + r_obs
    fx = 0.0
    fy = 0.0
    for k in range(ranges.shape[0]):
        px, py, d, valid = _beam_end(
            ranges[k], cos_t[k], sin_t[k], range_min, range_max,
            mount_x, mount_y, mount_cos, mount_sin,
        )  # fmt: skip
        use = valid & (d <= reach) & (d > 0.0)
        inv = 1.0 / (d if use else 1.0)
        w = (delta if d < r_obs else beta * (reach - d)) if use else 0.0
        fx -= w * (px * inv)
        fy -= w * (py * inv)
    return fx, fy
