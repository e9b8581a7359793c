"""Where navkit's classes lived before 30 November 2026, for old pickles (private).

A pickle names a class (or function) by its module: a ``GreedyStep``,
``GameState``, ``CarmenLog``, ``PotentialFieldController`` or potential field
pickled on 23 November names ``navkit.planning._greedy``,
``navkit.planning._soccer``, ``navkit.mapping._carmen``,
``navkit.control._potential_controller`` or ``navkit.planning._fields``,
modules that no longer exist, and loading one raised ModuleNotFoundError.
:func:`install` (run by ``navkit/__init__``, so before any of navkit's
packages is imported) adds one import finder for all of them, last on
:data:`sys.meta_path` (consulted only where no module of that name exists). It
answers each name of :data:`MOVED` with a module holding nothing but a look-up
of the names the old module held, in the public names of the package that has
them today (any other name is an AttributeError):

* a class found there restores the old state in its ``__setstate__``
  (renamed fields, run state moved: each class's own pickle support) or
  refuses it clearly (``FieldDStar`` before 6de62f3);
* a private class the old module held beside a public one (``_Pid``, the
  state of ``PotentialFieldController``) is looked up in that public class's
  module, as a pickle made today names it;
* a class that was a ``NamedTuple`` then (``BehaviourTarget``), whose pickle
  (protocol 2 and above) calls only ``cls.__new__(cls, *values)``, is today's
  class, whose ``__new__`` builds the record from them (review 54). One pickled
  with protocol 0 or 1 cannot load (TypeError): it is
  ``copyreg._reconstructor(cls, tuple, values)``, which calls
  ``tuple.__new__(cls, values)``; that refuses any class not a tuple, and a tuple
  subclass would come back as itself, with no step after it for a class to
  turn it into the record (short of replacing :mod:`copyreg`'s function for
  every pickle of the process);
* a name no longer public (``GridPath``, ``WorldPath``, ``FieldPath``,
  ``FieldGrid``) is a ValueError naming it and saying to build it again.

The look-up goes through the public faces by name, at unpickling time only (no
import of a higher layer here). No file stands at the old names (review 53).

Examples
--------
>>> import importlib
>>> importlib.import_module("navkit.planning._fields").ConicAttraction.__name__
'ConicAttraction'
>>> importlib.import_module("navkit.mapping._carmen").CarmenLog.__module__
'navkit.mapping.io._carmen'
"""

from __future__ import annotations

import importlib
import importlib.machinery
import sys
import types
from functools import partial
from typing import TYPE_CHECKING

if TYPE_CHECKING:
    from collections.abc import Callable, Sequence
    from typing import Any

__all__ = ["MOVED", "Moved", "gone", "install"]


class Moved:
    """An old module: the commit that moved it, where its names are today, which it held.

    Attributes
    ----------
    commit : str
        The commit that moved (or removed) the module.
    package : str
        The public package holding its names today (looked up by name).
    held : frozenset of str
        The public names the module held (its ``__all__`` then).
    beside : dict of str to str
        Private classes a pickle of a public one names: each looked up in the
        module of the public class given.
    """

    # A plain class, not a dataclass: dataclasses' import would cost every ``import navkit``.
    __slots__ = ("beside", "commit", "held", "package")

    def __init__(
        self,
        commit: str,
        package: str,
        held: frozenset[str],
        beside: dict[str, str] | None = None,
    ) -> None:
        self.commit = commit
        self.package = package
        self.held = held
        self.beside = beside or {}


_FIELDS = frozenset(
    (
        "AttractiveField",
        "BlendedAttraction",
        "CompositeField",
        "ConicAttraction",
        "FieldGrid",
        "KhatibRepulsion",
        "ParaboloidAttraction",
        "PiecewiseAttraction",
        "PiecewiseRepulsion",
        "PotentialField",
        "field_grid",
    )
)

