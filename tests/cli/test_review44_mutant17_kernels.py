"""Where the command looks for cached kernels (review 44, MUTANT17: a mutant that survived)."""

from __future__ import annotations

from pathlib import Path

import pytest

from navkit.cli import _kernels


def test_a_cache_dir_that_is_a_file_is_passed_over(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    # numba cannot cache under a file (even a writable, executable one): it caches
    # where it would without NUMBA_CACHE_DIR, and the command looks there.
    taken = tmp_path / "cache"
    taken.write_text("not a folder")
    taken.chmod(0o755)
    monkeypatch.setattr(_kernels, "_numba_cache_dir", lambda: str(taken))
    folders = _kernels.cache_folders("navkit.sim")
    assert folders and not any(taken in folder.parents for folder in folders)
    assert folders[0].name == "__pycache__"
