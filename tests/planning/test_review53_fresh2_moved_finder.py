"""The finder of navkit.planning's old module names, installed once, answering their names only.

4115ab9 answers ``navkit.planning._fields``, ``_field_dstar`` and
``reactive._fields`` (pickles of 23-30 November 2026) through a finder on
:data:`sys.meta_path`. ``install()`` counted it with ``isinstance``, so that
``importlib.reload`` of ``navkit.planning._moved`` (a new ``_Finder`` class)
added a second finder at each reload; and the old modules' names that are gone
today, functions included (``field_grid``, ``field_dstar_cells``, which a pickle
names by reference), stay a ValueError naming them while a name those modules
never held (``os``, ``MapPlanner``) is an AttributeError; ``python -m`` of an old
name says it has no code (it raised AttributeError from runpy); and the finder is
installed before navkit.planning imports its halves, so that a thread importing an old
name while another imports navkit.planning finds it (review 53, FRESH2).
"""

from __future__ import annotations

import os
import pickle
import runpy
import subprocess
import sys

import pytest

import navkit.planning  # installs the finder


def test_the_finder_is_installed_once_across_reloads() -> None:
    # In a process of its own: a reload leaves this one's _moved._Finder a new class.
    code = (
        "import importlib, sys\n"
        "import navkit.planning\n"
        "from navkit._shared import moved as _moved\n"
        "importlib.reload(_moved)\n"
        "importlib.reload(navkit.planning)\n"
        "_moved.install()\n"
        "print(sum(type(f).__qualname__ == '_Finder' for f in sys.meta_path))\n"
    )
    env = {**os.environ, "PYTHONPATH": os.pathsep.join(sys.path)}
    done = subprocess.run(
        [sys.executable, "-c", code], capture_output=True, text=True, env=env, timeout=120
    )
    assert done.returncode == 0, done.stderr
    assert done.stdout.split() == ["1"]


@pytest.mark.parametrize(
    ("module", "gone"),
    [
        ("navkit.planning._fields", "field_grid"),
        ("navkit.planning.reactive._fields", "FieldGrid"),
        ("navkit.planning._field_dstar", "field_dstar_cells"),
        ("navkit.planning._field_dstar", "FieldPath"),
    ],
)
def test_a_name_the_old_module_held_and_navkit_lost_is_named(module: str, gone: str) -> None:
    with pytest.raises(ValueError, match=f"names {gone}, which navkit no longer has"):
        pickle.loads(f"c{module}\n{gone}\n.".encode())


@pytest.mark.parametrize(
    ("module", "name"),
    [
        ("navkit.planning._field_dstar", "MapPlanner"),  # public today, not then
        ("navkit.planning._fields", "_public"),
        ("navkit.planning._fields", "os"),
    ],
)
def test_a_name_the_old_module_never_held_is_no_attribute(module: str, name: str) -> None:
    with pytest.raises(AttributeError, match=repr(name)):
        pickle.loads(f"c{module}\n{name}\n.".encode())


def test_the_old_names_still_give_todays_objects() -> None:
    loaded = pickle.loads(b"cnavkit.planning._field_dstar\nfield_dstar\n.")
    assert loaded is navkit.planning.field_dstar
    loaded = pickle.loads(b"cnavkit.planning.reactive._fields\nCompositeField\n.")
    assert loaded is navkit.planning.CompositeField


def test_running_an_old_name_says_it_has_no_code(monkeypatch: pytest.MonkeyPatch) -> None:
    # python -m navkit.planning._fields: runpy asked the finder for get_code, which
    # it lacked (AttributeError: '_Finder' object has no attribute 'get_code').
    monkeypatch.delitem(
        sys.modules, "navkit.planning._fields", raising=False
    )  # as in a new process
    with pytest.raises(ImportError, match="No code object available"):
        runpy.run_module("navkit.planning._fields")


_DURING_INIT = """
import importlib, sys

class Probe:
    # Imports an old name while navkit.planning's __init__ imports its grid half,
    # as a thread unpickling an old pickle then does: navkit.planning is in
    # sys.modules, half run, and importlib does not wait for a parent's import.
    seen = False

    def find_spec(self, name, path, target=None):
        if name == "navkit.planning.grid" and not Probe.seen:
            Probe.seen = True
            try:
                importlib.import_module("navkit.planning._fields")
                print("found")
            except ModuleNotFoundError:
                print("missing")
        return None

sys.meta_path.insert(0, Probe())
import navkit.planning
print(navkit.planning.ConicAttraction is sys.modules["navkit.planning._fields"].ConicAttraction)
"""


def test_an_old_name_imported_while_navkit_planning_initialises_is_found() -> None:
    # 7 of 25 runs of 8 threads unpickling old pickles at first import raised
    # ModuleNotFoundError: the finder was installed after the halves' imports.
    env = {**os.environ, "PYTHONPATH": os.pathsep.join(sys.path)}
    done = subprocess.run(
        [sys.executable, "-c", _DURING_INIT], capture_output=True, text=True, env=env, timeout=120
    )
    assert done.returncode == 0, done.stderr
    assert done.stdout.split() == ["found", "True"]
