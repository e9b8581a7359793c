"""Potential fields: a surface, filled contours or force arrows."""

from __future__ import annotations

import math
from typing import TYPE_CHECKING, Any, Literal

import numpy as np
from numpy.typing import ArrayLike

from navkit._shared.types import FloatArray, IntArray
from navkit._shared.validation import as_float_array, finite_float
from navkit.planning import PotentialField, SampledField, sample_field
from navkit.plot._figure import COORD_LIMIT, axes_for, finish_axes

if TYPE_CHECKING:
    from matplotlib.axes import Axes

__all__ = ["plot_field"]

_KINDS = ("surface", "contour", "quiver")
#: Most cells plot_field samples from a PotentialField (1024 × 1024).
MAX_FIELD_SAMPLES = 1 << 20
#: How far the float estimate of the samples may exceed the limit before sampling.
_ESTIMATE_SLACK = 1.01
#: Most cells drawn per axis: contours, the surface's facets, arrows.
_CONTOUR_CELLS = 512
_SURFACE_CELLS = 80
_ARROWS = 25


def _sampled(field: Any, xlim: Any, ylim: Any, resolution: Any) -> SampledField:
    if isinstance(field, SampledField):
        for name, value in (("xlim", xlim), ("ylim", ylim), ("resolution", resolution)):
            if value is not None:
                raise ValueError(
                    f"{name} is only for a PotentialField: a SampledField is drawn as sampled"
                )
        return field
    if not isinstance(field, PotentialField):
        raise TypeError(
            f"field must be a PotentialField or a SampledField, got {type(field).__name__}"
        )
    missing = [n for n, v in (("xlim", xlim), ("ylim", ylim), ("resolution", resolution))
               if v is None]  # fmt: skip
    if missing:
        raise ValueError(
            f"drawing a PotentialField needs xlim, ylim and resolution (missing: "
            f"{', '.join(missing)}); or give a SampledField (navkit.planning.sample_field)"
        )
    x = as_float_array(xlim, "xlim", shape=(2,))
    y = as_float_array(ylim, "ylim", shape=(2,))
    res = finite_float(resolution, "resolution")
    if res > 0.0 and x[1] > x[0] and y[1] > y[0]:  # else sample_field says what is wrong
        with np.errstate(over="ignore"):
            cells = float(np.ceil((x[1] - x[0]) / res) * np.ceil((y[1] - y[0]) / res))
        # Refused before sampling only when clearly too many: this float estimate can
        # exceed sample_field's exact count by a cell per axis (1025 × 1025 for its
        # 1024 × 1024), which is checked on the samples below.
        if not cells <= _ESTIMATE_SLACK * MAX_FIELD_SAMPLES:
            raise _too_many(f"about {cells:.3g}", res)
    sampled = sample_field(field, xlim=x, ylim=y, resolution=res)
    rows, cols = sampled.shape
    if rows * cols > MAX_FIELD_SAMPLES:
        raise _too_many(f"{rows} × {cols} = {rows * cols}", res)
    return sampled


def _too_many(needed: str, resolution: float) -> ValueError:
    return ValueError(
        f"plot_field samples at most {MAX_FIELD_SAMPLES} cells (1024 × 1024); xlim, ylim and "
        f"resolution {resolution!r} m would need {needed}: use a coarser resolution"
    )


def _stride(n: int, most: int) -> int:
    return max(1, math.ceil(n / most))


def _thinned(n: int, stride: int) -> IntArray:
    """Every ``stride``-th of ``n`` sample indices, the last one always kept.

    A plain ``[::stride]`` drops up to ``stride - 1`` samples at the far edge:
    the drawing would stop short of the field, and a field two samples wide
    could be left one sample wide, which matplotlib cannot contour.
    """
    out: IntArray = np.unique(np.append(np.arange(0, n, stride), n - 1))
    return out


