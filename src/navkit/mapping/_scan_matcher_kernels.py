"""numba kernels of Gauss–Newton scan-to-map matching (private).

Plain functions on arrays and scalars compiled with ``cache=True``;
:class:`navkit.mapping.ScanMatcher` validates input before calling them.

The map value is the occupancy probability ``M = 1 / (1 + exp(-l))`` of the
float32 log-odds ``l``, interpolated bilinearly between cell centres (grid
coordinates ``(row, col)`` with integers at cell centres; beyond the edge cells'
centres, in the map's outer half cell and past the edge, the cells beyond the edge
count as unknown, as in a map padded with unknown cells without end). The gradient is the
exact derivative of that interpolant: along columns it weights the row
differences by the *row* fraction and along rows the column differences by the
*column* fraction. (Hector SLAM's ``interpMapValueWithDerivatives`` swaps the
two factors, so its gradient is not the derivative of its own interpolant.)

``exp`` of the cell's log-odds runs in single precision (numba keeps a float32
a float32), everything after it in double. This is deliberate: it makes
:func:`accumulate` about 15-30 % faster, and the error it adds is negligible
(measured against the same kernels computing ``exp`` in float64: ``M`` and its
gradient within 2e-8 per cell, and matched poses of 360-beam scans on a
5 cm office map within 1e-10 m and 3e-11 rad, with the same iteration counts).

* :func:`interpolate_batch`: ``M``, ``∂M/∂row``, ``∂M/∂col`` at many points
  (used by the tests to check the gradient against finite differences);
* :func:`accumulate`: the Gauss–Newton sums ``H = Σ JᵀJ`` and ``g = Σ Jᵀ(1 - M)``
  of a scan at a pose, with the cost ``Σ (1 - M)²`` and ``Σ M``;
* :func:`match_level`: Gauss–Newton iterations on one map level with a step
  clamp, a backtracking line search and a convergence test;
* :func:`correlative_search` (:func:`correlative_search_kernel` with its
  scratch array): the best pose of a grid of rotations and
  translations around a guess (nearest-cell lookups), the start of
  Gauss–Newton when the guess may lie outside its basin.

Examples
--------
>>> import numpy as np
>>> logodds = np.zeros((2, 2), dtype=np.float32)
>>> logodds[:, 1] = np.log(9.0)          # p = 0.9 in the right column
>>> out = np.empty((1, 3))
>>> interpolate_batch(logodds, np.array([[0.5, 0.25]]), out)
>>> out.round(6)                          # M, dM/drow, dM/dcol
array([[0.6, 0. , 0.4]])
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np

from navkit._shared.jit import (
    njit_cached,
    njit_force_inline,
    njit_inline,
    njit_no_refcount,
    njit_released,
)
from navkit._shared.types import KernelInt

__all__ = [
    "STATUS_CONVERGED",
    "STATUS_MAX_ITERATIONS",
    "STATUS_SINGULAR",
    "accumulate",
    "correlative_search",
    "correlative_search_kernel",
    "interpolate_batch",
    "match_level",
]

#: Outcomes of :func:`match_level`.
STATUS_CONVERGED = 0
STATUS_MAX_ITERATIONS = 1
STATUS_SINGULAR = 2

# Backtracking halvings tried before a Gauss–Newton step counts as no progress.
_HALVINGS = 4

# A float32 whose exp overflows float32 (beyond 88.72), so that capping exp's argument
# at it changes no compiled result (a float32 stays a float32 in numba).
_EXP_OVERFLOWS = np.float32(89.0)


# The three map lookups below are compiled once each and inlined by LLVM
# (njit_force_inline): as numba IR-level inlined helpers their bodies were copied,
# typed and lowered again at each of their sites (_probability eight times over in
# accumulate), 0.5 s of accumulate's first use (0.65 -> 0.16 s; same results bit for
# bit, same speed).
@njit_force_inline
def _probability(logodds: np.ndarray, r: KernelInt, c: KernelInt, floor: float) -> float:
    # numba's float() keeps a float32 a float32, so exp runs in single precision:
    # M within about 1e-8 of the float64 formula, and accumulate 15-30 % faster
    # than with np.float64() here (measured; see the module docstring for the
    # effect on matched poses); the gradient is still the exact derivative of
    # the interpolant of these p.
    minus = -float(logodds[r, c])
    # Where float32's exp overflows to inf (p = 0) the argument is capped at a value
    # that still overflows it, bit for bit as before; as Python (NUMBA_DISABLE_JIT)
    # the cap keeps math.exp from raising OverflowError beyond 709 (p ~ 2e-39 there).
    if minus > _EXP_OVERFLOWS:
        minus = float(_EXP_OVERFLOWS)  # a float32 still (see above)
    p = 1.0 / (1.0 + math.exp(minus))
    # max(p, floor), without numba compiling max() for it on first use.
    return floor if floor > p else p


@njit_force_inline
def _edge_probability(logodds: np.ndarray, r: KernelInt, c: KernelInt, floor: float) -> float:
    # A neighbour of a point in the map's outer half cell may lie beyond the edge:
    # unknown there (log-odds 0, p = 1/2 exactly as _probability gives it), as
    # downsample counts the cells beyond an odd edge.
    if 0 <= r < logodds.shape[0] and 0 <= c < logodds.shape[1]:
        return _probability(logodds, r, c, floor)
    return floor if floor > 0.5 else 0.5


@njit_force_inline
def _interpolate(
    logodds: np.ndarray, row: float, col: float, floor: float
) -> tuple[float, float, float]:
    """``(M, ∂M/∂row, ∂M/∂col)`` at continuous grid coordinates; unknown beyond the map.

    Between the centres of cells ``(r0, c0)`` .. ``(r0 + 1, c0 + 1)`` with
    fractions ``b = row - r0`` and ``a = col - c0``::

        M = (1 - b) [(1 - a) p00 + a p01] + b [(1 - a) p10 + a p11]
        ∂M/∂col = (1 - b) (p01 - p00) + b (p11 - p10)
        ∂M/∂row = (1 - a) (p10 - p00) + a (p11 - p01)

    The map covers ``-0.5 <= row < rows - 0.5`` and ``-0.5 <= col < cols - 0.5``;
    beyond the edge cells' centres (in its outer half cell and past its edge)
    the neighbours beyond the edge count as unknown (``p = 1/2``, or ``floor``
    if higher), as in a map padded with unknown cells without end: ``M``
    continues from the edge cells to ``1/2`` a cell past their centres and stays
    there, with no gradient. (Zeros past the edge, Hector SLAM's value for a
    point out of its map's bounds, made a tight map match worse than the same
    map padded with unknown cells until review 50: a wall in the edge cells
    lost its pull on points half a cell beyond the edge, 16-28 mm mean error
    for a room with walls within 0.05 cell of the edge matched from guesses 1
    to 4 cm off, against 3-4 mm padded.) Zeros for NaN coordinates.
    """
    rows = logodds.shape[0]
    cols = logodds.shape[1]
    # Also false for NaN and for huge coordinates, before any int conversion.
    if 0.0 <= row < rows - 1 and 0.0 <= col < cols - 1:
        # np.int64, not int: numba compiles the int builtin as a function of its
        # own, once per process (review 51); both truncate with the same fptosi.
        r0: KernelInt = np.int64(row)
        c0: KernelInt = np.int64(col)
        p00 = _probability(logodds, r0, c0, floor)
        p01 = _probability(logodds, r0, c0 + 1, floor)
        p10 = _probability(logodds, r0 + 1, c0, floor)
        p11 = _probability(logodds, r0 + 1, c0 + 1, floor)
    elif row == row and col == col:  # (not NaN)
        # Zeros here, as once, made M jump from the edge cell's p to 0 at its
        # centre, inside the map: a wall in the outer half of the edge cells was
        # invisible (a room mapped tight to its walls matched 6x worse than the
        # same map with a margin, and 1-row maps not at all); zeros past the edge
        # (until review 50) cut the wall's pull half a cell short of the padded
        # map's. Farther than a cell past the edge every neighbour is unknown:
        # coordinates are clamped there (also huge ones, before the int conversion),
        # two cells out so that no neighbour is inside and the gradient is 0.
        if row < -1.0:
            row = -2.0
        elif row > rows:
            row = float(rows)
        if col < -1.0:
            col = -2.0
        elif col > cols:
            col = float(cols)
        r0 = math.floor(row)
        c0 = math.floor(col)
        p00 = _edge_probability(logodds, r0, c0, floor)
        p01 = _edge_probability(logodds, r0, c0 + 1, floor)
        p10 = _edge_probability(logodds, r0 + 1, c0, floor)
        p11 = _edge_probability(logodds, r0 + 1, c0 + 1, floor)
    else:
        return 0.0, 0.0, 0.0
    b = row - r0
    a = col - c0
    m = (1.0 - b) * ((1.0 - a) * p00 + a * p01) + b * ((1.0 - a) * p10 + a * p11)
    d_col = (1.0 - b) * (p01 - p00) + b * (p11 - p10)
    d_row = (1.0 - a) * (p10 - p00) + a * (p11 - p01)
    return m, d_row, d_col


@njit_cached
def interpolate_batch(logodds: np.ndarray, coords: np.ndarray, out: np.ndarray) -> None:
    """Fill ``out`` (N, 3) with ``M, ∂M/∂row, ∂M/∂col`` at ``coords`` (N, 2) ``(row, col)``.

    Beyond the edge cells' centres, neighbours beyond the map's edges count as
    unknown (``p = 1/2``): ``M = 1/2`` and no gradient a cell past the centres.
    """
    for i in range(coords.shape[0]):
        m, d_row, d_col = _interpolate(logodds, coords[i, 0], coords[i, 1], 0.0)
        out[i, 0] = m
        out[i, 1] = d_row
        out[i, 2] = d_col


@njit_no_refcount
def accumulate(
    logodds: np.ndarray,
    origin_x: float,
    origin_y: float,
    origin_yaw: float,
    resolution: float,
    points: np.ndarray,
    x: float,
    y: float,
    theta: float,
    floor: float,
    hessian: np.ndarray,
    gradient: np.ndarray,
) -> tuple[float, float]:
    """Gauss–Newton sums of the sensor-frame ``points`` (N, 2) at pose ``(x, y, theta)``.

    Fills ``hessian`` (3, 3) with ``Σ JᵢᵀJᵢ`` and ``gradient`` (3,) with
    ``Σ Jᵢᵀ (1 - Mᵢ)``, where ``Jᵢ = ∇M(Sᵢ(ξ)) ∂Sᵢ/∂ξ`` (world metres and
    radians) and ``Sᵢ(ξ)`` the world point. Returns ``(Σ (1 - Mᵢ)², Σ Mᵢ)``.
    When ``hessian`` has size 0 only the two sums are computed.
    """
    inv_res = 1.0 / resolution
    co = math.cos(origin_yaw)
    so = math.sin(origin_yaw)
    ct = math.cos(theta)
    st = math.sin(theta)
    with_jacobian = hessian.size > 0
    h00 = h01 = h02 = h11 = h12 = h22 = 0.0
    g0 = g1 = g2 = 0.0
    cost = 0.0
    total = 0.0
    for i in range(points.shape[0]):
        px = points[i, 0]
        py = points[i, 1]
        rx = ct * px - st * py
        ry = st * px + ct * py
        dx = x + rx - origin_x
        dy = y + ry - origin_y
        # Continuous (row, col): integers at cell centres.
        col = (co * dx + so * dy) * inv_res - 0.5
        row = (-so * dx + co * dy) * inv_res - 0.5
        m, d_row, d_col = _interpolate(logodds, row, col, floor)
        res = 1.0 - m
        cost += res * res
        total += m
        if with_jacobian:
            # ∇M in world coordinates, then ∂S/∂θ = (-ry, rx).
            jx = (d_col * co - d_row * so) * inv_res
            jy = (d_col * so + d_row * co) * inv_res
            jt = -jx * ry + jy * rx
            h00 += jx * jx
            h01 += jx * jy
            h02 += jx * jt
            h11 += jy * jy
            h12 += jy * jt
            h22 += jt * jt
            g0 += jx * res
            g1 += jy * res
            g2 += jt * res
    if with_jacobian:
        hessian[0, 0] = h00
        hessian[0, 1] = h01
        hessian[0, 2] = h02
        hessian[1, 0] = h01
        hessian[1, 1] = h11
        hessian[1, 2] = h12
        hessian[2, 0] = h02
        hessian[2, 1] = h12
        hessian[2, 2] = h22
        gradient[0] = g0
        gradient[1] = g1
        gradient[2] = g2
    return cost, total


@njit_inline
def _solve3(h: np.ndarray, g: np.ndarray, step: np.ndarray) -> bool:
    """Solve the symmetric 3×3 system ``h step = g`` (Cholesky); False when not positive definite.

    A tiny relative ridge (1e-9 of the largest diagonal entry) keeps a
    semi-definite matrix solvable; truly singular directions still fail.
    """
    # max(h[0, 0], h[1, 1], h[2, 2]), without numba compiling max() for it.
    largest = h[0, 0]
    largest = h[1, 1] if h[1, 1] > largest else largest
    largest = h[2, 2] if h[2, 2] > largest else largest
    ridge = 1e-9 * largest
    a00 = h[0, 0] + ridge
    a11 = h[1, 1] + ridge
    a22 = h[2, 2] + ridge
    if not a00 > 0.0:
        return False
    l00 = math.sqrt(a00)
    l10 = h[1, 0] / l00
    l20 = h[2, 0] / l00
    d1 = a11 - l10 * l10
    if not d1 > 1e-12 * a11:
        return False
    l11 = math.sqrt(d1)
    l21 = (h[2, 1] - l20 * l10) / l11
    d2 = a22 - l20 * l20 - l21 * l21
    if not d2 > 1e-12 * a22:
        return False
    l22 = math.sqrt(d2)
    y0 = g[0] / l00
    y1 = (g[1] - l10 * y0) / l11
    y2 = (g[2] - l20 * y0 - l21 * y1) / l22
    step[2] = y2 / l22
    step[1] = (y1 - l21 * step[2]) / l11
    step[0] = (y0 - l10 * step[1] - l20 * step[2]) / l00
    return math.isfinite(step[0]) and math.isfinite(step[1]) and math.isfinite(step[2])


@njit_released
def match_level(
    logodds: np.ndarray,
    origin_x: float,
    origin_y: float,
    origin_yaw: float,
    resolution: float,
    points: np.ndarray,
    pose: np.ndarray,
    max_iterations: int,
    max_step_xy: float,
    max_step_theta: float,
    tol_xy: float,
    tol_theta: float,
    prior: np.ndarray,
    translation_weight: float,
    rotation_weight: float,
    floor: float,
    hessian: np.ndarray,
    gradient: np.ndarray,
    step: np.ndarray,
    no_hessian: np.ndarray,
) -> tuple[int, int]:
    """Gauss–Newton on one map level, updating ``pose`` (3,) ``[x, y, theta]`` in place.

    The cost is the mean ``Σ (1 - M)² / n`` plus, when the weights are not
    zero, ``translation_weight² |t - t₀|² + rotation_weight² (θ - θ₀)²`` for
    the pose ``prior`` ``(x₀, y₀, θ₀)`` (Cartographer's real-time matcher
    penalises moving away from the initial guess the same way).

    Each iteration solves ``H Δξ = g`` (:func:`accumulate`, with the prior's
    terms added), clamps the
    translation of ``Δξ`` to ``max_step_xy`` (m, keeping its direction) and the
    rotation to ``max_step_theta`` (rad), and takes the step, halved up to four
    times until that cost (the mean plus the pull) does not increase. It stops when a step
    is below ``tol_xy`` and ``tol_theta`` (converged), when no halving lowers
    the cost (converged: a minimum along the Gauss–Newton direction), when ``H``
    is singular, or after ``max_iterations``.

    ``hessian`` (3, 3), ``gradient`` (3,), ``step`` (3,) and ``no_hessian``
    (0, 0) are scratch arrays of the caller (float64, C-contiguous), allocated
    in NumPy so that this kernel allocates nothing: numba's array allocation
    costs tenths of a second of first-use compilation.

    Returns
    -------
    (int, int)
        Iterations done and the status (``STATUS_*``).
    """
    x = pose[0]
    y = pose[1]
    theta = pose[2]
    inv_n = 1.0 / points.shape[0]
    wt2 = translation_weight * translation_weight
    wr2 = rotation_weight * rotation_weight
    for it in range(max_iterations):
        cost, _ = accumulate(
            logodds,
            origin_x,
            origin_y,
            origin_yaw,
            resolution,
            points,
            x,
            y,
            theta,
            floor,
            hessian,
            gradient,
        )
        ex = x - prior[0]
        ey = y - prior[1]
        et = theta - prior[2]
        cost = cost * inv_n + wt2 * (ex * ex + ey * ey) + wr2 * et * et
        for i in range(3):
            for j in range(3):
                hessian[i, j] *= inv_n
            gradient[i] *= inv_n
        hessian[0, 0] += wt2
        hessian[1, 1] += wt2
        hessian[2, 2] += wr2
        gradient[0] -= wt2 * ex
        gradient[1] -= wt2 * ey
        gradient[2] -= wr2 * et
        if not _solve3(hessian, gradient, step):
            pose[0] = x
            pose[1] = y
            pose[2] = theta
            return it, STATUS_SINGULAR
        norm = math.hypot(step[0], step[1])
        if norm > max_step_xy:
            step[0] *= max_step_xy / norm
            step[1] *= max_step_xy / norm
        turn = step[2]
        turn = -max_step_theta if -max_step_theta > turn else turn
        step[2] = max_step_theta if max_step_theta < turn else turn
        scale = 1.0
        accepted = False
        for _ in range(_HALVINGS + 1):
            nx = x + scale * step[0]
            ny = y + scale * step[1]
            nt = theta + scale * step[2]
            new_cost, _ = accumulate(
                logodds,
                origin_x,
                origin_y,
                origin_yaw,
                resolution,
                points,
                nx,
                ny,
                nt,
                floor,
                no_hessian,
                gradient,
            )
            ex = nx - prior[0]
            ey = ny - prior[1]
            et = nt - prior[2]
            new_cost = new_cost * inv_n + wt2 * (ex * ex + ey * ey) + wr2 * et * et
            if new_cost <= cost:
                accepted = True
                break
            scale *= 0.5
        if not accepted:
            pose[0] = x
            pose[1] = y
            pose[2] = theta
            return it + 1, STATUS_CONVERGED
        x = nx
        y = ny
        theta = nt
        if (
            math.hypot(scale * step[0], scale * step[1]) < tol_xy
            and abs(scale * step[2]) < tol_theta
        ):
            pose[0] = x
            pose[1] = y
            pose[2] = theta
            return it + 1, STATUS_CONVERGED
    pose[0] = x
    pose[1] = y
    pose[2] = theta
    return max_iterations, STATUS_MAX_ITERATIONS


@njit_released
def correlative_search_kernel(
    logodds: np.ndarray,
    origin_x: float,
    origin_y: float,
    origin_yaw: float,
    resolution: float,
    points: np.ndarray,
    pose: np.ndarray,
    steps_xy: int,
    step_xy: float,
    steps_theta: int,
    step_theta: float,
    translation_weight: float,
    rotation_weight: float,
    scratch: np.ndarray,
) -> float:
    """Move ``pose`` (3,) to the best of a grid of poses around it; returns that pose's cost.

    The grid: rotations ``theta + k step_theta`` for ``|k| <= steps_theta`` and
    translations ``(x + i step_xy, y + j step_xy)`` for ``|i|, |j| <= steps_xy``.
    The cost of a pose is the mean ``(1 - p)²`` of the points, ``p`` the
    occupancy probability of the cell each point falls in (1/2 off the map, as
    :func:`accumulate` takes it: unknown, a point there costs 1/4), plus
    the pull ``translation_weight² |t - t₀|² + rotation_weight² (θ - θ₀)²``
    towards the input pose ``t₀, θ₀`` — :func:`match_level`'s cost without the
    interpolation. A candidate is dropped as soon as its partial sum exceeds
    the best cost so far; candidates are visited from the input pose outwards
    and a tie keeps the earlier one, so a flat cost leaves the pose unchanged.
    ``scratch`` is a float64 C-contiguous (2, N) work array of the caller (N
    the number of points), so that this kernel allocates nothing
    (:func:`correlative_search` allocates it).
    """
    n = points.shape[0]
    inv_res = 1.0 / resolution
    inv_n = 1.0 / n
    co = math.cos(origin_yaw)
    so = math.sin(origin_yaw)
    rows = logodds.shape[0]
    cols = logodds.shape[1]
    x0 = pose[0]
    y0 = pose[1]
    t0 = pose[2]
    wt2 = translation_weight * translation_weight
    wr2 = rotation_weight * rotation_weight
    base_col = scratch[0]
    base_row = scratch[1]
    best = math.inf
    best_x = x0
    best_y = y0
    best_t = t0
    n_theta = 2 * steps_theta + 1
    n_xy = 2 * steps_xy + 1
    for kk in range(n_theta):
        # 0, -1, +1, -2, +2, ...: the guess first, then outwards.
        k = (kk + 1) // 2 if kk % 2 == 1 else -(kk // 2)
        theta = t0 + k * step_theta
        ct = math.cos(theta)
        st = math.sin(theta)
        for q in range(n):
            dx = x0 + ct * points[q, 0] - st * points[q, 1] - origin_x
            dy = y0 + st * points[q, 0] + ct * points[q, 1] - origin_y
            base_col[q] = (co * dx + so * dy) * inv_res
            base_row[q] = (-so * dx + co * dy) * inv_res
        turn = k * step_theta
        rot_pull = wr2 * (turn * turn)
        for ii in range(n_xy * n_xy):
            a = ii // n_xy
            b = ii % n_xy
            i = (a + 1) // 2 if a % 2 == 1 else -(a // 2)
            j = (b + 1) // 2 if b % 2 == 1 else -(b // 2)
            tx = i * step_xy
            ty = j * step_xy
            pull = rot_pull + wt2 * (tx * tx + ty * ty)
            if pull >= best:
                continue
            d_col = (co * tx + so * ty) * inv_res
            d_row = (-so * tx + co * ty) * inv_res
            limit = (best - pull) * n
            total = 0.0
            for q in range(n):
                col = base_col[q] + d_col
                row = base_row[q] + d_row
                if 0.0 <= row < rows and 0.0 <= col < cols:
                    p = _probability(logodds, np.int64(row), np.int64(col), 0.0)
                    total += (1.0 - p) * (1.0 - p)
                else:
                    total += 0.25
                if total > limit:
                    break
            cost = total * inv_n + pull
            if cost < best:
                best = cost
                best_x = x0 + tx
                best_y = y0 + ty
                best_t = theta
    pose[0] = best_x
    pose[1] = best_y
    pose[2] = best_t
    return best


def correlative_search(*args: Any) -> float:
    """:func:`correlative_search_kernel` on ``args`` (all but ``scratch``), scratch made here.

    The scratch array is allocated in NumPy (a microsecond per call) rather
    than in the kernel, where numba's array allocation would add tenths of a
    second to its first-use compilation.
    """
    kernel: Any = correlative_search_kernel
    points = args[5]
    return float(kernel(*args, np.empty((2, points.shape[0]))))
