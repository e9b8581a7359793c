"""Every public name has a numpydoc docstring with its Parameters and Returns.

What counts as public: every module and package of navkit reached by
``pkgutil`` whose dotted path has no component starting with ``_`` (``navkit``
itself, ``navkit.errors``, ``navkit.planning.grid``, ...), and in each the names
of its ``__all__``. An object exported by several modules (``navkit.NoPathError``
and ``navkit.errors.NoPathError``; ``navkit.planning`` re-exporting
``navkit.planning.grid``) is checked once, under the deepest exporting module on
the path to where it is defined. One test per public module; its failure lists,
one line per name, everything missing.

The rules (numpydoc: a section is a title underlined with dashes):

* **functions and methods** — public methods, classmethods and staticmethods
  in the class's own ``__dict__``, plus public ones a class inherits from a
  navkit base class that is not itself exported (checked once, under the first
  exporting subclass) — need their own docstring (an override without one is
  undocumented: the API reference shows it bare); a ``Parameters`` section when
  they take parameters besides ``self``/``cls``; a ``Returns`` (or ``Yields``)
  section unless the return annotation is ``None``;
* **classes** need a docstring (a dataclass's generated ``Name(field, ...)``
  does not count); when ``__init__`` (their own, a dataclass's or one inherited
  from a navkit class) takes parameters, the class docstring has the
  ``Parameters`` section (the API reference merges ``__init__`` into the class);
  no ``Returns``. A dataclass may document its fields (its ``__init__``
  parameters) in an ``Attributes`` section instead, as result types do.
  Enums, protocols and exceptions that keep ``Exception``'s ``__init__`` have
  no parameters to document;
* **functions, methods and classes** need an ``Examples`` section with a
  runnable example (``>>>``), which ``--doctest-modules`` runs;
* **properties** need a docstring; ``Returns`` is not required (the first
  line says what the property is);
* **every parameter is documented and every documented parameter exists**:
  the names in ``Parameters`` (and ``Other Parameters``) match the signature,
  ``a, b : float`` documents both, ``*args`` / ``**kwargs`` may be written with
  or without their stars;
* **data** (typing aliases such as ``OdometryMethod = Literal[...]``, constants
  such as registries) cannot carry ``__doc__``; they need an attribute docstring
  — a string literal right after the assignment in the module that defines
  them, which mkdocstrings renders and which this test finds by parsing the
  source. ``#:`` comments are not accepted (not rendered). Dunder names
  (``__version__``) are skipped.
"""

from __future__ import annotations

import ast
import dataclasses
import enum
import functools
import importlib
import inspect
import pkgutil
import re
import sys
from collections.abc import Callable, Iterator
from pathlib import Path
from typing import Any

import pytest

import navkit

SECTION = re.compile(r"^(?P<title>[A-Z][A-Za-z ]*)\n-{3,}[ \t]*$", re.MULTILINE)
PARAM_SECTIONS = ("Parameters", "Other Parameters")


# ----------------------------------------------------------------------------------
# Finding the public names.


def _public_modules() -> list[str]:
    """navkit and every module under it with no ``_``-prefixed path component."""
    names = ["navkit"]
    for info in pkgutil.walk_packages(navkit.__path__, "navkit.", onerror=lambda _: None):
        if not any(part.startswith("_") for part in info.name.split(".")[1:]):
            names.append(info.name)
    return sorted(names)


MODULES = _public_modules()


@dataclasses.dataclass(frozen=True)
class Item:
    """One thing to check: ``kind`` is function, class, method, property or data."""

    qualname: str
    kind: str
    obj: Any


@dataclasses.dataclass
class Inventory:
    items: dict[str, list[Item]]
    import_errors: dict[str, str]


def _home(obj: Any, exporters: list[str]) -> str:
    """The module an object is checked under: the deepest exporter on its path."""
    defined_in = getattr(obj, "__module__", None) or ""
    on_path = [m for m in exporters if defined_in == m or defined_in.startswith(m + ".")]
    candidates = on_path or exporters
    return max(candidates, key=lambda m: (m.count("."), m))


