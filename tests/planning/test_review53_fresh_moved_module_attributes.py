"""The old planning module names answer only what a pickle asks of them (review 53, FRESH).

4115ab9 answers ``navkit.planning._fields`` (and two other names of the first
days) with a module whose ``__getattr__`` looks names up in
:mod:`navkit.planning`. Once loading an old pickle has put such a module in
``sys.modules``, that ``__getattr__`` raised ValueError for any name it did not
know: ``hasattr(module, "foo")`` raised (PEP 562: a module ``__getattr__``
raises AttributeError), and ``pickle.dumps`` of an unrelated object without a
module (``pickle.whichmodule`` probes every module in ``sys.modules``) failed
with navkit's message. The refusal naming a class navkit no longer has stays
for the classes a pickle of then can name.
"""

from __future__ import annotations

import importlib
import pickle
import sys
import types
import warnings

import pytest

import navkit.planning  # installs the finder of the old names


def _old_module() -> object:
    importlib.import_module("navkit.planning._fields")  # as loading an old pickle does
    return sys.modules["navkit.planning._fields"]


def test_an_unknown_name_is_an_attribute_error() -> None:
    module = _old_module()
    assert not hasattr(module, "foo")
    assert getattr(module, "_private_probe", None) is None


def _orphan() -> None:
    """The code of a function that no module holds (see below)."""


def test_pickling_an_object_without_a_module_is_not_navkits_business() -> None:
    _old_module()
    # A function without a module that no module holds: pickle probes every module in
    # sys.modules for its name, then refuses it as unpicklable (by reference).
    orphan = types.FunctionType(_orphan.__code__, {}, "fresh_orphan")
    orphan.__qualname__ = "fresh_orphan_held_by_no_module"
    orphan.__module__ = None  # type: ignore[assignment]
    # Other libraries' modules warn when probed (mpmath 1.3's deprecated
    # ``mpmath.rational`` module __getattr__): not what this test is about.
    with pytest.raises(pickle.PicklingError), warnings.catch_warnings():
        warnings.simplefilter("ignore", DeprecationWarning)
        pickle.dumps(orphan)


def test_a_class_navkit_no_longer_has_is_still_named() -> None:
    module = _old_module()
    # FieldGrid: _fields held it (FieldPath was _field_dstar's: each module answers its own).
    with pytest.raises(ValueError, match="names FieldGrid, which navkit no longer has"):
        module.FieldGrid  # noqa: B018
    assert module.ConicAttraction is navkit.planning.ConicAttraction
