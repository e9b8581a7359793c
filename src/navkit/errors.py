"""Exceptions raised by navkit.

Every navkit-specific exception derives from :class:`NavkitError`, so callers can
catch all of them at once. Invalid arguments raise the built-in ``ValueError`` or
``TypeError`` (with the argument named in the message) rather than a navkit class.
"""

from __future__ import annotations

import math
import numbers
import sys

__all__ = ["DataNotFoundError", "FilterError", "KernelCacheWarning", "NavkitError", "NoPathError"]


_MAX_EXPANDED = 2**63 - 1


def _short(value: numbers.Integral) -> str:
    """An integer for a message; a huge one as its order of magnitude."""
    n = int(value)
    if abs(n) < 10**30:
        return str(n)
    # str() of a huge int may itself refuse (sys.int_info.default_max_str_digits).
    return f"an integer of about 10**{int(abs(n).bit_length() * math.log10(2))}"


class NavkitError(Exception):
    """Base class of navkit's own exceptions.

    Catch it to handle every navkit-specific failure at once; invalid arguments
    raise the built-in ``ValueError`` or ``TypeError`` instead.

    Examples
    --------
    >>> import numpy as np
    >>> from navkit.planning import astar
    >>> costs = np.ones((3, 3))
    >>> costs[:, 1] = np.inf  # a wall splits the grid
    >>> try:
    ...     astar(costs, (0, 0), (0, 2))
    ... except NavkitError as exc:
    ...     print(type(exc).__name__, exc)
    NoPathError no path from start_cell (0, 0) to goal_cell (0, 2) (expanded 3 cells)
    >>> issubclass(FilterError, NavkitError), issubclass(ValueError, NavkitError)
    (True, False)
    """


class NoPathError(NavkitError):
    """No path exists between the requested start and goal.

    Parameters
    ----------
    message : str
        Human-readable explanation.
    expanded : int, optional
        Number of nodes (cells or corners) the search expanded before it gave
        up: an integer in [0, 2**63 - 1], a 0-d integer array included (a
        ``TypeError`` for anything else, ``bool`` included; a ``ValueError``
        outside the range).

    Examples
    --------
    >>> err = NoPathError("goal unreachable", expanded=42)
    >>> err.expanded
    42
    """

    def __init__(self, message: str, expanded: int = 0) -> None:
        text: object = message
        count: object = expanded
        if not isinstance(text, str):
            raise TypeError(f"message must be a str, got {type(text).__name__}")
        numpy = sys.modules.get("numpy")  # no array without it; this module stays light
        if numpy is not None and isinstance(count, numpy.ndarray):
            # The shared check takes a 0-d integer array (np.array(3), what a
            # reduction of an integer array gives) and refuses every other array
            # as before. Imported here: navkit._shared imports this module.
            from navkit._shared.validation import bounded_int

            count = bounded_int(count, "expanded", 0, _MAX_EXPANDED)
        if isinstance(count, bool) or not isinstance(count, numbers.Integral):
            raise TypeError(f"expanded must be an integer, got {type(count).__name__}")
        if not 0 <= int(count) <= _MAX_EXPANDED:
            raise ValueError(f"expanded must be in [0, 2**63 - 1], got {_short(count)}")
        super().__init__(text)
        self.expanded: int = int(count)


class FilterError(NavkitError):
    """A filter step failed numerically (e.g. a covariance lost positive definiteness).

    Raised by the filters of :mod:`navkit.estimation`; the filter state is left
    exactly as it was before the failed step, so the filter stays usable.

    Examples
    --------
    A corrupt timestamp: predicting over a gap of 1e300 s would overflow.

    >>> from navkit.estimation import PlanarFusion
    >>> fusion = PlanarFusion(t0=0.0)
    >>> try:
    ...     fusion.update_yaw(1e300, 0.1, variance=1e-3)
    ... except FilterError as exc:
    ...     print(type(exc).__name__, isinstance(exc, NavkitError))
    FilterError True
    >>> fusion.t, fusion.update_yaw(0.1, 0.1, variance=1e-3).accepted
    (0.0, True)
    """


class DataNotFoundError(NavkitError, FileNotFoundError):
    """A data set navkit was asked to use (a map, a log) is not where it looked.

    Raised by the experiments that run on real data (``../shared/data`` beside
    a checkout, or the folder named by ``NAVKIT_DATA`` or ``data_dir=``). It is
    also a ``FileNotFoundError``.

    Examples
    --------
    >>> err = DataNotFoundError("turtlebot3_world.yaml not found in /tmp")
    >>> isinstance(err, FileNotFoundError), isinstance(err, NavkitError)
    (True, True)
    """


class KernelCacheWarning(RuntimeWarning):
    """numba cannot cache navkit's compiled kernels: each process compiles them again.

    Warned once per process when neither the package's ``__pycache__`` folders
    nor the user's cache folder is writable and ``NUMBA_CACHE_DIR`` is not set
    (a read-only installation or container); navkit then works without the
    cache, compiling on first use in every process.

    Examples
    --------
    >>> import warnings
    >>> with warnings.catch_warnings():
    ...     warnings.simplefilter("ignore", KernelCacheWarning)
    >>> issubclass(KernelCacheWarning, RuntimeWarning)
    True
    """
