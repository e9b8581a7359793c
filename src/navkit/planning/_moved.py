"""Where navkit.planning's classes lived before 30 November 2026, for old pickles (private).

A pickle names a class by its module: ``FieldDStar`` and the potential fields
pickled on 23 November name ``navkit.planning._field_dstar`` and
``navkit.planning._fields`` (on 30 November, briefly,
``navkit.planning.reactive._fields``), modules that no longer exist, and
loading one raised ModuleNotFoundError. :func:`install` adds an import finder
(last on :data:`sys.meta_path`, so consulted only where no module of that name
exists) that answers those three names with a module holding nothing but a
look-up of :mod:`navkit.planning`'s public names: a class found there restores
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


def _public(module: str, name: str) -> Any:
    """``name`` of the old ``module``: today's public class of that name."""
    planning = importlib.import_module("navkit.planning")
    if name in planning.__all__:
        return getattr(planning, name)
    if name.startswith("__"):  # a module attribute Python looks up (__path__, __file__)
        raise AttributeError(name)
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
    if not any(isinstance(finder, _Finder) for finder in sys.meta_path):
        sys.meta_path.append(_Finder())
