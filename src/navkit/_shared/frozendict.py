"""A read-only mapping that pickles (private): the named figures of frozen records.

:class:`FrozenDict` holds what a frozen record exposes as a mapping
(``TrialResult.values``, ``ScenarioResult.summary``). A plain dict there could
be changed in place (``result.summary["x"] = 1``), and a ``copy.copy`` of the
record shared it, so editing the copy's figures edited the original's.
:class:`types.MappingProxyType` cannot be pickled, and these records travel to
and from worker processes and Dask clusters.
"""

from __future__ import annotations

from collections.abc import ItemsView, Iterator, KeysView, Mapping, ValuesView
from typing import Any, NoReturn, TypeVar

__all__ = ["FrozenDict"]

_K = TypeVar("_K")
_V = TypeVar("_V")


class FrozenDict(Mapping[_K, _V]):
    """A read-only dict: equal to a dict with the same items, hashable if its values are.

    Built from what builds a dict (a mapping, pairs, keywords), always from a
    copy, so the source can change afterwards without changing it. Item and
    attribute assignment raise :class:`TypeError` and :class:`AttributeError`;
    ``dict(m)`` gives a dict to edit. Pickles under every protocol (as a dict
    does) and prints as a dict. ``json.dumps`` refuses it, as every
    non-dict mapping: convert with ``dict(m)``.

    Parameters
    ----------
    *args, **kwargs
        As for :class:`dict`.

    Examples
    --------
    >>> import pickle
    >>> m = FrozenDict({"a": 1.0, "b": 2.0})
    >>> m, m == {"a": 1.0, "b": 2.0}, pickle.loads(pickle.dumps(m, 0)) == m
    ({'a': 1.0, 'b': 2.0}, True, True)
    >>> m["a"] = 3.0
    Traceback (most recent call last):
    ...
    TypeError: FrozenDict is read-only: cannot set 'a' (edit a copy: dict(...))
    """

    __slots__ = ("_data",)

    _data: dict[_K, _V]

    def __init__(self, *args: Any, **kwargs: Any) -> None:
        _set_data(self, dict(*args, **kwargs))

    @classmethod
    def wrap(cls, data: dict[_K, _V]) -> FrozenDict[_K, _V]:
        """A FrozenDict over ``data`` itself, not a copy: for a dict nothing else holds.

        Saves the copy where a record has just built the dict (its checked
        figures); the caller must not keep or change ``data``.

        Parameters
        ----------
        data : dict
            The items; owned by the result from now on.

        Returns
        -------
        FrozenDict
            A read-only view of ``data``.

        Examples
        --------
        >>> FrozenDict.wrap({"a": 1.0})["a"]
        1.0
        """
        out = object.__new__(cls)
        _set_data(out, data)
        return out

    # -- reading: the dict's own methods (its views are read-only) --

    def __getitem__(self, key: _K) -> _V:
        return self._data[key]

    def __iter__(self) -> Iterator[_K]:
        return iter(self._data)

    def __reversed__(self) -> Iterator[_K]:
        # A dict's keys, last first: Mapping has no __reversed__, so reversed() refused.
        return reversed(self._data)

    def __len__(self) -> int:
        return len(self._data)

    def __contains__(self, key: object) -> bool:
        return key in self._data

    def keys(self) -> KeysView[_K]:
        return self._data.keys()

    def values(self) -> ValuesView[_V]:
        return self._data.values()

    def items(self) -> ItemsView[_K, _V]:
        return self._data.items()

    def get(self, key: _K, default: Any = None) -> Any:
        return self._data.get(key, default)

    # -- what a dict's user writes to get an editable dict: plain dicts back --

    def copy(self) -> dict[_K, _V]:
        """A plain dict of the same items, to edit (``dict.copy``'s spelling).

        Examples
        --------
        >>> figures = FrozenDict({"a": 1.0}).copy()
        >>> figures["b"] = 2.0
        >>> figures
        {'a': 1.0, 'b': 2.0}
        """
        return dict(self._data)

    def __or__(self, other: Mapping[_K, _V]) -> dict[_K, _V]:
        if not isinstance(other, Mapping):
            return NotImplemented
        return {**self._data, **other}

    def __ror__(self, other: Mapping[_K, _V]) -> dict[_K, _V]:
        if not isinstance(other, Mapping):
            return NotImplemented
        return {**other, **self._data}

    # -- comparing, hashing, printing: as a dict of the same items --

    def __eq__(self, other: object) -> bool:
        if isinstance(other, FrozenDict):
            return self._data == other._data
        if isinstance(other, dict):
            return self._data == other
        if isinstance(other, Mapping):
            return self._data == dict(other.items())
        return NotImplemented

    def __hash__(self) -> int:
        # Order-free, as equality is; a TypeError names the unhashable value's type.
        return hash(frozenset(self._data.items()))

    def __repr__(self) -> str:
        return repr(self._data)

    # -- immutability: clear errors rather than Python's generic ones --

    def __setitem__(self, key: object, value: object) -> NoReturn:
        raise TypeError(
            f"{type(self).__name__} is read-only: cannot set {key!r} (edit a copy: dict(...))"
        )

    def __delitem__(self, key: object) -> NoReturn:
        raise TypeError(
            f"{type(self).__name__} is read-only: cannot delete {key!r} (edit a copy: dict(...))"
        )

    def __setattr__(self, name: str, value: object) -> NoReturn:
        raise AttributeError(f"{type(self).__name__} is read-only: cannot set {name!r}")

    def __delattr__(self, name: str) -> NoReturn:
        raise AttributeError(f"{type(self).__name__} is read-only: cannot delete {name!r}")

    # -- copying and pickling --

    def __reduce__(self) -> tuple[Any, ...]:
        # A dict inside: every pickle protocol (0 and 1 refuse bare __slots__),
        # and the class by its import path, for worker processes and Dask.
        return (type(self), (self._data,))

    def __copy__(self) -> FrozenDict[_K, _V]:
        return self  # nothing to change in either

    def __deepcopy__(self, memo: dict[int, Any]) -> FrozenDict[_K, _V]:
        from copy import deepcopy

        return type(self).wrap(deepcopy(self._data, memo))


#: The slot's own setter: __setattr__ refuses, and object.__setattr__ takes
#: about 80 ns more per record built.
_set_data: Any = FrozenDict.__dict__["_data"].__set__
