"""Writing pictures atomically: a temporary file beside the target, then ``os.replace``."""

from __future__ import annotations

import os
from pathlib import Path
from typing import TYPE_CHECKING, Any

from navkit._shared.files import atomic_path as written_atomically
from navkit._shared.files import check_folder, link_loop
from navkit.plot._figure import bounded_float, figure_of

if TYPE_CHECKING:
    from matplotlib.axes import Axes
    from matplotlib.figure import Figure

__all__ = ["MAX_PIXELS", "output_path", "save_figure", "written_atomically"]

#: Largest picture written, pixels (8192 × 8192).
MAX_PIXELS = 1 << 26


def output_path(value: Any, name: str, suffix: str) -> Path:
    """A path to write a ``suffix`` file to, in an existing folder (nothing is created)."""
    if isinstance(value, bytes) or not isinstance(value, (str, os.PathLike)):
        raise TypeError(f"{name} must be a str or path-like, got {type(value).__name__}")
    text = os.fspath(value)
    if not isinstance(text, str):
        raise TypeError(f"{name} must be a str or path-like, got bytes")
    if not text or "\x00" in text:
        raise ValueError(f"{name} must be a non-empty file name without NUL characters")
    path = Path(text)
    if path.suffix.lower() != suffix:
        raise ValueError(f"{name} must end in {suffix}, got {text!r}")
    if path.is_dir():
        raise ValueError(f"{name} {text!r} is a folder")
    check_folder(path, name)  # (a looped folder too: the path's loop is the folder's)
    if link_loop(path):
        # exists() says False for it: found only by the rename, after the drawing.
        raise ValueError(f"{name} {text!r} is a loop of symbolic links")
    if path.exists() and not path.is_file():
        # Renaming the temporary file over it would replace the device or pipe itself.
        raise ValueError(f"{name} {text!r} is not a regular file (a device or a pipe?)")
    return path


def check_size(fig: Figure, dpi: float) -> None:
    width, height = fig.get_size_inches()
    pixels = float(width) * dpi * float(height) * dpi
    if not pixels <= MAX_PIXELS:
        raise ValueError(
            f"the figure ({width:g} × {height:g} in) at dpi {dpi:g} would be {pixels:.3g} "
            f"pixels; the most is {MAX_PIXELS} (8192 × 8192): use a smaller dpi"
        )


def save_figure(fig_or_ax: Figure | Axes, path: str | os.PathLike[str], *,
                dpi: float = 100.0) -> Path:  # fmt: skip
    """Write a figure to a PNG file atomically.

    The picture is rendered with the Agg renderer into a temporary file in the
    same folder, which then replaces ``path`` (``os.replace``): a failure
    leaves an existing file as it was, and nothing else is created (no
    folders).

    Parameters
    ----------
    fig_or_ax : matplotlib Figure or Axes
        The figure, or any of its axes (what the ``plot_*`` functions return).
    path : str or path-like
        The ``.png`` file to write, in an existing folder; replaced if it exists.
    dpi : float, default 100
        Resolution, dots per inch, in [10, 600]; the picture may have at most
        2**26 pixels.

    Returns
    -------
    Path
        The file written.

    Raises
    ------
    TypeError
        Not a Figure or Axes, a path that is not a str or path-like.
    ValueError
        A path not ending in ``.png`` or naming a folder, a loop of symbolic
        links or something else that is not a regular file (a device, a
        pipe), ``dpi`` out of range.
    FileNotFoundError
        The folder of ``path`` does not exist, or is (or lies below) a loop of
        symbolic links: ``"path: folder {folder} does not exist"``, the loop
        named after it. Nothing is drawn or written.
    NotADirectoryError
        A file stands where a folder of ``path`` should be:
        ``"path: {file} is a file, not a folder"``. Nothing is drawn or written.

    Examples
    --------
    >>> import tempfile
    >>> from pathlib import Path
    >>> import numpy as np
    >>> from navkit.mapping import OccupancyGrid
    >>> from navkit.plot import plot_grid
    >>> ax = plot_grid(OccupancyGrid.from_occupancy(np.eye(8, dtype=bool), resolution=0.1))
    >>> with tempfile.TemporaryDirectory() as folder:
    ...     png = save_figure(ax, Path(folder) / "map.png", dpi=50)
    ...     print(png.name, png.read_bytes()[:4], sorted(p.name for p in Path(folder).iterdir()))
    map.png b'\\x89PNG' ['map.png']
    """
    fig = figure_of(fig_or_ax, "fig_or_ax")
    resolution = bounded_float(dpi, "dpi", 10.0, 600.0)
    target = output_path(path, "path", ".png")
    check_size(fig, resolution)
    with written_atomically(target) as temporary:
        fig.savefig(temporary, format="png", dpi=resolution)
    return target
