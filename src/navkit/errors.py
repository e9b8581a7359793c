"""Exceptions raised by navkit.

Every navkit-specific exception derives from :class:`NavkitError`, so callers can
catch all of them at once. Invalid arguments raise the built-in ``ValueError`` or
``TypeError`` (with the argument named in the message) rather than a navkit class.
"""

from __future__ import annotations

__all__ = ["FilterError", "NavkitError", "NoPathError"]


class NavkitError(Exception):
    """Base class of navkit's own exceptions."""


class NoPathError(NavkitError):
    """No path exists between the requested start and goal.

    Parameters
    ----------
    message : str
        Human-readable explanation.
    expanded : int, optional
        Number of nodes (cells or corners) the search expanded before it gave up.

    Examples
    --------
    >>> err = NoPathError("goal unreachable", expanded=42)
    >>> err.expanded
    42
    """

    def __init__(self, message: str, expanded: int = 0) -> None:
        super().__init__(message)
        self.expanded = int(expanded)


class FilterError(NavkitError):
    """A filter step failed numerically (e.g. a covariance lost positive definiteness).

    Raised by the filters of :mod:`navkit.estimation`; the filter state is left
    exactly as it was before the failed step.
    """