def _members(
    cls: type, checked: set[tuple[type, str]], exported: set[int]
) -> Iterator[tuple[type, str, Any]]:
    """Public methods and properties of ``cls`` and of its unexported navkit base classes.

    An exported base class (``exported`` holds their ids) is checked under its
    own name; an unexported one's members are yielded once over the whole
    inventory (``checked``).
    """
    for klass in cls.__mro__:
        if not klass.__module__.startswith("navkit") or (
            klass is not cls and id(klass) in exported
        ):
            continue
        for name, attr in vars(klass).items():
            if name.startswith("_") or (klass, name) in checked:
                continue
            if isinstance(attr, (staticmethod, classmethod, property, functools.cached_property)):
                pass
            elif not inspect.isfunction(attr):
                continue  # fields, slots, enum members, nested constants
            checked.add((klass, name))
            yield klass, name, attr


@functools.cache
def _inventory() -> Inventory:
    errors: dict[str, str] = {}
    exporters: dict[int, tuple[Any, str, list[str]]] = {}
    for module_name in MODULES:
        try:
            module = importlib.import_module(module_name)
        except Exception as exc:  # a broken module fails its own test
            errors[module_name] = f"{type(exc).__name__}: {exc}"
            continue
        for name in getattr(module, "__all__", ()):
            if name.startswith("__"):
                continue
            if not hasattr(module, name):
                errors.setdefault(module_name, "")
                errors[module_name] += f"__all__ names {name!r}, which the module lacks\n"
                continue
            obj = getattr(module, name)
            entry = exporters.setdefault(id(obj), (obj, name, []))
            entry[2].append(module_name)

    items: dict[str, list[Item]] = {m: [] for m in MODULES}
    exported_classes = {id(obj) for obj, _, _ in exporters.values() if inspect.isclass(obj)}
    checked: set[tuple[type, str]] = set()
    # Sorted so that an unexported base class's members go to the same subclass every run.
    for obj, name, mods in sorted(exporters.values(), key=lambda e: (min(e[2]), e[1])):
        home = _home(obj, mods)
        qual = f"{home}.{name}"
        if inspect.isclass(obj):
            items[home].append(Item(qual, "class", obj))
            for klass, attr_name, attr in _members(obj, checked, exported_classes):
                where = qual if klass is obj else f"{qual} (from {klass.__qualname__})"
                kind = (
                    "property"
                    if isinstance(attr, (property, functools.cached_property))
                    else "method"
                )
                items[home].append(Item(f"{where}.{attr_name}", kind, attr))
        elif inspect.isroutine(obj) or (callable(obj) and not _is_typing_object(obj)):
            items[home].append(Item(qual, "function", obj))
        elif not inspect.ismodule(obj):
            items[home].append(Item(qual, "data", (home, name)))
    return Inventory(items, errors)


def _is_typing_object(obj: Any) -> bool:
    module = type(obj).__module__
    return module in ("typing", "types", "collections.abc", "typing_extensions")


# ----------------------------------------------------------------------------------
# Reading docstrings.


def _sections(doc: str) -> dict[str, str]:
    """numpydoc sections of a cleaned docstring: title -> body (the summary is '')."""
    out: dict[str, str] = {}
    matches = list(SECTION.finditer(doc))
    out[""] = doc[: matches[0].start()] if matches else doc
    for i, match in enumerate(matches):
        end = matches[i + 1].start() if i + 1 < len(matches) else len(doc)
        out[match["title"].strip()] = doc[match.end() : end]
    return out


def _documented_names(sections: dict[str, str], titles: tuple[str, ...]) -> list[str]:
    """Parameter names in the sections ``titles`` (Parameters, Other Parameters, ...).

    An unindented line that is not ``name[, name] [: type]`` is returned whole
    (with a leading space, never a valid name): a paragraph that strayed into the
    section, which numpydoc and griffe read as a malformed parameter.
    """
    names: list[str] = []
    for title in titles:
        in_paragraph = False
        for line in sections.get(title, "").splitlines():
            if not line.strip():
                in_paragraph = False
                continue
            if line[0].isspace() or in_paragraph:
                continue  # a description line, or the rest of a stray paragraph
            head = line.split(":", 1)[0]
            parts = [part.strip().lstrip("*") for part in head.split(",")]
            if all(part.isidentifier() for part in parts):
                names.extend(parts)
            else:
                names.append(" " + line.strip())
                in_paragraph = True
    return names


