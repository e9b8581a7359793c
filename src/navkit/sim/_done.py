"""The truth value of a controller's or tracker's ``done`` flag, checked."""

from __future__ import annotations

from numbers import Number
from typing import Any

import numpy as np

__all__ = ["done_flag"]

# Values whose truth is their length: a flag held in one, or its text, is a slip.
_CONTAINERS = (str, bytes, bytearray, list, tuple, dict, set, frozenset)


def done_flag(done: Any, name: str) -> bool:
    """``bool(done)``, or an error naming ``name`` where that would mislead or fail.

    ``name`` is what the message calls the flag ("tracker.done", "the
    controller's done"). A method ``done()`` written without ``@property`` is
    refused (``TypeError``): a bound method is true, and the run would end at
    its first step without a word. A value without a truth value (NumPy's
    "truth value ... is ambiguous" for an array of several flags) is refused
    naming ``name`` (``TypeError``). A number (or a one-element array, numeric
    or of objects, holding one) other than 0 or 1 is refused (``ValueError``):
    a NaN or a ``0.3`` is true in Python and would end the run silently, where
    a flag was meant. So is a masked value (``np.ma.masked``, a masked array
    with a masked element): missing, whatever lies under its mask. Strings
    and Python containers (list, tuple, dict, set, bytes) are refused
    (``TypeError``): their truth value is whether they are empty, so
    ``[False]`` and ``"False"`` are true. So is an object whose class defines
    neither ``__bool__`` nor ``__len__`` (``TypeError``): Python takes every
    such object for true, and it is what a ``__getattr__`` returning a default
    for every name gives for ``done``; a metaclass's do not count (they are
    the class's truth value), so a member of a plain ``Enum`` is refused too.
    Flags (``bool``, ``np.bool_``, one-element boolean arrays), 0 and 1, None,
    and anything else that is no number and defines its truth value keep it.

    Examples
    --------
    >>> import numpy as np
    >>> done_flag(np.True_, "tracker.done"), done_flag(0, "tracker.done")
    (True, False)
    >>> done_flag(np.float64("nan"), "tracker.done")
    Traceback (most recent call last):
    ...
    ValueError: tracker.done must be true or false, got float64 nan (a number other than 0 or 1)
    """
    if done is True or done is False:  # every control step: the common case first
        return done
    if type(done) is np.bool_:  # NumPy's flag (a comparison's result): 60 ns, not 550
        return bool(done)
    if callable(done):
        raise TypeError(
            f"{name} must be true or false (a property or an attribute), got a "
            f"{type(done).__name__}: a method done() needs @property"
        )
    if isinstance(done, _CONTAINERS) and _length_truth(type(done)):
        # Python's truth value of these is "not empty": [False] and "False" are true.
        raise TypeError(
            f"{name} must be true or false, got a {type(done).__name__} (whose truth "
            "value is whether it is empty, not what it holds)"
        )
    if isinstance(done, np.ma.MaskedArray) and np.any(done.mask):
        # Missing, not false: its truth value is the data under the mask's.
        raise ValueError(f"{name} must be true or false, got a masked value (missing)")
    value = done
    if issubclass(type(done), np.ndarray) and done.size == 1:
        if done.dtype.kind in "US":
            # Its truth value is its text's: "False" (and b"0") true, as for a str.
            raise TypeError(
                f"{name} must be true or false, got an ndarray of {done.dtype} (whose "
                "truth value is whether its text is empty, not what it says)"
            )
        if done.dtype.kind in "iufcO":
            # A NumPy scalar, or an object array's element; ``done`` itself is not changed.
            value = np.asarray(done).reshape(-1)[0]
            if done.dtype.kind == "O" and (
                not isinstance(value, Number) or isinstance(value, (bool, np.bool_))
            ):
                # The array's truth value is its element's: a str, a list or a masked
                # value in one is refused as it is alone. An array in one (perhaps the
                # array itself) is refused here, so that this recursion ends.
                if isinstance(value, np.ndarray) and value is not np.ma.masked:
                    raise TypeError(
                        f"{name} must be true or false, got an object array holding an array"
                    )
                return done_flag(value, name)
    if isinstance(value, Number) and not isinstance(value, (bool, np.bool_)):
        number: Any = value  # Number declares no comparisons; its subclasses have them
        try:
            flag = bool(number == 0 or number == 1)
        except Exception:  # a number that cannot be compared (a signalling Decimal NaN)
            flag = False
        if not flag:
            raise ValueError(
                f"{name} must be true or false, got {type(done).__name__} {_text(value)} "
                "(a number other than 0 or 1)"
            )
    kind = type(done)
    if not _defines_truth(kind):
        # Python takes any such object for true: a __getattr__ that answers every
        # name (a default for options, say) answers for ``done`` too, and the run
        # ended at its first step as "controller done".
        raise TypeError(
            f"{name} must be true or false, got a {kind.__name__}, which has no truth "
            f"value of its own (every {kind.__name__} is true); a __getattr__ that "
            "answers every name answers for done too"
        )
    try:
        return bool(done)
    except Exception as exc:
        raise TypeError(f"{name} must be true or false, got {type(done).__name__} ({exc})") from exc


def _text(value: Any) -> str:
    """``str(value)``, at most 40 characters: an int past 4300 digits has no str."""
    try:
        text = str(value)
    except ValueError:
        return "of more than 4300 digits"
    return text if len(text) <= 40 else f"{text[:18]}...{text[-18:]}"


def _length_truth(kind: type) -> bool:
    """Whether the truth value of a ``kind`` (a subclass of a container) is its length.

    Not when a class of the user's before the built-in one defines ``__bool__``
    (a NamedTuple of a status whose truth is its flag, say).
    """
    for klass in kind.__mro__:
        if klass in _CONTAINERS:
            return True
        if "__bool__" in vars(klass):
            return False
    return True  # pragma: no cover (kind is a subclass of one of _CONTAINERS)


def _defines_truth(kind: type) -> bool:
    """Whether ``kind`` or a class it inherits from defines ``__bool__`` or ``__len__``.

    Not ``getattr(kind, ...)``: that falls back to the metaclass, whose methods
    are the class's own truth value, not its instances' (``EnumType.__bool__``
    let every member of a plain Enum, all true, through).
    """
    return any(
        vars(klass).get(name) is not None
        for klass in kind.__mro__
        for name in ("__bool__", "__len__")
    )
