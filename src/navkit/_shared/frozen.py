"""Restoring frozen dataclasses that hold read-only arrays (private).

``pickle`` and :func:`copy.deepcopy` rebuild a slotted dataclass from its field
values without running ``__post_init__``, and the arrays they copy come back
writable: a "frozen" record whose arrays can be changed in place. The records'
``__setstate__`` use :func:`restore_read_only` to set their arrays read-only
again, and their ``__reduce__`` :func:`reduce_record`, which also keeps what a
subclass adds; ordinary classes with ``__slots__`` use :func:`restore_slots`,
and :func:`extra_state` for what a subclass adds when they reduce themselves.
:func:`frozen_setattr` gives a frozen slotted dataclass the ``__setattr__`` and
``__delattr__`` Python 3.11's dataclass decorator gets wrong for it.
A record class (or slotted class) that gained fields after a release names
them in an ``_added_fields`` class attribute (:func:`fill_added_fields`), so
that its own older pickles and its subclasses' load with those fields' defaults.
"""

from __future__ import annotations

import threading
import weakref
from collections.abc import Callable, Collection, Mapping, Sequence
from dataclasses import FrozenInstanceError, fields
from typing import Any, TypeVar

import numpy as np

__all__ = [
    "extra_state",
    "fill_added_fields",
    "frozen_setattr",
    "rebuild_from_state",
    "rebuild_record",
    "reduce_record",
    "restore_extra",
    "restore_read_only",
    "restore_slots",
    "slot_names",
]

_T = TypeVar("_T", bound=type)


def frozen_setattr(cls: _T) -> _T:
    """Class decorator (above ``@dataclass(frozen=True, slots=True)``): clear frozen errors.

    ``dataclass(frozen=True, slots=True)`` builds a new class for the slots, but
    the ``__setattr__`` and ``__delattr__`` it generated still refer to the
    class it started from, so setting or deleting any name that is not a field
    -- on the record or on an instance of a subclass -- raised ``TypeError:
    super(type, obj): obj must be an instance or subtype of type``. These
    replacements keep the frozen dataclass rules with the right class: on the
    record itself every name raises :class:`dataclasses.FrozenInstanceError`
    (an ``AttributeError``) naming the class; on a subclass the record's fields
    raise it too, and other names are set or deleted as the subclass's own
    layout allows (its ``__dict__`` or slots; ``AttributeError`` otherwise), as
    for frozen dataclasses without slots. Construction does not go through
    them (the generated ``__init__`` uses ``object.__setattr__``). A record
    with no ``__reduce__`` of its own also gets a ``__reduce_ex__`` that copies
    and pickles a subclass through :func:`reduce_record` (what it adds is kept;
    a user's ``__getstate__`` taken at its word, as Python takes it; a
    subclass's own ``__reduce__`` called instead, as Python calls it); the
    record's own pickles are unchanged.

    Examples
    --------
    >>> from dataclasses import dataclass
    >>> @frozen_setattr
    ... @dataclass(frozen=True, slots=True)
    ... class Point:
    ...     x: float
    >>> class Tagged(Point):
    ...     pass
    >>> Point(1.0).y = 2.0
    Traceback (most recent call last):
    ...
    dataclasses.FrozenInstanceError: cannot set attribute 'y': Point is frozen
    >>> Tagged(1.0).x = 2.0  # doctest: +ELLIPSIS
    Traceback (most recent call last):
    ...
    dataclasses.FrozenInstanceError: cannot assign to field 'x': Point is frozen ...
    >>> tagged = Tagged(1.0)
    >>> tagged.note = "kept"
    >>> tagged.note
    'kept'
    """
    names = frozenset(field.name for field in fields(cls))
    owner: type[Any] = cls

    def refuse(name: str, verb: str) -> FrozenInstanceError:
        if name in names:
            return FrozenInstanceError(
                f"cannot {verb} field {name!r}: {cls.__name__} is frozen (use dataclasses.replace)"
            )
        what = "set" if verb == "assign to" else verb
        return FrozenInstanceError(f"cannot {what} attribute {name!r}: {cls.__name__} is frozen")

    def __setattr__(self: Any, name: str, value: Any) -> None:
        if type(self) is owner or name in names:
            raise refuse(name, "assign to")
        super(owner, self).__setattr__(name, value)

    def __delattr__(self: Any, name: str) -> None:
        if type(self) is owner or name in names:
            raise refuse(name, "delete")
        super(owner, self).__delattr__(name)

    functions: list[Any] = [__setattr__, __delattr__]
    reductions = ("__reduce__", "__reduce_ex__")
    if all(getattr(cls, name) is getattr(object, name) for name in reductions):
        # A record without a __reduce__ of its own pickles and copies as the list of
        # its field values (the slotted dataclass's __getstate__): a user's subclass
        # lost the attributes it added (its __dict__, its slots), and one with a
        # __getstate__ returning a dict had its keys read as field values (review
        # 36). Subclasses go through reduce_record as the records with a __reduce__
        # do; the record itself pickles as before, byte for byte.

        def __reduce_ex__(self: Any, protocol: Any) -> Any:
            if type(self) is owner:
                return object.__reduce_ex__(self, protocol)
            reduce: Any = type(self).__reduce__
            if reduce is not object.__reduce__:
                # A subclass's own __reduce__ (a user's) is called, as Python's
                # __reduce_ex__ calls it; it was ignored (review 37).
                return self.__reduce__()
            return reduce_record(self)

        functions.append(__reduce_ex__)
    for function in functions:
        function.__qualname__ = f"{cls.__qualname__}.{function.__name__}"
        function.__module__ = cls.__module__
        setattr(cls, function.__name__, function)
    return cls


