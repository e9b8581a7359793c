"""Review 47 mutation review: what the compile notice's cache check reads of an index.

Two mutants of ``navkit.cli._kernels`` survived review 47's stale-cache tests:
the time stamp of numba 0.62 (``(st_mtime, st_size)``) compared by its time
alone (k06: the installed numba, 0.68, stamps with a digest, so only a written
index of the old form reaches it), and an entry's data file taken as there when
anything of its name is (k15: numba opens it as a file, and loads nothing from a
folder).
"""

from __future__ import annotations

import pickle
import shutil
import sys
from pathlib import Path

import pytest

from navkit.cli import _kernels

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))
from numba_index import TRANSFORM, empty_cache_folder, write_index

_TRANSFORM = TRANSFORM


@pytest.fixture
def cache_dir(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> Path:
    """The transform's folder in an empty NUMBA_CACHE_DIR of the test's own."""
    return empty_cache_folder(tmp_path, monkeypatch)


def _restamp(index: Path, stamp: object) -> None:
    with index.open("rb") as file:
        version = pickle.load(file)
        _, overloads = pickle.loads(file.read())
    index.write_bytes(pickle.dumps(version) + pickle.dumps((stamp, overloads)))


def test_a_time_stamp_counts_only_with_the_sources_time_and_size(cache_dir: Path) -> None:
    index = write_index(cache_dir, *_TRANSFORM)
    from navkit.mapping import _edt_kernels

    status = Path(_edt_kernels.__file__).stat()
    _restamp(index, (status.st_mtime, status.st_size))
    assert _kernels.kernels_cached("distance_transform")
    # The same time, another size: the source was rewritten within the clock's tick.
    _restamp(index, (status.st_mtime, status.st_size + 1))
    assert not _kernels.kernels_cached("distance_transform")
    _restamp(index, (status.st_mtime + 1.0, status.st_size))
    assert not _kernels.kernels_cached("distance_transform")


def test_an_entry_whose_data_file_is_a_folder_does_not_count(cache_dir: Path) -> None:
    write_index(cache_dir, *_TRANSFORM)
    assert _kernels.kernels_cached("distance_transform")
    (data,) = cache_dir.glob("*.nbc")
    data.unlink()
    data.mkdir()
    try:
        assert not _kernels.kernels_cached("distance_transform")
    finally:
        shutil.rmtree(data)
