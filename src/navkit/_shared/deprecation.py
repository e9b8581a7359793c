"""Renamed keyword arguments: the old name keeps working for a release, with a warning.

navkit renames an option when two packages used two words for one idea (one
vocabulary across packages). The old keyword stays accepted, as a keyword-only
argument defaulting to None and listed under "Other Parameters", and
:func:`renamed_keyword` resolves the pair at the top of the function. A
configuration record whose fields became keyword-only keeps taking them by
position for a release, with a warning: :func:`positional_deprecated`.
"""

from __future__ import annotations

import dataclasses
import functools
import warnings
from typing import Any, TypeVar

__all__ = ["positional_deprecated", "renamed_keyword"]

_T = TypeVar("_T")
_C = TypeVar("_C", bound=type)


def renamed_keyword(
    old_name: str,
    old_value: _T | None,
    new_name: str,
    new_value: _T,
    new_default: _T,
    *,
    use: str | None = None,
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
    use : str, optional
        What the warning tells the caller to write instead, when the new
        keyword takes the value in another form (``"after='loop'"`` for
        ``loop=True``); default ``new_name``, for the same value.
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
        # The old value is not always one the new name takes (loop=True is
        # after='loop'): "use after" alone sent callers to after=True.
        f"{old_name} is deprecated and will be removed in a future release: "
        f"use {new_name if use is None else use}",
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


def positional_deprecated(cls: _C) -> _C:
    """Class decorator (outermost, on a ``kw_only`` dataclass): positional fields still work.

    The dataclass's own ``__init__`` takes its fields by keyword only, which is
    what type checkers and :func:`inspect.signature` see; this wrapper still
    accepts them by position, in field order, with a :class:`DeprecationWarning`
    pointing at the caller's line, and passes them on as keywords. Fields added
    later, marked ``field(metadata={"positional": False})``, are never taken by
    position (they never were).

    Raises
    ------
    TypeError
        More positional arguments than fields, or a field given both by
        position and by keyword (as Python's own message says).

    Warns
    -----
    DeprecationWarning
        When any field was passed by position.

    Examples
    --------
    >>> import warnings
    >>> from dataclasses import dataclass
    >>> @positional_deprecated
    ... @dataclass(frozen=True, kw_only=True)
    ... class Band:
    ...     low: float = 0.0
    ...     high: float = 1.0
    >>> with warnings.catch_warnings(record=True) as caught:
    ...     warnings.simplefilter("always")
    ...     Band(0.5, high=2.0)
    Band(low=0.5, high=2.0)
    >>> print(caught[0].message)
    Band(low) by position is deprecated and will be removed in a future release: pass low=
    """
    names = [
        f.name for f in dataclasses.fields(cls) if f.init and f.metadata.get("positional", True)
    ]
    init = cls.__dict__["__init__"]  # the dataclass's own (mypy refuses cls.__init__)
    qualname = cls.__qualname__

    @functools.wraps(init)
    def __init__(self: Any, *args: Any, **kwargs: Any) -> None:
        if args:
            if len(args) > len(names):
                raise TypeError(
                    f"{qualname} takes at most {len(names)} positional arguments (deprecated; "
                    f"pass {', '.join(n + '=' for n in names)}), got {len(args)}"
                )
            given = names[: len(args)]
            for name in given:
                if name in kwargs:
                    raise TypeError(f"{qualname} got multiple values for argument {name!r}")
            warnings.warn(
                f"{qualname}({', '.join(given)}) by position is deprecated and will be removed "
                f"in a future release: pass {', '.join(n + '=' for n in given)}",
                DeprecationWarning,
                stacklevel=2,
            )
            kwargs.update(zip(given, args, strict=True))
        init(self, **kwargs)

    # Set on the class built by the dataclass decorator (a slotted one is a new class).
    setattr(cls, "__init__", __init__)  # noqa: B010 (mypy refuses assigning a method)
    return cls
