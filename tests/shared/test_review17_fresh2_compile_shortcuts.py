"""Fresh-eyes checks of navkit's numba shortcuts (session 21's compile_shortcuts).

* Every pairing numba's flag caches can meet answers as numba's own: flags of
  numba's classes and of subclasses (an added option, an option given another
  default, a ``values`` of its own, numba's ``CUDAFlags`` where importable),
  options set explicitly to their default, ``_values`` holding a key that is not
  an option of the class, and objects that are not flags at all (``==`` and
  ``!=`` both ways, ``NotImplemented`` included); hashes are numba's, so a dict
  built while one pair of methods is in place is probed with the other.
* A user's kernel that calls a navkit kernel compiles with the shortcuts on to
  its end: its own typing errors, and those of the navkit call it makes, read
  exactly as with the shortcuts off (in fresh interpreters, empty caches).
"""

from __future__ import annotations

import contextlib
import importlib
import itertools
import os
import random
import re
import subprocess
import sys
import textwrap
from pathlib import Path
from typing import Any

import pytest

from navkit._shared import compile_shortcuts
from navkit._shared.jit import load_numba

load_numba()
# Any: numba is not typed in every supported version.
targetconfig: Any = importlib.import_module("numba.core.targetconfig")
Flags: Any = importlib.import_module("numba.core.compiler").Flags
TargetConfig: Any = targetconfig.TargetConfig
Option: Any = targetconfig.Option


class _Extra(Flags):  # type: ignore[misc]  # (a class of Any)
    """An added option."""

    extra_level = Option(type=int, default=3, doc="an added option")


class _Redefault(Flags):  # type: ignore[misc]
    """One of numba's options with another default."""

    nrt = Option(type=bool, default=True, doc="nrt, on by default")


class _OwnValues(Flags):  # type: ignore[misc]
    """A ``values`` of its own (left to numba's methods)."""

    def values(self) -> dict[str, Any]:
        out: dict[str, Any] = super().values()
        out["computed"] = len(self._values)
        return out


def _classes() -> list[Any]:
    classes = [Flags, _Extra, _Redefault, _OwnValues]
    with contextlib.suppress(Exception):  # numba without its CUDA target: not needed
        classes.append(importlib.import_module("numba.cuda.compiler").CUDAFlags)
    return classes


def _make(cls: Any, rnd: random.Random) -> Any:
    flags = cls()
    for name, option in cls.options.items():
        draw = rnd.random()
        if draw < 0.15:
            flags._values[name] = option.default  # set, to the default
        elif draw < 0.3 and option.type is bool:
            setattr(flags, name, rnd.random() < 0.5)
    if rnd.random() < 0.1:
        flags._values["not_an_option"] = rnd.random() < 0.5  # as a copy from a subclass
    return flags


def _outcome(a: Any, b: Any) -> Any:
    try:
        return (a == b, a != b, a.__eq__(b))  # NotImplemented too
    except Exception as exc:  # compared with numba's: the same error
        return repr(exc)


@pytest.mark.parametrize("seed", range(3))
def test_every_pairing_answers_as_numba(seed: int) -> None:
    assert not compile_shortcuts.active()
    numba_hash, numba_eq = TargetConfig.__hash__, TargetConfig.__eq__
    rnd = random.Random(seed)
    classes = _classes()
    flags = [_make(rnd.choice(classes), rnd) for _ in range(60)]
    flags += [cls() for cls in classes]
    others: list[Any] = [None, 1, "flags", object()]
    objects = flags + others
    want = {
        (i, j): _outcome(a, b) for (i, a), (j, b) in itertools.product(enumerate(objects), repeat=2)
    }
    hashes = [hash(f) for f in flags]
    numbas = {f: i for i, f in enumerate(flags)}
    compile_shortcuts.begin()
    try:
        assert compile_shortcuts.active()
        assert TargetConfig.__eq__ is not numba_eq
        got = {
            (i, j): _outcome(a, b)
            for (i, a), (j, b) in itertools.product(enumerate(objects), repeat=2)
        }
        assert [hash(f) for f in flags] == hashes
        assert [numbas.get(f) for f in flags] == [numbas[f] for f in flags]
        ours = {f: i for i, f in enumerate(flags)}
    finally:
        compile_shortcuts.end()
    assert TargetConfig.__hash__ is numba_hash and TargetConfig.__eq__ is numba_eq
    assert got == want
    assert ours == numbas
    assert [ours.get(f) for f in flags] == [numbas.get(f) for f in flags]


_USER_CALLS_NAVKIT = """
import re
import numpy as np
from navkit._shared import compile_shortcuts
compile_shortcuts.ENABLED = {enabled}
import numba
from navkit.planning.reactive._greedy_kernels import _candidate

@numba.njit
def calls_then_fails(occupied):
    found = _candidate(occupied, 0, 0, 1, 1, 1.0, 1.0, 0.1, 1.0, 5.0)
    return found[0].no_such_attribute

@numba.njit
def calls_it_wrongly(occupied):
    return _candidate(occupied, "row", 0, 1, 1, 1.0, 1.0, 0.1, 1.0, 5.0)

for kernel in (calls_then_fails, calls_it_wrongly):
    try:
        kernel(np.zeros((3, 3), dtype=np.bool_))
    except numba.core.errors.TypingError as exc:
        print(repr(re.sub("0x[0-9a-f]+", "0x?", str(exc))))
    print(compile_shortcuts.active())
"""


def test_a_users_kernel_calling_a_navkit_one_reports_as_numba(tmp_path: Path) -> None:
    out = {}
    for enabled in (True, False):
        env = {**os.environ, "NUMBA_CACHE_DIR": str(tmp_path / str(enabled))}
        done = subprocess.run(
            [sys.executable, "-c", textwrap.dedent(_USER_CALLS_NAVKIT.format(enabled=enabled))],
            capture_output=True, text=True, timeout=300, env=env, check=True,
        )  # fmt: skip
        out[enabled] = done.stdout.splitlines()
    assert out[True] == out[False]
    assert len(out[True]) == 4
    assert "no_such_attribute" in out[True][0]
    assert re.search("getitem|No implementation", out[True][2])
    assert out[True][1] == out[True][3] == "False"  # off again once the compile failed
