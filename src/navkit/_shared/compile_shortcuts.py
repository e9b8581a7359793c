"""Cheaper numba internals while numba compiles navkit's kernels (private).

Two pieces of numba's own work cost a first use time that does not depend on
what navkit compiles, and change nothing in what numba makes of it (issue 17;
measured on a cold ``astar`` and a cold ``FieldDStar`` plan, numba 0.68):

* **Error-message markup.** numba's compiler uses exceptions for flow control
  (a value that has no numba type, a float that cannot be a literal, an
  overload template that does not match): about 5,000 a first ``astar`` and
  8,700 a first Field D* plan. Each message is marked up with numba's colour
  scheme (``numba.core.errors.HighlightColorScheme._markup``), which calls
  colorama's ``init()`` and ``deinit()`` every time; they wrap and swap
  ``sys.stdout`` and ``sys.stderr`` and back (about 20 µs a message: 0.1 s of
  a first ``astar``, 0.17 s of a Field D* plan). While a navkit kernel compiles,
  the scheme gets a ``_markup`` that builds the same string (the same bytes,
  colour codes included) without touching the streams.
* **Compile-flag comparisons.** numba's ``@overload`` templates cache what
  they compiled by (context, argument types, flags), and every operator an
  ``@overload`` template might implement (``a[i]``, ``a + b``, ...) looks that
  cache up, often for several templates. ``TargetConfig.__hash__`` and
  ``__eq__`` build a dict of every option (22 property reads) each time:
  about 5,000 hashes and 10,000 comparisons, 0.4-0.5 s, of a first ``astar``,
  11,000 and 17,000, 0.6 s, of a Field D* plan. While a navkit kernel
  compiles, ``__hash__`` returns the value numba's own computes, remembered
  per class (it depends on the option names alone: numba hashes the sorted
  names of the options dict),
  and ``__eq__`` compares the options set (``_values``), each filled in with
  the class's defaults where unset: the dicts numba's own ``values()`` builds,
  without the property reads. Flags of another class, or of a class that
  reads its options otherwise, go to numba's own comparison.

Both are switched on when the compile of a navkit kernel starts and back off
when the compiling thread releases numba's compiler lock, through the
listeners :mod:`navkit._shared.compile_gc` registers; compiles of other code
(the user's own kernels) run with numba as it is, except a user's kernel that
calls a navkit one, whose compile keeps the shortcuts from the navkit
kernel's compile to its own end: the shortcuts give the same answers and the
same messages, so nothing it compiles or reports changes. A ``TargetConfig``
class whose ``values`` or option properties are not the ones numba makes is
always left to numba's own methods.

The switch is one for the whole process while compiles are per thread, so,
as with the collector's pauses, the compiles under way are counted
process-wide: the first to start switches the shortcuts on, the last to end
puts numba's own methods back (and only its own: a method someone else
installed meanwhile is left in place). A child forked meanwhile keeps the
forking thread's count alone and, with none, gets numba's methods back.

:data:`ENABLED` turns the whole thing off (``navkit._shared.compile_shortcuts.ENABLED
= False``: compiles run with numba as it is; for measurements and tests).
"""

from __future__ import annotations

import importlib
import os
import threading
from collections.abc import Callable
from typing import Any

__all__ = ["ENABLED", "active", "begin", "end"]

#: Whether navkit compiles switch the shortcuts on (read when a compile starts).
ENABLED = True

#: Guards the three below (re-entrant, as compile_gc's).
_LOCK = threading.RLock()
#: Compiles with the shortcuts under way in every thread.
_COUNT = 0
#: What was replaced while the shortcuts are on: (owner, name, ours, replaced or
#: _MISSING for an attribute the owner did not have itself).
_SAVED: list[tuple[Any, str, Any, Any]] = []
#: This thread's share of the count (``count``): all that survives a fork.
_THREAD = threading.local()

_MISSING = object()

#: Per class: whether its values() and option properties are numba's own.
_PLAIN: dict[type, bool] = {}
#: Per class: its options' defaults.
_DEFAULTS: dict[type, dict[str, Any]] = {}


def _plain(cls: type, target_config: Any) -> bool:
    """Whether ``cls`` reads its options as numba's ``TargetConfig`` makes them.

    That is: ``values`` is ``TargetConfig.values``, and every option is a
    property made by numba's metaclass (``self._values.get(name, default)``).
    Only then do equal ``_values`` mean equal ``values()``.
    """
    plain = _PLAIN.get(cls)
    if plain is None:
        plain = getattr(cls, "values", None) is target_config.values
        for name in getattr(cls, "options", {}):
            prop = getattr(cls, name, None)
            getter = getattr(prop, "fget", None)
            qualname = getattr(getter, "__qualname__", "")
            if not isinstance(prop, property) or not qualname.endswith("make_prop.<locals>.getter"):
                plain = False
        _PLAIN[cls] = plain
    return plain


def _defaults(cls: Any) -> dict[str, Any]:
    """Every option of a ``TargetConfig`` class and its default."""
    defaults: dict[str, Any] | None = _DEFAULTS.get(cls)
    if defaults is None:
        defaults = _DEFAULTS[cls] = {name: opt.default for name, opt in cls.options.items()}
    return defaults