def _signature_names(func: Callable[..., Any], *, drop_first: bool) -> list[str] | None:
    try:
        sig = inspect.signature(func)
    except (TypeError, ValueError):
        return None
    params = list(sig.parameters.values())
    if drop_first and params:
        params = params[1:]
    return [p.name for p in params]


def _return_annotation(func: Callable[..., Any]) -> Any:
    try:
        return inspect.signature(func).return_annotation
    except (TypeError, ValueError):
        return inspect.Signature.empty


def _parameter_problems(
    doc: str, params: list[str], titles: tuple[str, ...] = PARAM_SECTIONS
) -> list[str]:
    sections = _sections(doc)
    problems: list[str] = []
    if params and not any(title in sections for title in titles):
        return [f"a {' or '.join(dict.fromkeys(t.split()[-1] for t in titles))} section"]
    documented = _documented_names(sections, titles)
    undocumented = [p for p in params if p not in documented]
    unknown = [d for d in documented if d not in params and not d.startswith(" ")]
    strays = [d.strip() for d in documented if d.startswith(" ")]
    if undocumented:
        problems.append(f"entries for parameter(s) {', '.join(undocumented)}")
    if unknown:
        problems.append(f"no documented parameter(s) {', '.join(unknown)} in the signature")
    problems.extend(
        f"a section header (Notes?) before the paragraph {d[:40]!r}... that ends the"
        " parameter list (numpydoc reads it as a parameter)"
        for d in strays
    )
    return problems


def _own_doc(obj: Any) -> str:
    doc = obj.__doc__ if isinstance(obj.__doc__, str) else ""
    return inspect.cleandoc(doc) if doc else ""


def _class_init(cls: type) -> Callable[..., Any] | None:
    """The ``__init__`` (or ``__new__``) whose parameters the class docstring documents."""
    if issubclass(cls, enum.Enum) or getattr(cls, "_is_protocol", False):
        return None
    for klass in cls.__mro__:
        own = vars(klass)
        if "__init__" in own or "__new__" in own:
            if not klass.__module__.startswith("navkit"):
                return None  # object's, Exception's, ...: nothing of navkit's to document
            constructor: Callable[..., Any] = own.get("__init__") or own["__new__"]
            return constructor
    return None


def _check_class(cls: type) -> list[str]:
    doc = _own_doc(cls)
    if dataclasses.is_dataclass(cls) and doc.startswith(f"{cls.__name__}("):
        doc = ""  # the text dataclasses generates for an undocumented class
    if not doc:
        return ["a docstring"]
    problems = _example_problems(doc)
    init = _class_init(cls)
    if init is None:
        return problems
    params = _signature_names(init, drop_first=True)
    # A dataclass's __init__ parameters are its fields: an Attributes section documents them.
    titles = (*PARAM_SECTIONS, "Attributes") if dataclasses.is_dataclass(cls) else PARAM_SECTIONS
    return problems + ([] if params is None else _parameter_problems(doc, params, titles))


def _example_problems(doc: str) -> list[str]:
    """An Examples section holding a doctest, or what is missing."""
    if ">>>" not in _sections(doc).get("Examples", ""):
        return ["an Examples section with a runnable example (>>>)"]
    return []


def _check_routine(item: Item) -> list[str]:
    attr = item.obj
    if item.kind == "property":
        func = attr.fget if isinstance(attr, property) else attr.func
        return [] if _own_doc(func) else ["a docstring"]
    drop_first = False
    func = attr
    if isinstance(attr, (staticmethod, classmethod)):
        func = attr.__func__
        drop_first = isinstance(attr, classmethod)
    elif item.kind == "method":
        drop_first = True
    doc = _own_doc(func)
    if not doc:
        return ["a docstring"]
    params = _signature_names(func, drop_first=drop_first)
    problems = [] if params is None else _parameter_problems(doc, params)
    returns = _return_annotation(func)
    sections = _sections(doc)
    if returns not in (None, "None") and "Returns" not in sections and "Yields" not in sections:
        problems.append("a Returns section")
    return problems + _example_problems(doc)