def read_only_view(array: np.ndarray[Any, Any]) -> np.ndarray[Any, Any]:
    """A read-only view of ``array``, which is left as it is (writeable or not).

    Examples
    --------
    >>> values = np.zeros(2)
    >>> read_only_view(values).flags.writeable, values.flags.writeable
    (False, True)
    """
    view = array.view()
    view.flags.writeable = False
    return view


def restore_read_only(
    record: Any, state: Sequence[Any] | Mapping[str, Any], arrays: Sequence[str]
) -> None:
    """Set ``record``'s fields from ``state`` (their values, in order); freeze ``arrays``.

    Parameters
    ----------
    record : dataclass instance
        The record being restored (its ``__setstate__``'s ``self``).
    state : list, dict or tuple
        The field values, in field order (what a slotted dataclass pickles; a
        pickle made before fields named in the class's ``_added_fields`` were
        added lacks them, and they get their defaults, see
        :func:`fill_added_fields`); a dict of them by name (the instance
        ``__dict__`` a dataclass without slots pickles: the record's pickles
        from before it had slots, old names mapped by the class's
        ``_renamed_fields``); or the tuple ``(instance __dict__ or None,
        {slot: value})`` of what a subclass adds, which :func:`reduce_record`
        restores after the rebuild (:func:`restore_extra`; the fields are left
        as they are).
    arrays : sequence of str
        Names of the fields holding arrays to make read-only (None values skipped).

    Raises
    ------
    ValueError
        A list of field values longer than the fields, or shorter by more than
        the fields added since a release; a dict naming a field the class does
        not have, or lacking one that was not added since a release.

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
    if isinstance(state, tuple):
        # What reduce_record restores after the rebuild (a subclass's __dict__ and
        # slots); the fields of older pickles come as a list.
        restore_extra(record, state)
        return
    names = [field.name for field in fields(record)]
    if isinstance(state, Mapping):
        _restore_field_dict(record, state, names)
    else:
        missing = len(names) - len(state)
        if missing > 0:
            # A pickle made before the last ``missing`` fields of _added_fields were
            # added: its list holds the others, in order; those get their defaults.
            added = list(_added_fields(type(record)))
            if missing <= len(added):
                later = set(added[len(added) - missing :])
                names = [name for name in names if name not in later]
        for name, value in zip(names, state, strict=True):
            object.__setattr__(record, name, value)
        fill_added_fields(record)
    for name in arrays:
        array = getattr(record, name)
        if isinstance(array, np.ndarray):
            array.flags.writeable = False


def _restore_field_dict(record: Any, state: Mapping[str, Any], names: Sequence[str]) -> None:
    """Set ``record``'s fields from the instance ``__dict__`` of a pickle made while its
    class was a dataclass without slots (old names through ``_renamed_fields``).

    Zipped with the fields as a list, its keys became the values: a ``GameState``
    pickled before issue 11 loaded with ``robot_xy='robot'`` and so on (review 50).
    """
    cls = type(record)
    renamed: Mapping[str, str] = getattr(cls, "_renamed_fields", None) or {}
    instance = getattr(record, "__dict__", None)
    for old, value in state.items():
        name = renamed.get(old, old)
        if name in names:
            object.__setattr__(record, name, value)
        elif instance is not None:
            instance[old] = value  # a subclass's own attribute
        else:
            raise ValueError(
                f"{cls.__name__} has no field {old!r}: this pickle of it was made by a "
                f"release whose fields differ (fields now: {', '.join(names)})"
            )
    fill_added_fields(record)
    unset = [name for name in names if not hasattr(record, name)]
    if unset:
        raise ValueError(
            f"this pickle of a {cls.__name__} holds no value for {', '.join(unset)}: it "
            "was made by a release whose fields differ"
        )


def slot_names(cls: type, *, below: type | None = None) -> list[str]:
    """Names of the slots of ``cls`` and its bases, private ones mangled.

    Parameters
    ----------
    cls : type
        The class.
    below : type, optional
        Stop at this base: only the slots of the classes before it in
        ``cls.__mro__`` (what subclasses of ``below`` add). All by default.

    Returns
    -------
    list of str
        The attribute names (``__dict__`` and ``__weakref__`` left out).

    Examples
    --------
    >>> class Base:
    ...     __slots__ = ("a",)
    >>> class Sub(Base):
    ...     __slots__ = ("b", "__c")
    >>> slot_names(Sub), slot_names(Sub, below=Base)
    (['b', '_Sub__c', 'a'], ['b', '_Sub__c'])
    """
    names = []
    for klass in cls.__mro__:
        if klass is below:
            break
        declared = klass.__dict__.get("__slots__", ())
        for name in (declared,) if isinstance(declared, str) else declared:
            if name in ("__dict__", "__weakref__"):
                continue
            if name.startswith("__") and not name.endswith("__"):
                name = f"_{klass.__name__.lstrip('_')}{name}"  # as Python mangles it
            names.append(name)
    return names


def extra_state(
    obj: Any, *, below: type | None = None, skip: Collection[str] = ()
) -> tuple[dict[str, Any] | None, dict[str, Any]] | None:
    """What ``obj`` holds beyond a base class's own state, in Python's pickle layout.

    For classes that copy and pickle through a ``__reduce__`` rebuilding the
    base's state alone: a subclass's attributes (its ``__dict__``, its slots)
    go into the reduce value's state, which :mod:`copy` and :mod:`pickle`
    restore after the rebuild, so that subclasses copy whole.

    Parameters
    ----------
    obj : object
        The object being copied or pickled.
    below : type, optional
        Only the slots of the classes before this one in the MRO (see
        :func:`slot_names`); all by default.
    skip : collection of str
        Slots left out (a dataclass's fields, copied by the rebuild).

    Returns
    -------
    tuple or None
        ``(instance __dict__ or None, {slot: value})``; None when there is
        nothing to add.

    Examples
    --------
    >>> class Base:
    ...     __slots__ = ("a",)
    >>> class Sub(Base):
    ...     __slots__ = ("b",)
    >>> sub = Sub()
    >>> sub.a, sub.b = 1, 2
    >>> extra_state(sub, below=Base), extra_state(Base())
    ((None, {'b': 2}), None)
    """
    slots = {
        name: getattr(obj, name)
        for name in slot_names(type(obj), below=below)
        if name not in skip and hasattr(obj, name)
    }
    instance = getattr(obj, "__dict__", None) or None
    if instance is None and not slots:
        return None
    return instance, slots


def reduce_record(record: Any, arrays: Collection[str] | None = None) -> tuple[Any, ...]:
    """``__reduce__`` of a frozen slotted dataclass holding read-only arrays.

    A slotted dataclass pickles and copies as the list of its field values:
    a subclass loses what it adds (its ``__dict__``, its own slots), and a
    subclass that is itself a slotted frozen dataclass (to add a field) gets a
    generated ``__setstate__`` of its own, which restores writable arrays. A
    ``__reduce__`` is inherited by every subclass (the dataclass decorator
    adds none): copies and pickles go through :func:`rebuild_record`. Give the
    record a ``__setstate__`` calling :func:`restore_read_only`: older pickles
    call it with the field values, and :mod:`pickle` and :mod:`copy` with what
    a subclass adds (its ``__dict__``, its slots), restored after the rebuild so
    that an attribute referring back to the record finds the new one. A record
    whose ``__setstate__`` is not navkit's gets what a subclass adds among the
    rebuild's arguments instead (an attribute referring back is then lost).

    A subclass whose own ``__getstate__`` or ``__setstate__`` (a user's: not
    the one a slotted frozen dataclass generates, nor navkit's) says what it
    pickles, to drop a lock or a cache, say, is taken at its word, as Python
    takes it: the state (the user's ``__getstate__``'s, else Python's default
    ``(instance __dict__ or None, {slot: value})``) goes to the user's
    ``__setstate__``, or without one is restored as Python restores it (see
    :func:`rebuild_from_state`), and the ``arrays`` are read-only again after
    it. The state is pickled (and deep-copied) after the new record exists, so
    a state referring back to the record (a parent link) refers to the new one:
    cycles are kept, as for any Python object.

    Parameters
    ----------
    record : dataclass instance
        The record being pickled or copied (its ``__reduce__``'s ``self``).
    arrays : collection of str, optional
        Fields whose arrays copies hold read-only. By default the fields whose
        arrays are read-only in ``record``: copies keep the flags as they were.

    Returns
    -------
    tuple
        ``(rebuild_record, (class, {field: value}, arrays, None, {}),
        (instance __dict__ or None, {other slot: value}))``, without the last
        item when a subclass adds nothing; ``(rebuild_record, (class, {field:
        value}, arrays, instance __dict__ or None, {other slot: value}))``
        when the class's ``__setstate__`` is not navkit's (the one a slotted
        dataclass subclass of the user's generates would read the pair as
        field values); ``(_shell_record, (shell,))`` for a class with a
        user's ``__getstate__`` or ``__setstate__``, the shell reducing to a
        new empty record and the state.

    Examples
    --------
    >>> import copy
    >>> from dataclasses import dataclass
    >>> @dataclass(frozen=True, slots=True)
    ... class Record:
    ...     values: np.ndarray
    ...     def __reduce__(self) -> tuple[Any, ...]:
    ...         return reduce_record(self, ("values",))
    >>> @dataclass(frozen=True, slots=True)
    ... class Tagged(Record):
    ...     tag: str = ""
    >>> copied = copy.deepcopy(Tagged(np.zeros(2), "a"))
    >>> type(copied).__name__, copied.tag, copied.values.flags.writeable
    ('Tagged', 'a', False)
    """
    values = {field.name: getattr(record, field.name) for field in fields(record)}
    if arrays is None:
        arrays = [
            name
            for name, value in values.items()
            if isinstance(value, np.ndarray) and not value.flags.writeable
        ]
    cls = type(record)
    if _takes_user_state(cls):
        # The state is pickled after the new record exists (the shell's), so that a
        # state referring back to the record finds the new one: in the rebuild's
        # arguments it recursed until RecursionError.
        return _shell_record, (_source_shell(record, tuple(arrays)),)
    extra = extra_state(record, skip=values)
    if extra is None:
        return rebuild_record, (type(record), values, tuple(arrays), None, {})
    if _restores_extra(type(record)):
        # After the rebuild, as Python restores any object's state: an attribute that
        # leads back to the record (a parent link, a bound method kept as a callback)
        # then finds the new record. Among the rebuild's arguments it was pickled (and
        # deep-copied) before the record existed: pickles lost the whole __dict__.
        return rebuild_record, (type(record), values, tuple(arrays), None, {}), extra
    return rebuild_record, (type(record), values, tuple(arrays), *extra)


def restore_extra(record: Any, state: tuple[Any, Any]) -> None:
    """Restore what a subclass adds to a record: ``(instance __dict__ or None, {slot: value})``.

    As Python restores the state of an object with slots, the record's own
    frozen guard passed (its subclass's attributes are not its fields).

    Examples
    --------
    >>> from dataclasses import dataclass
    >>> @dataclass(frozen=True, slots=True)
    ... class Record:
    ...     x: float
    >>> class Tagged(Record):
    ...     pass
    >>> tagged = object.__new__(Tagged)
    >>> restore_extra(tagged, ({"tag": "a"}, {}))
    >>> tagged.tag
    'a'
    """
    instance, slots = state
    if instance:
        record.__dict__.update(instance)
    for name, value in (slots or {}).items():
        object.__setattr__(record, name, value)


def _restores_extra(cls: type) -> bool:
    """Whether the ``__setstate__`` that :mod:`pickle` calls on a ``cls`` is navkit's.

    Navkit's read :func:`restore_extra`'s pair (through
    :func:`restore_read_only`). Not the one a slotted dataclass generates (a
    user's subclass that adds a field), which would set the pair's two items
    as the first two fields, nor a user's, which is not called on this path.
    """
    for klass in cls.__mro__:
        method = klass.__dict__.get("__setstate__")
        if method is not None:
            module = getattr(method, "__module__", None) or ""
            return module == "navkit" or module.startswith("navkit.")
    return False


def _user_getstate(cls: type) -> Any:
    """The ``__getstate__`` that a user's class gives ``cls``, or None.

    Not object's, not the one ``dataclass(frozen=True, slots=True)`` generates
    (it lists the fields alone, as :func:`reduce_record` would do better), and
    not one of navkit's own classes (whose pickles stay as they were).
    """
    return _user_method(cls, "__getstate__")


def _takes_user_state(cls: type) -> bool:
    """Whether a user's class gives ``cls`` its ``__getstate__`` or its ``__setstate__``."""
    module = cls.__module__
    if module == "navkit" or module.startswith("navkit."):
        # Every copy of a record asks: navkit's own classes (and their navkit bases)
        # answer without walking the MRO twice.
        return False
    return _user_getstate(cls) is not None or _user_method(cls, "__setstate__") is not None


def _user_method(cls: type, name: str) -> Any:
    """The method ``name`` that a user's class gives ``cls``: as :func:`_user_getstate`."""
    for klass in cls.__mro__:
        method = klass.__dict__.get(name)
        if method is None:
            continue
        module = klass.__module__
        if (
            klass is object
            or getattr(method, "__module__", None) == "dataclasses"
            or module == "navkit"
            or module.startswith("navkit.")
        ):
            return None
        return method
    return None


def _restore_default(record: Any, state: Any) -> None:
    """Restore ``state`` as :mod:`pickle` restores a class without ``__setstate__``.

    ``state`` is the instance ``__dict__`` or ``(__dict__, {slot: value})``. Set
    past the frozen guard (a record's fields are slots, which a user's state
    names): the record is not yet anyone's.
    """
    slots = None
    if isinstance(state, tuple) and len(state) == 2:
        state, slots = state
    for part in (state, slots):
        if not part:
            continue
        if not isinstance(part, Mapping):
            raise TypeError(
                f"{type(record).__name__}.__getstate__ returned a state that a class "
                "without a __setstate__ of its own cannot restore: a dict, or a pair "
                f"(dict or None, dict), got a {type(part).__name__} in it; define "
                "__setstate__ as well"
            )
        for name, value in part.items():
            object.__setattr__(record, name, value)


def rebuild_from_state(cls: type, state: Any, arrays: Collection[str]) -> Any:
    """The record of class ``cls`` restored from a user's ``__getstate__`` ``state``.

    What pickles of records with a user's ``__getstate__`` made before review
    32 load through; :func:`reduce_record` now pickles the state after the new
    record exists, restored the same way.

    As :mod:`pickle` and :mod:`copy` restore an object: through a
    ``__setstate__`` of the user's classes, or, without one, ``state`` as the
    instance ``__dict__`` or ``(__dict__, {slot: value})``, a field (a slot)
    set from either; nothing for a None state. The record's own
    ``__setstate__`` (navkit's, or a slotted dataclass's) reads a list of
    field values, never a user's state: it is not called. The fields
    named in ``arrays`` that hold writeable arrays then hold read-only views
    of them (the arrays themselves are not changed), and a record class
    with a ``_freeze_nested(record)`` method (arrays nested in its fields'
    tuples) has it called.

    Raises
    ------
    TypeError
        Without a user's ``__setstate__``, for a state that is not a dict
        (or such a pair), naming the class.

    Examples
    --------
    >>> from dataclasses import dataclass
    >>> @dataclass(frozen=True)
    ... class Record:
    ...     values: np.ndarray
    >>> record = rebuild_from_state(Record, {"values": np.zeros(2)}, ("values",))
    >>> record.values.flags.writeable
    False
    """
    record: Any = object.__new__(cls)
    _restore_state(record, state, arrays)
    return record


class _Shell:
    """Holder of a record copied or pickled through a user's state (:func:`reduce_record`).

    A source shell (``loaded`` False) stands for the original record: its
    reduce value is the new shell, then the state, which :mod:`pickle` and
    :mod:`copy` take after the new shell exists. A reference back to the record
    inside the state is reduced to the same source shell (found in
    ``_SHELLS``), that is to the new shell's record: cycles are kept, as
    Python keeps them for any object whose state refers back to it.
    """

    __slots__ = ("__weakref__", "arrays", "loaded", "record")

    def __init__(self, record: Any, arrays: tuple[str, ...], loaded: bool) -> None:
        self.record = record
        self.arrays = arrays
        self.loaded = loaded

    def __reduce__(self) -> tuple[Any, ...]:
        try:
            state = (_state_of(self.record), _Forget(self.record))
        except BaseException:
            # A user's __getstate__ that raised: the copy ends here, and the traceback
            # (which holds this shell) must not keep its entry.
            _forget(self.record)
            raise
        return _new_shell, (type(self.record), self.arrays), state

    def __setstate__(self, state: tuple[Any, Any]) -> None:
        _restore_state(self.record, state[0], self.arrays)


class _Forget:
    """Last item of a shell's state: pickled or copied once the state before it is, it
    drops the source shell from ``_SHELLS``."""

    __slots__ = ("record",)

    def __init__(self, record: Any) -> None:
        self.record = record

    def __reduce__(self) -> tuple[Any, ...]:
        _forget(self.record)
        return _nothing, ()


# Source shells of the records being copied or pickled in this thread, by id(record):
# the reductions of one record met again inside its own state share one shell. An
# entry holds its record, so the id is not reused while it is there. Weak values:
# the copy or pickle under way holds its shell (in its memo or on its stack) until it
# ends; one that failed after the shell's state was handed over (an item of the state
# that cannot be pickled or copied) never reaches _Forget, and its entry goes with
# the shell instead of keeping the record until that record is copied again.
_SHELLS = threading.local()


def _shells() -> weakref.WeakValueDictionary[int, _Shell]:
    table: weakref.WeakValueDictionary[int, _Shell] | None = getattr(_SHELLS, "table", None)
    if table is None:
        table = _SHELLS.table = weakref.WeakValueDictionary()
    return table


def _source_shell(record: Any, arrays: tuple[str, ...]) -> _Shell:
    table = _shells()
    shell = table.get(id(record))
    if shell is None or shell.record is not record:
        shell = table[id(record)] = _Shell(record, arrays, loaded=False)
    return shell


def _forget(record: Any) -> None:
    table = _shells()
    shell = table.get(id(record))
    if shell is not None and shell.record is record:
        del table[id(record)]


def _nothing() -> None:
    return None


def _new_shell(cls: type, arrays: tuple[str, ...]) -> _Shell:
    return _Shell(object.__new__(cls), arrays, loaded=True)


def _shell_record(shell: _Shell) -> Any:
    """The record a shell holds: the new one of a pickle or deep copy; for
    :func:`copy.copy` (the reduce value used as it is) a new record restored
    from the original's state, not copied, as Python copies any object."""
    if shell.loaded:
        return shell.record
    source = shell.record
    _forget(source)
    record = object.__new__(type(source))
    _restore_state(record, _state_of(source), shell.arrays)
    return record


def _state_of(record: Any) -> Any:
    """``record``'s state as Python takes it: its class's ``__getstate__`` if a user's
    class defines one, else the default ``(instance __dict__ or None, {slot: value})``
    (not the list of fields that a slotted dataclass's ``__getstate__`` gives)."""
    if _user_getstate(type(record)) is not None:
        return record.__getstate__()
    return object.__getstate__(record)


def _restore_state(record: Any, state: Any, arrays: Collection[str]) -> None:
    """Restore ``state`` into ``record`` as :func:`rebuild_from_state` does."""
    if state is not None:
        if _user_method(type(record), "__setstate__") is not None:
            record.__setstate__(state)
        else:
            # Not the record's own __setstate__ (navkit's loader of older pickles, or the
            # one a slotted dataclass generates: both read a list of field values, and a
            # user's dict went in as one, each field set to its own name).
            _restore_default(record, state)
    # A state taken before fields were added to the record class (by a user's
    # __getstate__ listing the fields of the day) lacks them.
    fill_added_fields(record)
    for name in arrays:
        value = getattr(record, name, None)
        if isinstance(value, np.ndarray) and value.flags.writeable:
            object.__setattr__(record, name, read_only_view(value))
    freeze_nested = getattr(type(record), "_freeze_nested", None)
    if freeze_nested is not None:
        # Arrays inside a field's tuples (Scene's labelled paths), which ``arrays``
        # does not reach: the record's own __setstate__ freezes them, and a user's
        # state skips it (their arrays came back writable, review 38).
        freeze_nested(record)


def rebuild_record(
    cls: type,
    values: Mapping[str, Any],
    arrays: Collection[str],
    instance: Mapping[str, Any] | None,
    slots: Mapping[str, Any],
) -> Any:
    """The record of class ``cls`` that :func:`reduce_record` took apart, ``arrays`` read-only.

    A writeable array (pickle and deepcopy hand back fresh ones) is kept as a
    read-only view of itself: the array given is never changed, so a
    :func:`copy.copy` cannot make the original record's array read-only. A
    record class whose fields were renamed maps the old names to the new ones
    in a ``_renamed_fields`` class attribute, so that pickles made before the
    rename load into the new fields; fields added since a release and missing
    from ``values`` get their defaults (:func:`fill_added_fields`).
    """
    record: Any = object.__new__(cls)
    renamed: Mapping[str, str] = getattr(cls, "_renamed_fields", None) or {}
    if renamed:
        values = {renamed.get(name, name): value for name, value in values.items()}
        arrays = {renamed.get(name, name) for name in arrays}
    for name, value in values.items():
        if name in arrays and isinstance(value, np.ndarray) and value.flags.writeable:
            value = read_only_view(value)
        object.__setattr__(record, name, value)
    fill_added_fields(record)
    if instance:
        record.__dict__.update(instance)
    for name, value in slots.items():
        object.__setattr__(record, name, value)
    return record


def _added_fields(cls: type) -> dict[str, Callable[[Any], Any]]:
    """The ``_added_fields`` of ``cls`` and its bases, bases' first, each in its order."""
    added: dict[str, Callable[[Any], Any]] = {}
    for klass in reversed(cls.__mro__):
        own = klass.__dict__.get("_added_fields")
        if own:
            added.update(own)
    return added


def fill_added_fields(record: Any) -> None:
    """Give ``record`` the defaults of the fields its class added after a release.

    A record class lists the fields it gained after a release in an
    ``_added_fields`` class attribute: a mapping from each name to a function
    of the record (its other fields set) that returns the field's value for a
    record made before the field existed, in the order the fields were added
    (a :class:`types.MappingProxyType`, not annotated: an annotation would
    make it a field). Pickles made before hold no value for them: the
    record's own as a shorter list of field values (:func:`restore_read_only`),
    a subclass's as a mapping without them (:func:`rebuild_record`) or a
    user's state (:func:`rebuild_from_state`); the field's slot was left unset,
    and ``repr``, ``==`` or any use of it raised ``AttributeError`` (review 50:
    a ``RangeNoise`` subclass pickled before review 49). Those call this after
    setting the fields they hold; a field that has a value is left as it is.
    The ``_added_fields`` of a record's bases count too.

    Parameters
    ----------
    record : dataclass instance or slotted object
        The record being restored (or an ordinary slotted object, through
        :func:`restore_slots`).

    Examples
    --------
    >>> from dataclasses import dataclass
    >>> from types import MappingProxyType
    >>> @dataclass(frozen=True, slots=True)
    ... class Reading:
    ...     value: float
    ...     unit: str = "m"  # added after a release
    ...     _added_fields = MappingProxyType({"unit": lambda reading: "m"})
    >>> old = object.__new__(Reading)
    >>> object.__setattr__(old, "value", 2.0)
    >>> fill_added_fields(old)
    >>> old
    Reading(value=2.0, unit='m')
    """
    cls = type(record)
    if getattr(cls, "_added_fields", None) is None:
        return
    for name, default in _added_fields(cls).items():
        if not hasattr(record, name):
            object.__setattr__(record, name, default(record))


def restore_slots(
    obj: Any,
    state: Any,
    *,
    read_only: Collection[str] = (),
    renamed: Mapping[str, str] | None = None,
) -> None:
    """Restore a slotted object from its default pickle state; freeze the arrays named.

    Parameters
    ----------
    obj : object
        The object being restored (its ``__setstate__``'s ``self``).
    state : tuple or dict
        Python's default state of a class with ``__slots__``: ``(instance
        __dict__ or None, {slot: value})``, so that subclasses (with a
        ``__dict__`` or slots of their own) copy whole; a bare ``{slot: value}``
        also loads.
    read_only : collection of str
        Slots holding arrays to make read-only (pickle and deepcopy hand back
        writable copies).
    renamed : mapping of str to str, optional
        Old slot names and the slots they are stored in now, for pickles made
        before a rename (an attribute that became a read-only property).

    Raises
    ------
    ValueError
        ``state`` names an attribute the object cannot hold (a slot the class
        dropped since the pickle was made, not mapped by ``renamed``).

    Notes
    -----
    Slots the class gained after a release are named in its ``_added_fields``,
    as a record's fields are (:func:`fill_added_fields`, called last here): a
    pickle made before one gets that slot's default, computed from the slots
    it holds; the arrays among them are made read-only by the default itself.

    Examples
    --------
    >>> import copy
    >>> class Holder:
    ...     __slots__ = ("values",)
    ...     def __init__(self) -> None:
    ...         self.values = np.zeros(2)
    ...         self.values.flags.writeable = False
    ...     def __setstate__(self, state: Any) -> None:
    ...         restore_slots(self, state, read_only=("values",))
    >>> copy.deepcopy(Holder()).values.flags.writeable
    False
    """
    instance, slots = state if isinstance(state, tuple) else (None, state)
    if instance:
        obj.__dict__.update(instance)
    for name, value in slots.items():
        if name == "__weakref__":
            # Not state (Python's default leaves it out): a state built from a
            # class's __slots__, which list it since review 36, may hold it.
            continue
        if renamed is not None:
            name = renamed.get(name, name)
        if name in read_only and isinstance(value, np.ndarray):
            value.flags.writeable = False
        try:
            object.__setattr__(obj, name, value)
        except AttributeError:
            # A slot (or attribute) the class no longer has, from a pickle made before
            # it was dropped or renamed without a ``renamed`` entry: a PotentialField-
            # Controller pickled before 908ac92 raised AttributeError 'mode' here
            # (review 51, FRESH), where a record's restore raises this ValueError.
            raise ValueError(
                f"{type(obj).__name__} has no attribute {name!r}: this pickle of it was "
                "made by a release whose attributes differ; build it again"
            ) from None
    if slots:
        # Slots the class gained after a release: an older pickle leaves them unset,
        # and the first use raised AttributeError (review 51: an AStarPlanner or World
        # pickled on the project's first days). Not for an object built by __new__ and
        # not filled, whose state holds no slot to make them from.
        fill_added_fields(obj)
