"""The no-cache warning names what helps: NUMBA_CACHE_DIR, the user cache folder, or sources.

numba ignores ``NUMBA_CACHE_DIR`` for a function whose source file is not there (a
frozen application shipping bytecode only) and caches it in its user cache folder
alone; the warning told such users to set ``NUMBA_CACHE_DIR`` all the same.
"""

from __future__ import annotations

import sys
import types
import warnings
from collections.abc import Callable
from typing import Any

import pytest

from navkit._shared import jit
from navkit.errors import KernelCacheWarning


def _refusing_njit(**options: Any) -> Callable[[Any], Any]:
    """An ``njit`` that, as numba with no writable folder, refuses to cache."""

    def decorate(func: Any) -> Any:
        if options.get("cache"):
            raise RuntimeError(f"cannot cache function {func.__name__!r}: no locator available")
        return func

    return decorate


def _kernel_from(filename: str) -> Callable[[float], float]:
    code = compile("def kernel(x):\n    return 2 * x\n", filename, "exec")
    namespace: dict[str, Any] = {}
    exec(code, namespace)
    kernel: Callable[[float], float] = namespace["kernel"]
    return kernel


@pytest.mark.parametrize("case", ["source", "frozen", "bytecode only"])
def test_the_warning_names_what_helps(
    monkeypatch: pytest.MonkeyPatch, tmp_path: Any, case: str
) -> None:
    source = tmp_path / "kernels.py"
    if case == "source":
        source.write_text("# the kernel's source\n")
    if case == "frozen":
        monkeypatch.setattr("sys.frozen", True, raising=False)
        # numba's own folder for this system (Linux: under XDG_CACHE_HOME), by name.
        monkeypatch.setenv("XDG_CACHE_HOME", str(tmp_path / "user cache"))
    monkeypatch.setattr(jit, "_CACHE_PROBLEM", [])
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        made = jit._make_dispatcher(_refusing_njit, {"cache": True}, _kernel_from(str(source)))
    assert isinstance(made, types.FunctionType) and made(2.0) == 4.0  # made without the cache
    [warning] = [w for w in caught if issubclass(w.category, KernelCacheWarning)]
    message = str(warning.message)
    assert str(source) in message
    if case == "frozen":
        assert "source file is not there" in message
        assert f"Make {jit.numba_user_cache_folder()} writable" in message
        if sys.platform.startswith("linux"):
            assert str(tmp_path / "user cache" / "numba") in message
        assert "NUMBA_CACHE_DIR to" not in message
    elif case == "bytecode only":  # not frozen: numba caches it nowhere
        assert "source file is not there" in message and ".py files" in message
        assert "NUMBA_CACHE_DIR to" not in message and "Make " not in message
    else:
        assert "Set NUMBA_CACHE_DIR to a writable folder" in message
        assert "read-only" in message
    assert [message] == jit._CACHE_PROBLEM
