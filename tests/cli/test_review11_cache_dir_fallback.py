"""The compilation notice looks where numba really caches, NUMBA_CACHE_DIR or not."""

from __future__ import annotations

import importlib
from pathlib import Path
from typing import Any

import numpy as np
import pytest
from numba.core import caching, config

from navkit.cli._kernels import KERNELS, cache_folders, kernels_cached
from navkit.planning import astar


def _numba_folder(package: str, module: str, function: str) -> Path:
    """Where numba itself caches the kernel (its locators' choice)."""
    kernel = getattr(importlib.import_module(f"{package}.{module}"), function)
    function_cache: Any = caching.FunctionCache  # untyped
    return Path(function_cache(kernel.py_func)._cache_path)


def _settings(tmp_path: Path) -> list[str]:
    blocker = tmp_path / "a-file"
    blocker.write_text("")
    return [
        "",  # unset
        str(tmp_path / "cache"),  # usable, made on first use
        str(blocker / "cache"),  # cannot be made: numba falls back
    ]


@pytest.mark.parametrize("kind", sorted(KERNELS))
def test_the_folders_hold_numbas_own_choice(
    monkeypatch: pytest.MonkeyPatch, tmp_path: Path, kind: str
) -> None:
    # With a NUMBA_CACHE_DIR numba cannot use, the check looked only there
    # while numba cached in __pycache__: "compiling ... once, cached
    # afterwards" on every run, the kernels long cached.
    (package, module, function), _ = KERNELS[kind]
    for setting in _settings(tmp_path):
        monkeypatch.setattr(config, "CACHE_DIR", setting)
        assert _numba_folder(package, module, function) in cache_folders(package), setting


def test_an_unusable_cache_dir_counts_the_cache_numba_uses(
    monkeypatch: pytest.MonkeyPatch, tmp_path: Path
) -> None:
    # The kernel cached first: under -n 2 on a cold cache the other worker may
    # write its index between the two reads, and a check of False == False says little.
    astar(np.ones((2, 2)), (0, 0), (1, 1))
    monkeypatch.setattr(config, "CACHE_DIR", "")
    where = cache_folders("navkit.planning.grid")
    cached = kernels_cached("astar")
    monkeypatch.setattr(config, "CACHE_DIR", _settings(tmp_path)[2])
    assert cache_folders("navkit.planning.grid") == where
    assert kernels_cached("astar") == cached
