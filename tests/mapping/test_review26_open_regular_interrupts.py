"""``open_regular`` interrupted at any point: the interrupt, and no descriptor lost or closed twice.

It returned ``os.fdopen(fd, "rb")`` inside a ``try`` whose ``except`` closed
``fd``: a ``KeyboardInterrupt`` delivered inside ``os.fdopen`` (Python code),
after the file object took the descriptor, closed it once as that object was
dropped and again in the ``except``, whose ``OSError`` (EBADF) replaced the
interrupt; saving a map read it as "m.pgm already exists and is not the image of
the map" (found by review 26's warnings-and-resources lens).
"""

from __future__ import annotations

import gc
import os
import sys
import warnings
from pathlib import Path

import pytest

from interrupt_points import delivery_points
from navkit.mapping.io._paths import open_regular

pytestmark = pytest.mark.skipif(
    not os.path.isdir("/proc/self/fd"), reason="counts descriptors in /proc/self/fd"
)


def _count() -> int:
    return len(os.listdir("/proc/self/fd"))


def _open_fds() -> int:
    gc.collect()
    return _count()


def test_every_interrupt_point_raises_the_interrupt_and_keeps_no_descriptor(
    tmp_path: Path,
) -> None:
    path = tmp_path / "log.txt"
    path.write_bytes(b"FLASER 0\n")

    def read() -> None:
        with open_regular(path, "CARMEN log") as fh:
            fh.read()

    points = delivery_points(read)
    before = _open_fds()
    for k in range(1, points + 1):
        seen: list[tuple[str, object]] = []

        def profile(
            frame: object, event: str, arg: object, k: int = k,
            seen: list[tuple[str, object]] = seen,
        ) -> None:
            if event in ("call", "c_return"):
                seen.append((event, arg))
                if len(seen) == k:
                    sys.setprofile(None)
                    raise KeyboardInterrupt

        # A file object dropped by the interrupt closes its descriptor, with a
        # ResourceWarning (expected here: the suite makes warnings errors).
        with warnings.catch_warnings():
            warnings.simplefilter("ignore", ResourceWarning)
            sys.setprofile(profile)
            try:
                read()
            except KeyboardInterrupt:
                pass  # anything else (the OSError of a second close) fails the test
            finally:
                sys.setprofile(None)
            # Only when a descriptor seems left (or before a new baseline): a collection
            # walks the whole heap, seconds late in a full run.
            if seen[-1] == ("c_return", os.open) or _count() != before:
                gc.collect()
        if seen[-1] == ("c_return", os.open):
            # The descriptor os.open returned, before it is bound to a name: nothing in
            # Python can close it (lost until the process ends), as with any open().
            before = _open_fds()
            continue
        assert _count() == before, f"a descriptor left open at point {k} of {points}"
    with open_regular(path, "CARMEN log") as fh:
        assert fh.read() == b"FLASER 0\n"
