"""Private conversion of a record's text fields to plain ``str``.

One helper for every record: a field given a ``str`` subclass (NumPy's
``np.str_``, a label read from an array) kept it, and NumPy 2 writes it as
``np.str_('x')`` in the record's repr and in messages quoting it.
"""

from __future__ import annotations

__all__ = ["as_text"]


def as_text(value: object, name: str) -> str:
    """``value`` as a plain ``str`` (``type(result) is str``).

    Parameters
    ----------
    value : object
        The text; a ``str`` subclass (``np.str_``) is copied to a plain ``str``.
    name : str
        The argument's name, for the message.

    Returns
    -------
    str
        ``value`` itself if it is a plain ``str``, else a plain copy of it.

    Raises
    ------
    TypeError
        ``value`` is no ``str`` (``bytes`` included), naming ``name``.

    Examples
    --------
    >>> import numpy as np
    >>> as_text(np.str_("scan"), "topic"), type(as_text(np.str_("scan"), "topic")).__name__
    ('scan', 'str')
    >>> as_text(b"scan", "topic")
    Traceback (most recent call last):
    ...
    TypeError: topic must be a str, got bytes
    """
    if not isinstance(value, str):
        raise TypeError(f"{name} must be a str, got {type(value).__name__}")
    # str.__str__ returns a plain str with the subclass's characters, and never
    # calls a subclass's own __str__ (which may say anything).
    return str.__str__(value)
