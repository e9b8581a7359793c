"""Renamed keyword arguments: the old name keeps working for a release, with a warning.

navkit renames an option when two packages used two words for one idea (one
vocabulary across packages). The old keyword stays accepted, as a keyword-only
argument defaulting to None and listed under "Other Parameters", and
:func:`renamed_keyword` resolves the pair at the top of the function.
"""

from __future__ import annotations

import warnings
from typing import TypeVar

__all__ = ["renamed_keyword"]

_T = TypeVar("_T")


def renamed_keyword(
    old_name: str,
    old_value: _T | None,
    new_name: str,
    new_value: _T,
    new_default: _T,
    *,
    stacklevel: int = 3,
) -> _T:
    """The value of a renamed keyword, warning when the caller used its old name.

    Parameters
    ----------
    old_name, new_name : str
        The keyword's old and new names (``"Class(old)"`` style qualifiers are
        allowed: they appear as written in the messages).
    old_value : object or None
        What the caller passed under the old name (None: not used).
    new_value : object
        What the caller passed under the new name (its default when not used).
    new_default : object
        The new name's default, to tell "not passed" from "passed".
    stacklevel : int, optional
        Passed to :func:`warnings.warn`; the default 3 points at the caller
        of the function that calls this one.

    Returns
    -------
    object
        ``old_value`` when the old name was used, else ``new_value``.

    Raises
    ------
    TypeError
        When both names were given. A new name passed with exactly its default
        value cannot be told from one not passed: the old name's value then
        wins, with the warning.

    Warns
    -----
    DeprecationWarning
        When the old name was used.

    Examples
    --------
    >>> import warnings
    >>> from navkit._shared.deprecation import renamed_keyword
    >>> renamed_keyword("max_range", None, "range_max", 5.0, 30.0)
    5.0
    >>> with warnings.catch_warnings(record=True) as caught:
    ...     warnings.simplefilter("always")
    ...     renamed_keyword("max_range", 4.0, "range_max", 30.0, 30.0)
    4.0
    >>> caught[0].category.__name__
    'DeprecationWarning'
    """
    if old_value is None:
        return new_value
    if _passed(new_value, new_default):
        raise TypeError(f"got both {new_name} and its old name {old_name}: pass only {new_name}")
    warnings.warn(
        f"{old_name} is deprecated and will be removed in a future release: use {new_name}",
        DeprecationWarning,
        stacklevel=stacklevel,
    )
    return old_value


def _passed(value: object, default: object) -> bool:
    """Whether ``value`` differs from ``default`` (arrays compare as passed unless identical)."""
    if value is default:
        return False
    try:
        return bool(value != default)
    except (TypeError, ValueError):  # an array's elementwise != has no single truth value
        return True