def _attribute_docstring(module_name: str, name: str, depth: int = 0) -> str | None:
    """The string literal after ``name = ...`` where ``module_name`` defines or imports it."""
    module = sys.modules.get(module_name) or importlib.import_module(module_name)
    source_file = getattr(module, "__file__", None)
    if source_file is None or depth > 10:
        return None
    tree = ast.parse(Path(source_file).read_text(encoding="utf-8"))
    body = tree.body
    for i, stmt in enumerate(body):
        targets: list[ast.expr] = []
        if isinstance(stmt, ast.Assign):
            targets = stmt.targets
        elif isinstance(stmt, ast.AnnAssign):
            targets = [stmt.target]
        elif isinstance(stmt, ast.ImportFrom) and stmt.module and stmt.level == 0:
            for alias in stmt.names:
                if (alias.asname or alias.name) == name:
                    return _attribute_docstring(stmt.module, alias.name, depth + 1)
            continue
        elif sys.version_info >= (3, 12) and isinstance(stmt, ast.TypeAlias):
            targets = [stmt.name]
        if any(isinstance(t, ast.Name) and t.id == name for t in targets):
            following = body[i + 1] if i + 1 < len(body) else None
            if (
                isinstance(following, ast.Expr)
                and isinstance(following.value, ast.Constant)
                and isinstance(following.value.value, str)
            ):
                return following.value.value
            return None
    return None


def _problems(item: Item) -> list[str]:
    if item.kind == "class":
        return _check_class(item.obj)
    if item.kind == "data":
        module_name, name = item.obj
        return [] if _attribute_docstring(module_name, name) else ["an attribute docstring"]
    return _check_routine(item)


# ----------------------------------------------------------------------------------
# The tests.


def test_public_modules_found() -> None:
    for expected in ("navkit", "navkit.errors", "navkit.geometry", "navkit.planning.grid"):
        assert expected in MODULES
    assert not any("._" in m for m in MODULES)


def test_checker_rules() -> None:
    """The checker itself: it catches what it should and accepts numpydoc forms."""

    def good(a: float, b: float, *args: int, key: str = "", **kwargs: int) -> float:
        """Sum.

        Parameters
        ----------
        a, b : float
            Terms.
        *args : int
            More.
        key : str
            Unused.
        kwargs
            More.

        Returns
        -------
        float
            The sum.

        Examples
        --------
        >>> good(1.0, 2.0)
        3.0
        """
        return a + b

    def bad(a: float, c: float) -> float:
        """Sum.

        Parameters
        ----------
        a : float
            Term.
        b : float
            Not there.
        """
        return a + c

    def quiet(a: float) -> None:
        """Nothing to return.

        Parameters
        ----------
        a : float
            Ignored.

        Examples
        --------
        >>> quiet(1.0)
        """

    assert _check_routine(Item("good", "function", good)) == []
    assert _check_routine(Item("quiet", "function", quiet)) == []
    problems = _check_routine(Item("bad", "function", bad))
    assert problems == [
        "entries for parameter(s) c",
        "no documented parameter(s) b in the signature",
        "a Returns section",
        "an Examples section with a runnable example (>>>)",
    ]

    @dataclasses.dataclass
    class Undocumented:
        x: float

    assert _check_class(Undocumented) == ["a docstring"]

    @dataclasses.dataclass
    class Result:
        """A result.

        Attributes
        ----------
        x : float
            A field.

        Both fields are finite.
        """

        x: float
        y: float

    Result.__module__ = "navkit.example"  # only navkit's constructors are documented
    problems = _check_class(Result)
    assert problems[0] == "an Examples section with a runnable example (>>>)"
    assert problems[1] == "entries for parameter(s) y"
    assert "Both fields are finite." in problems[2]
    assert _attribute_docstring("navkit.kinematics", "OdometryMethod")


@pytest.mark.parametrize("module_name", MODULES)
def test_public_names_documented(module_name: str) -> None:
    inventory = _inventory()
    if module_name in inventory.import_errors:
        pytest.fail(f"{module_name}: {inventory.import_errors[module_name]}")
    failures = []
    for item in inventory.items[module_name]:
        missing = _problems(item)
        if missing:
            failures.append(f"{item.qualname} ({item.kind}) lacks {'; '.join(missing)}")
    assert not failures, f"{len(failures)} undocumented in {module_name}:\n" + "\n".join(failures)
