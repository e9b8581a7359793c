"""The compile notice counts a stale cache index as no cache, as numba does (review 47).

``navkit plan``, ``run`` and ``demo`` say "compiling navkit's kernels once" when
a key kernel is not cached. The check took any index file of the kernel as a
cache, but numba uses one only when it was written by the same numba version
for the source as it is now (its stamp: ``(st_mtime, st_size)`` up to numba
0.62, the SHA-256 of the source's bytes in 0.68) and names a data file that
exists: after an upgrade or an edit numba recompiled with no notice.
"""

from __future__ import annotations

import json
import os
import pickle
import subprocess
import sys
from collections.abc import Callable
from pathlib import Path
from typing import Any

import pytest

from navkit.cli import _kernels

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))
from numba_index import TRANSFORM, empty_cache_folder, navkit_copy, write_index

_TRANSFORM = TRANSFORM

# In a fresh process on a copy of navkit: the check's answer for the transform,
# the notice for A* (its own kernel never cached here: about 3 s with the
# transform to compile, 2 s without), then whether numba itself loaded the
# transform from its cache or compiled it.
_PROBE = """
import io, json, sys
sys.path.insert(0, sys.argv[1])
import numpy as np
from navkit.cli import _kernels
from navkit.mapping import _edt_kernels
from navkit.mapping._obstacle_distance import obstacle_distance
assert _edt_kernels.__file__.startswith(sys.argv[1]), _edt_kernels.__file__
cached = _kernels.kernels_cached("distance_transform")
notice = io.StringIO()
_kernels.announce_compilation("astar", notice)
obstacle_distance(np.array([[True, False]]))
stats = _edt_kernels.band_distances.stats
print(json.dumps({
    "cached": cached, "notice": notice.getvalue(),
    "hit": bool(stats.cache_hits), "miss": bool(stats.cache_misses),
}))
"""


def _probe(app: Path, cache: Path) -> dict[str, Any]:
    env = {k: v for k, v in os.environ.items() if not k.startswith(("NUMBA_", "PYTHONWARN"))}
    env["NUMBA_CACHE_DIR"] = str(cache)
    done = subprocess.run(
        [sys.executable, "-c", _PROBE, str(app)],
        env=env, capture_output=True, text=True, timeout=600,
    )  # fmt: skip
    assert done.returncode == 0, done.stderr[-3000:]
    result: dict[str, Any] = json.loads(done.stdout.splitlines()[-1])
    # Exactly one of the two: the probe's call reached numba's cache.
    assert result["hit"] != result["miss"], result
    return result


def test_the_check_agrees_with_numba_when_the_source_changes(tmp_path: Path) -> None:
    app = navkit_copy(tmp_path / "app")
    cache = tmp_path / "cache"
    source = app / "navkit" / "mapping" / "_edt_kernels.py"

    cold = _probe(app, cache)
    assert (cold["cached"], cold["miss"]) == (False, True)
    assert "(about 3 s)" in cold["notice"]
    warm = _probe(app, cache)
    assert (warm["cached"], warm["hit"]) == (True, True)
    assert "(about 2 s)" in warm["notice"]

    # Only the time stamp changes: numba 0.62 recompiles (its stamp holds the
    # time), 0.68 does not (the source's bytes are the same): the check follows.
    status = source.stat()
    os.utime(source, (status.st_atime, status.st_mtime + 100.0))
    touched = _probe(app, cache)
    assert touched["cached"] == touched["hit"], touched

    # An edit (an upgrade of navkit): numba recompiles in silence; the check
    # said it was cached, and the notice left out the transform's 0.5 s.
    source.write_text(source.read_text() + "\n# edited\n")
    edited = _probe(app, cache)
    assert (edited["cached"], edited["miss"]) == (False, True)
    assert "(about 3 s)" in edited["notice"]


@pytest.fixture
def cache_dir(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> Path:
    """The transform's folder in an empty NUMBA_CACHE_DIR of the test's own."""
    return empty_cache_folder(tmp_path, monkeypatch)


def test_an_index_numba_writes_counts(cache_dir: Path) -> None:
    assert not _kernels.kernels_cached("distance_transform")
    write_index(cache_dir, *_TRANSFORM)
    assert _kernels.kernels_cached("distance_transform")


def test_an_index_of_other_source_does_not_count(cache_dir: Path) -> None:
    # The stamp numba gives the source changed (an edit, or numba 0.62's time
    # stamp after a reinstall): numba drops the index.
    index = write_index(cache_dir, *_TRANSFORM)
    with index.open("rb") as file:
        version = pickle.load(file)
        stamp, overloads = pickle.loads(file.read())
    other = bytes(32) if isinstance(stamp, bytes) else (stamp[0] - 1.0, stamp[1])
    index.write_bytes(pickle.dumps(version) + pickle.dumps((other, overloads)))
    assert not _kernels.kernels_cached("distance_transform")


def test_another_numba_versions_index_does_not_count(cache_dir: Path) -> None:
    # numba reads nothing past another version's number (an upgrade of numba).
    write_index(cache_dir, *_TRANSFORM, version="0.0.1")
    assert not _kernels.kernels_cached("distance_transform")


def test_an_index_whose_data_file_is_gone_does_not_count(cache_dir: Path) -> None:
    index = write_index(cache_dir, *_TRANSFORM)
    (data,) = cache_dir.glob("*.nbc")
    data.unlink()
    assert not _kernels.kernels_cached("distance_transform")
    # numba's flush: an index with no entries.
    with index.open("rb") as file:
        version = pickle.load(file)
        stamp, _ = pickle.loads(file.read())
    index.write_bytes(pickle.dumps(version) + pickle.dumps((stamp, {})))
    assert not _kernels.kernels_cached("distance_transform")


@pytest.mark.parametrize(
    "content",
    [
        lambda version: b"",
        lambda version: b"not a pickle",
        lambda version: pickle.dumps(version) + b"\x80",  # cut short
        lambda version: pickle.dumps(version) + pickle.dumps(3),  # no (stamp, entries)
    ],
)
def test_an_unreadable_index_does_not_count(
    cache_dir: Path, content: Callable[[str], bytes]
) -> None:
    import numba

    index = write_index(cache_dir, *_TRANSFORM)
    index.write_bytes(content(numba.__version__))
    assert not _kernels.kernels_cached("distance_transform")


def test_a_stamp_of_a_form_numba_never_wrote_counts_as_before(cache_dir: Path) -> None:
    # What another numba makes of it is not known: the notice stays as it was.
    index = write_index(cache_dir, *_TRANSFORM)
    with index.open("rb") as file:
        version = pickle.load(file)
        _, overloads = pickle.loads(file.read())
    index.write_bytes(pickle.dumps(version) + pickle.dumps(("a stamp", overloads)))
    assert _kernels.kernels_cached("distance_transform")
