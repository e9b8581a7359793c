"""The numba shortcuts of navkit's compiles: the same answers, on only while navkit compiles.

:mod:`navkit._shared.compile_shortcuts` replaces numba's compile-flag
``__hash__``/``__eq__`` and its colour scheme's ``_markup`` while a navkit
kernel compiles. These tests check that the replacements answer exactly as
numba's own (hypothesis), that they are on during a navkit compile and off
otherwise, that a user's numba (methods, config, warning filters, streams)
is as before once navkit has compiled, that a user's own typing error keeps
numba's message, and that what numba compiles is the same with and without.
The compiling checks run in a fresh interpreter with an empty numba cache.
"""

from __future__ import annotations

import importlib
import os
import subprocess
import sys
import textwrap
import threading
from pathlib import Path
from typing import Any

import pytest
from hypothesis import example, given
from hypothesis import strategies as st

from navkit._shared import compile_shortcuts
from navkit._shared.jit import load_numba

load_numba()
# Any: numba is not typed in every supported version.
errors: Any = importlib.import_module("numba.core.errors")
targetconfig: Any = importlib.import_module("numba.core.targetconfig")
Flags: Any = importlib.import_module("numba.core.compiler").Flags
TargetConfig: Any = targetconfig.TargetConfig


def _run(code: str, cache: Path, **env: str) -> str:
    environment = {**os.environ, "NUMBA_CACHE_DIR": str(cache), **env}
    out = subprocess.run(
        [sys.executable, "-c", textwrap.dedent(code)],
        check=True, capture_output=True, text=True, timeout=300, env=environment,
    )  # fmt: skip
    return out.stdout.strip()


# --- the replacements answer as numba's own ---------------------------------------------

#: Per option, values the setter accepts (the default among them, set explicitly).
_CHOICES: dict[str, list[Any]] = {
    "error_model": ["python", "numpy"],
    "fastmath": [False, True, {"nnan"}],
    "inline": ["never", "always"],
    "auto_parallel": [False, True],
}


def _choices(name: str, option: Any) -> list[Any]:
    if name in _CHOICES:
        return _CHOICES[name]
    if option.type is bool:
        return [False, True]
    return [option.default]


@st.composite
def _flags(draw: st.DrawFn) -> Any:
    """Flags with some options set (possibly to their default), the rest unset."""
    flags = Flags()
    for name, option in Flags.options.items():
        if draw(st.booleans()):
            setattr(flags, name, draw(st.sampled_from(_choices(name, option))))
    return flags


def _numba_methods() -> tuple[Any, Any]:
    assert not compile_shortcuts.active()  # numba's own are in place
    return TargetConfig.__hash__, TargetConfig.__eq__


@given(_flags(), _flags())
def test_flag_hash_and_equality_are_numbas(a: Any, b: Any) -> None:
    numba_hash, numba_eq = _numba_methods()
    fast_hash, fast_eq = compile_shortcuts._flag_methods(TargetConfig)
    assert fast_hash(a) == numba_hash(a)
    assert fast_eq(a, b) == numba_eq(a, b)
    assert fast_eq(a, Flags(a)) is True
    assert fast_eq(a, "not flags") is NotImplemented


def test_an_option_set_to_its_default_equals_it_unset() -> None:
    _, fast_eq = compile_shortcuts._flag_methods(TargetConfig)
    unset, default = Flags(), Flags()
    default.nrt = Flags.options["nrt"].default
    assert fast_eq(unset, default) is True
    default.nrt = not Flags.options["nrt"].default
    assert fast_eq(unset, default) is False


class _Computed(TargetConfig):  # type: ignore[misc]  # (a class of Any)
    """A config whose option's property is not numba's: left to numba's methods."""

    level = targetconfig.Option(type=int, default=0, doc="a level")
    other = targetconfig.Option(type=int, default=0, doc="another")


_Computed.level = property(lambda self: 7)  # every value reads as 7


def test_a_config_with_its_own_properties_is_compared_by_numba() -> None:
    numba_hash, numba_eq = _numba_methods()
    fast_hash, fast_eq = compile_shortcuts._flag_methods(TargetConfig)
    a, b = _Computed(), _Computed()
    a._values["level"] = 1  # a stored value the property does not read
    assert fast_eq(a, b) == numba_eq(a, b) is True
    assert fast_hash(a) == numba_hash(a)
    assert not compile_shortcuts._plain(_Computed, TargetConfig)