def _clipped_potential(sampled: SampledField, clip: float | None) -> FloatArray:
    """The potential with ``+inf`` (and values above ``clip``) drawn at the cap."""
    pot = np.array(sampled.potential, dtype=np.float64)
    finite = pot[np.isfinite(pot)]
    if not finite.size and clip is None:
        # No finite value to cap the infinities at: drawing them at 0 (as before)
        # showed a flat field of potential 0 where every point is inside an obstacle.
        raise ValueError(
            "field: every sampled potential is +inf (the window lies inside obstacles), "
            "there is no finite potential to draw; pass clip= to draw them at that cap, "
            "sample a window reaching outside the obstacles, or use kind='quiver'"
        )
    top = float(finite.max()) if finite.size else 0.0
    if clip is not None:
        top = min(top, clip) if finite.size else clip
    return np.minimum(pot, top)


def plot_field(
    field: PotentialField | SampledField,
    *,
    ax: Axes | None = None,
    kind: Literal["surface", "contour", "quiver"] = "surface",
    xlim: ArrayLike | None = None,
    ylim: ArrayLike | None = None,
    resolution: float | None = None,
    clip: float | None = None,
) -> Axes:
    """Draw a potential field: its surface, filled contours, or force arrows.

    Parameters
    ----------
    field : PotentialField or SampledField
        A navkit field (sampled here on ``xlim`` × ``ylim`` at ``resolution``)
        or one already sampled with :func:`navkit.planning.sample_field`.
    ax : matplotlib Axes, optional
        Where to draw; a new figure (Agg canvas, no window) when omitted. For
        ``kind="surface"`` it must be a 3-D axes (``projection="3d"``).
    kind : {"surface", "contour", "quiver"}, default "surface"
        ``"surface"``: the potential as a 3-D surface (x, y in m);
        ``"contour"``: filled contours of the potential with a colour bar, on
        world axes; ``"quiver"``: the force direction as arrows coloured by
        its magnitude, on world axes. Large fields are thinned for drawing
        (at most 512 × 512 contour cells, 80 × 80 facets, 25 × 25 arrows).
    xlim, ylim : array_like (min, max), optional
        Window in metres; only (and then required) with a PotentialField.
    resolution : float, optional
        Sample spacing in metres; only (and then required) with a
        PotentialField. At most 2**20 samples.
    clip : float, optional
        Potentials above this are drawn at it (repulsion grows without bound
        near obstacles); ``+inf`` potentials are always drawn at the largest
        finite one (or at ``clip``). A surface or contours of a field whose
        every potential is ``+inf`` need ``clip``.

    Returns
    -------
    matplotlib Axes
        The axes drawn on.

    Raises
    ------
    TypeError
        ``field`` is not a field, ``ax`` not an Axes, a bad option type.
    ValueError
        Unknown ``kind``; ``kind="surface"`` on 2-D axes; sampling options
        with a SampledField, missing ones with a PotentialField, a window
        beyond ±1e9 m or needing more than 2**20 samples; ``kind="contour"``
        of a field less than 2 samples wide or high; ``kind="surface"`` or
        ``"contour"`` of a field that is ``+inf`` everywhere, without ``clip``.

    Examples
    --------
    >>> from navkit.planning import ConicAttraction
    >>> ax = plot_field(ConicAttraction((0.0, 0.0)), kind="contour",
    ...                 xlim=(-1.0, 1.0), ylim=(-1.0, 1.0), resolution=0.1)
    >>> ax.get_xlabel()
    'x (m)'
    """
    if not isinstance(kind, str):
        raise TypeError(f"kind must be a str, got {type(kind).__name__}")
    if kind not in _KINDS:
        raise ValueError(f"kind must be one of {_KINDS}, got {kind!r}")
    cap = None if clip is None else finite_float(clip, "clip")
    sampled = _sampled(field, xlim, ylim, resolution)
    if max(abs(sampled.x[0]), abs(sampled.x[-1]), abs(sampled.y[0]), abs(sampled.y[-1])) \
            > COORD_LIMIT:  # fmt: skip
        raise ValueError(f"field must lie within ±{COORD_LIMIT:g} m to be drawn")
    if kind == "contour" and min(sampled.shape) < 2:
        raise ValueError(
            f"kind='contour' needs a field of at least 2 × 2 samples, got {sampled.shape[0]} × "
            f"{sampled.shape[1]} (rows along y, columns along x): sample a larger window or a "
            "finer resolution, or use kind='quiver'"
        )
    axes = axes_for(ax, three_d=kind == "surface")
    is_3d = axes.name == "3d"
    if kind == "surface" and not is_3d:
        raise ValueError(
            "kind='surface' needs 3-D axes (fig.add_subplot(projection='3d')); "
            "pass ax=None or use kind='contour'"
        )
    if kind != "surface" and is_3d:
        raise ValueError(f"kind={kind!r} draws on 2-D axes, got 3-D axes")
    fig = axes.get_figure()
    if kind == "surface":
        _surface(axes, sampled, cap)
    elif kind == "contour":
        pot = _clipped_potential(sampled, cap)
        s = _stride(max(pot.shape), _CONTOUR_CELLS)
        rows, cols = _thinned(pot.shape[0], s), _thinned(pot.shape[1], s)
        filled = axes.contourf(sampled.x[cols], sampled.y[rows], pot[np.ix_(rows, cols)],
                               levels=20, cmap="viridis")  # fmt: skip
        if fig is not None:
            fig.colorbar(filled, ax=axes, label="potential")
        finish_axes(axes)
    else:
        _quiver(axes, sampled, fig)
        finish_axes(axes)
    return axes


