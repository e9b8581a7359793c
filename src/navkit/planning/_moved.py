"""Where navkit.planning's classes lived before 30 November 2026, for old pickles (private).

A pickle names a class by its module: ``FieldDStar`` and the potential fields
pickled on 23 November name ``navkit.planning._field_dstar`` and
``navkit.planning._fields`` (on 30 November, briefly,
``navkit.planning.reactive._fields``), modules that no longer exist, and
loading one raised ModuleNotFoundError. :func:`install` adds an import finder
(last on :data:`sys.meta_path`, so consulted only where no module of that name
exists) that answers those three names with a module holding nothing but a
look-up, in :mod:`navkit.planning`'s public names, of the names the old module
held (any other name is an AttributeError): a class found there restores
the old state in its ``__setstate__`` (the potential fields: ``_restore`` in
``navkit.planning.reactive._potential_field``) or refuses it clearly
(``FieldDStar`` before 6de62f3); a name no longer public (``FieldPath``,
``FieldGrid``) is a ValueError naming it and saying to build it again. No
file stands at the old names (review 53).

Examples
--------
>>> import importlib
>>> importlib.import_module("navkit.planning._fields").ConicAttraction.__name__
'ConicAttraction'
"""

from __future__ import annotations

import importlib
import importlib.machinery
import sys
import types
from collections.abc import Sequence
from functools import partial
from typing import TYPE_CHECKING, Any, cast

if TYPE_CHECKING:
    from importlib.abc import Loader

__all__ = ["MOVED", "install"]

#: Modules of the first days -> the commit that moved their classes away.
MOVED = {
    "navkit.planning._field_dstar": "5e5f83f",
    "navkit.planning._fields": "5e5f83f",
    "navkit.planning.reactive._fields": "0123de4",
}

#: The public names the old modules held (their ``__all__`` then): all a pickle of then
#: names (FieldDStar and FieldPath lived in _field_dstar, the others in _fields).
_HELD = frozenset(
    (
        "AttractiveField",
        "BlendedAttraction",
        "CompositeField",
        "ConicAttraction",
        "FieldDStar",
        "FieldGrid",
        "FieldPath",
        "KhatibRepulsion",
        "ParaboloidAttraction",
        "PiecewiseAttraction",
        "PiecewiseRepulsion",
        "PotentialField",
        "field_dstar",
        "field_dstar_cells",
        "field_grid",
    )
)


def _public(module: str, name: str) -> Any:
    """``name`` of the old ``module``: today's public object of that name.

    Only the names the old modules held are answered. Any other is an
    AttributeError, as PEP 562 asks of a module ``__getattr__``: ``hasattr``
    probes and :func:`pickle.whichmodule`, which looks an object without a
    module up in every module of :data:`sys.modules`, raised this ValueError
    once an old pickle had put the module there (review 53, FRESH).
    """
    if name not in _HELD:
        raise AttributeError(f"module {module!r} has no attribute {name!r}")
    planning = importlib.import_module("navkit.planning")
    if name in planning.__all__:
        return getattr(planning, name)
    raise ValueError(
        f"{module}.{name}: a pickle made by navkit before {MOVED[module]} (30 November "
        f"2026) names {name}, which navkit no longer has; build the object again"
    )


class _Finder:
    """Finds and loads the modules of :data:`MOVED` (and nothing else).

    An import finder and loader by its methods (``importlib.abc``'s bases would
    cost their import to every ``import navkit.planning``).
    """

    def find_spec(
        self,
        fullname: str,
        path: Sequence[str] | None,
        target: types.ModuleType | None = None,
    ) -> importlib.machinery.ModuleSpec | None:
        if fullname not in MOVED:
            return None
        return importlib.machinery.ModuleSpec(fullname, cast("Loader", self))

    def create_module(self, spec: importlib.machinery.ModuleSpec) -> types.ModuleType | None:
        return None  # Python's default module

    def get_code(self, fullname: str) -> None:
        """No code: ``python -m`` (runpy) of an old name says so, not AttributeError."""
        return None

    def exec_module(self, module: types.ModuleType) -> None:
        module.__doc__ = f"Old name of navkit.planning's module, for pickles (see {__name__})."
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
