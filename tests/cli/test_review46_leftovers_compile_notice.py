"""The compile notice checks every kernel its estimate counts (review 46, LEFTOVERS).

``navkit plan`` and ``navkit run`` say "compiling navkit's kernels once (about
N s)" when a run will compile. N counts the kind of work's own kernels and the
distance transform's (``navkit.mapping._edt_kernels.band_distances``), but the
check looked only at one key kernel of the kind: with it cached and the
transform not (an upgrade changing only ``_edt_kernels``), the transform's
0.5 s went unannounced; with the transform cached and the key kernel not, the
notice over-counted it. Each is now checked, and the estimate is what is
missing.
"""

from __future__ import annotations

import importlib
import io
import sys
from pathlib import Path
from typing import Any

import pytest

from navkit.cli import _kernels

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))
from numba_index import write_index

# Spelled out rather than read from the module: the check must find this kernel.
_TRANSFORM = ("navkit.mapping", "_edt_kernels", "band_distances")


def _cache(tmp_path: Path, package: str, module: str, function: str) -> None:
    """An index of the kernel, as numba writes it, where numba would cache it under ``tmp_path``."""
    spec = importlib.util.find_spec(package)
    assert spec is not None and spec.submodule_search_locations
    folder = tmp_path / _kernels._subfolder(Path(next(iter(spec.submodule_search_locations))))
    folder.mkdir(exist_ok=True)
    write_index(folder, package, module, function)


@pytest.fixture
def empty_cache(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> Path:
    """An empty NUMBA_CACHE_DIR of the test's own, the JIT on."""
    monkeypatch.delattr(sys, "frozen", raising=False)
    monkeypatch.setattr(_kernels, "_numba_cache_dir", lambda: str(tmp_path))
    monkeypatch.setattr(_kernels, "jit_disabled", lambda: False)
    return tmp_path


@pytest.mark.parametrize("kind", ["astar", "field_dstar", "simulation"])
def test_the_transform_uncached_is_announced_alone(empty_cache: Path, kind: str) -> None:
    # The key kernel cached, the transform not: the notice was silent.
    _cache(empty_cache, *_kernels.KERNELS[kind][0])
    notice = io.StringIO()
    assert _kernels.announce_compilation(kind, notice, processes=2)
    assert "compiling navkit's kernels once (about 0.5 s, in each of 2 processes)" in (
        notice.getvalue()
    )
    # Both cached: nothing to say.
    _cache(empty_cache, *_TRANSFORM)
    quiet = io.StringIO()
    assert not _kernels.announce_compilation(kind, quiet)
    assert quiet.getvalue() == ""


@pytest.mark.parametrize("kind", ["astar", "field_dstar", "simulation"])
def test_the_transform_cached_is_not_counted(empty_cache: Path, kind: str) -> None:
    _, seconds = _kernels.KERNELS[kind]
    cold = io.StringIO()
    assert _kernels.announce_compilation(kind, cold)
    assert f"(about {seconds:.0f} s)" in cold.getvalue()
    _cache(empty_cache, *_TRANSFORM)
    warm_transform = io.StringIO()
    assert _kernels.announce_compilation(kind, warm_transform)
    assert f"(about {seconds - 0.5:.0f} s)" in warm_transform.getvalue()


def test_the_estimate_asks_the_patched_check_for_each_kernel(
    monkeypatch: pytest.MonkeyPatch,
) -> None:
    # Tests stand in for the cache through kernels_cached: it must be asked for
    # every kernel counted, or their stand-in would not reach the transform.
    asked: list[str] = []

    def kernels_cached(kind: str) -> bool:
        asked.append(kind)
        return kind != "distance_transform"

    monkeypatch.setattr(_kernels, "kernels_cached", kernels_cached)
    monkeypatch.setattr(_kernels, "jit_disabled", lambda: False)
    notice = io.StringIO()
    assert _kernels.announce_compilation("astar", notice)
    assert sorted(asked) == ["astar", "distance_transform"]
    assert "(about 0.5 s)" in notice.getvalue()


def test_an_unusable_cache_says_the_whole_estimate(empty_cache: Path) -> None:
    # Nothing is kept between runs then, whatever the folders hold.
    for key in (_kernels.KERNELS["astar"][0], _TRANSFORM):
        _cache(empty_cache, *key)
    notice = io.StringIO()
    assert _kernels.announce_compilation("astar", notice, problem="read-only")
    seconds = _kernels.KERNELS["astar"][1]
    assert f"(about {seconds:.0f} s), again in every run" in notice.getvalue()


def test_the_shared_kernel_is_a_real_kernel_numba_caches_where_looked() -> None:
    from numba.core import caching

    ((key, seconds),) = _kernels.SHARED_KERNELS.values()
    assert key == _TRANSFORM and seconds == _kernels._DISTANCE_TRANSFORM
    package, module, function = key
    kernel = getattr(importlib.import_module(f"{package}.{module}"), function)
    function_cache: Any = caching.FunctionCache  # untyped
    where = Path(function_cache(kernel.py_func)._cache_path)
    assert where in _kernels.cache_folders(package)
