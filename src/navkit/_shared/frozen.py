"""Restoring frozen dataclasses that hold read-only arrays (private).

``pickle`` and :func:`copy.deepcopy` rebuild a slotted dataclass from its field
values without running ``__post_init__``, and the arrays they copy come back
writable: a "frozen" record whose arrays can be changed in place. The records'
``__setstate__`` use :func:`restore_read_only` to set their arrays read-only
again.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import fields
from typing import Any

import numpy as np

__all__ = ["restore_read_only"]


def restore_read_only(record: Any, state: Sequence[Any], arrays: Sequence[str]) -> None:
    """Set ``record``'s fields from ``state`` (their values, in order); freeze ``arrays``.

    Parameters
    ----------
    record : dataclass instance
        The record being restored (its ``__setstate__``'s ``self``).
    state : sequence
        The field values, in field order (what a slotted dataclass pickles).
    arrays : sequence of str
        Names of the fields holding arrays to make read-only (None values skipped).

    Examples
    --------
    >>> import copy
    >>> from dataclasses import dataclass
    >>> @dataclass(frozen=True, slots=True)
    ... class Record:
    ...     values: np.ndarray
    ...     def __setstate__(self, state: list[Any]) -> None:
    ...         restore_read_only(self, state, ("values",))
    >>> copy.deepcopy(Record(np.zeros(2))).values.flags.writeable
    False
    """
    for field, value in zip(fields(record), state, strict=True):
        object.__setattr__(record, field.name, value)
    for name in arrays:
        array = getattr(record, name)
        if isinstance(array, np.ndarray):
            array.flags.writeable = False