#: Modules of the first days (23-30 November 2026) that held public objects, by name.
#: The modules that held kernels and helpers only are not here: nothing a user
#: pickles names them.
MOVED: dict[str, Moved] = {
    "navkit.planning._astar": Moved("5e5f83f", "navkit.planning", frozenset(("GridPath", "astar"))),
    "navkit.planning._distance_field": Moved(
        "5e5f83f", "navkit.planning", frozenset(("distance_field",))
    ),
    "navkit.planning._field_dstar": Moved(
        "5e5f83f",
        "navkit.planning",
        frozenset(("FieldDStar", "FieldPath", "field_dstar", "field_dstar_cells")),
    ),
    "navkit.planning._fields": Moved("5e5f83f", "navkit.planning", _FIELDS),
    "navkit.planning._greedy": Moved(
        "5e5f83f", "navkit.planning", frozenset(("GreedyStep", "greedy_step"))
    ),
    "navkit.planning._plan_path": Moved(
        "5e5f83f", "navkit.planning", frozenset(("WorldPath", "plan_path"))
    ),
    "navkit.planning._scan_forces": Moved(
        "5e5f83f",
        "navkit.planning",
        frozenset(("piecewise_repulsive_force_from_scan", "repulsive_force_from_scan")),
    ),
    "navkit.planning._soccer": Moved(
        "5e5f83f",
        "navkit.behaviours",
        frozenset(("BehaviourTarget", "GameState", "attack", "defend", "support")),
    ),
    "navkit.planning.reactive._fields": Moved("0123de4", "navkit.planning", _FIELDS),
    "navkit.control._potential_controller": Moved(
        "0123de4",
        "navkit.control",
        frozenset(("PotentialFieldController", "limit_velocity_change")),
        beside={"_Pid": "PotentialFieldController"},
    ),
    "navkit.mapping._carmen": Moved(
        "0123de4", "navkit.mapping.io", frozenset(("CarmenLog", "read_carmen"))
    ),
}


def _public(module: str, name: str) -> Any:
    """``name`` of the old ``module``: today's object of that name.

    Only the names the old module held are answered. Any other is an
    AttributeError, as PEP 562 asks of a module ``__getattr__``: ``hasattr``
    probes and :func:`pickle.whichmodule`, which looks an object without a
    module up in every module of :data:`sys.modules`, raised a ValueError
    once an old pickle had put the module there (review 53, FRESH).
    """
    moved = MOVED[module]
    if name in moved.beside:
        owner = _public(module, moved.beside[name])
        return getattr(sys.modules[owner.__module__], name)
    if name not in moved.held:
        raise AttributeError(f"module {module!r} has no attribute {name!r}")
    package = importlib.import_module(moved.package)
    if name in package.__all__:
        return getattr(package, name)
    raise _no_longer(module, name, moved.commit)


def _no_longer(module: str, name: str, commit: str) -> ValueError:
    """The refusal of ``module.name``, a name of the first days navkit no longer has."""
    return ValueError(
        f"{module}.{name}: a pickle made by navkit before {commit} (30 November "
        f"2026) names {name}, which navkit no longer has; build the object again"
    )


def _refuse(module: str, names: frozenset[str], commit: str, name: str) -> Any:
    if name in names:
        raise _no_longer(module, name, commit)
    raise AttributeError(f"module {module!r} has no attribute {name!r}")


def gone(module: str, names: tuple[str, ...], commit: str) -> Callable[[str], Any]:
    """A module ``__getattr__`` refusing ``names``, classes ``module`` held until ``commit``.

    For a module that exists today but lost a class a pickle of the first days
    names (pickle raised AttributeError): that name is a ValueError saying to
    build the object again, any other an AttributeError (PEP 562). Assign it
    under ``if not TYPE_CHECKING:``, or mypy takes every attribute of the module.

    Examples
    --------
    >>> getattr_ = gone("navkit.planning.grid._astar", ("GridPath",), "0123de4")
    >>> getattr_("GridPath")
    Traceback (most recent call last):
    ...
    ValueError: navkit.planning.grid._astar.GridPath: a pickle made by navkit before 0123de4 ...
    """
    return partial(_refuse, module, frozenset(names), commit)


class _Finder:
    """Finds and loads the modules of :data:`MOVED` (and nothing else).

    An import finder and loader by its methods (``importlib.abc``'s bases would
    cost their import to every ``import navkit``).
    """

    def find_spec(
        self,
        fullname: str,
        path: Sequence[str] | None,
        target: types.ModuleType | None = None,
    ) -> importlib.machinery.ModuleSpec | None:
        if fullname not in MOVED:
            return None
        return importlib.machinery.ModuleSpec(fullname, self)  # type: ignore[arg-type]

    def create_module(self, spec: importlib.machinery.ModuleSpec) -> types.ModuleType | None:
        return None  # Python's default module

    def get_code(self, fullname: str) -> None:
        """No code: ``python -m`` (runpy) of an old name says so, not AttributeError."""
        return None

    def exec_module(self, module: types.ModuleType) -> None:
        module.__doc__ = (
            f"Old name of a module of {MOVED[module.__name__].package}, for pickles "
            f"(see {__name__})."
        )
        module.__getattr__ = partial(_public, module.__name__)  # type: ignore[method-assign]


def install() -> None:
    """Put the finder last on :data:`sys.meta_path`, once.

    Examples
    --------
    >>> install()
    >>> sum(isinstance(f, _Finder) for f in sys.meta_path)
    1
    """
    # By name, not isinstance: importlib.reload of this module makes a new _Finder
    # class, and the finder of the first load must still count.
    if not any(
        type(finder).__module__ == __name__ and type(finder).__qualname__ == "_Finder"
        for finder in sys.meta_path
    ):
        sys.meta_path.append(_Finder())