_COLOURS = [None, "", "\x1b[31m", "\x1b[34m"]


@given(
    st.text(max_size=40),
    st.sampled_from(_COLOURS),
    st.sampled_from([None, "", "\x1b[1m"]),
)
@example("lone \ud800 surrogate", None, None)
@example("héllo wörld ✓", "\x1b[31m", "\x1b[1m")
def test_markup_is_numbas_string(message: str, colour: str | None, style: str | None) -> None:
    scheme_class = getattr(errors, "HighlightColorScheme", None)
    if scheme_class is None:
        pytest.skip("numba's colour scheme needs colorama")
    numba_scheme = scheme_class(errors.themes["no_color"])
    fast = compile_shortcuts._markup_method(errors)
    try:
        expected: Any = numba_scheme._markup(message, colour, style)
    except UnicodeEncodeError as exc:  # a lone surrogate: both refuse it
        expected = type(exc)
    try:
        got: Any = fast(message, colour, style)
    except UnicodeEncodeError as exc:
        got = type(exc)
    assert got == expected
    if expected is not UnicodeEncodeError:
        assert fast(message, colour) == numba_scheme._markup(message, colour)  # default style


# --- switched on and off ------------------------------------------------------------------


def test_begin_and_end_switch_the_shortcuts_and_put_numbas_own_back() -> None:
    numba_hash, numba_eq = _numba_methods()
    scheme = errors.termcolor()
    compile_shortcuts.begin()
    compile_shortcuts.begin()  # nested (a kernel's callee)
    try:
        assert compile_shortcuts.active()
        assert TargetConfig.__eq__ is not numba_eq
        compile_shortcuts.end()
        assert compile_shortcuts.active()  # the outer compile goes on
    finally:
        compile_shortcuts.end()
    assert not compile_shortcuts.active()
    assert TargetConfig.__hash__ is numba_hash and TargetConfig.__eq__ is numba_eq
    assert "_markup" not in vars(scheme)


def test_overlapping_compiles_in_two_threads_switch_off_once_both_end() -> None:
    inside, leave = threading.Event(), threading.Event()
    seen: list[bool] = []

    def other() -> None:
        compile_shortcuts.begin()
        try:
            inside.set()
            leave.wait(30)
            seen.append(compile_shortcuts.active())
        finally:
            compile_shortcuts.end()

    worker = threading.Thread(target=other)
    compile_shortcuts.begin()
    worker.start()
    assert inside.wait(30)
    compile_shortcuts.end()
    seen.append(compile_shortcuts.active())  # the other's compile is not over
    leave.set()
    worker.join(30)
    assert seen == [True, True]
    assert not compile_shortcuts.active()


def test_a_method_someone_installs_meanwhile_is_left_in_place() -> None:
    numba_hash, numba_eq = _numba_methods()

    def theirs(self: Any, other: Any) -> Any:
        return numba_eq(self, other)

    compile_shortcuts.begin()
    try:
        TargetConfig.__eq__ = theirs
    finally:
        compile_shortcuts.end()
    try:
        assert TargetConfig.__eq__ is theirs
        assert TargetConfig.__hash__ is numba_hash
    finally:
        TargetConfig.__eq__ = numba_eq


