"""Map images read by several threads at once (a ROS 2 node's multi-threaded executor).

Reading a Pillow image (PNG) hides Pillow's ``DecompressionBombWarning``
(navkit applies its own size limit) with ``warnings.catch_warnings``, which
changes the warning filters of the whole process and, on leaving, puts back
the list it found on entering. Two threads inside at once used to leave the
ignore filter installed for good (the later one to enter left last and put
back the list holding the earlier one's filter) and to let the warning
through in the other thread. The first test forces that interleaving (each
reader's ``Image.open`` waits, up to a timeout, for the other to get where
it did); the others start readers together at a tiny switch interval. The
filters must be left as they were and no warning may reach the caller:
navkit's readers now take turns while they change the filters.
"""

from __future__ import annotations

import sys
import threading
import warnings
from collections.abc import Iterator
from pathlib import Path

import numpy as np
import pytest
import yaml

from navkit.mapping import OccupancyGrid
from navkit.mapping.io import read_map, write_map

Image = pytest.importorskip("PIL.Image")

THREADS = 4
ROUNDS = 12


@pytest.fixture
def tiny_switch_interval() -> Iterator[None]:
    before = sys.getswitchinterval()
    sys.setswitchinterval(1e-6)
    try:
        yield
    finally:
        sys.setswitchinterval(before)


@pytest.fixture
def png_map(tmp_path: Path) -> tuple[Path, OccupancyGrid]:
    occupied = np.random.default_rng(3).random((120, 160)) < 0.2
    grid = OccupancyGrid.from_occupancy(occupied, resolution=0.05, origin=(1.0, -2.0, 0.0))
    path = tmp_path / "m.yaml"
    write_map(grid, path, mode="scale")  # a PNG: read with Pillow
    assert (tmp_path / "m.png").is_file()
    return path, read_map(path)


@pytest.fixture
def tiff_map(tmp_path: Path, png_map: tuple[Path, OccupancyGrid]) -> tuple[Path, OccupancyGrid]:
    """The PNG map's grey levels as a TIFF, which Pillow checks again when it decodes."""
    path, _ = png_map
    with Image.open(path.with_suffix(".png")) as png:
        png.convert("L").save(tmp_path / "t.tiff")
    tiff_yaml = tmp_path / "t.yaml"
    tiff_yaml.write_text(path.read_text().replace("m.png", "t.tiff"))
    return tiff_yaml, read_map(tiff_yaml)


def _read_together(path: Path, reads: int) -> list[OccupancyGrid]:
    barrier = threading.Barrier(THREADS)
    grids: list[OccupancyGrid] = []
    errors: list[BaseException] = []

    def work() -> None:
        try:
            barrier.wait()
            for _ in range(reads):
                grids.append(read_map(path))
        except BaseException as exc:  # pragma: no cover - reported below
            errors.append(exc)

    threads = [threading.Thread(target=work) for _ in range(THREADS)]
    for thread in threads:
        thread.start()
    for thread in threads:
        thread.join()
    assert not errors, errors
    return grids


def test_a_read_leaving_while_another_is_inside_restores_the_filters_of_neither(
    png_map: tuple[Path, OccupancyGrid], monkeypatch: pytest.MonkeyPatch
) -> None:
    path, expected = png_map
    # 19,200 pixels: above Pillow's limit (it warns) and below twice it (it would refuse).
    monkeypatch.setattr(Image, "MAX_IMAGE_PIXELS", 12_000)
    real_open = Image.open
    a_inside, b_inside, a_done = threading.Event(), threading.Event(), threading.Event()
    first: list[threading.Thread] = []
    waits: dict[str, bool] = {}

    def open_(*args: object, **kwargs: object) -> object:
        if threading.current_thread() is first[0]:
            a_inside.set()
            waits["a saw b inside"] = b_inside.wait(timeout=0.5)
        else:
            b_inside.set()
            # With the fix b holds navkit's lock here, which a needs again to decode
            # this large image: a's read ends only when this wait gives up.
            waits["b saw a done"] = a_done.wait(timeout=2.0)
        return real_open(*args, **kwargs)

    monkeypatch.setattr(Image, "open", open_)
    grids: list[OccupancyGrid] = []
    errors: list[BaseException] = []

    def read(done: threading.Event | None) -> None:
        try:
            grids.append(read_map(path))
        except BaseException as exc:  # pragma: no cover - reported below
            errors.append(exc)
        finally:
            if done is not None:
                done.set()

    before = list(warnings.filters)
    try:
        with warnings.catch_warnings(record=True) as caught:
            warnings.simplefilter("always")
            recording = list(warnings.filters)
            a = threading.Thread(target=read, args=(a_done,))
            b = threading.Thread(target=read, args=(None,))
            first.append(a)
            a.start()
            assert a_inside.wait(timeout=10.0)
            b.start()
            a.join(timeout=20.0)
            b.join(timeout=20.0)
            assert not a.is_alive() and not b.is_alive()
            left = list(warnings.filters)
        assert not errors, errors
        assert left == recording  # no ignore filter left behind
        assert [w.message for w in caught] == []  # none let through in b
        # b could not get inside while a was: it waited for a's turn to end.
        assert waits["a saw b inside"] is False
        assert len(grids) == 2
        for grid in grids:
            np.testing.assert_array_equal(grid.logodds, expected.logodds)
    finally:
        warnings.filters[:] = before


@pytest.mark.usefixtures("tiny_switch_interval")
def test_parallel_reads_leave_the_warning_filters_as_they_were(
    png_map: tuple[Path, OccupancyGrid],
) -> None:
    path, expected = png_map
    before = list(warnings.filters)
    try:
        for round_ in range(ROUNDS):
            grids = _read_together(path, reads=2)
            assert warnings.filters == before, f"filters changed in round {round_}"
            assert len(grids) == 2 * THREADS
            for grid in grids:
                np.testing.assert_array_equal(grid.logodds, expected.logodds)
    finally:
        warnings.filters[:] = before


@pytest.mark.usefixtures("tiny_switch_interval")
@pytest.mark.parametrize("kind", ["png_map", "tiff_map"])
def test_parallel_reads_of_a_large_image_give_no_decompression_bomb_warning(
    kind: str, request: pytest.FixtureRequest, monkeypatch: pytest.MonkeyPatch
) -> None:
    path, expected = request.getfixturevalue(kind)
    image = path.parent / yaml.safe_load(path.read_text())["image"]
    # 19,200 pixels: above Pillow's limit (it warns) and below twice it (it would refuse).
    monkeypatch.setattr(Image, "MAX_IMAGE_PIXELS", 12_000)
    before = list(warnings.filters)
    try:
        with warnings.catch_warnings(record=True) as caught:
            warnings.simplefilter("always")
            recording = list(warnings.filters)
            for _ in range(ROUNDS):
                _read_together(path, reads=2)
                # A filter left behind by one round would hide what the next lets through.
                warnings.filters[:] = recording
        bombs = [w for w in caught if issubclass(w.category, Image.DecompressionBombWarning)]
        assert bombs == []
        # The filter hid the warning from navkit's reads only: Pillow still warns its caller
        # (a TIFF again when it decodes, after navkit has opened the image).
        # The filter is set before Image.open: it warns already (a PNG; under an "error"
        # filter the warning would be raised there, not recorded).
        with (
            warnings.catch_warnings(record=True, action="always") as caught,
            Image.open(image) as img,
        ):
            img.load()
        assert Image.DecompressionBombWarning in [w.category for w in caught]
    finally:
        warnings.filters[:] = before
    assert read_map(path).shape == expected.shape