def _surface(ax: Axes, sampled: SampledField, cap: float | None) -> None:
    pot = _clipped_potential(sampled, cap)
    gx, gy = np.meshgrid(sampled.x, sampled.y)
    h, w = pot.shape
    ax.plot_surface(gx, gy, pot, rcount=min(h, _SURFACE_CELLS),  # type: ignore[attr-defined]
                    ccount=min(w, _SURFACE_CELLS), cmap="viridis", linewidth=0.0,
                    antialiased=False)  # fmt: skip
    ax.set_xlabel("x (m)")
    ax.set_ylabel("y (m)")
    ax.set_zlabel("potential")  # type: ignore[attr-defined]


def _quiver(ax: Axes, sampled: SampledField, fig: Any) -> None:
    h, w = sampled.shape
    s = max(_stride(h, _ARROWS), _stride(w, _ARROWS))
    force = sampled.force[::s, ::s]
    gx, gy = np.meshgrid(sampled.x[::s], sampled.y[::s])
    with np.errstate(over="ignore"):
        magnitude = np.hypot(force[..., 0], force[..., 1])
    magnitude = np.minimum(magnitude, np.finfo(np.float64).max)
    with np.errstate(invalid="ignore", divide="ignore"):
        ux = np.where(magnitude > 0.0, force[..., 0] / magnitude, 0.0)
        uy = np.where(magnitude > 0.0, force[..., 1] / magnitude, 0.0)
    # Forces near obstacles dwarf the rest: a log scale keeps the colours telling.
    from matplotlib.colors import LogNorm, Normalize

    positive = magnitude[magnitude > 0.0]
    norm: Normalize | None = None
    if positive.size and float(positive.max()) > 1e3 * float(positive.min()):
        norm = LogNorm(vmin=float(positive.min()), vmax=float(positive.max()))
        magnitude = np.maximum(magnitude, float(positive.min()))
    arrows = ax.quiver(
        gx,
        gy,
        ux,
        uy,
        magnitude,
        cmap="viridis",
        pivot="mid",
        angles="xy",
        scale_units="xy",
        scale=1.0 / (0.8 * s * sampled.resolution),
        norm=norm,
    )
    if fig is not None:
        fig.colorbar(arrows, ax=ax, label="force")
    ax.update_datalim([[sampled.x[0], sampled.y[0]], [sampled.x[-1], sampled.y[-1]]])
    # The arrows reach half their length past the outer samples: with the samples'
    # limits alone, a small field's edge arrows lost their heads (a single sample's
    # arrow, 0.8 cells long, was drawn in a window 0.05 cells wide).
    reach = 0.4 * s * sampled.resolution
    ax.update_datalim([[float(gx.min()) - reach, float(gy.min()) - reach],
                       [float(gx.max()) + reach, float(gy.max()) + reach]])  # fmt: skip
    ax.autoscale_view()
