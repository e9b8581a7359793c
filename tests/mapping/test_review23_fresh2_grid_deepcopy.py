"""copy.deepcopy of OccupancyGrid subclasses, after the writer lock's ``__deepcopy__``.

Found by the second fresh-eyes review of session 27: the ``__deepcopy__`` that
copies the log-odds under the writer lock built the copy with ``cls.__new__(cls)``
and the state, so a subclass whose ``__new__`` takes arguments (given by
``__getnewargs__``) could no longer be deep-copied (``TypeError``), one with its own
``__reduce__`` was deep-copied past it, and a container holding the grid's own
log-odds array before the grid got two arrays where the original has one. A grid
built by ``__new__`` and not filled yet could be neither pickled nor deep-copied
(``TypeError: cannot unpack``). Deep copies now follow the grid's reduction, as
``copy.deepcopy`` does for any object, with the log-odds still copied under the lock.
"""

from __future__ import annotations

import copy
import pickle
from typing import Any

import numpy as np

from navkit.mapping import OccupancyGrid


class _Tagged(OccupancyGrid):
    """A subclass whose ``__new__`` takes an argument, given back by ``__getnewargs__``."""

    def __new__(cls, tag: str, *args: Any, **kwargs: Any) -> _Tagged:
        grid = super().__new__(cls)
        grid.tag = tag
        return grid

    def __init__(self, tag: str, logodds: Any, *, resolution: float) -> None:
        super().__init__(logodds, resolution=resolution)

    def __getnewargs__(self) -> tuple[str]:
        return (self.tag,)


class _Rebuilt(OccupancyGrid):
    """A subclass that is copied and pickled through its own constructor."""

    def __init__(self, logodds: Any, *, resolution: float, name: str) -> None:
        super().__init__(logodds, resolution=resolution)
        self.name = name

    def __reduce__(self) -> tuple[Any, ...]:
        return (_rebuild, (self.logodds.copy(), self.resolution, self.name))


def _rebuild(logodds: Any, resolution: float, name: str) -> _Rebuilt:
    return _Rebuilt(logodds, resolution=resolution, name=f"rebuilt {name}")


class _Plain(OccupancyGrid):
    pass


def _logodds() -> np.ndarray:
    return np.random.default_rng(3).uniform(-2.0, 2.0, (6, 5))


def test_a_subclass_with_new_arguments_deep_copies_as_it_pickles() -> None:
    grid = _Tagged("lab", _logodds(), resolution=0.1)
    twin = copy.deepcopy(grid)
    assert type(twin) is _Tagged and twin.tag == "lab"
    assert twin.logodds.tobytes() == grid.logodds.tobytes()
    assert twin._logodds is not grid._logodds
    assert twin._writer_lock() is not grid._writer_lock()
    assert pickle.loads(pickle.dumps(grid)).tag == twin.tag


def test_a_subclass_reduce_is_followed_by_deepcopy() -> None:
    grid = _Rebuilt(_logodds(), resolution=0.1, name="a")
    twin = copy.deepcopy(grid)
    assert type(twin) is _Rebuilt and twin.name == "rebuilt a"
    assert twin.logodds.tobytes() == grid.logodds.tobytes()


def test_the_log_odds_stay_shared_with_what_was_copied_before_the_grid() -> None:
    grid = _Plain(_logodds(), resolution=0.1)
    grid.raw = grid._logodds
    for box in ([grid._logodds, grid], [grid, grid._logodds]):
        first, second = copy.deepcopy(box)
        twin = second if isinstance(second, OccupancyGrid) else first
        array = first if twin is second else second
        assert array is twin._logodds is twin.raw
        assert array is not grid._logodds
        assert array.tobytes() == grid._logodds.tobytes()


def test_a_grid_built_by_new_and_not_filled_pickles_and_deep_copies() -> None:
    empty = _Plain.__new__(_Plain)
    empty.note = "filled later"
    for twin in (
        copy.deepcopy(empty),
        *(pickle.loads(pickle.dumps(empty, protocol)) for protocol in range(6)),
    ):
        assert type(twin) is _Plain and twin.note == "filled later"
        assert not hasattr(twin, "_logodds")
    bare = _Plain.__new__(_Plain)
    assert type(copy.deepcopy(bare)) is _Plain
    assert type(pickle.loads(pickle.dumps(bare, 0))) is _Plain


def test_a_plain_grid_deep_copies_whole_with_its_own_lock() -> None:
    grid = OccupancyGrid(_logodds(), resolution=0.05, origin=(1.0, -2.0, 0.3))
    memo: dict[int, Any] = {}
    twin = copy.deepcopy(grid, memo)
    assert type(twin) is OccupancyGrid
    assert twin.logodds.tobytes() == grid.logodds.tobytes()
    assert (twin.origin, twin.resolution) == (grid.origin, grid.resolution)
    assert twin._writer_lock() is not grid._writer_lock()
    assert not twin.logodds.flags.writeable
    # copy.deepcopy's keep-alive: the originals whose ids the memo holds stay alive.
    kept = memo[id(memo)]
    assert any(item is grid._logodds for item in kept)
