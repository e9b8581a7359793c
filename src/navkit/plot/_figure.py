"""matplotlib on demand: the import, new Agg axes, and checks of plotting options."""

from __future__ import annotations

import array
from collections.abc import Iterator
from contextlib import contextmanager
from typing import TYPE_CHECKING, Any, Literal

import numpy as np
from numpy.typing import ArrayLike

from navkit._shared.types import FloatArray
from navkit._shared.validation import (
    as_float_array,
    bounded_int,
    finite_float,
    has_array_protocol,
)

if TYPE_CHECKING:
    from matplotlib.axes import Axes
    from matplotlib.figure import Figure

__all__ = [
    "COORD_LIMIT",
    "as_color",
    "as_coords",
    "as_label",
    "axes_for",
    "bounded_float",
    "bounded_int",
    "figure_of",
    "keep_directions",
    "require_matplotlib",
]

#: Largest coordinate magnitude drawn, m (as navkit's planners and maps accept).
COORD_LIMIT = 1e9
#: Size of the figures navkit.plot creates, inches (matplotlib's default).
FIGSIZE = (6.4, 4.8)

# Quoted for the shell the user pastes it into: unquoted, zsh refuses the brackets
# ("no matches found") and bash expands them to a matching file ("navkitp") in the
# current folder.
_MISSING = (
    "navkit.plot needs matplotlib, which is not installed; install the plot extra: "
    "pip install 'navkit[plot]'"
)


def require_matplotlib() -> None:
    """Import matplotlib or raise an ImportError naming the ``plot`` extra.

    The top-level package is imported first: ``from matplotlib.figure import
    Figure`` alone would find an already imported submodule even when
    ``matplotlib`` itself is hidden (``sys.modules["matplotlib"] = None``).
    """
    try:
        import matplotlib
        import matplotlib.figure  # noqa: F401
    except ImportError:
        raise ImportError(_MISSING) from None


def new_figure(*, layout: Literal["constrained"] | None = "constrained") -> Figure:
    """A Figure on the Agg canvas: no pyplot state, no window, safe in threads."""
    require_matplotlib()
    from matplotlib.backends.backend_agg import FigureCanvasAgg
    from matplotlib.figure import Figure

    fig = Figure(figsize=FIGSIZE, layout=layout)
    FigureCanvasAgg(fig)
    return fig


def axes_for(ax: Any, *, three_d: bool = False) -> Axes:
    """``ax`` checked, or new axes on a new Agg figure when it is None."""
    require_matplotlib()
    from matplotlib.axes import Axes

    if ax is None:
        fig = new_figure()
        return fig.add_subplot(projection="3d") if three_d else fig.add_subplot()
    if not isinstance(ax, Axes):
        raise TypeError(f"ax must be a matplotlib Axes or None, got {type(ax).__name__}")
    return ax


def figure_of(value: Any, name: str) -> Figure:
    """The Figure of a Figure or an Axes."""
    require_matplotlib()
    from matplotlib.axes import Axes
    from matplotlib.figure import Figure

    if isinstance(value, Figure):
        return value
    if isinstance(value, Axes):
        # A SubFigure's ``figure`` is the root Figure; a Figure's is itself.
        root = getattr(value.figure, "figure", None)
        if not isinstance(root, Figure):
            raise ValueError(f"{name}: the Axes does not belong to a Figure")
        return root
    raise TypeError(f"{name} must be a matplotlib Figure or Axes, got {type(value).__name__}")


def as_label(value: Any, name: str) -> str | None:
    """A legend label: a str or None."""
    if value is None or isinstance(value, str):
        return value
    raise TypeError(f"{name} must be a str or None, got {type(value).__name__}")


def as_color(value: Any, name: str) -> Any:
    """A matplotlib colour (``"red"``, ``"#1f77b4"``, ``"C0"``, an RGB(A) tuple) or None.

    An RGB(A) sequence may be a list or a 1-D ndarray too (a row of a colormap's
    ``cmap(values)``), returned as a tuple of floats.
    """
    if value is None:
        return None
    require_matplotlib()
    from matplotlib.colors import to_rgba

    if isinstance(value, (tuple, list, np.ndarray)):
        # Python floats: NumPy 2's scalars would show as np.float64(1.0) in the message.
        value = tuple(as_float_array(value, name, ndim=1).tolist())
    elif not isinstance(value, str):
        raise TypeError(
            f"{name} must be a matplotlib colour (a str or RGB(A) tuple) or None, "
            f"got {type(value).__name__}"
        )
    try:
        to_rgba(value)
    except (ValueError, TypeError):
        raise ValueError(f"{name}: {value!r} is not a matplotlib colour") from None
    return value


def array_like(value: object) -> bool:
    """Whether ``value`` is an array for an argument that also takes other objects.

    An ndarray, a list or tuple, a ``memoryview`` or ``array.array``, or an
    object NumPy reads through its array protocols (a tensor, a message's
    buffer): what the rest of navkit reads with ``np.asarray``. The caller
    refuses anything else with its own ``TypeError``.
    """
    return isinstance(value, (np.ndarray, list, tuple, memoryview, array.array)) or (
        has_array_protocol(value)
    )


def as_coords(value: ArrayLike, name: str, *, ncols: int = 2, nan_ok: bool = False) -> FloatArray:
    """An ``(n, ncols)`` float array of world coordinates within ±1e9 m."""
    arr = as_float_array(value, name, shape=(None, ncols), finite=not nan_ok)
    if nan_ok and np.isinf(arr).any():
        raise ValueError(f"{name} must be finite (or NaN), got an infinity")
    with np.errstate(invalid="ignore"):
        big = np.abs(arr[..., :2]) > COORD_LIMIT
    if big.any():
        raise ValueError(f"{name} must lie within ±{COORD_LIMIT:g} m to be drawn")
    return arr


def bounded_float(value: Any, name: str, lo: float, hi: float) -> float:
    """A finite float in ``[lo, hi]``."""
    out = finite_float(value, name)
    if not lo <= out <= hi:
        # repr, not :g: 1.0000001 printed as "1" would look inside [0, 1].
        raise ValueError(f"{name} must lie in [{lo:g}, {hi:g}], got {out!r}")
    return out


@contextmanager
def keep_directions(ax: Axes) -> Iterator[None]:
    """Keep the caller's axis directions (``invert_yaxis()``) through the drawing inside.

    ``imshow`` and ``set_xlim``/``set_ylim`` with increasing limits turn an
    inverted axis the right way round again.
    """
    x_inverted, y_inverted = ax.xaxis_inverted(), ax.yaxis_inverted()
    try:
        yield
    finally:
        # set_inverted keeps the limits (reordered) and the autoscaling state.
        ax.xaxis.set_inverted(x_inverted)
        ax.yaxis.set_inverted(y_inverted)


def finish_axes(ax: Axes) -> None:
    """Equal scales in metres with labelled axes (2-D world plots)."""
    ax.set_aspect("equal", adjustable="datalim")
    ax.set_xlabel("x (m)")
    ax.set_ylabel("y (m)")
