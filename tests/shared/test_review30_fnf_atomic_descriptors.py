"""atomic_paths cut by an interrupt at any point keeps no descriptor open (review 30, FNF).

The temporary files are made with ``os.open`` (``O_EXCL``) and synced through
another ``os.open``; each descriptor is closed whatever is raised after it is
bound to a name, and no temporary file is left. The one point no Python code
can cover is ``os.open``'s own return: CPython delivers a pending interrupt as
the call returns, before its result is stored, so that descriptor is lost until
the process ends (as with any ``open()``); the temporary file is still removed.
These pass as the code stands (they pin it): moving ``_new_temporary``'s
``os.close`` after a call, or ``_sync``'s out of its ``finally``, fails them.
"""

from __future__ import annotations

import gc
import os
import sys
from pathlib import Path

import numpy as np
import pytest

from navkit._shared.files import atomic_paths

pytestmark = pytest.mark.skipif(
    not os.path.isdir("/proc/self/fd"), reason="counts descriptors in /proc/self/fd"
)


def _open_fds(*, collect: bool) -> int:
    # A collection frees descriptors that only garbage (an interrupt's traceback
    # cycles) still holds; it walks the whole heap, which late in a full run takes
    # seconds, so the loop below collects only when a plain count differs.
    if collect:
        gc.collect()
    return len(os.listdir("/proc/self/fd"))


def _interrupted(call: object, k: int) -> tuple[str, object] | None:
    """Run ``call`` with a KeyboardInterrupt at its k-th delivery point; that point."""
    seen: list[tuple[str, object]] = []

    def profile(frame: object, event: str, arg: object) -> None:
        if event in ("call", "c_return"):
            seen.append((event, arg))
            if len(seen) == k:
                sys.setprofile(None)
                raise KeyboardInterrupt

    with np.errstate():
        sys.setprofile(profile)
        try:
            call()  # type: ignore[operator]
        except KeyboardInterrupt:
            return seen[-1]
        finally:
            sys.setprofile(None)
    return None


@pytest.mark.parametrize("count", [1, 2])
def test_every_interrupt_point_keeps_no_descriptor_and_no_temporary(
    tmp_path: Path, count: int
) -> None:
    targets = [tmp_path / f"map{i}.pgm" for i in range(count)]
    targets[0].write_text("old")

    def save() -> None:
        with atomic_paths(targets) as temporaries:
            for temporary in temporaries:
                os.truncate(temporary, 3)

    k = 0
    lost = 0
    before = _open_fds(collect=True)
    while True:
        k += 1
        point = _interrupted(save, k)
        if point is None:  # past the last point: the save went through
            break
        left = sorted(p.name for p in tmp_path.iterdir())
        assert left == sorted(t.name for t in targets if t.exists()), f"point {k}: {left}"
        if point == ("c_return", os.open):
            lost += 1
            before = _open_fds(collect=True)
            continue
        now = _open_fds(collect=False)
        if now != before:
            now = _open_fds(collect=True)
        assert now == before, f"a descriptor left open at point {k} ({point})"
    assert k > 30 and lost >= 2 * count  # every os.open was reached
    assert [t.read_bytes() for t in targets] == [b"\0\0\0"] * count