def _flag_methods(target_config: Any) -> tuple[Callable[..., Any], Callable[..., Any]]:
    """``__hash__`` and ``__eq__`` for numba's ``TargetConfig``, quicker and the same."""
    numba_hash = target_config.__hash__
    numba_eq = target_config.__eq__
    hashes: dict[type, int] = {}  # numba's hash per class: it depends on the option names

    def __hash__(self: Any) -> int:
        cls = type(self)
        value = hashes.get(cls)
        if value is None:
            value = numba_hash(self)
            if _plain(cls, target_config):
                hashes[cls] = value
        return value

    def __eq__(self: Any, other: Any) -> Any:
        cls = type(self)
        if type(other) is not cls or not _plain(cls, target_config):
            return numba_eq(self, other)
        mine, theirs = self._values, other._values
        if mine == theirs:
            return True
        # numba's values(): every option, set or default (the getters numba makes).
        defaults = _defaults(cls)
        full_mine, full_theirs = {**defaults, **mine}, {**defaults, **theirs}
        if len(full_mine) != len(defaults) or len(full_theirs) != len(defaults):
            return numba_eq(self, other)  # something else in _values: numba's way
        return full_mine == full_theirs

    return __hash__, __eq__


def _markup_method(errors: Any) -> Callable[..., str]:
    """numba's ``HighlightColorScheme._markup`` without colorama's stream swaps.

    The same string: the colour and style codes, the message, colorama's
    reset code, through the same UTF-8 round trip (a message that cannot be
    encoded raises as numba's does).
    """
    style_codes = errors.Style

    def _markup(msg: str, color: str | None = None, style: str | None = style_codes.BRIGHT) -> str:
        features = ""
        if color:
            features += color
        if style:
            features += style
        buffer = bytearray(b"")
        buffer += features.encode("utf-8")
        buffer += msg.encode("utf-8")
        buffer += style_codes.RESET_ALL.encode("utf-8")
        return buffer.decode("utf-8")

    return _markup


def _replacements() -> list[tuple[Any, str, Any]]:
    """(owner, attribute, replacement) for the numba installed, as far as it has them."""
    out: list[tuple[Any, str, Any]] = []
    targetconfig: Any = importlib.import_module("numba.core.targetconfig")
    target_config = getattr(targetconfig, "TargetConfig", None)
    if target_config is not None and "__eq__" in vars(target_config):
        new_hash, new_eq = _flag_methods(target_config)
        out += [(target_config, "__hash__", new_hash), (target_config, "__eq__", new_eq)]
    errors: Any = importlib.import_module("numba.core.errors")
    scheme_class = getattr(errors, "HighlightColorScheme", None)  # absent: no colorama
    if scheme_class is not None and hasattr(errors, "Style"):
        scheme = errors.termcolor()
        if type(scheme) is scheme_class and "_markup" not in vars(scheme):
            out.append((scheme, "_markup", _markup_method(errors)))
    return out


def _switch_on() -> None:
    # Made afresh each time (a few closures, once per outermost navkit compile):
    # they fall back on the methods in place now, whoever installed those.
    try:
        replacements = _replacements()
    except (ImportError, AttributeError, TypeError):  # a numba laid out otherwise: as it is
        return
    for owner, name, ours in replacements:
        replaced = vars(owner).get(name, _MISSING)
        setattr(owner, name, ours)
        _SAVED.append((owner, name, ours, replaced))


def _switch_off() -> None:
    while _SAVED:
        owner, name, ours, replaced = _SAVED.pop()
        if vars(owner).get(name, _MISSING) is not ours:  # replaced meanwhile: theirs
            continue
        if replaced is _MISSING:
            delattr(owner, name)
        else:
            setattr(owner, name, replaced)


def begin() -> None:
    """Count a navkit compile in; the first of those under way switches the shortcuts on.

    Examples
    --------
    >>> from navkit._shared import compile_shortcuts
    >>> from navkit._shared.jit import load_numba
    >>> load_numba()
    >>> compile_shortcuts.begin()
    >>> compile_shortcuts.active()
    True
    >>> compile_shortcuts.end()
    >>> compile_shortcuts.active()
    False
    """
    global _COUNT
    with _LOCK:
        if _COUNT == 0 and ENABLED:
            _switch_on()
        _COUNT += 1
        _THREAD.count = getattr(_THREAD, "count", 0) + 1


def end() -> None:
    """Count one out; the last to end puts numba's own methods back.

    Examples
    --------
    >>> from navkit._shared import compile_shortcuts
    >>> compile_shortcuts.begin()
    >>> compile_shortcuts.end()
    >>> compile_shortcuts.active()
    False
    """
    global _COUNT
    with _LOCK:
        _COUNT = max(_COUNT - 1, 0)
        _THREAD.count = max(getattr(_THREAD, "count", 0) - 1, 0)
        if _COUNT == 0:
            _switch_off()


def active() -> bool:
    """Whether the shortcuts are switched on now (a navkit compile is under way).

    Examples
    --------
    >>> from navkit._shared import compile_shortcuts
    >>> compile_shortcuts.active()
    False
    """
    with _LOCK:
        return bool(_SAVED)


def _before_fork() -> None:
    _LOCK.acquire()


def _after_fork_in_parent() -> None:
    _LOCK.release()


def _after_fork_in_child() -> None:
    """Keep only the forking thread's count; with none, numba's own methods are back."""
    global _LOCK, _COUNT
    _LOCK = threading.RLock()  # the parent's is held, by this thread's twin
    _COUNT = getattr(_THREAD, "count", 0)
    if _COUNT == 0:
        _switch_off()


if hasattr(os, "register_at_fork"):  # not on Windows, which cannot fork
    os.register_at_fork(
        before=_before_fork,
        after_in_parent=_after_fork_in_parent,
        after_in_child=_after_fork_in_child,
    )