def test_disabled_the_compile_runs_with_numba_as_it_is(monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setattr(compile_shortcuts, "ENABLED", False)
    _, numba_eq = _numba_methods()
    compile_shortcuts.begin()
    try:
        assert not compile_shortcuts.active()
        assert TargetConfig.__eq__ is numba_eq
    finally:
        compile_shortcuts.end()


@pytest.mark.skipif(not hasattr(os, "fork") or sys.platform != "linux", reason="needs os.fork")
def test_a_child_forked_during_another_threads_compile_has_numbas_methods() -> None:
    _, numba_eq = _numba_methods()
    inside, leave = threading.Event(), threading.Event()

    def other() -> None:
        compile_shortcuts.begin()
        try:
            inside.set()
            leave.wait(30)
        finally:
            compile_shortcuts.end()

    worker = threading.Thread(target=other)
    worker.start()
    assert inside.wait(30)
    try:
        read, write = os.pipe()
        pid = os.fork()
        if pid == 0:  # the child: report, then leave at once (no pytest teardown here)
            try:
                state = f"{compile_shortcuts.active()} {TargetConfig.__eq__ is numba_eq}"
                os.write(write, state.encode())
            finally:
                os._exit(0)
        os.close(write)
        with os.fdopen(read) as pipe:
            out = pipe.read()
        os.waitpid(pid, 0)
        assert compile_shortcuts.active()  # the parent's compile goes on
    finally:
        leave.set()
        worker.join(30)
    assert out == "False True"
    assert TargetConfig.__eq__ is numba_eq


# --- a real first use -------------------------------------------------------------------

_WATCH = """
import sys, warnings, numba
import numpy as np
from numba.core import config, errors, event, targetconfig
from navkit._shared import compile_shortcuts
from navkit._shared.jit import load_numba
from navkit.planning import astar

def snapshot():
    scheme = errors.termcolor()
    return (targetconfig.TargetConfig.__eq__, targetconfig.TargetConfig.__hash__,
            dict(vars(scheme)), list(warnings.filters), sys.stdout, sys.stderr,
            {k: v for k, v in vars(config).items() if k.isupper()})

load_numba()
seen = []

class Watch(event.Listener):
    def on_start(self, ev):
        dispatcher = ev.data["dispatcher"]
        seen.append((dispatcher.py_func.__module__.partition(".")[0], compile_shortcuts.active()))
    def on_end(self, ev):
        pass

event.register("numba:compile", Watch())
before = snapshot()

@numba.njit
def users_own(x):
    return x + 1

users_own(1)
astar(np.ones((6, 6)), (0, 0), (5, 5))
users_own(1.5)
print(sorted(set(seen)))
print(snapshot() == before)
"""


def test_on_during_navkit_compiles_only_and_the_users_numba_as_before(tmp_path: Path) -> None:
    lines = _run(_WATCH, tmp_path).splitlines()
    assert lines[-2] == "[('__main__', False), ('navkit', True)]"
    assert lines[-1] == "True"


_USERS_ERROR = """
import numba
import numpy as np
{prelude}

@numba.njit
def users_own(x):
    return x.no_such_attribute

try:
    users_own(1.0)
except numba.core.errors.TypingError as exc:
    print(repr(str(exc)))
"""


def test_a_users_typing_error_keeps_numbas_message(tmp_path: Path) -> None:
    # One line either way: numba's message names the line of the error.
    prelude = "from navkit.planning import astar; astar(np.ones((6, 6)), (0, 0), (5, 5))"
    with_navkit = _run(_USERS_ERROR.format(prelude=prelude), tmp_path / "a")
    without = _run(_USERS_ERROR.format(prelude="pass"), tmp_path / "b")
    assert "no_such_attribute" in without
    assert with_navkit == without
    if getattr(errors, "HighlightColorScheme", None) is not None and not os.environ.get(
        "NUMBA_DISABLE_ERROR_MESSAGE_HIGHLIGHTING"
    ):
        assert "\\x1b[" in without  # numba's markup, as usual


_COMPILED = """
import numpy as np
from navkit._shared import compile_shortcuts
compile_shortcuts.ENABLED = {enabled}
from navkit.planning import astar
astar(np.ones((6, 6)), (0, 0), (5, 5))
import re
import sys
from numba.core.dispatcher import Dispatcher
found = []
for module_name, module in sorted(sys.modules.items()):
    if not module_name.startswith("navkit.") or module is None:
        continue
    for name, value in sorted(vars(module).items()):
        if isinstance(value, Dispatcher) and value.py_func.__module__ == module_name:
            for sig in value.signatures:
                # Constants' symbols carry the address of a Python object (numba 0.62).
                ir = re.sub(
                    "(?<=pickledata[.])[0-9]+|(?<=picklebuf[.])[0-9]+", "N", value.inspect_llvm(sig)
                )
                found.append(module_name + name + str(sig) + ir)
print(len(found), hash("".join(found)) if found else None)
"""


@pytest.mark.slow
def test_numba_compiles_the_same_code_with_the_shortcuts(tmp_path: Path) -> None:
    seed = {"PYTHONHASHSEED": "0"}
    on = _run(_COMPILED.format(enabled=True), tmp_path / "on", **seed)
    off = _run(_COMPILED.format(enabled=False), tmp_path / "off", **seed)
    assert int(on.split()[0]) >= 2  # the search and the cost check, at least
    assert on == off
